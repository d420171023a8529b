// Conversions of fixed-size numbers (convert.hpp's rules): std::array and Vec3 <-> Array, row-major
// matrices (Mat3, 3 × P coefficients, N × 3 patches) and std::vector<Vec3> <-> Float64Array.
#pragma once
#include "convert.hpp"

namespace tristim::wasm {

/// Fixed-size numbers: a plain Array (corners, triplets, 3 × 3 matrices).
template <class T, size_t N>
struct Conv<std::array<T, N>> {
  static val to(const std::array<T, N>& a) {
    val out = val::array();
    for (const auto& x : a) out.call<void>("push", Conv<T>::to(x));
    return out;
  }
  static std::array<T, N> from(const val& v) {
    std::array<T, N> out{};
    if (absent(v)) return out;
    if constexpr (std::is_arithmetic_v<T>) {
      const auto d = vector_from<double>(v);
      if (d.size() != N) refuse("expected " + std::to_string(N) + " numbers, got " + std::to_string(d.size()));
      for (size_t i = 0; i < N; ++i) out[i] = static_cast<T>(d[i]);
    } else {  // an Array of N elements, each converted as a T (per-channel curves, ranges)
      if (type_of(v) != "object" || v["length"].isUndefined() || v["length"].as<size_t>() != N)
        refuse("expected an array of " + std::to_string(N) + " elements");
      for (size_t i = 0; i < N; ++i) out[i] = Conv<T>::from(v[i]);
    }
    return out;
  }
};
template <>
struct Conv<Vec3> {
  static val to(const Vec3& v) { return Conv<std::array<double, 3>>::to({v[0], v[1], v[2]}); }
  static Vec3 from(const val& v) {
    if (absent(v)) refuse("expected [X, Y, Z]");
    const auto a = Conv<std::array<double, 3>>::from(v);
    return Vec3(a[0], a[1], a[2]);
  }
};
/// Row-major matrices: Mat3 (9 values) and the 3 × P coefficients of a model (3P values).
template <class M>
struct MatrixConv {
  static val to(const M& m) {
    std::vector<double> v(m.size());
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) v[r * m.cols() + c] = m(r, c);
    return typed_array(v.data(), v.size());
  }
  static M from(const val& a) {
    const auto v = vector_from<double>(a);
    if (v.size() % 3 != 0) refuse("length " + std::to_string(v.size()) + " is not a multiple of 3");
    const Eigen::Index n = static_cast<Eigen::Index>(v.size() / 3);
    constexpr bool patches = M::RowsAtCompileTime == Eigen::Dynamic && M::ColsAtCompileTime == 3;  // N × 3
    M m(patches ? n : 3, M::ColsAtCompileTime == Eigen::Dynamic ? n : 3);
    if (static_cast<size_t>(m.size()) != v.size()) refuse("expected " + std::to_string(m.size()) + " values");
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) m(r, c) = v[r * m.cols() + c];
    return m;
  }
};
template <> struct Conv<Mat3> : MatrixConv<Mat3> {};
template <> struct Conv<Eigen::MatrixXd> : MatrixConv<Eigen::MatrixXd> {};
template <> struct Conv<Eigen::Matrix<double, Eigen::Dynamic, 3>> : MatrixConv<Eigen::Matrix<double, Eigen::Dynamic, 3>> {};
template <>
struct Conv<std::vector<Vec3>> {
  static val to(const std::vector<Vec3>& v) {
    std::vector<double> flat;
    flat.reserve(3 * v.size());
    for (const auto& x : v) flat.insert(flat.end(), {x[0], x[1], x[2]});
    return typed_array(flat.data(), flat.size());
  }
  static std::vector<Vec3> from(const val& a) {
    const auto d = vector_from<double>(a);
    if (d.size() % 3 != 0) refuse("length " + std::to_string(d.size()) + " is not a multiple of 3");
    std::vector<Vec3> out;
    for (size_t i = 0; i < d.size(); i += 3) out.emplace_back(d[i], d[i + 1], d[i + 2]);
    return out;
  }
};

}  // namespace tristim::wasm
