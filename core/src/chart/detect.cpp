// Chart detection: the pipeline of detect.hpp, candidates, confidence and JSON.
#include "tristim/chart/detect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "../detmath.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"

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

// Best score of the patches' colours against the reference read in another orientation that
// maps the grid onto itself (180°, the two mirrors; and 90°/270° for a square grid).
double symmetric_alternatives(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref,
                              const std::vector<Point>& where, int R, int C) {
  double best = 1e9;
  for (int t = 1; t < 8; ++t) {
    if (t % 2 == 1 && R != C) continue;  // 90° and 270° (and their mirrors) need a square grid
    std::vector<Vec3> permuted(ref.size());
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < C; ++c) {
        const int mc = t >= 4 ? C - 1 - c : c;  // mirror first
        int rr = r, cc = mc;
        if (t % 4 == 1) rr = mc, cc = R - 1 - r;          // quarter turn (square grids)
        if (t % 4 == 2) rr = R - 1 - r, cc = C - 1 - mc;  // half turn
        if (t % 4 == 3) rr = C - 1 - mc, cc = r;          // three quarters (square grids)
        permuted[size_t(r) * C + c] = ref[size_t(rr) * C + cc];
      }
    best = std::min(best, reference_fit_score(rgb, permuted, where));
  }
  return best;
}

Point centre_of(const std::array<double, 8>& k) {
  return Point((k[0] + k[2] + k[4] + k[6]) / 4, (k[1] + k[3] + k[5] + k[7]) / 4);
}

// One pass of the pipeline on a working image of longer side <= working_side; its progress is
// reported as the part [from, to] of the whole.
std::vector<ChartCandidate> detect_pass(const RawImage& image, const std::vector<Target>& wanted,
                                        const DetectOptions& options, int working_side, double from, double to) {
  auto progress = [&](const char* stage, double f) {
    if (options.progress) options.progress(stage, from + (to - from) * f);
  };
  progress("segment", 0.0);
  // The working image: the image itself when small enough (no copy), else box-downsampled.
  int factor = 1;
  RawImage scaled;
  if (std::max(image.width, image.height) > working_side) scaled = working_image(image, working_side, &factor);
  const RawImage& work = factor > 1 ? scaled : image;
  const RegionLabels regions = flat_regions(work);
  progress("segment", 0.2);
  const std::vector<PatchQuad> quads = patch_quads(work, regions);
  progress("group", 0.3);
  const std::vector<GridGroup> groups = group_grids(quads, 4);
  progress("orient", 0.4);

  std::vector<ChartCandidate> found;
  std::string reasons;
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const GridGroup& group = groups[gi];
    // A candidate per layout; the group keeps the best.
    ChartCandidate best;
    bool have = false;
    progress("orient", 0.4 + 0.55 * gi / groups.size());
    for (const Target& t : wanted) {
      const std::vector<Placement> placements = place_layout(work, group, t.grid, t.reference);
      if (placements.empty()) continue;
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
      if (!chosen->inside) {
        if (static_cast<int>(group.cells.size()) * 2 >= N)
          reasons = "a grid of " + std::to_string(group.cells.size()) + " patches fits the " + t.id +
                    " layout only partly inside the image: the chart may be cut off by the frame";
        continue;
      }
      if (chosen->mirrored) {
        reasons = "a " + t.id + " grid matches its colours only mirrored";
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
        check_corners(corners, image.width, image.height);
        LayoutOptions lo = t.layout;
        lo.gap = ref.gap;
        const ChartSample s = sample_chart(image, lo, corners);
        if (!t.reference.empty()) {
          std::vector<Vec3> rgb;
          for (const auto& ps : s.patches) rgb.emplace_back(ps.mean[0], ps.mean[1], ps.mean[2]);
          std::vector<Point> where;
          for (const auto& cell : t.grid.patches)
            where.emplace_back(t.grid.columns > 1 ? cell.column / (t.grid.columns - 1.0) : 0.5,
                               t.grid.rows > 1 ? cell.row / (t.grid.rows - 1.0) : 0.5);
          final_score = reference_fit_score(rgb, t.reference, where);
          alternative_score = symmetric_alternatives(rgb, t.reference, where, t.grid.rows, t.grid.columns);
          const std::vector<double> e = reference_fit_residuals(rgb, t.reference, where);
          for (size_t k = 0; k < e.size(); ++k) c.patches.push_back({s.patches[k].id, e[k]});
          std::vector<double> sorted = e;
          std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
          c.residual = sorted[sorted.size() / 2];
        } else {
          for (const auto& ps : s.patches) c.patches.push_back({ps.id, 0.0});
        }
      } catch (const Error& e) {
        reasons = std::string("a ") + t.id + " grid was found but its corners are unusable: " + e.what();
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
      const double dx = corners[2] - corners[0], dy = corners[3] - corners[1];
      c.angle = std::fmod(detmath::atan2(dy, dx) * 180 / kPi + 360.0, 360.0);
      c.orientation = static_cast<int>(std::lround(c.angle / 90.0)) % 4 * 90;
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
    if (c.confidence < options.min_confidence) {
      if (reasons.empty())
        reasons = "the best grid (" + c.chart + ", confidence " + std::to_string(c.confidence).substr(0, 4) +
                  ") does not match the chart's colours well enough";
      continue;
    }
    bool dup = false;
    for (const auto& o : out) dup = dup || contains(o.corners, centre_of(c.corners)) || contains(c.corners, centre_of(o.corners));
    if (!dup && static_cast<int>(out.size()) < options.max_candidates) out.push_back(c);
  }
  if (out.empty())
    throw Error(ErrorCode::ChartNotFound,
                "no chart found (" + std::to_string(quads.size()) + " patch-like regions, " +
                    std::to_string(groups.size()) + " grids)" + (reasons.empty() ? "" : ": " + reasons));
  return out;
}

}  // namespace

