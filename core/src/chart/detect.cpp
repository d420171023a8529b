// Chart detection: the pipeline of detect.hpp, candidates, confidence and JSON.
#include "tristim/chart/detect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <exception>
#include <iterator>

#include "../detmath.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/linearisation/linearisation.hpp"

namespace tristim {

namespace {

using Point = Eigen::Vector2d;
constexpr double kPi = 3.14159265358979323846;

struct Target {
  std::string id;          // reported chart id
  LayoutOptions layout;
  ChartLayout grid;
  std::vector<Vec3> reference;  // per layout patch, or empty
};

std::vector<Target> targets(const DetectOptions& o) {
  std::vector<std::string> ids = o.charts;
  if (ids.empty()) ids = {"cc24", "sg140"};
  std::vector<Target> out;
  for (const auto& id : ids) {
    Target t;
    t.id = id;
    if (id == "custom") {
      t.layout = o.custom;
      t.layout.chart = "custom";
      t.grid = chart_layout(t.layout);
      if (!o.custom_reference.empty() && o.custom_reference.size() != t.grid.patches.size())
        throw Error(ErrorCode::InvalidArgument, "custom reference: " + std::to_string(o.custom_reference.size()) +
                                                    " colours for " + std::to_string(t.grid.patches.size()) + " patches");
      t.reference = o.custom_reference;
    } else {
      t.layout.chart = id;
      // The detector starts from the printed charts' gaps (ArgyllCMS's ColorCheckerSG.cht:
      // 12.675 mm patches at a 15.175 mm pitch; ColorCheckerPassport.cht: 12.4 at 15.0) and
      // fits the gap anyway; chart_layout's defaults (0 and 0.14) only serve sampling.
      if (id == "sg140" || id == "sg140-2005") t.layout.gap = 0.197;
      if (id == "passport") t.layout.gap = 0.21;
      t.grid = chart_layout(t.layout);  // UnknownId for an unknown chart
      const ReferenceChart ref = reference_chart(id, "D50");
      for (const auto& cell : t.grid.patches) {
        const auto it = std::find(ref.ids.begin(), ref.ids.end(), cell.id);
        if (it == ref.ids.end()) throw Error(ErrorCode::Internal, "reference of " + id + " lacks patch " + cell.id);
        t.reference.push_back(ref.XYZ[static_cast<size_t>(it - ref.ids.begin())]);
      }
    }
    out.push_back(std::move(t));
  }
  return out;
}

double clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }

bool contains(const std::array<double, 8>& k, const Point& p) {
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    const double c = (k[2 * j] - k[2 * i]) * (p.y() - k[2 * i + 1]) - (k[2 * j + 1] - k[2 * i + 1]) * (p.x() - k[2 * i]);
    if (c < 0) return false;
  }
  return true;
}

// The scores of the patches' colours against the reference read in each other orientation that
// maps the grid onto itself (180°, the two mirrors; and 90°/270° for a square grid). `cells`:
// the layout index (row-major) of each colour in rgb (a chart cut by the frame shows some).
std::vector<FitScores> symmetric_alternatives(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref, const std::vector<int>& cells,
                                              const std::vector<Point>& where, const std::vector<bool>& unreliable, int R, int C) {
  std::vector<FitScores> out;
  for (int t = 1; t < 8; ++t) {
    if (t % 2 == 1 && R != C) continue;  // 90° and 270° (and their mirrors) need a square grid
    std::vector<Vec3> permuted;
    for (int k : cells) {
      const int r = k / C, c = k % C;
      const int mc = t >= 4 ? C - 1 - c : c;  // mirror first
      int rr = r, cc = mc;
      if (t % 4 == 1) rr = mc, cc = R - 1 - r;          // quarter turn (square grids)
      if (t % 4 == 2) rr = R - 1 - r, cc = C - 1 - mc;  // half turn
      if (t % 4 == 3) rr = C - 1 - mc, cc = r;          // three quarters (square grids)
      permuted.push_back(ref[size_t(rr) * C + cc]);
    }
    out.push_back(reference_fit_scores(rgb, permuted, where, unreliable));
  }
  return out;
}

// "4×6": the rows × columns a lattice spans, fewer first.
std::string grid_size(const GridGroup& g) {
  const int a = g.p_max - g.p_min + 1, b = g.q_max - g.q_min + 1;
  return std::to_string(std::min(a, b)) + "×" + std::to_string(std::max(a, b));
}

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

