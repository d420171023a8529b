// Phase I surface fit (Abed, Berns & Masaoka 2013, Figure 6): spectral RMS between a corrected
// measurement and another measurement of the same patches, minimised by bounded NLopt.
#include "tristim/surface/fit.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "../sum4.hpp"
#include "correction.hpp"
#include "minimise.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/surface/options_table.hpp"
#include "tristim/surface/saunderson.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim {

namespace {

using surface_detail::Minimum;
using surface_detail::PointCorrection;
using surface_detail::prepare_correction;

std::string nm_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string list_some(const std::vector<std::string>& ids) {
  std::string s;
  for (size_t i = 0; i < ids.size() && i < 5; ++i) s += (i ? ", " : "") + ids[i];
  if (ids.size() > 5) s += ", … (" + std::to_string(ids.size()) + " in all)";
  return s;
}

std::map<std::string, size_t> index_by_id(const SpectralData& d, const std::string& what) {
  std::map<std::string, size_t> m;
  for (size_t k = 0; k < d.names.size(); ++k) {
    const std::string id = normalise_patch_id(d.names[k]);
    if (!m.emplace(id, k).second)
      throw Error(ErrorCode::DuplicateId, what + ": two columns name patch '" + id + "'");
  }
  return m;
}

// The wavelengths of `d` inside [lo, hi] (with a small tolerance).
std::vector<double> grid_inside(const SpectralData& d, double lo, double hi) {
  std::vector<double> g;
  for (double w : d.wavelengths)
    if (w >= lo - 1e-9 && w <= hi + 1e-9) g.push_back(w);
  return g;
}

// Values of `d`'s columns `order` on `grid`: taken as they are when d has these wavelengths,
// interpolated by the spectra.hpp rule otherwise.
SpectralData on_grid(const SpectralData& d, const std::vector<size_t>& order, const std::vector<std::string>& ids,
                     const std::vector<double>& grid) {
  SpectralData sub;
  sub.wavelengths = d.wavelengths;
  sub.linear = d.linear;
  for (size_t k : order) sub.values.push_back(d.values[k]);
  sub.names = ids;
  bool same = true;
  std::vector<size_t> at;
  for (double w : grid) {
    const auto it = std::find_if(d.wavelengths.begin(), d.wavelengths.end(), [&](double x) { return std::fabs(x - w) < 1e-9; });
    if (it == d.wavelengths.end()) { same = false; break; }
    at.push_back(static_cast<size_t>(it - d.wavelengths.begin()));
  }
  if (!same) return align_spectra(sub, grid);
  SpectralData out;
  out.wavelengths = grid;
  out.names = ids;
  for (const auto& column : sub.values) {
    std::vector<double> v;
    for (size_t i : at) v.push_back(column[i]);
    out.values.push_back(std::move(v));
  }
  return out;
}

// Sum of squared differences of the corrected `measured` columns vs `target` at wavelength
// indices [w0, w1), for full row coefficients c (eq 4 / eq 5 per element); +inf where the
// Saunderson coefficients are singular. The objective of every Phase I evaluation: four partial
// sums (Sum4: by position within each patch's block of four wavelengths) run side by side and are
// added at the end, in this order in both builds, so neither waits on one chain of additions and
// both compilers vectorise the corrections (the division of eq 4 included). The correction's kind
// is chosen once, outside the loops.
double sum_squares(PointCorrection::Kind kind, const std::vector<std::vector<double>>& measured,
                   const std::vector<std::vector<double>>& target, size_t w0, size_t w1, const std::vector<double>& c) {
  PointCorrection p;
  try {
    p = prepare_correction(kind, c);
  } catch (const Error&) {
    return HUGE_VAL;
  }
  const size_t n = w1 - w0;
  auto run = [&](auto value) {
    Sum4 s;  // lanes run across wavelengths, carried over the patches
    for (size_t k = 0; k < measured.size(); ++k) {
      const double* m = measured[k].data() + w0;
      const double* t = target[k].data() + w0;
      s.add(static_cast<std::ptrdiff_t>(n), [&](std::ptrdiff_t w) {
        const double d = value(m[w]) - t[w];
        return d * d;
      });
    }
    return s.total();
  };
  if (p.kind == PointCorrection::Saunderson) return run([&](double R) { return p.t.apply(R); });
  return run([&](double R) { return p.a * R + p.b; });
}

// Bounded least squares start for the linear rows (closed form, clamped into the bounds).
std::vector<double> linear_start(const std::string& method, const std::vector<std::vector<double>>& m,
                                 const std::vector<std::vector<double>>& t, size_t w0, size_t w1) {
  double sxx = 0, sxy = 0, sx = 0, sy = 0, n = 0;
  for (size_t k = 0; k < m.size(); ++k)
    for (size_t w = w0; w < w1; ++w) {
      sxx += m[k][w] * m[k][w];
      sxy += m[k][w] * t[k][w];
      sx += m[k][w];
      sy += t[k][w];
      n += 1;
    }
  if (method == "scaler") return {sxx > 0 ? sxy / sxx : 1};
  if (method == "offset") return {n > 0 ? (sy - sx) / n : 0};
  const double det = n * sxx - sx * sx;
  if (!(std::fabs(det) > 1e-300)) return {1, n > 0 ? (sy - sx) / n : 0};
  const double mu = (n * sxy - sx * sy) / det;
  return {mu, (sy - mu * sx) / n};
}

}  // namespace

