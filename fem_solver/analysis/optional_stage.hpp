#pragma once
// A stage timing that may have no timers to report to (library use without a
// program around it, as in the unit tests).
#include <memory>
#include <string>

#include "common/log/stage_timers.hpp"

namespace tankfsi::fem {

using OptionalStage = std::unique_ptr<StageTimers::Scope>;

/// Times `stage` until the result is destroyed; nothing when `timers` is null.
[[nodiscard]] inline OptionalStage time_stage(StageTimers* timers, const std::string& stage) {
  // new T(prvalue): the scope is built in place (it can be neither copied nor moved).
  return timers == nullptr ? nullptr : OptionalStage(new StageTimers::Scope(timers->time(stage)));
}

}  // namespace tankfsi::fem
