#pragma once
// The readers under fuzzing take a file path (as the programs give them), so each
// input is written to one scratch file per fuzzing process and read back from
// there. The file lives in /dev/shm when it exists (no disk traffic at thousands
// of inputs per second), else in the temporary directory.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace tankfsi::fuzz {

/// Writes the input to this process's scratch file with the given extension
/// (".yaml", ".stl", ...) and returns its path.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  static const std::filesystem::path folder =
      std::filesystem::exists("/dev/shm") ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
  const std::filesystem::path file = folder / ("tankfsi_fuzz_" + std::to_string(::getpid()) + extension);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace tankfsi::fuzz
