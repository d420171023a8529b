// Spectral sensitivities from one chart photo (Jiang, Liu, Gu & Süsstrunk 2013 PCA basis +
// smoothness-constrained least squares); rules in tristim/absolute/sensitivities.hpp.
#include "tristim/absolute/sensitivities.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/options_table.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

const std::vector<double>& basis_grid() {
  static const std::vector<double> g = wavelength_grid(380, 780, 5);
  return g;
}

std::string fold(std::string s) {
  for (auto& c : s) c = (c == ' ' || c == '-') ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Per channel: the first K right singular vectors of the unit-norm curves (cameras × λ).
std::array<Eigen::MatrixXd, 3> basis(int K, const std::vector<std::string>& exclude, int& cameras) {
  std::vector<std::string> excluded;
  for (const auto& e : exclude) {
    camera_ssf(e);  // UnknownId for a name that is not built in
    excluded.push_back(fold(e));
  }
  std::vector<SpectralData> curves;
  for (const auto& name : camera_names())
    if (std::find(excluded.begin(), excluded.end(), fold(name)) == excluded.end())
      curves.push_back(align_spectra(camera_ssf(name), basis_grid()));
  cameras = static_cast<int>(curves.size());
  if (cameras < K)
    throw Error(ErrorCode::InvalidArgument, "the basis needs at least as many cameras as components");
  const int L = static_cast<int>(basis_grid().size());
  std::array<Eigen::MatrixXd, 3> B;
  for (int c = 0; c < 3; ++c) {
    Eigen::MatrixXd M(cameras, L);
    for (int k = 0; k < cameras; ++k) {
      for (int i = 0; i < L; ++i) M(k, i) = curves[k].values[c][i];
      M.row(k) /= M.row(k).norm();
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeThinV);
    B[c] = svd.matrixV().leftCols(K);
  }
  return B;
}

}  // namespace

SensitivityEstimate estimate_sensitivities_Jiang2013(const std::vector<Vec3>& rgb, const SpectralData& reflectances,
                                                     const SpectralData& illuminant, const SensitivityOptions& o) {
  const int N = static_cast<int>(rgb.size()), K = o.components;
  check_sensitivity_options(o);  // K and the smoothness inside sensitivity_option_table()'s rows
  if (static_cast<int>(reflectances.size()) != N)
    throw Error(ErrorCode::PatchMismatch, std::to_string(N) + " camera RGB rows but " +
                                              std::to_string(reflectances.size()) + " reflectances");
  if (N < K) throw Error(ErrorCode::TooFewPatches, "at least " + std::to_string(K) + " patches are needed for " +
                                                       std::to_string(K) + " components");
  if (illuminant.size() < 1) throw Error(ErrorCode::InvalidArgument, "the illuminant has no values");
  for (const auto& v : rgb)
    if (!v.allFinite()) throw Error(ErrorCode::NonFinite, "camera RGB has a non-finite value");
  const auto& g = basis_grid();
  const int L = static_cast<int>(g.size());
  const auto S = interpolate_spectrum(illuminant.wavelengths, illuminant.values[0], g, illuminant.linear);
  const SpectralData R = align_spectra(reflectances, g);
  Eigen::MatrixXd A(N, L);
  for (int i = 0; i < N; ++i)
    for (int l = 0; l < L; ++l) A(i, l) = R.values[i][l] * S[l] * 5.0;  // Δλ = 5 nm
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(L - 2, L);  // second differences
  for (int l = 0; l + 2 < L; ++l) {
    D(l, l) = 1;
    D(l, l + 1) = -2;
    D(l, l + 2) = 1;
  }
  SensitivityEstimate out;
  out.patches = N;
  out.components = K;
  const auto B = basis(K, o.exclude_cameras, out.basis_cameras);
  out.ssf.wavelengths = g;
  out.ssf.names = {"R", "G", "B"};
  double ss_all = 0, ref_all = 0;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd rho(N);
    for (int i = 0; i < N; ++i) rho[i] = rgb[i][c];
    if (!(rho.maxCoeff() > 0))
      throw Error(ErrorCode::InvalidArgument, std::string("channel ") + "RGB"[c] + " has no positive response");
    const Eigen::MatrixXd AB = A * B[c], DB = D * B[c];
    Eigen::MatrixXd H = AB.transpose() * AB;
    const double mu = o.smoothness > 0 ? o.smoothness * H.trace() / (DB.transpose() * DB).trace() : 0.0;
    H += mu * DB.transpose() * DB;
    const Eigen::VectorXd sigma = H.ldlt().solve(AB.transpose() * rho);
    Eigen::VectorXd curve = B[c] * sigma;
    if (curve.sum() < 0) curve = -curve;  // a basis sign flip cannot make a negative camera
    for (int l = 0; l < L; ++l)
      if (curve[l] < 0) {
        curve[l] = 0;
        ++out.clipped;
      }
    const Eigen::VectorXd pred = A * curve;
    const double ss = (pred - rho).squaredNorm(), ref = rho.squaredNorm();
    out.residual[c] = std::sqrt(ss / ref);
    ss_all += ss;
    ref_all += ref;
    out.ssf.values.push_back(std::vector<double>(curve.data(), curve.data() + L));
  }
  out.residual_rms = std::sqrt(ss_all / ref_all);
  double peak = 0;
  for (const auto& v : out.ssf.values) peak = std::max(peak, *std::max_element(v.begin(), v.end()));
  if (!(peak > 0)) throw Error(ErrorCode::IllPosed, "the estimated sensitivities are all zero");
  for (auto& v : out.ssf.values)
    for (auto& x : v) x /= peak;
  out.areas = channel_areas(out.ssf);
  return out;
}

