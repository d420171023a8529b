// The recipe's data path: reference → training set → linearisation → fit → evaluation → profile.
#include "tristim/profile/characterise.hpp"

#include <algorithm>
#include <cstring>
#include <map>

#include "tristim/capture/calibration.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/chart/light_trap.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/error.hpp"
#include "tristim/share/sha256.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/surface/joint.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim {

ReferenceChart recipe_reference(const Recipe& in) {
  const Recipe r = complete_recipe(in);
  if (r.reference.chart == "file")
    throw Error(ErrorCode::InvalidArgument, "the recipe's reference is a file: read it with reference_from_table");
  const SpectralData reflectances = correct_surface(r.surface, chart_reflectances(r.reference.chart));
  ReferenceChart ref = reference_from_spectra(reflectances, illuminant_spd(r.reference.illuminant),
                                              parse_observer(r.reference.observer));
  ref.chart_id = r.reference.chart;
  return ref;
}

namespace {

bool listed(const std::vector<std::string>& list, const std::string& id) {
  return std::find(list.begin(), list.end(), id) != list.end();
}

TrainingSet finish(std::vector<std::string> ids, std::vector<std::string> labels, std::vector<Vec3> rgb,
                   std::vector<Vec3> xyz, std::vector<std::string> excluded) {
  if (ids.empty()) throw Error(ErrorCode::TooFewPatches, "every patch was left out: nothing to fit");
  TrainingSet t;
  t.ids = std::move(ids);
  t.labels = std::move(labels);
  t.excluded = std::move(excluded);
  t.camera_RGB.resize(static_cast<Eigen::Index>(rgb.size()), 3);
  t.reference_XYZ.resize(static_cast<Eigen::Index>(xyz.size()), 3);
  for (size_t i = 0; i < rgb.size(); ++i) {
    t.camera_RGB.row(i) = rgb[i].transpose();
    t.reference_XYZ.row(i) = xyz[i].transpose();
  }
  return t;
}

bool joint_surface(const MethodChoice& surface) {
  const auto it = surface.settings.find("fit");
  return it != surface.settings.end() && it->second == "joint";
}

// Phase II (Abed, Berns & Masaoka 2013, Fig. 3) on the training set: the surface coefficients
// jointly with a 3×3 anchored to the white patch; returns the training reference XYZ of the
// fitted correction and records it in c.surface.
PatchMatrix joint_surface_XYZ(Characterisation& c, const TrainingSet& t) {
  const Recipe& r = c.recipe;
  if (r.reference.chart == "file")
    throw Error(ErrorCode::InvalidArgument, "the joint surface fit (Phase II) corrects a built-in chart's spectra; "
                                            "the reference is a file");
  const std::string white = normalise_patch_id(r.characterisation.white_patch);
  if (white.empty())
    throw Error(ErrorCode::IllPosed, "the joint surface fit (Phase II) is anchored to a white reference: set the "
                                     "characterisation's white_patch (the chart's white), or the fit would shrink "
                                     "the reference to lower its error");
  const SpectralData all = chart_reflectances(r.reference.chart);
  SpectralData mine{all.wavelengths, {}, {}, all.linear};
  int w = -1;
  for (size_t i = 0; i < t.ids.size(); ++i) {
    size_t k = 0;
    while (k < all.names.size() && normalise_patch_id(all.names[k]) != t.ids[i]) ++k;
    if (k == all.names.size())
      throw Error(ErrorCode::PatchMismatch, "patch '" + t.ids[i] + "' has no spectrum in chart " + r.reference.chart);
    mine.names.push_back(t.ids[i]);
    mine.values.push_back(all.values[k]);
    if (t.ids[i] == white) w = static_cast<int>(i);
  }
  if (w < 0) throw Error(ErrorCode::UnknownId, "white patch '" + white + "' is not in the training set");
  const SpectralData illuminant = illuminant_spd(r.reference.illuminant);
  const Observer observer = parse_observer(r.reference.observer);
  const ReferenceChart measured = reference_from_spectra(mine, illuminant, observer);
  JointFitOptions o;
  o.illuminant = illuminant;
  o.observer = observer;
  o.white_RGB = c.linear_RGB.row(w).transpose();
  o.white_reflectance = measured.XYZ[w][1] / measured.white[1];  // the white patch taken as flat
  const JointFitResult j = fit_surface_joint_Abed2013(r.surface, c.linear_RGB, mine, o);
  c.surface = j.choice;
  c.surface.settings["fit"] = "fixed";
  c.surface_status = j.status + (j.message.empty() ? "" : ": " + j.message);
  const ReferenceChart corrected = reference_from_spectra(correct_surface(c.surface, mine), illuminant, observer);
  PatchMatrix XYZ(static_cast<Eigen::Index>(t.ids.size()), 3);
  for (size_t i = 0; i < t.ids.size(); ++i) XYZ.row(static_cast<Eigen::Index>(i)) = corrected.XYZ[i].transpose();
  return XYZ;
}

}  // namespace

