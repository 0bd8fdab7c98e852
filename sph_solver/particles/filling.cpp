#include "sph_solver/particles/filling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sph_solver/walls/closest_point.hpp"
#include "sph_solver/walls/triangle_index.hpp"
#include "sph_solver/walls/wall_corner_values.hpp"

namespace tankfsi::sph {

namespace {

// Clearance tolerance, relative to L₀: far above the round-off of lattice coordinates
// (~1e-16 of the tank size), far below any geometric feature. The smooth wall's
// second-order error is allowed for apart (passes()).
constexpr double clearance_tolerance = 2e-3;
// A 2D wall face has a unit normal with |n_z| at most this; front and back faces have 1.
constexpr double max_in_plane_normal_z = 1e-6;

void validate(const FillSpec& spec) {
  if (!(spec.spacing > 0.0) || !std::isfinite(spec.spacing))
    throw std::invalid_argument("fill_tank: spacing must be positive and finite");
  if (!(spec.density > 0.0) || !std::isfinite(spec.density))
    throw std::invalid_argument("fill_tank: density must be positive and finite");
  if (spec.dimension != 2 && spec.dimension != 3)
    throw std::invalid_argument("fill_tank: dimension must be 2 or 3, got " + std::to_string(spec.dimension));
  if (std::isnan(spec.fill_level)) throw std::invalid_argument("fill_tank: fill_level is NaN");
  if (spec.region && (spec.region->isEmpty() || spec.region->min().hasNaN() || spec.region->max().hasNaN()))
    throw std::invalid_argument("fill_tank: the region is empty");
  if (spec.lattice_origin && !spec.lattice_origin->allFinite())
    throw std::invalid_argument("fill_tank: the lattice origin is not finite");
  if (spec.hydrostatic_pressure && (!(spec.gravity >= 0.0) || !std::isfinite(spec.gravity)))
    throw std::invalid_argument("fill_tank: gravity must be finite and >= 0 for a hydrostatic pressure");
}

// The faces of 2D walls that matter for particles at z = 0: those with an in-plane normal.
TriangleMesh in_plane_faces(const TriangleMesh& walls) {
  std::vector<std::array<int, 3>> kept;
  for (std::size_t t = 0; t < walls.triangle_count(); ++t)
    if (std::abs(walls.face_normals()[t].z()) <= max_in_plane_normal_z) kept.push_back(walls.triangles()[t]);
  return TriangleMesh(walls.vertices(), std::move(kept));
}

// Lattice indices n with origin + (n + 1/2) L₀ in [lo, hi], widened by one on each side:
// the exact tests on each point decide, the range only has to contain them.
std::pair<int, int> index_range(double origin, double lo, double hi, double spacing) {
  return {static_cast<int>(std::ceil((lo - origin) / spacing - 0.5)) - 1,
          static_cast<int>(std::floor((hi - origin) / spacing - 0.5)) + 1};
}

bool in_region(const Eigen::Vector3d& x, const std::optional<Eigen::AlignedBox3d>& region, int dimension) {
  if (!region) return true;
  for (int a = 0; a < dimension; ++a)
    if (x[a] < region->min()[a] || x[a] > region->max()[a]) return false;
  return true;
}

/// The walls as the particles see them: the nearest triangle and the smooth wall
/// behind it (wall_corner_values.hpp), which the clearance is measured to.
struct FillWalls {
  const TriangleMesh& mesh;
  TriangleIndex index{mesh};
  WallCornerValues corners{mesh};

