// A small JSON value with a strict parser and a round-trip writer (doubles printed with 17
// significant digits, so reading back gives the identical double). Used for profiles and CLI
// output; not a general-purpose library.
#pragma once
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tristim/error.hpp"

namespace tristim::json {

namespace detail {
struct Parser;
}

class Value {
 public:
  enum class Type { Null, Bool, Number, String, Array, Object };
  Value() = default;
  Value(std::nullptr_t) {}
  Value(bool b) : type_(Type::Bool), bool_(b) {}
  Value(double d) : type_(Type::Number), number_(d) {}
  Value(int i) : type_(Type::Number), number_(i) {}
  Value(long i) : type_(Type::Number), number_(static_cast<double>(i)) {}
  Value(long long i) : type_(Type::Number), number_(static_cast<double>(i)) {}
  Value(unsigned long i) : type_(Type::Number), number_(static_cast<double>(i)) {}
  Value(unsigned i) : type_(Type::Number), number_(i) {}
  Value(const char* s) : type_(Type::String), string_(s) {}
  Value(std::string s) : type_(Type::String), string_(std::move(s)) {}
  Value(const std::vector<double>& v);
  static Value array() { Value v; v.type_ = Type::Array; return v; }
  static Value object() { Value v; v.type_ = Type::Object; return v; }

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::Null; }
  bool is_number() const { return type_ == Type::Number; }
  bool is_string() const { return type_ == Type::String; }
  bool is_array() const { return type_ == Type::Array; }
  bool is_object() const { return type_ == Type::Object; }
  bool is_bool() const { return type_ == Type::Bool; }

  // Accessors throw Error(ProfileInvalid) naming `what` when the type is wrong.
  double as_number(const std::string& what = "value") const;
  /// A whole number in [lo, hi] (a double outside int's range cast to int is undefined
  /// behaviour; fuzz_profile found "patches": 7e9); Error(ProfileInvalid) naming `what` otherwise.
  int as_int(const std::string& what, int lo, int hi) const;
  bool as_bool(const std::string& what = "value") const;
  const std::string& as_string(const std::string& what = "value") const;
  const std::vector<Value>& as_array(const std::string& what = "value") const;
  std::vector<double> as_numbers(const std::string& what = "value") const;

  /// Array append / object set (keeps insertion order; set replaces an existing key).
  Value& push(Value v);
  Value& set(const std::string& key, Value v);
  /// Object member or nullptr.
  const Value* find(const std::string& key) const;
  /// Object member; Error(ProfileInvalid) "missing field <key>" if absent.
  const Value& at(const std::string& key) const;
  const std::vector<std::pair<std::string, Value>>& members() const { return object_; }
  size_t size() const { return type_ == Type::Array ? array_.size() : object_.size(); }

  /// Compact (indent < 0) or pretty JSON text.
  std::string dump(int indent = -1) const;

 private:
  friend struct detail::Parser;  // builds objects with a key index (no quadratic duplicate check)
  void dump_to(std::string& out, int indent, int depth) const;
  Type type_ = Type::Null;
  bool bool_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<Value> array_;
  std::vector<std::pair<std::string, Value>> object_;
};

/// Parses JSON text. Error(ParseError) with the byte offset on malformed input;
/// Error(LimitExceeded) beyond the limits of io/limits.hpp (size, depth, array/object length,
/// string length, number of values), so no document costs more than ~25 MB of values.
Value parse(const std::string& text);

/// Refuses an object member whose key is not in `known`: Error(code) "<where>: unknown field 'x'
/// (known: ...)". For readers that must not keep what they do not understand (profiles, recipes).
void reject_unknown(const Value& object, std::initializer_list<const char*> known, const std::string& where,
                    ErrorCode code);

/// A double as the shortest-safe round-trip text (17 significant digits; non-finite -> null).
std::string number_text(double d);

}  // namespace tristim::json