TrainingSet training_set(const Recipe& in, const ChartSample& sample, const ReferenceChart& reference) {
  const Recipe r = complete_recipe(in);
  std::vector<std::string> ids, labels, excluded;
  std::vector<Vec3> rgb, xyz;
  // A reference handed over without labels (or with a different number of them) is labelled by its ids.
  const bool labelled = reference.labels.size() == reference.ids.size();
  const auto row_of = [&reference](const std::string& id) {  // the reference row of a normalised id, or its size
    size_t k = 0;
    while (k < reference.ids.size() && normalise_patch_id(reference.ids[k]) != id) ++k;
    return k;
  };
  // The one pairing (pair_by_id, chart/reference.hpp: the sample's order), as the CLI's --rgb/--xyz.
  std::vector<std::string> sampled_ids;
  std::vector<Vec3> means;
  for (const PatchSample& p : sample.patches) {
    sampled_ids.push_back(p.id);
    means.emplace_back(p.mean[0], p.mean[1], p.mean[2]);
  }
  const PatchPairs pairs = sample.patches.empty() ? PatchPairs{} : pair_by_id(reference.ids, reference.XYZ, sampled_ids, means);
  if (!pairs.missing_in_reference.empty())
    throw Error(ErrorCode::PatchMismatch, "sampled patch '" + pairs.missing_in_reference.front() + "' is not in the reference");
  for (size_t i = 0; i < pairs.ids.size(); ++i) {
    const PatchSample& p = sample.patches[static_cast<size_t>(pairs.measured_rows[i])];
    const std::string& id = pairs.ids[i];
    const size_t k = static_cast<size_t>(pairs.reference_rows[i]);
    const std::string& label = labelled ? reference.labels[k] : reference.ids[k];
    if (listed(r.sampling.exclude, id)) {
      excluded.push_back(label + " (excluded)");
      continue;
    }
    if (const std::string why = excluding_flags(r.sampling, p.flags); !why.empty()) {
      excluded.push_back(label + " (" + why + ")");
      continue;
    }
    ids.push_back(id);
    labels.push_back(label);
    rgb.push_back(pairs.measured[i]);
    xyz.push_back(pairs.reference[i]);
  }
  std::vector<std::string> missing;
  for (const std::string& m : sample.missing) {  // a chart cut by the frame: these were not sampled
    missing.push_back(normalise_patch_id(m));
    const size_t k = row_of(missing.back());
    excluded.push_back((k < reference.ids.size() && labelled ? reference.labels[k] : m) + " (outside the frame)");
  }
  TrainingSet t = finish(std::move(ids), std::move(labels), std::move(rgb), std::move(xyz), std::move(excluded));
  t.sampled = true;
  t.missing = std::move(missing);
  return t;
}

TrainingSet training_set(const Recipe& in, const std::vector<std::string>& in_ids, const PatchMatrix& camera_RGB,
                         const PatchMatrix& reference_XYZ) {
  const Recipe r = complete_recipe(in);
  if (camera_RGB.rows() != reference_XYZ.rows() || static_cast<Eigen::Index>(in_ids.size()) != camera_RGB.rows())
    throw Error(ErrorCode::PatchMismatch, "ids, camera RGB and reference XYZ differ in length");
  std::vector<std::string> ids, labels, excluded;
  std::vector<Vec3> rgb, xyz;
  for (size_t i = 0; i < in_ids.size(); ++i) {
    const std::string id = normalise_patch_id(in_ids[i]);
    if (listed(r.sampling.exclude, id)) {
      excluded.push_back(in_ids[i] + " (excluded)");
      continue;
    }
    ids.push_back(id);
    labels.push_back(in_ids[i]);
    rgb.push_back(camera_RGB.row(i).transpose());
    xyz.push_back(reference_XYZ.row(i).transpose());
  }
  return finish(std::move(ids), std::move(labels), std::move(rgb), std::move(xyz), std::move(excluded));
}

