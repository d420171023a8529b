// Share links and project files: see tristim/share/link.hpp and docs/link-format.md.
#include "tristim/share/link.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "tristim/absolute/profile.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/chart/light_trap.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/share/sha256.hpp"
#include "tristim/version.hpp"

namespace tristim {
namespace {

constexpr const char* kFragmentKey = "tristim=";
constexpr std::size_t kCheckBytes = 12;  ///< leading bytes of SHA-256(payload JSON) after the last '.'
constexpr int kCoefficientDigits = 10, kMetricDigits = 6;

/// The recipe a v1 link's "recipe" is an RFC 7386 merge patch against: the default recipe as
/// tristim 0.1.0 completes it, pinned here (and in docs/link-format.md) so that a later change of
/// a default never changes what an old link means.
constexpr const char* kBaseRecipeV1 =
    R"({"format":"tristim-recipe","version":1,"reference":{"chart":"cc24","data_digest":"","illuminant":"D50",)"
    R"("observer":"1931"},"capture":{"dark_frames":0,"dark_mode":"per_pixel","flat_field":false,"falloff":false,)"
    R"("saturation":0,"noise_floor":0},"sampling":{"layout":{"chart":"cc24","rows":0,"columns":0,"margins":[0,0,0,0],)"
    R"("gap":-1},"corners":[0,0,0,0,0,0,0,0],"area":0.5,"exclude":[],"exclude_flagged":false},"linearisation":)"
    R"({"method":"identity","parameters":{},"settings":{}},"surface":{"method":"none","parameters":{},"settings":{}},)"
    R"("characterisation":{"model":"matrix-3x3","objective":{"method":"ls","parameters":{},"settings":{}},)"
    R"("white_patch":"","lab_white":[96.4212,100,82.5188]},"evaluation":{"leave_one_out":true,"held_out_digest":""}})";

bool same(const json::Value& a, const json::Value& b) { return a.dump() == b.dump(); }

/// The RFC 7386 merge patch that turns `base` into `target`.
json::Value merge_diff(const json::Value& base, const json::Value& target) {
  if (!base.is_object() || !target.is_object()) return target;
  json::Value patch = json::Value::object();
  for (const auto& [k, v] : target.members()) {
    const json::Value* b = base.find(k);
    if (b && same(*b, v)) continue;
    patch.set(k, b && b->is_object() && v.is_object() ? merge_diff(*b, v) : v);
  }
  for (const auto& [k, v] : base.members())
    if (!target.find(k)) patch.set(k, nullptr);
  return patch;
}

/// RFC 7386 MergePatch(target, patch).
json::Value merge_apply(const json::Value& target, const json::Value& patch) {
  if (!patch.is_object()) return patch;
  json::Value out = json::Value::object();
  if (target.is_object())
    for (const auto& [k, v] : target.members()) {
      const json::Value* p = patch.find(k);
      if (!p) out.set(k, v);
      else if (!p->is_null()) out.set(k, merge_apply(v, *p));
    }
  for (const auto& [k, v] : patch.members())
    if (!(target.is_object() && target.find(k)) && !v.is_null()) out.set(k, merge_apply(json::Value(), v));
  return out;
}

/// Patch values after the JSON: IEEE-754 doubles, little-endian.
void put_f64(std::string& out, double v) {
  std::uint64_t u;
  std::memcpy(&u, &v, 8);
  for (int i = 0; i < 8; ++i) out += static_cast<char>((u >> (8 * i)) & 0xff);
}
double get_f64(std::string_view in, std::size_t at) {
  std::uint64_t u = 0;
  for (int i = 0; i < 8; ++i) u |= std::uint64_t(static_cast<std::uint8_t>(in[at + i])) << (8 * i);
  double v;
  std::memcpy(&v, &u, 8);
  return v;
}

[[noreturn]] void bad(const std::string& message) { throw Error(ErrorCode::ParseError, "share payload: " + message); }

bool inline_reference(const Recipe& recipe) { return share_inline_reference(recipe); }

// ---- results as text lines -------------------------------------------------------------------

/// A value's text: numbers to `digits` significant digits (printf %.*g, correctly rounded in both
/// builds), strings as they are, arrays and objects as their values in order, space-separated.
void append_values(std::string& out, const json::Value& v, int digits) {
  switch (v.type()) {
    case json::Value::Type::Number: {
      const double d = v.as_number();
      char buf[40];
      if (!std::isfinite(d)) std::snprintf(buf, sizeof buf, "null");
      else std::snprintf(buf, sizeof buf, "%.*g", digits, d);
      out += (out.empty() || out.back() == ' ') ? "" : " ";
      out += buf;
      break;
    }
    case json::Value::Type::String: out += (out.empty() ? "" : " ") + v.as_string(); break;
    case json::Value::Type::Bool: out += std::string(out.empty() ? "" : " ") + (v.as_bool() ? "true" : "false"); break;
    case json::Value::Type::Null: out += std::string(out.empty() ? "" : " ") + "null"; break;
    case json::Value::Type::Array:
      for (const auto& e : v.as_array()) append_values(out, e, digits);
      break;
    case json::Value::Type::Object:
      for (const auto& [k, e] : v.members()) append_values(out, e, digits);
      break;
  }
}

const json::Value* at_path(const json::Value& root, const std::string& path) {
  const json::Value* v = &root;
  std::size_t start = 0;
  while (v && start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    v = v->is_object() ? v->find(key) : nullptr;
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return v;
}

struct ResultsWriter {
  const json::Value& root;
  std::string text;
  /// One line "name values" for the value at `path` (skipped when absent or null).
  /// keys: only these members of an object, in this order.
  void line(const std::string& name, const std::string& path, int digits, const std::vector<const char*>& keys = {}) {
    const json::Value* v = at_path(root, path);
    if (!v || v->is_null()) return;
    std::string values;
    if (keys.size() == 0) append_values(values, *v, digits);
    for (const char* k : keys)
      if (const json::Value* e = v->is_object() ? v->find(k) : nullptr) append_values(values, *e, digits);
    text += name + " " + values + "\n";
  }
  ShareResults done() const { return {text, "sha256:" + sha256_hex(text)}; }
};

std::vector<std::pair<std::string, std::string>> result_lines(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    const std::size_t sp = line.find(' ');
    out.emplace_back(line.substr(0, sp), sp == std::string::npos ? "" : line.substr(sp + 1));
    start = end + 1;
  }
  return out;
}

// ---- JSON fields -------------------------------------------------------------------------------

const json::Value& field(const json::Value& o, const char* key, const std::string& where) {
  const json::Value* v = o.find(key);
  if (!v) bad(where + ": missing field '" + key + "'");
  return *v;
}

const std::string& text_field(const json::Value& o, const char* key, const std::string& where) {
  const json::Value& v = field(o, key, where);
  if (!v.is_string()) bad(where + "." + key + " must be a string");
  return v.as_string();
}

PatchMatrix rows_of(const json::Value& v, const std::string& where, std::size_t n) {
  if (!v.is_array()) bad(where + " must be an array of numbers");
  std::vector<double> d;
  for (std::size_t i = 0; i < v.as_array().size(); ++i) {
    const json::Value& e = v.as_array()[i];
    if (!e.is_number() || !std::isfinite(e.as_number())) bad(where + "[" + std::to_string(i) + "] must be a finite number");
    d.push_back(e.as_number());
  }
  if (d.size() != 3 * n) bad(where + " must hold 3 numbers per patch (" + std::to_string(3 * n) + "), got " + std::to_string(d.size()));
  PatchMatrix m(static_cast<Eigen::Index>(n), 3);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) m(static_cast<Eigen::Index>(i), c) = d[3 * i + c];
  return m;
}

std::vector<double> flat(const PatchMatrix& m) {
  std::vector<double> d;
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (int c = 0; c < 3; ++c) d.push_back(m(i, c));
  return d;
}

/// `what` of version `got`, where this tristim reads `reads`.
std::string version_error(const std::string& what, const std::string& got, const std::string& reads) {
  return what + " version " + got + "; this tristim (" + std::string(kVersion) + ") reads " + reads;
}

struct ZStream {
  z_stream s{};
  bool inflating;
  ZStream(bool inflate_mode, std::string_view dictionary) : inflating(inflate_mode) {
    const int rc = inflating ? inflateInit2(&s, -15) : deflateInit2(&s, 9, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY);
    if (rc != Z_OK) throw Error(ErrorCode::Internal, "zlib could not start");
    if (dictionary.empty()) return;  // raw streams take their preset dictionary right after init
    const auto* d = reinterpret_cast<const Bytef*>(dictionary.data());
    const auto n = static_cast<uInt>(dictionary.size());
    if ((inflating ? inflateSetDictionary(&s, d, n) : deflateSetDictionary(&s, d, n)) != Z_OK) {
      inflating ? inflateEnd(&s) : deflateEnd(&s);
      throw Error(ErrorCode::Internal, "zlib refused the preset dictionary");
    }
  }
  ~ZStream() { inflating ? inflateEnd(&s) : deflateEnd(&s); }
};

}  // namespace

