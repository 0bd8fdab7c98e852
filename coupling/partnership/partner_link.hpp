#pragma once
// PartnerLink: the channel between the two programs of a coupled job.
//
// It owns duplicates of the program's communicator and of the
// inter-communicator to the partner (so the coupling's messages never meet
// the solver's), waits for messages with a time-out that names what was
// awaited, and carries the control messages of the protocol: each exchange
// starts with a control record from the sending program's leader (rank 0) to
// the receiving program's leader, broadcast there to every rank
// (coupling/PROTOCOL.md, "Messages").
#include <mpi.h>

#include <chrono>
#include <deque>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/settings.hpp"

namespace tankfsi::coupling {

/// A coupling failure: protocol mismatch, time-out, bad interface data.
class CouplingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Message tags on the inter-communicator (PROTOCOL.md, "Tags").
enum Tag : int {
  tag_hello = 100,
  tag_control = 101,
  tag_mesh_sizes = 110,
  tag_mesh_ids = 111,
  tag_mesh_coordinates = 112,
  tag_mesh_triangles = 113,
  tag_exchange_plan = 120,
  tag_force = 130,
  tag_displacement = 131,
  tag_added_mass = 132,
  tag_added_mass_normals = 133,
};

enum class ControlKind : std::int32_t { data = 1, finalize = 2, window_end = 3 };

/// The fixed-size record that opens every exchange (PROTOCOL.md, "Control").
struct Control {
  std::int32_t kind = static_cast<std::int32_t>(ControlKind::data);
  std::int32_t window = 0;     ///< 1-based window the data belongs to; 0: initial data
  std::int32_t iteration = 0;  ///< 0-based coupling iteration within the window
  std::int32_t converged = 1;  ///< implicit: 1 when the window is accepted
  double time = 0.0;           ///< end time of that window (s)
};

class PartnerLink {
 public:
  /// `local`: this program's ranks; `partner`: the inter-communicator to the
  /// other program. Both are duplicated; the caller keeps its own.
  PartnerLink(MPI_Comm local, MPI_Comm partner, Side side, double timeout_seconds);
  ~PartnerLink();
  PartnerLink(const PartnerLink&) = delete;
  PartnerLink& operator=(const PartnerLink&) = delete;

  [[nodiscard]] MPI_Comm local() const { return local_; }
  [[nodiscard]] MPI_Comm inter() const { return inter_; }
  [[nodiscard]] Side side() const { return side_; }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  [[nodiscard]] int partner_size() const { return partner_size_; }
  [[nodiscard]] bool leader() const { return rank_ == 0; }
  [[nodiscard]] std::string partner_name() const { return std::string("the ") + side_name(other(side_)) + " program"; }

  /// Collective over this program. Exchanges the hello records of both leaders
  /// (protocol version, side, rank count, `entries`) and returns the partner's
  /// entries on every rank.
  std::map<std::string, std::string> exchange_hello(const std::map<std::string, std::string>& entries);

  /// Leader only sends; collective in the sense that all ranks may call it.
  void send_control(const Control& control);
  /// Collective over this program: the leader waits for the partner's control
  /// record and every rank returns it. `what` names the awaited data in errors.
  /// A finalize record where data was awaited is an error.
  Control receive_control(const std::string& what);
  /// Collective over this program: waits for the partner's window-end record
  /// (kind 3: its restart and stop requests); anything else is an error.
  Control receive_window_end(const std::string& what);
  /// Collective over this program: waits for the partner's finalize record;
  /// a data record instead is an error (the partner expected more windows).
  void receive_finalize();

  /// Waits for every request, or throws CouplingError after the time-out
  /// naming `what` (cancelling the requests first unless they are
  /// collective: MPI cancels point-to-point requests only). Sleeps between
  /// tests so that waiting ranks leave the cores to the partner
  /// (oversubscribed runs).
  void wait(std::vector<MPI_Request>& requests, const std::string& what, bool collective = false);

  /// Seconds spent waiting for the partner so far (this rank).
  [[nodiscard]] double wait_seconds() const { return wait_seconds_; }

 private:
  /// Collective over this program: the leader waits for the partner's next
  /// control record, of any kind, and every rank returns it.
  Control receive_record(const std::string& what);

  MPI_Comm local_ = MPI_COMM_NULL;
  MPI_Comm inter_ = MPI_COMM_NULL;
  Side side_;
  double timeout_;
  int rank_ = 0;
  int size_ = 1;
  int partner_size_ = 1;
  double wait_seconds_ = 0.0;
  std::vector<MPI_Request> pending_controls_;
  std::deque<Control> control_buffers_;  ///< in flight; a deque keeps them in place
};

/// The protocol version this library speaks (PROTOCOL.md, "Versioning").
constexpr int protocol_major = 2;
constexpr int protocol_minor = 1;

}  // namespace tankfsi::coupling