namespace {

/// What a recipe's capture stage does to a chart image before it is sampled, on both paths (one
/// image, or an entry of `images`): a stored (TIFF/PNG/JPEG) image's full scale becomes the
/// saturation when none is set, and the light trap, if any, is measured again on this image
/// (Abed 2013 App. C step 1; after the dark frame of `frames` when given) and its flare added to
/// `cal`. Returns the trap (all 0 without one).
LightTrap capture_on_image(CaptureStage& cap, const RawImage& image, const SampleOptions& so, FrameCalibration& cal,
                           const FrameCalibration* frames) {
  if (image.meta.encoding == "stored" && cap.saturation == 0) cap.saturation = image.meta.white_level;
  if (!cap.has_light_trap()) return {};
  const LightTrap trap = measure_light_trap(image, cap.light_trap, so, frames);
  cal = with_light_trap(cal, trap);
  return trap;
}

}  // namespace

SampleOptions recipe_sample_options(const SamplingStage& sampling) {
  SampleOptions so;
  so.area = sampling.area;
  so.partial = true;  // a chart cut by the frame: the patches inside it (issue 48)
  return so;
}

ChartSample sample_recipe_chart(Recipe& recipe, const RawImage& image, LightTrap* trap) {
  const std::array<double, 8>& corners = recipe.sampling.corners;
  if (std::all_of(corners.begin(), corners.end(), [](double v) { return v == 0; }))
    throw Error(ErrorCode::InvalidArgument, "the recipe has no chart corners to sample the image with");
  const SampleOptions so = recipe_sample_options(recipe.sampling);
  FrameCalibration cal;
  const LightTrap measured = capture_on_image(recipe.capture, image, so, cal, nullptr);
  if (trap && recipe.capture.has_light_trap()) *trap = measured;
  return sample_chart(image, recipe.sampling.layout, corners, so, &cal);
}

// ---- several chart images (issue 48) ------------------------------------------------------

