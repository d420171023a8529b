// The worked example of the absolute chain (tristim/absolute/example.hpp) and the training
// stimuli CSV (tristim/absolute/stimuli_file.hpp): the CSV reads back exactly, and the chain
// fitted as a user would (n from the lens cap, S measured from the series, f(r) from the flat,
// areas from the camera's sensitivities) recovers Y within the paper's 2.4 %: every
// equal-tristimulus cell (above 1 cd/m²), and the 36 cells on average — the paper's 2.37 % is a
// mean relative error over a test set (section 4.1, Experiment (a)), not a bound per sample.
// The ColorChecker cells are compared with the colour module's floor too (matrix_floor.hpp):
// M, fitted on 24 projected colours (mixtures of three primaries), maps this camera's response
// to broadband reflectances under D65 with errors up to 6.7 % (C6) even when every step before
// M is exact (metamerism: the camera fails the Luther condition, eq 3); the chain must add
// little to that.
#include <cmath>
#include <cstdio>

#include "matrix_floor.hpp"
#include "test_support.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/absolute/example.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/absolute/stimuli_file.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

TEST_CASE("absolute: the example's light and training tables name what the example accepts", "[absolute]") {
  const AbsoluteExampleOptions defaults;
  const auto lights = example_light_table(), trainings = example_training_table();
  REQUIRE_FALSE(lights.empty());
  REQUIRE_FALSE(trainings.empty());
  CHECK(lights[0].id == defaults.illuminant);  // the defaults first
  CHECK(trainings[0].id == defaults.colour_training);
  for (const auto& l : lights) {
    INFO(l.id);
    CHECK_NOTHROW(illuminant_spd(l.id));  // a built-in light
    CHECK_FALSE(l.label.empty());
  }
  for (const auto& t : trainings) {
    INFO(t.id);
    CHECK((t.id == "projector" || t.id == "reflective"));  // the ids make_absolute_example reads
    CHECK_FALSE(t.label.empty());
    if (!t.transform.empty()) CHECK(model_info("Guarnera2018-" + t.transform).family == "Guarnera2018");
  }
}

TEST_CASE("absolute: the stimuli CSV of the example reads back exactly, bad rows are coded", "[absolute]") {
  const AbsoluteExample ex = make_absolute_example();
  REQUIRE(ex.stimuli.size() > 100);
  const auto rows = read_stimuli_csv(stimuli_to_csv(ex.stimuli), "example.csv");
  REQUIRE(rows.size() == ex.stimuli.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    const TrainingStimulus &a = rows[i].stimulus, &b = ex.stimuli[i];
    CHECK(a.id == b.id);
    CHECK(a.luminance_set == b.luminance_set);
    CHECK(a.exposure.exposure_s == b.exposure.exposure_s);
    CHECK(a.raw_RGB == b.raw_RGB);
    CHECK(a.falloff == b.falloff);
    CHECK(a.XYZ == b.XYZ);
    CHECK(rows[i].file.empty());
  }
  test::require_code([] { read_stimuli_csv("id,R,G,B\n1,1,2,3\n", "s.csv"); }, ErrorCode::MissingColumn);
  test::require_code([] { read_stimuli_csv("id,R,G,B,X,Y,Z\n1,1,2,3,4,4,4\n", "s.csv"); }, ErrorCode::MissingMetadata);
  test::require_code([] { read_stimuli_csv("id,set,exposure_s,f_number,R,G,B,X,Y,Z\n1,grey,0.01,8,1,2,3,4,4,4\n", "s.csv"); },
                     ErrorCode::InvalidArgument);
  test::require_code([] { read_stimuli_csv("id,exposure_s,f_number,R,G,B,X,Y,Z\n", "s.csv"); }, ErrorCode::EmptyFile);
  // Found by fuzz_stimuli: a file column, a row without a file, R but no G column (was a read
  // before the row), and a region coordinate no int holds (was an out-of-range cast).
  test::require_code([] { read_stimuli_csv("R,B,X,Y,Z,file\n1,2,3,4,5,\n", "s.csv"); }, ErrorCode::MissingColumn);
  test::require_code([] { read_stimuli_csv("file,x,y,w,h,X,Y,Z\na.dng,1e300,0,8,8,1,1,1\n", "s.csv"); }, ErrorCode::InvalidArgument);
}

namespace {
// The sum of the finite X, Y, Z in the central half (each way) of a cell, and how many there were.
Vec3 central_sum(const AbsoluteImage& img, const ExampleRegion& g, int& count) {
  const int W = img.luminance.width;
  Vec3 sum = Vec3::Zero();
  count = 0;
  for (int y = g.y + g.h / 4; y < g.y + g.h - g.h / 4; ++y)
    for (int x = g.x + g.w / 4; x < g.x + g.w - g.w / 4; ++x) {
      const size_t q = static_cast<size_t>(y) * W + x;
      const Vec3 v(img.XYZ[q * 3], img.XYZ[q * 3 + 1], img.XYZ[q * 3 + 2]);
      if (v.allFinite()) sum += v, ++count;
    }
  return sum;
}

}  // namespace

