#pragma once
// The kernel settings the kernel-table tests sweep: every kernel in both
// dimensions at the usual ratios h / L0 (a superset of the paper's quintic 2D /
// quartic 3D; the lattice identities hold whatever the kernel quality).
#include <vector>

#include "sph_solver/kernels/kernel.hpp"

namespace tankfsi::test {

struct KernelSetting {
  sph::KernelType type;
  int dimension;
  double h_over_dx;
};

inline std::vector<KernelSetting> kernel_settings() {
  std::vector<KernelSetting> result;
  for (sph::KernelType type : {sph::KernelType::quintic_spline, sph::KernelType::quartic_spline,
                               sph::KernelType::wendland_c2})
    for (int dimension : {2, 3})
      for (double h_over_dx : {1.2, 1.5}) result.push_back({type, dimension, h_over_dx});
  return result;
}

}  // namespace tankfsi::test
