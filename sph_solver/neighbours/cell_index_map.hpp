#pragma once
// CellIndexMap: occupied cell -> cell index, an open-addressing hash table with
// linear probing. Hashing the occupied cells (instead of a dense array over the
// bounding box) keeps memory proportional to the number of particles however far
// apart they are: two clusters 10^6 search radii apart would need 10^18 dense
// cells in 3D but occupy only a handful. The table is kept between builds so a
// steady simulation does not reallocate it every step.
#include <cstddef>
#include <vector>

#include "sph_solver/neighbours/cell_coordinates.hpp"

namespace tankfsi::sph {

class CellIndexMap {
 public:
  /// Forget every entry, keeping the storage.
  void clear();
  /// The index stored for cell; if absent, stores index_if_absent and returns it.
  int find_or_insert(const CellCoordinates& cell, int index_if_absent);
  /// The index stored for cell, or -1.
  [[nodiscard]] int find(const CellCoordinates& cell) const;
  [[nodiscard]] std::size_t size() const { return size_; }

 private:
  void grow();
  [[nodiscard]] std::size_t slot_of(const CellCoordinates& cell) const;

  std::vector<CellCoordinates> keys_;
  std::vector<int> values_;  ///< -1 marks an empty slot
  std::size_t size_ = 0;
};

}  // namespace tankfsi::sph
