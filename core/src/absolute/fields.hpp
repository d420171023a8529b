// The field lists (io/fields.hpp) the absolute profile, recipe and report are written with: the
// exposure's codec and the declarations (a binding and the CLI see them) are in
// tristim/absolute/fields.hpp, the lists of the report's parts (training summary, section 4.1
// figures, fit summary) are defined in report.cpp; the fall-off fit's list is declared in
// tristim/capture/calibration.hpp and defined in calibration.cpp.
#pragma once
#include "tristim/absolute/fields.hpp"
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/profile/fields.hpp"
