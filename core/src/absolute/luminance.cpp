// Guarnera 2018 section 3.1: training stimuli, eq (8) across exposures, reciprocity report
// (rules in tristim/absolute/luminance.hpp).
#include "tristim/absolute/luminance.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "tristim/error.hpp"

namespace tristim {

TrainingStimulus sample_stimulus(const RawImage& frame, int x, int y, int w, int h, const Normalisation& n,
                                 const ExposureSettings& exposure, const Vec3& XYZ, const std::string& id,
                                 bool luminance_set) {
  if (w <= 0 || h <= 0 || x < 0 || y < 0 || x + w > frame.width || y + h > frame.height)
    throw Error(ErrorCode::InvalidArgument, "stimulus '" + id + "': region " + std::to_string(x) + "," +
                                                std::to_string(y) + " " + std::to_string(w) + "x" + std::to_string(h) +
                                                " is not inside the " + std::to_string(frame.width) + "x" +
                                                std::to_string(frame.height) + " frame");
  TrainingStimulus s;
  s.id = id;
  s.exposure = exposure;
  s.XYZ = XYZ;
  s.luminance_set = luminance_set;
  double sum_f = 0;
  Vec3 sum_vf = Vec3::Zero();
  for (int yy = y; yy < y + h; ++yy)
    for (int xx = x; xx < x + w; ++xx) {
      const size_t p = static_cast<size_t>(yy) * frame.width + xx;
      const double f = n.falloff_factor(xx, yy);
      sum_f += f;
      for (int c = 0; c < 3; ++c) {
        const double v = frame.rgb[p * 3 + c];
        sum_vf[c] += v * f;
        const bool flagged = !frame.saturated.empty() && (frame.saturated[p] >> c & 1);
        if (n.zone(c, v, flagged) == Zone::Saturated) s.saturated[c] = true;
      }
    }
  s.raw_RGB = sum_vf / sum_f;
  s.falloff = sum_f / (static_cast<double>(w) * h);
  return s;
}

double stimulus_normalised(const TrainingStimulus& s, const Normalisation& n, int c) {
  return (s.raw_RGB[c] - n.noise_floor[c]) / (n.saturation[c] - n.noise_floor[c]) * n.area_ratio(c) * s.falloff;  // eq (7)
}

double LuminanceFit::luminance(int c, double normalised, const ExposureSettings& exposure) const {
  return curves[c](normalised) / exposure.factor(iso_reference);  // eqs (8), (10)
}

Vec3 stimulus_luminance(const TrainingStimulus& s, const Normalisation& n, const LuminanceFit& fit) {
  Vec3 L;
  for (int c = 0; c < 3; ++c) L[c] = fit.luminance(c, stimulus_normalised(s, n, c), s.exposure);
  return L;
}

namespace {

// Exposures are grouped by their settings (t, N, ISO), compared with a relative tolerance.
bool same_exposure(const ExposureSettings& a, const ExposureSettings& b) {
  auto close = [](double x, double y) { return std::fabs(x - y) <= 1e-6 * std::max(std::fabs(x), std::fabs(y)); };
  return close(a.exposure_s, b.exposure_s) && close(a.f_number, b.f_number) && close(a.iso, b.iso);
}

void check_monotonic(const std::vector<const TrainingStimulus*>& group, const Normalisation& n, double tol) {
  for (int c = 0; c < 3; ++c) {
    const double allow = tol * (n.saturation[c] - n.noise_floor[c]) + 3.0;
    for (const TrainingStimulus* lo : group)
      for (const TrainingStimulus* hi : group) {
        if (lo->saturated[c] || hi->saturated[c] || !(lo->XYZ[1] < hi->XYZ[1])) continue;
        const double v_lo = (lo->raw_RGB[c] - n.noise_floor[c]) * lo->falloff;
        const double v_hi = (hi->raw_RGB[c] - n.noise_floor[c]) * hi->falloff;
        if (v_hi < v_lo - allow)
          throw Error(ErrorCode::NonMonotonic,
                      "stimuli '" + lo->id + "' (Y = " + std::to_string(lo->XYZ[1]) + ") and '" + hi->id +
                          "' (Y = " + std::to_string(hi->XYZ[1]) + ") at " + hi->exposure.label() +
                          ": the brighter one reads lower in " + std::string(1, "RGB"[c]) +
                          " — check the order of the measured luminances");
      }
  }
}

}  // namespace

LuminanceFit fit_luminance_Guarnera2018(const std::vector<TrainingStimulus>& stimuli, const Normalisation& n,
                                        const LuminanceFitOptions& o) {
  n.check();
  LuminanceFit fit;
  std::vector<const TrainingStimulus*> used;
  for (const auto& s : stimuli) {
    if (!s.luminance_set) continue;
    if (!(s.exposure.exposure_s > 0) || !(s.exposure.f_number > 0))
      throw Error(ErrorCode::MissingMetadata, "stimulus '" + s.id + "': exposure time and f-number are needed");
    if (!s.XYZ.allFinite() || !s.raw_RGB.allFinite())
      throw Error(ErrorCode::NonFinite, "stimulus '" + s.id + "' has a non-finite value");
    if (s.XYZ[1] < 0) throw Error(ErrorCode::NegativeValue, "stimulus '" + s.id + "' has Y < 0");
    used.push_back(&s);
  }
  if (used.empty()) throw Error(ErrorCode::NoUsableData, "no equal-tristimulus (luminance) stimuli to fit the inverse OECF");
  fit.iso_reference = o.iso_reference > 0 ? o.iso_reference : used[0]->exposure.iso;

  // Group by exposure; check monotonicity within each.
  std::vector<std::vector<const TrainingStimulus*>> groups;
  for (const TrainingStimulus* s : used) {
    auto it = std::find_if(groups.begin(), groups.end(), [&](auto& g) { return same_exposure(g[0]->exposure, s->exposure); });
    if (it == groups.end()) groups.push_back({s});
    else it->push_back(s);
  }
  // Stable: two settings of equal ε (1/60 s f/8, 1/15 s f/16) stay in the order given, whichever
  // C++ library sorts them (libstdc++ natively, libc++ in wasm) — the first failing check is named.
  std::stable_sort(groups.begin(), groups.end(), [&](auto& a, auto& b) {
    return a[0]->exposure.factor(fit.iso_reference) < b[0]->exposure.factor(fit.iso_reference);
  });
  for (const auto& g : groups) check_monotonic(g, n, o.monotonic_tolerance);

  auto samples_of = [&](const std::vector<const TrainingStimulus*>& set, int c) {
    std::vector<OecfSample> out;
    for (const TrainingStimulus* s : set)
      if (!s->saturated[c]) out.push_back({stimulus_normalised(*s, n, c), s->exposure.factor(fit.iso_reference), s->XYZ[1]});
    return out;
  };
  bool any = false;
  for (int c = 0; c < 3; ++c) any = any || !samples_of(used, c).empty();
  if (!any) throw Error(ErrorCode::NoUsableData, "every luminance stimulus is saturated in every channel");
  for (int c = 0; c < 3; ++c) {
    const auto all = samples_of(used, c);
    try {
      fit.fits[c] = fit_inverse_oecf_Guarnera2018(all, o.oecf);
    } catch (const Error& e) {
      throw Error(e.code(), std::string("channel ") + "RGB"[c] + ": " + e.what());
    }
    fit.curves[c] = fit.fits[c].curve;
  }

  // Reciprocity: each exposure on its own against the common curve.
  std::ostringstream msg;
  for (const auto& g : groups) {
    ExposureReport r;
    r.exposure = g[0]->exposure;
    r.factor = r.exposure.factor(fit.iso_reference);
    for (int c = 0; c < 3; ++c) {
      const auto s = samples_of(g, c);
      r.samples[c] = static_cast<int>(s.size());
      double y_max = 0;
      for (const auto& x : s) y_max = std::max(y_max, x.Y);
      const double floor = o.oecf.y_floor * y_max;
      double num = 0, den = 0, ss = 0;
      for (const auto& x : s) {
        const double p = fit.curves[c](x.normalised) / x.exposure, w = 1.0 / ((x.Y + floor) * (x.Y + floor));
        num += w * p * x.Y;
        den += w * p * p;
        ss += w * (p - x.Y) * (p - x.Y);
      }
      if (den > 0 && num > 0) r.scale_ratio[c] = den / num;  // s = 1/u, u = Σwpy/Σwp²
      r.rms_relative[c] = s.empty() ? 0 : std::sqrt(ss / s.size());
      int positive = 0;
      for (const auto& x : s) positive += x.Y > 0;
      if (positive >= 3) {
        try {
          r.own[c] = fit_inverse_oecf_Guarnera2018(s, o.oecf).curve;
          r.own_fit[c] = true;
          r.slope_difference[c] = r.own[c].k3 - fit.curves[c].k3;
        } catch (const Error&) {
          r.own_fit[c] = false;  // too few distinct values in this exposure: scale ratio only
        }
      }
      const bool bad_scale = r.samples[c] > 0 && std::fabs(r.scale_ratio[c] - 1) > o.reciprocity_tolerance;
      const bool bad_slope = r.own_fit[c] && std::fabs(r.slope_difference[c]) > o.slope_tolerance;
      if (bad_scale || bad_slope) {
        r.parallel = false;
        if (!msg.str().empty()) msg << "; ";
        msg << r.exposure.label() << " " << "RGB"[c] << ": ";
        if (bad_scale) msg << "effective exposure " << r.scale_ratio[c] << "x the nominal t/N^2";
        if (bad_scale && bad_slope) msg << ", ";
        if (bad_slope) msg << "slope k3 differs by " << r.slope_difference[c];
      }
    }
    fit.reciprocity_ok = fit.reciprocity_ok && r.parallel;
    fit.exposures.push_back(r);
  }
  if (!fit.reciprocity_ok) fit.message = "reciprocity fails (per-exposure curves not parallel): " + msg.str();
  return fit;
}

}  // namespace tristim
