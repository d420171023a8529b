// core/src/detmath.hpp: cbrt, exp, log, pow, sin, cos and atan2 that give the same bits natively and in
// wasm. Accuracy against the C library (glibc natively, musl in wasm), the C conventions at zeros,
// infinities and NaN, and one pinned hash of many results, which both builds must reproduce.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cfloat>
#include <cstring>
#include <limits>
#include <random>
#include <vector>
#include <algorithm>

#include "detmath.hpp"
#include "test_support.hpp"

namespace {

namespace dm = tristim::detmath;

std::int64_t ordered(double x) {  // doubles as integers in numeric order (adjacent doubles differ by 1)
  std::int64_t i;
  std::memcpy(&i, &x, sizeof i);
  return i < 0 ? std::numeric_limits<std::int64_t>::min() - i : i;
}
std::int64_t ulps(double a, double b) {
  const std::int64_t d = ordered(a) - ordered(b);
  return d < 0 ? -d : d;
}

// Uniform doubles in [lo, hi) from mt19937's integers only (the library's distributions differ
// between libstdc++ and libc++; these are the same draws in both builds).
struct Draw {
  std::mt19937 rng{2026};
  double unit() {
    const std::uint32_t hi = rng() >> 5, lo = rng() >> 6;  // declaration order: the same draws in both builds
    return (hi * 67108864.0 + lo) / 9007199254740992.0;
  }
  double in(double lo, double hi) { return lo + (hi - lo) * unit(); }
};

template <class Ours, class Libm>
std::int64_t worst_ulps(Ours ours, Libm libm, int n, double lo, double hi, bool log_scale = false) {
  Draw d;
  std::int64_t worst = 0;
  for (int i = 0; i < n; ++i) {
    const double x = log_scale ? std::pow(10.0, d.in(lo, hi)) : d.in(lo, hi);
    worst = std::max(worst, ulps(ours(x), libm(x)));
  }
  return worst;
}

}  // namespace

TEST_CASE("detmath: within 2 units in the last place of the C library", "[colorimetry][detmath]") {
  // Ranges the colour formulas use, and wider: Lab's cube root of X/Xn, CIEDE2000's e^(−t²) and
  // the sines and cosines of hue angles, the hue atan2 of a*, b*.
  // cbrt: the C libraries' own cube roots are up to 3 units off (glibc), so the bound against
  // them is 4; against x86-64's 64-bit-mantissa long double (natively) it is 1.
  CHECK(worst_ulps([](double x) { return dm::cbrt(x); }, [](double x) { return std::cbrt(x); }, 200000, -300, 300, true) <= 4);
  CHECK(worst_ulps([](double x) { return dm::cbrt(-x); }, [](double x) { return std::cbrt(-x); }, 20000, -5, 5, true) <= 4);
#if LDBL_MANT_DIG == 64
  CHECK(worst_ulps([](double x) { return dm::cbrt(x); },
                   [](double x) { return static_cast<double>(std::cbrt(static_cast<long double>(x))); }, 200000, -300, 300,
                   true) <= 1);
#endif
  CHECK(worst_ulps([](double x) { return dm::exp(x); }, [](double x) { return std::exp(x); }, 200000, -700, 700) <= 2);
  CHECK(worst_ulps([](double x) { return dm::exp(x); }, [](double x) { return std::exp(x); }, 200000, -20, 1) <= 2);
  CHECK(worst_ulps([](double x) { return dm::sin(x); }, [](double x) { return std::sin(x); }, 200000, -7, 7) <= 2);
  CHECK(worst_ulps([](double x) { return dm::cos(x); }, [](double x) { return std::cos(x); }, 200000, -7, 7) <= 2);
  CHECK(worst_ulps([](double x) { return dm::sin(x); }, [](double x) { return std::sin(x); }, 50000, -1e5, 1e5) <= 2);
  CHECK(worst_ulps([](double x) { return dm::cos(x); }, [](double x) { return std::cos(x); }, 50000, -1e5, 1e5) <= 2);
  // atan2 over every quadrant and ratios from 1e-6 to 1e6.
  Draw d;
  std::int64_t worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double y = (d.unit() < 0.5 ? -1 : 1) * std::pow(10.0, d.in(-3, 3));
    const double x = (d.unit() < 0.5 ? -1 : 1) * std::pow(10.0, d.in(-3, 3));
    worst = std::max(worst, ulps(dm::atan2(y, x), std::atan2(y, x)));
  }
  CHECK(worst <= 2);
  // log and pow, for the linearisations (power laws, log-polynomials, Guarnera's OECF): log over
  // the whole range and near 1 (where ln x is small and the reduction matters most), pow over the
  // camera-value range with exponents of gamma curves and beyond, and large |y·ln x|.
  CHECK(worst_ulps([](double x) { return dm::log(x); }, [](double x) { return std::log(x); }, 200000, -307, 307, true) <= 1);
  CHECK(worst_ulps([](double x) { return dm::log(x); }, [](double x) { return std::log(x); }, 200000, 0.5, 2.0) <= 1);
  CHECK(worst_ulps([](double x) { return dm::log(x); }, [](double x) { return std::log(x); }, 2000, -323, -308, true) <= 1);
  {
    Draw p;
    std::int64_t worst_pow = 0, worst_big = 0, worst_gamma = 0;
    for (int i = 0; i < 200000; ++i) {
      const double x = std::pow(10.0, p.in(-6, 3)), y = p.in(-5, 5);
      worst_pow = std::max(worst_pow, ulps(dm::pow(x, y), std::pow(x, y)));
      const double x2 = p.in(0.5, 2.0), y2 = p.in(-140, 140);  // y·ln x up to ±100
      worst_big = std::max(worst_big, ulps(dm::pow(x2, y2), std::pow(x2, y2)));
      for (double g : {2.4, 1.0 / 2.4, 2.2, 1.0 / 2.2, 0.45})
        worst_gamma = std::max(worst_gamma, ulps(dm::pow(x * 1e-3, g), std::pow(x * 1e-3, g)));
    }
    CHECK(worst_pow <= 2);
    CHECK(worst_big <= 2);
    CHECK(worst_gamma <= 2);
  }
  // Exact points.
  CHECK(dm::log(1.0) == 0.0);
  CHECK(dm::log(2.0) == std::log(2.0));
  CHECK(dm::pow(2.0, 10.0) == 1024.0);
  CHECK(dm::pow(9.0, 0.5) == 3.0);
  CHECK(dm::pow(-2.0, 3.0) == -8.0);
  CHECK(dm::pow(0.5, -3.0) == 8.0);
  CHECK(dm::cbrt(27.0) == 3.0);
  CHECK(dm::cbrt(-0.125) == -0.5);
  CHECK(dm::cbrt(1e-300) == Approx(1e-100).epsilon(1e-15));
  CHECK(dm::cbrt(5e-324) == Approx(std::cbrt(5e-324)).epsilon(1e-15));  // subnormal
  CHECK(dm::exp(0.0) == 1.0);
  CHECK(dm::exp(1.0) == Approx(2.718281828459045).epsilon(1e-15));
  CHECK(dm::exp(-745.0) == Approx(std::exp(-745.0)).epsilon(0.5));  // the smallest subnormal
  CHECK(dm::sin(0.0) == 0.0);
  CHECK(dm::cos(0.0) == 1.0);
}