std::vector<size_t> free_coefficients(const std::string& method, const std::string& free) {
  const SurfaceMethod& m = surface_method(method);
  std::vector<size_t> idx;
  if (method != "saunderson") {
    for (size_t j = 0; j < m.coefficients.size(); ++j) idx.push_back(j);
    return idx;
  }
  const std::string ill =
      " is ill-posed: eq (3) depends on the six Saunderson coefficients only through the three of eq (4) "
      "(Appendix A), so different coefficient sets give identical corrections and the fit has no unique answer. "
      "Fix the instrument's (measurement) coefficients to a preset and fit the capture ones (free=capture)";
  if (free == "all") throw Error(ErrorCode::IllPosed, "fitting all six Saunderson coefficients" + ill);
  if (free == "capture" || free.empty()) return {3, 4, 5};
  if (free == "measurement") return {0, 1, 2};
  size_t start = 0;
  while (start <= free.size()) {
    size_t end = free.find('+', start);
    if (end == std::string::npos) end = free.size();
    const std::string name = free.substr(start, end - start);
    const auto it = std::find(m.coefficients.begin(), m.coefficients.end(), name);
    if (it == m.coefficients.end())
      throw Error(ErrorCode::InvalidArgument, "free Saunderson coefficient '" + name +
                                                  "' unknown (capture, measurement, or names k1, k2, k_ins, k1_capture, "
                                                  "k2_capture, k_ins_capture joined by '+')");
    const size_t j = static_cast<size_t>(it - m.coefficients.begin());
    if (std::find(idx.begin(), idx.end(), j) == idx.end()) idx.push_back(j);
    start = end + 1;
  }
  std::sort(idx.begin(), idx.end());
  if (idx.size() > 3)
    throw Error(ErrorCode::IllPosed, "fitting " + std::to_string(idx.size()) + " Saunderson coefficients" + ill);
  return idx;
}

