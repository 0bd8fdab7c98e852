#pragma once
// Particles against the walls at a step's end: a path from a particle's position
// at the step's start to its end that meets a wall triangle (the walls as they
// are at the end).
//
// A path that ends just behind the wall it met, no deeper than touching_depth
// (wall_contacts.hpp: where the walls' terms still see the particle as touching
// it), is a particle that the pressure did not hold off the wall — a thin sheet
// running up a wall at the free surface's pressure, which nothing but the
// no-penetration condition keeps in. That condition is then imposed on the
// particle itself, as polygon-wall particle methods do: it is put back on the
// wall's liquid side (a two-sided sheet's: the side the path came from; a
// thousandth of L0 in front of the plane) and loses its
// velocity into the wall relative to the wall's own (an inelastic contact). The
// steps report how many particles they put back. A deeper crossing is a step
// too long for the liquid's speed or the wall's motion: an error
// (FluidSolver::check_crossings, from the paths this search left).
#include <Eigen/Core>

#include <span>
#include <utility>
#include <vector>

#include "sph_solver/isph/wall_contacts.hpp"

namespace tankfsi::sph {

/// A triangle that the segment from `from` to `to` meets (the one with the lowest
/// index among several), or -1.
[[nodiscard]] int crossed_triangle(const WallModel& walls, const Eigen::Vector3d& from, const Eigen::Vector3d& to);

/// What return_to_walls() did and left.
struct WallCrossings {
  long long returned = 0;  ///< particles put back
  /// (particle, triangle) of each path still through a wall: the particle
  /// crossed it too deep to be put back (in order of the particles).
  std::vector<std::pair<int, int>> through;
};

/// Puts back the particles whose path from `start` to `position` ends at most
/// touching_depth behind the wall it met (above), in a `dimension`-D run, and
/// names those whose path still goes through a wall.
WallCrossings return_to_walls(const WallModel& walls, int dimension, std::span<const Eigen::Vector3d> start,
                              std::span<Eigen::Vector3d> position, std::span<Eigen::Vector3d> velocity);

}  // namespace tankfsi::sph
