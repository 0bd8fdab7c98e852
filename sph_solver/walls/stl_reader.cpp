#include "sph_solver/walls/stl_reader.hpp"

#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "common/config/config_error.hpp"

namespace tankfsi::sph {

namespace {

constexpr std::size_t header_bytes = 80;
constexpr std::size_t count_bytes = 4;
constexpr std::size_t facet_bytes = 50;  // 12 float32 (normal, 3 vertices) + uint16 attribute

using Corners = std::array<Eigen::Vector3d, 3>;

// Shared-vertex mesh from triangle soup, merging bit-equal coordinates (see header).
TriangleMesh merge_vertices(const std::vector<Corners>& soup) {
  std::map<std::array<double, 3>, int> index_of;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(soup.size());
  for (const auto& corners : soup) {
    std::array<int, 3> tri{};
    for (std::size_t k = 0; k < 3; ++k) {
      // + 0.0 turns −0 into +0, so the two zeros are one vertex.
      const std::array<double, 3> key{corners[k].x() + 0.0, corners[k].y() + 0.0, corners[k].z() + 0.0};
      const auto [it, inserted] = index_of.try_emplace(key, static_cast<int>(vertices.size()));
      if (inserted) vertices.emplace_back(key[0], key[1], key[2]);
      tri[k] = it->second;
    }
    triangles.push_back(tri);
  }
  return TriangleMesh(std::move(vertices), std::move(triangles));
}

std::uint32_t little_endian_u32(const unsigned char* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8) |
         (static_cast<std::uint32_t>(bytes[2]) << 16) | (static_cast<std::uint32_t>(bytes[3]) << 24);
}

double little_endian_float(const unsigned char* bytes) {
  return static_cast<double>(std::bit_cast<float>(little_endian_u32(bytes)));
}

std::vector<Corners> read_binary(const std::string& content, const std::filesystem::path& file) {
  const auto fail = [&](const std::string& message) { return ConfigError(Origin{file.string(), 0}, "", message); };
  const auto* bytes = reinterpret_cast<const unsigned char*>(content.data());
  const std::size_t n = little_endian_u32(bytes + header_bytes);
  const std::size_t expected = header_bytes + count_bytes + facet_bytes * n;
  if (content.size() < expected) {
    const std::size_t complete = (content.size() - header_bytes - count_bytes) / facet_bytes;
    throw fail("truncated binary STL: the header announces " + std::to_string(n) + " triangles (" +
               std::to_string(expected) + " bytes) but the file ends at byte offset " +
               std::to_string(content.size()) + ", inside triangle " + std::to_string(complete) +
               " (triangles are numbered from 0)");
  }
  if (content.size() > expected)
    throw fail("binary STL with " + std::to_string(content.size() - expected) +
               " unexpected bytes after the last of its " + std::to_string(n) + " triangles (byte offset " +
               std::to_string(expected) + ")");
  if (n == 0) throw fail("binary STL with zero triangles");
  std::vector<Corners> soup(n);
  for (std::size_t t = 0; t < n; ++t) {
    const std::size_t facet = header_bytes + count_bytes + facet_bytes * t;
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t offset = facet + 12 + 12 * k + 4 * c;  // skip the 12-byte normal
        const double value = little_endian_float(bytes + offset);
        if (!std::isfinite(value))
          throw fail("non-finite coordinate in triangle " + std::to_string(t) + ", vertex " + std::to_string(k) +
                     " at byte offset " + std::to_string(offset));
        soup[t][k][static_cast<Eigen::Index>(c)] = value;
      }
  }
  return soup;
}

