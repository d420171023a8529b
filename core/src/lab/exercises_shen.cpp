// The lab's exercise 3: Shen, Xin, Yang & Lou (2008), the J and L sweeps (Figs 2-3, Tables I-II),
// composed from the engine's Shen2008 and grey-polynomial linearisations, the virtual camera
// (eq 29) and the colorimetric (eqs 23-25) and spectral (eqs 26-28) characterisations. Rules in
// tristim/lab/exercises.hpp.
#include <algorithm>
#include <cmath>

#include "tristim/characterisation/fit.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/lab_options.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/linearisation/spectral.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

/// One noise realisation of the paper's simulation (eq 29) on `chart`.
LinearisationData simulate_eq29(const SpectralData& ssf, const SpectralData& refl, const SpectralData& d65,
                                const ReferenceChart& ref, double sigma, std::uint64_t seed) {
  SimulationOptions o;
  o.white_level = 80;  // the white diffuser's ρ = 22·80^(1/1.8) ≈ 251
  o.oecf = true;       // ρ = l·u^(1/γ), γ = 1.8, l = 22 (eq 29)
  o.noise_sigma = sigma;
  o.seed = seed;
  o.clip_max = 255;
  LinearisationData d{refl.names, lab_patch_matrix(simulate_camera_RGB(ssf, refl, d65, o)), lab_patch_matrix(ref.XYZ),
                      ref.white, refl, {}, 255};
  return d;
}

struct Scores {
  Summary colorimetric, spectral, rms;
};

/// The characterisations on the non-grey patches through a fitted OECF (the paper trains and
/// scores both on the non-grey patches, Tables I-II's notes).
Scores score(const Linearisation& l, const LinearisationData& d, const std::vector<std::string>& greys,
             const SpectralData& d65) {
  std::vector<Eigen::Index> keep;
  std::vector<std::string> ids;
  for (size_t i = 0; i < d.ids.size(); ++i)
    if (std::find(greys.begin(), greys.end(), d.ids[i]) == greys.end()) {
      keep.push_back(static_cast<Eigen::Index>(i));
      ids.push_back(d.ids[i]);
    }
  PatchMatrix rgb(static_cast<Eigen::Index>(keep.size()), 3), xyz(static_cast<Eigen::Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) {
    rgb.row(static_cast<Eigen::Index>(i)) = d.camera_RGB.row(keep[i]);
    xyz.row(static_cast<Eigen::Index>(i)) = d.reference_XYZ.row(keep[i]);
  }
  Scores s;
  s.colorimetric = evaluate(fit("Shen2008", linearise(l, rgb), xyz).fitted, xyz, d.white).dE00;  // eqs (23)-(25)
  const SpectralEvaluation e = evaluate_spectral(fit_spectral(l, ids, rgb, d.reflectances), ids, rgb, d.reflectances, d65);
  s.spectral = e.dE00_summary;  // eqs (26)-(28)
  s.rms = e.rms_summary;
  return s;
}

void accumulate(Summary& into, const Summary& s, double w) {
  into.mean += w * s.mean;
  into.std += w * s.std;
  into.max += w * s.max;
  into.median += w * s.median;
}

}  // namespace

