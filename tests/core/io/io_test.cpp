#include <string>

#include "test_support.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/data.hpp"
#include "tristim/io/patch_files.hpp"

using namespace tristim;

namespace {
/// Runs f, expects tristim::Error with `code` and, when line > 0, "line <line>" in the message.
template <class F>
void expect_error(F&& f, ErrorCode code, int line = 0) {
  try {
    f();
    FAIL("no error thrown, expected " << error_code_name(code));
  } catch (const Error& e) {
    INFO("message: " << e.what());
    CHECK(std::string(e.code_name()) == error_code_name(code));
    if (line > 0) CHECK(std::string(e.what()).find("line " + std::to_string(line)) != std::string::npos);
  }
}
}  // namespace

TEST_CASE("patch ids are normalised: A01 -> A1", "[io]") {
  CHECK(normalise_patch_id("A01") == "A1");
  CHECK(normalise_patch_id("a01") == "A1");
  CHECK(normalise_patch_id(" N10 ") == "N10");
  CHECK(normalise_patch_id("R01C02") == "R1C2");
  CHECK(normalise_patch_id("B00") == "B0");
  CHECK(normalise_patch_id("dark skin") == "dark skin");
  CHECK(normalise_patch_id("12") == "12");
}

TEST_CASE("per-patch CSV: XYZ, Lab, RGB columns, case-insensitive, index column", "[io]") {
  const PatchTable t = read_patch_file("index,Patch,x,y,z\n1,A01,10,20,30\n2,a02,1.5e1,2,3\n", "ref.csv");
  REQUIRE(t.ids == std::vector<std::string>{"A1", "A2"});
  CHECK(t.has_XYZ);
  CHECK_FALSE(t.has_Lab);
  CHECK(t.XYZ[1] == Vec3(15, 2, 3));
  const PatchTable lab = read_patch_file("SAMPLE_ID;LAB_L;LAB_A;LAB_B\r\nA1;50;-2;3\r\n", "x.csv");
  CHECK(lab.has_Lab);
  CHECK(lab.Lab[0] == Vec3(50, -2, 3));
  // "b" is Lab b* next to L and a; "B" is blue next to R and G.
  const PatchTable both = read_patch_file("patch,R,G,B,L,a,b\nD6,0.1,0.2,0.3,40,1,2\n", "x.csv");
  CHECK(both.RGB[0] == Vec3(0.1, 0.2, 0.3));
  CHECK(both.Lab[0] == Vec3(40, 1, 2));
  const PatchTable rgb = read_patch_file("\xEF\xBB\xBFid\tr\tg\tb\n# comment\n\nA1\t1\t2\t3\n", "x.tsv");
  CHECK(rgb.has_RGB);
  CHECK_FALSE(rgb.has_Lab);
  CHECK(rgb.RGB[0] == Vec3(1, 2, 3));
  // Trailing delimiters on every line (spreadsheet export).
  const PatchTable tr = read_patch_file("patch,X,Y,Z,\nA1,1,2,3,\n", "t.csv");
  CHECK(tr.XYZ[0] == Vec3(1, 2, 3));
  // Decimal commas in a ';'-separated file.
  const PatchTable eu = read_patch_file("patch;L;a;b\nA1;50,5;-2,25;3\n", "eu.csv");
  CHECK(eu.Lab[0] == Vec3(50.5, -2.25, 3));
  // Quoted cells may hold the delimiter.
  const PatchTable q = read_patch_file("name,X,Y,Z\n\"white, 9.5\",1,2,3\n", "x.csv");
  CHECK(q.ids[0] == "white, 9.5");
}

TEST_CASE("parse_delimited: cells, quotes, doubled quotes, white space and empty cells", "[io]") {
  // The rules of split_delimited, cell by cell (it builds plain cells from views and quoted ones
  // run by run; the expected cells here are what the rules say, written out by hand).
  const TextTable t = parse_delimited(
      "a,b,c,d,e\n"
      "\"x, y\",plain, padded ,,\"\"\n"
      "\"say \"\"hi\"\"\",ab\"cd\"ef, \" in \" ,\"a\"\"\",\"open, to the end\n",
      "q.csv");
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0] == std::vector<std::string>{"x, y", "plain", "padded", "", ""});
  CHECK(t.rows[1] == std::vector<std::string>{"say \"hi\"", "abcdef", "in", "a\"", "open, to the end"});
}

