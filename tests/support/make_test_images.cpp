// Writes the image files the CLI checks read (tests/CMakeLists.txt, fixture "image_files"):
//   chart8.tif    8-bit RGB TIFF, a cc24 chart, grid corners 20,16,340,16,340,226,20,226
//   chart16.png   the same chart as 16-bit PNG (values × 257)
//   chart.jpg     the same chart as JPEG (quality 95, 4:4:4)
//   truncated.png chart16.png cut to 60 %;   rgba.png  an 8-bit RGBA PNG (refused)
// Patch i (layout order) is R = 20 + 9i, G = 230 - 8i, B = 60 + 5i; background 128.
// usage: tristim_make_test_images <folder>
#include <fstream>
#include <stdexcept>
#include <iostream>

#include "image_writer.hpp"

using namespace tristim::test;

namespace {
void save(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: tristim_make_test_images <folder>\n";
    return 2;
  }
  const std::string dir = argv[1];
  try {
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
