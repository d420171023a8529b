// The linearisation table and its dispatcher.
#include "tristim/linearisation/linearisation.hpp"

#include "tristim/error.hpp"
#include "tristim/linearisation/guarnera2018.hpp"

namespace tristim {

namespace {

Linearisation fit_identity(const LinearisationData& data, const MethodChoice& choice) {
  Linearisation l;
  l.choice = choice;
  l.full_scale = data.full_scale > 0 ? data.full_scale : 1;
  return l;
}

double apply_identity(const Linearisation&, int, double value) { return value; }

std::vector<LinearisationMethod> build_table() {
  std::vector<LinearisationMethod> t;
  t.push_back({{"identity", "None (linear data, e.g. RAW)", "", {}}, fit_identity, apply_identity});
  t.push_back(linearisation_row_Guarnera2018());
  return t;
}

}  // namespace

const std::vector<LinearisationMethod>& linearisation_table() {
  static const std::vector<LinearisationMethod> table = build_table();
  return table;
}

const LinearisationMethod& linearisation_method(const std::string& id) {
  for (const auto& m : linearisation_table())
    if (m.info.id == id) return m;
  throw Error(ErrorCode::UnknownId, "unknown linearisation method '" + id + "'");
}

Linearisation fit_linearisation(const MethodChoice& choice, const LinearisationData& data) {
  const LinearisationMethod& m = linearisation_method(choice.method);
  if (data.camera_RGB.rows() == 0) throw Error(ErrorCode::TooFewPatches, "linearisation: no patches");
  return m.fit(data, complete_choice(m.info, choice));
}

PatchMatrix linearise(const Linearisation& fitted, const PatchMatrix& camera_RGB) {
  const LinearisationMethod& m = linearisation_method(fitted.choice.method);
  PatchMatrix out(camera_RGB.rows(), 3);
  for (Eigen::Index i = 0; i < camera_RGB.rows(); ++i)
    for (int c = 0; c < 3; ++c) out(i, c) = m.apply(fitted, c, camera_RGB(i, c));
  return out;
}

}  // namespace tristim
