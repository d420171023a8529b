// The detection test set (issue 12): synthetic photographs of ColorChecker Classic, Passport and
// Digital SG charts made by the virtual camera from a seed (tests/support/chart_scene.hpp), each
// run through tristim's detector; prints the detection rate, the median and 95th-percentile
// corner error and the rate of wrong orientations among accepted detections, per chart and in
// all. With --write DIR it also writes every scene as an 8-bit sRGB PPM (white balanced on the
// true white, for detectors that expect display images, e.g. OpenCV's mcc) and DIR/truth.csv
// with the true corners and tristim's result per image (read by compare_mcc.py).
//
//   detect_testset [--count 300] [--seed 1] [--source CHECKOUT] [--write DIR] [--verbose]
//                  [--only i]   (one scene, verbose: for debugging)
//                  [--scale k]  (images k times wider and higher, e.g. 2: 1800-3200 px wide, where
//                                detection works on a downsampled image; the same scenes otherwise)
//                  [--pairs]    (two charts per image instead: one of 10-30 % of the frame, any
//                                layout, and a Classic or SG of 3-6 %; both must be reported)
//                  [--dump]     (every candidate's corners and confidence per scene, one line each:
//                                to compare two builds of the detector exactly, e.g. with diff)
//                  [--no-finer] (DetectOptions::finer_pass false: the detector before issue 48's
//                                finer pass, for before/after figures)
//                  [--kinds all|k1,k2,…]  (issue 48's failure kinds instead, --count scenes each,
//                                default 20, 1200 × 800 × --scale: found, orientation, corner error,
//                                false positives and found after one click, per kind; chart_scene.hpp)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "chart_scene.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"

using namespace tristim;

namespace {

// "DUMP <scene> <chart> x1 y1 ... x4 y4 <confidence> <gap>" per candidate, or "DUMP <scene> none".
void dump(int scene, const std::vector<ChartCandidate>& cands) {
  if (cands.empty()) std::printf("DUMP %d none\n", scene);
  for (const auto& c : cands) {
    std::printf("DUMP %d %s", scene, c.chart.c_str());
    for (double v : c.corners) std::printf(" %.6f", v);
    std::printf(" %.6f %.6f\n", c.confidence, c.gap);
  }
}

// The candidates, or none when detection finds no chart (its reason in *why).
std::vector<ChartCandidate> detect_or_none(const RawImage& image, const DetectOptions& options, std::string* why) {
  try {
    return detect_charts(image, options);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::ChartNotFound) throw;
    *why = e.what();
  }
  return {};
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

void write_ppm(const std::string& path, const ChartScene& s) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(2);
  }
  std::fprintf(f, "P6\n%d %d\n255\n", s.image.width, s.image.height);
  std::vector<unsigned char> row(size_t(s.image.width) * 3);
  for (int y = 0; y < s.image.height; ++y) {
    for (int x = 0; x < s.image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = std::min(1.0, std::max(0.0, 0.9 * s.image.at(x, y, c) / s.white[c]));
        const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;  // sRGB
        row[size_t(x) * 3 + c] = static_cast<unsigned char>(std::lround(255 * e));
      }
    std::fwrite(row.data(), 1, row.size(), f);
  }
  std::fclose(f);
}