std::vector<ChartSample> sample_recipe_image(RecipeImage& e, size_t index, const std::uint8_t* bytes, size_t size,
                                             const RecipeImageFrames& frames) {
  const std::string named = "images[" + std::to_string(index) + "] ('" + e.name + "'): ";
  try {
    e.sha256 = sha256_hex(bytes, size);
    const RawImage image = decode_any(bytes, size);
    const SampleOptions so = recipe_sample_options(e.sampling);
    FrameCalibration cal;
    if (!frames.darks.empty()) {  // Abed 2013 App. C step 1: this image's own dark frames, averaged
      std::vector<const RawImage*> darks;
      for (const RawImage& d : frames.darks) darks.push_back(&d);
      try {
        cal = with_dark_frames(cal, image, darks, e.capture.dark_mode);
      } catch (const Error& x) {
        throw Error(x.code(), std::string("its dark frames: ") + x.what());
      }
      e.capture.dark_frames = static_cast<int>(darks.size());
    }
    if (frames.flat.size() > 1) throw Error(ErrorCode::InvalidArgument, "one flat field per image, not " + std::to_string(frames.flat.size()));
    if (!frames.flat.empty()) {  // App. C step 2 (per pixel) or Guarnera 2018 eq (7) (radial)
      try {
        cal = with_flat_frame(cal, image, frames.flat[0], e.capture.falloff ? "radial" : "pixel");
      } catch (const Error& x) {
        throw Error(x.code(), std::string("its flat field: ") + x.what());
      }
      e.capture.flat_field = !e.capture.falloff;
    }
    const FrameCalibration frames_only = cal;  // the trap is measured after this image's dark frame
    const LightTrap trap = capture_on_image(e.capture, image, so, cal, &frames_only);
    if (e.capture.has_light_trap()) e.capture.flare = trap.mean;
    // One chart: its patches outside the frame recorded in the entry (as characterise() records a
    // one-image recipe's); several candidates ("all") each have their own, named in the training set.
    const auto one = [&e](ChartSample sample) {
      e.sampling.missing.clear();
      for (const auto& m : sample.missing) e.sampling.missing.push_back(normalise_patch_id(m));
      return std::vector<ChartSample>{std::move(sample)};
    };
    const auto& c = e.sampling.corners;
    if (std::any_of(c.begin(), c.end(), [](double v) { return v != 0; }))
      return one(sample_chart(image, e.sampling.layout, c, so, &cal));
    DetectOptions o;
    o.charts = {e.sampling.layout.chart};
    if (e.sampling.layout.chart == "custom") o.custom = e.sampling.layout;
    const std::vector<ChartCandidate> found = detect_charts(image, o);
    std::vector<ChartSample> samples;
    if (e.candidate == "all") {
      e.sampling.missing.clear();
      for (const auto& k : found) samples.push_back(sample_chart(image, e.sampling.layout, k.corners, so, &cal));
      return samples;
    }
    const size_t k = e.candidate.empty() ? 0 : static_cast<size_t>(std::stoul(e.candidate));
    if (k >= found.size())
      throw Error(ErrorCode::InvalidArgument, "candidate " + e.candidate + " asked for, but " +
                                                  std::to_string(found.size()) + " chart(s) were detected");
    return one(sample_chart(image, e.sampling.layout, found[k].corners, so, &cal));
  } catch (const Error& x) {
    throw Error(x.code(), named + x.what());
  }
}

Recipe image_recipe(const Recipe& recipe, const RecipeImage& e) {
  Recipe r = recipe;
  r.reference = e.reference;
  r.capture = e.capture;
  r.sampling = e.sampling;
  r.images.clear();
  return r;
}

TrainingSet training_union(const Recipe& in, const std::vector<ChartPart>& charts) {
  const Recipe r = complete_recipe(in);
  const bool once = r.duplicates == kDuplicatesOnce;
  std::vector<std::string> ids, labels, excluded;
  std::vector<Vec3> rgb, xyz;
  std::vector<std::vector<int>> of_row;  // the charts (from 1) of each row
  std::map<std::string, size_t> seen;    // patch id + the reference XYZ's bits -> row
  for (size_t k = 0; k < charts.size(); ++k) {
    const TrainingSet& t = charts[k].training;
    const std::string prefix = std::to_string(k + 1) + ":";
    for (size_t i = 0; i < t.ids.size(); ++i) {
      const Vec3 X = t.reference_XYZ.row(static_cast<Eigen::Index>(i)).transpose();
      std::string key = t.ids[i] + '\0';
      key.append(reinterpret_cast<const char*>(X.data()), sizeof(double) * 3);
      const auto at = seen.find(key);
      if (once && at != seen.end()) {  // the same colour again: one row, its camera RGB summed (mean below)
        rgb[at->second] += t.camera_RGB.row(static_cast<Eigen::Index>(i)).transpose();
        of_row[at->second].push_back(static_cast<int>(k + 1));
        continue;
      }
      seen.emplace(key, ids.size());
      ids.push_back(prefix + t.ids[i]);
      labels.push_back(prefix + (t.labels.size() == t.ids.size() ? t.labels[i] : t.ids[i]));
      rgb.push_back(t.camera_RGB.row(static_cast<Eigen::Index>(i)).transpose());
      xyz.push_back(X);
      of_row.push_back({static_cast<int>(k + 1)});
    }
    for (const auto& x : t.excluded) excluded.push_back(prefix + x);
  }
  for (size_t j = 0; j < ids.size(); ++j) {
    if (of_row[j].size() < 2) continue;
    rgb[j] /= static_cast<double>(of_row[j].size());
    std::string prefix;
    for (int k : of_row[j]) prefix += (prefix.empty() ? "" : "+") + std::to_string(k);
    const auto strip = [](const std::string& s) { return s.substr(s.find(':') + 1); };
    ids[j] = prefix + ":" + strip(ids[j]);
    labels[j] = prefix + ":" + strip(labels[j]);
  }
  TrainingSet u = finish(std::move(ids), std::move(labels), std::move(rgb), std::move(xyz), std::move(excluded));
  u.chart_rows.resize(charts.size());
  for (size_t j = 0; j < of_row.size(); ++j)
    for (int k : of_row[j]) u.chart_rows[static_cast<size_t>(k - 1)].push_back(static_cast<int>(j));
  for (const auto& c : charts) u.chart_names.push_back(c.name);
  return u;
}

