#include "common/log/stage_timers.hpp"

#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace tankfsi {

StageTimers::Scope::Scope(StageTimers& timers, std::size_t index)
    : timers_(timers), index_(index), start_(std::chrono::steady_clock::now()) {
  PetscLogStagePush(timers_.stages_[index_].petsc_stage);
}

StageTimers::Scope::~Scope() {
  PetscLogStagePop();
  auto& stage = timers_.stages_[index_];
  stage.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  ++stage.calls;
}

StageTimers::Scope StageTimers::time(const std::string& stage) {
  for (std::size_t i = 0; i < stages_.size(); ++i)
    if (stages_[i].name == stage) return Scope(*this, i);
  Stage added;
  added.name = stage;
  // PETSc's stages are process-wide and refuse a name twice: a second set of
  // timers (a second solver in one process) shares the stage of that name.
  PetscLogStage existing = -1;
  if (PetscLogStageGetId(stage.c_str(), &existing) == 0 && existing >= 0)
    added.petsc_stage = existing;
  else if (PetscLogStageRegister(stage.c_str(), &added.petsc_stage) != 0)
    throw std::runtime_error("PETSc could not register log stage " + stage);
  stages_.push_back(added);
  return Scope(*this, stages_.size() - 1);
}

const StageTimers::Stage* StageTimers::find(const std::string& name) const {
  for (const auto& s : stages_)
    if (s.name == name) return &s;
  return nullptr;
}

double StageTimers::seconds(const std::string& stage) const {
  const Stage* s = find(stage);
  return s ? s->seconds : 0.0;
}

long StageTimers::calls(const std::string& stage) const {
  const Stage* s = find(stage);
  return s ? s->calls : 0;
}

nlohmann::json StageTimers::to_json() const {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& s : stages_) out[s.name] = {{"seconds", s.seconds}, {"calls", s.calls}};
  return out;
}

std::string StageTimers::table() const {
  std::ostringstream out;
  out << std::left << std::setw(20) << "stage" << std::right << std::setw(12) << "seconds" << std::setw(10) << "calls\n";
  for (const auto& s : stages_)
    out << std::left << std::setw(20) << s.name << std::right << std::setw(12) << std::fixed << std::setprecision(3)
        << s.seconds << std::setw(10) << s.calls << "\n";
  return out.str();
}

}  // namespace tankfsi
