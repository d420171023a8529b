// DNG Camera Profiles (profile/dcp.hpp): the Hue/Saturation/Value mapping table (ProfileHueSatMap),
// built from a profile against its ForwardMatrix and applied as the DNG SDK's
// RefBaselineHueSatMap does (DNG 1.6 chapter 6 "Applying the Hue/Saturation/Value Mapping Table").
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

#include "export_dcp_internal.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/dcp.hpp"
#include "tristim/version.hpp"

namespace tristim {

using namespace dcp_internal;

Vec3 dcp_internal::rgb_to_hsv(const Vec3& rgb) {
  const double mx = rgb.maxCoeff(), mn = rgb.minCoeff(), gap = mx - mn;
  double h = 0, s = 0;
  if (gap > 0 && mx > 0) {
    if (rgb[0] == mx) {
      h = (rgb[1] - rgb[2]) / gap;
      if (h < 0) h += 6;
    } else if (rgb[1] == mx) {
      h = 2 + (rgb[2] - rgb[0]) / gap;
    } else {
      h = 4 + (rgb[0] - rgb[1]) / gap;
    }
    s = gap / mx;
  }
  return Vec3(h * 60, s, mx);
}

Vec3 dcp_internal::hsv_to_rgb(const Vec3& hsv) {
  const double v = hsv[2], s = hsv[1];
  if (s <= 0) return Vec3(v, v, v);
  double h = std::fmod(hsv[0], 360.0);
  if (h < 0) h += 360;
  h /= 60;
  const int i = std::min(5, static_cast<int>(std::floor(h)));
  const double f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0: return Vec3(v, t, p);
    case 1: return Vec3(q, v, p);
    case 2: return Vec3(p, v, t);
    case 3: return Vec3(p, q, v);
    case 4: return Vec3(t, p, v);
    default: return Vec3(v, p, q);
  }
}

std::vector<float> dcp_internal::hue_sat_data(const Profile& p, const DcpCalibration& c, std::uint32_t H, std::uint32_t S,
                                std::uint32_t V, double rgb_scale) {
  const Mat3 pp = prophoto_to_xyz(), pp_inv = pp.inverse();
  const Mat3 fm_inv = c.forward_matrix.inverse();
  const Vec3 white = c.linear * c.camera_white;
  const Mat3 adapt = chromatic_adaptation_matrix(white / white[1], dcp_d50(), ChromaticAdaptation::Bradford);
  const double scale = rgb_scale > 0 ? rgb_scale : p.rgb_max;
  if (!(scale > 0) || !std::isfinite(scale))
    throw Error(ErrorCode::InvalidArgument, "DCP HueSatMap: the camera value of DNG 1.0 must be positive");
  const double wmax = c.camera_white.maxCoeff();
  const double k = wmax / (scale * white[1]);  // DNG XYZ (1 = white level) per model XYZ
  const bool invariant = model_info(p.model.id).exposure_invariant;
  // The value of a 2.5D table (V = 1) and of every slab of an exposure-invariant model: half the
  // perfect white's value, the middle of a chart's range (any value gives the same table then).
  const double v_ref = 0.5 * wmax / scale;
  std::vector<float> data(static_cast<std::size_t>(H) * S * V * 3);
  auto node = [&](std::uint32_t vi, std::uint32_t hi, std::uint32_t si) -> float* {
    return data.data() + 3 * ((static_cast<std::size_t>(vi) * H + hi) * S + si);
  };
  auto slab = [&](std::uint32_t vi, double v) {
    for (std::uint32_t hi = 0; hi < H; ++hi) {
      float last[3] = {0, 1, 1};
      for (std::uint32_t si = 0; si < S; ++si) {
        const double h = 360.0 * hi / H, s = S > 1 ? static_cast<double>(si) / (S - 1) : 0.0;
        const Vec3 xyz = pp * hsv_to_rgb(Vec3(h, s, v));
        const Vec3 cam = c.neutral.cwiseProduct(fm_inv * xyz);  // DNG camera RGB rendered at the node
        bool ok = cam.minCoeff() > 0 && cam.allFinite();
        Vec3 hsv;
        if (ok) {
          const Vec3 target = pp_inv * (k * (adapt * predict(p.model, Vec3(cam * scale))));
          hsv = rgb_to_hsv(target);
          ok = target.allFinite() && hsv[2] > 0 && (si == 0 || hsv[1] > 0);
        }
        float* e = node(vi, hi, si);
        if (!ok) {
          std::copy(last, last + 3, e);
          continue;
        }
        double dh = 0, ss = 1;
        if (si > 0) {
          dh = std::remainder(hsv[0] - h, 360.0);
          ss = hsv[1] / s;
        }
        e[0] = static_cast<float>(dh);
        e[1] = static_cast<float>(ss);
        e[2] = static_cast<float>(hsv[2] / v);
        std::copy(e, e + 3, last);
      }
    }
  };
  if (V == 1 || invariant) {
    slab(0, v_ref);
    for (std::uint32_t vi = 1; vi < V; ++vi) std::copy(node(0, 0, 0), node(1, 0, 0), node(vi, 0, 0));
  } else {
    for (std::uint32_t vi = 1; vi < V; ++vi) slab(vi, static_cast<double>(vi) / (V - 1));
    // Value 0 is black, where the change is undefined: the first slab's change holds below it.
    std::copy(node(1, 0, 0), node(2, 0, 0), node(0, 0, 0));
  }
  return data;
}

