#include "sph_solver/isph/close_pairs.hpp"

namespace tankfsi::sph {

namespace {
std::size_t at(int i) { return static_cast<std::size_t>(i); }
}  // namespace

std::vector<Eigen::Vector3d> close_pair_parting(const NeighbourList& neighbours,
                                                std::span<const Eigen::Vector3d> position,
                                                std::span<const std::int64_t> id, int owned, double distance) {
  std::vector<Eigen::Vector3d> move(at(owned), Eigen::Vector3d::Zero());
  if (!(distance > 0.0)) return move;
  // Below this the pair's direction is lost to rounding.
  const double coincident = 1e-9 * distance;
  for (int i = 0; i < owned; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const int j : neighbours.neighbours_of(i)) {
      const Eigen::Vector3d apart = position[at(i)] - position[at(j)];
      const double r = apart.norm();
      if (r >= distance) continue;
      const Eigen::Vector3d direction =
          r > coincident ? Eigen::Vector3d(apart / r)
                         : Eigen::Vector3d(id[at(i)] < id[at(j)] ? -1.0 : 1.0, 0.0, 0.0);
      sum += 0.5 * (distance - r) * direction;
    }
    const double length = sum.norm();
    move[at(i)] = length > 0.5 * distance ? Eigen::Vector3d(sum * (0.5 * distance / length)) : sum;
  }
  return move;
}

}  // namespace tankfsi::sph
