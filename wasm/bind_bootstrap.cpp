// Declarations: the bootstrap of a fit in steps (tristim/evaluation/bootstrap.hpp), for the page's
// "Uncertainty (bootstrap)": bootstrapRecipe(recipe, ids, linear_RGB, reference_XYZ, loo_dE00,
// settings, pixels) -> a BootstrapRun handle (owns wasm memory: call .delete()); pixels: null, or
// {std: 3N, n: N} of the sampled RAW's patches in the order of ids (resampled too under the identity
// linearisation). The handle: step(n) -> resamples done, done(), total(), result() -> the object
// `tristim fit --bootstrap`'s "bootstrap" JSON is,
// plus "train_ci" / "loo_ci" (the "ci" of the two means), and profileWith(profile JSON text) ->
// the profile text with the bootstrap added. bootstrapOptions(): the settings' table (ranges,
// defaults) the page's form is built from.
#include "tristim/evaluation/bootstrap.hpp"
#include "tristim/profile/recipe.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::class_;
using emscripten::optional_override;
using emscripten::val;
using wasm::Conv;
using wasm::def;
using wasm::guard;

namespace {
val parsed(const json::Value& v) { return val::global("JSON").call<val>("parse", val(v.dump())); }
}  // namespace

EMSCRIPTEN_BINDINGS(tristim_bootstrap) {
  class_<BootstrapRun>("BootstrapRun")
      .function("step", optional_override([](BootstrapRun& r, val n) { return guard([&] { return r.step(Conv<int>::from(n)); }); }))
      .function("done", &BootstrapRun::done)
      .function("total", &BootstrapRun::total)
      .function("result", optional_override([](const BootstrapRun& r) {
                  return guard([&] {
                    const BootstrapResult b = r.result();
                    json::Value o = bootstrap_json(b, r.model());
                    o.set("train_ci", interval_json(b.train_dE00_mean));
                    if (b.has_loo) o.set("loo_ci", interval_json(b.loo_dE00_mean));
                    return parsed(o);
                  }); }))
      .function("profileWith", optional_override([](const BootstrapRun& r, val profile) {
                  return guard([&] { return profile_with_bootstrap(Conv<std::string>::from(profile), r); }); }));
  emscripten::function("bootstrapRecipe", optional_override([](val recipe, val ids, val rgb, val xyz, val loo, val settings, val pixels) {
                         return guard([&] {
                           const bool px = !wasm::absent(pixels);
                           return bootstrap_recipe(Conv<Recipe>::from(recipe), Conv<std::vector<std::string>>::from(ids),
                                                   Conv<PatchMatrix>::from(rgb), Conv<PatchMatrix>::from(xyz),
                                                   wasm::absent(loo) ? std::vector<double>{} : Conv<std::vector<double>>::from(loo),
                                                   Conv<MethodChoice>::from(settings),
                                                   px ? Conv<PatchMatrix>::from(pixels["std"]) : PatchMatrix(),
                                                   px ? Conv<std::vector<double>>::from(pixels["n"]) : std::vector<double>{});
                         }); }));
  def<&bootstrap_option_table>("bootstrapOptions");
}