Point centre_of(const std::array<double, 8>& k) {
  return Point((k[0] + k[2] + k[4] + k[6]) / 4, (k[1] + k[3] + k[5] + k[7]) / 4);
}

// What detection looks at: the image in linear light (`image`: colours, edges, sampling) and, for
// a stored image, its values as stored (`stored`, sRGB-encoded 8 or 16 bits), where the flat
// regions are found: there the noise is spread evenly over the levels, where decoding bunches
// the dark levels into steps that the flat-region test, tuned to sensor noise, splits apart.
struct Frames {
  const RawImage& image;
  const RawImage* stored = nullptr;
  FlatRegionOptions flat = {};
  bool regions = false;  // lattices grown into flat regions that are not quads too (group_regions)
};

// One pass of the pipeline on a working image of longer side <= working_side; its progress is
// reported as the part [from, to] of the whole.
std::vector<ChartCandidate> detect_pass(const Frames& frames, const std::vector<Target>& wanted,
                                        const DetectOptions& options, int working_side, double from, double to) {
  const RawImage& image = frames.image;
  auto progress = [&](const char* stage, double f) {
    if (options.progress) options.progress(stage, from + (to - from) * f);
  };
  progress("segment", 0.0);
  // The working image: the image itself when small enough (no copy), else box-downsampled.
  int factor = 1;
  RawImage scaled;
  if (std::max(image.width, image.height) > working_side) scaled = working_image(image, working_side, &factor);
  const RawImage& work = factor > 1 ? scaled : image;
  RawImage stored_scaled;
  if (frames.stored && factor > 1) stored_scaled = working_image(*frames.stored, working_side);
  const RawImage& segmented = !frames.stored ? work : factor > 1 ? stored_scaled : *frames.stored;
  const RegionLabels regions = flat_regions(segmented, frames.flat);
  progress("segment", 0.2);
  const std::vector<PatchQuad> quads = patch_quads(segmented, regions);
  progress("group", 0.3);
  std::vector<GridGroup> groups = group_grids(quads, 4);
  if (frames.regions) {
    std::vector<GridGroup> more = group_regions(quads, regions, 4);
    groups.insert(groups.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
    std::stable_sort(groups.begin(), groups.end(), [](const GridGroup& a, const GridGroup& b) { return a.cells.size() > b.cells.size(); });
  }
  progress("orient", 0.4);

  std::vector<ChartCandidate> found;
  // Why nothing was found, said once: about the largest grid (groups come largest first).
  std::string reasons;
  auto note = [&](const std::string& why) {
    if (reasons.empty()) reasons = why;
  };
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const GridGroup& group = groups[gi];
    // A candidate per layout; the group keeps the best.
    ChartCandidate best;
    bool have = false;
    progress("orient", 0.4 + 0.55 * gi / groups.size());
    for (const Target& t : wanted) {
      const std::vector<Placement> placements = place_layout(work, group, t.grid, t.reference);
      if (placements.empty()) {
        note("a grid of " + grid_size(group) + " found but it fits no " + t.id + " layout (" +
             std::to_string(t.grid.rows) + "×" + std::to_string(t.grid.columns) + ")");
        continue;
      }
      const Placement& p = placements.front();
      if (std::getenv("TRISTIM_DETECT_DEBUG")) {
        std::fprintf(stderr, "GROUP %zu cells %zu p %d..%d q %d..%d layout %s\n", gi, group.cells.size(), group.p_min,
                     group.p_max, group.q_min, group.q_max, t.id.c_str());
        for (size_t i = 0; i < std::min<size_t>(4, placements.size()); ++i)
          std::fprintf(stderr, "  placement t %d off %d,%d res %.4f inside %d mirrored %d found %d corners %.1f,%.1f %.1f,%.1f %.1f,%.1f %.1f,%.1f\n",
                       placements[i].transform, placements[i].offset[0], placements[i].offset[1], placements[i].residual,
                       placements[i].inside, placements[i].mirrored, placements[i].found, placements[i].corners[0],
                       placements[i].corners[1], placements[i].corners[2], placements[i].corners[3], placements[i].corners[4],
                       placements[i].corners[5], placements[i].corners[6], placements[i].corners[7]);
      }
      const int N = static_cast<int>(t.grid.patches.size());
      // Without reference colours every placement scores 0: take the one holding the most
      // found cells, inside the image, not mirrored, with A1 nearest the image's top-left.
      const Placement* chosen = &p;
      if (t.reference.empty()) {
        double best_d = 1e300;
        int most = -1;
        for (const auto& q : placements)
          if (!q.mirrored && q.inside && q.found >= most) {
            const double d = q.corners[0] + q.corners[1];
            if (q.found > most || d < best_d) best_d = d, chosen = &q, most = q.found;
          }
      }
      // A placement running off the image: a chart cut by the frame when at least half of the
      // layout's patches were found as quads; it is refined and sampled where it is visible.
      // A lattice of fewer cells (6 or more: glare or the frame took the rest) may place a cut
      // chart too, by the colours of every patch inside the image; it is kept only when sure
      // (below).
      bool cut = !chosen->inside;
      const bool thin = cut && static_cast<int>(group.cells.size()) * 2 < N;
      if (cut && (!options.cut_charts || (thin && group.cells.size() < 6))) {
        if (static_cast<int>(group.cells.size()) * 2 >= N)
          note("a grid of " + grid_size(group) + " fits the " + t.id +
               " layout only partly inside the image: the chart may be cut off by the frame");
        else
          note("a grid of " + grid_size(group) + " found but its colours do not fit the " + t.id +
               " chart (its best placement runs off the image)");
        continue;
      }
      if (chosen->mirrored) {
        note("a grid of " + grid_size(group) + " matches the " + t.id + " colours only mirrored");
        continue;
      }
      double runner_up = 1e9;
      for (const auto& q : placements)
        if (&q != chosen) runner_up = std::min(runner_up, q.residual);
      std::array<double, 8> corners;
      for (int i = 0; i < 8; ++i) corners[i] = chosen->corners[i] * factor;
      // Refinement: on the working image (wide search), then on the full image (narrow).
      const double pitch_w = std::sqrt(std::abs(
          (chosen->corners[4] - chosen->corners[0]) * (chosen->corners[7] - chosen->corners[3]) -
          (chosen->corners[5] - chosen->corners[1]) * (chosen->corners[6] - chosen->corners[2])) / 2 / N);
      progress("refine", 0.4 + 0.55 * (gi + 0.5) / groups.size());
      Refinement ref;
      if (factor > 1) {
        ref = refine_corners(work, t.layout, chosen->corners, 0.3 * pitch_w, true);
        for (int i = 0; i < 8; ++i) corners[i] = ref.corners[i] * factor;
        LayoutOptions lo = t.layout;
        lo.gap = ref.gap;
        ref = refine_corners(image, lo, corners, 1.5 * factor + 1, true);
      } else {
        ref = refine_corners(image, t.layout, corners, 0.3 * pitch_w, true);
      }
      corners = ref.corners;
      // (refined corners of a chart at the border may leave the image: sampled as cut too)
      for (int i = 0; i < 4 && options.cut_charts; ++i)
        cut = cut || corners[2 * i] < 0 || corners[2 * i + 1] < 0 || corners[2 * i] > image.width ||
              corners[2 * i + 1] > image.height;
      ChartCandidate c;
      c.chart = t.id;
      c.corners = corners;
      c.gap = ref.gap;
      c.edge_rms = ref.rms;
      c.edges = ref.edges;
      c.orientation_resolved = !t.reference.empty();
      c.coverage = double(chosen->found) / N;
      c.runner_up_residual = runner_up;
      double final_score = 0, alternative_score = 1e9;
      try {
        check_corners(corners, image.width, image.height, cut);
        LayoutOptions lo = t.layout;
        lo.gap = ref.gap;
        SampleOptions so;
        so.partial = cut;
        so.nonuniform_threshold = reference_fit_nonuniform;  // flags for the fit (below)
        const ChartSample s = sample_chart(image, lo, corners, so);
        c.missing = s.missing;
        if (!t.reference.empty()) {
          if (s.patches.size() < 6) throw Error(ErrorCode::CornersOutside, "fewer than 6 patches inside the image");
          // The visible patches (layout order) and their reference colours and places.
          std::vector<Vec3> rgb, ref_visible;
          std::vector<bool> unreliable;  // clipped or not uniform: glare, a shadow's edge
          std::vector<int> cells;
          std::vector<Point> where;
          size_t next = 0;
          for (size_t k = 0; k < t.grid.patches.size() && next < s.patches.size(); ++k) {
            const auto& cell = t.grid.patches[k];
            if (s.patches[next].id != cell.id) continue;
            const PatchSample& ps = s.patches[next++];
            rgb.emplace_back(ps.mean[0], ps.mean[1], ps.mean[2]);
            unreliable.push_back(std::any_of(ps.flags.begin(), ps.flags.end(), [](const std::string& f) {
              return f == "saturated" || f == "nonuniform";
            }));
            ref_visible.push_back(t.reference[k]);
            cells.push_back(static_cast<int>(k));
            where.emplace_back(t.grid.columns > 1 ? cell.column / (t.grid.columns - 1.0) : 0.5,
                               t.grid.rows > 1 ? cell.row / (t.grid.rows - 1.0) : 0.5);
          }
          // The found orientation and the symmetric ones, ranked by one model (rank_with_glare).
          std::vector<FitScores> rivals{reference_fit_scores(rgb, ref_visible, where, unreliable)};
          for (const FitScores& a : symmetric_alternatives(rgb, t.reference, cells, where, unreliable, t.grid.rows, t.grid.columns))
            rivals.push_back(a);
          const bool glare = rank_with_glare(rivals, 0);
          final_score = glare ? rivals[0].glare : rivals[0].plain;
          for (size_t a = 1; a < rivals.size(); ++a) alternative_score = std::min(alternative_score, glare ? rivals[a].glare : rivals[a].plain);
          std::vector<double> sorted;  // the residuals with the fitted glare taken off
          const std::vector<double> e = reference_fit_residuals(rgb, ref_visible, where, unreliable, &sorted);
          for (size_t k = 0; k < e.size(); ++k) c.patches.push_back({s.patches[k].id, e[k]});
          std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
          c.residual = sorted[sorted.size() / 2];
        } else {
          for (const auto& ps : s.patches) c.patches.push_back({ps.id, 0.0});
        }
      } catch (const Error& e) {
        note("a grid of " + grid_size(group) + " was found but its " + t.id + " corners are unusable: " + e.what());
        continue;
      }
      // Confidence: the colours agree (median residual) and no other orientation of the chart
      // comes close at the final corners (nor did another placement on the lattice), and the
      // patch edges were seen around most patches.
      c.supported = ref.supported;
      double margin = 0.6;
      if (!t.reference.empty()) {
        const double best_score = final_score;
        c.alternative_residual = alternative_score;
        const double ratio = std::min(alternative_score, runner_up / std::max(chosen->residual, 1e-6) * best_score) /
                             std::max(best_score, 1e-6);
        margin = clamp01((ratio - 1.5) / 1.5);
      }
      const double fit = t.reference.empty() ? clamp01(c.coverage + c.supported) : clamp01((0.3 - c.residual) / 0.2);
      const double support = clamp01(0.3 + c.supported);
      c.confidence = fit * margin * support;
      if (std::getenv("TRISTIM_DETECT_DEBUG"))
        std::fprintf(stderr, "CANDIDATE %s residual %.4f score %.4f alternative %.4f runner-up %.4f/%.4f supported %.2f conf %.3f\n",
                     t.id.c_str(), c.residual, final_score, alternative_score, runner_up, chosen->residual, c.supported, c.confidence);
      // A thin lattice's chart: its colours fit (fit, margin >= 0.9), half of its patches are inside
      // the image and the edges of 70 % of those were seen.
      const double visible = double(c.patches.size()), supported_visible = c.supported * N / std::max(1.0, visible);
      if (thin && (fit < 0.9 || margin < 0.9 || supported_visible < 0.7 || 2 * visible < N)) {
        note("a grid of " + grid_size(group) + " found but its colours do not fit the " + t.id +
             " chart (its best placement runs off the image)");
        continue;
      }
      c.angle = chart_angle(corners);
      c.orientation = static_cast<int>(std::lround(c.angle / 90.0)) % 4 * 90;
      if (c.confidence < options.min_confidence)
        note("a grid of " + grid_size(group) + " found but its colours do not fit the " + t.id + " chart (residual " +
             fixed(c.residual, 3) + ", confidence " + fixed(c.confidence, 2) + ")");
      if (!have || c.confidence > best.confidence) {
        best = c;
        have = true;
      }
    }
    if (have) found.push_back(best);
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const ChartCandidate& a, const ChartCandidate& b) { return a.confidence > b.confidence; });
  // One candidate per chart: drop any whose centre lies inside a better one.
  std::vector<ChartCandidate> out;
  for (const auto& c : found) {
    if (c.confidence < options.min_confidence) continue;
    bool dup = false;
    for (const auto& o : out) dup = dup || contains(o.corners, centre_of(c.corners)) || contains(c.corners, centre_of(o.corners));
    if (!dup && static_cast<int>(out.size()) < options.max_candidates) out.push_back(c);
  }
  if (out.empty()) {
    if (reasons.empty())
      reasons = regions.count == 0 ? "no flat regions: the image may be blurred, noisy or out of focus at this scale"
                : quads.empty()    ? "no flat region is shaped like a patch"
                                   : "the largest flat regions form no grid";
    throw Error(ErrorCode::ChartNotFound, reasons + " (" + std::to_string(regions.count) + " flat regions, " +
                                              std::to_string(quads.size()) + " patch-like regions, " +
                                              std::to_string(groups.size()) + " grids)");
  }
  return out;
}

}  // namespace

