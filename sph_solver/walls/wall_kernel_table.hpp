#pragma once
// WallKernelTable: the wall kernel tables of METHOD.md §2 (paper eq 10). A particle
// near a flat wall misses the neighbours that a fluid continuing behind the wall
// would give it. The tables stand for those missing neighbours: the half-space
// behind the wall is filled with a lattice of virtual particles of the fluid's
// initial spacing L0, and their kernel sums are tabulated against the particle's
// height d above the wall, once per run.
//
// Geometry (the solver is written against exactly this): the wall is the plane
// through the origin with unit normal n pointing into the fluid; the particle is at
// x_i = d n, d >= 0. The virtual particles form a square (2D, in the plane z = 0) or
// cubic (3D) lattice of spacing L0 below the plane: layers at depths
// s = L0/2, 3L0/2, 5L0/2, ... (the mirror of a fluid lattice whose first layer is at
// L0/2 above the wall), lateral offsets at integer multiples of L0 from the
// particle's lateral position; each has volume L0^D. With x_ij = x_i - x_j,
// r = |x_ij|, W, W' = dW/dr and eta^2 = 0.01 h^2 (METHOD.md §1):
//
//   Z0(d) = L0^D sum_j W(r)                          density share (eq 11), >= 0
//   Z1(d) = L0^D sum_j W'(r) (x_ij . n) / r          normal component of sum_j V_j grad_i W_ij
//                                                    (pressure gradient, eq 12), <= 0;
//                                                    the lateral components cancel by symmetry
//   Z2(d) = L0^D sum_j r W'(r) / (r^2 + eta^2)       Morris Laplacian weight without its
//                                                    factor 2 (viscosity eq 14, PPE), <= 0
//
// and the representative depths d_k = M_k / Z_k (0 where Z_k = 0), M_k the same sums
// weighted by the depth s_j. A field that varies linearly with depth behind the wall,
// f(s) = a + b s, then sums exactly to Z_k f(d_k): this is the linear extrapolation of
// eq 13 (d = d_c). d_k >= L0/2; it is
// largest at the wall (0.57 L0 to 1.3 L0 over the kernels at h/L0 = 1.2 and 1.5) and
// falls towards L0/2 as d grows, because the support reaches less deep behind the
// wall (to R - d), while the particle's distance to it, d + d_k, grows.
//
// The table samples d uniformly on [0, support radius]; at() interpolates Z_k and M_k
// linearly (so the identity above also holds between the nodes, and d_k stays between
// its node values, never below L0/2) and returns d_k = M_k / Z_k.
#include <array>
#include <vector>

#include "sph_solver/kernels/kernel.hpp"

namespace tankfsi::sph {

/// Throws std::invalid_argument unless the lattice spacing of a kernel table is
/// positive and finite and the support spans at most
/// WallKernelTable::max_support_in_spacings of it (shared by the wall and corner tables).
void require_table_spacing(const Kernel& kernel, double spacing);

/// The wall terms of one particle at one distance from a flat wall (see above).
struct WallKernelValues {
  double z0 = 0, z1 = 0, z2 = 0;
  double depth0 = 0, depth1 = 0, depth2 = 0;
  /// Z3 = -L0^D sum_j W'(r) |l_j|^2 / (r (D - 1)), l_j the lateral offset of j: the
  /// tangential part of -sum_j V_j x_ij (x) grad_i W_ij (a full lattice gives
  /// lattice_moment() times the identity, so the fluid side holds that less Z3 of
  /// it). It completes the linear
  /// extrapolation of a pressure that also varies along the wall (hydrostatic
  /// pressure beside a vertical wall): >= 0.
  double z3 = 0;
  /// C0..C3: what Z0..Z3 lose per unit mean curvature H of the wall (H > 0 where
  /// it bulges towards the fluid): Z_k - H C_k to first order. A wall of principal
  /// curvatures k1, k2 lies (k1 y^2 + k2 z^2) / 2 in front of its tangent plane at
  /// lateral offset (y, z); the kernel weights on the plane over that sliver give
  /// C_k = integral of g_k |l|^2 / (D - 1) over the plane at distance d (l the
  /// lateral offset; in 2D the curve of curvature k has H = k/2 and the same form),
  /// g_k the summand of Z_k there. Computed on the continuum, by quadrature: the
  /// sliver is thinner than the lattice's layers.
  double c0 = 0, c1 = 0, c2 = 0, c3 = 0;
};

/// -L0^D sum_j W'(r) x_j^2 / r over a full lattice of spacing L0 (x_j a lattice
/// site's coordinate along one axis; the particle at the origin): the lattice's
/// moment -sum_j V_j x_ij (x) grad_i W_ij is this times the identity (the lattice
/// is cubic). The continuous kernel gives exactly 1, the lattice (a quadrature of
/// its integral) not quite: 0.99938 for the quintic spline in 2D and 1.00426 for
/// the quartic spline in 3D at h = 1.2 L0, 0.964 for Wendland C2 in 2D at h =
/// 1.2 L0 (tests/unit/sph/test_wall_kernel_table.cpp). The symmetric pressure
/// gradient of a linear pressure on the lattice is this times its gradient.
[[nodiscard]] double lattice_moment(const Kernel& kernel, double spacing);

class WallKernelTable {
 public:
  /// Linear interpolation errs by (step^2 / 8) max|Z_k''|, and Z_k'' scales as
  /// max|Z_k| / h^2. Over 400 intervals of the support the measured error is at most
  /// 1.5e-5 of max|Z_k| (1e-4 is the target; 160 intervals would just meet it) for
  /// every kernel, 2D and 3D (tests/unit/sph/test_wall_kernel_table.cpp).
  static constexpr int default_intervals = 400;
  /// Kernels wider than this many lattice spacings are refused: the table would cost
  /// O((support / L0)^D) kernel evaluations per node, and such a ratio is a unit
  /// mistake rather than an SPH setting (h / L0 is 1 to 3).
  static constexpr double max_support_in_spacings = 32.0;