TEST_CASE("detmath: C's conventions at zeros, infinities and NaN", "[colorimetry][detmath]") {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(std::signbit(dm::cbrt(-0.0)));
  CHECK(dm::cbrt(inf) == inf);
  CHECK(dm::cbrt(-inf) == -inf);
  CHECK(std::isnan(dm::cbrt(nan)));
  CHECK(dm::exp(inf) == inf);
  CHECK(dm::exp(-inf) == 0.0);
  CHECK(dm::exp(710.0) == inf);
  CHECK(std::isnan(dm::exp(nan)));
  CHECK(std::isnan(dm::sin(inf)));
  CHECK(std::isnan(dm::cos(-inf)));
  CHECK(std::isnan(dm::sin(nan)));
  CHECK(std::signbit(dm::sin(-0.0)));
  CHECK(dm::log(0.0) == -inf);
  CHECK(dm::log(-0.0) == -inf);
  CHECK(std::isnan(dm::log(-1.0)));
  CHECK(dm::log(inf) == inf);
  CHECK(std::isnan(dm::log(nan)));
  for (double y : {0.0, -0.0, 1.0, -1.0, 2.0, -2.0, 0.5, -0.5, 3.0, -3.0, 1e300, -1e300, inf, -inf, nan})
    for (double x : {0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 2.0, -2.0, 5e-324, inf, -inf, nan}) {
      const double ours = dm::pow(x, y), libm = std::pow(x, y);
      INFO("dm::pow(" << x << ", " << y << ") = " << ours << ", C library " << libm);
      if (std::isnan(libm)) {
        CHECK(std::isnan(ours));
      } else {
        CHECK(ulps(ours, libm) <= 2);
        CHECK(std::signbit(ours) == std::signbit(libm));
      }
    }
  for (double y : {0.0, -0.0, 1.0, -1.0, inf, -inf, nan})
    for (double x : {0.0, -0.0, 1.0, -1.0, inf, -inf, nan}) {
      const double ours = dm::atan2(y, x), libm = std::atan2(y, x);
      INFO("dm::atan2(" << y << ", " << x << ") = " << ours << ", C library " << libm);
      if (std::isnan(libm)) {
        CHECK(std::isnan(ours));
      } else {
        CHECK(ours == libm);
        CHECK(std::signbit(ours) == std::signbit(libm));
      }
    }
}

