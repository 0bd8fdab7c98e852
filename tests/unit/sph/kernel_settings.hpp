#pragma once
// The kernel settings the kernel-table tests sweep: every kernel in both
// dimensions at the usual ratios h / L0 and each kernel's default (a superset of the paper's quintic 2D /
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
  // The quartic spline's default 1.1 (kernel.hpp; the others' are 1.2 and 1.5).
  for (int dimension : {2, 3})
    result.push_back({sph::KernelType::quartic_spline, dimension,
                      sph::default_smoothing_length_ratio(sph::KernelType::quartic_spline)});
  return result;
}

}  // namespace tankfsi::test
