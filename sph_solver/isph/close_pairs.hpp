#pragma once
// Parting of close pairs: the last regularisation of a step (fluid_solver.hpp, 4b).
//
// The Fickian shift (Lind et al. 2012) is skipped at and next to the free surface,
// and in a thin sheet (a surge front, a run-up jet) that is every particle. There
// pairs close across the sheet's thickness; once the pressure in the sheet turns
// negative the symmetric gradient (METHOD.md eq 4) draws them together until a
// step throws one out (the 2D dam break at L0 = 0.005 m: cases/dam_break_2d). So,
// much as the collision models of MPS codes keep particles apart, each particle
// of a pair closer than a distance d moves away
// from the other by half the shortfall: an isolated pair ends d apart, its centre
// of mass in place. Pairs at d or beyond are untouched, which in a liquid of
// lattice spacing L0 and d <= L0/2 is every pair but the collapsed ones.
#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <vector>

#include "sph_solver/neighbours/neighbour_list.hpp"

namespace tankfsi::sph {

/// The moves that part the pairs closer than `distance` of the owned particles
/// 0 .. owned-1: for each neighbour j of i (`neighbours`, found at a nearby
/// configuration) with r = |x_i - x_j| < distance at `position` (owned then
/// ghosts), (distance - r)/2 along (x_i - x_j)/r; a particle's moves summed and
/// capped at distance/2. Coincident particles part along x, the lower `id` to -x,
/// so that every rank makes the same choice.
[[nodiscard]] std::vector<Eigen::Vector3d> close_pair_parting(const NeighbourList& neighbours,
                                                              std::span<const Eigen::Vector3d> position,
                                                              std::span<const std::int64_t> id, int owned,
                                                              double distance);

}  // namespace tankfsi::sph
