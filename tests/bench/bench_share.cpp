// Share links (share/link.hpp): how long a link is for each model (least squares, leave-one-out on)
// on a 24-patch chart and on the 140-patch ColorChecker SG, and how long making, reading and
// reproducing one takes. Camera RGB: the chart's reference through a fixed 3×3 and a gamma-like
// bend, with noise, so each value has all 17 significant digits as real sample means do.
// Prints "SIZE <chart> <model> <characters> (v1 <characters>)" per row (the link with the local
// page's address, http://127.0.0.1:8080/, as written — format version 2 — and as version 1 wrote
// it) and "BENCH share-<chart> <step> <ms>". Targets (issue 44): 24 patches well under 2,000
// characters (version 2: every model ≤ ~1,400), SG under 8,000.
#include <cmath>
#include <cstdio>
#include <random>

#include "bench_util.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/share/link.hpp"
#include "tristim/share/sha256.hpp"

using namespace tristim;

int main() {
  const std::string base = "http://127.0.0.1:8080/";
  for (const std::string chart : {"passport", "sg140"}) {
    Recipe recipe;
    recipe.reference.chart = chart;
    recipe.sampling.layout.chart = chart;
    recipe.sampling.corners = {335, 291, 649, 285, 649, 486, 328, 488};
    const ReferenceChart ref = recipe_reference(complete_recipe(recipe));
    std::mt19937_64 rng(44);
    std::normal_distribution<double> noise(0, 0.004);
    PatchMatrix RGB(ref.XYZ.size(), 3), XYZ(ref.XYZ.size(), 3);
    for (size_t i = 0; i < ref.XYZ.size(); ++i) {
      const Vec3& x = ref.XYZ[i];
      XYZ.row(i) = x.transpose();
      const Vec3 lin(3.1 * x[0] - 1.4 * x[1] - 0.5 * x[2], -0.9 * x[0] + 1.9 * x[1] + 0.04 * x[2], 0.05 * x[0] - 0.2 * x[1] + 1.05 * x[2]);
      for (int c = 0; c < 3; ++c) RGB(i, c) = 12 * std::pow(std::max(lin[c], 0.05), 1.02) * (1 + noise(rng));
    }
    Eigen::Index white = 0;  // the brightest patch, preserved (corrected-3x3 needs a white)
    XYZ.col(1).maxCoeff(&white);
    recipe.characterisation.white_patch = ref.labels[white];
    std::size_t smallest = SIZE_MAX, largest = 0, largest_v1 = 0;
    std::string largest_model;
    double make_ms = 0, read_ms = 0, reproduce_ms = 0;
    int n = 0;
    for (const ModelInfo& m : model_table()) {
      if (m.n_terms > static_cast<int>(ref.XYZ.size()) - 2) continue;
      Recipe r = recipe;
      r.characterisation.model = m.id;
      r = complete_recipe(r);
      const TrainingSet t = training_set(r, ref.labels, RGB, XYZ);
      std::string payload;
      SharePayload made;
      make_ms += bench::time_ms([&] {
        made = share_payload(characterise(r, t), t, {{"chart.dng", sha256_hex("x")}});
        payload = encode_share_payload(made);
      });
      const std::string link = share_link(base, payload);
      const std::size_t v1 = share_link(base, encode_share_payload_v1(made)).size();
      SharePayload back;
      read_ms += bench::time_ms([&] { back = decode_share_payload(link); });
      Reproduction rep;
      reproduce_ms += bench::time_ms([&] { rep = reproduce_share(back); });
      std::printf("SIZE %s %s %zu (v1 %zu)%s\n", chart.c_str(), m.id.c_str(), link.size(), v1,
                  rep.verdict == "reproduced" ? "" : " (differs!)");
      smallest = std::min(smallest, link.size());
      largest_v1 = std::max(largest_v1, v1);
      if (link.size() > largest) { largest = link.size(); largest_model = m.id; }
      ++n;
    }
    std::printf("share-%s: %d models, links of %zu to %zu characters (largest: %s; version 1: up to %zu)\n", chart.c_str(), n,
                smallest, largest, largest_model.c_str(), largest_v1);
    std::printf("BENCH share-%s make %.3f\nBENCH share-%s read %.3f\nBENCH share-%s reproduce %.3f\n", chart.c_str(), make_ms / n,
                chart.c_str(), read_ms / n, chart.c_str(), reproduce_ms / n);
  }
  return 0;
}
