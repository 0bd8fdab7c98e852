#include "coupling/added_mass/added_mass.hpp"

#include <array>
#include <cmath>

namespace tankfsi::coupling {

std::vector<double> vertex_normals(const InterfaceMesh& mesh) {
  std::vector<double> normals(3 * mesh.vertex_count(), 0.0);
  const auto& x = mesh.coordinates;
  for (const auto& t : mesh.triangles) {
    const auto corner = [&](int k, int c) { return x[3 * static_cast<std::size_t>(t[static_cast<std::size_t>(k)]) + static_cast<std::size_t>(c)]; };
    std::array<double, 3> e1{}, e2{};
    for (int c = 0; c < 3; ++c) {
      e1[static_cast<std::size_t>(c)] = corner(1, c) - corner(0, c);
      e2[static_cast<std::size_t>(c)] = corner(2, c) - corner(0, c);
    }
    // The cross product is twice the area times the unit normal: area weighting.
    const std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                  e1[0] * e2[1] - e1[1] * e2[0]};
    for (const int v : t)
      for (std::size_t c = 0; c < 3; ++c) normals[3 * static_cast<std::size_t>(v) + c] += n[c];
  }
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double length = std::sqrt(normals[3 * v] * normals[3 * v] + normals[3 * v + 1] * normals[3 * v + 1] +
                                     normals[3 * v + 2] * normals[3 * v + 2]);
    if (length > 0.0)
      for (std::size_t c = 0; c < 3; ++c) normals[3 * v + c] /= length;
  }
  return normals;
}

void symmetrise(std::span<double> matrix, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i)
    for (std::size_t j = i + 1; j < size; ++j) {
      const double mean = 0.5 * (matrix[i * size + j] + matrix[j * size + i]);
      matrix[i * size + j] = mean;
      matrix[j * size + i] = mean;
    }
}

}  // namespace tankfsi::coupling
