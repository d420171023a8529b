// tristim — the colorimetry lab's exercises, computed in the core so the page, the CLI
// (`tristim lab overfit`) and the tests print the same numbers.
//
// Exercise 2, "why a 3×3 is not enough": a camera (or the CMFs themselves, the Luther camera)
// photographs a training chart through the virtual camera (simulate/virtual_camera.hpp) with
// seeded Gaussian noise σ (relative to the white diffuser's G = 1); each model is fitted by least
// squares to the chart's reference XYZ and scored by mean CIEDE2000 on (a) the training patches,
// (b) leave-one-out (each patch predicted by the model fitted without it) and (c) a held-out
// set, the 1269 Munsell matte chips, noise-free. A model with more terms than the chart has
// patches is refused (TOO_FEW_PATCHES: infinitely many exact fits); with as many terms as
// patches the training error is ~0 and says nothing, which (b) and (c) show.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/json.hpp"

namespace tristim {

struct OverfitRow {
  std::string model;          ///< model id (model_table)
  std::string training;       ///< training chart id ("cc24", "sg140")
  int terms = 0;
  int patches = 0;            ///< training patches
  bool ok = false;            ///< false: refused (error_code, message)
  std::string error_code, message;
  /// Means; NaN when refused, loo also when N − 1 patches are too few for the model.
  double train_dE00 = std::numeric_limits<double>::quiet_NaN(), loo_dE00 = std::numeric_limits<double>::quiet_NaN(),
         test_dE00 = std::numeric_limits<double>::quiet_NaN();
};
/// {"model","training","terms","patches","ok","error_code","train_dE00","loo_dE00","test_dE00"}
/// (NaN as null): the CLI's row (the list also has message).
json::Value overfit_row_json(const OverfitRow& row);

struct OverfitOptions {
  std::vector<std::string> models{"matrix-3x3", "Finlayson2015-2", "Cheung2004-10", "Cheung2004-22", "Cheung2004-35"};
  std::vector<std::string> training{"cc24", "sg140"};
  double noise = 0.002;       ///< σ of the camera noise, fraction of the white's G
  std::uint64_t seed = 1;
};

/// Every model × training chart (see header). Error(UnknownId) for an unknown model or chart.
std::vector<OverfitRow> lab_overfit_exercise(const SpectralData& sensitivities, const SpectralData& illuminant,
                                             const OverfitOptions& options = {});

// Exercise 1, "spectra to colour": one patch's reflectance R(λ), the colour stimulus R(λ)·S(λ)
// under each illuminant (each S scaled to 100 at 560 nm), and its XYZ (CIE 15 integration,
// Y_white = 100), CIELAB (relative to that illuminant's white: the von Kries-type normalisation
// CIELAB builds in) and xy per illuminant × observer — what `tristim reference --chart <c>
// --illuminant <I> --observer <O>` prints for that patch.
struct ColourRow {
  std::string illuminant, observer;
  Vec3 XYZ = Vec3::Zero(), Lab = Vec3::Zero();
  double x = 0, y = 0;
};
struct SpectraToColour {
  std::string chart, patch;
  std::vector<double> wavelengths;
  std::vector<double> reflectance;
  std::vector<std::vector<double>> stimulus;  ///< one per illuminant, in the order given
  std::vector<std::string> illuminants;
  std::vector<ColourRow> rows;                ///< illuminant-major, then observer
};
/// `illuminants` empty: the exercise's D65, A and F11; `observers` empty: 1931 and 1964 (the page
/// leaves both to the engine). Error(UnknownId) for an unknown chart, patch, illuminant or observer.
SpectraToColour lab_spectra_to_colour(const std::string& chart, const std::string& patch,
                                      const std::vector<std::string>& illuminants = {},
                                      const std::vector<std::string>& observers = {});

/// The CIE 1931 colour-matching functions as R, G, B sensitivities on 380-780 nm at 5 nm (the
/// built-in cameras' grid): a camera that meets the Luther condition.
SpectralData cmf_sensitivities();

// ---- Results as tables (CLI CSV, the page's table and its CSV download) -------------------------

/// An exercise's results table: the column names carry their units ("dE00 mean (CIEDE2000)",
/// "NRMSE X (fraction of the range)"); every cell is text (numbers by json::number_text, "" none).
struct LabTable {
  std::string name;                            ///< file-name stem ("lab-shen-L")
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  ///< one text per column
};
/// RFC 4180 CSV: the header, then one line per row; a cell with a comma, quote or newline is
/// quoted (quotes doubled). The CLI prints it, the page downloads it.
std::string lab_table_csv(const LabTable& table);
/// Rows of Vec3 as an N × 3 PatchMatrix (the virtual camera's and the reference's output).
PatchMatrix lab_patch_matrix(const std::vector<Vec3>& rows);
/// A table cell: 6 significant digits; "" for NaN or infinity.
std::string lab_number(double value);

// ---- Exercise 3: Shen, Xin, Yang & Lou 2008 — the OECF without grey samples -------------------
// The paper's simulation (eq 29): ρ = l·u^(1/γ) + n, γ = 1.8, l = 22, ρ clipped to [0, 255], the
// perfect diffuser's linear G response u = 80 (white near ρ = 251), Gaussian noise σ in ρ units,
// here through a chosen camera's sensitivities under D65 (the paper: a scanner). The OECF is
// recovered per channel (a) from the non-grey patches (Shen2008, eqs 6-22, J Munsell basis
// functions, L iterations) and (b) from the grey patches (grey-polynomial, K = 2, the paper's
// "gray-based"); then, on the non-grey patches, a 10-term colorimetric characterisation (eqs 23-25)
// scored by mean CIEDE2000, and the spectral characterisation (eqs 26-28) scored by CIEDE2000 under
// D65 and spectral RMS. Means over `seeds` noise realisations (seed, seed + 1, …).
//   Figs 2-3: J sweep at L = 1, per σ;  Tables I-II: L = 0..3 at J = 8 (and the grey-based row).
struct ShenRow {
  std::string method;     ///< "Shen2008" | "grey-based"
  int J = 0, L = 0;       ///< 0 for grey-based
  double sigma = 0;       ///< noise σ, ρ units (0..255)
  bool ok = false;
  std::string error_code;
  Vec3 r_squared = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  ///< Tables I-II R² per channel
  Summary colorimetric_dE00;  ///< means over seeds of the per-seed mean, std and max
  Summary spectral_dE00, spectral_rms;
};
struct ShenOptions {
  std::string chart = "cc24";                    ///< "cc24" (the MCC, greys D1-D6) | "sg140" (the CDC's role)
  std::vector<int> J{3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  std::vector<double> sigmas{0, 1, 2, 3};
  int J_table = 8;                               ///< Tables I-II
  double sigma_table = 1;                        ///< noise of Tables I-II's rows
  int seeds = 3;
  std::uint64_t seed = 1;
};
struct ShenExercise {
  std::string chart;
  int non_grey = 0;                 ///< patches the OECF and the characterisations are fitted on
  std::vector<ShenRow> j_sweep;     ///< Figs 2-3: per σ, the grey-based row then J ascending (L = 1)
  std::vector<ShenRow> l_table;     ///< Tables I-II: grey-based, then L = 0..3 (J = J_table)
};
/// Error(UnknownId) for a chart other than cc24/sg140; InvalidArgument for seeds outside 1..20,
/// a negative σ, J outside 1..20. A J the chart cannot carry (TOO_FEW_PATCHES) is a row with ok false.
ShenExercise lab_shen_exercise(const SpectralData& sensitivities, const ShenOptions& options = {});
/// Tables: "lab-shen-J" (Figs 2-3) and "lab-shen-L" (Tables I-II, the paper's MCC/CDC rows beside).
LabTable shen_j_table(const ShenExercise& e);
LabTable shen_l_table(const ShenExercise& e);

// ---- Exercise 4: Abed, Berns & Masaoka 2013 Table IV — training-chart independence ------------
// surface/geometry_table.hpp's simulated experiment (geometry_experiment_Abed2013: instrument
// 45°:0°, diffuse capture, Table III coefficients, test = a matte CC24 in the capture geometry)
// with every training row of the paper: Classic, SG, Custom All, Custom-Matte, Custom-Glossy,
// Total. No spectra of the paper's custom chart exist, so "Custom" is 50 Munsell chips (every 25th
// of the 1269, in order) rendered with the Table III Custom-Matte row and again with the
// Custom-Glossy row; Custom All = both (100 patches); Total = Classic + SG + Custom All.
struct Table4Row {
  std::string training, method;   ///< paper's row name; geometry_table_methods() id
  int patches = 0;
  bool ok = false;
  std::string error_code;
  double dE_xyz_mean = 0, dE_xyz_max = 0, dE00_mean = 0, dE00_max = 0;  ///< ours, on the test chart
  double mu = 0;                  ///< corrected-3x3: eq (12)
  /// The paper's Table IV cell (Phase III, ten ColorChecker DC patches).
  double paper_dE_xyz_mean = 0, paper_dE_xyz_max = 0, paper_dE00_mean = 0, paper_dE00_max = 0;
};
/// The exercise's default camera noise σ (fraction of the white's G; lab_option_table's table4.noise).
constexpr double kTable4Noise = 0.001;
/// Error(UnknownId) for an unknown camera or illuminant; InvalidArgument for a noise outside
/// table4.noise's bounds (lab_option_table).
std::vector<Table4Row> lab_table4_exercise(const std::string& camera = "Nikon_D850", const std::string& illuminant = "D50",
                                           double noise = kTable4Noise, std::uint64_t seed = 1);
LabTable table4_table(const std::vector<Table4Row>& rows);

// ---- Exercise 5: Guarnera, Bianco & Schettini 2018 — exposure invariance, HDR, Table 4 --------
// (a) Exposure: models fitted by least squares on a simulated CC24 (k = 1), then the camera RGB of
// the 1269 Munsell chips scaled by k (an exposure change) and compared with their XYZ scaled by k
// (CIELAB white scaled alike): a model whose terms all scale with k (3×3, root-polynomial T2R,
// eq 15) gives the same ΔE00 at every k; a polynomial (1, R², RG, … — eq 14's offset too) does not.
struct ExposureRow {
  std::string model;
  double k = 1;
  double dE00_mean = 0, dE00_max = 0;
};
/// `models` empty: Guarnera2018-T1, -To, -T2R and Cheung2004-10; `ks` empty: 1/8 … 8 in stops (the
/// page leaves both to the engine).
std::vector<ExposureRow> lab_exposure_exercise(const SpectralData& sensitivities, const SpectralData& illuminant,
                                               const std::vector<std::string>& models = {},
                                               const std::vector<double>& ks = {});
LabTable exposure_table(const std::vector<ExposureRow>& rows);

// (b) Table 4: the Absolute mode's virtual bracket (absolute/example.hpp) under each light, with
// each colour training (projector: the paper's; reflective: ColorChecker SG patches), fitted as a
// user would (n from the lens cap, S measured, f(r) from the flat, eq 8 across the bracket, M of
// the training's transform), applied to a single shot (the middle exposure) and to the whole
// bracket by the weighted fusion and by Algorithm 1 (recursive), evaluated as the Absolute mode
// does (evaluate_absolute_test on the example's test scene, its chromatic rows: the 24
// ColorChecker cells, central half of each): NRMSE per X, Y, Z, mean ΔE00 (white per eq 16) and the
// mean relative Y error (16-pixel cells: a quarter of the example's pixels, NRMSE within 0.0015).
// The paper's rows beside: D65; A ~ its ILS (incandescent), F2 ~ its CWF.
struct GuarneraRow {
  std::string light, training, transform, shots;  ///< shots: "single" | "weighted" | "recursive"
  Vec3 NRMSE = Vec3::Zero();
  double dE00_mean = 0, relative_Y_error = 0;
  Vec3 paper_NRMSE = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  ///< Table 4 (single / multiple shot)
};
std::vector<GuarneraRow> lab_guarnera_table4(const std::string& camera = "Canon_EOS_5D_Mark_II",
                                             const std::vector<std::string>& lights = {"D65", "A", "F2"},
                                             const std::vector<std::string>& trainings = {"projector", "reflective"});
LabTable guarnera_table(const std::vector<GuarneraRow>& rows);

}  // namespace tristim

// The field lists of the over-fitting row and of a results table (defined in exercises.cpp): the
// CLI's rows and tables (--json) and the wasm binding use them.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(OverfitRow);
TRISTIM_FIELDS_DECLARE(LabTable);
}  // namespace tristim::fields