void dcp_internal::check_dims(std::uint32_t h, std::uint32_t s, std::uint32_t v, const std::string& what, bool reading) {
  if (h < 1 || s < 2 || v < 1)
    throw Error(reading ? ErrorCode::ProfileInvalid : ErrorCode::InvalidArgument,
                what + " divisions " + std::to_string(h) + "," + std::to_string(s) + "," + std::to_string(v) +
                    ": hue >= 1, saturation >= 2 and value >= 1 (DNG 1.6 ProfileHueSatMapDims)");
  if (h > kMaxHue || s > kMaxSat || v > kMaxVal || static_cast<std::uint64_t>(h) * s * v > kMaxNodes)
    throw Error(reading ? ErrorCode::LimitExceeded : ErrorCode::InvalidArgument,
                what + " divisions " + std::to_string(h) + "," + std::to_string(s) + "," + std::to_string(v) +
                    " beyond the limits (hue <= 360, saturation <= 256, value <= 256, at most 2,000,000 nodes)");
}

Vec3 dcp_render(const Dcp& d, const DcpTransform& t, const Vec3& camera_rgb, bool use_map) {
  Vec3 xyz = t.camera_to_xyz * camera_rgb;
  const DcpHsvTable& m = d.hue_sat_map;
  if (!use_map || m.empty()) return xyz;
  const Mat3 pp = prophoto_to_xyz();
  const Vec3 rgb = pp.inverse() * xyz;
  if (!rgb.allFinite() || rgb.minCoeff() < 0) return xyz;  // RawTherapee leaves colours outside ProPhoto to the matrix
  Vec3 hsv = rgb_to_hsv(rgb);
  const double g = m.data2.empty() ? 1.0 : t.weight1;
  auto entry = [&](std::size_t vi, std::size_t hi, std::size_t si, int k) {
    const std::size_t i = 3 * ((vi * m.hue + hi) * m.sat + si) + k;
    return g * m.data1[i] + (m.data2.empty() ? 0.0 : (1 - g) * m.data2[i]);
  };
  // The DNG SDK's RefBaselineHueSatMap: hue wraps, saturation and value indices clamped to the
  // table (their fractions are not), trilinear.
  const double hs = m.hue < 2 ? 0.0 : hsv[0] / 360.0 * m.hue, ss = hsv[1] * (m.sat - 1);
  std::size_t h0 = static_cast<std::size_t>(std::max(0.0, hs)), h1 = h0 + 1;
  if (h0 >= m.hue - 1) {
    h0 = m.hue - 1;
    h1 = 0;
  }
  const std::size_t s0 = std::min<std::size_t>(static_cast<std::size_t>(ss), m.sat - 2);
  const double hf = hs - h0, sf = ss - s0;
  double v_lookup = hsv[2];
  if (m.encoding == 1) v_lookup = sRGB_encode(std::min(1.0, v_lookup));
  const double vs = m.val < 2 ? 0.0 : std::min(v_lookup * (m.val - 1), static_cast<double>(m.val));
  const std::size_t v0 = m.val < 2 ? 0 : std::min<std::size_t>(static_cast<std::size_t>(std::max(0.0, vs)), m.val - 2);
  const std::size_t v1 = m.val < 2 ? 0 : v0 + 1;
  const double vf = m.val < 2 ? 0.0 : vs - v0;
  double delta[3];
  for (int k = 0; k < 3; ++k) {
    auto at_v = [&](std::size_t vi) {
      const double a = (1 - sf) * entry(vi, h0, s0, k) + sf * entry(vi, h0, s0 + 1, k);
      const double b = (1 - sf) * entry(vi, h1, s0, k) + sf * entry(vi, h1, s0 + 1, k);
      return (1 - hf) * a + hf * b;
    };
    delta[k] = (1 - vf) * at_v(v0) + vf * at_v(v1);
  }
  hsv[0] += delta[0];
  hsv[1] *= delta[1];
  hsv[2] *= delta[2];
  return pp * hsv_to_rgb(hsv);
}

}  // namespace tristim
