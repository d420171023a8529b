// Guarnera 2018 eq (8): power-law inverse OECF, its bounded fit (NLopt) and the linearisation
// table row `Guarnera2018` (rules in tristim/linearisation/guarnera2018.hpp).
#include "tristim/linearisation/guarnera2018.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tristim/error.hpp"
#include "../detmath.hpp"
#include "../citations.hpp"
#include "../optimise/bounded.hpp"

namespace tristim {

namespace {

// detmath's pow, exp and log (detmath.hpp): the same bits natively and in wasm, so the OECF fit
// (BOBYQA over these) takes the same steps in the page as on the command line.
double signed_pow(double x, double p) { return x < 0 ? -detmath::pow(-x, p) : detmath::pow(x, p); }

struct Problem {
  const std::vector<OecfSample>* samples;
  std::vector<double> inv_scale;  // 1/(Y + floor)
  double h_max = 1;               // k1 = x[0]·h_max
  bool fit_k1 = true;
};

InverseOecf curve_of(const Problem& p, const double* x) {
  InverseOecf c;
  int i = 0;
  c.k1 = p.fit_k1 ? x[i++] * p.h_max : 0.0;
  c.k2 = detmath::exp(x[i++]);
  c.k3 = x[i];
  return c;
}

double cost(const Problem& p, const InverseOecf& c) {
  double s = 0;
  const auto& v = *p.samples;
  for (size_t i = 0; i < v.size(); ++i) {
    const double r = (c(v[i].normalised) / v[i].exposure - v[i].Y) * p.inv_scale[i];
    s += r * r;
  }
  return std::isfinite(s) ? s : 1e300;
}

}  // namespace

double InverseOecf::operator()(double normalised) const {
  return signed_pow(normalised, 1.0 / k3) / k2 - k1;  // eq (8)
}

double InverseOecf::forward(double exposure) const { return signed_pow(k2 * (exposure + k1), k3); }

OecfFit fit_inverse_oecf_Guarnera2018(const std::vector<OecfSample>& samples, const OecfFitOptions& o) {
  if (samples.size() < 3)
    throw Error(ErrorCode::TooFewPatches, "inverse OECF (Guarnera 2018 eq 8): " + std::to_string(samples.size()) +
                                              " usable stimuli, at least 3 are needed");
  double y_max = 0, h_max = 0, r_min = samples[0].normalised, r_max = r_min;
  for (size_t i = 0; i < samples.size(); ++i) {
    const OecfSample& s = samples[i];
    if (!std::isfinite(s.normalised) || !std::isfinite(s.Y) || !std::isfinite(s.exposure))
      throw Error(ErrorCode::NonFinite, "inverse OECF: stimulus " + std::to_string(i + 1) + " has a non-finite value");
    if (s.Y < 0) throw Error(ErrorCode::NegativeValue, "inverse OECF: stimulus " + std::to_string(i + 1) + " has Y < 0");
    if (!(s.exposure > 0))
      throw Error(ErrorCode::NegativeValue, "inverse OECF: stimulus " + std::to_string(i + 1) + " has exposure <= 0");
    y_max = std::max(y_max, s.Y);
    h_max = std::max(h_max, s.Y * s.exposure);
    r_min = std::min(r_min, s.normalised);
    r_max = std::max(r_max, s.normalised);
  }
  if (!(y_max > 0)) throw Error(ErrorCode::IllPosed, "inverse OECF: no stimulus with Y > 0");
  if (!(r_max > r_min)) throw Error(ErrorCode::IllPosed, "inverse OECF: every normalised value is the same");

  Problem p;
  p.samples = &samples;
  p.h_max = h_max;
  p.fit_k1 = o.fit_k1;
  const double floor = o.y_floor * y_max;
  for (const auto& s : samples) p.inv_scale.push_back(1.0 / (s.Y + floor));

  // Start: k3 = 1, Y·ε ≈ a·R' + b (a = 1/k2, b = −k1): weighted linear least squares.
  double A00 = 0, A01 = 0, A11 = 0, t0 = 0, t1 = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const double w = p.inv_scale[i] / samples[i].exposure;
    const double u0 = samples[i].normalised * w, u1 = o.fit_k1 ? w : 0.0, y = samples[i].Y * p.inv_scale[i];
    A00 += u0 * u0;
    A01 += u0 * u1;
    A11 += u1 * u1;
    t0 += u0 * y;
    t1 += u1 * y;
  }
  double a, b = 0;
  if (o.fit_k1) {
    const double det = A00 * A11 - A01 * A01;
    if (!(std::fabs(det) > 1e-300)) throw Error(ErrorCode::IllPosed, "inverse OECF: the stimuli do not determine a line");
    a = (A11 * t0 - A01 * t1) / det;
    b = (A00 * t1 - A01 * t0) / det;
  } else {
    a = t0 / A00;
  }
  if (!(a > 0))
    throw Error(ErrorCode::NonMonotonic, "inverse OECF: the camera response decreases as the luminance increases");
  OecfFit out;
  out.samples = static_cast<int>(samples.size());
  InverseOecf best;
  best.k1 = o.fit_k1 ? -b : 0.0;
  best.k2 = 1.0 / a;
  best.k3 = 1.0;

