#pragma once
// Who sends what, and when, in each scheme (PROTOCOL.md, "Schemes").
//
// Explicit schemes: every window ends with each program sending its output
// (fluid: window-average forces; structure: displacements) and receiving the
// partner's. A program "lags" when it uses the partner's output of the
// previous window: both do in parallel staggered coupling, the first program
// does in sequential staggered coupling; the second program uses the first's
// output of the same window, so it receives one message ahead.
// Implicit schemes: one program, the controller, measures the residual,
// accelerates and decides whether the window is accepted: the second program
// in serial mode, the structure in parallel mode.
#include "coupling/settings.hpp"

namespace tankfsi::coupling {

/// True when `side` uses its partner's output of the previous window.
[[nodiscard]] inline bool lags(const CouplingSettings& s, Side side) {
  return s.scheme == Scheme::parallel_staggered || side == s.first;
}

/// True when `side` is the implicit scheme's controller.
[[nodiscard]] inline bool controls(const CouplingSettings& s, Side side) {
  if (!s.is_implicit()) return false;
  if (s.implicit_mode == ImplicitMode::parallel) return side == Side::structure;
  return side != s.first;
}

/// Explicit schemes: whether `side` sends its output at the end of a window
/// (the last window's output is needed only by a partner that does not lag).
[[nodiscard]] inline bool sends_output(const CouplingSettings& s, Side side, bool last_window) {
  return !last_window || !lags(s, other(side));
}

/// Explicit schemes: whether `side` receives at the end of a window (nothing
/// is needed after the last one).
[[nodiscard]] inline bool receives_input(bool last_window) { return !last_window; }

}  // namespace tankfsi::coupling