namespace {

// The image enlarged twice in each direction (bilinear; pixel (x, y) of the result covers
// [x/2, (x+1)/2) of the input, so coordinates scale by exactly 2), saturation bits copied.
RawImage upsampled(const RawImage& image) {
  RawImage out;
  out.meta = image.meta;
  out.width = 2 * image.width;
  out.height = 2 * image.height;
  out.rgb.resize(size_t(out.width) * out.height * 3);
  out.saturated.assign(size_t(out.width) * out.height, 0);
  const bool sat = image.saturated.size() == size_t(image.width) * image.height;
  for (int y = 0; y < out.height; ++y) {
    // centre (y + 0.5) / 2 - 0.5 in the input: y0 + 0.25 or 0.75 between rows y0, y0 + 1
    const int y0 = std::max(0, (y - 1) / 2), y1 = std::min(image.height - 1, (y + 1) / 2);
    const float wy = y0 == y1 ? 0.f : (y % 2 ? 0.25f : 0.75f);
    for (int x = 0; x < out.width; ++x) {
      const int x0 = std::max(0, (x - 1) / 2), x1 = std::min(image.width - 1, (x + 1) / 2);
      const float wx = x0 == x1 ? 0.f : (x % 2 ? 0.25f : 0.75f);
      float* o = &out.rgb[(size_t(y) * out.width + x) * 3];
      for (int c = 0; c < 3; ++c)
        o[c] = (1 - wy) * ((1 - wx) * image.at(x0, y0, c) + wx * image.at(x1, y0, c)) +
               wy * ((1 - wx) * image.at(x0, y1, c) + wx * image.at(x1, y1, c));
      if (sat) out.saturated[size_t(y) * out.width + x] = image.saturated[size_t(y / 2) * image.width + x / 2];
    }
  }
  return out;
}

// Only the candidates a second look may keep: confident, with a lattice holding at least half of
// the layout's patches (a chart whose patches are small in the coarse image may show a few cells,
// and a layout extrapolated from those can sit one cell off).
// With `edges_suffice`, a lattice of fewer cells will do when the refined grid's edges were seen
// around most patches (a chart of small patches in the enlarged image: the flat-region test keeps
// a few of them, the refinement on the image finds the rest).
void keep_sure(std::vector<ChartCandidate>& out, bool edges_suffice = false) {
  out.erase(std::remove_if(out.begin(), out.end(),
                           [&](const ChartCandidate& c) {
                             const bool lattice = c.coverage >= 0.5 || (edges_suffice && c.supported >= 0.7);
                             return !lattice || c.confidence < 0.9;
                           }),
            out.end());
}

// A pass that finds nothing: its candidates are none.
template <class Pass>
std::vector<ChartCandidate> or_none(Pass pass) {
  try {
    return pass();
  } catch (const Error& e) {
    if (e.code() != ErrorCode::ChartNotFound) throw;
  }
  return {};
}

// The passes over the whole of `image`.
std::vector<ChartCandidate> detect_image(const Frames& frames, const std::vector<Target>& wanted,
                                         const DetectOptions& options) {
  const RawImage& image = frames.image;
  // The pass at `working_side` first: it finds every chart from a few % of the frame up, so
  // several charts give several candidates. When it finds none and a coarser working image
  // (longer side <= kCoarseSide) is smaller, a pass on that: a large chart whose patches show
  // texture, noise or glare at the finer scale can still be flat there (scene 114 of the test
  // set). Either way the corners are refined on the full image. (A coarse pass first was faster
  // but, once it had found a chart, never looked for one too small for it.)
  // Last, when the first pass worked at full resolution and found nothing (DetectOptions::
  // finer_pass): a pass on the image enlarged twice. The patches of a chart of a few % of the
  // frame, ~10 px wide, lose most of their pixels to the flat-region test's smoothing and erosion
  // (a Digital SG of 2.4 % of 1200 × 800: 16 of its 140 patches kept as quads, no grid). A larger
  // image is left to the help: a seed's windows are searched at full resolution, then enlarged.
  constexpr int kCoarseSide = 1000;
  const int side = std::max(image.width, image.height), fine = std::max(1, options.working_side);
  const int fine_factor = (side + fine - 1) / fine;
  const bool coarse = (side + kCoarseSide - 1) / kCoarseSide > fine_factor;
  const bool finer = options.finer_pass && fine_factor == 1;
  const double first_share = coarse && finer ? 0.4 : coarse ? 0.7 : finer ? 0.5 : 1.0;
  std::exception_ptr first_miss;
  try {
    return detect_pass(frames, wanted, options, fine, 0.0, first_share);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::ChartNotFound || (!coarse && !finer)) throw;
    first_miss = std::current_exception();  // the reason reported when every pass misses
  }
  std::vector<ChartCandidate> out;
  if (coarse) {
    const double to = finer ? 0.6 : 1.0;
    out = or_none([&] { return detect_pass(frames, wanted, options, kCoarseSide, first_share, to); });
    keep_sure(out);
  }
  if (out.empty() && finer) {
    const RawImage large = upsampled(image);
    RawImage stored_large;
    if (frames.stored) stored_large = upsampled(*frames.stored);
    Frames enlarged{large, frames.stored ? &stored_large : nullptr};
    // Bilinear enlargement correlates neighbouring pixels' noise: estimate_noise's second
    // difference then sees a quarter of its σ (0.31 against 1.22 σ), so the threshold is raised
    // by as much.
    enlarged.flat.noise_multiple = 4 * FlatRegionOptions{}.noise_multiple;
    enlarged.regions = true;
    out = or_none([&] { return detect_pass(enlarged, wanted, options, 2 * side, coarse ? 0.6 : first_share, 1.0); });
    for (auto& c : out)
      for (double& v : c.corners) v /= 2;
    keep_sure(out, true);
  }
  if (out.empty()) std::rethrow_exception(first_miss);
  return out;
}

