#include "sph_solver/isph/particle_terms.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "sph_solver/walls/wall_kernel_table.hpp"

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// One neighbour j of owned particle i: x_ij = x_i - x_j, r = |x_ij|, and the
/// kernel's value W(r) and slope dW/dr there, as the neighbour list holds them.
struct Pair {
  int j;
  Eigen::Vector3d x_ij;
  double r;
  double value;
  double slope;
  /// grad_i W_ij = x_ij / r dW/dr; zero at r = 0, where dW/dr vanishes.
  [[nodiscard]] Eigen::Vector3d gradient() const {
    return r > 0.0 ? Eigen::Vector3d(x_ij * (slope / r)) : Eigen::Vector3d::Zero();
  }
};

/// The sums read each pair's kernel value and slope from the neighbour list.
void require_kernel_values(const Neighbourhood& n) {
  if (n.neighbours.values.size() != n.neighbours.indices.size() ||
      n.neighbours.slopes.size() != n.neighbours.indices.size() || n.neighbours.particle_count() < n.owned)
    throw std::logic_error("the ISPH sums need a neighbour list built with the kernel for every owned particle");
}

/// Calls f(pair) for every neighbour of owned particle i.
template <class F>
void for_each_neighbour(const Neighbourhood& n, int i, F&& f) {
  const NeighbourList& list = n.neighbours;
  const Eigen::Vector3d& x_i = n.position[at(i)];
  for (int k = list.offsets[at(i)]; k < list.offsets[at(i) + 1]; ++k) {
    const int j = list.indices[at(k)];
    f(Pair{j, x_i - n.position[at(j)], list.distances[at(k)], list.values[at(k)], list.slopes[at(k)]});
  }
}

/// The wall distance in the no-slip extrapolation factor (1 + d / r_iw), floored at
/// L0/4 so that a particle touching the wall gets a finite (5-fold at most
/// typical depths) rather than an infinite velocity gradient.
double extrapolation_distance(const Neighbourhood& n, const WallContact& c) {
  return std::max(c.distance, 0.25 * n.model.spacing);
}

/// The pressure gradient of a particle near walls from its fluid neighbours alone:
/// their sum covers the part T_fluid = I - sum_w T_w + T_overlaps of the moment tensor
/// -sum_j V_j x_ij (x) grad_i W_ij (the identity on a full lattice), each wall
/// holding T_w = -Z1 (r_iw + d1) n n^T normal to it and its tangential_moment along it
/// (Z3 (I - n n^T) on a flat wall; wall_contacts.hpp), each corner's
/// overlap (counted by both walls) T_o = -S, each octant of three walls (counted by
/// none then) -T_o; so
/// grad P = T_fluid^-1 sum_j V_j (P_j - P_i) grad_i W_ij. (In 2D the z row is the identity.)
/// Falls back to the plain sum if T_fluid is near singular (a particle in a narrow gap):
/// its determinant below 0.05^(D/2), a fluid share of ~0.22 per direction. (The
/// corner particle of a 2D tank has 0.07, of a 3D box 0.018 = 0.26^3: against a
/// bare 0.05 the 3D corner fell back and its pressure held it with 70 % of g.)
Eigen::Vector3d renormalised_gradient(const Neighbourhood& n, std::span<const WallContact> contacts,
                                      std::span<const BoundaryOverlap> overlaps, std::span<const CornerOctant> octants,
                                      const Eigen::Vector3d& fluid_gradient, double lattice_moment) {
  Eigen::Matrix3d fluid_moment = lattice_moment * Eigen::Matrix3d::Identity();
  for (const WallContact& c : contacts) {
    const Eigen::Matrix3d normal_part = c.normal * c.normal.transpose();
    fluid_moment -= -c.values.z1 * (c.distance + c.values.depth1) * normal_part;
    fluid_moment -= c.tangential_moment;
  }
  for (const BoundaryOverlap& o : overlaps) fluid_moment -= o.second_moment();
  for (const CornerOctant& o : octants) fluid_moment += o.second_moment();
  if (n.model.dimension == 2) {
    fluid_moment.row(2).setZero();
    fluid_moment.col(2).setZero();
    fluid_moment(2, 2) = 1.0;
  }
  const double near_singular = n.model.dimension == 2 ? 0.05 : 0.05 * std::sqrt(0.05);
  if (!(std::abs(fluid_moment.determinant()) > near_singular)) return fluid_gradient;
  return fluid_moment.inverse() * fluid_gradient;
}

