// The absolute data path: recipe + frames → profile; profile + series → maps → report (rules in
// tristim/absolute/characterise.hpp).
#include "tristim/absolute/characterise.hpp"

#include <algorithm>
#include <cmath>

#include "tristim/absolute/fit_frames.hpp"
#include "tristim/error.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

std::string last_component(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string names_list(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s.empty() ? "none" : s;
}

std::vector<double> log_space(double a, double b, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = a * std::pow(b / a, i / (n - 1.0));
  return v;
}

OecfPanel panel_of(const ExposureReport& r, const LuminanceFit& fit, const std::vector<TrainingStimulus>& stimuli,
                   const Normalisation& n) {
  OecfPanel p;
  p.exposure = r.exposure;
  p.label = r.exposure.label();
  p.factor = r.factor;
  p.parallel = r.parallel;
  p.samples = r.samples;
  p.scale_ratio = r.scale_ratio;
  p.slope_difference = r.slope_difference;
  p.rms_relative = r.rms_relative;
  const double eps = r.exposure.factor(fit.iso_reference);
  double r_max = 0;
  for (const auto& s : stimuli) {
    if (!s.luminance_set || std::fabs(s.exposure.factor(fit.iso_reference) - eps) > 1e-9 * eps) continue;
    for (int c = 0; c < 3; ++c) {
      const double R = stimulus_normalised(s, n, c);
      if (s.saturated[c] || !(s.XYZ[1] > 0) || !(R > 0)) continue;
      p.point_Y[c].push_back(s.XYZ[1]);
      p.point_R[c].push_back(R);
      r_max = std::max(r_max, R);
    }
  }
  for (int c = 0; c < 3; ++c) {
    for (double R : log_space(1e-3, std::max(1.0, r_max), 64)) {
      const double Y = fit.curves[c](R) / eps;  // eqs (8), (10)
      if (!(Y > 0)) continue;
      p.curve_R[c].push_back(R);
      p.curve_Y[c].push_back(Y);
      if (r.own_fit[c]) p.own_Y[c].push_back(r.own[c](R) / r.factor);  // the own fit is in this exposure's units
    }
    if (!r.own_fit[c]) p.own_Y[c].clear();
  }
  return p;
}

/// The fitted chain on its own unsaturated training stimuli, white E at their largest Y.
AbsoluteTraining training_figures(const AbsoluteProfile& p, const std::vector<TrainingStimulus>& stimuli) {
  AbsoluteTraining t;
  t.colour_stimuli = p.colour_stimuli;
  std::vector<Vec3> est, ref;
  double y_max = 0;
  for (const auto& s : stimuli) {
    t.luminance_stimuli += s.luminance_set;
    if (s.saturated[0] || s.saturated[1] || s.saturated[2]) {
      t.saturated_stimuli++;
      continue;
    }
    est.push_back(p.XYZ(stimulus_luminance(s, p.normalisation, p.luminance)));  // eq (4)
    ref.push_back(s.XYZ);
    y_max = std::max(y_max, s.XYZ[1]);
  }
  t.evaluated = static_cast<int>(est.size());
  PatchMatrix E(est.size(), 3), R(ref.size(), 3);
  for (size_t i = 0; i < est.size(); ++i) {
    E.row(i) = est[i].transpose();
    R.row(i) = ref[i].transpose();
  }
  if (y_max > 0) t.figures = evaluate_absolute(E, R, white_equal_energy(y_max));
  return t;
}

}  // namespace

int find_frame(const std::vector<std::string>& names, const std::string& file) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == file) return static_cast<int>(i);
  int found = -1;
  for (size_t i = 0; i < names.size(); ++i)
    if (last_component(names[i]) == last_component(file)) {
      if (found >= 0) return -1;
      found = static_cast<int>(i);
    }
  return found;
}

std::vector<OecfPanel> oecf_panels(const AbsoluteProfile& p, const std::vector<TrainingStimulus>& stimuli) {
  std::vector<OecfPanel> out;
  for (const auto& r : p.luminance.exposures) out.push_back(panel_of(r, p.luminance, stimuli, p.normalisation));
  return out;
}

