// The recipe's data path: reference → training set → linearisation → fit → evaluation → profile.
#include "tristim/profile/characterise.hpp"

#include <algorithm>

#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
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

TrainingSet finish(std::vector<std::string> ids, std::vector<Vec3> rgb, std::vector<Vec3> xyz,
                   std::vector<std::string> excluded) {
  if (ids.empty()) throw Error(ErrorCode::TooFewPatches, "every patch was left out: nothing to fit");
  TrainingSet t;
  t.ids = std::move(ids);
  t.excluded = std::move(excluded);
  t.camera_RGB.resize(static_cast<Eigen::Index>(rgb.size()), 3);
  t.reference_XYZ.resize(static_cast<Eigen::Index>(xyz.size()), 3);
  for (size_t i = 0; i < rgb.size(); ++i) {
    t.camera_RGB.row(i) = rgb[i].transpose();
    t.reference_XYZ.row(i) = xyz[i].transpose();
  }
  return t;
}

}  // namespace

TrainingSet training_set(const Recipe& in, const ChartSample& sample, const ReferenceChart& reference) {
  const Recipe r = complete_recipe(in);
  std::vector<std::string> ids, excluded;
  std::vector<Vec3> rgb, xyz;
  for (const PatchSample& p : sample.patches) {
    const std::string id = normalise_patch_id(p.id);
    size_t k = 0;
    while (k < reference.ids.size() && normalise_patch_id(reference.ids[k]) != id) ++k;
    if (k == reference.ids.size())
      throw Error(ErrorCode::PatchMismatch, "sampled patch '" + id + "' is not in the reference");
    if (listed(r.sampling.exclude, id)) {
      excluded.push_back(id + " (excluded)");
      continue;
    }
    if (r.sampling.exclude_flagged && !p.flags.empty()) {
      std::string why;
      for (const auto& f : p.flags) why += (why.empty() ? "" : ", ") + f;
      excluded.push_back(id + " (" + why + ")");
      continue;
    }
    ids.push_back(id);
    rgb.emplace_back(p.mean[0], p.mean[1], p.mean[2]);
    xyz.push_back(reference.XYZ[k]);
  }
  return finish(std::move(ids), std::move(rgb), std::move(xyz), std::move(excluded));
}

TrainingSet training_set(const Recipe& in, const std::vector<std::string>& in_ids, const PatchMatrix& camera_RGB,
                         const PatchMatrix& reference_XYZ) {
  const Recipe r = complete_recipe(in);
  if (camera_RGB.rows() != reference_XYZ.rows() || static_cast<Eigen::Index>(in_ids.size()) != camera_RGB.rows())
    throw Error(ErrorCode::PatchMismatch, "ids, camera RGB and reference XYZ differ in length");
  std::vector<std::string> ids, excluded;
  std::vector<Vec3> rgb, xyz;
  for (size_t i = 0; i < in_ids.size(); ++i) {
    const std::string id = normalise_patch_id(in_ids[i]);
    if (listed(r.sampling.exclude, id)) {
      excluded.push_back(id + " (excluded)");
      continue;
    }
    ids.push_back(id);
    rgb.push_back(camera_RGB.row(i).transpose());
    xyz.push_back(reference_XYZ.row(i).transpose());
  }
  return finish(std::move(ids), std::move(rgb), std::move(xyz), std::move(excluded));
}

Characterisation characterise(const Recipe& in, const TrainingSet& t) {
  Characterisation c;
  c.recipe = complete_recipe(in);
  LinearisationData data;
  data.ids = t.ids;
  data.camera_RGB = t.camera_RGB;
  data.reference_XYZ = t.reference_XYZ;
  if (c.recipe.reference.chart != "file")
    data.reflectances = correct_surface(c.recipe.surface, chart_reflectances(c.recipe.reference.chart));
  c.linearisation = fit_linearisation(c.recipe.linearisation, data);
  c.linear_RGB = linearise(c.linearisation, t.camera_RGB);
  const FitOptions options = recipe_fit_options(c.recipe, t.ids, c.linear_RGB, t.reference_XYZ, c.white_index);
  c.evaluation = evaluate_model(c.recipe.characterisation.model, c.linear_RGB, t.reference_XYZ, options,
                                c.white_index, c.recipe.evaluation.leave_one_out);
  c.profile = make_profile(c.evaluation, options, t.ids, c.linear_RGB, t.reference_XYZ,
                           c.white_index >= 0 ? t.ids[c.white_index] : "",
                           "");
  c.profile.observer = c.recipe.reference.observer == "1964" ? "CIE 1964 10°" : "CIE 1931 2°";
  c.profile.has_recipe = true;
  c.profile.recipe = c.recipe;
  return c;
}

}  // namespace tristim
