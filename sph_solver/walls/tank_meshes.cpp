#include "sph_solver/walls/tank_meshes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tankfsi::sph {

namespace {

using Triangles = std::vector<std::array<int, 3>>;
/// Vertex indices of a ring, counter-clockwise seen from +z, the first at the angle 0.
using Ring = std::vector<int>;

void require_positive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument(std::string(what) + " must be positive and finite, got " + std::to_string(value));
}

// Pieces of at most target_edge along a length. The relative slack keeps a length that
// is a multiple of the target (2.00 m / 0.01 m) from gaining a piece by round-off.
int pieces(double length, double target_edge) {
  return std::max(1, static_cast<int>(std::ceil(length / target_edge * (1.0 - 1e-12))));
}

Ring add_ring(std::vector<Eigen::Vector3d>& vertices, double radius, double z, int count) {
  Ring ring;
  for (int i = 0; i < count; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / count;
    ring.push_back(static_cast<int>(vertices.size()));
    vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
  }
  return ring;
}

// Vertex count of an inner ring whose radius is `fraction` of the wall's: proportional,
// so the triangles keep their size towards the centre.
int ring_count(int segments, double fraction) {
  return std::max(3, static_cast<int>(std::lround(segments * fraction)));
}

// Triangles between an inner ring (or a single centre vertex) and an outer ring, with
// the normal +z (upward) or -z. Both rings start at the angle 0; the ring whose next
// vertex comes first in angle advances, which covers the annulus between the two
// polygons without overlap for any pair of counts (n_inner + n_outer triangles).
void stitch(const Ring& inner, const Ring& outer, bool upward, Triangles& triangles) {
  const auto add = [&](int a, int b, int c) {
    if (upward)
      triangles.push_back({a, b, c});
    else
      triangles.push_back({a, c, b});
  };
  const std::size_t n_in = inner.size();
  const std::size_t n_out = outer.size();
  std::size_t i = 0;
  std::size_t j = 0;
  while (j < n_out || (n_in > 1 && i < n_in)) {
    // Outer next at angle (j+1)/n_out, inner next at (i+1)/n_in (turns); a centre
    // vertex never advances.
    const bool advance_outer = j < n_out && (n_in == 1 || i == n_in || (j + 1) * n_in <= (i + 1) * n_out);
    if (advance_outer) {
      add(outer[j], outer[(j + 1) % n_out], inner[i % n_in]);
      ++j;
    } else {
      add(outer[j % n_out], inner[(i + 1) % n_in], inner[i]);
      ++i;
    }
  }
}

// Quads between two rings of equal count, normals towards the axis; alternating
// diagonals as in make_open_cylinder.
void stitch_wall(const Ring& lower, const Ring& upper, int row, Triangles& triangles) {
  const std::size_t n = lower.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int a = lower[i], b = lower[(i + 1) % n], c = upper[(i + 1) % n], d = upper[i];
    if ((static_cast<int>(i) + row) % 2 == 0) {
      triangles.push_back({a, c, b});
      triangles.push_back({a, d, c});
    } else {
      triangles.push_back({a, d, b});
      triangles.push_back({b, d, c});
    }
  }
}

}  // namespace

TriangleMesh extrude_polyline(std::span<const Eigen::Vector2d> points, double depth, double target_edge) {
  if (points.size() < 2) throw std::invalid_argument("extrude_polyline: needs at least two points");
  require_positive(depth, "extrude_polyline: depth");
  require_positive(target_edge, "extrude_polyline: target_edge");
  std::vector<Eigen::Vector2d> path{points[0]};
  for (std::size_t s = 0; s + 1 < points.size(); ++s) {
    const Eigen::Vector2d& a = points[s];
    const Eigen::Vector2d& b = points[s + 1];
    const double length = (b - a).norm();
    if (!(length > 0.0))
      throw std::invalid_argument("extrude_polyline: segment " + std::to_string(s) + " has zero length");
    const int n = pieces(length, target_edge);
    for (int k = 1; k < n; ++k) path.emplace_back(a + (static_cast<double>(k) / n) * (b - a));
    path.push_back(b);
  }
  std::vector<Eigen::Vector3d> vertices;
  for (const auto& q : path) {  // vertex 2k at z = -depth/2, 2k + 1 at +depth/2
    vertices.emplace_back(q.x(), q.y(), -0.5 * depth);
    vertices.emplace_back(q.x(), q.y(), 0.5 * depth);
  }
  // Quad k: A0 A1 (point k), B0 B1 (point k + 1); the normal (−e_y, e_x) is the travel
  // direction e turned by +90°, the fluid side.
  Triangles triangles;
  for (int k = 0; k + 1 < static_cast<int>(path.size()); ++k) {
    const int a0 = 2 * k, a1 = 2 * k + 1, b0 = 2 * k + 2, b1 = 2 * k + 3;
    if (k % 2 == 0) {
      triangles.push_back({a0, b1, b0});
      triangles.push_back({a0, a1, b1});
    } else {
      triangles.push_back({a0, a1, b0});
      triangles.push_back({b0, a1, b1});
    }
  }
  return TriangleMesh(std::move(vertices), std::move(triangles));
}