AbsoluteCharacterisation characterise_absolute(const AbsoluteRecipe& in, const AbsoluteFrames& frames) {
  AbsoluteCharacterisation c;
  c.recipe = complete_absolute_recipe(in);
  const AbsoluteInputs& inputs = c.recipe.inputs;
  const AbsoluteOptions& o = c.recipe.options;
  if (frames.bracket.size() != inputs.bracket.size() || frames.lens_cap.size() != inputs.lens_cap.size() ||
      frames.others.size() != frames.other_names.size())
    throw Error(ErrorCode::InvalidArgument, "give one decoded frame per file the recipe names (bracket " +
                                                std::to_string(inputs.bracket.size()) + ", lens cap " +
                                                std::to_string(inputs.lens_cap.size()) + ")");
  if (!inputs.flat.empty() && !frames.flat)
    throw Error(ErrorCode::InvalidArgument, "the recipe names the flat field '" + inputs.flat + "': give its frame");
  auto present = [](const std::vector<const RawImage*>& v) { return std::all_of(v.begin(), v.end(), [](auto* f) { return f; }); };
  if (!present(frames.bracket) || !present(frames.lens_cap) || !present(frames.others))
    throw Error(ErrorCode::InvalidArgument, "a frame of the recipe is missing");
  int luminance = 0;
  for (const auto& s : inputs.stimuli) luminance += s.set == "luminance";
  if (!inputs.stimuli.empty() && luminance < 3)  // (none at all: fit_absolute_from_frames says EmptyFile)
    throw Error(ErrorCode::TooFewPatches, "the inverse OECF (eq 8) needs at least 3 equal-tristimulus stimuli, got " +
                                              std::to_string(luminance));

  AbsoluteFitFrames fi;
  for (const auto& a : inputs.stimuli) {
    FrameStimulus s;
    s.where = stimulus_where(a);
    s.stimulus.id = a.id;
    s.stimulus.exposure = a.exposure;
    s.stimulus.XYZ = a.XYZ;
    s.stimulus.luminance_set = a.set == "luminance";
    if (a.region()) {
      const int b = find_frame(inputs.bracket, a.file), k = b >= 0 ? -1 : find_frame(frames.other_names, a.file);
      if (b < 0 && k < 0)
        throw Error(ErrorCode::UnknownId, s.where + " names '" + a.file + "', which is not in the bracket (" +
                                              names_list(inputs.bracket) + ")");
      s.frame = b >= 0 ? frames.bracket[b] : frames.others[k];
      s.frame_name = "'" + a.file + "'";
      s.x = a.x, s.y = a.y, s.w = a.w, s.h = a.h;
    } else {
      s.stimulus.raw_RGB = a.RGB;
      s.stimulus.falloff = a.falloff;
    }
    fi.stimuli.push_back(s);
  }
  fi.lens_cap = frames.lens_cap;
  fi.flat = inputs.flat.empty() ? nullptr : frames.flat;
  fi.series = frames.bracket;
  fi.saturation = o.saturation;
  fi.noise_floor = o.noise_floor;
  const AbsoluteSensitivities& a = inputs.sensitivities;
  if (a.choice == "given") {
    fi.ssf = a.ssf;
    fi.areas_source = a.source;
  } else if (a.choice == "camera") {
    fi.ssf = camera_ssf(a.camera);
    fi.areas_source = "camera:" + a.camera;
  }
  fi.w = o.w;
  fi.options.transform = o.transform;
  fi.fusion = fusion_mode_from_id(o.fusion);
  AbsoluteFitFromFrames fitted = fit_absolute_from_frames(fi);
  c.stimuli = std::move(fitted.stimuli);
  c.profile = std::move(fitted.profile);
  c.profile.training = training_figures(c.profile, c.stimuli);
  c.profile.has_training = true;
  c.profile.recipe = c.recipe;
  c.profile.has_recipe = true;
  c.panels = oecf_panels(c.profile, c.stimuli);
  c.report = absolute_report(c.profile, nullptr);
  return c;
}

// ---- a series ------------------------------------------------------------------------------

std::string series_frame_name(const std::vector<std::string>& names, size_t i) {
  return i < names.size() && !names[i].empty() ? "'" + names[i] + "'" : "frame " + std::to_string(i + 1);
}