/// The component of `gradient` along the edge of an overlap (3D; zero in 2D, where
/// the edge is the z axis and nothing varies along it).
Eigen::Vector3d along_edge(const BoundaryOverlap& o, const Eigen::Vector3d& gradient) {
  const Eigen::Vector3d edge = o.normal_a.cross(o.normal_b).normalized();
  return gradient.dot(edge) * edge;
}

/// Shares a force on an overlap between its two walls: each its normal component,
/// half each of the rest.
std::pair<Eigen::Vector3d, Eigen::Vector3d> split_between_walls(const BoundaryOverlap& o, const Eigen::Vector3d& f) {
  const Eigen::Vector3d on_a = f.dot(o.normal_a) * o.normal_a;
  const Eigen::Vector3d on_b = f.dot(o.normal_b) * o.normal_b;
  const Eigen::Vector3d rest = 0.5 * (f - on_a - on_b);
  return {on_a + rest, on_b + rest};
}

}  // namespace

double wall_pressure_gradient(const FluidModel& model, const WallContact& contact, const Eigen::Vector3d& v_star,
                              double dt) {
  return model.density / dt * (v_star - contact.velocity).dot(contact.normal);
}

double contact_line_wall_gradient(const FluidModel& model, const WallContact& contact, const Eigen::Vector3d& a_star) {
  return model.density * a_star.dot(contact.normal);
}

double wall_laplacian_share(const Neighbourhood& n, int i, const Eigen::Vector3d& v_star, const Eigen::Vector3d& a_star,
                            double dt) {
  const auto contacts = n.walls.of(i);
  const auto gradient = [&](int k) { return wall_pressure_gradient(n.model, contacts[at(k)], v_star, dt); };
  const auto contact_line_gradient = [&](int k) { return contact_line_wall_gradient(n.model, contacts[at(k)], a_star); };
  double share = 0.0;
  for (const WallContact& c : contacts)
    share += 2.0 * c.values.z2 * wall_pressure_gradient(n.model, c, v_star, dt) * (c.distance + c.values.depth2);
  for (const BoundaryOverlap& o : n.walls.overlaps_of(i)) share -= o.laplacian_sum(gradient(o.first), gradient(o.second));
  for (const CornerOctant& o : n.walls.octants_of(i))
    share += o.laplacian_sum({gradient(o.contacts[0]), gradient(o.contacts[1]), gradient(o.contacts[2])});
  if (!n.surface.empty()) {
    for (const BoundaryOverlap& o : n.surface[at(i)].overlaps())
      share -= o.laplacian_sum(contact_line_gradient(o.first), 0.0);
    for (const CornerOctant& o : n.surface[at(i)].octants())
      share += o.laplacian_sum({contact_line_gradient(o.contacts[0]), contact_line_gradient(o.contacts[1]), 0.0});
  }
  return share;
}

std::vector<double> pressure_laplacian(const Neighbourhood& n, std::span<const double> mass,
                                       std::span<const double> density, std::span<const double> pressure) {
  require_kernel_values(n);
  std::vector<double> laplacian(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    double sum = 0.0;
    for_each_neighbour(n, i, [&](const Pair& p) {
      const double volume = (mass[at(i)] + mass[at(p.j)]) / (density[at(i)] + density[at(p.j)]);
      sum += laplacian_weight(n.model, p.r, p.slope, volume) * (pressure[at(i)] - pressure[at(p.j)]);
    });
    if (!n.surface.empty()) sum += n.surface[at(i)].laplacian_share() * pressure[at(i)];
    laplacian[at(i)] = sum;
  }
  return laplacian;
}

