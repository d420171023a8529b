// Common LUT Format writer and strict reader (profile/clf.hpp), and an IDT's CLF, plain matrix and JSON.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>

#include "tristim/error.hpp"
#include "tristim/profile/clf.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "tristim/version.hpp"
#include "../text_escape.hpp"

namespace tristim {

namespace {

constexpr std::size_t kMaxLut = 65536;

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

// XML's predefined entities, for the writer (escape) and the reader (Reader::unescape) alike.
constexpr CharEscape kEntities[] = {
    {'<', "&lt;"}, {'>', "&gt;"}, {'&', "&amp;"}, {'"', "&quot;"}, {'\'', "&apos;"}};

std::string escape(std::string_view s) {
  std::string o;
  append_escaped(o, s, kEntities, [](std::string& out, char c) {
    // Control characters other than tab/newline are not allowed in XML 1.0.
    out += (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') ? ' ' : c;
  });
  return o;
}

bool xml_name(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return true;
}

// --- a small XML reader: elements, attributes, text, comments, the declaration ------------------

struct Node {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attrs;
  std::vector<Node> children;
  std::string text;
  std::size_t offset = 0;
  const std::string* attr(std::string_view k) const {
    for (const auto& a : attrs)
      if (a.first == k) return &a.second;
    return nullptr;
  }
};

class XmlReader {
 public:
  explicit XmlReader(std::string_view t) : t_(t) {}
  Node document() {
    skip_misc();
    if (t_.compare(p_, 5, "<?xml") == 0) {
      const std::size_t e = t_.find("?>", p_);
      if (e == std::string_view::npos) fail("unterminated XML declaration");
      p_ = e + 2;
    }
    skip_misc();
    Node root = element(0);
    skip_misc();
    if (p_ != t_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(ErrorCode::ParseError, "CLF: " + what + " at offset " + std::to_string(p_));
  }
  void skip_ws() {
    while (p_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[p_]))) ++p_;
  }
  void skip_misc() {
    for (;;) {
      skip_ws();
      if (t_.compare(p_, 4, "<!--") != 0) return;
      const std::size_t e = t_.find("-->", p_ + 4);
      if (e == std::string_view::npos) fail("unterminated comment");
      p_ = e + 3;
    }
  }
  std::string name() {
    const std::size_t s = p_;
    while (p_ < t_.size() && (std::isalnum(static_cast<unsigned char>(t_[p_])) || t_[p_] == '_' || t_[p_] == '-' ||
                              t_[p_] == '.' || t_[p_] == ':'))
      ++p_;
    if (p_ == s) fail("expected a name");
    return std::string(t_.substr(s, p_ - s));
  }
  std::string unescape(std::string_view s) const {
    std::string o;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s[i] != '&') {
        o += s[i];
        continue;
      }
      const std::size_t e = s.find(';', i);
      if (e == std::string_view::npos) fail("unterminated entity");
      const CharEscape* row = escape_named(s.substr(i, e - i + 1), kEntities);
      if (!row) fail("unknown entity '&" + std::string(s.substr(i + 1, e - i - 1).substr(0, 16)) + ";'");
      o += row->raw;
      i = e;
    }
    return o;
  }
  Node element(int depth) {
    if (depth > 16) fail("elements nested deeper than 16");
    if (p_ >= t_.size() || t_[p_] != '<') fail("expected an element");
    Node n;
    n.offset = p_;
    ++p_;
    n.name = name();
    for (;;) {
      skip_ws();
      if (p_ >= t_.size()) fail("unterminated start tag <" + n.name + ">");
      if (t_[p_] == '/') {
        if (t_.compare(p_, 2, "/>") != 0) fail("expected '/>'");
        p_ += 2;
        return n;
      }
      if (t_[p_] == '>') {
        ++p_;
        break;
      }
      std::string k = name();
      skip_ws();
      if (p_ >= t_.size() || t_[p_] != '=') fail("expected '=' after attribute " + k);
      ++p_;
      skip_ws();
      if (p_ >= t_.size() || (t_[p_] != '"' && t_[p_] != '\'')) fail("expected a quoted value for attribute " + k);
      const char q = t_[p_++];
      const std::size_t e = t_.find(q, p_);
      if (e == std::string_view::npos) fail("unterminated attribute " + k);
      n.attrs.emplace_back(std::move(k), unescape(t_.substr(p_, e - p_)));
      p_ = e + 1;
    }
    for (;;) {
      const std::size_t lt = t_.find('<', p_);
      if (lt == std::string_view::npos) fail("no end tag </" + n.name + ">");
      n.text += unescape(t_.substr(p_, lt - p_));
      p_ = lt;
      if (t_.compare(p_, 4, "<!--") == 0) {
        skip_misc();
        continue;
      }
      if (t_.compare(p_, 2, "</") == 0) {
        p_ += 2;
        if (name() != n.name) fail("end tag does not match <" + n.name + ">");
        skip_ws();
        if (p_ >= t_.size() || t_[p_] != '>') fail("expected '>'");
        ++p_;
        return n;
      }
      n.children.push_back(element(depth + 1));
      if (n.children.size() > 1024) fail("more than 1024 child elements");
    }
  }
  std::string_view t_;
  std::size_t p_ = 0;
};

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::vector<double> array_values(const Node& array, std::size_t rows, std::size_t cols, const std::string& where) {
  std::vector<double> v;
  std::istringstream in(array.text);
  std::string tok;
  while (in >> tok) {
    if (v.size() >= rows * cols)
      throw Error(ErrorCode::RowLength, "CLF: " + where + " Array has more than the " + std::to_string(rows * cols) + " values its dim says");
    char* end = nullptr;
    const double d = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0')
      throw Error(ErrorCode::NonNumeric, "CLF: " + where + " value '" + tok.substr(0, 32) + "' is not a number");
    if (!std::isfinite(d)) throw Error(ErrorCode::NonFinite, "CLF: " + where + " value " + std::to_string(v.size() + 1) + " is not finite");
    v.push_back(d);
  }
  if (v.size() != rows * cols)
    throw Error(ErrorCode::RowLength, "CLF: " + where + " Array has " + std::to_string(v.size()) + " values; its dim says " +
                                          std::to_string(rows * cols));
  return v;
}

