// The colorimetry lab's chart photographs (rules in tristim/lab/render.hpp).
#include "tristim/lab/render.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/jpeg_writer.hpp"
#include "tristim/lab/lab_options.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "tristim/chart/layout.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/linearisation/oecf_Shen2008.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim {

namespace {

constexpr double kBoard = 0.03;       // the chart's black board, flat reflectance
constexpr double kBackground = 0.2;   // the scene around the chart, flat reflectance
constexpr double kSgGap = 0.197;      // the printed SG's gap / patch (ArgyllCMS ColorCheckerSG.cht)

void check_range(double v, double lo, double hi, const char* what) {
  if (!(v >= lo && v <= hi))
    throw Error(ErrorCode::InvalidArgument, std::string(what) + " must be in [" + json::number_text(lo) + ", " +
                                                json::number_text(hi) + "], got " + json::number_text(v));
}

// The flat-reflectance response: ρ·w (the virtual camera is linear in the reflectance).
std::array<double, 3> scaled(const std::array<double, 3>& w, double k) { return {k * w[0], k * w[1], k * w[2]}; }

// Corners of a head-on grid filling 70 % of the frame's width (or 70 % of its height).
std::array<double, 8> centred_corners(const ChartLayout& layout, int width, int height) {
  const double pw = layout.patches[0].u1 - layout.patches[0].u0, ph = layout.patches[0].v1 - layout.patches[0].v0;
  const double aspect = ph / pw;  // grid width / height for square patches
  double gw = 0.7 * width, gh = gw / aspect;
  if (gh > 0.7 * height) {
    gh = 0.7 * height;
    gw = gh * aspect;
  }
  const double x0 = std::round((width - gw) / 2), y0 = std::round((height - gh) / 2);
  gw = std::round(gw);
  gh = std::round(gh);
  return {x0, y0, x0 + gw, y0, x0 + gw, y0 + gh, x0, y0 + gh};
}

// DNG ColorMatrix1 (XYZ -> camera, CalibrationIlluminant1 = D65): least squares over the chart's
// patches under D65, scaled so that D65's white maps to a camera neutral whose largest value is 1
// (DNG 1.6 ch. 6).
std::array<double, 9> colour_matrix_D65(const SpectralData& ssf, const SpectralData& reflectances) {
  const SpectralData d65 = illuminant_spd("D65");
  const std::vector<Vec3> rgb = simulate_camera_RGB(ssf, reflectances, d65);
  const std::vector<Vec3> xyz = reflectances_to_XYZ(reflectances, d65);
  Eigen::MatrixXd X(xyz.size(), 3), C(rgb.size(), 3);
  for (size_t i = 0; i < xyz.size(); ++i) {
    X.row(static_cast<Eigen::Index>(i)) = xyz[i].transpose() / 100.0;
    C.row(static_cast<Eigen::Index>(i)) = rgb[i].transpose();
  }
  const Eigen::Matrix3d Mt = X.colPivHouseholderQr().solve(C);  // C ≈ X·Mᵀ
  const Eigen::Matrix3d M = Mt.transpose();
  const Eigen::Vector3d neutral = M * (illuminant_white_XYZ(d65) / 100.0);
  const double k = 1.0 / neutral.maxCoeff();
  std::array<double, 9> out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[static_cast<size_t>(3 * r + c)] = k * M(r, c);
  return out;
}

// One channel of measurement pixel (x, y) as stored, DN above black: the scene through fall-off,
// flare and (with `noise`) shot + read noise, rounded and clipped to [−black, saturation].
double pixel_dn(const LabRender& r, int x, int y, int c, GaussianNoise* noise) {
  const LabRenderOptions& o = r.options;
  const double cx = o.width / 2.0, cy = o.height / 2.0, r2max = cx * cx + cy * cy;
  const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
  const double f = o.falloff > 0 ? 1 - o.falloff * (dx * dx + dy * dy) / r2max : 1.0;
  const size_t ci = static_cast<size_t>(c);
  double v = r.scene[(static_cast<size_t>(y) * o.width + x) * 3 + ci] * f + o.flare * r.white[ci];
  if (noise) v += std::sqrt(std::max(0.0, o.shot_gain * v) + o.read_noise * o.read_noise) * noise->next();
  return std::min(std::max(std::round(v), -static_cast<double>(o.black)), r.saturation);
}

}  // namespace

