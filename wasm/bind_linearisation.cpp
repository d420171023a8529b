// Binding: the linearisation table, fitted curves and spectral characterisation (issue 11).
// Thin: convert, call the core, convert.
//
//   listLinearisations() -> [{id, label, reference, needs, options: [{name, type, label,
//       default, min, max, choices, description}]}]
//   fitLinearisation(choice, data) -> {linearisation (the core's JSON: re-usable as `fitted`),
//       linear: Float64Array(3N), rSquared: [R, G, B] (null when none), greys, greyReason,
//       fitted, monotonic, message, curves: [{channel, x, linear, greyBased?}] (101 samples)}
//     choice: "id" | "id:name=value,..." | {method, parameters, settings}
//     data: {rgb: Float64Array(3N), ids: string[], xyz?: Float64Array(3N), white?: [X, Y, Z],
//            reflectances?: chart id | {wavelengths, spectra: Float64Array(N*W) patch-major, ids},
//            basis?: same shape as reflectances (basis=user), fullScale?: number}
//   applyLinearisation(fitted, rgb) -> Float64Array(3N)
//   fitSpectral(fitted, data, illuminant = "D65", observer = "1931") -> {model (JSON), wavelengths,
//       ids, estimates: Float64Array(N*W) patch-major, rms: Float64Array(N), dE00: Float64Array(N),
//       summary: {rmsMean, rmsMax, dE00Mean, dE00Max}}
// Errors are JS Errors with .code (TOO_FEW_PATCHES, MISSING_COLUMN, WAVELENGTH_MISMATCH, ...).
#include "boundary.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/io/json.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/linearisation/spectral.hpp"

using namespace emscripten;
using namespace tristim;
using tristim::wasm::doubles_from_js;
using tristim::wasm::float64_array;
using tristim::wasm::guard;

