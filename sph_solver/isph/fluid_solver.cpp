#include "sph_solver/isph/fluid_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <optional>
#include <utility>

#include "sph_solver/isph/close_pairs.hpp"
#include "sph_solver/isph/free_surface.hpp"
#include "sph_solver/isph/particle_terms.hpp"
#include "sph_solver/isph/wall_crossings.hpp"
#include "sph_solver/neighbours/cell_list.hpp"
#include "sph_solver/neighbours/neighbour_candidates.hpp"

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

double global_max(MPI_Comm comm, double local) {
  double result = 0.0;
  MPI_Allreduce(&local, &result, 1, MPI_DOUBLE, MPI_MAX, comm);
  return result;
}

long long global_sum(MPI_Comm comm, long long local) {
  long long result = 0;
  MPI_Allreduce(&local, &result, 1, MPI_LONG_LONG, MPI_SUM, comm);
  return result;
}

double largest_norm(const std::vector<Eigen::Vector3d>& vectors) {
  double largest = 0.0;
  for (const auto& v : vectors) largest = std::max(largest, v.norm());
  return largest;
}

/// Owned values followed by the ghosts' copies.
template <class T>
std::vector<T> with_ghosts(const Halo& halo, std::vector<T> owned) {
  halo.exchange(owned);
  return owned;
}

/// Every owned and ghost point, its neighbour list and the owned particles' walls.
struct Configuration {
  std::vector<Eigen::Vector3d> position;
  NeighbourList neighbours;
  WallContacts walls;
};

/// The neighbour lists and walls of `positions` from candidates searched elsewhere.
Configuration configuration(const FluidSolver& solver, std::vector<Eigen::Vector3d> positions, int owned,
                            const NeighbourCandidates& pairs, const WallCandidates& walls) {
  Configuration c;
  c.position = std::move(positions);
  c.neighbours = pairs.within_radius(c.position, &solver.kernel());
  c.walls = find_wall_contacts(solver.walls(), std::span(c.position).first(at(owned)), solver.model().dimension, &walls);
  return c;
}

/// The configuration of `positions` by a search of their own.
Configuration configuration(const FluidSolver& solver, std::vector<Eigen::Vector3d> positions, int owned) {
  const NeighbourCandidates pairs(solver.model().dimension, positions, solver.kernel().support_radius(), 0.0, owned);
  const WallCandidates walls = find_wall_candidates(solver.walls(), std::span(positions).first(at(owned)), 0.0);
  return configuration(solver, std::move(positions), owned, pairs, walls);
}

/// One search for a step's two configurations, at x^n and at x~ (owned then ghosts
/// in both): every point moves by at most d between them, so pairs within the
/// support at x~ lie within support + 2 d at x^n, and walls within the cutoff + d.
struct StepSearch {
  NeighbourCandidates pairs;
  WallCandidates walls;
};

StepSearch search_of_step(const FluidSolver& solver, std::span<const Eigen::Vector3d> now,
                          std::span<const Eigen::Vector3d> next, int owned) {
  double largest_move = 0.0;
  for (std::size_t i = 0; i < now.size(); ++i) largest_move = std::max(largest_move, (next[i] - now[i]).norm());
  // A little more than the move: the candidates' check rounds against the skin.
  const double move = largest_move * (1.0 + 1e-9) + 1e-12 * solver.model().spacing;
  return {NeighbourCandidates(solver.model().dimension, now, solver.kernel().support_radius(), 2.0 * move, owned),
          find_wall_candidates(solver.walls(), now.first(at(owned)), move)};
}

/// The particle a failed check names, the same on every rank: of all ranks'
/// offenders, the one with the lowest id; `count` offenders in all.
struct Offender {
  long long count = 0;
  std::int64_t id = -1;
  Eigen::Vector3d from = Eigen::Vector3d::Zero();  ///< position at the step's start
  Eigen::Vector3d to = Eigen::Vector3d::Zero();    ///< position at its end
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  int triangle = -1;
};

