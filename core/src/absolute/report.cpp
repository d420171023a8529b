// The report of the absolute tele-colorimeter: from a profile, as JSON and as text (rules in
// tristim/absolute/report.hpp).
#include "tristim/absolute/report.hpp"

#include <cmath>
#include <cstdio>

#include "tristim/profile/fields.hpp"
#include "tristim/profile/profile.hpp"
#include "../citations.hpp"
#include "fields.hpp"

namespace tristim {

// ---- the field lists: the report's JSON comes from these ------------------------------------

namespace fields {

TRISTIM_FIELDS_DEFINE(AbsoluteTraining, member<&AbsoluteTraining::luminance_stimuli>("luminance_stimuli"),
                      member<&AbsoluteTraining::colour_stimuli>("colour_stimuli"),
                      member<&AbsoluteTraining::saturated_stimuli>("saturated_stimuli"),
                      member<&AbsoluteTraining::evaluated>("evaluated"), member<&AbsoluteTraining::figures>("figures"));

TRISTIM_FIELDS_DEFINE(AbsoluteMetrics, member<&AbsoluteMetrics::metrics>("metrics"),
               member<&AbsoluteMetrics::relative_Y_error>("relative_Y_error"),
               member<&AbsoluteMetrics::median_absolute_error>("median_absolute_error"),
               member<&AbsoluteMetrics::white>("white"));

TRISTIM_FIELDS(AbsoluteChannelFit, member<&AbsoluteChannelFit::k1>("k1"), member<&AbsoluteChannelFit::k2>("k2"),
               member<&AbsoluteChannelFit::k3>("k3"), member<&AbsoluteChannelFit::samples>("samples"),
               member<&AbsoluteChannelFit::rms_relative>("rms_relative"),
               member<&AbsoluteChannelFit::max_relative>("max_relative"),
               member<&AbsoluteChannelFit::r_squared>("r_squared"), member<&AbsoluteChannelFit::message>("message"));

TRISTIM_FIELDS(AbsoluteExposureCheck, member<&AbsoluteExposureCheck::exposure>("exposure"),
               member<&AbsoluteExposureCheck::label>("label"), member<&AbsoluteExposureCheck::factor>("factor"),
               member<&AbsoluteExposureCheck::parallel>("parallel"), member<&AbsoluteExposureCheck::samples>("samples"),
               member<&AbsoluteExposureCheck::scale_ratio>("scale_ratio"),
               member<&AbsoluteExposureCheck::slope_difference>("slope_difference"),
               member<&AbsoluteExposureCheck::rms_relative>("rms_relative"));

using Fit = AbsoluteFitSummary;
TRISTIM_FIELDS_DEFINE(Fit, member<&Fit::make>("make"), member<&Fit::model>("model"), member<&Fit::width>("width"),
               member<&Fit::height>("height"), member<&Fit::channels>("channels"),
               member<&Fit::iso_reference>("iso_reference"), member<&Fit::reciprocity_ok>("reciprocity_ok"),
               member<&Fit::reciprocity_message>("reciprocity_message"), member<&Fit::exposures>("exposures"),
               member<&Fit::noise_floor>("noise_floor"), member<&Fit::noise_sigma>("noise_sigma"),
               member<&Fit::saturation>("saturation"), member<&Fit::saturation_reported>("saturation_reported"),
               member<&Fit::saturation_fraction>("saturation_fraction"),
               member<&Fit::saturation_measured>("saturation_measured"), member<&Fit::areas>("areas"),
               member<&Fit::areas_source>("areas_source"), member_or_null<&Fit::has_falloff, &Fit::falloff>("falloff"),
               member<&Fit::w>("w"), member<&Fit::transform>("transform"), member<&Fit::colour_status>("colour_status"),
               member<&Fit::colour_message>("colour_message"), member<&Fit::colour_matrix>("colour_matrix"),
               member<&Fit::colour_stimuli>("colour_stimuli"), member<&Fit::colour_objective>("colour_objective"),
               member<&Fit::fusion>("fusion"));

// A region row names its frame, region, pixels and source; a per-patch row says whether it was saturated.
static bool region_row(const AbsoluteTestRow& r) { return !r.file.empty(); }
static bool patch_row(const AbsoluteTestRow& r) { return r.file.empty(); }
static json::Value region_json(const AbsoluteTestRow& r) {
  return json::Value(std::vector<double>{double(r.x), double(r.y), double(r.w), double(r.h)});
}
using Row = AbsoluteTestRow;
TRISTIM_FIELDS(Row, member<&Row::id>("id"), member<&Row::set>("set"), with_shown(member<&Row::file>("file"), region_row),
               with_shown(Field<Row>{"region", region_json, nullptr}, region_row),
               with_shown(member<&Row::pixels>("pixels"), region_row), with_shown(member<&Row::source>("source"), region_row),
               with_shown(member<&Row::source_label>("source_label"), region_row),
               with_shown(member<&Row::saturated>("saturated"), patch_row), member<&Row::estimated>("estimated"),
               member<&Row::reference>("reference"), member<&Row::relative_Y_error>("relative_Y_error"));

TRISTIM_FIELDS(AbsoluteFigures, member<&AbsoluteFigures::group>("group"), member<&AbsoluteFigures::label>("label"),
               member<&AbsoluteFigures::count>("count"),
               member<&AbsoluteFigures::metrics>("metrics"));

using Test = AbsoluteTestReport;
TRISTIM_FIELDS(Test, member<&Test::white_rule>("white_rule"), member<&Test::white_id>("white_id"),
               member<&Test::max_luminance>("max_luminance"), member<&Test::white>("white"),
               member<&Test::figures>("figures"), member<&Test::points>("points"), member<&Test::regions>("regions"));

using Maps = AbsoluteMapsSummary;
TRISTIM_FIELDS_DEFINE(Maps, member<&Maps::width>("width"), member<&Maps::height>("height"), member<&Maps::mode>("mode"),
               member<&Maps::exposures>("exposures"), member<&Maps::labels>("labels"), member<&Maps::names>("names"),
               member<&Maps::dominant_pixels>("dominant_pixels"), member<&Maps::saturated_pixels>("saturated_pixels"),
               member<&Maps::unreliable_pixels>("unreliable_pixels"), member<&Maps::finite_pixels>("finite_pixels"),
               member<&Maps::Y>("Y"), member<&Maps::Y_p01>("Y_p01"), member<&Maps::Y_p99>("Y_p99"));

// What the pointer reads on the maps (the page's read-out; `tristim absolute apply --points`, one
// per point after its id).
using Readout = AbsoluteReadout;
TRISTIM_FIELDS_DEFINE(Readout, member<&Readout::x>("x"), member<&Readout::y>("y"), member<&Readout::n>("n"),
                      member<&Readout::XYZ>("XYZ"), member<&Readout::L>("L"), member<&Readout::source>("source"),
                      member<&Readout::source_label>("source_label"), member<&Readout::contributors>("contributors"));

// How a profile is applied to a series and its report made (a JS caller's options; every member
// may be left out: its C++ default).
using ApplyOptions = AbsoluteApplyOptions;
TRISTIM_FIELDS_DEFINE(ApplyOptions, member<&ApplyOptions::mode>("mode", false),
                      member<&ApplyOptions::exposures>("exposures", false), member<&ApplyOptions::names>("names", false));
TRISTIM_FIELDS_DEFINE(AbsoluteEvaluateOptions, member<&AbsoluteEvaluateOptions::white>("white", false));

// The sensitivity estimate's uncertainty (tristim/absolute/sensitivities.hpp): the page's note and
// `tristim sensitivities estimate`'s "uncertainty".
using Uncertainty = SensitivityUncertainty;
TRISTIM_FIELDS_DEFINE(Uncertainty, member<&Uncertainty::ratio>("ratio"), member<&Uncertainty::u_loo>("u_loo"),
                      member<&Uncertainty::u_K>("u_K"), member<&Uncertainty::u>("u"),
                      member<&Uncertainty::coverage>("coverage"), member<&Uncertainty::loo_bases>("loo_bases"),
                      member<&Uncertainty::components_tried>("components_tried"),
                      member<&Uncertainty::nearest_camera>("nearest_camera"),
                      member<&Uncertainty::nearest_distance>("nearest_distance"),
                      member<&Uncertainty::residual_limit>("residual_limit"),
                      member<&Uncertainty::distance_limit>("distance_limit"), member<&Uncertainty::warnings>("warnings"),
                      member<&Uncertainty::message>("message"));

// The sensitivity estimate (tristim/absolute/sensitivities.hpp): `tristim sensitivities estimate`'s
// JSON and the page's object. "method" is always "Jiang2013"; the area ratios (A_R/A_G, A_B/A_G:
// what eq (7) uses) are written from `areas` and, read back, checked to be numbers only; the
// curves as {wavelengths, names, values} (SpectralData's own JS object is not changed).
namespace {
using Estimate = SensitivityEstimate;
const FieldList<SpectralData>& curve_fields() {
  static const FieldList<SpectralData> f = {member<&SpectralData::wavelengths>("wavelengths"),
                                            member<&SpectralData::names>("names"),
                                            member<&SpectralData::values>("values")};
  return f;
}
template <int C>
Field<Estimate> area_ratio(const char* name) {
  return {name, [](const Estimate& e) { return json::Value(e.areas[C] / e.areas[1]); },
          [](const json::Value& v, Estimate&, const Context& c, const std::string& p) {
            double ignored = 0;  // derived from areas
            fields::read(v, ignored, c, p);
          }};
}
}  // namespace
TRISTIM_FIELDS_DEFINE(Estimate,
                      Field<Estimate>{"method", [](const Estimate&) { return json::Value("Jiang2013"); },
                                      [](const json::Value& v, Estimate&, const Context& c, const std::string& p) {
                                        if (!v.is_string() || v.as_string() != "Jiang2013")
                                          c.refuse("'" + p + "' must be \"Jiang2013\"");
                                      }},
                      member<&Estimate::patches>("patches"), member<&Estimate::unpaired>("unpaired"),
                      member<&Estimate::components>("components"), member<&Estimate::basis_cameras>("basis_cameras"),
                      member<&Estimate::residual>("residual"), member<&Estimate::residual_rms>("residual_rms"),
                      member<&Estimate::areas>("areas"), area_ratio<0>("area_ratio_R_G"),
                      area_ratio<2>("area_ratio_B_G"), member<&Estimate::clipped>("clipped"),
                      member<&Estimate::ids>("ids"),
                      Field<Estimate>{"ssf",
                                      [](const Estimate& e) {
                                        json::Value o = json::Value::object();
                                        write_list(e.ssf, curve_fields(), o);
                                        return o;
                                      },
                                      [](const json::Value& v, Estimate& e, const Context& c, const std::string& p) {
                                        read_list(v, e.ssf, curve_fields(), c, p);
                                        bool ok = e.ssf.names.size() == e.ssf.values.size();
                                        for (const auto& col : e.ssf.values) ok = ok && col.size() == e.ssf.wavelengths.size();
                                        if (!ok) c.refuse("'" + p + "' must have one value column per name, one value per wavelength");
                                      }});

using Report = AbsoluteReport;
TRISTIM_FIELDS_DEFINE(Report, member<&Report::fit>("fit"),
               member_or_null<&Report::has_training, &Report::training>("training"),
               member_or_null<&Report::has_test, &Report::test>("test"),
               member_or_null<&Report::has_maps, &Report::maps>("maps"));

}  // namespace fields

namespace {

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

std::vector<AbsoluteWhiteRule> absolute_white_rules() {
  const std::string guarnera = citation::kGuarnera2018;
  return {{"", "the brightest chromatic stimulus, eq (16)", guarnera + ", eq (16) and section 4.1"},
          {"E", "E (X = Y = Z) at the largest Y", guarnera + ", section 4.1 (Experiments a and c)"}};
}

json::Value absolute_report_json(const AbsoluteReport& r) {
  json::Value o = json::Value::object();
  o.set("format", "tristim-absolute-report");
  o.set("reference", "Guarnera, Bianco & Schettini 2018, section 4.1 (white: eq 16)");
  fields::write_members(r, o);
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
