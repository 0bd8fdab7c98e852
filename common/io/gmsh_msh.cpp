#include "common/io/gmsh_msh.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string_view>

#include "common/io/text_fields.hpp"

namespace tankfsi::gmsh {

namespace {

struct ElementType {
  int nodes;
  const char* name;
};

// Gmsh's element types 1..19 (first and second order); index = type.
constexpr std::array<ElementType, 20> element_types{{
    {0, ""},
    {2, "2-node line"},
    {3, "3-node triangle"},
    {4, "4-node quadrangle"},
    {4, "4-node tetrahedron"},
    {8, "8-node hexahedron"},
    {6, "6-node prism"},
    {5, "5-node pyramid"},
    {3, "3-node line"},
    {6, "6-node triangle"},
    {9, "9-node quadrangle"},
    {10, "10-node tetrahedron"},
    {27, "27-node hexahedron"},
    {18, "18-node prism"},
    {14, "14-node pyramid"},
    {1, "point"},
    {8, "8-node quadrangle"},
    {20, "20-node hexahedron"},
    {15, "15-node prism"},
    {13, "13-node pyramid"},
}};

constexpr std::array<const char*, 4> entity_kinds{"point", "curve", "surface", "volume"};

// The file's lines with a cursor; errors name the file and the last line read.
class Lines {
 public:
  Lines(const std::string& content, std::filesystem::path file) : file_(std::move(file)) {
    std::istringstream in(content);
    std::string line;
    while (std::getline(in, line)) lines_.push_back(line);
  }

  [[nodiscard]] bool done() const { return next_ >= lines_.size(); }
  [[nodiscard]] int line() const { return static_cast<int>(next_); }  // 1-based number of the last line read

  /// The next line, trimmed; `inside` names the section for the end-of-file error.
  std::string_view next(std::string_view inside) {
    if (done()) throw error("unexpected end of file inside $" + std::string(inside));
    return trimmed(lines_[next_++]);
  }

  /// The next line split into at least `minimum` tokens.
  std::vector<std::string_view> tokens(std::string_view inside, std::size_t minimum, const char* what) {
    auto words = split_words(next(inside));
    if (words.size() < minimum)
      throw error(std::string("expected ") + what + " (" + std::to_string(minimum) + " numbers), found " +
                  std::to_string(words.size()));
    return words;
  }

  void expect_end(std::string_view section) {
    const std::string end = "$End" + std::string(section);
    const std::string_view found = next(section);
    if (found != end) throw error("expected " + end + ", found '" + std::string(found) + "'");
  }

  [[nodiscard]] ConfigError error(const std::string& message) const {
    return ConfigError(Origin{file_.string(), line()}, "", message);
  }

 private:
  std::filesystem::path file_;
  std::vector<std::string> lines_;
  std::size_t next_ = 0;
};

std::int64_t integer(std::string_view token, const Lines& in, const char* what) {
  if (token.starts_with('+')) token.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || ec != std::errc() || end != token.data() + token.size())
    throw in.error(std::string("expected ") + what + " (an integer), found '" + std::string(token) + "'");
  return value;
}

int small_integer(std::string_view token, const Lines& in, const char* what) {
  const std::int64_t value = integer(token, in, what);
  if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
    throw in.error(std::string(what) + " " + std::string(token) + " is out of range");
  return static_cast<int>(value);
}

std::int64_t non_negative(std::string_view token, const Lines& in, const char* what) {
  const std::int64_t value = integer(token, in, what);
  if (value < 0) throw in.error(std::string(what) + " must not be negative, found " + std::string(token));
  return value;
}

double real(std::string_view token, const Lines& in, const char* what) {
  if (token.starts_with('+')) token.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || ec != std::errc() || end != token.data() + token.size())
    throw in.error(std::string("expected ") + what + " (a number), found '" + std::string(token) + "'");
  if (!std::isfinite(value)) throw in.error(std::string("non-finite ") + what + " '" + std::string(token) + "'");
  return value;
}

void read_format(Lines& in) {
  const auto words = in.tokens("MeshFormat", 3, "version, file type and data size");
  if (words[0] != "4.1")
    throw in.error("unsupported MSH version " + std::string(words[0]) +
                   ": only version 4.1 ASCII is read; re-export with Mesh.MshFileVersion = 4.1 "
                   "(gmsh -format msh41)");
  const std::int64_t file_type = integer(words[1], in, "file type");
  if (file_type == 1)
    throw in.error("binary MSH files are not supported: re-export as ASCII (Mesh.Binary = 0)");
  if (file_type != 0) throw in.error("unknown MSH file type " + std::string(words[1]) + " (0 is ASCII)");
  static_cast<void>(non_negative(words[2], in, "data size"));
  in.expect_end("MeshFormat");
}

