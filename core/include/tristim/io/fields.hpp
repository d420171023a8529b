// Field lists: a struct that crosses a boundary (recipe, profile, report) is declared once, as a
// list of its members with their JSON names, and its JSON writer and strict reader come from that
// list:
//
//   template <> struct Schema<ReferenceStage> {
//     static const FieldList<ReferenceStage>& fields() {
//       static const FieldList<ReferenceStage> f = {member<&ReferenceStage::chart>("chart"), ...};
//       return f;
//     }
//   };
//   (or, shorter: TRISTIM_FIELDS(ReferenceStage, member<&ReferenceStage::chart>("chart"), ...))
//
//   write(value)            -> a JSON object with the listed members in list order
//   read(json, value, ctx)  -> members read into `value`; an unknown member is refused with
//                              ctx.code naming its dotted path, a missing required one too; a
//                              missing optional one keeps the value's C++ default
//
// Members convert by Codec<T>: bool, integers, finite doubles, strings, std::vector, std::array,
// fixed-size Eigen vectors (arrays of numbers), Eigen::MatrixXd (an array of rows), std::map with
// string keys (objects) and every struct with a Schema. A member that is not one C++ member (an
// array gathered from several, a value written only in some states) is a Field with its own write
// and read functions.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "tristim/error.hpp"
#include "tristim/io/json.hpp"

