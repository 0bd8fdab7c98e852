#pragma once
// The SPH sums of one ISPH step (METHOD.md §1, eqs 3-6, with the wall terms of
// §2, eqs 11-14), each for the owned particles 0 .. owned-1 over their neighbours
// among owned and ghost particles, plus the share of the walls behind them.
//
// Notation as METHOD.md: x_ij = x_i - x_j, r = |x_ij|, grad_i W_ij = x_ij/r W'(r),
// V_j = m_j / rho_j, eta^2 = 0.01 h^2. Wall terms use the tables Z_k(r_iw) with the
// linear-in-depth extrapolation of pressure and velocity into the wall
// (representative depths d_k) and the Neumann wall pressure of the projection,
// dP/dn = rho0 (v*_i - v_wall)·n / dt — which is METHOD.md's rho0 (F - a_wall)·n
// for a particle moving with the wall (v^n·n = v_wall·n), and also stops a particle
// that approaches the wall. It gives, with no division by r_iw:
//   P_i - P_w(d) = dP/dn (r_iw + d)
//   v_i - v_w(d) = (v_i - v_ws)(1 + d / r_iw)   (no-slip; r_iw floored at L0/4)
// Because the wall's impermeability enters the PPE through this Neumann condition,
// the velocity divergence has no wall share (counting the wall velocity there too
// would count the wall twice: a liquid at rest would not stay hydrostatic).
#include <Eigen/Core>

#include <span>
#include <vector>

#include "sph_solver/isph/fluid_model.hpp"
#include "sph_solver/isph/surface_contact.hpp"
#include "sph_solver/isph/wall_contacts.hpp"
#include "sph_solver/kernels/kernel.hpp"
#include "sph_solver/neighbours/neighbour_list.hpp"