std::vector<double> kernel_density(const Neighbourhood& n, std::span<const double> mass) {
  require_kernel_values(n);
  std::vector<double> density(at(n.owned));
  const double self_weight = n.kernel.value(0.0);
  for (int i = 0; i < n.owned; ++i) {
    double sum = mass[at(i)] * self_weight;
    for_each_neighbour(n, i, [&](const Pair& p) { sum += mass[at(p.j)] * p.value; });
    for (const WallContact& c : n.walls.of(i)) sum += n.model.density * c.values.z0;
    for (const BoundaryOverlap& o : n.walls.overlaps_of(i)) sum -= n.model.density * o.values.q0;
    for (const CornerOctant& o : n.walls.octants_of(i)) sum += n.model.density * o.values.q0;
    density[at(i)] = sum;
  }
  return density;
}

std::vector<double> position_divergence(const Neighbourhood& n, std::span<const double> mass,
                                        std::span<const double> density) {
  require_kernel_values(n);
  std::vector<double> divergence(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    double sum = 0.0;
    for_each_neighbour(n, i, [&](const Pair& p) { sum -= mass[at(p.j)] / density[at(p.j)] * p.r * p.slope; });
    for (const WallContact& c : n.walls.of(i))
      sum += -c.values.z1 * (c.distance + c.values.depth1) + (n.model.dimension - 1) * c.values.z3;
    for (const BoundaryOverlap& o : n.walls.overlaps_of(i)) sum -= o.position_divergence_share();
    for (const CornerOctant& o : n.walls.octants_of(i)) sum += o.position_divergence_share();
    if (!n.surface.empty() && n.surface[at(i)].active) {
      const SurfaceContact& air = n.surface[at(i)];
      sum += -air.values.z1 * (air.distance + air.values.depth1) + (n.model.dimension - 1) * air.values.z3;
      for (const BoundaryOverlap& o : air.overlaps()) sum -= o.position_divergence_share();
      for (const CornerOctant& o : air.octants()) sum += o.position_divergence_share();
    }
    divergence[at(i)] = sum;
  }
  return divergence;
}

bool near_free_surface(const Neighbourhood& n, std::span<const unsigned char> free_surface, int i) {
  if (free_surface[at(i)] != 0) return true;
  const auto neighbours = n.neighbours.neighbours_of(i);
  return std::any_of(neighbours.begin(), neighbours.end(), [&](int j) { return free_surface[at(j)] != 0; });
}

std::vector<double> moment_scale(const Neighbourhood& n, std::span<const double> mass,
                                 std::span<const double> density, std::span<const unsigned char> free_surface) {
  const double full = n.model.dimension * lattice_moment(n.kernel, n.model.spacing);
  std::vector<double> scale = position_divergence(n, mass, density);
  for (int i = 0; i < n.owned; ++i) {
    const bool has_air = !n.surface.empty() && n.surface[at(i)].active;
    scale[at(i)] = !has_air && near_free_surface(n, free_surface, i) ? 0.0
                                                                    : std::clamp(scale[at(i)] / full, 1.0 - 0.1, 1.0 + 0.1);
  }
  return scale;
}

std::vector<double> smoothed_moment_scale(const Neighbourhood& n, std::span<const double> scale) {
  require_kernel_values(n);
  const double self_weight = n.kernel.value(0.0);
  std::vector<double> smoothed(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    double sum = 0.0, weight = 0.0;
    if (scale[at(i)] != 0.0) {
      sum = self_weight * scale[at(i)];
      weight = self_weight;
    }
    for_each_neighbour(n, i, [&](const Pair& p) {
      if (scale[at(p.j)] == 0.0) return;
      sum += p.value * scale[at(p.j)];
      weight += p.value;
    });
    smoothed[at(i)] = weight > 0.0 ? sum / weight : 1.0;
  }
  return smoothed;
}

