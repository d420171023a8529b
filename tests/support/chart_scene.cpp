// Synthetic chart photographs for the detection tests (chart_scene.hpp).
#include "chart_scene.hpp"
#include "test_files.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "tristim/chart/detect.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSaturation = 15000;  // DN, a 14-bit sensor minus black

using Point = Eigen::Vector2d;

struct Shape {  // a background distractor: rotated rectangle or ellipse
  Point c;
  double a, b, angle;
  bool ellipse;
  Vec3 rgb;
};

Point apply(const Eigen::Matrix3d& H, double x, double y) {
  const Eigen::Vector3d q = H * Eigen::Vector3d(x, y, 1);
  return q.head<2>() / q.z();
}

// Camera RGB (white's G = 1) of every patch of `chart_id`, keyed like the layout.
std::vector<Vec3> patch_rgb(const std::string& chart_id, const ChartLayout& layout, const SpectralData& ssf,
                            const SpectralData& illuminant, Vec3* white) {
  const SpectralData refl = chart_reflectances(chart_id);
  const std::vector<Vec3> rgb = simulate_camera_RGB(ssf, refl, illuminant);
  SpectralData flat = refl;
  flat.names = {"white"};
  flat.values = {std::vector<double>(refl.wavelengths.size(), 1.0)};
  *white = simulate_camera_RGB(ssf, flat, illuminant)[0];
  std::vector<Vec3> out;
  for (const auto& cell : layout.patches) {
    const auto it = std::find(refl.names.begin(), refl.names.end(), cell.id);
    if (it == refl.names.end()) throw Error(ErrorCode::Internal, "no reflectance for " + cell.id);
    out.push_back(rgb[static_cast<size_t>(it - refl.names.begin())]);
  }
  return out;
}

void gaussian_blur(std::vector<float>& img, int w, int h, double sigma) {
  if (sigma < 0.2) return;
  const int r = static_cast<int>(std::ceil(3 * sigma));
  std::vector<float> k(2 * r + 1);
  float sum = 0;
  for (int i = -r; i <= r; ++i) sum += k[i + r] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)));
  for (auto& v : k) v /= sum;
  std::vector<float> tmp(img.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        float s = 0;
        for (int i = -r; i <= r; ++i) s += k[i + r] * img[(size_t(y) * w + std::min(w - 1, std::max(0, x + i))) * 3 + c];
        tmp[(size_t(y) * w + x) * 3 + c] = s;
      }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        float s = 0;
        for (int i = -r; i <= r; ++i) s += k[i + r] * tmp[(size_t(std::min(h - 1, std::max(0, y + i))) * w + x) * 3 + c];
        img[(size_t(y) * w + x) * 3 + c] = s;
      }
}

// A phone's processing of the scene: white balance on the true white (at 90 %), the sRGB
// curve, noise reduction (a 5×5 box mean where the local contrast is low, so edges stay), an
// unsharp mask (σ 1.2 px, amount 0.8), 8 bits; stored as a decoded JPEG's values (0..255). No
// JPEG blocks: the set has no encoder of its own.
void make_phone_like(ChartScene& s) {
  RawImage& o = s.image;
  const int W = o.width, Hh = o.height;
  std::vector<float> e(o.rgb.size());
  for (size_t i = 0; i < e.size(); ++i) {
    const double v = std::min(1.0, std::max(0.0, 0.9 * o.rgb[i] / s.white[i % 3]));
    e[i] = static_cast<float>(255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055));
  }
  std::vector<float> nr = e;
  for (int y = 2; y < Hh - 2; ++y)
    for (int x = 2; x < W - 2; ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0, lo = 1e9, hi = -1e9;
        for (int j = -2; j <= 2; ++j)
          for (int i = -2; i <= 2; ++i) {
            const double v = e[(size_t(y + j) * W + x + i) * 3 + c];
            sum += v, lo = std::min(lo, v), hi = std::max(hi, v);
          }
        if (hi - lo < 24) nr[(size_t(y) * W + x) * 3 + c] = static_cast<float>(sum / 25);
      }
  std::vector<float> blurred = nr;
  gaussian_blur(blurred, W, Hh, 1.2);
  o.meta.encoding = "stored";
  o.meta.layout = "rgb";
  o.meta.bits = 8;
  o.meta.white_level = 255;
  o.meta.saturation = {255, 255, 255};
  for (size_t i = 0; i < e.size(); ++i) {
    const double v = std::lround(std::min(255.0, std::max(0.0, nr[i] + 0.8 * (nr[i] - blurred[i]))));
    o.rgb[i] = static_cast<float>(v);
    if (v >= 255) o.saturated[i / 3] |= static_cast<std::uint8_t>(1u << (i % 3));
  }
  for (double& w : s.white) w = 255;
}

}  // namespace

