// ICC (lcms2), .cube, patch CSV, float TIFF and PFM writers.
#include "tristim/profile/export.hpp"

// C++17 has no `register`; lcms2.h uses it unless told not to.
#define CMS_NO_REGISTER_KEYWORD 1
#include <lcms2.h>
#include <lcms2_plugin.h>  // cmsMD5alloc/add/finish for the v4 Profile ID

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>

#include "tristim/error.hpp"
#include "tristim/number.hpp"
#include "tristim/version.hpp"
#include "../detmath.hpp"

namespace tristim {

namespace {

// XYZ in data units -> PCS XYZ (D50, white Y = 1).
struct PcsMapping {
  Mat3 cat;   // adaptation white -> D50
  double inv_white_Y;
  bool adapted;
};

PcsMapping pcs_mapping(const Profile& p) {
  PcsMapping m;
  const Vec3 d50 = whites::D50() / 100.0;
  const Vec3 w = p.white / p.white[1];
  m.adapted = (w - d50).cwiseAbs().maxCoeff() > 1e-4;
  m.cat = m.adapted ? chromatic_adaptation_matrix(w, d50, ChromaticAdaptation::Bradford) : Mat3::Identity();
  m.inv_white_Y = 1.0 / p.white[1];
  return m;
}

double rgb_scale_of(const Profile& p, double requested) {
  const double s = requested > 0 ? requested : p.rgb_max;
  if (!(s > 0) || !std::isfinite(s)) throw Error(ErrorCode::InvalidArgument, "export: rgb scale must be positive");
  return s;
}

struct LcmsContext {
  cmsContext ctx;
  std::string last_error;
  LcmsContext() { ctx = cmsCreateContext(nullptr, this); cmsSetLogErrorHandlerTHR(ctx, &LcmsContext::log); }
  ~LcmsContext() { cmsDeleteContext(ctx); }
  static void log(cmsContext c, cmsUInt32Number, const char* text) {
    auto* self = static_cast<LcmsContext*>(cmsGetContextUserData(c));
    if (self) self->last_error = text ? text : "";
  }
};

[[noreturn]] void export_failed(const LcmsContext& lc, const std::string& what) {
  throw Error(ErrorCode::ExportFailed, "ICC export: " + what + (lc.last_error.empty() ? "" : " (lcms2: " + lc.last_error + ")"));
}

void write_text_tag(const LcmsContext& lc, cmsHPROFILE h, cmsTagSignature sig, const std::string& text) {
  cmsMLU* mlu = cmsMLUalloc(lc.ctx, 1);
  if (!mlu) export_failed(lc, "out of memory");
  cmsMLUsetASCII(mlu, "en", "US", text.c_str());
  const bool ok = cmsWriteTag(h, sig, mlu);
  cmsMLUfree(mlu);
  if (!ok) export_failed(lc, "cannot write a text tag");
}

// XYZ of one camera value as the profile takes it: a profile with a linearisation stage takes
// stored (non-linear) values and linearises them first (profile.hpp).
Vec3 profile_XYZ(const Profile& p, const Vec3& camera) {
  if (!p.has_linearisation) return predict(p.model, camera);
  return profile_predict(p, camera.transpose()).row(0).transpose();
}

struct SamplerCargo {
  const Profile* profile;
  double rgb_scale, gamma;
  PcsMapping pcs;
};

// The CLUT holds c = (XYZ - kClutLow) / kClutSpan (16-bit, 0..1), so that XYZ from -0.5 to 2 is
// kept at the grid nodes: a model predicts negative XYZ for camera RGB far outside the chart's
// colours (e.g. strong red and blue with no green), and clipping those nodes to 0 would spoil the
// interpolation in every cell next to them, chart colours included. The B curves (tables of
// kOutputCurveEntries) then map c back to the PCS, clipping below 0 only at the end.
constexpr double kClutLow = -0.5, kClutSpan = 2.5;
constexpr int kOutputCurveEntries = 4096;

int clut_sampler(const cmsUInt16Number In[], cmsUInt16Number Out[], void* cargo) {
  const auto* c = static_cast<const SamplerCargo*>(cargo);
  Vec3 rgb;
  for (int k = 0; k < 3; ++k) {
    const double u = In[k] / 65535.0;                       // grid coordinate after the A curve
    rgb[k] = detmath::pow(u, c->gamma) * c->rgb_scale;          // back to camera RGB
  }
  const Vec3 xyz = c->pcs.cat * (profile_XYZ(*c->profile, rgb) * c->pcs.inv_white_Y);
  for (int k = 0; k < 3; ++k) {
    const double v = std::round((xyz[k] - kClutLow) / kClutSpan * 65535.0);
    Out[k] = static_cast<cmsUInt16Number>(v < 0 ? 0 : (v > 65535 ? 65535 : v));
  }
  return 1;
}

// B curve: c (0..1) -> encoded PCSXYZ. The ICC 16-bit PCSXYZ encoding is the same in v2
// (lut16Type, ICC.1:2001-04) and v4 (lut16Type, and lutAtoBType whose 0..1 output is that encoding
// over 0..0xFFFF, ICC.1:2010): u1Fixed15, 0x0000 = 0, 0x8000 = 1.0, 0xFFFF = 1 + 32767/32768.
// (Only the 16-bit *Lab* encoding differs between the versions: v2's legacy L* = 100 at 0xFF00,
// v4's at 0xFFFF.) XYZ outside 0 .. 1 + 32767/32768 is clipped here, the only place.
cmsToneCurve* output_curve(cmsContext ctx) {
  std::vector<cmsUInt16Number> t(kOutputCurveEntries);
  for (int i = 0; i < kOutputCurveEntries; ++i) {
    const double xyz = kClutLow + kClutSpan * i / (kOutputCurveEntries - 1.0);
    const double v = std::round(xyz * 32768.0);
    t[i] = static_cast<cmsUInt16Number>(v < 0 ? 0 : (v > 65535 ? 65535 : v));
  }
  return cmsBuildTabulatedToneCurve16(ctx, kOutputCurveEntries, t.data());
}

// The header's creation date (bytes 24..35, dateTimeNumber) is fixed, so that one profile always
// exports to the same bytes (the page's download equals the CLI's, and a re-export diffs clean);
// lcms2 would write the current time. Then, for v4 only, the Profile ID (bytes 84..99): the MD5 of
// the whole profile with the flags (44..47), rendering intent (64..67) and ID fields set to zero
// (ICC.1:2010 7.2.18). In v2 (ICC.1:2001-04) bytes 84..127 are reserved and must stay zero.
void finish_header(const LcmsContext& lc, std::vector<uint8_t>& b, bool with_profile_id) {
  const uint16_t date[6] = {2000, 1, 1, 0, 0, 0};  // year, month, day, hours, minutes, seconds (UTC)
  for (int k = 0; k < 6; ++k) {
    b[24 + 2 * k] = static_cast<uint8_t>(date[k] >> 8);
    b[25 + 2 * k] = static_cast<uint8_t>(date[k] & 0xFF);
  }
  std::fill(b.begin() + 84, b.begin() + 100, uint8_t{0});
  if (!with_profile_id) return;
  std::vector<uint8_t> z = b;
  std::fill(z.begin() + 44, z.begin() + 48, uint8_t{0});
  std::fill(z.begin() + 64, z.begin() + 68, uint8_t{0});
  cmsHANDLE md5 = cmsMD5alloc(lc.ctx);
  if (!md5) export_failed(lc, "out of memory");
  cmsMD5add(md5, z.data(), static_cast<cmsUInt32Number>(z.size()));
  cmsProfileID id;
  cmsMD5finish(&id, md5);  // frees the handle
  std::memcpy(b.data() + 84, id.ID8, 16);
}

}  // namespace

std::vector<uint8_t> export_icc(const Profile& p, const IccOptions& options) {
  const ModelInfo& info = model_info(p.model.id);
  const double scale = rgb_scale_of(p, options.rgb_scale);
  if (options.grid_points < 2 || options.grid_points > 255)
    throw Error(ErrorCode::InvalidArgument, "ICC export: grid points must be 2..255");
  if (!(options.shaper_gamma > 0)) throw Error(ErrorCode::InvalidArgument, "ICC export: shaper gamma must be > 0");
  const PcsMapping pcs = pcs_mapping(p);
  LcmsContext lc;
  cmsHPROFILE h = cmsCreateProfilePlaceholder(lc.ctx);
  if (!h) export_failed(lc, "cannot create a profile");
  std::unique_ptr<void, void (*)(void*)> guard(h, [](void* q) { cmsCloseProfile(q); });
  if (!(options.version == 4.3 || options.version == 2.4))
    throw Error(ErrorCode::InvalidArgument, "ICC export: version must be 4.3 or 2.4");
  cmsSetProfileVersion(h, options.version);
  cmsSetDeviceClass(h, cmsSigInputClass);
  cmsSetColorSpace(h, cmsSigRgbData);
  cmsSetPCS(h, cmsSigXYZData);
  cmsSetHeaderRenderingIntent(h, INTENT_RELATIVE_COLORIMETRIC);
  const std::string desc = options.description.empty()
                               ? "tristim " + p.model.id + " (" + objective_id(p.objective) + ")"
                               : options.description;
  write_text_tag(lc, h, cmsSigProfileDescriptionTag, desc);
  write_text_tag(lc, h, cmsSigCopyrightTag, std::string("Generated by tristim ") + kVersion + "; no copyright asserted");
  // The media white point and the adaptation, by version (both versions: PCS values are the
  // data relative to the profile white, adapted to D50 with Bradford when that white is not D50):
  //  - v4 (ICC.1:2010, mediaWhitePointTag): wtpt holds the media white *after* the chromatic
  //    adaptation of 'chad', i.e. the PCS white D50 for a profile whose media white is the adopted
  //    white; 'chad' records the adaptation so ICC-absolute colorimetry can undo it.
  //  - v2 (ICC.1:2001-04, mediaWhitePointTag): there is no 'chad' (it was added in v4); wtpt holds
  //    the media white as measured (here the profile white, Y = 1), and ICC-absolute colorimetry is
  //    PCS × wtpt / D50 component by component. Writing D50 there would make a D65 profile's
  //    absolute intent equal its relative one; writing 'chad' would add a tag v2 does not define.
  //    A white within 1e-4 of D50 is not adapted and its wtpt is the PCS D50 in both versions.
  const Vec3 media_white = p.white / p.white[1];
  const cmsCIEXYZ wtpt_v2{media_white[0], media_white[1], media_white[2]};
  const bool v2 = options.version < 4;
  if (!cmsWriteTag(h, cmsSigMediaWhitePointTag, v2 && pcs.adapted ? &wtpt_v2 : cmsD50_XYZ()))
    export_failed(lc, "cannot write wtpt");
  if (pcs.adapted && !v2) {
    cmsFloat64Number chad[9];  // lcms2 takes the 3×3 as 9 doubles, row major
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) chad[3 * r + c] = pcs.cat(r, c);
    if (!cmsWriteTag(h, cmsSigChromaticAdaptationTag, chad)) export_failed(lc, "cannot write chad");
  }
  if (info.linear && !p.has_linearisation) {  // (with a linearisation stage: the LUT form below)
    const Mat3 M = pcs.cat * p.model.coefficients.leftCols(3) * (scale * pcs.inv_white_Y);
    const cmsTagSignature sigs[3] = {cmsSigRedColorantTag, cmsSigGreenColorantTag, cmsSigBlueColorantTag};
    const cmsTagSignature trcs[3] = {cmsSigRedTRCTag, cmsSigGreenTRCTag, cmsSigBlueTRCTag};
    cmsToneCurve* lin = cmsBuildGamma(lc.ctx, 1.0);
    if (!lin) export_failed(lc, "cannot build a tone curve");
    for (int c = 0; c < 3; ++c) {
      cmsCIEXYZ col{M(0, c), M(1, c), M(2, c)};
      if (!cmsWriteTag(h, sigs[c], &col) || !cmsWriteTag(h, trcs[c], lin)) {
        cmsFreeToneCurve(lin);
        export_failed(lc, "cannot write the matrix/shaper tags");
      }
    }
    cmsFreeToneCurve(lin);
  } else {
    cmsPipeline* lut = cmsPipelineAlloc(lc.ctx, 3, 3);
    if (!lut) export_failed(lc, "cannot allocate the pipeline");
    cmsToneCurve* a = cmsBuildGamma(lc.ctx, 1.0 / options.shaper_gamma);
    cmsToneCurve* id = output_curve(lc.ctx);
    cmsToneCurve* A[3] = {a, a, a};
    cmsToneCurve* Bc[3] = {id, id, id};
    cmsStage* sa = cmsStageAllocToneCurves(lc.ctx, 3, A);
    cmsStage* clut = cmsStageAllocCLut16bit(lc.ctx, static_cast<cmsUInt32Number>(options.grid_points), 3, 3, nullptr);
    cmsStage* sb = cmsStageAllocToneCurves(lc.ctx, 3, Bc);
    cmsFreeToneCurve(a);
    cmsFreeToneCurve(id);
    SamplerCargo cargo{&p, scale, options.shaper_gamma, pcs};
    bool ok = sa && clut && sb && cmsStageSampleCLut16bit(clut, clut_sampler, &cargo, 0) &&
              cmsPipelineInsertStage(lut, cmsAT_END, sa) && cmsPipelineInsertStage(lut, cmsAT_END, clut) &&
              cmsPipelineInsertStage(lut, cmsAT_END, sb);
    if (ok) ok = cmsWriteTag(h, cmsSigAToB0Tag, lut);
    cmsPipelineFree(lut);
    if (!ok) export_failed(lc, "cannot write the AToB0 table");
  }
  cmsUInt32Number n = 0;
  if (!cmsSaveProfileToMem(h, nullptr, &n) || n < 128) export_failed(lc, "cannot size the profile");
  std::vector<uint8_t> bytes(n);
  if (!cmsSaveProfileToMem(h, bytes.data(), &n)) export_failed(lc, "cannot serialise the profile");
  bytes.resize(n);
  finish_header(lc, bytes, !v2);
  return bytes;
}

