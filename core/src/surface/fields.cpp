// Field lists of the surface stage's results (declared beside the structs in fit.hpp, joint.hpp
// and geometry_table.hpp): what `tristim surface fit / joint / table4 --json` prints, and the
// objects the module's fitSurface, fitSurfaceJoint and surfaceTable4 give.
#include <string>
#include <vector>

#include "tristim/io/fields.hpp"
#include "tristim/profile/fields.hpp"
#include "tristim/surface/fit.hpp"
#include "tristim/surface/geometry_table.hpp"
#include "tristim/surface/joint.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim::fields {

namespace {

/// A set of spectra as its members (wavelengths, names, values: one array per column, linear).
json::Value spectra_json(const SpectralData& d) {
  return object({{"wavelengths", json::Value(d.wavelengths)}, {"names", write(d.names)}, {"values", write(d.values)},
                 {"linear", d.linear}});
}

// ---- SurfaceFitResult ----
using Fit = SurfaceFitResult;
json::Value fit_method(const Fit& r) { return r.choice.method; }
json::Value fit_surface_text(const Fit& r) { return surface_choice_text(r.choice); }
json::Value fit_range(const Fit& r) {
  return r.wavelengths.empty() ? json::Value::array()
                               : json::Value(std::vector<double>{r.wavelengths.front(), r.wavelengths.back()});
}
json::Value fit_observer(const Fit& r) { return observer_name(r.observer); }
const FieldList<Fit>& fit_spectral_rms() {
  static const FieldList<Fit> f = {member<&Fit::spectral_rms_before>("before"), member<&Fit::spectral_rms_after>("after")};
  return f;
}
const FieldList<Fit>& fit_dE00() {
  static const FieldList<Fit> f = {member<&Fit::summary_dE00_before>("before"), member<&Fit::summary_dE00_after>("after")};
  return f;
}
json::Value fit_patches(const Fit& r) {
  return rows({{"patch", r.ids}, {"rms_before", r.rms_before}, {"rms_after", r.rms_after},
               {"dE00_before", r.dE00_before}, {"dE00_after", r.dE00_after}});
}
bool has_spectra(const Fit& r) { return !r.measured.values.empty(); }
json::Value fit_measured(const Fit& r) { return spectra_json(r.measured); }
json::Value fit_corrected(const Fit& r) { return spectra_json(r.corrected); }
json::Value fit_target(const Fit& r) { return spectra_json(r.target); }

// ---- JointFitResult ----
using Joint = JointFitResult;
json::Value joint_surface(const Joint& r) { return surface_choice_text(r.choice); }
json::Value joint_matrix(const Joint& r) {
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> m = r.matrix;
  return json::Value(std::vector<double>(m.data(), m.data() + 9));
}

// ---- GeometryTableCell ----
using Cell = GeometryTableCell;
bool cell_failed(const Cell& c) { return !c.ok; }
bool cell_has_mu(const Cell& c) { return c.method == "corrected-3x3"; }
json::Value cell_surface(const Cell& c) { return surface_choice_text(c.correction); }
void read_cell_surface(const json::Value& v, Cell& c, const Context& ctx, const std::string& path) {
  std::string text;
  read(v, text, ctx, path);
  try {
    c.correction = parse_choice(text);
    surface_method(c.correction.method);  // a correction of the table (Error UnknownId otherwise)
  } catch (const Error& e) {
    ctx.refuse("'" + path + "': " + e.what());
  }
}

}  // namespace

TRISTIM_FIELDS_DEFINE(SurfaceFitResult, Field<Fit>{"method", fit_method, nullptr}, member<&Fit::choice>("choice"),
                      Field<Fit>{"surface", fit_surface_text, nullptr}, member<&Fit::free>("free"),
                      Field<Fit>{"range_nm", fit_range, nullptr}, member<&Fit::wavelengths>("wavelengths"),
                      member<&Fit::illuminant>("illuminant"), Field<Fit>{"observer", fit_observer, nullptr},
                      member<&Fit::status>("status"), member<&Fit::message>("message"),
                      member<&Fit::evaluations>("evaluations"), section<Fit, fit_spectral_rms>("spectral_rms"),
                      section<Fit, fit_dE00>("dE00"), Field<Fit>{"patches", fit_patches, nullptr},
                      with_shown(Field<Fit>{"measured", fit_measured, nullptr}, has_spectra),
                      with_shown(Field<Fit>{"corrected", fit_corrected, nullptr}, has_spectra),
                      with_shown(Field<Fit>{"target", fit_target, nullptr}, has_spectra));

TRISTIM_FIELDS_DEFINE(JointFitResult, member<&Joint::choice>("choice"), Field<Joint>{"surface", joint_surface, nullptr},
                      Field<Joint>{"matrix", joint_matrix, nullptr},
                      member<&Joint::dE_xyz_rms_start>("dE_xyz_rms_start"), member<&Joint::dE_xyz_rms>("dE_xyz_rms"),
                      member<&Joint::status>("status"), member<&Joint::message>("message"),
                      member<&Joint::evaluations>("evaluations"));

TRISTIM_FIELDS_DEFINE(GeometryTableCell, member<&Cell::training>("training"), member<&Cell::method>("method"),
                      member<&Cell::ok>("ok"), with_shown(member<&Cell::error_code>("error_code", false), cell_failed),
                      member<&Cell::message>("message"), member<&Cell::dE_xyz>("dE_xyz"), member<&Cell::dE00>("dE00"),
                      Field<Cell>{"surface", cell_surface, read_cell_surface},
                      with_shown(member<&Cell::mu>("mu", false), cell_has_mu), member<&Cell::status>("status"));

}  // namespace tristim::fields
