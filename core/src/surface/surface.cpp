// The surface-correction table (none, scaler, offset, scaler-offset, saunderson) and its dispatcher.
#include "tristim/surface/surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "correction.hpp"
#include "../citations.hpp"
#include "../table_lookup.hpp"
#include "tristim/error.hpp"
#include "tristim/number.hpp"
#include "tristim/surface/saunderson.hpp"

namespace tristim {

namespace surface_detail {

PointCorrection::Kind correction_kind(const std::string& id) {
  if (id == "none") return PointCorrection::None;
  if (id == "scaler") return PointCorrection::Scaler;
  if (id == "offset") return PointCorrection::Offset;
  if (id == "scaler-offset") return PointCorrection::ScalerOffset;
  if (id == "saunderson") return PointCorrection::Saunderson;
  throw Error(ErrorCode::UnknownId, "unknown surface correction '" + id + "'");
}

PointCorrection prepare_correction(PointCorrection::Kind kind, const std::vector<double>& c) {
  PointCorrection p;
  p.kind = kind;
  switch (kind) {
    case PointCorrection::None: break;
    case PointCorrection::Scaler: p.a = c[0]; break;
    case PointCorrection::Offset: p.b = c[0]; break;
    case PointCorrection::ScalerOffset: p.a = c[0]; p.b = c[1]; break;  // eq (5)
    case PointCorrection::Saunderson:
      p.t = three_parameter_Abed2013({c[0], c[1], c[2]}, {c[3], c[4], c[5]});  // eq (4), Appendix A
      break;
  }
  return p;
}

Eigen::MatrixXd integration_matrix(const std::vector<double>& wavelengths, bool linear, const SpectralData& illuminant,
                                   Observer observer) {
  const size_t L = wavelengths.size();
  SpectralData unit;
  unit.wavelengths = wavelengths;
  unit.linear = linear;
  for (size_t j = 0; j < L; ++j) {
    std::vector<double> e(L, 0.0);
    e[j] = 1;
    unit.values.push_back(std::move(e));
    unit.names.push_back("e" + std::to_string(j));
  }
  const auto xyz = reflectances_to_XYZ(unit, illuminant, observer);
  Eigen::MatrixXd T(static_cast<Eigen::Index>(L), 3);
  for (size_t j = 0; j < L; ++j) T.row(static_cast<Eigen::Index>(j)) = xyz[j].transpose();
  return T;
}

std::vector<std::vector<double>> saunderson_starts(const std::vector<double>& base, const std::vector<size_t>& free,
                                                   double mu, double rho) {
  std::vector<std::vector<double>> starts = {base};
  const bool capture = free == std::vector<size_t>{3, 4, 5}, measurement = free == std::vector<size_t>{0, 1, 2};
  if (!capture && !measurement) return starts;
  std::vector<double> c = base;
  if (capture) {
    c[4] = c[1];
    c[3] = 1 - mu * (1 - c[0]);
    if (c[3] > 1e-6) c[5] = (rho + mu * c[2] * c[0]) / c[3];
  } else {
    c[1] = c[4];
    if (mu > 1e-6) c[0] = 1 - (1 - c[3]) / mu;
    if (c[0] > 1e-6 && mu > 1e-6) c[2] = (c[5] * c[3] - rho) / (mu * c[0]);
  }
  starts.push_back(c);
  std::vector<double> other = base;
  const size_t ins = capture ? 5 : 2;
  other[ins] = base[ins] > 0.5 ? 0 : 1;
  starts.push_back(other);
  return starts;
}

}  // namespace surface_detail

using surface_detail::PointCorrection;
using surface_detail::correction_kind;
using surface_detail::prepare_correction;

namespace {

const char* kSpectralHelp =
    "per-wavelength coefficients: ';'-separated entries 'nm/c1/c2/...' (the row's coefficients in order); "
    "empty = the scalar options at every wavelength";

OptionSpec spectral_option() { return text_option("spectral", "Per-wavelength coefficients", kSpectralHelp); }

// Where the coefficients come from (Phase II as an option of the normal fit path).
OptionSpec fit_option() {
  return text_option(
      "fit", "Coefficients",
      "fixed: applied as given; joint: fitted by the fit step jointly with a 3×3 matrix anchored to the chart's white "
      "patch (Phase II, Abed et al. 2013 Fig. 3), these values being the start and, for Saunderson, the fixed "
      "instrument geometry",
      "fixed", {"fixed", "joint"});
}

SpectralData apply_rows(const SpectralData& reflectances, const MethodChoice& choice) {
  check_reflectances(reflectances, "reflectances to correct");
  const PointCorrection::Kind kind = correction_kind(choice.method);
  if (kind == PointCorrection::None) return reflectances;
  const auto coefficients = surface_coefficients(choice, reflectances.wavelengths);
  SpectralData out = reflectances;
  for (size_t w = 0; w < reflectances.wavelengths.size(); ++w) {
    const PointCorrection p = prepare_correction(kind, coefficients[w]);
    for (auto& column : out.values) column[w] = p.value(column[w]);
  }
  return out;
}

std::vector<SurfaceMethod> build_table() {
  const std::string abed = std::string(citation::kAbed2013) + ", ";
  const std::string mu_text = "gain μ applied to every reflectance factor (1 = none)";
  const std::string rho_text = "offset ρ added to every reflectance factor (0 = none)";
  std::vector<SurfaceMethod> t;
  t.push_back({{"none", "None (reflectances as measured)", abed + "no correction (the uncorrected reference of Phase I and Table IV)", {}},
               apply_rows, {}, "", {}});
  t.push_back({{"scaler", "Scaler (R' = μR)", abed + "Phase I 'scaler'",
                {number_option("mu", "μ", 1, 0, 2, mu_text), spectral_option(), fit_option()}},
               apply_rows, {"mu"}, "R' = μR", {}});
  t.push_back({{"offset", "Offset (R' = R + ρ)", abed + "Phase I 'offset'",
                {number_option("rho", "ρ", 0, -0.5, 0.5, rho_text), spectral_option(), fit_option()}},
               apply_rows, {"rho"}, "R' = R + ρ", {}});
  t.push_back({{"scaler-offset", "Scaler-offset (R' = μR + ρ)", abed + "eq (5), Appendix B",
                {number_option("mu", "μ", 1, 0, 2, mu_text), number_option("rho", "ρ", 0, -0.5, 0.5, rho_text),
                 spectral_option(), fit_option()}},
               apply_rows, {"mu", "rho"}, "R' = μR + ρ, eq (5)", {}});
  // Defaults: measurement and capture both 45°:0° (the identity). k1, k2 stop at 0.99: at 1 every
  // patch would read the same.
  const SaundersonGeometry g = saunderson_preset("45-0").geometry;
  const std::string k1_text = "fraction of external light reflected at the surface (Fresnel; 0.040 parallel, 0.092 diffuse)";
  const std::string k2_text = "fraction of internal light reflected at the surface (0.4-0.6 for paints)";
  const std::string kins_text = "fraction of the surface (specular) reflection the detector receives (1 SCI, 0 SCE or 45:0)";
  t.push_back({{"saunderson", "Saunderson (measurement -> capture geometry)", abed + "eqs (1)-(4), Appendix A",
                {number_option("k1", "k1 (measurement)", g.k1, 0, 0.99, k1_text),
                 number_option("k2", "k2 (measurement)", g.k2, 0, 0.99, k2_text),
                 number_option("k_ins", "k_ins (measurement)", g.k_ins, 0, 1, kins_text),
                 number_option("k1_capture", "k1' (capture)", g.k1, 0, 0.99, k1_text),
                 number_option("k2_capture", "k2' (capture)", g.k2, 0, 0.99, k2_text),
                 number_option("k_ins_capture", "k_ins' (capture)", g.k_ins, 0, 1, kins_text), spectral_option(),
                 fit_option()}},
               apply_rows, {"k1", "k2", "k_ins", "k1_capture", "k2_capture", "k_ins_capture"}, "eq (3) as eq (4), App. A",
               {{"measurement", {{"k1", "k1"}, {"k2", "k2"}, {"k_ins", "k_ins"}}},
                {"capture", {{"k1", "k1_capture"}, {"k2", "k2_capture"}, {"k_ins", "k_ins_capture"}}}}});
  return t;
}

const OptionSpec& option_of(const MethodInfo& info, const std::string& name) {
  for (const auto& o : info.options)
    if (o.name == name) return o;
  throw Error(ErrorCode::Internal, "surface row '" + info.id + "' lacks option '" + name + "'");
}

double parse_number(const std::string& text, const std::string& context) {
  char* end = nullptr;
  const double v = tristim::parse_double(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw Error(ErrorCode::InvalidArgument, "spectral coefficients: '" + text + "' in '" + context + "' is not a number");
  return v;
}

// The shortest %.Ng text (N <= 17) that reads back to the same double: "0.092", not "0.091999...".
std::string exact_text(double v) {
  char buf[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (tristim::parse_double(buf, nullptr) == v) break;
  }
  return buf;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t end = s.find(sep, start);
    out.push_back(s.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

std::vector<SurfaceListing> surface_listing() {
  std::vector<SurfaceListing> out;
  for (const auto& r : surface_table())
    out.push_back({r.info.id, r.info.label, r.info.reference, r.info.options, r.coefficients, r.equation, r.geometry});
  return out;
}

const std::vector<SurfaceMethod>& surface_table() {
  return built_once<&build_table>();
}

const SurfaceMethod& surface_method(const std::string& id) {
  const auto id_of = [](const SurfaceMethod& r) { return r.info.id; };
  if (const SurfaceMethod* m = find_row(surface_table(), id, id_of)) return *m;
  throw Error(ErrorCode::UnknownId,
              "unknown surface correction '" + id + "' (methods: " + row_ids(surface_table(), id_of) + ")");
}

SpectralData correct_surface(const MethodChoice& choice, const SpectralData& reflectances) {
  const SurfaceMethod& m = surface_method(choice.method);
  return m.apply(reflectances, complete_choice(m.info, choice));
}

void check_reflectances(const SpectralData& reflectances, const std::string& what) {
  for (size_t k = 0; k < reflectances.values.size(); ++k)
    for (size_t w = 0; w < reflectances.values[k].size(); ++w) {
      const double v = reflectances.values[k][w];
      if (v >= 0 && v <= 1.5) continue;  // the message is built only for a bad value
      const std::string where = what + ": patch '" + (k < reflectances.names.size() ? reflectances.names[k] : "?") +
                                "' at " + exact_text(reflectances.wavelengths[w]) + " nm";
      if (!std::isfinite(v)) throw Error(ErrorCode::InvalidArgument, where + " is not finite");
      if (v < 0) throw Error(ErrorCode::NegativeValue, where + " is negative (" + exact_text(v) + ")");
      if (v > 1.5)
        throw Error(ErrorCode::InvalidArgument,
                    where + " is " + exact_text(v) + " > 1.5: reflectance factors are fractions (percent? divide by 100)");
    }
}

std::vector<std::vector<double>> surface_coefficients(const MethodChoice& choice, const std::vector<double>& wavelengths) {
  const SurfaceMethod& m = surface_method(choice.method);
  const size_t nc = m.coefficients.size();
  std::vector<double> scalar(nc);
  for (size_t j = 0; j < nc; ++j) scalar[j] = choice_number(choice, m.coefficients[j]);
  if (nc == 0 || choice_text(choice, "spectral").empty())
    return std::vector<std::vector<double>>(wavelengths.size(), scalar);
  // Per-wavelength table: "nm/c1/c2;...".
  const std::string& text = choice_text(choice, "spectral");
  std::vector<double> grid;
  std::vector<std::vector<double>> table;
  for (const std::string& entry : split(text, ';')) {
    const auto cells = split(entry, '/');
    if (cells.size() != nc + 1)
      throw Error(ErrorCode::InvalidArgument, m.info.id + ": spectral entry '" + entry + "' should be nm and " +
                                                  std::to_string(nc) + " coefficient(s) separated by '/'");
    const double nm = parse_number(cells[0], entry);
    if (!grid.empty() && !(nm > grid.back()))
      throw Error(ErrorCode::NonMonotonic, m.info.id + ": spectral wavelengths must increase ('" + entry + "')");
    std::vector<double> c(nc);
    for (size_t j = 0; j < nc; ++j) {
      c[j] = parse_number(cells[j + 1], entry);
      const OptionSpec& o = option_of(m.info, m.coefficients[j]);
      if (c[j] < o.min || c[j] > o.max)
        throw Error(ErrorCode::InvalidArgument, m.info.id + ": " + o.name + " = " + exact_text(c[j]) + " at " +
                                                    cells[0] + " nm is outside [" + exact_text(o.min) + ", " +
                                                    exact_text(o.max) + "]");
    }
    grid.push_back(nm);
    table.push_back(std::move(c));
  }
  std::vector<std::vector<double>> out(wavelengths.size(), std::vector<double>(nc));
  for (size_t w = 0; w < wavelengths.size(); ++w) {
    const double x = wavelengths[w];
    const size_t hi = static_cast<size_t>(std::upper_bound(grid.begin(), grid.end(), x) - grid.begin());
    if (hi == 0) out[w] = table.front();
    else if (hi == grid.size()) out[w] = table.back();
    else {
      const double t = (x - grid[hi - 1]) / (grid[hi] - grid[hi - 1]);
      for (size_t j = 0; j < nc; ++j) out[w][j] = (1 - t) * table[hi - 1][j] + t * table[hi][j];
    }
  }
  return out;
}

std::string spectral_coefficients_text(const std::vector<double>& wavelengths,
                                       const std::vector<std::vector<double>>& coefficients) {
  if (wavelengths.size() != coefficients.size())
    throw Error(ErrorCode::InvalidArgument, "spectral coefficients: one coefficient vector per wavelength expected");
  std::string s;
  for (size_t w = 0; w < wavelengths.size(); ++w) {
    if (w) s += ';';
    s += exact_text(wavelengths[w]);
    for (double c : coefficients[w]) s += '/' + exact_text(c);
  }
  return s;
}

MethodChoice surface_choice(const std::string& id, const std::vector<double>& coefficients) {
  const SurfaceMethod& m = surface_method(id);
  if (coefficients.size() != m.coefficients.size())
    throw Error(ErrorCode::InvalidArgument, id + " takes " + std::to_string(m.coefficients.size()) + " coefficient(s)");
  MethodChoice c;
  c.method = id;
  for (size_t j = 0; j < coefficients.size(); ++j) c.parameters[m.coefficients[j]] = coefficients[j];
  return complete_choice(m.info, c);
}

double surface_value(const std::string& id, const std::vector<double>& c, double R) {
  const SurfaceMethod& m = surface_method(id);
  if (c.size() != m.coefficients.size())
    throw Error(ErrorCode::InvalidArgument, id + " takes " + std::to_string(m.coefficients.size()) + " coefficient(s)");
  if (id == "saunderson") return saunderson_convert_Abed2013(R, {c[0], c[1], c[2]}, {c[3], c[4], c[5]});  // eq (3)
  return prepare_correction(correction_kind(id), c).value(R);
}

std::string surface_choice_text(const MethodChoice& choice) {
  std::string s = choice.method, sep = ":";
  for (const auto& [name, value] : choice.parameters) {
    s += sep + name + "=" + exact_text(value);
    sep = ",";
  }
  for (const auto& [name, value] : choice.settings) {
    if (value.empty() || (name == "fit" && value == "fixed")) continue;  // the defaults
    s += sep + name + "=" + value;
    sep = ",";
  }
  return s;
}

}  // namespace tristim