// ---- results -------------------------------------------------------------------------------------

namespace {

/// One results line: its name, the profile JSON path it reads, its digits and (for an object)
/// the members it keeps, in order.
struct ResultLine {
  std::string name, path;
  int digits;
  std::vector<const char*> keys;
};

ShareResults results_of(const json::Value& profile, const std::vector<ResultLine>& lines) {
  ResultsWriter w{profile, {}};
  for (const auto& l : lines) w.line(l.name, l.path, l.digits, l.keys);
  return w.done();
}

const std::vector<const char*> kSummary = {"mean", "median", "p95", "max"};

}  // namespace

ShareResults share_results(const Profile& profile) {
  std::vector<ResultLine> lines = {{"model", "model.id", kCoefficientDigits, {}},
                                   {"objective", "objective", kCoefficientDigits, {}},
                                   {"status", "fit.status", kCoefficientDigits, {}},
                                   {"coefficients", "model.coefficients", kCoefficientDigits, {}},
                                   {"linearisation", "linearisation", kCoefficientDigits, {}}};
  for (const std::string s : {"training", "loo"}) {
    lines.push_back({s + ".dE00", "metrics." + s + ".dE00", kMetricDigits, kSummary});
    lines.push_back({s + ".dE76.mean", "metrics." + s + ".dE76.mean", kMetricDigits, {}});
    lines.push_back({s + ".dE94.mean", "metrics." + s + ".dE94.mean", kMetricDigits, {}});
  }
  return results_of(json::parse(profile_to_json(profile)), lines);
}

ShareResults share_results(const AbsoluteProfile& profile) {
  return results_of(absolute_profile_json(profile),
                    {{"transform", "colour.transform", kCoefficientDigits, {}},
                     {"status", "colour.status", kCoefficientDigits, {}},
                     {"coefficients", "colour.coefficients", kCoefficientDigits, {}},
                     {"k", "linearisation.k", kCoefficientDigits, {}},
                     {"noise_floor", "normalisation.noise_floor", kCoefficientDigits, {}},
                     {"saturation", "normalisation.saturation", kCoefficientDigits, {}},
                     {"areas", "normalisation.areas", kCoefficientDigits, {}},
                     {"training.dE94", "training.figures.metrics.dE94", kMetricDigits, kSummary},
                     {"training.dE00", "training.figures.metrics.dE00", kMetricDigits, kSummary},
                     {"training.relative_Y_error", "training.figures.relative_Y_error", kMetricDigits, {}}});
}

// ---- payloads ------------------------------------------------------------------------------------

SharePayload share_payload(const Characterisation& c, const TrainingSet& training, const std::vector<ShareSource>& sources) {
  SharePayload p;
  p.tristim_version = kVersion;
  p.kind = "relative";
  p.recipe = c.recipe;
  p.labels = training.labels;
  p.camera_RGB = training.camera_RGB;
  if (inline_reference(c.recipe)) p.reference_XYZ = training.reference_XYZ;
  p.sources = sources;
  p.expected = share_results(c.profile);
  return p;
}

SharePayload share_payload(const AbsoluteCharacterisation& c) {
  const AbsoluteInputs& in = c.recipe.inputs;
  if (!in.bracket.empty() || !in.lens_cap.empty() || !in.flat.empty())
    throw Error(ErrorCode::InvalidArgument,
                "the absolute recipe names RAW frames (bracket, lens cap or flat), which a link does not carry: "
                "share a project file");
  for (const auto& row : in.stimuli)
    if (row.region())
      throw Error(ErrorCode::InvalidArgument, stimulus_where(row) + " is a region of '" + row.file +
                                                  "', which a link does not carry: share a project file");
  SharePayload p;
  p.tristim_version = kVersion;
  p.kind = "absolute";
  p.absolute = c.recipe;
  p.expected = share_results(c.profile);
  return p;
}

json::Value share_payload_json(const SharePayload& p) {
  json::Value o = fields::object({{"format", "tristim-link"}, {"version", p.version},
                                  {"tristim_version", p.tristim_version}, {"kind", p.kind}});
  if (p.kind == "absolute") {
    o.set("recipe", absolute_recipe_json(p.absolute));
  } else {
    o.set("recipe", recipe_json(p.recipe));
    json::Value ids = json::Value::array();
    for (const auto& id : p.labels) ids.push(id);
    json::Value patches = fields::object({{"ids", ids}, {"RGB", json::Value(flat(p.camera_RGB))}});
    if (p.reference_XYZ.rows() > 0) patches.set("XYZ", json::Value(flat(p.reference_XYZ)));
    o.set("patches", patches);
  }
  json::Value sources = json::Value::array();
  for (const auto& s : p.sources) sources.push(fields::object({{"name", s.name}, {"sha256", s.sha256}}));
  o.set("sources", sources);
  o.set("expected", fields::object({{"digest", p.expected.digest}, {"results", p.expected.text}}));
  return o;
}