namespace tristim::fields {

/// Who reads: the error code of a refusal and the prefix of its message ("recipe: ").
struct Context {
  ErrorCode code = ErrorCode::ProfileInvalid;
  const char* prefix = "";
  bool null_is_nan = false;  ///< a null number reads as NaN (how the writer spells a non-finite figure)
  bool missing_is_default = false;  ///< a missing required member keeps its C++ default (a JS caller's object)
  [[noreturn]] void refuse(const std::string& what) const { throw Error(code, prefix + what); }
};

/// "a.b" from "a" and "b" (the path of a member in messages).
inline std::string join(const std::string& path, const std::string& name) { return path.empty() ? name : path + "." + name; }

template <class S>
struct Field {
  const char* name;
  json::Value (*write)(const S&);
  /// nullptr: written only (reading it is refused).
  void (*read)(const json::Value&, S&, const Context&, const std::string& path);
  /// nullptr: always written; otherwise written only when it returns true.
  bool (*shown)(const S&) = nullptr;
  /// Absent from the input: refused (true) or the C++ default kept (false).
  bool required = true;
};
template <class S>
using FieldList = std::vector<Field<S>>;

/// Specialised per struct (see the header comment).
template <class S>
struct Schema;

template <class T, class = void>
struct has_schema : std::false_type {};
template <class T>
struct has_schema<T, std::void_t<decltype(Schema<T>::fields())>> : std::true_type {};

template <class T, class = void>
struct Codec;

template <class T>
json::Value write(const T& value) { return Codec<T>::write(value); }
template <class T>
void read(const json::Value& v, T& out, const Context& ctx, const std::string& path = "") { Codec<T>::read(v, out, ctx, path); }

// ---- scalars --------------------------------------------------------------------------------

template <>
struct Codec<bool> {
  static json::Value write(bool b) { return b; }
  static void read(const json::Value& v, bool& out, const Context& c, const std::string& p) {
    if (!v.is_bool()) c.refuse("'" + p + "' must be true or false");
    out = v.as_bool();
  }
};
template <>
struct Codec<double> {
  static json::Value write(double d) { return d; }
  static void read(const json::Value& v, double& out, const Context& c, const std::string& p) {
    if (v.is_null() && c.null_is_nan) {
      out = std::nan("");
      return;
    }
    if (!v.is_number() || !std::isfinite(v.as_number())) c.refuse("'" + p + "' must be a finite number");
    out = v.as_number();
  }
};
template <>
struct Codec<int> {
  static json::Value write(int i) { return i; }
  static void read(const json::Value& v, int& out, const Context& c, const std::string& p) {
    double d = 0;
    Codec<double>::read(v, d, c, p);
    if (d != std::floor(d) || std::fabs(d) > 1e9) c.refuse("'" + p + "' must be an integer");
    out = static_cast<int>(d);
  }
};
template <>
struct Codec<std::int64_t> {  // a count or time in seconds (exact up to 2^53 as a JSON number)
  static json::Value write(std::int64_t i) { return static_cast<long long>(i); }
  static void read(const json::Value& v, std::int64_t& out, const Context& c, const std::string& p) {
    double d = 0;
    Codec<double>::read(v, d, c, p);
    if (d != std::floor(d) || std::fabs(d) > 9007199254740992.0) c.refuse("'" + p + "' must be an integer");
    out = static_cast<std::int64_t>(d);
  }
};
template <>
struct Codec<std::string> {
  static json::Value write(const std::string& s) { return s; }
  static void read(const json::Value& v, std::string& out, const Context& c, const std::string& p) {
    if (!v.is_string()) c.refuse("'" + p + "' must be a string");
    out = v.as_string();
  }
};

// ---- sequences ------------------------------------------------------------------------------

/// Reads the elements of a JSON array (n: the length it must have, or -1 for any).
template <class T, class Out>
void read_elements(const json::Value& v, Out& out, long n, const Context& c, const std::string& p) {
  if (!v.is_array()) c.refuse("'" + p + "' must be an array");
  if (n >= 0 && static_cast<long>(v.size()) != n) c.refuse("'" + p + "' must have " + std::to_string(n) + " elements");
  const auto& a = v.as_array();
  for (size_t i = 0; i < a.size(); ++i) Codec<T>::read(a[i], out[i], c, p + "[" + std::to_string(i) + "]");
}
template <class Seq>
json::Value write_elements(const Seq& s) {
  json::Value a = json::Value::array();
  for (const auto& x : s) a.push(write(x));
  return a;
}

template <class T>
struct Codec<std::vector<T>> {
  static json::Value write(const std::vector<T>& v) { return write_elements(v); }
  static void read(const json::Value& v, std::vector<T>& out, const Context& c, const std::string& p) {
    std::vector<T> x(v.is_array() ? v.size() : 0);
    read_elements<T>(v, x, -1, c, p);
    out = std::move(x);
  }
};
// std::vector<bool> has no element references: its own codec.
template <>
struct Codec<std::vector<bool>> {
  static json::Value write(const std::vector<bool>& v) {
    json::Value a = json::Value::array();
    for (bool b : v) a.push(b);
    return a;
  }
  static void read(const json::Value& v, std::vector<bool>& out, const Context& c, const std::string& p) {
    if (!v.is_array()) c.refuse("'" + p + "' must be an array");
    out.clear();
    for (const auto& e : v.as_array()) {
      bool b = false;
      Codec<bool>::read(e, b, c, p + "[" + std::to_string(out.size()) + "]");
      out.push_back(b);
    }
  }
};
template <class T, size_t N>
struct Codec<std::array<T, N>> {
  static json::Value write(const std::array<T, N>& v) { return write_elements(v); }
  static void read(const json::Value& v, std::array<T, N>& out, const Context& c, const std::string& p) {
    read_elements<T>(v, out, static_cast<long>(N), c, p);
  }
};
/// A fixed-size Eigen vector (Vec3): an array of that many numbers.
template <int N>
struct Codec<Eigen::Matrix<double, N, 1>, std::enable_if_t<(N > 0)>> {
  static json::Value write(const Eigen::Matrix<double, N, 1>& v) {
    return json::Value(std::vector<double>(v.data(), v.data() + N));
  }
  static void read(const json::Value& v, Eigen::Matrix<double, N, 1>& out, const Context& c, const std::string& p) {
    read_elements<double>(v, out, N, c, p);
  }
};
/// A dynamic matrix: an array of rows, each an array of numbers.
template <>
struct Codec<Eigen::MatrixXd> {
  static json::Value write(const Eigen::MatrixXd& m) {
    json::Value a = json::Value::array();
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      std::vector<double> row(static_cast<size_t>(m.cols()));
      for (Eigen::Index k = 0; k < m.cols(); ++k) row[static_cast<size_t>(k)] = m(r, k);
      a.push(json::Value(row));
    }
    return a;
  }
  static void read(const json::Value& v, Eigen::MatrixXd& out, const Context& c, const std::string& p) {
    std::vector<std::vector<double>> rows;
    Codec<std::vector<std::vector<double>>>::read(v, rows, c, p);
    const size_t cols = rows.empty() ? 0 : rows[0].size();
    out.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols));
    for (size_t r = 0; r < rows.size(); ++r) {
      if (rows[r].size() != cols) c.refuse("'" + p + "' must have rows of one length");
      for (size_t k = 0; k < cols; ++k) out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = rows[r][k];
    }
  }
};
/// A map with string keys: a JSON object.
template <class V>
struct Codec<std::map<std::string, V>> {
  static json::Value write(const std::map<std::string, V>& m) {
    json::Value o = json::Value::object();
    for (const auto& [k, v] : m) o.set(k, fields::write(v));
    return o;
  }
  static void read(const json::Value& v, std::map<std::string, V>& out, const Context& c, const std::string& p) {
    if (!v.is_object()) c.refuse("'" + p + "' must be an object");
    out.clear();
    for (const auto& [k, x] : v.members()) Codec<V>::read(x, out[k], c, join(p, k));
  }
};