PatchMatrix icc_device_to_XYZ(const std::vector<uint8_t>& icc, const PatchMatrix& device_RGB) {
  LcmsContext lc;
  cmsHPROFILE in = cmsOpenProfileFromMemTHR(lc.ctx, icc.data(), static_cast<cmsUInt32Number>(icc.size()));
  if (!in) throw Error(ErrorCode::ParseError, "not an ICC profile lcms2 can open" + (lc.last_error.empty() ? "" : ": " + lc.last_error));
  cmsHPROFILE out = cmsCreateXYZProfileTHR(lc.ctx);
  cmsHTRANSFORM t = cmsCreateTransformTHR(lc.ctx, in, TYPE_RGB_DBL, out, TYPE_XYZ_DBL, INTENT_RELATIVE_COLORIMETRIC,
                                          cmsFLAGS_NOOPTIMIZE | cmsFLAGS_NOCACHE);
  cmsCloseProfile(in);
  cmsCloseProfile(out);
  if (!t) throw Error(ErrorCode::ExportFailed, "lcms2 cannot build a transform from this profile: " + lc.last_error);
  PatchMatrix res(device_RGB.rows(), 3);
  for (Eigen::Index i = 0; i < device_RGB.rows(); ++i) {
    // TYPE_RGB_DBL takes 0..1.
    double rgb[3] = {device_RGB(i, 0), device_RGB(i, 1), device_RGB(i, 2)};
    cmsCIEXYZ xyz;
    cmsDoTransform(t, rgb, &xyz, 1);
    res(i, 0) = xyz.X;
    res(i, 1) = xyz.Y;
    res(i, 2) = xyz.Z;
  }
  cmsDeleteTransform(t);
  return res;
}

