// The absolute profile as versioned JSON (rules in tristim/absolute/profile.hpp).
#include <cmath>

#include "tristim/absolute/profile.hpp"
#include "tristim/error.hpp"
#include "tristim/io/limits.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/version.hpp"
#include "fields.hpp"

namespace tristim {

namespace {

json::Value triple(const std::array<double, 3>& a) { return json::Value(std::vector<double>{a[0], a[1], a[2]}); }

std::array<double, 3> read_triple(const json::Value& o, const std::string& key, const std::string& where) {
  const auto v = o.at(key).as_numbers(where + "." + key);
  if (v.size() != 3) throw Error(ErrorCode::ProfileInvalid, where + "." + key + " must have 3 numbers");
  for (double x : v)
    if (!std::isfinite(x)) throw Error(ErrorCode::ProfileInvalid, where + "." + key + " must be finite");
  return {v[0], v[1], v[2]};
}

json::Value curve_json(const InverseOecf& k) { return json::Value(std::vector<double>{k.k1, k.k2, k.k3}); }

InverseOecf read_curve(const json::Value& v, const std::string& where) {
  const auto k = v.as_numbers(where);
  if (k.size() != 3 || !std::isfinite(k[0]) || !(k[1] > 0) || !(k[2] > 0) || !std::isfinite(k[1] * k[2]))
    throw Error(ErrorCode::ProfileInvalid, where + " must be [k1, k2 > 0, k3 > 0]");
  return {k[0], k[1], k[2]};
}

json::Value exposure_json(const ExposureSettings& e) {
  json::Value o = json::Value::object();
  o.set("exposure_s", e.exposure_s);
  o.set("f_number", e.f_number);
  o.set("iso", e.iso);
  return o;
}

}  // namespace

json::Value falloff_fit_json(const FalloffFit& f) { return fields::write(f); }

json::Value absolute_metrics_json(const AbsoluteMetrics& m) { return fields::write(m); }

// null is how the writer spells a non-finite figure (e.g. the mean ΔE of no stimuli)
static const fields::Context kFigures{ErrorCode::ProfileInvalid, "", true};

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
  o.set("format", "tristim-absolute-profile");
  o.set("version", p.version);
  o.set("tristim_version", kVersion);
  o.set("reference", "Guarnera, Bianco & Schettini 2018, eqs (4)-(15), Algorithms 1-2");
  json::Value cam = json::Value::object();
  cam.set("make", p.make);
  cam.set("model", p.model);
  cam.set("width", p.width);
  cam.set("height", p.height);
  o.set("camera", cam);

  const Normalisation& n = p.normalisation;
  json::Value no = json::Value::object();
  no.set("noise_floor", triple(n.noise_floor));
  no.set("noise_sigma", triple(n.noise_sigma));
  no.set("saturation", triple(n.saturation));
  no.set("areas", triple(n.areas));
  no.set("areas_source", p.areas_source);
  no.set("w", n.w);
  no.set("falloff", n.falloff ? falloff_fit_json(*n.falloff) : json::Value());
  o.set("normalisation", no);

  json::Value sat = json::Value::object();
  sat.set("level", triple(p.saturation.level));
  sat.set("reported", triple(p.saturation.reported));
  sat.set("fraction", triple(p.saturation.fraction));
  json::Value measured = json::Value::array();
  for (bool b : p.saturation.measured) measured.push(b);
  sat.set("measured", measured);
  sat.set("clipped_pixels", triple(p.saturation.clipped_pixels));
  o.set("saturation", sat);

  const LuminanceFit& L = p.luminance;
  json::Value lin = json::Value::object();
  const MethodChoice choice = p.linearisation_choice();
  lin.set("method", choice.method);
  json::Value params = json::Value::object();
  for (const auto& [k, v] : choice.parameters) params.set(k, v);
  lin.set("parameters", params);
  lin.set("iso_reference", L.iso_reference);
  json::Value ks = json::Value::array(), fits = json::Value::array();
  for (int c = 0; c < 3; ++c) {
    ks.push(curve_json(L.curves[c]));
    json::Value f = json::Value::object();
    f.set("samples", L.fits[c].samples);
    f.set("rms_relative", L.fits[c].rms_relative);
    f.set("max_relative", L.fits[c].max_relative);
    f.set("r_squared", L.fits[c].r_squared);
    f.set("message", L.fits[c].message);
    fits.push(f);
  }
  lin.set("k", ks);
  lin.set("fits", fits);
  o.set("linearisation", lin);