SharePayload share_payload_from_json(const json::Value& o) {
  if (!o.is_object()) bad("must be a JSON object");
  json::reject_unknown(o, {"format", "version", "tristim_version", "kind", "recipe", "patches", "sources", "expected"},
                       "share payload", ErrorCode::ParseError);
  if (text_field(o, "format", "payload") != "tristim-link") bad("\"format\" must be \"tristim-link\"");
  const json::Value& ver = field(o, "version", "payload");
  if (!ver.is_number()) bad("\"version\" must be a number");
  if (ver.as_number() != kPayloadVersion)
    throw Error(ErrorCode::ProfileVersion, version_error("link payload document", json::number_text(ver.as_number()), "version 1"));
  SharePayload p;
  p.tristim_version = text_field(o, "tristim_version", "payload");
  p.kind = text_field(o, "kind", "payload");
  if (p.kind == "relative") {
    p.recipe = recipe_from_json(field(o, "recipe", "payload"));
    const json::Value& patches = field(o, "patches", "payload");
    if (!patches.is_object()) bad("patches must be an object");
    json::reject_unknown(patches, {"ids", "RGB", "XYZ"}, "share payload patches", ErrorCode::ParseError);
    const json::Value& ids = field(patches, "ids", "patches");
    if (!ids.is_array() || ids.as_array().empty()) bad("patches.ids must be a non-empty array of strings");
    for (const auto& id : ids.as_array()) {
      if (!id.is_string()) bad("patches.ids must be strings");
      p.labels.push_back(id.as_string());
    }
    p.camera_RGB = rows_of(field(patches, "RGB", "patches"), "patches.RGB", p.labels.size());
    const bool builtin = !inline_reference(p.recipe);
    if (const json::Value* xyz = patches.find("XYZ")) {
      if (builtin) bad("patches.XYZ is only for a recipe whose reference is a file (this one names chart '" +
                       p.recipe.reference.chart + "')");
      p.reference_XYZ = rows_of(*xyz, "patches.XYZ", p.labels.size());
    } else if (!builtin) {
      bad("patches.XYZ missing: the recipe's reference is a file, so the link must carry it");
    }
  } else if (p.kind == "absolute") {
    if (o.find("patches")) bad("an absolute payload has no \"patches\" (its recipe's stimuli carry the data)");
    p.absolute = absolute_recipe_from_json(field(o, "recipe", "payload"));
  } else {
    bad("\"kind\" must be \"relative\" or \"absolute\", got '" + p.kind + "'");
  }
  const json::Value& sources = field(o, "sources", "payload");
  if (!sources.is_array()) bad("sources must be an array");
  for (const auto& s : sources.as_array()) {
    if (!s.is_object()) bad("sources must hold objects");
    json::reject_unknown(s, {"name", "sha256"}, "share payload source", ErrorCode::ParseError);
    ShareSource src{text_field(s, "name", "source"), text_field(s, "sha256", "source")};
    if (src.sha256.size() != 64 || src.sha256.find_first_not_of("0123456789abcdef") != std::string::npos)
      bad("source '" + src.name + "': sha256 must be 64 lower-case hex digits");
    p.sources.push_back(src);
  }
  const json::Value& expected = field(o, "expected", "payload");
  if (!expected.is_object()) bad("expected must be an object");
  json::reject_unknown(expected, {"digest", "results"}, "share payload expected", ErrorCode::ParseError);
  p.expected.digest = text_field(expected, "digest", "expected");
  p.expected.text = text_field(expected, "results", "expected");
  if (p.expected.digest != "sha256:" + sha256_hex(p.expected.text))
    bad("expected.digest is not the SHA-256 of expected.results");
  return p;
}

namespace {

/// A link's content: the payload JSON with a relative recipe as a merge patch against
/// kBaseRecipeV1 and the patches' numbers moved out of it, then (relative payloads) a NUL byte and
/// the camera RGB (and an inline reference's XYZ) as little-endian doubles, patch by patch.
std::string link_content(const SharePayload& p) {
  const json::Value full = share_payload_json(p);
  if (p.kind != "relative") return full.dump();
  json::Value o = json::Value::object();
  std::string values;
  for (const auto& [k, v] : full.members()) {
    if (k == "recipe") {
      o.set(k, merge_diff(json::parse(kBaseRecipeV1), v));
    } else if (k == "patches") {
      o.set(k, fields::object({{"ids", v.at("ids")}}));
      for (const char* m : {"RGB", "XYZ"})
        if (const json::Value* a = v.find(m))
          for (const auto& e : a->as_array()) put_f64(values, e.as_number());
    } else {
      o.set(k, v);
    }
  }
  std::string text = o.dump();
  text += '\0';
  return text + values;
}

/// The JSON before a content's NUL (all of it without one): ParseError when it is not JSON.
json::Value content_json(const std::string& content, std::size_t nul) {
  try {
    return json::parse(content.substr(0, nul));
  } catch (const Error& e) {
    if (e.code() == ErrorCode::LimitExceeded) throw;
    bad(std::string("not JSON: ") + e.what());
  }
}

/// The payload JSON (share_payload_from_json's form) of a version 1 link's content.
json::Value link_json(const std::string& content) {
  const std::size_t nul = content.find('\0');
  const json::Value o = content_json(content, nul);
  const std::string_view values = nul == std::string::npos ? std::string_view() : std::string_view(content).substr(nul + 1);
  const json::Value* kind = o.is_object() ? o.find("kind") : nullptr;
  if (!kind || !kind->is_string() || kind->as_string() != "relative") {
    if (nul != std::string::npos) bad("only a relative payload has patch values after its JSON");
    return o;
  }
  json::Value out = json::Value::object();
  for (const auto& [k, v] : o.members()) {
    if (k == "recipe") {
      if (!v.is_object()) bad("recipe must be an object (a merge patch)");
      out.set(k, merge_apply(json::parse(kBaseRecipeV1), v));
    } else if (k != "patches") {
      out.set(k, v);
    }
  }
  const json::Value* patches = o.find("patches");
  if (!patches || !patches->is_object()) bad("missing field 'patches'");
  json::reject_unknown(*patches, {"ids"}, "share payload patches", ErrorCode::ParseError);
  const json::Value& ids = field(*patches, "ids", "patches");
  if (!ids.is_array()) bad("patches.ids must be an array");
  const std::size_t n = ids.as_array().size();
  const json::Value* recipe = out.find("recipe");
  const json::Value* chart = recipe ? at_path(*recipe, "reference.chart") : nullptr;
  const bool inline_XYZ = chart && chart->is_string() && chart->as_string() == "file";
  const std::size_t count = 3 * n * (inline_XYZ ? 2 : 1);
  if (nul == std::string::npos || values.size() != 8 * count)
    bad("the patch values hold " + std::to_string(values.size()) + " bytes, not " + std::to_string(8 * count) +
        " (3 doubles per patch" + (inline_XYZ ? " for RGB and for XYZ)" : ")"));
  json::Value p = fields::object({{"ids", ids}});
  for (int part = 0; part < (inline_XYZ ? 2 : 1); ++part) {
    json::Value a = json::Value::array();
    for (std::size_t i = 0; i < 3 * n; ++i) a.push(get_f64(values, 8 * (part * 3 * n + i)));
    p.set(part == 0 ? "RGB" : "XYZ", a);
  }
  out.set("patches", p);
  return out;
}

// ---- version 2: the same document, compact -------------------------------------------------------

/// The preset dictionary of version 2 (docs/link-format.md): the base recipe, then the words a
/// link's JSON and results text usually hold, most common last (deflate reaches them cheapest).
const std::string& dictionary_v2() {
  static const std::string d = std::string(kBaseRecipeV1) +
      R"({"recipe":{"reference":{"chart":"file","illuminant":"D65","observer":"1964"},"linearisation":{"method":"Shen2008"},)"
      R"("surface":{"method":"Saunderson"},"capture":{"light_trap":[]},"exclude_flagged":true},)"
      R"("transform ","\nk ","\nnoise_floor ","\nsaturation ","\nareas ","\ntraining.dE94 ","\ntraining.relative_Y_error ",)"
      R"("tristim_version":"0.1.0","kind":"relative","recipe":{"reference":{"chart":"passport"},"sampling":{"layout":)"
      R"({"chart":"passport"},"corners":[]},"characterisation":{"model":"Finlayson2015-2","objective":{"method":"psm"},)"
      R"("white_patch":"D1"}},"sources":[".dng"],"results":["model matrix-3x3\nobjective ls\nstatus ok\ncoefficients ",)"
      R"(" "," "," ","\nlinearisation ","\ntraining.dE00 "," "," "," ","\ntraining.dE76.mean ","\ntraining.dE94.mean ",)"
      R"("\nloo.dE00 "," "," "," ","\nloo.dE76.mean ","\nloo.dE94.mean ","\n"]})";
  return d;
}

/// A number of the results text exactly as printed (printf %g, 10 or 6 significant digits):
/// value = ±m × 10^x in fixed style ("0.03176675373": m 3176675373, x −11), ±m' × 10^x with m'
/// the digits of m after the first in exponent style ("1.5e-05": m 15, x −5).
struct Decimal {
  bool negative = false, exponent_style = false;
  int x = 0;
  std::uint64_t m = 0;
};
constexpr int kMaxDecimalExponent = 400;

bool all_digits(std::string_view s) { return !s.empty() && s.find_first_not_of("0123456789") == std::string_view::npos; }

/// Reads a token like %g prints one; false for anything else (render_decimal must give it back).
bool parse_decimal(std::string_view t, Decimal& d) {
  d = Decimal{};
  if (!t.empty() && t[0] == '-') d.negative = true, t.remove_prefix(1);
  const std::size_t e = t.find('e');
  const std::string_view mant = t.substr(0, e), ipart = mant.substr(0, mant.find('.'));
  const std::string_view frac = ipart.size() < mant.size() ? mant.substr(ipart.size() + 1) : std::string_view();
  if (!all_digits(ipart) || (ipart.size() < mant.size() && !all_digits(frac))) return false;
  std::string digits = std::string(ipart) + std::string(frac);
  digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size()));
  if (digits.size() > 18) return false;
  for (char c : digits) d.m = d.m * 10 + std::uint64_t(c - '0');
  if (e == std::string_view::npos) {
    d.x = -static_cast<int>(frac.size());
    return frac.size() <= static_cast<std::size_t>(kMaxDecimalExponent);
  }
  const std::string_view ex = t.substr(e + 1);
  if (ipart.size() != 1 || ex.size() < 3 || ex.size() > 4 || (ex[0] != '+' && ex[0] != '-') || !all_digits(ex.substr(1))) return false;
  d.exponent_style = true;
  d.x = std::stoi(std::string(ex.substr(1))) * (ex[0] == '-' ? -1 : 1);
  return std::abs(d.x) <= kMaxDecimalExponent;
}