LabRenderFiles lab_render_files(const LabRenderOptions& options, const std::string& format_given) {
  const std::string format = format_given.empty() ? "dng" : format_given;
  std::string kinds;  // the ids of lab_file_kinds(), the one list of what is written
  const LabFileKind* kind = nullptr;
  const std::vector<LabFileKind> all = lab_file_kinds();
  for (const LabFileKind& k : all) {
    kinds += (kinds.empty() ? "" : ", ") + k.id;
    if (k.id == format) kind = &k;
  }
  if (!kind) throw Error(ErrorCode::InvalidArgument, "lab render writes " + kinds + ", not '" + format + "'");
  if (!kind->through_oecf && options.oecf != "linear")
    throw Error(ErrorCode::InvalidArgument, "a DNG holds linear sensor data: the OECF must be 'linear' (write a .tiff for '" + options.oecf + "')");
  const LabRender r = render_lab_chart(options);
  if (format == "tiff") return {lab_render_tiff(r), lab_render_json(r, 65535).dump(1), lab_reference_csv(r)};
  if (format == "jpeg") {
    const auto bytes = lab_render_jpeg(r);  // the quality is checked before the truth is written
    json::Value truth = lab_render_json(r, 255);
    truth.set("jpeg_quality", options.jpeg_quality);
    return {bytes, truth.dump(1), lab_reference_csv(r)};
  }
  return {lab_render_dng(r), lab_render_json(r).dump(1), lab_reference_csv(r)};
}

std::string lab_reference_csv(const LabRender& render) {
  LabTable t{"lab-reference", {"id", "X", "Y", "Z"}, {}};
  for (const LabPatchTruth& p : render.patches)
    t.rows.push_back({p.cell.empty() ? p.id : p.cell, json::number_text(p.XYZ[0]), json::number_text(p.XYZ[1]),
                      json::number_text(p.XYZ[2])});
  return lab_table_csv(t);
}

LabRenderFiles lab_render_reflectance_files(LabRenderOptions options, const SpectralData& reflectances,
                                            const std::string& format) {
  options.reflectances = reflectances;
  return lab_render_files(options, format);
}

std::vector<std::string> lab_oecf_ids() { return {"linear", "sRGB", "gamma=1.8", "gamma=2.2"}; }

std::vector<std::string> lab_chart_ids() { return {"cc24", "passport", "sg140"}; }

std::array<int, 2> lab_grid_shape(int n) {
  if (n < 1) throw Error(ErrorCode::InvalidArgument, "lab render: a chart needs at least one patch");
  const int columns = static_cast<int>(std::ceil(std::sqrt(1.5 * n) - 1e-9));
  return {(n + columns - 1) / columns, columns};
}

SpectralData lab_munsell_selection(const std::string& selection) {
  const std::string text = selection.compare(0, 8, "munsell:") == 0 ? selection.substr(8) : selection;
  const SpectralData& all = munsell_reflectances();
  // A chip's hue page: its id up to the value ("5R" of "5R4/14", "10YR" of "10YR6/10").
  auto hue_of = [](const std::string& id) {
    size_t i = id.size();
    while (i > 0 && !std::isalpha(static_cast<unsigned char>(id[i - 1]))) --i;
    return id.substr(0, i);
  };
  SpectralData out;
  out.wavelengths = all.wavelengths;
  auto add = [&](size_t k) {
    if (std::find(out.names.begin(), out.names.end(), all.names[k]) != out.names.end()) return;
    out.names.push_back(all.names[k]);
    out.values.push_back(all.values[k]);
  };
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string token = text.substr(start, comma - start);
    start = comma + 1;
    if (token.empty()) continue;
    const auto it = std::find(all.names.begin(), all.names.end(), token);
    if (it != all.names.end()) {
      add(static_cast<size_t>(it - all.names.begin()));
      continue;
    }
    const size_t before = out.names.size();
    if (token.find('/') == std::string::npos)
      for (size_t k = 0; k < all.names.size(); ++k)
        if (hue_of(all.names[k]) == token) add(k);
    if (out.names.size() == before)
      throw Error(ErrorCode::UnknownId, "lab render: '" + token + "' is neither a Munsell chip (e.g. 5R4/14) nor a hue page (e.g. 5R)");
  }
  if (out.names.empty()) throw Error(ErrorCode::InvalidArgument, "lab render: 'munsell:' names no chip (e.g. munsell:5R4/14,10YR6/10)");
  return out;
}

