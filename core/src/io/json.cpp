// Small JSON value: strict parser, round-trip writer.
#include "tristim/io/json.hpp"
#include "tristim/io/fields.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unordered_map>

#include "tristim/error.hpp"
#include "tristim/io/limits.hpp"
#include "tristim/number.hpp"
#include "../text_escape.hpp"

namespace tristim::json {

Value::Value(const std::vector<double>& v) : type_(Type::Array) {
  array_.reserve(v.size());
  for (double d : v) array_.emplace_back(d);
}

static const char* type_name(Value::Type t) {
  switch (t) {
    case Value::Type::Null: return "null";
    case Value::Type::Bool: return "boolean";
    case Value::Type::Number: return "number";
    case Value::Type::String: return "string";
    case Value::Type::Array: return "array";
    case Value::Type::Object: return "object";
  }
  return "?";
}

static Error wrong(const std::string& what, const char* want, Value::Type got) {
  const bool vowel = std::strchr("aeiou", want[0]) != nullptr;
  return Error(ErrorCode::ProfileInvalid, what + " must be " + (vowel ? "an " : "a ") + want + ", got " + type_name(got));
}

double Value::as_number(const std::string& what) const {
  if (type_ != Type::Number) throw wrong(what, "number", type_);
  return number_;
}
int Value::as_int(const std::string& what, int lo, int hi) const {
  const double x = as_number(what);
  if (!(x >= lo && x <= hi) || x != std::floor(x)) {
    char got[32];
    std::snprintf(got, sizeof got, "%.17g", x);
    throw Error(ErrorCode::ProfileInvalid,
                what + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + got);
  }
  return static_cast<int>(x);
}
bool Value::as_bool(const std::string& what) const {
  if (type_ != Type::Bool) throw wrong(what, "boolean", type_);
  return bool_;
}
const std::string& Value::as_string(const std::string& what) const {
  if (type_ != Type::String) throw wrong(what, "string", type_);
  return string_;
}
const std::vector<Value>& Value::as_array(const std::string& what) const {
  if (type_ != Type::Array) throw wrong(what, "array", type_);
  return array_;
}
std::vector<double> Value::as_numbers(const std::string& what) const {
  std::vector<double> out;
  for (const auto& v : as_array(what)) out.push_back(v.as_number(what + " element"));
  return out;
}

Value& Value::push(Value v) {
  if (type_ == Type::Null) type_ = Type::Array;
  if (type_ != Type::Array) throw Error(ErrorCode::Internal, "json: push on a non-array");
  array_.push_back(std::move(v));
  return array_.back();
}
Value& Value::set(const std::string& key, Value v) {
  if (type_ == Type::Null) type_ = Type::Object;
  if (type_ != Type::Object) throw Error(ErrorCode::Internal, "json: set on a non-object");
  for (auto& kv : object_)
    if (kv.first == key) {
      kv.second = std::move(v);
      return kv.second;
    }
  object_.emplace_back(key, std::move(v));
  return object_.back().second;
}
const Value* Value::find(const std::string& key) const {
  if (type_ != Type::Object) return nullptr;
  for (const auto& kv : object_)
    if (kv.first == key) return &kv.second;
  return nullptr;
}
const Value& Value::at(const std::string& key) const {
  const Value* v = find(key);
  if (!v) throw Error(ErrorCode::ProfileInvalid, "missing field '" + key + "'");
  return *v;
}

void reject_unknown(const Value& object, std::initializer_list<const char*> known, const std::string& where,
                    ErrorCode code) {
  for (const auto& kv : object.members()) {
    bool ok = false;
    for (const char* k : known) ok = ok || kv.first == k;
    if (!ok) {
      std::string list;
      for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      throw Error(code, where + ": unknown field '" + kv.first + "' (known: " + list + ")");
    }
  }
}

std::string number_text(double d) {
  if (!std::isfinite(d)) return "null";
  if (d == std::floor(d) && std::fabs(d) < 1e15) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", d);
    if (std::strcmp(buf, "-0") == 0) return "-0.0";
    return buf;
  }
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  return buf;
}

// JSON's short escapes, for the writer and the reader alike. The writer spells the other control
// characters (\b and \f included) as \u00XX and leaves '/' as it is.
constexpr CharEscape kEscapes[] = {{'"', "\\\"", true},  {'\\', "\\\\", true}, {'/', "\\/", false},
                                   {'\b', "\\b", false}, {'\f', "\\f", false},   {'\n', "\\n", true},
                                   {'\r', "\\r", true},  {'\t', "\\t", true}};

