// Declarations: the absolute tele-colorimeter (Guarnera, Bianco & Schettini 2018) as
// tristim/absolute/characterise.hpp has it — an AbsoluteRecipe and its frames fitted
// (fitAbsolute -> {recipe, profile JSON text, panels of fig 5, report}), a profile applied to a
// bracketed series (applyAbsolute -> the AbsoluteMaps handle), and the one report
// (tristim/absolute/report.hpp), which crosses as the object its JSON is — the same fields, to the
// bit, that `tristim absolute evaluate --json` prints. The recipe, its stimuli and the summaries
// and the options of applyAbsolute and report() cross by their field lists (tristim/absolute/fields.hpp,
// wasm/types.hpp; an unknown member refused with INVALID_ARGUMENT): the names and forms of
// the JSON, e.g. an exposure as [t, N, ISO] and a region row's rectangle as region: [x, y, w, h].
//
// AbsoluteMaps methods (the handle owns wasm memory: call .delete()): summary(), XYZ() ->
// Float32Array(3·w·h), source() -> Uint8Array(w·h) (dominant exposure, 255: none),
// contributors() -> Int32Array(w·h) (bit e: exposure e served the pixel), tiff() -> Uint8Array
// (the X, Y, Z map as a 32-bit float TIFF, as `tristim absolute apply` writes), readout(x, y,
// window) -> AbsoluteReadout (by its field list, as `tristim absolute apply --points` writes it), report(test stimuli, {white}) -> the report.
#include "raw_handle.hpp"
#include "tristim/absolute/characterise.hpp"
#include "tristim/profile/export.hpp"
#include "types.hpp"

using namespace tristim;
using namespace tristim::wasm;  // Conv, def, guard
using emscripten::val;
using emscripten::value_object;

template <>
struct tristim::wasm::Conv<AbsoluteProfile> {  // the profile's JSON text, both ways
  static val to(const AbsoluteProfile& p) { return val(absolute_profile_to_json(p)); }
  static AbsoluteProfile from(const val& v) { return absolute_profile_from_json(Conv<std::string>::from(v)); }
};
template <>
struct tristim::wasm::Conv<AbsoluteProgress> {  // onProgress(fraction, stage), optional
  static val to(const AbsoluteProgress&) { return val::undefined(); }
  static AbsoluteProgress from(const val& f) {
    if (wasm::absent(f)) return {};
    if (wasm::type_of(f) != "function") wasm::refuse("onProgress: expected a function, got " + wasm::type_of(f));
    return [f](double fraction, const std::string& stage) { f(val(fraction), val(stage)); };
  }
};

namespace {
using Frames = std::vector<const RawImage*>;
AbsoluteMaps apply(val profile, val frames, val options, val progress) {
  return guard([&] {
    return apply_absolute_series(Conv<AbsoluteProfile>::from(profile), Conv<Frames>::from(frames),
                                 Conv<AbsoluteApplyOptions>::from(options), Conv<AbsoluteProgress>::from(progress));
  });
}
val report(const AbsoluteMaps& m, val test, val options) {
  return guard([&] {
    return Conv<AbsoluteReport>::to(absolute_maps_report(m, Conv<std::vector<AbsoluteStimulus>>::from(test),
                                                         Conv<AbsoluteEvaluateOptions>::from(options)));
  });
}
}  // namespace

EMSCRIPTEN_BINDINGS(tristim_absolute) {
  using emscripten::class_;
  using emscripten::optional_override;
  { using S = AbsoluteFrames; value_object<S>("AbsoluteFrames") FIELD(bracket) FIELD(lens_cap) FIELD(flat) FIELD(other_names)
      FIELD(others); }
  { using S = OecfPanel; value_object<S>("OecfPanel") FIELD(exposure) FIELD(label) FIELD(factor) FIELD(parallel)
      FIELD(samples) FIELD(scale_ratio) FIELD(slope_difference) FIELD(rms_relative) FIELD(point_Y) FIELD(point_R)
      FIELD(curve_Y) FIELD(curve_R) FIELD(own_Y); }
  { using S = AbsoluteCharacterisation; value_object<S>("AbsoluteCharacterisation") FIELD(recipe) FIELD(profile) FIELD(panels)
      FIELD(report); }

  using M = const AbsoluteMaps&;
  class_<AbsoluteMaps>("AbsoluteMaps")
      .function("summary", optional_override([](M m) { return guard([&] { return Conv<AbsoluteMapsSummary>::to(absolute_maps_summary(m)); }); }))
      .function("XYZ", optional_override([](M m) { return Conv<std::vector<float>>::to(m.image.XYZ); }))
      .function("source", optional_override([](M m) { return Conv<std::vector<uint8_t>>::to(m.image.luminance.source); }))
      .function("contributors", optional_override([](M m) {
                  const auto& c = m.image.luminance.contributors;
                  return Conv<std::vector<int>>::to(std::vector<int>(c.begin(), c.end())); }))
      .function("tiff", optional_override([](M m) {
                  return guard([&] {
                    return Conv<std::vector<uint8_t>>::to(float_tiff(m.image.XYZ.data(), m.image.luminance.width,
                        m.image.luminance.height, "CIE XYZ, cd/m2 (tristim absolute, Guarnera 2018)")); }); }))
      .function("readout", optional_override([](M m, val x, val y, val window) {
                  return guard([&] {
                    return Conv<AbsoluteReadout>::to(absolute_readout(m, Conv<int>::from(x), Conv<int>::from(y),
                                                                      wasm::absent(window) ? 1 : Conv<int>::from(window)));
                  }); }))
      .function("report", optional_override([](M m) { return report(m, val::undefined(), val::undefined()); }))
      .function("report", optional_override([](M m, val test) { return report(m, test, val::undefined()); }))
      .function("report", optional_override([](M m, val test, val options) { return report(m, test, options); }));

  def<&complete_absolute_recipe>("completeAbsoluteRecipe");
  def<&absolute_recipe_to_json>("absoluteRecipeToJson");
  def<static_cast<AbsoluteRecipe (*)(const std::string&)>(&absolute_recipe_from_json)>("absoluteRecipeFromJson");
  def<&absolute_option_table>("listAbsoluteOptions");
  // The exposure-fusion picker (the page's catalog: fusionModes).
  { using S = FusionModeInfo; value_object<S>("FusionModeInfo") FIELD(id) FIELD(label) FIELD(reference) FIELD(about); }
  def<&fusion_mode_table>("listFusionModes");
  { using S = AbsoluteWhiteRule; value_object<S>("AbsoluteWhiteRule") FIELD(id) FIELD(label) FIELD(reference); }
  def<&absolute_white_rules>("listAbsoluteWhiteRules");
  def<&series_exposures>("checkAbsoluteSeries");
  def<&characterise_absolute>("fitAbsolute");
  emscripten::function("applyAbsolute", &apply);
  emscripten::function("applyAbsolute", optional_override([](val p, val f) { return apply(p, f, val::undefined(), val::undefined()); }));
  emscripten::function("applyAbsolute", optional_override([](val p, val f, val o) { return apply(p, f, o, val::undefined()); }));
  def<&white_Guarnera2018>("whiteGuarnera2018");
  def<&white_equal_energy>("whiteEqualEnergy");
  def<&evaluate_absolute>("evaluateAbsolute");
}
