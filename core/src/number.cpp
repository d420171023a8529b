// Decimal text -> double: Clinger's exact fast path, std::strtod for the rest (see number.hpp).
#include "tristim/number.hpp"

#include <cstdint>
#include <cstdlib>

namespace tristim {

namespace {

// 10^0 .. 10^22: every one is an exact double (5^22 < 2^53).
constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                             1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
// std::isspace in the "C" locale, which is what std::strtod skips.
inline bool is_space(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

}  // namespace

namespace detail {

bool parse_double_fast(const char* text, double* value, const char** end) noexcept {
  const char* p = text;
  while (is_space(*p)) ++p;
  bool negative = false;
  if (*p == '+' || *p == '-') negative = *p++ == '-';
  if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) return false;  // hexadecimal: strtod's
  std::uint64_t m = 0;  // significant digits (leading zeros dropped), at most 19 of them
  int digits = 0;       // how many are in m
  std::int64_t exp10 = 0;  // value = m * 10^exp10 (64 bits: one step per fraction digit)
  bool any = false;     // at least one mantissa digit (else "", ".", "inf", "nan": strtod's)
  for (; is_digit(*p); ++p) {
    any = true;
    if (m == 0 && *p == '0') continue;
    if (digits == 19) return false;
    m = m * 10 + static_cast<unsigned>(*p - '0');
    ++digits;
  }
  if (*p == '.') {
    for (++p; is_digit(*p); ++p) {
      any = true;
      --exp10;
      if (m == 0 && *p == '0') continue;
      if (digits == 19) return false;
      m = m * 10 + static_cast<unsigned>(*p - '0');
      ++digits;
    }
  }
  if (!any) return false;
  if (*p == 'e' || *p == 'E') {  // an exponent only counts with at least one digit ("1e" reads "1")
    const char* q = p + 1;
    bool exp_negative = false;
    if (*q == '+' || *q == '-') exp_negative = *q++ == '-';
    if (is_digit(*q)) {
      std::int64_t e = 0;
      for (; is_digit(*q); ++q) {
        if (e >= 100000000) {  // a huge exponent: zero stays zero, anything else is strtod's
          if (m != 0) return false;
          continue;
        }
        e = e * 10 + (*q - '0');
      }
      exp10 += exp_negative ? -e : e;
      p = q;
    }
  }
  double v = 0.0;
  if (m != 0) {
    if (m > (std::uint64_t{1} << 53)) return false;
    v = static_cast<double>(m);  // exact
    if (exp10 > 0) {
      if (exp10 > 22) return false;
      v *= kPow10[exp10];  // one correctly rounded operation on exact operands
    } else if (exp10 < 0) {
      if (exp10 < -22) return false;
      v /= kPow10[-exp10];
    }
  }
  *value = negative ? -v : v;
  *end = p;
  return true;
}

}  // namespace detail

double parse_double(const char* text, char** end) noexcept {
  double v;
  const char* stop;
  if (detail::parse_double_fast(text, &v, &stop)) {
    if (end) *end = const_cast<char*>(stop);
    return v;
  }
  return std::strtod(text, end);
}

}  // namespace tristim