std::string render_decimal(const Decimal& d) {
  std::string s = std::to_string(d.m);
  if (d.exponent_style) {
    char ex[16];
    std::snprintf(ex, sizeof ex, "e%c%02d", d.x < 0 ? '-' : '+', std::abs(d.x));
    s = s.substr(0, 1) + (s.size() > 1 ? "." + s.substr(1) : "") + ex;
  } else if (d.x >= 0) {
    s.append(static_cast<std::size_t>(d.x), '0');
  } else {
    const std::size_t k = static_cast<std::size_t>(-d.x);
    if (s.size() < k + 1) s.insert(0, k + 1 - s.size(), '0');
    s.insert(s.size() - k, ".");
  }
  return (d.negative ? "-" : "") + s;
}

void put_varint(std::string& out, std::uint64_t v) {
  for (; v >= 0x80; v >>= 7) out += static_cast<char>((v & 0x7f) | 0x80);
  out += static_cast<char>(v);
}

/// Reads a content's binary part in order; every read is bounded.
struct Cursor {
  std::string_view bytes;
  std::size_t at = 0;
  std::string_view take(std::size_t n, const char* what) {
    if (n > bytes.size() - at) bad(std::string("the binary part ends inside ") + what);
    at += n;
    return bytes.substr(at - n, n);
  }
  std::uint64_t varint(const char* what) {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      const auto b = static_cast<std::uint8_t>(take(1, what)[0]);
      if (shift == 63 && b > 1) break;
      v |= std::uint64_t(b & 0x7f) << shift;
      if (!(b & 0x80)) return v;
    }
    bad(std::string(what) + ": a number beyond 64 bits");
  }
};

/// Bytes [from, to) (big-endian: 0 is the most significant) of every value, byte by byte: plane k
/// holds byte k of each value in turn, so that bytes alike (exponents, leading zeros) sit together.
std::string planes(const std::vector<std::uint64_t>& values, int from, int to) {
  std::string out;
  for (int k = from; k < to; ++k)
    for (const std::uint64_t v : values) out += static_cast<char>((v >> (8 * (7 - k))) & 0xff);
  return out;
}
void unplane(std::vector<std::uint64_t>& values, std::string_view bytes, int from, int to) {
  for (int k = from; k < to; ++k)
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] |= std::uint64_t(static_cast<std::uint8_t>(bytes[(k - from) * values.size() + i])) << (8 * (7 - k));
}
constexpr int kMantissaHighPlanes = 4, kDoubleHighPlanes = 2;  ///< the compressible leading bytes

/// A relative payload's patches in the order of its built-in chart: the labels a link leaves out.
/// The writer (`writing`) keeps the ids when the chart cannot be made; the reader says why.
std::vector<std::string> chart_labels(const Recipe& recipe, bool writing) {
  if (inline_reference(recipe)) return {};
  try {
    return recipe_reference(recipe).labels;
  } catch (const Error&) {
    if (writing) return {};
    throw;
  }
}

std::string hex_bytes(std::string_view hex) {
  std::string out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) out += static_cast<char>(std::stoi(std::string(hex.substr(i, 2)), nullptr, 16));
  return out;
}

