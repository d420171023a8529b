// The files the tests, benchmarks and examples read that are not generated at run time: in the
// repository (tests/data/, core/data/, examples/) or installed from Debian by scripts/install-deps.sh.
// tests/data/SOURCES.md gives each one's origin, licence and use. Nothing outside the checkout and
// those packages is read.
#pragma once
#include <string>

namespace tristim::test {

/// Files that Debian packages install (absolute paths).
namespace debian {
/// A Canon EOS 30D CR2 (lossless-JPEG raw, 3504 x 2336, a landscape), package rawtran-doc.
constexpr const char* canon_30d_cr2 = "/usr/share/doc/rawtran/IMG_5952.CR2";
/// ArgyllCMS's reference files (CGATS .cie), package argyll-ref.
constexpr const char* argyll_colorchecker_cie = "/usr/share/color/argyll/ref/ColorChecker.cie";
constexpr const char* argyll_passport_cie = "/usr/share/color/argyll/ref/ColorCheckerPassport.cie";
}  // namespace debian

/// Repository files (paths relative to the checkout).
/// The example DNG: a ColorChecker Passport, Canon 550D (examples/web/SOURCES.md).
constexpr const char* passport_dng = "examples/web/passport.dng";
/// A Kodak DC50 KDC (768 x 512, GRBG, a city street): CC BY-NC-SA 4.0, in its own folder.
constexpr const char* kodak_dc50_kdc = "tests/data/copyleft/kodak-dc50/RAW_KODAK_DC50.KDC";
/// The Passport DNG's 24 patches as camera RGB (dcraw_emu, half size) and its sRGB preview JPEG.
constexpr const char* passport_rgb_csv = "tests/data/passport/camera_rgb_dcraw_emu.csv";
constexpr const char* passport_jpeg = "tests/data/passport/preview_dcraw_emu_srgb.jpg";

/// Full path of a test file: `path` itself when absolute, else `source_dir`/`path`.
inline std::string test_file_path(const std::string& source_dir, const std::string& path) {
  return !path.empty() && path[0] == '/' ? path : source_dir + "/" + path;
}

}  // namespace tristim::test
