#pragma once
// NeighbourCandidates: the pairs within radius + skin of one set of points, from
// which the neighbour lists of the same points moved a little are filtered without
// a new search (a Verlet list).
//
// A step looks for neighbours twice with the same particles and ghosts: at x^n and
// at the PPE's positions x~ = x^n + dt v^n (fluid_solver.hpp). When no point moves
// by more than d, no pair comes closer by more than 2 d, so every pair within the
// radius at the moved points lies within radius + 2 d at the searched ones: one
// search at radius + skin (skin >= 2 d) serves both. The filter tests each
// candidate's distance exactly as CellList does, so the lists hold the same pairs
// as a search of their own, in the candidates' order.
#include <Eigen/Core>

#include <span>
#include <string>
#include <vector>

#include "sph_solver/kernels/kernel.hpp"
#include "sph_solver/neighbours/neighbour_list.hpp"

namespace tankfsi::sph {

/// Throws std::invalid_argument, naming `what` (the caller) and the first point at
/// fault, unless `moved` has the points of `searched`, each moved by at most
/// `largest_move` (a non-finite point that stayed as it was passes): the test of
/// every search that lets moved points use candidates found before they moved.
void require_moved_within(std::span<const Eigen::Vector3d> searched, std::span<const Eigen::Vector3d> moved,
                          double largest_move, const std::string& what);

class NeighbourCandidates {
 public:
  /// Searches the rows 0 .. rows-1 of `points` (all when rows < 0) for neighbours
  /// within radius + skin (CellList). Throws std::invalid_argument for a radius that
  /// is not positive or a skin that is negative or not finite.
  NeighbourCandidates(int dimension, std::span<const Eigen::Vector3d> points, double radius, double skin,
                      int rows = -1);

  /// The neighbours within the radius at `moved` (one per searched point), with the
  /// kernel's value and slope of each pair when given a kernel. Throws
  /// std::invalid_argument when the count differs or a point moved by more than
  /// skin / 2 from where it was searched (a pair could then be missed).
  [[nodiscard]] NeighbourList within_radius(std::span<const Eigen::Vector3d> moved, const Kernel* kernel) const;

  [[nodiscard]] double skin() const { return skin_; }

 private:
  std::vector<Eigen::Vector3d> searched_;
  NeighbourList candidates_;  ///< indices only
  double radius_;
  double skin_;
};

}  // namespace tankfsi::sph
