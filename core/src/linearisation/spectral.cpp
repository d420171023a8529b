// Spectral characterisation, Shen et al. (2008) eqs (26)-(28).
#include "tristim/linearisation/spectral.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>

#include "tristim/error.hpp"
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

namespace fields {

namespace {

using M = SpectralModel;
using E = SpectralEvaluation;
constexpr const char* kFormat = "tristim-spectral";
constexpr int kVersion = 1;

void read_format(const json::Value& v, M&, const Context& c, const std::string& p) {
  if (!v.is_string() || v.as_string() != kFormat) c.refuse("'" + p + "' must be \"" + kFormat + "\"");
}
void read_version(const json::Value& v, M&, const Context& c, const std::string& p) {
  if (!v.is_number() || v.as_number() != kVersion)
    throw Error(ErrorCode::ProfileVersion, c.prefix + ("'" + p + "' must be " + std::to_string(kVersion)));
}

/// The two summaries' figures the CLI prints, flat, in this order; read back into the same members.
struct SummaryFigure {
  const char* name;
  Summary E::*summary;
  double Summary::*figure;
};
const SummaryFigure kSummaryFigures[] = {
    {"spectral_rms_mean", &E::rms_summary, &Summary::mean}, {"spectral_rms_std", &E::rms_summary, &Summary::std},
    {"spectral_rms_max", &E::rms_summary, &Summary::max},   {"dE00_mean", &E::dE00_summary, &Summary::mean},
    {"dE00_std", &E::dE00_summary, &Summary::std},          {"dE00_max", &E::dE00_summary, &Summary::max}};

json::Value summary_json(const E& e) {
  json::Value o = json::Value::object();
  for (const auto& f : kSummaryFigures) o.set(f.name, e.*f.summary.*f.figure);
  return o;
}
void read_summary(const json::Value& v, E& e, const Context& c, const std::string& p) {
  if (!v.is_object()) c.refuse("'" + p + "' must be an object");
  for (const auto& [name, x] : v.members()) {
    const SummaryFigure* f = nullptr;
    for (const auto& g : kSummaryFigures) f = name == g.name ? &g : f;
    if (!f) c.refuse("unknown field '" + join(p, name) + "'");
    read(x, e.*f->summary.*f->figure, c, join(p, name));
  }
}
/// One row per patch: {"patch", "spectral_rms", "dE00"}.
json::Value patches_json(const E& e) { return rows({{"patch", e.ids}, {"spectral_rms", e.rms}, {"dE00", e.dE00}}); }
struct PatchRow {
  std::string patch;
  double spectral_rms = 0, dE00 = 0;
};
void read_patches(const json::Value& v, E& e, const Context& c, const std::string& p);

}  // namespace

TRISTIM_FIELDS(PatchRow, member<&PatchRow::patch>("patch"), member<&PatchRow::spectral_rms>("spectral_rms"),
               member<&PatchRow::dE00>("dE00"));

namespace {

void read_patches(const json::Value& v, E& e, const Context& c, const std::string& p) {
  std::vector<PatchRow> rows;
  read(v, rows, c, p);
  e.ids.clear();
  e.rms.clear();
  e.dE00.clear();
  for (const PatchRow& r : rows) {
    e.ids.push_back(r.patch);
    e.rms.push_back(r.spectral_rms);
    e.dE00.push_back(r.dE00);
  }
}

}  // namespace

// The order is the document's (pinned bytes).
TRISTIM_FIELDS_DEFINE(SpectralModel, Field<M>{"format", [](const M&) { return json::Value(kFormat); }, read_format},
                      Field<M>{"version", [](const M&) { return json::Value(kVersion); }, read_version},
                      member<&M::linearisation>("linearisation"), member<&M::wavelengths>("wavelengths"),
                      member<&M::W>("W"), member<&M::training_patches>("training_patches", false),
                      // Written since the non-grey default; a model without them was trained on every patch.
                      member<&M::training_set>("training_set", false), member<&M::training_ids>("training_ids", false),
                      member<&M::greys>("greys", false), member<&M::grey_reason>("grey_reason", false),
                      // What `tristim spectral fit` writes beside the model: known, not read.
                      Field<M>{"training", [](const M&) { return json::Value(); },
                               [](const json::Value&, M&, const Context&, const std::string&) {},
                               [](const M&) { return false; }, false});

TRISTIM_FIELDS_DEFINE(SpectralEvaluation, Field<E>{"summary", summary_json, read_summary},
                      Field<E>{"patches", patches_json, read_patches});

void Checks<SpectralModel>::check(SpectralModel& m, const Context& c, const std::string& p) {
  for (size_t i = 0; i < m.wavelengths.size(); ++i)
    if (i > 0 && !(m.wavelengths[i] > m.wavelengths[i - 1])) c.refuse("'" + join(p, "wavelengths") + "' must be increasing");
  if (m.wavelengths.empty() || m.W.rows() != static_cast<Eigen::Index>(m.wavelengths.size()) || m.W.cols() != 3)
    c.refuse("'" + join(p, "W") + "' must have one row of 3 numbers per wavelength");
  if (m.training_patches < 0) c.refuse("'" + join(p, "training_patches") + "' must be >= 0");
  if (m.training_set != "all" && m.training_set != "non-grey")
    c.refuse("'" + join(p, "training_set") + "' must be \"all\" or \"non-grey\"");
}

}  // namespace fields

json::Value spectral_model_json(const SpectralModel& m) { return fields::write(m); }

SpectralModel spectral_model_from_json(const json::Value& o) {
  return linearisation_detail::read_fields<SpectralModel>(o, "spectral model: ");
}

}  // namespace tristim