TEST_CASE("spectral CSV: first column wavelength, one column per patch", "[io]") {
  const PatchTable t = read_patch_file("wavelength_nm,A01,A02\n400,0.1,0.2\n410,0.15,0.25\n420,0.2,0.3\n", "s.csv");
  CHECK(t.format == "csv-spectral");
  CHECK(t.has_spectra);
  CHECK(t.ids == std::vector<std::string>{"A1", "A2"});
  CHECK(t.spectra.wavelengths == std::vector<double>{400, 410, 420});
  CHECK(t.spectra.values[1][2] == 0.3);
  const auto real = read_patch_file(
      test::read_test_file("core/data/charts/colorchecker24_after_nov2014_reflectance_380-730_10nm.csv"), "cc24.csv");
  CHECK(real.ids.size() == 24);
  CHECK(real.ids.front() == "A1");
  CHECK(real.ids.back() == "D6");
}

TEST_CASE("colorimetry reads its built-in tables to the doubles read_spectral_csv reads", "[io][colorimetry]") {
  // colorimetry includes nothing of io, so it reads core/data's CIE tables itself (spectra.cpp).
  auto same = [](const SpectralData& a, const std::string& file) {
    INFO(file);
    const SpectralData b = read_spectral_csv(builtin_file(file), file);
    CHECK(a.wavelengths == b.wavelengths);
    CHECK(a.values == b.values);
  };
  same(cmfs(Observer::CIE1931_2), "cmf/cie1931_2deg_360-830_1nm.csv");
  same(cmfs(Observer::CIE1964_10), "cmf/cie1964_10deg_360-830_1nm.csv");
  CHECK(cmfs(Observer::CIE1931_2).names == std::vector<std::string>{"xbar", "ybar", "zbar"});
  int illuminants = 0;
  for (const std::string& id : illuminant_ids())
    for (const std::string& file : builtin_files())
      if (file.rfind("illuminants/" + id + "_", 0) == 0) {
        same(illuminant_spd(id), file);
        ++illuminants;
      }
  CHECK(illuminants == static_cast<int>(illuminant_ids().size()));
}

TEST_CASE("illuminant CSV: the wavelength and exactly one non-negative value column", "[io]") {
  const SpectralData d = read_illuminant_csv("wavelength_nm,F2\n400,1.5\n410,0\n420,2.25\n", "f2.csv");
  CHECK(d.names == std::vector<std::string>{"F2"});
  CHECK(d.wavelengths == std::vector<double>{400, 410, 420});
  CHECK(d.values[0] == std::vector<double>{1.5, 0, 2.25});
  // A table of several illuminants is refused (the CLI used to take its first column silently).
  expect_error([] { read_illuminant_csv("wavelength_nm,A,D65\n400,1,2\n410,1,2\n", "two.csv"); }, ErrorCode::InvalidArgument);
  expect_error([] { read_illuminant_csv("wavelength_nm,A\n400,1\n410,-0.5\n", "neg.csv"); }, ErrorCode::NegativeValue);
  expect_error([] { read_illuminant_csv("wavelength_nm,A\n400,0\n410,0\n", "zero.csv"); }, ErrorCode::NoUsableData);
  expect_error([] { read_illuminant_csv("wavelength_nm,A\n400,1\n400,1\n", "dup.csv"); }, ErrorCode::NonMonotonic, 3);
  expect_error([] { read_illuminant_csv("wavelength_nm\n400\n", "one.csv"); }, ErrorCode::MissingColumn, 1);
}

TEST_CASE("CGATS: Argyll .cie with spectra in percent, and a Lab reference", "[io]") {
  const PatchTable t = read_patch_file(test::read_test_file("tests/data/copyleft/dcamprof/cc24_ref-new.cie"), "cc24_ref-new.cie");
  CHECK(t.format == "cgats");
  REQUIRE(t.ids.size() == 24);
  CHECK(t.ids[0] == "A1");
  CHECK(t.has_XYZ);
  CHECK(t.has_RGB);
  REQUIRE(t.has_spectra);
  CHECK(t.spectra.wavelengths.front() == 380);
  CHECK(t.spectra.wavelengths.back() == 730);
  CHECK(t.spectra.values[0][0] == Approx(0.051603));  // 5.1603 % -> fraction
  CHECK(t.XYZ[0][1] == Approx(10.43));
  CHECK(t.keywords.at("ORIGINATOR") == "ColorChecker24 - November2014 and newer");
  const PatchTable lab = read_patch_file(test::read_test_file(test::debian::argyll_colorchecker_cie), "ColorChecker.cie");
  REQUIRE(lab.ids.size() == 24);
  CHECK(lab.has_Lab);
  CHECK(lab.Lab[0] == Vec3(37.99, 13.56, 14.06));
  // SAMPLE_LOC ids and XYZ + Lab (Passport by Ben Goren)
  const PatchTable pp =
      read_patch_file(test::read_test_file(test::debian::argyll_passport_cie), "ColorCheckerPassport.cie");
  CHECK(pp.ids.size() == 50);
  CHECK(pp.has_XYZ);
  CHECK(pp.has_Lab);
}

