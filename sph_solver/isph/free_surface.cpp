#include "sph_solver/isph/free_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// div r of a full kernel support is D; below this the support is cut by the surface.
double spread_threshold(int dimension) { return dimension == 2 ? 1.5 : 2.4; }

/// The plane of the free surface near particle i and the walls it meets at a right
/// angle (a contact line; see free_surface.hpp).
struct SurfacePlane {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double distance = 0.0;
  std::array<int, SurfaceContact::max_overlaps> walls{};  ///< indices of the particle's contacts
  int count = 0;
};

/// Whether walls k and l of the plane are square to each other (a vertical edge of
/// a box: the octant behind both and the air).
bool orthogonal_walls(std::span<const WallContact> contacts, const SurfacePlane& plane, int k, int l) {
  return std::abs(contacts[at(plane.walls[at(k)])].normal.dot(contacts[at(plane.walls[at(l)])].normal)) <
         BoundaryOverlap::orthogonal_cosine;
}

/// delta with Z0(delta) - sum_walls Q0(d_w, delta) + sum_pairs O0(d_w, d_v, delta) =
/// deficit — the air not already counted by the walls, by inclusion-exclusion (both
/// sides fall with delta) — by bisection; 0 if the deficit exceeds the left side at
/// the plane.
double distance_with_overlaps(const WallModel& walls, std::span<const WallContact> contacts,
                              const SurfacePlane& plane, double deficit) {
  const WallKernelTable& table = walls.table();
  if (plane.count == 0) return table.distance_for_share(deficit);
  const auto distance = [&](int k) { return contacts[at(plane.walls[at(k)])].distance; };
  const auto share = [&](double delta) {
    double s = table.at(delta).z0;
    for (int k = 0; k < plane.count; ++k) {
      s -= walls.corner_table().at(distance(k), delta).q0;
      for (int l = k + 1; l < plane.count; ++l)
        if (orthogonal_walls(contacts, plane, k, l)) s += walls.corner_table().octant(distance(k), distance(l), delta).q0;
    }
    return s;
  };
  double low = 0.0;
  double high = share(0.0) > deficit ? table.cutoff() : 0.0;
  for (int iteration = 0; iteration < 60 && high - low > 1e-9 * table.cutoff(); ++iteration) {
    const double middle = 0.5 * (low + high);
    (share(middle) > deficit ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

/// The surface plane from grad C and the deficit. A wall the surface meets counted
/// the air behind it as liquid, which tilts grad C towards the wall (20 degrees at
/// the contact line of a flat surface): walls within 60 degrees of square are tried,
/// the overlap's part is taken out of grad C, and a wall is kept if the corrected
/// normal is square to it within BoundaryOverlap::orthogonal_cosine — then the normal
/// is made exactly square to the walls kept (the corner table's geometry).
SurfacePlane walls_met(const WallModel& walls, std::span<const WallContact> contacts,
                       const Eigen::Vector3d& colour_gradient, double deficit) {
  constexpr double candidate_cosine = 0.5;
  const Eigen::Vector3d raw_normal = colour_gradient.normalized();
  SurfacePlane tried{raw_normal};
  for (std::size_t k = 0; k < contacts.size() && tried.count < SurfaceContact::max_overlaps; ++k)
    if (std::abs(contacts[k].normal.dot(raw_normal)) < candidate_cosine)
      tried.walls[static_cast<std::size_t>(tried.count++)] = static_cast<int>(k);
  SurfacePlane plane{raw_normal};
  if (tried.count > 0) {
    const double delta = distance_with_overlaps(walls, contacts, tried, deficit);
    Eigen::Vector3d gradient = colour_gradient;
    for (int k = 0; k < tried.count; ++k) {
      const WallContact& w = contacts[at(tried.walls[static_cast<std::size_t>(k)])];
      const CornerKernelValues q = walls.corner_table().at(w.distance, delta);
      gradient -= q.q1a * w.normal + q.q1b * raw_normal;
    }
    const Eigen::Vector3d corrected = gradient.normalized();
    for (int k = 0; k < tried.count; ++k) {
      const int w = tried.walls[static_cast<std::size_t>(k)];
      if (std::abs(contacts[at(w)].normal.dot(corrected)) < BoundaryOverlap::orthogonal_cosine)
        plane.walls[static_cast<std::size_t>(plane.count++)] = w;
    }
    if (plane.count > 0) {
      for (int k = 0; k < plane.count; ++k) {
        const Eigen::Vector3d& wall_normal = contacts[at(plane.walls[static_cast<std::size_t>(k)])].normal;
        gradient -= gradient.dot(wall_normal) * wall_normal;
      }
      if (gradient.norm() > 0.0) plane.normal = gradient.normalized();
    }
  }
  plane.distance = distance_with_overlaps(walls, contacts, plane, deficit);
  return plane;
}

}  // namespace

std::vector<unsigned char> detect_free_surface(const Neighbourhood& n, std::span<const double> mass,
                                              std::span<const double> density) {
  const auto spread = position_divergence(n, mass, density);
  const double rho0 = n.model.density;
  std::vector<unsigned char> flags(at(n.owned));
  for (int i = 0; i < n.owned; ++i)
    flags[at(i)] = density[at(i)] < n.model.free_surface_threshold * rho0 ||
                           spread[at(i)] < spread_threshold(n.model.dimension)
                       ? 1
                       : 0;
  return flags;
}

std::vector<SurfaceContact> surface_contacts(const Neighbourhood& n, std::span<const double> mass,
                                             std::span<const double> density, const WallModel& walls) {
  const WallKernelTable& table = walls.table();
  std::vector<SurfaceContact> contacts(at(n.owned));
  const double rest_density = n.model.density * table.lattice_share();
  const double closest = 0.25 * n.model.spacing;  // as the walls' extrapolation distance
  // A surface more than 2 L0 away (beyond the second layer of a lattice) hides in
  // the density noise of a liquid in motion (1e-4 of rho0 at L0 = 0.02 m, where the
  // second layer misses 2.7e-2 and the third 1e-4): it is not looked for.
  const double farthest = 2.0 * n.model.spacing;
  // The normal from the particles' own volumes m / rho0: the kernel-sum volumes of the
  // surface layer (up to 1/0.73 of them) would turn grad C of the layers below upwards.
  const std::vector<double> lattice_density(density.size(), n.model.density);
  const auto colour_gradient = concentration_gradient(n, mass, lattice_density);
  // A surface within reach has its first layer within reach too (free_surface.hpp,
  // "Which particles"): a deficit that a particle of the first layer's size does
  // not confirm is the walls' (a curved wall completes the kernel sum to 0.5-2 %).
  const double first_layer_deficit = table.at(n.model.spacing).z0;
  const auto deficit_of = [&](int j) { return 1.0 - density[at(j)] / rest_density; };
  // Its first layer lies between the particle and the surface: within delta (and a
  // quarter spacing for the stagger of the layers).
  const auto first_layer_near = [&](int i, double delta) {
    const NeighbourList& list = n.neighbours;
    for (int k = list.offsets[at(i)]; k < list.offsets[at(i) + 1]; ++k)
      if (list.distances[at(k)] <= delta + 0.25 * n.model.spacing && deficit_of(list.indices[at(k)]) >= first_layer_deficit)
        return true;
    return false;
  };
  for (int i = 0; i < n.owned; ++i) {
    const double deficit = deficit_of(i);
    if (!(deficit > 0.0)) continue;
    SurfaceContact c;
    const auto walls_of_i = n.walls.of(i);
    // A drop alone in the air (no liquid or wall within its support: grad C = 0) has
    // air all round, in no direction: its vector terms vanish, its PPE row keeps the
    // air's diagonal (without it the row would be empty and the pressure undefined).
    const bool alone = !(colour_gradient[at(i)].norm() > 0.0);
    const auto met = alone ? SurfacePlane{} : walls_met(walls, walls_of_i, colour_gradient[at(i)], deficit);
    c.normal = met.normal;
    const double delta = alone ? table.distance_for_share(deficit) : met.distance;
    if (!(delta < farthest)) continue;
    if (deficit < first_layer_deficit && !first_layer_near(i, delta)) continue;
    c.active = true;
    c.distance = std::max(delta, closest);
    c.values = table.at(c.distance);
    for (int k = 0; k < met.count; ++k) {
      const WallContact& w = walls_of_i[at(met.walls[static_cast<std::size_t>(k)])];
      BoundaryOverlap& o = c.overlap_storage[static_cast<std::size_t>(c.overlap_count)];
      o.first = met.walls[static_cast<std::size_t>(k)];
      o.second = -1;
      o.normal_a = w.normal;
      o.normal_b = c.normal;
      o.values = walls.corner_table().at(w.distance, c.distance);
      if (o.values.q0 > 0.0 || o.values.q2 < 0.0) ++c.overlap_count;
    }
    if (n.model.dimension == 3)
      for (int k = 0; k < met.count; ++k)
        for (int l = k + 1; l < met.count; ++l) {
          if (!orthogonal_walls(walls_of_i, met, k, l)) continue;
          const WallContact& a = walls_of_i[at(met.walls[at(k)])];
          const WallContact& b = walls_of_i[at(met.walls[at(l)])];
          CornerOctant& o = c.octant_storage[at(c.octant_count)];
          o.contacts = {met.walls[at(k)], met.walls[at(l)], -1};
          o.normals = {a.normal, b.normal, c.normal};
          o.values = walls.corner_table().octant(a.distance, b.distance, c.distance);
          if (o.values.q0 > 0.0 || o.values.q2 < 0.0) ++c.octant_count;
        }
    contacts[at(i)] = c;
  }
  return contacts;
}

std::vector<double> density_against_lattice(std::span<const double> density, double lattice_density, double rho0) {
  std::vector<double> read(density.begin(), density.end());
  for (double& d : read) d *= rho0 / lattice_density;
  return read;
}

std::vector<double> completed_density(std::span<const double> density, std::span<const SurfaceContact> contacts,
                                      double lattice_density, double rho0) {
  std::vector<double> completed = density_against_lattice(density.first(contacts.size()), lattice_density, rho0);
  for (std::size_t i = 0; i < contacts.size(); ++i)
    if (contacts[i].active) completed[i] = rho0;
  return completed;
}

}  // namespace tankfsi::sph
