// libFuzzer target: the K-NET ASCII record reader. Any input must either read
// or raise ConfigError naming the file and line; anything else is a finding.
#include "common/config/config_error.hpp"
#include "common/excitation/knet_record.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)tankfsi::read_knet_record(tankfsi::fuzz::input_file(data, size, ".NS"), 10.0);
  } catch (const tankfsi::ConfigError&) {
  }
  return 0;
}