  json::Value rec = json::Value::object();
  rec.set("ok", L.reciprocity_ok);
  rec.set("message", L.message);
  json::Value ex = json::Value::array();
  for (const auto& r : L.exposures) {
    json::Value e = exposure_json(r.exposure);
    e.set("factor", r.factor);
    e.set("samples", json::Value(std::vector<double>{double(r.samples[0]), double(r.samples[1]), double(r.samples[2])}));
    e.set("scale_ratio", triple(r.scale_ratio));
    e.set("slope_difference", triple(r.slope_difference));
    e.set("rms_relative", triple(r.rms_relative));
    json::Value own = json::Value::array();
    for (int c = 0; c < 3; ++c) own.push(r.own_fit[c] ? curve_json(r.own[c]) : json::Value());
    e.set("own", own);
    e.set("parallel", r.parallel);
    ex.push(e);
  }
  rec.set("exposures", ex);
  o.set("reciprocity", rec);

  json::Value col = json::Value::object();
  col.set("transform", p.transform);
  col.set("model", p.colour.id);
  col.set("objective", "psm");
  json::Value coef = json::Value::array();
  for (Eigen::Index c = 0; c < p.colour.coefficients.rows(); ++c) {
    std::vector<double> row(p.colour.coefficients.cols());
    for (Eigen::Index j = 0; j < p.colour.coefficients.cols(); ++j) row[j] = p.colour.coefficients(c, j);
    coef.push(json::Value(row));
  }
  col.set("coefficients", coef);
  col.set("stimuli", p.colour_stimuli);
  col.set("status", fit_status_name(p.colour_status));
  col.set("message", p.colour_message);
  col.set("objective_value", p.colour_objective);
  o.set("colour", col);
  o.set("fusion", fusion_mode_id(p.fusion));
  if (p.has_training) o.set("training", absolute_training_json(p.training));
  if (p.has_recipe) o.set("recipe", absolute_recipe_json(p.recipe));
  return o;
}

std::string absolute_profile_to_json(const AbsoluteProfile& p) { return absolute_profile_json(p).dump(2) + "\n"; }