  /// Throws std::invalid_argument unless spacing is positive and finite,
  /// support / spacing <= max_support_in_spacings, and intervals >= 1.
  WallKernelTable(const Kernel& kernel, double spacing, int intervals = default_intervals);

  /// The values at distance d from the wall, linearly interpolated. d < 0 (a particle
  /// that has crossed the wall) is clamped to d = 0, the strongest wall terms, which
  /// push it back; d >= cutoff() gives all zeros; a NaN distance gives NaN values
  /// (never a silent number).
  [[nodiscard]] WallKernelValues at(double distance) const;

  /// The inverse of Z0: the distance d at which the table's Z0(d) equals `share`,
  /// interpolated like at(), so at(distance_for_share(z)).z0 == z up to round-off.
  /// Z0 decreases strictly while the first virtual layer is in the support (every
  /// W(r) decreases as the particle moves away), so the inverse is unique there:
  /// share >= Z0(0) gives 0, share <= 0 gives cutoff(); NaN gives NaN. This reads
  /// the distance to a free surface from a particle's density deficit (free_surface.hpp).
  [[nodiscard]] double distance_for_share(double share) const;

  /// The exact lattice sums at distance d >= 0 (d = +inf gives zeros): the table's
  /// nodes, and the reference of the tests. Throws std::invalid_argument for a
  /// negative or NaN distance and for a spacing the constructor refuses.
  [[nodiscard]] static WallKernelValues direct_sum(const Kernel& kernel, double spacing, double distance);

  /// L0^D sum_j W over a full lattice, the particle itself included: the kernel sum
  /// (over rho0) of a particle inside the initial lattice, which the fluid part and
  /// Z0 add up to beside a flat wall. Not exactly 1: 1 - 6e-5 for the quintic spline
  /// at h = 1.2 L0 (the lattice is a quadrature of the kernel's integral).
  [[nodiscard]] double lattice_share() const { return lattice_share_; }

  /// The support radius: beyond it no virtual particle is a neighbour.
  [[nodiscard]] double cutoff() const { return cutoff_; }
  /// The lattice spacing L0.
  [[nodiscard]] double spacing() const { return spacing_; }
  /// Number of intervals of the table; node k is at d = cutoff() * k / intervals().
  [[nodiscard]] int intervals() const { return static_cast<int>(nodes_.size()) - 1; }

 private:
  /// Z_k and the depth moments M_k at one node, k = 0, 1, 2.
  struct Node {
    std::array<double, 3> z{};
    std::array<double, 3> moment{};
    double tangential = 0.0;  ///< Z3
    std::array<double, 4> curvature{};  ///< C0..C3
  };

  /// C0..C3 at distance >= 0 (WallKernelValues), by quadrature over the plane.
  static std::array<double, 4> curvature_moments(const Kernel& kernel, double distance);

  /// The lattice sums at distance >= 0 (arguments already checked).
  static Node sum_lattice(const Kernel& kernel, double spacing, double distance);
  /// Z_k and d_k = M_k / Z_k (0 where Z_k = 0).
  static WallKernelValues values_of(const Node& node);

  double cutoff_;
  double spacing_;
  double lattice_share_ = 0.0;
  double inverse_step_;  ///< intervals / cutoff
  std::vector<Node> nodes_;
};

}  // namespace tankfsi::sph
