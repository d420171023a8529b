// Spectral distributions, built-in CIE tables and spectrum -> XYZ (rules in tristim/spectra.hpp).
#include "tristim/colorimetry/spectra.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "tristim/data.hpp"
#include "tristim/error.hpp"
#include "tristim/number.hpp"

namespace tristim {

const std::vector<double>& SpectralData::column(std::string_view name) const {
  for (size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return values[k];
  throw Error(ErrorCode::MissingColumn, "no spectral column '" + std::string(name) + "'");
}

bool is_uniform(const std::vector<double>& w) {
  if (w.size() < 2) return false;
  const double h = w[1] - w[0];
  for (size_t i = 2; i < w.size(); ++i)
    if (std::abs((w[i] - w[i - 1]) - h) > 1e-9 * std::abs(h)) return false;
  return true;
}

std::vector<double> wavelength_grid(double start, double end, double step) {
  if (!(step > 0) || !(end >= start)) throw Error(ErrorCode::InvalidArgument, "bad wavelength grid");
  std::vector<double> out;
  const long n = std::lround((end - start) / step);
  for (long i = 0; i <= n; ++i) out.push_back(start + step * static_cast<double>(i));
  return out;
}

namespace {
// Sprague's boundary: two extra points per end, each a combination of the 6 nearest samples
// (CIE 167:2005 Table 4, colour's SPRAGUE_C_COEFFICIENTS), over 209. Row for index j = -2, -1, n, n+1.
const double kSpragueBoundary[4][6] = {{884, -1960, 3033, -2648, 1080, -180},
                                       {508, -540, 488, -367, 144, -24},
                                       {-24, 144, -367, 488, -540, 508},
                                       {-180, 1080, -2648, 3033, -1960, 884}};
const double* sprague_boundary_row(long j, size_t n) {
  return j == -2 ? kSpragueBoundary[0] : j == -1 ? kSpragueBoundary[1] : j == static_cast<long>(n) ? kSpragueBoundary[2] : kSpragueBoundary[3];
}
/// The interval Sprague's quintic is taken on for position t (in steps from the first sample) of
/// n samples: left node i, and X = t − i in [0, 1].
void sprague_interval(double t, size_t n, long& i, double& X) {
  i = static_cast<long>(std::floor(t));
  if (i >= static_cast<long>(n) - 1) i = static_cast<long>(n) - 2;
  if (i < 0) i = 0;
  X = t - static_cast<double>(i);
}
}  // namespace

double sprague_interpolate(const std::vector<double>& y, double x0, double h, double x) {
  const size_t n = y.size();
  auto r = [&](long j) -> double {  // j is an index into y, may be -2..n+1
    if (j >= 0 && j < static_cast<long>(n)) return y[static_cast<size_t>(j)];
    const double* c = sprague_boundary_row(j, n);
    const size_t base = j < 0 ? 0 : n - 6;
    double s = 0;
    for (int k = 0; k < 6; ++k) s += c[k] * y[base + k];
    return s / 209.0;
  };
  long i = 0;
  double X = 0;
  sprague_interval((x - x0) / h, n, i, X);
  if (X == 0.0) return y[static_cast<size_t>(i)];
  const double rm2 = r(i - 2), rm1 = r(i - 1), r0 = r(i), r1 = r(i + 1), r2 = r(i + 2), r3 = r(i + 3);
  // Sprague (1880) quintic through r0, r1 (CIE 167:2005 eq 6; colour's SpragueInterpolator).
  const double a0 = r0;
  const double a1 = (2 * rm2 - 16 * rm1 + 16 * r1 - 2 * r2) / 24;
  const double a2 = (-rm2 + 16 * rm1 - 30 * r0 + 16 * r1 - r2) / 24;
  const double a3 = (-9 * rm2 + 39 * rm1 - 70 * r0 + 66 * r1 - 33 * r2 + 7 * r3) / 24;
  const double a4 = (13 * rm2 - 64 * rm1 + 126 * r0 - 124 * r1 + 61 * r2 - 12 * r3) / 24;
  const double a5 = (-5 * rm2 + 25 * rm1 - 50 * r0 + 50 * r1 - 25 * r2 + 5 * r3) / 24;
  return a0 + a1 * X + a2 * X * X + a3 * X * X * X + a4 * X * X * X * X + a5 * X * X * X * X * X;
}

namespace {
void check_sizes(const std::vector<double>& w, size_t values) {
  if (w.empty() || w.size() != values)
    throw Error(ErrorCode::InvalidArgument, "spectrum with " + std::to_string(w.size()) + " wavelengths and " +
                                                std::to_string(values) + " values");
}
void check_increasing(const std::vector<double>& w) {
  for (size_t i = 1; i < w.size(); ++i)
    if (!(w[i] > w[i - 1]))
      throw Error(ErrorCode::NonMonotonic, "wavelengths not strictly increasing at " + std::to_string(w[i]) + " nm");
}
}  // namespace

std::vector<double> interpolate_spectrum(const std::vector<double>& w, const std::vector<double>& v,
                                         const std::vector<double>& nw, bool linear) {
  check_sizes(w, v.size());
  check_increasing(w);
  const bool sprague = !linear && w.size() >= 6 && is_uniform(w);
  const double h = w.size() > 1 ? w[1] - w[0] : 1;
  std::vector<double> out(nw.size());
  for (size_t k = 0; k < nw.size(); ++k) {
    const double x = nw[k];
    if (x <= w.front()) {
      out[k] = v.front();  // constant extrapolation (and the first node)
    } else if (x >= w.back()) {
      out[k] = v.back();
    } else if (sprague) {
      out[k] = sprague_interpolate(v, w.front(), h, x);
    } else {
      const size_t j = static_cast<size_t>(std::upper_bound(w.begin(), w.end(), x) - w.begin());  // w[j-1] <= x < w[j]
      const double f = (x - w[j - 1]) / (w[j] - w[j - 1]);
      out[k] = f == 0.0 ? v[j - 1] : v[j - 1] + f * (v[j] - v[j - 1]);
    }
  }
  return out;
}

PulledBackWeights pull_back_weights(const std::vector<double>& w, bool linear, const std::vector<double>& nw,
                                    const std::vector<double>& x, const std::vector<double>& y,
                                    const std::vector<double>& z) {
  check_sizes(w, w.size());
  check_increasing(w);
  for (const auto* c : {&x, &y, &z})
    if (c->size() != nw.size())
      throw Error(ErrorCode::InvalidArgument, "weights with " + std::to_string(c->size()) + " values for " +
                                                  std::to_string(nw.size()) + " wavelengths");
  // Row k of the interpolation matrix A holds the coefficients interpolate_spectrum applies to v at
  // nw[k]; accumulate weights[c][k] · (row k) into Aᵀ weights. Same branches, same index choices,
  // and a sample counts as read exactly when interpolate_spectrum reads it.
  const size_t n = w.size();
  const bool sprague = !linear && n >= 6 && is_uniform(w);
  const double h = n > 1 ? w[1] - w[0] : 1;
  // The sums in one array, sample-major (full[3 j + c]), each accumulated in the order of row k.
  std::vector<double> full(3 * n, 0.0);
  std::vector<char> read(n, 0);
  const double *wx = x.data(), *wy = y.data(), *wz = z.data();
  auto add = [&](size_t j, double a, size_t k) {
    read[j] = 1;
    double* f = &full[3 * j];
    f[0] += a * wx[k];
    f[1] += a * wy[k];
    f[2] += a * wz[k];
  };
  // Sprague (1880) quintic of sprague_interpolate, eq 6 of CIE 167:2005, written per sample:
  // value = Σ_q r_q (δ_q0 + Σ_p P[p][q] X^p / 24), q = -2..3 around the interval's left node.
  static const double P[5][6] = {{2, -16, 0, 16, -2, 0},
                                 {-1, 16, -30, 16, -1, 0},
                                 {-9, 39, -70, 66, -33, 7},
                                 {13, -64, 126, -124, 61, -12},
                                 {-5, 25, -50, 50, -25, 5}};
  for (size_t k = 0; k < nw.size(); ++k) {
    const double x = nw[k];
    if (x <= w.front()) {
      add(0, 1.0, k);
    } else if (x >= w.back()) {
      add(n - 1, 1.0, k);
    } else if (sprague) {
      long i = 0;
      double X = 0;
      sprague_interval((x - w.front()) / h, n, i, X);  // the interval sprague_interpolate takes
      if (X == 0.0) {
        add(static_cast<size_t>(i), 1.0, k);
        continue;
      }
      // The six coefficients first (independent of each other), then their sums.
      double coef[6];
      for (int q = 0; q < 6; ++q) {
        double a = P[4][q];
        for (int p = 3; p >= 0; --p) a = a * X + P[p][q];
        coef[q] = a * X / 24;
      }
      coef[2] += 1.0;  // a0 = r0
      for (int q = 0; q < 6; ++q) {
        const double a = coef[q];
        const long j = i + q - 2;
        if (j >= 0 && j < static_cast<long>(n)) {
          add(static_cast<size_t>(j), a, k);
        } else {  // a boundary point: a combination of the 6 nearest samples
          const double* c = sprague_boundary_row(j, n);
          const size_t base = j < 0 ? 0 : n - 6;
          for (int m = 0; m < 6; ++m) add(base + static_cast<size_t>(m), a * c[m] / 209.0, k);
        }
      }
    } else {
      const size_t j = static_cast<size_t>(std::upper_bound(w.begin(), w.end(), x) - w.begin());  // w[j-1] <= x < w[j]
      const double f = (x - w[j - 1]) / (w[j] - w[j - 1]);
      if (f == 0.0) {
        add(j - 1, 1.0, k);
      } else {
        add(j - 1, 1.0 - f, k);
        add(j, f, k);
      }
    }
  }
  PulledBackWeights out;
  out.samples = n;
  out.nodes.reserve(n);
  out.weights.reserve(3 * n);
  for (size_t j = 0; j < n; ++j) {
    if (!read[j]) continue;
    out.nodes.push_back(j);
    out.weights.insert(out.weights.end(), &full[3 * j], &full[3 * j] + 3);
  }
  return out;
}

Vec3 PulledBackWeights::dot(const std::vector<double>& v) const {
  if (v.size() != samples)
    throw Error(ErrorCode::InvalidArgument, "spectrum with " + std::to_string(samples) + " wavelengths and " +
                                                std::to_string(v.size()) + " values");
  double s0 = 0, s1 = 0, s2 = 0;
  const double* a = weights.data();
  for (size_t t = 0; t < nodes.size(); ++t, a += 3) {
    const double r = v[nodes[t]];
    s0 += a[0] * r;
    s1 += a[1] * r;
    s2 += a[2] * r;
  }
  return Vec3(s0, s1, s2);
}

SpectralData align_spectra(const SpectralData& d, const std::vector<double>& nw) {
  SpectralData out;
  out.wavelengths = nw;
  out.names = d.names;
  for (const auto& col : d.values) out.values.push_back(interpolate_spectrum(d.wavelengths, col, nw, d.linear));
  out.linear = d.linear;
  return out;
}

// ------------------------------------------------------------------ observers

Observer parse_observer(std::string_view id) {
  std::string s;
  for (char c : id) s.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  if (s == "1931" || s == "2" || s == "cie1931" || s == "cie 1931" || s == "cie1931_2" || s == "2deg" ||
      s == "cie 1931 2 degree standard observer")
    return Observer::CIE1931_2;
  if (s == "1964" || s == "10" || s == "cie1964" || s == "cie 1964" || s == "cie1964_10" || s == "10deg" ||
      s == "cie 1964 10 degree standard observer")
    return Observer::CIE1964_10;
  throw Error(ErrorCode::UnknownId, "unknown observer '" + std::string(id) + "' (use 1931 or 1964)");
}

const char* observer_name(Observer o) { return o == Observer::CIE1931_2 ? "1931" : "1964"; }

std::vector<ObserverInfo> list_observers() {
  return {{observer_name(Observer::CIE1931_2), "CIE 1931 2°"}, {observer_name(Observer::CIE1964_10), "CIE 1964 10°"}};
}

namespace {

// A compiled-in CIE table (core/data/cmf, core/data/illuminants): a header of column names, the
// first the wavelength, then one row of comma-separated numbers per wavelength. Read here rather
// than with io's read_spectral_csv, as colorimetry includes nothing of io (io reads files into
// colorimetry's types); parse_double reads each number as read_spectral_csv does, so the tables
// hold the same doubles (tests/core/io/io_test.cpp compares the two).
SpectralData builtin_spectra(std::string_view name) {
  const std::string_view text = builtin_file(name);
  auto bad = [&](const std::string& what) {
    return Error(ErrorCode::ParseError, "built-in table " + std::string(name) + ": " + what);
  };
  SpectralData d;
  std::string line;
  bool header = true;
  for (size_t pos = 0; pos < text.size();) {
    const size_t eol = std::min(text.find('\n', pos), text.size());
    line.assign(text.substr(pos, eol - pos));
    pos = eol + 1;
    if (line.empty()) continue;
    if (header) {  // the wavelength's name, then one name per column
      for (size_t a = line.find(','); a != std::string::npos;) {
        const size_t b = line.find(',', a + 1);
        d.names.push_back(line.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1));
        a = b;
      }
      d.values.assign(d.names.size(), {});
      header = false;
      continue;
    }
    const char* p = line.c_str();
    for (size_t k = 0; k <= d.names.size(); ++k) {
      char* end = nullptr;
      const double v = parse_double(p, &end);
      if (end == p || *end != (k < d.names.size() ? ',' : '\0')) throw bad("a malformed row: " + line);
      (k == 0 ? d.wavelengths : d.values[k - 1]).push_back(v);
      p = end + 1;
    }
  }
  if (d.names.empty() || d.wavelengths.empty()) throw bad("no columns or no rows");
  return d;
}

}  // namespace

const SpectralData& cmfs(Observer observer) {
  static std::once_flag once;
  static SpectralData table[2];
  std::call_once(once, [] {
    table[0] = builtin_spectra("cmf/cie1931_2deg_360-830_1nm.csv");
    table[1] = builtin_spectra("cmf/cie1964_10deg_360-830_1nm.csv");
  });
  return table[observer == Observer::CIE1931_2 ? 0 : 1];
}

SpectralLocus spectral_locus(Observer observer) {
  const SpectralData& c = cmfs(observer);
  SpectralLocus out;
  for (size_t i = 0; i < c.wavelengths.size(); ++i) {
    const double X = c.values[0][i], Y = c.values[1][i], Z = c.values[2][i], s = X + Y + Z;
    if (!(s > 0)) continue;
    out.wavelengths.push_back(c.wavelengths[i]);
    out.x.push_back(X / s);
    out.y.push_back(Y / s);
  }
  return out;
}

// ------------------------------------------------------------------ illuminants

namespace {
const std::map<std::string, std::string>& illuminant_files() {
  static const std::map<std::string, std::string> files = {
      {"A", "illuminants/A_300-780_5nm.csv"},     {"D50", "illuminants/D50_300-780_5nm.csv"},
      {"D55", "illuminants/D55_300-780_5nm.csv"}, {"D65", "illuminants/D65_300-780_5nm.csv"},
      {"D75", "illuminants/D75_300-780_5nm.csv"}, {"E", "illuminants/E_360-830_5nm.csv"},
      {"F2", "illuminants/F2_380-780_5nm.csv"},   {"F11", "illuminants/F11_380-780_5nm.csv"},
  };
  return files;
}
}  // namespace

std::vector<std::string> illuminant_ids() { return {"A", "D50", "D55", "D65", "D75", "E", "F2", "F11"}; }

std::vector<IlluminantInfo> list_illuminants() {
  const std::map<std::string, std::string> names = {{"A", "A (tungsten, 2856 K)"}, {"E", "E (equal energy)"},
                                                    {"F2", "F2 (cool white fluorescent)"}, {"F11", "F11 (TL84-type fluorescent)"}};
  std::vector<IlluminantInfo> out;
  for (const auto& id : illuminant_ids()) out.push_back({id, names.count(id) ? names.at(id) : "CIE " + id});
  return out;
}

SpectralData illuminant_spd(std::string_view id_in) {
  std::string id;
  for (char c : id_in) id.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  if (id == "FL2") id = "F2";
  if (id == "FL11") id = "F11";
  auto it = illuminant_files().find(id);
  if (it != illuminant_files().end()) {
    static std::mutex mutex;
    static std::map<std::string, SpectralData> cache;  // parsed once
    std::lock_guard<std::mutex> lock(mutex);
    auto c = cache.find(id);
    if (c == cache.end()) {
      SpectralData d = builtin_spectra(it->second);
      d.names = {id};
      d.linear = true;
      c = cache.emplace(id, std::move(d)).first;
    }
    return c->second;
  }
  if (id.size() >= 5 && id[0] == 'D') {
    char* end = nullptr;
    const std::string num = id.substr(1, id.size() - 1 - (id.back() == 'K' ? 1 : 0));
    const double T = tristim::parse_double(num.c_str(), &end);
    if (*end == '\0' && T >= 4000 && T <= 25000) {
      SpectralData d = daylight_spd(T);
      d.names = {id};
      return d;
    }
  }
  throw Error(ErrorCode::UnknownId, "unknown illuminant '" + std::string(id_in) +
                                        "' (use A, D50, D55, D65, D75, E, F2, F11, D<CCT> such as D4500, or an SPD file)");
}

SpectralData daylight_spd(double T) {
  if (!(T >= 4000 && T <= 25000))
    throw Error(ErrorCode::InvalidArgument, "daylight CCT " + std::to_string(T) + " K outside 4000..25000 K");
  static const SpectralData basis = builtin_spectra("illuminants/daylight_S0_S1_S2_300-830_5nm.csv");
  // CIE 15:2004 eq 3.3 (xD from T), eq 3.4 (yD), eq 3.5 (M1, M2).
  const double xD = T <= 7000 ? 0.244063 + 0.09911e3 / T + 2.9678e6 / (T * T) - 4.6070e9 / (T * T * T)
                              : 0.237040 + 0.24748e3 / T + 1.9018e6 / (T * T) - 2.0064e9 / (T * T * T);
  const double yD = -3.000 * xD * xD + 2.870 * xD - 0.275;
  const double M = 0.0241 + 0.2562 * xD - 0.7341 * yD;
  // Rounded to 3 decimals, as CIE 15:2004 §3.1 does for the tabulated D illuminants.
  const double M1 = std::round(((-1.3515 - 1.7703 * xD + 5.9114 * yD) / M) * 1000.0) / 1000.0;
  const double M2 = std::round(((0.0300 - 31.4424 * xD + 30.0717 * yD) / M) * 1000.0) / 1000.0;
  SpectralData d;
  d.wavelengths = basis.wavelengths;
  d.names = {"D" + std::to_string(static_cast<long>(std::lround(T)))};
  std::vector<double> s(d.wavelengths.size());
  double at560 = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    s[i] = basis.values[0][i] + M1 * basis.values[1][i] + M2 * basis.values[2][i];
    if (d.wavelengths[i] == 560.0) at560 = s[i];
  }
  for (auto& v : s) v *= 100.0 / at560;
  d.values = {s};
  d.linear = true;
  return d;
}

