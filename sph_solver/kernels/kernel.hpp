#pragma once
// Kernel: the SPH smoothing kernel W(r, h) and its radial derivative, in 2D or 3D
// (METHOD.md §1, "Kernels"). One class serves every kernel type; the type only
// selects the shape function w(q) of q = r/h, and W(r) = alpha_D w(r/h) / h^D.
//
// Shapes and normalisation constants (alpha_D makes the integral of W over the plane
// or space equal to 1; derivation in kernel.cpp, verified by tests/unit/sph/test_kernel.cpp):
//
// - quintic_spline (Morris, Fox & Zhu 1997, J. Comput. Phys. 136:214), support 3h:
//     w(q) = (3-q)^5 - 6(2-q)^5 + 15(1-q)^5, each term only where positive;
//     alpha_2D = 7/(478 pi), alpha_3D = 1/(120 pi).
//   (The 3D value 3/(359 pi) found in some texts is 0.3 % too large: the exact
//   integral of w(q) 4 pi q^2 over [0, 3] is 120 pi.)
// - quartic_spline, the M5 B-spline (Schoenberg 1946; Monaghan & Lattanzio 1985,
//   Astron. Astrophys. 149:135; Price 2012, J. Comput. Phys. 231:759), support 2.5h:
//     w(q) = (2.5-q)^4 - 5(1.5-q)^4 + 10(0.5-q)^4, each term only where positive;
//     alpha_2D = 96/(1199 pi), alpha_3D = 1/(20 pi).
// - wendland_c2 (Wendland 1995, Adv. Comput. Math. 4:389; Dehnen & Aly 2012,
//   MNRAS 425:1068), support 2h:
//     w(q) = (1 - q/2)^4 (2q + 1);  alpha_2D = 7/(4 pi), alpha_3D = 21/(16 pi).
//
// The paper uses the quintic spline in 2D and the quartic spline in 3D: default_kernel.
#include <Eigen/Core>

#include <span>
#include <string>
#include <string_view>

namespace tankfsi::sph {

enum class KernelType { quintic_spline, quartic_spline, wendland_c2 };

/// The paper's choice: quintic spline in 2D, quartic spline in 3D.
/// Throws std::invalid_argument unless dimension is 2 or 3.
[[nodiscard]] KernelType default_kernel(int dimension);

/// h / L0 for a case that names none (fluid.smoothing_length_ratio):
/// - quintic spline 1.2 (support 3.6 L0; at 1.1 the 2D tank at rest's lattice
///   does not hold: 0.12 m/s within 6 s against 2.6e-4 at 1.2,
///   cases/hydrostatic_3d/README.md, "The quartic spline's smoothing length");
/// - quartic spline 1.1 (support 2.75 L0, about 87 neighbours in 3D). At 1.2 (113
///   neighbours) the M5 spline is in its pairing instability (Dehnen & Aly 2012,
///   MNRAS 425:1068): measured in 3D (cases/hydrostatic_3d/README.md, "The
///   quartic spline's smoothing length"), a liquid at rest on its lattice in a
///   box deforms from about 2 s (largest speed 1.6e-3 m/s at 3 s, growing
///   fivefold every 0.5 s; 1.9e-5 m/s with 1.1), and the disordered liquid
///   of a cylinder keeps twice the kinetic energy;
/// - Wendland C2 1.5, the least at which it sums to 1 on the lattice.
[[nodiscard]] double default_smoothing_length_ratio(KernelType type);

/// The case-file word (fluid.kernel): "quintic_spline", "quartic_spline",
/// "wendland_c2", or "auto" for default_kernel(dimension).
/// Throws std::invalid_argument for any other word or dimension.
[[nodiscard]] KernelType parse_kernel_type(std::string_view word, int dimension);

/// The case-file word of a type (inverse of parse_kernel_type for explicit types).
[[nodiscard]] std::string_view kernel_name(KernelType type);

class Kernel {
 public:
  /// Throws std::invalid_argument unless dimension is 2 or 3 and h is positive and finite.
  Kernel(KernelType type, int dimension, double smoothing_length);

  /// W(r); r >= 0. Zero for r >= support_radius().
  [[nodiscard]] double value(double r) const;
  /// dW/dr at r >= 0; zero at r = 0 and for r >= support_radius().
  [[nodiscard]] double derivative(double r) const;
  /// W(r) and dW/dr together, bit for bit as value() and derivative() (the
  /// neighbour list's pairs take both).
  void value_and_derivative(double r, double& value, double& slope) const;
  /// value_and_derivative() of every radius (the same bits), into spans of the
  /// radii's size; throws std::invalid_argument when the sizes differ.
  void values_and_slopes(std::span<const double> radii, std::span<double> values, std::span<double> slopes) const;
  /// grad_i W_ij = x_ij / r * dW/dr with x_ij = x_i - x_j; zero at r = 0.
  [[nodiscard]] Eigen::Vector3d gradient(const Eigen::Vector3d& x_ij) const;
  /// The same when the caller already has r = |x_ij| (neighbour loops do).
  [[nodiscard]] Eigen::Vector3d gradient(const Eigen::Vector3d& x_ij, double r) const;

  /// Radius beyond which W vanishes: 3h, 2.5h or 2h.
  [[nodiscard]] double support_radius() const { return support_radius_; }
  [[nodiscard]] double smoothing_length() const { return smoothing_length_; }
  [[nodiscard]] int dimension() const { return dimension_; }
  [[nodiscard]] KernelType type() const { return type_; }

 private:
  KernelType type_;
  int dimension_;
  double smoothing_length_;
  double inverse_smoothing_length_;
  double support_radius_;
  double value_factor_;       ///< alpha_D / h^D
  double derivative_factor_;  ///< alpha_D / h^(D+1): dW/dr = derivative_factor_ * dw/dq
};

}  // namespace tankfsi::sph
