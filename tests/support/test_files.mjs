// The files the node and browser tests read that are not generated at run time: in the repository
// (tests/data/, core/data/, examples/) or installed from Debian by scripts/install-deps.sh.
// tests/data/SOURCES.md gives each one's origin, licence and use; tests/support/test_files.hpp is
// the same list for the Catch2 suite. Nothing outside the checkout and those packages is read.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');

/// Absolute paths of the files, by name.
export const testFiles = {
  /** The example DNG: a ColorChecker Passport, Canon 550D (examples/web/SOURCES.md). */
  passportDng: path.join(repoRoot, 'examples/web/passport.dng'),
  /** The Passport DNG's 24 patches as camera RGB (dcraw_emu, half size) and its sRGB preview JPEG. */
  passportRgbCsv: path.join(repoRoot, 'tests/data/passport/camera_rgb_dcraw_emu.csv'),
  passportJpeg: path.join(repoRoot, 'tests/data/passport/preview_dcraw_emu_srgb.jpg'),
  /** A Kodak DC50 KDC (768 x 512, GRBG, a city street; no chart): CC BY-NC-SA 4.0, its own folder. */
  kodakDc50Kdc: path.join(repoRoot, 'tests/data/copyleft/kodak-dc50/RAW_KODAK_DC50.KDC'),
  /** A Canon EOS 30D CR2 (3504 x 2336, a landscape): Debian package rawtran-doc. */
  canon30dCr2: '/usr/share/doc/rawtran/IMG_5952.CR2',
  /** ArgyllCMS's ColorChecker reference (CGATS .cie): Debian package argyll-ref. */
  argyllColorCheckerCie: '/usr/share/color/argyll/ref/ColorChecker.cie',
};

const debianPackage = {
  [testFiles.canon30dCr2]: 'rawtran-doc',
  [testFiles.argyllColorCheckerCie]: 'argyll-ref',
};

/// Bytes of a test file (a path of testFiles, or repository-relative). A missing file throws an
/// error naming it and, for a Debian file, its package; a test never skips for it.
export function readTestFile(file) {
  const full = path.isAbsolute(file) ? file : path.join(repoRoot, file);
  if (!fs.existsSync(full)) {
    const pkg = debianPackage[full];
    throw new Error(pkg
      ? `this test reads ${full}, which Debian's ${pkg} installs: run scripts/install-deps.sh`
      : `this test reads ${full}, a file of the repository, which is missing`);
  }
  return fs.readFileSync(full);
}
