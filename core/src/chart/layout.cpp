// Chart layouts, homography (DLT) and patch sampling.
#include "tristim/chart/layout.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "tristim/capture/calibration.hpp"
#include "tristim/chart/layout_options_table.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

// rows × columns patches inside the margins; between neighbouring patches a gap of `gap` times
// the patch size, none outside the outer patches (the corners are the outer patch corners).
ChartLayout grid(const std::string& chart, int rows, int columns, double ml, double mt, double mr,
                 double mb, double gap) {
  ChartLayout L;
  L.chart = chart;
  L.rows = rows;
  L.columns = columns;
  L.gap = gap;
  const double w = (1.0 - ml - mr) / (columns + (columns - 1) * gap);
  const double h = (1.0 - mt - mb) / (rows + (rows - 1) * gap);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      PatchCell p;
      p.row = r;
      p.column = c;
      p.u0 = ml + c * w * (1 + gap);
      p.u1 = p.u0 + w;
      p.v0 = mt + r * h * (1 + gap);
      p.v1 = p.v0 + h;
      L.patches.push_back(p);
    }
  return L;
}

// Gap between patches / patch size. Classic 24 and Passport: measured on the example Passport
// photo (patches ~46 px, gaps ~6.5 px). SG: unknown here, taken as 0 (cells touch); the default
// 50 % sampling area stays well inside the patches either way.
constexpr double kClassicGap = 0.14;
constexpr double kSgGap = 0.0;

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// The bounds of a custom grid's numbers: layout_option_table()'s rows (the page's inputs and
// `tristim sample --help` show the same).
const OptionSpec& bound(const std::string& name) {
  static const std::vector<OptionSpec> rows = layout_option_table();
  for (const OptionSpec& o : rows)
    if (o.name == name) return o;
  throw Error(ErrorCode::UnknownId, "layout option table: no row '" + name + "'");
}

std::string number_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace

std::vector<std::string> chart_layout_ids() {
  return {"cc24", "cc24-2005", "passport", "sg140", "sg140-2005", "custom"};
}

ChartLayout chart_layout(const LayoutOptions& o) {
  if (o.gap > bound("gap").max)
    throw Error(ErrorCode::InvalidArgument, "gap must be at most " + number_text(bound("gap").max) + " patch sizes");
  if (o.chart == "cc24" || o.chart == "cc24-2005" || o.chart == "passport") {
    // ColorChecker Classic / Passport classic side: 4 rows A-D, 6 columns 1-6; A1 = dark skin.
    ChartLayout L = grid(o.chart, 4, 6, 0, 0, 0, 0, o.gap >= 0 ? o.gap : kClassicGap);
    for (auto& p : L.patches) p.id = std::string(1, static_cast<char>('A' + p.row)) + std::to_string(p.column + 1);
    return L;
  }
  if (o.chart == "sg140" || o.chart == "sg140-2005") {
    // ColorChecker SG: 10 rows, 14 columns; id letter = COLUMN A-N, number = ROW 1-10.
    ChartLayout L = grid(o.chart, 10, 14, 0, 0, 0, 0, o.gap >= 0 ? o.gap : kSgGap);
    for (auto& p : L.patches) p.id = std::string(1, static_cast<char>('A' + p.column)) + std::to_string(p.row + 1);
    return L;
  }
  if (o.chart == "custom") {
    const OptionSpec &R = bound("rows"), &C = bound("columns");
    if (o.rows < R.min || o.columns < C.min || o.rows > R.max || o.columns > C.max)
      throw Error(ErrorCode::InvalidArgument, "a custom chart needs " + number_text(R.min) + ".." + number_text(R.max) +
                                                  " rows and " + number_text(C.min) + ".." + number_text(C.max) +
                                                  " columns, got " + std::to_string(o.rows) + " x " + std::to_string(o.columns));
    // A margin may pass its row's max (0.49: the page's box) as long as the opposite one leaves room.
    for (double m : {o.margin_left, o.margin_top, o.margin_right, o.margin_bottom})
      if (!(m >= bound("margin_left").min && m < 1))
        throw Error(ErrorCode::InvalidArgument, "margins must be fractions in [" + number_text(bound("margin_left").min) + ", 1)");
    if (!(o.margin_left + o.margin_right < 0.99) || !(o.margin_top + o.margin_bottom < 0.99))
      throw Error(ErrorCode::InvalidArgument, "margins leave no room for patches");
    ChartLayout L = grid("custom", o.rows, o.columns, o.margin_left, o.margin_top, o.margin_right,
                         o.margin_bottom, o.gap >= 0 ? o.gap : 0.0);
    for (auto& p : L.patches) p.id = "R" + std::to_string(p.row + 1) + "C" + std::to_string(p.column + 1);
    return L;
  }
  throw Error(ErrorCode::UnknownId, "unknown chart layout '" + o.chart +
                                        "' (known: cc24, cc24-2005, passport, sg140, sg140-2005, custom)");
}

