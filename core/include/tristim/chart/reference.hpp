// Colour charts. This header's first part is the reference data of the built-in charts (what a
// patch should measure); chart geometry for sampling images lives in its own section/files.
//
// Chart ids (TEAM.md): "cc24" ColorChecker Classic, X-Rite data for charts made after Nov 2014;
// "cc24-2005" the same before Nov 2014; "sg140" ColorChecker (Digital) SG after Nov 2014,
// "sg140-2005" before; "passport" the classic 24-patch side of the ColorChecker Passport (same
// ids and data as cc24, see core/data/SOURCES.md). Patch ids: cc24/passport "A1".."D6" (row A-D
// top to bottom, column 1-6; A1 = dark skin, D6 = black); SG "A1".."N10" (letter = column A-N,
// number = row 1-10).
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/colorimetry/spectra.hpp"

namespace tristim {

// ================================================================ reference data

struct ChartInfo {
  std::string id;           // "cc24"
  std::string name;         // "ColorChecker Classic (X-Rite, after Nov 2014)"
  int patches = 0;          // 24
  int rows = 0, columns = 0;
  std::string source;       // where the spectra and Lab come from (short)
};
/// The built-in reference charts, in a stable order.
std::vector<ChartInfo> list_charts();

/// Measured spectral reflectances (fractions) of a built-in chart; names = patch ids in the
/// chart's order. Error(UnknownId) for an unknown chart.
SpectralData chart_reflectances(std::string_view chart_id);

/// Reference colorimetry of a set of patches under one illuminant and observer.
/// XYZ: perfect diffuser Y = 100. Lab: relative to `white` (the illuminant's white for that
/// observer). sRGB: display-encoded 0..1 after Bradford adaptation from `white` to D65
/// (clipped to the gamut), for swatches only.
struct ReferenceChart {
  std::string chart_id;      // "cc24", or the file name for parsed files
  std::string illuminant_id; // "D65", or "" when the data came as XYZ/Lab
  Observer observer = Observer::CIE1931_2;
  std::vector<std::string> ids;     // the patches' keys (a file's normalised ids: normalise_patch_id)
  std::vector<std::string> labels;  // the same ids as the data spell them, one per id (a user
                                    // file's "A01"; the chart's own ids): what outputs write
  std::vector<Vec3> XYZ, Lab, sRGB;
  Vec3 white = Vec3(0, 0, 0);
};

/// Reference XYZ/Lab of a built-in chart computed from its spectra (spectra.hpp integration rule)
/// under `illuminant_id` (any id illuminant_spd accepts). Error(UnknownId) for unknown ids.
ReferenceChart reference_chart(std::string_view chart_id, std::string_view illuminant_id = "D65",
                               Observer observer = Observer::CIE1931_2);
/// The same from explicit spectra and SPD (e.g. a user's file).
ReferenceChart reference_from_spectra(const SpectralData& reflectances, const SpectralData& illuminant,
                                      Observer observer);
/// A measurement file as reference: spectra are integrated under the illuminant; an XYZ and/or Lab
/// table is used as given (missing Lab = XYZ_to_Lab relative to the illuminant's white; missing
/// XYZ = Lab_to_XYZ with that white; an XYZ table whose Y never exceeds 1.5 is taken to be on the
/// 0..1 scale and multiplied by 100). Error(MissingColumn) if the file has none of these.
ReferenceChart reference_from_table(const PatchTable& table, const SpectralData& illuminant, Observer observer);

/// X-Rite's published CIELAB (D50, 2°) of a built-in chart, as printed (2 decimals); ids as above.
struct PublishedReference {
  std::string chart_id, source;
  std::vector<std::string> ids;
  std::vector<Vec3> Lab;
};
PublishedReference published_reference_Lab(std::string_view chart_id);

/// Measured patches paired with reference patches by normalised id (normalise_patch_id): the one
/// pairing of the CLI's --rgb/--xyz and --test-rgb/--test-xyz and of training_set (the page's
/// chart samples and held-out files, `tristim fit --recipe`). Order: the measurement's, keeping
/// the ids present in both — the patches in the order the user measured them, which is a chart
/// sample's layout order, so per-patch lists, CSV exports and training digests are the same
/// whichever way the RGB arrived; a measured id appearing twice pairs twice. missing_in_measured
/// lists the reference's unpaired ids in the reference's order, missing_in_reference the
/// measurement's in its order (normalised). Error(PatchMismatch) if no id is shared, or if the
/// counts of ids and rows differ.
struct PatchPairs {
  std::vector<std::string> ids;
  std::vector<Vec3> measured, reference;
  std::vector<std::string> missing_in_measured, missing_in_reference;
  std::vector<int> measured_rows, reference_rows;  ///< each pair's row in the measured / reference input
};
PatchPairs pair_by_id(const std::vector<std::string>& reference_ids, const std::vector<Vec3>& reference,
                      const std::vector<std::string>& measured_ids, const std::vector<Vec3>& measured);

/// Display colour of XYZ seen under `white` (same scale as XYZ): Bradford to D65, then sRGB
/// encoded (0..1, clipped). For display only, never for measurement.
Vec3 display_sRGB(const Vec3& XYZ, const Vec3& white);
/// The linear part of display_sRGB: XYZ -> linear sRGB with `white` -> (1, 1, 1), whatever
/// white's scale (relative Y = 100 or absolute cd/m²).
Mat3 display_matrix(const Vec3& white);

}  // namespace tristim
