// Field lists (io/fields.hpp) shared by the absolute profile and report: the training summary (the
// exposure's codec and the declarations a binding sees are in tristim/absolute/fields.hpp; the
// fall-off fit's list is declared in tristim/capture/calibration.hpp and defined in
// calibration.cpp; the section 4.1 figures' list is in report.cpp).
#pragma once
#include "tristim/absolute/fields.hpp"
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/profile/fields.hpp"

namespace tristim::fields {

TRISTIM_FIELDS(AbsoluteTraining, member<&AbsoluteTraining::luminance_stimuli>("luminance_stimuli"),
               member<&AbsoluteTraining::colour_stimuli>("colour_stimuli"),
               member<&AbsoluteTraining::saturated_stimuli>("saturated_stimuli"),
               member<&AbsoluteTraining::evaluated>("evaluated"), member<&AbsoluteTraining::figures>("figures"));

}  // namespace tristim::fields
