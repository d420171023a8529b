#include "test_support.hpp"
#include "tristim/data.hpp"
#include "tristim/error.hpp"

using namespace tristim;

TEST_CASE("error codes have stable upper-snake names", "[error]") {
  CHECK(std::string(error_code_name(ErrorCode::MissingColumn)) == "MISSING_COLUMN");
  CHECK(std::string(error_code_name(ErrorCode::TooFewPatches)) == "TOO_FEW_PATCHES");
  Error e(ErrorCode::NonFinite, "x");
  CHECK(std::string(e.code_name()) == "NON_FINITE");
  CHECK(std::string(e.what()) == "x");
}

TEST_CASE("an unknown built-in data file is a coded error", "[data]") {
  try {
    builtin_file("no/such/file.csv");
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::UnknownId);
  }
}
