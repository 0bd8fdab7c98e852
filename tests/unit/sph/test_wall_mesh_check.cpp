// Whether a wall mesh can hold the liquid (wall_mesh_check.hpp): every generator's
// tank passes, and each defect — flipped triangle, non-manifold edge, leak below
// the fill level, inverted normals, crossing and overlapping triangles — is found
// and named.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "sph_solver/walls/primitive_meshes.hpp"
#include "sph_solver/walls/tank_meshes.hpp"
#include "sph_solver/walls/wall_mesh_check.hpp"

using namespace tankfsi::sph;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using Eigen::Vector3d;

namespace {

WallCheckOptions in_3d(double level) { return {.dimension = 3, .fill_level = level}; }

/// The mesh with triangles appended (vertices appended too, indices past the old ones).
TriangleMesh with_extra(const TriangleMesh& mesh, const std::vector<Vector3d>& points,
                        const std::vector<std::array<int, 3>>& local_triangles) {
  auto vertices = mesh.vertices();
  auto triangles = mesh.triangles();
  const int base = static_cast<int>(vertices.size());
  vertices.insert(vertices.end(), points.begin(), points.end());
  for (const auto& t : local_triangles) triangles.push_back({base + t[0], base + t[1], base + t[2]});
  return {vertices, triangles};
}

}  // namespace

TEST_CASE("generated tanks pass the wall checks", "[walls]") {
  CHECK(wall_mesh_problem(make_box(Vector3d::Zero(), Vector3d(2, 1, 1), NormalSide::inward), in_3d(0.5)).empty());
  CHECK(wall_mesh_problem(make_box(Vector3d::Zero(), Vector3d(2, 1, 1), NormalSide::inward, true), in_3d(0.5)).empty());
  CHECK(wall_mesh_problem(make_cylindrical_tank(1.0, 1.5, 24, 6, 4, DomeRoof{1.5, 4}), in_3d(1.0)).empty());
  CHECK(wall_mesh_problem(make_cylindrical_tank(1.0, 1.5, 24, 6, 4), in_3d(1.0)).empty());
  const WallCheckOptions in_2d{.dimension = 2, .fill_level = 0.5};
  CHECK(wall_mesh_problem(make_rectangular_tank_2d(2.0, 1.0, 0.1, 0.05), in_2d).empty());
  CHECK(wall_mesh_problem(make_overflow_tank_2d(OverflowTank2d{.target_edge = 0.02}), in_2d).empty());
}

TEST_CASE("a wall with a flipped triangle or a non-manifold edge is not a surface", "[walls]") {
  const TriangleMesh box = make_box(Vector3d::Zero(), Vector3d::Ones(), NormalSide::inward);
  auto triangles = box.triangles();
  std::swap(triangles[3][1], triangles[3][2]);
  const std::string flipped = wall_mesh_problem(TriangleMesh(box.vertices(), triangles), in_3d(0.5));
  CHECK_THAT(flipped, StartsWith("the wall mesh is not a valid surface:"));
  CHECK_THAT(flipped, Contains("inconsistent orientation"));
  // A fin on an edge of the box: three triangles share that edge.
  const auto& t0 = box.triangles()[0];
  auto fin = box.triangles();
  auto vertices = box.vertices();
  vertices.push_back(Vector3d(0.5, 0.5, -1.0));
  fin.push_back({t0[0], t0[1], static_cast<int>(vertices.size()) - 1});
  CHECK_THAT(wall_mesh_problem(TriangleMesh(vertices, fin), in_3d(0.5)), Contains("is non-manifold"));
}