namespace {

void check_same_frame(const std::vector<const RawImage*>& frames, const std::vector<std::string>& names, size_t i) {
  const RawImage &f = *frames[i], &first = *frames[0];
  if (f.meta.make != first.meta.make || f.meta.model != first.meta.model)
    throw Error(ErrorCode::FrameMismatch, series_frame_name(names, i) + " comes from " + f.meta.make + " " + f.meta.model +
                                              " but " + series_frame_name(names, 0) + " from " + first.meta.make + " " +
                                              first.meta.model);
  if (f.width != first.width || f.height != first.height)
    throw Error(ErrorCode::FrameMismatch, series_frame_name(names, i) + " is " + std::to_string(f.width) + "x" +
                                              std::to_string(f.height) + " but " + series_frame_name(names, 0) + " is " +
                                              std::to_string(first.width) + "x" + std::to_string(first.height) +
                                              " (measurement pixels)");
}

}  // namespace

ExposureSettings frame_exposure(const RawImage& f, const std::string& name, const ExposureSettings& given) {
  return given.exposure_s > 0 && given.f_number > 0 ? given : exposure_from_metadata(f.meta, name);
}

std::vector<ExposureSettings> series_exposures(const std::vector<const RawImage*>& frames, const AbsoluteApplyOptions& o) {
  if (frames.empty()) throw Error(ErrorCode::InvalidArgument, "no frames in the series");
  if (frames.size() > static_cast<size_t>(kMaxExposures))
    throw Error(ErrorCode::LimitExceeded, "at most " + std::to_string(kMaxExposures) + " exposures can be combined");
  if (!o.exposures.empty() && o.exposures.size() != frames.size())
    throw Error(ErrorCode::InvalidArgument, "give one exposure per frame, or none");
  for (const RawImage* f : frames)
    if (!f) throw Error(ErrorCode::InvalidArgument, "a frame of the series is missing");
  for (size_t i = 1; i < frames.size(); ++i) check_same_frame(frames, o.names, i);
  std::vector<ExposureSettings> exposures;  // then the exposures, once the frames belong together
  for (size_t i = 0; i < frames.size(); ++i)
    exposures.push_back(frame_exposure(*frames[i], series_frame_name(o.names, i), i < o.exposures.size() ? o.exposures[i] : ExposureSettings{}));
  return exposures;
}

AbsoluteMaps apply_absolute_series(const AbsoluteProfile& profile, const std::vector<const RawImage*>& frames,
                                   const AbsoluteApplyOptions& o, const AbsoluteProgress& progress) {
  AbsoluteMaps out;
  out.profile = profile;
  AbsoluteProfile& p = out.profile;
  if (!o.mode.empty()) p.fusion = fusion_mode_from_id(o.mode);
  const std::vector<ExposureSettings> exposures = series_exposures(frames, o);
  for (size_t i = 0; i < frames.size(); ++i) {
    check_profile_frame(p, *frames[i], series_frame_name(o.names, i));
    out.names.push_back(i < o.names.size() && !o.names[i].empty() ? o.names[i] : "frame " + std::to_string(i + 1));
  }
  if (p.fusion == FusionMode::Weighted) {  // streamed: one frame at a time into the accumulators
    ExposureFusion fusion(p.normalisation, p.luminance, frames[0]->width, frames[0]->height);
    for (size_t i = 0; i < frames.size(); ++i) {
      if (progress) progress(static_cast<double>(i) / (frames.size() + 1), "fusing " + exposures[i].label());
      fusion.add(*frames[i], exposures[i]);
    }
    out.image.luminance = fusion.finish();
    luminance_to_XYZ(p, out.image.luminance.L, out.image.XYZ);  // eq (4)
  } else {
    if (progress) progress(0.0, "Algorithm 1 over the series");
    out.image = apply_absolute(p, frames, exposures);
  }
  return out;
}

Vec3 window_mean(const AbsoluteImage& img, int x, int y, int window, int& n) {
  const int W = img.luminance.width, H = img.luminance.height, half = std::max(0, window / 2);
  if (x < 0 || y < 0 || x >= W || y >= H)
    throw Error(ErrorCode::InvalidArgument, "the point (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the image");
  Vec3 sum = Vec3::Zero();
  n = 0;
  for (int yy = std::max(0, y - half); yy <= std::min(H - 1, y + half); ++yy)
    for (int xx = std::max(0, x - half); xx <= std::min(W - 1, x + half); ++xx) {
      const size_t q = static_cast<size_t>(yy) * W + xx;
      const Vec3 v(img.XYZ[q * 3], img.XYZ[q * 3 + 1], img.XYZ[q * 3 + 2]);
      if (v.allFinite()) sum += v, ++n;
    }
  return n ? Vec3(sum / n) : Vec3::Constant(NAN);
}

