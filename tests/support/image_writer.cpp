// Test-time TIFF, PNG and JPEG writers (see image_writer.hpp).
#include "image_writer.hpp"

#include <cstdio>
#include <cstdlib>
#include <csetjmp>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <jpeglib.h>
#include <png.h>
#include <tiffio.h>

#include "tristim/chart/layout.hpp"

namespace tristim::test {

namespace {

// ---------------------------------------------------------------- TIFF
struct MemFile {
  std::vector<std::uint8_t> data;
  std::uint64_t pos = 0;
};
tmsize_t mem_read(thandle_t h, void* buf, tmsize_t n) {
  auto* f = static_cast<MemFile*>(h);
  if (f->pos >= f->data.size()) return 0;
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(n), f->data.size() - f->pos);
  std::memcpy(buf, f->data.data() + f->pos, k);
  f->pos += k;
  return static_cast<tmsize_t>(k);
}
tmsize_t mem_write(thandle_t h, void* buf, tmsize_t n) {
  auto* f = static_cast<MemFile*>(h);
  if (f->pos + n > f->data.size()) f->data.resize(f->pos + n);
  std::memcpy(f->data.data() + f->pos, buf, static_cast<std::size_t>(n));
  f->pos += n;
  return n;
}
toff_t mem_seek(thandle_t h, toff_t off, int whence) {
  auto* f = static_cast<MemFile*>(h);
  f->pos = (whence == SEEK_CUR ? f->pos : whence == SEEK_END ? f->data.size() : 0) + off;
  return f->pos;
}
int mem_close(thandle_t) { return 0; }
toff_t mem_size(thandle_t h) { return static_cast<MemFile*>(h)->data.size(); }
int mem_map(thandle_t, void**, toff_t*) { return 0; }
void mem_unmap(thandle_t, void*, toff_t) {}

void need(bool ok, const char* what) {
  if (!ok) throw std::runtime_error(std::string("test image writer: ") + what);
}

/// Row y (or plane `plane` of it when plane >= 0) packed as bytes of `bits` per sample.
std::vector<std::uint8_t> pack_row(const TestImage& im, int y, int plane, std::size_t row_bytes) {
  std::vector<std::uint8_t> out(row_bytes, 0);
  if (im.bits != 8 && im.bits != 16) return out;  // odd depths: zeros of the right size
  const int per = plane >= 0 ? 1 : im.channels;
  for (int x = 0; x < im.width; ++x)
    for (int s = 0; s < per; ++s) {
      const int c = plane >= 0 ? plane : s;
      const std::uint16_t v = im.samples[(static_cast<std::size_t>(y) * im.width + x) * im.channels + c];
      const std::size_t i = static_cast<std::size_t>(x) * per + s;
      if (im.bits == 8) out[i] = static_cast<std::uint8_t>(v);
      else std::memcpy(&out[2 * i], &v, 2);
    }
  return out;
}

}  // namespace

