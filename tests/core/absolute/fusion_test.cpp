// Exposure fusion and Algorithm 1 (Guarnera 2018 section 3.1): where each pixel's value comes
// from, a scene of four decades of luminance, coded errors for bad series, the profile JSON.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "absolute_bench.hpp"
#include "test_support.hpp"
#include "dng_writer.hpp"
#include "tristim/absolute/profile.hpp"

using namespace tristim;

namespace {

/// Two stimuli side by side: a dim one (left) and one bright enough to clip the long exposures.
VirtualScene two_level_scene(double dim, double bright) {
  VirtualScene s = uniform_scene(40, 20, projector_spectra({Vec3(1, 1, 1)}, {"dim"}), dim);
  s.stimuli.names.push_back("bright");
  s.stimuli.values.push_back(s.stimuli.values[0]);
  s.luminance = {dim, bright};
  for (int y = 0; y < s.height; ++y)
    for (int x = s.width / 2; x < s.width; ++x) s.label[static_cast<size_t>(y) * s.width + x] = 1;
  return s;
}

}  // namespace

TEST_CASE("absolute: the reliability weights of the zones", "[absolute]") {
  const double w = 10;
  CHECK(reliability_Guarnera2018(Zone::Under, -0.01, w) == 0);
  CHECK(reliability_Guarnera2018(Zone::Under, 0.05, w) == Approx(0.5));
  CHECK(reliability_Guarnera2018(Zone::Centre, 0.5, w) == 1);
  CHECK(reliability_Guarnera2018(Zone::Over, 0.95, w) == Approx(0.5));
  CHECK(reliability_Guarnera2018(Zone::Saturated, 1.0, w) == 0);
  Normalisation n;
  n.noise_floor = {10, 10, 10};
  n.saturation = {1010, 1010, 1010};
  CHECK(n.zone(1, 50) == Zone::Under);     // u = 0.04 < 1/w
  CHECK(n.zone(1, 510) == Zone::Centre);
  CHECK(n.zone(1, 980) == Zone::Over);     // u = 0.97 > (w-1)/w
  CHECK(n.zone(1, 1010) == Zone::Saturated);
  CHECK(n.zone(1, 500, true) == Zone::Saturated);  // flagged by the decoder
}

TEST_CASE("absolute: the fusion-mode table lists every mode by the id the recipe reads", "[absolute]") {
  const auto table = fusion_mode_table();
  REQUIRE(table.size() == 2);
  CHECK(table[0].id == fusion_mode_id(FusionMode::Weighted));  // the default first
  for (const auto& r : table) {
    INFO(r.id);
    CHECK(fusion_mode_id(fusion_mode_from_id(r.id)) == r.id);
    CHECK_FALSE(r.label.empty());
    CHECK(r.reference.rfind("Guarnera, Bianco & Schettini 2018", 0) == 0);
    CHECK_FALSE(r.about.empty());
  }
}

TEST_CASE("absolute: a pixel saturated in the long exposure takes a shorter one's value", "[absolute]") {
  const auto& b = test::bench();
  const VirtualScene scene = two_level_scene(40, 2000);  // 2000 cd/m² clips 1/60 s and longer
  const AbsoluteProfile p = test::profile_for(b, scene.width, scene.height);
  std::vector<RawImage> frames;
  for (int e : {4, 0}) frames.push_back(capture_virtual(b.sensor, scene, b.bracket[e], 70 + e));  // 1/15 s, 1/250 s
  const size_t bright = static_cast<size_t>(10) * scene.width + 30, dim = static_cast<size_t>(10) * scene.width + 10;
  REQUIRE(p.normalisation.zone(1, frames[0].rgb[bright * 3 + 1]) == Zone::Saturated);
  for (FusionMode mode : {FusionMode::Weighted, FusionMode::Recursive}) {
    AbsoluteProfile q = p;
    q.fusion = mode;
    const AbsoluteImage img = apply_absolute(q, {&frames[0], &frames[1]});
    INFO(fusion_mode_id(mode));
    CHECK(img.luminance.source[bright] == 1);                // the short exposure served it
    CHECK((img.luminance.contributors[bright] & 1u) == 0);   // the clipped long one did not
    CHECK(img.XYZ[bright * 3 + 1] == Approx(2000).epsilon(0.03));
    CHECK(img.luminance.source[dim] == 0);                   // the dim side: the long exposure
    CHECK(img.XYZ[dim * 3 + 1] == Approx(40).epsilon(0.03));
  }
  // Only the long exposure: the bright side cannot be measured (NaN), the rest can.
  const AbsoluteImage only_long = apply_absolute(p, {&frames[0]});
  CHECK(std::isnan(only_long.XYZ[bright * 3 + 1]));
  CHECK(only_long.luminance.saturated_pixels == static_cast<size_t>(scene.width / 2 * scene.height));
}