std::string export_cube(const Profile& p, int size, double rgb_scale) {
  if (size < 2 || size > 129) throw Error(ErrorCode::InvalidArgument, "cube size must be 2..129");
  const double scale = rgb_scale_of(p, rgb_scale);
  model_info(p.model.id);
  const int n1 = kCubeShaperSize;
  const double gamma = kCubeShaperGamma;
  std::string out;
  out.reserve(static_cast<size_t>(size) * size * size * 40 + static_cast<size_t>(n1) * 30 + 1024);
  char buf[200];
  // Resolve's .cube convention: comments only before the first keyword, no TITLE (OpenColorIO's
  // Resolve reader refuses it), both sizes and ranges, then the 1D rows, then the 3D rows.
  out += "# tristim " + std::string(kVersion) + " " + p.model.id + " (" + objective_id(p.objective) + ")\n";
  if (p.has_linearisation)
    std::snprintf(buf, sizeof buf, "# input: d = stored camera value / %.17g (non-linear, as in the image; the profile's %s linearisation is inside the LUT)\n",
                  scale, p.linearisation.choice.method.c_str());
  else
    std::snprintf(buf, sizeof buf, "# input: d = camera RGB / %.17g (linear; d = 1 is the brightest training value)\n", scale);
  out += buf;
  std::snprintf(buf, sizeof buf, "# output: CIE XYZ / white Y (white %.9g %.9g %.9g, %s), not clipped\n", p.white[0], p.white[1],
                p.white[2], p.illuminant.c_str());
  out += buf;
  std::snprintf(buf, sizeof buf, "# 1D shaper (%d rows, applied first): u = d^(1/%.1f) per channel, for d in 0..1\n", n1, gamma);
  out += buf;
  std::snprintf(buf, sizeof buf, "# 3D LUT (%d^3 rows, red fastest): XYZ at u = (i, j, k) / %d, i.e. d = u^%.1f\n", size, size - 1,
                gamma);
  out += buf;
  out += "# Inputs outside 0..1 are clamped. A reader without 1D shaper support reads this file wrongly.\n";
  out += "LUT_1D_SIZE " + std::to_string(n1) + "\nLUT_1D_INPUT_RANGE 0 1\n";
  out += "LUT_3D_SIZE " + std::to_string(size) + "\nLUT_3D_INPUT_RANGE 0 1\n";
  for (int i = 0; i < n1; ++i) {
    const double u = detmath::pow(static_cast<double>(i) / (n1 - 1), 1.0 / gamma);
    std::snprintf(buf, sizeof buf, "%.7g %.7g %.7g\n", u, u, u);
    out += buf;
  }
  const double inv = 1.0 / p.white[1];
  std::vector<double> d(static_cast<size_t>(size));
  for (int i = 0; i < size; ++i) d[i] = detmath::pow(static_cast<double>(i) / (size - 1), gamma) * scale;
  for (int b = 0; b < size; ++b)
    for (int g = 0; g < size; ++g)
      for (int r = 0; r < size; ++r) {
        const Vec3 xyz = profile_XYZ(p, Vec3(d[r], d[g], d[b])) * inv;
        std::snprintf(buf, sizeof buf, "%.7g %.7g %.7g\n", xyz[0], xyz[1], xyz[2]);
        out += buf;
      }
  return out;
}

