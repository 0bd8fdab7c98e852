// Topology checks and derived data of TriangleMesh: open edges, flipped triangles,
// degenerate triangles, out-of-range indices, non-manifold edges; normals, areas,
// pseudo-normals and the update after moving vertices.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "sph_solver/walls/mesh_topology.hpp"
#include "sph_solver/walls/primitive_meshes.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"

using namespace tankfsi::sph;
using Catch::Matchers::Contains;
using Eigen::Vector3d;

TEST_CASE("closed meshes pass the topology checks", "[wall_geometry]") {
  for (const auto& mesh : {make_box(Vector3d::Zero(), Vector3d::Ones(), NormalSide::outward),
                           make_box(Vector3d::Zero(), Vector3d::Ones(), NormalSide::inward),
                           make_icosphere(1.0, 2)}) {
    const auto report = check_topology(mesh.vertices(), mesh.triangles());
    INFO(report.summary());
    CHECK(report.ok());
    CHECK(mesh.boundary_edges().empty());
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
      for (int k = 0; k < 3; ++k) CHECK(mesh.neighbour(static_cast<int>(t), k) >= 0);
  }
}

TEST_CASE("an open box reports its four rim edges", "[wall_geometry]") {
  const TriangleMesh tank = make_box(Vector3d::Zero(), Vector3d(2, 1, 1), NormalSide::inward, true);
  REQUIRE(tank.triangle_count() == 10);
  const auto& rim = tank.boundary_edges();
  REQUIRE(rim.size() == 4);
  for (const auto& edge : rim) {
    CHECK(tank.vertices()[static_cast<std::size_t>(edge.vertices[0])].z() == 1.0);
    CHECK(tank.vertices()[static_cast<std::size_t>(edge.vertices[1])].z() == 1.0);
    CHECK(tank.neighbour(edge.triangle, edge.edge) == -1);
    CHECK(tank.is_boundary_vertex(edge.vertices[0]));
  }
  const auto strict = check_topology(tank.vertices(), tank.triangles());
  CHECK(strict.count(TopologyIssueKind::open_edge) == 4);
  CHECK_THAT(strict.summary(), Contains("is open: used by triangle"));
  // Open walls are the caller's choice.
  CHECK(check_topology(tank.vertices(), tank.triangles(), {.report_open_edges = false}).ok());
}

TEST_CASE("a flipped triangle is reported as inconsistent orientation", "[wall_geometry]") {
  const TriangleMesh cube = make_box(Vector3d::Zero(), Vector3d::Ones(), NormalSide::outward);
  auto triangles = cube.triangles();
  std::swap(triangles[5][1], triangles[5][2]);
  const auto report = check_topology(cube.vertices(), triangles);
  CHECK(report.count(TopologyIssueKind::inconsistent_orientation) == 3);  // one per edge of triangle 5
  CHECK(report.count(TopologyIssueKind::open_edge) == 0);
  for (const auto& issue : report.issues) {
    CHECK_THAT(issue.message, Contains("inconsistent orientation"));
    CHECK((issue.message.find("triangles 5 and") != std::string::npos ||
           issue.message.find(" and 5 have") != std::string::npos));
  }
}

TEST_CASE("degenerate, out-of-range and non-manifold triangles are reported", "[wall_geometry]") {
  const std::vector<Vector3d> vertices{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 1}, {0, 0, -1}};
  SECTION("zero area (collinear) and a repeated index") {
    const auto report = check_topology(vertices, std::vector<std::array<int, 3>>{{0, 1, 3}, {0, 1, 1}, {0, 1, 2}},
                                       {.report_open_edges = false});
    REQUIRE(report.count(TopologyIssueKind::degenerate_triangle) == 2);
    CHECK_THAT(report.issues[0].message, Contains("triangle 0 (vertices 0, 1, 3) is degenerate: zero area"));
    CHECK_THAT(report.issues[1].message, Contains("triangle 1 (vertices 0, 1, 1) is degenerate: a vertex index is repeated"));
    // The mesh still builds, with a zero normal for the degenerate triangle.
    const TriangleMesh mesh(vertices, {{0, 1, 3}, {0, 1, 2}});
    CHECK(mesh.face_areas()[0] == 0.0);
    CHECK(mesh.face_normals()[0] == Vector3d::Zero());
  }
  SECTION("index out of range") {
    const auto report = check_topology(vertices, std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 6, 2}, {-1, 0, 1}},
                                       {.report_open_edges = false});
    CHECK(report.count(TopologyIssueKind::index_out_of_range) == 2);
    CHECK_THAT(report.summary(), Contains("triangle 1 (vertices 0, 6, 2): vertex index out of range (the mesh has 6 vertices)"));
    CHECK_THROWS_WITH(TriangleMesh(vertices, {{0, 6, 2}}), Contains("out of range"));
  }
  SECTION("an edge shared by three triangles") {
    const auto report = check_topology(vertices, std::vector<std::array<int, 3>>{{0, 1, 2}, {1, 0, 4}, {1, 0, 5}},
                                       {.report_open_edges = false});
    REQUIRE(report.count(TopologyIssueKind::non_manifold_edge) == 1);
    CHECK_THAT(report.summary(), Contains("edge (0, 1) is non-manifold: used by 3 triangles (0, 1, 2)"));
  }
}

TEST_CASE("normals, areas and pseudo-normals, and their update when the wall moves", "[wall_geometry]") {
  TriangleMesh cube = make_box(Vector3d::Zero(), Vector3d(2, 2, 2), NormalSide::outward);
  double area = 0.0;
  for (const double a : cube.face_areas()) area += a;
  CHECK(area == Approx(24.0).epsilon(1e-15));
  // Each corner of a cube sees three faces under 90°: the vertex normal is (±1,±1,±1)/√3.
  for (std::size_t v = 0; v < cube.vertex_count(); ++v) {
    const Vector3d expected = (cube.vertices()[v] - Vector3d::Ones()).normalized();
    CHECK((cube.vertex_normals()[v] - expected).norm() < 1e-15);
  }
  // Edge pseudo-normals: between two faces of the same side, the face normal; on a
  // cube edge, the bisector.
  for (std::size_t t = 0; t < cube.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int other = cube.neighbour(static_cast<int>(t), k);
      const Vector3d expected = (cube.face_normals()[t] + cube.face_normals()[static_cast<std::size_t>(other)]).normalized();
      CHECK((cube.edge_normal(static_cast<int>(t), k) - expected).norm() < 1e-15);
    }
  // Move: scale by 3 and rotate; normals rotate, areas scale by 9.
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Vector3d> moved;
  for (const auto& x : cube.vertices()) moved.push_back(3.0 * rotation * x);
  const auto normals_before = cube.face_normals();
  const auto areas_before = cube.face_areas();
  const auto version = cube.geometry_version();
  cube.move_vertices(moved);
  CHECK(cube.geometry_version() == version + 1);
  for (std::size_t t = 0; t < cube.triangle_count(); ++t) {
    CHECK((cube.face_normals()[t] - rotation * normals_before[t]).norm() < 1e-14);
    CHECK(cube.face_areas()[t] == Approx(9.0 * areas_before[t]).epsilon(1e-14));
  }
  CHECK_THROWS_AS(cube.move_vertices(std::vector<Vector3d>(3)), std::invalid_argument);
  moved[2].x() = std::nan("");
  CHECK_THROWS_WITH(cube.move_vertices(moved), Contains("vertex 2 has a non-finite coordinate"));
}
