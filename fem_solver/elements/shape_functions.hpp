#pragma once
// Shape functions and in-plane quadrature of the two shell elements.
//   quadrilateral: bilinear, nodes at (r, s) = (-1,-1) (1,-1) (1,1) (-1,1);
//   triangle: linear, nodes at (0,0) (1,0) (0,1).
#include <array>
#include <vector>

namespace tankfsi::fem {

/// Values and natural derivatives of the (3 or 4) shape functions at one point.
struct ShapeValues {
  std::array<double, 4> h{};
  std::array<double, 4> dr{};
  std::array<double, 4> ds{};
};

struct QuadraturePoint {
  double r = 0.0;
  double s = 0.0;
  double weight = 0.0;
};

[[nodiscard]] ShapeValues shape_values(int node_count, double r, double s);
/// 2x2 Gauss on the square (exact for the bilinear element's stiffness terms in
/// (r, s) on a parallelogram); 3-point (edge mid-sides' interior rule, degree 2)
/// on the triangle.
[[nodiscard]] const std::vector<QuadraturePoint>& surface_quadrature(int node_count);
/// The element's centre in natural coordinates.
[[nodiscard]] QuadraturePoint element_centre(int node_count);

}  // namespace tankfsi::fem
