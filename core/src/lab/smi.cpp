// Camera quality as a colorimeter: ISO 17321-1 SMI and the Vora–Trussell μ-factor (rules in
// tristim/lab/smi.hpp).
#include "tristim/lab/smi.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <mutex>

#include "../optimise/bounded.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/data.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

const char* kIsoFile = "charts/colorchecker24_n_ohta_iso17321-1_reflectance_380-780_5nm.csv";
constexpr int kSmiPatches = 18;  // ISO 17321-1: the chromatic patches 1-18

using Mat = Eigen::MatrixXd;

void check_ssf(const SpectralData& s) {
  if (s.size() != 3) throw Error(ErrorCode::InvalidArgument, "camera sensitivities need exactly 3 channels (R, G, B)");
}

// The 18 chromatic patches: XYZ (Y_white = 100), camera RGB (white's G = 1) and both whites.
struct SmiData {
  std::vector<Vec3> XYZ, RGB;
  Vec3 white_XYZ, white_RGB;
};

SmiData smi_data(const SpectralData& ssf, const SpectralData& illuminant) {
  check_ssf(ssf);
  SpectralData refl = iso17321_reflectances();
  refl.names.resize(kSmiPatches);
  refl.values.resize(kSmiPatches);
  // The observer is summed exactly as the camera is (the virtual camera's rule on the camera's
  // grid, the CMFs sampled there), so a camera whose curves are the CMFs scores 100 to rounding.
  SpectralData observer = align_spectra(cmfs(Observer::CIE1931_2), ssf.wavelengths);
  SpectralData flat = refl;
  flat.names = {"white"};
  flat.values = {std::vector<double>(refl.wavelengths.size(), 1.0)};
  SmiData d;
  d.XYZ = simulate_camera_RGB(observer, refl, illuminant);  // Y of the white diffuser = 1
  for (auto& x : d.XYZ) x *= 100;
  d.white_XYZ = 100 * simulate_camera_RGB(observer, flat, illuminant)[0];
  d.RGB = simulate_camera_RGB(ssf, refl, illuminant);
  d.white_RGB = simulate_camera_RGB(ssf, flat, illuminant)[0];
  if (!(d.white_RGB.minCoeff() > 0))
    throw Error(ErrorCode::InvalidArgument, "camera sensitivities with no response in a channel under this illuminant");
  return d;
}

std::vector<double> delta_Es(const SmiData& d, const Mat3& M) {
  std::vector<double> out;
  for (size_t i = 0; i < d.XYZ.size(); ++i)
    out.push_back(delta_E_CIE1976(XYZ_to_Lab(M * d.RGB[i], d.white_XYZ), XYZ_to_Lab(d.XYZ[i], d.white_XYZ)));
  return out;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

CameraQuality finish(const SmiData& d, const Mat3& M, const std::string& camera, double mu) {
  CameraQuality q;
  q.camera = camera;
  q.dE = delta_Es(d, M);
  q.mean_dE = mean(q.dE);
  q.smi = 100 - 5.5 * q.mean_dE;
  q.mu_factor = mu;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) q.matrix[static_cast<size_t>(3 * r + c)] = M(r, c);
  return q;
}

// The n×3 matrix of curves on `grid`, each multiplied by the illuminant there.
Mat weighted(const SpectralData& curves, const std::vector<double>& grid, const std::vector<double>& L) {
  Mat X(grid.size(), 3);
  for (int c = 0; c < 3; ++c) {
    const auto v = interpolate_spectrum(curves.wavelengths, curves.values[static_cast<size_t>(c)], grid, curves.linear);
    for (size_t i = 0; i < grid.size(); ++i) X(static_cast<Eigen::Index>(i), c) = L[i] * v[i];
  }
  return X;
}

std::vector<double> illuminant_on(const SpectralData& illuminant, const std::vector<double>& grid) {
  if (illuminant.size() < 1) throw Error(ErrorCode::InvalidArgument, "illuminant without values");
  return interpolate_spectrum(illuminant.wavelengths, illuminant.values[0], grid, illuminant.linear);
}

}  // namespace

const SpectralData& iso17321_reflectances() {
  static std::once_flag once;
  static SpectralData d;
  std::call_once(once, [] { d = read_spectral_csv(builtin_file(kIsoFile), kIsoFile); });
  return d;
}

double mu_factor_VoraTrussell1993(const SpectralData& ssf, const SpectralData& illuminant) {
  check_ssf(ssf);
  const auto& grid = ssf.wavelengths;
  const auto L = illuminant_on(illuminant, grid);
  const Mat A = weighted(cmfs(Observer::CIE1931_2), grid, L), S = weighted(ssf, grid, L);
  // trace(P_A P_S) = ‖Q_Aᵀ Q_S‖²_F with orthonormal bases Q of the two column spaces.
  const Mat QA = A.householderQr().householderQ() * Mat::Identity(A.rows(), 3);
  const Mat QS = S.householderQr().householderQ() * Mat::Identity(S.rows(), 3);
  if (S.colPivHouseholderQr().rank() < 3)
    throw Error(ErrorCode::InvalidArgument, "camera sensitivities are linearly dependent (rank < 3)");
  return (QA.transpose() * QS).squaredNorm() / 3.0;
}

