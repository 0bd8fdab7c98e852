#include "sph_solver/walls/wall_kernel_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace tankfsi::sph {

void require_table_spacing(const Kernel& kernel, double spacing) {
  if (!std::isfinite(spacing) || spacing <= 0.0) {
    throw std::invalid_argument("wall kernel table: spacing must be positive and finite");
  }
  if (kernel.support_radius() > WallKernelTable::max_support_in_spacings * spacing) {
    throw std::invalid_argument("wall kernel table: the kernel support spans more than " +
                                std::to_string(static_cast<int>(WallKernelTable::max_support_in_spacings)) +
                                " lattice spacings");
  }
}

namespace {

/// L0^D sum_j term(a, r) over the lattice sites x_j = L0 (a, b, c) inside the
/// support (c = 0 in 2D), r = |x_j|, the particle itself (r = 0) included.
template <class Term>
double full_lattice_sum(const Kernel& kernel, double spacing, Term&& term) {
  const double support = kernel.support_radius();
  const int reach = static_cast<int>(support / spacing) + 1;
  const int reach_c = kernel.dimension() == 2 ? 0 : reach;
  double sum = 0.0;
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b)
      for (int c = -reach_c; c <= reach_c; ++c) {
        const double r = spacing * std::sqrt(static_cast<double>(a * a + b * b + c * c));
        if (r < support) sum += term(a, r);
      }
  return sum * std::pow(spacing, kernel.dimension());
}

/// L0^D sum_j W(|x_j|) over the full lattice.
double full_lattice_share(const Kernel& kernel, double spacing) {
  return full_lattice_sum(kernel, spacing, [&kernel](int, double r) { return kernel.value(r); });
}

/// The summands of Z0..Z3 (wall_kernel_table.hpp) of one virtual particle at
/// normal distance `height` and lateral distance squared `lateral_squared` from
/// the particle, r = sqrt(height^2 + lateral_squared) > 0: W, W' height / r,
/// r W' / (r^2 + eta^2), -W' lateral^2 / (r (D - 1)). The lattice sums and the
/// curvature moments take the same summands.
std::array<double, 4> table_summands(const Kernel& kernel, double height, double lateral_squared) {
  const double h = kernel.smoothing_length();
  const double r_squared = height * height + lateral_squared;
  const double r = std::sqrt(r_squared);
  const double slope = kernel.derivative(r);
  return {kernel.value(r), slope * height / r, r * slope / (r_squared + 0.01 * h * h),
          -slope * lateral_squared / r / (kernel.dimension() - 1)};
}

}  // namespace

double lattice_moment(const Kernel& kernel, double spacing) {
  require_table_spacing(kernel, spacing);
  // Sites on the plane a = 0 (the particle itself among them) add x_j^2 = 0.
  return full_lattice_sum(kernel, spacing, [&kernel, spacing](int a, double r) {
    return a == 0 ? 0.0 : -kernel.derivative(r) * (a * spacing) * (a * spacing) / r;
  });
}

WallKernelTable::WallKernelTable(const Kernel& kernel, double spacing, int intervals)
    : cutoff_(kernel.support_radius()), spacing_(spacing) {
  require_table_spacing(kernel, spacing);
  if (intervals < 1) throw std::invalid_argument("wall kernel table: at least one interval is needed");
  inverse_step_ = intervals / cutoff_;
  nodes_.reserve(static_cast<std::size_t>(intervals) + 1);
  // The last node, at the cutoff, sums to zero: every virtual particle is outside the support.
  for (int k = 0; k <= intervals; ++k) nodes_.push_back(sum_lattice(kernel, spacing, cutoff_ * k / intervals));
  // A particle at L0/2 above a wall completes, with Z0, the full lattice around it.
  lattice_share_ = full_lattice_share(kernel, spacing);
}

WallKernelValues WallKernelTable::at(double distance) const {
  if (std::isnan(distance)) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan};
  }
  if (distance >= cutoff_) return {};
  // Clamp a crossed particle to the wall surface; d < cutoff keeps position < intervals.
  const double position = std::max(distance, 0.0) * inverse_step_;
  const std::size_t index = std::min(static_cast<std::size_t>(position), nodes_.size() - 2);
  const double t = position - static_cast<double>(index);
  const Node& below = nodes_[index];
  const Node& above = nodes_[index + 1];
  Node node;
  for (std::size_t k = 0; k < 3; ++k) {
    node.z[k] = (1.0 - t) * below.z[k] + t * above.z[k];
    node.moment[k] = (1.0 - t) * below.moment[k] + t * above.moment[k];
  }
  node.tangential = (1.0 - t) * below.tangential + t * above.tangential;
  for (std::size_t k = 0; k < 4; ++k) node.curvature[k] = (1.0 - t) * below.curvature[k] + t * above.curvature[k];
  return values_of(node);
}

