// The metamerism explorer: metamer pairs searched in a reflectance set and metamers constructed
// with a metameric black (rules and references in tristim/lab/metamerism.hpp).
#include "tristim/lab/metamerism.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/lab/lab_options.hpp"
#include "tristim/lab/smi.hpp"
#include "tristim/linearisation/oecf_Shen2008.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

using Mat = Eigen::MatrixXd;

// A viewer as linear maps: tristimulus values (XYZ) of a reflectance r on the set's grid are
// T_k r under light k, CIELAB relative to white_k.
struct Viewer {
  std::string name;
  Mat T1, T2;
  Vec3 white1, white2;
  Vec3 XYZ(int light, const std::vector<double>& r) const {
    const Mat& T = light == 1 ? T1 : T2;
    return T * Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
  }
  Vec3 Lab(int light, const std::vector<double>& r) const { return XYZ_to_Lab(XYZ(light, r), light == 1 ? white1 : white2); }
};

// The n unit reflectances on `grid`: every viewer is linear in r, so its matrix is its response
// to these, computed by the same code that computes any reflectance's colour.
SpectralData unit_spectra(const std::vector<double>& grid) {
  SpectralData e;
  e.wavelengths = grid;
  for (size_t j = 0; j < grid.size(); ++j) {
    e.names.push_back(std::to_string(j));
    e.values.emplace_back(grid.size(), 0.0);
    e.values.back()[j] = 1.0;
  }
  return e;
}

Mat columns(const std::vector<Vec3>& v) {
  Mat m(3, static_cast<Eigen::Index>(v.size()));
  for (size_t j = 0; j < v.size(); ++j) m.col(static_cast<Eigen::Index>(j)) = v[j];
  return m;
}

Viewer observer_viewer(const std::vector<double>& grid, const SpectralData& L1, const SpectralData& L2, Observer obs) {
  const SpectralData e = unit_spectra(grid);
  Viewer v;
  v.name = std::string("observer ") + observer_name(obs);
  v.T1 = columns(reflectances_to_XYZ(e, L1, obs, &v.white1));  // CIE 15:2004 eq 7.1 per unit spectrum
  v.T2 = columns(reflectances_to_XYZ(e, L2, obs, &v.white2));
  return v;
}

Mat3 matrix_of(const std::array<double, 9>& m) {
  Mat3 M;
  M << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8];
  return M;
}

Viewer camera_viewer(const std::vector<double>& grid, const SpectralData& L1, const SpectralData& L2,
                     const SpectralData& ssf, const std::string& name) {
  const SpectralData e = unit_spectra(grid);
  Viewer v;
  v.name = name;
  const Mat C1 = columns(simulate_camera_RGB(ssf, e, L1)), C2 = columns(simulate_camera_RGB(ssf, e, L2));
  const Mat3 M1 = matrix_of(camera_quality(ssf, L1, name).matrix), M2 = matrix_of(camera_quality(ssf, L2, name).matrix);
  v.T1 = M1 * C1;
  v.T2 = M2 * C2;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(grid.size()));
  v.white1 = v.T1 * ones;  // = M1 · (white diffuser's RGB): the white the matrix keeps
  v.white2 = v.T2 * ones;
  return v;
}

struct Setup {
  MetamerResult result;
  std::vector<Viewer> viewers;  // observer first
  size_t matched = 0;           // index of the viewer the pair must match for
};

SpectralData light_of(const std::string& id, const SpectralData& given) { return given.values.empty() ? illuminant_spd(id) : given; }

Setup setup(const MetamerOptions& o, const SpectralData& set) {
  if (!has_id(metamer_match_table(), o.match))  // the viewers a pair can match for
    throw Error(ErrorCode::UnknownId, "match must be '" + ids_of(metamer_match_table(), "' or '") + "', got '" + o.match + "'");
  const bool has_camera = !o.camera.empty() || !o.sensitivities.values.empty();
  if (o.match == "camera" && !has_camera)
    throw Error(ErrorCode::InvalidArgument, "match 'camera' needs a camera (--camera or --sensitivities)");
  if (set.values.empty() || set.wavelengths.size() < 2) throw Error(ErrorCode::InvalidArgument, "reflectance set is empty");
  const SpectralData L1 = light_of(o.illuminant, o.illuminant_spd), L2 = light_of(o.second, o.second_spd);
  const Observer obs = parse_observer(o.observer);
  Setup s;
  s.result.wavelengths = set.wavelengths;
  s.result.illuminant = o.illuminant;
  s.result.second = o.second;
  s.result.observer = observer_name(obs);
  s.result.match = o.match;
  s.result.max_match = o.max_match;
  s.viewers.push_back(observer_viewer(set.wavelengths, L1, L2, obs));
  if (has_camera) {
    const SpectralData ssf = o.sensitivities.values.empty() ? camera_ssf(o.camera) : o.sensitivities;
    s.result.camera = o.camera.empty() ? "sensitivities" : o.camera;
    s.result.camera_matrix =
        "camera RGB -> XYZ by the ISO 17321-1 3x3 of each light (white-preserving, least mean dE*ab on "
        "ColorChecker 1-18, CIE 1931: tristim lab smi)";
    s.viewers.push_back(camera_viewer(set.wavelengths, L1, L2, ssf, s.result.camera));
    if (o.match == "camera") s.matched = 1;
  }
  return s;
}