TEST_CASE("absolute: the example is the same natively and in wasm (pinned hashes)", "[absolute]") {
  // The page builds this example in wasm, `tristim absolute example` natively: the virtual
  // camera's noise and response use detmath, so the frames, the fit and the measured XYZ
  // must agree to the bit (the user's chain as in the next test).
  const AbsoluteExample ex = make_absolute_example();
  test::BitHash frames;
  for (const RawImage& f : ex.frames)
    for (float v : f.rgb) frames.add(v);
  for (const RawImage& f : ex.lens_cap)
    for (float v : f.rgb) frames.add(v);
  for (float v : ex.flat.rgb) frames.add(v);
  std::vector<const RawImage*> caps, series;
  for (const auto& c : ex.lens_cap) caps.push_back(&c);
  for (const auto& f : ex.frames) series.push_back(&f);
  const DarkFrame cap = average_dark_frames(caps);
  const Normalisation n =
      make_normalisation(&cap, measure_saturation(series), &ex.sensor.ssf, fit_falloff_Guarnera2018(ex.flat, &cap), 10);
  const AbsoluteProfile p = fit_absolute_Guarnera2018(ex.stimuli, n);
  test::BitHash chain;
  for (int c = 0; c < 3; ++c)
    for (double v : {p.luminance.curves[c].k1, p.luminance.curves[c].k2, p.luminance.curves[c].k3}) chain.add(v);
  for (float v : apply_absolute(p, series).XYZ) chain.add(v);
  INFO("frames " << frames.text() << ", fit and XYZ " << chain.text());
  CHECK(frames.value == 0x1fd7e359f1478383ULL);
  CHECK(chain.value == 0x8a70162d0b8dfa43ULL);
}

TEST_CASE("absolute: the example, fitted as a user would, measures Y within 2.4 %", "[absolute]") {
  const AbsoluteExample ex = make_absolute_example();
  std::vector<const RawImage*> caps, series;
  for (const auto& c : ex.lens_cap) caps.push_back(&c);
  for (const auto& f : ex.frames) series.push_back(&f);
  const DarkFrame cap = average_dark_frames(caps);
  const SaturationEstimate sat = measure_saturation(series);
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c);
    CHECK(sat.measured[c]);
    CHECK(sat.level[c] == Approx(ex.sensor.saturation).margin(2));
  }
  const Normalisation n = make_normalisation(&cap, sat, &ex.sensor.ssf, fit_falloff_Guarnera2018(ex.flat, &cap), 10);
  std::vector<TrainingStimulus> stimuli;
  for (const auto& r : read_stimuli_csv(stimuli_to_csv(ex.stimuli), "example.csv")) {
    TrainingStimulus s = r.stimulus;
    for (int c = 0; c < 3; ++c) s.saturated[c] = n.zone(c, s.raw_RGB[c]) == Zone::Saturated;
    stimuli.push_back(s);
  }
  AbsoluteProfile p = fit_absolute_Guarnera2018(stimuli, n);
  CHECK(p.luminance.reciprocity_ok);
  const AbsoluteImage img = apply_absolute(p, series);
  // The scene's chart spectra, as make_absolute_example builds them (cc24 under D65).
  const SpectralData chart = reflected_spectra(chart_reflectances("cc24"), illuminant_spd("D65"));
  std::vector<double> err, floor_err, chain_err;
  std::printf("  cell     truth Y cd/m2   measured (rel)        M floor (rel)      measured vs floor\n");
  for (const auto& g : ex.regions) {
    int count = 0;
    const Vec3 sum = central_sum(img, g, count);
    REQUIRE(count > 0);
    const double Y = sum[1] / count, rel = (Y - g.XYZ[1]) / g.XYZ[1];
    err.push_back(std::fabs(rel));
    if (g.id[0] == 'E') {
      // The equal-tristimulus ladder tests the luminance module (eq 9) cell by cell.
      std::printf("  %-8s %12.3f %12.3f (%+.4f)\n", g.id.c_str(), g.XYZ[1], Y, rel);
      INFO(g.id << " Y " << g.XYZ[1] << " measured " << Y);
      CHECK(std::fabs(rel) < (g.XYZ[1] < 1 ? 0.05 : 0.024));
      continue;
    }
    size_t k = 0;
    while (k < chart.size() && chart.names[k] != g.id) ++k;
    REQUIRE(k < chart.size());
    const double floor_Y = test::matrix_floor_XYZ(p, ex.sensor.ssf, chart, k, g.XYZ[1])[1];
    const double floor_rel = (floor_Y - g.XYZ[1]) / g.XYZ[1], chain_rel = (Y - floor_Y) / floor_Y;
    floor_err.push_back(std::fabs(floor_rel));
    chain_err.push_back(std::fabs(chain_rel));
    std::printf("  %-8s %12.3f %12.3f (%+.4f) %12.3f (%+.4f) %+.4f\n", g.id.c_str(), g.XYZ[1], Y, rel, floor_Y, floor_rel,
                chain_rel);
    INFO(g.id << " Y " << g.XYZ[1] << " measured " << Y << ", what M gives with an exact luminance module " << floor_Y);
    CHECK(std::fabs(chain_rel) < 0.01);
  }
  const Summary s = summarize(err), f = summarize(floor_err), c = summarize(chain_err);
  std::printf("example: |relative Y error| over %zu cells: median %.4f mean %.4f max %.4f\n", err.size(), s.median, s.mean, s.max);
  std::printf("example: ColorChecker cells, M floor |rel Y| mean %.4f max %.4f; measured vs floor mean %.4f max %.4f\n",
              f.mean, f.max, c.mean, c.max);
  CHECK(s.mean < 0.024);  // the paper's 2.37 % (a mean over its test set)
}