TEST_CASE("CGATS: i1Profiler-style export with SampleID, SAMPLE_NAME and nm columns", "[io]") {
  const std::string text =
      "CGATS.17\nORIGINATOR\t\"i1Profiler\"\nNUMBER_OF_FIELDS\t6\nBEGIN_DATA_FORMAT\nSampleID\tSAMPLE_NAME\tnm380\tnm390\tnm400\t"
      "nm410\nEND_DATA_FORMAT\nNUMBER_OF_SETS\t2\nBEGIN_DATA\n1\tA01\t0.05\t0.06\t0.07\t0.08\n2\tA02\t0.1\t0.2\t0.3\t0.4\n"
      "END_DATA\n";
  const PatchTable t = read_patch_file(text, "export.txt");
  CHECK(t.ids == std::vector<std::string>{"A1", "A2"});  // SAMPLE_NAME, not the numeric SampleID
  REQUIRE(t.has_spectra);
  CHECK(t.spectra.wavelengths == std::vector<double>{380, 390, 400, 410});
  CHECK(t.spectra.values[1][3] == 0.4);
}

TEST_CASE("Argyll .ti2-style SAMPLE_ID numbers next to SAMPLE_LOC patch names", "[io]") {
  const PatchTable t = read_patch_file(
      "CTI2\nBEGIN_DATA_FORMAT\nSAMPLE_ID SAMPLE_LOC XYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\nBEGIN_DATA\n1 \"A01\" 1 2 3\n2 \"A02\" 4 5 6\n"
      "END_DATA\n",
      "chart.ti2");
  CHECK(t.ids == std::vector<std::string>{"A1", "A2"});
  // Only numeric ids: the first id column is used.
  const PatchTable n = read_patch_file("SAMPLE_ID,X,Y,Z\n1,1,2,3\n2,1,2,3\n", "n.csv");
  CHECK(n.ids == std::vector<std::string>{"1", "2"});
}