std::vector<Eigen::Vector3d> viscous_acceleration(const Neighbourhood& n, std::span<const double> mass,
                                                  std::span<const double> density,
                                                  std::span<const Eigen::Vector3d> velocity,
                                                  std::vector<Eigen::Vector3d>& wall_force) {
  require_kernel_values(n);
  std::vector<Eigen::Vector3d> acceleration(at(n.owned), Eigen::Vector3d::Zero());
  const double mu = n.model.viscosity;
  if (mu == 0.0) return acceleration;
  const double eta2 = n.model.eta_squared();
  for (int i = 0; i < n.owned; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    const double rho_i = density[at(i)];
    for_each_neighbour(n, i, [&](const Pair& p) {
      // x_ij · grad_i W_ij = r W'(r)
      const double weight = mass[at(p.j)] * 2.0 * mu / (rho_i * density[at(p.j)]) * p.r * p.slope / (p.r * p.r + eta2);
      sum += weight * (velocity[at(i)] - velocity[at(p.j)]);
    });
    const auto contacts = n.walls.of(i);
    for (const WallContact& c : contacts) {
      const double extrapolation = 1.0 + c.values.depth2 / extrapolation_distance(n, c);
      const Eigen::Vector3d wall_part = 2.0 * mu / rho_i * c.values.z2 * extrapolation * (velocity[at(i)] - c.velocity);
      sum += wall_part;
      add_wall_force(n.wall_mesh, c, -mass[at(i)] * wall_part, wall_force);
    }
    // A corner's overlap carries each wall's no-slip extrapolation, (v_i - v_w)(a + s_A)/a
    // for wall A: summed over it, 2 M2A / a (v_i - v_wA). One copy is taken out, the
    // mean of the two (the velocity in the corner follows neither wall's alone).
    for (const BoundaryOverlap& o : n.walls.overlaps_of(i)) {
      const WallContact& a = contacts[at(o.first)];
      const WallContact& b = contacts[at(o.second)];
      const Eigen::Vector3d part_a = mu / rho_i * o.values.m2a / extrapolation_distance(n, a) * (velocity[at(i)] - a.velocity);
      const Eigen::Vector3d part_b = mu / rho_i * o.values.m2b / extrapolation_distance(n, b) * (velocity[at(i)] - b.velocity);
      sum -= part_a + part_b;
      add_wall_force(n.wall_mesh, a, mass[at(i)] * part_a, wall_force);
      add_wall_force(n.wall_mesh, b, mass[at(i)] * part_b, wall_force);
    }
    // A box's corner: after the three half-spaces and the three pairs' means the
    // octant is counted no times; one copy, the mean of the three walls', back in.
    for (const CornerOctant& o : n.walls.octants_of(i))
      for (std::size_t w = 0; w < 3; ++w) {
        const WallContact& c = contacts[at(o.contacts[w])];
        const Eigen::Vector3d part =
            2.0 / 3.0 * mu / rho_i * o.values.m2[w] / extrapolation_distance(n, c) * (velocity[at(i)] - c.velocity);
        sum += part;
        add_wall_force(n.wall_mesh, c, -mass[at(i)] * part, wall_force);
      }
    acceleration[at(i)] = sum;
  }
  return acceleration;
}

std::vector<double> velocity_divergence(const Neighbourhood& n, std::span<const double> mass,
                                        std::span<const double> density, std::span<const Eigen::Vector3d> velocity) {
  require_kernel_values(n);
  std::vector<double> divergence(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    double sum = 0.0;
    for_each_neighbour(n, i, [&](const Pair& p) {
      sum += mass[at(p.j)] * (velocity[at(i)] - velocity[at(p.j)]).dot(p.gradient());
    });
    divergence[at(i)] = -sum / density[at(i)];
  }
  return divergence;
}

