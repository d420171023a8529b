// The linearisation table, its dispatcher, application to patches and images, plot samples and
// the JSON form of a fitted linearisation.
#include "tristim/linearisation/linearisation.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "rows.hpp"
#include "../table_lookup.hpp"
#include "tristim/profile/fields.hpp"
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

// ---- JSON: the field lists --------------------------------------------------------------------

namespace fields {

TRISTIM_FIELDS_DEFINE(Extrapolation, member<&Extrapolation::patch>("patch"), member<&Extrapolation::channel>("channel"),
               member<&Extrapolation::x>("x"), member<&Extrapolation::bound>("bound"),
               member<&Extrapolation::relative>("relative"));

namespace {

using L = Linearisation;

json::Value choice_parameters(const L& l) { return parameters_json(l.choice); }
void read_choice_parameters(const json::Value& v, L& l, const Context& c, const std::string& p) {
  read_parameters(v, l.choice, c, p);
}
/// R² per channel: null where there is nothing to compare with (NaN), in any reader's context.
json::Value r_squared_json(const L& l) {
  json::Value a = json::Value::array();
  for (double r : l.r_squared) a.push(std::isfinite(r) ? json::Value(r) : json::Value());
  return a;
}
void read_r_squared(const json::Value& v, L& l, const Context& c, const std::string& p) {
  Context nan = c;
  nan.null_is_nan = true;
  read(v, l.r_squared, nan, p);
}
bool has_extrapolated(const L& l) { return !l.extrapolated.empty(); }
bool has_grey_based(const CurveSamples& s) { return !s.grey_based.empty(); }

}  // namespace

// The order is the JSON's (profiles and spectral models embed it: pinned bytes).
TRISTIM_FIELDS_DEFINE(Linearisation, nested<&L::choice, &MethodChoice::method>("method"),
                      Field<L>{"parameters", choice_parameters, read_choice_parameters},
                      nested<&L::choice, &MethodChoice::settings>("settings"), member<&L::full_scale>("full_scale"),
                      member<&L::coefficients>("coefficients"), member<&L::domain>("domain"),
                      Field<L>{"r_squared", r_squared_json, read_r_squared},
                      member<&L::fitted>("fitted"), member<&L::greys>("greys"), member<&L::grey_reason>("grey_reason"),
                      member<&L::grey_coefficients>("grey_coefficients"), member<&L::monotonic>("monotonic"),
                      member<&L::message>("message"),
                      with_shown(member<&L::extrapolated>("extrapolated", false), has_extrapolated));

TRISTIM_FIELDS_DEFINE(CurveSamples, member<&CurveSamples::x>("x"), member<&CurveSamples::linear>("linear"),
                      with_shown(member<&CurveSamples::grey_based>("grey_based", false), has_grey_based));

void Checks<Linearisation>::check(Linearisation& l, const Context& c, const std::string& p) {
  l.choice = complete_choice(linearisation_method(l.choice.method).info, l.choice);
  if (!(l.full_scale > 0)) c.refuse("'" + join(p, "full_scale") + "' must be > 0");
  // A curve that needs coefficients must have them.
  const std::string& id = l.choice.method;
  if (id != "identity" && id != "sRGB")
    for (int ch = 0; ch < 3; ++ch)
      if (l.coefficients[ch].empty())
        c.refuse("'" + join(p, "coefficients") + "' of channel " + std::to_string(ch) + " are empty");
}

}  // namespace fields

json::Value linearisation_json(const Linearisation& l) { return fields::write(l); }

Linearisation linearisation_from_json(const json::Value& o) {
  return linearisation_detail::read_fields<Linearisation>(o, "linearisation: ");
}

}  // namespace tristim
