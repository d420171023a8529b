// Model table, term expansions and prediction (whole images: image_kernels.cpp).
#include "tristim/characterisation/models.hpp"

#include <cmath>
#include <Eigen/Core>
#include <algorithm>

#include "../detmath.hpp"
#include "../citations.hpp"
#include "../table_lookup.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

using Terms = std::vector<Monomial>;

// Cheung 2004 term lists exactly as colour-science's matrix_augmented_Cheung2004 orders them
// (checked against colour_test_correction_expected.json).
const Terms kR_G_B = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const Monomial kOne = {0, 0, 0};
const Terms kCross2 = {{1, 1, 0}, {1, 0, 1}, {0, 1, 1}};    // RG RB GB
const Terms kSquares = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}};   // R² G² B²
const Monomial kRGB = {1, 1, 1};
const Terms kCubes = {{3, 0, 0}, {0, 3, 0}, {0, 0, 3}};
const Terms kCheung16Mid = {{2, 1, 0}, {0, 2, 1}, {1, 0, 2}};  // R²G G²B B²R
const Terms kCheung19Mid = {{2, 0, 1}, {1, 2, 0}, {0, 1, 2}};  // R²B G²R B²G

Terms cat(std::initializer_list<Terms> parts) {
  Terms out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

Terms cheung_terms(int n) {
  switch (n) {
    case 3: return kR_G_B;
    case 4: return cat({kR_G_B, {kOne}});
    case 5: return cat({kR_G_B, {kRGB}, {kOne}});
    case 7: return cat({kR_G_B, kCross2, {kOne}});
    case 8: return cat({kR_G_B, kCross2, {kRGB}, {kOne}});
    case 10: return cat({kR_G_B, kCross2, kSquares, {kOne}});
    case 11: return cat({kR_G_B, kCross2, kSquares, {kRGB}, {kOne}});
    case 14: return cat({kR_G_B, kCross2, kSquares, {kRGB}, kCubes, {kOne}});
    case 16: return cat({kR_G_B, kCross2, kSquares, {kRGB}, kCheung16Mid, kCubes});
    case 17: return cat({kR_G_B, kCross2, kSquares, {kRGB}, kCheung16Mid, kCubes, {kOne}});
    case 19: return cat({kR_G_B, kCross2, kSquares, {kRGB}, kCheung16Mid, kCheung19Mid, kCubes});
    case 20:
      return cat({kR_G_B, kCross2, kSquares, {kRGB}, kCheung16Mid, kCheung19Mid, kCubes, {kOne}});
    case 22:
      return cat({kR_G_B, kCross2, kSquares, {kRGB}, kCheung16Mid, kCheung19Mid, kCubes,
                  {{2, 1, 1}, {1, 2, 1}, {1, 1, 2}}});
    case 35:
      return cat({kR_G_B, kCross2, kSquares, {kRGB}, kCheung16Mid, kCheung19Mid, kCubes,
                  {{3, 1, 0}, {3, 0, 1}, {1, 3, 0}, {0, 3, 1}, {1, 0, 3}, {0, 1, 3}},
                  {{2, 1, 1}, {1, 2, 1}, {1, 1, 2}},
                  {{2, 2, 0}, {2, 0, 2}, {0, 2, 2}},
                  {{4, 0, 0}, {0, 4, 0}, {0, 0, 4}},
                  {kOne}});
    default:
      throw Error(ErrorCode::InvalidArgument,
                  "Cheung 2004 expansion: " + std::to_string(n) +
                      " terms is not one of 3,4,5,7,8,10,11,14,16,17,19,20,22,35");
  }
}

// R, G, B and the terms of each degree from 2 up to `degree` (1..4), in that order; `what` names
// the expansion in the error.
Terms terms_up_to(int degree, const Terms& d2, const Terms& d3, const Terms& d4, const std::string& what) {
  if (degree < 1 || degree > 4)
    throw Error(ErrorCode::InvalidArgument, what + ": degree " + std::to_string(degree) + " is not 1..4");
  const Terms* higher[] = {&d2, &d3, &d4};
  Terms out = kR_G_B;
  for (int d = 2; d <= degree; ++d) out.insert(out.end(), higher[d - 2]->begin(), higher[d - 2]->end());
  return out;
}

// Finlayson 2015 (colour-science's polynomial_expansion_Finlayson2015 order), per degree.
Terms finlayson_terms(int degree) {
  const Terms d2 = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  const Terms d3 = {{3, 0, 0}, {0, 3, 0}, {0, 0, 3}, {1, 2, 0}, {0, 1, 2}, {1, 0, 2},
                    {2, 1, 0}, {0, 2, 1}, {2, 0, 1}, {1, 1, 1}};
  const Terms d4 = {{4, 0, 0}, {0, 4, 0}, {0, 0, 4}, {3, 1, 0}, {3, 0, 1}, {1, 3, 0},
                    {0, 3, 1}, {1, 0, 3}, {0, 1, 3}, {2, 2, 0}, {0, 2, 2}, {2, 0, 2},
                    {2, 1, 1}, {1, 2, 1}, {1, 1, 2}};
  return terms_up_to(degree, d2, d3, d4, "Finlayson 2015 expansion");
}

// Root-polynomial terms: the distinct roots of the polynomial terms (squares of a single
// channel reduce to the channel, so colour drops them), colour's order.
Terms finlayson_root_terms(int degree) {
  const Terms d2 = {{1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  const Terms d3 = {{1, 2, 0}, {0, 1, 2}, {1, 0, 2}, {2, 1, 0}, {0, 2, 1}, {2, 0, 1}, {1, 1, 1}};
  const Terms d4 = {{3, 1, 0}, {3, 0, 1}, {1, 3, 0}, {0, 3, 1}, {1, 0, 3}, {0, 1, 3},
                    {2, 1, 1}, {1, 2, 1}, {1, 1, 2}};
  return terms_up_to(degree, d2, d3, d4, "Finlayson 2015 root-polynomial");
}

const Terms kShen2008 = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0}, {0, 2, 0},
                         {0, 0, 2}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {0, 0, 0}};  // eq (23)
const Terms kGuarneraT2R = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                            {1, 1, 0}, {1, 0, 1}, {0, 1, 1}};  // eq (15), paper's order