std::array<double, 9> homography_unit_square(const std::array<double, 8>& corners) {
  const double src[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  // Normalise the image points (Hartley): centroid to 0, mean distance sqrt(2).
  double cx = 0, cy = 0;
  for (int i = 0; i < 4; ++i) {
    cx += corners[2 * i] / 4;
    cy += corners[2 * i + 1] / 4;
  }
  double md = 0;
  for (int i = 0; i < 4; ++i) {
    const double dx = corners[2 * i] - cx, dy = corners[2 * i + 1] - cy;
    md += std::sqrt(dx * dx + dy * dy) / 4;
  }
  const double s = md > 0 ? std::sqrt(2.0) / md : 1.0;
  Eigen::Matrix<double, 8, 9> A = Eigen::Matrix<double, 8, 9>::Zero();
  for (int i = 0; i < 4; ++i) {
    const double u = src[i][0] - 0.5, v = src[i][1] - 0.5;  // unit square centred
    const double x = (corners[2 * i] - cx) * s, y = (corners[2 * i + 1] - cy) * s;
    A.row(2 * i) << -u, -v, -1, 0, 0, 0, x * u, x * v, x;
    A.row(2 * i + 1) << 0, 0, 0, -u, -v, -1, y * u, y * v, y;
  }
  Eigen::JacobiSVD<Eigen::Matrix<double, 8, 9>> svd(A, Eigen::ComputeFullV);
  const Eigen::Matrix<double, 9, 1> h = svd.matrixV().col(8);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  Eigen::Matrix3d Tinv, Tsrc;  // image denormalisation, unit-square centring
  Tinv << 1 / s, 0, cx, 0, 1 / s, cy, 0, 0, 1;
  Tsrc << 1, 0, -0.5, 0, 1, -0.5, 0, 0, 1;
  Eigen::Matrix3d H = Tinv * Hn * Tsrc;
  H /= H(2, 2);
  std::array<double, 9> out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[r * 3 + c] = H(r, c);
  return out;
}

void check_corners(const std::array<double, 8>& k, int width, int height, bool may_leave_image) {
  for (int i = 0; i < 4; ++i) {
    const double x = k[2 * i], y = k[2 * i + 1];
    if (!std::isfinite(x) || !std::isfinite(y) || (!may_leave_image && (x < 0 || y < 0 || x > width || y > height))) {
      std::ostringstream ss;
      ss << "corner " << i + 1 << " (" << x << ", " << y << ") lies outside the " << width << " x "
         << height << " image";
      throw Error(ErrorCode::CornersOutside, ss.str());
    }
  }
  // Convex and clockwise in image coordinates (y down): every turn has a positive cross product.
  double area2 = 0;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4, l = (i + 2) % 4;
    const double t = cross(k[2 * j] - k[2 * i], k[2 * j + 1] - k[2 * i + 1], k[2 * l] - k[2 * j],
                           k[2 * l + 1] - k[2 * j + 1]);
    if (!(t > 0))
      throw Error(ErrorCode::CornersCrossed,
                  "the corners do not form a convex quadrilateral going clockwise from the top-left "
                  "(A1) corner: crossed, mirrored or collinear");
    area2 += k[2 * i] * k[2 * j + 1] - k[2 * j] * k[2 * i + 1];
  }
  if (!(std::abs(area2) / 2 >= 1.0))
    throw Error(ErrorCode::CornersCrossed, "the corners enclose less than one pixel");
}