std::vector<Eigen::Vector3d> pressure_acceleration(const Neighbourhood& n, std::span<const double> mass,
                                                   std::span<const double> density, std::span<const double> pressure,
                                                   std::span<const Eigen::Vector3d> predicted_velocity,
                                                   std::span<const Eigen::Vector3d> predicted_acceleration, double dt,
                                                   std::vector<Eigen::Vector3d>& wall_force) {
  require_kernel_values(n);
  std::vector<Eigen::Vector3d> acceleration(at(n.owned));
  const double rho0 = n.model.density;
  // The sums below give M grad P for a linear pressure on the lattice (M the
  // lattice's moment, wall_kernel_table.hpp), in the liquid and, with the walls'
  // tables, beside walls, in corners and at the surface alike: divided by M, a
  // hydrostatic lattice is in balance to the tables' accuracy everywhere. (A
  // lattice sum of about a microsecond a call: summed here, not carried along.)
  const double moment = lattice_moment(n.kernel, n.model.spacing);
  // 1 / (s M) per particle; the pairs take the mean of theirs (moment_scale(), particle_terms.hpp).
  const auto calibration_of = [&](int i) {
    return n.moment_scale.empty() ? 1.0 / moment : 1.0 / (n.moment_scale[at(i)] * moment);
  };
  for (int i = 0; i < n.owned; ++i) {
    const double rho_i = density[at(i)];
    const double p_i = pressure[at(i)] / (rho_i * rho_i);
    const double calibration = calibration_of(i);
    const auto add_force = [&](const WallContact& c, int k, const Eigen::Vector3d& part) {
      add_wall_force(n.wall_mesh, c, -calibration * mass[at(k)] * part, wall_force);
    };
    Eigen::Vector3d pairs = Eigen::Vector3d::Zero();  // calibrated already
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();    // the walls' and the air's, to calibrate
    Eigen::Vector3d fluid_gradient = Eigen::Vector3d::Zero();  // sum_j V_j (P_j - P_i) grad_i W_ij
    for_each_neighbour(n, i, [&](const Pair& p) {
      const double rho_j = density[at(p.j)];
      const Eigen::Vector3d grad = p.gradient();
      pairs -= 0.5 * (calibration + calibration_of(p.j)) * mass[at(p.j)] *
               (p_i + pressure[at(p.j)] / (rho_j * rho_j)) * grad;
      fluid_gradient += mass[at(p.j)] / rho_j * (pressure[at(p.j)] - pressure[at(i)]) * grad;
    });
    const auto contacts = n.walls.of(i);
    const auto normal_gradient = [&](int k) {
      return wall_pressure_gradient(n.model, contacts[at(k)], predicted_velocity[at(i)], dt);
    };
    const SurfaceContact* air = !n.surface.empty() && n.surface[at(i)].active ? &n.surface[at(i)] : nullptr;
    const auto contact_line_gradient = [&](int k) {
      return contact_line_wall_gradient(n.model, contacts[at(k)], predicted_acceleration[at(i)]);
    };
    // The linear pressure in an octant of two walls and the air: each plane's normal gradient.
    const auto air_octant_gradient = [&](const CornerOctant& o) -> Eigen::Vector3d {
      return contact_line_gradient(o.contacts[0]) * o.normals[0] + contact_line_gradient(o.contacts[1]) * o.normals[1] +
             pressure[at(i)] / air->distance * o.normals[2];
    };
    if (air != nullptr) {
      // The air beyond the free surface (free_surface.hpp): its pressure continues
      // the liquid's linearly to P = 0 on the surface plane. Where it overlaps a wall
      // the wall's moment (below) already holds the overlap: out of the air's sum.
      sum -= air->values.z1 * rho0 * p_i * air->pressure_sum_factor() * air->normal;
      fluid_gradient += air->values.z1 * air->pressure_difference_factor() * pressure[at(i)] * air->normal;
      for (const BoundaryOverlap& o : air->overlaps())
        fluid_gradient -= o.pressure_difference_sum(contact_line_gradient(o.first) * o.normal_a +
                                                    pressure[at(i)] / air->distance * o.normal_b);
      for (const CornerOctant& o : air->octants())
        fluid_gradient += o.pressure_difference_sum(air_octant_gradient(o));
    }
    const auto corners = n.walls.overlaps_of(i);
    const auto octants = n.walls.octants_of(i);
    const Eigen::Vector3d tangential_gradient =
        contacts.empty() ? Eigen::Vector3d::Zero()
                         : renormalised_gradient(n, contacts, corners, octants, fluid_gradient, moment);
    for (const WallContact& c : contacts) {
      const double wall_pressure = pressure[at(i)] - wall_pressure_gradient(n.model, c, predicted_velocity[at(i)], dt) *
                                                         (c.distance + c.values.depth1);
      const Eigen::Vector3d along_wall = tangential_gradient - tangential_gradient.dot(c.normal) * c.normal;
      const Eigen::Vector3d wall_part =
          -c.values.z1 * (rho0 * p_i + wall_pressure / rho0) * c.normal - c.tangential_moment * along_wall / rho0;
      sum += wall_part;
      add_force(c, i, wall_part);
    }
    // Overlaps, counted by both of their half-spaces: one copy of
    // -(1/rho0) sum_o V (P_i + P_k) grad W = -(2 P_i Q1 - S G) / rho0 back.
    const auto one_copy = [&](const BoundaryOverlap& o, const Eigen::Vector3d& g) -> Eigen::Vector3d {
      const Eigen::Vector3d gradient = g + along_edge(o, tangential_gradient);
      return o.gradient_sum() * (rho0 * p_i + pressure[at(i)] / rho0) + o.pressure_difference_sum(gradient) / rho0;
    };
    for (const BoundaryOverlap& o : corners) {
      const Eigen::Vector3d part =
          one_copy(o, normal_gradient(o.first) * o.normal_a + normal_gradient(o.second) * o.normal_b);
      sum += part;
      const auto [on_a, on_b] = split_between_walls(o, part);
      add_force(contacts[at(o.first)], i, on_a);
      add_force(contacts[at(o.second)], i, on_b);
    }
    // Octants: one wall copy back in with the linear field of the planes' normal
    // gradients, its force on the walls shared as an overlap's (each wall its
    // normal part, the rest in equal shares).
    const auto add_octant_copy = [&](const CornerOctant& o, const Eigen::Vector3d& gradient) {
      const Eigen::Vector3d part =
          -(o.gradient_sum() * (rho0 * p_i + pressure[at(i)] / rho0) + o.pressure_difference_sum(gradient) / rho0);
      sum += part;
      const int wall_count = o.contacts[2] < 0 ? 2 : 3;
      Eigen::Vector3d rest = part;
      for (std::size_t w = 0; w < at(wall_count); ++w) rest -= part.dot(o.normals[w]) * o.normals[w];
      for (std::size_t w = 0; w < at(wall_count); ++w)
        add_force(contacts[at(o.contacts[w])], i, part.dot(o.normals[w]) * o.normals[w] + rest / wall_count);
    };
    // A box's corner of three walls.
    for (const CornerOctant& o : octants) {
      Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
      for (std::size_t w = 0; w < 3; ++w) gradient += normal_gradient(o.contacts[w]) * o.normals[w];
      add_octant_copy(o, gradient);
    }
    // A vertical edge at the surface: two walls and the air (surface_contact.hpp).
    if (air != nullptr)
      for (const CornerOctant& o : air->octants()) add_octant_copy(o, air_octant_gradient(o));
    if (air != nullptr)
      for (const BoundaryOverlap& o : air->overlaps()) {
        // A contact line: the overlap is air, which the wall's half-space counted as
        // liquid; the copy comes off the wall.
        const Eigen::Vector3d part =
            one_copy(o, contact_line_gradient(o.first) * o.normal_a + pressure[at(i)] / air->distance * o.normal_b);
        sum += part;
        add_force(contacts[at(o.first)], i, part);
      }
    acceleration[at(i)] = pairs + calibration * sum;
  }
  return acceleration;
}

