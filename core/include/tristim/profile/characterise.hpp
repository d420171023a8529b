// From a recipe and its inputs to a profile: the one data path the CLI and the page share.
//
//   chart sample (or patch tables) ─┐
//   reference (built-in chart → surface stage → illuminant/observer, or a file) ─┴→ training set
//   → linearisation stage → model + objective → training / leave-one-out metrics → profile
//
// The profile embeds the (completed) recipe, so `tristim fit --recipe` on the same inputs
// reproduces it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/capture/raw.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/profile/recipe.hpp"

namespace tristim {

struct LightTrap;

/// The reference of a recipe whose reference.chart is built in: the chart's reflectances through
/// the surface stage (surface/surface.hpp), integrated under reference.illuminant and
/// reference.observer. Error(InvalidArgument) when reference.chart is "file" (read the file and
/// use reference_from_table instead).
ReferenceChart recipe_reference(const Recipe& recipe);

/// Patches that go into the fit, paired by id.
struct TrainingSet {
  std::vector<std::string> ids;       ///< the patches' keys (normalise_patch_id): what pairs and digests use
  std::vector<std::string> labels;    ///< the same patches as the user's data spell them (a reference or
                                      ///< patch file's "A01", "Q001"): what per-patch outputs write
  PatchMatrix camera_RGB;     ///< as sampled (before the linearisation stage), N × 3
  PatchMatrix reference_XYZ;  ///< N × 3, Y = 100 for the perfect diffuser
  std::vector<std::string> excluded;  ///< ids left out, with the reason: "A3 (nonuniform)"
  /// From a chart sample (training_set of a ChartSample): true, and `missing` its patches outside
  /// the frame (normalised ids, layout order), which characterise() records in the profile's
  /// recipe (sampling.missing). From tables: false, and the recipe's record is kept as it is.
  bool sampled = false;
  std::vector<std::string> missing;
  /// Several charts (training_union): each chart's name and the rows that came from it (a row
  /// merged from several charts is listed under each). Empty for one chart.
  std::vector<std::string> chart_names;
  std::vector<std::vector<int>> chart_rows;
};

/// Pairs a chart sample with a reference by patch id, leaving out the recipe's sampling.exclude
/// ids and the patches flagged as sampling.exclude_flags (or, with exclude_flagged, any flag)
/// names (excluding_flags, recipe.hpp); the patches of a chart cut by the
/// frame (sample.missing) are listed in `excluded` as "D1 (outside the frame)". Error(PatchMismatch) when a
/// sampled patch is not in the reference; Error(TooFewPatches) when nothing is left. Labels: the
/// reference's (a user file's own spelling; the layout's ids for a built-in chart).
TrainingSet training_set(const Recipe& recipe, const ChartSample& sample, const ReferenceChart& reference);
/// How a recipe's chart is sampled: its sampling stage's area, and a chart cut by the frame
/// sampled where it is inside (SampleOptions::partial), as the page samples it.
SampleOptions recipe_sample_options(const SamplingStage& sampling);

/// The chart of a one-image recipe sampled on `image`: the one path of `tristim fit --recipe
/// --raw` and of a share link sampled again from its image (the page samples with the same
/// options). The recipe's layout, corners and area; a chart cut by the frame is sampled where it
/// is inside (ChartSample::missing names the patches whose sample area leaves the image, which
/// training_set records as left out; CornersOutside when no patch is inside); the recipe's light
/// trap, if any, measured again on this image (Abed 2013 App. C step 1) and subtracted (`trap`,
/// when given, receives it). A stored (TIFF/PNG/JPEG) image sets capture.saturation when the
/// recipe has none. Error(InvalidArgument) when the recipe has no corners.
ChartSample sample_recipe_chart(Recipe& recipe, const RawImage& image, LightTrap* trap = nullptr);

/// The same from paired tables (rows already matched by id). `ids` as the user's file spells them
/// (or already normalised): they are the labels, their normalised forms the keys.
TrainingSet training_set(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& camera_RGB,
                         const PatchMatrix& reference_XYZ);

/// The frames of one image of a recipe with several, decoded (Abed 2013 App. C steps 1-2, as
/// `sample --dark --flat` takes them for one image): dark frames, averaged and subtracted in
/// entry.capture.dark_mode; at most one flat field, per pixel or, when entry.capture.falloff, as
/// the radial fall-off fit (Guarnera 2018 eq 7). Empty: the image is used as decoded.
struct RecipeImageFrames {
  std::vector<RawImage> darks;
  std::vector<RawImage> flat;
};

/// The chart samples of one image of a recipe with several (issue 48). `bytes`: the image file
/// (RAW, TIFF, PNG, JPEG); its SHA-256 is recorded in entry.sha256 and, for a stored (non-linear)
/// image, its full scale in entry.capture.saturation when that is 0. `frames`, if any, calibrate
/// it (entry.capture.dark_frames and flat_field / falloff record what was applied). The light
/// trap, if any, is measured again on this image after its dark frame (Abed 2013 App. C step 1;
/// the flare recorded in entry.capture.flare) and subtracted; then the chart is sampled at
/// entry.sampling.corners, or, when they are all 0, detected (chart/detect.hpp, looking for the
/// layout's chart) and the candidate(s) entry.candidate names sampled: the best by default, "all",
/// or one index. Every error names the image ("images[1] ('b.dng'): …") and keeps its code: a
/// file that does not decode (RawUnsupported, …), FrameMismatch (a frame of another size or
/// camera), InvalidArgument (two flats; a candidate index beyond those found), ChartNotFound, the
/// sampling's codes.
std::vector<ChartSample> sample_recipe_image(RecipeImage& entry, size_t index, const std::uint8_t* bytes, size_t size,
                                             const RecipeImageFrames& frames = {});

/// The recipe an image entry trains with: `recipe` with the entry's reference, capture and
/// sampling stages in place of its own (and no images).
Recipe image_recipe(const Recipe& recipe, const RecipeImage& entry);

/// One chart of several: its name ("b.dng", "b.dng #2" for a second candidate) and its training set.
struct ChartPart {
  std::string name;
  TrainingSet training;
};
/// The union of several charts' training sets, in order: chart k's (from 1) ids and labels become
/// "k:A1". With recipe.duplicates "each" that is the concatenation of their rows. With "once"
/// (the default), rows of the same colour — the same patch id and bit-identical reference XYZ, e.g.
/// two shots of one chart — become one row "1+2:A1" whose camera RGB is their mean, so each colour
/// weighs once in the fit. Error(TooFewPatches) when nothing is left.
TrainingSet training_union(const Recipe& recipe, const std::vector<ChartPart>& charts);

struct Characterisation {
  Recipe recipe;                 ///< completed
  Linearisation linearisation;   ///< the fitted linearisation stage (identity for RAW)
  PatchMatrix linear_RGB;        ///< the training camera RGB after linearisation
  PatchMatrix reference_XYZ;     ///< the training reference XYZ as fitted (after a joint surface fit)
  ModelEvaluation evaluation;    ///< fit, training and leave-one-out metrics
  int white_index = -1;          ///< row of the preserved white patch, or -1
  /// The surface correction the training reference went through: the recipe's, or, when its
  /// `fit` option is "joint", the Phase II result (fit "fixed", so it reproduces that reference).
  MethodChoice surface{"none", {}, {}};
  std::string surface_status;    ///< Phase II only: "ok", "at_bound", "iteration_limit" (+ message)
  Profile profile;               ///< embeds the recipe
};

/// Runs the linearisation, characterisation and evaluation stages of `recipe` on `training`.
/// A surface stage with fit "joint" (Phase II, surface/joint.hpp) is fitted here, on the linear
/// RGB, jointly with a 3×3 anchored to the white patch (characterisation.white_patch, required:
/// it stands in for the paper's PTFE, its reflectance taken as flat at its measured Y/Y_white);
/// the training reference XYZ are then those of the fitted correction. Needs a built-in chart.
Characterisation characterise(const Recipe& recipe, const TrainingSet& training);

/// Figures of one chart of a fit on several (training_union): mean/max CIEDE2000 over its rows in
/// training and leave-one-out, and held out — the model fitted (same objective and options) on
/// the rows of the other charts only and evaluated on this chart's (Abed 2013 Table IV's
/// train-on-one, test-on-another); no held-out figure when the other charts' rows are too few.
struct ChartFigures {
  std::string name;
  int patches = 0;
  Summary training_dE00;
  bool has_loo = false;
  Summary loo_dE00;
  bool has_held_out = false;
  Summary held_out_dE00;
  std::string held_out_error;  ///< why there is no held-out figure ("" when there is one)
};
/// One entry per chart of `training` (none for a single chart).
std::vector<ChartFigures> chart_figures(const Characterisation& c, const TrainingSet& training);

}  // namespace tristim

// ChartFigures' field list (io/fields.hpp), defined in characterise.cpp: {"chart", "patches",
// "training": {"dE00_mean", "dE00_max"} (null for a chart without patches), "loo": {…} (null without
// leave-one-out), "held_out": {…} (null without a held-out figure), "held_out_error"} — what
// `tristim fit` writes as the profile's "charts" and what FitOutcome.charts is in JS.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(ChartFigures);
}  // namespace tristim::fields