SceneRandom::SceneRandom(std::uint64_t seed) : engine_(seed) {}
double SceneRandom::uniform() { return static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0); }
int SceneRandom::integer(int n) { return std::min(n - 1, static_cast<int>(uniform() * n)); }

SceneSpec random_scene_spec(const std::string& chart, std::uint64_t seed, int width, int height, bool photos) {
  SceneRandom rng(seed * 0x9E3779B97F4A7C15ull + 17);
  SceneSpec s;
  s.chart = chart;
  s.width = width;
  s.height = height;
  s.seed = seed;
  const auto cams = camera_names();
  s.camera = cams[static_cast<size_t>(rng.integer(static_cast<int>(cams.size())))];
  const char* illums[] = {"A", "D50", "D65", "D75", "F2", "F11"};
  s.illuminant = illums[rng.integer(6)];
  s.area_fraction = std::exp(rng.uniform(std::log(0.03), std::log(0.9)));
  s.tilt_deg = rng.uniform(0, s.area_fraction > 0.5 ? 20 : 45);
  s.tilt_axis_deg = rng.uniform(0, 360);
  s.rotation_deg = rng.uniform(0, 360);
  s.focal = rng.uniform(1.5, 6);
  s.cx = rng.uniform(0.3, 0.7);
  s.cy = rng.uniform(0.3, 0.7);
  // Gaps around the printed charts' (ArgyllCMS .cht: Classic 0.14, Passport 0.21, SG 0.197).
  s.gap = chart == "cc24" ? rng.uniform(0.1, 0.18) : rng.uniform(0.15, 0.25);
  s.exposure = std::exp(rng.uniform(std::log(0.05), std::log(0.8)));
  s.shot_gain = rng.uniform(0.5, 8);
  s.read_noise = rng.uniform(1, 8);
  s.blur_sigma = rng.uniform(0.3, 2.0);
  s.vignetting = rng.uniform(0, 0.5);
  s.gradient = rng.uniform(0, 0.3);
  if (rng.uniform() < 0.4) {
    s.glare_patches = 1 + rng.integer(2);
    s.glare_strength = rng.uniform(0.3, 1.5);
  }
  s.photo_background = photos && rng.uniform() < 0.5;
  return s;
}

