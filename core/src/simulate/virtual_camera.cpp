// The virtual camera (rules in tristim/simulate.hpp).
#include "tristim/simulate/virtual_camera.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <mutex>

#include "../detmath.hpp"
#include "tristim/data.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"

namespace tristim {

namespace {

const char* kCameraFile = "cameras/camera_sensitivities_52cameras_380-780_5nm.csv";

const SpectralData& all_cameras() {
  static std::once_flag once;
  static SpectralData d;
  std::call_once(once, [] { d = read_spectral_csv(builtin_file(kCameraFile), kCameraFile); });
  return d;
}

std::string fold(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == ' ' || c == '-' || c == '_') out.push_back('_');
    else out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  return out;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::vector<std::string> camera_names() {
  std::vector<std::string> out;
  for (const auto& n : all_cameras().names)
    if (ends_with(n, "_R")) out.push_back(n.substr(0, n.size() - 2));
  return out;
}

SpectralData camera_ssf(std::string_view name) {
  const SpectralData& all = all_cameras();
  const std::string want = fold(name);
  for (size_t k = 0; k + 2 < all.names.size(); ++k) {
    const std::string& n = all.names[k];
    if (!ends_with(n, "_R") || fold(n.substr(0, n.size() - 2)) != want) continue;
    SpectralData d;
    d.wavelengths = all.wavelengths;
    d.names = {"R", "G", "B"};
    d.values = {all.values[k], all.values[k + 1], all.values[k + 2]};
    return d;
  }
  throw Error(ErrorCode::UnknownId, "unknown camera '" + std::string(name) + "' (see `tristim list` for the 52 built-in cameras, or give an SSF CSV)");
}

SpectralData read_ssf_csv(std::string_view text, std::string_view source) {
  SpectralData d = read_spectral_csv(text, source);
  auto find = [&](std::initializer_list<const char*> suffixes) -> int {
    for (size_t k = 0; k < d.names.size(); ++k) {
      std::string n = fold(d.names[k]);
      for (const char* s : suffixes) {
        const std::string suf(s);
        if (n == suf || ends_with(n, "_" + suf)) return static_cast<int>(k);
      }
    }
    return -1;
  };
  int r = find({"r", "red"}), g = find({"g", "green"}), b = find({"b", "blue"});
  if (r < 0 || g < 0 || b < 0) {
    if (d.names.size() != 3)
      throw Error(ErrorCode::MissingColumn, std::string(source) + ": an SSF file needs R, G and B columns after the wavelength (found " +
                                                std::to_string(d.names.size()) + " data columns)");
    r = 0;
    g = 1;
    b = 2;
  }
  SpectralData out;
  out.wavelengths = d.wavelengths;
  out.names = {"R", "G", "B"};
  out.values = {d.values[r], d.values[g], d.values[b]};
  return out;
}

GaussianNoise::GaussianNoise(uint64_t seed) : engine_(seed) {}

double GaussianNoise::next() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Uniforms in (0, 1] from the top 53 bits; Box-Muller (basic form).
  const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * (1.0 / 9007199254740992.0);
  const double u2 = static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0);
  const double r = std::sqrt(-2.0 * detmath::log(u1));  // detmath: the same noise in every build
  const double t = 6.283185307179586 * u2;
  spare_ = r * detmath::sin(t);
  has_spare_ = true;
  return r * detmath::cos(t);
}

std::vector<Vec3> simulate_camera_RGB(const SpectralData& ssf, const SpectralData& reflectances,
                                      const SpectralData& illuminant, const SimulationOptions& o) {
  if (ssf.size() != 3) throw Error(ErrorCode::InvalidArgument, "camera sensitivities need exactly 3 channels");
  if (illuminant.size() < 1) throw Error(ErrorCode::InvalidArgument, "illuminant without values");
  if (!(o.white_level > 0)) throw Error(ErrorCode::InvalidArgument, "white level must be > 0");
  if (o.noise_sigma < 0 || !std::isfinite(o.noise_sigma)) throw Error(ErrorCode::InvalidArgument, "noise sigma must be >= 0");
  if (o.oecf && !(o.oecf_gamma > 0 && o.oecf_scale > 0)) throw Error(ErrorCode::InvalidArgument, "OECF gamma and scale must be > 0");
  const auto& grid = ssf.wavelengths;
  const auto S = interpolate_spectrum(illuminant.wavelengths, illuminant.values[0], grid, illuminant.linear);
  std::vector<double> w[3];  // SSF_c · S
  double white_G = 0;
  for (int c = 0; c < 3; ++c) {
    w[c].resize(grid.size());
    for (size_t i = 0; i < grid.size(); ++i) w[c][i] = ssf.values[c][i] * S[i];
  }
  for (double v : w[1]) white_G += v;
  if (!(white_G > 0)) throw Error(ErrorCode::InvalidArgument, "no green response to the illuminant");
  const double k = o.white_level / white_G;
  GaussianNoise noise(o.seed);
  std::vector<Vec3> out;
  if (reflectances.values.empty()) return out;
  // Σ_i w_c(λ_i) R(λ_i) over the SSF grid with R interpolated onto it (linear in the samples) is
  // Σ_j (Aᵀ w_c)_j r_j over the reflectance grid: the weights pulled back once (pull_back_weights,
  // as reflectances_to_XYZ does), one short dot product per reflectance and channel.
  const PulledBackWeights p =
      pull_back_weights(reflectances.wavelengths, reflectances.linear, grid, w[0], w[1], w[2]);
  for (const auto& col : reflectances.values) {
    Vec3 rgb;
    const Vec3 sums = p.dot(col);
    for (int c = 0; c < 3; ++c) {
      double u = sums[c];
      u *= k;
      if (o.oecf) u = o.oecf_scale * detmath::pow(std::max(u, 0.0), 1.0 / o.oecf_gamma);  // eq (29)
      if (o.noise_sigma > 0) u += o.noise_sigma * noise.next();
      if (o.clip_max > 0) u = std::min(std::max(u, 0.0), o.clip_max);
      if (o.quantise) u = std::round(u);
      rgb[c] = u;
    }
    out.push_back(rgb);
  }
  return out;
}

}  // namespace tristim
