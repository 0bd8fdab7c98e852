#include "sph_solver/neighbours/neighbour_candidates.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sph_solver/neighbours/cell_list.hpp"

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

}  // namespace

NeighbourCandidates::NeighbourCandidates(int dimension, std::span<const Eigen::Vector3d> points, double radius,
                                         double skin, int rows)
    : searched_(points.begin(), points.end()), radius_(radius), skin_(skin) {
  if (!(std::isfinite(skin) && skin >= 0.0))
    throw std::invalid_argument("neighbour candidates: the skin must be finite and at least 0, got " +
                                std::to_string(skin));
  CellList cells(dimension);
  cells.build(points, radius + skin);
  candidates_ = cells.neighbour_indices(rows);
}

void require_moved_within(std::span<const Eigen::Vector3d> searched, std::span<const Eigen::Vector3d> moved,
                          double largest_move, const std::string& what) {
  if (moved.size() != searched.size())
    throw std::invalid_argument(what + ": " + std::to_string(moved.size()) + " points for the " +
                                std::to_string(searched.size()) + " searched");
  const double largest_move_squared = largest_move * largest_move;
  for (std::size_t i = 0; i < moved.size(); ++i)
    if (!((moved[i] - searched[i]).squaredNorm() <= largest_move_squared) && moved[i] != searched[i])
      throw std::invalid_argument(what + ": point " + std::to_string(i) + " moved by " +
                                  std::to_string((moved[i] - searched[i]).norm()) + ", more than " +
                                  std::to_string(largest_move) + " allowed");
}

NeighbourList NeighbourCandidates::within_radius(std::span<const Eigen::Vector3d> moved, const Kernel* kernel) const {
  // A displacement of skin/2 keeps every pair (the caller's skin carries the
  // margin for the rounding of the displacements it measured).
  require_moved_within(searched_, moved, 0.5 * skin_, "neighbour candidates");
  const double radius_squared = radius_ * radius_;
  NeighbourList list;
  const int rows = candidates_.particle_count();
  list.offsets.reserve(at(rows) + 1);
  list.offsets.push_back(0);
  // Every candidate is written and kept only when within the radius (the count
  // advanced arithmetically, without a branch: CellList does the same); the
  // squared distances get their roots in one pass at the end.
  list.indices.resize(candidates_.indices.size());
  list.distances.resize(candidates_.indices.size());
  std::size_t used = 0;
  for (int i = 0; i < rows; ++i) {
    const Eigen::Vector3d x_i = moved[at(i)];
    for (int k = candidates_.offsets[at(i)]; k < candidates_.offsets[at(i) + 1]; ++k) {
      const int j = candidates_.indices[at(k)];
      const double r_squared = (x_i - moved[at(j)]).squaredNorm();
      list.indices[used] = j;
      list.distances[used] = r_squared;
      used += static_cast<std::size_t>(r_squared < radius_squared);
    }
    list.offsets.push_back(static_cast<int>(used));
  }
  list.indices.resize(used);
  list.distances.resize(used);
  for (double& r : list.distances) r = std::sqrt(r);
  if (kernel != nullptr) add_kernel_values(list, *kernel);
  return list;
}

}  // namespace tankfsi::sph
