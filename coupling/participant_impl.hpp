#pragma once
// Participant::Impl: the state and the steps of one program's side of the
// coupling, shared by the files that implement it (participant.cpp:
// initialisation, messages and data; participant_restart.cpp: restart points;
// participant_windows.cpp: completing a window by each scheme). Private to the
// library.
#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "coupling/acceleration/acceleration.hpp"
#include "coupling/interface/interface_exchange.hpp"
#include "coupling/mapping/nearest_projection.hpp"
#include "coupling/participant.hpp"
#include "coupling/partnership/partner_link.hpp"
#include "coupling/schemes/schedule.hpp"
#include "coupling/time/window_interpolation.hpp"

namespace tankfsi::coupling {

class Participant::Impl {
 public:
  // Window ends within this fraction of its length count as reached: sub-steps
  // that add up to dt_c in floating point land a few ulps short or long.
  static constexpr double window_end_tolerance = 1e-9;
  // A window's verdict in the control record (PROTOCOL.md, "Control").
  static constexpr std::int32_t verdict_repeat = 0;
  static constexpr std::int32_t verdict_accept = 1;
  static constexpr std::int32_t verdict_stop = -1;
  using Clock = std::chrono::steady_clock;

  Impl(Side side, const CouplingSettings& settings, MPI_Comm local, MPI_Comm partner,
       std::map<std::string, std::string> fingerprints)
      : side_(side), settings_(settings), link_(local, partner, side, settings.timeout),
        fingerprints_(std::move(fingerprints)), controller_(controls(settings, side)) {
    settings_.check();
  }

  void set_interface(const std::vector<std::int64_t>& ids, const std::vector<double>& coordinates,
                     const std::vector<std::array<std::int64_t, 3>>& triangles) {
    if (side_ != Side::structure) throw CouplingError("set_interface: only the structure side declares the interface");
    if (initialized_) throw CouplingError("set_interface: after initialize()");
    declared_ids_ = ids;
    declared_coordinates_ = coordinates;
    declared_triangles_ = triangles;
    declared_ = true;
  }

  void exchange_interface();
  void initialize();
  void advance(double dt);
  void read(Field field, double relative_dt, std::span<double> values) const;
  void write(Field field, std::span<const double> values);
  void finalize();

  [[nodiscard]] const InterfaceMesh& mesh() const {
    require_exchanged("interface_mesh");
    return exchange_->mesh();
  }
  [[nodiscard]] std::size_t value_count() const {
    require_exchanged("value_count");
    if (side_ == Side::structure) return exchange_->part_size();
    return own_points_.empty() ? 3 * exchange_->global_vertex_count() : own_points_.size();
  }
  void set_own_vertices(std::vector<double> coordinates) {
    if (side_ != Side::fluid) throw CouplingError("set_own_vertices: only the fluid side maps onto the partner's mesh");
    if (initialized_) throw CouplingError("set_own_vertices: after initialize()");
    if (coordinates.empty() || coordinates.size() % 3 != 0)
      throw CouplingError("set_own_vertices: 3 coordinates per vertex expected, got " + std::to_string(coordinates.size()));
    own_points_ = std::move(coordinates);
  }
  /// Fluid: own values -> the whole mesh's (partial) values.
  [[nodiscard]] std::vector<double> to_mesh(std::span<const double> own) const {
    if (!mapping_) return {own.begin(), own.end()};
    std::vector<double> on_mesh(3 * exchange_->global_vertex_count());
    mapping_->conservative(own, on_mesh);
    return on_mesh;
  }
  [[nodiscard]] bool is_ongoing() const {
    return window_start_ < settings_.end_time - window_end_tolerance * settings_.time_window;
  }
  [[nodiscard]] double time() const { return window_start_ + elapsed_; }
  [[nodiscard]] double max_time_step() const { return window_length() - elapsed_; }

  bool take(bool& flag) {
    const bool was = flag;
    flag = false;
    return was;
  }

  Side side_;
  CouplingSettings settings_;
  PartnerLink link_;
  std::map<std::string, std::string> fingerprints_;
  bool controller_;
  std::unique_ptr<InterfaceExchange> exchange_;
  std::unique_ptr<Acceleration> acceleration_;

  bool declared_ = false;
  std::vector<std::int64_t> declared_ids_;
  std::vector<double> declared_coordinates_;
  std::vector<std::array<std::int64_t, 3>> declared_triangles_;

  bool initialized_ = false;
  bool finalized_ = false;
  int window_ = 1;
  int iteration_ = 0;
  double window_start_ = 0.0;
  double elapsed_ = 0.0;