/// An optional value: null when absent.
template <class T>
struct Codec<std::optional<T>> {
  static json::Value write(const std::optional<T>& v) { return v ? Codec<T>::write(*v) : json::Value(); }
  static void read(const json::Value& v, std::optional<T>& out, const Context& c, const std::string& p) {
    if (v.is_null()) {
      out.reset();
      return;
    }
    T x{};
    Codec<T>::read(v, x, c, p);
    out = std::move(x);
  }
};

// ---- tables -------------------------------------------------------------------------------

/// One column of a table written as rows: a name and its values (texts or numbers), one per row.
struct Column {
  const char* name;
  const std::vector<std::string>* texts = nullptr;
  const std::vector<double>* numbers = nullptr;
  Column(const char* n, const std::vector<std::string>& v) : name(n), texts(&v) {}
  Column(const char* n, const std::vector<double>& v) : name(n), numbers(&v) {}
  size_t size() const { return texts ? texts->size() : numbers->size(); }
  json::Value at(size_t i) const { return texts ? json::Value((*texts)[i]) : json::Value((*numbers)[i]); }
};
/// Parallel columns as an array of objects, one per row ({"patch": "A1", "rms": 0.1}, ...); the
/// first column sets the number of rows.
inline json::Value rows(std::initializer_list<Column> columns) {
  json::Value a = json::Value::array();
  const size_t n = columns.size() ? columns.begin()->size() : 0;
  for (size_t i = 0; i < n; ++i) {
    json::Value o = json::Value::object();
    for (const Column& c : columns) o.set(c.name, c.at(i));
    a.push(o);
  }
  return a;
}

/// A JSON object from its members in order ({"before", x}, {"after", y}): the one way to write
/// an object that is no declared struct (a command's own summary).
inline json::Value object(std::initializer_list<std::pair<const char*, json::Value>> members) {
  json::Value o = json::Value::object();
  for (const auto& [name, value] : members) o.set(name, value);
  return o;
}

// ---- declared structs -----------------------------------------------------------------------

/// Appends the members of `list` of `s` to the JSON object `o`.
template <class S>
void write_list(const S& s, const FieldList<S>& list, json::Value& o) {
  for (const auto& f : list)
    if (!f.shown || f.shown(s)) o.set(f.name, f.write(s));
}
/// Appends the listed members of `s` to the JSON object `o`.
template <class S>
void write_members(const S& s, json::Value& o) { write_list(s, Schema<S>::fields(), o); }
/// Some of the listed members of `s`, in the order `names` gives (a short form of a struct).
template <class S>
json::Value write_picked(const S& s, std::initializer_list<const char*> names) {
  json::Value o = json::Value::object();
  for (const char* n : names)
    for (const auto& f : Schema<S>::fields())
      if (std::string(f.name) == n) o.set(n, f.write(s));
  return o;
}

/// The listed members of `o` into `s`: unknown members (other than `also_known`) and missing
/// required ones refused, naming "path.name".
template <class S>
void read_list(const json::Value& o, S& s, const FieldList<S>& list, const Context& c, const std::string& path,
               std::initializer_list<const char*> also_known = {}) {
  if (!o.is_object()) c.refuse(path.empty() ? std::string("expected a JSON object") : "'" + path + "' must be an object");
  for (const auto& [name, v] : o.members()) {
    bool known = false;
    for (const auto& f : list) known = known || name == f.name;
    for (const char* k : also_known) known = known || name == k;
    if (!known) c.refuse("unknown field '" + join(path, name) + "'");
  }
  for (const auto& f : list) {
    const json::Value* v = o.find(f.name);
    if (!v) {
      if (f.required && !c.missing_is_default) c.refuse("missing field '" + join(path, f.name) + "'");
      continue;
    }
    if (!f.read) c.refuse("'" + join(path, f.name) + "' cannot be read");
    f.read(*v, s, c, join(path, f.name));
  }
}
template <class S>
void read_members(const json::Value& o, S& s, const Context& c, const std::string& path,
                  std::initializer_list<const char*> also_known = {}) {
  read_list(o, s, Schema<S>::fields(), c, path, also_known);
}

/// What a struct's reader checks beyond its list, after its members are read (a known method, a
/// monotonic axis, …): specialise Checks<S>::check to refuse through the context.
template <class S>
struct Checks {
  static void check(S&, const Context&, const std::string&) {}
};

template <class S>
struct Codec<S, std::enable_if_t<has_schema<S>::value>> {
  static json::Value write(const S& s) {
    json::Value o = json::Value::object();
    write_members(s, o);
    return o;
  }
  static void read(const json::Value& v, S& out, const Context& c, const std::string& p) {
    read_members(v, out, c, p);
    Checks<S>::check(out, c, p);
  }
};

// ---- versioned documents --------------------------------------------------------------------

/// A document type: {"format": format, "version": version, ...}. `what` names it in messages
/// ("recipe", "absolute profile"); `invalid` is the code of a refusal, `version_code` the code of
/// another version.
struct Document {
  const char* format;
  int version;
  const char* what;
  ErrorCode invalid, version_code;
};

