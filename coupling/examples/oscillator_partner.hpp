#pragma once
// OscillatorPartner: one side of the partitioned two-mass oscillator
// (two_mass_oscillator.hpp) driven through a Participant: the solver dummies
// run it as a program, the coupling tests run both sides in one binary.
//
//   OscillatorPartner side(Side::structure, local, base, vertices);
//   side.declare(p); p.exchange_interface(); side.start(p); p.initialize();
//   double error = side.run(p, dt_c / 4, on_window);
#include <mpi.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "coupling/examples/two_mass_oscillator.hpp"
#include "coupling/participant.hpp"

namespace tankfsi::coupling::examples {

class OscillatorPartner {
 public:
  OscillatorPartner(Side side, MPI_Comm local, OscillatorParameters base, int vertices)
      : side_(side), base_(base), vertices_(vertices) {
    MPI_Comm_rank(local, &rank_);
    MPI_Comm_size(local, &size_);
  }

  /// Structure side: declares vertices k = rank, rank + ranks, ... (ids
  /// 1000 + 3k, so that ids are neither contiguous nor indices) on a strip of
  /// triangles (k, k+1, k+2). Every fluid slice then talks to every structure rank.
  void declare(Participant& p) const {
    if (side_ != Side::structure) return;
    std::vector<std::int64_t> ids;
    std::vector<double> xyz;
    std::vector<std::array<std::int64_t, 3>> triangles;
    for (int k = rank_; k < vertices_; k += size_) {
      ids.push_back(id_of(k));
      xyz.insert(xyz.end(), {0.01 * k, 0.01 * (k % 2), 0.0});
      if (k + 2 < vertices_) triangles.push_back({id_of(k), id_of(k + 1), id_of(k + 2)});
    }
    p.set_interface(ids, xyz, triangles);
  }

  /// After the interface exchange: the oscillators of the vertices this rank
  /// holds, at rest with x1(0) = x1_initial, and their initial data. The
  /// fluid integrates vertex k on its rank k mod ranks and writes zero force
  /// for the others (partial forces sum over the fluid's ranks).
  /// `constant_force` (fluid side, not NaN): write that force along x at every
  /// vertex instead, for a structure partner's step response.
  void start(Participant& p, double constant_force = std::numeric_limits<double>::quiet_NaN()) {
    constant_force_ = constant_force;
    const auto& ids = p.interface_mesh().ids;
    const std::size_t n = ids.size();
    params_.resize(n);
    dofs_.resize(n);
    integrated_.assign(n, true);
    values_.assign(3 * n, 0.0);
    start_.assign(3 * n, 0.0);
    end_.assign(3 * n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      params_[k] = base_.at_vertex(ids[k]);
      const auto& q = params_[k];
      if (side_ == Side::fluid) {
        integrated_[k] = static_cast<int>(k % static_cast<std::size_t>(size_)) == rank_;
        dofs_[k] = {q.m1, q.k1 + q.kc};
        dofs_[k].start(q.x1_initial, 0.0, 0.0);  // kc x2(0) = 0
        if (integrated_[k]) values_[3 * k] = std::isnan(constant_force_) ? q.kc * q.x1_initial : constant_force_;
      } else {
        dofs_[k] = {q.m2, q.k2};
        dofs_[k].start(0.0, 0.0, q.kc * q.x1_initial);
      }
    }
    p.write(side_ == Side::fluid ? Field::force : Field::displacement, values_);
  }

  /// One step of dt: reads, integrates, writes (the caller advances).
  void step(Participant& p, double dt) {
    if (side_ == Side::fluid) {
      if (std::isnan(constant_force_)) {
        p.read(Field::displacement, 0.0, start_);
        p.read(Field::displacement, dt, end_);
        for (std::size_t k = 0; k < dofs_.size(); ++k) {
          const double before = dofs_[k].u;
          dofs_[k].step(dt, params_[k].kc * end_[3 * k]);
          // The force over the step, trapezoidal as Newmark integrates it (eq 16).
          values_[3 * k] = integrated_[k] ? params_[k].kc * (0.5 * (before + dofs_[k].u) - 0.5 * (start_[3 * k] + end_[3 * k])) : 0.0;
        }
      }
      p.write(Field::force, values_);
    } else {
      p.read(Field::force, dt, end_);
      for (std::size_t k = 0; k < dofs_.size(); ++k) {
        dofs_[k].step(dt, end_[3 * k]);
        values_[3 * k] = dofs_[k].u;
      }
      p.write(Field::displacement, values_);
    }
  }

  /// The participant loop with steps of at most `own_step`; `on_window` is
  /// called after every accepted window with its number. Returns the largest
  /// |x - exact| / x1(0) of this rank's masses over the window ends
  /// (infinity once non-finite).
  double run(Participant& p, double own_step, const std::function<void(int)>& on_window = nullptr) {
    double max_error = 0.0;
    auto saved = dofs_;
    while (p.is_ongoing()) {
      if (p.requires_writing_checkpoint()) saved = dofs_;
      const double dt = std::min(own_step, p.max_time_step());
      step(p, dt);
      p.advance(dt);
      if (p.requires_reading_checkpoint()) dofs_ = saved;
      if (!p.window_completed()) continue;
      if (on_window) on_window(p.window_reports().back().window);
      if (!std::isnan(constant_force_)) continue;
      for (std::size_t k = 0; k < dofs_.size(); ++k) {
        if (!integrated_[k]) continue;
        const Eigen::Vector2d exact = oscillator_exact(params_[k], p.time());
        const double error = std::abs(dofs_[k].u - exact[side_ == Side::fluid ? 0 : 1]) / params_[k].x1_initial;
        max_error = std::isfinite(error) ? std::max(max_error, error) : std::numeric_limits<double>::infinity();
      }
    }
    return max_error;
  }

  [[nodiscard]] static std::int64_t id_of(int k) { return 1000 + 3 * static_cast<std::int64_t>(k); }

 private:
  Side side_;
  OscillatorParameters base_;
  int vertices_;
  int rank_ = 0, size_ = 1;
  double constant_force_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<OscillatorParameters> params_;
  std::vector<NewmarkDof> dofs_;
  std::vector<bool> integrated_;
  std::vector<double> values_, start_, end_;
};

}  // namespace tankfsi::coupling::examples
