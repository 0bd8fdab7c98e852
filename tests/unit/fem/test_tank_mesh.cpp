// The tank generator: a closed, consistently oriented surface with the
// regions and sets the cases use; and the wetted interface mesh.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "fem_solver/mesh/interface_mesh.hpp"
#include "fem_solver/mesh/shell_surfaces.hpp"
#include "fem_solver/mesh/tank_mesh.hpp"

using namespace tankfsi::fem;

namespace {

TankSpec small_tank() {
  TankSpec t;
  t.radius = 15.0;
  t.wall_height = 18.0;
  t.dome_radius = 30.0;
  t.element_size = 2.0;
  t.liquid_level = 14.8;
  return t;
}

/// Signed volume enclosed by the surface (divergence theorem over triangles
/// and split quads): positive when the normals point outward.
double enclosed_volume(const ShellMesh& mesh) {
  double volume = 0.0;
  for (const auto& e : mesh.elements) {
    const auto p = [&](int k) { return mesh.nodes[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(k)])]; };
    volume += p(0).dot(p(1).cross(p(2))) / 6.0;
    if (e.node_count() == 4) volume += p(0).dot(p(2).cross(p(3))) / 6.0;
  }
  return volume;
}

}  // namespace

TEST_CASE("tank mesh is watertight and consistently oriented outward", "[fem][mesh]") {
  const ShellMesh mesh = tank_mesh(small_tank());
  REQUIRE_NOTHROW(mesh.check());
  // Closed and consistently oriented: every directed edge occurs exactly
  // once and its reverse exactly once (a hole leaves an edge without its
  // reverse, a flipped element repeats a directed edge).
  std::map<std::pair<int, int>, int> directed;
  for (const auto& e : mesh.elements)
    for (int k = 0; k < e.node_count(); ++k)
      ++directed[{e.nodes[static_cast<std::size_t>(k)], e.nodes[static_cast<std::size_t>((k + 1) % e.node_count())]}];
  bool closed = true;
  for (const auto& [edge, count] : directed) {
    closed = closed && count == 1;
    const auto reverse = directed.find({edge.second, edge.first});
    closed = closed && reverse != directed.end() && reverse->second == 1;
  }
  CHECK(closed);
  // Outward: the enclosed volume is positive and near the true one (cylinder
  // plus spherical cap; the polygonal section loses ~(2 pi/n)^2/6 ~ 0.1 %).
  const TankSpec t = small_tank();
  const double rise = t.dome_radius - std::sqrt(t.dome_radius * t.dome_radius - t.radius * t.radius);
  const double exact = std::numbers::pi * t.radius * t.radius * t.wall_height +
                       std::numbers::pi * rise * rise * (3.0 * t.dome_radius - rise) / 3.0;
  CHECK(enclosed_volume(mesh) == Approx(exact).epsilon(0.01));
  // Quads on the wall and mostly on the roof; triangles on the bottom.
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const std::string& region = mesh.region_names[static_cast<std::size_t>(mesh.elements[e].region)];
    if (region == "wall") CHECK(mesh.elements[e].node_count() == 4);
    if (region == "bottom") CHECK(mesh.elements[e].node_count() == 3);
  }
  const auto roof = mesh.elements_of("roof");
  std::size_t roof_quads = 0;
  for (const int e : roof) roof_quads += mesh.elements[static_cast<std::size_t>(e)].node_count() == 4 ? 1 : 0;
  CHECK(roof_quads > roof.size() / 2);
  // Every element near the target size (0.4 to 1.6 of it: rings halve their count).
  for (const auto& e : mesh.elements)
    for (int k = 0; k < e.node_count(); ++k) {
      const double edge = (mesh.nodes[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(k)])] -
                           mesh.nodes[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>((k + 1) % e.node_count())])])
                              .norm();
      CHECK(edge > 0.4 * t.element_size);
      CHECK(edge < 1.6 * t.element_size);
    }
  // The base is the whole bottom plate at z = 0.
  for (const int n : mesh.node_sets.at("base")) CHECK(mesh.nodes[static_cast<std::size_t>(n)].z() == 0.0);
  CHECK(mesh.nodes_of("bottom") == mesh.node_sets.at("base"));
}

TEST_CASE("open-top tank: no roof, the wall's top ring a free edge, the wetted set as with a roof", "[fem][mesh]") {
  TankSpec t = small_tank();
  t.dome_radius = 0.0;
  const ShellMesh open = tank_mesh(t);
  REQUIRE_NOTHROW(open.check());
  CHECK_THROWS_AS(open.elements_of("roof"), std::out_of_range);
  // Every edge that has no reverse is on the top ring z = H.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& e : open.elements)
    for (int k = 0; k < e.node_count(); ++k)
      ++directed[{e.nodes[static_cast<std::size_t>(k)], e.nodes[static_cast<std::size_t>((k + 1) % e.node_count())]}];
  std::size_t free_edges = 0;
  for (const auto& [edge, count] : directed)
    if (directed.count({edge.second, edge.first}) == 0) {
      ++free_edges;
      CHECK(open.nodes[static_cast<std::size_t>(edge.first)].z() == Approx(t.wall_height));
      CHECK(open.nodes[static_cast<std::size_t>(edge.second)].z() == Approx(t.wall_height));
    }
  CHECK(free_edges == open.node_sets.at("wall_top").size());
  const ShellMesh roofed = tank_mesh(small_tank());
  CHECK(open.element_sets.at("wetted").size() == roofed.element_sets.at("wetted").size());
  t.dome_radius = 10.0;  // below the tank radius, and not 0
  CHECK_THROWS_AS(tank_mesh(t), std::invalid_argument);
}

