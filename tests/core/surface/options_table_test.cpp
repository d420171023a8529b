// The surface step's number rows (surface_option_table, the page's inputs and --help) against the
// checks fit_surface() and geometry_experiment_Abed2013() make: a row's default and its bounds are
// accepted, a value past either bound is refused with a coded error naming the option.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "option_rows.hpp"
#include "test_support.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/surface/fit.hpp"
#include "tristim/surface/geometry_table.hpp"
#include "tristim/surface/options_table.hpp"

using namespace tristim;

namespace {

/// The row `name` of surface_option_table().
OptionSpec row(const std::string& name) {
  const auto rows = surface_option_table();
  const auto it = std::find_if(rows.begin(), rows.end(), [&](const OptionSpec& o) { return o.name == name; });
  REQUIRE(it != rows.end());
  return *it;
}

// The built-in SG spectra, 380-730 nm at 10 nm (core/data).
SpectralData sg() {
  return read_spectral_csv(test::read_test_file("core/data/charts/colorcheckerSG_before_nov2014_reflectance_380-730_10nm.csv"),
                           "dcamprof SG before 2014");
}

/// fit_surface of the SG onto itself over [lo, hi]: "" when it fits, else the error's code name
/// and message.
std::pair<std::string, std::string> fit_over(const SpectralData& d, double lo, double hi) {
  SurfaceFitOptions o;
  o.range_min = lo;
  o.range_max = hi;
  try {
    fit_surface({"scaler", {}, {}}, d, d, o);
  } catch (const Error& e) {
    return {error_code_name(e.code()), e.what()};
  }
  return {"", ""};
}

}  // namespace

TEST_CASE("surface option table: its rows, units and steps", "[surface][catalog]") {
  for (const OptionSpec& o : surface_option_table()) CHECK(o.type == "number");
  CHECK(tristim::test::check_number_rows(surface_option_table(), true) == "range_min range_max noise ");
  CHECK(row("range_min").unit == "nm");
  CHECK(row("range_min").default_number < row("range_max").default_number);
}

TEST_CASE("surface option table: fit_surface refuses a range past the rows' bounds", "[surface][catalog]") {
  const SpectralData d = sg();
  const double lo = row("range_min").default_number, hi = row("range_max").default_number;
  CHECK(fit_over(d, lo, hi).first == "");
  for (const char* name : {"range_min", "range_max"}) {
    const OptionSpec o = row(name);
    for (double past : {o.min - 1, o.max + 1}) {
      INFO(name << " = " << past);
      const bool first = std::string(name) == "range_min";
      const auto [code, message] = fit_over(d, first ? past : lo, first ? hi : past);
      CHECK(code == "INVALID_ARGUMENT");
      CHECK(message.find(name) != std::string::npos);
    }
  }
  // At a bound the range is the rows' to take: the SG's 380-730 nm does not cover 300 nm, which
  // the data refuses (WavelengthMismatch), not the bound.
  CHECK(fit_over(d, row("range_min").min, hi).first == "WAVELENGTH_MISMATCH");
  // "both 0" stays the overlap of the two sets.
  CHECK(fit_over(d, 0, 0).first == "");
}

TEST_CASE("surface option table: the simulated Table IV refuses a noise past the row's bounds", "[surface][catalog]") {
  const OptionSpec o = row("noise");
  for (double ok : {o.min, o.default_number, o.max}) {
    INFO("noise " << ok);
    CHECK(geometry_experiment_Abed2013("Nikon_D850", "D50", ok, 1).training.size() == 4);
  }
  for (double past : {o.min - 1e-6, o.max + 1e-6}) {
    INFO("noise " << past);
    try {
      geometry_experiment_Abed2013("Nikon_D850", "D50", past, 1);
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.code() == ErrorCode::InvalidArgument);
      CHECK(std::string(e.what()).find("noise") != std::string::npos);
    }
  }
}
