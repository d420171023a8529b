// Parsing the bytes of a named input (a file on the command line) so that every error names it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "tristim/error.hpp"

namespace tristim {

/// parse(data, size) on `bytes`, the contents of the input called `name` (a file path); a
/// tristim::Error it throws comes out with the same code and "'<name>': " before its message.
template <class Parse>
auto parse_named(const std::string& name, const std::string& bytes, Parse&& parse) {
  try {
    return parse(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  } catch (const Error& e) {
    throw Error(e.code(), "'" + name + "': " + e.what());
  }
}

}  // namespace tristim