void read_physical_names(Lines& in, MshFile& msh) {
  const std::int64_t n = non_negative(in.tokens("PhysicalNames", 1, "the number of names")[0], in, "number of names");
  for (std::int64_t k = 0; k < n; ++k) {
    const std::string_view line = in.next("PhysicalNames");
    const auto words = split_words(line);
    const auto open = line.find('"');
    const auto close = line.rfind('"');
    if (words.size() < 3 || open == std::string_view::npos || close == open)
      throw in.error("expected: dimension, tag, \"name\"");
    const int dimension = small_integer(words[0], in, "physical dimension");
    const int tag = small_integer(words[1], in, "physical tag");
    msh.physical_names[{dimension, tag}] = std::string(line.substr(open + 1, close - open - 1));
  }
  in.expect_end("PhysicalNames");
}

// Points: tag, x y z, count, physical tags. Curves, surfaces, volumes: tag,
// bounding box (6 numbers), count, physical tags, then their bounding entities.
void read_entities(Lines& in, MshFile& msh) {
  const auto header = in.tokens("Entities", 4, "the numbers of points, curves, surfaces and volumes");
  std::array<std::int64_t, 4> n{};
  for (std::size_t d = 0; d < 4; ++d) n[d] = non_negative(header[d], in, "number of entities");
  for (int dimension = 0; dimension < 4; ++dimension) {
    const std::size_t count_at = dimension == 0 ? 4 : 7;
    for (std::int64_t k = 0; k < n[static_cast<std::size_t>(dimension)]; ++k) {
      const std::string what = std::string("a ") + entity_kinds[static_cast<std::size_t>(dimension)] +
                               (dimension == 0 ? ": tag, x y z" : ": tag, bounding box") + ", number of physical tags";
      const auto words = in.tokens("Entities", count_at + 1, what.c_str());
      const int tag = small_integer(words[0], in, "entity tag");
      const std::int64_t groups = non_negative(words[count_at], in, "number of physical tags");
      if (words.size() < count_at + 1 + static_cast<std::size_t>(groups))
        throw in.error(std::string(entity_kinds[static_cast<std::size_t>(dimension)]) + " " + std::string(words[0]) +
                       " announces " + std::to_string(groups) + " physical tags but the line ends before them");
      std::vector<int>& tags = msh.entity_groups[{dimension, tag}];
      for (std::int64_t g = 0; g < groups; ++g)
        tags.push_back(small_integer(words[count_at + 1 + static_cast<std::size_t>(g)], in, "physical tag"));
    }
  }
  msh.has_entities = true;
  in.expect_end("Entities");
}

// The header of $Nodes and $Elements: number of blocks, number of items, minimum and
// maximum tag; the item count is checked against the blocks' at the end.
struct BlockedSection {
  std::int64_t blocks = 0;
  std::int64_t total = 0;
};

BlockedSection read_blocked_header(Lines& in, std::string_view section, const char* items) {
  const std::string what = std::string("blocks, ") + items + ", minimum and maximum tag";
  const auto header = in.tokens(section, 4, what.c_str());
  return {non_negative(header[0], in, "number of blocks"), non_negative(header[1], in, "number of items")};
}

void expect_total(Lines& in, std::string_view section, const char* items, const BlockedSection& header,
                  std::int64_t found) {
  if (found != header.total)
    throw in.error("the $" + std::string(section) + " header announces " + std::to_string(header.total) + " " + items +
                   " but its blocks hold " + std::to_string(found));
  in.expect_end(section);
}

// Blocks of: entity dim, entity tag, parametric, count; the node tags one per line; then
// their coordinates x y z (plus dim parametric coordinates when parametric).
void read_nodes(Lines& in, MshFile& msh) {
  const BlockedSection header = read_blocked_header(in, "Nodes", "nodes");
  std::int64_t found = 0;
  for (std::int64_t b = 0; b < header.blocks; ++b) {
    const auto block = in.tokens("Nodes", 4, "a node block: entity dimension, entity tag, parametric, count");
    const std::int64_t dimension = non_negative(block[0], in, "entity dimension");
    const bool parametric = integer(block[2], in, "parametric flag") != 0;
    const std::int64_t n = non_negative(block[3], in, "number of nodes in the block");
    const std::size_t first = msh.nodes.size();
    for (std::int64_t k = 0; k < n; ++k) {
      const auto words = in.tokens("Nodes", 1, "a node tag");
      const std::int64_t tag = integer(words[0], in, "node tag");
      if (tag <= 0) throw in.error("node tag " + std::string(words[0]) + " is not positive");
      const auto [it, inserted] = msh.node_index.try_emplace(tag, static_cast<int>(msh.nodes.size()));
      if (!inserted) throw in.error("node tag " + std::to_string(tag) + " appears twice");
      msh.nodes.push_back(MshNode{tag, Eigen::Vector3d::Zero(), static_cast<int>(dimension), in.line()});
    }
    const std::size_t expected = 3 + (parametric ? static_cast<std::size_t>(dimension) : 0);
    for (std::int64_t k = 0; k < n; ++k) {
      MshNode& node = msh.nodes[first + static_cast<std::size_t>(k)];
      const auto words = in.tokens("Nodes", expected, "node coordinates");
      if (words.size() != expected)
        throw in.error("expected " + std::to_string(expected) + " numbers for node " + std::to_string(node.tag) +
                       ", found " + std::to_string(words.size()));
      node.position = Eigen::Vector3d(real(words[0], in, "x"), real(words[1], in, "y"), real(words[2], in, "z"));
    }
    found += n;
  }
  expect_total(in, "Nodes", "nodes", header, found);
}

