// The field lists (io/fields.hpp) of the absolute mode's structs that cross a boundary — the
// recipe and its parts, the training figures, the maps summary, the pointer read-out, the sensitivity
// estimate and its uncertainty, the options of applying a profile and of its report, and the report — declared here so a binding converts them by their lists
// and the CLI writes them by the same lists, and defined once in core/src/absolute (recipe.cpp,
// report.cpp). An exposure is the array [t, N, ISO] wherever it is written.
#pragma once
#include <array>

#include "tristim/absolute/characterise.hpp"
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/absolute/report.hpp"
#include "tristim/absolute/sensitivities.hpp"
#include "tristim/io/fields.hpp"

namespace tristim::fields {

template <>
struct Codec<ExposureSettings> {
  static json::Value write(const ExposureSettings& e) {
    return json::Value(std::vector<double>{e.exposure_s, e.f_number, e.iso});
  }
  static void read(const json::Value& v, ExposureSettings& e, const Context& c, const std::string& path) {
    std::array<double, 3> x{};
    fields::read(v, x, c, path);
    e = {x[0], x[1], x[2]};
  }
};

TRISTIM_FIELDS_DECLARE(AbsoluteStimulus);
TRISTIM_FIELDS_DECLARE(AbsoluteSensitivities);
TRISTIM_FIELDS_DECLARE(AbsoluteInputs);
TRISTIM_FIELDS_DECLARE(AbsoluteOptions);
TRISTIM_FIELDS_DECLARE(AbsoluteRecipe);
TRISTIM_FIELDS_DECLARE(AbsoluteMetrics);
TRISTIM_FIELDS_DECLARE(AbsoluteTraining);
TRISTIM_FIELDS_DECLARE(AbsoluteFitSummary);
TRISTIM_FIELDS_DECLARE(AbsoluteMapsSummary);
TRISTIM_FIELDS_DECLARE(AbsoluteReadout);
TRISTIM_FIELDS_DECLARE(AbsoluteApplyOptions);
TRISTIM_FIELDS_DECLARE(AbsoluteEvaluateOptions);
TRISTIM_FIELDS_DECLARE(SensitivityUncertainty);
TRISTIM_FIELDS_DECLARE(SensitivityEstimate);
TRISTIM_FIELDS_DECLARE(AbsoluteReport);

}  // namespace tristim::fields