double lab_encode(const LabRenderOptions& o, double dn, double saturation) {
  const double x = std::min(std::max(dn / saturation, 0.0), 1.0);
  if (o.oecf == "linear") return x;
  if (o.oecf == "sRGB" || o.oecf == "srgb") return sRGB_encode(x);
  if (o.oecf.compare(0, 6, "gamma=") == 0) {
    char* end = nullptr;
    const std::string g = o.oecf.substr(6);
    const double gamma = std::strtod(g.c_str(), &end);
    if (!g.empty() && *end == '\0' && gamma >= 0.2 && gamma <= 5) return std::pow(x, 1.0 / gamma);
  }
  throw Error(ErrorCode::InvalidArgument, "oecf must be linear, sRGB or gamma=<0.2..5>, got '" + o.oecf + "'");
}

namespace {

// The RGB image through the OECF at `full_scale` (65535: 16-bit TIFF, 255: 8-bit JPEG), one pixel per
// measurement pixel; fall-off, flare and noise as in the DNG (one noise draw per pixel and channel).
std::vector<std::uint16_t> encoded_rgb(const LabRender& r, double full_scale) {
  const LabRenderOptions& o = r.options;
  lab_encode(o, 0, 1);  // an unknown OECF fails before any work
  const bool noisy = o.shot_gain > 0 || o.read_noise > 0;
  GaussianNoise noise(o.seed);
  std::vector<std::uint16_t> rgb(static_cast<size_t>(r.width) * r.height * 3);
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x)
      for (int c = 0; c < 3; ++c)
        rgb[(static_cast<size_t>(y) * r.width + x) * 3 + static_cast<size_t>(c)] = static_cast<std::uint16_t>(
            std::lround(full_scale * lab_encode(o, pixel_dn(r, x, y, c, noisy ? &noise : nullptr), r.saturation)));
  return rgb;
}

}  // namespace

std::vector<std::uint8_t> lab_render_tiff(const LabRender& r) { return write_tiff_rgb16(encoded_rgb(r, 65535), r.width, r.height); }

std::vector<std::uint8_t> lab_render_jpeg(const LabRender& r) {
  const auto v = encoded_rgb(r, 255);
  return write_jpeg_rgb8(std::vector<std::uint8_t>(v.begin(), v.end()), r.width, r.height, r.options.jpeg_quality);
}

