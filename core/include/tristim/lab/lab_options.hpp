// The bounds of the numbers a user gives the colorimetry lab: the chart photograph's exposure,
// noise, fall-off, flare and seed (LabRenderOptions), the exercises' noise (OverfitOptions,
// lab_table4_exercise) and the metamer search's threshold and count (MetamerOptions) — one
// OptionSpec row each, which the page builds its number boxes from (labels, units,
// min/max/step/default), `tristim lab --help` lists, and the lab's functions check values against
// (lab_option), so a bound is written once.
#pragma once
#include <string>
#include <vector>

#include "tristim/methods.hpp"

namespace tristim {

/// Rows named "<subcommand>.<member>": render.exposure, render.shot_gain, render.read_noise,
/// render.falloff, render.flare, render.seed (LabRenderOptions; `tristim lab render`),
/// overfit.noise (OverfitOptions::noise; `lab overfit`), table4.noise (lab_table4_exercise's noise;
/// `lab table4`: the surface step's Table IV noise row, surface/options_table.hpp), metamers.max_match, metamers.top (MetamerOptions; `lab metamers`). Defaults are
/// the structs' defaults; every value inside a row's [min, max] is one the function accepts, and
/// every value outside it is refused with Error(InvalidArgument).
std::vector<OptionSpec> lab_option_table();

/// A kind of file the lab's renderer writes (lab_render_files' `format`; the page's File picker).
struct LabFileKind {
  std::string id;          ///< "dng" | "tiff" | "jpeg": lab_render_files' format
  std::string label;       ///< what the picker shows
  std::string extension;   ///< a file name's extension, without the dot
  std::string media_type;  ///< the file's MIME type (a download's)
  bool through_oecf = true;  ///< encoded through LabRenderOptions::oecf (false: linear sensor data, oecf "linear")
};
/// dng (linear sensor data), tiff (16 bits through the OECF), jpeg (8 bits through the OECF, at
/// LabRenderOptions::jpeg_quality): lab_render_files accepts exactly these ids.
std::vector<LabFileKind> lab_file_kinds();

/// The viewers a metamer pair can be made to match for (MetamerOptions::match; the page's "Match
/// for"): "observer" (the CIE observer's ΔE00) and "camera" (the camera's, through its best 3×3
/// matrix to XYZ); metamer_pairs and construct_metamer accept exactly these ids.
std::vector<MethodInfo> metamer_match_table();

/// The charts exercise 3 trains on (ShenOptions::chart; the page's "Training chart"), named by
/// their role in Shen et al. 2008: "cc24" (the paper's MCC: its 18 non-grey patches) and "sg140"
/// (in the CDC's role); lab_shen_exercise accepts exactly these ids.
std::vector<MethodInfo> shen_training_table();

/// `value` checked against row `name` of lab_option_table(): returned when inside [min, max] (and
/// whole for an integer row); otherwise Error(InvalidArgument) naming the option, its bounds and the
/// value. Error(Internal) for a name the table does not have.
double lab_option(const std::string& name, double value);

/// A value of row `o` as text: every digit for an integer row, 6 significant digits otherwise
/// (the help's and the error messages' spelling).
std::string lab_option_number(const OptionSpec& o, double value);

}  // namespace tristim