/// Version 2 content: JSON NUL binary (docs/link-format.md). `tail`: where its incompressible part
/// (the SHA-256s and the values' low bytes) starts.
std::string link_content_v2(const SharePayload& p, std::size_t& tail) {
  json::Value o = fields::object({{"tristim_version", p.tristim_version}, {"kind", p.kind}});
  std::string bin;
  if (p.kind == "absolute") {
    o.set("recipe", absolute_recipe_json(p.absolute));
  } else {
    o.set("recipe", merge_diff(json::parse(kBaseRecipeV1), recipe_json(p.recipe)));
    if (p.labels != chart_labels(p.recipe, true)) {
      json::Value ids = json::Value::array();
      for (const auto& id : p.labels) ids.push(id);
      o.set("ids", ids);
    }
  }
  json::Value names = json::Value::array();
  for (const auto& s : p.sources) {
    if (s.sha256.size() != 64 || s.sha256.find_first_not_of("0123456789abcdef") != std::string::npos)
      throw Error(ErrorCode::InvalidArgument, "source '" + s.name + "': sha256 must be 64 lower-case hex digits");
    names.push(s.name);
    bin += hex_bytes(s.sha256);
  }
  o.set("sources", names);
  // The results text with its numbers cut out (parts), the numbers as exact decimals.
  json::Value parts = json::Value::array();
  std::string part, heads;
  std::vector<std::uint64_t> mantissas;
  const std::string& text = p.expected.text;
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == ' ' || text[i] == '\n') { part += text[i++]; continue; }
    const std::size_t j = std::min(text.find_first_of(" \n", i), text.size());
    const std::string_view token = std::string_view(text).substr(i, j - i);
    Decimal d;
    if (parse_decimal(token, d) && render_decimal(d) == token) {
      parts.push(part);
      part.clear();
      const std::uint64_t zigzag = d.x < 0 ? 2 * std::uint64_t(-d.x) - 1 : 2 * std::uint64_t(d.x);
      put_varint(heads, zigzag << 2 | std::uint64_t(d.exponent_style) << 1 | std::uint64_t(d.negative));
      mantissas.push_back(d.m);
    } else {
      part += token;
    }
    i = j;
  }
  parts.push(part);
  o.set("results", parts);
  std::vector<std::uint64_t> doubles;
  if (p.kind == "relative") {
    std::vector<double> values = flat(p.camera_RGB), xyz = flat(p.reference_XYZ);
    values.insert(values.end(), xyz.begin(), xyz.end());
    for (const double v : values) {
      std::uint64_t u;
      std::memcpy(&u, &v, 8);
      doubles.push_back(u);
    }
  }
  // The compressible part first; the SHA-256s and the low bytes (all but incompressible) last,
  // where encode_share_payload ends a deflate block so that they get a block of their own.
  const std::string head = o.dump() + '\0' + heads + planes(mantissas, 0, kMantissaHighPlanes) + planes(doubles, 0, kDoubleHighPlanes);
  tail = head.size();
  return head + bin + planes(mantissas, kMantissaHighPlanes, 8) + planes(doubles, kDoubleHighPlanes, 8);
}

/// The payload JSON document (share_payload_from_json's form) of version 2 content.
json::Value link_json_v2(const std::string& content) {
  const std::size_t nul = content.find('\0');
  if (nul == std::string::npos) bad("no binary part after the JSON");
  const json::Value o = content_json(content, nul);
  if (!o.is_object()) bad("must be a JSON object");
  json::reject_unknown(o, {"tristim_version", "kind", "recipe", "ids", "sources", "results"}, "share payload", ErrorCode::ParseError);
  const std::string& kind = text_field(o, "kind", "payload");
  json::Value out = fields::object({{"format", "tristim-link"}, {"version", kPayloadVersion},
                                    {"tristim_version", field(o, "tristim_version", "payload")}, {"kind", kind}});
  const json::Value& recipe = field(o, "recipe", "payload");
  std::size_t patches = 0, doubles = 0;
  json::Value ids = json::Value::array();
  if (kind == "relative") {
    if (!recipe.is_object()) bad("recipe must be an object (a merge patch)");
    out.set("recipe", merge_apply(json::parse(kBaseRecipeV1), recipe));
    const Recipe r = recipe_from_json(out.at("recipe"));
    if (const json::Value* given = o.find("ids")) {
      if (!given->is_array()) bad("ids must be an array of strings");
      ids = *given;
    } else {
      if (inline_reference(r)) bad("\"ids\" missing: the recipe's reference is a file (or several images), so the link must name its patches");
      for (const auto& label : chart_labels(r, false)) ids.push(label);
    }
    patches = ids.as_array().size();
    doubles = 3 * patches * (inline_reference(r) ? 2 : 1);
  } else {
    if (o.find("ids")) bad("only a relative payload has \"ids\"");
    out.set("recipe", recipe);
  }
  const json::Value& names = field(o, "sources", "payload");
  if (!names.is_array()) bad("sources must be an array of names");
  const json::Value& parts = field(o, "results", "payload");
  if (!parts.is_array() || parts.as_array().empty()) bad("results must be a non-empty array of strings");
  const std::size_t n = parts.as_array().size() - 1;
  // The binary part: heads, high planes, SHA-256s, low planes (link_content_v2).
  Cursor in{std::string_view(content).substr(nul + 1)};
  if (n > in.bytes.size() || doubles > in.bytes.size() || 32 * names.as_array().size() > in.bytes.size())
    bad("the binary part is shorter than the JSON announces");
  std::vector<Decimal> numbers(n);
  for (auto& d : numbers) {
    const std::uint64_t head = in.varint("the results' numbers");
    d.negative = head & 1;
    d.exponent_style = head & 2;
    const std::uint64_t zigzag = head >> 2;
    if (zigzag > 2 * kMaxDecimalExponent) bad("results: a number's exponent beyond " + std::to_string(kMaxDecimalExponent));
    d.x = zigzag & 1 ? -static_cast<int>((zigzag + 1) / 2) : static_cast<int>(zigzag / 2);
  }
  std::vector<std::uint64_t> mantissas(n), bits(doubles);
  unplane(mantissas, in.take(n * kMantissaHighPlanes, "the results' numbers"), 0, kMantissaHighPlanes);
  unplane(bits, in.take(doubles * kDoubleHighPlanes, "the patch values"), 0, kDoubleHighPlanes);
  json::Value sources = json::Value::array();
  for (const auto& name : names.as_array()) {
    if (!name.is_string()) bad("sources must be an array of names");
    std::string hex;
    for (char c : in.take(32, "the sources' SHA-256")) {
      char b[3];
      std::snprintf(b, sizeof b, "%02x", static_cast<unsigned>(static_cast<std::uint8_t>(c)));
      hex += b;
    }
    sources.push(fields::object({{"name", name}, {"sha256", hex}}));
  }
  unplane(mantissas, in.take(n * (8 - kMantissaHighPlanes), "the results' numbers"), kMantissaHighPlanes, 8);
  const std::size_t left = in.bytes.size() - in.at;
  if (left != doubles * (8 - kDoubleHighPlanes))
    bad("the patch values hold " + std::to_string(kDoubleHighPlanes * doubles + left) + " bytes, not " +
        std::to_string(8 * doubles) + " (3 doubles per patch" + (doubles > 3 * patches ? " for RGB and for XYZ)" : ")"));
  unplane(bits, in.take(left, "the patch values"), kDoubleHighPlanes, 8);
  std::string text;
  for (std::size_t i = 0; i <= n; ++i) {
    if (!parts.as_array()[i].is_string()) bad("results must be an array of strings");
    text += parts.as_array()[i].as_string();
    if (i < n) {
      numbers[i].m = mantissas[i];
      text += render_decimal(numbers[i]);
    }
    if (text.size() > kMaxLinkInflatedBytes) throw Error(ErrorCode::LimitExceeded, "share payload: results text beyond 1 MiB");
  }
  if (kind == "relative") {
    json::Value patch_values = fields::object({{"ids", ids}});
    for (std::size_t part = 0; 3 * patches * part < doubles; ++part) {
      json::Value a = json::Value::array();
      for (std::size_t i = 0; i < 3 * patches; ++i) {
        double v;
        std::memcpy(&v, &bits[part * 3 * patches + i], 8);
        a.push(v);
      }
      patch_values.set(part == 0 ? "RGB" : "XYZ", a);
    }
    out.set("patches", patch_values);
  }
  out.set("sources", sources);
  out.set("expected", fields::object({{"digest", "sha256:" + sha256_hex(text)}, {"results", text}}));
  return out;
}

