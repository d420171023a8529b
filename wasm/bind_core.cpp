// Binding: version, error codes, built-in data listing.
#include "boundary.hpp"
#include "tristim/data.hpp"
#include "tristim/version.hpp"

using namespace emscripten;
using tristim::wasm::guard;

namespace {
std::string version() { return tristim::kVersion; }
val builtin_files() {
  return guard([] {
    val out = val::array();
    for (const auto& f : tristim::builtin_files()) out.call<void>("push", val(f));
    return out;
  });
}
std::string builtin_file(const std::string& name) {
  return guard([&] { return std::string(tristim::builtin_file(name)); });
}
}  // namespace

EMSCRIPTEN_BINDINGS(tristim_core) {
  function("version", &version);
  function("builtinFiles", &builtin_files);
  function("builtinFile", &builtin_file);
}