std::vector<Eigen::Vector3d> concentration_gradient(const Neighbourhood& n, std::span<const double> mass,
                                                    std::span<const double> density) {
  require_kernel_values(n);
  std::vector<Eigen::Vector3d> gradient(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for_each_neighbour(n, i, [&](const Pair& p) { sum += mass[at(p.j)] / density[at(p.j)] * p.gradient(); });
    for (const WallContact& c : n.walls.of(i)) sum += c.values.z1 * c.normal;
    for (const BoundaryOverlap& o : n.walls.overlaps_of(i)) sum -= o.gradient_sum();
    for (const CornerOctant& o : n.walls.octants_of(i)) sum += o.gradient_sum();
    gradient[at(i)] = sum;
  }
  return gradient;
}

std::vector<Eigen::Vector3d> velocity_change_over_shift(const Neighbourhood& n, std::span<const double> mass,
                                                        std::span<const double> density,
                                                        std::span<const Eigen::Vector3d> velocity,
                                                        std::span<const Eigen::Vector3d> shift) {
  require_kernel_values(n);
  std::vector<Eigen::Vector3d> change(at(n.owned), Eigen::Vector3d::Zero());
  for (int i = 0; i < n.owned; ++i) {
    if (shift[at(i)].isZero()) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for_each_neighbour(n, i, [&](const Pair& p) {
      sum += mass[at(p.j)] / density[at(p.j)] * p.gradient().dot(shift[at(i)]) * (velocity[at(p.j)] - velocity[at(i)]);
    });
    change[at(i)] = sum;
  }
  return change;
}

}  // namespace tankfsi::sph
