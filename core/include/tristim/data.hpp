// Standard tables compiled into the library from core/data (origin: core/data/SOURCES.md).
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "tristim/error.hpp"

namespace tristim {

/// Contents of a built-in data file, by its path relative to core/data
/// (e.g. "cmf/cie1931_2deg_360-830_1nm.csv"). Throws Error(UnknownId) if there is none.
std::string_view builtin_file(std::string_view name);

/// Every built-in data file name, sorted.
std::vector<std::string> builtin_files();

}  // namespace tristim
