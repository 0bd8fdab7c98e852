#pragma once
// CornerKernelTable: the lattice sums over the quarter-space behind two orthogonal
// planes, the part that two wall kernel tables (wall_kernel_table.hpp) both count.
//
// Why. A particle near a corner of the tank (floor and side wall) or near a contact
// line (side wall and free surface, free_surface.hpp) sees two half-spaces of
// virtual particles, one per plane. They overlap in the quarter-space behind both,
// which is then counted twice: at the corner particle of the 2D tank the density is
// 7 % high and the PPE and the pressure gradient double the corner's share, which
// throws the corner particle out at 8 g and shifts the pressure of the whole tank by
// ~1 %. Inclusion-exclusion — two half-spaces minus their overlap — counts every
// virtual particle once; this table is the overlap.
//
// Geometry: planes A and B through the origin with unit normals n_A, n_B (n_A . n_B
// = 0) pointing into the fluid, edge direction e = n_A x n_B (3D). The particle is at
// x_i = a n_A + b n_B, a, b >= 0. The virtual particles of the overlap lie at
//   x_k = -s_A n_A - s_B n_B + c L0 e,  s_A, s_B in {L0/2, 3L0/2, ...}, c integer (3D),
// so x_ik = x_i - x_k = (a + s_A) n_A + (b + s_B) n_B - c L0 e. With V = L0^D,
// r = |x_ik|, W' = dW/dr and eta^2 = 0.01 h^2 (as the wall tables):
//   Q0 = V sum W                                density share
//   Q1A n_A + Q1B n_B = V sum grad_i W_ik       Q1A = V sum W'/r (a + s_A) <= 0 (the e part cancels)
//   Q2 = V sum r W' / (r^2 + eta^2)             Laplacian weight without its factor 2, <= 0
//   S_XY = V sum W'/r x_X x_Y                   second moments, x_A = a + s_A, x_B = b + s_B,
//                                               x_e = c L0 (S_Ae = S_Be = 0): <= 0 on the diagonal
//   M2A = V sum r W'/(r^2 + eta^2) (a + s_A)    first moments of the Laplacian weight, <= 0
// A pressure that varies linearly in the overlap, P_k = P_i + G . (x_k - x_i), then sums to
//   V sum (P_i + P_k) grad_i W_ik = 2 P_i (Q1A n_A + Q1B n_B) - S G,
//   V sum 2 r W'/(r^2 + eta^2) (P_i - P_k) = 2 (M2A G_A + M2B G_B),
// with S the symmetric tensor of the S_XY in the basis (n_A, n_B, e); and the moment
// tensor -V sum x_ik (x) grad_i W_ik of the overlap is -S.
//
// The table samples a and b uniformly on [0, support radius] and interpolates
// bilinearly (every value is a sum, so the identities above hold between the nodes
// too). Q(a, b) with A and B swapped is Q(b, a) with the A and B entries swapped.
#include <array>
#include <vector>

#include "sph_solver/kernels/kernel.hpp"

namespace tankfsi::sph {

/// The overlap's sums at one particle (see above); all zero beyond the support.
struct CornerKernelValues {
  double q0 = 0, q1a = 0, q1b = 0, q2 = 0;
  double saa = 0, sab = 0, sbb = 0, see = 0;
  double m2a = 0, m2b = 0;
};

/// The same sums over the octant behind three orthogonal planes A, B, C (a corner
/// of a 3D box): sites x_k = -s_A n_A - s_B n_B - s_C n_C, the particle at
/// x_i = a n_A + b n_B + c n_C, components x_X = d_X + s_X in the planes' basis.
/// The three half-spaces count the octant three times and the three pairs'
/// overlaps take it out three times: inclusion-exclusion adds it back once.
struct OctantKernelValues {
  double q0 = 0, q2 = 0;
  std::array<double, 3> q1{};                ///< V sum W'/r x_X
  std::array<double, 3> m2{};                ///< V sum r W'/(r^2 + eta^2) x_X
  std::array<std::array<double, 3>, 3> s{};  ///< V sum W'/r x_X x_Y
};

class CornerKernelTable {
 public:
  /// 160 intervals per axis: bilinear interpolation errs like the wall tables' linear
  /// one, by (step^2 / 8) times the second derivatives: at most 9e-5 of the values at
  /// the edge for every kernel, 2D and 3D (tests/unit/sph/test_corner_kernel_table.cpp).
  static constexpr int default_intervals = 160;

  /// Throws std::invalid_argument unless spacing is positive and finite, the support
  /// spans at most WallKernelTable::max_support_in_spacings spacings and intervals >= 1.
  CornerKernelTable(const Kernel& kernel, double spacing, int intervals = default_intervals);

  /// The values at distances a from plane A and b from plane B, bilinearly
  /// interpolated; negative distances are clamped to 0, NaN gives NaN values.
  [[nodiscard]] CornerKernelValues at(double a, double b) const;

  /// The exact lattice sums at a, b >= 0: the table's nodes and the tests' reference.
  [[nodiscard]] static CornerKernelValues direct_sum(const Kernel& kernel, double spacing, double a, double b);

  /// The octant behind three planes at distances a, b, c >= 0 (3D), summed
  /// directly: it holds a few dozen sites at most, and only particles within the
  /// support of a box's corner need it — no table.
  [[nodiscard]] OctantKernelValues octant(double a, double b, double c) const;

  [[nodiscard]] double cutoff() const { return cutoff_; }
  [[nodiscard]] int intervals() const { return intervals_; }

 private:
  static CornerKernelValues sum_lattice(const Kernel& kernel, double spacing, double a, double b);

  Kernel kernel_;
  double spacing_;
  double cutoff_;
  int intervals_;
  double inverse_step_;
  std::vector<CornerKernelValues> nodes_;  ///< (intervals + 1)^2, a fastest
};

}  // namespace tankfsi::sph
