// Shen, Xin, Yang & Lou (2008): the inverse OECF from non-grey samples (eqs 6-22), the
// reflectance basis it needs (eq 7) and its row of the linearisation table.
#include "tristim/linearisation/oecf_Shen2008.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <map>
#include <cstdlib>
#include <sstream>
#include <string_view>

#include "rows.hpp"
#include "../citations.hpp"
#include "tristim/data.hpp"
#include "tristim/error.hpp"
#include "tristim/number.hpp"
#include "tristim/io/patch_files.hpp"

namespace tristim {

namespace {

// The built-in table is trusted and large (1269 × 81 numbers): a plain parse_double pass instead of
// the checking reader (read_spectral_csv), which takes ~100× longer on it. A malformed built-in
// file is a bug (Error Internal).
SpectralData parse_builtin_spectral(std::string_view name) {
  const std::string text(builtin_file(name));
  SpectralData s;
  size_t pos = text.find('\n');
  if (pos == std::string::npos) throw Error(ErrorCode::Internal, "built-in " + std::string(name) + ": no header");
  {
    size_t start = text.find(',');  // skip "wavelength_nm"
    while (start < pos) {
      const size_t end = std::min(text.find(',', start + 1), pos);
      s.names.push_back(text.substr(start + 1, end - start - 1));
      start = end;
    }
  }
  s.values.resize(s.names.size());
  // Room for every row up front: no reallocation (and in wasm no allocator calls) while parsing.
  const size_t rows = static_cast<size_t>(std::count(text.begin() + static_cast<std::ptrdiff_t>(pos) + 1, text.end(), '\n')) + 1;
  s.wavelengths.reserve(rows);
  for (auto& column : s.values) column.reserve(rows);
  const char* p = text.c_str() + pos + 1;
  const char* const end = text.c_str() + text.size();
  while (p < end && *p != '\0') {
    char* next = nullptr;
    s.wavelengths.push_back(tristim::parse_double(p, &next));
    p = next;
    for (auto& column : s.values) {
      if (*p != ',') throw Error(ErrorCode::Internal, "built-in " + std::string(name) + ": short row");
      column.push_back(tristim::parse_double(p + 1, &next));
      p = next;
    }
    while (p < end && (*p == '\r' || *p == '\n')) ++p;
  }
  return s;
}

}  // namespace

const SpectralData& munsell_reflectances() {
  static const SpectralData set = parse_builtin_spectral("reflectances/munsell_matt_1269_reflectance_380-780_5nm.csv");
  return set;
}

std::vector<double> working_grid(const std::vector<double>& patch_wavelengths, const std::vector<double>& set_wavelengths) {
  if (patch_wavelengths.empty() || set_wavelengths.empty())
    throw Error(ErrorCode::WavelengthMismatch, "a reflectance set without wavelengths");
  const double lo = set_wavelengths.front(), hi = set_wavelengths.back();
  std::vector<double> grid;
  for (double w : patch_wavelengths)
    if (w >= lo - 1e-9 && w <= hi + 1e-9) grid.push_back(w);
  std::ostringstream range;
  range << "the patches' reflectances (" << patch_wavelengths.front() << "-" << patch_wavelengths.back()
        << " nm) and the basis set (" << lo << "-" << hi << " nm)";
  if (grid.size() < 8 || grid.front() > 400 + 1e-9 || grid.back() < 700 - 1e-9)
    throw Error(ErrorCode::WavelengthMismatch,
                range.str() + " share less than 400-700 nm with at least 8 samples");
  return grid;
}

namespace {

// R Rᵀ (N × N) of a set resampled on a grid; cached for the built-in set (one grid at a time).
Eigen::MatrixXd gram(const SpectralData& set, const std::vector<double>& wavelengths) {
  const size_t N = wavelengths.size();
  Eigen::MatrixXd R(N, set.size());
  // Where every wavelength is one of the set's own, take the values as they are (the interpolation
  // rule passes through its samples); otherwise resample each reflectance.
  std::vector<size_t> at;
  for (double w : wavelengths) {
    const auto it = std::lower_bound(set.wavelengths.begin(), set.wavelengths.end(), w - 1e-9);
    if (it == set.wavelengths.end() || std::fabs(*it - w) > 1e-9) break;
    at.push_back(static_cast<size_t>(it - set.wavelengths.begin()));
  }
  for (size_t s = 0; s < set.size(); ++s) {
    if (at.size() == N) {
      for (size_t i = 0; i < N; ++i) R(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s)) = set.values[s][at[i]];
      continue;
    }
    const std::vector<double> v = interpolate_spectrum(set.wavelengths, set.values[s], wavelengths, set.linear);
    for (size_t i = 0; i < N; ++i) R(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s)) = v[i];
  }
  return R * R.transpose();
}

}  // namespace