/// Collective: `local` is this rank's first offender (id -1: none), `count`
/// how many this rank has.
Offender first_offender(MPI_Comm comm, const Offender& local, long long count) {
  Offender all;
  all.count = global_sum(comm, count);
  if (all.count == 0) return all;
  std::int64_t lowest = local.id >= 0 ? local.id : std::numeric_limits<std::int64_t>::max();
  MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPI_INT64_T, MPI_MIN, comm);
  // The owner of the lowest id fills the buffer, the others add zeros.
  std::array<double, 10> values{};
  if (local.id == lowest) {
    for (int k = 0; k < 3; ++k) {
      values[at(k)] = local.from[k];
      values[at(3 + k)] = local.to[k];
      values[at(6 + k)] = local.velocity[k];
    }
    values[9] = local.triangle;
  }
  MPI_Allreduce(MPI_IN_PLACE, values.data(), 10, MPI_DOUBLE, MPI_SUM, comm);
  all.id = lowest;
  all.from = Eigen::Vector3d(values[0], values[1], values[2]);
  all.to = Eigen::Vector3d(values[3], values[4], values[5]);
  all.velocity = Eigen::Vector3d(values[6], values[7], values[8]);
  all.triangle = static_cast<int>(values[9]);
  return all;
}

std::string point_text(const Eigen::Vector3d& x) {
  std::ostringstream text;
  text << std::setprecision(10) << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return text.str();
}

}  // namespace

FluidSolver::FluidSolver(MPI_Comm comm, const FluidModel& model, TriangleMesh walls, Particles particles,
                         const Eigen::AlignedBox3d& domain, const std::string& ppe_options, StageTimers* timers)
    : comm_(comm),
      model_(model),
      kernel_(model.kernel, model.dimension, model.smoothing_length),
      walls_(std::move(walls), model_, kernel_),
      particles_(std::move(particles)),
      domain_(domain),
      decomposition_(comm, model.dimension),
      ppe_(comm, ppe_options),
      timers_(timers != nullptr ? timers : &fallback_timers_),
      wall_force_(walls_.mesh().vertex_count(), Eigen::Vector3d::Zero()) {
  MPI_Comm_rank(comm_, &rank_);
  int size = 1;
  MPI_Comm_size(comm_, &size);
  // Every rank holds every particle: keep a disjoint share, then balance and migrate.
  std::vector<int> share;
  for (int i = 0; i < particles_.count(); ++i)
    if (particles_.id[at(i)] % size == rank_) share.push_back(i);
  particles_.reorder(share);
  decomposition_.balance(particles_.position);
  decomposition_.migrate(particles_);
  predicted_density_.assign(particles_.size(), std::numeric_limits<double>::quiet_NaN());
  free_surface_flags_ = predicted_density_;
}

StageTimers::Scope FluidSolver::stage(const std::string& name) { return timers_->time(name); }

double FluidSolver::max_speed() const { return global_max(comm_, largest_norm(particles_.velocity)); }

FluidSolver::FastestParticle FluidSolver::fastest_particle() const {
  Offender local;
  double fastest = -1.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const double speed = particles_.velocity[i].norm();
    if (speed > fastest || (speed == fastest && particles_.id[i] < local.id)) {
      fastest = speed;
      local.id = particles_.id[i];
      local.to = particles_.position[i];
      local.velocity = particles_.velocity[i];
    }
  }
  // Only the fastest over all ranks is an offender: the others drop theirs.
  const double largest = global_max(comm_, fastest);
  const bool mine = local.id >= 0 && fastest == largest;
  if (!mine) local.id = -1;
  const Offender all = first_offender(comm_, local, mine ? 1 : 0);
  return {all.id, all.to, all.velocity};
}

double FluidSolver::max_pressure() const {
  double largest = 0.0;
  for (const double p : particles_.pressure) largest = std::max(largest, std::abs(p));
  return global_max(comm_, largest);
}

long long FluidSolver::global_particle_count() const { return global_sum(comm_, particles_.count()); }

std::vector<Eigen::Vector3d> FluidSolver::total_wall_forces() const {
  std::vector<Eigen::Vector3d> total(wall_force_.size());
  MPI_Allreduce(wall_force_.data(), total.data(), static_cast<int>(3 * wall_force_.size()), MPI_DOUBLE, MPI_SUM, comm_);
  return total;
}

