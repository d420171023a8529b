// Binding: colorimetry and reference data (charts, illuminants, cameras, reference files, ΔE,
// spectral locus, virtual camera). Thin: convert types, call the core.
//
// Conventions: N = number of patches; per-patch triplets are flat Float64Array(3N), patch-major
// ([X0, Y0, Z0, X1, ...]). XYZ on the Y = 100 scale (perfect diffuser). `observer` is "1931" or
// "1964" (a number works too). Errors are JS Errors with .code (UNKNOWN_ID, NON_FINITE, ...).
#include <string>
#include <vector>

#include "boundary.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "tristim/colorimetry/spectra.hpp"

using namespace emscripten;
using tristim::wasm::guard;

namespace {

using tristim::Vec3;

tristim::Observer observer_from(const val& v) {
  if (v.isUndefined() || v.isNull()) return tristim::Observer::CIE1931_2;
  if (v.isNumber()) return tristim::parse_observer(std::to_string(static_cast<long>(v.as<double>())));
  return tristim::parse_observer(v.as<std::string>());
}

std::string string_from(const val& v, const char* fallback) {
  if (v.isUndefined() || v.isNull()) return fallback;
  return v.as<std::string>();
}

val triplets(const std::vector<Vec3>& v) {
  std::vector<double> flat;
  flat.reserve(3 * v.size());
  for (const auto& x : v) flat.insert(flat.end(), {x[0], x[1], x[2]});
  return tristim::wasm::float64_array(flat.data(), flat.size());
}

std::vector<Vec3> triplets_from(const val& a, const char* what) {
  const auto d = tristim::wasm::doubles_from_js(a);
  if (d.size() % 3 != 0)
    throw tristim::Error(tristim::ErrorCode::InvalidArgument,
                         std::string(what) + ": length " + std::to_string(d.size()) + " is not a multiple of 3");
  std::vector<Vec3> out;
  for (size_t i = 0; i < d.size(); i += 3) out.emplace_back(d[i], d[i + 1], d[i + 2]);
  return out;
}

val strings(const std::vector<std::string>& v) {
  val out = val::array();
  for (const auto& s : v) out.call<void>("push", val(s));
  return out;
}

std::vector<std::string> strings_from(const val& a) {
  std::vector<std::string> out;
  const size_t n = a["length"].as<size_t>();
  for (size_t i = 0; i < n; ++i) out.push_back(a[i].as<std::string>());
  return out;
}

val reference_out(const tristim::ReferenceChart& r, const std::string& format) {
  val o = val::object();
  o.set("chartId", r.chart_id);
  o.set("illuminant", r.illuminant_id);
  o.set("observer", std::string(tristim::observer_name(r.observer)));
  o.set("format", format);
  o.set("ids", strings(r.ids));
  o.set("XYZ", triplets(r.XYZ));
  o.set("Lab", triplets(r.Lab));
  o.set("sRGB", triplets(r.sRGB));
  val white = val::array();
  for (int k = 0; k < 3; ++k) white.call<void>("push", r.white[k]);
  o.set("white", white);
  return o;
}

/// listCharts() -> [{id, name, patches, rows, columns, source}]
val list_charts() {
  return guard([] {
    val out = val::array();
    for (const auto& c : tristim::list_charts()) {
      val o = val::object();
      o.set("id", c.id);
      o.set("name", c.name);
      o.set("patches", c.patches);
      o.set("rows", c.rows);
      o.set("columns", c.columns);
      o.set("source", c.source);
      out.call<void>("push", o);
    }
    return out;
  });
}

/// listIlluminants() -> [{id, name}] ("D<CCT>" ids such as "D4500" are accepted too)
val list_illuminants() {
  return guard([] {
    val out = val::array();
    for (const auto& id : tristim::illuminant_ids()) {
      val o = val::object();
      o.set("id", id);
      o.set("name", id == "F2" ? "F2 (cool white fluorescent)" : id == "F11" ? "F11 (TL84-type fluorescent)"
                    : id == "A" ? "A (tungsten, 2856 K)" : id == "E" ? "E (equal energy)" : "CIE " + id);
      out.call<void>("push", o);
    }
    return out;
  });
}

/// listCameras() -> [{id, name}] (id as accepted by simulateCamera, e.g. "Canon_EOS_5D_Mark_II")
val list_cameras() {
  return guard([] {
    val out = val::array();
    for (const auto& id : tristim::camera_names()) {
      std::string name = id;
      for (auto& c : name)
        if (c == '_') c = ' ';
      val o = val::object();
      o.set("id", id);
      o.set("name", name);
      out.call<void>("push", o);
    }
    return out;
  });
}

/// referenceChart(chartId, illuminantId = "D65", observer = "1931")
///   -> {ids: string[N], XYZ: Float64Array(3N), Lab: Float64Array(3N), sRGB: Float64Array(3N),
///       white: [X, Y, Z], chartId, illuminant, observer, format: "builtin"}
/// Lab relative to `white` (the illuminant's white, Y = 100); sRGB display-encoded 0..1 after
/// Bradford adaptation to D65.
val reference_chart(const std::string& chart_id, const val& illuminant, const val& observer) {
  return guard([&] {
    const auto r = tristim::reference_chart(chart_id, string_from(illuminant, "D65"), observer_from(observer));
    return reference_out(r, "builtin");
  });
}

/// parseReferenceFile(text, fileName, illuminantId = "D65", observer = "1931") -> same shape as
/// referenceChart, with chartId = fileName and format "csv" | "csv-spectral" | "cgats".
/// Spectral files are integrated under the illuminant; XYZ/Lab tables are used as given (a missing
/// Lab is computed against the illuminant's white, a missing XYZ from Lab with that white).
/// Errors: EMPTY_FILE, PARSE_ERROR, MISSING_COLUMN, NON_NUMERIC, NON_FINITE, NON_MONOTONIC,
/// DUPLICATE_ID, ROW_LENGTH (message names the line), UNKNOWN_ID (illuminant/observer).
val parse_reference_file(const std::string& text, const std::string& file_name, const val& illuminant,
                         const val& observer) {
  return guard([&] {
    const tristim::PatchTable t = tristim::read_patch_file(text, file_name);
    auto r = tristim::reference_from_table(t, tristim::illuminant_spd(string_from(illuminant, "D65")), observer_from(observer));
    r.chart_id = file_name;
    return reference_out(r, t.format);
  });
}

/// parsePatchFile(text, fileName) -> {format, ids, XYZ?, Lab?, RGB?: Float64Array(3N),
///   wavelengths?: Float64Array(W), spectra?: Float64Array(N*W) patch-major} — whatever the file has
/// (e.g. camera RGB measurements to pair with a reference). Errors as parseReferenceFile.
val parse_patch_file(const std::string& text, const std::string& file_name) {
  return guard([&] {
    const tristim::PatchTable t = tristim::read_patch_file(text, file_name);
    val o = val::object();
    o.set("format", t.format);
    o.set("ids", strings(t.ids));
    if (t.has_XYZ) o.set("XYZ", triplets(t.XYZ));
    if (t.has_Lab) o.set("Lab", triplets(t.Lab));
    if (t.has_RGB) o.set("RGB", triplets(t.RGB));
    if (t.has_spectra) {
      o.set("wavelengths", tristim::wasm::float64_array(t.spectra.wavelengths.data(), t.spectra.wavelengths.size()));
      std::vector<double> flat;
      for (const auto& c : t.spectra.values) flat.insert(flat.end(), c.begin(), c.end());
      o.set("spectra", tristim::wasm::float64_array(flat.data(), flat.size()));
    }
    return o;
  });
}

/// pairById(referenceIds, referenceXYZ: Float64Array(3N), measuredIds, measuredRGB: Float64Array(3M))
///   -> {ids, reference: Float64Array(3K), measured: Float64Array(3K), missingInMeasured: string[],
///       missingInReference: string[]} in the reference's order; ids normalised ("A01" = "A1").
/// PATCH_MISMATCH if no id is shared.
val pair_by_id(const val& ref_ids, const val& ref, const val& meas_ids, const val& meas) {
  return guard([&] {
    const auto p = tristim::pair_by_id(strings_from(ref_ids), triplets_from(ref, "referenceXYZ"), strings_from(meas_ids),
                                       triplets_from(meas, "measuredRGB"));
    val o = val::object();
    o.set("ids", strings(p.ids));
    o.set("reference", triplets(p.reference));
    o.set("measured", triplets(p.measured));
    o.set("missingInMeasured", strings(p.missing_in_measured));
    o.set("missingInReference", strings(p.missing_in_reference));
    return o;
  });
}

/// spectralLocus(observer = "1931") -> {wavelengths, x, y: Float64Array(471)} (360-830 nm, 1 nm)
val spectral_locus(const val& observer) {
  return guard([&] {
    const auto l = tristim::spectral_locus(observer_from(observer));
    val o = val::object();
    o.set("wavelengths", tristim::wasm::float64_array(l.wavelengths.data(), l.wavelengths.size()));
    o.set("x", tristim::wasm::float64_array(l.x.data(), l.x.size()));
    o.set("y", tristim::wasm::float64_array(l.y.data(), l.y.size()));
    return o;
  });
}

/// deltaE(method, Lab1: Float64Array(3N), Lab2: Float64Array(3N)) -> Float64Array(N)
/// method: "CIE2000" | "CIE1994" | "CIE1976" (Lab1 is the reference for CIE1994).
val delta_E(const std::string& method, const val& lab1, const val& lab2) {
  return guard([&] {
    const auto a = triplets_from(lab1, "Lab1"), b = triplets_from(lab2, "Lab2");
    if (a.size() != b.size())
      throw tristim::Error(tristim::ErrorCode::InvalidArgument, "Lab1 and Lab2 differ in length");
    if (method != "CIE2000" && method != "CIE1994" && method != "CIE1976")
      throw tristim::Error(tristim::ErrorCode::UnknownId, "unknown ΔE method '" + method + "' (CIE2000, CIE1994, CIE1976)");
    std::vector<double> out(a.size());
    for (size_t i = 0; i < a.size(); ++i)
      out[i] = method == "CIE2000"   ? tristim::delta_E_CIE2000(a[i], b[i])
               : method == "CIE1994" ? tristim::delta_E_CIE1994(a[i], b[i])
                                     : tristim::delta_E_CIE1976(a[i], b[i]);
    return tristim::wasm::float64_array(out.data(), out.size());
  });
}

/// XYZToLab(xyz Float64Array(3N), white [X,Y,Z]) -> Float64Array(3N) L*a*b* (CIE 15) relative
/// to white (same scale as xyz).
val XYZ_to_Lab_js(const val& xyz, const val& white) {
  return guard([&] {
    const auto w = triplets_from(white, "white");
    if (w.size() != 1) throw tristim::Error(tristim::ErrorCode::InvalidArgument, "white must be [X, Y, Z]");
    std::vector<Vec3> out;
    for (const auto& v : triplets_from(xyz, "XYZ")) out.push_back(tristim::XYZ_to_Lab(v, w[0]));
    return triplets(out);
  });
}

/// XYZToDisplaySRGB(xyz Float64Array(3N), white [X,Y,Z]) -> Float64Array(3N) sRGB 0..1 for
/// display: Bradford from white to D65, sRGB encoded and clipped (never used for measurement).
val XYZ_to_display_sRGB_js(const val& xyz, const val& white) {
  return guard([&] {
    const auto w = triplets_from(white, "white");
    if (w.size() != 1) throw tristim::Error(tristim::ErrorCode::InvalidArgument, "white must be [X, Y, Z]");
    std::vector<Vec3> out;
    for (const auto& v : triplets_from(xyz, "XYZ")) out.push_back(tristim::display_sRGB(v, w[0]));
    return triplets(out);
  });
}

/// displayMatrix(white [X,Y,Z]) -> Float64Array(9), row-major: XYZ -> linear sRGB with white ->
/// (1,1,1) (Bradford to D65); for rendering whole images in the worker.
val display_matrix_js(const val& white) {
  return guard([&] {
    const auto w = triplets_from(white, "white");
    if (w.size() != 1) throw tristim::Error(tristim::ErrorCode::InvalidArgument, "white must be [X, Y, Z]");
    const tristim::Mat3 M = tristim::display_matrix(w[0]);
    double m[9];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[3 * r + c] = M(r, c);
    return tristim::wasm::float64_array(m, 9);
  });
}

/// simulateCamera(cameraId, chartId, illuminantId = "D65", options = {}) -> {ids, RGB: Float64Array(3N)}
/// options: {whiteLevel = 1, noise = 0, seed = 1, oecfGamma, oecfScale (both set -> Shen & Xin 2008
/// eq 29), clipMax = 0, quantise = false}. Same numbers as `tristim simulate`.
val simulate_camera(const std::string& camera, const std::string& chart_id, const val& illuminant, const val& options) {
  return guard([&] {
    tristim::SimulationOptions o;
    auto num = [&](const char* key, double fallback) {
      if (options.isUndefined() || options.isNull()) return fallback;
      const val v = options[key];
      return v.isUndefined() || v.isNull() ? fallback : v.as<double>();
    };
    o.white_level = num("whiteLevel", 1.0);
    o.noise_sigma = num("noise", 0.0);
    o.seed = static_cast<uint64_t>(num("seed", 1.0));
    const double g = num("oecfGamma", 0), l = num("oecfScale", 0);
    if (g > 0 || l > 0) {
      o.oecf = true;
      o.oecf_gamma = g > 0 ? g : 1.8;
      o.oecf_scale = l > 0 ? l : 22;
    }
    o.clip_max = num("clipMax", 0.0);
    o.quantise = num("quantise", 0.0) != 0.0;
    const auto refl = tristim::chart_reflectances(chart_id);
    const auto rgb = tristim::simulate_camera_RGB(tristim::camera_ssf(camera), refl,
                                                  tristim::illuminant_spd(string_from(illuminant, "D65")), o);
    val out = val::object();
    out.set("ids", strings(refl.names));
    out.set("RGB", triplets(rgb));
    return out;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_colorimetry) {
  function("listCharts", &list_charts);
  function("listIlluminants", &list_illuminants);
  function("listCameras", &list_cameras);
  function("referenceChart", &reference_chart);
  function("parseReferenceFile", &parse_reference_file);
  function("parsePatchFile", &parse_patch_file);
  function("pairById", &pair_by_id);
  function("spectralLocus", &spectral_locus);
  function("deltaE", &delta_E);
  function("simulateCamera", &simulate_camera);
  function("XYZToLab", &XYZ_to_Lab_js);
  function("XYZToDisplaySRGB", &XYZ_to_display_sRGB_js);
  function("displayMatrix", &display_matrix_js);
}