ChartScene render_chart_scene(const SceneSpec& spec, const std::vector<const RawImage*>& photos) {
  const int W = spec.width, Hh = spec.height;
  SceneRandom rng(spec.seed);
  LayoutOptions lo;
  lo.chart = spec.chart;
  lo.gap = spec.gap;
  const ChartLayout layout = chart_layout(lo);
  const SpectralData ssf = camera_ssf(spec.camera), illum = illuminant_spd(spec.illuminant);
  Vec3 white;
  const std::string ref_id = spec.chart == "sg140" ? "sg140" : "cc24";
  const std::vector<Vec3> patches = patch_rgb(ref_id, layout, ssf, illum, &white);
  const std::vector<Vec3>& rgb = patches;  // white's G = 1 (simulate_camera_RGB's white_level)
  const Vec3 frame = 0.025 * white;
  // Other colours (distractors, the Passport's creative side): the SG's patches.
  LayoutOptions sg;
  sg.chart = "sg140";
  Vec3 unused;
  const std::vector<Vec3> others = patch_rgb("sg140", chart_layout(sg), ssf, illum, &unused);

  // Geometry: chart plane in 3D -> pinhole camera -> fitted into the frame.
  const double pw = layout.patches[0].u1 - layout.patches[0].u0, ph = layout.patches[0].v1 - layout.patches[0].v0;
  const double aspect = ph / pw;  // physical width / height of the grid (square patches)
  const double t = spec.tilt_deg * kPi / 180, ax = spec.tilt_axis_deg * kPi / 180, rot = spec.rotation_deg * kPi / 180;
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(rot, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(t, Eigen::Vector3d(std::cos(ax), std::sin(ax), 0)))
                                .toRotationMatrix();
  auto project = [&](double u, double v) {
    const Eigen::Vector3d P = R * Eigen::Vector3d((u - 0.5) * aspect, v - 0.5, 0) + Eigen::Vector3d(0, 0, spec.focal);
    return Point(P.x() / P.z(), P.y() / P.z());
  };
  std::array<Point, 4> k = {project(0, 0), project(1, 0), project(1, 1), project(0, 1)};
  auto area = [](const std::array<Point, 4>& q) {
    double a = 0;
    for (int i = 0; i < 4; ++i) a += q[i].x() * q[(i + 1) % 4].y() - q[(i + 1) % 4].x() * q[i].y();
    return std::abs(a) / 2;
  };
  double scale = std::sqrt(spec.area_fraction * W * Hh / area(k));
  Point centre(0, 0);
  for (const auto& p : k) centre += p / 4;
  const Point target(spec.cx * W, spec.cy * Hh);
  std::array<double, 8> corners{};
  for (int attempt = 0; attempt < 60; ++attempt) {
    bool fits = true;
    for (int i = 0; i < 4; ++i) {
      const Point p = target + scale * (k[i] - centre);
      corners[2 * i] = p.x();
      corners[2 * i + 1] = p.y();
      fits = fits && p.x() > 0.02 * W && p.y() > 0.02 * Hh && p.x() < 0.98 * W && p.y() < 0.98 * Hh;
    }
    if (fits || spec.allow_cut) break;
    scale *= 0.95;
  }
  const auto h9 = homography_unit_square(corners);
  Eigen::Matrix3d H;
  H << h9[0], h9[1], h9[2], h9[3], h9[4], h9[5], h9[6], h9[7], h9[8];
  const Eigen::Matrix3d Hi = H.inverse();

  ChartScene out;
  out.spec = spec;
  out.corners = corners;
  for (int c = 0; c < 3; ++c) out.white[c] = white[c] * spec.exposure * kSaturation;
  std::array<Point, 4> kk;
  for (int i = 0; i < 4; ++i) kk[i] = Point(corners[2 * i], corners[2 * i + 1]);
  out.area_fraction = area(kk) / (double(W) * Hh);
  for (int i = 0; i < 4; ++i)
    out.cut = out.cut || kk[i].x() < 0 || kk[i].y() < 0 || kk[i].x() > W || kk[i].y() > Hh;

  // Board around the grid (chart units): a frame of ~0.4 patch; the Passport adds its creative
  // side above the classic one.
  const double mu = 0.4 * pw, mv = 0.4 * ph;
  const bool passport = spec.chart == "passport";
  const double top = passport ? -1.25 : -mv;
  auto board = [&](double u, double v, Vec3& c) -> bool {
    if (u < -mu || u > 1 + mu || v < top || v > 1 + mv) return false;
    c = frame;
    if (u >= 0 && u < 1 && v >= 0 && v < 1) {
      const int col = std::min(layout.columns - 1, static_cast<int>(u / (pw * (1 + layout.gap))));
      const int row = std::min(layout.rows - 1, static_cast<int>(v / (ph * (1 + layout.gap))));
      const PatchCell& cell = layout.patches[size_t(row) * layout.columns + col];
      if (u >= cell.u0 && u < cell.u1 && v >= cell.v0 && v < cell.v1) c = rgb[size_t(row) * layout.columns + col];
    } else if (passport && v < -0.15 && v > -1.15 && u > 0 && u < 1) {
      // Creative side: 8 colours, a 5 × 2 block of near-neutrals, 8 greys (SG colours).
      const double y = (v + 1.15) / 1.0;  // 0..1 top to bottom
      if (y < 0.18) {
        const int i = static_cast<int>(u * 8);
        if (std::fmod(u * 8, 1.0) > 0.12 && y > 0.04) c = others[size_t(15 + 10 * i) % others.size()];
      } else if (y > 0.25 && y < 0.75 && u > 0.15 && u < 0.85) {
        const int i = static_cast<int>((u - 0.15) / 0.14), j = static_cast<int>((y - 0.25) / 0.25);
        if (std::fmod((u - 0.15) / 0.14, 1.0) > 0.1 && std::fmod((y - 0.25) / 0.25, 1.0) > 0.1)
          c = others[size_t(40 + 2 * i + 30 * j) % others.size()];
      } else if (y > 0.8 && y < 0.97) {
        const int i = static_cast<int>(u * 8);
        if (std::fmod(u * 8, 1.0) > 0.1) c = (0.03 + 0.11 * i) * white;
      }
    }
    return true;
  };
  // A grid-like object beside the chart, in its plane: 4 × 5 tiles of SG colours on a dark
  // board, half a grid's width to the right of the chart (distracts the lattice search).
  const double ox0 = 1 + mu + 0.35, ox1 = ox0 + 0.8;
  std::vector<size_t> tiles(spec.grid_object ? 20 : 0);  // no draw otherwise: other scenes stay as they were
  for (auto& t : tiles) t = size_t(rng.integer(static_cast<int>(others.size())));
  auto object = [&](double u, double v, Vec3& c) -> bool {
    if (!spec.grid_object || u < ox0 || u > ox1 || v < -0.05 || v > 1.05) return false;
    c = frame;
    const double a = (u - ox0) / (ox1 - ox0) * 5, b = (v + 0.05) / 1.1 * 4;
    if (std::fmod(a, 1.0) > 0.12 && std::fmod(b, 1.0) > 0.12)
      c = others[tiles[size_t(std::min(3, int(b))) * 5 + size_t(std::min(4, int(a)))]];
    return true;
  };
  const double reach_u = spec.grid_object ? ox1 : 1 + mu, reach_v0 = spec.grid_object ? std::min(top, -0.05) : top;

  // Background, one value per pixel.
  std::vector<float> img(size_t(W) * Hh * 3);
  const RawImage* photo = nullptr;
  if (spec.photo_background) {
    std::vector<const RawImage*> usable;
    for (const RawImage* p : photos)
      if (p && p->width > 16 && p->height > 16) usable.push_back(p);
    if (!usable.empty()) photo = usable[static_cast<size_t>(rng.integer(static_cast<int>(usable.size())))];
  }
  if (photo) {
    const double cw = photo->width * rng.uniform(0.4, 1.0);
    const double ch = std::min<double>(photo->height, cw * Hh / W);
    const double x0 = rng.uniform(0, photo->width - cw), y0 = rng.uniform(0, photo->height - ch);
    double mean = 0;
    for (size_t i = 1; i < photo->rgb.size(); i += 3 * 97) mean += photo->rgb[i];
    mean /= double(photo->rgb.size() / (3 * 97) + 1);
    const double gain = rng.uniform(0.1, 0.5) / std::max(mean, 1e-9);
    for (int y = 0; y < Hh; ++y)
      for (int x = 0; x < W; ++x) {
        const int sx = std::min(photo->width - 1, static_cast<int>(x0 + (x + 0.5) * cw / W));
        const int sy = std::min(photo->height - 1, static_cast<int>(y0 + (y + 0.5) * ch / Hh));
        for (int c = 0; c < 3; ++c) img[(size_t(y) * W + x) * 3 + c] = static_cast<float>(gain * photo->at(sx, sy, c));
      }
  } else {
    Vec3 c1 = rng.uniform(0.05, 0.6) * white, c2 = rng.uniform(0.05, 0.6) * white;
    for (int c = 0; c < 3; ++c) c1[c] *= rng.uniform(0.6, 1.4), c2[c] *= rng.uniform(0.6, 1.4);
    const double dir = rng.uniform(0, 2 * kPi);
    std::vector<Shape> shapes(20 + rng.integer(30));
    for (auto& s : shapes) {
      s.c = Point(rng.uniform(0, W), rng.uniform(0, Hh));
      s.a = rng.uniform(0.01, 0.2) * W;
      s.b = s.a * rng.uniform(0.3, 1.5);
      s.angle = rng.uniform(0, kPi);
      s.ellipse = rng.uniform() < 0.4;
      s.rgb = (rng.uniform() < 0.5 ? patches[size_t(rng.integer(static_cast<int>(patches.size())))]
                                    : others[size_t(rng.integer(static_cast<int>(others.size())))]) *
              rng.uniform(0.3, 1.2);
    }
    for (int y = 0; y < Hh; ++y)
      for (int x = 0; x < W; ++x) {
        const double f = 0.5 + 0.5 * std::sin(((x * std::cos(dir) + y * std::sin(dir)) / std::max(W, Hh)) * kPi);
        Vec3 c = (1 - f) * c1 + f * c2;
        for (const auto& s : shapes) {
          const Point d(x + 0.5 - s.c.x(), y + 0.5 - s.c.y());
          const double u = (d.x() * std::cos(s.angle) + d.y() * std::sin(s.angle)) / s.a;
          const double v = (-d.x() * std::sin(s.angle) + d.y() * std::cos(s.angle)) / s.b;
          if (s.ellipse ? u * u + v * v < 0.25 : std::abs(u) < 0.5 && std::abs(v) < 0.5) c = s.rgb;
        }
        for (int ch = 0; ch < 3; ++ch) img[(size_t(y) * W + x) * 3 + ch] = static_cast<float>(c[ch]);
      }
  }
  // The board, 3×3 supersampled (pixels whose centre maps near it).
  for (int y = 0; y < Hh; ++y)
    for (int x = 0; x < W; ++x) {
      const Point q = apply(Hi, x + 0.5, y + 0.5);
      if (q.x() < -mu - 0.1 || q.x() > reach_u + 0.1 || q.y() < reach_v0 - 0.1 || q.y() > 1 + mv + 0.1) continue;
      Vec3 sum = Vec3::Zero();
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
          const Point s = apply(Hi, x + (i + 0.5) / 3, y + (j + 0.5) / 3);
          Vec3 c;
          if (!board(s.x(), s.y(), c) && !object(s.x(), s.y(), c))
            for (int ch = 0; ch < 3; ++ch) c[ch] = img[(size_t(y) * W + x) * 3 + ch];
          sum += c;
        }
      for (int ch = 0; ch < 3; ++ch) img[(size_t(y) * W + x) * 3 + ch] = static_cast<float>(sum[ch] / 9);
    }
  // Glare: a Gaussian highlight (the illuminant's colour) on some patches.
  const double patch_px = std::sqrt(out.area_fraction * W * Hh / layout.patches.size()) / (1 + layout.gap);
  for (int g = 0; g < spec.glare_patches; ++g) {
    const PatchCell& cell = layout.patches[size_t(rng.integer(static_cast<int>(layout.patches.size())))];
    const Point c = apply(H, (cell.u0 + cell.u1) / 2 + rng.uniform(-0.3, 0.3) * pw, (cell.v0 + cell.v1) / 2 + rng.uniform(-0.3, 0.3) * ph);
    const double s = rng.uniform(0.25, 0.5) * patch_px;
    const int r = static_cast<int>(3 * s);
    for (int y = std::max(0, int(c.y()) - r); y < std::min(Hh, int(c.y()) + r); ++y)
      for (int x = std::max(0, int(c.x()) - r); x < std::min(W, int(c.x()) + r); ++x) {
        const double e = spec.glare_strength * std::exp(-0.5 * ((x + 0.5 - c.x()) * (x + 0.5 - c.x()) + (y + 0.5 - c.y()) * (y + 0.5 - c.y())) / (s * s));
        for (int ch = 0; ch < 3; ++ch) img[(size_t(y) * W + x) * 3 + ch] += static_cast<float>(e * white[ch]);
      }
  }
  // A cast shadow: the light beyond a line through the chart (random direction, within a quarter
  // of the grid of its centre) drops by `shadow`, over a soft edge of about a patch.
  if (spec.shadow > 0) {
    const double dir = rng.uniform(0, 2 * kPi);
    const Point through = apply(H, 0.5 + rng.uniform(-0.25, 0.25), 0.5 + rng.uniform(-0.25, 0.25));
    const double soft = std::max(1.0, 0.7 * patch_px);
    for (int y = 0; y < Hh; ++y)
      for (int x = 0; x < W; ++x) {
        const double d = (x + 0.5 - through.x()) * std::cos(dir) + (y + 0.5 - through.y()) * std::sin(dir);
        const double f = 1 - spec.shadow / (1 + std::exp(-d / (0.25 * soft)));
        for (int ch = 0; ch < 3; ++ch) img[(size_t(y) * W + x) * 3 + ch] *= static_cast<float>(f);
      }
  }
  // Uneven light: vignetting and a linear gradient.
  const double gdir = rng.uniform(0, 2 * kPi);
  for (int y = 0; y < Hh; ++y)
    for (int x = 0; x < W; ++x) {
      const double dx = (x + 0.5 - W / 2.0) / (W / 2.0), dy = (y + 0.5 - Hh / 2.0) / (Hh / 2.0);
      const double light = (1 - spec.vignetting * (dx * dx + dy * dy) / 2) *
                           (1 + spec.gradient * 0.5 * (dx * std::cos(gdir) + dy * std::sin(gdir)));
      for (int ch = 0; ch < 3; ++ch) img[(size_t(y) * W + x) * 3 + ch] *= static_cast<float>(light);
    }
  gaussian_blur(img, W, Hh, spec.blur_sigma);
  // Exposure, noise, clipping.
  RawImage& o = out.image;
  o.width = W;
  o.height = Hh;
  o.meta.make = "tristim";
  o.meta.model = "Synthetic chart scene";
  o.meta.layout = "bayer";
  o.meta.width = W;
  o.meta.height = Hh;
  o.meta.saturation = {kSaturation, kSaturation, kSaturation};
  o.rgb.resize(img.size());
  o.saturated.assign(size_t(W) * Hh, 0);
  GaussianNoise noise(spec.seed ^ 0xA5A5A5A5ull);
  for (size_t i = 0; i < img.size(); ++i) {
    const double dn = std::max(0.0, double(img[i])) * spec.exposure * kSaturation;
    double v = dn + std::sqrt(spec.shot_gain * dn + spec.read_noise * spec.read_noise) * noise.next();
    if (v >= kSaturation) {
      v = kSaturation;
      o.saturated[i / 3] |= static_cast<std::uint8_t>(1u << (i % 3));
    }
    o.rgb[i] = static_cast<float>(v);
  }
  if (spec.phone) make_phone_like(out);
  return out;
}