// ------------------------------------------------------------------ spectrum -> XYZ

namespace {
/// Illuminant on the CMF grid and the normalising k = 100 / Σ S ȳ.
struct Weights {
  std::vector<double> Sx, Sy, Sz;  // S·x̄, S·ȳ, S·z̄ on the CMF grid
  double k;
};
Weights weights(const SpectralData& illuminant, Observer observer) {
  if (illuminant.values.empty()) throw Error(ErrorCode::InvalidArgument, "illuminant without values");
  const SpectralData& c = cmfs(observer);
  const auto S = interpolate_spectrum(illuminant.wavelengths, illuminant.values[0], c.wavelengths, illuminant.linear);
  Weights w;
  const size_t n = c.wavelengths.size();
  w.Sx.resize(n);
  w.Sy.resize(n);
  w.Sz.resize(n);
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    w.Sx[i] = S[i] * c.values[0][i];
    w.Sy[i] = S[i] * c.values[1][i];
    w.Sz[i] = S[i] * c.values[2][i];
    sum += w.Sy[i];
  }
  if (!(sum > 0)) throw Error(ErrorCode::InvalidArgument, "illuminant has no power in the visible range");
  w.k = 100.0 / sum;  // CIE 15:2004 eq 7.2
  return w;
}
Vec3 integrate(const Weights& w, const std::vector<double>& R) {
  double X = 0, Y = 0, Z = 0;
  for (size_t i = 0; i < R.size(); ++i) {  // CIE 15:2004 eq 7.1
    X += R[i] * w.Sx[i];
    Y += R[i] * w.Sy[i];
    Z += R[i] * w.Sz[i];
  }
  return Vec3(w.k * X, w.k * Y, w.k * Z);
}
}  // namespace

