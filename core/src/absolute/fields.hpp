// Field lists (io/fields.hpp) shared by the absolute recipe, profile and report: an exposure as
// the array [t, N, ISO], the fall-off fit, the section 4.1 figures and the training summary.
#pragma once
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/profile/fields.hpp"

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

TRISTIM_FIELDS(FalloffFit, member<&FalloffFit::p1>("p1"), member<&FalloffFit::p2>("p2"), member<&FalloffFit::p3>("p3"),
               member<&FalloffFit::centre_x>("centre_x"), member<&FalloffFit::centre_y>("centre_y"),
               member<&FalloffFit::r_scale>("r_scale"), member<&FalloffFit::width>("width"),
               member<&FalloffFit::height>("height"), member<&FalloffFit::bins>("bins"),
               member<&FalloffFit::rms_residual>("rms_residual"), member<&FalloffFit::max_residual>("max_residual"));

TRISTIM_FIELDS(AbsoluteMetrics, member<&AbsoluteMetrics::metrics>("metrics"),
               member<&AbsoluteMetrics::relative_Y_error>("relative_Y_error"),
               member<&AbsoluteMetrics::median_absolute_error>("median_absolute_error"),
               member<&AbsoluteMetrics::white>("white"));

TRISTIM_FIELDS(AbsoluteTraining, member<&AbsoluteTraining::luminance_stimuli>("luminance_stimuli"),
               member<&AbsoluteTraining::colour_stimuli>("colour_stimuli"),
               member<&AbsoluteTraining::saturated_stimuli>("saturated_stimuli"),
               member<&AbsoluteTraining::evaluated>("evaluated"), member<&AbsoluteTraining::figures>("figures"));

}  // namespace tristim::fields
