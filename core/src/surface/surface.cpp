// The surface-correction table and its dispatcher.
#include "tristim/surface/surface.hpp"

#include "tristim/error.hpp"

namespace tristim {

namespace {

SpectralData apply_none(const SpectralData& reflectances, const MethodChoice&) { return reflectances; }

std::vector<SurfaceMethod> build_table() {
  std::vector<SurfaceMethod> t;
  t.push_back({{"none", "None (reflectances as measured)", "", {}}, apply_none});
  return t;
}

}  // namespace

const std::vector<SurfaceMethod>& surface_table() {
  static const std::vector<SurfaceMethod> table = build_table();
  return table;
}

const SurfaceMethod& surface_method(const std::string& id) {
  for (const auto& m : surface_table())
    if (m.info.id == id) return m;
  throw Error(ErrorCode::UnknownId, "unknown surface correction '" + id + "'");
}

SpectralData correct_surface(const MethodChoice& choice, const SpectralData& reflectances) {
  const SurfaceMethod& m = surface_method(choice.method);
  return m.apply(reflectances, complete_choice(m.info, choice));
}

}  // namespace tristim
