// Binding: RAW decoding, frame calibration and chart sampling (core: raw, calibration, chart_layout).
//
// JS API (every function throws an Error with .code on bad input):
//
// decodeRaw(bytes: Uint8Array) -> RawImage
//   Decodes a camera RAW file held in memory. The returned object owns wasm memory: call
//   .delete() when done. Codes: EMPTY_FILE, RAW_UNSUPPORTED, RAW_TRUNCATED, RAW_CORRUPT, RAW_TOO_LARGE.
//
// class RawImage
//   width(), height()      measurement image size (half resolution for Bayer sensors: one pixel
//                          per 2×2 CFA block; 3×3 blocks for X-Trans; see metadata().layout)
//   metadata()             plain object: make, model, lens, iso, shutter_s, f_number, timestamp,
//                          timestamp_iso, layout, cfa_pattern, cfa_width, cfa_height, block,
//                          sensor_width, sensor_height, raw_width, raw_height, width, height, bits,
//                          cfa_black[4], black_level[3], white_level, saturation[3], rgb_cam[9],
//                          cam_xyz[9], as_shot_wb[3], daylight_wb[3], decoder (LibRaw's)
//   linearHash()           hex FNV-1a hash of the uncalibrated linear data (native == wasm)
//   preview(maxSide)       {width, height, scale, rgba: Uint8Array(width*height*4)} — display only
//                          (as-shot WB, LibRaw matrix, sRGB curve); preview pixel (i, j) covers
//                          measurement pixels [i*scale, (i+1)*scale) in x and y
//   setDark(frames, options?)   frames: RawImage or RawImage[] (lens-cap / light-trap shots),
//                          averaged; options {mode: 'pixel' (default) | 'channel'}.
//                          Returns {frames, mean: [3], noise: [3]} (DN). FRAME_MISMATCH.
//   clearDark()
//   setFlat(flat, options?)     flat: RawImage of a uniform white surface; options
//                          {mode: 'pixel' (default, Abed 2013 App. C) | 'radial' (Guarnera 2018
//                          eq 7), whiteReflectance: number | [r, g, b] (pixel mode)}. Uses the
//                          dark frame set before. Returns {mode, target: [3], reflectanceUnits}
//                          or {mode: 'radial', p1, p2, p3, rmsResidual, maxResidual, bins}.
//                          FRAME_MISMATCH, FLAT_FIELD_ZERO.
//   clearFlat()
//   saturationMask()       Uint8Array(width*height) copy: bit 1 = R, 2 = G, 4 = B clipped
//   linearRGB()            Float32Array(width*height*3) copy, row-major interleaved R, G, B,
//                          black-subtracted DN, with the dark/flat set on this image applied
//   delete()
//
// listChartLayouts() -> string[]   ("cc24", "cc24-2005", "passport", "sg140", "sg140-2005", "custom")
//
// sampleChart(raw, layout, corners, options?) ->
//   {ids: string[N], RGB: Float64Array(3N), std: Float64Array(3N), n: Int32Array(N),
//    saturatedFraction: Float64Array(3N), flags: string[][] ("saturated", "dark", "nonuniform"),
//    centres: Float64Array(2N), patchQuads: Float64Array(8N), sampleQuads: Float64Array(8N),
//    homography: Float64Array(9)}
//   layout: {chart: id, rows?, columns?, margins?: [left, top, right, bottom] (fractions), gap?}
//   corners: Float64Array(8) x1,y1..x4,y4 clockwise from the top-left (A1) corner, measurement
//   image coordinates (pixel (x, y) covers [x, x+1) × [y, y+1)); options: {area: 0.5,
//   darkFraction: 0.002, nonuniformThreshold: 0.05}. RGB is linear camera RGB (no WB) with the
//   image's dark/flat applied. Codes: CORNERS_OUTSIDE, CORNERS_CROSSED, PATCH_TOO_SMALL,
//   UNKNOWN_ID, INVALID_ARGUMENT, FRAME_MISMATCH.
#include <optional>

#include "boundary.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/capture/raw.hpp"

using namespace emscripten;
using tristim::wasm::guard;

namespace {

bool is_object(const val& v) { return !v.isNull() && v.typeOf().as<std::string>() == "object"; }
/// options.key is present and not undefined.
bool has(const val& v, const char* key) { return is_object(v) && !v[key].isUndefined(); }

struct RawHandle {
  tristim::RawImage image;
  tristim::FrameCalibration calibration;

  int width() const { return image.width; }
  int height() const { return image.height; }

