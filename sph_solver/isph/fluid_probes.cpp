#include "sph_solver/isph/fluid_probes.hpp"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

/// Collective: sum_j V_j W(|x - x_j|) f_j for the given fields, and sum_j V_j W.
template <std::size_t N, class Field>
std::array<double, N + 1> kernel_sums(const FluidSolver& solver, const Eigen::Vector3d& x, Field field) {
  std::array<double, N + 1> sums{};
  const Particles& p = solver.particles();
  for (int j = 0; j < p.count(); ++j) {
    const double r = (x - p.position[at(j)]).norm();
    if (r >= solver.kernel().support_radius()) continue;
    const double weight = p.mass[at(j)] / solver.model().density * solver.kernel().value(r);
    const std::array<double, N> values = field(j);
    for (std::size_t k = 0; k < N; ++k) sums[k] += weight * values[k];
    sums[N] += weight;
  }
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(N + 1), MPI_DOUBLE, MPI_SUM, solver.comm());
  return sums;
}

}  // namespace

double pressure_at(const FluidSolver& solver, const Eigen::Vector3d& point) {
  const auto& p = solver.particles();
  const auto sums = kernel_sums<1>(solver, point, [&p](int j) { return std::array<double, 1>{p.pressure[at(j)]}; });
  return sums[1] > 0.0 ? sums[0] / sums[1] : not_a_number;
}

Eigen::Vector3d velocity_at(const FluidSolver& solver, const Eigen::Vector3d& point) {
  const auto& p = solver.particles();
  const auto sums = kernel_sums<3>(solver, point, [&p](int j) {
    const Eigen::Vector3d& v = p.velocity[at(j)];
    return std::array<double, 3>{v.x(), v.y(), v.z()};
  });
  if (!(sums[3] > 0.0)) return Eigen::Vector3d::Constant(not_a_number);
  return Eigen::Vector3d(sums[0], sums[1], sums[2]) / sums[3];
}

double surface_elevation(const FluidSolver& solver, const Eigen::Vector3d& point, double top) {
  const FluidModel& model = solver.model();
  const Eigen::Vector3d up = model.up();
  const double step = 0.25 * model.spacing;
  const double base = point.dot(up);
  const int samples = std::max(2, static_cast<int>(std::ceil((top - base) / step)) + 1);
  const double support = solver.kernel().support_radius();
  // Colour sums at the samples from this rank's particles near the line.
  std::vector<double> colour(at(samples), 0.0);
  const Particles& p = solver.particles();
  for (int j = 0; j < p.count(); ++j) {
    const Eigen::Vector3d offset = p.position[at(j)] - point;
    const double height = offset.dot(up);
    const double lateral_squared = (offset - height * up).squaredNorm();
    if (lateral_squared >= support * support) continue;
    const int first = std::max(0, static_cast<int>(std::floor((height - support) / step)));
    const int last = std::min(samples - 1, static_cast<int>(std::ceil((height + support) / step)));
    for (int k = first; k <= last; ++k) {
      const double dz = height - k * step;
      const double r = std::sqrt(lateral_squared + dz * dz);
      if (r < support) colour[at(k)] += p.mass[at(j)] / model.density * solver.kernel().value(r);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, colour.data(), samples, MPI_DOUBLE, MPI_SUM, solver.comm());
  std::vector<Eigen::Vector3d> sample_points(at(samples));
  for (int k = 0; k < samples; ++k) sample_points[at(k)] = point + k * step * up;
  const WallContacts walls = find_wall_contacts(solver.walls(), sample_points, model.dimension);
  for (int k = 0; k < samples; ++k) {
    double wall_share = 0.0;
    for (const WallContact& c : walls.of(k)) wall_share += c.values.z0;
    colour[at(k)] /= std::max(1.0 - wall_share, 1e-3);
  }
  for (int k = samples - 1; k > 0; --k) {
    if (colour[at(k - 1)] >= 0.5 && colour[at(k)] < 0.5) {
      const double fraction = (colour[at(k - 1)] - 0.5) / (colour[at(k - 1)] - colour[at(k)]);
      return (k - 1 + fraction) * step;
    }
  }
  return colour[0] >= 0.5 ? (samples - 1) * step : not_a_number;
}

double front_position(const FluidSolver& solver, const Eigen::Vector3d& point, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d up = solver.model().up();
  const double band = 2.0 * solver.model().spacing;
  double front = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& x : solver.particles().position) {
    const double height = (x - point).dot(up);
    if (height >= 0.0 && height < band) front = std::max(front, (x - point).dot(direction));
  }
  MPI_Allreduce(MPI_IN_PLACE, &front, 1, MPI_DOUBLE, MPI_MAX, solver.comm());
  return std::isfinite(front) ? front : not_a_number;
}

std::array<double, 2> liquid_volume(const FluidSolver& solver, const Eigen::AlignedBox3d& box) {
  const Particles& p = solver.particles();
  std::array<double, 2> volume{};
  for (int j = 0; j < p.count(); ++j)
    volume[box.contains(p.position[at(j)]) ? 0 : 1] += p.mass[at(j)] / solver.model().density;
  MPI_Allreduce(MPI_IN_PLACE, volume.data(), 2, MPI_DOUBLE, MPI_SUM, solver.comm());
  return volume;
}

double kinetic_energy(const FluidSolver& solver) {
  const Particles& p = solver.particles();
  double energy = 0.0;
  for (int j = 0; j < p.count(); ++j) energy += 0.5 * p.mass[at(j)] * p.velocity[at(j)].squaredNorm();
  MPI_Allreduce(MPI_IN_PLACE, &energy, 1, MPI_DOUBLE, MPI_SUM, solver.comm());
  return energy;
}

}  // namespace tankfsi::sph
