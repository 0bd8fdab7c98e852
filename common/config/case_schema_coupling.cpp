#include "common/config/case_schema.hpp"

namespace tankfsi {

// Coupling of the two programs (METHOD.md section 4, eqs 16-18).
std::vector<KeySpec> coupling_keys() {
  const std::vector<std::string> implicit{"implicit"};
  return {
      choice_key("coupling.scheme", {"parallel_staggered", "sequential_staggered", "implicit"},
                 "Coupling scheme: the paper's parallel or sequential staggered, or implicit (strong).")
          .is_required(),
      real_key("coupling.time_window", "Coupling interval dt_c between data exchanges.").unit_is("s").is_required().above(0),
      choice_key("coupling.structure_load", {"ramp", "window_average"},
                 "How the structure applies the fluid's window-average force over a window: ramp (eq 17, "
                 "with coupling.ramp_chi) or window_average (held constant: the window's impulse exactly, "
                 "no zig-zag or lag; stable where the liquid's added mass outweighs the structure).")
          .default_is("ramp"),
      real_key("coupling.ramp_chi", "Ramp parameter chi of eq 17: 1 is smooth, 2 conserves each window's impulse.")
          .default_is("1").at_least(1).at_most(2).only_when("coupling.structure_load", {"ramp"}),
      choice_key("coupling.added_mass", {"none", "computed"},
                 "Added-mass partitioning (coupling/PROTOCOL.md, 'Added mass'): none (the paper), or computed: "
                 "at t = 0 the fluid computes the added-mass operator of the wetted surface with its own "
                 "pressure equation (one solve per interface vertex), the structure carries it in its "
                 "inertia, and the fluid's forces leave out the impulse its liquid gives for the wall's change "
                 "of velocity at each window start (one more pressure solve per window). Keeps staggered "
                 "coupling stable where the liquid outweighs the wall.")
          .default_is("none"),
      choice_key("coupling.first", {"fluid", "structure"},
                 "Which program advances a window first (sequential staggered and serial implicit).")
          .default_is("fluid").only_when("coupling.scheme", {"sequential_staggered", "implicit"}),
      choice_key("coupling.implicit.mode", {"serial", "parallel"},
                 "serial: the programs take turns within a window (the first as coupling.first); "
                 "parallel: both advance the window at once and both interface fields are accelerated.")
          .default_is("serial").only_when("coupling.scheme", implicit),
      choice_key("coupling.implicit.on_nonconvergence", {"stop", "accept"},
                 "What a window that has not converged in max_iterations does: stop the run with a "
                 "diagnostic, or accept the last iterate and go on (counted in the summary).")
          .default_is("stop").only_when("coupling.scheme", implicit),
      integer_key("coupling.implicit.max_iterations", "Most coupling iterations in one window.")
          .default_is("30").at_least(1).only_when("coupling.scheme", implicit),
      real_key("coupling.implicit.relative_tolerance",
               "Convergence when the interface residual falls below this fraction of the interface values.")
          .default_is("1e-4").above(0).below(1).only_when("coupling.scheme", implicit),
      real_key("coupling.implicit.absolute_tolerance", "Convergence when the interface residual norm falls below this.")
          .default_is("0").at_least(0).only_when("coupling.scheme", implicit),
      choice_key("coupling.acceleration.type", {"constant", "aitken", "iqn_ils"},
                 "Acceleration of implicit coupling iterations.")
          .default_is("aitken").only_when("coupling.scheme", implicit),
      real_key("coupling.acceleration.initial_relaxation", "Under-relaxation factor of the first iteration.")
          .default_is("0.5").above(0).at_most(1).only_when("coupling.scheme", implicit),
      integer_key("coupling.acceleration.reused_windows", "Past windows whose residuals IQN-ILS reuses.")
          .default_is("8").at_least(0).only_when("coupling.scheme", implicit),
      real_key("coupling.acceleration.filter_tolerance", "QR filter threshold of IQN-ILS.")
          .default_is("0.01").above(0).below(1).only_when("coupling.scheme", implicit),
      real_key("coupling.timeout", "Longest wait for the partner's data before the job is stopped.")
          .unit_is("s").default_is("600").above(0),
  };
}

}  // namespace tankfsi
