#include "fem_solver/analysis/corotational_newmark.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fem_solver/analysis/optional_stage.hpp"

namespace tankfsi::fem {
namespace {

constexpr double newton_tolerance = 1e-8;  ///< |r| relative to the largest term of the equation
constexpr int newton_limit = 30;

double norm_of(Vec x) {
  PetscReal n = 0.0;
  petsc_check(VecNorm(x, NORM_2, &n), "VecNorm");
  return n;
}

}  // namespace

CorotationalNewmark::CorotationalNewmark(StructureSystem& system, RayleighCoefficients damping,
                                         TimeIntegrationRule rule)
    : system_(system),
      assembler_(system.assembler()),
      forces_(system),
      damping_(damping),
      rule_(rule),
      m_(system.mass()),
      tangent_(forces_.create_tangent()) {
  for (PetscVector* v : {&u_, &v_, &a_, &g_, &load_, &increment_, &delta_, &v_new_, &a_new_, &g_new_, &residual_, &work_})
    petsc_check(VecDuplicate(m_, v->out()), "VecDuplicate");
  for (PetscVector* v : {&u_, &v_, &a_, &g_, &load_}) petsc_check(VecSet(v->get(), 0.0), "VecSet");
  nodal_u_ = assembler_.gather(u_.get(), 1.0);  // the prescribed values of constrained DOFs
}

void CorotationalNewmark::set_displacement(const NodalValues& nodal) {
  nodal_u_ = nodal;
  assembler_.scatter(nodal_u_, u_.get());
}

void CorotationalNewmark::evaluate(const NodalValues& nodal, Vec velocity, bool with_tangent,
                                   CorotationalElement::Tangent kind) {
  if (damping_.beta != 0.0) assembler_.gather(velocity, 0.0, nodal_velocity_);
  forces_.evaluate(nodal, nodal_velocity_, damping_.beta, g_new_.get(), with_tangent ? tangent_.get() : nullptr, kind);
}

bool CorotationalNewmark::converged(int iteration, double residual, double scale) const {
  const double tolerance = std::max(newton_tolerance * scale, forces_.force_resolution());
  if (residual <= tolerance) return true;
  if (iteration < newton_limit) return false;
  std::ostringstream out;
  out << "Newton's method did not converge in " << iteration << " iterations (residual " << residual
      << " N against a tolerance of " << tolerance << " N)";
  throw std::runtime_error(out.str());
}

void CorotationalNewmark::solve(Mat matrix, Vec rhs, Vec increment) {
  petsc_check(MatSetOption(matrix, MAT_SPD, PETSC_TRUE), "MatSetOption");
  const auto solver = system_.make_solver(matrix);
  ++factorisations_;
  solver->solve(rhs, increment);
}

void CorotationalNewmark::initialise(Vec displacement, Vec velocity, Vec load) {
  if (displacement != u_.get()) {
    petsc_check(VecCopy(displacement, u_.get()), "VecCopy");
    assembler_.gather(u_.get(), 1.0, nodal_u_);
  }
  if (velocity != v_.get()) petsc_check(VecCopy(velocity, v_.get()), "VecCopy");
  if (load != load_.get()) petsc_check(VecCopy(load, load_.get()), "VecCopy");
  // a = M^-1 (F - g - alpha M v)
  evaluate(nodal_u_, v_.get(), false);
  strain_energy_ = forces_.strain_energy();
  petsc_check(VecCopy(g_new_.get(), g_.get()), "VecCopy");
  petsc_check(VecWAXPY(work_.get(), -1.0, g_.get(), load_.get()), "VecWAXPY");
  petsc_check(VecPointwiseDivide(a_.get(), work_.get(), m_), "VecPointwiseDivide");
  petsc_check(VecAXPY(a_.get(), -damping_.alpha, v_.get()), "VecAXPY");
}

void CorotationalNewmark::set_load(Vec load) { initialise(u_.get(), v_.get(), load); }

void CorotationalNewmark::set_added_mass(Mat, Mat, std::unique_ptr<LinearSolve>) {
  throw std::invalid_argument("an added mass is not available with co-rotational (large-rotation) kinematics");
}

void CorotationalNewmark::prepare(double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("Newmark step needs dt > 0");
}

void CorotationalNewmark::step(double dt, Vec load) {
  prepare(dt);
  const double gamma = rule_.gamma;
  const double am = rule_.alpha_m;
  const double af = rule_.alpha_f;
  const auto [a0, a1, a2, a3, a4, a5] = rule_.step_coefficients(dt);
  (void)a4, (void)a5;  // the velocity's update below uses gamma directly
  const double alpha = damping_.alpha;
  // Predictor: the acceleration held, D = dt v + dt^2/2 a.
  petsc_check(VecAXPBYPCZ(increment_.get(), dt, 0.5 * dt * dt, 0.0, v_.get(), a_.get()), "VecAXPBYPCZ");
  int iteration = 0;
  double residual = 0.0;
  double scale = 0.0;
  for (;; ++iteration) {
    // a_new = a0 D - a2 v - a3 a;  v_new = v + dt ((1 - gamma) a + gamma a_new)
    petsc_check(VecAXPBYPCZ(a_new_.get(), -a2, -a3, 0.0, v_.get(), a_.get()), "VecAXPBYPCZ");
    petsc_check(VecAXPY(a_new_.get(), a0, increment_.get()), "VecAXPY");
    petsc_check(VecCopy(v_.get(), v_new_.get()), "VecCopy");
    petsc_check(VecAXPBYPCZ(v_new_.get(), dt * (1.0 - gamma), dt * gamma, 1.0, a_.get(), a_new_.get()), "VecAXPBYPCZ");
    assembler_.gather(increment_.get(), 0.0, nodal_increment_);
    CorotationalForces::compose(nodal_u_, nodal_increment_, nodal_new_);
    evaluate(nodal_new_, v_new_.get(), true);
    // r = F_{n+1-af} - g_{n+1-af} - M (a_{n+1-am} + alpha v_{n+1-af}); its terms' sizes give the scale.
    petsc_check(VecAXPBYPCZ(residual_.get(), 1.0 - af, af, 0.0, load, load_.get()), "VecAXPBYPCZ");
    scale = norm_of(residual_.get());
    petsc_check(VecAXPBYPCZ(work_.get(), 1.0 - af, af, 0.0, g_new_.get(), g_.get()), "VecAXPBYPCZ");
    scale = std::max(scale, norm_of(work_.get()));
    petsc_check(VecAXPY(residual_.get(), -1.0, work_.get()), "VecAXPY");
    petsc_check(VecAXPBYPCZ(work_.get(), 1.0 - am, am, 0.0, a_new_.get(), a_.get()), "VecAXPBYPCZ");
    petsc_check(VecAXPBYPCZ(work_.get(), alpha * (1.0 - af), alpha * af, 1.0, v_new_.get(), v_.get()), "VecAXPBYPCZ");
    petsc_check(VecPointwiseMult(work_.get(), m_, work_.get()), "VecPointwiseMult");
    scale = std::max(scale, norm_of(work_.get()));
    petsc_check(VecAXPY(residual_.get(), -1.0, work_.get()), "VecAXPY");
    residual = norm_of(residual_.get());
    if (!std::isfinite(residual)) throw std::runtime_error("the co-rotational Newmark step gave a non-finite residual");
    if (converged(iteration, residual, scale)) break;
    // K_eff = (1 - af)(1 + a1 beta_R) K_t + ((1 - am) a0 + (1 - af) a1 alpha) M
    petsc_check(MatScale(tangent_.get(), (1.0 - af) * (1.0 + a1 * damping_.beta)), "MatScale");
    petsc_check(VecCopy(m_, work_.get()), "VecCopy");
    petsc_check(VecScale(work_.get(), (1.0 - am) * a0 + (1.0 - af) * a1 * alpha), "VecScale");
    petsc_check(MatDiagonalSet(tangent_.get(), work_.get(), ADD_VALUES), "MatDiagonalSet");
    solve(tangent_.get(), residual_.get(), delta_.get());
    petsc_check(VecAXPY(increment_.get(), 1.0, delta_.get()), "VecAXPY");
  }
  iterations_ += iteration;
  most_iterations_ = std::max(most_iterations_, iteration);
  strain_energy_ = forces_.strain_energy();
  set_displacement(nodal_new_);
  std::swap(v_, v_new_);
  std::swap(a_, a_new_);
  std::swap(g_, g_new_);
  if (load != load_.get()) petsc_check(VecCopy(load, load_.get()), "VecCopy");
}

int CorotationalNewmark::equilibrate(Vec load) {
  petsc_check(VecSet(increment_.get(), 0.0), "VecSet");
  petsc_check(VecSet(v_new_.get(), 0.0), "VecSet");
  int iteration = 0;
  for (;; ++iteration) {
    assembler_.gather(increment_.get(), 0.0, nodal_increment_);
    CorotationalForces::compose(nodal_u_, nodal_increment_, nodal_new_);
    evaluate(nodal_new_, v_new_.get(), true, CorotationalElement::Tangent::full);
    petsc_check(VecWAXPY(residual_.get(), -1.0, g_new_.get(), load), "VecWAXPY");
    const double scale = std::max(norm_of(load), norm_of(g_new_.get()));
    const double residual = norm_of(residual_.get());
    if (!std::isfinite(residual)) throw std::runtime_error("the co-rotational equilibrium gave a non-finite residual");
    if (converged(iteration, residual, scale)) break;
    solve(tangent_.get(), residual_.get(), delta_.get());
    petsc_check(VecAXPY(increment_.get(), 1.0, delta_.get()), "VecAXPY");
  }
  strain_energy_ = forces_.strain_energy();
  set_displacement(nodal_new_);
  petsc_check(VecSet(v_.get(), 0.0), "VecSet");
  petsc_check(VecSet(a_.get(), 0.0), "VecSet");
  std::swap(g_, g_new_);
  if (load != load_.get()) petsc_check(VecCopy(load, load_.get()), "VecCopy");
  return iteration;
}

void CorotationalNewmark::save(NewmarkState& state) const {
  const std::pair<const PetscVector*, PetscVector*> pairs[] = {
      {&u_, &state.u}, {&v_, &state.v}, {&a_, &state.a}, {&g_, &state.ku}, {&load_, &state.f}};
  for (const auto& [from, to] : pairs) {
    if (!*to) petsc_check(VecDuplicate(from->get(), to->out()), "VecDuplicate");
    petsc_check(VecCopy(from->get(), to->get()), "VecCopy");
  }
  for (PetscVector* unused : {&state.kv, &state.ka}) {
    if (!*unused) petsc_check(VecDuplicate(m_, unused->out()), "VecDuplicate");
    petsc_check(VecSet(unused->get(), 0.0), "VecSet");
  }
}

void CorotationalNewmark::restore(const NewmarkState& state) {
  const std::pair<const PetscVector*, PetscVector*> pairs[] = {
      {&state.u, &u_}, {&state.v, &v_}, {&state.a, &a_}, {&state.ku, &g_}, {&state.f, &load_}};
  for (const auto& [from, to] : pairs) {
    if (!*from) throw std::logic_error("CorotationalNewmark::restore: no state saved");
    petsc_check(VecCopy(from->get(), to->get()), "VecCopy");
  }
  assembler_.gather(u_.get(), 1.0, nodal_u_);
  evaluate(nodal_u_, v_.get(), false);
  strain_energy_ = forces_.strain_energy();
}

double CorotationalNewmark::energy() const {
  PetscScalar kinetic = 0.0;
  petsc_check(VecPointwiseMult(work_.get(), m_, v_.get()), "VecPointwiseMult");
  petsc_check(VecDot(work_.get(), v_.get(), &kinetic), "VecDot");
  return 0.5 * kinetic + strain_energy_;
}

NodalValues CorotationalNewmark::support_forces() {
  evaluate(nodal_u_, v_.get(), false);
  return forces_.reactions();
}

}  // namespace tankfsi::fem
