// Characterisation models: camera RGB -> CIE XYZ, fitted from patch pairs.
//
// Every model here is linear in its coefficients: XYZ = M · φ(RGB), with φ a fixed term
// expansion of P terms and M a 3 × P matrix. The models differ only in φ; the objectives
// (least squares, Guarnera's pattern search, mean CIEDE2000) differ only in how M is chosen.
//
// Scale: no hidden normalisation. M maps the caller's RGB units to the caller's XYZ units
// (Guarnera 2018 works in cd/m²; reflective data usually have Y = 100 for the perfect
// diffuser). Internally the least-squares design matrix is column-equilibrated for numerical
// stability only; the coefficients returned are in absolute units.
//
// Shapes: PatchMatrix is N × 3, one row per patch, columns R,G,B or X,Y,Z.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"

namespace tristim {

/// N × 3, one row per patch (R, G, B) or (X, Y, Z).
using PatchMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3>;

/// Most terms any model here has (Cheung 2004, 35 terms).
constexpr int kMaxModelTerms = 35;

/// One term R^r·G^g·B^b (or its (r+g+b)-th root for root-polynomials); {0,0,0} is the offset 1.
struct Monomial {
  int r, g, b;
};

/// One row of the method table (colour-science's MATRIX_COLOUR_CORRECTION_METHODS idea).
struct ModelInfo {
  std::string id;          ///< e.g. "Finlayson2015-2"; the same string in C++, JS, files, UI
  std::string label;       ///< human-readable, e.g. "Root-polynomial, degree 2 (6 terms)"
  std::string reference;   ///< the paper and equation (core/src/citations.hpp), never empty
  int n_terms;             ///< P
  std::vector<std::string> term_names;  ///< e.g. {"R","G","B","(RG)^1/2",...}
  std::vector<Monomial> terms;          ///< the expansion φ, in order
  bool root;               ///< each term is the (degree)-th signed root of its monomial
  bool linear;             ///< a plain 3×3 matrix (ICC matrix/shaper export possible)
  bool exposure_invariant; ///< φ(kρ) = kφ(ρ) for k > 0 (no offset, no powers ≠ 1)
  std::string duplicate_of;  ///< same span as another id (compare lists only the original)
};

/// Every model, in a stable order.
const std::vector<ModelInfo>& model_table();
/// Looks a model up by id; Error(UnknownId) naming the id otherwise.
const ModelInfo& model_info(const std::string& id);
struct Model;
/// Error(ProfileInvalid) unless model.coefficients is 3 × info.n_terms.
void check_coefficient_shape(const Model& model, const ModelInfo& info);

// --- term expansions (exposed for tests and fast paths) --------------------------------------

/// Cheung et al. (2004) polynomial terms as colour-science's matrix_augmented_Cheung2004
/// defines them; `terms` ∈ {3,4,5,7,8,10,11,14,16,17,19,20,22,35}. Error(InvalidArgument)
/// for another count.
std::vector<double> expansion_Cheung2004(const Vec3& RGB, int terms);
/// Finlayson, Mackiewicz & Hurlbert (2015) polynomial (root = false) or root-polynomial
/// (root = true) expansion of `degree` 1..4, colour-science's term order. The k-th root of a
/// product of degree k keeps the sign of the product (sign(p)·|p|^(1/k)), so negative
/// black-subtracted values do not produce NaN; for non-negative inputs this is colour's
/// expansion exactly.
std::vector<double> expansion_Finlayson2015(const Vec3& RGB, int degree, bool root = true);
/// Shen et al. (2008) eq (23): [u1, u2, u3, u1², u2², u3², u1u2, u1u3, u2u3, 1].
std::vector<double> expansion_Shen2008(const Vec3& RGB);
/// Any model's expansion by id.
std::vector<double> expansion(const std::string& model_id, const Vec3& RGB);
/// The expansion of a table row into out[0..n_terms) (no allocation).
void expand(const ModelInfo& info, double r, double g, double b, double* out);

// --- fitting ------------------------------------------------------------------------------

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

/// A fitted model: enough to predict.
struct Model {
  std::string id;                ///< model_table() id
  Eigen::MatrixXd coefficients;  ///< 3 × P
};

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

// --- prediction ---------------------------------------------------------------------------

/// XYZ = M·φ(RGB) for each row. Error(ProfileInvalid) if M's shape does not fit the model.
PatchMatrix predict(const Model& model, const PatchMatrix& camera_RGB);
Vec3 predict(const Model& model, const Vec3& camera_RGB);

/// Applies a model to an interleaved linear float RGB image (n_pixels × 3) -> interleaved XYZ
/// (n_pixels × 3). xyz may be rgb itself (in place: one image buffer instead of two, the same
/// floats); any other overlap is Error(InvalidArgument). Tight loops, no per-pixel allocation;
/// the 3×3, affine and degree-2 root-polynomial models have dedicated paths.
void apply_to_image(const Model& model, const float* rgb, size_t n_pixels, float* xyz);

/// Caps the x86 vector kernels apply_to_image may choose at run time, for tests and benchmarks
/// that compare them: 0 = 4-lane SSE2 (the wasm SIMD128 kernels' arithmetic), 1 = AVX2+FMA,
/// 2 = AVX-512 (the default: the widest the CPU has). Returns the previous cap; no effect
/// (returns 0) where there are no such kernels (wasm, other CPUs).
int set_image_kernel_limit(int level);

}  // namespace tristim