/// Twelve leading bytes of SHA-256(bytes).
std::string check_of(std::string_view bytes) {
  Sha256 h;
  h.update(bytes);
  const auto sum = h.digest();
  return std::string(reinterpret_cast<const char*>(sum.data()), kCheckBytes);
}

/// "<version>." base64url(deflate-raw) "." base64url(check). Version 1's check is over the content;
/// version 2's over the compressed bytes, so that no character can change unnoticed, not even one
/// in bits deflate ignores (a block's padding).
std::string link_text(int version, const std::string& content, std::string_view dictionary, std::size_t block_end = 0) {
  const std::string data = deflate_raw(content, dictionary, block_end);
  return std::to_string(version) + "." + base64url_encode(data) + "." + base64url_encode(check_of(version == 1 ? content : data));
}

}  // namespace

const std::string& share_link_dictionary() { return dictionary_v2(); }

bool share_inline_reference(const Recipe& recipe) { return recipe.reference.chart == "file" || !recipe.images.empty(); }

std::string encode_share_payload_v1(const SharePayload& payload) { return link_text(1, link_content(payload), {}); }

std::string encode_share_payload(const SharePayload& payload) {
  std::size_t tail = 0;
  const std::string content = link_content_v2(payload, tail);
  return link_text(kLinkVersion, content, dictionary_v2(), tail);
}

SharePayload decode_share_payload(std::string_view text) {
  if (text.size() > kMaxLinkChars)
    throw Error(ErrorCode::LimitExceeded, "share link of " + std::to_string(text.size()) + " characters (limit " +
                                              std::to_string(kMaxLinkChars) + ")");
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  const std::size_t hash = text.find('#');
  if (hash != std::string_view::npos) {  // a link: its fragment's tristim= parameter
    std::string_view fragment = text.substr(hash + 1);
    std::size_t at = 0;
    for (;;) {
      if (fragment.substr(at, std::char_traits<char>::length(kFragmentKey)) == kFragmentKey) break;
      at = fragment.find('&', at);
      if (at == std::string_view::npos) bad("the link has no '#tristim=' fragment");
      ++at;
    }
    fragment = fragment.substr(at + std::char_traits<char>::length(kFragmentKey));
    text = fragment.substr(0, fragment.find('&'));
  }
  if (text.empty()) bad("empty");
  const std::size_t dot1 = text.find('.');
  const std::string_view version = text.substr(0, dot1);
  if (version.empty() || version.size() > 9 || version.find_first_not_of("0123456789") != std::string_view::npos)
    bad("does not start with a format version (\"2.\"): not a tristim link");
  if (version != "1" && version != "2")
    throw Error(ErrorCode::ProfileVersion, version_error("link format", std::string(version), "versions 1 and 2"));
  if (dot1 == std::string_view::npos) bad("truncated after its version");
  const std::size_t dot2 = text.find('.', dot1 + 1);
  if (dot2 == std::string_view::npos) bad("truncated: no check after the data");
  const std::string data = base64url_decode(text.substr(dot1 + 1, dot2 - dot1 - 1), "share payload data");
  const std::string check = base64url_decode(text.substr(dot2 + 1), "share payload check");
  if (check.size() != kCheckBytes) bad("the check has " + std::to_string(check.size()) + " bytes, not " + std::to_string(kCheckBytes) + " (truncated?)");
  const bool v1 = version == "1";
  if (!v1 && check != check_of(data)) bad("the check does not match the data: the link was changed or cut");
  const std::string json_text = inflate_raw(data, kMaxLinkInflatedBytes, "share payload", v1 ? std::string_view() : dictionary_v2());
  if (v1 && check != check_of(json_text)) bad("the check does not match the content: the link was changed or cut");
  return share_payload_from_json(v1 ? link_json(json_text) : link_json_v2(json_text));
}

std::string share_link(const std::string& base, const std::string& payload) {
  return base.substr(0, base.find('#')) + "#" + kFragmentKey + payload;
}

TrainingSet share_training(const SharePayload& p) {
  if (p.kind != "relative") throw Error(ErrorCode::InvalidArgument, "an absolute payload has no relative training set");
  if (inline_reference(p.recipe)) return training_set(p.recipe, p.labels, p.camera_RGB, p.reference_XYZ);
  const ReferenceChart ref = recipe_reference(p.recipe);
  std::map<std::string, std::size_t> row;
  for (std::size_t i = 0; i < ref.ids.size(); ++i) row[ref.ids[i]] = i;
  PatchMatrix XYZ(static_cast<Eigen::Index>(p.labels.size()), 3);
  for (std::size_t i = 0; i < p.labels.size(); ++i) {
    const auto it = row.find(normalise_patch_id(p.labels[i]));
    if (it == row.end())
      throw Error(ErrorCode::PatchMismatch, "share payload: patch '" + p.labels[i] + "' is not in the recipe's chart '" +
                                                p.recipe.reference.chart + "'");
    XYZ.row(static_cast<Eigen::Index>(i)) = ref.XYZ[it->second].transpose();
  }
  return training_set(p.recipe, p.labels, p.camera_RGB, XYZ);
}

std::string share_sample_payload(const Recipe& recipe, const ChartSample& sample, const ReferenceChart& reference,
                                 const std::vector<ShareSource>& sources) {
  const TrainingSet training = training_set(recipe, sample, reference);
  return encode_share_payload(share_payload(characterise(recipe, training), training, sources));
}

std::string share_absolute_payload(const AbsoluteRecipe& recipe) {
  return encode_share_payload(share_payload(characterise_absolute(recipe, AbsoluteFrames{})));
}

TrainingSet sample_training(Recipe& recipe, const RawImage& image, const ReferenceChart* reference) {
  const ChartSample sample = sample_recipe_chart(recipe, image);  // as fit --recipe --raw (a cut chart too)
  return training_set(recipe, sample, reference ? *reference : recipe_reference(recipe));
}

bool can_resample(const SharePayload& p) {
  const auto& c = p.recipe.sampling.corners;
  const CaptureStage& cap = p.recipe.capture;
  return p.kind == "relative" && p.recipe.images.empty() && std::any_of(c.begin(), c.end(), [](double v) { return v != 0; }) && cap.dark_frames == 0 &&
         !cap.flat_field && !cap.falloff;
}

Reproduction reproduce_link(const std::string& text) { return reproduce_share(decode_share_payload(text)); }

Reproduction reproduce_share_image(const SharePayload& p, const std::vector<std::uint8_t>& bytes) {
  if (p.kind != "relative") throw Error(ErrorCode::InvalidArgument, "an absolute link is reproduced from its stimuli rows, not an image");
  if (!can_resample(p))
    throw Error(ErrorCode::InvalidArgument, "the recipe applied dark frames or a flat field, which a link does not carry: "
                                            "its patches cannot be sampled again from the image alone");
  const std::string sum = sha256_hex(bytes.data(), bytes.size());
  const auto src = std::find_if(p.sources.begin(), p.sources.end(), [&](const ShareSource& s) { return s.sha256 == sum; });
  if (src == p.sources.end())
    throw Error(ErrorCode::PatchMismatch, "this image (SHA-256 " + sum.substr(0, 16) + "…) is not the link's source" +
                                              (p.sources.empty() ? std::string(" (the link names none)")
                                                                 : " ('" + p.sources.front().name + "', " + p.sources.front().sha256.substr(0, 16) + "…)"));
  const RawImage image = decode_any(bytes.data(), bytes.size());
  Recipe recipe = p.recipe;
  TrainingSet training;
  if (recipe.reference.chart == "file") {  // the inline reference, as a chart to pair the sample with
    ReferenceChart ref;
    ref.chart_id = "file";
    for (std::size_t i = 0; i < p.labels.size(); ++i) {
      ref.ids.push_back(normalise_patch_id(p.labels[i]));
      ref.labels.push_back(p.labels[i]);
      ref.XYZ.push_back(p.reference_XYZ.row(static_cast<Eigen::Index>(i)).transpose());
    }
    training = sample_training(recipe, image, &ref);
  } else {
    training = sample_training(recipe, image);
  }
  SharePayload resampled = p;
  resampled.labels = training.labels;
  resampled.camera_RGB = training.camera_RGB;
  if (recipe.reference.chart == "file") resampled.reference_XYZ = training.reference_XYZ;
  Reproduction r = reproduce_share(resampled);
  r.payload = share_payload_json(p).dump();
  r.resampled = true;
  return r;
}