Characterisation characterise(const Recipe& in, const TrainingSet& t) {
  Characterisation c;
  c.recipe = complete_recipe(in);
  if (t.sampled && c.recipe.images.empty()) c.recipe.sampling.missing = t.missing;  // what the profile was made without
  if (!c.recipe.images.empty() && joint_surface(c.recipe.surface))
    throw Error(ErrorCode::InvalidArgument, "the joint surface fit (Phase II) corrects one built-in chart's spectra; "
                                            "the recipe has " + std::to_string(c.recipe.images.size()) + " images");
  LinearisationData data;
  data.ids = t.ids;
  data.camera_RGB = t.camera_RGB;
  data.reference_XYZ = t.reference_XYZ;
  data.white = c.recipe.characterisation.lab_white;      // the reference's white: greys are neutral under it
  data.full_scale = c.recipe.capture.saturation;         // 255 / 65535 for a stored image (0: max of the data)
  if (c.recipe.reference.chart != "file" && c.recipe.images.empty())  // several charts: no one chart's spectra
    data.reflectances = correct_surface(c.recipe.surface, chart_reflectances(c.recipe.reference.chart));
  c.linearisation = fit_linearisation(c.recipe.linearisation, data);
  c.linear_RGB = linearise(c.linearisation, t.camera_RGB);
  c.surface = c.recipe.surface;
  c.reference_XYZ = joint_surface(c.recipe.surface) ? joint_surface_XYZ(c, t) : t.reference_XYZ;
  const PatchMatrix& reference_XYZ = c.reference_XYZ;
  const FitOptions options = recipe_fit_options(c.recipe, t.ids, c.linear_RGB, reference_XYZ, c.white_index);
  c.evaluation = evaluate_model(c.recipe.characterisation.model, c.linear_RGB, reference_XYZ, options,
                                c.white_index, c.recipe.evaluation.leave_one_out);
  c.profile = make_profile(c.evaluation, options, t.ids, c.linear_RGB, reference_XYZ,
                           c.white_index >= 0 ? t.ids[c.white_index] : "",
                           "");
  c.profile.observer = c.recipe.reference.observer == "1964" ? "CIE 1964 10°" : "CIE 1931 2°";
  c.profile.has_recipe = true;
  c.profile.recipe = c.recipe;
  c.profile.has_training_data = true;
  c.profile.training_labels = t.labels.size() == t.ids.size() ? t.labels : t.ids;
  c.profile.training_camera_RGB = t.camera_RGB;
  c.profile.training_reference_XYZ = t.reference_XYZ;
  if (c.linearisation.choice.method != "identity") {
    // The profile takes the stored values (a JPEG's, a TIFF's) and linearises them itself.
    c.profile.has_linearisation = true;
    c.profile.linearisation = c.linearisation;
    c.profile.training_digest = training_digest(t.ids, t.camera_RGB, reference_XYZ);
    // device 1.0 of the ICC/.cube exports: the encoding's full scale (255, 65535)
    if (c.linearisation.full_scale > 0) c.profile.rgb_max = c.linearisation.full_scale;
  }
  return c;
}