ChartSample sample_chart(const RawImage& image, const LayoutOptions& layout_options,
                         const std::array<double, 8>& corners, const SampleOptions& options,
                         const FrameCalibration* calibration) {
  if (!(options.area > 0 && options.area <= 1))
    throw Error(ErrorCode::InvalidArgument, "sampling area must be in (0, 1], got " + std::to_string(options.area));
  if (image.width < 1 || image.height < 1) throw Error(ErrorCode::InvalidArgument, "empty image");
  if (calibration) calibration->check_compatible(image);
  ChartSample out;
  out.layout = chart_layout(layout_options);
  check_corners(corners, image.width, image.height, options.partial);
  out.homography = homography_unit_square(corners);
  Eigen::Matrix3d H;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H(r, c) = out.homography[r * 3 + c];
  const Eigen::Matrix3d Hi = H.inverse();
  const auto snap = [](double t) { return std::round(t * 1e9) * 1e-9; };
  const auto fwd = [&](double u, double v) {
    const Eigen::Vector3d p = H * Eigen::Vector3d(u, v, 1);
    return std::array<double, 2>{p(0) / p(2), p(1) / p(2)};
  };
  const auto noise = calibration ? calibration->noise_floor() : std::array<double, 3>{0, 0, 0};
  const double half = options.area / 2;
  for (const auto& cell : out.layout.patches) {
    PatchSample s;
    s.id = cell.id;
    const double uc = (cell.u0 + cell.u1) / 2, vc = (cell.v0 + cell.v1) / 2;
    const double du = (cell.u1 - cell.u0) * half, dv = (cell.v1 - cell.v0) * half;
    const double u0 = uc - du, u1 = uc + du, v0 = vc - dv, v1 = vc + dv;
    s.centre = fwd(uc, vc);
    const double pu[4] = {cell.u0, cell.u1, cell.u1, cell.u0}, pv[4] = {cell.v0, cell.v0, cell.v1, cell.v1};
    const double su[4] = {u0, u1, u1, u0}, sv[4] = {v0, v0, v1, v1};
    for (int i = 0; i < 4; ++i) {
      const auto a = fwd(pu[i], pv[i]), b = fwd(su[i], sv[i]);
      s.quad[2 * i] = a[0];
      s.quad[2 * i + 1] = a[1];
      s.sample_quad[2 * i] = b[0];
      s.sample_quad[2 * i + 1] = b[1];
    }
    if (options.partial) {
      bool inside = true;
      for (int i = 0; i < 4; ++i)
        inside = inside && s.sample_quad[2 * i] >= 0 && s.sample_quad[2 * i] <= image.width &&
                 s.sample_quad[2 * i + 1] >= 0 && s.sample_quad[2 * i + 1] <= image.height;
      if (!inside) {
        out.missing.push_back(cell.id);
        continue;
      }
    }
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (auto uv : {std::array<double, 2>{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}}) {
      const auto p = fwd(uv[0], uv[1]);
      xmin = std::min(xmin, p[0]);
      xmax = std::max(xmax, p[0]);
      ymin = std::min(ymin, p[1]);
      ymax = std::max(ymax, p[1]);
    }
    const int x0 = std::max(0, static_cast<int>(std::floor(xmin))),
              x1 = std::min(image.width - 1, static_cast<int>(std::ceil(xmax)));
    const int y0 = std::max(0, static_cast<int>(std::floor(ymin))),
              y1 = std::min(image.height - 1, static_cast<int>(std::ceil(ymax)));
    // Pixel centres often fall exactly on a sample-area edge (an axis-aligned area with corners on
    // half pixels). Which side they land on must not depend on the last bit of the inverse
    // homography, which differs between builds (native SIMD vs wasm scalar): both sides of each
    // test are snapped to a 1e-9 grid in patch coordinates first.
    const double su0 = snap(u0), su1 = snap(u1), sv0 = snap(v0), sv1 = snap(v1), suc = snap(uc), svc = snap(vc);
    // Welford per channel, in double; raw (dark-subtracted, DN) means for the noise-floor test.
    std::array<double, 3> mean{}, m2{}, raw_mean{};
    std::array<int, 3> nsat{};
    // Quadrant sums (2 x 2 in patch coordinates) for the spatial uniformity test.
    std::array<std::array<double, 3>, 4> qsum{};
    std::array<int, 4> qn{};
    int n = 0;
    float cal[3], dn[3];
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector3d q = Hi * Eigen::Vector3d(x + 0.5, y + 0.5, 1);
        const double u = snap(q(0) / q(2)), v = snap(q(1) / q(2));
        if (u < su0 || u >= su1 || v < sv0 || v >= sv1) continue;
        if (calibration) {
          calibration->calibrated(image, x, y, cal);
          calibration->dark_subtracted(image, x, y, dn);
        } else {
          for (int c = 0; c < 3; ++c) cal[c] = dn[c] = image.at(x, y, c);
        }
        ++n;
        const int quadrant = (u >= suc ? 1 : 0) + (v >= svc ? 2 : 0);
        ++qn[quadrant];
        for (int c = 0; c < 3; ++c) qsum[quadrant][c] += cal[c];
        const std::uint8_t sat = image.saturated[static_cast<size_t>(y) * image.width + x];
        for (int c = 0; c < 3; ++c) {
          const double d = cal[c] - mean[c];
          mean[c] += d / n;
          m2[c] += d * (cal[c] - mean[c]);
          raw_mean[c] += (dn[c] - raw_mean[c]) / n;
          if (sat & (1u << c)) ++nsat[c];
        }
      }
    if (n < options.min_pixels)
      throw Error(ErrorCode::PatchTooSmall,
                  "patch " + cell.id + " covers " + std::to_string(n) + " pixel(s), fewer than " +
                      std::to_string(options.min_pixels) + ": give corners further apart, a larger area, or a closer photo");
    s.n = n;
    bool saturated = false, dark = false, nonuniform = false;
    for (int c = 0; c < 3; ++c) {
      s.mean[c] = mean[c];
      s.std[c] = n > 1 ? std::sqrt(m2[c] / (n - 1)) : 0.0;
      s.saturated_fraction[c] = static_cast<double>(nsat[c]) / n;
      saturated = saturated || nsat[c] > 0;
      const double floor = std::max(options.dark_fraction * image.meta.saturation[c], 3.0 * noise[c]);
      const bool is_dark = raw_mean[c] < floor;
      dark = dark || is_dark;
      // Non-uniform: the four quadrant means differ by more than the threshold (relative to the
      // mean) AND by more than 4 standard errors — a gradient, glare, dust or a patch border
      // inside the sample area. Pixel noise alone (large σ, flat patch) does not flag.
      if (!is_dark && mean[c] > 0 && *std::min_element(qn.begin(), qn.end()) > 0) {
        double qmin = 1e300, qmax = -1e300;
        for (int q = 0; q < 4; ++q) {
          const double m = qsum[q][c] / qn[q];
          qmin = std::min(qmin, m);
          qmax = std::max(qmax, m);
        }
        const double standard_error = s.std[c] / std::sqrt(n / 4.0);
        if (qmax - qmin > options.nonuniform_threshold * mean[c] && qmax - qmin > 4.0 * standard_error)
          nonuniform = true;
      }
    }
    if (saturated) s.flags.push_back("saturated");
    if (dark) s.flags.push_back("dark");
    if (nonuniform) s.flags.push_back("nonuniform");
    out.patches.push_back(std::move(s));
  }
  if (out.patches.empty())
    throw Error(ErrorCode::CornersOutside, "no patch's sample area lies inside the " + std::to_string(image.width) +
                                               " x " + std::to_string(image.height) + " image");
  return out;
}

std::string chart_sample_to_csv(const ChartSample& sample) {
  std::ostringstream o;
  o.precision(8);
  o << "patch,R,G,B,R_std,G_std,B_std,n,flags\n";
  for (const auto& p : sample.patches) {
    o << p.id;
    for (double v : p.mean) o << ',' << v;
    for (double v : p.std) o << ',' << v;
    o << ',' << p.n << ',';
    for (size_t i = 0; i < p.flags.size(); ++i) o << (i ? ";" : "") << p.flags[i];
    o << '\n';
  }
  return o.str();
}

}  // namespace tristim
