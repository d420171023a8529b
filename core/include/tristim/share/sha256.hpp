// SHA-256 (FIPS 180-4, section 6.2). Used by share links and project files (share/link.hpp) for
// the digest of the expected results and the identity of the source images. A small
// implementation of our own: the wasm build has no crypto library (no OpenSSL, no libsodium),
// the page's Subtle Crypto is async and absent from workers on plain http origins, and the same
// function natively and in wasm gives the same digest by construction. Checked against the
// FIPS 180-2 example vectors (tests/core/share/sha256_test.cpp).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tristim {

/// Incremental SHA-256: update() any number of times, then digest() once.
class Sha256 {
 public:
  Sha256();
  void update(const void* data, std::size_t size);
  void update(std::string_view bytes) { update(bytes.data(), bytes.size()); }
  std::array<std::uint8_t, 32> digest();

 private:
  void block(const std::uint8_t* p);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t used_ = 0;
  std::uint64_t length_ = 0;  ///< bytes hashed so far
};

/// The 64 lower-case hex digits of SHA-256(bytes).
std::string sha256_hex(std::string_view bytes);
std::string sha256_hex(const void* data, std::size_t size);
std::string sha256_hex(const std::vector<std::uint8_t>& bytes);

}  // namespace tristim
