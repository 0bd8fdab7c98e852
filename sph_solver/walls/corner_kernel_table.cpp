#include "sph_solver/walls/corner_kernel_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sph_solver/walls/wall_kernel_table.hpp"

namespace tankfsi::sph {
namespace {

/// The fields of CornerKernelValues in one order, for sums and interpolation.
template <class Values>
auto fields(Values& v) {
  return std::array{&v.q0, &v.q1a, &v.q1b, &v.q2, &v.saa, &v.sab, &v.sbb, &v.see, &v.m2a, &v.m2b};
}

void add_scaled(CornerKernelValues& sum, const CornerKernelValues& term, double weight) {
  const auto to = fields(sum);
  const auto from = fields(term);
  for (std::size_t k = 0; k < to.size(); ++k) *to[k] += weight * *from[k];
}

}  // namespace

CornerKernelTable::CornerKernelTable(const Kernel& kernel, double spacing, int intervals)
    : kernel_(kernel), spacing_(spacing), cutoff_(kernel.support_radius()), intervals_(intervals) {
  require_table_spacing(kernel, spacing);
  if (intervals < 1) throw std::invalid_argument("corner kernel table: at least one interval is needed");
  inverse_step_ = intervals / cutoff_;
  const auto nodes = static_cast<std::size_t>(intervals + 1);
  nodes_.reserve(nodes * nodes);
  for (int j = 0; j <= intervals; ++j)
    for (int i = 0; i <= intervals; ++i)
      nodes_.push_back(sum_lattice(kernel, spacing, cutoff_ * i / intervals, cutoff_ * j / intervals));
}

CornerKernelValues CornerKernelTable::at(double a, double b) const {
  if (std::isnan(a) || std::isnan(b)) {
    CornerKernelValues nan_values;
    for (double* f : fields(nan_values)) *f = std::numeric_limits<double>::quiet_NaN();
    return nan_values;
  }
  if (a >= cutoff_ || b >= cutoff_) return {};  // the overlap is out of reach of one plane
  const double u = std::max(a, 0.0) * inverse_step_;
  const double w = std::max(b, 0.0) * inverse_step_;
  const int i = std::min(static_cast<int>(u), intervals_ - 1);
  const int j = std::min(static_cast<int>(w), intervals_ - 1);
  const double tu = u - i;
  const double tw = w - j;
  const auto node = [this](int ii, int jj) -> const CornerKernelValues& {
    return nodes_[static_cast<std::size_t>(jj) * static_cast<std::size_t>(intervals_ + 1) + static_cast<std::size_t>(ii)];
  };
  CornerKernelValues v;
  add_scaled(v, node(i, j), (1.0 - tu) * (1.0 - tw));
  add_scaled(v, node(i + 1, j), tu * (1.0 - tw));
  add_scaled(v, node(i, j + 1), (1.0 - tu) * tw);
  add_scaled(v, node(i + 1, j + 1), tu * tw);
  return v;
}

OctantKernelValues CornerKernelTable::octant(double a, double b, double c) const {
  const double support_squared = cutoff_ * cutoff_;
  const double h = kernel_.smoothing_length();
  const double eta_squared = 0.01 * h * h;
  const std::array<double, 3> distance{std::max(a, 0.0), std::max(b, 0.0), std::max(c, 0.0)};
  OctantKernelValues sum;
  const double volume = spacing_ * spacing_ * spacing_;
  std::array<double, 3> x{};
  for (int la = 0;; ++la) {
    x[0] = distance[0] + (la + 0.5) * spacing_;
    if (x[0] * x[0] >= support_squared) break;
    for (int lb = 0;; ++lb) {
      x[1] = distance[1] + (lb + 0.5) * spacing_;
      if (x[0] * x[0] + x[1] * x[1] >= support_squared) break;
      for (int lc = 0;; ++lc) {
        x[2] = distance[2] + (lc + 0.5) * spacing_;
        const double r_squared = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
        if (r_squared >= support_squared) break;
        const double r = std::sqrt(r_squared);  // > 0: every x_X >= L0/2
        const double slope = kernel_.derivative(r);
        const double per_r = volume * slope / r;
        const double laplacian = volume * r * slope / (r_squared + eta_squared);
        sum.q0 += volume * kernel_.value(r);
        sum.q2 += laplacian;
        for (std::size_t u = 0; u < 3; ++u) {
          sum.q1[u] += per_r * x[u];
          sum.m2[u] += laplacian * x[u];
          for (std::size_t v = 0; v < 3; ++v) sum.s[u][v] += per_r * x[u] * x[v];
        }
      }
    }
  }
  return sum;
}

CornerKernelValues CornerKernelTable::direct_sum(const Kernel& kernel, double spacing, double a, double b) {
  require_table_spacing(kernel, spacing);
  if (!(a >= 0.0) || !(b >= 0.0)) throw std::invalid_argument("corner kernel table: distances must be >= 0");
  return sum_lattice(kernel, spacing, a, b);
}

// Layer pairs (s_A, s_B) from the edge outwards, and along the edge (3D) the sites
// within the support: about (R / L0)^3 / 4 of them at a = b = 0 in 3D.
CornerKernelValues CornerKernelTable::sum_lattice(const Kernel& kernel, double spacing, double a, double b) {
  const double support = kernel.support_radius();
  const double support_squared = support * support;
  const double h = kernel.smoothing_length();
  const double eta_squared = 0.01 * h * h;
  const bool planar = kernel.dimension() == 2;
  CornerKernelValues sum;
  for (int layer_a = 0;; ++layer_a) {
    const double x_a = a + (layer_a + 0.5) * spacing;
    if (x_a >= support) break;
    for (int layer_b = 0;; ++layer_b) {
      const double x_b = b + (layer_b + 0.5) * spacing;
      const double in_plane = x_a * x_a + x_b * x_b;
      if (in_plane >= support_squared) break;
      const int reach = planar ? 0 : static_cast<int>(std::sqrt(support_squared - in_plane) / spacing) + 1;
      for (int c = -reach; c <= reach; ++c) {
        const double x_e = c * spacing;
        const double r_squared = in_plane + x_e * x_e;
        if (r_squared >= support_squared) continue;
        const double r = std::sqrt(r_squared);  // > 0: x_a, x_b >= L0/2
        const double slope = kernel.derivative(r);
        const double per_r = slope / r;
        const double laplacian = r * slope / (r_squared + eta_squared);
        sum.q0 += kernel.value(r);
        sum.q1a += per_r * x_a;
        sum.q1b += per_r * x_b;
        sum.q2 += laplacian;
        sum.saa += per_r * x_a * x_a;
        sum.sab += per_r * x_a * x_b;
        sum.sbb += per_r * x_b * x_b;
        sum.see += per_r * x_e * x_e;
        sum.m2a += laplacian * x_a;
        sum.m2b += laplacian * x_b;
      }
    }
  }
  const double volume = std::pow(spacing, kernel.dimension());
  for (double* f : fields(sum)) *f *= volume;
  return sum;
}

}  // namespace tankfsi::sph