LabRender render_lab_chart(const LabRenderOptions& o) {
  const auto ids = lab_chart_ids();
  const bool munsell = o.reflectances.values.empty() && o.chart.compare(0, 8, "munsell:") == 0;
  const bool generated = munsell || !o.reflectances.values.empty();
  if (!generated && std::find(ids.begin(), ids.end(), o.chart) == ids.end())
    throw Error(ErrorCode::UnknownId, "lab render: unknown chart '" + o.chart + "' (cc24, passport, sg140, munsell:<chips> or reflectances)");
  if (o.width < 64 || o.height < 64 || o.width > 4000 || o.height > 4000)
    throw Error(ErrorCode::InvalidArgument, "lab render: --size must be 64..4000 pixels per side (the sensor is twice that)");
  lab_option("render.exposure", o.exposure);
  lab_option("render.falloff", o.falloff);
  lab_option("render.flare", o.flare);
  lab_option("render.shot_gain", o.shot_gain);
  lab_option("render.read_noise", o.read_noise);
  lab_option("render.seed", static_cast<double>(o.seed));
  check_range(o.bits, 10, 16, "bits");
  check_range(o.black, 0, (1 << o.bits) / 2, "black level");
  if (o.cfa.size() != 4 || std::count(o.cfa.begin(), o.cfa.end(), 'G') != 2 || o.cfa.find('R') == std::string::npos ||
      o.cfa.find('B') == std::string::npos)
    throw Error(ErrorCode::InvalidArgument, "lab render: CFA must be a 2x2 Bayer pattern (RGGB, BGGR, GRBG, GBRG), got '" + o.cfa + "'");

  const SpectralData ssf = o.sensitivities.values.empty() ? camera_ssf(o.camera) : o.sensitivities;
  const SpectralData illum = o.illuminant_spd.values.empty() ? illuminant_spd(o.illuminant) : o.illuminant_spd;
  SpectralData refl = munsell ? lab_munsell_selection(o.chart)
                     : generated ? o.reflectances
                                 : chart_reflectances(o.chart == "sg140" ? "sg140" : "cc24");
  if (!generated)
    for (auto& n : refl.names) n = normalise_patch_id(n);
  if (generated) {
    if (refl.names.size() < 3 || refl.names.size() > 2000)
      throw Error(ErrorCode::InvalidArgument, "lab render: a chart of one's own needs 3..2000 patches, '" + o.chart + "' has " +
                                                  std::to_string(refl.names.size()));
    for (size_t i = 0; i < refl.names.size(); ++i)
      if (std::find(refl.names.begin(), refl.names.begin() + static_cast<std::ptrdiff_t>(i), refl.names[i]) !=
          refl.names.begin() + static_cast<std::ptrdiff_t>(i))
        throw Error(ErrorCode::InvalidArgument, "lab render: patch id '" + refl.names[i] + "' appears twice in '" + o.chart + "'");
  }
  const SpectralData seen = o.surface.method == "none" ? refl : correct_surface(o.surface, refl);
  const std::vector<Vec3> response = simulate_camera_RGB(ssf, seen, illum);  // white's G = 1
  SpectralData flat = refl;
  flat.names = {"white"};
  flat.values = {std::vector<double>(refl.wavelengths.size(), 1.0)};
  const Vec3 w = simulate_camera_RGB(ssf, flat, illum)[0];
  const std::vector<Vec3> xyz = reflectances_to_XYZ(refl, illum);
  // The board's reflectance is flat kBoard (as drawn below: kBoard × the white's response), so its
  // XYZ is that of the flat spectrum under the same light; a generated grid's empty cells carry it.
  SpectralData board_refl = flat;
  board_refl.names = {"board"};
  board_refl.values = {std::vector<double>(refl.wavelengths.size(), kBoard)};
  const Vec3 board_xyz = reflectances_to_XYZ(board_refl, illum)[0];

  LayoutOptions lo;
  lo.chart = o.chart;
  if (o.chart == "sg140") lo.gap = kSgGap;
  if (generated) {  // the custom layout, gap 0, exactly as `tristim sample --chart custom` lays it
    const auto shape = lab_grid_shape(static_cast<int>(refl.names.size()));
    lo.chart = "custom";
    lo.rows = shape[0];
    lo.columns = shape[1];
  }
  const ChartLayout layout = chart_layout(lo);

  LabRender out;
  out.options = o;
  out.width = o.width;
  out.height = o.height;
  out.layout = layout.chart;
  out.rows = layout.rows;
  out.columns = layout.columns;
  out.saturation = static_cast<double>((1 << o.bits) - 1 - o.black);
  const double s = out.saturation, e = o.exposure;
  for (int c = 0; c < 3; ++c) out.white[static_cast<size_t>(c)] = e * s * w[c];
  const std::array<double, 3> flare = scaled(out.white, o.flare);

  bool given = false;
  for (double v : o.corners) given = given || v != 0;
  out.corners = given ? o.corners : centred_corners(layout, o.width, o.height);
  check_corners(out.corners, o.width, o.height);
  out.options.corners = out.corners;

  const std::array<double, 3> board = scaled(out.white, kBoard), background = scaled(out.white, kBackground);
  // Per layout cell: its response in DN (u = e·s·ρ) and the truth; a generated grid's cells past
  // the last reflectance show the board and are in the truth as board patches (id = the cell's).
  std::vector<std::array<double, 3>> patch_dn;
  for (size_t ci = 0; ci < layout.patches.size(); ++ci) {
    const PatchCell& cell = layout.patches[ci];
    size_t k = ci;
    if (!generated) {
      const auto it = std::find(refl.names.begin(), refl.names.end(), normalise_patch_id(cell.id));
      if (it == refl.names.end()) throw Error(ErrorCode::Internal, "lab render: no reflectance for patch " + cell.id);
      k = static_cast<size_t>(it - refl.names.begin());
    }
    LabPatchTruth t;
    t.board = generated && ci >= refl.names.size();
    t.id = t.board ? cell.id : generated ? refl.names[k] : cell.id;
    if (generated) t.cell = cell.id;
    std::array<double, 3> u{};
    for (int c = 0; c < 3; ++c) {
      const size_t ci = static_cast<size_t>(c);
      u[ci] = t.board ? board[ci] : e * s * response[k][c];
      t.linear[ci] = u[ci] * 1.0 + flare[ci];  // the pixel formula with f(r) = 1
      t.rgb[ci] = std::min(std::max(std::round(t.linear[ci]), -static_cast<double>(o.black)), s);
      t.XYZ[ci] = t.board ? board_xyz[c] : xyz[k][c];
    }
    patch_dn.push_back(u);
    out.patches.push_back(t);
  }

  // Chart coordinates of a point of the image.
  const auto h9 = homography_unit_square(out.corners);
  Eigen::Matrix3d H;
  H << h9[0], h9[1], h9[2], h9[3], h9[4], h9[5], h9[6], h9[7], h9[8];
  const Eigen::Matrix3d Hi = H.inverse();
  const PatchCell& p0 = layout.patches[0];
  const double pw = p0.u1 - p0.u0, ph = p0.v1 - p0.v0, margin = 0.4;
  // Which surface a point of the chart plane shows: -2 background, -1 board, else a patch index.
  auto surface_at = [&](double x, double y) -> int {
    const Eigen::Vector3d q = Hi * Eigen::Vector3d(x, y, 1);
    const double u = q.x() / q.z(), v = q.y() / q.z();
    if (u < -margin * pw || u > 1 + margin * pw || v < -margin * ph || v > 1 + margin * ph) return -2;
    if (u < 0 || u >= 1 || v < 0 || v >= 1) return -1;
    const int col = std::min(layout.columns - 1, static_cast<int>(u / (pw * (1 + layout.gap))));
    const int row = std::min(layout.rows - 1, static_cast<int>(v / (ph * (1 + layout.gap))));
    const size_t k = static_cast<size_t>(row) * layout.columns + col;
    const PatchCell& cell = layout.patches[k];
    return u >= cell.u0 && u < cell.u1 && v >= cell.v0 && v < cell.v1 ? static_cast<int>(k) : -1;
  };
  auto dn_of = [&](int k) -> const std::array<double, 3>& {
    return k >= 0 ? patch_dn[static_cast<size_t>(k)] : k == -1 ? board : background;
  };

  // Noise-free linear image (before flare), 3×3 supersampled where a pixel straddles an edge.
  const size_t n_pix = static_cast<size_t>(o.width) * o.height;
  std::vector<double> img(n_pix * 3);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      int k[9];
      bool same = true;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
          k[3 * j + i] = surface_at(x + (i + 0.5) / 3, y + (j + 0.5) / 3);
          same = same && k[3 * j + i] == k[0];
        }
      double* px = &img[(static_cast<size_t>(y) * o.width + x) * 3];
      for (int c = 0; c < 3; ++c) {
        if (same) {
          px[c] = dn_of(k[0])[static_cast<size_t>(c)];
        } else {
          double sum = 0;
          for (int i = 0; i < 9; ++i) sum += dn_of(k[i])[static_cast<size_t>(c)];
          px[c] = sum / 9;
        }
      }
    }

  out.scene = img;
  // Sensor: fall-off, flare, noise, rounding, clipping; one value per CFA site.
  const int sw = 2 * o.width, sh = 2 * o.height;
  out.sensor.resize(static_cast<size_t>(sw) * sh);
  const bool noisy = o.shot_gain > 0 || o.read_noise > 0;
  GaussianNoise noise(o.seed);
  const std::string rgb = "RGB";
  int channel[4];
  for (int i = 0; i < 4; ++i) channel[i] = static_cast<int>(rgb.find(o.cfa[static_cast<size_t>(i)]));
  for (int y = 0; y < sh; ++y)
    for (int x = 0; x < sw; ++x) {
      const int bx = x / 2, by = y / 2, c = channel[2 * (y % 2) + (x % 2)];
      const double v = pixel_dn(out, bx, by, c, noisy ? &noise : nullptr);
      out.sensor[static_cast<size_t>(y) * sw + x] = static_cast<std::uint16_t>(v + o.black);
    }

  out.dng.make = "tristim lab";
  out.dng.model = o.camera;
  out.dng.cfa = o.cfa;
  out.dng.black = static_cast<std::uint16_t>(o.black);
  out.dng.white = static_cast<std::uint16_t>((1 << o.bits) - 1);
  out.dng.color_matrix = colour_matrix_D65(ssf, refl);
  out.dng.as_shot_neutral = {w[0] / w[1], 1.0, w[2] / w[1]};
  out.dng.exposure_s = 1.0 / 125;
  out.dng.f_number = 8;
  out.dng.iso = 100;
  return out;
}

