// ACES IDT (profile/idt.hpp): the rawtoaces v1 / P-2013-001 matrix by Levenberg–Marquardt.
#include "tristim/profile/idt.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "tristim/data.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "../detmath.hpp"

namespace tristim {

Mat3 aces2065_1_to_XYZ() {
  // SMPTE ST 2065-1 AP0 primaries and white; NPM = P·diag(P⁻¹·W) (SMPTE RP 177 eq 3.3).
  const double xy[3][2] = {{0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.0770}};
  Mat3 P;
  // Each primary's XYZ with Y = y (x, y, 1 - x - y): AP0's blue has y < 0, so no division by y.
  for (int i = 0; i < 3; ++i) P.col(i) = Vec3(xy[i][0], xy[i][1], 1.0 - xy[i][0] - xy[i][1]);
  const Vec3 S = P.inverse() * aces_white_XYZ();
  return P * S.asDiagonal();
}

Vec3 aces_white_XYZ() { return xyY_to_XYZ(Vec3(0.32168, 0.33767, 1.0)); }

const SpectralData& idt_training_190() {
  static const SpectralData set = [] {
    const char* name = "reflectances/training_190patches_reflectance_380-780_5nm.csv";
    return read_spectral_csv(builtin_file(name), name);
  }();
  return set;
}

ChromaticAdaptation idt_adaptation(const std::string& id) {
  std::string s;
  for (char c : id) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "cat02") return ChromaticAdaptation::CAT02;
  if (s == "bradford") return ChromaticAdaptation::Bradford;
  throw Error(ErrorCode::UnknownId, "unknown chromatic adaptation '" + id + "' (CAT02 or Bradford)");
}

const char* idt_adaptation_name(ChromaticAdaptation a) {
  return a == ChromaticAdaptation::Bradford ? "Bradford" : a == ChromaticAdaptation::CAT02 ? "CAT02" : "von Kries";
}

namespace {

// CIE 15:2004 eq 8.1-8.3: f(t) and its derivative (the exact constants of XYZ_to_Lab).
constexpr double kEps = 216.0 / 24389.0, kKappa = 24389.0 / 27.0;
// detmath: the same bits natively and in wasm (docs/reproducibility.md).
double df_Lab(double t) { return t > kEps ? 1.0 / (3.0 * detmath::cbrt(t * t)) : kKappa / 116.0; }

void check_finite(const std::vector<Vec3>& v, const char* what) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!v[i].allFinite())
      throw Error(ErrorCode::NonFinite, std::string(what) + " of sample " + std::to_string(i + 1) + " is not finite");
}

// What every IDT fit needs of its training pairs: as many camera RGB as reference XYZ rows, at
// least 3 (the matrix's rank), all finite. `who` starts the messages, `unit` names a row.
void check_pairs(const std::vector<Vec3>& rgb, const std::vector<Vec3>& xyz, const std::string& who, const char* unit) {
  if (rgb.size() != xyz.size())
    throw Error(ErrorCode::InvalidArgument, who + ": " + std::to_string(rgb.size()) + " camera RGB rows but " +
                                                std::to_string(xyz.size()) + " reference rows");
  if (rgb.size() < 3)
    throw Error(ErrorCode::TooFewPatches,
                who + ": " + std::to_string(rgb.size()) + " " + unit + "; the matrix needs at least 3");
  check_finite(rgb, "camera RGB");
  check_finite(xyz, "reference XYZ");
}

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

Mat3 matrix_of(const Vec6& x) {  // rows summing to one: B(i,2) = 1 - B(i,0) - B(i,1)
  Mat3 B;
  for (int i = 0; i < 3; ++i) B.row(i) << x[2 * i], x[2 * i + 1], 1.0 - x[2 * i] - x[2 * i + 1];
  return B;
}

struct Objective {
  const std::vector<Vec3>& rgb;
  std::vector<Vec3> lab_target;
  Mat3 N = aces2065_1_to_XYZ();
  Vec3 white = aces_white_XYZ();

  double cost(const Vec6& x) const {
    const Mat3 M = N * matrix_of(x);
    double s = 0;
    for (size_t p = 0; p < rgb.size(); ++p) s += (XYZ_to_Lab(M * rgb[p], white) - lab_target[p]).squaredNorm();
    return s;
  }
  // Normal equations JᵀJ, Jᵀr of the 3N residuals Lab(N·B·ρ) − Lab_target.
  void normal(const Vec6& x, Mat6& JtJ, Vec6& Jtr) const {
    const Mat3 M = N * matrix_of(x);
    JtJ.setZero();
    Jtr.setZero();
    for (size_t p = 0; p < rgb.size(); ++p) {
      const Vec3 XYZ = M * rgb[p];
      const Vec3 r = XYZ_to_Lab(XYZ, white) - lab_target[p];
      const double dx = df_Lab(XYZ[0] / white[0]) / white[0], dy = df_Lab(XYZ[1] / white[1]) / white[1],
                   dz = df_Lab(XYZ[2] / white[2]) / white[2];
      Mat3 D;  // ∂Lab/∂XYZ
      D << 0, 116 * dy, 0, 500 * dx, -500 * dy, 0, 0, 200 * dy, -200 * dz;
      const Mat3 DN = D * N;  // ∂Lab/∂(B·ρ)
      Eigen::Matrix<double, 3, 6> J;
      for (int i = 0; i < 3; ++i) {
        J.col(2 * i) = DN.col(i) * (rgb[p][0] - rgb[p][2]);
        J.col(2 * i + 1) = DN.col(i) * (rgb[p][1] - rgb[p][2]);
      }
      JtJ.noalias() += J.transpose() * J;
      Jtr.noalias() += J.transpose() * r;
    }
  }
};

}  // namespace