void FluidSolver::remove_escaped() {
  std::vector<int> kept;
  kept.reserve(particles_.size());
  long long removed = 0;
  double volume = 0.0;
  for (int i = 0; i < particles_.count(); ++i) {
    const Eigen::Vector3d& x = particles_.position[at(i)];
    if (x.allFinite() && domain_.contains(x)) {
      kept.push_back(i);
    } else {
      ++removed;
      volume += particles_.mass[at(i)] / model_.density;
    }
  }
  if (removed > 0) particles_.reorder(kept);
  // One reduction for the three sums (counts are exact in a double below 2^53).
  std::array<double, 3> sums{static_cast<double>(removed), volume, static_cast<double>(particles_.count())};
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), 3, MPI_DOUBLE, MPI_SUM, comm_);
  removed_this_step_ = static_cast<long long>(sums[0]);
  removed_count_ += removed_this_step_;
  removed_volume_ += sums[1];
  particles_after_removal_ = static_cast<long long>(sums[2]);
}

void FluidSolver::rebalance() {
  decomposition_.balance(particles_.position);
  decomposition_.migrate(particles_);
  CellList cells(model_.dimension);
  cells.build(particles_.position, kernel_.support_radius());
  particles_.reorder(cells.cell_order());
}

void FluidSolver::redistribute() {
  if (steps_ % rebalance_interval == 0) {
    rebalance();
  } else {
    decomposition_.migrate(particles_);
  }
}

void FluidSolver::resume(const Checkpoint& state, const std::optional<std::vector<double>>& cuts) {
  restore(state);
  if (cuts) {
    decomposition_.restore_cuts(*cuts);  // none on one rank: the particles stay in their order
  } else {
    rebalance();
  }
  predicted_density_.assign(particles_.size(), std::numeric_limits<double>::quiet_NaN());
  free_surface_flags_ = predicted_density_;
}

std::vector<Eigen::Vector3d> FluidSolver::present_wall_forces(const Eigen::Vector3d& ground_acceleration) {
  // The particles stay as they are (balanced and migrated since construction
  // or the last step); only the halo is built, as every step rebuilds it.
  halo_.build(comm_, decomposition_, particles_.position, kernel_.support_radius() + 0.5 * model_.spacing);
  const int owned = particles_.count();
  const auto mass = with_ghosts(halo_, particles_.mass);
  const auto velocity = with_ghosts(halo_, particles_.velocity);
  auto pressure = particles_.pressure;
  halo_.exchange(pressure);
  const Configuration now = configuration(*this, with_ghosts(halo_, particles_.position), owned);
  Neighbourhood n{kernel_, model_, now.position, now.neighbours, now.walls, walls_.mesh(), owned};
  // Read against the lattice as in a step (completed_density()); no air here.
  const auto kernel_sum = with_ghosts(halo_, kernel_density(n, mass));
  const auto density = with_ghosts(
      halo_, density_against_lattice(kernel_sum, model_.density * walls_.table().lattice_share(), model_.density));
  // The moments as a step divides by (without the air, the surface's particles
  // take their neighbours').
  const auto scale = moment_scales(n, mass, density, with_ghosts(halo_, detect_free_surface(n, mass, kernel_sum)));
  n.moment_scale = scale;
  // The walls' Neumann pressure gradient rho (v* - v_w) . n / dt of the liquid
  // at rest, v* = dt F on resting walls: rho F . n whatever dt.
  const double dt = 1.0;
  const std::vector<Eigen::Vector3d> predicted(at(owned), dt * model_.body_force(ground_acceleration));
  std::vector<Eigen::Vector3d> forces(walls_.mesh().vertex_count(), Eigen::Vector3d::Zero());
  // Only the walls' reactions are wanted, not the particles' accelerations.
  static_cast<void>(viscous_acceleration(n, mass, density, velocity, forces));
  const std::vector<Eigen::Vector3d> acceleration(at(owned), model_.body_force(ground_acceleration));
  static_cast<void>(pressure_acceleration(n, mass, density, pressure, predicted, acceleration, dt, forces));
  return forces;
}

