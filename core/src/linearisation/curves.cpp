// Curves every linearisation row shares: the fixed ones (identity, gamma, sRGB), polynomial and
// log-polynomial evaluation with numerical inverses, least-squares polynomial fits, R², the
// monotonicity check and the helpers for clipped samples.
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "rows.hpp"
#include "tristim/error.hpp"
#include "../detmath.hpp"

namespace tristim {

// ---- public building blocks ------------------------------------------------------------------

double polyval(const std::vector<double>& c, double x) {
  double y = 0;
  for (size_t k = c.size(); k-- > 0;) y = y * x + c[k];
  return y;
}

std::vector<double> polyfit(const std::vector<double>& x, const std::vector<double>& y, int degree) {
  if (degree < 0) throw Error(ErrorCode::InvalidArgument, "polynomial degree must be >= 0");
  const int n = static_cast<int>(x.size());
  if (n != static_cast<int>(y.size())) throw Error(ErrorCode::Internal, "polyfit: x and y differ in length");
  if (n < degree + 1)
    throw Error(ErrorCode::TooFewPatches, "a polynomial of degree " + std::to_string(degree) + " needs at least " +
                                              std::to_string(degree + 1) + " samples, got " + std::to_string(n));
  // Vandermonde in x shifted and scaled to [-1, 1]: the monomial basis on [0, 1] is badly
  // conditioned from degree ~5; the coefficients are mapped back to powers of x afterwards.
  const double lo = *std::min_element(x.begin(), x.end()), hi = *std::max_element(x.begin(), x.end());
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  if (degree > 0 && !(half > 1e-12 * std::max(1.0, std::fabs(mid))))
    throw Error(ErrorCode::IllConditioned, "every sample has the same value: no curve can be fitted");
  const double s = degree > 0 ? half : 1.0;
  Eigen::MatrixXd V(n, degree + 1);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const double t = (x[i] - mid) / s;
    double p = 1;
    for (int k = 0; k <= degree; ++k, p *= t) V(i, k) = p;
    b[i] = y[i];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(V);
  if (qr.rank() < degree + 1)
    throw Error(ErrorCode::IllConditioned, "only " + std::to_string(qr.rank()) + " distinct sample values for a degree-" +
                                               std::to_string(degree) + " polynomial");
  const Eigen::VectorXd a = qr.solve(b);
  // Σ a_k ((x - mid)/s)^k expanded in powers of x (binomial theorem).
  std::vector<double> c(degree + 1, 0.0);
  for (int k = 0; k <= degree; ++k) {
    double binom = 1;  // C(k, j)
    for (int j = 0; j <= k; ++j) {
      c[j] += a[k] * binom * detmath::pow(-mid, k - j) / detmath::pow(s, k);
      binom = binom * (k - j) / (j + 1);
    }
  }
  return c;
}

double coefficient_of_determination(const std::vector<double>& y, const std::vector<double>& fit) {
  double mean = 0;
  for (double v : y) mean += v;
  mean /= static_cast<double>(y.size());
  double ss_res = 0, ss_tot = 0;
  for (size_t i = 0; i < y.size(); ++i) {
    ss_res += (y[i] - fit[i]) * (y[i] - fit[i]);
    ss_tot += (y[i] - mean) * (y[i] - mean);
  }
  return ss_tot > 0 ? 1 - ss_res / ss_tot : std::numeric_limits<double>::quiet_NaN();
}

double squared_correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const size_t n = a.size();
  double ma = 0, mb = 0;
  for (size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= static_cast<double>(n);
  mb /= static_cast<double>(n);
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (!(saa > 0) || !(sbb > 0)) return std::numeric_limits<double>::quiet_NaN();
  return sab * sab / (saa * sbb);
}

double sRGB_decode(double v) {
  const double a = std::fabs(v);
  const double l = a <= 0.04045 ? a / 12.92 : detmath::pow((a + 0.055) / 1.055, 2.4);
  return v < 0 ? -l : l;
}

std::vector<std::string> split_ids(const std::string& list) {
  std::vector<std::string> out;
  std::string item;
  auto flush = [&] {
    const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
    if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
    item.clear();
  };
  for (char ch : list) {
    if (ch == ';' || ch == ',') flush();
    else item += ch;
  }
  flush();
  return out;
}

namespace linearisation_detail {

// ---- helpers ---------------------------------------------------------------------------------

void add_warning(Linearisation& l, const std::string& warning) {
  l.message += (l.message.empty() ? "" : "; ") + warning;
}

double full_scale_of(const LinearisationData& data) {
  if (data.full_scale > 0) return data.full_scale;
  double m = 0;
  for (Eigen::Index i = 0; i < data.camera_RGB.size(); ++i)
    if (std::isfinite(data.camera_RGB.data()[i])) m = std::max(m, data.camera_RGB.data()[i]);
  return m > 0 ? m : 1.0;
}

void check_data(const LinearisationData& data) {
  if (!data.ids.empty() && data.ids.size() != static_cast<size_t>(data.camera_RGB.rows()))
    throw Error(ErrorCode::PatchMismatch, "linearisation: " + std::to_string(data.ids.size()) + " ids for " +
                                              std::to_string(data.camera_RGB.rows()) + " rows of camera RGB");
  if (data.reference_XYZ.rows() != 0 && data.reference_XYZ.rows() != data.camera_RGB.rows())
    throw Error(ErrorCode::PatchMismatch, "linearisation: " + std::to_string(data.reference_XYZ.rows()) +
                                              " reference rows for " + std::to_string(data.camera_RGB.rows()) +
                                              " rows of camera RGB");
  if (!data.camera_RGB.allFinite()) throw Error(ErrorCode::NonFinite, "linearisation: camera RGB holds NaN or Inf");
  if (!data.reference_XYZ.allFinite()) throw Error(ErrorCode::NonFinite, "linearisation: reference XYZ holds NaN or Inf");
  if (!(data.full_scale >= 0) || !std::isfinite(data.full_scale))
    throw Error(ErrorCode::InvalidArgument, "linearisation: full scale must be a finite number >= 0");
}

std::vector<int> usable_rows(const LinearisationData& data, const std::vector<int>& candidates, int channel,
                             double full_scale, Linearisation& l) {
  static const char* kChannel = "RGB";
  std::vector<int> rows;
  std::vector<std::string> clipped;
  const bool known_scale = data.full_scale > 0;
  for (int r : candidates) {
    const double x = data.camera_RGB(r, channel) / full_scale;
    if (known_scale && (x <= 0 || x >= 1 - 0.5 / 255)) {
      clipped.push_back(data.ids.empty() ? std::to_string(r + 1) : data.ids[r]);
      continue;
    }
    rows.push_back(r);
  }
  if (!clipped.empty()) {
    std::string s;
    for (const auto& id : clipped) s += (s.empty() ? "" : " ") + id;
    add_warning(l, std::string("channel ") + kChannel[channel] + ": clipped (0 or full scale) and left out: " + s);
  }
  return rows;
}

void check_extrapolation(Linearisation& l, const LinearisationData& data) {
  static const char* kChannel = "RGB";
  l.extrapolated.clear();
  std::ostringstream above, below;
  std::string last_above, last_below;
  for (Eigen::Index r = 0; r < data.camera_RGB.rows(); ++r) {
    const std::string id = data.ids.empty() ? std::to_string(r + 1) : data.ids[static_cast<size_t>(r)];
    for (int c = 0; c < 3; ++c) {
      const double x = data.camera_RGB(r, c) / l.full_scale, lo = l.domain[c][0], hi = l.domain[c][1];
      if (!std::isfinite(x) || (x >= lo && x <= hi)) continue;
      const double bound = x > hi ? hi : lo;
      Extrapolation e{id, c, x, bound, (x - bound) / (bound != 0 ? std::fabs(bound) : hi - lo)};
      l.extrapolated.push_back(e);
      std::ostringstream& s = x > hi ? above : below;
      std::string& last = x > hi ? last_above : last_below;
      if (last != id) s << (last.empty() ? "" : "), ") << id << " (";
      else s << ", ";
      last = id;
      s << kChannel[c] << " " << std::showpos << std::fixed << std::setprecision(1) << 100 * e.relative << std::noshowpos << " %";
    }
  }
  if (!last_above.empty())
    add_warning(l, "extrapolated above the fitted range (relative to its top): " + above.str() + ")");
  if (!last_below.empty())
    add_warning(l, "extrapolated below the fitted range (relative to its bottom): " + below.str() + ")");
}

void record_fit(Linearisation& l, const LinearisationData& data, const std::array<std::vector<int>, 3>& rows,
                double full_scale) {
  std::vector<bool> used(static_cast<size_t>(data.camera_RGB.rows()), false);
  for (int c = 0; c < 3; ++c) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int r : rows[c]) {
      lo = std::min(lo, data.camera_RGB(r, c) / full_scale);
      hi = std::max(hi, data.camera_RGB(r, c) / full_scale);
      used[static_cast<size_t>(r)] = true;
    }
    if (rows[c].empty()) lo = 0, hi = 1;
    l.domain[c] = {lo, hi};
  }
  l.fitted.clear();
  for (size_t r = 0; r < used.size(); ++r)
    if (used[r]) l.fitted.push_back(data.ids.empty() ? std::to_string(r + 1) : data.ids[r]);
}