namespace {

/// The camera RGB rows with a reflectance of the same patch id (normalise_patch_id), and those
/// reflectances as columns in the rows' order.
struct Pairs {
  SpectralData reflectances;
  std::vector<Vec3> RGB;
};
Pairs pair_by_id(const std::vector<std::string>& ids, const std::vector<Vec3>& rgb, const SpectralData& reflectances) {
  if (ids.size() != rgb.size())
    throw Error(ErrorCode::PatchMismatch, std::to_string(ids.size()) + " patch ids but " + std::to_string(rgb.size()) +
                                              " camera RGB rows");
  std::vector<std::string> names;
  for (const auto& n : reflectances.names) names.push_back(normalise_patch_id(n));
  Pairs p;
  p.reflectances.wavelengths = reflectances.wavelengths;
  p.reflectances.linear = reflectances.linear;
  for (size_t i = 0; i < ids.size(); ++i) {
    const auto k = std::find(names.begin(), names.end(), normalise_patch_id(ids[i]));
    if (k == names.end()) continue;
    p.reflectances.names.push_back(ids[i]);
    p.reflectances.values.push_back(reflectances.values[k - names.begin()]);
    p.RGB.push_back(rgb[i]);
  }
  if (p.RGB.empty())
    throw Error(ErrorCode::PatchMismatch, "no camera RGB patch id matches a reflectance (" +
                                              (ids.empty() ? std::string("no patches") : "e.g. '" + ids[0] + "'") + ")");
  return p;
}

}  // namespace

SensitivityEstimate estimate_sensitivities_by_id(const std::vector<std::string>& ids, const std::vector<Vec3>& rgb,
                                                 const SpectralData& reflectances, const SpectralData& illuminant,
                                                 const SensitivityOptions& o) {
  const Pairs p = pair_by_id(ids, rgb, reflectances);
  SensitivityEstimate e = estimate_sensitivities_Jiang2013(p.RGB, p.reflectances, illuminant, o);
  e.ids = p.reflectances.names;
  e.unpaired = static_cast<int>(ids.size() - p.RGB.size());
  return e;
}

SensitivityUncertainty sensitivity_uncertainty_by_id(const std::vector<std::string>& ids, const std::vector<Vec3>& rgb,
                                                     const SpectralData& reflectances, const SpectralData& illuminant,
                                                     const SensitivityOptions& options, const SensitivityEstimate& e,
                                                     const SensitivityUncertaintyOptions& uo) {
  const Pairs p = pair_by_id(ids, rgb, reflectances);
  return sensitivity_uncertainty(p.RGB, p.reflectances, illuminant, options, e, uo);
}