std::string patch_csv(const std::vector<std::string>& ids, const PatchMatrix& rgb, const PatchMatrix& ref,
                      const PatchMatrix& est, const Vec3& white, const PatchMatrix& loo) {
  const Metrics m = evaluate(est, ref, white);
  const bool has_loo = loo.rows() == ref.rows() && loo.rows() > 0;
  Metrics ml;
  if (has_loo) ml = evaluate(loo, ref, white);
  std::ostringstream o;
  o.precision(10);
  o << "id,R,G,B,X_ref,Y_ref,Z_ref,X_est,Y_est,Z_est,dE76,dE94,dE00,dL,dC,dH,dE_xyz,rel_Y";
  if (has_loo) o << ",X_loo,Y_loo,Z_loo,dE00_loo";
  o << "\n";
  for (Eigen::Index i = 0; i < ref.rows(); ++i) {
    std::string id = i < static_cast<Eigen::Index>(ids.size()) ? ids[i] : std::to_string(i + 1);
    if (id.find_first_of(",\"\n") != std::string::npos) {
      std::string q = "\"";
      for (char c : id) q += c == '"' ? std::string("\"\"") : std::string(1, c);
      id = q + "\"";
    }
    o << id;
    for (int c = 0; c < 3; ++c) o << "," << rgb(i, c);
    for (int c = 0; c < 3; ++c) o << "," << ref(i, c);
    for (int c = 0; c < 3; ++c) o << "," << est(i, c);
    const auto& p = m.patches;
    o << "," << p.dE76[i] << "," << p.dE94[i] << "," << p.dE00[i] << "," << p.dL[i] << "," << p.dC[i] << ","
      << p.dH[i] << "," << p.dE_xyz[i] << ",";
    if (std::isfinite(p.rel_Y[i])) o << p.rel_Y[i];
    if (has_loo) {
      for (int c = 0; c < 3; ++c) o << "," << loo(i, c);
      o << "," << ml.patches.dE00[i];
    }
    o << "\n";
  }
  return o.str();
}

