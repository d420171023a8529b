// The absolute chain's training chart (Guarnera 2018 section 4) as one virtual scene, shared by the
// Catch2 suite and tests/cli/absolute_fixture.cpp (no test framework, no files).
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/absolute/virtual_bracket.hpp"
#include "tristim/chart/reference.hpp"

namespace tristim::test {

/// 0, 30, …, 870 and 890 cd/m² (the paper's luminance training set).
inline std::vector<double> training_luminances() {
  std::vector<double> y;
  for (int v = 0; v <= 870; v += 30) y.push_back(v);
  y.push_back(890);
  return y;
}

struct TrainingChart {
  VirtualScene scene;
  std::vector<std::string> ids;  ///< per stimulus: "Y<cd/m²>", then the ColorChecker's patch ids
};

/// A width × height scene of the training chart: equal-tristimulus light at each of
/// training_luminances(), then the 24 ColorChecker colours (D65, white 700 cd/m²) projected, in
/// `cell`-pixel cells, `columns` per row, row by row; the last stimulus fills the rest of the frame.
inline TrainingChart training_chart(int width, int height, int columns, int cell) {
  const SpectralData E = projector_spectra({Vec3(1, 1, 1)}, {"E"});
  const ReferenceChart cc = reference_chart("cc24", "D65");
  std::vector<Vec3> targets;
  for (const auto& x : cc.XYZ) targets.push_back(x * 7.0);
  const SpectralData proj = projector_spectra(targets, cc.ids);
  TrainingChart t;
  VirtualScene& s = t.scene;
  s.width = width;
  s.height = height;
  s.stimuli = E;
  for (double y : training_luminances()) {
    if (!s.luminance.empty()) s.stimuli.values.push_back(E.values[0]), s.stimuli.names.push_back("E");
    s.luminance.push_back(y);
    t.ids.push_back("Y" + std::to_string(static_cast<int>(y)));
  }
  for (size_t k = 0; k < targets.size(); ++k) {
    s.stimuli.values.push_back(proj.values[k]);
    s.stimuli.names.push_back(cc.ids[k]);
    s.luminance.push_back(targets[k][1]);
    t.ids.push_back(cc.ids[k]);
  }
  const int n = static_cast<int>(t.ids.size());
  s.label.resize(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      s.label[static_cast<size_t>(y) * width + x] = static_cast<std::uint16_t>(std::min(n - 1, (y / cell) * columns + x / cell));
  return t;
}

}  // namespace tristim::test
