// Fitting a model of the table (models.hpp) to patch pairs: the objectives (least squares,
// Guarnera's pattern search, mean or RMS CIEDE2000), white-point preservation, the fit's summary
// and the closed-form leave-one-out of least squares. Scale: no hidden normalisation (models.hpp);
// the least-squares design matrix is column-equilibrated for numerical stability only.
#pragma once
#include <string>
#include <vector>

#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/colorimetry.hpp"

namespace tristim {

enum class Objective {
  LeastSquares,   ///< "ls": min Σ‖XYZ − Mφ‖², QR of the (equilibrated) design matrix
  PatternSearch,  ///< "psm": Guarnera 2018 eq (11)-(12), Algorithm 2, started from "ls"
  DeltaE2000,     ///< "de2000": min mean (or RMS) weighted CIEDE2000 under a stated white
};
const char* objective_id(Objective objective);
/// "ls" | "psm" | "de2000" (also accepts "least-squares", "pattern-search", "ciede2000").
Objective objective_from_id(const std::string& id);
/// {"ls", "psm", "de2000"}.
std::vector<std::string> objective_ids();

/// Guarnera et al. (2018) Algorithm 2 (a generalised pattern search on the coordinate
/// directions ±e_i, opportunistic poll). The paper states only α > 1 and β < 1; the defaults
/// below are those of MATLAB's patternsearch (the [LT00] GPS 2N method the paper cites):
/// expansion 2, contraction 0.5, mesh tolerance 1e-6, at most 100 × (number of variables)
/// iterations. Steps are relative: a step Δ on coefficient (i, j) changes output channel i by
/// Δ·‖XYZ_i‖ (the design column is equilibrated), so the defaults hold for any absolute scale.
struct PatternSearchOptions {
  double initial_step = 1.0;     ///< Δ_0
  double expansion = 2.0;        ///< α_k
  double contraction = 0.5;      ///< β_k
  double step_threshold = 1e-6;  ///< thresh
  int max_iterations = 0;        ///< 0: 100 × number of variables
};

/// The perceptual objective: mean_i w_i·ΔE00_i / Σw_i with Lab relative to `white`
/// (with `rms`: sqrt(Σ w_i·ΔE00_i² / Σw_i), the loss OpenCV's ccm minimises).
/// Started from the least-squares solution. By default the mean (a sum of Euclidean norms) is
/// minimised by an unbounded, iteratively reweighted Levenberg–Marquardt ("irls"), the RMS (a
/// sum of squares) by an unbounded Levenberg–Marquardt on the per-patch ΔE00 ("lm"). NLopt's
/// derivative-free optimisers ("bobyqa", "sbplx", …) remain selectable, each coefficient bounded
/// to LS ± (|LS| + ‖XYZ_i‖) in the equilibrated coordinates. (Until issue 13, "auto" meant BOBYQA
/// for the mean; BOBYQA stops at its default tolerances 0.005–0.7 ΔE00 above the mean irls reaches
/// on the Passport patches, and is 5–50× slower.)
struct DeltaE2000Options {
  /// "auto" (lm for the RMS loss, irls for the mean), "lm" (RMS only), "irls" (mean only),
  /// "bobyqa" (NLOPT_LN_BOBYQA), "sbplx" (NLOPT_LN_SBPLX), "newuoa", "praxis", "cobyla", "neldermead".
  std::string algorithm = "auto";
  double xtol_rel = 1e-5;
  double ftol_rel = 1e-7;
  int max_evaluations = 0;           ///< 0: 200 × number of variables
  bool rms = false;                  ///< minimise the (weighted) RMS instead of the mean
  double initial_step = 0.01;        ///< first step, relative to ‖XYZ_i‖ (equilibrated coordinates)
};

struct FitOptions {
  Objective objective = Objective::LeastSquares;
  /// White of the CIELAB conversions (ΔE00 objective); same scale as the XYZ data.
  Vec3 white = whites::D50();
  /// Per-patch weights for the ΔE00 objective (empty: all 1).
  std::vector<double> weights;
  /// White-point preservation: when true the fit maps white_RGB to white_XYZ exactly
  /// (an equality-constrained fit; every objective optimises in the constraint's null space).
  bool preserve_white = false;
  Vec3 white_RGB = Vec3::Zero();
  Vec3 white_XYZ = Vec3::Zero();
  PatternSearchOptions psm;
  DeltaE2000Options de2000;
  /// Condition number (of the equilibrated design matrix) above which the fit is flagged
  /// ill-conditioned (status), and above which it is refused (Error IllConditioned).
  double warn_condition = 1e6;
  double max_condition = 1e12;
};

enum class FitStatus {
  Ok,
  IllConditioned,     ///< finished, but cond > warn_condition: coefficients are shaky
  ExactlyDetermined,  ///< as many patches as free coefficients: zero training error is no merit
  IterationLimit,     ///< the optimiser stopped at its iteration/evaluation limit
};
/// "ok" | "ill_conditioned" | "exactly_determined" | "iteration_limit".
const char* fit_status_name(FitStatus status);

/// The outcome of a fit (a summary, like Ceres's Solver::Summary).
struct FitResult {
  Model model;
  Objective objective = Objective::LeastSquares;
  FitStatus status = FitStatus::Ok;
  std::string message;            ///< empty when ok; otherwise what to worry about
  int iterations = 0;             ///< PSM iterations / NLopt evaluations; 0 for ls
  int evaluations = 0;            ///< objective evaluations
  double condition_number = 0;    ///< 2-norm condition of the equilibrated design matrix
  double objective_value = 0;     ///< final objective (ls: RMS residual over all channels)
  double start_objective_value = 0;  ///< the objective at the ls start (psm, de2000)
  bool white_preserved = false;
  PatchMatrix fitted;             ///< N × 3 predictions on the training patches
  PatchMatrix residuals;          ///< fitted − reference
  /// "corrected-3x3" only (fit_corrected_3x3): the white scaling μ of Abed 2013 eq (27); 0 otherwise.
  double mu = 0;
};

/// Checks a training pair: same N (PatchMismatch), finite (NonFinite), XYZ ≥ 0
/// (NegativeValue), at least one patch (TooFewPatches).
void validate_patches(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ);

/// Generic fit of a model from the table by id (the dispatcher).
/// Errors: UnknownId, PatchMismatch, NonFinite, NegativeValue, TooFewPatches (fewer patches
/// than free coefficients), IllConditioned (a constant channel, a term that is zero on every
/// patch, or cond > max_condition), FitFailed (the optimiser failed).
FitResult fit(const std::string& model_id, const PatchMatrix& camera_RGB,
              const PatchMatrix& reference_XYZ, const FitOptions& options = {});

/// Leave-one-out predictions of the least-squares fit in closed form: row k is what the fit
/// without patch k predicts for patch k, y_k − e_k/(1 − h_kk) (the PRESS residual, h the hat
/// matrix of the equilibrated design; with white preservation, of the null-space design), except
/// the white patch's own fold (white_patch_index), which is refitted without the constraint.
/// Equal to N refits up to rounding (the refits re-equilibrate each fold's columns).
/// Errors as a refit's: TooFewPatches, IllConditioned (a fold with a constant channel or
/// leverage 1).
PatchMatrix leave_one_out_least_squares(const std::string& model_id, const PatchMatrix& camera_RGB,
                                        const PatchMatrix& reference_XYZ, const FitOptions& options = {},
                                        int white_patch_index = -1);

/// Linear 3×3 matrix, XYZ = M·RGB (Abed 2013 eq 7 without offsets; Guarnera 2018 T1 eq 13).
FitResult fit_matrix_3x3(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                         const FitOptions& options = {});
/// Affine 3×4 matrix, XYZ = M·[R,G,B,1] (Abed 2013 eq 6, pseudo-inverse eq 26; Guarnera To eq 14).
FitResult fit_matrix_3x4(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                         const FitOptions& options = {});
/// Abed, Berns & Masaoka 2013 "corrected 3×3" (eqs 6-13; Appendix C steps 4-7, eqs 26-28) as the
/// model "corrected-3x3": the least-squares 3×4 of eq (26), its offset column dropped (M'), scaled by
/// μ = (M'·RGB_w)⁺·XYZ_w (eq 27) so that the white reference maps to its XYZ in the least-squares
/// sense; XYZ = μ·M'·RGB (eq 28). The white reference is options.white_RGB / white_XYZ (the PTFE of
/// the paper, or the chart's white patch with its reference XYZ); it sets μ and is not preserved
/// exactly (preserve_white is not needed and not honoured). Closed form: objective ls only.
/// Errors: InvalidArgument (another objective, no white reference), the 3×4's (TooFewPatches
/// below 4 patches, IllConditioned), IllPosed (M'·RGB_w = 0).
FitResult fit_corrected_3x3(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                            const FitOptions& options);
/// Shen et al. 2008 10-term second-order polynomial, eqs (23)-(25).
FitResult fit_Shen2008(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                       const FitOptions& options = {});
/// Cheung et al. 2004 polynomial of `terms` terms (colour-science's expansion).
FitResult fit_Cheung2004(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ, int terms,
                         const FitOptions& options = {});
/// Finlayson, Mackiewicz & Hurlbert 2015 root-polynomial of `degree` 1..4 (IEEE Trans. Image Process. 24(5)).
FitResult fit_Finlayson2015(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                            int degree, const FitOptions& options = {});
/// Guarnera et al. 2018 transforms: "T1" (eq 13), "To" (eq 14), "T2R" (eq 15, term order of
/// the paper). The paper fits them with the pattern search: pass Objective::PatternSearch.
FitResult fit_Guarnera2018(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                           const std::string& transform, const FitOptions& options = {});

}  // namespace tristim