namespace {
void check_image(const float* pixels, int width, int height) {
  if (width <= 0 || height <= 0 || !pixels)
    throw Error(ErrorCode::InvalidArgument, "image writer: empty image");
}
bool little_endian() {
  const uint16_t one = 1;
  uint8_t b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}
void copy_floats_le(uint8_t* dst, const float* src, size_t n) {
  if (little_endian()) {
    std::memcpy(dst, src, n * 4);
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    uint32_t u;
    std::memcpy(&u, src + i, 4);
    for (int k = 0; k < 4; ++k) dst[4 * i + k] = static_cast<uint8_t>(u >> (8 * k));
  }
}
}  // namespace

// float_tiff and float_tiff_bands: export_tiff.cpp (libtiff).

std::vector<uint8_t> float_pfm(const float* pixels, int width, int height) {
  check_image(pixels, width, height);
  const std::string header = "PF\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
  const size_t row = static_cast<size_t>(width) * 3;
  std::vector<uint8_t> b(header.size() + row * height * 4);
  std::memcpy(b.data(), header.data(), header.size());
  for (int y = 0; y < height; ++y)
    copy_floats_le(b.data() + header.size() + static_cast<size_t>(y) * row * 4,
                   pixels + static_cast<size_t>(height - 1 - y) * row, row);
  return b;
}

