// Evaluation: per-patch differences, summaries, leave-one-out, compare and transfer tables.
#include "tristim/evaluation/evaluation.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#ifndef __EMSCRIPTEN__
#include <thread>
#endif

#include "tristim/characterisation/ridge.hpp"
#include "tristim/error.hpp"
#include "tristim/io/limits.hpp"
#include "tristim/profile/recipe.hpp"
#include "tristim/profile/profile.hpp"

namespace tristim {

namespace {

// The q-quantile of v (finite values): linear interpolation between its order statistics
// floor(q(n − 1)) and the next (numpy's default). `sorted`: v is in order already; otherwise v is
// reordered (nth_element, O(n)).
double quantile_of(std::vector<double>& v, double q, bool sorted) {
  const size_t n = v.size();
  const double pos = q * static_cast<double>(n - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const auto at = v.begin() + static_cast<std::ptrdiff_t>(lo);
  if (!sorted) std::nth_element(v.begin(), at, v.end());
  const double next = lo + 1 >= n ? *at : sorted ? *(at + 1) : *std::min_element(at + 1, v.end());
  return *at + (pos - static_cast<double>(lo)) * (next - *at);
}

}  // namespace

double quantile(std::vector<double> values, double q) {
  if (!(q >= 0 && q <= 1)) throw Error(ErrorCode::InvalidArgument, "quantile: q must lie in [0, 1]");
  values.erase(std::remove_if(values.begin(), values.end(), [](double d) { return !std::isfinite(d); }), values.end());
  return values.empty() ? std::nan("") : quantile_of(values, q, false);
}

Summary summarize(const std::vector<double>& values) {
  Summary s;
  std::vector<double> v;
  v.reserve(values.size());
  for (double d : values)
    if (std::isfinite(d)) v.push_back(d);
  if (v.empty()) {
    const double nan = std::nan("");
    return {nan, nan, nan, nan, nan, nan, nan};
  }
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  s.min = v.front();
  s.max = v.back();
  s.median = quantile_of(v, 0.5, true);
  s.p95 = quantile_of(v, 0.95, true);
  double sum = 0, sq = 0;
  for (double d : v) {
    sum += d;
    sq += d * d;
  }
  s.mean = sum / static_cast<double>(n);
  s.rms = std::sqrt(sq / static_cast<double>(n));
  double var = 0;
  for (double d : v) var += (d - s.mean) * (d - s.mean);
  s.std = std::sqrt(var / static_cast<double>(n));
  return s;
}

Metrics evaluate(const PatchMatrix& est, const PatchMatrix& ref, const Vec3& white) {
  if (est.rows() != ref.rows())
    throw Error(ErrorCode::PatchMismatch, "evaluate: " + std::to_string(est.rows()) + " estimates for " +
                                              std::to_string(ref.rows()) + " reference patches");
  if (!(white.minCoeff() > 0) || !white.allFinite())
    throw Error(ErrorCode::InvalidArgument, "evaluate: the white must be positive, finite XYZ");
  Metrics m;
  const Eigen::Index n = ref.rows();
  auto& p = m.patches;
  for (auto* v : {&p.dE76, &p.dE94, &p.dE00, &p.dL, &p.dC, &p.dH, &p.dE_xyz, &p.rel_Y}) v->resize(n);
  std::vector<double> abs_rel;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec3 r = ref.row(i).transpose(), e = est.row(i).transpose();
    const Vec3 Lr = XYZ_to_Lab(r, white), Le = XYZ_to_Lab(e, white);
    p.dE76[i] = delta_E_CIE1976(Lr, Le);
    p.dE94[i] = delta_E_CIE1994(Lr, Le);
    const DeltaE2000 d = delta_E_CIE2000_components(Lr, Le);
    p.dE00[i] = d.dE;
    p.dL[i] = d.dL;
    p.dC[i] = d.dC;
    p.dH[i] = d.dH;
    p.dE_xyz[i] = (e - r).norm();
    p.rel_Y[i] = r[1] > 0 ? (e[1] - r[1]) / r[1] : std::nan("");
    if (r[1] > 0) abs_rel.push_back(std::fabs(p.rel_Y[i]));
  }
  m.dE76 = summarize(p.dE76);
  m.dE94 = summarize(p.dE94);
  m.dE00 = summarize(p.dE00);
  m.dE_xyz = summarize(p.dE_xyz);
  m.abs_rel_Y = summarize(abs_rel);
  for (int c = 0; c < 3; ++c) {
    const double range = n > 0 ? ref.col(c).maxCoeff() - ref.col(c).minCoeff() : 0;
    const double rmse = n > 0 ? std::sqrt((est.col(c) - ref.col(c)).squaredNorm() / static_cast<double>(n)) : 0;
    m.NRMSE[c] = range > 0 ? rmse / range : std::nan("");
  }
  return m;
}

namespace {
PatchMatrix drop_row(const PatchMatrix& m, Eigen::Index k) {
  PatchMatrix out(m.rows() - 1, 3);
  for (Eigen::Index i = 0, j = 0; i < m.rows(); ++i)
    if (i != k) out.row(j++) = m.row(i);
  return out;
}
}  // namespace

PatchMatrix leave_one_out(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                          const FitOptions& options, int white_patch_index) {
  validate_patches(rgb, xyz);
  const Eigen::Index n = rgb.rows();
  if (n < 2) throw Error(ErrorCode::TooFewPatches, "leave-one-out needs at least 2 patches");
  // The corrected 3×3 is not a least-squares fit of its own terms (μ comes from the white): no
  // PRESS identity, so it refits each fold; every fold keeps the white reference, which App. C
  // measures apart from the chart (the PTFE), so μ is always defined.
  const bool corrected = model_id == kCorrected3x3;
  if (options.objective == Objective::LeastSquares && !corrected)
    return leave_one_out_least_squares(model_id, rgb, xyz, options, white_patch_index);
  // Other objectives refit once per patch (N fits of N - 1 patches, work ~ N^2): capped.
  if (static_cast<std::size_t>(n) > limits::kMaxLeaveOneOutPatches)
    throw Error(ErrorCode::LimitExceeded, "leave-one-out refits the model once per patch: " + std::to_string(n) +
                                              " patches, over the limit of " + std::to_string(limits::kMaxLeaveOneOutPatches));
  PatchMatrix out(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) {
    FitOptions o = options;
    std::vector<double> w;
    if (!options.weights.empty()) {
      for (Eigen::Index i = 0; i < n; ++i)
        if (i != k) w.push_back(options.weights[i]);
      o.weights = w;
    }
    if (k == white_patch_index) o.preserve_white = false;
    o.warn_condition = INFINITY;  // a held-out fit's warnings are not reported
    const FitResult r = fit(model_id, drop_row(rgb, k), drop_row(xyz, k), o);
    out.row(k) = predict(r.model, Vec3(rgb.row(k).transpose())).transpose();
  }
  return out;
}

StoppingCheck leave_one_out_stopping_check(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                                           const FitOptions& options, int white_patch_index, double loo_mean,
                                           double condition_number, double min_condition) {
  StoppingCheck c;
  c.loo_mean = loo_mean;
  if (options.objective == Objective::LeastSquares || !(condition_number > min_condition) || !std::isfinite(loo_mean))
    return c;
  FitOptions o = options;
  o.de2000.xtol_rel /= 100;
  o.de2000.ftol_rel /= 100;
  o.psm.step_threshold /= 100;
  c.perturbed_loo_mean = evaluate(leave_one_out(model_id, rgb, xyz, o, white_patch_index), xyz, options.white).dE00.mean;
  c.checked = true;
  c.flagged = std::fabs(c.perturbed_loo_mean - loo_mean) > std::max(0.05, 0.02 * loo_mean);
  return c;
}

ModelEvaluation evaluate_model(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                               const FitOptions& options, int white_patch_index, bool with_loo) {
  ModelEvaluation ev;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  ev.fit = fit(model_id, rgb, xyz, options);
  ev.fit_cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  ev.fit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ev.training = evaluate(ev.fit.fitted, xyz, options.white);
  const ModelInfo& info = model_info(model_id);
  const int q = info.n_terms - (options.preserve_white ? 1 : 0);
  if (with_loo && rgb.rows() - 1 >= std::max(q, 1)) {
    try {
      ev.loo_XYZ = leave_one_out(model_id, rgb, xyz, options, white_patch_index);
      ev.loo = evaluate(ev.loo_XYZ, xyz, options.white);
      ev.has_loo = true;
    } catch (const Error& e) {
      // A fold can be refused (e.g. the only patch that made a channel vary was held out):
      // no LOO figure then, but the fit itself stands.
      if (e.code() != ErrorCode::TooFewPatches && e.code() != ErrorCode::IllConditioned &&
          e.code() != ErrorCode::LimitExceeded)
        throw;
      ev.has_loo = false;
      if (!ev.fit.message.empty()) ev.fit.message += "; ";
      ev.fit.message += std::string("no leave-one-out figure: ") + e.what();
    }
  }
  return ev;
}

namespace {
std::atomic<int> g_compare_threads{0};
}  // namespace

void set_compare_threads(int n) {
  if (n < 0) throw Error(ErrorCode::InvalidArgument, "compare threads must be 0 (one per hardware thread) or more, got " + std::to_string(n));
  g_compare_threads = n;
}

int compare_threads() { return g_compare_threads; }

std::vector<CompareRow> compare_models(const PatchMatrix& rgb, const PatchMatrix& xyz, const FitOptions& options,
                                       std::vector<std::string> model_ids, std::vector<Objective> objectives,
                                       int white_patch_index) {
  validate_patches(rgb, xyz);
  if (model_ids.empty())
    for (const auto& m : model_table())
      if (m.duplicate_of.empty()) model_ids.push_back(m.id);
  if (objectives.empty())
    objectives = {Objective::LeastSquares, Objective::PatternSearch, Objective::DeltaE2000};
  // Rows are independent: natively they are spread over the hardware threads (each row's numbers do
  // not depend on which thread or in which order it runs); the wasm build runs them in order.
  std::vector<std::pair<std::string, Objective>> tasks;
  for (const auto& id : model_ids) {
    (void)model_info(id);  // UnknownId before any work
    for (Objective obj : objectives) tasks.emplace_back(id, obj);
  }
  std::vector<CompareRow> rows(tasks.size());
  auto run_row = [&](std::size_t t) {
    const std::string& id = tasks[t].first;
    const Objective obj = tasks[t].second;
    const ModelInfo& info = model_info(id);
    CompareRow row;
    row.model_id = id;
    row.objective = obj;
    row.n_terms = info.n_terms;
    FitOptions o = options;
    o.objective = obj;
    try {
      const ModelEvaluation ev = evaluate_model(id, rgb, xyz, o, white_patch_index, true);
      row.seconds = ev.fit_seconds;
      row.cpu_seconds = ev.fit_cpu_seconds;
      row.ok = true;
      row.status = ev.fit.status;
      row.message = ev.fit.message;
      row.condition_number = ev.fit.condition_number;
      row.train_dE00 = ev.training.dE00;
      row.train_dE_xyz = ev.training.dE_xyz;
      row.has_loo = ev.has_loo;
      if (ev.has_loo) {
        row.loo_dE00 = ev.loo.dE00;
        row.loo_dE_xyz = ev.loo.dE_xyz;
      }
    } catch (const Error& e) {
      row.ok = false;
      row.error_code = e.code_name();
      row.message = e.what();
    }
    rows[t] = std::move(row);
  };
#ifdef __EMSCRIPTEN__
  for (std::size_t t = 0; t < tasks.size(); ++t) run_row(t);
#else
  const unsigned cap = g_compare_threads > 0 ? static_cast<unsigned>(g_compare_threads)
                                             : std::max(1u, std::min(16u, std::thread::hardware_concurrency()));
  const std::size_t n_threads = std::min<std::size_t>(tasks.size(), cap);
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> failures(n_threads);
  auto worker = [&](std::size_t w) {
    try {
      for (std::size_t t; (t = next.fetch_add(1)) < tasks.size();) run_row(t);
    } catch (...) {
      failures[w] = std::current_exception();
      next = tasks.size();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < n_threads; ++w) pool.emplace_back(worker, w);
  worker(0);
  for (auto& th : pool) th.join();
  for (auto& f : failures)
    if (f) std::rethrow_exception(f);
#endif
  std::stable_sort(rows.begin(), rows.end(), [](const CompareRow& a, const CompareRow& b) {
    auto key = [](const CompareRow& r) {
      if (!r.ok) return std::make_pair(2, 0.0);
      if (!r.has_loo) return std::make_pair(1, r.train_dE00.mean);
      return std::make_pair(0, r.loo_dE00.mean);
    };
    return key(a) < key(b);
  });
  return rows;
}

std::vector<TransferCell> transfer_table(const std::vector<NamedPatches>& training, const PatchMatrix& test_RGB,
                                         const PatchMatrix& test_XYZ, const std::vector<std::string>& model_ids,
                                         const std::vector<Objective>& objectives, const FitOptions& options) {
  validate_patches(test_RGB, test_XYZ);
  std::vector<TransferCell> cells;
  for (const auto& t : training)
    for (const auto& id : model_ids)
      for (Objective obj : objectives) {
        TransferCell c;
        c.training_set = t.name;
        c.model_id = id;
        c.objective = obj;
        FitOptions o = options;
        o.objective = obj;
        try {
          const FitResult r = fit(id, t.camera_RGB, t.reference_XYZ, o);
          const Metrics m = evaluate(predict(r.model, test_RGB), test_XYZ, options.white);
          c.ok = true;
          c.message = r.message;
          c.dE_xyz = m.dE_xyz;
          c.dE00 = m.dE00;
        } catch (const Error& e) {
          c.error_code = e.code_name();
          c.message = e.what();
        }
        cells.push_back(std::move(c));
      }
  return cells;
}

RidgeRow ridge_row(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz, const FitOptions& options) {
  RidgeRow r;
  r.row.model_id = model_id;
  r.row.n_terms = model_info(model_id).n_terms;
  FitOptions ls = options;
  ls.objective = Objective::LeastSquares;
  try {
    const RidgeResult f = fit_ridge(model_id, rgb, xyz, ls);
    const Metrics train = evaluate(f.fit.fitted, xyz, options.white), loo = evaluate(f.loo_XYZ, xyz, options.white);
    r.row.ok = r.row.has_loo = true;
    r.row.message = f.fit.message;
    r.row.condition_number = f.fit.condition_number;
    r.row.train_dE00 = train.dE00;
    r.row.train_dE_xyz = train.dE_xyz;
    r.row.loo_dE00 = loo.dE00;
    r.row.loo_dE_xyz = loo.dE_xyz;
    r.lambda = f.lambda;
  } catch (const Error& e) {
    r.row.error_code = e.code_name();
    r.row.message = e.what();
  }
  return r;
}

namespace {
FitOptions options_of(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& rgb, const PatchMatrix& xyz,
                      int& white_index) {
  if (ids.size() != static_cast<size_t>(rgb.rows()))
    throw Error(ErrorCode::InvalidArgument, std::to_string(ids.size()) + " patch ids for " + std::to_string(rgb.rows()) + " patches");
  return recipe_fit_options(recipe, ids, rgb, xyz, white_index);
}
}  // namespace

StoppingCheck recipe_stopping_check(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& rgb,
                                    const PatchMatrix& xyz, double loo_mean, double condition_number) {
  int white_index = -1;
  const FitOptions o = options_of(recipe, ids, rgb, xyz, white_index);
  return leave_one_out_stopping_check(complete_recipe(recipe).characterisation.model, rgb, xyz, o, white_index, loo_mean,
                                      condition_number);
}

RidgeRow recipe_ridge_row(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& rgb,
                          const PatchMatrix& xyz) {
  int white_index = -1;
  FitOptions o = options_of(recipe, ids, rgb, xyz, white_index);
  o.preserve_white = false;  // ridge has no white constraint (ridge.hpp)
  return ridge_row(complete_recipe(recipe).characterisation.model, rgb, xyz, o);
}

}  // namespace tristim

namespace tristim::fields {

TRISTIM_FIELDS_DEFINE(Summary, member<&Summary::min>("min"), member<&Summary::median>("median"),
                      member<&Summary::mean>("mean"), member<&Summary::p95>("p95"), member<&Summary::max>("max"),
                      member<&Summary::rms>("rms"), member<&Summary::std>("std"));

TRISTIM_FIELDS_DEFINE(PatchErrors, member<&PatchErrors::dE76>("dE76"), member<&PatchErrors::dE94>("dE94"),
                      member<&PatchErrors::dE00>("dE00"), member<&PatchErrors::dL>("dL"),
                      member<&PatchErrors::dC>("dC"), member<&PatchErrors::dH>("dH"),
                      member<&PatchErrors::dE_xyz>("dE_xyz"), member<&PatchErrors::rel_Y>("rel_Y"));

TRISTIM_FIELDS_DEFINE(Metrics, member<&Metrics::dE76>("dE76"), member<&Metrics::dE94>("dE94"),
                      member<&Metrics::dE00>("dE00"), member<&Metrics::dE_xyz>("dE_xyz"),
                      member<&Metrics::abs_rel_Y>("abs_rel_Y"), member<&Metrics::NRMSE>("NRMSE"));

}  // namespace tristim::fields

namespace tristim::fields {
namespace {

// A RidgeRow carries its CompareRow: one list of the row's members serves both structs.
CompareRow& row_of(CompareRow& r) { return r; }
const CompareRow& row_of(const CompareRow& r) { return r; }
CompareRow& row_of(RidgeRow& r) { return r.row; }
const CompareRow& row_of(const RidgeRow& r) { return r.row; }

/// The CompareRow member M of an S (a row, or the row a ridge row carries), under a JSON name.
template <class S, auto M>
Field<S> row_member(const char* name, bool required = true, bool (*shown)(const S&) = nullptr) {
  using T = typename member_traits<decltype(M)>::type;
  return {name, [](const S& s) { return Codec<T>::write(row_of(s).*M); },
          [](const json::Value& v, S& s, const Context& c, const std::string& p) { Codec<T>::read(v, row_of(s).*M, c, p); },
          shown, required};
}

json::Value objective_json(Objective o) { return objective_id(o); }
void read_objective(const json::Value& v, Objective& out, const Context& c, const std::string& p) {
  std::string id;
  Codec<std::string>::read(v, id, c, p);
  try {
    out = objective_from_id(id);
  } catch (const Error&) {
    c.refuse("'" + p + "': unknown objective '" + id + "' (expected ls, psm or de2000)");
  }
}

/// A row's status: fit_status_name's word, or "error" when the fit was refused (which reads back as
/// the default status: a refused row has none).
template <class S>
Field<S> row_status() {
  return {"status", [](const S& s) { return json::Value(row_of(s).ok ? fit_status_name(row_of(s).status) : "error"); },
          [](const json::Value& v, S& s, const Context& c, const std::string& p) {
            std::string name;
            Codec<std::string>::read(v, name, c, p);
            if (name == "error") {
              row_of(s).status = FitStatus::Ok;
              return;
            }
            try {
              row_of(s).status = fit_status_from_name(name);
            } catch (const Error&) {
              c.refuse("'" + p + "': unknown fit status '" + name + "'");
            }
          }};
}

template <class S>
bool has_loo(const S& s) { return row_of(s).has_loo; }

/// The members of a compare row in `tristim compare --json`'s order.
template <class S>
FieldList<S> compare_row_fields() {
  return {row_member<S, &CompareRow::model_id>("model"),
          {"objective", [](const S& s) { return objective_json(row_of(s).objective); },
           [](const json::Value& v, S& s, const Context& c, const std::string& p) { read_objective(v, row_of(s).objective, c, p); }},
          row_member<S, &CompareRow::n_terms>("n_terms"),
          row_member<S, &CompareRow::ok>("ok"),
          row_member<S, &CompareRow::error_code>("error_code"),
          row_status<S>(),
          row_member<S, &CompareRow::message>("message"),
          row_member<S, &CompareRow::condition_number>("condition_number"),
          row_member<S, &CompareRow::seconds>("seconds"),
          row_member<S, &CompareRow::cpu_seconds>("cpu_seconds"),
          row_member<S, &CompareRow::train_dE00>("train_dE00"),
          row_member<S, &CompareRow::train_dE_xyz>("train_dE_xyz"),
          row_member<S, &CompareRow::has_loo>("has_loo"),
          row_member<S, &CompareRow::loo_dE00>("loo_dE00", false, &has_loo<S>),
          row_member<S, &CompareRow::loo_dE_xyz>("loo_dE_xyz", false, &has_loo<S>)};
}

/// "ridge": true, which marks a ridge row among compare rows (nothing else reads as one).
Field<RidgeRow> ridge_mark() {
  return {"ridge", [](const RidgeRow&) { return json::Value(true); },
          [](const json::Value& v, RidgeRow&, const Context& c, const std::string& p) {
            if (!v.is_bool() || !v.as_bool()) c.refuse("'" + p + "' must be true (a ridge row)");
          },
          nullptr, false};
}

}  // namespace

const FieldList<CompareRow>& Schema<CompareRow>::fields() {
  static const FieldList<CompareRow> list = compare_row_fields<CompareRow>();
  return list;
}

const FieldList<RidgeRow>& Schema<RidgeRow>::fields() {
  static const FieldList<RidgeRow> list = [] {
    FieldList<RidgeRow> f = compare_row_fields<RidgeRow>();
    f.push_back(ridge_mark());
    f.push_back(member<&RidgeRow::lambda>("lambda"));
    return f;
  }();
  return list;
}

TRISTIM_FIELDS_DEFINE(StoppingCheck, member<&StoppingCheck::checked>("checked"), member<&StoppingCheck::flagged>("flagged"),
                      member<&StoppingCheck::loo_mean>("loo_mean"),
                      member<&StoppingCheck::perturbed_loo_mean>("perturbed_loo_mean"));

TRISTIM_FIELDS_DEFINE(TransferCell, member<&TransferCell::training_set>("training_set"),
                      member<&TransferCell::model_id>("model"),
                      Field<TransferCell>{"objective", [](const TransferCell& t) { return objective_json(t.objective); },
                                          [](const json::Value& v, TransferCell& t, const Context& c, const std::string& p) {
                                            read_objective(v, t.objective, c, p);
                                          }},
                      member<&TransferCell::ok>("ok"), member<&TransferCell::error_code>("error_code"),
                      member<&TransferCell::dE_xyz>("dE_xyz"), member<&TransferCell::dE00>("dE00"));

}  // namespace tristim::fields