// ---- polynomial curves and their inverses -------------------------------------------------------

double apply_polynomial(const Linearisation& l, int c, double value) {
  return polyval(l.coefficients[c], value / l.full_scale);
}

double apply_log_polynomial(const Linearisation& l, int c, double value) {
  const double x = value / l.full_scale;
  return x > 0 ? detmath::exp(polyval(l.coefficients[c], detmath::log(x))) : 0.0;
}

namespace {

// Inverse of an increasing stretch of `apply` by bisection in x over [lo, hi]; the ends are
// returned (clamped) for values outside the curve's range there.
double invert(const Linearisation& l, int c, double y, double (*apply)(const Linearisation&, int, double)) {
  const double fs = l.full_scale;
  double lo = std::min(0.0, l.domain[c][0]), hi = std::max(1.0, l.domain[c][1]);
  // Restrict to the increasing stretch that holds the fitted range (scan 512 steps outward).
  const int steps = 512;
  const double dx = (hi - lo) / steps;
  const double a = l.domain[c][0], b = l.domain[c][1];
  double left = a, right = b;
  while (left - dx >= lo && apply(l, c, (left - dx) * fs) < apply(l, c, left * fs)) left -= dx;
  while (right + dx <= hi && apply(l, c, (right + dx) * fs) > apply(l, c, right * fs)) right += dx;
  if (left > lo && apply(l, c, lo * fs) < apply(l, c, left * fs)) left = lo;
  if (right < hi && apply(l, c, hi * fs) > apply(l, c, right * fs)) right = hi;
  double ylo = apply(l, c, left * fs), yhi = apply(l, c, right * fs);
  if (!(yhi > ylo)) return 0.5 * (left + right) * fs;  // a flat or decreasing curve: nothing better
  if (y <= ylo) return left * fs;
  if (y >= yhi) return right * fs;
  for (int it = 0; it < 100 && right - left > 1e-15 * std::max(1.0, std::fabs(right)); ++it) {
    const double m = 0.5 * (left + right);
    if (apply(l, c, m * fs) < y) left = m;
    else right = m;
  }
  return 0.5 * (left + right) * fs;
}

}  // namespace

