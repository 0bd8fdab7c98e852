#include "coupling/partnership/partner_link.hpp"

#include <algorithm>
#include <sstream>
#include <thread>

namespace tankfsi::coupling {

namespace {

using Clock = std::chrono::steady_clock;

std::string encode(const std::map<std::string, std::string>& entries) {
  std::string text;
  for (const auto& [key, value] : entries) text += key + "=" + value + "\n";
  return text;
}

std::map<std::string, std::string> decode(const std::string& text) {
  std::map<std::string, std::string> entries;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) entries[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return entries;
}

std::string format_seconds(double s) {
  std::ostringstream out;
  out << s << " s";
  return out.str();
}

}  // namespace

PartnerLink::PartnerLink(MPI_Comm local, MPI_Comm partner, Side side, double timeout_seconds)
    : side_(side), timeout_(timeout_seconds) {
  if (partner == MPI_COMM_NULL) throw CouplingError("no partner program in this MPI job");
  int is_inter = 0;
  MPI_Comm_test_inter(partner, &is_inter);
  if (!is_inter) throw CouplingError("the partner communicator is not an inter-communicator");
  MPI_Comm_dup(local, &local_);
  MPI_Comm_dup(partner, &inter_);
  MPI_Comm_rank(local_, &rank_);
  MPI_Comm_size(local_, &size_);
  MPI_Comm_remote_size(inter_, &partner_size_);
}

PartnerLink::~PartnerLink() {
  // A run that ends early (an error) may leave control records the partner
  // never took: let them complete on their own rather than wait.
  for (auto& r : pending_controls_)
    if (r != MPI_REQUEST_NULL) MPI_Request_free(&r);
  if (inter_ != MPI_COMM_NULL) MPI_Comm_free(&inter_);
  if (local_ != MPI_COMM_NULL) MPI_Comm_free(&local_);
}

void PartnerLink::wait(std::vector<MPI_Request>& requests, const std::string& what, bool collective) {
  if (requests.empty()) return;
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration<double>(timeout_);
  // First yield the core for a few tens of microseconds (a partner that answers
  // at once is noticed at once), then sleep in naps of 2 % of the time waited so
  // far (20 us to 1 ms): a partner that computes for long costs no CPU and few
  // wake-ups, each of which would take a core from a computing rank when there
  // are more ranks than cores, and waking late costs at most 2 % of the wait.
  const auto yield_until = start + std::chrono::microseconds(50);
  int done = 0;
  for (;;) {
    MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
    if (done) break;
    const auto now = Clock::now();
    if (now > deadline) {
      if (!collective)
        for (auto& r : requests)
          if (r != MPI_REQUEST_NULL) MPI_Cancel(&r);
      throw CouplingError("timed out after " + format_seconds(timeout_) + " (coupling.timeout) waiting for " + what +
                          " from " + partner_name() + " (rank " + std::to_string(rank_) + " of the " +
                          side_name(side_) + " program)");
    }
    if (now < yield_until) {
      std::this_thread::yield();
    } else {
      const auto nap = std::chrono::duration_cast<std::chrono::microseconds>(now - start) / 50;
      std::this_thread::sleep_for(std::clamp(nap, std::chrono::microseconds(20), std::chrono::microseconds(1000)));
    }
  }
  requests.clear();
  wait_seconds_ += std::chrono::duration<double>(Clock::now() - start).count();
}

std::map<std::string, std::string> PartnerLink::exchange_hello(const std::map<std::string, std::string>& entries) {
  std::map<std::string, std::string> mine = entries;
  mine["protocol"] = "tankfsi-coupling";
  mine["protocol.major"] = std::to_string(protocol_major);
  mine["protocol.minor"] = std::to_string(protocol_minor);
  mine["side"] = side_name(side_);
  mine["ranks"] = std::to_string(size_);
  std::string received;
  if (leader()) {
    const std::string text = encode(mine);
    long long lengths[2] = {static_cast<long long>(text.size()), 0};
    std::vector<MPI_Request> requests(2);
    MPI_Isend(&lengths[0], 1, MPI_LONG_LONG, 0, tag_hello, inter_, &requests[0]);
    MPI_Irecv(&lengths[1], 1, MPI_LONG_LONG, 0, tag_hello, inter_, &requests[1]);
    wait(requests, "the hello record (is the partner a tankfsi coupling participant?)");
    if (lengths[1] < 0 || lengths[1] > (1 << 24)) throw CouplingError("the partner's hello record is malformed");
    received.resize(static_cast<std::size_t>(lengths[1]));
    requests.resize(2);
    MPI_Isend(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, tag_hello, inter_, &requests[0]);
    MPI_Irecv(received.data(), static_cast<int>(received.size()), MPI_CHAR, 0, tag_hello, inter_, &requests[1]);
    wait(requests, "the hello record");
  }
  long long length = static_cast<long long>(received.size());
  MPI_Bcast(&length, 1, MPI_LONG_LONG, 0, local_);
  received.resize(static_cast<std::size_t>(length));
  MPI_Bcast(received.data(), static_cast<int>(length), MPI_CHAR, 0, local_);
  return decode(received);
}

void PartnerLink::send_control(const Control& control) {
  if (!leader()) return;
  // Records sent earlier and taken by now are forgotten.
  if (!pending_controls_.empty()) {
    int done = 0;
    MPI_Testall(static_cast<int>(pending_controls_.size()), pending_controls_.data(), &done, MPI_STATUSES_IGNORE);
    if (done) {
      pending_controls_.clear();
      control_buffers_.clear();
    }
  }
  control_buffers_.push_back(control);
  pending_controls_.emplace_back();
  MPI_Isend(&control_buffers_.back(), sizeof(Control), MPI_BYTE, 0, tag_control, inter_, &pending_controls_.back());
}

Control PartnerLink::receive_record(const std::string& what) {
  Control control;
  std::vector<MPI_Request> request(1);
  if (leader()) {
    MPI_Irecv(&control, sizeof(Control), MPI_BYTE, 0, tag_control, inter_, &request[0]);
    wait(request, what);
    request.resize(1);
  }
  // The other ranks wait for the leader as the leader waits for the partner (a
  // blocking broadcast would spin on their cores meanwhile).
  MPI_Ibcast(&control, sizeof(Control), MPI_BYTE, 0, local_, &request[0]);
  wait(request, what, true);
  return control;
}

Control PartnerLink::receive_control(const std::string& what) {
  const Control control = receive_record(what);
  if (control.kind == static_cast<std::int32_t>(ControlKind::finalize))
    throw CouplingError(partner_name() + " finished (at t = " + format_seconds(control.time) + ") while the " +
                        side_name(side_) + " program waited for " + what);
  if (control.kind != static_cast<std::int32_t>(ControlKind::data))
    throw CouplingError("malformed control record from " + partner_name() + " while waiting for " + what);
  return control;
}

Control PartnerLink::receive_window_end(const std::string& what) {
  const Control control = receive_record(what);
  if (control.kind != static_cast<std::int32_t>(ControlKind::window_end))
    throw CouplingError("protocol out of step: the " + std::string(side_name(side_)) + " program expected " + what +
                        " and received a record of kind " + std::to_string(control.kind) + " for window " +
                        std::to_string(control.window) + " (does the partner speak protocol version " +
                        std::to_string(protocol_major) + "?)");
  return control;
}

void PartnerLink::receive_finalize() {
  const Control control = receive_record("the end of the run");
  if (control.kind != static_cast<std::int32_t>(ControlKind::finalize))
    throw CouplingError(partner_name() + " sent data for window " + std::to_string(control.window) +
                        " after this program had finished its last window (do both programs use the same end_time?)");
}

}  // namespace tankfsi::coupling
