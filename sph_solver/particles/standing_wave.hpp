#pragma once
// StandingWave: the initial velocity of a free linear sloshing mode in a
// rectangular tank (Faltinsen & Timokha 2009, ch. 4): a small-amplitude standing
// wave that starts from the still surface at its largest velocity, so that the
// liquid's initial state is the lattice at rest positions with the hydrostatic
// pressure (exact for the mode at that phase: d phi/dt = 0 then).
//
// Tank x in [x0, x0 + L], floor at y = y0 (2D: the plane z = 0), depth H. Mode n,
// wave number k = n pi / L, frequency omega^2 = g k tanh(k H). The velocity
// potential phi = A cos(k (x - x0)) cosh(k (y - y0)) cos(omega t), with A k =
// a omega / sinh(k H), gives the surface elevation
//   eta(x, t) = a cos(k (x - x0)) sin(omega t)   (a: the amplitude at the walls)
// and the initial velocity u = grad phi at t = 0:
//   u_x = -(a omega / sinh(k H)) sin(k (x - x0)) cosh(k (y - y0)),
//   u_y =  (a omega / sinh(k H)) cos(k (x - x0)) sinh(k (y - y0)),
// divergence-free, tangential on the floor and the side walls.
#include <Eigen/Core>

#include "sph_solver/particles/particles.hpp"

namespace tankfsi::sph {

struct StandingWave {
  double x0 = 0.0;         ///< the wall at x0 (m)
  double width = 0.0;      ///< L (m)
  double floor = 0.0;      ///< y0 (m)
  double depth = 0.0;      ///< H (m): the still liquid's depth
  int mode = 1;            ///< n >= 1
  double amplitude = 0.0;  ///< a (m), of the surface elevation at the walls
  double gravity = 9.81;   ///< g (m/s^2)

  /// k = n pi / L.
  [[nodiscard]] double wave_number() const;
  /// omega = sqrt(g k tanh(k H)) (rad/s).
  [[nodiscard]] double frequency() const;
  /// The initial velocity at a point (2D, z ignored).
  [[nodiscard]] Eigen::Vector3d velocity(const Eigen::Vector3d& x) const;
};

/// Sets every particle's velocity to the wave's initial velocity. Throws
/// std::invalid_argument unless width, depth and gravity are positive, mode >= 1 and
/// the amplitude is finite.
void apply_standing_wave(const StandingWave& wave, Particles& particles);

}  // namespace tankfsi::sph
