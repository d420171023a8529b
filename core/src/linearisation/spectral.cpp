// Spectral characterisation, Shen et al. (2008) eqs (26)-(28).
#include "tristim/linearisation/spectral.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>

#include "tristim/error.hpp"
#include "tristim/io/limits.hpp"
#include "../citations.hpp"
#include "rows.hpp"

namespace tristim {

namespace {

void check_rows(const std::vector<std::string>& ids, const PatchMatrix& camera_RGB, const char* who) {
  if (ids.size() != static_cast<size_t>(camera_RGB.rows()))
    throw Error(ErrorCode::PatchMismatch, std::string(who) + ": " + std::to_string(ids.size()) + " ids for " +
                                              std::to_string(camera_RGB.rows()) + " rows of camera RGB");
  if (!camera_RGB.allFinite()) throw Error(ErrorCode::NonFinite, std::string(who) + ": camera RGB holds NaN or Inf");
}

}  // namespace

const MethodInfo& spectral_method() {
  static const MethodInfo info{"pseudo-inverse", "Pseudo-inverse spectral characterisation (Shen et al. 2008)",
                               std::string(citation::kShen2008) + ", eqs (26)-(28)", grey_options()};
  return info;
}

SpectralModel fit_spectral(const Linearisation& linearisation, const std::vector<std::string>& ids,
                           const PatchMatrix& camera_RGB, const SpectralData& reflectances, const MethodChoice& options) {
  check_rows(ids, camera_RGB, "spectral fit");
  if (reflectances.wavelengths.empty()) throw Error(ErrorCode::MissingColumn, "spectral fit: no reflectances");
  const MethodChoice choice = complete_choice(spectral_method(), options);
  SpectralModel m;
  m.linearisation = linearisation;
  m.wavelengths = reflectances.wavelengths;
  // The training set (the paper's: the non-grey patches), by the Shen2008 linearisation's rule.
  LinearisationData data;
  data.ids = ids;
  data.camera_RGB = camera_RGB;
  data.reflectances = reflectances;
  GreySelection greys;
  const std::vector<int> rows = training_rows(data, choice, greys);
  const bool all = choice_number(choice, "use_greys") != 0;
  m.training_set = all ? "all" : "non-grey";
  m.grey_reason = greys.reason;
  for (int r : greys.rows) m.greys.push_back(ids[static_cast<size_t>(r)]);
  for (int r : rows) m.training_ids.push_back(ids[static_cast<size_t>(r)]);
  const Eigen::Index Q = static_cast<Eigen::Index>(rows.size());
  m.training_patches = static_cast<int>(Q);
  if (Q < 3)
    throw Error(ErrorCode::TooFewPatches, "spectral fit: W (eq 27) needs at least 3 " +
                                              std::string(all ? "" : "non-grey ") + "patches, got " + std::to_string(Q) +
                                              (all ? "" : " (use_greys = 1 trains on the greys too)"));
  const Eigen::Index N = static_cast<Eigen::Index>(m.wavelengths.size());
  PatchMatrix stored(Q, 3);
  for (Eigen::Index q = 0; q < Q; ++q) stored.row(q) = camera_RGB.row(rows[static_cast<size_t>(q)]);
  const PatchMatrix u = linearise(linearisation, stored);  // [û]ᵀ, Q × 3
  Eigen::MatrixXd R(N, Q);                                 // [r], N × Q
  for (Eigen::Index q = 0; q < Q; ++q) {
    const std::vector<double>& r = reflectances.column(m.training_ids[static_cast<size_t>(q)]);
    for (Eigen::Index i = 0; i < N; ++i) R(i, q) = r[static_cast<size_t>(i)];
  }
  // eq (27): W = [r][û]⁺; with [û] (3 × Q) of full row rank, [û]⁺ = [û]ᵀ([û][û]ᵀ)⁻¹, computed
  // as the least-squares solution of [û]ᵀ Wᵀ = [r]ᵀ by SVD.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(u), Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto& sv = svd.singularValues();
  if (!(sv[2] > 1e-12 * sv[0]))
    throw Error(ErrorCode::IllConditioned, "spectral fit: the linearised responses [û] have rank < 3 (eq 27)");
  m.W = svd.solve(R.transpose()).transpose();
  return m;
}

SpectralData estimate_reflectances(const SpectralModel& model, const std::vector<std::string>& ids,
                                   const PatchMatrix& camera_RGB) {
  check_rows(ids, camera_RGB, "spectral estimate");
  const PatchMatrix u = linearise(model.linearisation, camera_RGB);
  SpectralData out;
  out.wavelengths = model.wavelengths;
  out.names = ids;
  for (Eigen::Index q = 0; q < u.rows(); ++q) {
    const Eigen::VectorXd r = model.W * u.row(q).transpose();  // eq (26)
    out.values.emplace_back(r.data(), r.data() + r.size());
  }
  return out;
}

double spectral_rms(const std::vector<double>& measured, const std::vector<double>& estimated) {
  if (measured.size() != estimated.size() || measured.empty())
    throw Error(ErrorCode::InvalidArgument, "spectral RMS: two reflectances of the same, non-zero length needed");
  double s = 0;
  for (size_t i = 0; i < measured.size(); ++i) s += (measured[i] - estimated[i]) * (measured[i] - estimated[i]);
  return std::sqrt(s / static_cast<double>(measured.size()));  // eq (28)
}

SpectralEvaluation evaluate_spectral(const SpectralModel& model, const std::vector<std::string>& ids,
                                     const PatchMatrix& camera_RGB, const SpectralData& measured,
                                     const SpectralData& illuminant, Observer observer) {
  const SpectralData est = estimate_reflectances(model, ids, camera_RGB);
  const Vec3 white = illuminant_white_XYZ(illuminant, observer);
  SpectralEvaluation e;
  e.ids = ids;
  // Measured and estimated spectra on the model's grid, each set integrated with one set of
  // weights (the same values as sd_to_XYZ per spectrum, which recomputed them every time).
  SpectralData meas, estd;
  meas.wavelengths = estd.wavelengths = model.wavelengths;
  for (size_t q = 0; q < ids.size(); ++q) {
    meas.values.push_back(
        interpolate_spectrum(measured.wavelengths, measured.column(ids[q]), model.wavelengths, measured.linear));
    estd.values.push_back(est.values[q]);
    meas.names.push_back(ids[q]);
    estd.names.push_back(ids[q]);
    e.rms.push_back(spectral_rms(meas.values.back(), est.values[q]));
  }
  const std::vector<Vec3> a = reflectances_to_XYZ(meas, illuminant, observer);
  const std::vector<Vec3> b = reflectances_to_XYZ(estd, illuminant, observer);
  for (size_t q = 0; q < ids.size(); ++q)
    e.dE00.push_back(delta_E_CIE2000(XYZ_to_Lab(a[q], white), XYZ_to_Lab(b[q], white)));
  e.rms_summary = summarize(e.rms);
  e.dE00_summary = summarize(e.dE00);
  return e;
}

void estimate_reflectance_image(const SpectralModel& model, const float* rgb, size_t n_pixels, float* bands) {
  const size_t N = model.wavelengths.size();
  std::vector<float> w0(N), w1(N), w2(N);
  for (size_t i = 0; i < N; ++i) {
    w0[i] = static_cast<float>(model.W(static_cast<Eigen::Index>(i), 0));
    w1[i] = static_cast<float>(model.W(static_cast<Eigen::Index>(i), 1));
    w2[i] = static_cast<float>(model.W(static_cast<Eigen::Index>(i), 2));
  }
  const size_t block = 4096;
  std::vector<float> u(3 * block);
  ImageLineariser lineariser(model.linearisation);  // its tables made once, not per block
  for (size_t start = 0; start < n_pixels; start += block) {
    const size_t n = std::min(block, n_pixels - start);
    std::copy(rgb + 3 * start, rgb + 3 * (start + n), u.begin());
    lineariser.apply(u.data(), n);
    for (size_t p = 0; p < n; ++p) {
      const float a = u[3 * p], b = u[3 * p + 1], c = u[3 * p + 2];
      float* out = bands + (start + p) * N;
      for (size_t i = 0; i < N; ++i) out[i] = w0[i] * a + w1[i] * b + w2[i] * c;  // eq (26)
    }
  }
}

std::string spectral_csv(const SpectralData& s) {
  std::string out = "wavelength_nm";
  for (const auto& n : s.names) out += "," + n;
  out += "\n";
  char buf[40];
  for (size_t i = 0; i < s.wavelengths.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.10g", s.wavelengths[i]);
    out += buf;
    for (const auto& col : s.values) {
      std::snprintf(buf, sizeof buf, ",%.9g", col[i]);
      out += buf;
    }
    out += "\n";
  }
  return out;
}

json::Value spectral_model_json(const SpectralModel& m) {
  json::Value o = json::Value::object();
  o.set("format", "tristim-spectral");
  o.set("version", 1);
  o.set("linearisation", linearisation_json(m.linearisation));
  o.set("wavelengths", json::Value(m.wavelengths));
  json::Value W = json::Value::array();
  for (Eigen::Index i = 0; i < m.W.rows(); ++i) W.push(json::Value(std::vector<double>{m.W(i, 0), m.W(i, 1), m.W(i, 2)}));
  o.set("W", W);
  o.set("training_patches", m.training_patches);
  o.set("training_set", m.training_set);
  o.set("training_ids", linearisation_detail::strings_json(m.training_ids));
  o.set("greys", linearisation_detail::strings_json(m.greys));
  o.set("grey_reason", m.grey_reason);
  return o;
}

SpectralModel spectral_model_from_json(const json::Value& o) {
  auto invalid = [](const std::string& what) { return Error(ErrorCode::ProfileInvalid, "spectral model: " + what); };
  if (!o.is_object()) throw invalid("not a JSON object");
  const json::Value* f = o.find("format");
  if (!f || !f->is_string() || f->as_string() != "tristim-spectral") throw invalid("'format' must be \"tristim-spectral\"");
  const json::Value* v = o.find("version");
  if (!v || !v->is_number() || v->as_number() != 1) throw Error(ErrorCode::ProfileVersion, "spectral model: version must be 1");
  SpectralModel m;
  const json::Value* lin = o.find("linearisation");
  if (!lin) throw invalid("missing 'linearisation'");
  m.linearisation = linearisation_from_json(*lin);
  const json::Value* wl = o.find("wavelengths");
  if (!wl || !wl->is_array()) throw invalid("'wavelengths' must be an array");
  m.wavelengths = wl->as_numbers("wavelengths");
  for (size_t i = 0; i < m.wavelengths.size(); ++i)
    if (!std::isfinite(m.wavelengths[i]) || (i > 0 && !(m.wavelengths[i] > m.wavelengths[i - 1])))
      throw invalid("'wavelengths' must be finite and increasing");
  const json::Value* W = o.find("W");
  if (!W || !W->is_array() || W->size() != m.wavelengths.size() || m.wavelengths.empty())
    throw invalid("'W' must have one row per wavelength");
  m.W.resize(static_cast<Eigen::Index>(m.wavelengths.size()), 3);
  for (size_t i = 0; i < m.wavelengths.size(); ++i) {
    const std::vector<double> row = W->as_array()[i].as_numbers("W row");
    if (row.size() != 3) throw invalid("each row of 'W' must have 3 numbers");
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(row[static_cast<size_t>(c)])) throw invalid("'W' must be finite");
      m.W(static_cast<Eigen::Index>(i), c) = row[static_cast<size_t>(c)];
    }
  }
  const json::Value* q = o.find("training_patches");
  if (q && q->is_number()) m.training_patches = q->as_int("training_patches", 0, limits::kMaxJsonInt);
  // Written since the non-grey default; a model without them was trained on every patch.
  if (const json::Value* t = o.find("training_set")) {
    if (!t->is_string() || (t->as_string() != "all" && t->as_string() != "non-grey"))
      throw invalid("'training_set' must be \"all\" or \"non-grey\"");
    m.training_set = t->as_string();
  }
  for (const auto& [key, out] : {std::pair{"training_ids", &m.training_ids}, std::pair{"greys", &m.greys}})
    if (const json::Value* a = o.find(key)) *out = linearisation_detail::strings_from_json(*a, std::string("spectral model: '") + key + "'");
  if (const json::Value* r = o.find("grey_reason"); r && r->is_string()) m.grey_reason = r->as_string();
  return m;
}

}  // namespace tristim
