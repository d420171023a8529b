// tristim — the metamerism explorer: pairs of reflectances that match under one illuminant and
// not under another, for a CIE observer and for a camera.
//
// Viewers. The observer: CIE XYZ (CIE 15 integration, spectra.hpp; Y_white = 100) and CIELAB
// relative to each light's own white. A camera: its RGB by the virtual camera (white diffuser's
// G = 1, simulate/virtual_camera.hpp), mapped to XYZ by its ISO 17321-1 matrix fitted under
// *that* light (lab/smi.hpp: the white-preserving 3×3 minimising the mean ΔE*ab of ColorChecker
// patches 1–18, CIE 1931) — the camera as a colorimeter characterised for each light — then
// CIELAB relative to the light's white. Differences: CIEDE2000 (Sharma, Wu & Dalal 2005).
//
// Search (metamer_pairs): every pair of a reflectance set (by default the 1269 Munsell matte
// chips) whose ΔE00 under the first illuminant is below `max_match` for the matching viewer,
// ranked by the largest ΔE00 under the second. Not all N(N−1)/2 pairs are compared: with
// ΔE00² = ΔL² + ΔC² + ΔH² + R_T·ΔC·ΔH and |R_T| ≤ 2, ΔE00 ≥ |ΔL'|/S_L, and S_L ≤ 1 + 0.015·50²/√(20 + 50²)
// (Sharma eq 18 at L̄ = 0 or 100), so after sorting by L* only pairs with
// |ΔL*| < S_L,max · max_match can match: a sweep over a window of the sorted list.
//
// Construction (construct_metamer): the metameric black of Wyszecki (1958, "Evaluation of
// metameric colors", J. Opt. Soc. Am. 48(7)), in Cohen & Kappauf's (1982, "Metameric color
// stimuli, fundamental metamers, and Wyszecki's metameric blacks", Am. J. Psychol. 95(4))
// form: with A the 3×n matrix taking a reflectance on its grid to the viewer's tristimulus values
// under the first illuminant (built column by column from the same integration, so A r is exactly
// what the viewer computes), R = Aᵀ(AAᵀ)⁻¹A the projector onto the fundamental metamers and
// b = (I − R) v a metameric black (A b = 0), the metamer is r' = r + α b: the same tristimulus
// values under the first illuminant for any α. v is chosen among ± the rows of the second
// illuminant's matrix (the directions that change the colour most under the second light), and α
// is the largest with r' in [0, 1]; the candidate giving the largest ΔE00 under the second light
// wins.
#pragma once
#include <string>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/json.hpp"

namespace tristim {

struct MetamerOptions {
  std::string illuminant = "D65";   ///< first light: the pair matches under it
  SpectralData illuminant_spd;      ///< empty: illuminant_spd(illuminant)
  std::string second = "A";         ///< second light
  SpectralData second_spd;          ///< empty: illuminant_spd(second)
  std::string observer = "1931";    ///< "1931" or "1964"
  std::string camera;               ///< one of the 52, or a label for `sensitivities`; empty: no camera
  SpectralData sensitivities;       ///< R, G, B curves instead of the built-in camera
  std::string match = "observer";   ///< the viewer the pair must match for: "observer" or "camera"
  double max_match = 0.5;           ///< search: ΔE00 under the first light below this
  int top = 10;                     ///< search: at most this many pairs
};

/// One viewer's view of a pair (a, b) under the first (1) and second (2) light.
struct MetamerView {
  std::string viewer;               ///< "observer 1931" / "observer 1964", or the camera's name
  Vec3 XYZ_a1 = Vec3::Zero(), XYZ_b1 = Vec3::Zero(), XYZ_a2 = Vec3::Zero(), XYZ_b2 = Vec3::Zero();
  Vec3 Lab_a1 = Vec3::Zero(), Lab_b1 = Vec3::Zero(), Lab_a2 = Vec3::Zero(), Lab_b2 = Vec3::Zero();
  double dE00_1 = 0, dE00_2 = 0;
};

struct MetamerPair {
  std::string a, b;                 ///< ids (a constructed metamer: "<id> + black")
  std::vector<double> reflectance_a, reflectance_b;  ///< on MetamerResult::wavelengths
  double alpha = 0;                 ///< construction: the black's scale (0 for a searched pair)
  std::vector<MetamerView> views;   ///< the observer, then the camera if one was chosen
};

struct MetamerResult {
  std::vector<double> wavelengths;
  std::string illuminant, second, observer, camera, match;
  std::string camera_matrix;        ///< how camera RGB becomes XYZ (empty without a camera)
  double max_match = 0;
  int compared = 0;                 ///< search: pairs whose ΔE00 was computed
  int all_pairs = 0;                ///< search: N(N−1)/2
  int matching = 0;                 ///< search: pairs below max_match (before `top`)
  std::vector<MetamerPair> pairs;   ///< search: by ΔE00 under the second light, largest first
};

/// The search over `set` (reflectances, fractions, one column per sample; default: the Munsell
/// matte set). Errors: UnknownId (illuminant, observer, camera, match), InvalidArgument (max_match
/// not > 0, top < 1, match "camera" without a camera, a set of fewer than 2 samples).
MetamerResult metamer_pairs(const MetamerOptions& options);
MetamerResult metamer_pairs_in(const MetamerOptions& options, const SpectralData& set);

/// A metamer of the Munsell chip `id` (e.g. "5R5/6"), or of column `id` of `set`. Errors as above,
/// UnknownId for an id not in the set.
MetamerResult construct_metamer(const MetamerOptions& options, const std::string& id);
MetamerResult construct_metamer_in(const MetamerOptions& options, const SpectralData& set, const std::string& id);

/// The Munsell matte chip ids (the search's default set, the construction's choices).
std::vector<std::string> munsell_ids();

/// {"illuminant","second","observer","camera","match","camera_matrix","max_match","compared",
///  "all_pairs","matching","wavelengths","pairs":[{"a","b","alpha","reflectance_a","reflectance_b",
///  "views":[{"viewer","XYZ_a1",…,"Lab_b2","dE00_1","dE00_2"}]}]}.
json::Value metamer_result_json(const MetamerResult& result);

}  // namespace tristim

// The field lists of the explorer's result (defined in metamerism.cpp): the CLI's JSON and the
// wasm binding use them.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(MetamerView);
TRISTIM_FIELDS_DECLARE(MetamerPair);
TRISTIM_FIELDS_DECLARE(MetamerResult);
}  // namespace tristim::fields
