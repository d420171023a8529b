// The linearisation table, its dispatcher, application to patches and images, plot samples and
// the JSON form of a fitted linearisation.
#include "tristim/linearisation/linearisation.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "rows.hpp"
#include "../table_lookup.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/error.hpp"
#include "tristim/linearisation/guarnera2018.hpp"

namespace tristim {

namespace {

std::vector<LinearisationMethod> build_table() {
  using namespace linearisation_detail;
  std::vector<LinearisationMethod> t{row_identity(), row_gamma(), row_sRGB()};
  for (auto& r : rows_polynomial()) t.push_back(std::move(r));
  t.push_back(linearisation_row_Guarnera2018());  // absolute colorimetry, guarnera2018.cpp
  t.push_back(row_Shen2008());
  return t;
}

}  // namespace

const std::vector<LinearisationMethod>& linearisation_table() {
  return built_once<&build_table>();
}

const LinearisationMethod& linearisation_method(const std::string& id) {
  const auto id_of = [](const LinearisationMethod& r) { return r.info.id; };
  if (const LinearisationMethod* m = find_row(linearisation_table(), id, id_of)) return *m;
  throw Error(ErrorCode::UnknownId, "unknown linearisation method '" + id + "'");
}

std::vector<LinearisationListing> linearisation_listing() {
  std::vector<LinearisationListing> out;
  for (const auto& r : linearisation_table())
    out.push_back({r.info.id, r.info.label, r.info.reference, r.needs, linearisation_needs_text(r.needs), r.info.options});
  return out;
}

std::string linearisation_needs_text(const std::string& needs) {
  if (needs.empty()) return "needs nothing but the camera RGB";
  if (needs == "greys") return "fitted on the chart's grey patches (found automatically from the reference, or listed)";
  if (needs == "reference") return "fitted against the reference XYZ of every patch";
  if (needs == "reflectances") return "fitted on non-grey patches with known reflectances (a built-in chart's spectra)";
  throw Error(ErrorCode::UnknownId, "unknown linearisation need '" + needs + "'");
}

Linearisation fit_linearisation(const MethodChoice& choice, const LinearisationData& data) {
  const LinearisationMethod& m = linearisation_method(choice.method);
  if (data.camera_RGB.rows() == 0) throw Error(ErrorCode::TooFewPatches, "linearisation: no patches");
  return m.fit(data, complete_choice(m.info, choice));
}

namespace {

// out(i, c) = curve(fitted, c, in(i, c)) for every patch and channel; curve: a row's apply or inverse.
template <class Curve>
PatchMatrix each_channel(const Linearisation& fitted, const PatchMatrix& in, Curve LinearisationMethod::*curve) {
  const LinearisationMethod& m = linearisation_method(fitted.choice.method);
  PatchMatrix out(in.rows(), 3);
  for (Eigen::Index i = 0; i < in.rows(); ++i)
    for (int c = 0; c < 3; ++c) out(i, c) = (m.*curve)(fitted, c, in(i, c));
  return out;
}

}  // namespace

PatchMatrix linearise(const Linearisation& fitted, const PatchMatrix& camera_RGB) {
  return each_channel(fitted, camera_RGB, &LinearisationMethod::apply);
}

PatchMatrix delinearise(const Linearisation& fitted, const PatchMatrix& linear_RGB) {
  return each_channel(fitted, linear_RGB, &LinearisationMethod::inverse);
}

void linearise_image(const Linearisation& fitted, float* rgb, size_t n_pixels) {
  ImageLineariser(fitted).apply(rgb, n_pixels);
}

ImageLineariser::ImageLineariser(const Linearisation& fitted)
    : fitted_(fitted), method_(linearisation_method(fitted.choice.method)) {}

void ImageLineariser::apply(float* rgb, size_t n_pixels) {
  if (fitted_.choice.method == "identity") return;
  const LinearisationMethod& m = method_;
  if (m.apply == linearisation_detail::apply_polynomial) {  // Horner inline: no call per sample
    const double inv = 1.0 / fitted_.full_scale;
    for (int c = 0; c < 3; ++c) {
      const std::vector<double>& k = fitted_.coefficients[c];
      for (size_t i = 0; i < n_pixels; ++i) {
        const double x = rgb[3 * i + c] * inv;
        double y = 0;
        for (size_t j = k.size(); j-- > 0;) y = y * x + k[j];
        rgb[3 * i + c] = static_cast<float>(y);
      }
    }
    return;
  }
  // The curves (gamma, sRGB, log-polynomials, eq 8) call detmath's pow / exp / log, ~4× the C
  // library's cost. Samples that are whole numbers 0..65535 (8- and 16-bit JPEG, PNG, TIFF) take
  // the value from their channel's table, filled on first use: the same float as a call per
  // sample. Without a float-to-int conversion (wasm guards each one) or a second array of flags: a
  // sample's bits, as an unsigned number, are at most 65535.0f's exactly when it is +0..65535
  // (−0, negatives and NaN have larger bits); x + 2^23 rounds x to a whole number, exactly x when
  // x is one, and its low 23 bits are then x. An entry not yet filled holds a signalling NaN,
  // which no curve's float (a converted double: NaNs come out quiet) can be; were one to, the
  // entry would only be computed again. A channel at a time: one 256 KB table stays in cache (all
  // three at once was slower). On a 16-bit 24 MP image about 2× faster in wasm and 1.3–1.5×
  // natively than a conversion and a flag per sample (on an AMD EPYC VM).
  constexpr std::uint32_t kEmpty = 0x7fa5a5a5u, kMaxBits = 0x477fff00u;  // 65535.0f
  constexpr float kTwo23 = 8388608.0f;
  if (tables_.empty()) tables_.assign(3 * 65536, kEmpty);
  for (int c = 0; c < 3; ++c) {
    std::uint32_t* table = tables_.data() + 65536 * static_cast<size_t>(c);
    for (size_t i = 0; i < n_pixels; ++i) {
      float& v = rgb[3 * i + c];
      const float x = v;
      std::uint32_t bits;
      std::memcpy(&bits, &x, 4);
      if (bits <= kMaxBits) {
        const float whole = x + kTwo23;
        if (whole - kTwo23 == x) {
          std::uint32_t k;
          std::memcpy(&k, &whole, 4);
          std::uint32_t& entry = table[k & 0x7fffffu];
          if (entry == kEmpty) {
            const float y = static_cast<float>(m.apply(fitted_, c, x));
            std::memcpy(&entry, &y, 4);
          }
          std::memcpy(&v, &entry, 4);
          continue;
        }
      }
      v = static_cast<float>(m.apply(fitted_, c, x));
    }
  }
}

CurveSamples sample_curve(const Linearisation& fitted, int channel, int n) {
  if (channel < 0 || channel > 2 || n < 2) throw Error(ErrorCode::InvalidArgument, "sample_curve: channel 0..2, n >= 2");
  const LinearisationMethod& m = linearisation_method(fitted.choice.method);
  CurveSamples s;
  const double a = fitted.domain[channel][0], b = fitted.domain[channel][1];
  const bool shen = fitted.choice.method == "Shen2008";
  const bool grey = shen && !fitted.grey_coefficients[channel].empty();
  const double top = shen ? m.apply(fitted, channel, b * fitted.full_scale) : 1.0;
  const double grey_top = grey ? polyval(fitted.grey_coefficients[channel], b) : 1.0;
  for (int i = 0; i < n; ++i) {
    const double x = a + (b - a) * i / (n - 1);
    s.x.push_back(x);
    s.linear.push_back(m.apply(fitted, channel, x * fitted.full_scale) / top);
    if (grey) s.grey_based.push_back(polyval(fitted.grey_coefficients[channel], x) / grey_top);
  }
  return s;
}

// ---- JSON ----------------------------------------------------------------------------------------

namespace linearisation_detail {

json::Value strings_json(const std::vector<std::string>& v) {
  json::Value a = json::Value::array();
  for (const auto& s : v) a.push(s);
  return a;
}

std::vector<std::string> strings_from_json(const json::Value& a, const std::string& what) {
  if (!a.is_array()) throw Error(ErrorCode::ProfileInvalid, what + " must be an array");
  std::vector<std::string> out;
  for (const auto& e : a.as_array()) {
    if (!e.is_string()) throw Error(ErrorCode::ProfileInvalid, what + " must hold strings");
    out.push_back(e.as_string());
  }
  return out;
}

}  // namespace linearisation_detail

namespace {

using linearisation_detail::strings_json;

[[noreturn]] void invalid(const std::string& what) {
  throw Error(ErrorCode::ProfileInvalid, "linearisation: " + what);
}

const json::Value& field(const json::Value& o, const std::string& key) {
  const json::Value* v = o.find(key);
  if (!v) invalid("missing field '" + key + "'");
  return *v;
}

std::vector<std::string> strings_of(const json::Value& o, const std::string& key) {
  return linearisation_detail::strings_from_json(field(o, key), "linearisation: '" + key + "'");
}

std::array<std::vector<double>, 3> triple_of(const json::Value& o, const std::string& key) {
  const json::Value& a = field(o, key);
  if (!a.is_array() || a.size() != 3) invalid("'" + key + "' must be an array of 3 arrays");
  std::array<std::vector<double>, 3> out;
  for (int c = 0; c < 3; ++c) {
    const json::Value& e = a.as_array()[static_cast<size_t>(c)];
    if (!e.is_array()) invalid("'" + key + "' must be an array of 3 arrays");
    for (const auto& v : e.as_array()) {
      if (!v.is_number() || !std::isfinite(v.as_number())) invalid("'" + key + "' must hold finite numbers");
      out[static_cast<size_t>(c)].push_back(v.as_number());
    }
  }
  return out;
}

}  // namespace

namespace fields {
TRISTIM_FIELDS_DEFINE(Extrapolation, member<&Extrapolation::patch>("patch"), member<&Extrapolation::channel>("channel"),
               member<&Extrapolation::x>("x"), member<&Extrapolation::bound>("bound"),
               member<&Extrapolation::relative>("relative"));
}  // namespace fields

json::Value linearisation_json(const Linearisation& l) {
  json::Value o = json::Value::object();
  o.set("method", l.choice.method);
  json::Value p = json::Value::object(), s = json::Value::object();
  for (const auto& [k, v] : l.choice.parameters) p.set(k, v);
  for (const auto& [k, v] : l.choice.settings) s.set(k, v);
  o.set("parameters", p);
  o.set("settings", s);
  o.set("full_scale", l.full_scale);
  json::Value coef = json::Value::array(), dom = json::Value::array(), grey = json::Value::array(),
              r2 = json::Value::array();
  for (int c = 0; c < 3; ++c) {
    coef.push(json::Value(l.coefficients[c]));
    dom.push(json::Value(std::vector<double>{l.domain[c][0], l.domain[c][1]}));
    grey.push(json::Value(l.grey_coefficients[c]));
    r2.push(std::isfinite(l.r_squared[c]) ? json::Value(l.r_squared[c]) : json::Value(nullptr));
  }
  o.set("coefficients", coef);
  o.set("domain", dom);
  o.set("r_squared", r2);
  o.set("fitted", strings_json(l.fitted));
  o.set("greys", strings_json(l.greys));
  o.set("grey_reason", l.grey_reason);
  o.set("grey_coefficients", grey);
  o.set("monotonic", l.monotonic);
  o.set("message", l.message);
  if (!l.extrapolated.empty()) o.set("extrapolated", fields::write(l.extrapolated));  // other rows: unchanged JSON
  return o;
}

Linearisation linearisation_from_json(const json::Value& o) {
  if (!o.is_object()) invalid("not a JSON object");
  Linearisation l;
  const json::Value& method = field(o, "method");
  if (!method.is_string()) invalid("'method' must be a string");
  MethodChoice choice;
  choice.method = method.as_string();
  const json::Value& p = field(o, "parameters");
  const json::Value& s = field(o, "settings");
  if (!p.is_object() || !s.is_object()) invalid("'parameters' and 'settings' must be objects");
  for (const auto& [k, v] : p.members()) {
    if (!v.is_number()) invalid("parameter '" + k + "' must be a number");
    choice.parameters[k] = v.as_number();
  }
  for (const auto& [k, v] : s.members()) {
    if (!v.is_string()) invalid("setting '" + k + "' must be a string");
    choice.settings[k] = v.as_string();
  }
  l.choice = complete_choice(linearisation_method(choice.method).info, choice);
  const json::Value& fs = field(o, "full_scale");
  if (!fs.is_number() || !(fs.as_number() > 0) || !std::isfinite(fs.as_number())) invalid("'full_scale' must be > 0");
  l.full_scale = fs.as_number();
  l.coefficients = triple_of(o, "coefficients");
  const auto dom = triple_of(o, "domain");
  for (int c = 0; c < 3; ++c) {
    if (dom[c].size() != 2) invalid("'domain' must hold 3 pairs");
    l.domain[c] = {dom[c][0], dom[c][1]};
  }
  const json::Value& r2 = field(o, "r_squared");
  if (!r2.is_array() || r2.size() != 3) invalid("'r_squared' must have 3 entries");
  for (int c = 0; c < 3; ++c) {
    const json::Value& v = r2.as_array()[static_cast<size_t>(c)];
    if (v.is_null()) continue;
    if (!v.is_number()) invalid("'r_squared' must hold numbers or null");
    l.r_squared[c] = v.as_number();
  }
  l.fitted = strings_of(o, "fitted");
  l.greys = strings_of(o, "greys");
  const json::Value& reason = field(o, "grey_reason");
  if (!reason.is_string()) invalid("'grey_reason' must be a string");
  l.grey_reason = reason.as_string();
  l.grey_coefficients = triple_of(o, "grey_coefficients");
  const json::Value& mono = field(o, "monotonic");
  if (!mono.is_bool()) invalid("'monotonic' must be true or false");
  l.monotonic = mono.as_bool();
  const json::Value& msg = field(o, "message");
  if (!msg.is_string()) invalid("'message' must be a string");
  l.message = msg.as_string();
  if (const json::Value* e = o.find("extrapolated"))
    fields::read(*e, l.extrapolated, fields::Context{ErrorCode::ProfileInvalid, "linearisation: "}, "extrapolated");
  // A curve that needs coefficients must have them.
  const std::string& id = l.choice.method;
  if (id != "identity" && id != "sRGB")
    for (int c = 0; c < 3; ++c)
      if (l.coefficients[c].empty()) invalid("'coefficients' of channel " + std::to_string(c) + " are empty");
  return l;
}

}  // namespace tristim
