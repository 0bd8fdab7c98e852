#include "sph_solver/neighbours/cell_coordinates.hpp"

#include <cstddef>

namespace tankfsi::sph {

namespace {

// True if the highest set bit of x is lower than the highest set bit of y.
bool has_lower_top_bit(std::uint64_t x, std::uint64_t y) { return x < y && x < (x ^ y); }

}  // namespace

bool morton_less(const CellCoordinates& a, const CellCoordinates& b) {
  std::size_t deciding_axis = 0;
  std::uint64_t deciding_difference = 0;
  for (std::size_t axis = 0; axis < a.size(); ++axis) {
    const std::uint64_t difference = static_cast<std::uint64_t>(a[axis]) ^ static_cast<std::uint64_t>(b[axis]);
    // Strictly higher top bit only: on a tie the earlier axis keeps the decision,
    // which makes x the most significant axis within a bit level.
    if (has_lower_top_bit(deciding_difference, difference)) {
      deciding_axis = axis;
      deciding_difference = difference;
    }
  }
  return a[deciding_axis] < b[deciding_axis];
}

}  // namespace tankfsi::sph
