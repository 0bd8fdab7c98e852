#pragma once
// Walls as the particles see them (METHOD.md §2, eqs 10-15): the wall mesh with its
// spatial index, curvature and motion (WallModel), and each particle's wall
// contacts — the walls within its kernel support, with the table values that stand
// for the virtual particles behind them (WallContacts).
//
// Several walls: a particle near a corner sees each wall of the corner as its own
// half-space. Triangles within the support are visited nearest first; a triangle
// becomes a new contact unless its plane is nearly parallel (normals within ~37°,
// cos > 0.8) to a contact already taken — the same flat or gently curved wall, whose
// nearest triangle already stands for it. A triangle whose plane the particle lies
// behind (the far side of a thin plate) is not a contact. The half-spaces of two
// walls meeting at a corner overlap behind the corner; for orthogonal walls the
// overlap is taken out once with the corner kernel table (boundary_overlap.hpp), so
// every virtual particle counts once, and where three orthogonal walls meet the
// octant behind all three is added back once; overlaps of walls at other angles
// are not corrected.
//
// Distance (eq 15): the true point-triangle distance to the nearest triangle of the
// wall, plus how far the smooth wall the facets approximate lies behind it there
// (WallCornerValues::smooth_depth: the sagitta of a faceted cylinder, 0 on a flat
// wall); the normal that smooth wall's, interpolated at the closest point from the
// triangle's corner normals (wall_corner_values.hpp: a flat wall keeps its plane's
// normal exactly). Measured by the facets alone, a cylinder of 32 facets (2 L0
// wide) completed its outer rings' kernel sums to -2.1 % at the vertices and held
// its liquid inside the polygon; the wall's distance and normal then belonged to
// different walls, and the liquid next to it kept 2-3 times the speeds of the
// rest (cases/hydrostatic_3d/README.md). Which wall a triangle belongs to and
// which side of it the particle is on go by the triangle's own plane. A particle
// that has crossed a wall by less than L0/2 is treated as touching it (distance 0),
// so the strongest wall terms push it back; one further behind is not in contact
// (it has left through the wall). But one behind a triangle's plane, beside the
// triangle and in front of another wall is round a convex edge of the solid
// (liquid flowing over the top of a plate, below the top face's plane): that
// triangle is no wall for it — taken at distance 0 it stood for a half-space of
// wall through the liquid itself. (Behind every wall near it, beside a facet —
// just outside a faceted cylinder, say — it has crossed, and touches.)
//
// Two-sided triangles (WallModel::two_sided: a coupled sheet, such as an elastic
// gate, that the liquid may wet on both faces) are walls from behind too: a
// particle right behind a triangle (its closest point the foot of its
// perpendicular) sees it with the normal turned round (and the curvature's
// sign); behind a triangle's plane and beside it (the sheet's other triangles,
// or its free edge) it is round the sheet's edge, as round a convex edge above,
// never touching: a sheet has no inside to have been crossed into (a path
// through it is caught at the step's end, wall_crossings.hpp).
//
// Curvature: the flat-wall tables count the virtual fluid behind the wall's tangent
// plane. A wall of mean curvature H (positive where it bulges towards the fluid;
// H = κ/2 for the curve of a 2D section) leaves out, or adds where negative, a
// sliver (k1 y^2 + k2 z^2)/2 thick at lateral offset (y, z) from the foot: each
// Z_k becomes Z_k - H C_k to first order, C_k the kernel weights over that sliver
// per unit H (WallKernelValues). (Scaling Z_k by 1 - 2 H d_k, the area of the
// layers at its representative depth, overstated the sliver's Z1 2.6-fold at
// L0/2 from the wall (quartic spline): inside a cylinder of radius 10 L0, Z1 came out 4 %
// above the continuum's, and the liquid next to the wall was pushed inwards at
// 0.02-0.4 g in its first step, growing with depth.)
// The sliver also bends the tangential moment Z3 (I - n n^T) (WallContact::
// tangential_moment): between lateral directions a and b it weighs
// (1/2) integral w l_a l_b (l^T K l) over the plane (w the kernel factor of Z3's
// summand, K the wall's shape operator, H = tr K / 2), which a radial w turns
// into H C3 P + (C3/2) K_dev, P the projector along the wall and K_dev = K - H P
// (WallCornerValues::shape_deviator). A sphere's is 0; a cylinder's
// sliver lies across the axis, not along it, so its moment along the axis
// changes by H C3 / 2 and around it by 3 H C3 / 2. (Taking H C3 both ways made
// the vertical pressure gradient beside a cylinder's wall too large: in
// cases/hydrostatic_3d the ring next to the wall rose 0.016 g faster than the
// next ring at the first step (0.015 g with the pressure gradient divided by
// the particles' own moments; -0.0001 g with the deviator), and in a damped
// settling run a steady roll went up the wall, inwards at mid-depth and out
// along the floor.)
// Only curvature the kernel can resolve is kept: at vertices with |H| × support > 0.5
// (sharp edges and corners, which the per-wall contacts already handle) each
// triangle takes its own wall's curvature from the neighbouring vertices
// (wall_corner_values.hpp), so a cylinder's wall keeps 1/(2R) down to its foot.
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "sph_solver/isph/boundary_overlap.hpp"
#include "sph_solver/isph/fluid_model.hpp"
#include "sph_solver/kernels/kernel.hpp"
#include "sph_solver/walls/triangle_index.hpp"
#include "sph_solver/walls/corner_kernel_table.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"
#include "sph_solver/walls/wall_corner_values.hpp"
#include "sph_solver/walls/wall_kernel_table.hpp"