// A copy of the pixels [x0, x1) × [y0, y1) of `image`.
RawImage crop(const RawImage& image, int x0, int y0, int x1, int y1) {
  RawImage out;
  out.meta = image.meta;
  out.width = x1 - x0;
  out.height = y1 - y0;
  out.rgb.resize(size_t(out.width) * out.height * 3);
  out.saturated.assign(size_t(out.width) * out.height, 0);
  const bool sat = image.saturated.size() == size_t(image.width) * image.height;
  for (int y = y0; y < y1; ++y) {
    const size_t from = size_t(y) * image.width + x0, to = size_t(y - y0) * out.width;
    std::copy_n(image.rgb.begin() + from * 3, size_t(out.width) * 3, out.rgb.begin() + to * 3);
    if (sat) std::copy_n(image.saturated.begin() + from, out.width, out.saturated.begin() + to);
  }
  return out;
}

// Detection within the window [x0, x1) × [y0, y1) (clamped to the image): a crop, so a chart
// that is small in the frame is searched at a finer working scale; corners come back in the
// image's coordinates. `from`..`to`: this window's share of the progress.
std::vector<ChartCandidate> detect_window(const Frames& frames, const std::vector<Target>& wanted,
                                          const DetectOptions& options, double x0, double y0, double x1, double y1,
                                          double from, double to) {
  const RawImage& image = frames.image;
  const int ix0 = std::max(0, static_cast<int>(std::floor(x0))), iy0 = std::max(0, static_cast<int>(std::floor(y0)));
  const int ix1 = std::min(image.width, static_cast<int>(std::ceil(x1)));
  const int iy1 = std::min(image.height, static_cast<int>(std::ceil(y1)));
  if (ix1 - ix0 < 16 || iy1 - iy0 < 16)
    throw Error(ErrorCode::InvalidArgument, "box: the region searched lies outside the image or is under 16 px across");
  DetectOptions o = options;
  if (options.progress)
    o.progress = [&](const std::string& stage, double f) { options.progress(stage, from + (to - from) * f); };
  if (ix0 == 0 && iy0 == 0 && ix1 == image.width && iy1 == image.height) return detect_image(frames, wanted, o);
  const RawImage part = crop(image, ix0, iy0, ix1, iy1);
  RawImage stored_part;
  if (frames.stored) stored_part = crop(*frames.stored, ix0, iy0, ix1, iy1);
  std::vector<ChartCandidate> out = detect_image(Frames{part, frames.stored ? &stored_part : nullptr}, wanted, o);
  for (auto& c : out)
    for (int k = 0; k < 4; ++k) c.corners[2 * k] += ix0, c.corners[2 * k + 1] += iy0;
  // A chart cut by the window but not by the image is left to a larger window.
  out.erase(std::remove_if(out.begin(), out.end(),
                           [&](const ChartCandidate& c) {
                             if (c.missing.empty()) return false;
                             for (int k = 0; k < 4; ++k) {
                               const double x = c.corners[2 * k], y = c.corners[2 * k + 1];
                               if ((x < ix0 && ix0 > 0) || (x > ix1 && ix1 < image.width) || (y < iy0 && iy0 > 0) ||
                                   (y > iy1 && iy1 < image.height))
                                 return true;
                             }
                             return false;
                           }),
            out.end());
  if (out.empty()) throw Error(ErrorCode::ChartNotFound, "the chart found runs off the window searched");
  return out;
}

