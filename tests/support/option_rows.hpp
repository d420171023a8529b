// Checks every engine option table's number rows share (tests of layout, surface, ... tables).
#pragma once

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "tristim/methods.hpp"

namespace tristim::test {

/// Each row is an integer or a number with min < max, its default within them, a step, a label and
/// a description (and a unit when `units`); returns the rows' names, each followed by a space.
inline std::string check_number_rows(const std::vector<OptionSpec>& rows, bool units) {
  std::string names;
  for (const OptionSpec& o : rows) {
    names += o.name + " ";
    INFO(o.name);
    CHECK((o.type == "integer" || o.type == "number"));
    CHECK(o.min < o.max);
    CHECK(o.default_number >= o.min);
    CHECK(o.default_number <= o.max);
    CHECK(o.step > 0);
    CHECK(!o.label.empty());
    CHECK(!o.description.empty());
    if (units) CHECK(!o.unit.empty());
  }
  return names;
}

}  // namespace tristim::test
