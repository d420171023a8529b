// Benchmark: the absolute tele-colorimeter (Guarnera 2018) on five 24 MP brackets (6000 × 4000
// Bayer sensor = 3000 × 2000 measurement pixels), fused into X, Y, Z in cd/m². Prints figures,
// asserts nothing. Frames are streamed: each is made (not timed), added to the fusion, dropped,
// so only one decoded frame and the accumulators live at a time (the page does the same).
//   fuse5x24MP        decoded frames → ExposureFusion::add ×5 → finish → eq (4)
//   decode+fuse5x24MP DNG bytes → decode_raw → add, ×5 → finish → eq (4)  (the page's path)
// Frames are noise-free (noise costs nothing in the fusion, a lot to simulate).
// Output lines "BENCH <case> <step> <ms>" and "PEAK <case> <MiB>" are read by scripts/bench.sh.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "dng_writer.hpp"
#include "synthetic.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/absolute/virtual_bracket.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;
using namespace tristim::bench;

namespace {

constexpr int kW = 3000, kH = 2000;

// A scene of 8 × 6 blocks spanning four decades (0.5 … 5000 cd/m²) of equal-tristimulus light.
VirtualScene scene() {
  VirtualScene s;
  s.width = kW;
  s.height = kH;
  s.stimuli = projector_spectra({Vec3(1, 1, 1)}, {"E"});
  for (int k = 1; k < 48; ++k) {
    s.stimuli.values.push_back(s.stimuli.values[0]);
    s.stimuli.names.push_back("E");
  }
  for (int k = 0; k < 48; ++k) s.luminance.push_back(0.5 * std::pow(10.0, 4.0 * k / 47));
  s.label.resize(static_cast<size_t>(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) s.label[static_cast<size_t>(y) * kW + x] = static_cast<std::uint16_t>((y * 6 / kH) * 8 + x * 8 / kW);
  return s;
}

AbsoluteProfile profile(const VirtualSensor& sensor) {
  AbsoluteProfile p;
  p.make = sensor.make;
  p.model = sensor.model;
  p.width = kW;
  p.height = kH;
  p.normalisation.noise_floor = {8, 8, 8};
  p.normalisation.noise_sigma = {3, 2, 3};
  p.normalisation.saturation = {15000, 15000, 15000};
  p.normalisation.areas = channel_areas(sensor.ssf);
  FalloffFit f;
  f.p1 = 0.3;
  p.normalisation.falloff = test::centred_falloff(f, kW, kH);
  for (int c = 0; c < 3; ++c) p.luminance.curves[c] = {0.0, 4.0, c == 1 ? 1.0 : 1.02};  // k3 ≠ 1: the power path
  p.colour.id = "Guarnera2018-T1";
  p.colour.coefficients = Eigen::MatrixXd::Identity(3, 3);
  return p;
}

}  // namespace

int main() {
  VirtualSensor sensor;
  sensor.ssf = camera_ssf("Canon_EOS_5D_Mark_II");
  sensor.electrons_per_dn = 0;
  sensor.read_noise = 0;
  const VirtualScene s = scene();
  const AbsoluteProfile p = profile(sensor);
  const std::vector<ExposureSettings> bracket = {{1.0 / 1000, 8, 0}, {1.0 / 250, 8, 0}, {1.0 / 60, 8, 0},
                                                 {1.0 / 15, 8, 0}, {1.0 / 4, 8, 0}};
  std::printf("CASE fuse5x24MP: five 3000x2000 measurement frames (24 MP Bayer), weighted fusion, T1 matrix\n");
  std::printf("CASE decode+fuse5x24MP: the same from uncompressed 16-bit DNGs (decode_raw, one at a time)\n");
  for (const bool decode : {false, true}) {
    const std::string name = decode ? "decode+fuse5x24MP" : "fuse5x24MP";
    double t_decode = 0, t_add = 0;
    ExposureFusion fusion(p.normalisation, p.luminance, kW, kH);
    for (size_t e = 0; e < bracket.size(); ++e) {
      std::unique_ptr<RawImage> frame;
      if (decode) {
        DngWriteOptions o;
        o.make = sensor.make;
        o.model = sensor.model;
        o.white = 16000;
        o.exposure_s = bracket[e].exposure_s;
        o.f_number = bracket[e].f_number;
        std::vector<std::uint8_t> bytes =
            write_dng(capture_virtual_mosaic(sensor, s, bracket[e], e), 2 * kW, 2 * kH, o);
        t_decode += time_ms([&] { frame = std::make_unique<RawImage>(decode_raw(bytes)); });
      } else {
        frame = std::make_unique<RawImage>(capture_virtual(sensor, s, bracket[e], e));
      }
      t_add += time_ms([&] { fusion.add(*frame, bracket[e]); });
    }
    AbsoluteImage img;
    const double t_finish = time_ms([&] { img.luminance = fusion.finish(); });
    const double t_xyz = time_ms([&] { luminance_to_XYZ(p, img.luminance.L, img.XYZ); });
    if (decode) std::printf("BENCH %s decode %.1f\n", name.c_str(), t_decode);
    std::printf("BENCH %s add %.1f\n", name.c_str(), t_add);
    std::printf("BENCH %s finish %.1f\n", name.c_str(), t_finish);
    std::printf("BENCH %s eq4_xyz %.1f\n", name.c_str(), t_xyz);
    std::printf("BENCH %s total %.1f\n", name.c_str(), t_decode + t_add + t_finish + t_xyz);
    std::printf("PEAK %s %.0f\n", name.c_str(), peak_mib());
    // A check that the numbers are right: the block of 50 cd/m² (k = 20 → 0.5·10^(80/47)).
    const size_t q = static_cast<size_t>(2 * kH / 6 + kH / 12) * kW + 4 * kW / 8 + kW / 16;
    std::printf("CASE %s: block of Y = %.2f cd/m2 reads L(G) = %.2f (planted eq 8 curve, identity matrix); dominant pixels per exposure:", name.c_str(),
                s.luminance[s.label[q]] * virtual_XYZ(sensor, s, 0)[1] / s.luminance[0], img.XYZ[q * 3 + 1]);
    for (auto n : img.luminance.dominant_pixels) std::printf(" %zu", n);
    std::printf("\n");
  }
  return 0;
}