std::vector<double> FluidSolver::added_mass_operator(std::span<const int> vertices,
                                                     std::span<const Eigen::Vector3d> normals) {
  if (vertices.size() != normals.size())
    throw std::invalid_argument("added_mass_operator: " + std::to_string(normals.size()) + " normals for " +
                                std::to_string(vertices.size()) + " vertices");
  const std::size_t count = vertices.size();
  halo_.build(comm_, decomposition_, particles_.position, kernel_.support_radius() + 0.5 * model_.spacing);
  const int owned = particles_.count();
  const auto mass = with_ghosts(halo_, particles_.mass);
  const auto index = with_ghosts(halo_, global_indices());
  Configuration now = configuration(*this, with_ghosts(halo_, particles_.position), owned);
  // The walls at rest; each column sets the velocity of the contacts on one vertex's triangles.
  WallContacts& contacts = now.walls;
  for (WallContact& c : contacts.contacts) c.velocity.setZero();
  std::vector<int> column_of_vertex(walls_.mesh().vertex_count(), -1);
  for (std::size_t j = 0; j < count; ++j) column_of_vertex[at(vertices[j])] = static_cast<int>(j);
  struct Touch {
    int contact;
    double weight;  ///< the vertex's barycentric weight at the contact's closest point
  };
  std::vector<std::vector<Touch>> touching(count);
  for (int i = 0; i < owned; ++i)
    for (int c = contacts.offsets[at(i)]; c < contacts.offsets[at(i) + 1]; ++c)
      for_each_vertex_share(walls_.mesh(), contacts.contacts[at(c)], [&](int vertex, double share) {
        if (const int j = column_of_vertex[at(vertex)]; j >= 0) touching[at(j)].push_back({c, share});
      });
  Neighbourhood n{kernel_, model_, now.position, now.neighbours, contacts, walls_.mesh(), owned};
  const auto kernel_sum = with_ghosts(halo_, kernel_density(n, mass));
  const auto free_surface = with_ghosts(halo_, detect_free_surface(n, mass, kernel_sum));
  const std::vector<SurfaceContact> air = surface_contacts(n, mass, kernel_sum, walls_);
  n.surface = air;
  const auto density =
      with_ghosts(halo_, completed_density(kernel_sum, air, model_.density * walls_.table().lattice_share(),
                                           model_.density));
  const auto scale = moment_scales(n, mass, density, free_surface);
  n.moment_scale = scale;
  ppe_.assemble(n, mass, density, index, std::vector<unsigned char>(mass.size(), 0));
  std::vector<double> matrix(count * count, 0.0);
  std::vector<double> pressure;
  for (std::size_t j = 0; j < count; ++j) {
    for (const Touch& t : touching[j]) contacts.contacts[at(t.contact)].velocity += t.weight * normals[j];
    const auto impulse = wall_motion_impulse(n, mass, density, pressure);
    // The liquid pushes back against the motion: A_ij = -impulse_i . n_i.
    for (std::size_t i = 0; i < count; ++i) matrix[i * count + j] = -impulse[at(vertices[i])].dot(normals[i]);
    for (const Touch& t : touching[j]) contacts.contacts[at(t.contact)].velocity.setZero();
  }
  return matrix;
}

std::vector<Eigen::Vector3d> FluidSolver::wall_motion_impulse(const Neighbourhood& n, std::span<const double> mass,
                                                             std::span<const double> density,
                                                             std::vector<double>& pressure,
                                                             double residual_floor) {
  // With dt = 1 and v* = 0 the projection's pressure is the pressure impulse
  // and the walls' reaction (force times dt) the impulse on each vertex.
  const double dt = 1.0;
  const std::vector<Eigen::Vector3d> at_rest(at(n.owned), Eigen::Vector3d::Zero());
  std::vector<double> source(at(n.owned));
  for (int i = 0; i < n.owned; ++i) source[at(i)] = -wall_laplacian_share(n, i, at_rest[0], at_rest[0], dt);
  pressure.assign(at(n.owned), 0.0);
  ppe_.solve_assembled(source, pressure, residual_floor);
  halo_.exchange(pressure);
  std::vector<Eigen::Vector3d> impulse(walls_.mesh().vertex_count(), Eigen::Vector3d::Zero());
  static_cast<void>(pressure_acceleration(n, mass, density, pressure, at_rest, at_rest, dt, impulse));
  return impulse;
}

std::vector<double> FluidSolver::moment_scales(const Neighbourhood& n, std::span<const double> mass,
                                               std::span<const double> density,
                                               std::span<const unsigned char> free_surface) {
  const auto known = with_ghosts(halo_, moment_scale(n, mass, density, free_surface));
  return with_ghosts(halo_, smoothed_moment_scale(n, known));
}

std::vector<std::int64_t> FluidSolver::global_indices() const {
  long long offset = 0;
  const long long count = particles_.count();
  MPI_Exscan(&count, &offset, 1, MPI_LONG_LONG, MPI_SUM, comm_);
  if (rank_ == 0) offset = 0;  // MPI_Exscan leaves rank 0's result undefined
  std::vector<std::int64_t> index(at(particles_.count()));
  for (int i = 0; i < particles_.count(); ++i) index[at(i)] = offset + i;
  return index;
}