// Two charts per scene (random_two_chart_scene): every chart must come out as a candidate of its
// own, in the right orientation. Prints the rates per size and in all; returns the exit status.
int run_pairs(int count, std::uint64_t seed, double scale, const std::vector<const RawImage*>& photos, bool verbose,
              bool dumping, bool finer) {
  const char* larges[3] = {"cc24", "passport", "sg140"};
  const char* smalls[2] = {"sg140", "cc24"};
  const int widths[3] = {900, 1200, 1600};
  int both = 0, found[2] = {0, 0}, wrong = 0, stray = 0, n = 0;
  std::vector<double> errors[2], ms;
  for (int i = 0; i < count; ++i) {
    SceneRandom pick(seed * 7919 + static_cast<std::uint64_t>(i) + 1000003);
    const int w = static_cast<int>(std::lround(scale * widths[pick.integer(3)])), h = w * 2 / 3;
    const std::string large = larges[i % 3], small = smalls[i % 2];
    const TwoChartScene scene = random_two_chart_scene(large, small, seed * 100003 + static_cast<std::uint64_t>(i), w, h, photos);
    if (!scene.ok) {
      std::printf("  %3d skipped: the two charts overlap\n", i);
      continue;
    }
    ++n;
    DetectOptions options;
    options.finer_pass = finer;
    options.charts = {large};
    if (small != large) options.charts.push_back(small);
    std::string why;
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<ChartCandidate> cands = detect_or_none(scene.image, options, &why);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (dumping) dump(i, cands);
    const ChartScene* truths[2] = {&scene.large, &scene.small};
    bool ok[2] = {false, false};
    std::vector<bool> used(cands.size(), false);
    double err[2] = {NAN, NAN};
    for (int k = 0; k < 2; ++k)
      for (size_t j = 0; j < cands.size(); ++j) {
        const DetectionScore sc = score_detection(*truths[k], &cands[j].corners, cands[j].confidence);
        if (!sc.located) continue;
        used[j] = true;
        if (sc.oriented) {
          ok[k] = true;
          err[k] = sc.corner_error;
          errors[k].push_back(sc.corner_error);
        } else {
          ++wrong;
        }
      }
    for (size_t j = 0; j < cands.size(); ++j) stray += !used[j];
    found[0] += ok[0];
    found[1] += ok[1];
    both += ok[0] && ok[1];
    if (verbose)
      std::printf("  %3d %4dx%-4d %-8s %5.1f%% + %-5s %4.1f%% (tilt %4.1f): %zu candidates, large %s %.2f px, small %s %.2f px, %.0f ms\n",
                  i, w, h, large.c_str(), 100 * scene.large.area_fraction, small.c_str(), 100 * scene.small.area_fraction,
                  scene.small.spec.tilt_deg, cands.size(), ok[0] ? "ok" : "MISS", err[0], ok[1] ? "ok" : "MISS", err[1], ms.back());
  }
  std::printf("tristim chart detection, %d two-chart scenes (seed %llu, scale %g)\n", n, static_cast<unsigned long long>(seed), scale);
  std::printf("both found %.1f%%, large %.1f%%, small %.1f%%, wrong orientations %d, candidates at no chart %d\n",
              100.0 * both / std::max(1, n), 100.0 * found[0] / std::max(1, n), 100.0 * found[1] / std::max(1, n), wrong, stray);
  std::printf("corner error median/p95 px: large %.3f/%.3f, small %.3f/%.3f; median time %.1f ms\n", percentile(errors[0], 0.5),
              percentile(errors[0], 0.95), percentile(errors[1], 0.5), percentile(errors[1], 0.95), percentile(ms, 0.5));
  std::printf("RESULT pairs=%d both=%.4f wrong_orientation=%d stray=%d\n", n, double(both) / std::max(1, n), wrong, stray);
  return 0;
}

struct Tally {
  int n = 0, detected = 0, correct = 0, wrong_orientation = 0, misplaced = 0;
  std::vector<double> errors, ms;
};

}  // namespace

