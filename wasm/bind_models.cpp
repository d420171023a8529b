// Binding: characterisation models, profiles, exports. Thin: convert, call the core, convert.
//
// Shapes: rgb, xyz are Float64Array(3N) (or arrays of numbers), patch-interleaved
// [R0,G0,B0,R1,...]; ids is a string[] of N patch ids ([] -> "1".."N"). XYZ in the caller's
// units (reflective: Y = 100 for the perfect diffuser; absolute: cd/m² with a white in cd/m²).
// Metrics objects: {dE76, dE94, dE00, dE_xyz, abs_rel_Y: {min, median, mean, p95, max, rms,
// std}, NRMSE: [X, Y, Z], patches: {ids, dE76, dE94, dE00, dL, dC, dH, dE_xyz, rel_Y}} (NaN
// becomes null). Errors are JS Errors with .code (PATCH_MISMATCH, TOO_FEW_PATCHES, ...).
#include <cstring>

#include "boundary.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/io/json.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/profile/profile.hpp"

using namespace emscripten;
using namespace tristim;
using tristim::wasm::doubles_from_js;
using tristim::wasm::float64_array;
using tristim::wasm::guard;

namespace {

val from_json(const json::Value& v) { return val::global("JSON").call<val>("parse", val(v.dump())); }

PatchMatrix patches_from_js(const val& a, const char* what) {
  const std::vector<double> v = doubles_from_js(a);
  if (v.size() % 3 != 0)
    throw Error(ErrorCode::RowLength, std::string(what) + ": length " + std::to_string(v.size()) + " is not a multiple of 3");
  PatchMatrix m(v.size() / 3, 3);
  for (size_t i = 0; i < v.size() / 3; ++i)
    for (int c = 0; c < 3; ++c) m(i, c) = v[3 * i + c];
  return m;
}

val patches_to_js(const PatchMatrix& m) {
  std::vector<double> v(m.rows() * 3);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (int c = 0; c < 3; ++c) v[3 * i + c] = m(i, c);
  return float64_array(v.data(), v.size());
}

std::vector<std::string> ids_from_js(const val& ids, size_t n) {
  std::vector<std::string> out;
  if (!ids.isUndefined() && !ids.isNull()) {
    const size_t len = ids["length"].as<size_t>();
    for (size_t i = 0; i < len; ++i) out.push_back(ids[i].as<std::string>());
  }
  if (out.empty())
    for (size_t i = 0; i < n; ++i) out.push_back(std::to_string(i + 1));
  if (out.size() != n)
    throw Error(ErrorCode::PatchMismatch, std::to_string(out.size()) + " ids for " + std::to_string(n) + " patches");
  for (size_t i = 0; i < out.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (out[i] == out[j]) throw Error(ErrorCode::DuplicateId, "duplicate patch id '" + out[i] + "'");
  return out;
}

bool has(const val& o, const char* key) {
  return !o.isUndefined() && !o.isNull() && !o[key].isUndefined() && !o[key].isNull();
}

Vec3 vec3_from_js(const val& a, const char* what) {
  const auto v = doubles_from_js(a);
  if (v.size() != 3) throw Error(ErrorCode::InvalidArgument, std::string(what) + " must be [X, Y, Z]");
  return Vec3(v[0], v[1], v[2]);
}

struct Parsed {
  std::vector<std::string> ids;
  PatchMatrix rgb, xyz;
  FitOptions options;
  int white_index = -1;
  std::string illuminant;
};

Parsed parse_inputs(const val& rgb_js, const val& xyz_js, const val& ids_js, const val& opt) {
  Parsed p;
  p.rgb = patches_from_js(rgb_js, "rgb");
  p.xyz = patches_from_js(xyz_js, "xyz");
  validate_patches(p.rgb, p.xyz);
  p.ids = ids_from_js(ids_js, static_cast<size_t>(p.rgb.rows()));
  FitOptions& o = p.options;
  if (has(opt, "objective")) o.objective = objective_from_id(opt["objective"].as<std::string>());
  if (has(opt, "white")) o.white = vec3_from_js(opt["white"], "options.white");
  if (has(opt, "illuminant")) p.illuminant = opt["illuminant"].as<std::string>();
  if (has(opt, "weights")) o.weights = doubles_from_js(opt["weights"]);
  if (has(opt, "whitePatch")) {
    const std::string id = opt["whitePatch"].as<std::string>();
    for (size_t i = 0; i < p.ids.size(); ++i)
      if (p.ids[i] == id) p.white_index = static_cast<int>(i);
    if (p.white_index < 0) throw Error(ErrorCode::UnknownId, "whitePatch '" + id + "' is not one of the patch ids");
    o.preserve_white = true;
    o.white_RGB = p.rgb.row(p.white_index).transpose();
    o.white_XYZ = p.xyz.row(p.white_index).transpose();
  }
  if (has(opt, "psm")) {
    const val s = opt["psm"];
    if (has(s, "initialStep")) o.psm.initial_step = s["initialStep"].as<double>();
    if (has(s, "expansion")) o.psm.expansion = s["expansion"].as<double>();
    if (has(s, "contraction")) o.psm.contraction = s["contraction"].as<double>();
    if (has(s, "stepThreshold")) o.psm.step_threshold = s["stepThreshold"].as<double>();
    if (has(s, "maxIterations")) o.psm.max_iterations = s["maxIterations"].as<int>();
  }
  if (has(opt, "de2000")) {
    const val s = opt["de2000"];
    if (has(s, "algorithm")) o.de2000.algorithm = s["algorithm"].as<std::string>();
    if (has(s, "xtolRel")) o.de2000.xtol_rel = s["xtolRel"].as<double>();
    if (has(s, "ftolRel")) o.de2000.ftol_rel = s["ftolRel"].as<double>();
    if (has(s, "maxEvaluations")) o.de2000.max_evaluations = s["maxEvaluations"].as<int>();
    if (has(s, "rms")) o.de2000.rms = s["rms"].as<bool>();
  }
  return p;
}

/// listModels() -> [{id, label, reference, nTerms, terms: string[], linear, exposureInvariant,
/// duplicateOf}] in table order.
val list_models() {
  return guard([] {
    val out = val::array();
    for (const auto& m : model_table()) {
      val o = val::object();
      o.set("id", m.id);
      o.set("label", m.label);
      o.set("reference", m.reference);
      o.set("nTerms", m.n_terms);
      val t = val::array();
      for (const auto& n : m.term_names) t.call<void>("push", val(n));
      o.set("terms", t);
      o.set("linear", m.linear);
      o.set("exposureInvariant", m.exposure_invariant);
      o.set("duplicateOf", m.duplicate_of);
      out.call<void>("push", o);
    }
    return out;
  });
}

/// listObjectives() -> [{id: 'ls'|'psm'|'de2000', label, reference}].
val list_objectives() {
  return guard([] {
    val out = val::array();
    auto add = [&](const char* id, const char* label, const char* ref) {
      val o = val::object();
      o.set("id", std::string(id));
      o.set("label", std::string(label));
      o.set("reference", std::string(ref));
      out.call<void>("push", o);
    };
    add("ls", "Least squares", "pseudo-inverse: Abed 2013 eq (26), Shen 2008 eq (25)");
    add("psm", "Pattern search: median + mean + max of the L1 XYZ error", "Guarnera 2018 eqs (11)-(12), Algorithm 2");
    add("de2000", "Mean CIEDE2000 (NLopt BOBYQA)", "CIEDE2000 under the stated white");
    return out;
  });
}

/// fitModel(rgb, xyz, ids, options) with options {model (required), objective ('ls'), white
/// ([X,Y,Z], default D50 Y=100), illuminant (name for the profile), whitePatch (id to map
/// exactly), weights (N, de2000), loo (true), psm: {initialStep, expansion, contraction,
/// stepThreshold, maxIterations}, de2000: {algorithm ('auto': Levenberg-Marquardt for rms,
/// BOBYQA for the mean; 'lm', 'bobyqa', 'sbplx', ...), xtolRel, ftolRel, maxEvaluations, rms}}
/// -> {profile: JSON string, metrics: {training, loo (or null)}, status, message,
///     conditionNumber, iterations, evaluations, objectiveValue, startObjectiveValue,
///     model, objective, coefficients: Float64Array(3P) row-major, fitted: Float64Array(3N),
///     looXYZ: Float64Array(3N) or null}.
val fit_model(val rgb, val xyz, val ids, val options) {
  return guard([&] {
    if (!has(options, "model")) throw Error(ErrorCode::InvalidArgument, "options.model is required");
    const std::string model = options["model"].as<std::string>();
    Parsed p = parse_inputs(rgb, xyz, ids, options);
    const bool loo = !has(options, "loo") || options["loo"].as<bool>();
    const ModelEvaluation ev = evaluate_model(model, p.rgb, p.xyz, p.options, p.white_index, loo);
    const Profile prof = make_profile(ev, p.options, p.ids, p.rgb, p.xyz,
                                      p.white_index >= 0 ? p.ids[p.white_index] : "", p.illuminant);
    val out = val::object();
    out.set("profile", profile_to_json(prof));
    val metrics = val::object();
    metrics.set("training", from_json(metrics_json(ev.training, p.ids, true)));
    metrics.set("loo", ev.has_loo ? from_json(metrics_json(ev.loo, p.ids, true)) : val::null());
    out.set("metrics", metrics);
    out.set("status", std::string(fit_status_name(ev.fit.status)));
    out.set("message", ev.fit.message);
    out.set("conditionNumber", ev.fit.condition_number);
    out.set("iterations", ev.fit.iterations);
    out.set("evaluations", ev.fit.evaluations);
    out.set("objectiveValue", ev.fit.objective_value);
    out.set("startObjectiveValue", ev.fit.start_objective_value);
    out.set("model", model);
    out.set("objective", std::string(objective_id(ev.fit.objective)));
    const auto& C = ev.fit.model.coefficients;
    std::vector<double> coef(C.size());
    for (Eigen::Index r = 0; r < C.rows(); ++r)
      for (Eigen::Index c = 0; c < C.cols(); ++c) coef[r * C.cols() + c] = C(r, c);
    out.set("coefficients", float64_array(coef.data(), coef.size()));
    out.set("fitted", patches_to_js(ev.fit.fitted));
    out.set("looXYZ", ev.has_loo ? patches_to_js(ev.loo_XYZ) : val::null());
    return out;
  });
}

/// evaluateProfile(profileJson, rgb, xyz, ids) -> {model, objective, white: [X,Y,Z],
/// sameDataAsTraining (digest match), metrics (with per-patch arrays), estimated: Float64Array(3N)}.
val evaluate_profile(std::string profile_json, val rgb, val xyz, val ids) {
  return guard([&] {
    const Profile prof = profile_from_json(profile_json);
    Parsed p = parse_inputs(rgb, xyz, ids, val::undefined());
    const PatchMatrix est = predict(prof.model, p.rgb);
    const Metrics m = evaluate(est, p.xyz, prof.white);
    val out = val::object();
    out.set("model", prof.model.id);
    out.set("objective", std::string(objective_id(prof.objective)));
    val w = val::array();
    for (int c = 0; c < 3; ++c) w.call<void>("push", prof.white[c]);
    out.set("white", w);
    out.set("sameDataAsTraining", training_digest(p.ids, p.rgb, p.xyz) == prof.training_digest);
    out.set("metrics", from_json(metrics_json(m, p.ids, true)));
    out.set("estimated", patches_to_js(est));
    return out;
  });
}

/// compareModels(rgb, xyz, ids, options) with options {objectives: ['ls','psm','de2000'],
/// models: [ids] (default: every non-duplicate model), white, whitePatch, psm, de2000}
/// -> rows sorted by leave-one-out mean CIEDE2000: [{model, objective, nTerms, ok, errorCode,
/// status, message, conditionNumber, seconds, cpuSeconds, train: {dE00, dE_xyz}, loo: {dE00, dE_xyz} | null}].
val compare_models_js(val rgb, val xyz, val ids, val options) {
  return guard([&] {
    Parsed p = parse_inputs(rgb, xyz, ids, options);
    std::vector<Objective> objectives;
    if (has(options, "objectives")) {
      const size_t n = options["objectives"]["length"].as<size_t>();
      for (size_t i = 0; i < n; ++i) objectives.push_back(objective_from_id(options["objectives"][i].as<std::string>()));
    }
    std::vector<std::string> models;
    if (has(options, "models")) {
      const size_t n = options["models"]["length"].as<size_t>();
      for (size_t i = 0; i < n; ++i) models.push_back(model_info(options["models"][i].as<std::string>()).id);
    }
    const auto rows = compare_models(p.rgb, p.xyz, p.options, models, objectives, p.white_index);
    val out = val::array();
    for (const auto& r : rows) {
      val o = val::object();
      o.set("model", r.model_id);
      o.set("objective", std::string(objective_id(r.objective)));
      o.set("nTerms", r.n_terms);
      o.set("ok", r.ok);
      o.set("errorCode", r.error_code);
      o.set("status", std::string(r.ok ? fit_status_name(r.status) : "error"));
      o.set("message", r.message);
      o.set("conditionNumber", r.condition_number);
      o.set("seconds", r.seconds);
      o.set("cpuSeconds", r.cpu_seconds);
      if (r.ok) {
        val t = val::object();
        t.set("dE00", from_json(summary_json(r.train_dE00)));
        t.set("dE_xyz", from_json(summary_json(r.train_dE_xyz)));
        o.set("train", t);
      } else {
        o.set("train", val::null());
      }
      if (r.has_loo) {
        val l = val::object();
        l.set("dE00", from_json(summary_json(r.loo_dE00)));
        l.set("dE_xyz", from_json(summary_json(r.loo_dE_xyz)));
        o.set("loo", l);
      } else {
        o.set("loo", val::null());
      }
      out.call<void>("push", o);
    }
    return out;
  });
}

/// applyProfileToImage(profileJson, rgb Float32Array(3·width·height) linear camera RGB,
/// width, height) -> Float32Array(3·width·height) XYZ (a copy; safe to keep or transfer).
val apply_profile_to_image(std::string profile_json, val rgb, int width, int height) {
  return guard([&] {
    const Profile prof = profile_from_json(profile_json);
    if (width <= 0 || height <= 0) throw Error(ErrorCode::InvalidArgument, "width and height must be positive");
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
    if (rgb["length"].as<size_t>() != n)
      throw Error(ErrorCode::RowLength, "rgb has " + std::to_string(rgb["length"].as<size_t>()) +
                                            " values, width × height × 3 = " + std::to_string(n));
    std::vector<float> in(n);
    val(typed_memory_view(n, in.data())).call<void>("set", rgb);
    std::vector<float> out(n);
    apply_to_image(prof.model, in.data(), n / 3, out.data());
    return tristim::wasm::float32_array(out.data(), n);
  });
}

/// applyProfile(profileJson, raw: RawImage from decodeRaw) -> {width, height, XYZ: Float32Array
/// (3·width·height)}: the profile applied to the RAW's linear camera RGB, with the dark/flat
/// calibration set on it (via raw.linearRGB(), so the data cross the boundary once more than
/// needed; the RawImage handle type is private to bind_raw.cpp).
val apply_profile_raw(std::string profile_json, val raw) {
  return guard([&] {
    const Profile prof = profile_from_json(profile_json);
    if (raw.isUndefined() || raw.isNull() || raw["linearRGB"].isUndefined())
      throw Error(ErrorCode::InvalidArgument, "applyProfile needs a RawImage from decodeRaw");
    const int width = raw.call<int>("width"), height = raw.call<int>("height");
    const val rgb = raw.call<val>("linearRGB");
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
    if (rgb["length"].as<size_t>() != n) throw Error(ErrorCode::Internal, "RawImage size mismatch");
    std::vector<float> in(n);
    val(typed_memory_view(n, in.data())).call<void>("set", rgb);
    std::vector<float> out(n);
    apply_to_image(prof.model, in.data(), n / 3, out.data());
    val res = val::object();
    res.set("width", width);
    res.set("height", height);
    res.set("XYZ", tristim::wasm::float32_array(out.data(), n));
    return res;
  });
}

/// exportIcc(profileJson, options?) with options {rgbScale, gridPoints (33), version (4.3|2.4),
/// description} -> Uint8Array (ICC input profile: matrix/shaper for 3×3 models, AToB0 LUT else).
val export_icc_js(std::string profile_json, val options) {
  return guard([&] {
    const Profile prof = profile_from_json(profile_json);
    IccOptions o;
    if (has(options, "rgbScale")) o.rgb_scale = options["rgbScale"].as<double>();
    if (has(options, "gridPoints")) o.grid_points = options["gridPoints"].as<int>();
    if (has(options, "version")) o.version = options["version"].as<double>();
    if (has(options, "description")) o.description = options["description"].as<std::string>();
    const std::vector<uint8_t> icc = export_icc(prof, o);
    return val::global("Uint8Array").new_(typed_memory_view(icc.size(), icc.data()));
  });
}

/// exportCube(profileJson, size (2..256), rgbScale? (0 = training max)) -> .cube text.
std::string export_cube_js(std::string profile_json, int size, double rgb_scale) {
  return guard([&] { return export_cube(profile_from_json(profile_json), size, rgb_scale); });
}

/// exportPatchCsv(profileJson, rgb, xyz, ids) -> per-patch CSV text (estimates and errors).
std::string export_patch_csv(std::string profile_json, val rgb, val xyz, val ids) {
  return guard([&] {
    const Profile prof = profile_from_json(profile_json);
    Parsed p = parse_inputs(rgb, xyz, ids, val::undefined());
    return patch_csv(p.ids, p.rgb, p.xyz, predict(prof.model, p.rgb), prof.white);
  });
}

val export_icc_1(std::string profile_json) { return export_icc_js(profile_json, val::undefined()); }
std::string export_cube_2(std::string profile_json, int size) { return export_cube_js(profile_json, size, 0); }

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_models) {
  function("listModels", &list_models);
  function("listObjectives", &list_objectives);
  function("fitModel", &fit_model);
  function("evaluateProfile", &evaluate_profile);
  function("compareModels", &compare_models_js);
  function("applyProfileToImage", &apply_profile_to_image);
  function("applyProfile", &apply_profile_raw);
  function("exportIcc", &export_icc_js);
  function("exportIcc", &export_icc_1);
  function("exportCube", &export_cube_js);
  function("exportCube", &export_cube_2);
  function("exportPatchCsv", &export_patch_csv);
}
