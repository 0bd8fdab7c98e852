#pragma once
// Modal analysis: the lowest natural modes of K phi = omega^2 M phi with SLEPc
// (generalised Hermitian, shift-and-invert about 0 so the lowest converge
// first; each shifted solve is a Cholesky factorisation with MUMPS by default).
// Options: -eps_ (-eps_nev, -eps_tol, -eps_type ...) and -st_ (-st_ksp_type,
// -st_pc_type ...) from the case's solver_options or the command line.
#include <vector>

#include "fem_solver/assembly/system_assembler.hpp"

namespace tankfsi::fem {

struct NaturalMode {
  double omega = 0.0;             ///< rad/s
  double frequency = 0.0;         ///< Hz
  double period = 0.0;            ///< s
  Eigen::Vector3d participation;  ///< Gamma_k = phi^T M iota_k (phi M-normalised), kg^0.5
  Eigen::Vector3d effective_mass; ///< Gamma_k^2 (kg) per direction x y z
  NodalValues shape;              ///< M-normalised mode shape, whole structure
};

struct ModalResult {
  std::vector<NaturalMode> modes;  ///< ascending frequency
  Eigen::Vector3d free_mass = Eigen::Vector3d::Zero();  ///< iota_k^T M iota_k over the free DOFs (kg)
  int iterations = 0;
};

/// Computes `count` modes; throws std::runtime_error when SLEPc converges
/// fewer, naming how many it found.
[[nodiscard]] ModalResult solve_modes(SystemAssembler& assembler, Mat stiffness, int count);

}  // namespace tankfsi::fem
