// Participant: advancing in time and completing a window by each scheme (participant_impl.hpp).
#include "coupling/participant_impl.hpp"

#include <algorithm>
#include <cmath>

#include "common/io/exact_number.hpp"
#include "common/run/checkpoint_series.hpp"

namespace tankfsi::coupling {

namespace {

double norm(MPI_Comm comm, std::span<const double> v) { return std::sqrt(weighted_dot(comm, v, v, {})); }

std::array<double, 3> component_sums(MPI_Comm comm, std::span<const double> values, double factor) {
  std::array<double, 3> local{};
  for (std::size_t i = 0; i < values.size(); ++i) local[i % 3] += values[i] * factor;
  std::array<double, 3> global{};
  MPI_Allreduce(local.data(), global.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

}  // namespace

// ---- windows --------------------------------------------------------------

void Participant::Impl::advance(double dt) {
  require_initialized("advance");
  if (finalized_) throw CouplingError("advance: after finalize()");
  if (stopped_) throw CouplingError("advance: the partners agreed to stop at t = " + std::to_string(time()) + " s");
  if (!is_ongoing()) throw CouplingError("advance: the coupled run has ended (t = " + std::to_string(time()) + " s)");
  const double remaining = max_time_step();
  if (!(dt > 0) || dt > remaining * (1 + window_end_tolerance) + window_end_tolerance * settings_.time_window)
    throw CouplingError("advance(" + std::to_string(dt) + " s): the step must be positive and at most max_time_step() = " +
                        std::to_string(remaining) + " s");
  if (side_ == Side::fluid) {
    if (!step_force_written_)
      throw CouplingError("advance: the fluid must write(force) before each step (the force over that step, eq 16)");
    force_average_.add(step_force_, dt);
    step_force_written_ = false;
  }
  window_completed_ = false;
  elapsed_ += dt;
  if (elapsed_ >= window_length() * (1 - window_end_tolerance)) {
    elapsed_ = window_length();
    const auto start = Clock::now();
    const double wait_before = link_.wait_seconds();
    complete_window();
    work_seconds_ += std::chrono::duration<double>(Clock::now() - start).count() - (link_.wait_seconds() - wait_before);
  }
}

void Participant::Impl::complete_window() {
  if (!settings_.is_implicit())
    complete_explicit();
  else if (controller_)
    complete_controller();
  else
    complete_follower();
}

void Participant::Impl::complete_explicit() {
  const bool last = last_window();
  last_output_part_ = output_part();
  if (sends_output(settings_, side_, last)) send_part(last_output_part_, window_, verdict_accept);
  std::vector<double> next;
  const bool lagging = lags(settings_, side_);
  const auto receive_input = [&](int from_window) {
    next = receive_part(from_window, 0, partner_data_name() + " of window " + std::to_string(from_window)).part;
  };
  // The window-end records come where both programs have sent and taken
  // everything of this window: after the lagging side's receive, before the
  // receive of the side one window ahead (which a stop makes unnecessary).
  if (receives_input(last) && lagging) receive_input(window_);
  agree_on_window_end(last);
  if (receives_input(last) && !lagging && stop_signal_ == 0) receive_input(window_ + 1);
  accept(next, 1, true, -1, -1);
}

void Participant::Impl::complete_follower() {
  last_output_part_ = output_part();
  send_part(last_output_part_, window_, verdict_accept);
  const Received verdict = receive_part(window_, iteration_, "the verdict on window " + std::to_string(window_));
  if (verdict.control.converged == verdict_stop)
    throw CouplingError(link_.partner_name() + " stopped the run: window " + std::to_string(window_) +
                        " did not converge in " + std::to_string(settings_.max_iterations) +
                        " coupling iterations (coupling.implicit.max_iterations)");
  if (verdict.control.converged == verdict_repeat) {
    repeat(verdict.part);
  } else {
    agree_on_window_end(last_window());
    accept(last_window() ? std::vector<double>{} : verdict.part, iteration_ + 1, true, -1, -1);
  }
}

std::vector<double> Participant::Impl::predicted(const std::vector<double>& last,
                                                 const std::vector<double>& previous) const {
  // Linear extrapolation of the converged outputs of the last two windows.
  std::vector<double> guess(last.size());
  for (std::size_t i = 0; i < guess.size(); ++i) guess[i] = 2 * last[i] - previous[i];
  return guess;
}

void Participant::Impl::complete_controller() {
  const bool parallel = settings_.implicit_mode == ImplicitMode::parallel;
  const bool last = last_window();
  // x̂: this program's output; in parallel mode followed by the partner's.
  std::vector<double> output = output_part();
  last_output_part_ = output;
  const std::size_t own_size = output.size();
  if (parallel) {
    const Received forces = receive_part(window_, iteration_, "forces of window " + std::to_string(window_));
    output.insert(output.end(), forces.part.begin(), forces.part.end());
  }
  // Residuals of the displacement and force fields, relative to the output.
  double largest_absolute = 0.0;  // for the message of a window that does not converge
  const auto field_residual = [&](std::size_t begin, std::size_t end, double& relative) {
    std::vector<double> r(end - begin);
    for (std::size_t i = begin; i < end; ++i) r[i - begin] = output[i] - sent_input_[i];
    const double r_norm = norm(link_.local(), r);
    const double x_norm = norm(link_.local(), std::span<const double>(output).subspan(begin, end - begin));
    relative = x_norm > 0 ? r_norm / x_norm : r_norm;
    largest_absolute = std::max(largest_absolute, r_norm);
    return r_norm <= std::max(settings_.absolute_tolerance, settings_.relative_tolerance * x_norm);
  };
  double residual_d = -1, residual_f = -1;
  bool converged = true;
  std::vector<double> weights;
  if (parallel) {
    converged = field_residual(0, own_size, residual_d);
    converged = field_residual(own_size, output.size(), residual_f) && converged;
    // Each field weighted by the inverse of its size, so that metres and
    // newtons count alike in the least-squares problem.
    const double d_scale = norm(link_.local(), std::span<const double>(output).first(own_size));
    const double f_scale = norm(link_.local(), std::span<const double>(output).subspan(own_size));
    weights.assign(output.size(), 1.0);
    for (std::size_t i = 0; i < output.size(); ++i) {
      const double scale = i < own_size ? d_scale : f_scale;
      weights[i] = scale > 0 ? 1.0 / scale : 1.0;
    }
  } else {
    converged = field_residual(0, own_size, side_ == Side::structure ? residual_d : residual_f);
  }
  const bool out_of_iterations = !converged && iteration_ + 1 >= settings_.max_iterations;
  if (out_of_iterations && settings_.stop_on_nonconvergence) {
    send_part(std::vector<double>(parallel ? own_size : output.size(), 0.0), window_, verdict_stop);
    throw CouplingError("window " + std::to_string(window_) + " (t = " + std::to_string(window_start_) + " to " +
                        std::to_string(window_start_ + window_length()) + " s) did not converge in " +
                        std::to_string(settings_.max_iterations) +
                        " coupling iterations (coupling.implicit.max_iterations); relative residual " +
                        std::to_string(std::max(residual_d, residual_f)) + ", absolute " +
                        exact_text(largest_absolute) + " (coupling.implicit.absolute_tolerance " +
                        exact_text(settings_.absolute_tolerance) + ")");
  }
  const bool accepted = converged || out_of_iterations;
  std::vector<double> next;
  if (accepted) {
    acceleration_->window_converged();
    previous_output_ = last_output_;
    last_output_ = output;
    next = predicted(last_output_, previous_output_);
  } else {
    next = acceleration_->next_input(sent_input_, output, weights);
  }
  // The follower's part of the next input goes to it with the verdict.
  const std::size_t follower_size = parallel ? own_size : next.size();
  send_part(std::vector<double>(next.begin(), next.begin() + static_cast<long>(follower_size)), window_,
            accepted ? verdict_accept : verdict_repeat);
  const int iterations = iteration_ + 1;
  if (accepted) agree_on_window_end(last);  // before the follower runs the next window (serial)
  std::vector<double> own_input;
  if (parallel) {
    own_input.assign(next.begin() + static_cast<long>(own_size), next.end());
  } else if (!(accepted && last) && !(accepted && stop_signal_ != 0)) {
    own_input = receive_part(accepted ? window_ + 1 : window_, accepted ? 0 : iteration_ + 1,
                             partner_data_name() + " of the next coupling iteration")
                    .part;
  }
  sent_input_ = std::move(next);
  if (accepted)
    accept(last ? std::vector<double>{} : own_input, iterations, converged, residual_d, residual_f);
  else
    repeat(own_input);
}

void Participant::Impl::accept(const std::vector<double>& next_input_part, int iterations, bool converged,
                               double residual_d, double residual_f) {
  WindowReport report;
  report.window = window_;
  report.start_time = window_start_;
  report.end_time = window_start_ + window_length();
  report.iterations = iterations;
  report.converged = converged;
  report.displacement_residual = residual_d;
  report.force_residual = residual_f;
  if (side_ == Side::structure) {
    report.impulse_given = component_sums(link_.local(), force_input_, window_length());
    report.impulse_applied = component_sums(link_.local(), ramp_.mean(), window_length());
  }
  reports_.push_back(report);
  if (side_ == Side::fluid && settings_.added_mass_operator) previous_wall_velocity_ = path_.velocity(window_length());

  window_start_ += window_length();
  elapsed_ = 0.0;
  ++window_;
  iteration_ = 0;
  if (side_ == Side::fluid) {
    path_.next_window();
    force_average_.reset();
  } else {
    ramp_.next_window();
    displacement_written_ = false;
  }
  // A restart continues from here: the next input is what the partner sends again.
  if (restart_agreed_) {
    capture_restart_state();
    next_restart_time_ = next_output_time(window_start_, restart_interval_);
    restart_point_due_ = true;
    restart_agreed_ = false;
  }
  if (stop_signal_ != 0) {
    stopped_ = true;
    exchange_->finish_sends("the partner to take the last interface data");
  } else if (!next_input_part.empty()) {
    aim(next_input_part);
  }
  window_completed_ = true;
  write_checkpoint_ = settings_.is_implicit() && is_ongoing() && !stopped_;
}

void Participant::Impl::repeat(const std::vector<double>& next_input_part) {
  elapsed_ = 0.0;
  ++iteration_;
  if (side_ == Side::fluid)
    force_average_.reset();
  else
    displacement_written_ = false;
  aim(next_input_part);
  window_completed_ = false;
  read_checkpoint_ = true;
}

}  // namespace tankfsi::coupling