AbsoluteReadout absolute_readout(const AbsoluteMaps& m, int x, int y, int window) {
  const FusedLuminance& L = m.image.luminance;
  AbsoluteReadout r;
  r.XYZ = window_mean(m.image, x, y, window, r.n);
  r.x = x, r.y = y;
  const size_t q = static_cast<size_t>(y) * L.width + x;
  r.L = Vec3(L.L[q * 3], L.L[q * 3 + 1], L.L[q * 3 + 2]);
  if (L.source[q] != 255) {
    r.source = L.source[q];
    r.source_label = L.exposures[L.source[q]].label();
  }
  for (int b = 0; b < kMaxExposures; ++b)
    if (L.contributors[q] >> b & 1) r.contributors.push_back(b);
  return r;
}

AbsoluteMapsSummary absolute_maps_summary(const AbsoluteMaps& m) {
  const FusedLuminance& L = m.image.luminance;
  AbsoluteMapsSummary s;
  s.width = L.width;
  s.height = L.height;
  s.mode = fusion_mode_id(m.profile.fusion);
  s.exposures = L.exposures;
  for (const auto& e : L.exposures) s.labels.push_back(e.label());
  s.names = m.names;
  for (auto d : L.dominant_pixels) s.dominant_pixels.push_back(static_cast<double>(d));
  s.saturated_pixels = static_cast<double>(L.saturated_pixels);
  s.unreliable_pixels = static_cast<double>(L.unreliable_pixels);
  std::vector<double> Y;
  for (size_t q = 0; q < m.image.XYZ.size() / 3; ++q)
    if (std::isfinite(m.image.XYZ[q * 3 + 1])) Y.push_back(m.image.XYZ[q * 3 + 1]);
  s.finite_pixels = static_cast<double>(Y.size());
  if (!Y.empty()) {
    s.Y = summarize(Y);
    s.Y_p01 = quantile(Y, 0.01);
    s.Y_p99 = quantile(Y, 0.99);
  }
  return s;
}

// ---- the test scene ------------------------------------------------------------------------