TEST_CASE("every malformed input gives its error code and line", "[io][errors]") {
  SECTION("empty file") {
    expect_error([] { read_patch_file("", "a.csv"); }, ErrorCode::EmptyFile);
    expect_error([] { read_patch_file("\n\n  \n", "a.csv"); }, ErrorCode::EmptyFile);
    expect_error([] { read_patch_file("patch,X,Y,Z\n", "a.csv"); }, ErrorCode::EmptyFile);
    expect_error([] { read_patch_file("", "a.ti3"); }, ErrorCode::EmptyFile);
    expect_error([] { read_patch_file("wavelength,A1\n", "s.csv"); }, ErrorCode::EmptyFile);
  }
  SECTION("missing column") {
    expect_error([] { read_patch_file("patch,X,Y\nA1,1,2\n", "a.csv"); }, ErrorCode::MissingColumn, 1);
    expect_error([] { read_patch_file("patch,foo\nA1,1\n", "a.csv"); }, ErrorCode::MissingColumn, 1);
    expect_error([] { read_patch_file("wavelength\n400\n", "s.csv"); }, ErrorCode::MissingColumn, 1);
    expect_error([] {
      read_patch_file("CTI3\nBEGIN_DATA_FORMAT\nSAMPLE_ID LAB_L LAB_A\nEND_DATA_FORMAT\nBEGIN_DATA\nA1 1 2\nEND_DATA\n", "a.ti3");
    }, ErrorCode::MissingColumn, 2);  // the BEGIN_DATA_FORMAT line
  }
  SECTION("non-numeric cell") {
    expect_error([] { read_patch_file("patch,X,Y,Z\nA1,1,2,3\nA2,1,two,3\n", "a.csv"); }, ErrorCode::NonNumeric, 3);
    expect_error([] { read_patch_file("patch,X,Y,Z\nA1,1,,3\n", "a.csv"); }, ErrorCode::NonNumeric, 2);
    expect_error([] { read_patch_file("wavelength,A1\n400,0.1\n410,abc\n", "s.csv"); }, ErrorCode::NonNumeric, 3);
    // One comma and no dot, but no decimal-comma number (a stray quote kept the comma): NON_NUMERIC, read
    // without touching the discarded decimal-comma copy (fuzz_patch_file, crash-0031f042…).
    expect_error([] { read_patch_file("patch,R,G,B\nI1,121.4,130.7,INATOR \"G,B\n", "a.csv"); }, ErrorCode::NonNumeric, 2);
    expect_error([] {
      read_patch_file("CTI3\nBEGIN_DATA_FORMAT\nSAMPLE_ID XYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\nBEGIN_DATA\nA1 1 2 x\nEND_DATA\n", "a.ti3");
    }, ErrorCode::NonNumeric, 6);
  }
  SECTION("NaN and Inf") {
    expect_error([] { read_patch_file("patch,X,Y,Z\nA1,1,nan,3\n", "a.csv"); }, ErrorCode::NonFinite, 2);
    expect_error([] { read_patch_file("patch,L,a,b\nA1,1,2,3\nA2,inf,2,3\n", "a.csv"); }, ErrorCode::NonFinite, 3);
    expect_error([] { read_patch_file("wavelength,A1\n400,-Infinity\n", "s.csv"); }, ErrorCode::NonFinite, 2);
    expect_error([] { read_patch_file("patch,X,Y,Z\nA1,1,1e999,3\n", "a.csv"); }, ErrorCode::NonFinite, 2);
  }
  SECTION("non-monotonic wavelengths") {
    expect_error([] { read_patch_file("wavelength,A1\n400,0.1\n410,0.2\n405,0.3\n", "s.csv"); }, ErrorCode::NonMonotonic, 4);
    expect_error([] { read_patch_file("wavelength,A1\n400,0.1\n400,0.2\n", "s.csv"); }, ErrorCode::NonMonotonic, 3);
    expect_error([] { read_patch_file("patch,400,390\nA1,0.1,0.2\n", "a.csv"); }, ErrorCode::NonMonotonic, 1);
  }
  SECTION("duplicate patch ids (after normalisation)") {
    expect_error([] { read_patch_file("patch,X,Y,Z\nA1,1,2,3\nA2,1,2,3\nA01,1,2,3\n", "a.csv"); }, ErrorCode::DuplicateId, 4);
    expect_error([] { read_patch_file("wavelength,A1,A01\n400,0.1,0.2\n", "s.csv"); }, ErrorCode::DuplicateId, 1);
    expect_error([] {
      read_patch_file("CTI3\nBEGIN_DATA_FORMAT\nSAMPLE_ID XYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\nBEGIN_DATA\nA1 1 2 3\nA1 1 2 3\nEND_DATA\n",
                      "a.ti3");
    }, ErrorCode::DuplicateId, 7);
  }
  SECTION("wrong number of values in a row") {
    expect_error([] { read_patch_file("patch,X,Y,Z\nA1,1,2,3\nA2,1,2\n", "a.csv"); }, ErrorCode::RowLength, 3);
    expect_error([] { read_patch_file("wavelength,A1\n400,0.1,0.3\n", "s.csv"); }, ErrorCode::RowLength, 2);
    expect_error([] {
      read_patch_file("CTI3\nBEGIN_DATA_FORMAT\nSAMPLE_ID XYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\nBEGIN_DATA\nA1 1 2 3 4\nEND_DATA\n", "a.ti3");
    }, ErrorCode::RowLength, 6);
    expect_error([] {
      read_patch_file("CTI3\nBEGIN_DATA_FORMAT\nSAMPLE_ID XYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\nNUMBER_OF_SETS 2\nBEGIN_DATA\nA1 1 2 3\nEND_DATA\n",
                      "a.ti3");
    }, ErrorCode::RowLength, 6);  // the BEGIN_DATA line
  }
  SECTION("structure") {
    expect_error([] { read_patch_file("CTI3\nBEGIN_DATA_FORMAT\nSAMPLE_ID XYZ_X\n", "a.ti3"); }, ErrorCode::ParseError, 2);
    expect_error([] {
      read_patch_file("CTI3\nBEGIN_DATA_FORMAT\nSAMPLE_ID XYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\nBEGIN_DATA\nA1 1 2 3\n", "a.ti3");
    }, ErrorCode::ParseError, 5);
    expect_error([] { read_patch_file("CTI3\nBEGIN_DATA\nA1 1 2 3\nEND_DATA\n", "a.ti3"); }, ErrorCode::ParseError, 2);
    expect_error([] { read_patch_file("CTI3\nDESCRIPTOR \"x\"\n", "a.ti3"); }, ErrorCode::ParseError);
    expect_error([] { read_patch_file("patch,,Y,Z\nA1,1,2,3\n", "a.csv"); }, ErrorCode::ParseError, 1);
  }
}
