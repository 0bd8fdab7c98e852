#pragma once
// Integer coordinates of a cell of the neighbour-search grid, counted from the
// lower corner of the points' bounding box (so never negative for occupied cells),
// and the Z-order (Morton order) of cells, which keeps cells that are close in
// space close in the ordering (Morton 1966, IBM technical report).
#include <array>
#include <cstdint>

namespace tankfsi::sph {

/// (x, y, z) cell indices; z = 0 in 2D.
using CellCoordinates = std::array<std::int64_t, 3>;

/// Strict weak order of non-negative cell coordinates along the Z-order curve: the
/// order of the keys obtained by interleaving the coordinates' bits (x most significant
/// within each bit level, then y, then z). Computed without building the key, by
/// finding the axis whose coordinates differ in the most significant bit (Chan 2002,
/// "Closest-point problems simplified on the RAM"), so it works for any 63-bit coordinates.
[[nodiscard]] bool morton_less(const CellCoordinates& a, const CellCoordinates& b);

}  // namespace tankfsi::sph