std::vector<std::uint8_t> write_tiff(const TestImage& im, const TiffWriteOptions& o) {
  MemFile file;
  std::string mode = "w";
  mode += o.big_endian ? "b" : "l";
  if (o.big_tiff) mode += "8";
  TIFF* t = TIFFClientOpen("test.tif", mode.c_str(), &file, mem_read, mem_write, mem_seek, mem_close, mem_size,
                           mem_map, mem_unmap);
  need(t != nullptr, "TIFFClientOpen");
  std::unique_ptr<TIFF, void (*)(TIFF*)> guard(t, TIFFClose);
  const int colour_samples = im.channels - o.extra_samples;
  const int photometric = o.photometric >= 0 ? o.photometric
                          : colour_samples == 1 ? PHOTOMETRIC_MINISBLACK
                          : colour_samples == 4 ? PHOTOMETRIC_SEPARATED
                                                : PHOTOMETRIC_RGB;
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(im.width));
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(im.height));
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, static_cast<std::uint16_t>(im.channels));
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, static_cast<std::uint16_t>(im.bits));
  TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, static_cast<std::uint16_t>(o.sample_format));
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, o.planar_separate ? PLANARCONFIG_SEPARATE : PLANARCONFIG_CONTIG);
  TIFFSetField(t, TIFFTAG_COMPRESSION, static_cast<std::uint16_t>(o.compression));
  if (o.compression == COMPRESSION_JPEG) {
    TIFFSetField(t, TIFFTAG_JPEGQUALITY, o.jpeg_quality);
    if (o.jpeg_ycbcr) {
      TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_YCBCR);
      TIFFSetField(t, TIFFTAG_JPEGCOLORMODE, JPEGCOLORMODE_RGB);
    } else {
      TIFFSetField(t, TIFFTAG_PHOTOMETRIC, static_cast<std::uint16_t>(photometric));
    }
  } else {
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, static_cast<std::uint16_t>(photometric));
  }
  if (o.predictor != 1) TIFFSetField(t, TIFFTAG_PREDICTOR, static_cast<std::uint16_t>(o.predictor));
  if (photometric == PHOTOMETRIC_PALETTE) {
    std::vector<std::uint16_t> map(std::size_t(1) << im.bits);
    for (std::size_t i = 0; i < map.size(); ++i) map[i] = static_cast<std::uint16_t>(i * 257);
    TIFFSetField(t, TIFFTAG_COLORMAP, map.data(), map.data(), map.data());
  }
  if (o.extra_samples > 0) {
    std::vector<std::uint16_t> kinds(o.extra_samples, EXTRASAMPLE_UNASSALPHA);
    TIFFSetField(t, TIFFTAG_EXTRASAMPLES, static_cast<std::uint16_t>(o.extra_samples), kinds.data());
  }
  if (o.orientation > 0) TIFFSetField(t, TIFFTAG_ORIENTATION, static_cast<std::uint16_t>(o.orientation));
  if (!o.make.empty()) TIFFSetField(t, TIFFTAG_MAKE, o.make.c_str());
  if (!o.model.empty()) TIFFSetField(t, TIFFTAG_MODEL, o.model.c_str());
  if (!o.datetime.empty()) TIFFSetField(t, TIFFTAG_DATETIME, o.datetime.c_str());
  if (!o.icc.empty()) TIFFSetField(t, TIFFTAG_ICCPROFILE, static_cast<std::uint32_t>(o.icc.size()), o.icc.data());
  const int planes = o.planar_separate ? im.channels : 1;
  if (o.tile > 0) {
    TIFFSetField(t, TIFFTAG_TILEWIDTH, static_cast<std::uint32_t>(o.tile));
    TIFFSetField(t, TIFFTAG_TILELENGTH, static_cast<std::uint32_t>(o.tile));
    const std::size_t tile_bytes = static_cast<std::size_t>(TIFFTileSize(t));
    const std::size_t tile_row = tile_bytes / o.tile;
    const std::size_t line = static_cast<std::size_t>(TIFFScanlineSize(t));
    for (int p = 0; p < planes; ++p)
      for (int y0 = 0; y0 < im.height; y0 += o.tile)
        for (int x0 = 0; x0 < im.width; x0 += o.tile) {
          std::vector<std::uint8_t> tile(tile_bytes, 0);
          const std::size_t px_bytes = line / im.width;
          for (int r = 0; r < o.tile && y0 + r < im.height; ++r) {
            const auto row = pack_row(im, y0 + r, o.planar_separate ? p : -1, line);
            const int cols = std::min(o.tile, im.width - x0);
            std::memcpy(&tile[r * tile_row], &row[x0 * px_bytes], cols * px_bytes);
          }
          need(TIFFWriteTile(t, tile.data(), x0, y0, 0, static_cast<std::uint16_t>(p)) >= 0, "TIFFWriteTile");
        }
  } else {
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP,
                 o.rows_per_strip > 0 ? static_cast<std::uint32_t>(o.rows_per_strip) : TIFFDefaultStripSize(t, 0));
    const std::size_t line = static_cast<std::size_t>(TIFFScanlineSize(t));
    for (int p = 0; p < planes; ++p)
      for (int y = 0; y < im.height; ++y) {
        auto row = pack_row(im, y, o.planar_separate ? p : -1, line);
        need(TIFFWriteScanline(t, row.data(), static_cast<std::uint32_t>(y), static_cast<std::uint16_t>(p)) == 1,
             "TIFFWriteScanline");
      }
  }
  need(TIFFWriteDirectory(t) == 1, "TIFFWriteDirectory");
  guard.reset();
  return file.data;
}