std::string term_name(const Monomial& m, bool root) {
  const int d = m.r + m.g + m.b;
  if (d == 0) return "1";
  std::string s;
  auto add = [&](char c, int e) {
    if (e == 0) return;
    s += c;
    if (e > 1) s += std::to_string(e);
  };
  add('R', m.r);
  add('G', m.g);
  add('B', m.b);
  if (root && d > 1) s = "(" + s + ")^1/" + std::to_string(d);
  return s;
}

ModelInfo make(const std::string& id, const std::string& label, const std::string& reference,
               Terms terms, bool root, const std::string& duplicate_of = "") {
  ModelInfo m;
  m.id = id;
  m.label = label;
  m.reference = reference;
  m.n_terms = static_cast<int>(terms.size());
  for (const auto& t : terms) m.term_names.push_back(term_name(t, root));
  m.terms = std::move(terms);
  m.root = root;
  m.linear = m.n_terms == 3 && m.terms[0].r == 1 && m.terms[1].g == 1 && m.terms[2].b == 1;
  m.exposure_invariant = true;
  for (const auto& t : m.terms)
    if (t.r + t.g + t.b != 1 && !(root && t.r + t.g + t.b > 0)) m.exposure_invariant = false;
  m.duplicate_of = duplicate_of;
  return m;
}

// The families the pickers group the models by; every row of build_table names one.
std::vector<ModelFamily> build_families() {
  return {
      {"matrix", "Matrices", "XYZ = M·RGB, or M·[R, G, B, 1] with an offset."},
      {"polynomial", "Polynomials", "Many terms fit 24 patches closely: judge them by the leave-one-out error."},
      {"root-polynomial", "Root-polynomials", "Exposure-invariant; degree 2 is Guarnera T2R."},
      {"Guarnera2018", "Guarnera et al. 2018",
       "The paper's T1, To and T2R; fitted by pattern search there (objective \"psm\")."},
  };
}

