#pragma once
// NeighbourList: every particle's neighbours in compressed sparse row (CSR) form,
// the layout the solver's pair loops and the PPE matrix assembly walk through:
// the neighbours of i are indices[offsets[i] .. offsets[i+1]).
#include <span>
#include <vector>

namespace tankfsi::sph {

struct NeighbourList {
  std::vector<int> offsets;  ///< size = particle count + 1, offsets[0] = 0
  std::vector<int> indices;  ///< neighbour indices, row after row

  [[nodiscard]] int particle_count() const { return offsets.empty() ? 0 : static_cast<int>(offsets.size()) - 1; }
  [[nodiscard]] std::span<const int> neighbours_of(int i) const {
    return std::span<const int>(indices).subspan(static_cast<std::size_t>(offsets[static_cast<std::size_t>(i)]),
                                                 static_cast<std::size_t>(offsets[static_cast<std::size_t>(i) + 1] -
                                                                          offsets[static_cast<std::size_t>(i)]));
  }
};

}  // namespace tankfsi::sph