TEST_CASE("detmath: log_float within 1 unit of the float's last place, C's conventions", "[colorimetry][detmath]") {
  // The reference: the double log (detmath's, within 1 unit of a double) rounded to float; at most
  // 1 float unit apart from it over every binade of positive floats, subnormals included.
  Draw d;
  std::int64_t worst = 0;
  for (int i = 0; i < 300000; ++i) {
    const double mantissa = d.in(0.5, 1.0);
    const int exponent = static_cast<int>(d.in(-149, 129));
    const float x = static_cast<float>(std::ldexp(mantissa, exponent));
    if (!(x > 0.f) || std::isinf(x)) continue;
    const float ours = dm::log_float(x), ref = static_cast<float>(dm::log(x));
    std::int32_t a, b;
    std::memcpy(&a, &ours, 4);
    std::memcpy(&b, &ref, 4);
    INFO("log_float(" << x << ") = " << ours << ", reference " << ref);
    REQUIRE(std::signbit(ours) == std::signbit(ref));
    worst = std::max<std::int64_t>(worst, std::abs(std::int64_t(a) - std::int64_t(b)));
  }
  CHECK(worst <= 1);
  CHECK(dm::log_float(1.0f) == 0.0f);
  CHECK(dm::log_float(0.0f) == -std::numeric_limits<float>::infinity());
  CHECK(dm::log_float(-0.0f) == -std::numeric_limits<float>::infinity());
  CHECK(std::isnan(dm::log_float(-1.0f)));
  CHECK(std::isnan(dm::log_float(std::numeric_limits<float>::quiet_NaN())));
  CHECK(dm::log_float(std::numeric_limits<float>::infinity()) == std::numeric_limits<float>::infinity());
  CHECK(dm::log_float(std::numeric_limits<float>::denorm_min()) == static_cast<float>(dm::log(std::numeric_limits<float>::denorm_min())));
}

TEST_CASE("detmath: log_float_n gives log_float's bits, four at a time or one by one", "[colorimetry][detmath]") {
  // Every binade of positive floats (subnormals included), with zeros, negatives, infinities and
  // NaN sprinkled in so that some groups of four take the vector path and others log_float;
  // lengths that leave a tail; in place and out of place.
  Draw d;
  const float specials[] = {0.0f, -0.0f, -1.0f, std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::max(), std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::min(), 1.0f};
  std::vector<float> in(200003);
  for (float& x : in) {
    if (d.in(0, 1) < 0.01) {
      x = specials[static_cast<int>(d.in(0, 9.999))];
    } else {
      const double mantissa = d.in(0.5, 1.0);
      const int exponent = static_cast<int>(d.in(-149, 128.999));
      x = static_cast<float>(std::ldexp(mantissa, exponent));
    }
  }
  std::vector<float> out(in.size()), same = in;
  dm::log_float_n(in.data(), out.data(), in.size());
  dm::log_float_n(same.data(), same.data(), same.size());
  size_t differ = 0, first = in.size();
  for (size_t i = 0; i < in.size(); ++i) {
    const float ref = dm::log_float(in[i]);
    if (std::memcmp(&ref, &out[i], 4) != 0 || std::memcmp(&ref, &same[i], 4) != 0) {
      ++differ;
      first = std::min(first, i);
    }
  }
  INFO("first difference at " << first << " (x = " << (first < in.size() ? in[first] : 0.f) << ")");
  CHECK(differ == 0);
}

TEST_CASE("detmath: the same bits in every build (a pinned hash of 100,000 results)", "[colorimetry][detmath]") {
  // Natively and in wasm this test must see the same hash: the functions use IEEE operations
  // only. A change to detmath.hpp that moves a bit changes the hash; re-pin it in both builds.
  Draw d;
  tristim::test::BitHash h;
  for (int i = 0; i < 20000; ++i) {
    const double a = d.in(-10, 10), b = d.in(1e-3, 200);
    h.add(dm::cbrt(b));
    h.add(dm::exp(a));
    h.add(dm::sin(a));
    h.add(dm::cos(a));
    h.add(dm::atan2(a, d.in(-10, 10)));
  }
  CHECK(h.value == 0x6ef1a704ce2f7863ULL);
  // log and pow, a hash of their own: the one above stays as it was.
  h = {};
  for (int i = 0; i < 20000; ++i) {
    const double mantissa = d.in(0.5, 1.0);  // one draw per statement: the same order in both builds
    const int exponent = static_cast<int>(d.in(-60, 60));
    const double x = std::ldexp(mantissa, exponent), y = d.in(-8, 8);
    h.add(dm::log(x));
    h.add(dm::pow(x, y));
    h.add(dm::pow(d.in(0, 1), 1.0 / 2.4));
  }
  CHECK(h.value == 0x070bb164dcd5766eULL);
  // log_float, a hash of its own.
  h = {};
  for (int i = 0; i < 20000; ++i) {
    const double mantissa = d.in(0.5, 1.0);
    const int exponent = static_cast<int>(d.in(-140, 128));
    h.add(dm::log_float(static_cast<float>(std::ldexp(mantissa, exponent))));
  }
  CHECK(h.value == 0xf48036e62f272d03ULL);
}
