// libFuzzer target: the case-file reader (YAML parse, schema validation,
// defaults). Any input must either load or raise ConfigError with a location;
// any other exception, a crash or a sanitizer report is a finding.
#include "common/config/case_config.hpp"
#include "common/config/case_schema.hpp"
#include "common/config/config_error.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const tankfsi::Schema& schema = tankfsi::case_schema();
  try {
    const auto config = tankfsi::CaseConfig::load(tankfsi::fuzz::input_file(data, size, ".yaml"), {}, schema);
    (void)config.resolved_yaml();
  } catch (const tankfsi::ConfigError&) {
  }
  return 0;
}
