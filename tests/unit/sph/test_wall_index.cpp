// TriangleIndex (BVH) queries (nearest, within a radius of a point, near a box)
// against brute force over all triangles, on an icosphere and an open cylinder,
// before and after a deformation of the wall (refit and rebuild).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "sph_solver/walls/closest_point.hpp"
#include "sph_solver/walls/primitive_meshes.hpp"
#include "sph_solver/walls/triangle_index.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;

namespace {

// Lowest index among the nearest, like the index promises.
std::optional<WallHit> brute_nearest(const TriangleMesh& mesh, const Vector3d& p, double max_distance) {
  std::optional<WallHit> best;
  for (int t = 0; t < static_cast<int>(mesh.triangle_count()); ++t) {
    const ClosestPoint cp = closest_point_on_triangle(p, mesh, t);
    if (cp.squared_distance >= max_distance * max_distance) continue;
    if (!best || cp.squared_distance < best->closest.squared_distance) best = WallHit{t, cp};
  }
  return best;
}

std::vector<int> brute_within(const TriangleMesh& mesh, const Vector3d& p, double radius) {
  std::vector<int> found;
  for (int t = 0; t < static_cast<int>(mesh.triangle_count()); ++t)
    if (closest_point_on_triangle(p, mesh, t).squared_distance < radius * radius) found.push_back(t);
  return found;
}

std::vector<int> brute_near_box(const TriangleMesh& mesh, const Eigen::AlignedBox3d& region, double radius) {
  std::vector<int> found;
  for (int t = 0; t < static_cast<int>(mesh.triangle_count()); ++t) {
    Eigen::AlignedBox3d box(mesh.corner(t, 0));
    box.extend(mesh.corner(t, 1)).extend(mesh.corner(t, 2));
    if (box.squaredExteriorDistance(region) < radius * radius) found.push_back(t);
  }
  return found;
}

// Compares every query on `points`; returns how many found something within the radii.
int compare_with_brute_force(const TriangleMesh& mesh, const TriangleIndex& index, const std::vector<Vector3d>& points) {
  int hits = 0;
  for (const auto& p : points) {
    for (const double max_distance : {0.05, 0.3, 10.0}) {
      const auto expected = brute_nearest(mesh, p, max_distance);
      const auto found = index.nearest(p, max_distance);
      REQUIRE(expected.has_value() == found.has_value());
      if (!found) continue;
      REQUIRE(found->triangle == expected->triangle);
      REQUIRE(found->closest.squared_distance == expected->closest.squared_distance);
      REQUIRE(found->closest.point == expected->closest.point);
    }
    for (const double radius : {0.1, 0.4}) {
      std::vector<int> found;
      index.within(p, radius, [&](const WallHit& hit) {
        REQUIRE(hit.closest.squared_distance < radius * radius);
        found.push_back(hit.triangle);
      });
      std::sort(found.begin(), found.end());
      REQUIRE(found == brute_within(mesh, p, radius));
      if (!found.empty()) ++hits;
      // A region around p: every triangle whose box comes within the radius of
      // it, so every triangle within the radius of p too.
      const Eigen::AlignedBox3d region(p - Vector3d(0.05, 0.1, 0.0), p + Vector3d(0.1, 0.0, 0.05));
      std::vector<int> near;
      index.near_box(region, radius, near);
      std::sort(near.begin(), near.end());
      REQUIRE(near == brute_near_box(mesh, region, radius));
      REQUIRE(std::includes(near.begin(), near.end(), found.begin(), found.end()));
    }
  }
  return hits;
}

std::vector<Vector3d> random_points(std::mt19937_64& rng, Eigen::AlignedBox3d box, double margin, int n) {
  box.extend(box.min() - Vector3d::Constant(margin));
  box.extend(box.max() + Vector3d::Constant(margin));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vector3d> points;
  for (int i = 0; i < n; ++i) points.push_back(box.min() + Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(box.sizes()));
  return points;
}

// A smooth, large deformation: up to ~0.2 of the radius, so boxes change a lot.
std::vector<Vector3d> deformed(const std::vector<Vector3d>& x) {
  std::vector<Vector3d> y;
  for (const auto& v : x)
    y.push_back(v + 0.2 * Vector3d(std::sin(2.0 * v.x() + v.y()), std::cos(3.0 * v.y() - v.z()), std::sin(v.x() + 2.0 * v.z())));
  return y;
}

void check_mesh(TriangleMesh mesh, std::mt19937_64& rng) {
  TriangleIndex index(mesh);
  const auto points = random_points(rng, mesh.bounding_box(), 0.5, 400);
  CHECK(compare_with_brute_force(mesh, index, points) > 200);

  // After a deformation: the stale index refuses to answer, the refitted and the
  // rebuilt ones agree with brute force on the moved wall.
  const std::vector<Vector3d> original = mesh.vertices();
  mesh.move_vertices(deformed(original));
  REQUIRE_THROWS_AS(index.nearest(points.front(), 1.0), std::logic_error);
  index.refit();
  CHECK(compare_with_brute_force(mesh, index, points) > 200);
  TriangleIndex rebuilt(mesh);
  CHECK(compare_with_brute_force(mesh, rebuilt, points) > 200);
  // And back again: refit follows any motion.
  mesh.move_vertices(original);
  index.refit();
  CHECK(compare_with_brute_force(mesh, index, points) > 200);
}

}  // namespace

TEST_CASE("triangle index: nearest and within equal brute force on an icosphere", "[wall_geometry]") {
  std::mt19937_64 rng(3);
  check_mesh(make_icosphere(1.0, 3), rng);
}

TEST_CASE("triangle index: nearest and within equal brute force on a cylinder", "[wall_geometry][heavy]") {
  std::mt19937_64 rng(4);
  check_mesh(make_open_cylinder(1.0, 2.0, 40, 16, NormalSide::inward), rng);
}

TEST_CASE("triangle index: empty mesh and non-positive radii find nothing", "[wall_geometry]") {
  const TriangleMesh empty;
  const TriangleIndex empty_index(empty);
  CHECK_FALSE(empty_index.nearest(Vector3d::Zero(), 1.0).has_value());
  const TriangleMesh box = make_box(Vector3d::Zero(), Vector3d::Ones(), NormalSide::inward);
  const TriangleIndex index(box);
  CHECK_FALSE(index.nearest(Vector3d::Constant(0.5), 0.0).has_value());
  CHECK(index.nearest(Vector3d::Constant(0.5), 0.5 + 1e-12).has_value());
  CHECK_FALSE(index.nearest(Vector3d::Constant(0.5), 0.5).has_value());  // strictly closer than the limit
  int visited = 0;
  index.within(Vector3d::Constant(0.5), -1.0, [&](const WallHit&) { ++visited; });
  CHECK(visited == 0);
}
