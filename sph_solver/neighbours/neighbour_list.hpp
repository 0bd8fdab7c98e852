#pragma once
// NeighbourList: every particle's neighbours in compressed sparse row (CSR) form,
// the layout the solver's pair loops and the PPE matrix assembly walk through:
// the neighbours of i are indices[offsets[i] .. offsets[i+1]).
//
// With each neighbour it keeps the pair's distance and, when built for a kernel,
// the kernel's value and slope there: a step evaluates each pair's kernel once
// for all its sums (density, divergences, viscosity, PPE, pressure gradient,
// shifting) rather than once per sum.
#include <span>
#include <vector>

#include "sph_solver/kernels/kernel.hpp"

namespace tankfsi::sph {

struct NeighbourList {
  std::vector<int> offsets;       ///< size = row count + 1, offsets[0] = 0
  std::vector<int> indices;       ///< neighbour indices, row after row
  std::vector<double> distances;  ///< r = |x_i - x_j| of each entry
  std::vector<double> values;     ///< W(r) of each entry (empty: built without a kernel)
  std::vector<double> slopes;     ///< dW/dr at r of each entry (empty: built without a kernel)

  [[nodiscard]] int particle_count() const { return offsets.empty() ? 0 : static_cast<int>(offsets.size()) - 1; }
  [[nodiscard]] std::span<const int> neighbours_of(int i) const {
    return std::span<const int>(indices).subspan(static_cast<std::size_t>(offsets[static_cast<std::size_t>(i)]),
                                                 static_cast<std::size_t>(offsets[static_cast<std::size_t>(i) + 1] -
                                                                          offsets[static_cast<std::size_t>(i)]));
  }
};

/// Fills the kernel's value and slope of every entry of `list` from its distance.
inline void add_kernel_values(NeighbourList& list, const Kernel& kernel) {
  list.values.resize(list.distances.size());
  list.slopes.resize(list.distances.size());
  kernel.values_and_slopes(list.distances, list.values, list.slopes);
}

}  // namespace tankfsi::sph
