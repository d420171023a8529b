// The absolute profile as versioned JSON (rules in tristim/absolute/profile.hpp), written and read
// from the field lists below (io/fields.hpp): one declaration per section of the document.
#include <cmath>

#include "tristim/absolute/profile.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/version.hpp"
#include "fields.hpp"

namespace tristim {

namespace fields {

// The figures' reading: null is how the writer spells a non-finite figure (e.g. the mean ΔE of no
// stimuli, a fall-off's residual); everything else is read strictly.
const Context kFigures{ErrorCode::ProfileInvalid, "", true};
const Context kStrict{ErrorCode::ProfileInvalid, "", false};

/// An eq (8) curve: [k1, k2 > 0, k3 > 0].
template <>
struct Codec<InverseOecf> {
  static json::Value write(const InverseOecf& k) { return json::Value(std::vector<double>{k.k1, k.k2, k.k3}); }
  static void read(const json::Value& v, InverseOecf& out, const Context& c, const std::string& p) {
    std::array<double, 3> k{};
    fields::read(v, k, c, p);
    if (!(k[1] > 0) || !(k[2] > 0) || !std::isfinite(k[1] * k[2])) c.refuse("'" + p + "' must be [k1, k2 > 0, k3 > 0]");
    out = {k[0], k[1], k[2]};
  }
};

TRISTIM_FIELDS(SaturationEstimate, member<&SaturationEstimate::level>("level"),
               member<&SaturationEstimate::reported>("reported"), member<&SaturationEstimate::fraction>("fraction"),
               member<&SaturationEstimate::measured>("measured"),
               member<&SaturationEstimate::clipped_pixels>("clipped_pixels"));

TRISTIM_FIELDS(OecfFit, member<&OecfFit::samples>("samples"), member<&OecfFit::rms_relative>("rms_relative"),
               member<&OecfFit::max_relative>("max_relative"), member<&OecfFit::r_squared>("r_squared"),
               member<&OecfFit::message>("message"));

/// An exposure's own curve per channel, null where it had too few stimuli (own_fit false).
Field<ExposureReport> own_curves() {
  return {"own",
          [](const ExposureReport& r) {
            json::Value a = json::Value::array();
            for (int c = 0; c < 3; ++c) a.push(r.own_fit[c] ? fields::write(r.own[c]) : json::Value());
            return a;
          },
          [](const json::Value& v, ExposureReport& r, const Context& c, const std::string& p) {
            std::array<std::optional<InverseOecf>, 3> own;
            fields::read(v, own, c, p);
            for (int k = 0; k < 3; ++k)
              if ((r.own_fit[k] = own[k].has_value())) r.own[k] = *own[k];
          }};
}

TRISTIM_FIELDS(ExposureReport, nested<&ExposureReport::exposure, &ExposureSettings::exposure_s>("exposure_s"),
               nested<&ExposureReport::exposure, &ExposureSettings::f_number>("f_number"),
               nested<&ExposureReport::exposure, &ExposureSettings::iso>("iso"), member<&ExposureReport::factor>("factor"),
               member<&ExposureReport::samples>("samples"), member<&ExposureReport::scale_ratio>("scale_ratio"),
               member<&ExposureReport::slope_difference>("slope_difference"),
               member<&ExposureReport::rms_relative>("rms_relative"), own_curves(),
               member<&ExposureReport::parallel>("parallel"));

using P = AbsoluteProfile;

const FieldList<P>& camera_fields() {
  static const FieldList<P> f = {member<&P::make>("make"), member<&P::model>("model"), member<&P::width>("width"),
                                 member<&P::height>("height")};
  return f;
}

const FieldList<P>& normalisation_fields() {
  static const FieldList<P> f = {
      nested<&P::normalisation, &Normalisation::noise_floor>("noise_floor"),
      nested<&P::normalisation, &Normalisation::noise_sigma>("noise_sigma"),
      nested<&P::normalisation, &Normalisation::saturation>("saturation"),
      nested<&P::normalisation, &Normalisation::areas>("areas"), member<&P::areas_source>("areas_source"),
      nested<&P::normalisation, &Normalisation::w>("w"),
      {"falloff", [](const P& p) { return fields::write(p.normalisation.falloff); },
       [](const json::Value& v, P& p, const Context&, const std::string& path) {
         fields::read(v, p.normalisation.falloff, kFigures, path);
       }}};
  return f;
}

/// The linearisation stage as a recipe names it (method, parameters; written only, the method
/// checked on reading), then eq (8)'s curves and their fits. Reading k sets each curve twice (the
/// common curve and its fit's), as the fit leaves them.
const FieldList<P>& linearisation_fields() {
  static const FieldList<P> f = {
      {"method", [](const P& p) { return json::Value(p.linearisation_choice().method); },
       [](const json::Value& v, P&, const Context& c, const std::string& path) {
         if (!v.is_string() || v.as_string() != "Guarnera2018") c.refuse("'" + path + "' must be Guarnera2018");
       }},
      {"parameters", [](const P& p) { return fields::write(p.linearisation_choice().parameters); },
       [](const json::Value&, P&, const Context&, const std::string&) {}},
      nested<&P::luminance, &LuminanceFit::iso_reference>("iso_reference"),
      {"k", [](const P& p) { return fields::write(p.luminance.curves); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         fields::read(v, p.luminance.curves, c, path);
         for (int k = 0; k < 3; ++k) p.luminance.fits[k].curve = p.luminance.curves[k];
       }},
      {"fits", [](const P& p) { return fields::write(p.luminance.fits); },
       [](const json::Value& v, P& p, const Context&, const std::string& path) {
         std::array<OecfFit, 3> fits = p.luminance.fits;  // keeps each fit's curve (read from k)
         fields::read(v, fits, kFigures, path);
         p.luminance.fits = fits;
       },
       nullptr, false}};
  return f;
}

const FieldList<P>& reciprocity_fields() {
  static const FieldList<P> f = {nested<&P::luminance, &LuminanceFit::reciprocity_ok>("ok"),
                                 nested<&P::luminance, &LuminanceFit::message>("message"),
                                 nested<&P::luminance, &LuminanceFit::exposures>("exposures")};
  return f;
}

/// M (eq 11, Algorithm 2's pattern search) with its model id and fit summary.
const FieldList<P>& colour_fields() {
  static const FieldList<P> f = {
      member<&P::transform>("transform"), nested<&P::colour, &Model::id>("model"),
      {"objective", [](const P&) { return json::Value("psm"); },
       [](const json::Value& v, P&, const Context& c, const std::string& path) {
         if (!v.is_string()) c.refuse("'" + path + "' must be a string");
       }},
      nested<&P::colour, &Model::coefficients>("coefficients"), member<&P::colour_stimuli>("stimuli"),
      {"status", [](const P& p) { return json::Value(fit_status_name(p.colour_status)); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         std::string s;
         fields::read(v, s, c, path);
         p.colour_status = fit_status_from_name(s);
       }},
      member<&P::colour_message>("message"), member<&P::colour_objective>("objective_value")};
  return f;
}

TRISTIM_FIELDS(
    AbsoluteProfile,
    {"tristim_version", [](const P&) { return json::Value(kVersion); },
     [](const json::Value& v, P&, const Context& c, const std::string& path) {
       if (!v.is_string()) c.refuse("'" + path + "' must be a string");
     }},
    {"reference", [](const P&) { return json::Value("Guarnera, Bianco & Schettini 2018, eqs (4)-(15), Algorithms 1-2"); },
     [](const json::Value&, P&, const Context&, const std::string&) {}},
    section<P, &camera_fields>("camera"), section<P, &normalisation_fields>("normalisation"),
    member<&P::saturation>("saturation"), section<P, &linearisation_fields>("linearisation"),
    section<P, &reciprocity_fields>("reciprocity"), section<P, &colour_fields>("colour"),
    {"fusion", [](const P& p) { return json::Value(fusion_mode_id(p.fusion)); },
     [](const json::Value& v, P& p, const Context& c, const std::string& path) {
       std::string s;
       fields::read(v, s, c, path);
       p.fusion = fusion_mode_from_id(s);
     }},
    with_shown<P>({"training", [](const P& p) { return fields::write(p.training); },
                   [](const json::Value& v, P& p, const Context&, const std::string& path) {
                     fields::read(v, p.training, kFigures, path);
                     p.has_training = true;
                   },
                   nullptr, false},
                  [](const P& p) { return p.has_training; }),
    // Read after the rest, with its own codes (RecipeInvalid / RecipeVersion).
    with_shown<P>({"recipe", [](const P& p) { return absolute_recipe_json(p.recipe); },
                   [](const json::Value&, P&, const Context&, const std::string&) {}, nullptr, false},
                  [](const P& p) { return p.has_recipe; }));

}  // namespace fields

namespace {
using fields::kFigures;
const fields::Document kDocument{"tristim-absolute-profile", kAbsoluteProfileVersion, "absolute profile",
                                 ErrorCode::ProfileInvalid, ErrorCode::ProfileVersion};

/// What the field lists cannot say: the fall-off's scale, the normalisation's own rules, the
/// colour model's id and shape.
void check_profile(AbsoluteProfile& p) {
  Normalisation& n = p.normalisation;
  if (n.falloff && !(n.falloff->r_scale > 0)) throw Error(ErrorCode::ProfileInvalid, "falloff.r_scale must be positive");
  n.check();
  if (p.colour.id != "Guarnera2018-" + p.transform)
    throw Error(ErrorCode::ProfileInvalid, "colour.model must be Guarnera2018-" + p.transform);
  check_coefficient_shape(p.colour, model_info(p.colour.id));
}
}  // namespace

json::Value falloff_fit_json(const FalloffFit& f) { return fields::write(f); }

json::Value absolute_metrics_json(const AbsoluteMetrics& m) { return fields::write(m); }

AbsoluteMetrics absolute_metrics_from_json(const json::Value& o, const std::string& where) {
  AbsoluteMetrics a;
  fields::read(o, a, kFigures, where);
  return a;
}

json::Value absolute_training_json(const AbsoluteTraining& t) { return fields::write(t); }

AbsoluteTraining absolute_training_from_json(const json::Value& o, const std::string& where) {
  AbsoluteTraining t;
  fields::read(o, t, kFigures, where);
  return t;
}

json::Value absolute_profile_json(const AbsoluteProfile& p) {
  json::Value o = json::Value::object();
  o.set("format", kDocument.format);
  o.set("version", p.version);
  fields::write_members(p, o);
  return o;
}

std::string absolute_profile_to_json(const AbsoluteProfile& p) { return absolute_profile_json(p).dump(2) + "\n"; }

AbsoluteProfile absolute_profile_from_json(const std::string& text) {
  const json::Value o = fields::parse_document(text, kDocument);
  AbsoluteProfile p;
  try {
    fields::read_document(o, p, kDocument, fields::kStrict);
    check_profile(p);
  } catch (const Error& e) {
    if (e.code() == ErrorCode::ProfileInvalid || e.code() == ErrorCode::ProfileVersion) throw;
    throw Error(ErrorCode::ProfileInvalid, std::string("absolute profile: ") + e.what());
  }
  if (const json::Value* r = o.find("recipe")) {  // its own errors: RecipeInvalid / RecipeVersion
    p.recipe = absolute_recipe_from_json(*r);
    p.has_recipe = true;
  }
  return p;
}

}  // namespace tristim
