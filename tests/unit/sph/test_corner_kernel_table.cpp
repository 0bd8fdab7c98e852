// Corner kernel tables (corner_kernel_table.hpp) against lattices the test builds
// itself: the fluid filling the quarter-space in front of two orthogonal walls, the
// two walls' half-space tables, and the overlap behind both. Planes A: y = 0
// (n_A = e_y) and B: x = 0 (n_B = e_x); in 3D the edge is the z axis.
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <array>
#include <utility>
#include <cmath>
#include <vector>

#include "kernel_settings.hpp"
#include "sph_solver/kernels/kernel.hpp"
#include "sph_solver/walls/corner_kernel_table.hpp"
#include "sph_solver/walls/wall_kernel_table.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;

namespace {

constexpr double spacing = 0.013;  // odd on purpose, as in the wall table tests

using Setting = tankfsi::test::KernelSetting;
const auto settings = tankfsi::test::kernel_settings;

/// Lattice sites x_j = x_i + L0 k around x_i within the support, with their x_ij.
std::vector<Vector3d> neighbour_offsets(const Kernel& kernel) {
  const int reach = static_cast<int>(std::ceil(kernel.support_radius() / spacing));
  const int z_reach = kernel.dimension() == 3 ? reach : 0;
  std::vector<Vector3d> result;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j)
      for (int k = -z_reach; k <= z_reach; ++k) {
        const Vector3d x_ij = -spacing * Vector3d(i, j, k);
        if (x_ij.norm() < kernel.support_radius()) result.push_back(x_ij);
      }
  return result;
}

double volume(const Kernel& kernel) { return std::pow(spacing, kernel.dimension()); }
double laplacian_weight(const Kernel& kernel, const Vector3d& x_ij) {
  const double h = kernel.smoothing_length();
  return x_ij.dot(kernel.gradient(x_ij)) / (x_ij.squaredNorm() + 0.01 * h * h);
}

}  // namespace

TEST_CASE("corner table: fluid + two walls - overlap = the full lattice", "[corner_table]") {
  // A fluid particle of the quarter-space lattice x, y > 0 at (a, b) = ((i + 1/2) L0,
  // (j + 1/2) L0): its fluid neighbours, the two walls' tables and the overlap must
  // count every site of the full lattice once: the density share, the gradient
  // (zero on the full lattice) and the Laplacian weight. direct_sum: round-off
  // (1e-12 of the scale); the table adds its interpolation error (1e-4 by design).
  for (const Setting& s : settings()) {
    const Kernel kernel(s.type, s.dimension, s.h_over_dx * spacing);
    const WallKernelTable walls(kernel, spacing);
    const CornerKernelTable corner(kernel, spacing);
    INFO(kernel_name(s.type) << " " << s.dimension << "D h/L0 = " << s.h_over_dx);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const double a = (j + 0.5) * spacing;  // distance to A (y = 0)
        const double b = (i + 0.5) * spacing;  // distance to B (x = 0)
        const Vector3d x_i(b, a, 0.0);
        double density = 0.0, laplacian = 0.0, full_density = 0.0, full_laplacian = 0.0, gradient_scale = 0.0;
        Vector3d gradient = Vector3d::Zero();
        for (const Vector3d& x_ij : neighbour_offsets(kernel)) {
          const Vector3d x_j = x_i - x_ij;
          full_density += volume(kernel) * kernel.value(x_ij.norm());
          full_laplacian += volume(kernel) * laplacian_weight(kernel, x_ij);
          gradient_scale += volume(kernel) * kernel.gradient(x_ij).norm();  // sum |V grad W|: the gradient's scale
          if (x_j.x() < 0.0 || x_j.y() < 0.0) continue;
          density += volume(kernel) * kernel.value(x_ij.norm());
          laplacian += volume(kernel) * laplacian_weight(kernel, x_ij);
          gradient += volume(kernel) * kernel.gradient(x_ij);
        }
        const WallKernelValues wall_a = WallKernelTable::direct_sum(kernel, spacing, a);
        const WallKernelValues wall_b = WallKernelTable::direct_sum(kernel, spacing, b);
        const std::array<std::pair<CornerKernelValues, double>, 2> variants{
            std::pair{CornerKernelTable::direct_sum(kernel, spacing, a, b), 1e-12}, std::pair{corner.at(a, b), 1e-4}};
        for (const auto& [q, tolerance] : variants) {
          const Vector3d completed = gradient + wall_a.z1 * Vector3d::UnitY() + wall_b.z1 * Vector3d::UnitX() -
                                     (q.q1a * Vector3d::UnitY() + q.q1b * Vector3d::UnitX());
          INFO("a = " << a / spacing << " L0, b = " << b / spacing << " L0, tolerance " << tolerance);
          CHECK(std::abs(density + wall_a.z0 + wall_b.z0 - q.q0 - full_density) < tolerance * full_density);
          CHECK(std::abs(laplacian + wall_a.z2 + wall_b.z2 - q.q2 - full_laplacian) < tolerance * std::abs(full_laplacian));
          CHECK(completed.norm() <= tolerance * gradient_scale);
        }
      }
  }
}