  val metadata() const {
    return guard([&] { return val::global("JSON").call<val>("parse", val(tristim::metadata_to_json(image.meta))); });
  }
  std::string linear_hash() const {
    return guard([&] { return tristim::hash_hex(tristim::linear_data_hash(image)); });
  }
  val preview(int max_side) const {
    return guard([&] {
      const tristim::Preview pv = tristim::render_preview(image, max_side);
      val out = val::object();
      out.set("width", pv.width);
      out.set("height", pv.height);
      out.set("scale", pv.scale);
      out.set("rgba", val::global("Uint8Array").new_(typed_memory_view(pv.rgba.size(), pv.rgba.data())));
      return out;
    });
  }
  val set_dark(val frames, val options) {
    return guard([&] {
      std::vector<const tristim::RawImage*> ptrs;
      if (frames.isArray()) {
        const unsigned n = frames["length"].as<unsigned>();
        for (unsigned i = 0; i < n; ++i) ptrs.push_back(&frames[i].as<RawHandle*>(allow_raw_pointers())->image);
      } else {
        ptrs.push_back(&frames.as<RawHandle*>(allow_raw_pointers())->image);
      }
      tristim::DarkMode mode = tristim::DarkMode::PerPixel;
      if (has(options, "mode")) {
        const std::string m = options["mode"].as<std::string>();
        if (m == "channel") mode = tristim::DarkMode::PerChannel;
        else if (m != "pixel") throw tristim::Error(tristim::ErrorCode::InvalidArgument, "dark mode is 'pixel' or 'channel'");
      }
      tristim::DarkFrame dark = tristim::average_dark_frames(ptrs);
      tristim::FrameCalibration next = calibration;
      next.dark = std::move(dark);
      next.dark_mode = mode;
      next.check_compatible(image);
      calibration = std::move(next);
      val out = val::object();
      out.set("frames", calibration.dark->frames);
      out.set("mean", triple(calibration.dark->mean));
      out.set("noise", triple(calibration.dark->noise));
      return out;
    });
  }
  val set_dark1(val frames) { return set_dark(frames, val::undefined()); }
  void clear_dark() { calibration.dark.reset(); }
  val set_flat(val flat_val, val options) {
    return guard([&] {
      const tristim::RawImage& flat = flat_val.as<RawHandle*>(allow_raw_pointers())->image;
      std::string mode = "pixel";
      std::optional<std::array<double, 3>> refl;
      if (is_object(options)) {
        if (has(options, "mode")) mode = options["mode"].as<std::string>();
        if (has(options, "whiteReflectance")) {
          const val r = options["whiteReflectance"];
          if (r.isNumber()) {
            const double v = r.as<double>();
            refl = std::array<double, 3>{v, v, v};
          } else {
            const auto v = tristim::wasm::doubles_from_js(r);
            if (v.size() != 3) throw tristim::Error(tristim::ErrorCode::InvalidArgument, "whiteReflectance: a number or [r, g, b]");
            refl = std::array<double, 3>{v[0], v[1], v[2]};
          }
        }
      }
      const tristim::DarkFrame* dark = calibration.dark ? &*calibration.dark : nullptr;
      tristim::FrameCalibration next = calibration;
      val out = val::object();
      out.set("mode", mode);
      if (mode == "pixel") {
        next.flat = tristim::make_flat_field(flat, dark, calibration.dark_mode, refl);
        next.falloff.reset();
        out.set("target", triple(next.flat->target));
        out.set("reflectanceUnits", next.flat->reflectance_units);
      } else if (mode == "radial") {
        next.falloff = tristim::fit_falloff_Guarnera2018(flat, dark);
        next.flat.reset();
        out.set("p1", next.falloff->p1);
        out.set("p2", next.falloff->p2);
        out.set("p3", next.falloff->p3);
        out.set("rmsResidual", next.falloff->rms_residual);
        out.set("maxResidual", next.falloff->max_residual);
        out.set("bins", next.falloff->bins);
      } else {
        throw tristim::Error(tristim::ErrorCode::InvalidArgument, "flat mode is 'pixel' or 'radial'");
      }
      next.check_compatible(image);
      calibration = std::move(next);
      return out;
    });
  }
  val set_flat1(val flat) { return set_flat(flat, val::undefined()); }
  void clear_flat() {
    calibration.flat.reset();
    calibration.falloff.reset();
  }
  val saturation_mask() const {
    return guard([&] {
      return val::global("Uint8Array").new_(typed_memory_view(image.saturated.size(), image.saturated.data()));
    });
  }
  val linear_rgb() const {
    return guard([&] {
      if (!calibration.dark && !calibration.flat && !calibration.falloff)
        return tristim::wasm::float32_array(image.rgb.data(), image.rgb.size());
      const tristim::RawImage cal = tristim::apply_calibration(image, calibration);
      return tristim::wasm::float32_array(cal.rgb.data(), cal.rgb.size());
    });
  }