static void escape(std::string& out, const std::string& s) {
  out += '"';
  append_escaped(out, s, kEscapes, [](std::string& o, char c) {
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned char>(c));
      o += buf;
    } else {
      o += c;
    }
  });
  out += '"';
}

void Value::dump_to(std::string& out, int indent, int depth) const {
  auto newline = [&](int d) {
    if (indent < 0) return;
    out += '\n';
    out.append(static_cast<size_t>(indent * d), ' ');
  };
  switch (type_) {
    case Type::Null: out += "null"; break;
    case Type::Bool: out += bool_ ? "true" : "false"; break;
    case Type::Number: out += number_text(number_); break;
    case Type::String: escape(out, string_); break;
    case Type::Array: {
      out += '[';
      // Arrays of numbers stay on one line even when pretty-printing.
      bool flat = true;
      for (const auto& v : array_) flat = flat && (v.type_ == Type::Number || v.type_ == Type::Null);
      for (size_t i = 0; i < array_.size(); ++i) {
        if (i) out += indent >= 0 && flat ? ", " : ",";
        if (!flat) newline(depth + 1);
        array_[i].dump_to(out, indent, depth + 1);
      }
      if (!flat && !array_.empty()) newline(depth);
      out += ']';
      break;
    }
    case Type::Object: {
      out += '{';
      for (size_t i = 0; i < object_.size(); ++i) {
        if (i) out += ',';
        newline(depth + 1);
        escape(out, object_[i].first);
        out += indent >= 0 ? ": " : ":";
        object_[i].second.dump_to(out, indent, depth + 1);
      }
      if (!object_.empty()) newline(depth);
      out += '}';
      break;
    }
  }
}

std::string Value::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  return out;
}

namespace detail {
struct Parser {
  const std::string& s;
  size_t i = 0;
  int depth = 0;
  size_t values = 0;