TEST_CASE("octant: fluid + three walls - three overlaps + octant = the full lattice", "[corner_table]") {
  // A particle of the octant lattice x, y, z > 0 near the corner of three walls
  // (x = 0, y = 0, z = 0; a box's corner): its fluid neighbours, the three walls'
  // half-space sums, the three pairs' overlaps taken out and the octant put back
  // must count every site of the full lattice once: density, gradient (zero on the
  // full lattice), Laplacian weight and the trace of the moment tensor (div r).
  // Direct sums throughout: round-off (1e-12 of the scale).
  for (const Setting& s : settings()) {
    if (s.dimension != 3) continue;
    const Kernel kernel(s.type, s.dimension, s.h_over_dx * spacing);
    const CornerKernelTable corner(kernel, spacing);
    INFO(kernel_name(s.type) << " 3D h/L0 = " << s.h_over_dx);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 4; ++k) {
          const Vector3d x_i((i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing);
          double density = 0.0, laplacian = 0.0, trace = 0.0, full_density = 0.0, full_laplacian = 0.0,
                 full_trace = 0.0, gradient_scale = 0.0;
          Vector3d gradient = Vector3d::Zero();
          for (const Vector3d& x_ij : neighbour_offsets(kernel)) {
            const Vector3d x_j = x_i - x_ij;
            full_density += volume(kernel) * kernel.value(x_ij.norm());
            full_laplacian += volume(kernel) * laplacian_weight(kernel, x_ij);
            gradient_scale += volume(kernel) * kernel.gradient(x_ij).norm();
            full_trace -= volume(kernel) * x_ij.dot(kernel.gradient(x_ij));
            if (x_j.x() < 0.0 || x_j.y() < 0.0 || x_j.z() < 0.0) continue;
            density += volume(kernel) * kernel.value(x_ij.norm());
            laplacian += volume(kernel) * laplacian_weight(kernel, x_ij);
            gradient += volume(kernel) * kernel.gradient(x_ij);
            trace -= volume(kernel) * x_ij.dot(kernel.gradient(x_ij));
          }
          // The walls: normals e_x, e_y, e_z at distances x_i's coordinates.
          const std::array<Vector3d, 3> normals{Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
          for (int w = 0; w < 3; ++w) {
            const WallKernelValues half = WallKernelTable::direct_sum(kernel, spacing, x_i[w]);
            density += half.z0;
            laplacian += half.z2;
            gradient += half.z1 * normals[static_cast<std::size_t>(w)];
            trace += -half.z1 * (x_i[w] + half.depth1) + 2.0 * half.z3;
            for (int v = w + 1; v < 3; ++v) {
              // The pair (w, v): plane A = w, plane B = v.
              const CornerKernelValues q = CornerKernelTable::direct_sum(kernel, spacing, x_i[w], x_i[v]);
              density -= q.q0;
              laplacian -= q.q2;
              gradient -= q.q1a * normals[static_cast<std::size_t>(w)] + q.q1b * normals[static_cast<std::size_t>(v)];
              trace -= -(q.saa + q.sbb + q.see);
            }
          }
          const OctantKernelValues o = corner.octant(x_i.x(), x_i.y(), x_i.z());
          density += o.q0;
          laplacian += o.q2;
          gradient += o.q1[0] * normals[0] + o.q1[1] * normals[1] + o.q1[2] * normals[2];
          trace += -(o.s[0][0] + o.s[1][1] + o.s[2][2]);
          INFO("x_i = (" << x_i.x() / spacing << ", " << x_i.y() / spacing << ", " << x_i.z() / spacing << ") L0");
          CHECK(std::abs(density - full_density) < 1e-12 * full_density);
          CHECK(std::abs(laplacian - full_laplacian) < 1e-12 * std::abs(full_laplacian));
          CHECK(gradient.norm() <= 1e-12 * gradient_scale);
          CHECK(std::abs(trace - full_trace) < 1e-12 * full_trace);
        }
    // The octant is not nothing where it matters: at the corner particle its
    // density share is about 1 % of the full sum.
    const double first = (0.5 * spacing);
    CHECK(corner.octant(first, first, first).q0 > 0.005);
    CHECK(corner.octant(corner.cutoff(), 0.0, 0.0).q0 == 0.0);
  }
}

TEST_CASE("corner table: linear pressures in the overlap", "[corner_table]") {
  // The identities of the header against the overlap's sites summed here: for
  // P_k = P_i + G . (x_k - x_i), sum V (P_i + P_k) grad W = 2 P_i Q1 - S G and
  // sum 2 V (x . grad W)/(r^2 + eta^2) (P_i - P_k) = 2 (M2A G_A + M2B G_B).
  const Vector3d G(-310.0, 9810.0, 120.0);  // Pa/m; x: along n_B, y: along n_A, z: the edge
  const double p_i = 2500.0;
  for (const Setting& s : settings()) {
    const Kernel kernel(s.type, s.dimension, s.h_over_dx * spacing);
    INFO(kernel_name(s.type) << " " << s.dimension << "D h/L0 = " << s.h_over_dx);
    for (const auto& [a, b] : {std::array{0.0, 0.0}, std::array{0.5 * spacing, 1.5 * spacing},
                               std::array{1.7 * spacing, 0.3 * spacing}}) {
      const Vector3d x_i(b, a, 0.0);
      Vector3d gradient_sum = Vector3d::Zero();
      double laplacian_sum = 0.0, density = 0.0;
      const int reach = static_cast<int>(kernel.support_radius() / spacing) + 2;
      const int z_reach = s.dimension == 3 ? reach : 0;
      for (int i = 0; i < reach; ++i)
        for (int j = 0; j < reach; ++j)
          for (int k = -z_reach; k <= z_reach; ++k) {
            const Vector3d x_k(-(i + 0.5) * spacing, -(j + 0.5) * spacing, k * spacing);
            const Vector3d x_ik = x_i - x_k;
            if (x_ik.norm() >= kernel.support_radius()) continue;
            const double p_k = p_i + G.dot(x_k - x_i);
            density += volume(kernel) * kernel.value(x_ik.norm());
            gradient_sum += volume(kernel) * (p_i + p_k) * kernel.gradient(x_ik);
            laplacian_sum += 2.0 * volume(kernel) * laplacian_weight(kernel, x_ik) * (p_i - p_k);
          }
      const CornerKernelValues q = CornerKernelTable::direct_sum(kernel, spacing, a, b);
      // Basis: n_A = e_y, n_B = e_x, e = e_z; S in that basis.
      const double g_a = G.y(), g_b = G.x(), g_e = G.z();
      const Vector3d from_table = 2.0 * p_i * (q.q1a * Vector3d::UnitY() + q.q1b * Vector3d::UnitX()) -
                                  (q.saa * g_a + q.sab * g_b) * Vector3d::UnitY() -
                                  (q.sab * g_a + q.sbb * g_b) * Vector3d::UnitX() - q.see * g_e * Vector3d::UnitZ();
      const double scale = gradient_sum.norm() + 1.0;
      CHECK(std::abs(density - q.q0) <= 1e-12 * (density + 1e-3));
      CHECK((from_table - gradient_sum).norm() <= 1e-10 * scale);
      CHECK(std::abs(2.0 * (q.m2a * g_a + q.m2b * g_b) - laplacian_sum) <= 1e-10 * (std::abs(laplacian_sum) + 1.0));
    }
  }
}

TEST_CASE("corner table: interpolation, symmetry and support", "[corner_table]") {
  for (const Setting& s : settings()) {
    const Kernel kernel(s.type, s.dimension, s.h_over_dx * spacing);
    const CornerKernelTable table(kernel, spacing);
    INFO(kernel_name(s.type) << " " << s.dimension << "D h/L0 = " << s.h_over_dx);
    const CornerKernelValues at_edge = CornerKernelTable::direct_sum(kernel, spacing, 0.0, 0.0);
    const double step = table.cutoff() / table.intervals();
    double worst_q0 = 0.0, worst_q1 = 0.0, worst_q2 = 0.0;
    for (int i = 0; i < 40; ++i)
      for (int j = 0; j < 40; ++j) {
        // Cell centres, where bilinear interpolation errs most.
        const double a = (std::floor(i * table.intervals() / 40.0) + 0.5) * step;
        const double b = (std::floor(j * table.intervals() / 40.0) + 0.5) * step;
        const CornerKernelValues exact = CornerKernelTable::direct_sum(kernel, spacing, a, b);
        const CornerKernelValues interpolated = table.at(a, b);
        worst_q0 = std::max(worst_q0, std::abs(interpolated.q0 - exact.q0) / at_edge.q0);
        worst_q1 = std::max(worst_q1, std::abs(interpolated.q1a - exact.q1a) / std::abs(at_edge.q1a));
        worst_q2 = std::max(worst_q2, std::abs(interpolated.q2 - exact.q2) / std::abs(at_edge.q2));
        // Swapping the planes swaps the entries.
        const CornerKernelValues swapped = CornerKernelTable::direct_sum(kernel, spacing, b, a);
        CHECK(swapped.q1a == Approx(exact.q1b).margin(1e-12 * std::abs(at_edge.q1a)));
        CHECK(swapped.saa == Approx(exact.sbb).margin(1e-12 * std::abs(at_edge.saa)));
        CHECK(swapped.m2a == Approx(exact.m2b).margin(1e-12 * std::abs(at_edge.m2a)));
      }
    INFO("worst interpolation error / value at the edge: Q0 " << worst_q0 << ", Q1 " << worst_q1 << ", Q2 " << worst_q2);
    // 2e-4: the header's ~1e-4 (measured 9e-5 for every kernel, 2D and 3D).
    CHECK(worst_q0 < 2e-4);
    CHECK(worst_q1 < 2e-4);
    CHECK(worst_q2 < 2e-4);
    // Signs at the edge; nothing beyond the support of either plane.
    CHECK(at_edge.q0 > 0.0);
    CHECK(at_edge.q1a < 0.0);
    CHECK(at_edge.q2 < 0.0);
    CHECK(at_edge.saa < 0.0);
    CHECK(table.at(table.cutoff(), 0.0).q0 == 0.0);
    CHECK(table.at(0.0, 1.5 * table.cutoff()).q2 == 0.0);
    CHECK(std::isnan(table.at(std::nan(""), 0.0).q0));
    CHECK(table.at(-spacing, 0.0).q0 == table.at(0.0, 0.0).q0);
  }
  const Kernel kernel(KernelType::quintic_spline, 2, 1.2 * spacing);
  CHECK_THROWS_AS(CornerKernelTable(kernel, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(CornerKernelTable(kernel, spacing, 0), std::invalid_argument);
  CHECK_THROWS_AS(CornerKernelTable::direct_sum(kernel, spacing, -1e-9, 0.0), std::invalid_argument);
}