int main(int argc, char** argv) {
  int count = 300;
  std::uint64_t seed = 1;
  std::string source_dir = TRISTIM_SOURCE_DIR, write_dir;
  bool verbose = false;
  int only = -1;
  double scale = 1;
  bool pairs = false, dumping = false, count_given = false, finer = true;
  std::string kinds;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--count" && i + 1 < argc) count = std::atoi(argv[++i]), count_given = true;
    else if (a == "--kinds" && i + 1 < argc) kinds = argv[++i];
    else if (a == "--seed" && i + 1 < argc) seed = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--source" && i + 1 < argc) source_dir = argv[++i];
    else if (a == "--write" && i + 1 < argc) write_dir = argv[++i];
    else if (a == "--verbose") verbose = true;
    else if (a == "--only" && i + 1 < argc) only = std::atoi(argv[++i]), verbose = true;
    else if (a == "--scale" && i + 1 < argc) scale = std::atof(argv[++i]);
    else if (a == "--pairs") pairs = true;
    else if (a == "--dump") dumping = true;
    else if (a == "--no-finer") finer = false;
    else {
      std::fprintf(stderr, "usage: detect_testset [--count 300] [--seed 1] [--source CHECKOUT] [--write DIR] [--verbose] [--only i] [--scale k] [--pairs] [--dump] [--kinds all|k1,k2,...] [--no-finer]\n");
      return 2;
    }
  }
  if (!(scale > 0) || scale > 8) {
    std::fprintf(stderr, "detect_testset: --scale must lie in (0, 8]\n");
    return 2;
  }
  std::vector<RawImage> photos;
  try {
    photos = background_photos(source_dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "detect_testset: %s\n", e.what());
    return 1;
  }
  std::vector<const RawImage*> photo_ptrs;
  for (const auto& p : photos) photo_ptrs.push_back(&p);
  if (pairs) return run_pairs(count, seed, scale, photo_ptrs, verbose, dumping, finer);
  if (!kinds.empty()) {
    std::vector<std::string> list;
    for (size_t at = 0; kinds != "all" && at <= kinds.size();) {
      const size_t comma = std::min(kinds.find(',', at), kinds.size());
      list.push_back(kinds.substr(at, comma - at));
      at = comma + 1;
    }
    const int width = static_cast<int>(std::lround(1200 * scale));
    std::printf("tristim chart detection, issue 48's failure kinds: %d scenes each, %dx%d (seed %llu)\n",
                count_given ? count : 20, width, width * 2 / 3, static_cast<unsigned long long>(seed));
    DetectOptions base;
    base.finer_pass = finer;
    print_failure_kinds(run_failure_kinds(list, count_given ? count : 20, seed, width, photo_ptrs, verbose, base));
    return 0;
  }
  FILE* truth = nullptr;
  if (!write_dir.empty()) {
    truth = std::fopen((write_dir + "/truth.csv").c_str(), "w");
    if (!truth) {
      std::fprintf(stderr, "cannot write %s/truth.csv\n", write_dir.c_str());
      return 2;
    }
    std::fprintf(truth, "file,chart,width,height,x1,y1,x2,y2,x3,y3,x4,y4,gap,pitch,area,tristim_detected,tristim_located,"
                        "tristim_oriented,tristim_error,tristim_confidence,tristim_ms,tx1,ty1,tx2,ty2,tx3,ty3,tx4,ty4,"
                        "tristim_gap\n");
  }
  const char* charts[3] = {"cc24", "passport", "sg140"};
  const int widths[3] = {900, 1200, 1600};
  std::map<std::string, Tally> tally;
  for (int i = only >= 0 ? only : 0; i < (only >= 0 ? only + 1 : count); ++i) {
    const std::string chart = charts[i % 3];
    SceneRandom pick(seed * 7919 + static_cast<std::uint64_t>(i));
    const int w = static_cast<int>(std::lround(scale * widths[pick.integer(3)])), h = w * 2 / 3;
    const SceneSpec spec = random_scene_spec(chart, seed * 100003 + static_cast<std::uint64_t>(i), w, h, !photos.empty());
    const ChartScene scene = render_chart_scene(spec, photo_ptrs);
    LayoutOptions layout;
    layout.chart = chart;
    layout.gap = spec.gap;
    const double gap = chart_layout(layout).gap;
    DetectOptions options;
    options.charts = {chart};
    options.finer_pass = finer;
    std::string why;
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<ChartCandidate> found = detect_or_none(scene.image, options, &why);
    if (verbose && found.empty()) std::printf("  %3d %-8s not found: %s\n", i, chart.c_str(), why.c_str());
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (dumping) dump(i, found);
    const DetectionScore s = score_detection(scene, found.empty() ? nullptr : &found[0].corners,
                                             found.empty() ? 0.0 : found[0].confidence);
    for (const std::string key : {chart, std::string("all")}) {
      Tally& t = tally[key];
      ++t.n;
      t.ms.push_back(ms);
      t.detected += s.detected;
      t.correct += s.oriented;
      t.wrong_orientation += s.located && !s.oriented;
      t.misplaced += s.detected && !s.located;
      if (s.oriented) t.errors.push_back(s.corner_error);
    }
    if (verbose)
      std::printf("  %3d %-8s %4dx%-4d area %5.1f%% tilt %4.1f rot %5.1f blur %.1f glare %d photo %d: %s err %.2f px "
                  "(pitch %.1f) conf %.2f %.0f ms %s %s\n",
                  i, chart.c_str(), w, h, 100 * scene.area_fraction, spec.tilt_deg, spec.rotation_deg, spec.blur_sigma,
                  spec.glare_patches, spec.photo_background ? 1 : 0,
                  !s.detected ? "MISS" : s.oriented ? "ok" : s.located ? "WRONG-ORIENTATION" : "MISPLACED",
                  s.corner_error, s.pitch, s.confidence, ms, spec.illuminant.c_str(), spec.camera.c_str());
    if (truth) {
      char name[64];
      std::snprintf(name, sizeof name, "scene_%03d.ppm", i);
      write_ppm(write_dir + "/" + name, scene);
      std::fprintf(truth, "%s,%s,%d,%d", name, chart.c_str(), w, h);
      for (double v : scene.corners) std::fprintf(truth, ",%.3f", v);
      std::fprintf(truth, ",%.4f,%.3f,%.5f,%d,%d,%d,%.4f,%.4f,%.1f", gap, s.pitch, scene.area_fraction, s.detected,
                   s.located, s.oriented, s.detected ? s.corner_error : NAN, s.confidence, ms);
      for (int k = 0; k < 8; ++k) std::fprintf(truth, ",%.3f", found.empty() ? NAN : found[0].corners[k]);
      std::fprintf(truth, ",%.4f\n", found.empty() ? NAN : found[0].gap);
    }
  }
  if (truth) std::fclose(truth);
  std::printf("tristim chart detection, %d synthetic scenes (seed %llu)\n", count, static_cast<unsigned long long>(seed));
  std::printf("%-9s %4s %9s %9s %12s %10s %11s %11s %9s\n", "chart", "n", "detected", "correct", "wrong-orient",
              "misplaced", "median px", "p95 px", "median ms");
  for (const std::string key : {"cc24", "passport", "sg140", "all"}) {
    const Tally& t = tally[key];
    if (!t.n) continue;
    std::printf("%-9s %4d %8.1f%% %8.1f%% %12d %10d %11.3f %11.3f %9.1f\n", key.c_str(), t.n, 100.0 * t.detected / t.n,
                100.0 * t.correct / t.n, t.wrong_orientation, t.misplaced, percentile(t.errors, 0.5),
                percentile(t.errors, 0.95), percentile(t.ms, 0.5));
  }
  const Tally& all = tally["all"];
  std::printf("RESULT rate=%.4f median_px=%.4f p95_px=%.4f wrong_orientation=%d misplaced=%d\n",
              double(all.correct) / std::max(1, all.n), percentile(all.errors, 0.5), percentile(all.errors, 0.95),
              all.wrong_orientation, all.misplaced);
  return 0;
}