double inverse_polynomial(const Linearisation& l, int c, double y) { return invert(l, c, y, apply_polynomial); }

double inverse_log_polynomial(const Linearisation& l, int c, double y) {
  if (!(y > 0)) return 0.0;
  return invert(l, c, y, apply_log_polynomial);
}

void check_monotonic(Linearisation& l, double (*apply)(const Linearisation&, int, double)) {
  static const char* kChannel = "RGB";
  for (int c = 0; c < 3; ++c) {
    const double a = l.domain[c][0], b = l.domain[c][1];
    if (!(b > a)) continue;
    const int n = 256;
    double prev = apply(l, c, a * l.full_scale);
    double first_bad = -1;
    for (int i = 1; i <= n; ++i) {
      const double x = a + (b - a) * i / n;
      const double y = apply(l, c, x * l.full_scale);
      if (!(y > prev)) {
        first_bad = x;
        break;
      }
      prev = y;
    }
    if (first_bad >= 0) {
      l.monotonic = false;
      std::ostringstream s;
      s.precision(3);
      s << "channel " << kChannel[c] << ": the curve is not increasing over the fitted range (x = " << a << " .. " << b
        << "; it stops increasing at x = " << first_bad << ")";
      add_warning(l, s.str());
    }
  }
}

// ---- identity, gamma, sRGB ---------------------------------------------------------------------

namespace {

Linearisation fit_fixed(const LinearisationData& data, const MethodChoice& choice) {
  check_data(data);
  Linearisation l;
  l.choice = choice;
  l.full_scale = full_scale_of(data);
  return l;
}

double apply_identity(const Linearisation&, int, double value) { return value; }

Linearisation fit_gamma(const LinearisationData& data, const MethodChoice& choice) {
  Linearisation l = fit_fixed(data, choice);
  for (auto& c : l.coefficients) c = {choice_number(choice, "gamma")};
  return l;
}

// OpenCV ccm's gammaCorrection: sign(x)·|x|^γ.
double apply_gamma(const Linearisation& l, int c, double value) {
  const double x = value / l.full_scale, g = l.coefficients[c].at(0);
  return x < 0 ? -detmath::pow(-x, g) : detmath::pow(x, g);
}
double inverse_gamma(const Linearisation& l, int c, double y) {
  const double g = l.coefficients[c].at(0);
  return (y < 0 ? -detmath::pow(-y, 1 / g) : detmath::pow(y, 1 / g)) * l.full_scale;
}

double apply_sRGB(const Linearisation& l, int, double value) { return sRGB_decode(value / l.full_scale); }
// The one sRGB encoder (colorimetry.hpp), odd-symmetric here; linear values above 1 map to full scale.
double inverse_sRGB(const Linearisation& l, int, double y) {
  return (y < 0 ? -sRGB_encode(-y) : sRGB_encode(y)) * l.full_scale;
}

}  // namespace

LinearisationMethod row_identity() {
  return {{"identity", "None (linear data, e.g. RAW)", "no inverse OECF: RAW values are linear in exposure already", {}},
          "", fit_fixed, apply_identity, apply_identity};
}

LinearisationMethod row_gamma() {
  OptionSpec g{"gamma", "number", "Exponent γ", 2.2, "", 0.1, 10, {},
               "linear = (stored / full scale)^γ; 2.2 is OpenCV ccm's default"};
  return {{"gamma", "Gamma (power law)", "OpenCV ccm LINEARIZATION_GAMMA", {g}}, "", fit_gamma, apply_gamma, inverse_gamma};
}

LinearisationMethod row_sRGB() {
  return {{"sRGB", "sRGB transfer function", "IEC 61966-2-1:1999", {}}, "", fit_fixed, apply_sRGB, inverse_sRGB};
}

}  // namespace linearisation_detail
}  // namespace tristim
