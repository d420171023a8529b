// The absolute tele-colorimeter (Guarnera 2018 sections 3.1-3.2) fitted from what a user has:
// decoded frames and training stimuli. The glue between them — n and σ from averaged lens-cap
// frames, S measured from the frames (LibRaw's level without a pile-up) or given, the areas
// A_R, A_G, A_B from sensitivities, f(r) from a flat field (eq 7), the training regions sampled,
// one camera for every frame — in one place for the CLI (`tristim absolute fit`) and the page.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "tristim/absolute/profile.hpp"

namespace tristim {

/// One training stimulus: per patch (frame == nullptr: stimulus.raw_RGB and .falloff are the
/// measurement, .exposure must be given) or a region of a decoded training frame (sampled with
/// sample_stimulus; the exposure from the frame's metadata when .exposure has no time or
/// f-number).
struct FrameStimulus {
  TrainingStimulus stimulus;        ///< id, exposure, XYZ (cd/m²), luminance_set; RGB per patch
  const RawImage* frame = nullptr;  ///< the region's frame (nullptr: a per-patch stimulus)
  std::string frame_name;           ///< how messages name the frame, e.g. "'y30.dng'"
  int x = 0, y = 0, w = 0, h = 0;   ///< the region, measurement pixels
  std::string where;                ///< how messages name the stimulus ("": "stimulus '<id>'")
};

struct AbsoluteFitFrames {
  std::vector<FrameStimulus> stimuli;
  std::vector<const RawImage*> lens_cap;  ///< averaged: n and σ per channel (none: noise_floor)
  const RawImage* flat = nullptr;         ///< equal-tristimulus flat field for f(r) (none: f = 1)
  std::vector<const RawImage*> series;    ///< the scene's frames, if at hand (S measured on them too)
  double saturation = 0;                  ///< S in DN; 0: measured from the training frames and the series
  double noise_floor = 0;                 ///< n in DN when there are no lens-cap frames
  std::optional<SpectralData> ssf;        ///< sensitivities for A_R, A_G, A_B (none: 1, 1, 1)
  std::string areas_source = "none";      ///< recorded in the profile ("camera:<name>", "file:<name>")
  double w = 10;                          ///< zone parameter
  AbsoluteFitOptions options;
  FusionMode fusion = FusionMode::Weighted;
};

struct AbsoluteFitFromFrames {
  AbsoluteProfile profile;                ///< make, model, size (of the flat), S, areas, fusion set
  std::vector<TrainingStimulus> stimuli;  ///< as fitted (regions sampled, saturated flags set)
};

/// Builds the normalisation (eq 7) from the frames, samples the stimuli and fits
/// (fit_absolute_Guarnera2018). Errors: EmptyFile (no stimuli); InvalidArgument (per-patch
/// stimuli only and no S given); MissingMetadata (a per-patch stimulus without exposure, a frame
/// without exposure time or f-number); FrameMismatch (frames from two cameras, a region's frame
/// and the flat of different sizes); those of the fits.
AbsoluteFitFromFrames fit_absolute_from_frames(const AbsoluteFitFrames& input);

}  // namespace tristim
