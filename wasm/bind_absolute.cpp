// Declarations: the absolute tele-colorimeter (Guarnera, Bianco & Schettini 2018) — the training
// stimuli CSV, the fit of an absolute profile (noise floor from lens-cap frames, S measured from
// the frames, f(r) from a flat, areas from built-in or given sensitivities, eq 8 per channel across every
// exposure, the colour matrix), OECF samples per channel and exposure (fig 5), the profile applied
// to a bracketed series of decoded RAWs (the AbsoluteMaps handle: X, Y, Z in cd/m², the source
// exposure per pixel, read-outs, region figures as section 4.1) and the virtual-camera example.
//
// AbsoluteMaps methods (the handle owns wasm memory: call .delete()): summary(), XYZ() ->
// Float32Array(3·w·h), source() -> Uint8Array(w·h) (dominant exposure, 255: none),
// contributors() -> Int32Array(w·h) (bit e: exposure e served the pixel), tiff() -> Uint8Array
// (the X, Y, Z map as a 32-bit float TIFF, as `tristim absolute apply` writes), readout(x, y, window)
// -> PixelReadout, measure(regions, white) -> RegionFigures.
#include <algorithm>
#include <cmath>
#include <optional>

#include "raw_handle.hpp"
#include "tristim/absolute/example.hpp"
#include "tristim/absolute/fit_frames.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/absolute/stimuli_file.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::val;
using emscripten::value_object;
using wasm::Conv;
using wasm::def;
using wasm::guard;
using wasm::RawHandle;

template <>
struct tristim::wasm::Conv<FusionMode> : EnumConv<FusionMode, &fusion_mode_id, &fusion_mode_from_id> {};

