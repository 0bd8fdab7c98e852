// solver_dummy: either side of a coupled job, with the two-mass oscillator
// (two_mass_oscillator.hpp) for physics, through the C++ Participant. It
// tests the coupling without the real solvers and shows the participant loop.
//
//   mpirun -np 2 solver_dummy --side fluid case.yaml : -np 1 solver_dummy --side structure case.yaml
//   mpirun -np 1 solver_dummy --side fluid case.yaml --vertices 100000 : -np 1 solver_dummy --side structure case.yaml --vertices 100000
//
// Options: --vertices N (interface size, default 12); --check TOL (exit 1 if
// the error against the closed form exceeds TOL); --fail-at-window K (throw
// at window K, to see the job end with this side's message); --kill-at-window
// K (die by SIGKILL at window K); --constant-force FX (fluid side: instead of
// the oscillator, a constant force FX along x on every vertex, for a structure
// partner's step response, as modal_structure --check-step does). Prints one
// summary line per side.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>

#include "common/config/case_config.hpp"
#include "common/config/case_schema.hpp"
#include "common/parallel/program_groups.hpp"
#include "coupling/examples/oscillator_partner.hpp"
#include "coupling/participant.hpp"

using namespace tankfsi;
using namespace tankfsi::coupling;

namespace {

struct Options {
  Side side = Side::fluid;
  std::string case_file;
  int vertices = 12;
  double check = -1;
  int fail_at = -1;
  int kill_at = -1;
  double constant_force = std::nan("");
};

Options parse(int argc, char** argv) {
  Options o;
  bool side_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--side") {
      const std::string s = value();
      if (s != "fluid" && s != "structure") throw std::invalid_argument("--side must be fluid or structure");
      o.side = s == "fluid" ? Side::fluid : Side::structure;
      side_given = true;
    } else if (a == "--vertices") o.vertices = std::stoi(value());
    else if (a == "--check") o.check = std::stod(value());
    else if (a == "--fail-at-window") o.fail_at = std::stoi(value());
    else if (a == "--kill-at-window") o.kill_at = std::stoi(value());
    else if (a == "--constant-force") o.constant_force = std::stod(value());
    else if (a.size() > 5 && a.substr(a.size() - 5) == ".yaml") o.case_file = a;
    else throw std::invalid_argument("unknown argument " + a);
  }
  if (!side_given || o.case_file.empty())
    throw std::invalid_argument("usage: solver_dummy --side fluid|structure CASE.yaml [--vertices N] [--check TOL] "
                                "[--fail-at-window K] [--kill-at-window K]");
  return o;
}

int run(const Options& o, const ProgramGroups& groups) {
  const auto config = CaseConfig::load(o.case_file, {}, case_schema());
  const CouplingSettings settings = read_coupling_settings(config);
  Participant p(o.side, settings, groups.local, groups.partner, case_fingerprints(config));
  int rank = 0, size = 1;
  MPI_Comm_rank(groups.local, &rank);
  MPI_Comm_size(groups.local, &size);
  const auto wall_start = std::chrono::steady_clock::now();

  // 1. The structure declares its share of a strip of vertices; the fluid
  //    receives the whole strip.
  examples::OscillatorPartner oscillators(o.side, groups.local, examples::OscillatorParameters{}, o.vertices);
  oscillators.declare(p);
  p.exchange_interface();
  // 2. The oscillators and the initial data.
  oscillators.start(p, o.constant_force);
  p.initialize();

  // 3. The participant loop (timed from here: set-up is not per window).
  const auto loop_start = std::chrono::steady_clock::now();
  const auto timings_at_start = p.timings();
  const double own_step = settings.time_window / (o.side == Side::fluid ? 3.0 : 4.0);
  const double max_error = oscillators.run(p, own_step, [&](int window) {
    if (window == o.fail_at) throw std::runtime_error("failing on purpose at window " + std::to_string(window));
    if (window == o.kill_at) std::raise(SIGKILL);
  });
  p.finalize();

  // 4. Summary: error, iterations, and the share of wall time in the coupling.
  double error = 0.0;
  MPI_Allreduce(&max_error, &error, 1, MPI_DOUBLE, MPI_MAX, groups.local);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
  const double setup = std::chrono::duration<double>(loop_start - wall_start).count();
  auto timings = p.timings();
  timings.wait -= timings_at_start.wait;
  timings.work -= timings_at_start.work;
  long long iterations = 0;
  for (const auto& r : p.window_reports()) iterations += r.iterations;
  const auto windows = static_cast<long long>(p.window_reports().size());
  if (rank == 0)
    std::printf("solver_dummy (%s, %d ranks): %lld windows, %d vertices, error %.3e, %.2f iterations per window, "
                "wall %.3f s, solver %.3f s, coupling wait %.3f s, coupling work %.3f s, %.3f ms per window, "
                "set-up %.3f s\n",
                side_name(o.side), size, windows, o.vertices, error, windows ? double(iterations) / double(windows) : 0.0,
                wall, wall - timings.wait - timings.work, timings.wait, timings.work, windows ? 1e3 * wall / double(windows) : 0.0, setup);
  if (o.check >= 0 && !(error <= o.check)) {
    if (rank == 0) std::fprintf(stderr, "solver_dummy (%s): error %.3e above --check %.3e\n", side_name(o.side), error, o.check);
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  Options options;
  try {
    options = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "solver_dummy: " << e.what() << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  ProgramGroups groups;
  int status = 0;
  try {
    groups = split_program_groups(MPI_COMM_WORLD, side_name(options.side));
    status = run(options, groups);
  } catch (const std::exception& e) {
    // A failure on one side must end the partner too: abort the whole job.
    std::cerr << "solver_dummy (" << side_name(options.side) << "): error: " << e.what() << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  free_program_groups(groups);
  MPI_Finalize();
  return status;
}
