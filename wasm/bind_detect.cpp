// Declarations: automatic chart detection (issue 12) on a decoded image (the RawImage handle as
// decoded: its dark/flat/light trap are not applied, as `tristim sample` and `tristim detect` detect
// on the decoded file, so the page's corners equal the CLI's). detectCharts(raw, options?: DetectOptions, onProgress?: (stage, fraction))
// -> ChartCandidate[], best first; CHART_NOT_FOUND when there is none. Corners are in the
// convention sampleChart takes (A1's outer corner first, clockwise; measurement-image pixels).
#include "tristim/chart/detect.hpp"
#include "raw_handle.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::val;
using emscripten::value_object;
using wasm::def;
using wasm::RawHandle;

namespace {

/// A JS function called with (stage, fraction) while the detector works; may be left out.
struct ProgressCallback {
  val fn = val::undefined();
};

}  // namespace

template <>
struct tristim::wasm::Conv<ProgressCallback> {
  static ProgressCallback from(const val& v) {
    if (!absent(v) && type_of(v) != "function") refuse("onProgress: expected a function, got " + type_of(v));
    return {v};
  }
};

namespace {

std::vector<ChartCandidate> detect(const RawHandle* h, DetectOptions options, const ProgressCallback& progress) {
  if (!wasm::absent(progress.fn))
    options.progress = [&](const std::string& stage, double fraction) { progress.fn(val(stage), val(fraction)); };
  return detect_charts(h->image, options);
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_detect) {
  { using S = DetectOptions; value_object<S>("DetectOptions") FIELD(charts) FIELD(custom) FIELD(custom_reference)
      FIELD(working_side) FIELD(seed) FIELD(box) FIELD(cut_charts) FIELD(min_confidence) FIELD(max_candidates); }
  { using S = PatchAgreement; value_object<S>("PatchAgreement") FIELD(id) FIELD(residual); }
  { using S = ChartCandidate; value_object<S>("ChartCandidate") FIELD(chart) FIELD(corners) FIELD(confidence)
      FIELD(orientation) FIELD(angle) FIELD(orientation_resolved) FIELD(residual) FIELD(runner_up_residual) FIELD(gap)
      FIELD(edge_rms) FIELD(edges) FIELD(coverage) FIELD(supported) FIELD(alternative_residual) FIELD(patches) FIELD(missing); }

  def<&detect>("detectCharts");
}