  explicit FillWalls(const TriangleMesh& m) : mesh(m) {
    // Normals only: the curvature is not needed here.
    const std::vector<double> no_curvature(mesh.vertex_count(), std::numeric_limits<double>::quiet_NaN());
    corners.update(mesh, no_curvature);
  }
};

bool passes(const FillWalls& walls, const FillSpec& spec, const Eigen::Vector3d& x) {
  if (!(x[spec.dimension - 1] < spec.fill_level) || !in_region(x, spec.region, spec.dimension)) return false;
  const auto hit = walls.index.nearest(x, std::numeric_limits<double>::infinity());
  if (!hit) return false;
  const double to_facet = signed_distance(x, walls.mesh, hit->triangle, hit->closest);
  // In front of the facets, whatever the smooth wall behind them: the particles
  // stop at the facets (a crossing is one of them, wall_crossings.hpp), and facets
  // that lie more than L0/2 inside the smooth wall would leave the outer ring of a
  // cylinder behind them.
  if (!(to_facet >= clearance_tolerance * spec.spacing)) return false;
  const double depth = walls.corners.smooth_depth(walls.mesh, hit->triangle, hit->closest.barycentric);
  const double distance = to_facet + depth;
  // The smooth wall's depth behind a facet is a quadratic, short of the curved
  // wall's by its second-order error, depth^2 / (2R) at a cylinder's facet middle
  // (largest_edge_curvature()); allowed for twice over. Without it the ring of
  // particles L0/2 inside the smooth cylinder lost those by the facets' middles
  // once the facets lay 0.2 L0 off it (cases/hydrostatic_3d at element_size 0.25
  // m, 0.29 L0: 235 of the outer ring's 600), and the liquid fell into the gaps
  // (cases/hydrostatic_3d/README.md, "Coarse facets").
  const double second_order = depth * depth * walls.corners.largest_edge_curvature(walls.mesh, hit->triangle);
  return distance >= (0.5 - clearance_tolerance) * spec.spacing - second_order;
}

// Lattice points that pass the level, region and clearance tests, in lattice order.
std::vector<Eigen::Vector3d> lattice_points(const TriangleMesh& mesh, const FillSpec& spec) {
  const int dims = spec.dimension;
  const int up = dims - 1;
  const double h = spec.spacing;
  const FillWalls walls(mesh);
  const Eigen::AlignedBox3d walls_box = mesh.bounding_box();
  const Eigen::Vector3d origin = spec.lattice_origin.value_or(walls_box.min());
  Eigen::AlignedBox3d search = walls_box;
  for (int a = 0; a < dims && spec.region; ++a) {
    search.min()[a] = std::max(search.min()[a], spec.region->min()[a]);
    search.max()[a] = std::min(search.max()[a], spec.region->max()[a]);
  }
  search.max()[up] = std::min(search.max()[up], spec.fill_level);
  if (search.isEmpty()) return {};

  std::array<std::pair<int, int>, 3> range{};  // z stays at index 0 (z = 0) in 2D
  for (int a = 0; a < dims; ++a)
    range[static_cast<std::size_t>(a)] = index_range(origin[a], search.min()[a], search.max()[a], h);
  const auto coordinate = [&](int a, int n) { return a < dims ? origin[a] + (n + 0.5) * h : 0.0; };

  std::vector<Eigen::Vector3d> points;
  for (int k = range[2].first; k <= range[2].second; ++k)
    for (int j = range[1].first; j <= range[1].second; ++j)
      for (int i = range[0].first; i <= range[0].second; ++i) {
        const Eigen::Vector3d x(coordinate(0, i), coordinate(1, j), coordinate(2, k));
        if (passes(walls, spec, x)) points.push_back(x);
      }
  return points;
}

struct FilledPoints {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> volumes;
};

// Rings about the z axis (filling.hpp), layer by layer from the walls' lowest z.
FilledPoints ring_points(const TriangleMesh& mesh, const FillSpec& spec) {
  const double h = spec.spacing;
  const double radius = *spec.cylinder_radius;
  const FillWalls walls(mesh);
  const double floor = spec.lattice_origin ? spec.lattice_origin->z() : mesh.bounding_box().min().z();
  FilledPoints out;
  for (int k = 0; floor + (k + 0.5) * h < spec.fill_level; ++k) {
    const double z = floor + (k + 0.5) * h;
    for (int m = 0; radius - (m + 0.5) * h > 0.0; ++m) {
      const double r = radius - (m + 0.5) * h;
      const int n = std::max(1, static_cast<int>(std::lround(2.0 * std::numbers::pi * r / h)));
      const bool innermost = r - h <= 0.0;
      const double area = innermost ? std::numbers::pi * (r + 0.5 * h) * (r + 0.5 * h) : 2.0 * std::numbers::pi * r * h;
      const double turn = (m % 2 == 0 ? 0.0 : 0.5) + (k % 2 == 0 ? 0.0 : 0.25);
      for (int i = 0; i < n; ++i) {
        const double phi = 2.0 * std::numbers::pi * (i + turn) / n;
        const Eigen::Vector3d x(n == 1 ? 0.0 : r * std::cos(phi), n == 1 ? 0.0 : r * std::sin(phi), z);
        if (!passes(walls, spec, x)) continue;
        out.points.push_back(x);
        out.volumes.push_back(area / n * h);
      }
    }
  }
  return out;
}

}  // namespace

Particles fill_tank(const TriangleMesh& walls, const FillSpec& spec) {
  validate(spec);
  std::optional<TriangleMesh> planar;
  if (spec.dimension == 2) planar.emplace(in_plane_faces(walls));
  const TriangleMesh& mesh = planar ? *planar : walls;
  if (mesh.triangle_count() == 0)
    throw std::invalid_argument(planar ? "fill_tank: the 2D walls have no face with an in-plane normal"
                                       : "fill_tank: the walls have no triangles");
  if (planar && !(mesh.bounding_box().min().z() < 0.0 && mesh.bounding_box().max().z() > 0.0))
    throw std::invalid_argument("fill_tank: 2D walls must straddle the plane z = 0 of the particles");

  if (spec.cylinder_radius && !(spec.dimension == 3 && *spec.cylinder_radius > 0.0))
    throw std::invalid_argument("fill_tank: a cylindrical filling is 3D, with a positive radius");
  FilledPoints filled;
  if (spec.cylinder_radius) {
    filled = ring_points(mesh, spec);
  } else {
    filled.points = lattice_points(mesh, spec);
    filled.volumes.assign(filled.points.size(), std::pow(spec.spacing, spec.dimension));
  }
  const std::vector<Eigen::Vector3d>& points = filled.points;
  if (points.empty())
    throw std::invalid_argument("fill_tank: no lattice point lies inside the walls below the fill level " +
                                std::to_string(spec.fill_level) + " (and in the region, if any)");

  const int up = spec.dimension - 1;
  double surface = -std::numeric_limits<double>::infinity();
  for (const auto& x : points) surface = std::max(surface, x[up] + 0.5 * spec.spacing);
  Particles particles;
  for (std::size_t n = 0; n < points.size(); ++n) {
    const double pressure =
        spec.hydrostatic_pressure ? spec.density * spec.gravity * (surface - points[n][up]) : 0.0;
    particles.push_back(static_cast<std::int64_t>(n), points[n], Eigen::Vector3d::Zero(),
                        spec.density * filled.volumes[n], pressure);
  }
  return particles;
}

}  // namespace tankfsi::sph