IdtResult fit_idt(const std::vector<Vec3>& rgb, const std::vector<Vec3>& xyz, const Vec3& white_balance,
                  const IdtOptions& options) {
  check_pairs(rgb, xyz, "IDT fit", "samples");
  Objective f{rgb, {}};
  f.lab_target.reserve(xyz.size());
  for (const Vec3& v : xyz) f.lab_target.push_back(XYZ_to_Lab(v, f.white));

  // Levenberg–Marquardt (Marquardt's scaling by diag JᵀJ), from B = I as rawtoaces and colour start.
  Vec6 x;
  x << 1, 0, 0, 1, 0, 0;
  double c = f.cost(x), lambda = 1e-3;
  int it = 0;
  bool converged = false;
  for (; it < 500 && !converged; ++it) {
    Mat6 JtJ;
    Vec6 Jtr;
    f.normal(x, JtJ, Jtr);
    for (;;) {
      Mat6 A = JtJ;
      A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-12);
      const Vec6 step = A.ldlt().solve(-Jtr);
      const Vec6 xn = x + step;
      const double cn = f.cost(xn);
      if (std::isfinite(cn) && cn <= c) {
        converged = step.norm() <= 1e-13 * (1 + x.norm()) || c - cn <= 1e-16 * c;
        x = xn;
        c = cn;
        lambda = std::max(lambda / 10, 1e-12);
        break;
      }
      lambda *= 10;
      if (lambda > 1e12) {
        converged = true;  // no descent direction left: a (local) minimum to machine precision
        break;
      }
    }
  }
  if (!x.allFinite()) throw Error(ErrorCode::FitFailed, "IDT fit: the solver diverged");

  IdtResult r;
  r.matrix = matrix_of(x);
  r.white_balance = white_balance;
  r.adaptation = idt_adaptation_name(options.adaptation);
  r.patches = static_cast<int>(rgb.size());
  r.iterations = it;
  r.objective = std::sqrt(c);
  r.white_balanced_RGB = rgb;
  r.target_XYZ = xyz;
  const Mat3 M = f.N * r.matrix;
  for (size_t p = 0; p < rgb.size(); ++p) {
    const Vec3 lab = XYZ_to_Lab(M * rgb[p], f.white);
    r.delta_E76.push_back(delta_E_CIE1976(f.lab_target[p], lab));
    r.delta_E00.push_back(delta_E_CIE2000(f.lab_target[p], lab));
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double d : v) s += d;
    return s / static_cast<double>(v.size());
  };
  r.mean_delta_E76 = mean(r.delta_E76);
  r.mean_delta_E00 = mean(r.delta_E00);
  r.max_delta_E76 = *std::max_element(r.delta_E76.begin(), r.delta_E76.end());
  r.max_delta_E00 = *std::max_element(r.delta_E00.begin(), r.delta_E00.end());
  if (!converged) {
    r.status = "warning";
    r.message = "the solver stopped after " + std::to_string(it) + " iterations before converging";
  }
  return r;
}