TEST_CASE("absolute: a scene of four decades (0.1-1000 cd/m²) measured within 3 % per decade", "[absolute]") {
  const auto& b = test::bench();
  // A ramp along x, 0.1 → 1000 cd/m² on a log scale; equal-tristimulus light.
  VirtualScene s = uniform_scene(400, 24, projector_spectra({Vec3(1, 1, 1)}, {"E"}), 1.0);
  s.gain.resize(s.label.size());
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) s.gain[static_cast<size_t>(y) * s.width + x] = static_cast<float>(std::pow(10.0, -1 + 4.0 * (x + 0.5) / s.width));
  const AbsoluteProfile p = test::profile_for(b, s.width, s.height);
  // Three-stop bracket from 1/1000 s to 4 s at f/8 (covers the ramp at Z_c ≈ 3.2 stops per shot).
  std::vector<ExposureSettings> bracket = {{1.0 / 1000, 8, 100}, {1.0 / 125, 8, 100}, {1.0 / 15, 8, 100},
                                           {0.5, 8, 100}, {4.0, 8, 100}};
  std::vector<RawImage> frames;
  for (size_t e = 0; e < bracket.size(); ++e) frames.push_back(capture_virtual(b.sensor, s, bracket[e], 900 + e));
  std::vector<const RawImage*> ptrs;
  for (const auto& f : frames) ptrs.push_back(&f);
  const AbsoluteImage img = apply_absolute(p, ptrs);
  const double Y_E = virtual_XYZ(b.sensor, s, 0)[1];  // luminance of gain 1
  std::printf("Four decades, fused 5 exposures (1/1000 s .. 4 s, f/8), per-pixel |relative Y error|:\n");
  for (int d = 0; d < 4; ++d) {
    std::vector<double> err;
    std::vector<int> served(bracket.size(), 0);
    for (int y = 0; y < s.height; ++y)
      for (int x = d * s.width / 4; x < (d + 1) * s.width / 4; ++x) {
        const size_t q = static_cast<size_t>(y) * s.width + x;
        err.push_back(std::fabs(img.XYZ[q * 3 + 1] / (Y_E * s.gain[q]) - 1));
        served[img.luminance.source[q]]++;
      }
    const Summary e = summarize(err);
    std::printf("  %6.1f-%6.1f cd/m2: median %.4f mean %.4f p95 %.4f; dominant exposure counts", std::pow(10.0, d - 1),
                std::pow(10.0, d), e.median, e.mean, e.p95);
    for (int k : served) std::printf(" %d", k);
    std::printf("\n");
    INFO("decade " << d);
    CHECK(e.median < 0.03);
    CHECK(e.mean < 0.03);
  }
}

TEST_CASE("absolute: the fusion's 4-pixel loop gives the scalar loop's floats", "[absolute]") {
  // 7 pixels a row: 0-3 go through the 4-lane loop, 4-6 through the scalar one. The fall-off is
  // centred at x = 3.5, so pixels x and 6 - x see the same f(r): given the same values and flags
  // they must fuse to the same bits. Values span the zones (dark, under, centre, over, clipped)
  // and the decoder's saturation flags, in two exposures.
  const auto& b = test::bench();
  const int W = 7, H = 48;
  const AbsoluteProfile p = test::profile_for(b, W, H);
  const Normalisation& n = p.normalisation;
  REQUIRE(n.falloff);
  const SpectralData E = projector_spectra({Vec3(1, 1, 1)}, {"E"});
  std::mt19937 rng(11);
  std::vector<RawImage> frames;
  for (int e : {4, 0}) {
    RawImage f = capture_virtual(b.sensor, uniform_scene(W, H, E, 100.0), b.bracket[e], 80 + e);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < 4; ++x) {
        const size_t a = static_cast<size_t>(y) * W + x, m = static_cast<size_t>(y) * W + (W - 1 - x);
        for (int c = 0; c < 3; ++c) {
          const double lo = n.noise_floor[c] - 20, hi = n.saturation[c] + 20;
          f.rgb[a * 3 + c] = static_cast<float>(std::uniform_real_distribution<double>(lo, hi)(rng));
          f.rgb[m * 3 + c] = f.rgb[a * 3 + c];
        }
        f.saturated[a] = static_cast<std::uint8_t>(rng() % 8 == 0 ? rng() % 8 : 0);
        f.saturated[m] = f.saturated[a];
      }
    frames.push_back(std::move(f));
  }
  ExposureFusion fusion(n, p.luminance, W, H);
  fusion.add(frames[0], b.bracket[4]);
  fusion.add(frames[1], b.bracket[0]);
  const FusedLuminance L = fusion.finish();
  int compared = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < 3; ++x) {
      const size_t a = static_cast<size_t>(y) * W + x, m = static_cast<size_t>(y) * W + (W - 1 - x);
      INFO("row " << y << " pixel " << x);
      REQUIRE(L.source[a] == L.source[m]);
      REQUIRE(L.contributors[a] == L.contributors[m]);
      for (int c = 0; c < 3; ++c) {
        const float u = L.L[a * 3 + c], v = L.L[m * 3 + c];
        REQUIRE(std::isnan(u) == std::isnan(v));
        if (!std::isnan(u)) REQUIRE(std::memcmp(&u, &v, sizeof u) == 0);
        compared += !std::isnan(u);
      }
    }
  CHECK(compared > 200);  // most channels are measured
}

