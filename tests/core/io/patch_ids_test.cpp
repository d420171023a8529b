// Patch ids come back as the user's file spelled them. The readers keep two spellings of each id:
// the normalised key that pairs a file's "A01" with a chart's "A1" (normalise_patch_id), and the
// label, the id as written ("Q001" stays "Q001"), which every output writes. Pairing by key is
// unchanged; the label follows the patch through pairing, the training set and the reference.
#include <string>
#include <vector>

#include "test_support.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/profile/export.hpp"

using namespace tristim;
using Ids = std::vector<std::string>;

TEST_CASE("patch readers keep each id as written next to its normalised key", "[io][ids]") {
  SECTION("per-patch CSV") {
    const PatchTable t = read_patch_file("patch,R,G,B\nQ001,1,2,3\nQ002,4,5,6\n a03 ,7,8,9\n", "p.csv");
    CHECK(t.ids == Ids{"Q1", "Q2", "A3"});
    CHECK(t.labels == Ids{"Q001", "Q002", "a03"});  // trimmed, case and zeros kept
  }
  SECTION("a quoted id keeps its delimiter") {
    const PatchTable t = read_patch_file("patch,X,Y,Z\n\"red, 01\",1,2,3\n", "q.csv");
    CHECK(t.labels == Ids{"red, 01"});
  }
  SECTION("CGATS (Argyll's SAMPLE_LOC A01 next to SAMPLE_ID 1..N)") {
    const PatchTable t = read_patch_file(
        "CTI3\nBEGIN_DATA_FORMAT\nSAMPLE_ID SAMPLE_LOC RGB_R RGB_G RGB_B\nEND_DATA_FORMAT\nBEGIN_DATA\n"
        "1 A01 10 20 30\n2 B12 40 50 60\nEND_DATA\n",
        "t.ti3");
    CHECK(t.ids == Ids{"A1", "B12"});
    CHECK(t.labels == Ids{"A01", "B12"});
  }
  SECTION("spectral CSV: the column names") {
    const PatchTable t = read_patch_file("wavelength_nm,A01,Q007\n400,0.1,0.2\n410,0.1,0.2\n", "s.csv");
    CHECK(t.ids == Ids{"A1", "Q7"});
    CHECK(t.spectra.names == Ids{"A1", "Q7"});  // the spectra are looked up by key
    CHECK(t.labels == Ids{"A01", "Q007"});
  }
  SECTION("spectra in a per-patch table") {
    const PatchTable t = read_patch_file("patch,400,410\nQ010,0.1,0.2\n", "r.csv");
    CHECK(t.spectra.names == Ids{"Q10"});
    CHECK(t.labels == Ids{"Q010"});
  }
  SECTION("no id column: row numbers, the same in both") {
    const PatchTable t = read_patch_file("R,G,B\n1,2,3\n4,5,6\n", "n.csv");
    CHECK(t.ids == Ids{"1", "2"});
    CHECK(t.labels == t.ids);
  }
  SECTION("a duplicate is named as the file spells it") {
    try {
      read_patch_file("patch,X,Y,Z\nA1,1,2,3\nA01,1,2,3\n", "d.csv");
      FAIL("no error");
    } catch (const Error& e) {
      CHECK(e.code() == ErrorCode::DuplicateId);
      CHECK(std::string(e.what()).find("'A01'") != std::string::npos);
      CHECK(std::string(e.what()).find("line 2") != std::string::npos);
    }
  }
}

TEST_CASE("pairing still matches A01 with A1, and the labels follow the patches", "[io][ids]") {
  const PatchTable measured = read_patch_file("id,R,G,B\nB01,4,5,6\nA01,1,2,3\nC01,7,8,9\n", "m.csv");
  const PatchTable reference = read_patch_file("patch,X,Y,Z\nA1,10,20,30\nB1,40,50,60\nC1,70,80,90\n", "r.csv");
  const PatchPairs p = pair_by_id(reference.ids, reference.XYZ, measured.ids, measured.RGB);
  REQUIRE(p.ids == Ids{"B1", "A1", "C1"});  // the measurement's order
  CHECK(p.missing_in_measured.empty());
  CHECK(p.missing_in_reference.empty());
  CHECK(p.measured[1] == Vec3(1, 2, 3));
  CHECK(p.reference[0] == Vec3(40, 50, 60));
  CHECK(patch_labels(measured, p.ids) == Ids{"B01", "A01", "C01"});
  CHECK(patch_labels(reference, p.ids) == Ids{"B1", "A1", "C1"});
  // Any spelling of the key finds the label; an id the table lacks is returned as it is.
  CHECK(patch_labels(measured, {"a1", "Z9"}) == Ids{"A01", "Z9"});
  // The labels themselves pair too (pair_by_id normalises both sides).
  const PatchPairs q = pair_by_id(reference.labels, reference.XYZ, measured.labels, measured.RGB);
  CHECK(q.ids == p.ids);
}

