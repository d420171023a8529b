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
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

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
  const int W = img.luminance.width;
  std::printf("  cell     truth Y cd/m2   measured (rel)        M floor (rel)      measured vs floor\n");
  for (const auto& g : ex.regions) {
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (int y = g.y + g.h / 4; y < g.y + g.h - g.h / 4; ++y)
      for (int x = g.x + g.w / 4; x < g.x + g.w - g.w / 4; ++x) {
        const size_t q = static_cast<size_t>(y) * W + x;
        const Vec3 v(img.XYZ[q * 3], img.XYZ[q * 3 + 1], img.XYZ[q * 3 + 2]);
        if (v.allFinite()) sum += v, ++count;
      }
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
