// The inverse OECF from non-grey samples with known reflectances: Shen, Xin, Yang & Lou (2008),
// "Estimation of Optoelectronic Conversion Functions of Imaging Devices Without Using Gray
// Samples", Color Res. Appl. 33(2) 135-141.
//
// Per channel, with ρ the stored value (here x = ρ / full scale, which only rescales c_k) and
// α the weights of a patch's reflectance on J basis functions:
//   u = F⁻¹(ρ) = Σ_{k=0..K} c_k ρ^k                                   eq (6)
//   r = Σ_{j=1..J} α_j b_j                                             eq (7)
//   Σ_k c_k ρ^k = Σ_j α_j (mᵀ b_j)                                     eq (8)
//   Σ_{k≥1} (c_k/c_0) ρ^k − Σ_j (mᵀb_j/c_0) α_j = −1                   eq (9)-(17)
//   c_d = −Λ_α⁺ 1  (Λ_α: Q × (K+J) rows [ρ..ρ^K, α_1..α_J])            eq (18)-(19)
//   û = αᵀ d  (an estimate of u / c_0)                                 eq (20)
//   ĉ = [ρ̃ᵀ]⁺ [û]  (ρ̃ = [1, ρ, .., ρ^K])                               eq (21)-(22)
//   L times: û ← [ρ̃ᵀ] ĉ;  d ← [αᵀ]⁺ û;  û ← [αᵀ] d;  ĉ ← [ρ̃ᵀ]⁺ û       (the paper's loop)
// The paper's loop writes "û ← [αᵀ]⁺ d" in its third line; eq (20), which the comment cites, is
// û = αᵀ d, and that is what is computed here.
//
// The scale c_0: eq (9) divides by c_0, so û is u / c_0 — of unknown scale and sign. As the
// paper says, the scale cancels when the linear response is normalised: the recovered curve is
// divided by its value at the brightest fitted patch of the channel (1 there). The division
// needs c_0 ≠ 0: a true inverse OECF through the origin (c_0 = 0 exactly) leaves eq (19) no
// solution of that form; the fit then reports a large residual (status in the message).
//
// The basis (eq 7) has no mean term, so it is the uncentred PCA of the reflectance set (the
// eigenvectors of R Rᵀ, largest first): a mean-centred basis would add a constant α_0 = 1
// column, collinear with c_0. Each b_j is scaled to unit norm with a positive sum.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "tristim/colorimetry/spectra.hpp"

namespace tristim {

/// J reflectance basis functions on a wavelength grid (eq 7).
struct ReflectanceBasis {
  std::vector<double> wavelengths;  ///< N, nm
  Eigen::MatrixXd functions;        ///< N × J, column j = b_{j+1}
  std::vector<double> explained;    ///< fraction of Σ‖r‖² captured by the first 1..J functions
  int samples = 0;                  ///< reflectances the PCA saw
  std::string source;               ///< "munsell1269", "patches" or "user"
};

/// The 1269 matte Munsell chips (University of Eastern Finland spectral database, via the
/// harbik/colorimetry crate; core/data/SOURCES.md), 380-780 nm at 5 nm, fractions. Parsed once.
const SpectralData& munsell_reflectances();

/// The grid the patches' reflectances and a basis set are compared on: the patches' own
/// wavelengths inside the set's range. Error(WavelengthMismatch) if that grid does not span
/// 400-700 nm or has fewer than 8 samples.
std::vector<double> working_grid(const std::vector<double>& patch_wavelengths, const std::vector<double>& set_wavelengths);

/// Uncentred PCA of `set` resampled on `wavelengths` (spectra.hpp rule). Errors:
/// TooFewPatches (fewer reflectances than J), InvalidArgument (J < 1 or J > number of
/// wavelengths), WavelengthMismatch (the grid leaves the set's range).
ReflectanceBasis reflectance_basis(const SpectralData& set, const std::vector<double>& wavelengths, int J,
                                   const std::string& source);

/// α (Q × J): least-squares weights of each named reflectance on the basis, α = B⁺ r.
/// Reflectances are resampled onto basis.wavelengths; Error(MissingColumn) for an absent id.
Eigen::MatrixXd basis_weights(const ReflectanceBasis& basis, const SpectralData& reflectances,
                              const std::vector<std::string>& ids);

/// One channel's solve with every intermediate.
struct ShenChannelFit {
  std::vector<double> c;            ///< eq (12): c_k / c_0, k = 1..K, from eq (19)
  std::vector<double> d;            ///< eq (14): mᵀb_j / c_0, j = 1..J, from eq (19)
  std::vector<double> c_hat;        ///< ĉ_0..ĉ_K after eq (22) and L iterations (û units)
  std::vector<std::vector<double>> history;  ///< ĉ after eq (22) (L = 0) and after each iteration
  std::vector<double> u_hat;        ///< final û per sample (eq 20, from the basis side)
  double residual_rms = 0;          ///< RMS of Λ_α c_d + 1 (eq 18), relative to 1
  double condition = 0;             ///< 2-norm condition of the column-equilibrated Λ_α
};

/// Eqs (18)-(22) and the L loop for one channel: x (Q stored values / full scale), alpha
/// (Q × J). Error(TooFewPatches) if Q < K + J; Error(IllConditioned) if Λ_α has rank < K + J.
ShenChannelFit oecf_Shen2008(const std::vector<double>& x, const Eigen::MatrixXd& alpha, int K, int L);

}  // namespace tristim
