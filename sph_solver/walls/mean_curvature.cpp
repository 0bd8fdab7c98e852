#include "sph_solver/walls/mean_curvature.hpp"

#include <array>
#include <stdexcept>

namespace tankfsi::sph {

void compute_vertex_mean_curvature(const TriangleMesh& mesh, std::vector<double>& curvature) {
  const std::size_t nv = mesh.vertex_count();
  std::vector<Eigen::Vector3d> laplacian(nv, Eigen::Vector3d::Zero());  // Σ (cot α + cot β)(x_i − x_j)
  std::vector<double> mixed_area(nv, 0.0);

  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (!(mesh.face_areas()[t] > 0.0)) continue;
    const auto& tri = mesh.triangles()[t];
    const std::array<Eigen::Vector3d, 3> x{mesh.corner(static_cast<int>(t), 0), mesh.corner(static_cast<int>(t), 1),
                                           mesh.corner(static_cast<int>(t), 2)};
    const double twice_area = 2.0 * mesh.face_areas()[t];
    std::array<double, 3> cot{};
    std::array<double, 3> dot{};  // e1·e2 at each corner: negative means obtuse
    for (std::size_t k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = x[(k + 1) % 3] - x[k];
      const Eigen::Vector3d e2 = x[(k + 2) % 3] - x[k];
      dot[k] = e1.dot(e2);
      cot[k] = dot[k] / twice_area;  // cos/sin: e1·e2 / |e1 × e2|
    }
    const bool obtuse = dot[0] < 0.0 || dot[1] < 0.0 || dot[2] < 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      // Edge (i, j) opposite corner k.
      const std::size_t i = (k + 1) % 3;
      const std::size_t j = (k + 2) % 3;
      const Eigen::Vector3d xij = x[i] - x[j];
      laplacian[static_cast<std::size_t>(tri[i])] += cot[k] * xij;
      laplacian[static_cast<std::size_t>(tri[j])] -= cot[k] * xij;
      if (!obtuse) {
        // Voronoi area (Meyer eq. 7): 1/8 Σ (cot α + cot β)|x_i − x_j|², split per triangle.
        const double share = cot[k] * xij.squaredNorm() / 8.0;
        mixed_area[static_cast<std::size_t>(tri[i])] += share;
        mixed_area[static_cast<std::size_t>(tri[j])] += share;
      } else {
        // Obtuse triangle: its circumcentre lies outside, use area/2 at the obtuse corner,
        // area/4 at the others (Meyer Fig. 4).
        const double area = mesh.face_areas()[t];
        mixed_area[static_cast<std::size_t>(tri[k])] += dot[k] < 0.0 ? 0.5 * area : 0.25 * area;
      }
    }
  }

  curvature.assign(nv, 0.0);
  for (std::size_t v = 0; v < nv; ++v) {
    if (mesh.is_boundary_vertex(static_cast<int>(v)) || !(mixed_area[v] > 0.0)) continue;
    const Eigen::Vector3d k_normal = laplacian[v] / (2.0 * mixed_area[v]);
    curvature[v] = 0.5 * k_normal.dot(mesh.vertex_normals()[v]);
  }

  // Boundary vertices: mean over interior neighbours (see header).
  std::vector<double> sum(nv, 0.0);
  std::vector<int> count(nv, 0);
  for (const auto& tri : mesh.triangles())
    for (std::size_t k = 0; k < 3; ++k) {
      const int a = tri[k];
      const int b = tri[(k + 1) % 3];
      // An edge with an interior end is used by exactly two triangles (else that end
      // would be a boundary vertex), so every interior neighbour is counted twice: a
      // plain average.
      if (mesh.is_boundary_vertex(a) && !mesh.is_boundary_vertex(b)) {
        sum[static_cast<std::size_t>(a)] += curvature[static_cast<std::size_t>(b)];
        ++count[static_cast<std::size_t>(a)];
      }
      if (mesh.is_boundary_vertex(b) && !mesh.is_boundary_vertex(a)) {
        sum[static_cast<std::size_t>(b)] += curvature[static_cast<std::size_t>(a)];
        ++count[static_cast<std::size_t>(b)];
      }
    }
  for (std::size_t v = 0; v < nv; ++v)
    if (mesh.is_boundary_vertex(static_cast<int>(v)) && count[v] > 0) curvature[v] = sum[v] / static_cast<double>(count[v]);
}

std::vector<double> vertex_mean_curvature(const TriangleMesh& mesh) {
  std::vector<double> curvature;
  compute_vertex_mean_curvature(mesh, curvature);
  return curvature;
}

}  // namespace tankfsi::sph
