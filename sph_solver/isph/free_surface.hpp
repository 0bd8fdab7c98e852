#pragma once
// The free surface as a boundary of the liquid, treated like the walls (METHOD.md
// §1 step 2 "free surface", §2 eqs 10-14): the Dirichlet condition P = 0 is imposed
// at the surface itself, not at the centres of the outermost particles.
//
// Why. A particle of the top layer sits half a spacing below the surface; its
// share of the weight is carried by the pressure under it, which is rho g L0/2 at
// its centre, not 0. Setting P = 0 at the particle (the classical ISPH Dirichlet
// particle) loses that half layer, and the symmetric pressure gradient (eq 4), whose
// kernel support is cut by the surface, then holds the particle up with only about
// half its weight: the top layer falls into the next and seeds surface waves.
//
// How. The liquid missing above a particle near the surface is completed by a
// half-space of virtual "air" particles on the lattice of spacing L0 beyond a plane
// at distance delta from the particle, normal n (unit, from the surface into the
// liquid) — the geometry of the wall kernel tables (wall_kernel_table.hpp), so the
// same tables Z_k(delta), d_k(delta) give their sums. The air's pressure is the
// linear continuation of the liquid's through P = 0 on the plane:
//   P_air(s) = -P_i s / delta at height s above the plane,
// which is the ghost-fluid Dirichlet condition (Gibou et al. 2002, J Comput Phys
// 176:205). With it
//   - PPE row (eq 6): sum_air a (P_i - P_air) = 2 Z2 (1 + d2/delta) P_i, a diagonal
//     term only, so the matrix stays symmetric; every particle is an unknown, and
//     the top layer's pressure comes out as rho g delta;
//   - pressure gradient (eq 4): the air term -Z1 n (P_i + P_air(d1)) / rho0 =
//     -Z1 n P_i (1 - d1/delta) / rho0, beside the wall terms;
//   - densities: the air completes the kernel sum to rho0 (see below).
// On a lattice under a flat surface this makes the linear hydrostatic pressure an
// exact solution of the PPE and an exact equilibrium of every layer, and the air
// terms of all particles sum to zero (the pairs (i, k) and their mirror images
// cancel: (delta_i - s_k) is odd under the swap), so the walls carry the whole weight.
//
// delta from the density. Beneath a flat surface the kernel sum of a particle at
// depth delta misses exactly the air's share Z0(delta) of the rest density
// rho_L = rho0 L0^D sum W of a full lattice (WallKernelTable::lattice_share), so
//   delta = Z0^-1(1 - rho*_i / rho_L)     (rho*_i with the walls' share),
// read from the table (WallKernelTable::distance_for_share). (Against rho0 itself
// the lattice's own 6e-5 would put a surface 2.6 L0 above every particle.) It varies continuously
// with the particle positions — there is no flag that switches a particle between
// Dirichlet and unknown from one step to the next. A particle that misses more than
// a half-space (a drop, a jet, a corner of the liquid) gets delta = 0, floored at
// L0/4 as the walls' extrapolation distance is. The normal is the direction of the
// colour gradient grad C_i (walls included), which points into the liquid; a drop
// with nothing else in its support (grad C = 0) has air on every side and a zero
// normal, so only the scalar air terms (density, PPE diagonal) act on it.
//
// Contact lines. Where the surface meets a wall at a right angle, the wall's half-
// space counted the air behind the wall above the surface as liquid (the quarter-
// space behind both planes). Then the deficit is Z0(delta) - Q0(d_w, delta) (corner
// table), solved for delta by bisection; the normal is grad C with that overlap's
// part taken out, made square to the wall; and the overlap, counted by the wall and
// the air, is taken out once from every sum (boundary_overlap.hpp).
//
// Which particles. Those whose deficit puts the surface within 2 L0 (the first two
// layers of a lattice): a farther surface is lost in the density noise of a liquid
// in motion (1e-4), and its air share (1e-4 at the third layer) is as small. No
// free-surface flag is involved, so nothing switches with a flag. Each of them has
// its density completed (the air's share: rho_L, read against the lattice rho0;
// completed_density()) for the volumes and the divergence, and no density error.
// A surface that close has its first layer (deficit
// Z0(L0) or more) between it and the particle: a particle with a smaller deficit
// and no such neighbour within delta + L0/4 gets no air. Walls are not exact enough
// to go without this: a curved wall of facets twice L0 wide completes its
// particles' sums only to 0.5-2 %, which read as air 1.4-1.9 L0 away deep in the
// liquid, and the air's Dirichlet share (times the large pressure there) pulled the
// PPE's pressure of a cylindrical tank at rest 18 % below hydrostatic.
//
// Free-surface flags (the count in fluid.csv, the shifting's exclusion zone): a
// density below beta rho0, or a kernel support that is not
// full (div r below 1.5 in 2D, 2.4 in 3D: Lee et al. 2008; Lind et al. 2012); the
// second catches a surface layer squeezed by a wave, whose density would call it
// interior.
#include <Eigen/Core>

#include <span>
#include <vector>

#include "sph_solver/isph/particle_terms.hpp"
#include "sph_solver/isph/surface_contact.hpp"
#include "sph_solver/isph/wall_contacts.hpp"
#include "sph_solver/walls/wall_kernel_table.hpp"

namespace tankfsi::sph {

/// Free-surface flags of the owned particles (see above), from the kernel-sum
/// densities of owned and ghost particles.
[[nodiscard]] std::vector<unsigned char> detect_free_surface(const Neighbourhood& n, std::span<const double> mass,
                                                            std::span<const double> density);

/// The air contacts of the owned particles, from the kernel-sum densities of owned
/// and ghost particles.
[[nodiscard]] std::vector<SurfaceContact> surface_contacts(const Neighbourhood& n, std::span<const double> mass,
                                                           std::span<const double> density, const WallModel& walls);

/// The density the step's sums divide by (volumes m / rho), completed by the air
/// and read against the lattice: rho0 where a contact is active (it has a deficit
/// by construction), the kernel sum times rho0 / rho_L elsewhere, rho_L =
/// `lattice_density` the kernel sum of a full lattice (rho0
/// WallKernelTable::lattice_share()). So a lattice's volumes are L0^D, the volume
/// the wall tables are summed with. (Against the raw kernel sum the Wendland C2
/// kernel at h = 1.5 L0, whose lattice sum is 1.0031, put the PPE's pressure of a
/// 3D box at rest 0.5-0.9 % above rho g (H - z); read against the lattice, 0.012-
/// 0.025 % in the layers measured below the top two (the first, second, third and
/// sixth). The quartic spline's lattice sum is 1.00002.)
/// Owned particles.
[[nodiscard]] std::vector<double> completed_density(std::span<const double> density,
                                                    std::span<const SurfaceContact> contacts, double lattice_density,
                                                    double rho0);

/// Kernel sums read against the lattice, rho rho0 / rho_L, without the air (as
/// completed_density() where no contact is active).
[[nodiscard]] std::vector<double> density_against_lattice(std::span<const double> density, double lattice_density,
                                                          double rho0);

}  // namespace tankfsi::sph