TEST_CASE("a reference file's ids as written reach the training set and the per-patch CSV", "[io][ids][recipe]") {
  const SpectralData d65 = illuminant_spd("D65");
  const PatchTable file = read_patch_file("patch,X,Y,Z\nA01,10,9,8\nA02,40,41,30\nA03,20,22,40\nA04,90,95,85\n", "ref.csv");
  const ReferenceChart ref = reference_from_table(file, d65, Observer::CIE1931_2);
  CHECK(ref.ids == Ids{"A1", "A2", "A3", "A4"});
  CHECK(ref.labels == Ids{"A01", "A02", "A03", "A04"});
  // A built-in chart is labelled by its own ids.
  const ReferenceChart cc24 = reference_chart("cc24", "D50");
  CHECK(cc24.labels == cc24.ids);

  Recipe recipe;
  recipe.reference.chart = "file";
  recipe.characterisation.model = "matrix-3x3";
  recipe.evaluation.leave_one_out = false;

  SECTION("a chart sample (layout ids A1..) paired with the file") {
    ChartSample sample;
    for (int i = 0; i < 4; ++i) {
      PatchSample p;
      p.id = "A" + std::to_string(i + 1);
      const Vec3 xyz = ref.XYZ[static_cast<size_t>(i)];
      p.mean = {xyz[0] * 0.5, xyz[1] * 0.6, xyz[2] * 0.7};
      sample.patches.push_back(p);
    }
    Recipe ex = recipe;
    ex.sampling.exclude = {"a3"};
    const TrainingSet t = training_set(ex, sample, ref);
    CHECK(t.ids == Ids{"A1", "A2", "A4"});
    CHECK(t.labels == Ids{"A01", "A02", "A04"});
    CHECK(t.excluded == Ids{"A03 (excluded)"});
    // A reference handed over without labels (one the page saved before they existed) is labelled by its ids.
    ReferenceChart bare = ref;
    bare.labels.clear();
    CHECK(training_set(recipe, sample, bare).labels == Ids{"A1", "A2", "A3", "A4"});
  }
  SECTION("paired tables: the ids given are the labels, their normalised forms the keys") {
    PatchMatrix rgb(4, 3), xyz(4, 3);
    for (int i = 0; i < 4; ++i) {
      xyz.row(i) = ref.XYZ[static_cast<size_t>(i)].transpose();
      rgb.row(i) << 0.5 * xyz(i, 0), 0.6 * xyz(i, 1), 0.7 * xyz(i, 2);
    }
    const TrainingSet t = training_set(recipe, Ids{"Q001", "Q002", "Q003", "Q004"}, rgb, xyz);
    CHECK(t.ids == Ids{"Q1", "Q2", "Q3", "Q4"});
    CHECK(t.labels == Ids{"Q001", "Q002", "Q003", "Q004"});
    // The same keys, so the same training digest as from the normalised ids.
    const TrainingSet k = training_set(recipe, t.ids, rgb, xyz);
    CHECK(training_digest(t.ids, t.camera_RGB, t.reference_XYZ) == training_digest(k.ids, k.camera_RGB, k.reference_XYZ));
    const Characterisation c = characterise(recipe, t);
    const std::string csv = patch_csv(t.labels, c.linear_RGB, t.reference_XYZ, c.evaluation.fit.fitted,
                                      recipe.characterisation.lab_white);
    CHECK(csv.find("\nQ001,") != std::string::npos);
    CHECK(csv.find("\nQ004,") != std::string::npos);
    CHECK(csv.find("\nQ1,") == std::string::npos);
  }
}
