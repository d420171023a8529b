// The lab tests' bad-option cases: default options with one change, refused with a code.
#pragma once
#include "test_support.hpp"

namespace tristim::test {

/// Options built by default, changed by `set`, then given to `run`, which must throw `code`.
template <class Options, class Set, class Run>
void require_refused(ErrorCode code, Set set, Run run) {
  Options o;
  set(o);
  require_code([&] { run(o); }, code);
}

}  // namespace tristim::test
