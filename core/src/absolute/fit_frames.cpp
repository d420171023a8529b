// The absolute fit from frames and stimuli (rules in tristim/absolute/fit_frames.hpp).
#include "tristim/absolute/fit_frames.hpp"

#include <algorithm>

#include "tristim/error.hpp"

namespace tristim {

AbsoluteFitFromFrames fit_absolute_from_frames(const AbsoluteFitFrames& in) {
  if (in.stimuli.empty()) throw Error(ErrorCode::EmptyFile, "no training stimuli");
  // One camera for every frame given.
  std::string make, model;
  bool known = false;
  auto same_camera = [&](const RawImage& f, const std::string& what) {
    if (!known) {
      make = f.meta.make, model = f.meta.model, known = true;
    } else if (f.meta.make != make || f.meta.model != model) {
      throw Error(ErrorCode::FrameMismatch, what + " comes from " + f.meta.make + " " + f.meta.model + " but the others from " +
                                                make + " " + model);
    }
  };
  std::vector<const RawImage*> training;  // each training frame once
  for (const auto& s : in.stimuli)
    if (s.frame && std::find(training.begin(), training.end(), s.frame) == training.end()) {
      same_camera(*s.frame, "training frame " + s.frame_name);
      training.push_back(s.frame);
    }
  for (size_t i = 0; i < in.series.size(); ++i) same_camera(*in.series[i], "frame " + std::to_string(i + 1) + " of the series");
  for (size_t i = 0; i < in.lens_cap.size(); ++i) same_camera(*in.lens_cap[i], "lens-cap frame " + std::to_string(i + 1));
  if (in.flat) same_camera(*in.flat, "the flat field");

  // Eq (7): n and σ from the lens cap, S, areas, f(r).
  std::optional<DarkFrame> cap;
  if (!in.lens_cap.empty()) cap = average_dark_frames(in.lens_cap);
  SaturationEstimate sat;
  std::vector<const RawImage*> all = training;  // each frame once: a region may lie in a frame of the series
  for (const RawImage* f : in.series)
    if (std::find(all.begin(), all.end(), f) == all.end()) all.push_back(f);
  if (in.saturation > 0) {
    sat.level = sat.reported = {in.saturation, in.saturation, in.saturation};
    sat.fraction = {1, 1, 1};
  } else if (!all.empty()) {
    sat = measure_saturation(all);  // the brightest shots show where the body really clips
  } else {
    throw Error(ErrorCode::InvalidArgument,
                "per-patch stimuli need the saturation level S (DN), or RAW frames to measure it from");
  }
  std::optional<FalloffFit> falloff;
  if (in.flat) falloff = fit_falloff_Guarnera2018(*in.flat, cap ? &*cap : nullptr);
  Normalisation n = make_normalisation(cap ? &*cap : nullptr, sat, in.ssf ? &*in.ssf : nullptr, falloff, in.w);
  if (!cap && in.noise_floor != 0) {
    n.noise_floor = {in.noise_floor, in.noise_floor, in.noise_floor};
    n.check();
  }

  AbsoluteFitFromFrames out;
  for (const auto& a : in.stimuli) {
    const std::string where = a.where.empty() ? "stimulus '" + a.stimulus.id + "'" : a.where;
    TrainingStimulus s;
    if (a.frame) {
      const RawImage& f = *a.frame;
      if (falloff && (f.width != falloff->width || f.height != falloff->height))
        throw Error(ErrorCode::FrameMismatch, where + ": its frame " + a.frame_name + " and the flat field differ in size");
      ExposureSettings e = a.stimulus.exposure;
      if (!(e.exposure_s > 0) || !(e.f_number > 0)) e = exposure_from_metadata(f.meta, where + " (" + a.frame_name + ")");
      s = sample_stimulus(f, a.x, a.y, a.w, a.h, n, e, a.stimulus.XYZ, a.stimulus.id, a.stimulus.luminance_set);
    } else {
      if (!(a.stimulus.exposure.exposure_s > 0) || !(a.stimulus.exposure.f_number > 0))
        throw Error(ErrorCode::MissingMetadata, where + ": a per-patch stimulus needs exposure_s and f_number");
      s = a.stimulus;
      for (int c = 0; c < 3; ++c) s.saturated[c] = n.zone(c, s.raw_RGB[c]) == Zone::Saturated;
    }
    out.stimuli.push_back(s);
  }
  AbsoluteProfile& p = out.profile;
  p = fit_absolute_Guarnera2018(out.stimuli, n, in.options);
  p.make = make;
  p.model = model;
  if (falloff) p.width = falloff->width, p.height = falloff->height;
  p.saturation = sat;
  p.areas_source = in.areas_source;
  p.fusion = in.fusion;
  return out;
}

}  // namespace tristim