std::vector<Vec3> reflectances_to_XYZ(const SpectralData& reflectances, const SpectralData& illuminant, Observer observer,
                                      Vec3* white_XYZ) {
  const Weights w = weights(illuminant, observer);
  if (white_XYZ) *white_XYZ = integrate(w, std::vector<double>(w.Sy.size(), 1.0));  // illuminant_white_XYZ
  std::vector<Vec3> out;
  if (reflectances.values.empty()) return out;
  // X = k Σ_i Sx̄_i (A r)_i over the CMF grid, A the interpolation onto it (linear in r), equals
  // k Σ_j (Aᵀ Sx̄)_j r_j over the reflectance's own grid: the weights are pulled back once
  // (pull_back_weights) and each reflectance costs one short dot product per channel instead of
  // an interpolation to 471 wavelengths. Same values up to summation order.
  check_sizes(reflectances.wavelengths, reflectances.values[0].size());  // first column's errors first, as before
  const PulledBackWeights p =
      pull_back_weights(reflectances.wavelengths, reflectances.linear, cmfs(observer).wavelengths, w.Sx, w.Sy, w.Sz);
  out.reserve(reflectances.values.size());
  for (const auto& col : reflectances.values) {
    const Vec3 s = p.dot(col);
    out.push_back(Vec3(w.k * s[0], w.k * s[1], w.k * s[2]));  // CIE 15:2004 eq 7.1
  }
  return out;
}

Vec3 sd_to_XYZ(const std::vector<double>& wavelengths, const std::vector<double>& reflectance, const SpectralData& illuminant,
               Observer observer) {
  SpectralData d;
  d.wavelengths = wavelengths;
  d.values = {reflectance};
  d.names = {"sample"};
  return reflectances_to_XYZ(d, illuminant, observer)[0];
}

Vec3 illuminant_white_XYZ(const SpectralData& illuminant, Observer observer) {
  const Weights w = weights(illuminant, observer);
  return integrate(w, std::vector<double>(w.Sy.size(), 1.0));
}

bool reflectance_to_fraction(SpectralData& d) {
  double mx = 0;
  for (const auto& c : d.values)
    for (double v : c) mx = std::max(mx, v);
  if (mx <= 2.0) return false;
  for (auto& c : d.values)
    for (auto& v : c) v /= 100.0;
  return true;
}

}  // namespace tristim