StepReport FluidSolver::step(double t, double dt, const Eigen::Vector3d& ground_acceleration) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("FluidSolver::step: dt must be positive");
  StepReport report;
  report.time_step = dt;
  const Eigen::Vector3d body_force = model_.body_force(ground_acceleration);
  const double rho0 = model_.density;
  // The kernel-sum density of the initial lattice (1 - 6e-5 of rho0 for the quintic
  // spline at h = 1.2 L0): what the discretisation reads as rho0.
  const double rest_density = rho0 * walls_.table().lattice_share();
  check_finite(t);  // what the step starts from (restored, moved, or the last step's result)
  const double speed_before = max_speed();
  {
    auto scope = stage("neighbours");
    remove_escaped();
    redistribute();
    // Ghosts must cover every neighbour at x~ too: the support plus twice the
    // largest displacement of the step (two particles approaching each other).
    const double margin = std::max(0.5 * model_.spacing, 2.5 * dt * (speed_before + dt * body_force.norm()));
    halo_.build(comm_, decomposition_, particles_.position, kernel_.support_radius() + margin);
  }
  const int owned = particles_.count();
  const std::vector<Eigen::Vector3d> start = particles_.position;  // for the wall-crossing check
  std::fill(wall_force_.begin(), wall_force_.end(), Eigen::Vector3d::Zero());
  const std::vector<std::int64_t> global_index = global_indices();
  const auto mass = with_ghosts(halo_, particles_.mass);
  const auto velocity_n = with_ghosts(halo_, particles_.velocity);
  const auto index = with_ghosts(halo_, global_index);

  // 1. Predictor at x^n; the PPE's positions x~ = x^n + dt v^n (fluid_solver.hpp).
  std::vector<Eigen::Vector3d> x_star(at(owned));
  std::vector<Eigen::Vector3d> v_star(at(owned));
  std::vector<Eigen::Vector3d> a_star(at(owned));  // (v* - v^n) / dt
  for (int i = 0; i < owned; ++i) x_star[at(i)] = particles_.position[at(i)] + dt * velocity_n[at(i)];
  std::vector<double> density_now;  // kernel sums at x^n
  std::vector<Eigen::Vector3d> x_star_all;  // owned and ghosts
  std::optional<StepSearch> search;         // for both configurations, at x^n and at x~
  Configuration now;
  {
    auto scope = stage("neighbours");
    auto x_now_all = with_ghosts(halo_, particles_.position);
    x_star_all = with_ghosts(halo_, x_star);
    search.emplace(search_of_step(*this, x_now_all, x_star_all, owned));
    now = configuration(*this, std::move(x_now_all), owned, search->pairs, search->walls);
  }
  {
    auto scope = stage("predictor");
    const Neighbourhood n{kernel_, model_, now.position, now.neighbours, now.walls, walls_.mesh(), owned};
    const auto density = with_ghosts(halo_, kernel_density(n, mass));
    density_now.assign(density.begin(), density.begin() + owned);
    const auto viscous = viscous_acceleration(n, mass, density, velocity_n, wall_force_);
    for (int i = 0; i < owned; ++i) {
      a_star[at(i)] = viscous[at(i)] + body_force;
      if (model_.dimension == 2) a_star[at(i)].z() = 0.0;
      v_star[at(i)] = velocity_n[at(i)] + dt * a_star[at(i)];
    }
  }

  // 2. Pressure Poisson equation at x~.
  Configuration next;
  {
    auto scope = stage("neighbours");
    next = configuration(*this, std::move(x_star_all), owned, search->pairs, search->walls);
    search.reset();
  }
  Neighbourhood n{kernel_, model_, next.position, next.neighbours, next.walls, walls_.mesh(), owned};
  std::vector<double> density;
  std::vector<unsigned char> free_surface;
  std::vector<SurfaceContact> air;
  std::vector<double> scale;
  std::vector<double> source(at(owned));
  {
    auto scope = stage("ppe_assemble");
    const auto kernel_sum = with_ghosts(halo_, kernel_density(n, mass));
    free_surface = with_ghosts(halo_, detect_free_surface(n, mass, kernel_sum));
    double max_error = 0.0;
    long long surface = 0;
    for (int i = 0; i < owned; ++i) {
      surface += free_surface[at(i)];
      if (free_surface[at(i)] == 0) max_error = std::max(max_error, std::abs(kernel_sum[at(i)] - rest_density) / rho0);
    }
    report.free_surface_particles = global_sum(comm_, surface);
    report.max_density_error = global_max(comm_, max_error);
    // The air beyond the free surface completes the kernel support of the particles
    // near it (free_surface.hpp): from here on their density is the rest density.
    air = surface_contacts(n, mass, kernel_sum, walls_);
    n.surface = air;
    density = with_ghosts(halo_, completed_density(kernel_sum, air, rest_density, rho0));
    scale = moment_scales(n, mass, density, free_surface);
    n.moment_scale = scale;
    predicted_density_.assign(kernel_sum.begin(), kernel_sum.begin() + owned);
    const auto v_all = with_ghosts(halo_, v_star);
    const auto divergence = velocity_divergence(n, mass, density, v_all);
    for (int i = 0; i < owned; ++i) {
      const double wall_share = wall_laplacian_share(n, i, v_star[at(i)], a_star[at(i)], dt);
      // The density error of the state x^n, against the rest density of the lattice;
      // the air completes it near the free surface. (At the PPE's positions the
      // density would hold the step's own compression too, which the divergence term
      // and the walls' Neumann share already remove.)
      const double error = rest_density - (air[at(i)].active ? rest_density : density_now[at(i)]);
      source[at(i)] = rho0 / dt * divergence[at(i)] + model_.density_error_weight * error / (dt * dt) - wall_share;
    }
  }
  // Every particle is an unknown: the free surface enters through the air's share.
  const std::vector<unsigned char> dirichlet(free_surface.size(), 0);
  std::vector<double> pressure = particles_.pressure;
  {
    auto scope = stage("ppe_solve");
    try {
      const auto solved = ppe_.solve(n, mass, density, index, dirichlet, source, pressure, particles_.id);
      report.ppe_iterations = solved.iterations;
      report.ppe_residual = solved.residual_norm;
      report.ppe_twin_failed = solved.twin_failed;
      report.ppe_hierarchy_built = solved.hierarchy_built;
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(step_prefix(t) + e.what());
    }
  }

  // The walls' velocity jump's share of the step (set_wall_velocity_jump()).
  jump_impulse_.clear();
  if (!wall_velocity_jump_.empty()) {
    auto scope = stage("wall_jump");
    const TriangleMesh& mesh = walls_.mesh();
    WallContacts jumped = next.walls;
    for (WallContact& c : jumped.contacts) c.velocity = at_contact(mesh, wall_velocity_jump_, c);
    Neighbourhood moved{kernel_, model_, next.position, next.neighbours, jumped, mesh, owned, n.surface, scale};
    std::vector<double> jump_pressure;
    try {
      // The step's pressure holds the jump's (p = impulse / dt): solving the
      // jump's part to a lower residual than the whole's buys nothing.
      jump_impulse_ = wall_motion_impulse(moved, mass, density, jump_pressure, report.ppe_residual * dt);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(step_prefix(t) + "the walls' velocity jump: " + e.what());
    }
    wall_velocity_jump_.clear();
  }

  // 3. Corrector and positions; 4. shifting.
  {
    auto scope = stage("corrector");
    halo_.exchange(pressure);
    const auto pressure_term = pressure_acceleration(n, mass, density, pressure, v_star, a_star, dt, wall_force_);
    std::vector<Eigen::Vector3d> v_new(at(owned));
    for (int i = 0; i < owned; ++i) {
      v_new[at(i)] = v_star[at(i)] + dt * pressure_term[at(i)];
      if (model_.dimension == 2) v_new[at(i)].z() = 0.0;
      particles_.position[at(i)] += 0.5 * dt * (particles_.velocity[at(i)] + v_new[at(i)]);
      particles_.pressure[at(i)] = pressure[at(i)];
    }
    if (model_.shifting) {
      const double speed = global_max(comm_, largest_norm(v_new));
      const double diffusion = model_.shifting_diffusion(speed, dt);
      const double cap = 0.2 * model_.spacing;
      const auto gradient = concentration_gradient(n, mass, density);
      std::vector<Eigen::Vector3d> shift(at(owned), Eigen::Vector3d::Zero());
      for (int i = 0; i < owned; ++i) {
        // Lind et al. (2012) shift particles at the surface only along it; with the
        // surface normal taken from grad C itself that tangential part is zero, so
        // they are not shifted at all — a normal shift would pack the layers under
        // the surface into it until the surface particles no longer count as
        // surface (rho* >= beta rho0).
        if (near_free_surface(n, free_surface, i)) continue;
        Eigen::Vector3d dr = -diffusion * gradient[at(i)];
        if (model_.dimension == 2) dr.z() = 0.0;
        const double length = dr.norm();
        shift[at(i)] = length > cap ? dr * (cap / length) : dr;
      }
      if (model_.close_pair_distance > 0.0) {
        // 4b. Pairs that the shift leaves closer than the distance, at the step's
        // end positions (close_pairs.hpp).
        std::vector<Eigen::Vector3d> shifted(at(owned));
        for (int i = 0; i < owned; ++i) shifted[at(i)] = particles_.position[at(i)] + shift[at(i)];
        const auto parting = close_pair_parting(n.neighbours, with_ghosts(halo_, std::move(shifted)),
                                                with_ghosts(halo_, particles_.id),
                                                owned, model_.close_pair_distance * model_.spacing);
        for (int i = 0; i < owned; ++i) shift[at(i)] += parting[at(i)];  // in 2D in the plane, as the positions are
      }
      const auto v_all = with_ghosts(halo_, v_new);
      const auto change = velocity_change_over_shift(n, mass, density, v_all, shift);
      for (int i = 0; i < owned; ++i) {
        particles_.position[at(i)] += shift[at(i)];
        v_new[at(i)] += change[at(i)];
      }
    }
    particles_.velocity = std::move(v_new);
  }
  const WallCrossings crossings = return_to_walls(walls_, model_.dimension, start, particles_.position,
                                                  particles_.velocity);
  report.wall_returned_particles = global_sum(comm_, crossings.returned);
  free_surface_flags_.assign(free_surface.begin(), free_surface.begin() + owned);
  report.removed_particles = removed_this_step_;
  report.particles = particles_after_removal_;
  report.max_speed = max_speed();
  report.max_pressure = max_pressure();
  {
    auto scope = stage("checks");
    check_finite(t);
    check_crossings(crossings, start, t);
  }
  ++steps_;
  return report;
}