// Whether `p` lies within the candidate's grid enlarged by `grow` about its centre.
bool near_candidate(const ChartCandidate& c, const Point& p, double grow) {
  const Point m = centre_of(c.corners);
  std::array<double, 8> k;
  for (int i = 0; i < 4; ++i) {
    k[2 * i] = m.x() + grow * (c.corners[2 * i] - m.x());
    k[2 * i + 1] = m.y() + grow * (c.corners[2 * i + 1] - m.y());
  }
  return contains(k, p);
}

std::vector<double> checked(const std::vector<double>& v, size_t n, const char* name) {
  if (v.size() != n)
    throw Error(ErrorCode::InvalidArgument, std::string(name) + ": expected " + std::to_string(n) + " numbers, got " +
                                                std::to_string(v.size()));
  for (double x : v)
    if (!std::isfinite(x)) throw Error(ErrorCode::InvalidArgument, std::string(name) + ": a number is not finite");
  return v;
}

// Detection helped by a point on or near the chart: windows centred on the seed, growing from an
// eighth of the image's longer side to the whole image; the first that finds a chart covering
// the seed wins. Small windows see a small chart at full resolution;
// a window that cuts a large chart finds nothing and the next one holds it.
std::vector<ChartCandidate> detect_near(const Frames& frames, const std::vector<Target>& wanted,
                                        const DetectOptions& options, const Point& seed) {
  const RawImage& image = frames.image;
  if (seed.x() < 0 || seed.y() < 0 || seed.x() >= image.width || seed.y() >= image.height)
    throw Error(ErrorCode::InvalidArgument, "seed: (" + fixed(seed.x(), 1) + ", " + fixed(seed.y(), 1) +
                                                ") lies outside the " + std::to_string(image.width) + "×" +
                                                std::to_string(image.height) + " image");
  const double side = std::max(image.width, image.height);
  const double halves[] = {side / 8, side / 5, side / 3, side / 2, side};
  std::string why;
  for (size_t i = 0; i < std::size(halves); ++i) {
    const double h = halves[i];
    std::vector<ChartCandidate> out;
    try {
      out = detect_window(frames, wanted, options, seed.x() - h, seed.y() - h, seed.x() + h, seed.y() + h,
                          double(i) / std::size(halves), double(i + 1) / std::size(halves));
    } catch (const Error& e) {
      if (e.code() != ErrorCode::ChartNotFound) throw;
      why = e.what();
    }
    // Near: within the grid enlarged to twice its size, or within 5 % of the image's longer side of
    // its centre (a click just beside a small chart).
    out.erase(std::remove_if(out.begin(), out.end(),
                             [&](const ChartCandidate& c) {
                               return !near_candidate(c, seed, 2.0) && (centre_of(c.corners) - seed).norm() > 0.05 * side;
                             }),
              out.end());
    if (!out.empty()) return out;
    if (why.empty()) why = "the charts found lie away from it";
  }
  throw Error(ErrorCode::ChartNotFound, "no chart near the seed (" + fixed(seed.x(), 0) + ", " + fixed(seed.y(), 0) +
                                            "): " + why);
}

}  // namespace