namespace {

val js_of(const json::Value& v) { return val::global("JSON").call<val>("parse", val(v.dump())); }
json::Value json_of(const val& v) { return json::parse(val::global("JSON").call<std::string>("stringify", v)); }
bool present(const val& o, const char* key) {
  return !o.isUndefined() && !o.isNull() && !o[key].isUndefined() && !o[key].isNull();
}

PatchMatrix patches(const val& a, const char* what) {
  const std::vector<double> v = doubles_from_js(a);
  if (v.size() % 3 != 0)
    throw Error(ErrorCode::RowLength, std::string(what) + ": length " + std::to_string(v.size()) + " is not a multiple of 3");
  PatchMatrix m(static_cast<Eigen::Index>(v.size() / 3), 3);
  for (size_t i = 0; i < v.size() / 3; ++i)
    for (int c = 0; c < 3; ++c) m(static_cast<Eigen::Index>(i), c) = v[3 * i + static_cast<size_t>(c)];
  return m;
}

val patches_js(const PatchMatrix& m) {
  std::vector<double> v(static_cast<size_t>(m.rows()) * 3);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (int c = 0; c < 3; ++c) v[3 * static_cast<size_t>(i) + static_cast<size_t>(c)] = m(i, c);
  return float64_array(v.data(), v.size());
}

std::vector<std::string> strings_of(const val& a) {
  std::vector<std::string> out;
  if (a.isUndefined() || a.isNull()) return out;
  const size_t n = a["length"].as<size_t>();
  for (size_t i = 0; i < n; ++i) out.push_back(a[i].as<std::string>());
  return out;
}

val strings_js(const std::vector<std::string>& v) {
  val a = val::array();
  for (const auto& s : v) a.call<void>("push", val(s));
  return a;
}

/// A chart id, or {wavelengths, spectra (patch-major), ids}.
SpectralData reflectances_of(const val& r) {
  if (r.isString()) {
    SpectralData s = chart_reflectances(r.as<std::string>());
    for (auto& n : s.names) n = normalise_patch_id(n);
    return s;
  }
  SpectralData s;
  s.wavelengths = doubles_from_js(r["wavelengths"]);
  s.names = strings_of(r["ids"]);
  const std::vector<double> v = doubles_from_js(r["spectra"]);
  const size_t W = s.wavelengths.size();
  if (W == 0 || v.size() != W * s.names.size())
    throw Error(ErrorCode::RowLength, "reflectances: spectra must hold ids.length × wavelengths.length values");
  for (size_t k = 0; k < s.names.size(); ++k) s.values.emplace_back(v.begin() + static_cast<long>(k * W), v.begin() + static_cast<long>((k + 1) * W));
  for (auto& n : s.names) n = normalise_patch_id(n);
  reflectance_to_fraction(s);
  return s;
}

MethodChoice choice_of(const val& c) {
  if (c.isString()) return parse_choice(c.as<std::string>());
  MethodChoice m;
  m.method = c["method"].as<std::string>();
  const json::Value j = json_of(c);
  if (const json::Value* p = j.find("parameters"))
    for (const auto& [k, v] : p->members()) m.parameters[k] = v.as_number(k);
  if (const json::Value* s = j.find("settings"))
    for (const auto& [k, v] : s->members()) m.settings[k] = v.as_string(k);
  return m;
}

LinearisationData data_of(const val& d) {
  LinearisationData out;
  out.camera_RGB = patches(d["rgb"], "rgb");
  out.ids = strings_of(d["ids"]);
  for (auto& id : out.ids) id = normalise_patch_id(id);
  if (present(d, "xyz")) out.reference_XYZ = patches(d["xyz"], "xyz");
  if (present(d, "white")) {
    const auto w = doubles_from_js(d["white"]);
    if (w.size() != 3) throw Error(ErrorCode::InvalidArgument, "white must be [X, Y, Z]");
    out.white = Vec3(w[0], w[1], w[2]);
  }
  if (present(d, "reflectances")) out.reflectances = reflectances_of(d["reflectances"]);
  if (present(d, "basis")) out.basis_reflectances = reflectances_of(d["basis"]);
  if (present(d, "fullScale")) out.full_scale = d["fullScale"].as<double>();
  return out;
}

val list_linearisations() {
  return guard([] {
    val a = val::array();
    for (const auto& m : linearisation_table()) {
      val o = val::object();
      o.set("id", m.info.id);
      o.set("label", m.info.label);
      o.set("reference", m.info.reference);
      o.set("needs", m.needs);
      val opts = val::array();
      for (const auto& s : m.info.options) {
        val p = val::object();
        p.set("name", s.name);
        p.set("type", s.type);
        p.set("label", s.label);
        if (s.type == "choice" || s.type == "text") p.set("default", s.default_text);
        else p.set("default", s.default_number);
        p.set("min", s.min);
        p.set("max", s.max);
        p.set("choices", strings_js(s.choices));
        p.set("description", s.description);
        opts.call<void>("push", p);
      }
      o.set("options", opts);
      a.call<void>("push", o);
    }
    return a;
  });
}

val fit_linearisation_js(const val& choice, const val& data) {
  return guard([&] {
    const LinearisationData d = data_of(data);
    const Linearisation l = fit_linearisation(choice_of(choice), d);
    val o = val::object();
    o.set("linearisation", js_of(linearisation_json(l)));
    o.set("linear", patches_js(linearise(l, d.camera_RGB)));
    val r2 = val::array();
    for (int c = 0; c < 3; ++c) r2.call<void>("push", std::isfinite(l.r_squared[c]) ? val(l.r_squared[c]) : val::null());
    o.set("rSquared", r2);
    o.set("greys", strings_js(l.greys));
    o.set("greyReason", l.grey_reason);
    o.set("fitted", strings_js(l.fitted));
    o.set("monotonic", l.monotonic);
    o.set("message", l.message);
    val curves = val::array();
    for (int c = 0; c < 3; ++c) {
      const CurveSamples s = sample_curve(l, c, 101);
      val cv = val::object();
      cv.set("channel", std::string(1, "RGB"[c]));
      cv.set("x", float64_array(s.x.data(), s.x.size()));
      cv.set("linear", float64_array(s.linear.data(), s.linear.size()));
      if (!s.grey_based.empty()) cv.set("greyBased", float64_array(s.grey_based.data(), s.grey_based.size()));
      curves.call<void>("push", cv);
    }
    o.set("curves", curves);
    return o;
  });
}

val apply_linearisation_js(const val& fitted, const val& rgb) {
  return guard([&] { return patches_js(linearise(linearisation_from_json(json_of(fitted)), patches(rgb, "rgb"))); });
}

val fit_spectral_js(const val& fitted, const val& data, const val& illuminant, const val& observer) {
  return guard([&] {
    const LinearisationData d = data_of(data);
    if (d.reflectances.size() == 0) throw Error(ErrorCode::MissingColumn, "fitSpectral needs data.reflectances");
    const Linearisation l = linearisation_from_json(json_of(fitted));
    const SpectralModel m = fit_spectral(l, d.ids, d.camera_RGB, d.reflectances);
    const SpectralData ill = illuminant_spd(illuminant.isString() ? illuminant.as<std::string>() : "D65");
    const Observer obs = parse_observer(observer.isString() ? observer.as<std::string>() : "1931");
    const SpectralEvaluation e = evaluate_spectral(m, d.ids, d.camera_RGB, d.reflectances, ill, obs);
    const SpectralData est = estimate_reflectances(m, d.ids, d.camera_RGB);
    std::vector<double> flat;
    for (const auto& v : est.values) flat.insert(flat.end(), v.begin(), v.end());
    val o = val::object();
    o.set("model", js_of(spectral_model_json(m)));
    o.set("wavelengths", float64_array(m.wavelengths.data(), m.wavelengths.size()));
    o.set("ids", strings_js(d.ids));
    o.set("estimates", float64_array(flat.data(), flat.size()));
    o.set("rms", float64_array(e.rms.data(), e.rms.size()));
    o.set("dE00", float64_array(e.dE00.data(), e.dE00.size()));
    val s = val::object();
    s.set("rmsMean", e.rms_summary.mean);
    s.set("rmsMax", e.rms_summary.max);
    s.set("dE00Mean", e.dE00_summary.mean);
    s.set("dE00Max", e.dE00_summary.max);
    o.set("summary", s);
    return o;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_linearisation) {
  function("listLinearisations", &list_linearisations);
  function("fitLinearisation", &fit_linearisation_js);
  function("applyLinearisation", &apply_linearisation_js);
  function("fitSpectral", &fit_spectral_js);
}