std::vector<ChartCandidate> detect_charts(const RawImage& image, const DetectOptions& options) {
  const std::vector<Target> wanted = targets(options);
  if (image.width < 1 || image.height < 1 || image.rgb.size() != size_t(image.width) * image.height * 3)
    throw Error(ErrorCode::InvalidArgument, "chart detection needs a non-empty RGB image");
  // The pass at `working_side` first: it finds every chart from a few % of the frame up, so
  // several charts give several candidates. When it finds none and a coarser working image
  // (longer side <= kCoarseSide) is smaller, a pass on that: a large chart whose patches show
  // texture, noise or glare at the finer scale can still be flat there (scene 114 of the test
  // set). Either way the corners are refined on the full image. (A coarse pass first was faster
  // but, once it had found a chart, never looked for one too small for it.)
  constexpr int kCoarseSide = 1000;
  const int side = std::max(image.width, image.height), fine = std::max(1, options.working_side);
  const bool coarse = (side + kCoarseSide - 1) / kCoarseSide > (side + fine - 1) / fine;
  std::vector<ChartCandidate> out;
  try {
    out = detect_pass(image, wanted, options, fine, 0.0, coarse ? 0.7 : 1.0);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::ChartNotFound || !coarse) throw;
    try {
      out = detect_pass(image, wanted, options, kCoarseSide, 0.7, 1.0);
    } catch (const Error& e2) {
      if (e2.code() != ErrorCode::ChartNotFound) throw;
    }
    // Only confident candidates whose lattice holds at least half of the layout's patches: a
    // chart whose patches are small in the coarse image may show a few cells, and a layout
    // extrapolated from those can sit one cell off.
    out.erase(std::remove_if(out.begin(), out.end(),
                             [](const ChartCandidate& c) { return c.coverage < 0.5 || c.confidence < 0.9; }),
              out.end());
    if (out.empty()) throw;  // the finer pass's reason
  }
  if (options.progress) options.progress("done", 1.0);
  return out;
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
    o << "]}";
  }
  o << "]}\n";
  return o.str();
}

}  // namespace tristim