SensitivityUncertainty sensitivity_uncertainty(const std::vector<Vec3>& rgb, const SpectralData& reflectances,
                                               const SpectralData& illuminant, const SensitivityOptions& options,
                                               const SensitivityEstimate& e, const SensitivityUncertaintyOptions& uo) {
  SensitivityUncertainty u;
  u.coverage = uo.coverage;
  u.residual_limit = uo.residual_limit;
  u.distance_limit = uo.distance_limit;
  const auto ratios = [](const std::array<double, 3>& A) { return std::array<double, 2>{A[0] / A[1], A[2] / A[1]}; };
  u.ratio = ratios(e.areas);
  // Leave-one-camera-out bases: every basis camera left out in turn (jackknife).
  std::vector<std::string> basis_cameras;
  for (const auto& name : camera_names()) {
    bool out = false;
    for (const auto& x : options.exclude_cameras) out = out || fold(x) == fold(name);
    if (!out) basis_cameras.push_back(name);
  }
  std::vector<std::array<double, 2>> loo;
  for (const auto& cam : basis_cameras) {
    SensitivityOptions o = options;
    o.exclude_cameras.push_back(cam);
    if (static_cast<int>(basis_cameras.size()) - 1 < o.components) break;
    loo.push_back(ratios(estimate_sensitivities_Jiang2013(rgb, reflectances, illuminant, o).areas));
  }
  u.loo_bases = static_cast<int>(loo.size());
  // Basis size: K − 1, K, K + 1 where the patches and the basis allow.
  std::vector<std::array<double, 2>> byK;
  for (int K = options.components - 1; K <= options.components + 1; ++K) {
    if (K < 1 || K > 12 || K > static_cast<int>(rgb.size()) || K > static_cast<int>(basis_cameras.size())) continue;
    SensitivityOptions o = options;
    o.components = K;
    byK.push_back(K == options.components ? u.ratio : ratios(estimate_sensitivities_Jiang2013(rgb, reflectances, illuminant, o).areas));
    u.components_tried.push_back(K);
  }
  for (int r = 0; r < 2; ++r) {
    const double n = static_cast<double>(loo.size());
    if (n > 1) {
      double mean = 0, ss = 0;
      for (const auto& v : loo) mean += v[r] / n;
      for (const auto& v : loo) ss += (v[r] - mean) * (v[r] - mean);
      u.u_loo[r] = std::sqrt((n - 1) / n * ss) / u.ratio[r];
    }
    double lo = u.ratio[r], hi = u.ratio[r];
    for (const auto& v : byK) lo = std::min(lo, v[r]), hi = std::max(hi, v[r]);
    u.u_K[r] = 0.5 * (hi - lo) / u.ratio[r];
    u.u[r] = u.coverage * std::hypot(u.u_loo[r], u.u_K[r]);
  }
  // Distance to the nearest basis camera.
  u.nearest_distance = std::numeric_limits<double>::infinity();
  for (const auto& cam : basis_cameras) {
    const double d = sensitivity_rms(e.ssf, camera_ssf(cam));
    if (d < u.nearest_distance) u.nearest_distance = d, u.nearest_camera = cam;
  }
  char line[256];
  if (e.residual_rms > uo.residual_limit) {
    u.warnings.push_back("OUTSIDE_BASIS_RESIDUAL");
    std::snprintf(line, sizeof line, "the basis reproduces the camera's responses only to %.1f %% RMS (limit %.1f %%): "
                  "the camera is unlike the %d basis cameras, its areas may be off by more than stated",
                  100 * e.residual_rms, 100 * uo.residual_limit, static_cast<int>(basis_cameras.size()));
    u.message += (u.message.empty() ? "" : "; ") + std::string(line);
  }
  if (u.nearest_distance > uo.distance_limit) {
    u.warnings.push_back("OUTSIDE_BASIS_DISTANCE");
    std::snprintf(line, sizeof line, "the estimate is %.3f (RMS, peak 1) from the nearest basis camera (%s; limit %.3f): "
                  "the camera is unlike the basis cameras, its areas may be off by more than stated",
                  u.nearest_distance, u.nearest_camera.c_str(), uo.distance_limit);
    u.message += (u.message.empty() ? "" : "; ") + std::string(line);
  }
  return u;
}

double sensitivity_rms(const SpectralData& a, const SpectralData& b) {
  if (a.size() != 3 || b.size() != 3) throw Error(ErrorCode::InvalidArgument, "sensitivities need 3 channels");
  double ss = 0;
  size_t n = 0;
  for (int c = 0; c < 3; ++c) {
    const auto bv = interpolate_spectrum(b.wavelengths, b.values[c], a.wavelengths, b.linear);
    const double pa = *std::max_element(a.values[c].begin(), a.values[c].end());
    const double pb = *std::max_element(bv.begin(), bv.end());
    if (!(pa > 0) || !(pb > 0)) throw Error(ErrorCode::InvalidArgument, "a sensitivity curve has no positive value");
    for (size_t i = 0; i < bv.size(); ++i) {
      const double d = a.values[c][i] / pa - bv[i] / pb;
      ss += d * d;
      ++n;
    }
  }
  return std::sqrt(ss / n);
}

std::string sensitivities_to_csv(const SpectralData& ssf) {
  if (ssf.size() != 3) throw Error(ErrorCode::InvalidArgument, "sensitivities need 3 channels");
  double peak = 0;
  for (const auto& v : ssf.values) peak = std::max(peak, *std::max_element(v.begin(), v.end()));
  if (!(peak > 0)) throw Error(ErrorCode::InvalidArgument, "the sensitivities have no positive value");
  std::string out = "wavelength_nm,R,G,B\n";
  char buf[128];
  for (size_t i = 0; i < ssf.wavelengths.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.10g,%.8g,%.8g,%.8g\n", ssf.wavelengths[i], ssf.values[0][i] / peak,
                  ssf.values[1][i] / peak, ssf.values[2][i] / peak);
    out += buf;
  }
  return out;
}

}  // namespace tristim