Reproduction reproduce_link_image(const std::string& text, const std::vector<std::uint8_t>& image_bytes) {
  return reproduce_share_image(decode_share_payload(text), image_bytes);
}

Reproduction reproduce_share(const SharePayload& p) {
  Reproduction r;
  r.payload = share_payload_json(p).dump();
  r.kind = p.kind;
  r.expected_version = p.tristim_version;
  r.actual_version = kVersion;
  r.expected = p.expected;
  if (p.kind == "absolute") {
    const AbsoluteCharacterisation c = characterise_absolute(p.absolute, AbsoluteFrames{});
    r.actual = share_results(c.profile);
    r.profile = absolute_profile_to_json(c.profile);
  } else {
    const Characterisation c = characterise(p.recipe, share_training(p));
    r.actual = share_results(c.profile);
    r.profile = profile_to_json(c.profile);
  }
  r.verdict = r.actual.digest == r.expected.digest ? "reproduced" : "differs";
  const auto e = result_lines(r.expected.text), a = result_lines(r.actual.text);
  std::map<std::string, std::string> am(a.begin(), a.end()), em(e.begin(), e.end());
  for (const auto& [name, value] : e) {
    const auto it = am.find(name);
    const std::string actual = it == am.end() ? "" : it->second;
    if (actual != value) r.differences.push_back({name, value, actual});
  }
  for (const auto& [name, value] : a)
    if (!em.count(name)) r.differences.push_back({name, "", value});
  return r;
}

json::Value reproduction_json(const Reproduction& r) {
  auto results = [](const ShareResults& s) {
    json::Value values = json::Value::object();
    for (const auto& [name, value] : result_lines(s.text)) values.set(name, value);
    return fields::object({{"digest", s.digest}, {"results", values}});
  };
  json::Value diffs = json::Value::array();
  for (const auto& d : r.differences)
    diffs.push(fields::object({{"name", d.name}, {"expected", d.expected}, {"actual", d.actual}}));
  return fields::object({{"verdict", r.verdict}, {"kind", r.kind},
                         {"tristim_version", fields::object({{"link", r.expected_version}, {"this", r.actual_version}})},
                         {"expected", results(r.expected)}, {"actual", results(r.actual)}, {"differences", diffs},
                         {"resampled", r.resampled}});
}

// ---- base64url and deflate-raw -------------------------------------------------------------------

std::string base64url_encode(std::string_view bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16 | std::uint32_t(std::uint8_t(bytes[i + 1])) << 8 |
                            std::uint8_t(bytes[i + 2]);
    out += abc[v >> 18]; out += abc[(v >> 12) & 63]; out += abc[(v >> 6) & 63]; out += abc[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    out += abc[v >> 18]; out += abc[(v >> 12) & 63];
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16 | std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    out += abc[v >> 18]; out += abc[(v >> 12) & 63]; out += abc[(v >> 6) & 63];
  }
  return out;
}

std::string base64url_decode(std::string_view text, const std::string& what) {
  while (!text.empty() && text.back() == '=') text.remove_suffix(1);
  if (text.size() % 4 == 1) throw Error(ErrorCode::ParseError, what + ": base64url of impossible length " + std::to_string(text.size()));
  std::string out;
  out.reserve(text.size() * 3 / 4);
  std::uint32_t acc = 0;
  int bits = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    int v;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '-') v = 62;
    else if (c == '_') v = 63;
    else throw Error(ErrorCode::ParseError, what + ": character " + std::to_string(i) + " is not base64url");
    acc = (acc << 6) | std::uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((acc >> bits) & 0xff);
    }
  }
  if (acc & ((1u << bits) - 1))  // canonical only: a changed last character is refused, not ignored
    throw Error(ErrorCode::ParseError, what + ": the last base64url character has bits set that encode nothing");
  return out;
}

std::string deflate_raw(std::string_view bytes, std::string_view dictionary, std::size_t block_end) {
  if (bytes.size() > (1u << 30)) throw Error(ErrorCode::LimitExceeded, "deflate input beyond 1 GiB");
  block_end = std::min(block_end, bytes.size());
  ZStream z(false, dictionary);
  std::string out(deflateBound(&z.s, static_cast<uLong>(bytes.size())) + 64, '\0');  // + a block end
  z.s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.s.next_out = reinterpret_cast<Bytef*>(&out[0]);
  z.s.avail_out = static_cast<uInt>(out.size());
  if (block_end > 0) {  // Z_BLOCK: the block ends here, its bits unaligned, the history kept
    z.s.avail_in = static_cast<uInt>(block_end);
    if (deflate(&z.s, Z_BLOCK) != Z_OK || z.s.avail_in != 0) throw Error(ErrorCode::Internal, "deflate could not end a block");
  }
  z.s.avail_in = static_cast<uInt>(bytes.size() - block_end);
  if (deflate(&z.s, Z_FINISH) != Z_STREAM_END) throw Error(ErrorCode::Internal, "deflate did not finish");
  out.resize(z.s.total_out);
  return out;
}

std::string inflate_raw(std::string_view bytes, std::size_t max_bytes, const std::string& what, std::string_view dictionary) {
  if (bytes.size() > (1u << 30)) throw Error(ErrorCode::LimitExceeded, what + ": compressed data beyond 1 GiB");
  ZStream z(true, dictionary);
  z.s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.s.avail_in = static_cast<uInt>(bytes.size());
  std::string out;
  char buf[16384];
  for (;;) {
    z.s.next_out = reinterpret_cast<Bytef*>(buf);
    z.s.avail_out = sizeof buf;
    const int rc = inflate(&z.s, Z_NO_FLUSH);
    const std::size_t got = sizeof buf - z.s.avail_out;
    if (out.size() + got > max_bytes)  // checked per 16 KiB while inflating: a bomb stops here
      throw Error(ErrorCode::LimitExceeded, what + ": inflates beyond " + std::to_string(max_bytes) + " bytes");
    out.append(buf, got);
    if (rc == Z_STREAM_END) break;
    if (rc == Z_OK) continue;
    if (rc == Z_BUF_ERROR && z.s.avail_in == 0) throw Error(ErrorCode::ParseError, what + ": the compressed data is truncated");
    if (rc == Z_BUF_ERROR) continue;
    throw Error(ErrorCode::ParseError, what + ": corrupt compressed data at byte " + std::to_string(z.s.total_in) +
                                           (z.s.msg ? std::string(" (") + z.s.msg + ")" : std::string()));
  }
  if (z.s.avail_in != 0) throw Error(ErrorCode::ParseError, what + ": " + std::to_string(z.s.avail_in) + " bytes after the compressed data");
  // The bits after the last block's end fill the last byte with zeros (as every deflate writer
  // pads): a link whose final character changes only those bits is refused, not read the same.
  // data_type: the bits zlib took from the input but did not use (it may read a byte ahead).
  const std::size_t unused = static_cast<std::size_t>(z.s.data_type & 63), taken = (unused + 7) / 8;
  std::uint64_t tail = 0;
  for (std::size_t j = 0; j < taken && j < z.s.total_in; ++j)
    tail |= std::uint64_t(static_cast<std::uint8_t>(bytes[z.s.total_in - taken + j])) << (8 * j);
  if (unused > 0 && (tail >> (8 * taken - unused)) != 0)
    throw Error(ErrorCode::ParseError, what + ": bits set after the end of the compressed data");
  return out;
}