TEST_CASE("wetted interface: triangles over the mesh's own nodes, facing the liquid", "[fem][mesh]") {
  const ShellMesh mesh = tank_mesh(small_tank());
  const InterfaceMesh interface = extract_interface(mesh, "wetted");
  std::size_t expected = 0;
  for (const int e : mesh.element_sets.at("wetted")) expected += mesh.elements[static_cast<std::size_t>(e)].node_count() - 2;
  CHECK(interface.triangles.size() == expected);
  for (std::size_t i = 0; i < interface.node_ids.size(); ++i)
    CHECK(interface.positions[i] == mesh.nodes[static_cast<std::size_t>(interface.node_ids[i])]);
  // Normals into the liquid: towards the axis on the wall, up on the bottom.
  for (const auto& tri : interface.triangles) {
    const auto& a = interface.positions[static_cast<std::size_t>(tri[0])];
    const auto& b = interface.positions[static_cast<std::size_t>(tri[1])];
    const auto& c = interface.positions[static_cast<std::size_t>(tri[2])];
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    const Eigen::Vector3d inward = centre.z() < 1e-9 ? Eigen::Vector3d(0, 0, 1) : Eigen::Vector3d(-centre.x(), -centre.y(), 0.0);
    CHECK(normal.dot(inward) > 0.0);
    CHECK(centre.z() < 14.8 + small_tank().element_size);
  }
}

TEST_CASE("cylinder and sphere patches: consistently oriented, normals away from the centre", "[fem][mesh]") {
  CylinderPatch c;
  c.phi_start = -30.0;
  c.phi_end = 330.0;  // a full circle: the seam is shared, not doubled
  c.divisions_phi = 12;
  SpherePatch s;
  s.theta_end = 150.0;
  s.phi_end = 120.0;
  for (const ShellMesh& mesh : {cylinder_patch(c), sphere_patch(s)}) {
    REQUIRE_NOTHROW(mesh.check());  // includes the orientation across every shared edge
    for (const auto& e : mesh.elements) {
      const auto p = [&](int k) { return mesh.nodes[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(k)])]; };
      const Eigen::Vector3d normal = (p(1) - p(0)).cross(p(2) - p(0));
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (int k = 0; k < e.node_count(); ++k) centre += p(k) / e.node_count();
      const Eigen::Vector3d outward = mesh.node_sets.count("z_start") != 0 ? Eigen::Vector3d(centre.x(), centre.y(), 0.0) : centre;
      CHECK(normal.dot(outward) > 0.0);
    }
  }
  // One element turned over is found, and named with its neighbour.
  ShellMesh flipped = cylinder_patch(c);
  std::swap(flipped.elements[5].nodes[1], flipped.elements[5].nodes[3]);
  try {
    flipped.check();
    FAIL("a flipped element passed the check");
  } catch (const MeshDefect& defect) {
    CHECK(defect.elements.size() == 2);
    CHECK((defect.elements[0] == 5 || defect.elements[1] == 5));
    CHECK(std::string(defect.what()).find("oriented oppositely") != std::string::npos);
  }
}

TEST_CASE("plate patch: the parallelogram, its edges, its normal and the wetted set", "[fem][mesh]") {
  PlatePatch p;
  p.corner = Eigen::Vector3d(0.0, 0.0, -0.1);
  p.side_u = Eigen::Vector3d(1.0, 0.0, 0.0);
  p.side_v = Eigen::Vector3d(0.0, 0.0, 0.2);
  p.divisions_u = 10;
  p.divisions_v = 2;
  p.wetted = true;
  const ShellMesh mesh = plate_patch(p);
  REQUIRE_NOTHROW(mesh.check());
  CHECK(mesh.nodes.size() == 33);
  CHECK(mesh.quad_count() == 20);
  CHECK(mesh.element_sets.at("wetted").size() == 20);
  CHECK(mesh.node_sets.at("u_start").size() == 3);
  CHECK(mesh.node_sets.at("v_end").size() == 11);
  for (const int n : mesh.node_sets.at("u_end")) CHECK(mesh.nodes[static_cast<std::size_t>(n)].x() == Approx(1.0));
  for (const int n : mesh.node_sets.at("v_start")) CHECK(mesh.nodes[static_cast<std::size_t>(n)].z() == Approx(-0.1));
  // x x z = -y: every element's own normal and the exact node normals agree.
  for (const auto& e : mesh.elements) {
    const auto x = [&](int k) { return mesh.nodes[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(k)])]; };
    CHECK((x(1) - x(0)).cross(x(2) - x(0)).normalized().isApprox(Eigen::Vector3d(0, -1, 0)));
  }
  for (const auto& n : mesh.node_normals) CHECK(n.isApprox(Eigen::Vector3d(0, -1, 0)));
  p.wetted = false;
  CHECK(plate_patch(p).element_sets.count("wetted") == 0);
  p.side_v = 2.0 * p.side_u;
  CHECK_THROWS_AS(plate_patch(p), std::invalid_argument);
}
