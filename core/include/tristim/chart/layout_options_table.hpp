// The bounds of the numbers a user gives for a chart's grid and its sampling: a custom layout's
// rows, columns, gap and margins (LayoutOptions, layout.hpp) and the sampled area of each patch
// (SampleOptions::area) — one OptionSpec row each, which the page builds its inputs from (labels,
// units, min/max/step/default) and `tristim sample --help` lists.
#pragma once
#include <vector>

#include "tristim/methods.hpp"

namespace tristim {

/// Rows named as the members they bound: rows, columns, gap, margin_left, margin_top,
/// margin_right, margin_bottom (LayoutOptions, chart "custom"), area (SampleOptions). Every value
/// inside a row's [min, max] is one chart_layout() / sample_chart() accept, in any combination
/// (a margin's max is below half, so opposite margins always leave room for patches).
std::vector<OptionSpec> layout_option_table();

}  // namespace tristim