// Blocks of: entity dim, entity tag, element type, count; one element per line: tag, node tags.
void read_elements(Lines& in, MshFile& msh, const BlockCheck& check) {
  const BlockedSection header = read_blocked_header(in, "Elements", "elements");
  std::int64_t found = 0;
  for (std::int64_t b = 0; b < header.blocks; ++b) {
    const auto words = in.tokens("Elements", 4, "an element block: entity dimension, entity tag, type, count");
    MshElementBlock block;
    block.dimension = static_cast<int>(std::min<std::int64_t>(non_negative(words[0], in, "entity dimension"), 4));
    block.entity = small_integer(words[1], in, "entity tag");
    block.type = small_integer(words[2], in, "element type");
    block.line = in.line();
    const std::int64_t n = non_negative(words[3], in, "number of elements in the block");
    if (check) check(msh, block);
    const int corners = element_node_count(block.type);
    for (std::int64_t k = 0; k < n; ++k) {
      const auto items = split_words(in.next("Elements"));
      if (corners > 0 ? items.size() != static_cast<std::size_t>(corners) + 1 : items.size() < 2)
        throw in.error("expected an element tag and " + (corners > 0 ? std::to_string(corners) : std::string("its")) +
                       " node tags, found " + std::to_string(items.size()) + " numbers");
      MshElement element;
      element.tag = integer(items[0], in, "element tag");
      element.line = in.line();
      for (std::size_t c = 1; c < items.size(); ++c) element.nodes.push_back(integer(items[c], in, "node tag"));
      block.elements.push_back(std::move(element));
    }
    found += n;
    msh.blocks.push_back(std::move(block));
  }
  expect_total(in, "Elements", "elements", header, found);
}

void skip_section(Lines& in, std::string_view name) {
  const std::string end = "$End" + std::string(name);
  for (std::string_view line = in.next(name); line != end; line = in.next(name)) continue;
}

}  // namespace

int element_node_count(int type) {
  return type > 0 && static_cast<std::size_t>(type) < element_types.size()
             ? element_types[static_cast<std::size_t>(type)].nodes
             : 0;
}

std::string element_type_name(int type) {
  return element_node_count(type) > 0 ? element_types[static_cast<std::size_t>(type)].name
                                      : "type " + std::to_string(type);
}

ConfigError MshFile::error_at(int line, const std::string& message) const {
  return ConfigError(Origin{file.string(), line}, "", message);
}

int MshFile::node(std::int64_t tag, int line) const {
  const auto it = node_index.find(tag);
  if (it == node_index.end()) throw error_at(line, "unknown node tag " + std::to_string(tag));
  return it->second;
}

const std::vector<int>& MshFile::groups_of(int dimension, int entity, int line) const {
  static const std::vector<int> none;
  if (!has_entities) return none;
  const auto it = entity_groups.find({dimension, entity});
  if (it == entity_groups.end()) {
    const std::string kind =
        dimension >= 0 && dimension < 4 ? entity_kinds[static_cast<std::size_t>(dimension)] : "entity";
    throw error_at(line, kind + " entity " + std::to_string(entity) + " of this element is not listed in $Entities");
  }
  return it->second;
}

int MshFile::physical_tag(int dimension, const std::string& name) const {
  for (const auto& [key, value] : physical_names)
    if (key.first == dimension && value == name) return key.second;
  return -1;
}

std::string MshFile::listed_names(int dimension) const {
  std::string known;
  for (const auto& [key, name] : physical_names)
    if (key.first == dimension) known += (known.empty() ? "'" : ", '") + name + "'";
  return known.empty() ? std::string("none") : known;
}

MshFile read_msh(const std::filesystem::path& file, const BlockCheck& check) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream)
    throw ConfigError(Origin{file.string(), 0}, "", std::string("cannot read Gmsh file: ") + std::strerror(errno));
  const std::string content((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  Lines in(content, file);
  MshFile msh;
  msh.file = file;
  bool first = true;
  while (!in.done()) {
    const std::string_view line = in.next("the file");
    if (line.empty()) continue;
    if (first && line != "$MeshFormat")
      throw in.error("not a Gmsh MSH file: expected $MeshFormat, found '" + std::string(line.substr(0, 40)) + "'");
    first = false;
    if (!line.starts_with('$')) throw in.error("expected a section ($Name), found '" + std::string(line) + "'");
    const std::string_view name = line.substr(1);
    if (name == "MeshFormat")
      read_format(in);
    else if (name == "PhysicalNames")
      read_physical_names(in, msh);
    else if (name == "Entities")
      read_entities(in, msh);
    else if (name == "Nodes")
      read_nodes(in, msh);
    else if (name == "Elements")
      read_elements(in, msh, check);
    else
      skip_section(in, name);
  }
  if (first) throw in.error("empty file: expected $MeshFormat");
  return msh;
}

}  // namespace tankfsi::gmsh