MetamerPair make_pair(const std::vector<Viewer>& viewers, std::string a, std::string b, std::vector<double> ra,
                      std::vector<double> rb, double alpha) {
  MetamerPair p;
  p.a = std::move(a);
  p.b = std::move(b);
  p.reflectance_a = std::move(ra);
  p.reflectance_b = std::move(rb);
  p.alpha = alpha;
  for (const auto& v : viewers) {
    MetamerView w;
    w.viewer = v.name;
    w.XYZ_a1 = v.XYZ(1, p.reflectance_a);
    w.XYZ_b1 = v.XYZ(1, p.reflectance_b);
    w.XYZ_a2 = v.XYZ(2, p.reflectance_a);
    w.XYZ_b2 = v.XYZ(2, p.reflectance_b);
    w.Lab_a1 = XYZ_to_Lab(w.XYZ_a1, v.white1);
    w.Lab_b1 = XYZ_to_Lab(w.XYZ_b1, v.white1);
    w.Lab_a2 = XYZ_to_Lab(w.XYZ_a2, v.white2);
    w.Lab_b2 = XYZ_to_Lab(w.XYZ_b2, v.white2);
    w.dE00_1 = delta_E_CIE2000(w.Lab_a1, w.Lab_b1);
    w.dE00_2 = delta_E_CIE2000(w.Lab_a2, w.Lab_b2);
    p.views.push_back(w);
  }
  return p;
}

// The largest S_L of CIEDE2000 (Sharma et al. 2005 eq 18), at L̄' = 0 or 100.
const double kMaxSL = 1 + 0.015 * 2500 / std::sqrt(20.0 + 2500);

}  // namespace

std::vector<std::string> munsell_ids() { return munsell_reflectances().names; }

MetamerResult metamer_pairs(const MetamerOptions& o) { return metamer_pairs_in(o, munsell_reflectances()); }

MetamerResult metamer_pairs_in(const MetamerOptions& o, const SpectralData& set) {
  lab_option("metamers.max_match", o.max_match);
  lab_option("metamers.top", o.top);
  if (set.size() < 2) throw Error(ErrorCode::InvalidArgument, "metamer search needs at least 2 reflectances");
  Setup s = setup(o, set);
  const Viewer& v = s.viewers[s.matched];
  const size_t n = set.size();
  std::vector<Vec3> lab1(n);
  for (size_t i = 0; i < n; ++i) lab1[i] = v.Lab(1, set.values[i]);
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return lab1[a][0] < lab1[b][0]; });
  // ΔE00 ≥ |ΔL*| / S_L ≥ |ΔL*| / kMaxSL: only pairs within that L* window can match (header).
  const double window = kMaxSL * o.max_match;
  struct Found {
    size_t i, j;
    double dE2;
  };
  std::vector<Found> found;
  MetamerResult& r = s.result;
  r.all_pairs = static_cast<int>(n * (n - 1) / 2);
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n && lab1[order[b]][0] - lab1[order[a]][0] < window; ++b) {
      const size_t i = std::min(order[a], order[b]), j = std::max(order[a], order[b]);
      ++r.compared;
      if (delta_E_CIE2000(lab1[i], lab1[j]) < o.max_match)
        found.push_back({i, j, delta_E_CIE2000(v.Lab(2, set.values[i]), v.Lab(2, set.values[j]))});
    }
  r.matching = static_cast<int>(found.size());
  std::sort(found.begin(), found.end(), [](const Found& x, const Found& y) {
    return x.dE2 != y.dE2 ? x.dE2 > y.dE2 : (x.i != y.i ? x.i < y.i : x.j < y.j);
  });
  if (found.size() > static_cast<size_t>(o.top)) found.resize(static_cast<size_t>(o.top));
  for (const auto& f : found)
    r.pairs.push_back(make_pair(s.viewers, set.names[f.i], set.names[f.j], set.values[f.i], set.values[f.j], 0));
  return r;
}

