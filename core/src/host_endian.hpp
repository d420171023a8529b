// The byte order of the machine running the core (x86-64 and wasm: little-endian), for the image
// libraries that want 16-bit samples in a stated order.
#pragma once
#include <cstdint>
#include <cstring>

namespace tristim {

/// True when the low byte of a 16-bit word comes first in memory.
inline bool host_is_little_endian() {
  const std::uint16_t one = 1;
  std::uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

}  // namespace tristim