ShenExercise lab_shen_exercise(const SpectralData& ssf, const ShenOptions& o) {
  if (!has_id(shen_training_table(), o.chart))
    throw Error(ErrorCode::UnknownId, "exercise 3 trains on " + ids_of(shen_training_table(), " or ") + ", not '" + o.chart + "'");
  if (o.seeds < 1 || o.seeds > 20) throw Error(ErrorCode::InvalidArgument, "seeds must be 1..20");
  for (double s : o.sigmas)
    if (!(s >= 0 && s <= 50)) throw Error(ErrorCode::InvalidArgument, "noise sigma must be in [0, 50] (rho units)");
  if (!(o.sigma_table >= 0 && o.sigma_table <= 50)) throw Error(ErrorCode::InvalidArgument, "table noise sigma must be in [0, 50]");
  for (int J : o.J)
    if (J < 1 || J > 20) throw Error(ErrorCode::InvalidArgument, "J must be 1..20, got " + std::to_string(J));
  if (o.J_table < 1 || o.J_table > 20) throw Error(ErrorCode::InvalidArgument, "J must be 1..20");
  const SpectralData refl = chart_reflectances(o.chart);
  const SpectralData d65 = illuminant_spd("D65");
  const ReferenceChart ref = reference_from_spectra(refl, d65, Observer::CIE1931_2);
  // The MCC's greys are its bottom row; on the SG the engine's automatic rule finds them.
  const std::string grey_ids = o.chart == "cc24" ? "D1;D2;D3;D4;D5;D6" : "";
  ShenExercise out;
  out.chart = o.chart;

  // One σ: the grey-based row, then a Shen2008 row per (J, L) pair; means over the seeds.
  auto rows_for = [&](double sigma, const std::vector<std::pair<int, int>>& JL) {
    std::vector<ShenRow> rows(JL.size() + 1);
    rows[0].method = "grey-based";
    for (size_t k = 0; k < JL.size(); ++k) {
      rows[k + 1].method = "Shen2008";
      rows[k + 1].J = JL[k].first;
      rows[k + 1].L = JL[k].second;
    }
    for (auto& r : rows) {
      r.sigma = sigma;
      r.ok = true;
      r.r_squared = Vec3::Zero();
    }
    const double w = 1.0 / o.seeds;
    for (int s = 0; s < o.seeds; ++s) {
      const LinearisationData d = simulate_eq29(ssf, refl, d65, ref, sigma, o.seed + static_cast<std::uint64_t>(s));
      const Linearisation grey = fit_linearisation(MethodChoice{"grey-polynomial", {{"K", 2}}, {{"grey", grey_ids}}}, d);
      out.non_grey = static_cast<int>(d.ids.size() - grey.greys.size());
      const Scores g = score(grey, d, grey.greys, d65);
      accumulate(rows[0].colorimetric_dE00, g.colorimetric, w);
      accumulate(rows[0].spectral_dE00, g.spectral, w);
      accumulate(rows[0].spectral_rms, g.rms, w);
      for (size_t k = 0; k < JL.size(); ++k) {
        ShenRow& r = rows[k + 1];
        if (!r.ok) continue;
        try {
          const Linearisation l = fit_linearisation(
              MethodChoice{"Shen2008", {{"K", 2}, {"J", r.J}, {"L", r.L}}, {{"grey", grey_ids}}}, d);
          const Scores sc = score(l, d, l.greys, d65);
          r.r_squared += w * l.r_squared;
          accumulate(r.colorimetric_dE00, sc.colorimetric, w);
          accumulate(r.spectral_dE00, sc.spectral, w);
          accumulate(r.spectral_rms, sc.rms, w);
        } catch (const Error& e) {
          r.ok = false;
          r.error_code = e.code_name();
        }
      }
    }
    rows[0].r_squared = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    for (auto& r : rows)
      if (!r.ok) {  // refused: no partial sums from the seeds before the refusal
        ShenRow refused;
        refused.method = r.method;
        refused.J = r.J;
        refused.L = r.L;
        refused.sigma = sigma;
        refused.error_code = r.error_code;
        r = refused;
      }
    return rows;
  };

  for (double sigma : o.sigmas) {
    std::vector<std::pair<int, int>> JL;
    for (int J : o.J) JL.emplace_back(J, 1);  // Figs 2-3: L = 1
    const auto rows = rows_for(sigma, JL);
    out.j_sweep.insert(out.j_sweep.end(), rows.begin(), rows.end());
  }
  out.l_table = rows_for(o.sigma_table, {{o.J_table, 0}, {o.J_table, 1}, {o.J_table, 2}, {o.J_table, 3}});
  return out;
}

