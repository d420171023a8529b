// Writes the image files the CLI checks read (tests/CMakeLists.txt, fixture "image_files"):
//   chart8.tif    8-bit RGB TIFF, a cc24 chart, grid corners 20,16,340,16,340,226,20,226
//   chart16.png   the same chart as 16-bit PNG (values × 257)
//   chart.jpg     the same chart as JPEG (quality 95, 4:4:4)
//   truncated.png chart16.png cut to 60 %;   rgba.png  an 8-bit RGBA PNG (refused)
// Patch i (layout order) is R = 20 + 9i, G = 230 - 8i, B = 60 + 5i; background 128.
// usage: tristim_make_test_images <folder>
//        tristim_make_test_images --fuzz-seeds <folder>   (the seed corpora of tests/fuzz:
//        <folder>/tiff, png, jpeg: small files of every layout the decoders read; <folder>/raw:
//        tiny DNGs of every CFA layout and a few broken headers; <folder>/recipe: one complete
//        recipe per linearisation, surface and objective method and per model)
#include <fstream>
#include <stdexcept>
#include <iostream>

#include "dng_writer.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/profile/recipe.hpp"
#include "tristim/surface/surface.hpp"
#include "image_writer.hpp"

using namespace tristim::test;

namespace {
void save(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}
void fuzz_seeds(const std::string& dir) {
  const auto img = [](int w, int h, int channels, int bits) {
    return make_image(w, h, channels, bits, [&](int x, int y, int c) {
      return ((x * 37 + y * 11 + c * 101) * (bits == 16 ? 257 : 1)) % (1 << bits);
    });
  };
  TiffWriteOptions lzw;
  lzw.compression = 5;
  lzw.predictor = 2;
  lzw.rows_per_strip = 4;
  TiffWriteOptions tiles;
  tiles.compression = 8;
  tiles.tile = 16;
  tiles.planar_separate = true;
  TiffWriteOptions packbits;
  packbits.compression = 32773;
  packbits.big_endian = true;
  packbits.make = "Scanner";
  TiffWriteOptions jpeg;
  jpeg.compression = 7;
  jpeg.jpeg_ycbcr = true;
  jpeg.rows_per_strip = 16;
  save(dir + "/tiff/rgb8.tif", write_tiff(img(12, 9, 3, 8)));
  save(dir + "/tiff/grey16_lzw.tif", write_tiff(img(12, 9, 1, 16), lzw));
  save(dir + "/tiff/rgb16_tiles_planar.tif", write_tiff(img(20, 18, 3, 16), tiles));
  save(dir + "/tiff/rgb8_packbits_be.tif", write_tiff(img(12, 9, 3, 8), packbits));
  save(dir + "/tiff/rgb8_jpeg.tif", write_tiff(img(16, 16, 3, 8), jpeg));
  PngWriteOptions interlaced;
  interlaced.interlace = true;
  interlaced.gamma = 0.45455;
  save(dir + "/png/rgb8.png", write_png(img(12, 9, 3, 8)));
  save(dir + "/png/rgb16_interlaced.png", write_png(img(12, 9, 3, 16), interlaced));
  save(dir + "/png/grey16.png", write_png(img(12, 9, 1, 16)));
  JpegWriteOptions progressive;
  progressive.progressive = true;
  progressive.subsample = true;
  JpegWriteOptions arithmetic;
  arithmetic.arithmetic = true;
  save(dir + "/jpeg/rgb.jpg", write_jpeg(img(16, 16, 3, 8)));
  save(dir + "/jpeg/rgb_progressive_420.jpg", write_jpeg(img(24, 16, 3, 8), progressive));
  save(dir + "/jpeg/grey_arithmetic.jpg", write_jpeg(img(16, 8, 1, 8), arithmetic));

  // RAW (fuzz_raw): our own DNGs, small enough for libFuzzer's -max_len; at least 22 pixels a
  // side (LibRaw takes anything smaller for no RAW at all).
  const auto cfa = [](int w, int h) {
    std::vector<std::uint16_t> v(static_cast<std::size_t>(w) * h);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<std::uint16_t>(512 + (i * 2654435761u) % 3000);
    return v;
  };
  tristim::DngWriteOptions bayer;
  bayer.black = 512;
  bayer.white = 4095;
  bayer.exposure_s = 0.01;
  bayer.f_number = 8;
  const auto rggb = tristim::write_dng(cfa(24, 24), 24, 24, bayer);
  save(dir + "/raw/rggb.dng", rggb);
  tristim::DngWriteOptions bggr = bayer;
  bggr.cfa = "BGGR";
  save(dir + "/raw/bggr.dng", tristim::write_dng(cfa(24, 22), 24, 22, bggr));
  tristim::DngWriteOptions xtrans;
  xtrans.cfa = "GGRGGB" "GGBGGR" "BRGRBG" "GGBGGR" "GGRGGB" "RBGBRG";
  save(dir + "/raw/xtrans.dng", tristim::write_dng(cfa(24, 24), 24, 24, xtrans));
  tristim::DngWriteOptions cmyg;
  cmyg.cfa = "CMYG";
  save(dir + "/raw/cmyg.dng", tristim::write_dng(cfa(24, 24), 24, 24, cmyg));
  tristim::DngWriteOptions huge = bayer;
  huge.header_width = 60000;
  huge.header_height = 60000;
  save(dir + "/raw/huge_header.dng", tristim::write_dng(cfa(24, 24), 24, 24, huge));
  save(dir + "/raw/truncated.dng", std::vector<std::uint8_t>(rggb.begin(), rggb.begin() + rggb.size() * 3 / 4));

  // Recipes (fuzz_recipe): every method id once, options completed, so each reader branch has a seed.
  const auto save_recipe = [&](const std::string& name, const tristim::Recipe& r) {
    const std::string text = tristim::recipe_to_json(tristim::complete_recipe(r));
    save(dir + "/recipe/" + name + ".json", std::vector<std::uint8_t>(text.begin(), text.end()));
  };
  for (const auto& m : tristim::linearisation_table()) {
    tristim::Recipe r;
    r.linearisation.method = m.info.id;
    r.sampling.exclude = {"A3"};
    save_recipe("linearisation-" + m.info.id, r);
  }
  for (const auto& m : tristim::surface_table()) {
    tristim::Recipe r;
    r.surface.method = m.info.id;
    save_recipe("surface-" + m.info.id, r);
  }
  for (const auto& m : tristim::objective_table()) {
    tristim::Recipe r;
    r.characterisation.objective.method = m.info.id;
    r.characterisation.white_patch = "D1";
    save_recipe("objective-" + m.info.id, r);
  }
  for (const auto& m : tristim::model_table()) {
    tristim::Recipe r;
    r.characterisation.model = m.id;
    r.sampling.corners = {1.25, 2.5, 101.125, 3, 99.0625, 80.5, 0.1, 79.9};
    save_recipe("model-" + m.id, r);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool seeds = argc == 3 && std::string(argv[1]) == "--fuzz-seeds";
  if (argc != 2 && !seeds) {
    std::cerr << "usage: tristim_make_test_images [--fuzz-seeds] <folder>\n";
    return 2;
  }
  const std::string dir = argv[argc - 1];
  try {
    if (seeds) {
      fuzz_seeds(dir);
      return 0;
    }
    std::vector<std::array<std::uint16_t, 3>> colours;
    for (int i = 0; i < 24; ++i)
      colours.push_back({static_cast<std::uint16_t>(20 + 9 * i), static_cast<std::uint16_t>(230 - 8 * i),
                         static_cast<std::uint16_t>(60 + 5 * i)});
    RenderedChart chart = render_chart("cc24", 360, 240, 20, 16, 320, 210, colours, {128, 128, 128}, 8);
    save(dir + "/chart8.tif", write_tiff(chart.image));
    JpegWriteOptions jo;
    jo.quality = 95;
    save(dir + "/chart.jpg", write_jpeg(chart.image, jo));
    TestImage wide = chart.image;
    wide.bits = 16;
    for (auto& v : wide.samples) v = static_cast<std::uint16_t>(v * 257);
    const auto png = write_png(wide);
    save(dir + "/chart16.png", png);
    save(dir + "/truncated.png", std::vector<std::uint8_t>(png.begin(), png.begin() + png.size() * 6 / 10));
    save(dir + "/rgba.png", write_png(make_image(8, 8, 4, 8, [](int x, int y, int c) { return x * 20 + y + c; })));
  } catch (const std::exception& e) {
    std::cerr << "tristim_make_test_images: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