SurfaceFitResult fit_surface(const MethodChoice& start, const SpectralData& measured, const SpectralData& target,
                             const SurfaceFitOptions& options) {
  const SurfaceMethod& row = surface_method(start.method);
  const MethodChoice first = complete_choice(row.info, start);
  check_reflectances(measured, "measured set");
  check_reflectances(target, "target set");
  if (measured.size() == 0 || target.size() == 0) throw Error(ErrorCode::TooFewPatches, "surface fit: a set has no patches");

  // Pair the patches by normalised name; both sets must hold the same ones.
  const auto mi = index_by_id(measured, "measured set"), ti = index_by_id(target, "target set");
  std::vector<std::string> only_m, only_t, ids;
  std::vector<size_t> order_m, order_t;
  for (size_t k = 0; k < measured.names.size(); ++k) {
    const std::string id = normalise_patch_id(measured.names[k]);
    const auto it = ti.find(id);
    if (it == ti.end()) { only_m.push_back(id); continue; }
    ids.push_back(id);
    order_m.push_back(k);
    order_t.push_back(it->second);
  }
  for (const auto& [id, k] : ti)
    if (!mi.count(id)) only_t.push_back(id);
  if (!only_m.empty() || !only_t.empty())
    throw Error(ErrorCode::PatchMismatch,
                "the two sets do not hold the same patches" +
                    (only_m.empty() ? std::string() : "; only in the measured set: " + list_some(only_m)) +
                    (only_t.empty() ? std::string() : "; only in the target set: " + list_some(only_t)));

  // Range and grid.
  const double m_lo = measured.wavelengths.front(), m_hi = measured.wavelengths.back();
  const double t_lo = target.wavelengths.front(), t_hi = target.wavelengths.back();
  double lo = options.range_min, hi = options.range_max;
  if (lo != 0 || hi != 0) {  // a given range: inside the rows of surface_option_table()
    check_surface_option("range_min", lo);
    check_surface_option("range_max", hi);
  } else {
    lo = std::max(m_lo, t_lo);
    hi = std::min(m_hi, t_hi);
    if (!(hi >= lo))
      throw Error(ErrorCode::WavelengthMismatch, "the measured set covers " + nm_text(m_lo) + "-" + nm_text(m_hi) +
                                                     " nm and the target set " + nm_text(t_lo) + "-" + nm_text(t_hi) +
                                                     " nm: no common range");
  }
  if (!(hi >= lo) || !std::isfinite(lo) || !std::isfinite(hi))
    throw Error(ErrorCode::InvalidArgument, "wavelength range " + nm_text(lo) + "-" + nm_text(hi) + " nm is empty");
  for (const auto* d : {&measured, &target})
    if (d->wavelengths.front() > lo + 1e-9 || d->wavelengths.back() < hi - 1e-9)
      throw Error(ErrorCode::WavelengthMismatch,
                  std::string(d == &measured ? "the measured set" : "the target set") + " covers " +
                      nm_text(d->wavelengths.front()) + "-" + nm_text(d->wavelengths.back()) + " nm, not the range " +
                      nm_text(lo) + "-" + nm_text(hi) + " nm");
  const std::vector<double> grid = grid_inside(measured, lo, hi);
  if (grid.empty())
    throw Error(ErrorCode::WavelengthMismatch, "the measured set has no wavelength inside " + nm_text(lo) + "-" + nm_text(hi) + " nm");

  SurfaceFitResult r;
  r.wavelengths = grid;
  r.ids = ids;
  r.measured = on_grid(measured, order_m, ids, grid);
  r.target = on_grid(target, order_t, ids, grid);
  const auto& M = r.measured.values;
  const auto& T = r.target.values;
  const size_t L = grid.size();

  // Free coefficients, bounds and the fit (one block of wavelengths, or each wavelength).
  const std::vector<size_t> free = free_coefficients(row.info.id, options.free);
  for (size_t j : free) r.free.push_back(row.coefficients[j]);
  std::vector<double> base(row.coefficients.size()), lb, ub;
  for (size_t j = 0; j < row.coefficients.size(); ++j) base[j] = choice_number(first, row.coefficients[j]);
  for (size_t j : free)
    for (const auto& o : row.info.options)
      if (o.name == row.coefficients[j]) { lb.push_back(o.min); ub.push_back(o.max); }
  const bool saunderson = row.info.id == "saunderson";
  const PointCorrection::Kind kind = surface_detail::correction_kind(row.info.id);
  bool hit_limit = false;

  auto fit_block = [&](size_t w0, size_t w1) -> std::vector<double> {
    if (free.empty()) return base;
    auto full = [&](const double* x) {
      std::vector<double> c = base;
      for (size_t i = 0; i < free.size(); ++i) c[free[i]] = x[i];
      return c;
    };
    auto f = [&](const double* x) { return sum_squares(kind, M, T, w0, w1, full(x)); };
    std::vector<std::vector<double>> starts;
    auto pick = [&](const std::vector<double>& c) {
      std::vector<double> x;
      for (size_t j : free) x.push_back(c[j]);
      return x;
    };
    if (!saunderson) {
      starts.push_back(linear_start(row.info.id, M, T, w0, w1));
      starts.push_back(pick(base));
    } else {
      const auto so = linear_start("scaler-offset", M, T, w0, w1);  // Appendix B start, see correction.hpp
      for (const auto& c : surface_detail::saunderson_starts(base, free, so[0], so[1])) starts.push_back(pick(c));
    }
    const Minimum m = surface_detail::minimise_from_starts(f, starts, lb, ub, options.max_evaluations,
                                                           "surface fit (" + row.info.id + ")");
    r.evaluations += m.evaluations;
    hit_limit = hit_limit || m.hit_limit;
    return full(m.x.data());
  };

  std::vector<std::vector<double>> coefficients(L);
  if (options.per_wavelength && !free.empty()) {
    for (size_t w = 0; w < L; ++w) coefficients[w] = fit_block(w, w + 1);
    r.choice = first;
    for (size_t j = 0; j < row.coefficients.size(); ++j) r.choice.parameters[row.coefficients[j]] = coefficients[L / 2][j];
    r.choice.settings["spectral"] = spectral_coefficients_text(grid, coefficients);
  } else {
    const std::vector<double> c = fit_block(0, L);
    std::fill(coefficients.begin(), coefficients.end(), c);
    r.choice = first;
    if (r.choice.settings.count("spectral")) r.choice.settings["spectral"] = "";
    for (size_t j = 0; j < row.coefficients.size(); ++j) r.choice.parameters[row.coefficients[j]] = c[j];
  }
  r.choice = complete_choice(row.info, r.choice);

  // Corrected set and the report.
  r.corrected = r.measured;
  for (size_t w = 0; w < L; ++w) {
    const PointCorrection p = prepare_correction(kind, coefficients[w]);
    for (size_t k = 0; k < M.size(); ++k) r.corrected.values[k][w] = p.value(M[k][w]);
  }
  const SpectralData illuminant = options.illuminant.size() ? options.illuminant : illuminant_spd("D50");
  r.white = illuminant_white_XYZ(illuminant, options.observer);
  r.illuminant = illuminant.names.empty() ? "" : illuminant.names[0];
  r.observer = options.observer;
  // XYZ through the integration rule as one L × 3 matrix (correction.hpp): the same numbers
  // as reflectances_to_XYZ, without aligning every column to the 1 nm grid.
  const Eigen::MatrixXd Tm = surface_detail::integration_matrix(grid, r.measured.linear, illuminant, options.observer);
  auto xyz_of = [&](const SpectralData& d) {
    std::vector<Vec3> out;
    for (const auto& column : d.values) out.push_back(Tm.transpose() * Eigen::Map<const Eigen::VectorXd>(column.data(), L));
    return out;
  };
  const auto xyz_m = xyz_of(r.measured), xyz_c = xyz_of(r.corrected), xyz_t = xyz_of(r.target);
  double ss_before = 0, ss_after = 0;
  for (size_t k = 0; k < M.size(); ++k) {
    double b = 0, a = 0;
    for (size_t w = 0; w < L; ++w) {
      b += (M[k][w] - T[k][w]) * (M[k][w] - T[k][w]);
      a += (r.corrected.values[k][w] - T[k][w]) * (r.corrected.values[k][w] - T[k][w]);
    }
    ss_before += b;
    ss_after += a;
    r.rms_before.push_back(std::sqrt(b / L));
    r.rms_after.push_back(std::sqrt(a / L));
    const Vec3 lab_t = XYZ_to_Lab(xyz_t[k], r.white);
    r.dE00_before.push_back(delta_E_CIE2000(lab_t, XYZ_to_Lab(xyz_m[k], r.white)));
    r.dE00_after.push_back(delta_E_CIE2000(lab_t, XYZ_to_Lab(xyz_c[k], r.white)));
  }
  const double count = static_cast<double>(M.size() * L);
  r.spectral_rms_before = std::sqrt(ss_before / count);
  r.spectral_rms_after = std::sqrt(ss_after / count);
  r.summary_dE00_before = summarize(r.dE00_before);
  r.summary_dE00_after = summarize(r.dE00_after);

  // Status: an evaluation limit, or a coefficient resting on a bound (the data asked for more).
  std::string at_bound;
  if (!options.per_wavelength)
    for (size_t i = 0; i < free.size(); ++i) {
      const double v = coefficients[0][free[i]];
      if (v <= lb[i] + 1e-9 || v >= ub[i] - 1e-9)
        at_bound += (at_bound.empty() ? "" : ", ") + row.coefficients[free[i]] + " = " + nm_text(v);
    }
  if (hit_limit) {
    r.status = "iteration_limit";
    r.message = "the optimiser stopped at its evaluation limit";
  } else if (!at_bound.empty()) {
    r.status = "at_bound";
    r.message = "coefficient(s) on a bound of the table (" + at_bound + "): the data ask for a correction the bounds do not allow";
  }
  return r;
}

}  // namespace tristim
