// The custom grid's and the sampling's option rows (bounds as chart_layout() and sample_chart()
// check them: tests/core/chart/layout_options_table_test.cpp holds the two together).
#include "tristim/chart/layout_options_table.hpp"

#include <string>

#include "tristim/chart/layout.hpp"

namespace tristim {

namespace {

OptionSpec with_form(OptionSpec o, double step, const std::string& unit) {
  o.step = step;
  o.unit = unit;
  return o;
}

}  // namespace

std::vector<OptionSpec> layout_option_table() {
  // chart_layout(): a custom grid has 1..1000 rows and columns, a gap up to 2 patch sizes, margins
  // in [0, 1) whose opposite pairs sum below 0.99 (so 0.49 each always leaves room).
  const char* margin_about = "custom layout: the space between a given corner and the patch grid on that side";
  std::vector<OptionSpec> rows{
      with_form(number_option("rows", "Rows", 4, 1, 1000, "custom layout: patch rows, top to bottom (ids R1C1, R1C2, …)",
                              "integer"), 1, ""),
      with_form(number_option("columns", "Columns", 6, 1, 1000, "custom layout: patch columns, left to right", "integer"), 1,
                ""),
      with_form(number_option("gap", "Gap", 0, 0, 2,
                              "custom layout: the space between neighbouring patches (none outside them: the corners "
                              "are the outer corners of the corner patches)"),
                0.01, "× patch size"),
  };
  for (const auto& [side, across] : {std::pair{"left", "width"}, {"top", "height"}, {"right", "width"}, {"bottom", "height"}})
    rows.push_back(with_form(number_option(std::string("margin_") + side, std::string("Margin ") + side, 0, 0, 0.49,
                                           margin_about),
                             0.01, std::string("fraction of the chart's ") + across));
  // sample_chart(): area in (0, 1]; Abed et al. 2013 App. C step 3 average the central part.
  rows.push_back(with_form(number_option("area", "Sampled area per patch", SampleOptions{}.area, 0.05, 1,
                                         "the central part of each patch averaged (Abed et al. 2013 App. C step 3: "
                                         "0.5, the middle half of each side)"),
                           0.05, "fraction of the patch's side"));
  return rows;
}

}  // namespace tristim