Image3f read_pfm(const std::string& bytes) {
  size_t i = 0;
  auto token = [&]() {
    while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
    const size_t start = i;
    while (i < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
    return bytes.substr(start, i - start);
  };
  if (token() != "PF") throw Error(ErrorCode::ParseError, "PFM: not a colour PFM (expected 'PF' at byte 0)");
  const std::string ws = token(), hs = token(), ss = token();
  char* end = nullptr;
  const long w = std::strtol(ws.c_str(), &end, 10);
  const long h = std::strtol(hs.c_str(), &end, 10);
  const double scale = tristim::parse_double(ss.c_str(), &end);
  if (w <= 0 || h <= 0 || w > 100000 || h > 100000 || scale == 0 || !std::isfinite(scale))
    throw Error(ErrorCode::ParseError, "PFM: bad header (width, height or scale)");
  ++i;  // the single whitespace after the scale
  const size_t row = static_cast<size_t>(w) * 3;
  const size_t need = row * static_cast<size_t>(h) * 4;
  if (bytes.size() < i + need)
    throw Error(ErrorCode::ParseError, "PFM: file ends after " + std::to_string(bytes.size()) + " bytes, " +
                                           std::to_string(i + need) + " needed");
  Image3f img;
  img.width = static_cast<int>(w);
  img.height = static_cast<int>(h);
  img.pixels.resize(row * static_cast<size_t>(h));
  const bool file_le = scale < 0;
  for (long y = 0; y < h; ++y) {
    const uint8_t* src = reinterpret_cast<const uint8_t*>(bytes.data()) + i + static_cast<size_t>(y) * row * 4;
    float* dst = img.pixels.data() + static_cast<size_t>(h - 1 - y) * row;
    for (size_t k = 0; k < row; ++k) {
      uint32_t u = 0;
      for (int b = 0; b < 4; ++b) u |= static_cast<uint32_t>(src[4 * k + (file_le ? b : 3 - b)]) << (8 * b);
      std::memcpy(dst + k, &u, 4);
    }
  }
  return img;
}

Image3f apply_profile(const Profile& profile, const float* rgb, int width, int height) {
  if (width <= 0 || height <= 0 || !rgb) throw Error(ErrorCode::InvalidArgument, "apply: empty image");
  Image3f out;
  out.width = width;
  out.height = height;
  const size_t n = static_cast<size_t>(width) * height;
  out.pixels.resize(n * 3);
  if (profile.has_linearisation) {  // stored values: the profile's linearisation stage first
    std::copy(rgb, rgb + n * 3, out.pixels.begin());
    linearise_image(profile.linearisation, out.pixels.data(), n);
    apply_to_image(profile.model, out.pixels.data(), n, out.pixels.data());  // in place: no third image
    return out;
  }
  apply_to_image(profile.model, rgb, n, out.pixels.data());
  return out;
}

}  // namespace tristim
