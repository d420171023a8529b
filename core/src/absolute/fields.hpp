// The JSON form of ExposureSettings shared by the absolute recipe, profile and report: the array
// [t, N, ISO] (io/fields.hpp's Codec, so structs list it as an ordinary member).
#pragma once
#include "tristim/absolute/normalisation.hpp"
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

}  // namespace tristim::fields