namespace {
/// The example fitted as a user would (the same steps as above) with `transform`, applied with
/// the weighted fusion; the 24 ColorChecker cells' patch means (central half) against their truth,
/// white per eq (16) (the ColorChecker white at the scene's largest Y).
AbsoluteMetrics chart_cells(const AbsoluteExample& ex, const std::string& transform) {
  std::vector<const RawImage*> caps, series;
  for (const auto& c : ex.lens_cap) caps.push_back(&c);
  for (const auto& f : ex.frames) series.push_back(&f);
  const DarkFrame cap = average_dark_frames(caps);
  const Normalisation n = make_normalisation(&cap, measure_saturation(series), &ex.sensor.ssf, fit_falloff_Guarnera2018(ex.flat, &cap), 10);
  std::vector<TrainingStimulus> stimuli = ex.stimuli;
  for (auto& s : stimuli)
    for (int c = 0; c < 3; ++c) s.saturated[c] = n.zone(c, s.raw_RGB[c]) == Zone::Saturated;
  AbsoluteFitOptions o;
  o.transform = transform;
  const AbsoluteProfile p = fit_absolute_Guarnera2018(stimuli, n, o);
  const AbsoluteImage img = apply_absolute(p, series);
  std::vector<Vec3> est, ref;
  double y_max = 0;
  Vec3 white = Vec3::Zero();
  for (const auto& g : ex.regions) {
    y_max = std::max(y_max, g.XYZ[1]);
    if (g.id == ex.white_id) white = g.XYZ;
    if (g.id[0] == 'E') continue;
    int count = 0;
    const Vec3 sum = central_sum(img, g, count);
    est.push_back(sum / count);
    ref.push_back(g.XYZ);
  }
  PatchMatrix E(est.size(), 3), R(ref.size(), 3);
  for (size_t i = 0; i < est.size(); ++i) E.row(i) = est[i].transpose(), R.row(i) = ref[i].transpose();
  return evaluate_absolute(E, R, white_Guarnera2018(white, y_max));
}
}  // namespace

TEST_CASE("absolute: the example under A and F2 — projector training cannot meet Table 4, reflective training (T2R) does", "[absolute]") {
  std::printf("example ColorChecker cells (patch means), weighted fusion:\n  light  training    M    rel Y    NRMSE X/Y/Z           mean NRMSE  dE00 mean\n");
  for (const char* light : {"A", "F2"}) {
    AbsoluteExampleOptions o;
    o.illuminant = light;
    o.colour_training = "projector";
    const AbsoluteMetrics proj = chart_cells(make_absolute_example(o), "T1");
    o.colour_training = "reflective";
    const AbsoluteExample ex = make_absolute_example(o);
    int colour = 0;
    for (const auto& s : ex.stimuli) colour += s.luminance_set ? 0 : 1;
    CHECK(colour > 60);  // the SG patches unlike the Classic's (80 of 140 for this camera's unsaturated ones)
    const AbsoluteMetrics refl = chart_cells(ex, "T2R");
    for (const auto& [name, m] : {std::pair{"projector  T1 ", proj}, std::pair{"reflective T2R", refl}})
      std::printf("  %-5s  %s  %.4f   %.4f/%.4f/%.4f   %.4f      %.3f\n", light, name, m.relative_Y_error, m.metrics.NRMSE[0],
                  m.metrics.NRMSE[1], m.metrics.NRMSE[2], m.metrics.NRMSE.mean(), m.metrics.dE00.mean);
    INFO(light);
    // Table 4 (the checks): 2.4 % relative Y, NRMSE 1.3 % (multi-shot)
    CHECK(refl.relative_Y_error < 0.024);
    CHECK(refl.metrics.NRMSE.mean() < 0.013);
    CHECK(proj.relative_Y_error > refl.relative_Y_error);
  }
  AbsoluteExampleOptions bad;
  bad.colour_training = "printed";
  test::require_code([&] { make_absolute_example(bad); }, ErrorCode::InvalidArgument);
  bad.colour_training = "reflective";
  bad.illuminant = "D1";
  test::require_code([&] { make_absolute_example(bad); }, ErrorCode::UnknownId);
}