std::vector<RawImage> background_photos(const std::string& source_dir) {
  std::vector<RawImage> out;
  for (const char* f : {test::debian::canon_30d_cr2, test::kodak_dc50_kdc, test::passport_dng}) {
    const std::string path = test::test_file_path(source_dir, f);
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw Error(ErrorCode::InvalidArgument, "background photo not found: '" + path +
                                                  "' (tests/data/SOURCES.md says where it comes from)");
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string bytes = ss.str();
    RawImage img = decode_raw(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    if (std::string(f).find("passport") != std::string::npos) {  // keep the rows above the classic side
      img.height = std::min(img.height, 260);
      img.rgb.resize(size_t(img.width) * img.height * 3);
      img.saturated.resize(size_t(img.width) * img.height);
    }
    out.push_back(std::move(img));
  }
  return out;
}

namespace {

// Axis-aligned box [x0, x1) × [y0, y1) around a scene's chart board (the Passport's creative side
// included) plus `margin` px, clipped to the image.
std::array<int, 4> board_box(const ChartScene& s, double margin) {
  LayoutOptions lo;
  lo.chart = s.spec.chart;
  lo.gap = s.spec.gap;
  const ChartLayout layout = chart_layout(lo);
  const double mu = 0.4 * (layout.patches[0].u1 - layout.patches[0].u0);
  const double mv = 0.4 * (layout.patches[0].v1 - layout.patches[0].v0);
  const double top = s.spec.chart == "passport" ? -1.25 : -mv;
  const auto h9 = homography_unit_square(s.corners);
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (double u : {-mu, 1 + mu})
    for (double v : {top, 1 + mv}) {
      const double w = h9[6] * u + h9[7] * v + h9[8];
      const double x = (h9[0] * u + h9[1] * v + h9[2]) / w, y = (h9[3] * u + h9[4] * v + h9[5]) / w;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  const int W = s.spec.width, H = s.spec.height;
  return {std::max(0, static_cast<int>(std::floor(x0 - margin))), std::max(0, static_cast<int>(std::floor(y0 - margin))),
          std::min(W, static_cast<int>(std::ceil(x1 + margin))), std::min(H, static_cast<int>(std::ceil(y1 + margin)))};
}

}  // namespace

TwoChartScene render_two_chart_scene(const SceneSpec& large, const SceneSpec& small,
                                     const std::vector<const RawImage*>& photos) {
  TwoChartScene out;
  out.large = render_chart_scene(large, photos);
  out.small = render_chart_scene(small, photos);
  out.image = std::move(out.large.image);
  out.large.image = RawImage();
  const double margin = 4 + 3 * small.blur_sigma;
  const auto a = board_box(out.large, margin), b = board_box(out.small, margin);
  out.ok = small.width == large.width && small.height == large.height &&
           (a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1]);
  if (out.ok) {
    const int W = out.image.width;
    for (int y = b[1]; y < b[3]; ++y)
      for (int x = b[0]; x < b[2]; ++x) {
        const size_t i = size_t(y) * W + size_t(x);
        for (int c = 0; c < 3; ++c) out.image.rgb[3 * i + c] = out.small.image.rgb[3 * i + c];
        out.image.saturated[i] = out.small.image.saturated[i];
      }
  }
  out.small.image = RawImage();
  return out;
}

TwoChartScene random_two_chart_scene(const std::string& large_chart, const std::string& small_chart,
                                     std::uint64_t seed, int width, int height,
                                     const std::vector<const RawImage*>& photos) {
  SceneSpec a = random_scene_spec(large_chart, seed, width, height, !photos.empty());
  SceneSpec b = random_scene_spec(small_chart, seed ^ 0x5DEECE66Dull, width, height, !photos.empty());
  SceneRandom rng(seed * 0x2545F4914F6CDD1Dull + 3);
  a.area_fraction = rng.uniform(0.1, 0.3);
  a.cx = rng.uniform(0.3, 0.38);
  a.cy = rng.uniform(0.4, 0.6);
  b.area_fraction = rng.uniform(0.03, 0.06);
  b.cx = rng.uniform(0.8, 0.86);
  b.cy = rng.uniform(0.25, 0.75);
  b.camera = a.camera;
  b.illuminant = a.illuminant;
  b.exposure = a.exposure;
  b.photo_background = a.photo_background;
  TwoChartScene s;
  for (int attempt = 0; attempt < 8; ++attempt) {
    s = render_two_chart_scene(a, b, photos);
    if (s.ok) break;
    a.area_fraction *= 0.8;
  }
  return s;
}

DetectionScore score_detection(const ChartScene& scene, const std::array<double, 8>* corners, double confidence) {
  DetectionScore s;
  LayoutOptions lo;
  lo.chart = scene.spec.chart;
  const size_t n = chart_layout(lo).patches.size();
  s.pitch = std::sqrt(scene.area_fraction * scene.spec.width * scene.spec.height / double(n));
  if (!corners) return s;
  s.detected = true;
  s.confidence = confidence;
  double best = 1e300;
  int best_shift = 0;
  for (int shift = 0; shift < 4; ++shift) {
    double e = 0;
    for (int i = 0; i < 4; ++i) {
      const int j = (i + shift) % 4;
      e += std::hypot((*corners)[2 * j] - scene.corners[2 * i], (*corners)[2 * j + 1] - scene.corners[2 * i + 1]) / 4;
    }
    if (shift == 0) s.corner_error = e;
    if (e < best) best = e, best_shift = shift;
  }
  s.located = best < 0.25 * s.pitch;
  s.oriented = s.located && best_shift == 0;
  return s;
}

const std::vector<std::string>& failure_kinds() {
  static const std::vector<std::string> kinds = {"tilted-glare", "tilted-shadow", "tilted-glare-shadow",
                                                 "tilted-grid", "small",
                                                 "passport-open", "cut", "perspective", "phone-jpeg", "sg", "no-chart"};
  return kinds;
}

SceneSpec failure_kind_spec(const std::string& kind, int index, std::uint64_t seed, int width, int height, bool photos) {
  const char* charts[3] = {"cc24", "passport", "sg140"};
  std::string chart = charts[index % 3];
  if (kind == "passport-open") chart = "passport";
  if (kind == "sg") chart = "sg140";
  std::uint64_t h = seed * 1000003 + static_cast<std::uint64_t>(index);
  for (char c : kind) h = h * 131 + static_cast<unsigned char>(c);
  SceneSpec s = random_scene_spec(chart, h, width, height, photos);
  SceneRandom rng(h ^ 0x6A09E667F3BCC909ull);
  if (kind.rfind("tilted-", 0) == 0) {
    s.area_fraction = rng.uniform(0.30, 0.40);
    s.tilt_deg = rng.uniform(25, 33);
    s.focal = rng.uniform(2, 4);
    s.glare_patches = 0;
    if (kind == "tilted-glare") s.glare_patches = 2 + rng.integer(2), s.glare_strength = rng.uniform(1, 2);
    if (kind == "tilted-shadow") s.shadow = rng.uniform(0.5, 0.75);
    if (kind == "tilted-glare-shadow") {
      s.glare_patches = 2 + rng.integer(2), s.glare_strength = rng.uniform(1, 2);
      s.shadow = rng.uniform(0.5, 0.75);
    }
    if (kind == "tilted-grid") {
      s.grid_object = true;
      s.area_fraction = rng.uniform(0.2, 0.3);  // room for the object beside
      s.cx = rng.uniform(0.3, 0.4);
    }
  } else if (kind == "small") {
    s.area_fraction = rng.uniform(0.02, 0.035);
    s.tilt_deg = rng.uniform(0, 30);
  } else if (kind == "passport-open") {
    s.area_fraction = rng.uniform(0.08, 0.2);
    s.tilt_deg = rng.uniform(0, 30);
  } else if (kind == "cut") {
    s.area_fraction = rng.uniform(0.2, 0.35);
    s.tilt_deg = rng.uniform(0, 20);
    s.allow_cut = true;
    const double edge = rng.uniform(0.8, 0.88);
    switch (rng.integer(4)) {
      case 0: s.cx = edge; break;
      case 1: s.cx = 1 - edge; break;
      case 2: s.cy = edge; break;
      default: s.cy = 1 - edge; break;
    }
  } else if (kind == "perspective") {
    s.area_fraction = rng.uniform(0.15, 0.4);
    s.tilt_deg = rng.uniform(35, 50);
    s.focal = rng.uniform(1.2, 1.6);
  } else if (kind == "phone-jpeg") {
    s.phone = true;
    s.area_fraction = rng.uniform(0.08, 0.4);
  } else if (kind == "no-chart") {
    s.area_fraction = 1e-4;  // a chart of a few pixels: nothing to find
  } else if (kind != "sg") {
    throw Error(ErrorCode::UnknownId, "unknown failure kind '" + kind + "'");
  }
  return s;
}

namespace {

double percentile_of(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

}  // namespace

std::vector<KindFigures> run_failure_kinds(const std::vector<std::string>& kinds, int count, std::uint64_t seed,
                                           int width, const std::vector<const RawImage*>& photos, bool verbose,
                                           const DetectOptions& base) {
  std::vector<KindFigures> out;
  for (const std::string& kind : kinds.empty() ? failure_kinds() : kinds) {
    KindFigures f;
    f.kind = kind;
    for (int i = 0; i < count; ++i) {
      const SceneSpec spec = failure_kind_spec(kind, i, seed, width, width * 2 / 3, !photos.empty());
      const ChartScene scene = render_chart_scene(spec, photos);
      DetectOptions options = base;
      options.charts = {spec.chart};
      auto run = [&](const DetectOptions& o, std::string* why) {
        try {
          return detect_charts(scene.image, o);
        } catch (const Error& e) {
          if (e.code() != ErrorCode::ChartNotFound) throw;
          if (why) *why = e.what();
          return std::vector<ChartCandidate>{};
        }
      };
      std::string why;
      const auto t0 = std::chrono::steady_clock::now();
      const std::vector<ChartCandidate> found = run(options, &why);
      f.ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      ++f.n;
      const bool none = kind == "no-chart";
      DetectionScore best;
      for (const auto& c : found) {
        const DetectionScore sc = score_detection(scene, &c.corners, c.confidence);
        if (none || !sc.located) ++f.false_positives;
        if (!none && sc.located && (!best.located || (sc.oriented && !best.oriented))) best = sc;
      }
      f.found += best.oriented;
      f.wrong_orientation += best.located && !best.oriented;
      if (best.oriented) f.errors.push_back(best.corner_error);
      if (!none && !best.oriented && why.empty()) why = found.empty() ? "?" : "a candidate away from the chart";
      bool clicked = best.oriented;
      if (!none && !best.oriented) {
        f.why.push_back(why);
        // One click near the chart: its centre moved by up to a quarter of the grid's size.
        SceneRandom rng(seed * 31 + static_cast<std::uint64_t>(i) + 7);
        double cx = 0, cy = 0;
        for (int k = 0; k < 4; ++k) cx += scene.corners[2 * k] / 4, cy += scene.corners[2 * k + 1] / 4;
        const double size = std::sqrt(scene.area_fraction * spec.width * spec.height);
        cx = std::min(spec.width - 1.0, std::max(0.0, cx + rng.uniform(-0.25, 0.25) * size));
        cy = std::min(spec.height - 1.0, std::max(0.0, cy + rng.uniform(-0.25, 0.25) * size));
        DetectOptions helped = options;
        helped.seed = {cx, cy};
        for (const auto& c : run(helped, nullptr)) clicked = clicked || score_detection(scene, &c.corners, 0).oriented;
      }
      f.found_with_click += clicked;
      if (verbose)
        std::printf("  %-13s %3d %-8s area %5.1f%% tilt %4.1f: %s%s%s\n", kind.c_str(), i, spec.chart.c_str(),
                    100 * scene.area_fraction, spec.tilt_deg,
                    none ? (found.empty() ? "none (right)" : "FALSE POSITIVE") : best.oriented ? "found" : best.located ? "WRONG-ORIENTATION" : "MISS",
                    !none && !best.oriented ? (clicked ? ", found after a click" : ", missed after a click too") : "",
                    !none && !best.oriented ? (": " + why).c_str() : "");
    }
    out.push_back(std::move(f));
  }
  return out;
}

void print_failure_kinds(const std::vector<KindFigures>& figures) {
  std::printf("%-14s %4s %8s %7s %6s %10s %8s %11s %9s\n", "kind", "n", "found", "wrong-o", "false+", "median px",
              "p95 px", "with click", "median ms");
  for (const auto& f : figures)
    std::printf("%-14s %4d %7.1f%% %7d %6d %10.3f %8.3f %10.1f%% %9.1f\n", f.kind.c_str(), f.n,
                f.kind == "no-chart" ? NAN : 100.0 * f.found / std::max(1, f.n), f.wrong_orientation, f.false_positives,
                percentile_of(f.errors, 0.5), percentile_of(f.errors, 0.95),
                f.kind == "no-chart" ? NAN : 100.0 * f.found_with_click / std::max(1, f.n), percentile_of(f.ms, 0.5));
  for (const auto& f : figures)
    std::printf("KIND %s n=%d found=%d wrong_orientation=%d false_positives=%d found_with_click=%d median_px=%.4f\n",
                f.kind.c_str(), f.n, f.found, f.wrong_orientation, f.false_positives, f.found_with_click,
                percentile_of(f.errors, 0.5));
}

SceneSpec plain_scene_spec(const std::string& chart, double rotation, std::uint64_t seed) {
  SceneSpec s;
  s.chart = chart;
  s.width = 900;
  s.height = 600;
  s.area_fraction = 0.15;
  s.tilt_deg = 12;
  s.tilt_axis_deg = 30;
  s.rotation_deg = rotation;
  s.blur_sigma = 0.8;
  s.seed = seed;
  return s;
}

double max_corner_error(const std::array<double, 8>& a, const std::array<double, 8>& b) {
  double e = 0;
  for (int i = 0; i < 4; ++i) e = std::max(e, std::hypot(a[2 * i] - b[2 * i], a[2 * i + 1] - b[2 * i + 1]));
  return e;
}

}  // namespace tristim