std::vector<ModelInfo> build_table() {
  std::vector<ModelInfo> t;
  const std::string abed = citation::kAbed2013, guarnera = citation::kGuarnera2018;
  const auto add = [&t](const char* family, ModelInfo m) {
    m.family = family;
    t.push_back(std::move(m));
  };
  add("matrix", make("matrix-3x3", "Linear 3×3 matrix", abed + ", eq (7); " + guarnera + ", T1 eq (13)", kR_G_B,
                     false));
  add("matrix", make("matrix-3x4", "Affine 3×4 matrix (with offset)",
                     abed + ", eqs (6), (26); " + guarnera + ", To eq (14)", cat({kR_G_B, {kOne}}), false));
  add("polynomial", make("Shen2008", "Second-order polynomial, 10 terms",
                         std::string(citation::kShen2008) + ", eqs (23)-(25)", kShen2008, false));
  for (int d = 1; d <= 4; ++d) {
    Terms terms = finlayson_root_terms(d);
    const std::string label = "Root-polynomial, degree " + std::to_string(d) + " (" +
                              std::to_string(terms.size()) + " terms)";
    add("root-polynomial", make("Finlayson2015-" + std::to_string(d), label,
                                std::string(citation::kFinlayson2015) + " (root-polynomial)", std::move(terms),
                                true, d == 1 ? "matrix-3x3" : ""));
  }
  for (int n : {3, 4, 5, 7, 8, 10, 11, 14, 16, 17, 19, 20, 22, 35}) {
    std::string dup;
    if (n == 3) dup = "matrix-3x3";
    if (n == 4) dup = "matrix-3x4";
    if (n == 10) dup = "Shen2008";
    add("polynomial", make("Cheung2004-" + std::to_string(n), "Polynomial, " + std::to_string(n) + " terms",
                           std::string(citation::kCheung2004) + " (colour-science's terms)", cheung_terms(n),
                           false, dup));
  }
  add("Guarnera2018", make("Guarnera2018-T1", "Guarnera T1 (linear)", guarnera + ", eq (13)", kR_G_B, false,
                           "matrix-3x3"));
  add("Guarnera2018", make("Guarnera2018-To", "Guarnera To (linear + offset)", guarnera + ", eq (14)",
                           cat({kR_G_B, {kOne}}), false, "matrix-3x4"));
  add("Guarnera2018", make("Guarnera2018-T2R", "Guarnera T2R (second-order root-polynomial)",
                           guarnera + ", eq (15)", kGuarneraT2R, true, "Finlayson2015-2"));
  // Last, so the rows above keep their places; the span of matrix-3x3, fitted differently
  // (fit_corrected_3x3: the 3×4 of eq 26 without its offset, scaled by μ of eq 27).
  add("matrix", make(kCorrected3x3, "Corrected 3×3 (3×4 without offset, scaled by μ from the white)",
                     abed + ", eqs (6)-(13), (26)-(28)", kR_G_B, false, "matrix-3x3"));
  return t;
}

inline double signed_root(double p, int k) {
  if (k == 1) return p;
  if (k == 2) return p >= 0 ? std::sqrt(p) : -std::sqrt(-p);
  if (k == 3) return detmath::cbrt(p);  // the same bits in both builds (detmath.hpp)
  if (k == 4) return p >= 0 ? std::sqrt(std::sqrt(p)) : -std::sqrt(std::sqrt(-p));
  return p >= 0 ? detmath::pow(p, 1.0 / k) : -detmath::pow(-p, 1.0 / k);
}

inline double ipow(double x, int e) {
  double y = 1;
  for (int i = 0; i < e; ++i) y *= x;
  return y;
}

std::vector<double> to_vector(const ModelInfo& info, const Vec3& RGB) {
  std::vector<double> out(info.n_terms);
  expand(info, RGB[0], RGB[1], RGB[2], out.data());
  return out;
}


}  // namespace