CameraQuality camera_quality_with_matrix(const SpectralData& ssf, const SpectralData& illuminant,
                                         const std::array<double, 9>& m, const std::string& camera) {
  const SmiData d = smi_data(ssf, illuminant);
  Mat3 M;
  M << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8];
  return finish(d, M, camera, mu_factor_VoraTrussell1993(ssf, illuminant));
}

CameraQuality camera_quality(const SpectralData& ssf, const SpectralData& illuminant, const std::string& camera) {
  const SmiData d = smi_data(ssf, illuminant);
  const Eigen::Index n = static_cast<Eigen::Index>(d.XYZ.size());
  Mat R(3, n), X(3, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    R.col(i) = d.RGB[static_cast<size_t>(i)];
    X.col(i) = d.XYZ[static_cast<size_t>(i)];
  }
  // White-point preserving least squares (Finlayson & Drew 1997): the least-squares matrix moved
  // along (R Rᵀ)⁻¹ r_w until it maps r_w onto x_w.
  const Mat3 G = (R * R.transpose()).inverse();
  const Mat3 Mls = X * R.transpose() * G;
  const Vec3 rw = d.white_RGB, xw = d.white_XYZ;
  const Eigen::RowVector3d gw = rw.transpose() * G;
  const Mat3 M0 = Mls + (xw - Mls * rw) * gw / (gw * rw).value();
  // Matrices keeping the white: M0 + Q Bᵀ, B an orthonormal basis of r_w's complement (Bᵀ r_w = 0).
  const Mat3 Qr = rw.householderQr().householderQ();
  const Eigen::Matrix<double, 3, 2> B = Qr.rightCols<2>();
  auto matrix = [&](const double* p) {
    Eigen::Matrix<double, 3, 2> Q;
    Q << p[0], p[1], p[2], p[3], p[4], p[5];
    return Mat3(M0 + Q * B.transpose());
  };
  const double scale = M0.cwiseAbs().maxCoeff();
  optimise::BoundedOptions o;
  o.algorithm = optimise::Algorithm::Bobyqa;
  o.lower.assign(6, -10 * scale);
  o.upper.assign(6, 10 * scale);
  o.initial_step.assign(6, 0.05 * scale);
  o.xtol_rel = 1e-10;
  o.max_evaluations = 20000;
  const auto best = optimise::minimise_bounded([&](const double* p) { return mean(delta_Es(d, matrix(p))); },
                                               std::vector<double>(6, 0.0), o);
  // The optimiser's answer unless it failed or did worse than its start.
  const Mat3 M = !best.failed && best.f <= mean(delta_Es(d, M0)) ? matrix(best.x.data()) : M0;
  return finish(d, M, camera, mu_factor_VoraTrussell1993(ssf, illuminant));
}

std::vector<CameraQuality> camera_quality_ranking(const SpectralData& illuminant) {
  std::vector<CameraQuality> out;
  for (const auto& name : camera_names()) out.push_back(camera_quality(camera_ssf(name), illuminant, name));
  std::stable_sort(out.begin(), out.end(), [](const CameraQuality& a, const CameraQuality& b) {
    return a.smi != b.smi ? a.smi > b.smi : a.camera < b.camera;
  });
  return out;
}

LutherFit luther_fit(const SpectralData& ssf, const SpectralData& illuminant) {
  check_ssf(ssf);
  const auto& grid = ssf.wavelengths;
  const auto L = illuminant_on(illuminant, grid);
  const std::vector<double> ones(grid.size(), 1.0);
  const Mat A = weighted(cmfs(Observer::CIE1931_2), grid, L), S = weighted(ssf, grid, L);
  const Mat A1 = weighted(cmfs(Observer::CIE1931_2), grid, ones);
  const Mat C = A.colPivHouseholderQr().solve(S);  // 3×3: column c = a_·c
  const Mat F = A1 * C;
  LutherFit out;
  out.wavelengths = grid;
  double peak = 0;
  for (const auto& v : ssf.values)
    for (double x : v) peak = std::max(peak, x);
  if (!(peak > 0)) throw Error(ErrorCode::InvalidArgument, "camera sensitivities are all zero");
  for (int c = 0; c < 3; ++c) {
    const size_t cc = static_cast<size_t>(c);
    for (size_t i = 0; i < grid.size(); ++i) {
      out.camera[cc].push_back(ssf.values[cc][i] / peak);
      out.fit[cc].push_back(F(static_cast<Eigen::Index>(i), c) / peak);
    }
    for (int k = 0; k < 3; ++k) out.coefficients[static_cast<size_t>(3 * k + c)] = C(k, c) / peak;
  }
  return out;
}

namespace fields {
using Q = CameraQuality;
TRISTIM_FIELDS_DEFINE(Q, member<&Q::camera>("camera"), member<&Q::smi>("smi"), member<&Q::mu_factor>("mu_factor"),
                      member<&Q::mean_dE>("mean_dE"), member<&Q::matrix>("matrix"), member<&Q::dE>("dE"));
}  // namespace fields

json::Value camera_quality_json(const CameraQuality& q) {
  return fields::write_picked(q, {"camera", "smi", "mu_factor", "mean_dE"});
}

}  // namespace tristim