namespace tankfsi::sph {

/// Positions and neighbours of owned + ghost particles; rows 0 .. owned-1 are used,
/// and the neighbour list must hold their kernel values and slopes
/// (CellList::neighbour_list(&kernel, owned)): the sums throw std::logic_error otherwise.
struct Neighbourhood {
  const Kernel& kernel;
  const FluidModel& model;
  std::span<const Eigen::Vector3d> position;  ///< owned then ghosts
  const NeighbourList& neighbours;
  const WallContacts& walls;                  ///< for the owned particles
  const TriangleMesh& wall_mesh;
  int owned = 0;
  /// The air beyond the free surface for the owned particles (free_surface.hpp);
  /// empty: no free-surface terms (a liquid that fills its support everywhere).
  std::span<const SurfaceContact> surface = {};
  /// Each particle's moment against the lattice's, smoothed (smoothed_moment_scale()),
  /// owned then ghosts; empty: the lattice's, 1 for all.
  std::span<const double> moment_scale = {};
};

/// Kernel-sum density rho_i = sum_j m_j W_ij + m_i W(0) + rho0 sum_w Z0 (eq 11).
[[nodiscard]] std::vector<double> kernel_density(const Neighbourhood& n, std::span<const double> mass);

/// div r_i = -sum_j V_j x_ij · grad_i W_ij, with the walls' share
/// -Z1 (r_iw + d1) + (D - 1) Z3: D inside the liquid (a full support), about D/2 at
/// the free surface (Lee et al. 2008; Lind et al. 2012), so it finds surface particles
/// even where the density is not yet reduced (a surface layer squeezed by a wave).
/// Once the air is known (n.surface) its half-space's share is counted as a wall's.
[[nodiscard]] std::vector<double> position_divergence(const Neighbourhood& n, std::span<const double> mass,
                                                      std::span<const double> density);

/// True for a free-surface particle (`free_surface`: the flags of owned and ghost
/// particles, detect_free_surface()) and for one with a free-surface neighbour.
[[nodiscard]] bool near_free_surface(const Neighbourhood& n, std::span<const unsigned char> free_surface, int i);

/// The moment of each owned particle's support against the lattice's,
/// s_i = div r_i / (D M) (position_divergence() with the air; M = lattice_moment()),
/// kept within [1 - 0.1, 1 + 0.1]; 0, unknown, near the free surface where the
/// particle has no air (near_free_surface(); `free_surface` as there). The pairs
/// take these smoothed (smoothed_moment_scale()).
///
/// Why. The symmetric pressure gradient (eq 4) of a linear pressure is M grad P on
/// the lattice, which its division by M undoes; on the disordered arrangement a
/// liquid in motion takes the moment is smaller (a cylindrical tank at rest after
/// 3 s: s = 0.9958 on average, 0.9869 to 1.0103 in its interior), so a liquid at
/// rest balances only under a pressure gradient 1/s times rho g: the PPE's pressure
/// came out 0.4 % too steep. Dividing each pair by its particles' own moment instead,
/// (1/s_i + 1/s_j) / (2 M), keeps the pairs' forces opposite and equal (momentum
/// conserved, the walls carry the whole weight) and is the lattice's 1/M on a
/// lattice. The walls' and the air's half-spaces are counted as lattices (their
/// tables), so a particle beside them is corrected for its liquid's share only.
/// Outside the bounds (a drop, a jet: a support the walls and the air do not
/// complete) the moment says nothing about the gradient's scale; nor does it
/// where the surface cuts a support the air does not complete (the air stops at
/// two layers: the third layer of a 2D lattice, whose quintic support of 3.6 L0
/// reaches 1.1 L0 past the surface, misses 0.2 % of its moment to it; taken for
/// disorder, that raised the 2D tank at rest's largest speed to 1.3e-3 m/s, with
/// the moments unsmoothed: 5.3e-4 with this rule).
[[nodiscard]] std::vector<double> moment_scale(const Neighbourhood& n, std::span<const double> mass,
                                               std::span<const double> density,
                                               std::span<const unsigned char> free_surface);

/// The moments the pairs divide by: each owned particle's kernel-weighted mean of
/// the known (not 0) moment_scale() `scale` of itself and its neighbours (owned
/// and ghost particles), 1 if none is known (a lattice's). Why the mean: a pair's
/// factor that differs from its neighbours' leaves the symmetric sum of a uniform
/// pressure P a force 2 P / rho^2 sum m (c_ij - c_i) grad W (the gradient of the
/// factor), large where P is; the particles' own moments vary by 0.3 % rms in a
/// disordered liquid and, unsmoothed, raised the 2D tank at rest's largest speed
/// from 1.2-2.2e-4 to 3.4-5.3e-4 m/s.
[[nodiscard]] std::vector<double> smoothed_moment_scale(const Neighbourhood& n, std::span<const double> scale);

/// The weight a_ij = 2 V (x_ij · grad_i W_ij) / (r^2 + eta^2) of the Laplacian
/// (eq 6, with the factor 2), x_ij · grad_i W_ij = r dW/dr (`slope` = dW/dr at r):
/// sum_j a_ij (f_i - f_j) approximates lap f.
/// Inline: the PPE's assembly takes it for every pair of every row.
[[nodiscard]] inline double laplacian_weight(const FluidModel& model, double r, double slope, double volume) {
  return 2.0 * volume * r * slope / (r * r + model.eta_squared());
}

/// (lap P)_i = sum_j a_ij (P_i - P_j) + the air's share (free_surface.hpp),
/// V_ij = (m_i + m_j)/(rho_i + rho_j): the PPE's operator on the liquid (the walls'
/// share is known and on the right-hand side), for checks and diagnostics.
[[nodiscard]] std::vector<double> pressure_laplacian(const Neighbourhood& n, std::span<const double> mass,
                                                     std::span<const double> density,
                                                     std::span<const double> pressure);

/// Morris viscous acceleration (mu/rho lap v)_i (eq 5) with the wall term
/// 2 mu / rho_i Z2 (v_i - v_w(d2)) (eq 14). `wall_force` gets -m_i times the wall
/// part per vertex.
[[nodiscard]] std::vector<Eigen::Vector3d> viscous_acceleration(const Neighbourhood& n, std::span<const double> mass,
                                                                std::span<const double> density,
                                                                std::span<const Eigen::Vector3d> velocity,
                                                                std::vector<Eigen::Vector3d>& wall_force);

/// (div v)_i = -(1/rho_i) sum_j m_j v_ij · grad_i W_ij (no wall share, see above).
[[nodiscard]] std::vector<double> velocity_divergence(const Neighbourhood& n, std::span<const double> mass,
                                                      std::span<const double> density,
                                                      std::span<const Eigen::Vector3d> velocity);

/// -(grad P / rho)_i = -sum_j m_j (P_i/rho_i^2 + P_j/rho_j^2) grad_i W_ij (eq 4), the
/// wall term -Z1 n (rho0 P_i / rho_i^2 + P_w(d1) / rho0) and the air term of the free
/// surface -Z1 n_s (rho0 P_i / rho_i^2 + P_air(d1) / rho0) (free_surface.hpp),
/// divided by the lattice's moment M (lattice_moment(), wall_kernel_table.hpp):
/// these sums give M grad P for a linear pressure on the initial lattice, so a
/// hydrostatic liquid on it is in balance inside and beside walls alike. With
/// n.moment_scale each pair is divided by its particles' own moments, each
/// particle's walls and air by its own (moment_scale()).
/// `wall_force` gets -m_i times the wall part per vertex (divided likewise).
/// `predicted_acceleration` is the predictor's (v* - v^n) / dt, body force and
/// viscosity: the walls' part of the air's overlaps reads only it
/// (contact_line_wall_gradient()).
[[nodiscard]] std::vector<Eigen::Vector3d> pressure_acceleration(
    const Neighbourhood& n, std::span<const double> mass, std::span<const double> density,
    std::span<const double> pressure, std::span<const Eigen::Vector3d> predicted_velocity,
    std::span<const Eigen::Vector3d> predicted_acceleration, double dt, std::vector<Eigen::Vector3d>& wall_force);

/// The walls' known share of the PPE row of owned particle i (the Neumann
/// condition, to the right-hand side): sum_w 2 Z2 dP/dn (r_iw + d2), less each
/// corner's overlap with the linear field of the two walls' dP/dn, less the walls'
/// part of the overlaps of the air with walls (boundary_overlap.hpp), with the
/// walls' gradient there from a_star = (v* - v^n) / dt (contact_line_wall_gradient()).
[[nodiscard]] double wall_laplacian_share(const Neighbourhood& n, int i, const Eigen::Vector3d& v_star,
                                          const Eigen::Vector3d& a_star, double dt);

/// dP/dn at a wall contact: rho0 (v*_i - v_wall)·n / dt (see above).
[[nodiscard]] double wall_pressure_gradient(const FluidModel& model, const WallContact& contact,
                                            const Eigen::Vector3d& v_star, double dt);

/// The wall's dP/dn in the air's overlap with it (a contact line, and the octant of
/// two walls and the air at a vertical edge): rho0 a*·n, the predictor's
/// acceleration a* = (v* - v^n) / dt alone — with which a liquid at rest balances —
/// without the part rho0 (v^n_i - v_wall)·n / dt that stops the particle's approach
/// to the wall.
///
/// Why. The overlap is counted by the wall's half-space, with the wall's field, and
/// by the air's, without the wall's gradient; one copy comes out. The wall's
/// half-space is symmetric along the wall, so its sum pushes along n only. Had the
/// copy that comes out carried the approach part too, the rest of the wall's
/// half-space, below the surface plane, would push the particle along the wall (up
/// as it moves towards the wall, down as it leaves it) by a fixed share of its
/// approach speed in every step, whatever the step's length — a transfer the PPE
/// does not see. In a 3D box at rest (cases/hydrostatic_3d/box.yaml) it fed the
/// bobbing of the particles at the top of the vertical edges, where two walls meet
/// the air: it grew about 20-fold a period of 0.94 s, faster with shorter steps
/// (largest speed 1.0e-3 m/s in the first second, 0.23 m/s at 2.6 s). Without it:
/// 2.1e-5 m/s at 1 s, and the edges do not bob.
[[nodiscard]] double contact_line_wall_gradient(const FluidModel& model, const WallContact& contact,
                                                const Eigen::Vector3d& a_star);

/// grad C_i = sum_j V_j grad_i W_ij + Z1 n per wall: zero inside a uniform
/// particle distribution (walls included), pointing to where particles crowd.
[[nodiscard]] std::vector<Eigen::Vector3d> concentration_gradient(const Neighbourhood& n, std::span<const double> mass,
                                                                  std::span<const double> density);

/// (dr · grad) v_i = sum_j V_j (v_j - v_i)(grad_i W_ij · dr_i): the change of the
/// velocity field over a shift dr_i (Taylor, first order).
[[nodiscard]] std::vector<Eigen::Vector3d> velocity_change_over_shift(const Neighbourhood& n,
                                                                      std::span<const double> mass,
                                                                      std::span<const double> density,
                                                                      std::span<const Eigen::Vector3d> velocity,
                                                                      std::span<const Eigen::Vector3d> shift);

}  // namespace tankfsi::sph
