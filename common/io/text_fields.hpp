#pragma once
// Small helpers of the text readers (Gmsh MSH, ground-motion CSV): trimming
// and splitting a line into its whitespace-separated words.
#include <algorithm>
#include <string_view>
#include <vector>

namespace tankfsi {

/// `text` without leading and trailing blanks, tabs and carriage returns.
inline std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

/// The words of `line`, separated by blanks, tabs or carriage returns.
inline std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t begin = 0;
  while ((begin = line.find_first_not_of(" \t\r", begin)) != std::string_view::npos) {
    const std::size_t end = std::min(line.find_first_of(" \t\r", begin), line.size());
    words.push_back(line.substr(begin, end - begin));
    begin = end;
  }
  return words;
}

}  // namespace tankfsi
