// Guarnera 2018 section 3.1: exposure settings, eq (7), measured saturation, zones
// (rules in tristim/absolute/normalisation.hpp).
#include "tristim/absolute/normalisation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tristim/error.hpp"

namespace tristim {

double ExposureSettings::factor(double iso_reference) const {
  const double gain = (iso > 0 && iso_reference > 0) ? iso / iso_reference : 1.0;
  return exposure_s / (f_number * f_number) * gain;  // eq (5): t/N²
}

std::string ExposureSettings::label() const {
  char buf[96];
  if (exposure_s > 0 && exposure_s < 0.5)
    std::snprintf(buf, sizeof buf, "1/%.4g s f/%.3g", 1.0 / exposure_s, f_number);
  else
    std::snprintf(buf, sizeof buf, "%.4g s f/%.3g", exposure_s, f_number);
  std::string s = buf;
  if (iso > 0) s += " ISO " + std::to_string(static_cast<long long>(std::lround(iso)));
  return s;
}

ExposureSettings exposure_from_metadata(const RawMetadata& meta, const std::string& source, bool require_iso) {
  std::string missing;
  auto miss = [&](const char* what) { missing += std::string(missing.empty() ? "" : ", ") + what; };
  if (!(meta.shutter_s > 0) || !std::isfinite(meta.shutter_s)) miss("exposure time");
  if (!(meta.f_number > 0) || !std::isfinite(meta.f_number)) miss("f-number");
  if (require_iso && !(meta.iso > 0)) miss("ISO");
  if (!missing.empty())
    throw Error(ErrorCode::MissingMetadata, source + ": the file does not record its " + missing +
                                                " (give them explicitly)");
  return {meta.shutter_s, meta.f_number, meta.iso > 0 ? meta.iso : 0.0};
}

std::array<double, 3> channel_areas(const SpectralData& ssf) {
  if (ssf.size() != 3) throw Error(ErrorCode::InvalidArgument, "channel areas need exactly 3 sensitivity curves");
  std::array<double, 3> A{};
  const auto& wl = ssf.wavelengths;
  for (int c = 0; c < 3; ++c) {
    for (size_t i = 1; i < wl.size(); ++i)
      A[c] += 0.5 * (ssf.values[c][i] + ssf.values[c][i - 1]) * (wl[i] - wl[i - 1]);
    if (!(A[c] > 0) || !std::isfinite(A[c]))
      throw Error(ErrorCode::InvalidArgument, std::string("the ") + "RGB"[c] + " sensitivity has no positive area");
  }
  return A;
}

SaturationEstimate measure_saturation(const std::vector<const RawImage*>& frames) {
  if (frames.empty() || !frames[0]) throw Error(ErrorCode::InvalidArgument, "no frames to measure the saturation level from");
  const RawImage& first = *frames[0];
  SaturationEstimate s;
  s.reported = first.meta.saturation;
  std::array<double, 3> vmax{-1e300, -1e300, -1e300};
  double total = 0;
  for (const RawImage* f : frames) {
    if (!f) throw Error(ErrorCode::InvalidArgument, "a frame is missing");
    if (f->meta.make != first.meta.make || f->meta.model != first.meta.model)
      throw Error(ErrorCode::FrameMismatch, "frames from " + first.meta.make + " " + first.meta.model + " and " +
                                                f->meta.make + " " + f->meta.model + " cannot share a saturation level");
    const size_t n = f->rgb.size();
    for (size_t i = 0; i < n; ++i) vmax[i % 3] = std::max(vmax[i % 3], static_cast<double>(f->rgb[i]));
    total += static_cast<double>(n / 3);
  }
  for (int c = 0; c < 3; ++c) {
    const double m = vmax[c];
    const double delta = std::max(1.0, 1e-3 * std::fabs(m));
    double spike = 0, below = 0;
    for (const RawImage* f : frames) {
      const size_t n = f->rgb.size();
      for (size_t i = static_cast<size_t>(c); i < n; i += 3) {
        const double v = f->rgb[i];
        if (v >= m - delta) spike += 1;
        else if (v >= m - 5 * delta) below += 1;
      }
    }
    const double reported = s.reported[c] > 0 ? s.reported[c] : m;
    const double density_below = below / 4.0;  // per δ-wide band, over the 4δ under the spike
    s.measured[c] = spike >= 16 && spike > 4.0 * density_below && m > 0;
    s.level[c] = s.measured[c] ? std::min(m, reported) : reported;
    s.fraction[c] = reported > 0 ? s.level[c] / reported : 1.0;
    s.clipped_pixels[c] = s.measured[c] ? spike / total : 0.0;
  }
  return s;
}

const char* zone_name(Zone zone) {
  switch (zone) {
    case Zone::Under: return "Z_u";
    case Zone::Centre: return "Z_c";
    case Zone::Over: return "Z_o";
    case Zone::Saturated: return "saturated";
  }
  return "?";
}

double Normalisation::falloff_factor(int x, int y) const {
  return falloff ? falloff->factor(x + 0.5, y + 0.5) : 1.0;
}

double Normalisation::normalised(int c, double v, int x, int y) const {
  return (v - noise_floor[c]) / (saturation[c] - noise_floor[c]) * area_ratio(c) * falloff_factor(x, y);  // eq (7)
}

Zone Normalisation::zone(int c, double v, bool flagged) const {
  const double range = saturation[c] - noise_floor[c];
  if (flagged || v >= saturation[c] - std::max(0.5, 1e-4 * range)) return Zone::Saturated;
  const double u = (v - noise_floor[c]) / range;
  if (u < 1.0 / w) return Zone::Under;
  if (u > (w - 1.0) / w) return Zone::Over;
  return Zone::Centre;
}

void Normalisation::check() const {
  for (int c = 0; c < 3; ++c) {
    if (!(saturation[c] > noise_floor[c]) || !std::isfinite(saturation[c]) || !std::isfinite(noise_floor[c]))
      throw Error(ErrorCode::InvalidArgument, std::string("normalisation: the saturation level of ") + "RGB"[c] +
                                                  " must exceed its noise floor");
    if (!(noise_sigma[c] >= 0) || !std::isfinite(noise_sigma[c]))
      throw Error(ErrorCode::InvalidArgument, "normalisation: the noise sigma must be >= 0");
    if (!(areas[c] > 0) || !std::isfinite(areas[c]))
      throw Error(ErrorCode::InvalidArgument, "normalisation: channel areas must be positive");
  }
  if (!(w > 2) || !std::isfinite(w)) throw Error(ErrorCode::InvalidArgument, "the zone parameter w must be > 2");
}

Normalisation make_normalisation(const DarkFrame* lens_cap, const SaturationEstimate& saturation,
                                 const SpectralData* ssf, const std::optional<FalloffFit>& falloff, double w) {
  Normalisation n;
  if (lens_cap) {
    n.noise_floor = lens_cap->mean;
    n.noise_sigma = lens_cap->noise;
  }
  n.saturation = saturation.level;
  if (ssf) n.areas = channel_areas(*ssf);
  n.falloff = falloff;
  n.w = w;
  n.check();
  return n;
}

}  // namespace tristim
