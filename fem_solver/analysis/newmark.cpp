#include "fem_solver/analysis/newmark.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace tankfsi::fem {

TimeIntegrationRule TimeIntegrationRule::generalized_alpha(double spectral_radius) {
  if (!(spectral_radius >= 0.0 && spectral_radius <= 1.0))
    throw std::invalid_argument("the generalized-alpha spectral radius must lie in [0, 1]");
  if (spectral_radius == 1.0) return average_acceleration();
  const double rho = spectral_radius;
  TimeIntegrationRule rule;
  rule.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
  rule.alpha_f = rho / (rho + 1.0);
  rule.gamma = 0.5 - rule.alpha_m + rule.alpha_f;
  rule.beta = 0.25 * (1.0 - rule.alpha_m + rule.alpha_f) * (1.0 - rule.alpha_m + rule.alpha_f);
  return rule;
}

NewmarkIntegrator::NewmarkIntegrator(Mat stiffness, Vec mass_diagonal, RayleighCoefficients damping,
                                     SolverFactory factory, TimeIntegrationRule rule)
    : k_(stiffness), m_(mass_diagonal), damping_(damping), rule_(rule), factory_(std::move(factory)) {
  for (PetscVector* v :
       {&u_, &v_, &a_, &rhs_, &work_, &work2_, &a_new_, &u_new_, &ku_, &kv_, &ka_, &ka_new_, &load_})
    petsc_check(VecDuplicate(m_, v->out()), "VecDuplicate");
  for (PetscVector* v : {&u_, &v_, &a_, &ku_, &kv_, &ka_, &load_}) petsc_check(VecSet(v->get(), 0.0), "VecSet");
}

void NewmarkIntegrator::damping_times(Vec x, Vec out) const {
  // C x = alpha M x + beta K x
  petsc_check(MatMult(k_, x, out), "MatMult");
  petsc_check(VecScale(out, damping_.beta), "VecScale");
  petsc_check(VecPointwiseMult(work2_.get(), m_, x), "VecPointwiseMult");
  petsc_check(VecAXPY(out, damping_.alpha, work2_.get()), "VecAXPY");
}

void NewmarkIntegrator::initialise(Vec displacement, Vec velocity, Vec load) {
  if (displacement != u_.get()) petsc_check(VecCopy(displacement, u_.get()), "VecCopy");
  if (velocity != v_.get()) petsc_check(VecCopy(velocity, v_.get()), "VecCopy");
  if (load != load_.get()) petsc_check(VecCopy(load, load_.get()), "VecCopy");
  // a = M^-1 (F - K u - C v)
  petsc_check(MatMult(k_, u_.get(), ku_.get()), "MatMult");
  petsc_check(VecWAXPY(rhs_.get(), -1.0, ku_.get(), load), "VecWAXPY");
  damping_times(v_.get(), work_.get());
  petsc_check(VecAXPY(rhs_.get(), -1.0, work_.get()), "VecAXPY");
  solve_inertia();
  // The products the steps carry along (see the header).
  petsc_check(MatMult(k_, v_.get(), kv_.get()), "MatMult");
  petsc_check(MatMult(k_, a_.get(), ka_.get()), "MatMult");
}

void NewmarkIntegrator::set_load(Vec load) {
  if (!carries_k_products()) {
    initialise(u_.get(), v_.get(), load);
    return;
  }
  if (load != load_.get()) petsc_check(VecCopy(load, load_.get()), "VecCopy");
  // a = (M + M_a)^-1 (F - K u - alpha M v - beta_R K v), K u and K v as carried.
  petsc_check(VecPointwiseMult(work_.get(), m_, v_.get()), "VecPointwiseMult");
  petsc_check(VecWAXPY(rhs_.get(), -1.0, ku_.get(), load), "VecWAXPY");
  const PetscScalar weights[2] = {-damping_.alpha, -damping_.beta};
  Vec terms[2] = {work_.get(), kv_.get()};
  petsc_check(VecMAXPY(rhs_.get(), 2, weights, terms), "VecMAXPY");
  solve_inertia();
  petsc_check(MatMult(k_, a_.get(), ka_.get()), "MatMult");
}

void NewmarkIntegrator::solve_inertia() {
  if (inertia_)
    inertia_->solve(rhs_.get(), a_.get());
  else
    petsc_check(VecPointwiseDivide(a_.get(), rhs_.get(), m_), "VecPointwiseDivide");
}

bool NewmarkIntegrator::carries_k_products() const { return damping_.beta != 0.0 || rule_.alpha_f != 0.0; }

