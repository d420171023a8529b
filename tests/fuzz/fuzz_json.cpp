// The JSON parser (io/json.hpp) and the writer on what it accepted: dump(parse(x)) must parse.
#include "fuzz_support.hpp"
#include "tristim/io/json.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::json::Value v = tristim::json::parse(input);
  tristim::json::parse(v.dump());
  tristim::json::parse(v.dump(2));
})