namespace {

using Handles = std::vector<const RawHandle*>;

std::vector<const RawImage*> images_of(const Handles& h) {
  std::vector<const RawImage*> out;
  for (const auto* x : h) out.push_back(&x->image);
  return out;
}

/// One training stimulus as the page holds it: per patch (RGB, falloff) or a region of a frame.
struct AbsoluteStimulus {
  std::string id;
  std::string set;              ///< "luminance" | "colour" | "" (luminance when X = Y = Z within 2 %)
  ExposureSettings exposure;    ///< zeros for a region row: from its frame's metadata
  Vec3 RGB = Vec3::Zero();      ///< black-subtracted DN (per patch)
  double falloff = 1;           ///< f(r) of the patch (per patch)
  std::string file;             ///< the file a region row names (the page maps it to `frame`)
  int frame = -1;               ///< index into fitAbsolute's frames; −1: a per-patch row
  int x = 0, y = 0, w = 0, h = 0;
  Vec3 XYZ = Vec3::Zero();      ///< measured, cd/m²
  int line = 0;
};

bool equal_tristimulus(const Vec3& v) {
  return std::fabs(v[0] - v[1]) <= 0.02 * v[1] && std::fabs(v[2] - v[1]) <= 0.02 * v[1];
}

std::vector<AbsoluteStimulus> read_stimuli(const std::string& text, const std::string& name) {
  std::vector<AbsoluteStimulus> out;
  for (const auto& r : read_stimuli_csv(text, name.empty() ? "stimuli" : name)) {
    AbsoluteStimulus s;
    s.id = r.stimulus.id;
    s.set = r.stimulus.luminance_set ? "luminance" : "colour";
    s.exposure = r.stimulus.exposure;
    s.RGB = r.stimulus.raw_RGB;
    s.falloff = r.stimulus.falloff;
    s.file = r.file;
    s.x = r.x, s.y = r.y, s.w = r.w, s.h = r.h;
    s.XYZ = r.stimulus.XYZ;
    s.line = r.line;
    out.push_back(s);
  }
  return out;
}

struct AbsoluteFitInput {
  std::vector<AbsoluteStimulus> stimuli;
  double noise_floor = 0;       ///< n in DN when no lens-cap frames are given
  double saturation = 0;        ///< S in DN; 0: measured from the frames (LibRaw's level without a pile-up)
  std::string camera;           ///< built-in sensitivities for A_R, A_G, A_B ("": none, 1, 1, 1)
  SpectralData ssf;             ///< given sensitivities (an uploaded CSV, an estimate); used when set, before `camera`
  std::string ssf_source;       ///< what they are, recorded in the profile's areas_source ("file:x.csv", "estimate:…")
  double w = 10;                ///< zone parameter
  std::string transform = "T1"; ///< T1 | To | T2R (eqs 13-15)
  FusionMode fusion = FusionMode::Weighted;
};

struct ChannelFit {
  double k1 = 0, k2 = 1, k3 = 1;  ///< eq (8), exposure units relative to iso_reference
  int samples = 0;
  double rms_relative = 0, max_relative = 0, r_squared = 0;
  std::string message;
};

/// One exposure of fig 5: the normalised R', G', B' (eq 7) against the luminance Y, cd/m².
struct OecfPanel {
  ExposureSettings exposure;
  std::string label;
  double factor = 0;                                   ///< ε relative to the reference ISO
  bool parallel = true;                                ///< the reciprocity check of this exposure
  std::array<int, 3> samples{};
  std::array<double, 3> scale_ratio{}, slope_difference{}, rms_relative{};
  std::array<std::vector<double>, 3> point_Y, point_R; ///< the training stimuli (Y > 0, R' > 0)
  std::array<std::vector<double>, 3> curve_Y, curve_R; ///< the common curve at this ε
  std::array<std::vector<double>, 3> own_Y;            ///< the exposure's own fit at curve_R (empty: none)
};

struct AbsoluteFitOutcome {
  std::string profile;  ///< the absolute profile JSON (applyAbsolute takes it back)
  std::string make, model;
  std::array<ChannelFit, 3> channels;
  double iso_reference = 0;
  std::vector<OecfPanel> panels;  ///< shortest exposure first
  bool reciprocity_ok = true;
  std::string reciprocity_message;
  std::array<double, 3> noise_floor{}, noise_sigma{}, saturation{}, saturation_reported{}, saturation_fraction{}, areas{};
  std::array<bool, 3> saturation_measured{};
  std::string areas_source;
  bool has_falloff = false;
  FalloffFit falloff;
  int luminance_stimuli = 0, colour_stimuli = 0, saturated_stimuli = 0;
  std::string transform, colour_message;
  FitStatus colour_status = FitStatus::Ok;
  Eigen::MatrixXd colour_matrix;  ///< M, 3 × P row-major
  /// The fitted chain on its own unsaturated training stimuli (white: E at their largest Y).
  std::vector<std::string> ids;
  std::vector<Vec3> estimated, measured;
  AbsoluteMetrics training;
};

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

AbsoluteFitOutcome fit_absolute(const AbsoluteFitInput& in, const Handles& frames, const Handles& lens_cap,
                                const Handles& flat, const Handles& series) {
  if (flat.size() > 1) throw Error(ErrorCode::InvalidArgument, "one flat field at most");
  AbsoluteFitFrames fi;
  for (const auto& a : in.stimuli) {
    FrameStimulus s;
    s.where = "stimulus '" + a.id + "'" + (a.line ? " (line " + std::to_string(a.line) + ")" : "");
    bool luminance_set = equal_tristimulus(a.XYZ);
    if (a.set == "luminance" || a.set == "oecf") luminance_set = true;
    else if (a.set == "colour" || a.set == "color") luminance_set = false;
    else if (!a.set.empty()) throw Error(ErrorCode::InvalidArgument, s.where + ": set is luminance or colour, not '" + a.set + "'");
    s.stimulus.id = a.id;
    s.stimulus.exposure = a.exposure;
    s.stimulus.XYZ = a.XYZ;
    s.stimulus.luminance_set = luminance_set;
    if (a.frame >= 0) {
      if (a.frame >= static_cast<int>(frames.size()))
        throw Error(ErrorCode::InvalidArgument, s.where + ": frame " + std::to_string(a.frame) + " was not given");
      s.frame = &frames[a.frame]->image;
      s.frame_name = "'" + a.file + "'";
      s.x = a.x, s.y = a.y, s.w = a.w, s.h = a.h;
    } else {
      s.stimulus.raw_RGB = a.RGB;
      s.stimulus.falloff = a.falloff;
    }
    fi.stimuli.push_back(s);
  }
  fi.lens_cap = images_of(lens_cap);
  if (!flat.empty()) fi.flat = &flat[0]->image;
  fi.series = images_of(series);
  fi.saturation = in.saturation;
  fi.noise_floor = in.noise_floor;
  if (!in.ssf.names.empty()) {
    fi.ssf = in.ssf;
    fi.areas_source = in.ssf_source.empty() ? "given" : in.ssf_source;
  } else if (!in.camera.empty()) {
    fi.ssf = camera_ssf(in.camera);
    fi.areas_source = "camera:" + in.camera;
  }
  fi.w = in.w;
  fi.options.transform = in.transform;
  fi.fusion = in.fusion;
  const AbsoluteFitFromFrames fitted = fit_absolute_from_frames(fi);
  const AbsoluteProfile& p = fitted.profile;
  const std::vector<TrainingStimulus>& stimuli = fitted.stimuli;
  const Normalisation& n = p.normalisation;
  const SaturationEstimate& sat = p.saturation;
  AbsoluteFitOutcome out;
  out.profile = absolute_profile_to_json(p);
  out.make = p.make;
  out.model = p.model;
  for (int c = 0; c < 3; ++c) {
    const OecfFit& f = p.luminance.fits[c];
    out.channels[c] = {p.luminance.curves[c].k1, p.luminance.curves[c].k2, p.luminance.curves[c].k3, f.samples,
                       f.rms_relative, f.max_relative, f.r_squared, f.message};
  }
  out.iso_reference = p.luminance.iso_reference;
  for (const auto& r : p.luminance.exposures) out.panels.push_back(panel_of(r, p.luminance, stimuli, n));
  out.reciprocity_ok = p.luminance.reciprocity_ok;
  out.reciprocity_message = p.luminance.message;
  out.noise_floor = n.noise_floor;
  out.noise_sigma = n.noise_sigma;
  out.saturation = n.saturation;
  out.saturation_reported = sat.reported;
  out.saturation_fraction = sat.fraction;
  out.saturation_measured = sat.measured;
  out.areas = n.areas;
  out.areas_source = p.areas_source;
  out.has_falloff = n.falloff.has_value();
  if (n.falloff) out.falloff = *n.falloff;
  out.transform = p.transform;
  out.colour_message = p.colour_message;
  out.colour_status = p.colour_status;
  out.colour_matrix = p.colour.coefficients;
  out.colour_stimuli = p.colour_stimuli;
  double y_max = 0;
  for (const auto& s : stimuli) {
    out.luminance_stimuli += s.luminance_set;
    if (s.saturated[0] || s.saturated[1] || s.saturated[2]) {
      out.saturated_stimuli++;
      continue;
    }
    out.ids.push_back(s.id);
    out.estimated.push_back(p.XYZ(stimulus_luminance(s, n, p.luminance)));  // eq (4)
    out.measured.push_back(s.XYZ);
    y_max = std::max(y_max, s.XYZ[1]);
  }
  PatchMatrix est(out.estimated.size(), 3), ref(out.measured.size(), 3);
  for (size_t i = 0; i < out.estimated.size(); ++i) {
    est.row(i) = out.estimated[i].transpose();
    ref.row(i) = out.measured[i].transpose();
  }
  if (y_max > 0) out.training = evaluate_absolute(est, ref, white_equal_energy(y_max));
  return out;
}

// ---- applying a profile ------------------------------------------------------------------------

struct AbsoluteApplyOptions {
  std::string mode;                       ///< "" (the profile's), "weighted" or "recursive"
  std::vector<ExposureSettings> exposures;  ///< per frame (zeros: from its metadata), or none
  std::vector<std::string> names;         ///< file names for messages
};

struct AbsoluteMaps {
  AbsoluteImage image;
  std::vector<std::string> labels;  ///< per exposure
};

struct AbsoluteMapsSummary {
  int width = 0, height = 0;
  std::string mode;
  std::vector<ExposureSettings> exposures;
  std::vector<std::string> labels;
  std::vector<double> dominant_pixels;
  double saturated_pixels = 0, unreliable_pixels = 0, finite_pixels = 0;
  Summary Y;  ///< over finite pixels, cd/m²
  double Y_p01 = 0, Y_p99 = 0;
};

struct PixelReadout {
  int x = 0, y = 0, n = 0;         ///< window centre and finite pixels averaged
  Vec3 XYZ = Vec3::Constant(NAN);  ///< mean over the window, cd/m²
  Vec3 L = Vec3::Constant(NAN);    ///< L(R), L(G), L(B) at the centre pixel, cd/m² (eq 10)
  int source = -1;                 ///< dominant exposure at the centre, −1: none
  std::string source_label;
  std::vector<int> contributors;   ///< exposures that served the centre pixel
};

/// A region with its reference X, Y, Z (cd/m²); `inset` of each side is left out of the mean.
struct AbsoluteRegion {
  std::string id;
  int x = 0, y = 0, w = 0, h = 0;
  Vec3 XYZ = Vec3::Zero();
};

struct RegionFigures {
  std::vector<std::string> ids;
  std::vector<Vec3> estimated, reference;  ///< region means (central half), cd/m²
  std::vector<double> relative_Y;          ///< (Y_est − Y_ref)/Y_ref
  std::vector<int> source;                 ///< dominant exposure at the region centre
  AbsoluteMetrics metrics;                 ///< section 4.1 figures against `white`
};

/// The exposure of every frame of a series (given, or from its metadata), after checking that
/// the frames share one camera and size. FrameMismatch, MissingMetadata (naming the file),
/// LimitExceeded beyond kMaxExposures frames.
std::vector<ExposureSettings> series_exposures(const Handles& frames, const AbsoluteApplyOptions& o) {
  if (frames.empty()) throw Error(ErrorCode::InvalidArgument, "no frames in the series");
  if (frames.size() > static_cast<size_t>(kMaxExposures))
    throw Error(ErrorCode::LimitExceeded, "at most " + std::to_string(kMaxExposures) + " exposures can be combined");
  if (!o.exposures.empty() && o.exposures.size() != frames.size())
    throw Error(ErrorCode::InvalidArgument, "give one exposure per frame, or none");
  auto name = [&](size_t i) {
    return i < o.names.size() && !o.names[i].empty() ? "'" + o.names[i] + "'" : "frame " + std::to_string(i + 1);
  };
  std::vector<ExposureSettings> exposures;
  const RawImage& first = frames[0]->image;
  for (size_t i = 0; i < frames.size(); ++i) {
    const RawImage& f = frames[i]->image;
    if (i > 0 && (f.meta.make != first.meta.make || f.meta.model != first.meta.model))
      throw Error(ErrorCode::FrameMismatch, name(i) + " comes from " + f.meta.make + " " + f.meta.model + " but " + name(0) +
                                                " from " + first.meta.make + " " + first.meta.model);
    if (i > 0 && (f.width != first.width || f.height != first.height))
      throw Error(ErrorCode::FrameMismatch, name(i) + " is " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                                                " but " + name(0) + " is " + std::to_string(first.width) + "x" +
                                                std::to_string(first.height) + " (measurement pixels)");
  }
  for (size_t i = 0; i < frames.size(); ++i) {  // then the exposures, once the frames belong together
    const RawImage& f = frames[i]->image;
    const bool given = i < o.exposures.size() && o.exposures[i].exposure_s > 0 && o.exposures[i].f_number > 0;
    exposures.push_back(given ? o.exposures[i] : exposure_from_metadata(f.meta, name(i)));
  }
  return exposures;
}

AbsoluteMaps apply_maps(const std::string& profile_text, const Handles& frames, const AbsoluteApplyOptions& o,
                        const val& progress) {
  AbsoluteProfile p = absolute_profile_from_json(profile_text);
  if (!o.mode.empty()) p.fusion = fusion_mode_from_id(o.mode);
  const std::vector<ExposureSettings> exposures = series_exposures(frames, o);
  for (size_t i = 0; i < frames.size(); ++i)
    check_profile_frame(p, frames[i]->image,
                        i < o.names.size() && !o.names[i].empty() ? "'" + o.names[i] + "'" : "frame " + std::to_string(i + 1));
  const bool report = !wasm::absent(progress);
  AbsoluteMaps out;
  if (p.fusion == FusionMode::Weighted) {  // streamed: one frame at a time into the accumulators
    ExposureFusion fusion(p.normalisation, p.luminance, frames[0]->image.width, frames[0]->image.height);
    for (size_t i = 0; i < frames.size(); ++i) {
      if (report) progress(val(static_cast<double>(i) / (frames.size() + 1)), val("fusing " + exposures[i].label()));
      fusion.add(frames[i]->image, exposures[i]);
    }
    out.image.luminance = fusion.finish();
    luminance_to_XYZ(p, out.image.luminance.L, out.image.XYZ);  // eq (4)
  } else {
    if (report) progress(val(0.0), val(std::string("Algorithm 1 over the series")));
    out.image = apply_absolute(p, images_of(frames), exposures);
  }
  for (const auto& e : out.image.luminance.exposures) out.labels.push_back(e.label());
  return out;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

AbsoluteMapsSummary maps_summary(const AbsoluteMaps& m) {
  const FusedLuminance& L = m.image.luminance;
  AbsoluteMapsSummary s;
  s.width = L.width;
  s.height = L.height;
  s.exposures = L.exposures;
  s.labels = m.labels;
  for (auto d : L.dominant_pixels) s.dominant_pixels.push_back(static_cast<double>(d));
  s.saturated_pixels = static_cast<double>(L.saturated_pixels);
  s.unreliable_pixels = static_cast<double>(L.unreliable_pixels);
  std::vector<double> Y;
  for (size_t q = 0; q < m.image.XYZ.size() / 3; ++q)
    if (std::isfinite(m.image.XYZ[q * 3 + 1])) Y.push_back(m.image.XYZ[q * 3 + 1]);
  s.finite_pixels = static_cast<double>(Y.size());
  if (!Y.empty()) {
    s.Y = summarize(Y);
    s.Y_p01 = percentile(Y, 0.01);
    s.Y_p99 = percentile(Y, 0.99);
  }
  return s;
}

PixelReadout maps_readout(const AbsoluteMaps& m, int x, int y, int window) {
  const FusedLuminance& L = m.image.luminance;
  PixelReadout r;
  if (x < 0 || y < 0 || x >= L.width || y >= L.height) throw Error(ErrorCode::InvalidArgument, "the point is outside the image");
  r.x = x, r.y = y;
  const int half = std::max(0, window / 2);
  Vec3 sum = Vec3::Zero();
  for (int yy = std::max(0, y - half); yy <= std::min(L.height - 1, y + half); ++yy)
    for (int xx = std::max(0, x - half); xx <= std::min(L.width - 1, x + half); ++xx) {
      const size_t q = static_cast<size_t>(yy) * L.width + xx;
      const Vec3 v(m.image.XYZ[q * 3], m.image.XYZ[q * 3 + 1], m.image.XYZ[q * 3 + 2]);
      if (v.allFinite()) sum += v, ++r.n;
    }
  if (r.n) r.XYZ = sum / r.n;
  const size_t q = static_cast<size_t>(y) * L.width + x;
  r.L = Vec3(L.L[q * 3], L.L[q * 3 + 1], L.L[q * 3 + 2]);
  if (L.source[q] != 255) {
    r.source = L.source[q];
    r.source_label = m.labels[L.source[q]];
  }
  for (int b = 0; b < kMaxExposures; ++b)
    if (L.contributors[q] >> b & 1) r.contributors.push_back(b);
  return r;
}

RegionFigures maps_measure(const AbsoluteMaps& m, const std::vector<AbsoluteRegion>& regions, const Vec3& white) {
  const FusedLuminance& L = m.image.luminance;
  RegionFigures f;
  for (const auto& g : regions) {
    if (g.w <= 0 || g.h <= 0 || g.x < 0 || g.y < 0 || g.x + g.w > L.width || g.y + g.h > L.height)
      throw Error(ErrorCode::InvalidArgument, "region '" + g.id + "' is not inside the image");
    const int ix = g.w / 4, iy = g.h / 4;  // the central half of each side
    Vec3 sum = Vec3::Zero();
    int n = 0;
    for (int y = g.y + iy; y < g.y + g.h - iy; ++y)
      for (int x = g.x + ix; x < g.x + g.w - ix; ++x) {
        const size_t q = static_cast<size_t>(y) * L.width + x;
        const Vec3 v(m.image.XYZ[q * 3], m.image.XYZ[q * 3 + 1], m.image.XYZ[q * 3 + 2]);
        if (v.allFinite()) sum += v, ++n;
      }
    f.ids.push_back(g.id);
    f.estimated.push_back(n ? Vec3(sum / n) : Vec3::Constant(NAN));
    f.reference.push_back(g.XYZ);
    f.relative_Y.push_back(g.XYZ[1] > 0 ? (f.estimated.back()[1] - g.XYZ[1]) / g.XYZ[1] : NAN);
    const size_t c = static_cast<size_t>(g.y + g.h / 2) * L.width + g.x + g.w / 2;
    f.source.push_back(L.source[c] == 255 ? -1 : L.source[c]);
  }
  PatchMatrix est(regions.size(), 3), ref(regions.size(), 3);
  for (size_t i = 0; i < regions.size(); ++i) {
    est.row(i) = f.estimated[i].transpose();
    ref.row(i) = f.reference[i].transpose();
  }
  if (!regions.empty()) f.metrics = evaluate_absolute(est, ref, white);
  return f;
}

std::vector<int> maps_contributors(const AbsoluteMaps& m) {
  return std::vector<int>(m.image.luminance.contributors.begin(), m.image.luminance.contributors.end());
}

// ---- the example ---------------------------------------------------------------------------------

struct AbsoluteExampleOut {
  std::string camera, make, model, white_id, stimuli_csv;
  std::vector<ExposureSettings> bracket;
  std::vector<std::string> labels;
  std::vector<RawHandle> frames, lens_cap;
  RawHandle flat;
  std::vector<AbsoluteRegion> regions;
};

AbsoluteExampleOut example(const AbsoluteExampleOptions& o) {
  AbsoluteExample ex = make_absolute_example(o);
  AbsoluteExampleOut out;
  out.camera = ex.camera;
  out.make = ex.sensor.make;
  out.model = ex.sensor.model;
  out.white_id = ex.white_id;
  out.stimuli_csv = stimuli_to_csv(ex.stimuli);
  out.bracket = ex.bracket;
  for (const auto& e : ex.bracket) out.labels.push_back(e.label());
  for (auto& f : ex.frames) out.frames.push_back({std::move(f), {}});
  for (auto& f : ex.lens_cap) out.lens_cap.push_back({std::move(f), {}});
  out.flat = {std::move(ex.flat), {}};
  for (const auto& g : ex.regions) out.regions.push_back({g.id, g.x, g.y, g.w, g.h, g.XYZ});
  return out;
}

val example_js(val options) {
  return guard([&] {
    const AbsoluteExampleOut ex = example(Conv<AbsoluteExampleOptions>::from(options));
    val out = val::object();
    out.set("camera", val(ex.camera));
    out.set("make", val(ex.make));
    out.set("model", val(ex.model));
    out.set("white_id", val(ex.white_id));
    out.set("stimuli_csv", val(ex.stimuli_csv));
    out.set("bracket", Conv<std::vector<ExposureSettings>>::to(ex.bracket));
    out.set("labels", Conv<std::vector<std::string>>::to(ex.labels));
    out.set("regions", Conv<std::vector<AbsoluteRegion>>::to(ex.regions));
    val frames = val::array(), caps = val::array();
    for (const auto& f : ex.frames) frames.call<void>("push", val(f));
    for (const auto& f : ex.lens_cap) caps.call<void>("push", val(f));
    out.set("frames", frames);
    out.set("lens_cap", caps);
    out.set("flat", val(ex.flat));
    return out;
  });
}

AbsoluteMaps apply_js(val profile, val frames, val options, val progress) {
  return guard([&] {
    if (!wasm::absent(progress) && wasm::type_of(progress) != "function")
      wasm::refuse("onProgress: expected a function, got " + wasm::type_of(progress));
    return apply_maps(Conv<std::string>::from(profile), Conv<Handles>::from(frames),
                      Conv<AbsoluteApplyOptions>::from(options), progress);
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_absolute) {
  using emscripten::class_;
  using emscripten::optional_override;
  { using S = ExposureSettings; value_object<S>("ExposureSettings") FIELD(exposure_s) FIELD(f_number) FIELD(iso); }
  { using S = AbsoluteStimulus; value_object<S>("AbsoluteStimulus") FIELD(id) FIELD(set) FIELD(exposure) FIELD(RGB)
      FIELD(falloff) FIELD(file) FIELD(frame) FIELD(x) FIELD(y) FIELD(w) FIELD(h) FIELD(XYZ) FIELD(line); }
  { using S = AbsoluteFitInput; value_object<S>("AbsoluteFitInput") FIELD(stimuli) FIELD(noise_floor) FIELD(saturation)
      FIELD(camera) FIELD(ssf) FIELD(ssf_source) FIELD(w) FIELD(transform) FIELD(fusion); }
  { using S = ChannelFit; value_object<S>("ChannelFit") FIELD(k1) FIELD(k2) FIELD(k3) FIELD(samples) FIELD(rms_relative)
      FIELD(max_relative) FIELD(r_squared) FIELD(message); }
  { using S = OecfPanel; value_object<S>("OecfPanel") FIELD(exposure) FIELD(label) FIELD(factor) FIELD(parallel)
      FIELD(samples) FIELD(scale_ratio) FIELD(slope_difference) FIELD(rms_relative) FIELD(point_Y) FIELD(point_R)
      FIELD(curve_Y) FIELD(curve_R) FIELD(own_Y); }
  { using S = AbsoluteMetrics; value_object<S>("AbsoluteMetrics") FIELD(metrics) FIELD(relative_Y_error)
      FIELD(median_absolute_error) FIELD(white); }
  { using S = AbsoluteFitOutcome; value_object<S>("AbsoluteFitOutcome") FIELD(profile) FIELD(make) FIELD(model)
      FIELD(channels) FIELD(iso_reference) FIELD(panels) FIELD(reciprocity_ok) FIELD(reciprocity_message)
      FIELD(noise_floor) FIELD(noise_sigma) FIELD(saturation) FIELD(saturation_reported) FIELD(saturation_fraction)
      FIELD(areas) FIELD(saturation_measured) FIELD(areas_source) FIELD(has_falloff) FIELD(falloff)
      FIELD(luminance_stimuli) FIELD(colour_stimuli) FIELD(saturated_stimuli) FIELD(transform) FIELD(colour_message)
      FIELD(colour_status) FIELD(colour_matrix) FIELD(ids) FIELD(estimated) FIELD(measured) FIELD(training); }
  { using S = AbsoluteApplyOptions; value_object<S>("AbsoluteApplyOptions") FIELD(mode) FIELD(exposures) FIELD(names); }
  { using S = AbsoluteMapsSummary; value_object<S>("AbsoluteMapsSummary") FIELD(width) FIELD(height) FIELD(mode)
      FIELD(exposures) FIELD(labels) FIELD(dominant_pixels) FIELD(saturated_pixels) FIELD(unreliable_pixels)
      FIELD(finite_pixels) FIELD(Y) FIELD(Y_p01) FIELD(Y_p99); }
  { using S = PixelReadout; value_object<S>("PixelReadout") FIELD(x) FIELD(y) FIELD(n) FIELD(XYZ) FIELD(L) FIELD(source)
      FIELD(source_label) FIELD(contributors); }
  { using S = AbsoluteRegion; value_object<S>("AbsoluteRegion") FIELD(id) FIELD(x) FIELD(y) FIELD(w) FIELD(h) FIELD(XYZ); }
  { using S = RegionFigures; value_object<S>("RegionFigures") FIELD(ids) FIELD(estimated) FIELD(reference)
      FIELD(relative_Y) FIELD(source) FIELD(metrics); }
  { using S = AbsoluteExampleOptions; value_object<S>("AbsoluteExampleOptions") FIELD(camera) FIELD(cell)
      FIELD(white_luminance) FIELD(illuminant) FIELD(colour_training) FIELD(seed); }

  class_<AbsoluteMaps>("AbsoluteMaps")
      .function("summary", optional_override([](const AbsoluteMaps& m) { return guard([&] { return val(maps_summary(m)); }); }))
      .function("XYZ", optional_override([](const AbsoluteMaps& m) { return Conv<std::vector<float>>::to(m.image.XYZ); }))
      .function("source", optional_override([](const AbsoluteMaps& m) {
                  return Conv<std::vector<uint8_t>>::to(m.image.luminance.source); }))
      .function("contributors", optional_override([](const AbsoluteMaps& m) { return Conv<std::vector<int>>::to(maps_contributors(m)); }))
      .function("tiff", optional_override([](const AbsoluteMaps& m) {
                  return guard([&] {
                    const FusedLuminance& L = m.image.luminance;
                    return Conv<std::vector<uint8_t>>::to(
                        float_tiff(m.image.XYZ.data(), L.width, L.height, "CIE XYZ, cd/m2 (tristim absolute, Guarnera 2018)"));
                  }); }))
      .function("readout", optional_override([](const AbsoluteMaps& m, val x, val y, val window) {
                  return guard([&] {
                    return val(maps_readout(m, Conv<int>::from(x), Conv<int>::from(y), wasm::absent(window) ? 1 : Conv<int>::from(window)));
                  }); }))
      .function("measure", optional_override([](const AbsoluteMaps& m, val regions, val white) {
                  return guard([&] {
                    return val(maps_measure(m, Conv<std::vector<AbsoluteRegion>>::from(regions), Conv<Vec3>::from(white)));
                  }); }));

  def<&read_stimuli>("readAbsoluteStimuli");
  def<&series_exposures>("checkAbsoluteSeries");
  def<&fit_absolute>("fitAbsolute");
  emscripten::function("applyAbsolute", &apply_js);
  emscripten::function("applyAbsolute", optional_override([](val p, val f) { return apply_js(p, f, val::undefined(), val::undefined()); }));
  emscripten::function("applyAbsolute", optional_override([](val p, val f, val o) { return apply_js(p, f, o, val::undefined()); }));
  emscripten::function("absoluteExample", &example_js);
  emscripten::function("absoluteExample", optional_override([]() { return example_js(val::undefined()); }));
  def<&white_Guarnera2018>("whiteGuarnera2018");
  def<&white_equal_energy>("whiteEqualEnergy");
  def<&evaluate_absolute>("evaluateAbsolute");
}
