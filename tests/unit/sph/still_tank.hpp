#pragma once
// Liquids at rest on their initial lattice, for the tests of the ISPH sums: a 2D
// tank of water 0.6 m wide, filled to 0.4 m (L0 = 0.02 m, quintic spline, h =
// 1.2 L0), with the hydrostatic pressure rho g (level - y), its neighbour list and
// wall contacts; a 3D liquid in any tank with its air; cases/hydrostatic_3d's oil.
#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "sph_solver/isph/free_surface.hpp"
#include "sph_solver/isph/particle_terms.hpp"
#include "sph_solver/neighbours/cell_list.hpp"
#include "sph_solver/particles/filling.hpp"
#include "sph_solver/walls/tank_meshes.hpp"

namespace tankfsi::test {

using namespace tankfsi::sph;

inline constexpr double width = 0.6;
inline constexpr double level = 0.4;
inline constexpr double g = 9.81;

inline FluidModel water() {
  FluidModel m;
  m.dimension = 2;
  m.kernel = KernelType::quintic_spline;
  m.spacing = 0.02;
  m.smoothing_length = 1.2 * m.spacing;
  m.density = 1000.0;
  m.viscosity = 1e-3;
  return m;
}

/// `model`'s water filled into `walls` up to `fill_level` on the lattice, with the
/// hydrostatic pressure.
inline Particles fill_water(const FluidModel& model, const TriangleMesh& walls, double fill_level) {
  FillSpec spec;
  spec.spacing = model.spacing;
  spec.density = model.density;
  spec.fill_level = fill_level;
  spec.dimension = model.dimension;
  spec.hydrostatic_pressure = true;
  spec.gravity = model.gravity;
  return fill_tank(walls, spec);
}

/// The walls' box widened by 2 m: a FluidSolver's domain that no particle leaves.
inline Eigen::AlignedBox3d domain_around(const TriangleMesh& walls) {
  Eigen::AlignedBox3d domain = walls.bounding_box();
  domain.min().array() -= 2.0;
  domain.max().array() += 2.0;
  return domain;
}

/// cases/hydrostatic_3d's liquid: oil (quartic spline, L0 = 0.05 m, h its default 1.1 L0).
inline FluidModel oil_3d() {
  FluidModel m = water();
  m.dimension = 3;
  m.kernel = KernelType::quartic_spline;
  m.spacing = 0.05;
  m.smoothing_length = default_smoothing_length_ratio(m.kernel) * m.spacing;
  m.density = 860.0;
  return m;
}

/// cases/hydrostatic_3d's tank and liquid: oil 0.5 m deep in an upright cylinder of
/// R = 0.5 m, 0.6 m high, with 32 wall facets (2 pi R / 2 L0, as the case's
/// generator) and a dome roof of radius 1 m, filled on rings inside the smooth
/// cylinder the facets approximate, with the hydrostatic pressure.
struct OilCylinder {
  static constexpr double radius = 0.5;
  static constexpr double depth = 0.5;
  static constexpr int segments = 32;
  FluidModel model = oil_3d();
  TriangleMesh walls = [this] {
    const double height = 0.6, dome = 1.0, edge = 2.0 * model.spacing;
    const DomeRoof roof{dome, static_cast<int>(std::ceil(dome * std::asin(radius / dome) / edge))};
    return make_cylindrical_tank(radius, height, segments, static_cast<int>(std::ceil(height / edge)),
                                 static_cast<int>(std::ceil(radius / edge)), roof);
  }();
  Particles particles = [this] {
    FillSpec spec;
    spec.spacing = model.spacing;
    spec.density = model.density;
    spec.fill_level = depth;
    spec.dimension = 3;
    spec.hydrostatic_pressure = true;
    spec.gravity = model.gravity;
    spec.cylinder_radius = radius;  // the smooth wall the facets approximate
    return fill_tank(walls, spec);
  }();
};

/// A 3D liquid at rest in `walls` with its air: neighbours, wall contacts, kernel
/// sums, the air and the densities it completes.
struct StillLiquid3d {
  const FluidModel& model;
  const Kernel kernel{model.kernel, 3, model.smoothing_length};
  const WallModel walls;
  const Particles& particles;
  const NeighbourList neighbours = [this] {
    CellList cells(3);
    cells.build(particles.position, kernel.support_radius());
    return cells.neighbour_list(&kernel);
  }();
  const WallContacts contacts = find_wall_contacts(walls, particles.position, 3);
  const std::vector<double> density = kernel_density(view({}), particles.mass);
  const std::vector<SurfaceContact> air = surface_contacts(view({}), particles.mass, density, walls);
  const std::vector<double> completed =
      completed_density(density, air, model.density * walls.table().lattice_share(), model.density);
  /// The kernel sums read against the lattice without the air (as a step reads
  /// them away from the surface).
  const std::vector<double> against_lattice =
      density_against_lattice(density, model.density * walls.table().lattice_share(), model.density);

  StillLiquid3d(const FluidModel& m, const TriangleMesh& mesh, const Particles& p)
      : model(m), walls(mesh, m, kernel), particles(p) {}
  [[nodiscard]] Neighbourhood view(std::span<const SurfaceContact> surface) const {
    return {kernel, model, particles.position, neighbours, contacts, walls.mesh(), particles.count(), surface};
  }
  [[nodiscard]] Neighbourhood view() const { return view(air); }
};

/// A tank filled to `level` at rest with hydrostatic pressure, and its neighbourhood.
struct Tank {
  FluidModel model = water();
  Kernel kernel{model.kernel, 2, model.smoothing_length};
  WallModel walls{make_rectangular_tank_2d(width, 0.6, 0.2, 0.04), model, kernel};
  Particles particles;
  NeighbourList neighbours;
  WallContacts contacts;
  std::vector<double> density;

  Tank() {
    particles = fill_water(model, walls.mesh(), level);
    CellList cells(2);
    cells.build(particles.position, kernel.support_radius());
    neighbours = cells.neighbour_list(&kernel);
    contacts = find_wall_contacts(walls, particles.position, 2);
    density = kernel_density(view(), particles.mass);
  }

  /// The sums' view of the tank; `surface`: the air beyond the free surface, if any.
  [[nodiscard]] Neighbourhood view(std::span<const SurfaceContact> surface = {}) const {
    return {kernel, model, particles.position, neighbours, contacts, walls.mesh(), particles.count(), surface};
  }
  [[nodiscard]] double support() const { return kernel.support_radius(); }
  /// Away from the free surface (its truncated kernel is not the walls' business).
  [[nodiscard]] bool submerged(int i) const { return particles.position[static_cast<std::size_t>(i)].y() < level - support(); }
  [[nodiscard]] bool near_floor(int i) const { return particles.position[static_cast<std::size_t>(i)].y() < support(); }
  [[nodiscard]] bool near_side(int i) const {
    const double x = particles.position[static_cast<std::size_t>(i)].x();
    return x < support() || x > width - support();
  }
};


}  // namespace tankfsi::test
