// The smooth wall behind the facets (wall_corner_values.hpp): corner normals of a
// faceted cylinder are its radial directions, a flat wall keeps its plane's normal
// bit for bit, and where the cylinder meets its bottom at a sharp edge each side
// keeps its own normal and curvature; a box of a few large triangles is flat.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <vector>

#include "sph_solver/walls/mean_curvature.hpp"
#include "sph_solver/walls/primitive_meshes.hpp"
#include "sph_solver/walls/tank_meshes.hpp"
#include "sph_solver/walls/wall_corner_values.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;

namespace {
constexpr double same_wall_cosine = 0.8;  // the contacts' rule (wall_contacts.cpp)
std::size_t at(int i) { return static_cast<std::size_t>(i); }
}  // namespace

TEST_CASE("corner values of a faceted tank: radial normals, each wall its own at the foot", "[wall_geometry]") {
  // R = 1, 32 facets around (each 11.25 degrees from the next), wall 1 m in 8 layers.
  const double radius = 1.0;
  const TriangleMesh tank = make_cylindrical_tank(radius, 1.0, 32, 8, 4);
  std::vector<double> h = vertex_mean_curvature(tank);
  // The vertices on the sharp edges (the foot ring and the open rim) are not
  // resolvable: marked as the wall model does.
  for (std::size_t v = 0; v < tank.vertex_count(); ++v) {
    const Vector3d& p = tank.vertices()[v];
    const bool on_ring = std::abs(std::hypot(p.x(), p.y()) - radius) < 1e-9;
    if (on_ring && (std::abs(p.z()) < 1e-9 || std::abs(p.z() - 1.0) < 1e-9)) h[v] = std::numeric_limits<double>::quiet_NaN();
  }
  // The wall's own curvature, from a vertex half way up (|H| = 1/(2R) for a cylinder).
  double wall_h = 0.0;
  for (std::size_t v = 0; v < tank.vertex_count(); ++v)
    if (std::abs(tank.vertices()[v].z() - 0.5) < 1e-9) wall_h = h[v];
  REQUIRE(std::abs(std::abs(wall_h) * 2.0 * radius - 1.0) < 0.02);

  WallCornerValues corners(tank);
  corners.update(tank, h, same_wall_cosine);
  const auto& triangles = tank.triangles();
  double worst_wall_angle = 0.0, worst_face_angle = 0.0;
  int foot_corners = 0;
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    const Vector3d& face = tank.face_normals()[at(t)];
    const bool bottom = face.z() > 0.99;
    for (int k = 0; k < 3; ++k) {
      const Vector3d& p = tank.corner(t, k);
      const Vector3d& n = corners.normals(t)[at(k)];
      const double c = corners.curvature_at(t, Vector3d::Unit(k));
      CHECK(std::isfinite(c));
      if (bottom) {
        CHECK(n == face);  // the flat bottom stays exactly flat, also at the foot
        if (std::hypot(p.x(), p.y()) > radius - 1e-9) CHECK(c == 0.0);
        continue;
      }
      // Wall: the corner normal is the inward radial direction at the vertex.
      const Vector3d inward = Vector3d(-p.x(), -p.y(), 0.0).normalized();
      worst_wall_angle = std::max(worst_wall_angle, std::atan2(n.cross(inward).norm(), n.dot(inward)));
      worst_face_angle = std::max(worst_face_angle, std::atan2(face.cross(inward).norm(), face.dot(inward)));
      if (std::abs(p.z()) < 1e-9) {
        ++foot_corners;
        CHECK(std::abs(c / wall_h - 1.0) < 0.05);  // the wall's curvature down to its foot
      }
    }
  }
  INFO("facet normals up to " << worst_face_angle << " rad from radial, corner normals " << worst_wall_angle);
  CHECK(worst_face_angle > 0.09);       // half a facet's angle, 0.098 rad
  CHECK(worst_wall_angle < 1e-9);       // the symmetric ring of facets: radial to round-off
  CHECK(foot_corners >= 32);
}

TEST_CASE("corner values of a flat wall are its plane's, bit for bit", "[wall_geometry]") {
  const TriangleMesh plane = make_rectangle(Vector3d(0.1, -0.3, 0.2), Vector3d(0.7, 0.2, 0.1), Vector3d(-0.1, 0.4, 0.3), 6);
  const std::vector<double> h = vertex_mean_curvature(plane);
  WallCornerValues corners(plane);
  corners.update(plane, h, same_wall_cosine);
  for (int t = 0; t < static_cast<int>(plane.triangles().size()); ++t)
    for (int k = 0; k < 3; ++k) CHECK(corners.normals(t)[at(k)] == plane.face_normals()[at(t)]);
}

TEST_CASE("a box of two triangles per face has flat walls: no curvature from its edges", "[wall_geometry]") {
  // Every vertex of the 12-triangle box is a corner of three walls. Meyer's mean
  // curvature there is finite and small for triangles this large (-1.36 1/m: the
  // 90-degree edges spread over 1 m facets), so it passed for a curvature the kernel
  // resolves and scaled every wall table by 7 %. It is no wall's curvature.
  const TriangleMesh box = make_box(Vector3d(0.0, 0.0, 0.0), Vector3d(1.0, 1.0, 0.6), NormalSide::inward);
  const std::vector<double> h = vertex_mean_curvature(box);
  CHECK(std::abs(h[0]) > 1.0);  // what the corner gives; the walls must not take it
  WallCornerValues corners(box);
  corners.update(box, h, same_wall_cosine);
  for (int t = 0; t < static_cast<int>(box.triangles().size()); ++t)
    for (int k = 0; k < 3; ++k) {
      Vector3d w = Vector3d::Zero();
      w[k] = 1.0;
      CHECK(corners.curvature_at(t, w) == 0.0);
      CHECK(corners.normals(t)[at(k)] == box.face_normals()[at(t)]);
    }
}
