// libFuzzer target: the STL reader (ASCII and binary) and the wall checks a
// read mesh goes through before filling. The reader must either return a mesh
// or raise ConfigError; the checks must answer for any mesh it returns.
#include "common/config/config_error.hpp"
#include "sph_solver/walls/stl_reader.hpp"
#include "sph_solver/walls/wall_mesh_check.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto mesh = tankfsi::sph::read_stl(tankfsi::fuzz::input_file(data, size, ".stl"));
    (void)tankfsi::sph::wall_mesh_problem(mesh, {.dimension = 3, .fill_level = 0.5});
  } catch (const tankfsi::ConfigError&) {
  }
  return 0;
}