// ---- project files ---------------------------------------------------------------------------------

namespace {
constexpr std::string_view kProjectMagic = "TRISTIM-PROJECT 1\n";
constexpr std::string_view kProjectPrefix = "TRISTIM-PROJECT ";
[[noreturn]] void bad_project(const std::string& message) { throw Error(ErrorCode::ParseError, "project file: " + message); }
}  // namespace

bool is_project_file(std::string_view bytes) { return bytes.substr(0, kProjectPrefix.size()) == kProjectPrefix; }

std::string project_to_bytes(const Project& project) {
  json::Value images = json::Value::array();
  std::size_t offset = 0;
  for (const auto& im : project.images) {
    images.push(fields::object({{"name", im.name}, {"sha256", sha256_hex(im.bytes.data(), im.bytes.size())},
                                {"offset", static_cast<double>(offset)}, {"size", static_cast<double>(im.bytes.size())}}));
    offset += im.bytes.size();
  }
  const json::Value header = fields::object(
      {{"format", "tristim-project"}, {"version", kProjectVersion}, {"payload", share_payload_json(project.payload)},
       {"images", images}, {"session", project.session.is_object() ? project.session : json::Value::object()}});
  const std::string text = header.dump();
  std::string out(kProjectMagic);
  out += std::to_string(text.size()) + "\n" + text;
  if (out.size() + offset > kMaxProjectBytes) throw Error(ErrorCode::LimitExceeded, "project file beyond 1 GiB");
  for (const auto& im : project.images) out.append(im.bytes.begin(), im.bytes.end());
  return out;
}

Project project_from_bytes(std::string_view bytes) {
  if (bytes.size() > kMaxProjectBytes)
    throw Error(ErrorCode::LimitExceeded, "project file of " + std::to_string(bytes.size()) + " bytes (limit 1 GiB)");
  if (!is_project_file(bytes)) bad_project("does not start with \"TRISTIM-PROJECT\"");
  if (bytes.substr(0, kProjectMagic.size()) != kProjectMagic) {
    const std::string_view v = bytes.substr(kProjectPrefix.size(), bytes.find('\n') - kProjectPrefix.size());
    throw Error(ErrorCode::ProfileVersion, version_error("project file", std::string(v.substr(0, 16)), "version 1"));
  }
  std::size_t at = kProjectMagic.size();
  const std::size_t nl = bytes.find('\n', at);
  if (nl == std::string_view::npos || nl == at || nl - at > 10) bad_project("no header length");
  std::size_t length = 0;
  for (std::size_t i = at; i < nl; ++i) {
    if (bytes[i] < '0' || bytes[i] > '9') bad_project("header length is not a number");
    length = length * 10 + std::size_t(bytes[i] - '0');
  }
  at = nl + 1;
  if (length > bytes.size() - at) bad_project("truncated header (" + std::to_string(length) + " bytes announced)");
  json::Value header;
  try {
    header = json::parse(std::string(bytes.substr(at, length)));
  } catch (const Error& e) {
    if (e.code() == ErrorCode::LimitExceeded) throw;
    bad_project(std::string("header is not JSON: ") + e.what());
  }
  if (!header.is_object()) bad_project("header must be a JSON object");
  json::reject_unknown(header, {"format", "version", "payload", "images", "session"}, "project file", ErrorCode::ParseError);
  if (text_field(header, "format", "project") != "tristim-project") bad_project("\"format\" must be \"tristim-project\"");
  const json::Value& ver = field(header, "version", "project");
  if (!ver.is_number() || ver.as_number() != kProjectVersion)
    throw Error(ErrorCode::ProfileVersion, version_error("project file", ver.is_number() ? json::number_text(ver.as_number()) : "?", "version 1"));
  Project p;
  p.payload = share_payload_from_json(field(header, "payload", "project"));
  const std::string_view blob = bytes.substr(at + length);
  const json::Value& images = field(header, "images", "project");
  if (!images.is_array()) bad_project("images must be an array");
  for (const auto& e : images.as_array()) {
    if (!e.is_object()) bad_project("images must hold objects");
    json::reject_unknown(e, {"name", "sha256", "offset", "size"}, "project image", ErrorCode::ParseError);
    ProjectImage im;
    im.name = text_field(e, "name", "image");
    const double off = field(e, "offset", "image").is_number() ? field(e, "offset", "image").as_number() : -1;
    const double size = field(e, "size", "image").is_number() ? field(e, "size", "image").as_number() : -1;
    if (!(off >= 0) || !(size >= 0) || off != std::floor(off) || size != std::floor(size) || off > double(blob.size()) ||
        size > double(blob.size()) - off)
      bad_project("image '" + im.name + "' lies outside the file (truncated?)");
    const std::string_view part = blob.substr(static_cast<std::size_t>(off), static_cast<std::size_t>(size));
    im.bytes.assign(part.begin(), part.end());
    if (sha256_hex(part) != text_field(e, "sha256", "image"))
      bad_project("image '" + im.name + "': SHA-256 differs from the header's (damaged file)");
    p.images.push_back(std::move(im));
  }
  const json::Value& session = field(header, "session", "project");
  if (!session.is_object()) bad_project("session must be an object");
  p.session = session;
  return p;
}

Reproduction reproduce_project(const Project& project) {
  const SharePayload& p = project.payload;
  if (can_resample(p))
    for (const auto& im : project.images) {
      const std::string sum = sha256_hex(im.bytes.data(), im.bytes.size());
      for (const auto& s : p.sources)
        if (s.sha256 == sum) return reproduce_share_image(p, im.bytes);
    }
  return reproduce_share(p);
}

std::vector<std::uint8_t> project_file(const std::string& payload, const std::vector<ProjectImage>& images,
                                       const std::string& session_json) {
  Project project;
  project.payload = decode_share_payload(payload);
  project.images = images;
  if (!session_json.empty()) {
    project.session = json::parse(session_json);
    if (!project.session.is_object()) throw Error(ErrorCode::InvalidArgument, "a project's session must be a JSON object");
  }
  const std::string bytes = project_to_bytes(project);
  return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
}

ProjectContents open_project(const std::vector<std::uint8_t>& bytes) {
  const Project p = project_from_bytes(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  return {encode_share_payload(p.payload), p.images, p.session.dump()};
}

}  // namespace tristim