std::vector<std::uint8_t> lab_render_dng(const LabRender& r) {
  return write_dng(r.sensor, 2 * r.width, 2 * r.height, r.dng);
}

json::Value lab_render_json(const LabRender& r, double full_scale) {
  const LabRenderOptions& o = r.options;
  auto arr = [](const double* v, size_t n) { return json::Value(std::vector<double>(v, v + n)); };
  json::Value j = fields::object(
      {{"camera", o.camera}, {"chart", o.chart}, {"illuminant", o.illuminant},
       {"surface", surface_choice_text(o.surface.method == "none" ? surface_choice("none", {}) : o.surface)},
       {"width", r.width}, {"height", r.height}, {"sensor_width", 2 * r.width}, {"sensor_height", 2 * r.height},
       {"cfa", o.cfa}, {"black", o.black}, {"white_level", (1 << o.bits) - 1}, {"saturation", r.saturation},
       {"exposure", o.exposure}, {"falloff", o.falloff}, {"flare", o.flare},
       {"noise", fields::object({{"shot_gain", o.shot_gain}, {"read_noise", o.read_noise},
                                 {"seed", static_cast<double>(o.seed)}})}});
  if (full_scale > 0) {
    j.set("oecf", o.oecf);
    j.set("full_scale", full_scale);
  }
  j.set("corners", arr(r.corners.data(), 8));
  j.set("white", arr(r.white.data(), 3));
  j.set("color_matrix", arr(r.dng.color_matrix.data(), 9));
  const bool generated = r.layout == "custom";
  if (generated) {
    j.set("layout", fields::object({{"chart", r.layout}, {"rows", r.rows}, {"columns", r.columns}}));
    std::string corners;
    for (double c : r.corners) corners += (corners.empty() ? "" : ",") + json::number_text(c);
    j.set("sample_args", "--chart custom --rows " + std::to_string(r.rows) + " --columns " + std::to_string(r.columns) +
                             " --corners " + corners);
  }
  json::Value patches = json::Value::array();
  for (const auto& p : r.patches) {
    json::Value q = fields::object({{"id", p.id}, {"rgb", arr(p.rgb.data(), 3)}, {"linear", arr(p.linear.data(), 3)},
                                    {"XYZ", arr(p.XYZ.data(), 3)}});
    if (generated) q.set("cell", p.cell);
    if (p.board) q.set("board", true);
    if (full_scale > 0) {
      std::array<double, 3> stored{};
      for (size_t c = 0; c < 3; ++c) stored[c] = std::round(full_scale * lab_encode(o, p.rgb[c], r.saturation));
      q.set("stored", arr(stored.data(), 3));
    }
    patches.push(q);
  }
  j.set("patches", patches);
  return j;
}

}  // namespace tristim