// ---------------------------------------------------------------- PNG
namespace {
void png_append(png_structp png, png_bytep data, size_t n) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + n);
}
void png_flush(png_structp) {}

/// Rows as the file stores them (16-bit big-endian; palette: index = position in `palette`).
std::vector<std::vector<std::uint8_t>> png_rows(const TestImage& im, const PngWriteOptions& o, int depth,
                                                std::vector<png_color>* palette) {
  std::vector<std::vector<std::uint8_t>> rows;
  const int per = o.palette ? 1 : im.channels;
  for (int y = 0; y < im.height; ++y) {
    std::vector<std::uint8_t> row((static_cast<std::size_t>(im.width) * per * depth + 7) / 8, 0);
    for (int x = 0; x < im.width; ++x) {
      if (o.palette) {
        png_color col{static_cast<png_byte>(im.samples[(y * im.width + x) * 3]),
                      static_cast<png_byte>(im.samples[(y * im.width + x) * 3 + 1]),
                      static_cast<png_byte>(im.samples[(y * im.width + x) * 3 + 2])};
        std::size_t k = 0;
        while (k < palette->size() && std::memcmp(&(*palette)[k], &col, sizeof col) != 0) ++k;
        if (k == palette->size()) palette->push_back(col);
        row[x] = static_cast<std::uint8_t>(k);
        continue;
      }
      for (int c = 0; c < per; ++c) {
        const std::uint16_t v = im.samples[(static_cast<std::size_t>(y) * im.width + x) * im.channels + c];
        const std::size_t i = static_cast<std::size_t>(x) * per + c;
        if (depth == 16) {
          row[2 * i] = static_cast<std::uint8_t>(v >> 8);
          row[2 * i + 1] = static_cast<std::uint8_t>(v & 255);
        } else if (depth == 8) {
          row[i] = static_cast<std::uint8_t>(v);
        } else {  // 1, 2, 4-bit grey, packed from the most significant bit
          const std::size_t bit = i * depth;
          row[bit / 8] |= static_cast<std::uint8_t>(v << (8 - depth - bit % 8));
        }
      }
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

/// libpng calls only, under setjmp: no C++ object and no call that throws in this frame (native
/// wasm exceptions refuse a function with both setjmp and landing pads; see core image_png.cpp).
bool png_write_all(png_structp png, png_infop info, const TestImage& im, const PngWriteOptions& o, int colour,
                   int depth, png_colorp palette, int n_palette, png_bytepp rows, std::vector<std::uint8_t>* out) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, out, png_append, png_flush);
  png_set_IHDR(png, info, im.width, im.height, depth, colour,
               o.interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (o.gamma > 0) png_set_gAMA(png, info, o.gamma);
  if (o.srgb) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  if (o.palette) png_set_PLTE(png, info, palette, n_palette);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}
}  // namespace

std::vector<std::uint8_t> write_png(const TestImage& im, const PngWriteOptions& o) {
  int colour = im.channels == 1 ? PNG_COLOR_TYPE_GRAY
               : im.channels == 2 ? PNG_COLOR_TYPE_GRAY_ALPHA
               : im.channels == 3 ? PNG_COLOR_TYPE_RGB
                                  : PNG_COLOR_TYPE_RGB_ALPHA;
  int depth = im.bits;
  if (o.palette) colour = PNG_COLOR_TYPE_PALETTE;
  if (o.grey_bits > 0) depth = o.grey_bits;
  std::vector<png_color> palette;
  std::vector<std::vector<std::uint8_t>> rows = png_rows(im, o, depth, &palette);
  std::vector<png_bytep> ptrs;
  for (auto& r : rows) ptrs.push_back(r.data());
  std::vector<std::uint8_t> out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  need(png != nullptr, "png_create_write_struct");
  png_infop info = png_create_info_struct(png);
  const bool ok = info && png_write_all(png, info, im, o, colour, depth, palette.data(),
                                        static_cast<int>(palette.size()), ptrs.data(), &out);
  png_destroy_write_struct(&png, &info);
  need(ok, "libpng write");
  return out;
}

// ---------------------------------------------------------------- JPEG
namespace {
struct JpegWriteErr {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
};
void jpeg_write_error(j_common_ptr c) { std::longjmp(reinterpret_cast<JpegWriteErr*>(c->err)->jump, 1); }

/// libjpeg calls only, under setjmp: no C++ object and no call that throws in this frame (see
/// png_write_all). `pixels`: the whole image, rows of width × channels samples.
bool jpeg_write_all(jpeg_compress_struct* c, JpegWriteErr* err, const TestImage& im, const JpegWriteOptions& o,
                    unsigned char** buf, unsigned long* len, JSAMPLE* pixels) {
  if (setjmp(err->jump)) return false;
  jpeg_create_compress(c);
  jpeg_mem_dest(c, buf, len);
  c->image_width = im.width;
  c->image_height = im.height;
  c->input_components = im.channels;
  c->in_color_space = im.channels == 1 ? JCS_GRAYSCALE : o.cmyk ? JCS_CMYK : JCS_RGB;
  jpeg_set_defaults(c);
  if (o.rgb) jpeg_set_colorspace(c, JCS_RGB);
  jpeg_set_quality(c, o.quality, TRUE);
  if (im.channels == 3 && !o.rgb) {
    const int h = o.subsample ? 2 : 1;
    c->comp_info[0].h_samp_factor = c->comp_info[0].v_samp_factor = h;
    for (int k = 1; k < 3; ++k) c->comp_info[k].h_samp_factor = c->comp_info[k].v_samp_factor = 1;
  }
  if (o.progressive) jpeg_simple_progression(c);
  c->arith_code = o.arithmetic ? TRUE : FALSE;
  c->dct_method = JDCT_ISLOW;
  jpeg_start_compress(c, TRUE);
  if (!o.icc.empty()) jpeg_write_icc_profile(c, o.icc.data(), static_cast<unsigned>(o.icc.size()));
  const std::size_t stride = static_cast<std::size_t>(im.width) * im.channels;
  while (c->next_scanline < c->image_height) {
    JSAMPROW r[1] = {pixels + c->next_scanline * stride};
    jpeg_write_scanlines(c, r, 1);
  }
  jpeg_finish_compress(c);
  return true;
}
}  // namespace

std::vector<std::uint8_t> write_jpeg(const TestImage& im, const JpegWriteOptions& o) {
  need(im.bits == 8, "JPEG writer: 8-bit samples only");
  std::vector<JSAMPLE> pixels(static_cast<std::size_t>(im.width) * im.height * im.channels);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<JSAMPLE>(im.samples[i]);
  jpeg_compress_struct c{};
  JpegWriteErr err{};
  c.err = jpeg_std_error(&err.pub);
  err.pub.error_exit = jpeg_write_error;
  unsigned char* buf = nullptr;
  unsigned long len = 0;
  const bool ok = jpeg_write_all(&c, &err, im, o, &buf, &len, pixels.data());
  jpeg_destroy_compress(&c);
  std::vector<std::uint8_t> out;
  if (ok && buf) out.assign(buf, buf + len);
  std::free(buf);
  need(ok, "libjpeg write");
  return out;
}

// ---------------------------------------------------------------- charts
RenderedChart render_chart(const std::string& chart, int width, int height, int x0, int y0, int w, int h,
                           const std::vector<std::array<std::uint16_t, 3>>& colours,
                           std::array<std::uint16_t, 3> background, int bits) {
  LayoutOptions lo;
  lo.chart = chart;
  const ChartLayout layout = chart_layout(lo);
  need(colours.size() == layout.patches.size(), "render_chart: one colour per patch");
  RenderedChart out;
  out.image = make_image(width, height, 3, bits, [&](int x, int y, int c) {
    const double u = (x + 0.5 - x0) / w, v = (y + 0.5 - y0) / h;
    for (std::size_t i = 0; i < layout.patches.size(); ++i) {
      const PatchCell& p = layout.patches[i];
      if (u >= p.u0 && u < p.u1 && v >= p.v0 && v < p.v1) return colours[i][c];
    }
    return background[c];
  });
  out.corners = {double(x0), double(y0), double(x0 + w), double(y0), double(x0 + w), double(y0 + h),
                 double(x0), double(y0 + h)};
  return out;
}

}  // namespace tristim::test