ReflectanceBasis reflectance_basis(const SpectralData& set, const std::vector<double>& wavelengths, int J,
                                   const std::string& source) {
  const int N = static_cast<int>(wavelengths.size());
  if (J < 1 || J > N)
    throw Error(ErrorCode::InvalidArgument, "J = " + std::to_string(J) + " basis functions on " + std::to_string(N) +
                                                " wavelengths (1 <= J <= " + std::to_string(N) + ")");
  if (static_cast<int>(set.size()) < J)
    throw Error(ErrorCode::TooFewPatches, "the basis set (" + source + ") has " + std::to_string(set.size()) +
                                              " reflectances, fewer than J = " + std::to_string(J));
  if (set.wavelengths.empty() || wavelengths.front() < set.wavelengths.front() - 1e-9 ||
      wavelengths.back() > set.wavelengths.back() + 1e-9)
    throw Error(ErrorCode::WavelengthMismatch, "the basis set (" + source + ") does not cover " +
                                                   std::to_string(wavelengths.front()) + "-" +
                                                   std::to_string(wavelengths.back()) + " nm");
  static std::vector<double> cached_grid;
  static Eigen::MatrixXd cached_gram;
  Eigen::MatrixXd G;
  if (&set == &munsell_reflectances()) {
    if (cached_grid != wavelengths) {
      cached_gram = gram(set, wavelengths);
      cached_grid = wavelengths;
    }
    G = cached_gram;
  } else {
    G = gram(set, wavelengths);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
  if (eig.info() != Eigen::Success) throw Error(ErrorCode::FitFailed, "PCA of the basis set failed");
  ReflectanceBasis b;
  b.wavelengths = wavelengths;
  b.samples = static_cast<int>(set.size());
  b.source = source;
  b.functions.resize(N, J);
  const double total = std::max(G.trace(), 1e-300);
  double captured = 0;
  for (int j = 0; j < J; ++j) {
    Eigen::VectorXd v = eig.eigenvectors().col(N - 1 - j);  // eigenvalues ascend
    if (v.sum() < 0) v = -v;
    b.functions.col(j) = v.normalized();
    captured += std::max(0.0, eig.eigenvalues()[N - 1 - j]);
    b.explained.push_back(captured / total);
  }
  if (eig.eigenvalues()[N - J] <= 1e-12 * eig.eigenvalues()[N - 1])
    throw Error(ErrorCode::IllConditioned, "the basis set (" + source + ") spans fewer than J = " + std::to_string(J) +
                                               " independent reflectances");
  return b;
}

Eigen::MatrixXd basis_weights(const ReflectanceBasis& basis, const SpectralData& reflectances,
                              const std::vector<std::string>& ids) {
  const Eigen::Index N = basis.functions.rows(), J = basis.functions.cols();
  Eigen::MatrixXd R(N, static_cast<Eigen::Index>(ids.size()));
  for (size_t q = 0; q < ids.size(); ++q) {
    const std::vector<double> v =
        interpolate_spectrum(reflectances.wavelengths, reflectances.column(ids[q]), basis.wavelengths, reflectances.linear);
    for (Eigen::Index i = 0; i < N; ++i) R(i, static_cast<Eigen::Index>(q)) = v[static_cast<size_t>(i)];
  }
  // Columns of B are orthonormal, so B⁺ = Bᵀ.
  Eigen::MatrixXd alpha = (basis.functions.transpose() * R).transpose();
  (void)J;
  return alpha;
}

namespace {

Eigen::JacobiSVD<Eigen::MatrixXd> svd_of(const Eigen::MatrixXd& A) {
  return Eigen::JacobiSVD<Eigen::MatrixXd>(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
}

std::vector<double> to_std(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

Eigen::VectorXd vandermonde_times(const std::vector<double>& x, const std::vector<double>& c) {
  Eigen::VectorXd u(static_cast<Eigen::Index>(x.size()));
  for (size_t i = 0; i < x.size(); ++i) u[static_cast<Eigen::Index>(i)] = polyval(c, x[i]);
  return u;
}

}  // namespace

ShenChannelFit oecf_Shen2008(const std::vector<double>& x, const Eigen::MatrixXd& alpha, int K, int L) {
  const int Q = static_cast<int>(x.size()), J = static_cast<int>(alpha.cols());
  if (alpha.rows() != Q) throw Error(ErrorCode::Internal, "oecf_Shen2008: x and alpha differ in rows");
  if (K < 1 || L < 0) throw Error(ErrorCode::InvalidArgument, "oecf_Shen2008: K >= 1 and L >= 0 needed");
  if (Q < K + J)
    throw Error(ErrorCode::TooFewPatches, std::to_string(Q) + " samples, fewer than K + J = " + std::to_string(K) + " + " +
                                              std::to_string(J) + " unknowns of eq (19)");
  // eq (18): Λ_α rows [ρ, ..., ρ^K, α_1, ..., α_J], columns scaled to unit norm for the solve.
  Eigen::MatrixXd A(Q, K + J);
  for (int q = 0; q < Q; ++q) {
    double p = x[static_cast<size_t>(q)];
    for (int k = 0; k < K; ++k, p *= x[static_cast<size_t>(q)]) A(q, k) = p;
    A.row(q).tail(J) = alpha.row(q);
  }
  Eigen::VectorXd scale(K + J);
  for (int j = 0; j < K + J; ++j) {
    scale[j] = A.col(j).norm();
    if (!(scale[j] > 0)) throw Error(ErrorCode::IllConditioned, "eq (19): a column of Λ_α is zero on every sample");
    A.col(j) /= scale[j];
  }
  const auto svd = svd_of(A);
  const Eigen::VectorXd& sv = svd.singularValues();
  ShenChannelFit f;
  f.condition = sv[sv.size() - 1] > 0 ? sv[0] / sv[sv.size() - 1] : std::numeric_limits<double>::infinity();
  if (!(sv[sv.size() - 1] > 1e-13 * sv[0]))
    throw Error(ErrorCode::IllConditioned, "eq (19): Λ_α has rank < K + J = " + std::to_string(K + J) +
                                               " (the samples do not determine the OECF and the basis weights)");
  // eq (19): c_d = −Λ_α⁺ 1
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(Q);
  const Eigen::VectorXd cd = (-svd.solve(ones)).cwiseQuotient(scale);
  f.residual_rms = std::sqrt(((A * cd.cwiseProduct(scale)) + ones).squaredNorm() / Q);
  f.c = to_std(cd.head(K));
  const Eigen::VectorXd d0 = -cd.tail(J);  // c_d = [c; −d], eq (17)
  f.d = to_std(d0);
  // eq (20): û = αᵀ d; eq (22): ĉ = [ρ̃ᵀ]⁺ [û]
  Eigen::VectorXd u = alpha * d0;
  f.c_hat = polyfit(x, to_std(u), K);
  f.history.push_back(f.c_hat);
  const auto alpha_svd = svd_of(alpha);
  for (int it = 0; it < L; ++it) {
    u = vandermonde_times(x, f.c_hat);            // û from the polynomial, eq (21)
    const Eigen::VectorXd d = alpha_svd.solve(u);  // d ← [αᵀ]⁺ û, eq (20)
    f.d = to_std(d);
    u = alpha * d;                                 // û from the basis, eq (20)
    f.c_hat = polyfit(x, to_std(u), K);            // eq (22)
    f.history.push_back(f.c_hat);
  }
  f.u_hat = to_std(u);
  return f;
}

std::vector<OptionSpec> grey_options() {
  return {
      {"grey", "text", "Grey patches", 0, "", 0, 0, {},
       "';'-separated ids of grey patches (left out of the fit unless use_greys is 1; Shen2008 compares its curve with "
       "theirs, R²); empty: automatic"},
      {"grey_threshold", "number", "Grey threshold (ΔE00)", 2, "", 0.01, 50, {},
       "automatic greys: CIEDE2000 from the neutral of the same L* below this"},
      {"use_greys", "boolean", "Fit on greys too", 0, "", 0, 1, {},
       "1: the grey patches take part in the fit (the paper fits on non-grey samples only)"},
  };
}

std::vector<int> training_rows(const LinearisationData& data, const MethodChoice& choice, GreySelection& greys) {
  greys = select_greys(data, split_ids(choice_text(choice, "grey")), choice_number(choice, "grey_threshold"));
  const bool use_greys = choice_number(choice, "use_greys") != 0;
  std::vector<bool> is_grey(data.ids.size(), false);
  for (int r : greys.rows) is_grey[static_cast<size_t>(r)] = true;
  std::vector<int> rows;
  for (size_t r = 0; r < static_cast<size_t>(data.camera_RGB.rows()); ++r)
    if (use_greys || r >= is_grey.size() || !is_grey[r]) rows.push_back(static_cast<int>(r));
  return rows;
}

namespace linearisation_detail {

namespace {

const char* kChannel = "RGB";

std::string id_of(const LinearisationData& data, int r) { return data.ids.empty() ? std::to_string(r + 1) : data.ids[r]; }

Linearisation fit_Shen2008(const LinearisationData& data, const MethodChoice& choice) {
  check_data(data);
  if (data.reflectances.size() == 0)
    throw Error(ErrorCode::MissingColumn, "Shen2008 needs the patches' reflectances");
  if (data.ids.empty()) throw Error(ErrorCode::MissingColumn, "Shen2008 needs patch ids to pair RGB with reflectances");
  const int K = static_cast<int>(choice_number(choice, "K")), J = static_cast<int>(choice_number(choice, "J")),
            L = static_cast<int>(choice_number(choice, "L"));
  Linearisation l;
  l.choice = choice;
  l.full_scale = full_scale_of(data);

  GreySelection greys;
  const std::vector<int> candidates = training_rows(data, choice, greys);
  l.grey_reason = greys.reason;
  for (int r : greys.rows) l.greys.push_back(id_of(data, r));
  const bool use_greys = choice_number(choice, "use_greys") != 0;

  // eq (7): the basis, on the patches' wavelengths inside the set's range.
  const std::string source = choice_text(choice, "basis");
  const SpectralData* set = &munsell_reflectances();
  if (source == "patches") set = &data.reflectances;
  if (source == "user") {
    if (data.basis_reflectances.size() == 0)
      throw Error(ErrorCode::MissingColumn, "Shen2008 basis=user: no reflectance set was given for the basis");
    set = &data.basis_reflectances;
  }
  const ReflectanceBasis basis =
      reflectance_basis(*set, working_grid(data.reflectances.wavelengths, set->wavelengths), J, source);
  std::vector<std::string> all_ids;
  for (size_t r = 0; r < data.ids.size(); ++r) all_ids.push_back(data.ids[r]);
  const Eigen::MatrixXd alpha_all = basis_weights(basis, data.reflectances, all_ids);

  std::array<std::vector<int>, 3> used;
  for (int c = 0; c < 3; ++c) {
    used[c] = usable_rows(data, candidates, c, l.full_scale, l);
    const int Q = static_cast<int>(used[c].size());
    if (Q == 0) throw Error(ErrorCode::NoUsableData, std::string("Shen2008, channel ") + kChannel[c] + ": no usable patch");
    std::vector<double> x;
    Eigen::MatrixXd alpha(Q, J);
    for (int q = 0; q < Q; ++q) {
      x.push_back(data.camera_RGB(used[c][q], c) / l.full_scale);
      alpha.row(q) = alpha_all.row(used[c][q]);
    }
    ShenChannelFit f;
    try {
      f = oecf_Shen2008(x, alpha, K, L);
    } catch (const Error& e) {
      throw Error(e.code(), std::string("Shen2008, channel ") + kChannel[c] + " (" + std::to_string(Q) +
                                (use_greys ? " usable patches): " : " usable non-grey patches): ") + e.what());
    }
    // Normalisation (the paper: c_0 "cancelled through the normalization of linear response"):
    // 1 at the brightest fitted patch.
    const double top = polyval(f.c_hat, *std::max_element(x.begin(), x.end()));
    if (!(std::fabs(top) > 1e-300) || !std::isfinite(top))
      throw Error(ErrorCode::FitFailed, std::string("Shen2008, channel ") + kChannel[c] + ": the recovered curve is 0 at the brightest patch");
    l.coefficients[c] = f.c_hat;
    for (double& v : l.coefficients[c]) v /= top;
  }
  record_fit(l, data, used, l.full_scale);
  check_extrapolation(l, data);  // fitted on the non-grey patches, applied to every patch

  // R² with the greys (Tables I-II): per channel, the squared correlation between the recovered
  // OECF and the grey-based one of the same order K ("between the OECFs estimated from nongray
  // samples and those obtained from gray samples"), both sampled at 101 points over the range
  // of the (unclipped) greys, where the grey-based curve is supported by data.
  if (!greys.rows.empty()) {
    MethodChoice grey_choice{"grey-polynomial", {{"K", K}}, {{"grey", choice_text(choice, "grey")}}};
    grey_choice.parameters["grey_threshold"] = choice_number(choice, "grey_threshold");
    try {
      const Linearisation g = fit_linearisation(grey_choice, data);
      for (int c = 0; c < 3; ++c) {
        l.grey_coefficients[c] = g.coefficients[c];
        const double a = g.domain[c][0], b = g.domain[c][1];
        std::vector<double> estimated, grey_based;
        for (int i = 0; i <= 100; ++i) {
          const double xv = a + (b - a) * i / 100.0;
          estimated.push_back(polyval(l.coefficients[c], xv));
          grey_based.push_back(polyval(g.coefficients[c], xv));
        }
        l.r_squared[c] = squared_correlation(estimated, grey_based);
      }
    } catch (const Error& e) {
      add_warning(l, std::string("no grey-based OECF to compare with (") + e.what() + ")");
      for (auto& g : l.grey_coefficients) g.clear();
    }
  }
  check_monotonic(l, apply_polynomial);
  return l;
}

}  // namespace

LinearisationMethod row_Shen2008() {
  std::vector<OptionSpec> o{
      {"K", "integer", "Order K", 2, "", 1, 6, {}, "order of the inverse-OECF polynomial, eq (6); the paper's 2"},
      {"J", "integer", "Basis functions J", 8, "", 1, 40, {}, "reflectance basis functions, eq (7); the paper's 8"},
      {"L", "integer", "Refinements L", 2, "", 0, 20, {}, "iterations of the refinement loop after eq (22); the paper's 2"},
      {"basis", "choice", "Basis set", 0, "munsell1269", 0, 0, {"munsell1269", "patches", "user"},
       "reflectances the PCA basis comes from: the 1269 Munsell chips, the patches' own, or a set given with the data"},
  };
  for (OptionSpec& g : grey_options()) o.push_back(std::move(g));
  return {{"Shen2008", "Non-grey samples with known reflectances (Shen et al. 2008)",
           std::string(citation::kShen2008) + ", eqs (6)-(22)", o},
          "reflectances", fit_Shen2008, apply_polynomial, inverse_polynomial};
}

}  // namespace linearisation_detail
}  // namespace tristim
