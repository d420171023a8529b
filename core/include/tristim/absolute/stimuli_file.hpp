// Training stimuli of the absolute tele-colorimeter (Guarnera 2018 section 4, the luminance and
// colour training sets) as a CSV: the format `tristim absolute fit --stimuli` reads and the page
// loads. One row per stimulus and shot; column names exact (case-sensitive: the region's x, y
// differ from the measured X, Y):
//   id, set (luminance | colour; empty: luminance when X = Y = Z within 2 %),
//   exposure_s, f_number, iso (empty: from the RAW metadata of a region row's file),
//   either  file, x, y, w, h   (a region of a RAW, measurement pixels)
//   or      R, G, B [, falloff] (black-subtracted DN of the region, f(r) of eq 7; default 1),
//   X, Y, Z (measured, cd/m²).
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "tristim/absolute/luminance.hpp"

namespace tristim {

/// One row of a stimuli CSV. For a per-patch row `stimulus` is complete (saturated flags are
/// set later, when S is known); a region row names its `file` and region and carries the
/// exposure given in the row (zeros: from the file's metadata).
struct StimulusRow {
  TrainingStimulus stimulus;
  std::string file;        ///< "" for a per-patch row
  int x = 0, y = 0, w = 0, h = 0;
  int line = 0;            ///< line in the file, for messages
};

/// The equal-tristimulus rule of a row without a set: X and Z within 2 % of Y (section 3.1's
/// luminance training asks for X = Y = Z; a calibrated projector reaches it to about that).
bool equal_tristimulus(const Vec3& XYZ);

/// Reads a stimuli CSV. Errors (naming `source` and the line): MissingColumn (no X, Y, Z; neither
/// R, G, B nor file; a file row without x, y, w, h), NonNumeric/NonFinite cells, InvalidArgument
/// (a set other than luminance/colour), MissingMetadata (a per-patch row without exposure_s and
/// f_number), EmptyFile (no rows).
std::vector<StimulusRow> read_stimuli_csv(std::string_view text, const std::string& source);

/// Per-patch rows of the same format (id, set, exposure_s, f_number, iso, R, G, B, falloff, X, Y,
/// Z; 17 significant digits), e.g. stimuli sampled from RAWs to be fitted elsewhere.
std::string stimuli_to_csv(const std::vector<TrainingStimulus>& stimuli);

}  // namespace tristim