/// Parses a document's text: a stated limit (io/limits.hpp) keeps LimitExceeded, anything else
/// that is not JSON is `d.invalid`.
json::Value parse_document(const std::string& text, const Document& d);
/// Refuses what is not an object of the document's format and version (`d.invalid`,
/// `d.version_code`).
void check_document(const json::Value& o, const Document& d);

/// {"format", "version", then the listed members of `s`}.
template <class S>
json::Value write_document(const S& s, const Document& d) {
  json::Value o = json::Value::object();
  o.set("format", d.format);
  o.set("version", d.version);
  write_members(s, o);
  return o;
}
/// check_document, then the listed members into `s` (the context's code and prefix for them).
template <class S>
void read_document(const json::Value& o, S& s, const Document& d, const Context& c) {
  check_document(o, d);
  read_members(o, s, c, "", {"format", "version"});
}

// ---- declaring members ----------------------------------------------------------------------

template <class>
struct member_traits;
template <class S, class T>
struct member_traits<T S::*> {
  using owner = S;
  using type = T;
};

/// The C++ member M under a JSON name, converted by Codec<its type>.
template <auto M>
Field<typename member_traits<decltype(M)>::owner> member(const char* name, bool required = true) {
  using S = typename member_traits<decltype(M)>::owner;
  using T = typename member_traits<decltype(M)>::type;
  return {name, [](const S& s) { return Codec<T>::write(s.*M); },
          [](const json::Value& v, S& s, const Context& c, const std::string& p) { Codec<T>::read(v, s.*M, c, p); },
          nullptr, required};
}

/// `f`, written only when `shown(value)` is true.
template <class S>
Field<S> with_shown(Field<S> f, bool (*shown)(const S&)) {
  f.shown = shown;
  return f;
}

/// The member M written only when the bool member Has is true (null otherwise); written only.
template <auto Has, auto M>
Field<typename member_traits<decltype(M)>::owner> member_or_null(const char* name) {
  using S = typename member_traits<decltype(M)>::owner;
  using T = typename member_traits<decltype(M)>::type;
  return {name, [](const S& s) { return s.*Has ? Codec<T>::write(s.*M) : json::Value(); }, nullptr, nullptr, true};
}

/// A member written by a function of its own (a summary another module writes); written only.
template <auto M, json::Value (*Write)(const typename member_traits<decltype(M)>::type&)>
Field<typename member_traits<decltype(M)>::owner> member_as(const char* name) {
  using S = typename member_traits<decltype(M)>::owner;
  return {name, [](const S& s) { return Write(s.*M); }, nullptr, nullptr, true};
}

/// The member M2 of the member M1 (a value kept in a part of the struct), under a JSON name.
template <auto M1, auto M2>
Field<typename member_traits<decltype(M1)>::owner> nested(const char* name, bool required = true) {
  using S = typename member_traits<decltype(M1)>::owner;
  using T = typename member_traits<decltype(M2)>::type;
  return {name, [](const S& s) { return Codec<T>::write(s.*M1.*M2); },
          [](const json::Value& v, S& s, const Context& c, const std::string& p) { Codec<T>::read(v, s.*M1.*M2, c, p); },
          nullptr, required};
}

/// Some members of S written as one nested JSON object (a section of the document): the fields
/// List() gives, each read and written on the same S.
template <class S, const FieldList<S>& (*List)()>
Field<S> section(const char* name) {
  return {name, [](const S& s) {
            json::Value o = json::Value::object();
            write_list(s, List(), o);
            return o;
          },
          [](const json::Value& v, S& s, const Context& c, const std::string& p) { read_list(v, s, List(), c, p); }};
}

}  // namespace tristim::fields

/// Declares the field list of `Type` (inside namespace tristim::fields, at namespace scope).
#define TRISTIM_FIELDS(Type, ...)                             \
  template <>                                                 \
  struct Schema<Type> {                                       \
    static const FieldList<Type>& fields() {                  \
      static const FieldList<Type> list = {__VA_ARGS__};      \
      return list;                                            \
    }                                                         \
  }

/// A field list declared in a public header (so a binding sees `has_schema<Type>`) and defined in
/// one source file with TRISTIM_FIELDS_DEFINE (inside namespace tristim::fields, at namespace
/// scope). `name` names the struct in messages.
#define TRISTIM_FIELDS_DECLARE(Type)                  \
  template <>                                         \
  struct Schema<Type> {                               \
    static constexpr const char* name = #Type;        \
    static const FieldList<Type>& fields();           \
  }
#define TRISTIM_FIELDS_DEFINE(Type, ...)                       \
  const FieldList<Type>& Schema<Type>::fields() {              \
    static const FieldList<Type> list = {__VA_ARGS__};         \
    return list;                                               \
  }
