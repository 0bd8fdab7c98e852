// Restart of the coupling library (Participant::request_stop, the
// window-end records, restart_state, resume) with the two-mass oscillator
// on every split and scheme: one program asks to stop, both see the same
// restart point, and a new pair of participants resumed from it (each side
// with its oscillator as it was) gives the window reports of the run
// straight through bit for bit — residuals and iteration counts of implicit
// windows, the impulses given and applied of every window.
#include <catch2/catch.hpp>

#include <optional>

#include "coupling/examples/oscillator_partner.hpp"
#include "coupling/partnership/partner_link.hpp"
#include "partner_split.hpp"

using namespace tankfsi::coupling;
using namespace tankfsi::coupling::testing;

namespace {

struct Stopped {};

CouplingSettings settings_of(Scheme scheme, Side first, ImplicitMode mode, AccelerationType acceleration) {
  CouplingSettings s;
  s.scheme = scheme;
  s.first = first;
  s.implicit_mode = mode;
  s.acceleration = acceleration;
  s.end_time = 0.3;
  s.time_window = 0.01;
  s.timeout = 60;
  s.relative_tolerance = 1e-10;
  s.absolute_tolerance = 1e-13;
  s.max_iterations = 50;
  return s;
}

std::vector<CouplingSettings> schemes() {
  std::vector<CouplingSettings> all;
  all.push_back(settings_of(Scheme::parallel_staggered, Side::fluid, ImplicitMode::serial, AccelerationType::constant));
  for (const Side first : {Side::fluid, Side::structure}) {
    all.push_back(settings_of(Scheme::sequential_staggered, first, ImplicitMode::serial, AccelerationType::constant));
    for (const auto acceleration : {AccelerationType::aitken, AccelerationType::iqn_ils})
      all.push_back(settings_of(Scheme::implicit, first, ImplicitMode::serial, acceleration));
  }
  for (const auto acceleration : {AccelerationType::aitken, AccelerationType::iqn_ils})
    all.push_back(settings_of(Scheme::implicit, Side::fluid, ImplicitMode::parallel, acceleration));
  return all;
}

void check_same_reports(const std::vector<WindowReport>& straight, const std::vector<WindowReport>& resumed) {
  REQUIRE(resumed.size() == straight.size());
  for (std::size_t w = 0; w < straight.size(); ++w) {
    CAPTURE(w);
    CHECK(resumed[w].window == straight[w].window);
    CHECK(resumed[w].end_time == straight[w].end_time);
    CHECK(resumed[w].iterations == straight[w].iterations);
    CHECK(resumed[w].displacement_residual == straight[w].displacement_residual);
    CHECK(resumed[w].force_residual == straight[w].force_residual);
    CHECK(resumed[w].impulse_given == straight[w].impulse_given);
    CHECK(resumed[w].impulse_applied == straight[w].impulse_applied);
  }
}

}  // namespace

TEST_CASE("a stopped pair resumed from its restart point goes on as the run straight through", "[coupling][restart]") {
  const examples::OscillatorParameters parameters;
  const int vertices = 12;
  for (const int fluid_ranks : fluid_rank_choices()) {
    PartnerSplit split(fluid_ranks);
    const double own_step = (split.side == Side::fluid ? 0.3 : 0.25) * 0.01;
    for (const CouplingSettings& settings : schemes()) {
      CAPTURE(fluid_ranks, static_cast<int>(settings.scheme), static_cast<int>(settings.first),
              static_cast<int>(settings.implicit_mode), static_cast<int>(settings.acceleration));
      // Straight through.
      std::vector<WindowReport> straight;
      const auto start = [&](Participant& p, examples::OscillatorPartner& side) {
        side.declare(p);
        p.exchange_interface();
        side.start(p);
        p.initialize();
      };
      {
        Participant p(split.side, settings, split.local, split.partner);
        examples::OscillatorPartner side(split.side, split.local, parameters, vertices);
        start(p, side);
        // No interval, no stop: no restart point but the run's end.
        side.run(p, own_step, [&](int) { CHECK(p.restart_point_due() == !p.is_ongoing()); });
        p.finalize();
        straight = p.window_reports();
      }
      // The fluid asks to stop after window 12: both programs end window 13 at its restart point.
      CouplingRestartState state;
      std::optional<examples::OscillatorPartner> kept;
      {
        Participant p(split.side, settings, split.local, split.partner);
        examples::OscillatorPartner side(split.side, split.local, parameters, vertices);
        start(p, side);
        try {
          side.run(p, own_step, [&](int window) {
            if (window == 12 && split.side == Side::fluid) p.request_stop();
            if (!p.restart_point_due()) return;
            CHECK(window == 13);
            CHECK(p.stop_signal() == -1);
            state = p.restart_state();
            kept = side;
            throw Stopped{};
          });
          FAIL("the run did not stop");
        } catch (const Stopped&) {
        }
        CHECK_THROWS_AS(p.advance(own_step), CouplingError);  // stopped: no further window
        p.finalize();
      }
      REQUIRE(kept);
      CHECK(state.window == 14);
      CHECK(state.reports.size() == 13);
      // Resumed: new participants, each side's oscillator as it was.
      Participant p(split.side, settings, split.local, split.partner);
      kept->declare(p);
      p.exchange_interface();
      p.resume(state);
      CHECK(p.time() == state.window_start);
      kept->run(p, own_step);
      p.finalize();
      check_same_reports(straight, p.window_reports());
    }
  }
}