  // Fluid: forces of the step to come, their window average, the wall path.
  std::vector<double> step_force_;
  bool step_force_written_ = false;
  WindowAverage force_average_;
  DisplacementPath path_;
  // Structure: displacements written, the ramp of the force read.
  std::vector<double> displacement_;
  bool displacement_written_ = false;
  LoadRamp ramp_;
  std::vector<double> force_input_;  ///< the F̄ the ramp aims at (eq 17)
  // Initial data written before initialize().
  std::vector<double> initial_values_;
  // The added-mass operator (coupling.added_mass: computed; added_mass.hpp):
  // fluid, the whole matrix (written as partial sums, then summed) and the
  // wall velocity of the last accepted window (whole mesh), which the next
  // window's change is taken from; structure, the rows of its vertices; both,
  // the normals of every vertex (ascending id order).
  std::vector<double> added_mass_;
  std::vector<double> added_mass_normals_;
  std::vector<double> previous_wall_velocity_;
  // Fluid with its own wall vertices: the mapping onto the partner's mesh.
  std::vector<double> own_points_;
  std::unique_ptr<NearestProjection> mapping_;
  mutable std::vector<double> mesh_scratch_;

  // Implicit controller: the input it sent (or, parallel, also its own), the
  // converged outputs of the last two windows (for the next window's guess).
  std::vector<double> sent_input_;
  std::vector<double> previous_output_;
  std::vector<double> last_output_;

  bool write_checkpoint_ = false;
  bool read_checkpoint_ = false;
  bool window_completed_ = false;

  // Restart points (PROTOCOL.md, "Window ends").
  double restart_interval_ = 0.0;
  double next_restart_time_ = std::numeric_limits<double>::infinity();
  bool stop_requested_ = false;
  bool restart_agreed_ = false;     ///< at the window end being completed
  bool restart_point_due_ = false;  ///< for restart_point_due()
  bool stopped_ = false;
  int stop_signal_ = 0;
  CouplingRestartState restart_state_;
  std::vector<double> last_output_part_;  ///< this program's output of the last window (its distributed part)

  void resume(const CouplingRestartState& state);
  std::vector<WindowReport> reports_;
  double work_seconds_ = 0.0;

 private:
  void require_exchanged(const char* what) const {
    if (!exchange_) throw CouplingError(std::string(what) + ": call exchange_interface() or initialize() first");
  }
  void require_initialized(const char* what) const {
    if (!initialized_) throw CouplingError(std::string(what) + ": call initialize() first");
  }
  [[nodiscard]] double window_length() const {
    return std::min(settings_.time_window, settings_.end_time - window_start_);
  }
  [[nodiscard]] bool last_window() const {
    return window_start_ + window_length() >= settings_.end_time - window_end_tolerance * settings_.time_window;
  }
  [[nodiscard]] int my_tag() const { return side_ == Side::fluid ? tag_force : tag_displacement; }
  [[nodiscard]] int partner_tag() const { return side_ == Side::fluid ? tag_displacement : tag_force; }
  [[nodiscard]] std::string partner_data_name() const {
    return side_ == Side::fluid ? "displacements" : "forces";
  }

  void handshake();
  /// Everything initialize() and resume() set up before the first exchange.
  void start_data();
  /// The window-end records (not after the last window, where both write a
  /// checkpoint anyway): sets restart_agreed_ and stop_signal_.
  void agree_on_window_end(bool last);
  /// Fills restart_state_ (in accept(), between the window's end and the next input).
  void capture_restart_state();
  /// Fluid: a whole-interface array from a slice, and back.
  [[nodiscard]] std::vector<double> whole(const std::vector<double>& part) const;
  [[nodiscard]] std::vector<double> part_of(const CouplingRestartState& state, const std::string& name) const;
  /// This program's output of the window in its distributed part: fluid, the
  /// force average on its slice; structure, its displacements.
  [[nodiscard]] std::vector<double> output_part();
  /// Sends a part as the message of the end of `window` (0: initialize) and
  /// the current iteration, with the controller's verdict.
  void send_part(const std::vector<double>& part, int window, std::int32_t verdict);
  struct Received {
    Control control;
    std::vector<double> part;
  };
  Received receive_part(int expected_window, int expected_iteration, const std::string& what);
  /// The input the program reads from, made from a received part: fluid, the
  /// whole displacement array; structure, its forces.
  void aim(const std::vector<double>& part);
  /// initialize(): the fluid's added-mass operator to the structure (PROTOCOL.md, "Added mass").
  void exchange_added_mass();
  void complete_window();
  void complete_explicit();
  void complete_follower();
  void complete_controller();
  void accept(const std::vector<double>& next_input_part, int iterations, bool converged, double residual_d,
              double residual_f);
  void repeat(const std::vector<double>& next_input_part);
  [[nodiscard]] std::vector<double> predicted(const std::vector<double>& last, const std::vector<double>& previous) const;
};

}  // namespace tankfsi::coupling