TEST_CASE("absolute: the fusion gives the same cd/m² natively and in wasm (pinned hashes)", "[absolute]") {
  // The page fuses a bracket in wasm, the CLI natively: the same frames must give the same floats.
  // Everything here is built from exact arithmetic (the virtual camera's noise uses the C library,
  // whose last bits differ between glibc and Emscripten's musl): a hand-made normalisation with a
  // fall-off, curves with k3 ≠ 1, and three frames whose values cross every zone, some flagged.
  const int W = 64, H = 32;
  Normalisation n;
  n.noise_floor = {512, 510, 515};
  n.noise_sigma = {3, 2.5, 3.5};
  n.saturation = {15000, 16000, 15500};
  n.areas = {0.9, 1.0, 1.1};
  FalloffFit f;
  f.p1 = -0.2;
  f.p2 = 0.05;
  f.p3 = 1;
  f.centre_x = W / 2.0;
  f.centre_y = H / 2.0;
  f.r_scale = std::sqrt(f.centre_x * f.centre_x + f.centre_y * f.centre_y);
  f.width = W;
  f.height = H;
  n.falloff = f;
  LuminanceFit fit;
  fit.iso_reference = 100;
  const double k3[3] = {0.93, 1.07, 0.98};
  for (int c = 0; c < 3; ++c) fit.curves[c] = InverseOecf{0.002 * (c + 1), 0.8 + 0.1 * c, k3[c]};
  const std::vector<ExposureSettings> bracket = {{1 / 250.0, 8, 100}, {1 / 60.0, 8, 100}, {1 / 15.0, 8, 100}};
  std::vector<RawImage> frames;
  for (size_t e = 0; e < bracket.size(); ++e) {
    RawImage img;
    img.width = W;
    img.height = H;
    img.rgb.resize(size_t(W) * H * 3);
    img.saturated.assign(size_t(W) * H, 0);
    const double gain = bracket[e].factor() / bracket[1].factor();
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        for (int c = 0; c < 3; ++c) {
          const size_t i = static_cast<size_t>(y) * W + x;
          const double level = static_cast<double>((7 * x + 13 * y + 29 * c + 3) % 101) / (x < W - 8 ? 80 : 16);  // 0 .. 1.25 (6.25 at the right)
          const double v = n.noise_floor[c] - 4 + level * gain * (n.saturation[c] - n.noise_floor[c]);
          img.rgb[i * 3 + c] = static_cast<float>(std::min(v, n.saturation[c] + 10));
          if (v >= n.saturation[c] && (x + y) % 3 == 0) img.saturated[i] |= static_cast<std::uint8_t>(1 << c);
        }
    frames.push_back(std::move(img));
  }
  const auto hash = [](const FusedLuminance& L) {
    test::BitHash h;
    for (float v : L.L) h.add(v);
    for (size_t i = 0; i < L.source.size(); ++i) h.add(L.source[i] * 65536.0 + L.contributors[i]);
    return h;
  };
  ExposureFusion fusion(n, fit, W, H);
  for (size_t e = 0; e < frames.size(); ++e) fusion.add(frames[e], bracket[e]);
  const FusedLuminance weighted = fusion.finish();
  const FusedLuminance recursive =
      select_exposures_Guarnera2018({&frames[0], &frames[1], &frames[2]}, bracket, n, fit);
  size_t measured = 0;
  for (float v : weighted.L) measured += std::isfinite(v);
  CHECK(measured > weighted.L.size() / 2);  // the values do reach the fusion
  CHECK(weighted.saturated_pixels > 0);
  size_t with_nan = 0;  // finish counts the pixels with a channel no exposure reached (4 at a time)
  for (size_t p = 0; p < weighted.L.size(); p += 3)
    with_nan += std::isnan(weighted.L[p]) || std::isnan(weighted.L[p + 1]) || std::isnan(weighted.L[p + 2]);
  CHECK(weighted.saturated_pixels == with_nan);
  INFO("weighted " << hash(weighted).text() << ", recursive " << hash(recursive).text());
  CHECK(hash(weighted).value == 0x43a0727447be8383ULL);
  CHECK(hash(recursive).value == 0x5e857382c7be8383ULL);
}

