// Spectral model JSON (linearisation/spectral.hpp: SpectralModel's field list, with the
// Linearisation it embeds): what `tristim spectral apply model.json` reads. A model it accepts
// writes a text that reads again to the same text, and estimates reflectances of one patch.
#include "fuzz_support.hpp"
#include "tristim/io/json.hpp"
#include "tristim/linearisation/spectral.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::SpectralModel m = tristim::fuzz::round_trip(
      input, [](const std::string& text) { return tristim::spectral_model_from_json(tristim::json::parse(text)); },
      [](const tristim::SpectralModel& model) { return tristim::spectral_model_json(model).dump(2); });
  tristim::estimate_reflectances(m, {"A1"}, tristim::PatchMatrix::Constant(1, 3, 0.5 * m.linearisation.full_scale));
})