std::string FluidSolver::step_prefix(double t) const {
  std::ostringstream text;
  text << "step " << steps_ + 1 << " at t = " << t << " s: ";
  return text.str();
}

void FluidSolver::check_finite(double t) const {
  Offender local;
  long long count = 0;
  for (int i = 0; i < particles_.count(); ++i) {
    const bool finite = particles_.position[at(i)].allFinite() && particles_.velocity[at(i)].allFinite() &&
                        std::isfinite(particles_.pressure[at(i)]);
    if (finite) continue;
    if (count++ == 0) local = {0, particles_.id[at(i)], particles_.position[at(i)], particles_.position[at(i)], particles_.velocity[at(i)], -1};
  }
  if (const Offender bad = first_offender(comm_, local, count); bad.count > 0)
    throw std::runtime_error(step_prefix(t) + std::to_string(bad.count) +
                             " particle(s) with a non-finite position, velocity or pressure; the first, id " +
                             std::to_string(bad.id) + ", at " + point_text(bad.to) + " with velocity " +
                             point_text(bad.velocity));
}

void FluidSolver::check_crossings(const WallCrossings& crossings, const std::vector<Eigen::Vector3d>& start,
                                  double t) const {
  // A path through a wall (the walls at the step's end) that return_to_walls()
  // left: the liquid has left the tank where no overflow can happen.
  Offender local;
  const auto count = static_cast<long long>(crossings.through.size());
  if (count > 0) {
    const auto [i, triangle] = crossings.through.front();
    local = {0, particles_.id[at(i)], start[at(i)], particles_.position[at(i)], particles_.velocity[at(i)], triangle};
  }
  if (const Offender bad = first_offender(comm_, local, count); bad.count > 0)
    throw std::runtime_error(step_prefix(t) + std::to_string(bad.count) + " particle(s) crossed a wall; the first, id " +
                             std::to_string(bad.id) + ", went from " + point_text(bad.from) + " to " +
                             point_text(bad.to) + " through wall triangle " + std::to_string(bad.triangle) +
                             " (speed " + std::to_string(bad.velocity.norm()) +
                             " m/s): the step is too long for the liquid's speed or the wall's motion");
}

}  // namespace tankfsi::sph
