#pragma once
// Particles: the fluid particles one rank owns, structure of arrays.
//
// Only the persistent state lives here — what a particle carries from one step to
// the next and across ranks when it migrates: identity, position, velocity, mass and
// the pressure of the last step (the PPE's warm start). Everything a step computes
// on the way (densities, intermediate velocities, wall hits) lives in the step's own
// work arrays, sized owned + ghost.
//
// In 2D every position and velocity has z = 0.
#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tankfsi::sph {

struct Particles {
  std::vector<std::int64_t> id;  ///< global, unique, stable for the whole run
  std::vector<Eigen::Vector3d> position;
  std::vector<Eigen::Vector3d> velocity;
  std::vector<double> mass;
  std::vector<double> pressure;

  [[nodiscard]] std::size_t size() const { return id.size(); }
  [[nodiscard]] int count() const { return static_cast<int>(id.size()); }

  void push_back(std::int64_t particle_id, const Eigen::Vector3d& x, const Eigen::Vector3d& v, double m, double p) {
    id.push_back(particle_id);
    position.push_back(x);
    velocity.push_back(v);
    mass.push_back(m);
    pressure.push_back(p);
  }

  void clear() {
    id.clear();
    position.clear();
    velocity.clear();
    mass.clear();
    pressure.clear();
  }

  /// Keeps the particles order[0], order[1], ... in that order (a permutation, or a
  /// selection when order is shorter: removal of particles).
  void reorder(const std::vector<int>& order);
};

}  // namespace tankfsi::sph