void NewmarkIntegrator::set_added_mass(Mat added_mass, Mat product, std::unique_ptr<LinearSolve> inertia) {
  added_mass_ = added_mass;
  added_mass_product_ = product != nullptr ? product : added_mass;
  inertia_ = std::move(inertia);
  inertia_matrix_.reset();
  if (added_mass_ == nullptr) inertia_.reset();
  if (added_mass_ != nullptr && !inertia_) {
    petsc_check(MatDuplicate(added_mass_, MAT_COPY_VALUES, inertia_matrix_.out()), "MatDuplicate");
    petsc_check(MatDiagonalSet(inertia_matrix_.get(), m_, ADD_VALUES), "MatDiagonalSet");
    petsc_check(MatSetOption(inertia_matrix_.get(), MAT_SPD, PETSC_TRUE), "MatSetOption");
    inertia_ = factory_(inertia_matrix_.get());
  }
  solver_.reset();  // K_eff changes: factorised again at the next step
}

void NewmarkIntegrator::factorise(double dt) {
  const double gamma = rule_.gamma;
  const double beta = rule_.beta;
  // c_m a0: the inertia's share of K_eff after dividing by (1 - alpha_f) (see the header).
  const double a0 = (1.0 - rule_.alpha_m) / (1.0 - rule_.alpha_f) / (beta * dt * dt);
  const double a1 = gamma / (beta * dt);
  petsc_check(MatDuplicate(k_, MAT_COPY_VALUES, effective_.out()), "MatDuplicate");
  petsc_check(MatScale(effective_.get(), 1.0 + a1 * damping_.beta), "MatScale");
  petsc_check(VecCopy(m_, work_.get()), "VecCopy");
  petsc_check(VecScale(work_.get(), a0 + a1 * damping_.alpha), "VecScale");
  petsc_check(MatDiagonalSet(effective_.get(), work_.get(), ADD_VALUES), "MatDiagonalSet");
  // The added mass is inertia only (no Rayleigh share): a0 M_a. It couples
  // vertices K does not: the merged pattern is built once per factorisation.
  if (added_mass_ != nullptr)
    petsc_check(MatAXPY(effective_.get(), a0, added_mass_, DIFFERENT_NONZERO_PATTERN), "MatAXPY");
  petsc_check(MatSetOption(effective_.get(), MAT_SPD, PETSC_TRUE), "MatSetOption");
  solver_ = factory_(effective_.get());
  factorised_dt_ = dt;
  ++factorisations_;
}

void NewmarkIntegrator::prepare(double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("Newmark step needs dt > 0");
  if (!solver_ || std::abs(dt - factorised_dt_) > 1e-12 * dt) factorise(dt);
}

