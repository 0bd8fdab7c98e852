#pragma once
// The partitioned two-mass oscillator the solver dummies run (and the tests
// check against the monolithic closed form): at every interface vertex i, in
// x only,
//
//   fluid side:     m1 x1'' = -k1 x1 - kc (x1 - x2)
//   structure side: m2 x2'' = -k2 x2 + F,   F = kc (x1 - x2)
//
// so the "fluid" writes the force of the coupling spring on the structure and
// reads the structure's displacement x2, as the real programs do. Each side
// integrates with Newmark's average acceleration (METHOD.md §3), sub-stepping
// the window. Vertex i has its own stiffness, so data sent to the wrong
// vertex shows in the answer.
#include <Eigen/Dense>

#include <cmath>
#include <cstdint>
#include <vector>

namespace tankfsi::coupling::examples {

struct OscillatorParameters {
  double m1 = 1.0, m2 = 1.0;
  double k1 = 40.0, k2 = 60.0, kc = 20.0;
  double x1_initial = 1.0;  ///< x1(0); x2(0) = 0, both at rest
  /// The stiffnesses of vertex `id` (k1, k2, kc scaled by 1 + 0.01 (id mod 7)).
  [[nodiscard]] OscillatorParameters at_vertex(std::int64_t id) const {
    OscillatorParameters p = *this;
    const double s = 1.0 + 0.01 * static_cast<double>(id % 7);
    p.k1 *= s;
    p.k2 *= s;
    p.kc *= s;
    return p;
  }
};

/// One single-DOF Newmark integrator (average acceleration), load at step end.
struct NewmarkDof {
  double mass = 1.0, stiffness = 1.0;
  double u = 0.0, v = 0.0, a = 0.0;

  void start(double u0, double v0, double load0) {
    u = u0;
    v = v0;
    a = (load0 - stiffness * u0) / mass;
  }
  void step(double dt, double load_end) {
    const double predictor = u + dt * v + 0.25 * dt * dt * a;
    const double a_new = (load_end - stiffness * predictor) / (mass + 0.25 * dt * dt * stiffness);
    u = predictor + 0.25 * dt * dt * a_new;
    v += 0.5 * dt * (a + a_new);
    a = a_new;
  }
};

/// Monolithic closed form of the two masses (x1, x2) at time t.
[[nodiscard]] inline Eigen::Vector2d oscillator_exact(const OscillatorParameters& p, double t) {
  Eigen::Matrix2d mass;
  mass << p.m1, 0, 0, p.m2;
  Eigen::Matrix2d stiffness;
  stiffness << p.k1 + p.kc, -p.kc, -p.kc, p.k2 + p.kc;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> modes(stiffness, mass);
  const Eigen::Matrix2d shapes = modes.eigenvectors();  // M-orthonormal
  const Eigen::Vector2d x0(p.x1_initial, 0.0);
  const Eigen::Vector2d q0 = shapes.transpose() * mass * x0;
  Eigen::Vector2d q;
  for (int k = 0; k < 2; ++k) q[k] = q0[k] * std::cos(std::sqrt(modes.eigenvalues()[k]) * t);
  return shapes * q;
}

}  // namespace tankfsi::coupling::examples
