#include "sph_solver/walls/primitive_meshes.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

namespace tankfsi::sph {

namespace {

using Triangles = std::vector<std::array<int, 3>>;

void orient(Triangles& triangles, NormalSide side) {
  if (side == NormalSide::inward)
    for (auto& t : triangles) std::swap(t[1], t[2]);
}

}  // namespace

TriangleMesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, NormalSide side, bool open_top) {
  std::vector<Eigen::Vector3d> vertices;
  for (int i = 0; i < 8; ++i)  // vertex i has x from bit 0, y from bit 1, z from bit 2
    vertices.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  // Outward faces, counter-clockwise seen from outside.
  Triangles triangles{{0, 2, 1}, {1, 2, 3},   // z = lo
                      {0, 1, 4}, {1, 5, 4},   // y = lo
                      {1, 3, 5}, {3, 7, 5},   // x = hi
                      {3, 2, 7}, {2, 6, 7},   // y = hi
                      {2, 0, 6}, {0, 4, 6}};  // x = lo
  if (!open_top) {
    triangles.push_back({4, 5, 6});  // z = hi
    triangles.push_back({5, 7, 6});
  }
  orient(triangles, side);
  return TriangleMesh(std::move(vertices), std::move(triangles));
}

TriangleMesh make_open_cylinder(double radius, double height, int segments, int layers, NormalSide side) {
  if (segments < 3 || layers < 1) throw std::invalid_argument("make_open_cylinder: segments >= 3, layers >= 1");
  std::vector<Eigen::Vector3d> vertices;
  for (int j = 0; j <= layers; ++j)
    for (int i = 0; i < segments; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / segments;
      vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), height * j / layers);
    }
  const auto id = [&](int i, int j) { return j * segments + (i % segments); };
  Triangles triangles;
  for (int j = 0; j < layers; ++j)
    for (int i = 0; i < segments; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        triangles.push_back({a, b, c});
        triangles.push_back({a, c, d});
      } else {
        triangles.push_back({a, b, d});
        triangles.push_back({b, c, d});
      }
    }
  orient(triangles, side);
  return TriangleMesh(std::move(vertices), std::move(triangles));
}

TriangleMesh make_icosphere(double radius, int subdivisions, NormalSide side) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> vertices{{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                        {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                        {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  Triangles triangles{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9},  {5, 11, 4},
                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6},  {3, 6, 8},
                      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& x : vertices) x = radius * x.normalized();
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, inserted] = midpoint.try_emplace(key, static_cast<int>(vertices.size()));
      if (inserted)
        vertices.push_back(radius * (vertices[static_cast<std::size_t>(a)] + vertices[static_cast<std::size_t>(b)])
                                        .normalized());
      return it->second;
    };
    Triangles finer;
    for (const auto& t : triangles) {
      const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    triangles = std::move(finer);
  }
  orient(triangles, side);
  return TriangleMesh(std::move(vertices), std::move(triangles));
}

TriangleMesh make_rectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                            int cells) {
  if (cells < 1) throw std::invalid_argument("make_rectangle: cells >= 1");
  std::vector<Eigen::Vector3d> vertices;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i)
      vertices.push_back(origin + (static_cast<double>(i) / cells) * u + (static_cast<double>(j) / cells) * v);
  Triangles triangles;
  const auto id = [&](int i, int j) { return j * (cells + 1) + i; };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return TriangleMesh(std::move(vertices), std::move(triangles));
}

}  // namespace tankfsi::sph
