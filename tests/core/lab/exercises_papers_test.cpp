// The lab's exercises 3-5: the papers' tables reproduced by simulation and asserted against the
// papers' figures with stated tolerances — or, where the simulation disagrees, the disagreement
// asserted (and explained in docs/lab.md and the page's text).
#include <cmath>

#include "test_support.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {
const ShenRow& shen_row(const std::vector<ShenRow>& rows, const std::string& method, int J, int L, double sigma) {
  for (const auto& r : rows)
    if (r.method == method && r.J == J && r.L == L && r.sigma == sigma) return r;
  FAIL("no row " << method << " J " << J << " L " << L << " sigma " << sigma);
  return rows.front();
}
double mean_over(const std::vector<ShenRow>& rows, double sigma, int J0, int J1, bool spectral) {
  double s = 0;
  int n = 0;
  for (const auto& r : rows)
    if (r.method == "Shen2008" && r.sigma == sigma && r.J >= J0 && r.J <= J1 && r.ok) {
      s += spectral ? r.spectral_dE00.mean : r.colorimetric_dE00.mean;
      ++n;
    }
  return s / n;
}
}  // namespace

TEST_CASE("lab shen: Tables I-II — R2 > 0.995, the non-grey OECF as good as the grey-based one", "[lab]") {
  const SpectralData ssf = camera_ssf("Canon_EOS_5D_Mark_II");
  for (const std::string chart : {"cc24", "sg140"})
    for (double sigma : {0.0, 1.0}) {
      ShenOptions o;
      o.chart = chart;
      o.sigmas.clear();
      o.sigma_table = sigma;
      const ShenExercise e = lab_shen_exercise(ssf, o);
      REQUIRE(e.l_table.size() == 5);
      const ShenRow& grey = e.l_table[0];
      INFO(chart << " sigma " << sigma << ": grey-based " << grey.colorimetric_dE00.mean);
      CHECK(e.non_grey == (chart == "cc24" ? 18 : static_cast<int>(e.non_grey)));
      for (int L = 0; L <= 3; ++L) {
        const ShenRow& r = shen_row(e.l_table, "Shen2008", 8, L, sigma);
        INFO("L " << L << " R2 " << r.r_squared.transpose() << " dE00 " << r.colorimetric_dE00.mean << " spectral "
                  << r.spectral_dE00.mean << " rms " << r.spectral_rms.mean);
        REQUIRE(r.ok);
        // The paper: "the correlation coefficients in all cases are larger than 0.995".
        CHECK(r.r_squared.minCoeff() > 0.995);
        // Table I: the proposed method within 0.11 dE00 of the grey-based one (MCC 2.03-2.16 vs
        // 2.13, CDC 2.38-2.39 vs 2.38). Ours: within 0.15 on the 18 MCC patches, 0.5 on the SG at
        // L = 0 and 0.35 for L >= 1 (with sigma = 1 the gap narrows with L, as Table I's MCC rows).
        const double tol = chart == "cc24" ? 0.15 : (L == 0 ? 0.5 : 0.35);
        CHECK(std::fabs(r.colorimetric_dE00.mean - grey.colorimetric_dE00.mean) < tol);
        // Disagreement, asserted: our level is about half the paper's (a noise-free camera model
        // and exact reflectances, against a real scanner's Table I at 2.0-2.4).
        CHECK(r.colorimetric_dE00.mean < (chart == "cc24" ? 2.03 : 2.38));
        if (chart == "cc24") {
          // Table II: spectral RMS 0.040 on the MCC for every row; ours within 0.006.
          CHECK(std::fabs(r.spectral_rms.mean - 0.040) < 0.006);
          CHECK(std::fabs(r.spectral_rms.mean - grey.spectral_rms.mean) < 0.003);
        }
      }
      // Tables I-II: increasing L generally improves the OECF (the worst channel's R2; with
      // sigma = 1 — noise-free every L is above 0.9999).
      if (sigma > 0) CHECK(shen_row(e.l_table, "Shen2008", 8, 3, sigma).r_squared.minCoeff() >=
            shen_row(e.l_table, "Shen2008", 8, 0, sigma).r_squared.minCoeff() - 1e-5);
    }
}

