#pragma once
// The readers under fuzzing take a file path (as the programs give them), so each
// input is written to one scratch file per fuzzing process and read back from
// there. The file lives in /dev/shm when it exists (no disk traffic at thousands
// of inputs per second), else in the temporary directory; it is removed when
// the process exits (libFuzzer ends its runs with exit()).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace tankfsi::fuzz {

/// Writes the input to this process's scratch file with the given extension
/// (".yaml", ".stl", ...) and returns its path. One extension per process:
/// the file is made once, at the first call.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  struct ScratchFile {
    std::filesystem::path path;
    ~ScratchFile() {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
  };
  static const std::filesystem::path folder =
      std::filesystem::exists("/dev/shm") ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
  static const ScratchFile scratch{folder / ("tankfsi_fuzz_" + std::to_string(::getpid()) + extension)};
  const std::filesystem::path& file = scratch.path;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace tankfsi::fuzz
