// The report of the absolute tele-colorimeter: from a profile, as JSON and as text (rules in
// tristim/absolute/report.hpp).
#include "tristim/absolute/report.hpp"

#include <cmath>
#include <cstdio>

#include "tristim/profile/profile.hpp"

namespace tristim {

namespace {

json::Value triple(double a, double b, double c) { return json::Value(std::vector<double>{a, b, c}); }
json::Value triple(const Vec3& v) { return triple(v[0], v[1], v[2]); }
json::Value triple(const std::array<double, 3>& v) { return triple(v[0], v[1], v[2]); }
json::Value triple(const std::array<int, 3>& v) { return triple(v[0], v[1], v[2]); }

json::Value strings(const std::vector<std::string>& v) {
  json::Value a = json::Value::array();
  for (const auto& s : v) a.push(s);
  return a;
}

json::Value exposure_json(const ExposureSettings& e) {
  return json::Value(std::vector<double>{e.exposure_s, e.f_number, e.iso});
}

json::Value fit_json(const AbsoluteFitSummary& f) {
  json::Value o = json::Value::object();
  o.set("make", f.make);
  o.set("model", f.model);
  o.set("width", f.width);
  o.set("height", f.height);
  json::Value ch = json::Value::array();
  for (const auto& c : f.channels) {
    json::Value x = json::Value::object();
    x.set("k1", c.k1);
    x.set("k2", c.k2);
    x.set("k3", c.k3);
    x.set("samples", c.samples);
    x.set("rms_relative", c.rms_relative);
    x.set("max_relative", c.max_relative);
    x.set("r_squared", c.r_squared);
    x.set("message", c.message);
    ch.push(x);
  }
  o.set("channels", ch);
  o.set("iso_reference", f.iso_reference);
  o.set("reciprocity_ok", f.reciprocity_ok);
  o.set("reciprocity_message", f.reciprocity_message);
  json::Value ex = json::Value::array();
  for (const auto& e : f.exposures) {
    json::Value x = json::Value::object();
    x.set("exposure", exposure_json(e.exposure));
    x.set("label", e.label);
    x.set("factor", e.factor);
    x.set("parallel", e.parallel);
    x.set("samples", triple(e.samples));
    x.set("scale_ratio", triple(e.scale_ratio));
    x.set("slope_difference", triple(e.slope_difference));
    x.set("rms_relative", triple(e.rms_relative));
    ex.push(x);
  }
  o.set("exposures", ex);
  o.set("noise_floor", triple(f.noise_floor));
  o.set("noise_sigma", triple(f.noise_sigma));
  o.set("saturation", triple(f.saturation));
  o.set("saturation_reported", triple(f.saturation_reported));
  o.set("saturation_fraction", triple(f.saturation_fraction));
  json::Value measured = json::Value::array();
  for (bool b : f.saturation_measured) measured.push(b);
  o.set("saturation_measured", measured);
  o.set("areas", triple(f.areas));
  o.set("areas_source", f.areas_source);
  o.set("falloff", f.has_falloff ? falloff_fit_json(f.falloff) : json::Value());
  o.set("w", f.w);
  o.set("transform", f.transform);
  o.set("colour_status", f.colour_status);
  o.set("colour_message", f.colour_message);
  json::Value m = json::Value::array();
  for (Eigen::Index r = 0; r < f.colour_matrix.rows(); ++r) {
    std::vector<double> row(f.colour_matrix.cols());
    for (Eigen::Index c = 0; c < f.colour_matrix.cols(); ++c) row[c] = f.colour_matrix(r, c);
    m.push(json::Value(row));
  }
  o.set("colour_matrix", m);
  o.set("colour_stimuli", f.colour_stimuli);
  o.set("colour_objective", f.colour_objective);
  o.set("fusion", f.fusion);
  return o;
}

json::Value row_json(const AbsoluteTestRow& r) {
  json::Value o = json::Value::object();
  o.set("id", r.id);
  o.set("set", r.set);
  if (!r.file.empty()) {
    o.set("file", r.file);
    o.set("region", json::Value(std::vector<double>{double(r.x), double(r.y), double(r.w), double(r.h)}));
    o.set("pixels", r.pixels);
    o.set("source", r.source);
    o.set("source_label", r.source_label);
  } else {
    o.set("saturated", r.saturated);
  }
  o.set("estimated", triple(r.estimated));
  o.set("reference", triple(r.reference));
  o.set("relative_Y_error", r.relative_Y_error);
  return o;
}

json::Value test_json(const AbsoluteTestReport& t) {
  json::Value o = json::Value::object();
  o.set("white_rule", t.white_rule);
  o.set("white_id", t.white_id);
  o.set("max_luminance", t.max_luminance);
  o.set("white", triple(t.white));
  json::Value figures = json::Value::array();
  for (const auto& f : t.figures) {
    json::Value x = json::Value::object();
    x.set("group", f.group);
    x.set("label", f.label);
    x.set("count", f.count);
    x.set("metrics", absolute_metrics_json(f.metrics));
    figures.push(x);
  }
  o.set("figures", figures);
  json::Value points = json::Value::array(), regions = json::Value::array();
  for (const auto& r : t.points) points.push(row_json(r));
  for (const auto& r : t.regions) regions.push(row_json(r));
  o.set("points", points);
  o.set("regions", regions);
  return o;
}

json::Value maps_json(const AbsoluteMapsSummary& s) {
  json::Value o = json::Value::object();
  o.set("width", s.width);
  o.set("height", s.height);
  o.set("mode", s.mode);
  json::Value ex = json::Value::array();
  for (const auto& e : s.exposures) ex.push(exposure_json(e));
  o.set("exposures", ex);
  o.set("labels", strings(s.labels));
  o.set("names", strings(s.names));
  o.set("dominant_pixels", json::Value(s.dominant_pixels));
  o.set("saturated_pixels", s.saturated_pixels);
  o.set("unreliable_pixels", s.unreliable_pixels);
  o.set("finite_pixels", s.finite_pixels);
  o.set("Y", summary_json(s.Y));
  o.set("Y_p01", s.Y_p01);
  o.set("Y_p99", s.Y_p99);
  return o;
}

// ---- text -------------------------------------------------------------------------------------

std::string num(double v, int digits = 4) {
  if (!std::isfinite(v)) return "-";
  char b[48];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}
std::string pct(double v) { return std::isfinite(v) ? num(100 * v, 3) + " %" : "-"; }
std::string three(const Vec3& v, int digits = 4) { return num(v[0], digits) + " / " + num(v[1], digits) + " / " + num(v[2], digits); }

std::string figures_text(const std::string& title, const AbsoluteMetrics& m) {
  const Metrics& x = m.metrics;
  return title + "\n" +
         "  dE94 mean / median / max        " + num(x.dE94.mean) + " / " + num(x.dE94.median) + " / " + num(x.dE94.max) + "\n" +
         "  dE00 mean / median / max        " + num(x.dE00.mean) + " / " + num(x.dE00.median) + " / " + num(x.dE00.max) + "\n" +
         "  NRMSE X / Y / Z                 " + pct(x.NRMSE[0]) + " / " + pct(x.NRMSE[1]) + " / " + pct(x.NRMSE[2]) + "\n" +
         "  relative Y error (mean |dY|/Y)  " + pct(m.relative_Y_error) + "\n" +
         "  median |dX| / |dY| / |dZ|       " + three(m.median_absolute_error) + " cd/m2\n" +
         "  CIELAB white                    " + three(m.white, 6) + " cd/m2\n";
}

}  // namespace

AbsoluteFitSummary absolute_fit_summary(const AbsoluteProfile& p) {
  AbsoluteFitSummary f;
  f.make = p.make;
  f.model = p.model;
  f.width = p.width;
  f.height = p.height;
  for (int c = 0; c < 3; ++c) {
    const OecfFit& x = p.luminance.fits[c];
    const InverseOecf& k = p.luminance.curves[c];
    f.channels[c] = {k.k1, k.k2, k.k3, x.samples, x.rms_relative, x.max_relative, x.r_squared, x.message};
  }
  f.iso_reference = p.luminance.iso_reference;
  f.reciprocity_ok = p.luminance.reciprocity_ok;
  f.reciprocity_message = p.luminance.message;
  for (const auto& r : p.luminance.exposures)
    f.exposures.push_back({r.exposure, r.exposure.label(), r.factor, r.parallel, r.samples, r.scale_ratio, r.slope_difference,
                           r.rms_relative});
  const Normalisation& n = p.normalisation;
  f.noise_floor = n.noise_floor;
  f.noise_sigma = n.noise_sigma;
  f.saturation = n.saturation;
  f.saturation_reported = p.saturation.reported;
  f.saturation_fraction = p.saturation.fraction;
  f.saturation_measured = p.saturation.measured;
  f.areas = n.areas;
  f.areas_source = p.areas_source;
  f.has_falloff = n.falloff.has_value();
  if (n.falloff) f.falloff = *n.falloff;
  f.w = n.w;
  f.transform = p.transform;
  f.colour_status = fit_status_name(p.colour_status);
  f.colour_message = p.colour_message;
  f.colour_matrix = p.colour.coefficients;
  f.colour_stimuli = p.colour_stimuli;
  f.colour_objective = p.colour_objective;
  f.fusion = fusion_mode_id(p.fusion);
  return f;
}

json::Value absolute_report_json(const AbsoluteReport& r) {
  json::Value o = json::Value::object();
  o.set("format", "tristim-absolute-report");
  o.set("reference", "Guarnera, Bianco & Schettini 2018, section 4.1 (white: eq 16)");
  o.set("fit", fit_json(r.fit));
  o.set("training", r.has_training ? absolute_training_json(r.training) : json::Value());
  o.set("test", r.has_test ? test_json(r.test) : json::Value());
  o.set("maps", r.has_maps ? maps_json(r.maps) : json::Value());
  return o;
}

std::string absolute_report_text(const AbsoluteReport& r) {
  const AbsoluteFitSummary& f = r.fit;
  std::string s = "absolute profile: " + f.make + " " + f.model + " (Guarnera, Bianco & Schettini 2018)\n";
  s += "inverse OECF per channel (eq 8), exposure units at ISO " + num(f.iso_reference) + ":\n";
  for (int c = 0; c < 3; ++c) {
    const AbsoluteChannelFit& k = f.channels[c];
    s += std::string("  ") + "RGB"[c] + ": k1 " + num(k.k1, 6) + "  k2 " + num(k.k2, 6) + "  k3 " + num(k.k3, 6) + "  (" +
         std::to_string(k.samples) + " stimuli, RMS relative error " + pct(k.rms_relative) + ", R2 " + num(k.r_squared, 6) +
         ")\n";
  }
  s += "  n " + num(f.noise_floor[0]) + " / " + num(f.noise_floor[1]) + " / " + num(f.noise_floor[2]) + " DN, S " +
       num(f.saturation[0], 6) + " / " + num(f.saturation[1], 6) + " / " + num(f.saturation[2], 6) + " DN, areas " +
       f.areas_source + ", fall-off " + (f.has_falloff ? "p1 " + num(f.falloff.p1) + " p2 " + num(f.falloff.p2) : "none") +
       ", w " + num(f.w) + "\n";
  s += std::string("reciprocity: ") + (f.reciprocity_ok ? "holds" : "fails: " + f.reciprocity_message) + " (" +
       std::to_string(f.exposures.size()) + " exposures)\n";
  s += "colour matrix " + f.transform + " (eqs 11-15): " + f.colour_status +
       (f.colour_message.empty() ? "" : " (" + f.colour_message + ")") + ", " + std::to_string(f.colour_stimuli) + " stimuli\n";
  if (r.has_training)
    s += figures_text("\ntraining: " + std::to_string(r.training.evaluated) + " stimuli (" +
                          std::to_string(r.training.luminance_stimuli) + " luminance, " +
                          std::to_string(r.training.colour_stimuli) + " colour, " +
                          std::to_string(r.training.saturated_stimuli) + " left out saturated); white E",
                      r.training.figures);
  if (r.has_test) {
    const AbsoluteTestReport& t = r.test;
    const std::string white = t.white_rule == "eq16" ? "eq (16) from '" + t.white_id + "'" : "E";
    for (const auto& g : t.figures)
      s += figures_text("\ntest, " + g.label + ": " + std::to_string(g.count) + " stimuli; white " + white + " at Y_Q " +
                            num(t.max_luminance, 6) + " cd/m2",
                        g.metrics);
    s += "\n" + std::string("id             set        estimated X / Y / Z (cd/m2)      reference X / Y / Z        rel. Y     source\n");
    auto rows = [&](const std::vector<AbsoluteTestRow>& v) {
      for (const auto& x : v) {
        char line[512];
        std::snprintf(line, sizeof line, "%-14s %-10s %-32s %-26s %-10s %s\n", x.id.c_str(), x.set.c_str(),
                      three(x.estimated, 5).c_str(), three(x.reference, 5).c_str(), pct(x.relative_Y_error).c_str(),
                      x.file.empty() ? (x.saturated ? "per patch, saturated" : "per patch") : x.source_label.c_str());
        s += line;
      }
    };
    rows(t.points);
    rows(t.regions);
  }
  if (r.has_maps) {
    const AbsoluteMapsSummary& m = r.maps;
    s += "\nmaps: " + std::to_string(m.width) + "x" + std::to_string(m.height) + " from " + std::to_string(m.labels.size()) +
         " exposures (" + m.mode + "); Y " + num(m.Y.min) + " … " + num(m.Y.max) + " cd/m2 (median " + num(m.Y.median) +
         "); " + num(m.saturated_pixels, 10) + " pixels saturated in every exposure, " + num(m.unreliable_pixels, 10) +
         " without a reliable value\n";
    for (size_t e = 0; e < m.labels.size(); ++e)
      s += "  " + m.labels[e] + (e < m.names.size() ? " (" + m.names[e] + ")" : "") + ": dominant in " +
           num(m.dominant_pixels[e], 10) + " pixels\n";
  }
  return s;
}

}  // namespace tristim