std::vector<ChartCandidate> detect_charts(const RawImage& stored_or_linear, const DetectOptions& options) {
  const std::vector<Target> wanted = targets(options);
  if (stored_or_linear.width < 1 || stored_or_linear.height < 1 ||
      stored_or_linear.rgb.size() != size_t(stored_or_linear.width) * stored_or_linear.height * 3)
    throw Error(ErrorCode::InvalidArgument, "chart detection needs a non-empty RGB image");
  // A stored image (a phone's JPEG, a converter's TIFF or PNG) holds sRGB-encoded values; the
  // 3×3 fit against the reference wants linear light, so they are decoded with the sRGB curve
  // (IEC 61966-2-1) first — in a copy; the flat regions are still found in the stored values
  // (Frames). The corners do not depend on it.
  RawImage decoded;
  if (stored_or_linear.meta.encoding == "stored" && stored_or_linear.meta.white_level > 0) {
    decoded = stored_or_linear;
    const double full = stored_or_linear.meta.white_level;
    std::vector<float> table(256);
    for (int v = 0; v < 256; ++v) table[size_t(v)] = static_cast<float>(full * sRGB_decode(v / full));
    for (float& v : decoded.rgb) {
      const double x = std::min(full, std::max(0.0, double(v)));
      v = full == 255 && x == std::floor(x) ? table[size_t(x)] : static_cast<float>(full * sRGB_decode(x / full));
    }
  }
  const Frames frames{decoded.rgb.empty() ? stored_or_linear : decoded, decoded.rgb.empty() ? nullptr : &stored_or_linear};
  std::vector<ChartCandidate> out;
  if (!options.seed.empty()) {
    if (!options.box.empty()) throw Error(ErrorCode::InvalidArgument, "seed and box: give one of them");
    const std::vector<double> s = checked(options.seed, 2, "seed");
    out = detect_near(frames, wanted, options, Point(s[0], s[1]));
  } else if (!options.box.empty()) {
    const std::vector<double> b = checked(options.box, 4, "box");
    const double x0 = std::min(b[0], b[2]), x1 = std::max(b[0], b[2]), y0 = std::min(b[1], b[3]), y1 = std::max(b[1], b[3]);
    // A rough box: enlarged by a tenth of its size on each side, so a chart it cuts is still whole.
    const double mx = 0.1 * (x1 - x0), my = 0.1 * (y1 - y0);
    out = detect_window(frames, wanted, options, x0 - mx, y0 - my, x1 + mx, y1 + my, 0.0, 1.0);
  } else {
    out = detect_image(frames, wanted, options);
  }
  if (options.progress) options.progress("done", 1.0);
  return out;
}

