// Benchmark of issue 46's exports: a 33³ .cube and a 90×30×30 DCP HueSatMap from a degree-3
// root-polynomial profile, and the ACES IDT (190 training spectra, Levenberg–Marquardt) with its
// CLF written and read back. Prints "BENCH <case> <step> <ms>" (fastest of 5) natively and in wasm
// (scripts/bench.sh); no timing is asserted. Issue 46's target: < 200 ms natively, within 2× in wasm.
#include <cstdio>
#include <random>

#include "bench_util.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/profile/clf.hpp"
#include "tristim/profile/dcp.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/idt.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

// A degree-3 root-polynomial profile (Finlayson, Mackiewicz & Hurlbert 2015) of a plausible camera:
// a 3×3 part and small higher terms, seeded.
Profile root_polynomial_3() {
  Profile p;
  p.model.id = "Finlayson2015-3";
  const ModelInfo& info = model_info(p.model.id);
  p.model.coefficients = Eigen::MatrixXd::Zero(3, info.n_terms);
  Mat3 m;
  m << 0.65, 0.28, 0.03, 0.27, 0.90, -0.17, 0.02, -0.12, 0.95;
  p.model.coefficients.leftCols(3) = m * 80;
  std::mt19937 rng(46);
  std::uniform_real_distribution<double> u(-0.2, 0.4);
  for (int t = 3; t < info.n_terms; ++t)
    for (int r = 0; r < 3; ++r) p.model.coefficients(r, t) = u(rng);
  p.white = whites::D50();
  p.illuminant = "D50";
  p.rgb_max = 1.2;
  return p;
}

}  // namespace

int main() {
  using bench::best_ms;
  const Profile p = root_polynomial_3();
  std::size_t sink = 0;
  std::printf("BENCH export cube-33-first-call %.2f\n", bench::time_ms([&] { sink += export_cube(p, 33).size(); }));
  std::printf("BENCH export cube-33 %.2f\n", best_ms(5, [&] { sink += export_cube(p, 33).size(); }));
  DcpOptions o;
  o.camera_model = "Bench Camera";
  o.hue_sat_map = {90, 30, 30};
  // The first call apart: in wasm it runs V8's baseline code (Liftoff) before the optimised tier
  // replaces it, which is what a single timed call (dcp_test's "[speed]" case) sees.
  std::printf("BENCH export dcp-hue-sat-map-90x30x30-first-call %.2f\n", bench::time_ms([&] { sink += write_dcp(make_dcp(p, o)).size(); }));
  std::printf("BENCH export dcp-hue-sat-map-90x30x30 %.2f\n", best_ms(5, [&] { sink += write_dcp(make_dcp(p, o)).size(); }));
  o.hue_sat_map = {0, 0, 0};
  std::printf("BENCH export dcp-matrices-only %.2f\n", best_ms(5, [&] { sink += write_dcp(make_dcp(p, o)).size(); }));
  const SpectralData ssf = camera_ssf("Canon_EOS_5D_Mark_II"), d55 = illuminant_spd("D55");
  idt_training_190();  // parsed once, outside the timing
  std::printf("BENCH export idt-190-fit %.2f\n", best_ms(5, [&] { sink += idt_from_sensitivities(ssf, d55, idt_training_190()).patches; }));
  const IdtFiles f = idt_camera_files("Canon_EOS_5D_Mark_II", "D55", "CAT02");
  std::printf("BENCH export idt-clf-read %.3f\n", best_ms(5, [&] { sink += read_clf(f.clf).info.size(); }));
  std::printf("PEAK export %.1f\n", bench::peak_mib());
  return sink == 0;  // keeps the work from being optimised away
}