// Tokens of an ASCII STL with their 1-based line numbers.
class AsciiTokens {
 public:
  AsciiTokens(const std::string& content, const std::filesystem::path& file) : file_(file) {
    std::istringstream lines(content);
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
      ++number;
      std::istringstream words(line);
      std::string word;
      while (words >> word) tokens_.push_back({word, number});
    }
    last_line_ = number;
  }

  [[nodiscard]] bool done() const { return next_ >= tokens_.size(); }
  [[nodiscard]] int line() const { return done() ? last_line_ : tokens_[next_].line; }
  [[nodiscard]] ConfigError error(const std::string& message) const {
    return ConfigError(Origin{file_.string(), line()}, "", message);
  }
  [[nodiscard]] bool peek_is(std::string_view keyword) const { return !done() && lowered(next_) == keyword; }

  // Consumes the next token, which must be `keyword` (case-insensitive).
  void expect(std::string_view keyword) {
    if (done()) throw error("unexpected end of file, expected '" + std::string(keyword) + "'");
    if (lowered(next_) != keyword)
      throw error("expected '" + std::string(keyword) + "', found '" + tokens_[next_].text + "'");
    ++next_;
  }

  double number(const char* what) {
    if (done()) throw error(std::string("unexpected end of file, expected ") + what);
    const std::string& text = tokens_[next_].text;
    std::string_view digits = text;
    if (digits.starts_with('+')) digits.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
      throw error(std::string("expected ") + what + ", found '" + text + "'");
    if (!std::isfinite(value)) throw error(std::string("expected ") + what + ", found the non-finite '" + text + "'");
    ++next_;
    return value;
  }

  // Skips the rest of the current line (a solid's optional name).
  void skip_line() {
    const int current = tokens_[next_ - 1].line;
    while (!done() && tokens_[next_].line == current) ++next_;
  }

 private:
  struct Token {
    std::string text;
    int line;
  };
  [[nodiscard]] std::string lowered(std::size_t i) const {
    std::string text = tokens_[i].text;
    for (char& ch : text) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return text;
  }

  std::filesystem::path file_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  int last_line_ = 0;
};

// solid name / (facet normal nx ny nz / outer loop / vertex x y z ×3 / endloop / endfacet)* /
// endsolid name; several solids may follow each other in one file.
std::vector<Corners> read_ascii(const std::string& content, const std::filesystem::path& file) {
  AsciiTokens tokens(content, file);
  std::vector<Corners> soup;
  while (!tokens.done()) {
    tokens.expect("solid");
    tokens.skip_line();
    while (!tokens.peek_is("endsolid")) {
      tokens.expect("facet");
      tokens.expect("normal");
      for (int c = 0; c < 3; ++c) static_cast<void>(tokens.number("a normal component"));
      tokens.expect("outer");
      tokens.expect("loop");
      Corners corners;
      for (auto& corner : corners) {
        tokens.expect("vertex");
        for (int c = 0; c < 3; ++c) corner[c] = tokens.number("a vertex coordinate");
      }
      tokens.expect("endloop");
      tokens.expect("endfacet");
      soup.push_back(corners);
    }
    tokens.expect("endsolid");
    tokens.skip_line();
  }
  if (soup.empty()) throw tokens.error("ASCII STL with zero triangles");
  return soup;
}

bool starts_with_solid(const std::string& content) {
  const auto first = content.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return false;
  std::string word = content.substr(first, 5);
  for (char& ch : word) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return word == "solid";
}

// True if the file has no control characters other than white space: an ASCII STL.
// A binary STL nearly always has some (the triangle count at byte 80 has a zero byte
// below 2^24 triangles), which tells a truncated binary file with a "solid..." header
// from a broken ASCII one.
bool is_text(const std::string& content) {
  for (const char ch : content) {
    const auto byte = static_cast<unsigned char>(ch);
    if ((byte < 0x20 && std::isspace(byte) == 0) || byte == 0x7f) return false;
  }
  return true;
}

}  // namespace

TriangleMesh read_stl(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError(Origin{file.string(), 0}, "", std::string("cannot read STL file: ") + std::strerror(errno));
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  const bool binary_size_matches =
      content.size() >= header_bytes + count_bytes &&
      content.size() == header_bytes + count_bytes +
                            facet_bytes * little_endian_u32(reinterpret_cast<const unsigned char*>(content.data()) +
                                                            header_bytes);
  if (binary_size_matches) return merge_vertices(read_binary(content, file));
  if (starts_with_solid(content) && is_text(content)) return merge_vertices(read_ascii(content, file));
  if (content.size() < header_bytes + count_bytes)
    throw ConfigError(Origin{file.string(), 0}, "",
                      "not an STL file: " + std::to_string(content.size()) +
                          " bytes, too short for binary STL, and it does not start with 'solid'");
  return merge_vertices(read_binary(content, file));  // reports the size mismatch
}

}  // namespace tankfsi::sph
