#pragma once
// NeighbourList: every particle's neighbours in compressed sparse row (CSR) form,
// the layout the solver's pair loops and the PPE matrix assembly walk through:
// the neighbours of i are indices[offsets[i] .. offsets[i+1]).
//
// With each neighbour it keeps the pair's distance and, when built for a kernel,
// the kernel's value and slope there: a step evaluates each pair's kernel once
// for all its sums (density, divergences, viscosity, PPE, pressure gradient,
// shifting) rather than once per sum.
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "sph_solver/kernels/kernel.hpp"

namespace tankfsi::sph {

/// An allocator whose resize() leaves new numbers unset. The lists are sized to
/// their candidate count and every entry written at once, twice a step: zeroing
/// them first was 2.6 % of a 2D dam break's run (perf, L0 = 0.01 m, 2 ranks).
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  explicit UninitialisedAllocator(const UninitialisedAllocator<U>& /*other*/) {}
  template <class U, class... Args>
  void construct(U* place, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) {
      ::new (static_cast<void*>(place)) U;
    } else {
      ::new (static_cast<void*>(place)) U(std::forward<Args>(args)...);
    }
  }
};

/// A vector of numbers that resize() does not zero.
template <class T>
using ListVector = std::vector<T, UninitialisedAllocator<T>>;

struct NeighbourList {
  std::vector<int> offsets;      ///< size = row count + 1, offsets[0] = 0
  ListVector<int> indices;       ///< neighbour indices, row after row
  ListVector<double> distances;  ///< r = |x_i - x_j| of each entry
  ListVector<double> values;     ///< W(r) of each entry (empty: built without a kernel)
  ListVector<double> slopes;     ///< dW/dr at r of each entry (empty: built without a kernel)

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
