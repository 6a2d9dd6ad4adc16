// hilbertIndex — the position of a cell along the Hilbert curve over a 65536 × 65536 grid: cells
// next to each other on the curve are next to each other in the plane (spawn spots, spawn_layout.cpp;
// the spatial row order, row_order.cpp). Private to throng_sim.
#pragma once
#include <cstdint>
#include <utility>

namespace throng::sim {

/// Position of cell (x, y), x and y < 65536, along the Hilbert curve (< 2^32).
[[nodiscard]] inline std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t n = 1u << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

}  // namespace throng::sim