  if (o.fit_k3) {
    std::vector<double> x, lb, ub, step;
    if (o.fit_k1) {
      x.push_back(best.k1 / h_max);
      lb.push_back(-1);
      ub.push_back(1);
      step.push_back(0.01);
    }
    x.push_back(detmath::log(best.k2));
    lb.push_back(x.back() - 8);
    ub.push_back(x.back() + 8);
    step.push_back(0.05);
    x.push_back(std::clamp(1.0, o.k3_min, o.k3_max));
    lb.push_back(o.k3_min);
    ub.push_back(o.k3_max);
    step.push_back(0.02);
    for (size_t i = 0; i < x.size(); ++i) x[i] = std::clamp(x[i], lb[i], ub[i]);
    optimise::BoundedOptions bounded;  // BOBYQA
    bounded.lower = std::move(lb);
    bounded.upper = std::move(ub);
    bounded.initial_step = std::move(step);
    bounded.xtol_rel = o.xtol_rel;
    bounded.ftol_rel = 1e-14;
    bounded.max_evaluations = o.max_evaluations;
    const optimise::BoundedMinimum m =
        optimise::minimise_bounded([&p](const double* v) { return cost(p, curve_of(p, v)); }, x, bounded);
    out.evaluations = m.evaluations;
    const InverseOecf found = curve_of(p, m.x.data());
    if (!m.failed) {
      if (cost(p, found) <= cost(p, best)) best = found;
    } else {
      out.message = m.message + "; the linear start is kept";
    }
    if (m.hit_limit) out.message = "the optimiser reached its evaluation limit";
    if (std::fabs(best.k3 - o.k3_min) < 1e-9 || std::fabs(best.k3 - o.k3_max) < 1e-9)
      out.message += std::string(out.message.empty() ? "" : "; ") + "k3 ended on its bound";
  }
  out.curve = best;
  double ss = 0, ss_tot = 0, y_mean = 0;
  for (const auto& s : samples) y_mean += s.Y;
  y_mean /= samples.size();
  for (size_t i = 0; i < samples.size(); ++i) {
    const double y_hat = best(samples[i].normalised) / samples[i].exposure;
    const double r = (y_hat - samples[i].Y) * p.inv_scale[i];
    ss += r * r;
    out.max_relative = std::max(out.max_relative, std::fabs(r));
    ss_tot += (samples[i].Y - y_mean) * (samples[i].Y - y_mean);
    out.r_squared += (y_hat - samples[i].Y) * (y_hat - samples[i].Y);
  }
  out.r_squared = ss_tot > 0 ? 1.0 - out.r_squared / ss_tot : 1.0;
  out.rms_relative = std::sqrt(ss / samples.size());
  return out;
}

// ---- the linearisation table row ------------------------------------------------------------