namespace {

PatchMatrix rows_of(const PatchMatrix& m, const std::vector<int>& rows) {
  PatchMatrix out(static_cast<Eigen::Index>(rows.size()), m.cols());
  for (size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = m.row(rows[i]);
  return out;
}

Summary summary_of(const std::vector<double>& v, const std::vector<int>& rows) {
  std::vector<double> x;
  for (int i : rows) x.push_back(v[static_cast<size_t>(i)]);
  return summarize(x);
}

}  // namespace

std::vector<ChartFigures> chart_figures(const Characterisation& c, const TrainingSet& t) {
  std::vector<ChartFigures> out;
  const ModelEvaluation& ev = c.evaluation;
  for (size_t k = 0; k < t.chart_rows.size(); ++k) {
    const std::vector<int>& mine = t.chart_rows[k];
    ChartFigures f;
    f.name = k < t.chart_names.size() ? t.chart_names[k] : std::to_string(k + 1);
    f.patches = static_cast<int>(mine.size());
    if (mine.empty()) {
      out.push_back(f);
      continue;
    }
    f.training_dE00 = summary_of(ev.training.patches.dE00, mine);
    f.has_loo = ev.has_loo;
    if (ev.has_loo) f.loo_dE00 = summary_of(ev.loo.patches.dE00, mine);
    // Held out: fitted on the rows no chart but another gave, evaluated on this chart's rows.
    std::vector<bool> in(static_cast<size_t>(c.linear_RGB.rows()), false);
    for (int i : mine) in[static_cast<size_t>(i)] = true;
    std::vector<int> others;
    for (size_t i = 0; i < in.size(); ++i)
      if (!in[i]) others.push_back(static_cast<int>(i));
    try {
      if (others.empty()) throw Error(ErrorCode::TooFewPatches, "no patch of another chart to train on");
      int white = -1;
      FitOptions o = recipe_fit_options(c.recipe, t.ids, c.linear_RGB, c.reference_XYZ, white);
      if (white >= 0 && in[static_cast<size_t>(white)]) o.preserve_white = false;  // never fitted on what it tests
      const FitResult r = fit(c.recipe.characterisation.model, rows_of(c.linear_RGB, others),
                              rows_of(c.reference_XYZ, others), o);
      const Metrics m = evaluate(predict(r.model, rows_of(c.linear_RGB, mine)), rows_of(c.reference_XYZ, mine), o.white);
      f.has_held_out = true;
      f.held_out_dE00 = m.dE00;
    } catch (const Error& e) {
      f.held_out_error = std::string(e.code_name()) + ": " + e.what();
    }
    out.push_back(f);
  }
  return out;
}

namespace {
using fields::Context;
using fields::Field;

// A summary as the figures write it: its mean and max CIEDE2000.
const fields::FieldList<Summary>& mean_max_fields() {
  static const fields::FieldList<Summary> list = {fields::member<&Summary::mean>("dE00_mean"),
                                                  fields::member<&Summary::max>("dE00_max")};
  return list;
}
bool trained(const ChartFigures& f) { return f.patches > 0; }
bool has_loo(const ChartFigures& f) { return f.has_loo && f.patches > 0; }
bool has_held_out(const ChartFigures& f) { return f.has_held_out; }

/// The summary M as {"dE00_mean", "dE00_max"} when Has(figures), null otherwise; read back with
/// the flag Flag (if any) set to whether it was an object.
template <bool (*Has)(const ChartFigures&), bool ChartFigures::*Flag, Summary ChartFigures::*M>
Field<ChartFigures> mean_max(const char* name) {
  return {name,
          [](const ChartFigures& f) {
            if (!Has(f)) return json::Value();
            json::Value o = json::Value::object();
            fields::write_list(f.*M, mean_max_fields(), o);
            return o;
          },
          [](const json::Value& v, ChartFigures& f, const Context& c, const std::string& p) {
            if constexpr (Flag != nullptr) f.*Flag = !v.is_null();
            if (!v.is_null()) fields::read_list(v, f.*M, mean_max_fields(), c, p);
          }};
}
}  // namespace

namespace fields {
TRISTIM_FIELDS_DEFINE(ChartFigures, member<&ChartFigures::name>("chart"), member<&ChartFigures::patches>("patches"),
                      (mean_max<trained, nullptr, &ChartFigures::training_dE00>("training")),
                      (mean_max<has_loo, &ChartFigures::has_loo, &ChartFigures::loo_dE00>("loo")),
                      (mean_max<has_held_out, &ChartFigures::has_held_out, &ChartFigures::held_out_dE00>("held_out")),
                      member<&ChartFigures::held_out_error>("held_out_error"));
}  // namespace fields

}  // namespace tristim