void check_coefficient_shape(const Model& model, const ModelInfo& info) {
  if (model.coefficients.rows() != 3 || model.coefficients.cols() != info.n_terms)
    throw Error(ErrorCode::ProfileInvalid,
                "model '" + model.id + "' needs a 3 × " + std::to_string(info.n_terms) +
                    " coefficient matrix, got " + std::to_string(model.coefficients.rows()) + " × " +
                    std::to_string(model.coefficients.cols()));
}

const std::vector<ModelInfo>& model_table() {
  return built_once<&build_table>();
}

const std::vector<ModelFamily>& model_families() {
  return built_once<&build_families>();
}

const ModelInfo& model_info(const std::string& id) {
  if (const ModelInfo* m = find_row(model_table(), id, [](const ModelInfo& r) { return r.id; })) return *m;
  throw Error(ErrorCode::UnknownId, "unknown model id '" + id + "'");
}

void expand(const ModelInfo& info, double r, double g, double b, double* out) {
  // Powers up to 4 (every model's highest) formed once per channel exactly as ipow forms them
  // (x^0 = 1, x^e = x^(e-1)·x): each term is the same product of the same doubles as
  // ipow(r)·ipow(g)·ipow(b), without a loop per term.
  constexpr int kTable = 5;
  double P[3][kTable];
  const double x[3] = {r, g, b};
  for (int c = 0; c < 3; ++c) {
    P[c][0] = 1;
    P[c][1] = x[c];
    for (int e = 2; e < kTable; ++e) P[c][e] = P[c][e - 1] * x[c];
  }
  for (int j = 0; j < info.n_terms; ++j) {
    const Monomial& m = info.terms[j];
    const double p = unsigned(m.r) < kTable && unsigned(m.g) < kTable && unsigned(m.b) < kTable ? P[0][m.r] * P[1][m.g] * P[2][m.b]
                                                                                      : ipow(r, m.r) * ipow(g, m.g) * ipow(b, m.b);
    out[j] = info.root ? signed_root(p, m.r + m.g + m.b) : p;
  }
}

std::vector<double> expansion_Cheung2004(const Vec3& RGB, int terms) {
  return to_vector(model_info("Cheung2004-" + std::to_string((cheung_terms(terms), terms))), RGB);
}

std::vector<double> expansion_Finlayson2015(const Vec3& RGB, int degree, bool root) {
  if (root) return to_vector(model_info("Finlayson2015-" + std::to_string((finlayson_terms(degree), degree))), RGB);
  ModelInfo poly = make("poly", "", "", finlayson_terms(degree), false);
  return to_vector(poly, RGB);
}

std::vector<double> expansion_Shen2008(const Vec3& RGB) { return to_vector(model_info("Shen2008"), RGB); }

std::vector<double> expansion(const std::string& model_id, const Vec3& RGB) {
  return to_vector(model_info(model_id), RGB);
}

PatchMatrix predict(const Model& model, const PatchMatrix& camera_RGB) {
  const ModelInfo& info = model_info(model.id);
  check_coefficient_shape(model, info);
  PatchMatrix out(camera_RGB.rows(), 3);
  // The coefficients in a plain array (the same sums in the same order as through the matrix).
  const int n = info.n_terms;
  double k[3][kMaxModelTerms];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < n; ++j) k[c][j] = model.coefficients(c, j);
  double phi[kMaxModelTerms];
  for (Eigen::Index i = 0; i < camera_RGB.rows(); ++i) {
    expand(info, camera_RGB(i, 0), camera_RGB(i, 1), camera_RGB(i, 2), phi);
    for (int c = 0; c < 3; ++c) {
      double s = 0;
      for (int j = 0; j < n; ++j) s += k[c][j] * phi[j];
      out(i, c) = s;
    }
  }
  return out;
}

Vec3 predict(const Model& model, const Vec3& camera_RGB) {
  PatchMatrix in(1, 3);
  in.row(0) = camera_RGB.transpose();
  return predict(model, in).row(0).transpose();
}

}  // namespace tristim
