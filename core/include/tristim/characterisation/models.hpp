// Characterisation models: camera RGB -> CIE XYZ, fitted from patch pairs.
//
// Every model here is linear in its coefficients: XYZ = M · φ(RGB), with φ a fixed term
// expansion of P terms and M a 3 × P matrix. The models differ only in φ; the objectives
// (least squares, Guarnera's pattern search, mean CIEDE2000) differ only in how M is chosen
// (fit.hpp, which fits a model of this table).
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
#include "tristim/io/fields.hpp"

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
  std::string family;      ///< the id of its row in model_families() (pickers group by it)
};

/// A group of models the pickers show together (the page's model checklist, `tristim models`).
struct ModelFamily {
  std::string id;     ///< e.g. "root-polynomial"; ModelInfo::family names it
  std::string label;  ///< e.g. "Root-polynomials"
  std::string about;  ///< one sentence of advice on choosing among them (citations stay on the models)
};

/// The id of Abed 2013's corrected 3×3 (fit.hpp, fit_corrected_3x3): the span of matrix-3x3, fitted in
/// closed form from the 3×4 and a white reference, not by an objective.
constexpr const char* kCorrected3x3 = "corrected-3x3";
/// Every model, in a stable order.
const std::vector<ModelInfo>& model_table();
/// Every family, in the order its first model appears in model_table().
const std::vector<ModelFamily>& model_families();
/// Looks a model up by id; Error(UnknownId) naming the id otherwise.
const ModelInfo& model_info(const std::string& id);
/// A fitted model: enough to predict.
struct Model {
  std::string id;                ///< model_table() id
  Eigen::MatrixXd coefficients;  ///< 3 × P
};

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

// Field lists (io/fields.hpp), defined in methods.cpp with the other catalog rows': a model row,
// its terms ({r, g, b} exponents) and a family are the objects their JSON is (`tristim models
// --json`, the page's listModels / listModelFamilies).
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(Monomial);
TRISTIM_FIELDS_DECLARE(ModelInfo);
TRISTIM_FIELDS_DECLARE(ModelFamily);
}  // namespace tristim::fields