MetamerResult construct_metamer(const MetamerOptions& o, const std::string& id) {
  return construct_metamer_in(o, munsell_reflectances(), id);
}

MetamerResult construct_metamer_in(const MetamerOptions& o, const SpectralData& set, const std::string& id) {
  const auto it = std::find(set.names.begin(), set.names.end(), id);
  if (it == set.names.end()) throw Error(ErrorCode::UnknownId, "no reflectance '" + id + "' in the set (e.g. a Munsell id such as 5R5/6)");
  Setup s = setup(o, set);
  const Viewer& v = s.viewers[s.matched];
  const std::vector<double>& r = set.values[static_cast<size_t>(it - set.names.begin())];
  const Eigen::Index n = static_cast<Eigen::Index>(r.size());
  // Orthonormal basis Q of span(T1ᵀ): R = Q Qᵀ is Cohen & Kappauf's projector Aᵀ(AAᵀ)⁻¹A.
  const Mat Q = v.T1.transpose().householderQr().householderQ() * Mat::Identity(n, 3);
  const Eigen::Map<const Eigen::VectorXd> r0(r.data(), n);
  double best_dE = -1, best_alpha = 0;
  std::vector<double> best = r;
  for (int k = 0; k < 3; ++k)
    for (double sign : {1.0, -1.0}) {
      const Eigen::VectorXd u = sign * v.T2.row(k).transpose();
      const Eigen::VectorXd b = u - Q * (Q.transpose() * u);  // metameric black: T1 b = 0
      // The largest α with 0 ≤ r + α b ≤ 1.
      double alpha = std::numeric_limits<double>::infinity();
      for (Eigen::Index i = 0; i < n; ++i) {
        if (b[i] > 0) alpha = std::min(alpha, (1 - r0[i]) / b[i]);
        if (b[i] < 0) alpha = std::min(alpha, -r0[i] / b[i]);
      }
      if (!std::isfinite(alpha) || alpha <= 0) continue;
      std::vector<double> m(r.size());
      for (Eigen::Index i = 0; i < n; ++i) m[static_cast<size_t>(i)] = std::clamp(r0[i] + alpha * b[i], 0.0, 1.0);
      const double dE = delta_E_CIE2000(v.Lab(2, r), v.Lab(2, m));
      if (dE > best_dE) {
        best_dE = dE;
        best_alpha = alpha;
        best = m;
      }
    }
  s.result.pairs.push_back(make_pair(s.viewers, id, id + " + black", r, best, best_alpha));
  return s.result;
}

namespace fields {
using V = MetamerView;
TRISTIM_FIELDS_DEFINE(V, member<&V::viewer>("viewer"), member<&V::XYZ_a1>("XYZ_a1"), member<&V::XYZ_b1>("XYZ_b1"),
                      member<&V::XYZ_a2>("XYZ_a2"), member<&V::XYZ_b2>("XYZ_b2"), member<&V::Lab_a1>("Lab_a1"),
                      member<&V::Lab_b1>("Lab_b1"), member<&V::Lab_a2>("Lab_a2"), member<&V::Lab_b2>("Lab_b2"),
                      member<&V::dE00_1>("dE00_1"), member<&V::dE00_2>("dE00_2"));
using P = MetamerPair;
TRISTIM_FIELDS_DEFINE(P, member<&P::a>("a"), member<&P::b>("b"), member<&P::alpha>("alpha"),
                      member<&P::reflectance_a>("reflectance_a"), member<&P::reflectance_b>("reflectance_b"),
                      member<&P::views>("views"));
using R = MetamerResult;
TRISTIM_FIELDS_DEFINE(R, member<&R::illuminant>("illuminant"), member<&R::second>("second"), member<&R::observer>("observer"),
                      member<&R::camera>("camera"), member<&R::match>("match"), member<&R::camera_matrix>("camera_matrix"),
                      member<&R::max_match>("max_match"), member<&R::compared>("compared"), member<&R::all_pairs>("all_pairs"),
                      member<&R::matching>("matching"), member<&R::wavelengths>("wavelengths"), member<&R::pairs>("pairs"));
}  // namespace fields

json::Value metamer_result_json(const MetamerResult& result) { return fields::write(result); }

}  // namespace tristim