IdtTraining idt_training_from_spectra(const SpectralData& ssf, const SpectralData& illuminant,
                                      const SpectralData& reflectances, ChromaticAdaptation adaptation) {
  if (ssf.size() != 3) throw Error(ErrorCode::InvalidArgument, "IDT: the sensitivities need 3 columns (R, G, B), not " + std::to_string(ssf.size()));
  if (illuminant.size() < 1) throw Error(ErrorCode::InvalidArgument, "IDT: the illuminant has no spectral column");
  if (reflectances.size() < 1) throw Error(ErrorCode::EmptyFile, "IDT: the training set has no reflectance");
  auto covers = [](const std::vector<double>& w) { return !w.empty() && w.front() < 780 && w.back() > 380; };
  if (!covers(ssf.wavelengths) || !covers(illuminant.wavelengths) || !covers(reflectances.wavelengths))
    throw Error(ErrorCode::WavelengthMismatch, "IDT: sensitivities, illuminant and reflectances must each cover part of 380-780 nm");
  // rawtoaces' shape, 380-780 nm at 5 nm: sums over it stand for the integrals.
  const std::vector<double> grid = wavelength_grid(380, 780, 5);
  const SpectralData S = align_spectra(ssf, grid), R = align_spectra(reflectances, grid),
                     cmf = align_spectra(cmfs(Observer::CIE1931_2), grid);
  std::vector<double> I = interpolate_spectrum(illuminant.wavelengths, illuminant.values[0], grid, illuminant.linear);
  const size_t n = grid.size();

  int cmax = 0;  // the channel whose sensitivity peaks highest (colour's normalise_illuminant)
  double peak = -1;
  for (int c = 0; c < 3; ++c)
    for (double v : S.values[c])
      if (v > peak) peak = v, cmax = c;
  double k = 0;
  for (size_t i = 0; i < n; ++i) k += I[i] * S.values[cmax][i];
  if (!(k > 0) || !std::isfinite(k)) throw Error(ErrorCode::InvalidArgument, "IDT: the camera has no response to the illuminant");
  for (double& v : I) v /= k;

  Vec3 white = Vec3::Zero();
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < n; ++i) white[c] += I[i] * S.values[c][i];
  if (!(white.minCoeff() > 0))
    throw Error(ErrorCode::InvalidArgument, "IDT: a channel of the camera has no positive response to the illuminant's white");

  IdtTraining t;
  t.white_balance = Vec3(white[1] / white[0], 1.0, white[1] / white[2]);
  double ybar = 0;
  Vec3 XYZ_w = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) {
    ybar += I[i] * cmf.values[1][i];
    for (int c = 0; c < 3; ++c) XYZ_w[c] += I[i] * cmf.values[c][i];
  }
  XYZ_w /= ybar;
  const Mat3 cat = chromatic_adaptation_matrix(XYZ_w, aces_white_XYZ(), adaptation);
  for (size_t p = 0; p < R.size(); ++p) {
    Vec3 rho = Vec3::Zero(), XYZ = Vec3::Zero();
    for (size_t i = 0; i < n; ++i) {
      const double ir = I[i] * R.values[p][i];
      for (int c = 0; c < 3; ++c) {
        rho[c] += ir * S.values[c][i];
        XYZ[c] += ir * cmf.values[c][i];
      }
    }
    t.white_balanced_RGB.push_back(rho.cwiseProduct(t.white_balance) / white[1]);
    t.target_XYZ.push_back(cat * (XYZ / ybar));
  }
  return t;
}

IdtResult idt_from_sensitivities(const SpectralData& ssf, const SpectralData& illuminant, const SpectralData& reflectances,
                                 const IdtOptions& options) {
  const IdtTraining t = idt_training_from_spectra(ssf, illuminant, reflectances, options.adaptation);
  return fit_idt(t.white_balanced_RGB, t.target_XYZ, t.white_balance, options);
}

IdtResult idt_from_patches(const std::vector<Vec3>& camera_RGB, const std::vector<Vec3>& reference_XYZ,
                           const Vec3& illuminant_white_XYZ, const IdtOptions& options) {
  check_pairs(camera_RGB, reference_XYZ, "IDT", "patches");
  if (!illuminant_white_XYZ.allFinite() || !(illuminant_white_XYZ.minCoeff() > 0))
    throw Error(ErrorCode::InvalidArgument, "IDT: the illuminant's white XYZ must be positive");
  const Vec3 white = illuminant_white_XYZ / illuminant_white_XYZ[1];
  // The white balance: the most neutral bright patch of the reference (C*ab <= 4, highest L*).
  size_t pick = 0;
  double best_L = -1, best_C = 1e300;
  size_t least_C = 0;
  for (size_t p = 0; p < reference_XYZ.size(); ++p) {
    const Vec3 lab = XYZ_to_Lab(reference_XYZ[p] / illuminant_white_XYZ[1], white);
    const double C = std::sqrt(lab[1] * lab[1] + lab[2] * lab[2]);
    if (C < best_C) best_C = C, least_C = p;
    if (C <= 4 && lab[0] > best_L && camera_RGB[p].minCoeff() > 0) best_L = lab[0], pick = p;
  }
  const bool neutral_found = best_L >= 0;
  if (!neutral_found) pick = least_C;
  const Vec3 n = camera_RGB[pick];
  if (!(n.minCoeff() > 0))
    throw Error(ErrorCode::NegativeValue, "IDT: the neutral patch " + std::to_string(pick + 1) + " has a camera value <= 0");
  const Vec3 wb(n[1] / n[0], 1.0, n[1] / n[2]);
  const double scale = (reference_XYZ[pick][1] / illuminant_white_XYZ[1]) / n[1];
  const Mat3 cat = chromatic_adaptation_matrix(white, aces_white_XYZ(), options.adaptation);
  std::vector<Vec3> rgb, xyz;
  for (size_t p = 0; p < camera_RGB.size(); ++p) {
    rgb.push_back(camera_RGB[p].cwiseProduct(wb) * scale);
    xyz.push_back(cat * (reference_XYZ[p] / illuminant_white_XYZ[1]));
  }
  IdtResult r = fit_idt(rgb, xyz, wb, options);
  r.exposure = scale;
  if (!neutral_found) {
    r.status = "warning";
    r.message = "no reference patch has C*ab <= 4: the white balance comes from patch " + std::to_string(pick + 1) +
                " (C*ab " + std::to_string(best_C) + ")";
  }
  return r;
}

}  // namespace tristim