  static val triple(const std::array<double, 3>& a) {
    val out = val::array();
    for (double v : a) out.call<void>("push", v);
    return out;
  }
};

RawHandle decode_raw(val bytes) {
  return guard([&] {
    RawHandle handle;
    {
      const std::vector<uint8_t> data = tristim::wasm::bytes_from_js(bytes);
      handle.image = tristim::decode_raw(data);
    }  // the file's bytes are freed before the image is handed to JS
    return handle;
  });
}

val list_chart_layouts() {
  return guard([] {
    val out = val::array();
    for (const auto& id : tristim::chart_layout_ids()) out.call<void>("push", val(id));
    return out;
  });
}

val sample_chart(val raw, val layout, val corners_js, val options) {
  return guard([&] {
    const RawHandle* h = raw.as<RawHandle*>(allow_raw_pointers());
    tristim::LayoutOptions lo;
    if (!has(layout, "chart"))
      throw tristim::Error(tristim::ErrorCode::InvalidArgument, "layout needs {chart}");
    lo.chart = layout["chart"].as<std::string>();
    if (has(layout, "rows")) lo.rows = layout["rows"].as<int>();
    if (has(layout, "columns")) lo.columns = layout["columns"].as<int>();
    if (has(layout, "gap")) lo.gap = layout["gap"].as<double>();
    if (has(layout, "margins")) {
      const auto m = tristim::wasm::doubles_from_js(layout["margins"]);
      if (m.size() != 4) throw tristim::Error(tristim::ErrorCode::InvalidArgument, "margins: [left, top, right, bottom]");
      lo.margin_left = m[0];
      lo.margin_top = m[1];
      lo.margin_right = m[2];
      lo.margin_bottom = m[3];
    }
    const auto c = tristim::wasm::doubles_from_js(corners_js);
    if (c.size() != 8) throw tristim::Error(tristim::ErrorCode::InvalidArgument, "corners: 8 numbers x1,y1..x4,y4");
    std::array<double, 8> corners;
    std::copy(c.begin(), c.end(), corners.begin());
    tristim::SampleOptions so;
    if (is_object(options)) {
      if (has(options, "area")) so.area = options["area"].as<double>();
      if (has(options, "darkFraction")) so.dark_fraction = options["darkFraction"].as<double>();
      if (has(options, "nonuniformThreshold")) so.nonuniform_threshold = options["nonuniformThreshold"].as<double>();
    }
    const tristim::ChartSample s = tristim::sample_chart(h->image, lo, corners, so, &h->calibration);
    const size_t n = s.patches.size();
    std::vector<double> rgb(3 * n), sd(3 * n), sat(3 * n), centres(2 * n), quads(8 * n), squads(8 * n);
    std::vector<int> counts(n);
    val ids = val::array(), flags = val::array();
    for (size_t i = 0; i < n; ++i) {
      const auto& p = s.patches[i];
      ids.call<void>("push", val(p.id));
      val f = val::array();
      for (const auto& fl : p.flags) f.call<void>("push", val(fl));
      flags.call<void>("push", f);
      for (int k = 0; k < 3; ++k) {
        rgb[3 * i + k] = p.mean[k];
        sd[3 * i + k] = p.std[k];
        sat[3 * i + k] = p.saturated_fraction[k];
      }
      centres[2 * i] = p.centre[0];
      centres[2 * i + 1] = p.centre[1];
      for (int k = 0; k < 8; ++k) {
        quads[8 * i + k] = p.quad[k];
        squads[8 * i + k] = p.sample_quad[k];
      }
      counts[i] = p.n;
    }
    using tristim::wasm::float64_array;
    val out = val::object();
    out.set("ids", ids);
    out.set("RGB", float64_array(rgb.data(), rgb.size()));
    out.set("std", float64_array(sd.data(), sd.size()));
    out.set("n", val::global("Int32Array").new_(typed_memory_view(counts.size(), counts.data())));
    out.set("saturatedFraction", float64_array(sat.data(), sat.size()));
    out.set("flags", flags);
    out.set("centres", float64_array(centres.data(), centres.size()));
    out.set("patchQuads", float64_array(quads.data(), quads.size()));
    out.set("sampleQuads", float64_array(squads.data(), squads.size()));
    out.set("homography", float64_array(s.homography.data(), 9));
    return out;
  });
}
val sample_chart3(val raw, val layout, val corners) { return sample_chart(raw, layout, corners, val::undefined()); }

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_raw) {
  class_<RawHandle>("RawImage")
      .function("width", &RawHandle::width)
      .function("height", &RawHandle::height)
      .function("metadata", &RawHandle::metadata)
      .function("linearHash", &RawHandle::linear_hash)
      .function("preview", &RawHandle::preview)
      .function("setDark", &RawHandle::set_dark)
      .function("setDark", &RawHandle::set_dark1)
      .function("clearDark", &RawHandle::clear_dark)
      .function("setFlat", &RawHandle::set_flat)
      .function("setFlat", &RawHandle::set_flat1)
      .function("clearFlat", &RawHandle::clear_flat)
      .function("saturationMask", &RawHandle::saturation_mask)
      .function("linearRGB", &RawHandle::linear_rgb);
  function("decodeRaw", &decode_raw);
  function("listChartLayouts", &list_chart_layouts);
  function("sampleChart", &sample_chart);
  function("sampleChart", &sample_chart3);
}