namespace tankfsi::sph {

class WallModel {
 public:
  /// The mesh's normals must point to the fluid. Walls start at rest,
  /// one-sided.
  WallModel(TriangleMesh mesh, const FluidModel& model, const Kernel& kernel);
  WallModel(const WallModel&) = delete;
  WallModel& operator=(const WallModel&) = delete;

  [[nodiscard]] const TriangleMesh& mesh() const { return *mesh_; }
  [[nodiscard]] const TriangleIndex& index() const { return index_; }
  [[nodiscard]] const WallKernelTable& table() const { return table_; }
  [[nodiscard]] const CornerKernelTable& corner_table() const { return corner_table_; }
  /// Normal and curvature of each triangle's own wall at its corners (see above).
  [[nodiscard]] const WallCornerValues& corner_values() const { return corner_values_; }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& vertex_velocities() const { return velocities_; }

  /// Moves the wall (a deforming structure): positions and velocities per vertex,
  /// in the tank-base frame. Updates the index and curvature. (The wall's
  /// acceleration is not needed: the Neumann wall pressure follows from v* - v_wall.)
  void move(std::span<const Eigen::Vector3d> positions, std::span<const Eigen::Vector3d> velocities);
  /// Replaces the whole wall (a coupled run's, build_interface_wall): new
  /// topology, at rest; the kernel tables stay (they depend on the kernel only).
  /// `two_sided`: one flag per triangle (empty: all one-sided).
  void replace_mesh(TriangleMesh mesh, std::vector<char> two_sided = {});
  /// Whether triangle t is a wall from both faces (see above).
  [[nodiscard]] bool two_sided(int t) const {
    return !two_sided_.empty() && two_sided_[static_cast<std::size_t>(t)] != 0;
  }

 private:
  void update_curvature();