TEST_CASE("open edges are allowed above the fill level and on a 2D section's faces only", "[walls]") {
  const TriangleMesh open_top = make_box(Vector3d::Zero(), Vector3d(2, 1, 1), NormalSide::inward, true);
  CHECK(wall_mesh_problem(open_top, in_3d(0.99)).empty());
  const std::string leak = wall_mesh_problem(open_top, in_3d(1.2));
  CHECK_THAT(leak, StartsWith("the walls are open below the fill level 1.2 m (4 open edges)"));
  CHECK_THAT(leak, Contains("is used by triangle"));
  // A hole in the floor: drop one floor triangle of a closed box.
  const TriangleMesh box = make_box(Vector3d::Zero(), Vector3d(2, 1, 1), NormalSide::inward);
  auto triangles = box.triangles();
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (box.face_normals()[t].z() > 0.9) {
      triangles.erase(triangles.begin() + static_cast<long>(t));
      break;
    }
  CHECK_THAT(wall_mesh_problem(TriangleMesh(box.vertices(), triangles), in_3d(0.5)),
             Contains("open below the fill level 0.5 m (3 open edges)"));
  // The 2D section is open at z = ±depth/2 at every height; its rim is above the level.
  const TriangleMesh section = make_rectangular_tank_2d(2.0, 1.0, 0.1, 0.05);
  CHECK(wall_mesh_problem(section, {.dimension = 2, .fill_level = 0.9}).empty());
  CHECK_THAT(wall_mesh_problem(section, {.dimension = 2, .fill_level = 1.1}), Contains("open below the fill level"));
  // In 3D the same open faces leak.
  CHECK_THAT(wall_mesh_problem(section, in_3d(0.5)), Contains("open below the fill level"));
}

TEST_CASE("walls whose normals point out of the liquid are inverted", "[walls]") {
  const std::string closed = wall_mesh_problem(make_box(Vector3d::Zero(), Vector3d(2, 1, 1), NormalSide::outward),
                                               in_3d(0.5));
  CHECK_THAT(closed, StartsWith("the walls are inverted"));
  CHECK_THAT(closed, Contains("+2 m^3"));  // the box's volume
  CHECK_THAT(wall_mesh_problem(make_box(Vector3d::Zero(), Vector3d(2, 1, 1), NormalSide::outward, true), in_3d(0.5)),
             StartsWith("the walls are inverted"));
  const TriangleMesh cylinder = make_open_cylinder(1.0, 1.0, 16, 2, NormalSide::outward);
  CHECK_THAT(wall_mesh_problem(cylinder, in_3d(-1.0)), StartsWith("the walls are inverted"));
  CHECK(wall_mesh_problem(make_open_cylinder(1.0, 1.0, 16, 2, NormalSide::inward), in_3d(-1.0)).empty());
}

TEST_CASE("crossing and overlapping triangles are a self-intersecting wall", "[walls]") {
  const TriangleMesh box = make_box(Vector3d::Zero(), Vector3d(2, 1, 1), NormalSide::inward);
  // A separate closed tetrahedron poking through the floor.
  const std::vector<Vector3d> tetra{{0.5, 0.5, -0.2}, {0.8, 0.5, -0.2}, {0.6, 0.8, -0.2}, {0.6, 0.6, 0.3}};
  const std::vector<std::array<int, 3>> faces{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  const std::string poke = wall_mesh_problem(with_extra(box, tetra, faces), in_3d(0.5));
  CHECK_THAT(poke, StartsWith("the wall mesh intersects itself"));
  CHECK_THAT(poke, Contains("intersect near"));
  // The same tetrahedron inside the tank, touching nothing, is a valid obstacle...
  std::vector<Vector3d> inside = tetra;
  for (auto& p : inside) p.z() += 0.4;
  const auto obstacle = with_extra(box, inside, faces);
  // (its own normals point outward, into the liquid around it).
  CHECK(wall_mesh_problem(obstacle, in_3d(0.9)).empty());
  // Two coplanar triangles overlapping on the floor plane, not connected to it.
  const std::vector<Vector3d> flaps{{0.2, 0.2, 0.5}, {0.6, 0.2, 0.5}, {0.2, 0.6, 0.5},
                                    {0.3, 0.3, 0.5}, {0.7, 0.3, 0.5}, {0.3, 0.7, 0.5}};
  const auto doubled = with_extra(box, flaps, {{0, 1, 2}, {3, 4, 5}});
  // (open flaps above the fill level: no leak; they add no volume about their own plane)
  CHECK_THAT(wall_mesh_problem(doubled, in_3d(0.1)), StartsWith("the wall mesh intersects itself"));
}
