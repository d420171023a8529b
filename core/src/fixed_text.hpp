// A number as fixed-point text for messages ("0.25"), the same characters in every locale-free build.
#pragma once
#include <ios>
#include <sstream>
#include <string>

namespace tristim {

/// v with `digits` digits after the point (std::fixed), e.g. fixed_text(2.0 / 3, 2) = "0.67".
inline std::string fixed_text(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace tristim
