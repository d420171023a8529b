// Grey- and colour-based polynomial linearisations (OpenCV ccm's GRAYPOLYFIT, GRAYLOGPOLYFIT,
// COLORPOLYFIT, COLORLOGPOLYFIT families) and the choice of grey patches.
//
// Differences from OpenCV, on purpose: the grey rows fit one curve per channel (OpenCV fits one
// curve on the greys' luma, 0.2126 R + 0.7152 G + 0.0722 B, and applies it to every channel),
// and a grey's linear value is its reflectance factor — the mean of its reflectance when
// reflectances are known (Shen et al. 2008, Fig 5: "normalized average reflectance of gray
// samples"), else Y / Y_white (OpenCV: the grey's Y).
#include <cmath>
#include <sstream>

#include "rows.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "../detmath.hpp"
#include "../fixed_text.hpp"

namespace tristim {

namespace {

/// Reference XYZ of every row and its white: data.reference_XYZ, or the reflectances under
/// D65 (2°). Error(MissingColumn) naming `who` when there is neither.
PatchMatrix reference_XYZ_of(const LinearisationData& data, Vec3& white, const std::string& who) {
  if (data.reference_XYZ.rows() > 0) {
    white = data.white;
    return data.reference_XYZ;
  }
  if (data.reflectances.size() == 0)
    throw Error(ErrorCode::MissingColumn, who + " needs the patches' reference XYZ or reflectances");
  const SpectralData d65 = illuminant_spd("D65");
  white = illuminant_white_XYZ(d65);
  // The rows' spectra in row order, integrated with one set of weights (D65 on the CMF grid)
  // instead of one per row (the same values: sd_to_XYZ is this for one spectrum).
  SpectralData rows;
  rows.wavelengths = data.reflectances.wavelengths;
  rows.linear = data.reflectances.linear;
  for (Eigen::Index i = 0; i < data.camera_RGB.rows(); ++i) {
    const std::string id = data.ids.empty() ? std::to_string(i + 1) : data.ids[i];
    rows.values.push_back(data.reflectances.column(id));
    rows.names.push_back(id);
  }
  const std::vector<Vec3> XYZ = reflectances_to_XYZ(rows, d65);
  PatchMatrix xyz(data.camera_RGB.rows(), 3);
  for (Eigen::Index i = 0; i < xyz.rows(); ++i) xyz.row(i) = XYZ[static_cast<size_t>(i)].transpose();
  return xyz;
}

}  // namespace

GreySelection select_greys(const LinearisationData& data, const std::vector<std::string>& given, double threshold) {
  GreySelection g;
  if (!given.empty()) {
    for (const auto& raw : given) {
      const std::string id = normalise_patch_id(raw);
      int found = -1;
      for (size_t i = 0; i < data.ids.size(); ++i)
        if (data.ids[i] == id) found = static_cast<int>(i);
      if (found < 0) throw Error(ErrorCode::UnknownId, "grey patch '" + raw + "' is not among the patches");
      g.rows.push_back(found);
    }
    g.reason = "given: " + std::to_string(g.rows.size()) + " patches";
    return g;
  }
  Vec3 white;
  const PatchMatrix xyz = reference_XYZ_of(data, white, "finding the grey patches");
  std::string listed;
  for (Eigen::Index i = 0; i < xyz.rows(); ++i) {
    const Vec3 lab = XYZ_to_Lab(xyz.row(i).transpose(), white);
    const double dE = delta_E_CIE2000(Vec3(lab[0], 0, 0), lab);
    if (dE < threshold) {
      g.rows.push_back(static_cast<int>(i));
      listed += (listed.empty() ? "" : ", ") + (data.ids.empty() ? std::to_string(i + 1) : data.ids[i]) + " " + fixed_text(dE, 2);
    }
  }
  g.reason = "automatic: CIEDE2000 from the neutral of the same L* below " + fixed_text(threshold, 2) +
             " (OpenCV ccm's rule): " + (listed.empty() ? "none" : listed);
  return g;
}

namespace linearisation_detail {

PatchMatrix grey_values(const LinearisationData& data, const std::vector<int>& rows) {
  PatchMatrix t = PatchMatrix::Zero(data.camera_RGB.rows(), 3);
  if (data.reflectances.size() > 0) {
    const std::vector<double>& w = data.reflectances.wavelengths;
    for (int r : rows) {
      const std::vector<double>& refl = data.reflectances.column(data.ids.at(r));
      double sum = 0;
      int n = 0;
      for (size_t i = 0; i < w.size(); ++i)
        if (w[i] >= 400 - 1e-9 && w[i] <= 700 + 1e-9) sum += refl[i], ++n;
      if (n == 0)  // a set that does not reach 400-700 nm: its whole range
        for (double v : refl) sum += v, ++n;
      t.row(r).setConstant(sum / n);
    }
    return t;
  }
  Vec3 white;
  const PatchMatrix xyz = reference_XYZ_of(data, white, "the grey patches' linear values");
  for (int r : rows) t.row(r).setConstant(xyz(r, 1) / white[1]);
  return t;
}

namespace {

bool is_log(const MethodChoice& choice) { return choice.method.find("log") != std::string::npos; }

/// The linear value each row should map to, per channel (rows × 3).
PatchMatrix targets(const LinearisationData& data, bool grey, const std::vector<int>& rows, const std::string& who) {
  if (grey) return grey_values(data, rows);
  PatchMatrix t = PatchMatrix::Zero(data.camera_RGB.rows(), 3);
  Vec3 white;
  const PatchMatrix xyz = reference_XYZ_of(data, white, who);
  const Mat3 M = display_matrix(white);  // XYZ -> linear sRGB, white -> (1, 1, 1) (Bradford to D65)
  for (int r : rows) t.row(r) = (M * xyz.row(r).transpose()).transpose();
  return t;
}

Linearisation fit_polynomial_row(const LinearisationData& data, const MethodChoice& choice) {
  check_data(data);
  const bool grey = choice.method.rfind("grey", 0) == 0, log = is_log(choice);
  const int K = static_cast<int>(choice_number(choice, "K"));
  Linearisation l;
  l.choice = choice;
  l.full_scale = full_scale_of(data);
  std::vector<int> candidates;
  if (grey) {
    const GreySelection g = select_greys(data, split_ids(choice_text(choice, "grey")), choice_number(choice, "grey_threshold"));
    candidates = g.rows;
    l.grey_reason = g.reason;
    for (int r : g.rows) l.greys.push_back(data.ids.empty() ? std::to_string(r + 1) : data.ids[r]);
  } else {
    for (Eigen::Index i = 0; i < data.camera_RGB.rows(); ++i) candidates.push_back(static_cast<int>(i));
  }
  const PatchMatrix t = targets(data, grey, candidates, choice.method);
  std::array<std::vector<int>, 3> used;
  static const char* kChannel = "RGB";
  for (int c = 0; c < 3; ++c) {
    std::vector<double> x, y;
    for (int r : usable_rows(data, candidates, c, l.full_scale, l)) {
      const double xv = data.camera_RGB(r, c) / l.full_scale, yv = t(r, c);
      if (log && !(xv > 0 && yv > 0)) continue;  // OpenCV's LogPolyfit mask
      used[c].push_back(r);
      x.push_back(log ? detmath::log(xv) : xv);
      y.push_back(log ? detmath::log(yv) : yv);
    }
    const std::string where = choice.method + ", channel " + kChannel[c] + ": " + std::to_string(x.size()) +
                              (grey ? " usable grey patches" : " usable patches");
    if (x.empty()) throw Error(ErrorCode::NoUsableData, where + (grey ? " (" + l.grey_reason + ")" : ""));
    try {
      l.coefficients[c] = polyfit(x, y, K);
    } catch (const Error& e) {
      throw Error(e.code(), where + "; " + e.what());
    }
    std::vector<double> yl, fl;
    for (size_t i = 0; i < x.size(); ++i) {
      yl.push_back(log ? detmath::exp(y[i]) : y[i]);
      const double f = polyval(l.coefficients[c], x[i]);
      fl.push_back(log ? detmath::exp(f) : f);
    }
    l.r_squared[c] = coefficient_of_determination(yl, fl);
    if (static_cast<int>(x.size()) == K + 1)
      add_warning(l, std::string("channel ") + kChannel[c] + ": as many samples as coefficients — the curve passes through every one, R² says nothing");
  }
  record_fit(l, data, used, l.full_scale);
  check_monotonic(l, log ? apply_log_polynomial : apply_polynomial);
  return l;
}

std::vector<OptionSpec> polynomial_options(bool grey) {
  std::vector<OptionSpec> o{{"K", "integer", "Degree K", 3, "", 1, 7, {}, "polynomial degree per channel (OpenCV ccm's default 3)"}};
  if (grey) {
    o.push_back({"grey", "text", "Grey patches", 0, "", 0, 0, {},
                 "';'-separated patch ids; empty: every patch within grey_threshold of neutral"});
    o.push_back({"grey_threshold", "number", "Grey threshold (ΔE00)", 2, "", 0.01, 50, {},
                 "automatic greys: CIEDE2000 from the neutral of the same L* below this (OpenCV's 2)"});
  }
  return o;
}

}  // namespace

std::vector<LinearisationMethod> rows_polynomial() {
  return {
      {{"grey-polynomial", "Polynomial on the grey patches (per channel)", "ISO 14524 style; OpenCV ccm GRAYPOLYFIT",
        polynomial_options(true)},
       "greys", fit_polynomial_row, apply_polynomial, inverse_polynomial},
      {{"grey-log-polynomial", "Log-polynomial on the grey patches (per channel)", "OpenCV ccm GRAYLOGPOLYFIT",
        polynomial_options(true)},
       "greys", fit_polynomial_row, apply_log_polynomial, inverse_log_polynomial},
      {{"colour-polynomial", "Polynomial per channel against the reference's linear sRGB", "OpenCV ccm COLORPOLYFIT",
        polynomial_options(false)},
       "reference", fit_polynomial_row, apply_polynomial, inverse_polynomial},
      {{"colour-log-polynomial", "Log-polynomial per channel against the reference's linear sRGB",
        "OpenCV ccm COLORLOGPOLYFIT", polynomial_options(false)},
       "reference", fit_polynomial_row, apply_log_polynomial, inverse_log_polynomial},
  };
}

}  // namespace linearisation_detail
}  // namespace tristim