double chart_angle(const std::array<double, 8>& corners) {
  const double dx = corners[2] - corners[0], dy = corners[3] - corners[1];
  const double a = std::fmod(detmath::atan2(dy, dx) * 180 / kPi + 360.0, 360.0);
  // A hair anticlockwise of 0 (e.g. 359.9996) is 0, not "360.00" in the two decimals printed.
  return a >= 360.0 - 0.005 ? 0.0 : a;
}

std::string candidates_to_json(const std::vector<ChartCandidate>& candidates) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o << "{\"candidates\":[";
  for (size_t i = 0; i < candidates.size(); ++i) {
    const ChartCandidate& c = candidates[i];
    o << (i ? "," : "") << "{\"chart\":\"" << c.chart << "\",\"corners\":[";
    o.precision(3);
    for (int k = 0; k < 4; ++k) o << (k ? "," : "") << '[' << c.corners[2 * k] << ',' << c.corners[2 * k + 1] << ']';
    o << "],\"confidence\":";
    o << c.confidence << ",\"orientation\":" << c.orientation;
    o.precision(2);
    o << ",\"angle\":" << c.angle << ",\"orientation_resolved\":" << (c.orientation_resolved ? "true" : "false");
    o.precision(4);
    o << ",\"residual\":" << c.residual << ",\"gap\":" << c.gap;
    o.precision(3);
    o << ",\"edge_rms\":" << c.edge_rms << ",\"edges\":" << c.edges << ",\"coverage\":" << c.coverage << ",\"patches\":[";
    o.precision(4);
    for (size_t k = 0; k < c.patches.size(); ++k)
      o << (k ? "," : "") << "{\"id\":\"" << c.patches[k].id << "\",\"residual\":" << c.patches[k].residual << '}';
    o << "],\"missing\":[";
    for (size_t k = 0; k < c.missing.size(); ++k) o << (k ? "," : "") << '"' << c.missing[k] << '"';
    o << "]}";
  }
  o << "]}\n";
  return o.str();
}

}  // namespace tristim