void NewmarkIntegrator::step(double dt, Vec load) {
  prepare(dt);
  const double gamma = rule_.gamma;
  const auto [a0, a1, a2, a3, a4, a5] = rule_.step_coefficients(dt);
  const double alpha = damping_.alpha;
  const double beta_r = damping_.beta;
  // Generalized alpha, divided by (1 - alpha_f): the inertia terms carry c_m =
  // (1 - alpha_m)/(1 - alpha_f) and the old acceleration alpha_m/(1 - alpha_f);
  // the state at t_n enters with r = alpha_f/(1 - alpha_f): + r (F_n - K u_n - C v_n).
  // All three vanish (c_m = 1) for average acceleration.
  const double cm = (1.0 - rule_.alpha_m) / (1.0 - rule_.alpha_f);
  const double am = rule_.alpha_m / (1.0 - rule_.alpha_f);
  const double r = rule_.alpha_f / (1.0 - rule_.alpha_f);
  const bool k_products = carries_k_products();
  // rhs = F + r (F_n - K u - C v) + M (cm (a0 u + a2 v + a3 a) - am a) + C (a1 u + a4 v + a5 a)
  //       + M_a (cm (a0 u + a2 v + a3 a) - am a),  C = alpha M + beta_R K:
  //     = F + r F_n + M ((cm a0 + alpha a1) u + (cm a2 + alpha (a4 - r)) v + (cm a3 - am + alpha a5) a)
  //         + beta_R (a1 K u + (a4 - r) K v + a5 K a) - r K u + M_a (...)
  petsc_check(VecAXPBYPCZ(work_.get(), cm * a0 + alpha * a1, cm * a2 + alpha * (a4 - r), 0.0, u_.get(), v_.get()),
              "VecAXPBYPCZ");
  petsc_check(VecAXPY(work_.get(), cm * a3 - am + alpha * a5, a_.get()), "VecAXPY");
  petsc_check(VecPointwiseMult(rhs_.get(), m_, work_.get()), "VecPointwiseMult");
  petsc_check(VecAXPY(rhs_.get(), 1.0, load), "VecAXPY");
  if (r != 0.0) petsc_check(VecAXPY(rhs_.get(), r, load_.get()), "VecAXPY");
  if (added_mass_ != nullptr) {
    petsc_check(VecAXPBYPCZ(work_.get(), cm * a0, cm * a2, 0.0, u_.get(), v_.get()), "VecAXPBYPCZ");
    petsc_check(VecAXPY(work_.get(), cm * a3 - am, a_.get()), "VecAXPY");
    petsc_check(MatMultAdd(added_mass_product_, work_.get(), rhs_.get(), rhs_.get()), "MatMultAdd");
  }
  if (k_products) {
    const PetscScalar weights[3] = {beta_r * a1 - r, beta_r * (a4 - r), beta_r * a5};
    Vec products[3] = {ku_.get(), kv_.get(), ka_.get()};
    petsc_check(VecMAXPY(rhs_.get(), 3, weights, products), "VecMAXPY");
  }
  solver_->solve(rhs_.get(), u_new_.get());
  PetscReal norm = 0.0;
  petsc_check(VecNorm(u_new_.get(), NORM_INFINITY, &norm), "VecNorm");
  if (!std::isfinite(norm)) throw std::runtime_error("the Newmark step produced a non-finite displacement");
  // a_new = a0 (u_new - u) - a2 v - a3 a;  v_new = v + dt ((1 - gamma) a + gamma a_new)
  petsc_check(VecWAXPY(a_new_.get(), -1.0, u_.get(), u_new_.get()), "VecWAXPY");
  petsc_check(VecAXPBYPCZ(a_new_.get(), -a2, -a3, a0, v_.get(), a_.get()), "VecAXPBYPCZ");
  petsc_check(VecAXPBYPCZ(v_.get(), dt * (1.0 - gamma), dt * gamma, 1.0, a_.get(), a_new_.get()), "VecAXPBYPCZ");
  if (k_products) {
    // K u_new = (rhs - (cm a0 + a1 alpha) M u_new - cm a0 M_a u_new) / (1 + a1 beta_R); then K a and K v as a and v.
    const double inertia = cm * a0 + a1 * alpha;
    petsc_check(VecPointwiseMult(work_.get(), m_, u_new_.get()), "VecPointwiseMult");
    if (added_mass_ != nullptr) {
      petsc_check(MatMult(added_mass_product_, u_new_.get(), work2_.get()), "MatMult");
      petsc_check(VecAXPY(work_.get(), cm * a0 / inertia, work2_.get()), "VecAXPY");
    }
    petsc_check(VecAXPBY(work_.get(), 1.0 / (1.0 + a1 * beta_r), -inertia / (1.0 + a1 * beta_r), rhs_.get()),
                "VecAXPBY");
    petsc_check(VecWAXPY(ka_new_.get(), -1.0, ku_.get(), work_.get()), "VecWAXPY");
    petsc_check(VecAXPBYPCZ(ka_new_.get(), -a2, -a3, a0, kv_.get(), ka_.get()), "VecAXPBYPCZ");
    petsc_check(VecAXPBYPCZ(kv_.get(), dt * (1.0 - gamma), dt * gamma, 1.0, ka_.get(), ka_new_.get()), "VecAXPBYPCZ");
    std::swap(ka_, ka_new_);
    std::swap(ku_, work_);
  }
  std::swap(a_, a_new_);
  std::swap(u_, u_new_);
  if (load != load_.get()) petsc_check(VecCopy(load, load_.get()), "VecCopy");
}

double NewmarkIntegrator::energy() const {
  PetscScalar kinetic = 0.0;
  PetscScalar strain = 0.0;
  petsc_check(VecPointwiseMult(work2_.get(), m_, v_.get()), "VecPointwiseMult");
  petsc_check(VecDot(work2_.get(), v_.get(), &kinetic), "VecDot");
  petsc_check(MatMult(k_, u_.get(), work2_.get()), "MatMult");
  petsc_check(VecDot(work2_.get(), u_.get(), &strain), "VecDot");
  return 0.5 * (kinetic + strain);
}

void NewmarkIntegrator::save(NewmarkState& state) const {
  const std::pair<const PetscVector*, PetscVector*> pairs[] = {
      {&u_, &state.u}, {&v_, &state.v}, {&a_, &state.a}, {&ku_, &state.ku}, {&kv_, &state.kv}, {&ka_, &state.ka},
      {&load_, &state.f}};
  for (const auto& [from, to] : pairs) {
    if (!*to) petsc_check(VecDuplicate(from->get(), to->out()), "VecDuplicate");
    petsc_check(VecCopy(from->get(), to->get()), "VecCopy");
  }
}

void NewmarkIntegrator::restore(const NewmarkState& state) {
  const std::pair<const PetscVector*, PetscVector*> pairs[] = {
      {&state.u, &u_}, {&state.v, &v_}, {&state.a, &a_}, {&state.ku, &ku_}, {&state.kv, &kv_}, {&state.ka, &ka_},
      {&state.f, &load_}};
  for (const auto& [from, to] : pairs) {
    if (!*from) throw std::logic_error("NewmarkIntegrator::restore: no state saved");
    petsc_check(VecCopy(from->get(), to->get()), "VecCopy");
  }
}

}  // namespace tankfsi::fem
