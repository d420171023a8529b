// Field lists (io/fields.hpp) shared by the absolute profile and report: the fall-off fit and the
// training summary (the exposure's codec and the declarations a binding sees are in
// tristim/absolute/fields.hpp; the section 4.1 figures' list is in report.cpp).
#pragma once
#include "tristim/absolute/fields.hpp"
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/profile/fields.hpp"

namespace tristim::fields {

TRISTIM_FIELDS(FalloffFit, member<&FalloffFit::p1>("p1"), member<&FalloffFit::p2>("p2"), member<&FalloffFit::p3>("p3"),
               member<&FalloffFit::centre_x>("centre_x"), member<&FalloffFit::centre_y>("centre_y"),
               member<&FalloffFit::r_scale>("r_scale"), member<&FalloffFit::width>("width"),
               member<&FalloffFit::height>("height"), member<&FalloffFit::bins>("bins"),
               member<&FalloffFit::rms_residual>("rms_residual"), member<&FalloffFit::max_residual>("max_residual"));

TRISTIM_FIELDS(AbsoluteTraining, member<&AbsoluteTraining::luminance_stimuli>("luminance_stimuli"),
               member<&AbsoluteTraining::colour_stimuli>("colour_stimuli"),
               member<&AbsoluteTraining::saturated_stimuli>("saturated_stimuli"),
               member<&AbsoluteTraining::evaluated>("evaluated"), member<&AbsoluteTraining::figures>("figures"));

}  // namespace tristim::fields