namespace {

/// The paper's rows of Tables I-II (real scans, J = 8): R, G, B R²; colorimetric ΔE00 mean, std,
/// max; spectral ΔE00 mean, std, max; spectral RMS mean. Grey-based first, then L = 0..3.
struct PaperShenRow {
  double r2[3], col[3], spec[3], rms;
};
constexpr PaperShenRow kPaperMCC[] = {
    {{NAN, NAN, NAN}, {2.13, 1.75, 5.96}, {3.58, 2.76, 12.11}, 0.040},
    {{0.9988, 0.9981, 0.9666}, {2.03, 1.68, 6.12}, {4.15, 2.64, 12.31}, 0.040},
    {{0.9980, 0.9990, 0.9954}, {2.11, 1.71, 5.95}, {3.65, 2.48, 11.18}, 0.040},
    {{0.9973, 0.9990, 0.9995}, {2.14, 1.73, 5.85}, {3.43, 2.47, 10.73}, 0.040},
    {{0.9969, 0.9988, 0.9998}, {2.16, 1.76, 5.81}, {3.35, 2.46, 10.60}, 0.040}};
constexpr PaperShenRow kPaperCDC[] = {
    {{NAN, NAN, NAN}, {2.38, 1.82, 10.36}, {3.05, 1.81, 12.09}, 0.033},
    {{0.9999, 0.9998, 0.9995}, {2.38, 1.83, 10.34}, {3.13, 1.88, 12.58}, 0.033},
    {{0.9999, 0.9998, 0.9998}, {2.39, 1.83, 10.13}, {3.05, 1.78, 12.49}, 0.033},
    {{0.9998, 0.9997, 0.9998}, {2.39, 1.82, 10.11}, {3.03, 1.77, 12.39}, 0.033},
    {{0.9998, 0.9997, 0.9997}, {2.39, 1.82, 10.11}, {3.02, 1.76, 12.32}, 0.033}};

}  // namespace

LabTable shen_j_table(const ShenExercise& e) {
  LabTable t{"lab-shen-J",
             {"chart", "method", "J (basis functions)", "L (iterations)", "noise sigma (rho, 0-255)",
              "colorimetric dE00 mean (CIEDE2000)", "spectral dE00 mean (CIEDE2000, D65)", "spectral RMS mean (reflectance)",
              "error"},
             {}};
  for (const auto& r : e.j_sweep)
    t.rows.push_back({e.chart, r.method, r.J ? std::to_string(r.J) : "", r.J ? std::to_string(r.L) : "", lab_number(r.sigma),
                      r.ok ? lab_number(r.colorimetric_dE00.mean) : "", r.ok ? lab_number(r.spectral_dE00.mean) : "",
                      r.ok ? lab_number(r.spectral_rms.mean) : "", r.error_code});
  return t;
}

LabTable shen_l_table(const ShenExercise& e) {
  LabTable t{"lab-shen-L",
             {"chart", "method", "J (basis functions)", "L (iterations)", "noise sigma (rho, 0-255)", "R2 red", "R2 green",
              "R2 blue", "colorimetric dE00 mean (CIEDE2000)", "colorimetric dE00 std", "colorimetric dE00 max",
              "spectral dE00 mean (CIEDE2000, D65)", "spectral dE00 max", "spectral RMS mean (reflectance)",
              "paper R2 red", "paper R2 green", "paper R2 blue", "paper colorimetric dE00 mean", "paper spectral dE00 mean",
              "paper spectral RMS mean", "error"},
             {}};
  const PaperShenRow* paper = e.chart == "cc24" ? kPaperMCC : kPaperCDC;
  for (size_t i = 0; i < e.l_table.size(); ++i) {
    const ShenRow& r = e.l_table[i];
    const PaperShenRow& p = paper[std::min<size_t>(i, 4)];
    t.rows.push_back({e.chart, r.method, r.J ? std::to_string(r.J) : "", r.J ? std::to_string(r.L) : "", lab_number(r.sigma),
                      lab_number(r.r_squared[0]), lab_number(r.r_squared[1]), lab_number(r.r_squared[2]), lab_number(r.colorimetric_dE00.mean),
                      lab_number(r.colorimetric_dE00.std), lab_number(r.colorimetric_dE00.max), lab_number(r.spectral_dE00.mean),
                      lab_number(r.spectral_dE00.max), lab_number(r.spectral_rms.mean), lab_number(p.r2[0]), lab_number(p.r2[1]), lab_number(p.r2[2]),
                      lab_number(p.col[0]), lab_number(p.spec[0]), lab_number(p.rms), r.error_code});
  }
  return t;
}

}  // namespace tristim
