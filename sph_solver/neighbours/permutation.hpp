#pragma once
// Reordering of per-particle arrays. The solver keeps particles in cell order
// (CellList::cell_order) so that neighbours sit close in memory; every per-particle
// array (positions, velocities, pressures, ...) is reordered with the same permutation.
// Convention: order[k] is the old index of the element that moves to position k.
#include <cstddef>
#include <span>
#include <stdexcept>
#include <vector>

namespace tankfsi::sph {

/// True if order holds each of 0 .. size-1 exactly once.
[[nodiscard]] inline bool is_permutation(std::span<const int> order) {
  std::vector<bool> seen(order.size(), false);
  for (int index : order) {
    if (index < 0 || static_cast<std::size_t>(index) >= order.size() || seen[static_cast<std::size_t>(index)]) {
      return false;
    }
    seen[static_cast<std::size_t>(index)] = true;
  }
  return true;
}

/// result[k] = values[order[k]]. Throws std::invalid_argument if the sizes differ or
/// order is not a permutation (a wrong order would silently mix particles' data).
template <class T>
[[nodiscard]] std::vector<T> apply_permutation(const std::vector<T>& values, std::span<const int> order) {
  if (values.size() != order.size() || !is_permutation(order)) {
    throw std::invalid_argument("apply_permutation: order is not a permutation of the values' indices");
  }
  std::vector<T> result;
  result.reserve(values.size());
  for (int index : order) result.push_back(values[static_cast<std::size_t>(index)]);
  return result;
}

}  // namespace tankfsi::sph