const Node& only_array(const Node& op) {
  if (op.children.size() != 1 || op.children[0].name != "Array")
    throw Error(ErrorCode::ParseError, "CLF: <" + op.name + "> at offset " + std::to_string(op.offset) + " needs exactly one <Array>");
  return op.children[0];
}

void check_depths(const Node& op) {
  for (const char* k : {"inBitDepth", "outBitDepth"}) {
    const std::string* d = op.attr(k);
    if (!d || *d != "32f")
      throw Error(ErrorCode::ParseError, "CLF: <" + op.name + "> needs " + k + "=\"32f\" (the only depth tristim writes)");
  }
}

}  // namespace

std::string write_clf(const ClfDocument& c) {
  if (!c.matrix.allFinite()) throw Error(ErrorCode::InvalidArgument, "CLF: the matrix is not finite");
  if (c.lut1d.size() == 1 || c.lut1d.size() > kMaxLut)
    throw Error(ErrorCode::InvalidArgument, "CLF: a LUT1D needs 2 to 65536 entries, not " + std::to_string(c.lut1d.size()));
  for (const Vec3& v : c.lut1d)
    if (!v.allFinite()) throw Error(ErrorCode::InvalidArgument, "CLF: a LUT1D value is not finite");
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<ProcessList xmlns=\"urn:AMPAS:CLF:v3.0\" compCLFversion=\"3.0\" id=\"" << escape(c.id) << "\" name=\""
    << escape(c.name) << "\">\n";
  if (!c.description.empty()) o << "  <Description>" << escape(c.description) << "</Description>\n";
  if (!c.input_descriptor.empty()) o << "  <InputDescriptor>" << escape(c.input_descriptor) << "</InputDescriptor>\n";
  if (!c.output_descriptor.empty()) o << "  <OutputDescriptor>" << escape(c.output_descriptor) << "</OutputDescriptor>\n";
  if (!c.info.empty()) {
    o << "  <Info>\n";
    for (const auto& [k, v] : c.info) {
      if (!xml_name(k)) throw Error(ErrorCode::InvalidArgument, "CLF: Info element name '" + k + "' is not an XML name");
      o << "    <" << k << ">" << escape(v) << "</" << k << ">\n";
    }
    o << "  </Info>\n";
  }
  if (!c.lut1d.empty()) {
    o << "  <LUT1D id=\"linearisation\" name=\"linearisation\" inBitDepth=\"32f\" outBitDepth=\"32f\" interpolation=\"linear\">\n"
      << "    <Array dim=\"" << c.lut1d.size() << " 3\">\n";
    for (const Vec3& v : c.lut1d) o << "      " << num(v[0]) << " " << num(v[1]) << " " << num(v[2]) << "\n";
    o << "    </Array>\n  </LUT1D>\n";
  }
  o << "  <Matrix id=\"matrix\" name=\"camera RGB to ACES2065-1\" inBitDepth=\"32f\" outBitDepth=\"32f\">\n"
    << "    <Array dim=\"3 3\">\n";
  for (int r = 0; r < 3; ++r) o << "      " << num(c.matrix(r, 0)) << " " << num(c.matrix(r, 1)) << " " << num(c.matrix(r, 2)) << "\n";
  o << "    </Array>\n  </Matrix>\n</ProcessList>\n";
  return o.str();
}