double WallKernelTable::distance_for_share(double share) const {
  if (std::isnan(share)) return std::numeric_limits<double>::quiet_NaN();
  if (share >= nodes_.front().z[0]) return 0.0;
  if (share <= 0.0) return cutoff_;
  // Z0 at the nodes is non-increasing: the first node at or below `share`, by bisection.
  const auto below = std::partition_point(nodes_.begin(), nodes_.end(),
                                          [share](const Node& node) { return node.z[0] > share; });
  const auto k = static_cast<std::size_t>(below - nodes_.begin());  // 1 <= k < size: Z0(0) > share > 0 = Z0(cutoff)
  const double upper = nodes_[k - 1].z[0];
  const double lower = nodes_[k].z[0];
  const double t = upper > lower ? (upper - share) / (upper - lower) : 0.0;
  return (static_cast<double>(k - 1) + t) / inverse_step_;
}

WallKernelValues WallKernelTable::direct_sum(const Kernel& kernel, double spacing, double distance) {
  require_table_spacing(kernel, spacing);
  if (!(distance >= 0.0)) throw std::invalid_argument("wall kernel table: distance must be >= 0 (and not NaN)");
  return values_of(sum_lattice(kernel, spacing, distance));
}

// Layer by layer from the surface down, visiting only the lattice sites inside the
// support: the layer at depth s lies at normal distance z = d + s from the particle,
// and its sites within reach form a disc (3D) or a segment (2D) of lateral radius
// sqrt(R^2 - z^2). At d = 0 that is about (2 pi / 3)(R / L0)^3 sites in 3D: 55 for
// the quartic spline at h = 1.2 L0 (R = 3 L0), and a table of 400 intervals builds in
// about 0.2 ms (its curvature moments, 2049 kernel evaluations a node, in about 9 ms).
WallKernelTable::Node WallKernelTable::sum_lattice(const Kernel& kernel, double spacing, double distance) {
  const double support = kernel.support_radius();
  const double support_squared = support * support;
  const bool planar = kernel.dimension() == 2;
  Node node;
  for (int layer = 0;; ++layer) {
    const double depth = (layer + 0.5) * spacing;
    const double height = distance + depth;  // x_ij . n
    if (height >= support) break;
    // One site more than the disc needs, against rounding; the radius test below decides.
    const int reach = static_cast<int>(std::sqrt(support_squared - height * height) / spacing) + 1;
    const int reach_b = planar ? 0 : reach;
    for (int a = -reach; a <= reach; ++a) {
      for (int b = -reach_b; b <= reach_b; ++b) {
        const double lateral_squared = spacing * spacing * (a * a + b * b);
        if (height * height + lateral_squared >= support_squared) continue;
        const std::array<double, 4> weight = table_summands(kernel, height, lateral_squared);  // r > 0: height >= L0/2
        for (std::size_t k = 0; k < 3; ++k) {
          node.z[k] += weight[k];
          node.moment[k] += weight[k] * depth;
        }
        node.tangential += weight[3];
      }
    }
  }
  const double volume = std::pow(spacing, kernel.dimension());
  for (std::size_t k = 0; k < 3; ++k) {
    node.z[k] *= volume;
    node.moment[k] *= volume;
  }
  node.tangential *= volume;
  node.curvature = curvature_moments(kernel, distance);
  return node;
}

// C_k = integral over the plane at distance d of g_k(r) |l|^2 / (D - 1), with
// r^2 = d^2 + |l|^2; the summands g_k as in sum_lattice (x_ij . n = d on the
// plane). In polar form (3D: dA = 2 pi l dl; 2D: both sides of the particle) a
// single integral over l in [0, sqrt(R^2 - d^2)], by Simpson's rule: 2048
// intervals agree with 2^17 to 1.3e-12 of C_k's size near the wall, over every
// kernel, 2D and 3D, h/L0 = 1.2 and 1.5, at 23 distances (measured).
// tests/unit/sph/test_wall_kernel_table.cpp compares C_k with the sliver itself.
std::array<double, 4> WallKernelTable::curvature_moments(const Kernel& kernel, double distance) {
  std::array<double, 4> c{};
  const double support = kernel.support_radius();
  if (distance >= support) return c;
  const bool planar = kernel.dimension() == 2;
  const double reach = std::sqrt(support * support - distance * distance);
  constexpr int intervals = 2048;
  const double step = reach / intervals;
  // i = 0 (l = 0) has measure 0, and on the plane through the particle r = 0 there.
  for (int i = 1; i <= intervals; ++i) {
    const double l = i * step;
    const double weight = (i == intervals ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0)) * step / 3.0;
    const double measure = planar ? 2.0 * l * l : std::numbers::pi * l * l * l;  // |l|^2 / (D - 1) dA
    const std::array<double, 4> g = table_summands(kernel, distance, l * l);
    for (std::size_t k = 0; k < 4; ++k) c[k] += weight * measure * g[k];
  }
  return c;
}

WallKernelValues WallKernelTable::values_of(const Node& node) {
  const auto depth = [&node](std::size_t k) { return node.z[k] != 0.0 ? node.moment[k] / node.z[k] : 0.0; };
  return {node.z[0],    node.z[1],          node.z[2],          depth(0),           depth(1), depth(2),
          node.tangential, node.curvature[0], node.curvature[1], node.curvature[2], node.curvature[3]};
}

}  // namespace tankfsi::sph
