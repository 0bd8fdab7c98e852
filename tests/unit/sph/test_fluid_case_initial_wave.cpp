// fluid.initial_velocity read from a case file (sph_solver/app/fluid_case.cpp):
// a standing wave gives every particle the mode's velocity for the tank's filled
// depth (the top of the highest layer, 0.70 m for a level of 0.70 m at L0 = 0.02),
// and the cases it does not describe are refused with the key and a reason; a case
// without the optional solver keys gets FluidModel's defaults, and its kernel's
// smoothing length when it names none.
#include <catch2/catch.hpp>

#include <string>

#include "common/config/case_config.hpp"
#include "common/config/case_schema.hpp"
#include "common/config/config_error.hpp"
#include "sph_solver/app/fluid_case.hpp"
#include "sph_solver/particles/standing_wave.hpp"
#include "support/text_files.hpp"

using namespace tankfsi;
using namespace tankfsi::sph;

namespace {

const std::string sloshing_case = R"(title: standing wave
end_time: 1.0
fluid:
  dimension: 2
  spacing: 0.02
  density: 1000
  viscosity: 0.001
  geometry: {type: rectangular_tank, width: 2.0, wall_height: 1.0}
  fill: {level: 0.70}
  initial_velocity: {type: standing_wave, amplitude: 0.01, mode: 1}
)";

FluidCase read(const std::string& text, const std::vector<Override>& overrides = {}) {
  const testing::ScratchFolder folder;
  const auto file = testing::write_text(folder, "case.yaml", text);
  return read_fluid_case(CaseConfig::load(file, overrides, case_schema()));
}

}  // namespace

TEST_CASE("a standing wave case starts with the mode's velocity", "[fluid_case]") {
  const FluidCase c = read(sloshing_case);
  StandingWave wave;
  wave.width = 2.0;
  wave.depth = 0.70;
  wave.amplitude = 0.01;
  REQUIRE(c.particles.count() == 3500);
  for (std::size_t i = 0; i < c.particles.size(); ++i)
    REQUIRE((c.particles.velocity[i] - wave.velocity(c.particles.position[i])).norm() < 1e-15);
  // The pressure is still the hydrostatic one (the mode's d phi/dt is 0 at t = 0).
  const FluidCase at_rest = read(testing::with_line(sloshing_case, 10, ""));
  REQUIRE(at_rest.particles.velocity[0].norm() == 0.0);
  CHECK(c.particles.pressure == at_rest.particles.pressure);
}

TEST_CASE("a standing wave is refused where it does not apply", "[fluid_case]") {
  CHECK_THROWS_WITH(read(sloshing_case, {{"fluid.fill.region", "[0, 0, -1, 1, 0.7, 1]", ""}}),
                    Catch::Contains("fluid.initial_velocity.type: a standing wave fills the whole tank"));
  CHECK_THROWS_WITH(read(sloshing_case, {{"fluid.initial_velocity.amplitude", "0.08", ""}}),
                    Catch::Contains("fluid.initial_velocity.amplitude: a linear standing wave needs an amplitude of "
                                    "at most 10 % of the depth"));
  CHECK_THROWS_WITH(read(sloshing_case, {{"fluid.geometry.type", "overflow_tank", ""}}),
                    Catch::Contains("fluid.initial_velocity.type: a standing wave needs fluid.geometry.type "
                                    "rectangular_tank"));
}

// The fluid model's own defaults (FluidModel, which the unit tests construct) are
// the case file's (case_schema_fluid.cpp): a case that leaves the keys out gets
// the model the tests check.
TEST_CASE("a case without the solver's optional keys gets FluidModel's defaults", "[fluid_case]") {
  const FluidModel defaults;
  const FluidModel read_model = read(testing::with_line(sloshing_case, 10, "")).model;
  CHECK(read_model.preconditioner_radius == defaults.preconditioner_radius);
  CHECK(read_model.density_error_weight == defaults.density_error_weight);
  CHECK(read_model.free_surface_threshold == defaults.free_surface_threshold);
  CHECK(read_model.shifting == defaults.shifting);
  CHECK(read_model.shifting_coefficient == defaults.shifting_coefficient);
  CHECK(read_model.close_pair_distance == defaults.close_pair_distance);
}

// fluid.smoothing_length_ratio, when not given, is the kernel's
// (default_smoothing_length_ratio(), kernel.hpp): the quartic spline's 1.1 keeps it
// out of its pairing instability, Wendland C2's 1.5 is the least that sums to 1.
TEST_CASE("a case without a smoothing length takes its kernel's", "[fluid_case]") {
  const double spacing = 0.02;
  CHECK(read(sloshing_case).model.smoothing_length == Approx(1.2 * spacing).epsilon(1e-15));
  CHECK(read(sloshing_case, {{"fluid.kernel", "quartic_spline", ""}}).model.smoothing_length ==
        Approx(1.1 * spacing).epsilon(1e-15));
  CHECK(read(sloshing_case, {{"fluid.kernel", "wendland_c2", ""}}).model.smoothing_length ==
        Approx(1.5 * spacing).epsilon(1e-15));
  CHECK(read(sloshing_case, {{"fluid.kernel", "quartic_spline", ""}, {"fluid.smoothing_length_ratio", "1.3", ""}})
            .model.smoothing_length == Approx(1.3 * spacing).epsilon(1e-15));
}