ClfDocument read_clf(std::string_view text) {
  if (text.size() > (std::size_t(64) << 20)) throw Error(ErrorCode::LimitExceeded, "CLF: larger than 64 MB");
  const Node root = XmlReader(text).document();
  if (root.name != "ProcessList") throw Error(ErrorCode::ParseError, "CLF: the root element is <" + root.name + ">, not <ProcessList>");
  ClfDocument c;
  if (const auto* a = root.attr("id")) c.id = *a;
  if (const auto* a = root.attr("name")) c.name = *a;
  bool matrix = false;
  for (const Node& n : root.children) {
    if (matrix) throw Error(ErrorCode::ParseError, "CLF: <" + n.name + "> after the Matrix (tristim's IDT ends with it)");
    if (n.name == "Description") c.description = trim(n.text);
    else if (n.name == "InputDescriptor") c.input_descriptor = trim(n.text);
    else if (n.name == "OutputDescriptor") c.output_descriptor = trim(n.text);
    else if (n.name == "Info") {
      for (const Node& i : n.children) c.info.emplace_back(i.name, trim(i.text));
    } else if (n.name == "LUT1D") {
      if (!c.lut1d.empty()) throw Error(ErrorCode::ParseError, "CLF: a second <LUT1D>");
      check_depths(n);
      const Node& a = only_array(n);
      const std::string* dim = a.attr("dim");
      unsigned long len = 0, ch = 0;
      if (!dim || std::sscanf(dim->c_str(), "%lu %lu", &len, &ch) != 2 || ch != 3)
        throw Error(ErrorCode::ParseError, "CLF: the LUT1D Array needs dim=\"N 3\"");
      if (len < 2 || len > kMaxLut) throw Error(ErrorCode::LimitExceeded, "CLF: a LUT1D of " + std::to_string(len) + " entries (2 to 65536)");
      const std::vector<double> v = array_values(a, len, 3, "LUT1D");
      for (std::size_t i = 0; i < len; ++i) c.lut1d.emplace_back(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    } else if (n.name == "Matrix") {
      check_depths(n);
      const Node& a = only_array(n);
      const std::string* dim = a.attr("dim");
      if (!dim || trim(*dim) != "3 3") throw Error(ErrorCode::ParseError, "CLF: the Matrix Array needs dim=\"3 3\"");
      const std::vector<double> v = array_values(a, 3, 3, "Matrix");
      for (int i = 0; i < 9; ++i) c.matrix(i / 3, i % 3) = v[i];
      matrix = true;
    } else {
      throw Error(ErrorCode::ParseError, "CLF: <" + n.name + "> at offset " + std::to_string(n.offset) +
                                             " is not an element of tristim's IDT (Description, InputDescriptor, "
                                             "OutputDescriptor, Info, LUT1D, Matrix)");
    }
  }
  if (!matrix) throw Error(ErrorCode::ParseError, "CLF: no <Matrix>");
  return c;
}

Vec3 apply_clf(const ClfDocument& c, const Vec3& rgb) {
  Vec3 v = rgb;
  if (!c.lut1d.empty()) {
    const double n1 = static_cast<double>(c.lut1d.size() - 1);
    for (int ch = 0; ch < 3; ++ch) {
      const double x = std::clamp(rgb[ch], 0.0, 1.0) * n1;
      const std::size_t i = std::min(static_cast<std::size_t>(x), c.lut1d.size() - 2);
      const double f = x - static_cast<double>(i);
      v[ch] = c.lut1d[i][ch] * (1 - f) + c.lut1d[i + 1][ch] * f;
    }
  }
  return c.matrix * v;
}

namespace {

std::string triple(const Vec3& v) { return num(v[0]) + " " + num(v[1]) + " " + num(v[2]); }

json::Value mat_json(const Mat3& m) {
  json::Value a = json::Value::array();
  for (int r = 0; r < 3; ++r) a.push(std::vector<double>{m(r, 0), m(r, 1), m(r, 2)});
  return a;
}

}  // namespace

ClfDocument idt_clf(const IdtResult& r, const IdtRecipe& recipe) {
  ClfDocument c;
  c.id = "tristim-idt";
  std::string source;
  for (const auto& [k, v] : recipe)
    if (k == "Camera" || k == "Sensitivities" || k == "CameraRGB") source = v;
  c.name = "tristim IDT" + (source.empty() ? std::string() : " " + source);
  c.description = "ACES Input Transform: camera-native linear RGB (black subtracted) to ACES2065-1; white balance, "
                  "exposure and the rawtoaces v1 matrix in one 3x3";
  c.input_descriptor = "Camera-native linear RGB (a perfect diffuser under the illuminant reads G = " +
                       num(1 / r.exposure) + ")";
  c.output_descriptor = "ACES2065-1";
  c.info.emplace_back("Release", std::string("tristim ") + kVersion);
  c.info.emplace_back("Method", "rawtoaces v1 / AMPAS P-2013-001: B with rows summing to one, least-squares CIE 1976 dE*ab "
                                "against the ACES white; " + r.adaptation + " adaptation");
  for (const auto& kv : recipe) c.info.push_back(kv);
  c.info.emplace_back("WhiteBalance", triple(r.white_balance));
  c.info.emplace_back("Exposure", num(r.exposure));
  c.info.emplace_back("MatrixB", triple(r.matrix.row(0).transpose()) + "  " + triple(r.matrix.row(1).transpose()) + "  " +
                                     triple(r.matrix.row(2).transpose()));
  char fit[200];
  std::snprintf(fit, sizeof fit, "%d samples: dE76 mean %.3f max %.3f; dE00 mean %.3f max %.3f", r.patches, r.mean_delta_E76,
                r.max_delta_E76, r.mean_delta_E00, r.max_delta_E00);
  c.info.emplace_back("Fit", fit);
  c.matrix = r.camera_matrix();
  return c;
}

std::string idt_matrix_text(const IdtResult& r) {
  std::string s = "# tristim " + std::string(kVersion) + " ACES IDT: camera-native linear RGB -> ACES2065-1 (" + r.adaptation +
                  ")\n# = exposure * B * diag(white balance); white balance (R G B): " + triple(r.white_balance) +
                  "; exposure: " + num(r.exposure) + "\n";
  for (int i = 0; i < 3; ++i) s += "# B row " + std::to_string(i + 1) + ": " + triple(r.matrix.row(i).transpose()) + "\n";
  const Mat3 m = r.camera_matrix();
  for (int i = 0; i < 3; ++i) s += triple(m.row(i).transpose()) + "\n";
  return s;
}

json::Value idt_json(const IdtResult& r, const IdtRecipe& recipe) {
  json::Value o = json::Value::object();
  o.set("matrix", mat_json(r.matrix));
  o.set("white_balance", std::vector<double>{r.white_balance[0], r.white_balance[1], r.white_balance[2]});
  o.set("exposure", r.exposure);
  o.set("camera_matrix", mat_json(r.camera_matrix()));
  o.set("adaptation", r.adaptation);
  json::Value rec = json::Value::object();
  for (const auto& [k, v] : recipe) rec.set(k, v);
  o.set("recipe", rec);
  json::Value e = json::Value::object();
  e.set("samples", r.patches);
  const std::pair<const char*, double> figures[] = {{"delta_E76_mean", r.mean_delta_E76}, {"delta_E76_max", r.max_delta_E76},
                                                    {"delta_E00_mean", r.mean_delta_E00}, {"delta_E00_max", r.max_delta_E00},
                                                    {"objective", r.objective}};
  for (const auto& [k, v] : figures) e.set(k, v);
  e.set("delta_E76", r.delta_E76);
  e.set("delta_E00", r.delta_E00);
  o.set("errors", e);
  o.set("iterations", r.iterations);
  o.set("status", r.status);
  o.set("message", r.message);
  return o;
}

json::Value clf_json(const ClfDocument& c) {
  json::Value o = json::Value::object();
  const std::pair<const char*, const std::string*> texts[] = {{"id", &c.id}, {"name", &c.name}, {"description", &c.description},
                                                              {"input", &c.input_descriptor}, {"output", &c.output_descriptor}};
  for (const auto& [k, v] : texts) o.set(k, *v);
  json::Value info = json::Value::object();
  for (const auto& [k, v] : c.info) info.set(k, v);
  o.set("info", info);
  o.set("lut1d_entries", static_cast<int>(c.lut1d.size()));
  o.set("matrix", mat_json(c.matrix));
  const Vec3 w = apply_clf(c, Vec3::Ones());
  o.set("aces_of_camera_1_1_1", std::vector<double>{w[0], w[1], w[2]});
  return o;
}

IdtFiles idt_files(const IdtResult& r, const IdtRecipe& recipe) {
  return {write_clf(idt_clf(r, recipe)), idt_matrix_text(r), idt_json(r, recipe).dump(2) + "\n", r};
}

IdtRecipe idt_recipe(const std::pair<std::string, std::string>& source, const std::pair<std::string, std::string>& illuminant,
                     const std::string& training, ChromaticAdaptation adaptation) {
  IdtRecipe r = {source, illuminant};
  if (!training.empty()) r.emplace_back("Training", training);
  r.emplace_back("Adaptation", idt_adaptation_name(adaptation));
  return r;
}

IdtFiles idt_camera_files(const std::string& camera, const std::string& illuminant, const std::string& adaptation) {
  IdtOptions o;
  o.adaptation = idt_adaptation(adaptation);
  const IdtResult r = idt_from_sensitivities(camera_ssf(camera), illuminant_spd(illuminant), idt_training_190(), o);
  return idt_files(r, idt_recipe({"Camera", camera}, {"Illuminant", illuminant}, kIdtTraining190, o.adaptation));
}

IdtFiles idt_sensitivities_files(std::string_view csv, const std::string& name, const std::string& illuminant,
                                 const std::string& adaptation) {
  IdtOptions o;
  o.adaptation = idt_adaptation(adaptation);
  const IdtResult r = idt_from_sensitivities(read_ssf_csv(csv, name), illuminant_spd(illuminant), idt_training_190(), o);
  return idt_files(r, idt_recipe({"Sensitivities", name}, {"Illuminant", illuminant}, kIdtTraining190, o.adaptation));
}

IdtFiles idt_chart_files(const std::vector<Vec3>& rgb, const std::vector<Vec3>& xyz, const Vec3& white,
                         const std::string& adaptation, const std::string& rgb_name, const std::string& reference_name,
                         const std::pair<std::string, std::string>& illuminant) {
  IdtOptions o;
  o.adaptation = idt_adaptation(adaptation);
  const IdtResult r = idt_from_patches(rgb, xyz, white, o);
  IdtRecipe recipe = idt_recipe({"CameraRGB", rgb_name}, illuminant, "", o.adaptation);
  recipe.insert(recipe.begin() + 1, {"Reference", reference_name});
  return idt_files(r, recipe);
}

}  // namespace tristim