TEST_CASE("absolute: bad series are refused with codes", "[absolute]") {
  const auto& b = test::bench();
  const VirtualScene scene = two_level_scene(40, 200);
  const AbsoluteProfile p = test::profile_for(b, scene.width, scene.height);
  const RawImage a = capture_virtual(b.sensor, scene, b.bracket[2], 1);
  // Another camera in the series (and not the profile's).
  VirtualSensor other = b.sensor;
  other.model = "Another body";
  const RawImage foreign = capture_virtual(other, scene, b.bracket[2], 2);
  test::require_code([&] { apply_absolute(p, {&a, &foreign}); }, ErrorCode::FrameMismatch);
  ExposureFusion fusion(p.normalisation, p.luminance, scene.width, scene.height);
  fusion.add(a, b.bracket[2]);
  test::require_code([&] { fusion.add(foreign, b.bracket[2]); }, ErrorCode::FrameMismatch);
  // Another size.
  VirtualScene big = uniform_scene(48, 20, scene.stimuli, 40);
  const RawImage wide = capture_virtual(b.sensor, big, b.bracket[2], 3);
  test::require_code([&] { apply_absolute(p, {&a, &wide}); }, ErrorCode::FrameMismatch);
  // Missing exposure metadata.
  RawImage no_meta = a;
  no_meta.meta.shutter_s = 0;
  test::require_code([&] { apply_absolute(p, {&no_meta}); }, ErrorCode::MissingMetadata);
  // All saturated / all dark.
  const RawImage white_out = capture_virtual(b.sensor, two_level_scene(50000, 90000), b.bracket[4], 4);
  test::require_code([&] { apply_absolute(p, {&white_out}); }, ErrorCode::NoUsableData);
  const RawImage black = capture_virtual(b.sensor, two_level_scene(0, 0), b.bracket[0], 5);
  test::require_code([&] { apply_absolute(p, {&black}); }, ErrorCode::NoUsableData);
  // More exposures than the contributor mask holds.
  std::vector<const RawImage*> many(17, &a);
  test::require_code([&] { apply_absolute(p, many); }, ErrorCode::LimitExceeded);
}

TEST_CASE("absolute: the profile JSON round trip is exact", "[absolute]") {
  const auto& b = test::bench();
  const VirtualScene scene = two_level_scene(40, 700);
  AbsoluteProfile p = test::profile_for(b, scene.width, scene.height);
  const std::string text = absolute_profile_to_json(p);
  const AbsoluteProfile q = absolute_profile_from_json(text);
  CHECK(absolute_profile_to_json(q) == text);
  const RawImage f = capture_virtual(b.sensor, scene, b.bracket[2], 9);
  const AbsoluteImage x = apply_absolute(p, {&f}), y = apply_absolute(q, {&f});
  CHECK(x.XYZ == y.XYZ);
  CHECK(q.linearisation_choice().method == "Guarnera2018");
  test::require_code([&] { absolute_profile_from_json("{\"format\":\"tristim-absolute-profile\",\"version\":2}"); },
                     ErrorCode::ProfileVersion);
  test::require_code([&] { absolute_profile_from_json("{\"format\":\"tristim-profile\",\"version\":1}"); },
                     ErrorCode::ProfileInvalid);
  std::string broken = text;
  broken.replace(broken.find("\"k\""), 3, "\"q\"");
  test::require_code([&] { absolute_profile_from_json(broken); }, ErrorCode::ProfileInvalid);
}

TEST_CASE("absolute: a virtual bracket frame written as DNG decodes to the same image and exposure", "[absolute]") {
  const auto& b = test::bench();
  const VirtualScene scene = two_level_scene(40, 2000);
  const ExposureSettings e{1.0 / 125, 5.6, 0};
  const RawImage direct = capture_virtual(b.sensor, scene, e, 31);
  DngWriteOptions o;
  o.make = b.sensor.make;
  o.model = b.sensor.model;
  o.white = static_cast<std::uint32_t>(b.sensor.reported_saturation);
  o.exposure_s = e.exposure_s;
  o.f_number = e.f_number;
  const RawImage decoded = decode_raw(write_dng(capture_virtual_mosaic(b.sensor, scene, e, 31), 2 * scene.width,
                                                2 * scene.height, o));
  CHECK(decoded.rgb == direct.rgb);
  CHECK(decoded.saturated == direct.saturated);
  CHECK(decoded.meta.make == direct.meta.make);
  CHECK(decoded.meta.model == direct.meta.model);
  const ExposureSettings read = exposure_from_metadata(decoded.meta, "virtual.dng");
  CHECK(read.exposure_s == Approx(1.0 / 125));
  CHECK(read.f_number == Approx(5.6));
  CHECK(read.iso == 0);  // not written (see dng_writer.hpp): no ISO scaling
  CHECK(decoded.meta.saturation[1] == b.sensor.reported_saturation);
}