namespace {

struct RowOptions {
  double n, S, area_ratio[3], exposure;
};

RowOptions row_options(const MethodChoice& c, double saturation) {
  RowOptions r;
  r.n = choice_number(c, "noise_floor");
  r.S = saturation;
  const double A[3] = {choice_number(c, "area_R"), choice_number(c, "area_G"), choice_number(c, "area_B")};
  for (int k = 0; k < 3; ++k) r.area_ratio[k] = A[1] / A[k];
  const double N = choice_number(c, "f_number"), iso = choice_number(c, "iso");
  r.exposure = choice_number(c, "exposure_s") / (N * N) * (iso > 0 ? iso / 100.0 : 1.0);
  return r;
}

Linearisation fit_row(const LinearisationData& data, const MethodChoice& choice) {
  if (data.reference_XYZ.rows() != data.camera_RGB.rows())
    throw Error(ErrorCode::PatchMismatch,
                "Guarnera2018 linearisation needs the known luminance Y (cd/m²) of every patch");
  double S = choice_number(choice, "saturation");
  if (!(S > 0)) S = data.full_scale > 0 ? data.full_scale : data.camera_RGB.maxCoeff();
  const RowOptions r = row_options(choice, S);
  if (!(S > r.n))
    throw Error(ErrorCode::InvalidArgument, "Guarnera2018: saturation must exceed the noise floor");
  OecfFitOptions fo;
  fo.y_floor = choice_number(choice, "y_floor");
  fo.fit_k3 = choice_number(choice, "fit_k3") != 0;
  Linearisation l;
  l.choice = choice;
  l.full_scale = S;
  for (int c = 0; c < 3; ++c) {
    std::vector<OecfSample> samples;
    for (Eigen::Index i = 0; i < data.camera_RGB.rows(); ++i) {
      const double v = data.camera_RGB(i, c);
      if (v >= S * 0.999) continue;  // saturated: no information about F
      samples.push_back({normalise_Guarnera2018(v, r.n, S, r.area_ratio[c]), r.exposure, data.reference_XYZ(i, 1)});
    }
    const OecfFit f = fit_inverse_oecf_Guarnera2018(samples, fo);
    l.coefficients[c] = {f.curve.k1, f.curve.k2, f.curve.k3};
    l.r_squared[c] = f.r_squared;
    if (!f.message.empty()) l.message += std::string(l.message.empty() ? "" : "; ") + "RGB"[c] + ": " + f.message;
  }
  return l;
}

double apply_row(const Linearisation& l, int c, double value) {
  const RowOptions r = row_options(l.choice, l.full_scale);
  const InverseOecf k{l.coefficients[c][0], l.coefficients[c][1], l.coefficients[c][2]};
  return k(normalise_Guarnera2018(value, r.n, r.S, r.area_ratio[c])) / r.exposure;  // eqs (7), (8)
}

// The inverse of apply_row: exposure-normalised luminance -> stored value (eq 8's OECF, then eq 7 undone).
double inverse_row(const Linearisation& l, int c, double linear) {
  const RowOptions r = row_options(l.choice, l.full_scale);
  const InverseOecf k{l.coefficients[c][0], l.coefficients[c][1], l.coefficients[c][2]};
  return k.forward(linear * r.exposure) / r.area_ratio[c] * (r.S - r.n) + r.n;
}


}  // namespace

LinearisationMethod linearisation_row_Guarnera2018() {
  MethodInfo info;
  info.id = "Guarnera2018";
  info.label = "Power law per channel, absolute (cd/m²)";
  info.reference = std::string(citation::kGuarnera2018) + ", eqs (7)-(8)";
  info.options = {
      number_option("noise_floor", "Noise floor n (DN)", 0, 0, 1e9, "mean level of the lens-cap frames, eq (7)"),
      number_option("saturation", "Saturation S (DN)", 0, 0, 1e9, "clip level, eq (7); 0: the data's full scale"),
      number_option("area_R", "Area A_R", 1, 1e-9, 1e9, "area under the red sensitivity, eq (7)"),
      number_option("area_G", "Area A_G", 1, 1e-9, 1e9, "area under the green sensitivity, eq (7)"),
      number_option("area_B", "Area A_B", 1, 1e-9, 1e9, "area under the blue sensitivity, eq (7)"),
      number_option("exposure_s", "Exposure time t (s)", 1, 1e-9, 1e6, "exposure time of the training shots"),
      number_option("f_number", "f-number N", 1, 0.1, 1000, "aperture of the training shots"),
      number_option("iso", "ISO", 0, 0, 1e7, "0: no ISO scaling; else the exposure is multiplied by ISO/100"),
      number_option("y_floor", "Relative floor", 0.01, 1e-6, 1,
                    "residuals relative to Y + floor·max Y (the fit's weighting)"),
  };
  OptionSpec k3;
  k3.name = "fit_k3";
  k3.type = "boolean";
  k3.label = "Fit the exponent k3";
  k3.default_number = 1;
  k3.min = 0;
  k3.max = 1;
  k3.description = "0: linear sensor (k3 = 1)";
  info.options.push_back(k3);
  return {info, "reference", fit_row, apply_row, inverse_row};
}

}  // namespace tristim
