#include "common/config/case_schema.hpp"

namespace tankfsi {

std::vector<KeySpec> top_level_keys() {
  return {
      text_key("title", "One line saying what the case is; printed in the log and the report.").default_is("''"),
      real_key("end_time", "Simulated time at which a time-domain run stops.").unit_is("s").above(0),
  };
}

const Schema& case_schema() {
  static const Schema schema = [] {
    Schema s;
    for (auto section : {top_level_keys, fluid_keys, structure_keys, coupling_keys, excitation_keys, output_keys})
      for (auto& key : section()) s.keys.push_back(std::move(key));
    return s;
  }();
  return schema;
}

}  // namespace tankfsi