AbsoluteTestReport evaluate_absolute_test(const AbsoluteProfile& p, const AbsoluteMaps* maps,
                                          const std::vector<AbsoluteStimulus>& rows, const AbsoluteEvaluateOptions& o) {
  AbsoluteRecipe completed;  // the 2 % rule and the row checks, as for training rows
  completed.inputs.stimuli = rows;
  completed = complete_absolute_recipe(completed);
  const std::vector<AbsoluteStimulus>& test = completed.inputs.stimuli;
  AbsoluteTestReport t;
  std::vector<AbsoluteTestRow> all;  // in the order given: points and regions interleaved
  for (const auto& s : test) {
    AbsoluteTestRow r;
    r.id = s.id, r.set = s.set, r.file = s.file;
    r.x = s.x, r.y = s.y, r.w = s.w, r.h = s.h;
    r.reference = s.XYZ;
    if (s.region()) {
      if (!maps) throw Error(ErrorCode::InvalidArgument, stimulus_where(s) + " is a region: give the bracket it names");
      if (find_frame(maps->names, s.file) < 0)
        throw Error(ErrorCode::UnknownId, stimulus_where(s) + " names '" + s.file + "', which is not in the bracket (" +
                                              names_list(maps->names) + ")");
      const FusedLuminance& L = maps->image.luminance;
      if (s.x < 0 || s.y < 0 || s.x + s.w > L.width || s.y + s.h > L.height)
        throw Error(ErrorCode::InvalidArgument, stimulus_where(s) + ": region " + std::to_string(s.x) + "," + std::to_string(s.y) +
                                                    " " + std::to_string(s.w) + "x" + std::to_string(s.h) +
                                                    " is not inside the " + std::to_string(L.width) + "x" +
                                                    std::to_string(L.height) + " image");
      const int ix = s.w / 4, iy = s.h / 4;  // the central half of each side: away from the edges
      Vec3 sum = Vec3::Zero();
      for (int y = s.y + iy; y < s.y + s.h - iy; ++y)
        for (int x = s.x + ix; x < s.x + s.w - ix; ++x) {
          const size_t q = static_cast<size_t>(y) * L.width + x;
          const Vec3 v(maps->image.XYZ[q * 3], maps->image.XYZ[q * 3 + 1], maps->image.XYZ[q * 3 + 2]);
          if (v.allFinite()) sum += v, ++r.pixels;
        }
      if (r.pixels) r.estimated = sum / r.pixels;
      const size_t centre = static_cast<size_t>(s.y + s.h / 2) * L.width + s.x + s.w / 2;
      if (L.source[centre] != 255) {
        r.source = L.source[centre];
        r.source_label = L.exposures[L.source[centre]].label();
      }
    } else {
      TrainingStimulus st;
      st.id = s.id;
      st.exposure = s.exposure;
      st.raw_RGB = s.RGB;
      st.falloff = s.falloff;
      for (int c = 0; c < 3; ++c) r.saturated = r.saturated || p.normalisation.zone(c, s.RGB[c]) == Zone::Saturated;
      if (!r.saturated) r.estimated = p.XYZ(stimulus_luminance(st, p.normalisation, p.luminance));  // eqs (7), (8), (10), (4)
    }
    if (s.XYZ[1] > 0) r.relative_Y_error = (r.estimated[1] - s.XYZ[1]) / s.XYZ[1];
    all.push_back(r);
  }
  // The white (section 4.1): eq (16) with the white patch, or E, at the largest Y of the scene.
  const AbsoluteTestRow* white = nullptr;
  for (const auto& r : all) {
    t.max_luminance = std::max(t.max_luminance, r.reference[1]);
    if (!o.white.empty() && r.id == o.white) white = &r;
    if (o.white.empty() && r.set == "colour" && (!white || r.reference[1] > white->reference[1])) white = &r;
  }
  if (!o.white.empty() && o.white != "E" && !white)
    throw Error(ErrorCode::UnknownId, "the white patch '" + o.white + "' is not a stimulus of the test scene");
  if (o.white == "E") white = nullptr;
  if (!(t.max_luminance > 0)) throw Error(ErrorCode::NoUsableData, "the test scene has no stimulus with Y > 0");
  t.white_rule = white ? "eq16" : "E";
  t.white_id = white ? white->id : "";
  t.white = white ? white_Guarnera2018(white->reference, t.max_luminance) : white_equal_energy(t.max_luminance);
  // The figures: every row with an estimate, then chromatic and equal-tristimulus rows apart.
  auto figures = [&](const std::string& group, const std::string& label) {
    std::vector<const AbsoluteTestRow*> use;
    for (const auto& r : all)
      if (!r.saturated && (group == "all" || r.set == group)) use.push_back(&r);
    AbsoluteFigures f;
    f.group = group, f.label = label, f.count = static_cast<int>(use.size());
    PatchMatrix E(use.size(), 3), R(use.size(), 3);
    for (size_t i = 0; i < use.size(); ++i) {
      E.row(i) = use[i]->estimated.transpose();
      R.row(i) = use[i]->reference.transpose();
    }
    if (!use.empty()) f.metrics = evaluate_absolute(E, R, t.white);
    return f;
  };
  t.figures.push_back(figures("all", "every stimulus"));
  int colour = 0;
  for (const auto& r : all) colour += !r.saturated && r.set == "colour";
  if (colour > 0 && colour < t.figures[0].count) {
    t.figures.push_back(figures("colour", "chromatic"));
    t.figures.push_back(figures("luminance", "equal-tristimulus"));
  }
  for (auto& r : all) (r.file.empty() ? t.points : t.regions).push_back(std::move(r));
  return t;
}

AbsoluteReport absolute_report(const AbsoluteProfile& p, const AbsoluteMaps* maps, const std::vector<AbsoluteStimulus>& test,
                               const AbsoluteEvaluateOptions& o) {
  AbsoluteReport r;
  r.fit = absolute_fit_summary(p);
  r.has_training = p.has_training;
  r.training = p.training;
  if (maps) {
    r.has_maps = true;
    r.maps = absolute_maps_summary(*maps);
  }
  if (!test.empty()) {
    r.has_test = true;
    r.test = evaluate_absolute_test(p, maps, test, o);
  }
  return r;
}

AbsoluteReport absolute_maps_report(const AbsoluteMaps& maps, const std::vector<AbsoluteStimulus>& test,
                                    const AbsoluteEvaluateOptions& o) {
  return absolute_report(maps.profile, &maps, test, o);
}

}  // namespace tristim
