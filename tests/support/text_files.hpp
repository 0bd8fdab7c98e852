#pragma once
// Small helpers for tests that write input files (meshes, records) and break them
// one line at a time.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "support/scratch_folder.hpp"

namespace tankfsi::testing {

/// Writes `content` byte for byte to folder/name and returns the path.
inline std::filesystem::path write_text(const ScratchFolder& folder, const std::string& name,
                                        const std::string& content) {
  const std::filesystem::path file = folder.file(name);
  std::ofstream(file, std::ios::binary) << content;
  return file;
}

/// The text with line `number` (1-based) replaced.
inline std::string with_line(const std::string& text, int number, const std::string& replacement) {
  std::istringstream in(text);
  std::string line, out;
  for (int i = 1; std::getline(in, line); ++i) out += (i == number ? replacement : line) + "\n";
  return out;
}

/// The 1-based number of the first line of `text` equal to `line`; throws
/// std::invalid_argument when there is none (a test that names a line its text
/// lacks is wrong).
inline int line_number(const std::string& text, const std::string& line) {
  std::istringstream in(text);
  std::string current;
  for (int i = 1; std::getline(in, current); ++i)
    if (current == line) return i;
  throw std::invalid_argument("line not found: " + line);
}

}  // namespace tankfsi::testing
