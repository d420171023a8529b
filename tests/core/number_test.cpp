// parse_double (tristim/number.hpp) against std::strtod: the same double bit for bit and the same end
// pointer, on hand-picked edge cases and on generated strings (random digits, decimal points,
// exponents, signs, white space, trailing text, and %.Ng prints of random doubles as real files
// hold them). Runs in both builds: natively against glibc's strtod, in wasm against musl's.
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "tristim/number.hpp"

using namespace tristim;

namespace {

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

struct Tally {
  long checked = 0, fast = 0, mismatches = 0;
  std::string first;  // the first mismatch, with both results
};

void check(const std::string& s, Tally& t) {
  char* end_ref = nullptr;
  char* end_new = nullptr;
  const double ref = std::strtod(s.c_str(), &end_ref);
  const double got = parse_double(s.c_str(), &end_new);
  double fast_value;
  const char* fast_end;
  if (detail::parse_double_fast(s.c_str(), &fast_value, &fast_end)) ++t.fast;
  ++t.checked;
  const bool same_value = bits(ref) == bits(got) || (ref != ref && got != got);  // NaN payloads aside
  if (!same_value || end_ref != end_new) {
    if (t.mismatches++ == 0) {
      char buf[200];
      std::snprintf(buf, sizeof buf, " -> parse_double %.17g (0x%016" PRIx64 ", end %d), strtod %.17g (0x%016" PRIx64 ", end %d)",
                    got, bits(got), static_cast<int>(end_new - s.c_str()), ref, bits(ref),
                    static_cast<int>(end_ref - s.c_str()));
      t.first = "'" + s + "'" + buf;
    }
  }
}

}  // namespace

TEST_CASE("parse_double: edge cases read as std::strtod reads them", "[io][number]") {
  const std::vector<std::string> cases = {
      "", " ", "+", "-", ".", "-.", "+.e1", "0", "-0", "+0.0", "-0.000e-5", "00012.5000", ".5", "5.", "-5.e-1",
      "1e", "1e+", "1e-", "1E5", "1.e5", ".e5", "e5", "1e+05", "1e-0", "0x1p3", "-0X10", "0x", "inf", "-Infinity",
      "nan", "NAN(123)", " \t\n\v\f\r1.5abc", "  -7", "9007199254740992", "9007199254740993", "9007199254740991",
      "-9007199254740993e-3", "1e22", "1e23", "1e-22", "1e-23", "9e22", "123456789012345678",
      "1234567890123456789", "12345678901234567890", "0.1", "0.2", "0.3", "0.7", "2.2250738585072014e-308",
      "4.9e-324", "1.7976931348623157e308", "1e309", "-1e309", "1e-400", "0e999999999999",
      "1e999999999999", "1e-999999999999", "0.000000000000000000000000001", "1,5", "1.5.3", "--1", "+-1",
      "3.14159265358979323846", "100000000000000000000000", "1.0000000000000000000001",
      "0.00000000000000000000000000000000000000000000000000000000000000000000000001e70",
      "1000000000000000000000e-20", "8.589973e9", "1.7976931348623159e308", "5e-324", "2.5e-324",
      "0.0000001", "1234.5678e-3", "780", "380.0,0.0512", "0.0512\r\n"};
  Tally t;
  for (const auto& s : cases) check(s, t);
  INFO("first mismatch: " << t.first);
  CHECK(t.mismatches == 0);
  CHECK(t.fast > 10);  // the fast path is in use, not only the fallback
}

TEST_CASE("parse_double: generated strings read as std::strtod reads them", "[io][number]") {
  // mt19937 integers only: the same strings in both builds (library distributions differ).
  std::mt19937 rng(20261126);
  auto below = [&](unsigned n) { return static_cast<unsigned>(rng() % n); };
  auto digits = [&](unsigned n, std::string& s) {
    for (unsigned i = 0; i < n; ++i) s += static_cast<char>('0' + below(10));
  };
  Tally t;
  for (int i = 0; i < 200000; ++i) {
    std::string s;
    if (below(10) == 0) s += below(2) ? " " : "\t ";
    const unsigned sign = below(4);
    if (sign == 1) s += '-';
    if (sign == 2) s += '+';
    if (below(4) == 0) s += std::string(below(4), '0');  // leading zeros
    digits(below(4) == 0 ? below(22) : below(6), s);
    if (below(4) != 0) {
      s += '.';
      digits(below(4) == 0 ? below(24) : below(8), s);
    }
    if (below(3) == 0) {
      s += below(2) ? 'e' : 'E';
      const unsigned es = below(3);
      if (es == 1) s += '-';
      if (es == 2) s += '+';
      const unsigned ex = below(8) == 0 ? below(700) : below(30);
      if (below(10) == 0) s += "00";  // leading zeros of the exponent
      if (below(6) != 0) s += std::to_string(ex);  // else "1e" / "1e-": the exponent is not read
    }
    const unsigned tail = below(12);
    if (tail == 0) s += ',';
    if (tail == 1) s += "e";
    if (tail == 2) s += "e+";
    if (tail == 3) s += " 5";
    if (tail == 4) s += ".";
    check(s, t);
  }
  // Numbers as files hold them: %.Ng prints (N = 1..17) of doubles over many magnitudes.
  for (int i = 0; i < 100000; ++i) {
    const unsigned hi = rng() >> 5, lo = rng() >> 6;  // declaration order: the same draws in both builds
    const double mantissa = (static_cast<double>(hi) * 67108864.0 + lo) / 9007199254740992.0;
    const int e = static_cast<int>(below(80)) - 40;
    double v = mantissa;
    for (int k = 0; k < (e < 0 ? -e : e); ++k) v = e < 0 ? v / 10 : v * 10;
    if (below(2)) v = -v;
    char buf[64];
    const char* format = below(3) == 0 ? "%.*e" : "%.*g";  // one draw per statement (argument order is unspecified)
    const int precision = 1 + static_cast<int>(below(17));
    std::snprintf(buf, sizeof buf, format, precision, v);
    check(buf, t);
  }
  std::printf("parse_double: %ld strings, %ld by the fast path, %ld mismatches\n", t.checked, t.fast, t.mismatches);
  INFO("first mismatch: " << t.first);
  CHECK(t.mismatches == 0);
  CHECK(t.fast > t.checked / 3);             // most short numbers take the fast path
  CHECK(t.fast < t.checked - t.checked / 20);  // and the fallback is exercised too
}
