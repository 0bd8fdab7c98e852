#include "fem_solver/analysis/newmark.hpp"

#include <cmath>
#include <stdexcept>

namespace tankfsi::fem {

NewmarkIntegrator::NewmarkIntegrator(Mat stiffness, Vec mass_diagonal, RayleighCoefficients damping,
                                     SolverFactory factory)
    : k_(stiffness), m_(mass_diagonal), damping_(damping), factory_(std::move(factory)) {
  for (PetscVector* v : {&u_, &v_, &a_, &rhs_, &work_, &work2_, &combination_, &a_new_}) petsc_check(VecDuplicate(m_, v->out()), "VecDuplicate");
  for (PetscVector* v : {&u_, &v_, &a_}) petsc_check(VecSet(v->get(), 0.0), "VecSet");
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
  // a = M^-1 (F - K u - C v)
  petsc_check(MatMult(k_, u_.get(), work_.get()), "MatMult");
  petsc_check(VecWAXPY(rhs_.get(), -1.0, work_.get(), load), "VecWAXPY");
  damping_times(v_.get(), work_.get());
  petsc_check(VecAXPY(rhs_.get(), -1.0, work_.get()), "VecAXPY");
  petsc_check(VecPointwiseDivide(a_.get(), rhs_.get(), m_), "VecPointwiseDivide");
}

void NewmarkIntegrator::factorise(double dt) {
  const double a0 = 1.0 / (beta * dt * dt);
  const double a1 = gamma / (beta * dt);
  petsc_check(MatDuplicate(k_, MAT_COPY_VALUES, effective_.out()), "MatDuplicate");
  petsc_check(MatScale(effective_.get(), 1.0 + a1 * damping_.beta), "MatScale");
  petsc_check(VecCopy(m_, work_.get()), "VecCopy");
  petsc_check(VecScale(work_.get(), a0 + a1 * damping_.alpha), "VecScale");
  petsc_check(MatDiagonalSet(effective_.get(), work_.get(), ADD_VALUES), "MatDiagonalSet");
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
  const double a0 = 1.0 / (beta * dt * dt);
  const double a1 = gamma / (beta * dt);
  const double a2 = 1.0 / (beta * dt);
  const double a3 = 1.0 / (2.0 * beta) - 1.0;
  const double a4 = gamma / beta - 1.0;
  const double a5 = dt / 2.0 * (gamma / beta - 2.0);
  // rhs = F + M (a0 u + a2 v + a3 a) + C (a1 u + a4 v + a5 a)
  petsc_check(VecAXPBYPCZ(work_.get(), a0, a2, 0.0, u_.get(), v_.get()), "VecAXPBYPCZ");
  petsc_check(VecAXPY(work_.get(), a3, a_.get()), "VecAXPY");
  petsc_check(VecPointwiseMult(rhs_.get(), m_, work_.get()), "VecPointwiseMult");
  petsc_check(VecAXPY(rhs_.get(), 1.0, load), "VecAXPY");
  if (damping_.alpha != 0.0 || damping_.beta != 0.0) {
    petsc_check(VecAXPBYPCZ(combination_.get(), a1, a4, 0.0, u_.get(), v_.get()), "VecAXPBYPCZ");
    petsc_check(VecAXPY(combination_.get(), a5, a_.get()), "VecAXPY");
    damping_times(combination_.get(), work_.get());
    petsc_check(VecAXPY(rhs_.get(), 1.0, work_.get()), "VecAXPY");
  }
  // u_new from K_eff; then a_new = a0 (u_new - u) - a2 v - a3 a,
  // v_new = v + dt ((1 - gamma) a + gamma a_new).
  petsc_check(VecCopy(u_.get(), work_.get()), "VecCopy");
  solver_->solve(rhs_.get(), u_.get());
  petsc_check(VecWAXPY(a_new_.get(), -1.0, work_.get(), u_.get()), "VecWAXPY");
  petsc_check(VecScale(a_new_.get(), a0), "VecScale");
  petsc_check(VecAXPY(a_new_.get(), -a2, v_.get()), "VecAXPY");
  petsc_check(VecAXPY(a_new_.get(), -a3, a_.get()), "VecAXPY");
  petsc_check(VecAXPBYPCZ(v_.get(), dt * (1.0 - gamma), dt * gamma, 1.0, a_.get(), a_new_.get()), "VecAXPBYPCZ");
  petsc_check(VecCopy(a_new_.get(), a_.get()), "VecCopy");
  PetscReal norm = 0.0;
  petsc_check(VecNorm(u_.get(), NORM_INFINITY, &norm), "VecNorm");
  if (!std::isfinite(norm)) throw std::runtime_error("the Newmark step produced a non-finite displacement");
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

}  // namespace tankfsi::fem
