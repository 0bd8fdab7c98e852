#include "fem_solver/elements/shape_functions.hpp"

#include <cmath>
#include <stdexcept>

namespace tankfsi::fem {

ShapeValues shape_values(int node_count, double r, double s) {
  ShapeValues v;
  if (node_count == 4) {
    constexpr std::array<double, 4> ri{-1.0, 1.0, 1.0, -1.0};
    constexpr std::array<double, 4> si{-1.0, -1.0, 1.0, 1.0};
    for (std::size_t i = 0; i < 4; ++i) {
      v.h[i] = 0.25 * (1.0 + ri[i] * r) * (1.0 + si[i] * s);
      v.dr[i] = 0.25 * ri[i] * (1.0 + si[i] * s);
      v.ds[i] = 0.25 * si[i] * (1.0 + ri[i] * r);
    }
    return v;
  }
  if (node_count == 3) {
    v.h = {1.0 - r - s, r, s, 0.0};
    v.dr = {-1.0, 1.0, 0.0, 0.0};
    v.ds = {-1.0, 0.0, 1.0, 0.0};
    return v;
  }
  throw std::invalid_argument("shell elements have 3 or 4 nodes, not " + std::to_string(node_count));
}

const std::vector<QuadraturePoint>& surface_quadrature(int node_count) {
  static const double g = 1.0 / std::sqrt(3.0);
  static const std::vector<QuadraturePoint> quad{{-g, -g, 1.0}, {g, -g, 1.0}, {g, g, 1.0}, {-g, g, 1.0}};
  static const std::vector<QuadraturePoint> triangle{
      {1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0}, {2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0}, {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0}};
  return node_count == 4 ? quad : triangle;
}

QuadraturePoint element_centre(int node_count) {
  return node_count == 4 ? QuadraturePoint{0.0, 0.0, 4.0} : QuadraturePoint{1.0 / 3.0, 1.0 / 3.0, 0.5};
}

}  // namespace tankfsi::fem