  std::unique_ptr<TriangleMesh> mesh_;  ///< on the heap: the index points to it
  TriangleIndex index_;
  WallKernelTable table_;
  CornerKernelTable corner_table_;
  double support_radius_;
  std::vector<double> curvature_;  ///< per vertex, NaN where not resolvable (scratch of update_curvature)
  WallCornerValues corner_values_;
  std::vector<Eigen::Vector3d> velocities_;
  std::vector<char> two_sided_;  ///< per triangle, or empty: none
};

/// A closest point of a wall: a triangle and the barycentric coordinates of the
/// point on it, with its share of the contact.
struct WallFoot {
  int triangle = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  double weight = 1.0;
};

/// Most closest points a contact blends (see find_wall_contacts).
inline constexpr int max_wall_feet = 4;
/// Width of the blend, in L0: hits of one wall whose distance exceeds the
/// nearest's by less than this share the contact.
inline constexpr double wall_foot_blend_band = 0.1;

/// One wall seen by one particle.
struct WallContact {
  /// The closest points it stands for, nearest first; weights sum to 1. One,
  /// but where the nearest triangle of the wall is about to change (see
  /// find_wall_contacts).
  std::array<WallFoot, max_wall_feet> feet{};
  int foot_count = 1;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();       ///< unit, towards the fluid
  double distance = 0.0;                                  ///< r_iw >= 0
  WallKernelValues values;                                ///< curvature-corrected
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();     ///< wall velocity at the closest point
  /// The missing neighbours' part of -sum_j V_j x_ij (x) grad_i W_ij along the
  /// wall: values.z3 (I - n n^T), less the sliver's anisotropic share on a wall
  /// curved unequally in its two directions (see above; tangential_moment()).
  Eigen::Matrix3d tangential_moment = Eigen::Matrix3d::Zero();
};

/// values.z3 (I - n n^T) - (C3 / 2) K_dev: the tangential moment of a wall of unit
/// normal n whose shape operator has the traceless part K_dev (in the plane normal
/// to n; see above), `values` already bent by the mean curvature (Z3 - H C3). In
/// 2D (one lateral direction in the plane, the z row not used) and where the
/// sliver took Z3 to zero (curved() never passes zero), the first term alone.
[[nodiscard]] Eigen::Matrix3d tangential_moment(const WallKernelValues& values, const Eigen::Vector3d& normal,
                                                const Eigen::Matrix3d& shape_deviator, int dimension);

/// The contacts of particles 0 .. n-1, the overlaps of orthogonal pairs of them
/// (corners: first and second index the particle's own contacts) and the octants
/// of orthogonal triples (a box's corners), in CSR form.
struct WallContacts {
  std::vector<int> offsets{0};
  std::vector<WallContact> contacts;
  std::vector<int> overlap_offsets{0};
  std::vector<BoundaryOverlap> overlaps;
  std::vector<int> octant_offsets{0};
  std::vector<CornerOctant> octants;

  [[nodiscard]] std::span<const WallContact> of(int i) const {
    return std::span<const WallContact>(contacts).subspan(begin(offsets, i), count(offsets, i));
  }
  [[nodiscard]] std::span<const BoundaryOverlap> overlaps_of(int i) const {
    return std::span<const BoundaryOverlap>(overlaps).subspan(begin(overlap_offsets, i), count(overlap_offsets, i));
  }
  [[nodiscard]] std::span<const CornerOctant> octants_of(int i) const {
    return std::span<const CornerOctant>(octants).subspan(begin(octant_offsets, i), count(octant_offsets, i));
  }