AbsoluteProfile absolute_profile_from_json(const std::string& text) {
  const fields::Document d{"tristim-absolute-profile", kAbsoluteProfileVersion, "absolute profile", ErrorCode::ProfileInvalid,
                           ErrorCode::ProfileVersion};
  const json::Value o = fields::parse_document(text, d);
  fields::check_document(o, d);
  AbsoluteProfile p;
  try {
    const json::Value& cam = o.at("camera");
    p.make = cam.at("make").as_string("camera.make");
    p.model = cam.at("model").as_string("camera.model");
    p.width = cam.at("width").as_int("camera.width", 0, limits::kMaxJsonInt);
    p.height = cam.at("height").as_int("camera.height", 0, limits::kMaxJsonInt);

    const json::Value& no = o.at("normalisation");
    Normalisation& n = p.normalisation;
    n.noise_floor = read_triple(no, "noise_floor", "normalisation");
    n.noise_sigma = read_triple(no, "noise_sigma", "normalisation");
    n.saturation = read_triple(no, "saturation", "normalisation");
    n.areas = read_triple(no, "areas", "normalisation");
    p.areas_source = no.at("areas_source").as_string("normalisation.areas_source");
    n.w = no.at("w").as_number("normalisation.w");
    const json::Value& fo = no.at("falloff");
    if (!fo.is_null()) {
      FalloffFit f;
      fields::read(fo, f, kFigures, "falloff");
      if (!(f.r_scale > 0)) throw Error(ErrorCode::ProfileInvalid, "falloff.r_scale must be positive");
      n.falloff = f;
    }
    n.check();

    const json::Value& sat = o.at("saturation");
    p.saturation.level = read_triple(sat, "level", "saturation");
    p.saturation.reported = read_triple(sat, "reported", "saturation");
    p.saturation.fraction = read_triple(sat, "fraction", "saturation");
    p.saturation.clipped_pixels = read_triple(sat, "clipped_pixels", "saturation");
    const auto& measured = sat.at("measured").as_array("saturation.measured");
    if (measured.size() != 3) throw Error(ErrorCode::ProfileInvalid, "saturation.measured must have 3 entries");
    for (int c = 0; c < 3; ++c) p.saturation.measured[c] = measured[c].as_bool("saturation.measured");

    const json::Value& lin = o.at("linearisation");
    if (lin.at("method").as_string("linearisation.method") != "Guarnera2018")
      throw Error(ErrorCode::ProfileInvalid, "linearisation.method must be Guarnera2018");
    p.luminance.iso_reference = lin.at("iso_reference").as_number("linearisation.iso_reference");
    const auto& ks = lin.at("k").as_array("linearisation.k");
    if (ks.size() != 3) throw Error(ErrorCode::ProfileInvalid, "linearisation.k must have 3 rows");
    for (int c = 0; c < 3; ++c) p.luminance.curves[c] = p.luminance.fits[c].curve = read_curve(ks[c], "linearisation.k");
    if (const auto* fits = lin.find("fits"); fits && fits->is_array() && fits->size() == 3)
      for (int c = 0; c < 3; ++c) {
        const json::Value& f = fits->as_array()[c];
        p.luminance.fits[c].samples = f.at("samples").as_int("linearisation.fits.samples", 0, limits::kMaxJsonInt);
        p.luminance.fits[c].rms_relative = f.at("rms_relative").as_number();
        p.luminance.fits[c].max_relative = f.at("max_relative").as_number();
        p.luminance.fits[c].r_squared = f.at("r_squared").as_number();
        p.luminance.fits[c].message = f.at("message").as_string();
      }

    const json::Value& rec = o.at("reciprocity");
    p.luminance.reciprocity_ok = rec.at("ok").as_bool("reciprocity.ok");
    p.luminance.message = rec.at("message").as_string("reciprocity.message");
    for (const auto& e : rec.at("exposures").as_array("reciprocity.exposures")) {
      ExposureReport r;
      r.exposure = {e.at("exposure_s").as_number(), e.at("f_number").as_number(), e.at("iso").as_number()};
      r.factor = e.at("factor").as_number();
      const auto s = read_triple(e, "samples", "reciprocity.exposures");
      for (int c = 0; c < 3; ++c) r.samples[c] = static_cast<int>(s[c]);
      r.scale_ratio = read_triple(e, "scale_ratio", "reciprocity.exposures");
      r.slope_difference = read_triple(e, "slope_difference", "reciprocity.exposures");
      r.rms_relative = read_triple(e, "rms_relative", "reciprocity.exposures");
      const auto& own = e.at("own").as_array("reciprocity.exposures.own");
      if (own.size() != 3) throw Error(ErrorCode::ProfileInvalid, "reciprocity.exposures.own must have 3 entries");
      for (int c = 0; c < 3; ++c)
        if ((r.own_fit[c] = !own[c].is_null())) r.own[c] = read_curve(own[c], "reciprocity.exposures.own");
      r.parallel = e.at("parallel").as_bool();
      p.luminance.exposures.push_back(r);
    }

    const json::Value& col = o.at("colour");
    p.transform = col.at("transform").as_string("colour.transform");
    p.colour.id = col.at("model").as_string("colour.model");
    if (p.colour.id != "Guarnera2018-" + p.transform)
      throw Error(ErrorCode::ProfileInvalid, "colour.model must be Guarnera2018-" + p.transform);
    const ModelInfo& info = model_info(p.colour.id);
    const auto& rows = col.at("coefficients").as_array("colour.coefficients");
    if (rows.size() != 3) throw Error(ErrorCode::ProfileInvalid, "colour.coefficients must have 3 rows");
    p.colour.coefficients.resize(3, info.n_terms);
    for (int c = 0; c < 3; ++c) {
      const auto r = rows[c].as_numbers("colour.coefficients");
      if (static_cast<int>(r.size()) != info.n_terms)
        throw Error(ErrorCode::ProfileInvalid, "colour.coefficients rows need " + std::to_string(info.n_terms) + " numbers");
      for (int j = 0; j < info.n_terms; ++j) {
        if (!std::isfinite(r[j])) throw Error(ErrorCode::ProfileInvalid, "non-finite colour coefficient");
        p.colour.coefficients(c, j) = r[j];
      }
    }
    p.colour_stimuli = col.at("stimuli").as_int("colour.stimuli", 0, limits::kMaxJsonInt);
    p.colour_status = fit_status_from_name(col.at("status").as_string("colour.status"));
    p.colour_message = col.at("message").as_string("colour.message");
    p.colour_objective = col.at("objective_value").as_number("colour.objective_value");
    p.fusion = fusion_mode_from_id(o.at("fusion").as_string("fusion"));
    if (const json::Value* tr = o.find("training")) {
      p.training = absolute_training_from_json(*tr, "training");
      p.has_training = true;
    }
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
