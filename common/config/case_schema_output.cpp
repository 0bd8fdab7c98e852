#include "common/config/case_schema.hpp"

namespace tankfsi {

std::vector<KeySpec> output_keys() {
  return {
      output_path_key("output.dir",
                      "Run folder for all results; {case} is the case name. An existing run of the same "
                      "program there is never overwritten.")
          .default_is("runs/{case}"),
      real_key("output.field_interval", "Interval between HDF5 field snapshots.").unit_is("s").default_is("0.1").above(0),
      real_key("output.probe_interval", "Interval between probe samples.").unit_is("s").default_is("0.01").above(0),
      real_key("output.checkpoint_interval",
               "Simulated time between checkpoints (RUN/checkpoints/, the last two kept; --restart continues "
               "from one); 0: only at the end and when the job gets SIGTERM or SIGUSR1. A coupled job "
               "writes them at the end of the first coupling window at or after each multiple.")
          .unit_is("s").default_is("0").at_least(0),
      choice_key("output.log_level", {"error", "warning", "info", "debug"}, "Least severe message written.")
          .default_is("info"),
      boolean_key("output.plots", "Write plots and report.md at the end of the run.").default_is("true"),
  };
}

}  // namespace tankfsi