 private:
  static std::size_t begin(const std::vector<int>& o, int i) { return static_cast<std::size_t>(o[static_cast<std::size_t>(i)]); }
  static std::size_t count(const std::vector<int>& o, int i) {
    return static_cast<std::size_t>(o[static_cast<std::size_t>(i) + 1] - o[static_cast<std::size_t>(i)]);
  }
};

/// The triangles within the wall tables' cutoff + skin of each of a set of points,
/// in CSR form, with their closest points to the point searched (each point's
/// nearest first, ties by triangle index, the order find_wall_contacts keeps them
/// in, so that it only has to mend the order where a point moved): a step's two
/// searches (at x^n and at x~, fluid_solver.hpp) take their contacts from these
/// without the spatial index, as long as no point moved by more than the skin
/// and the wall did not move. A point that has not moved at all (x^n) takes the
/// closest points as they are: the same numbers a new test would compute.
struct WallCandidates {
  std::vector<int> offsets{0};
  std::vector<WallHit> hits;
  std::vector<Eigen::Vector3d> searched;  ///< the points searched
  double skin = 0.0;
  std::uint64_t wall_version = 0;  ///< the mesh's geometry_version() when searched
};

[[nodiscard]] WallCandidates find_wall_candidates(const WallModel& walls, std::span<const Eigen::Vector3d> positions,
                                                  double skin);

/// The wall contacts of the given particles (METHOD.md eq 15 and the rules above);
/// with `candidates` (of these particles, moved by at most their skin since) only
/// their triangles are tested: the same contacts as a search of the index, which
/// finds the triangles within the cutoff, sorted the same way. Throws
/// std::invalid_argument for candidates of other points or of a moved wall.
///
/// Each contact is the nearest triangle of its wall, blended with the wall's next
/// nearest ones where their distances come within `wall_foot_blend_band` L0 of it.
/// Why: inside a faceted curved wall (a cylinder) the nearest facet changes on the
/// bisector of two facets, where the closest point jumps from one facet to the
/// other; the wall force of the particle then jumped between their vertices and
/// the wall's normal and velocity at the contact with it, so the fluid's forces on a
/// deforming wall were not a continuous function of the wall's motion (implicit
/// coupling stalled at the size of those jumps: cases/flexible_cylinder_3d). Each
/// foot k of the wall (nearest first, distance d_k, at most max_wall_feet) weighs
/// taper((d_k - d_0) / band) - taper((d_m - d_0) / band), d_m the distance of the
/// first hit of the wall left out (taper of it 0 when none), normalised, with
/// taper(s) = (1 - s)^2 (1 + 2 s) on [0, 1] and 0 beyond: continuous when hits
/// trade places (two equidistant feet weigh alike) and when one enters or leaves
/// the band or the kept set. The distance (eq 15), and so the tables, stay the
/// nearest triangle's; the normal, velocity and curvature at the contact are the
/// weighted means over its feet, and its wall force is shared out over their
/// vertices by weight times barycentric coordinate.
[[nodiscard]] WallContacts find_wall_contacts(const WallModel& walls, std::span<const Eigen::Vector3d> positions,
                                              int dimension, const WallCandidates* candidates = nullptr);

/// How far behind a wall's plane, in L0, a particle that crossed the triangle
/// itself still touches it (distance 0, see above); further behind it has left
/// through the wall.
inline constexpr double touching_depth = 0.5;

/// The normal (unit, towards the fluid) of triangle t's plane as the particles of
/// a `dimension`-D run see it; zero for the front and back of a 2D section (and a
/// degenerate triangle).
[[nodiscard]] Eigen::Vector3d wall_plane_normal(const TriangleMesh& mesh, int triangle, int dimension);

/// Calls visit(vertex, share) for each corner of each foot of the contact, share =
/// the foot's weight times the corner's barycentric coordinate (the shares sum to 1;
/// a vertex of two feet is visited twice).
template <class Visit>
void for_each_vertex_share(const TriangleMesh& mesh, const WallContact& contact, Visit&& visit) {
  for (int f = 0; f < contact.foot_count; ++f) {
    const WallFoot& foot = contact.feet[static_cast<std::size_t>(f)];
    const auto& corners = mesh.triangles()[static_cast<std::size_t>(foot.triangle)];
    for (int k = 0; k < 3; ++k) visit(corners[static_cast<std::size_t>(k)], foot.weight * foot.barycentric[k]);
  }
}

/// A per-vertex wall field (velocity, ...) at a contact's closest points:
/// barycentric interpolation over each foot's triangle, weighted.
[[nodiscard]] Eigen::Vector3d at_contact(const TriangleMesh& mesh, std::span<const Eigen::Vector3d> vertex_values,
                                         const WallContact& contact);

/// Adds the force `force` that particle i exerts on the wall through `contact` to
/// the vertices of its feet's triangles, shared by weight times barycentric
/// coordinate.
void add_wall_force(const TriangleMesh& mesh, const WallContact& contact, const Eigen::Vector3d& force,
                    std::vector<Eigen::Vector3d>& vertex_forces);

}  // namespace tankfsi::sph