TEST_CASE("lab shen: Figs 2-3 — the J sweep", "[lab]") {
  const ShenExercise e = lab_shen_exercise(camera_ssf("Canon_EOS_5D_Mark_II"));
  REQUIRE(e.j_sweep.size() == 4 * 11);
  // Fig 2: the colorimetric error "keeps stable with respect to J" for sigma 0 and 1: within 0.15.
  for (double sigma : {0.0, 1.0}) {
    double lo = 1e9, hi = 0;
    for (int J = 3; J <= 12; ++J) {
      const double v = shen_row(e.j_sweep, "Shen2008", J, 1, sigma).colorimetric_dE00.mean;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    INFO("sigma " << sigma << ": " << lo << " .. " << hi);
    CHECK(hi - lo < 0.15);
  }
  // Fig 2 at sigma = 3: larger J is worse. (The paper sees it beyond J = 10 on the 140-sample CDC;
  // on the 18 MCC patches it starts at J = 8 — its "rather fluctuant" MCC.)
  CHECK(mean_over(e.j_sweep, 3, 8, 12, false) > mean_over(e.j_sweep, 3, 3, 7, false) + 0.5);
  // Fig 3: spectral errors larger for J <= 4 (noise-free) and for J >= 9 (noisy) than for 5-8.
  CHECK(mean_over(e.j_sweep, 0, 3, 4, true) > mean_over(e.j_sweep, 0, 5, 8, true));
  CHECK(mean_over(e.j_sweep, 2, 9, 12, true) > mean_over(e.j_sweep, 2, 5, 8, true));
  // Coded errors.
  ShenOptions bad;
  bad.chart = "cc48";
  test::require_code([&] { lab_shen_exercise(cmf_sensitivities(), bad); }, ErrorCode::UnknownId);
  bad = ShenOptions{};
  bad.seeds = 0;
  test::require_code([&] { lab_shen_exercise(cmf_sensitivities(), bad); }, ErrorCode::InvalidArgument);
  bad = ShenOptions{};
  bad.J = {17};  // 17 + K = 19 unknowns on 18 non-grey patches: a row refused, not an exception
  bad.sigmas = {0};
  const ShenExercise refused = lab_shen_exercise(cmf_sensitivities(), bad);
  CHECK_FALSE(refused.j_sweep[1].ok);
  CHECK(refused.j_sweep[1].error_code == "TOO_FEW_PATCHES");
  // The CSV: header with units, one line per row, the paper's columns.
  const std::string csv = lab_table_csv(shen_l_table(refused));
  CHECK(csv.rfind("chart,method,J (basis functions),L (iterations),\"noise sigma (rho, 0-255)\"", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 6);
}

TEST_CASE("lab table4: Abed 2013 Table IV, every row — independence asserted, the Classic disagreement too", "[lab]") {
  const auto rows = lab_table4_exercise();
  REQUIRE(rows.size() == 30);
  auto cell = [&](const std::string& t, const std::string& m) -> const Table4Row& {
    for (const auto& r : rows)
      if (r.training == t && r.method == m) return r;
    FAIL("no cell " << t << " " << m);
    return rows.front();
  };
  const std::vector<std::string> trainings{"Classic", "SG", "Custom All", "Custom-Matte", "Custom-Glossy", "Total"};
  const std::vector<int> patches{24, 140, 100, 50, 50, 264};
  const std::vector<std::string> corrected{"scaler-offset", "saunderson", "corrected-3x3"};
  for (size_t t = 0; t < trainings.size(); ++t) {
    INFO(trainings[t]);
    for (const auto& m : {"scaler-offset", "saunderson", "matrix-3x3", "matrix-3x4", "corrected-3x3"}) {
      REQUIRE(cell(trainings[t], m).ok);
      CHECK(cell(trainings[t], m).patches == patches[t]);
      CHECK(cell(trainings[t], m).paper_dE00_mean > 2);  // the paper's cell is beside ours
    }
    const double m33 = cell(trainings[t], "matrix-3x3").dE00_mean, m34 = cell(trainings[t], "matrix-3x4").dE00_mean;
    for (const auto& m : corrected) {
      const Table4Row& r = cell(trainings[t], m);
      INFO(m << " " << r.dE00_mean << " (paper " << r.paper_dE00_mean << "), 3x3 " << m33 << ", 3x4 " << m34);
      // The paper: the 3x4 gives the largest errors in every row.
      CHECK(r.dE00_mean < m34);
      // The paper: surface correction beats the plain 3x3 in every row but the Classic (where
      // its 3x3 is 2.5 against 2.3-2.4). Ours: every row but the Classic — and on the Classic
      // the plain 3x3 is AHEAD of every corrected method (the disagreement, asserted below).
      if (trainings[t] != "Classic") CHECK(r.dE00_mean < m33);
      // Disagreement in level: no measurement noise, a uniform light and a test chart the
      // Saunderson model describes exactly — ours about half the paper's 2.3-3.0.
      CHECK(r.dE00_mean < r.paper_dE00_mean);
    }
    CHECK(cell(trainings[t], "corrected-3x3").mu == Approx(1).margin(0.1));  // eq (12): mu near 1
  }
  for (const auto& m : corrected) CHECK(cell("Classic", "matrix-3x3").dE00_mean < cell("Classic", m).dE00_mean);
  // Independence of the training chart (the paper's claim): each corrected method's mean dE00
  // spans < 0.25 over the six rows (paper: 0.3-0.7); the 3x4's spans > 3 (paper: 9.3).
  auto span = [&](const std::string& m) {
    double lo = 1e9, hi = 0;
    for (const auto& t : trainings) lo = std::min(lo, cell(t, m).dE00_mean), hi = std::max(hi, cell(t, m).dE00_mean);
    return hi - lo;
  };
  for (const auto& m : corrected) CHECK(span(m) < 0.25);
  CHECK(span("matrix-3x4") > 3);
  test::require_code([] { lab_table4_exercise("Nikon_D851"); }, ErrorCode::UnknownId);
  test::require_code([] { lab_table4_exercise("Nikon_D850", "D50", -1); }, ErrorCode::InvalidArgument);
}

TEST_CASE("lab guarnera: exposure invariance of T1 and T2R, not of a polynomial or an offset", "[lab]") {
  const auto rows = lab_exposure_exercise(camera_ssf("Canon_EOS_5D_Mark_II"), illuminant_spd("D65"));
  REQUIRE(rows.size() == 4 * 7);
  auto at = [&](const std::string& m, double k) {
    for (const auto& r : rows)
      if (r.model == m && r.k == k) return r.dE00_mean;
    FAIL("no row");
    return 0.0;
  };
  for (double k : {0.125, 0.25, 0.5, 2.0, 4.0, 8.0}) {
    INFO("k " << k);
    CHECK(std::fabs(at("Guarnera2018-T1", k) - at("Guarnera2018-T1", 1)) < 1e-9);
    CHECK(std::fabs(at("Guarnera2018-T2R", k) - at("Guarnera2018-T2R", 1)) < 1e-9);
  }
  // The 10-term polynomial and the offset drift with exposure: at k = 1/8 and 8 several times
  // their error at k = 1.
  CHECK(at("Cheung2004-10", 8) > 4 * at("Cheung2004-10", 1));
  CHECK(at("Cheung2004-10", 0.125) > 2 * at("Cheung2004-10", 1));
  CHECK(at("Guarnera2018-To", 0.125) > 4 * at("Guarnera2018-To", 1));
  // And T2R beats T1 at every k (the root-polynomial's extra terms keep the invariance).
  CHECK(at("Guarnera2018-T2R", 1) < at("Guarnera2018-T1", 1));
  test::require_code([] { lab_exposure_exercise(cmf_sensitivities(), illuminant_spd("D65"), {"T9"}); }, ErrorCode::UnknownId);
  test::require_code([] { lab_exposure_exercise(cmf_sensitivities(), illuminant_spd("D65"), {"Guarnera2018-T1"}, {0}); },
                     ErrorCode::InvalidArgument);
}

TEST_CASE("lab guarnera: Table 4 under D65, A and F2 — reflective training meets it, projector training does not", "[lab]") {
  const auto rows = lab_guarnera_table4();
  REQUIRE(rows.size() == 3 * 2 * 3);
  auto row = [&](const std::string& light, const std::string& training, const std::string& shots) -> const GuarneraRow& {
    for (const auto& r : rows)
      if (r.light == light && r.training == training && r.shots == shots) return r;
    FAIL("no row");
    return rows.front();
  };
  for (const char* light : {"D65", "A", "F2"}) {
    const GuarneraRow &refl = row(light, "reflective", "weighted"), &proj = row(light, "projector", "weighted");
    INFO(light << ": reflective " << refl.NRMSE.transpose() << ", projector " << proj.NRMSE.transpose() << ", paper "
               << refl.paper_NRMSE.transpose());
    CHECK(refl.transform == "T2R");
    // Table 4, multiple shot: ours with reflective training at or below the paper's mean NRMSE.
    CHECK(refl.NRMSE.mean() <= refl.paper_NRMSE.mean());
    CHECK(refl.relative_Y_error < 0.024);  // section 4.1: 2.37 %
    // Algorithm 1 and the weighted fusion agree (within 0.0005 NRMSE per channel), and one
    // well-exposed shot is as good (the virtual sensor's noise is small; the paper's multi-shot
    // gain comes from real noise and clipping).
    CHECK((row(light, "reflective", "recursive").NRMSE - refl.NRMSE).cwiseAbs().maxCoeff() < 0.0005);
    CHECK((row(light, "reflective", "single").NRMSE - refl.NRMSE).cwiseAbs().maxCoeff() < 0.001);
    // Disagreement, asserted: projector training (the paper's) misses Table 4 under A and F2 —
    // three primaries cannot match broadband reflectances for a camera that fails the Luther
    // condition (absolute/example.hpp); under D65 it meets it.
    if (std::string(light) == "D65") CHECK(proj.NRMSE.mean() <= proj.paper_NRMSE.mean());
    else CHECK(proj.NRMSE.mean() > 1.5 * proj.paper_NRMSE.mean());
  }
  test::require_code([] { lab_guarnera_table4("Canon_EOS_5D_Mark_II", {"D1"}, {"projector"}); }, ErrorCode::UnknownId);
  test::require_code([] { lab_guarnera_table4("Canon_EOS_5D_Mark_II", {"D65"}, {"printed"}); }, ErrorCode::InvalidArgument);
}