TriangleMesh make_rectangular_tank_2d(double width, double height, double depth, double target_edge) {
  require_positive(width, "make_rectangular_tank_2d: width");
  require_positive(height, "make_rectangular_tank_2d: height");
  // Down the left wall, along the floor, up the right wall: the interior on the left.
  const std::array<Eigen::Vector2d, 4> points{Eigen::Vector2d(0.0, height), Eigen::Vector2d(0.0, 0.0),
                                              Eigen::Vector2d(width, 0.0), Eigen::Vector2d(width, height)};
  return extrude_polyline(points, depth, target_edge);
}

TriangleMesh make_overflow_tank_2d(const OverflowTank2d& tank) {
  require_positive(tank.inner_width, "make_overflow_tank_2d: inner_width");
  require_positive(tank.inner_wall_height, "make_overflow_tank_2d: inner_wall_height");
  require_positive(tank.plate_thickness, "make_overflow_tank_2d: plate_thickness");
  require_positive(tank.margin, "make_overflow_tank_2d: margin");
  require_positive(tank.outer_wall_height, "make_overflow_tank_2d: outer_wall_height");
  const double w = tank.inner_width, hi = tank.inner_wall_height, t = tank.plate_thickness;
  const double left = -t - tank.margin, right = w + t + tank.margin, ho = tank.outer_wall_height;
  // The wetted outline from the catch tank's left rim to its right rim, over both plates.
  const std::array<Eigen::Vector2d, 12> points{
      Eigen::Vector2d(left, ho), Eigen::Vector2d(left, 0.0),                    // catch tank, left wall
      Eigen::Vector2d(-t, 0.0),  Eigen::Vector2d(-t, hi),  Eigen::Vector2d(0.0, hi),  // left plate
      Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(w, 0.0),                       // inner floor
      Eigen::Vector2d(w, hi),    Eigen::Vector2d(w + t, hi), Eigen::Vector2d(w + t, 0.0),  // right plate
      Eigen::Vector2d(right, 0.0), Eigen::Vector2d(right, ho)};                 // catch tank, right wall
  return extrude_polyline(points, tank.depth, tank.target_edge);
}

TriangleMesh make_cylindrical_tank(double radius, double wall_height, int segments, int layers, int bottom_rings,
                                   const std::optional<DomeRoof>& roof) {
  require_positive(radius, "make_cylindrical_tank: radius");
  require_positive(wall_height, "make_cylindrical_tank: wall_height");
  if (segments < 3 || layers < 1 || bottom_rings < 1)
    throw std::invalid_argument("make_cylindrical_tank: segments >= 3, layers >= 1, bottom_rings >= 1");
  if (roof && (roof->rings < 1 || !(roof->radius >= radius) || !std::isfinite(roof->radius)))
    throw std::invalid_argument("make_cylindrical_tank: the dome needs rings >= 1 and a radius >= the tank radius");

  std::vector<Eigen::Vector3d> vertices;
  Triangles triangles;
  std::vector<Ring> wall;
  for (int j = 0; j <= layers; ++j) wall.push_back(add_ring(vertices, radius, wall_height * j / layers, segments));
  for (int j = 0; j < layers; ++j)
    stitch_wall(wall[static_cast<std::size_t>(j)], wall[static_cast<std::size_t>(j + 1)], j, triangles);

  // Bottom: from the wall's bottom ring inwards to the centre, normals up.
  Ring outer = wall.front();
  for (int k = bottom_rings - 1; k >= 0; --k) {
    const double fraction = static_cast<double>(k) / bottom_rings;
    const Ring inner = k == 0 ? add_ring(vertices, 0.0, 0.0, 1)
                              : add_ring(vertices, radius * fraction, 0.0, ring_count(segments, fraction));
    stitch(inner, outer, true, triangles);
    outer = inner;
  }

  if (roof) {
    // Sphere centred on the axis at z = wall_height - R_d cos θ0, sin θ0 = radius / R_d;
    // ring k at the polar angle θ0 (rings - k) / rings, the apex at k = rings.
    const double theta0 = std::asin(std::min(1.0, radius / roof->radius));
    const double centre = wall_height - roof->radius * std::cos(theta0);
    outer = wall.back();
    for (int k = 1; k <= roof->rings; ++k) {
      const double theta = theta0 * (roof->rings - k) / roof->rings;
      const double ring_radius = roof->radius * std::sin(theta);
      const double z = centre + roof->radius * std::cos(theta);
      const Ring inner = k == roof->rings ? add_ring(vertices, 0.0, z, 1)
                                          : add_ring(vertices, ring_radius, z,
                                                     ring_count(segments, ring_radius / radius));
      stitch(inner, outer, false, triangles);
      outer = inner;
    }
  }
  return TriangleMesh(std::move(vertices), std::move(triangles));
}

}  // namespace tankfsi::sph