  [[noreturn]] void fail(const std::string& what) {
    throw Error(ErrorCode::ParseError, "JSON: " + what + " at byte " + std::to_string(i));
  }
  [[noreturn]] void too_much(const std::string& what, size_t limit) {
    throw Error(ErrorCode::LimitExceeded,
                "JSON: " + what + " at byte " + std::to_string(i) + " (the limit is " + std::to_string(limit) + ")");
  }
  void ws() {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\n' || s[i] == '\r' || s[i] == '\t')) ++i;
  }
  /// Steps over `c` if it comes next.
  bool eat(char c) {
    if (i >= s.size() || s[i] != c) return false;
    ++i;
    return true;
  }
  bool lit(const char* w) {
    const size_t n = std::strlen(w);
    if (s.compare(i, n, w) == 0) {
      i += n;
      return true;
    }
    return false;
  }
  Value value() {
    ws();
    if (i >= s.size()) fail("unexpected end");
    if (++depth > limits::kMaxJsonDepth) too_much("nesting too deep", static_cast<size_t>(limits::kMaxJsonDepth));
    if (++values > limits::kMaxJsonValues) too_much("too many values", limits::kMaxJsonValues);
    Value v;
    const char c = s[i];
    if (c == '{') v = object();
    else if (c == '[') v = array();
    else if (c == '"') v = Value(str());
    else if (lit("true")) v = Value(true);
    else if (lit("false")) v = Value(false);
    else if (lit("null")) v = Value();
    else v = Value(number());
    --depth;
    return v;
  }
  // RFC 8259 number: -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?, finite as a double
  // (the page's JSON.parse refuses "07" and "1."; a value beyond double's range is refused here,
  // not read as infinity).
  double number() {
    const size_t start = i;
    auto digit = [&] { return i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); };
    auto digits = [&] {
      if (!digit()) return false;
      while (digit()) ++i;
      return true;
    };
    if (i < s.size() && s[i] == '-') ++i;
    if (!digit()) fail("invalid value");
    if (s[i] == '0') ++i;
    else digits();
    bool ok = true;
    if (i < s.size() && s[i] == '.') ok = (++i, digits());
    if (ok && i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
      ++i;
      if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
      ok = digits();
    }
    while (i < s.size() && (digit() || s[i] == '.' || s[i] == 'e' || s[i] == 'E' || s[i] == '+' || s[i] == '-')) {
      ok = false;
      ++i;
    }
    const std::string t = s.substr(start, i - start);
    if (!ok) fail("invalid number '" + t + "'");
    const double d = tristim::parse_double(t.c_str(), nullptr);
    if (!std::isfinite(d)) fail("number '" + t + "' is out of range");
    return d;
  }
  static void utf8(std::string& out, unsigned cp) {
    if (cp < 0x80) out += static_cast<char>(cp);
    else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }
  unsigned hex4() {
    if (i + 4 > s.size()) fail("bad \\u escape");
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s[i++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= c - '0';
      else if (c >= 'a' && c <= 'f') v |= c - 'a' + 10;
      else if (c >= 'A' && c <= 'F') v |= c - 'A' + 10;
      else fail("bad \\u escape");
    }
    return v;
  }
  std::string str() {
    ++i;  // opening quote
    std::string out;
    while (true) {
      if (i >= s.size()) fail("unterminated string");
      const char c = s[i++];
      if (c == '"') break;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in string");
      if (out.size() >= limits::kMaxJsonString) too_much("string too long", limits::kMaxJsonString);
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i >= s.size()) fail("unterminated string");
      const char e = s[i++];
      if (e != 'u') {
        const char spelled[2] = {'\\', e};
        const CharEscape* row = escape_named(std::string_view(spelled, 2), kEscapes);
        if (!row) fail("bad escape");
        out += row->raw;
        continue;
      }
      unsigned cp = hex4();  // \uXXXX, a surrogate pair as one code point
      if (cp >= 0xD800 && cp < 0xDC00 && i + 1 < s.size() && s[i] == '\\' && s[i + 1] == 'u') {
        i += 2;
        const unsigned lo = hex4();
        cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
      }
      utf8(out, cp);
    }
    return out;
  }
  Value array() {
    ++i;
    Value v = Value::array();
    ws();
    if (eat(']')) return v;
    while (true) {
      if (v.size() >= limits::kMaxJsonArray) too_much("array too long", limits::kMaxJsonArray);
      v.push(value());
      ws();
      if (eat(',')) continue;
      if (eat(']')) return v;
      fail("expected ',' or ']'");
    }
  }
  Value object() {
    ++i;
    Value v = Value::object();
    std::unordered_map<std::string, size_t> index;  // a repeated key replaces the earlier value
    ws();
    if (eat('}')) return v;
    while (true) {
      ws();
      if (i >= s.size() || s[i] != '"') fail("expected a key");
      if (v.size() >= limits::kMaxJsonArray) too_much("object with too many members", limits::kMaxJsonArray);
      std::string key = str();
      ws();
      if (!eat(':')) fail("expected ':'");
      Value member = value();
      const auto at = index.find(key);
      if (at != index.end()) {
        v.object_[at->second].second = std::move(member);
      } else {
        index.emplace(key, v.object_.size());
        v.object_.emplace_back(std::move(key), std::move(member));
      }
      ws();
      if (eat(',')) continue;
      if (eat('}')) return v;
      fail("expected ',' or '}'");
    }
  }
};
}  // namespace detail

Value parse(const std::string& text) {
  if (text.size() > limits::kMaxJsonBytes)
    throw Error(ErrorCode::LimitExceeded, "JSON: " + std::to_string(text.size()) + " bytes, over the limit of " +
                                              std::to_string(limits::kMaxJsonBytes) + " for a profile or recipe");
  detail::Parser p{text};
  Value v = p.value();
  p.ws();
  if (p.i != text.size()) p.fail("trailing characters");
  return v;
}

}  // namespace tristim::json

namespace tristim::fields {

json::Value parse_document(const std::string& text, const Document& d) {
  try {
    return json::parse(text);
  } catch (const Error& e) {
    const bool limit = e.code() == ErrorCode::LimitExceeded;
    throw Error(limit ? e.code() : d.invalid, std::string(d.what) + (limit ? ": " : ": not valid JSON: ") + e.what());
  }
}

void check_document(const json::Value& o, const Document& d) {
  const std::string what = d.what;
  if (!o.is_object())
    throw Error(d.invalid, std::string(std::strchr("aeiou", what[0]) ? "an " : "a ") + what + " must be a JSON object");
  const json::Value* fmt = o.find("format");
  if (!fmt || !fmt->is_string() || fmt->as_string() != d.format)
    throw Error(d.invalid, "not a tristim " + what + " (\"format\" must be \"" + d.format + "\")");
  const json::Value* ver = o.find("version");
  if (!ver) throw Error(d.invalid, what + ": missing field 'version'");
  if (!ver->is_number() || ver->as_number() != d.version)
    throw Error(d.version_code, what + " version " + (ver->is_number() ? json::number_text(ver->as_number()) : "?") +
                                    " is not supported (this tristim reads version " + std::to_string(d.version) + ")");
}

}  // namespace tristim::fields
