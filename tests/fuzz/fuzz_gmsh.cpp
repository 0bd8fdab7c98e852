// libFuzzer target: the Gmsh MSH 4.1 reader (the one parser both programs use)
// through the fluid's surface reader. Any input must either read or raise
// ConfigError naming the file and line; anything else is a finding.
#include "common/config/config_error.hpp"
#include "sph_solver/walls/gmsh_reader.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)tankfsi::sph::read_gmsh_surface(tankfsi::fuzz::input_file(data, size, ".msh"));
  } catch (const tankfsi::ConfigError&) {
  }
  return 0;
}
