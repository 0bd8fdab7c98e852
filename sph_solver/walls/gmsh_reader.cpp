#include "sph_solver/walls/gmsh_reader.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "common/config/config_error.hpp"

namespace tankfsi::sph {

namespace {

constexpr int triangle_type = 2;
constexpr int quadrangle_type = 3;
constexpr int surface_dimension = 2;

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t begin = 0;
  while ((begin = line.find_first_not_of(" \t\r", begin)) != std::string_view::npos) {
    const std::size_t end = std::min(line.find_first_of(" \t\r", begin), line.size());
    tokens.push_back(line.substr(begin, end - begin));
    begin = end;
  }
  return tokens;
}

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
    auto words = split(next(inside));
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

  [[nodiscard]] ConfigError error(const std::string& message) const { return error_at(line(), message); }
  [[nodiscard]] ConfigError error_at(int number, const std::string& message) const {
    return ConfigError(Origin{file_.string(), number}, "", message);
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

struct SurfaceElement {
  std::array<std::int64_t, 4> nodes{};
  int corners = 3;  // 3 (triangle) or 4 (quadrangle)
  int surface = 0;  // entity tag
  int line = 0;
};

// Everything read from the file, before the selection and the vertex numbering.
struct Contents {
  std::map<int, std::string> names;                 // two-dimensional physical groups
  bool has_entities = false;
  std::map<int, std::vector<int>> surface_groups;   // surface entity -> physical tags
  std::vector<std::int64_t> node_tags;
  std::vector<Eigen::Vector3d> coordinates;
  std::unordered_map<std::int64_t, int> node_index;
  std::vector<SurfaceElement> elements;
};

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

void read_physical_names(Lines& in, Contents& contents) {
  const std::int64_t n = non_negative(in.tokens("PhysicalNames", 1, "the number of names")[0], in, "number of names");
  for (std::int64_t k = 0; k < n; ++k) {
    const std::string_view line = in.next("PhysicalNames");
    const auto words = split(line);
    const auto open = line.find('"');
    const auto close = line.rfind('"');
    if (words.size() < 3 || open == std::string_view::npos || close == open)
      throw in.error("expected: dimension, tag, \"name\"");
    const int dimension = small_integer(words[0], in, "physical dimension");
    const int tag = small_integer(words[1], in, "physical tag");
    if (dimension == surface_dimension) contents.names[tag] = std::string(line.substr(open + 1, close - open - 1));
  }
  in.expect_end("PhysicalNames");
}

// Points, curves and volumes are skipped line by line; surfaces give their physical
// tags: tag, bounding box (6 numbers), count, tags..., then the bounding curves.
void read_entities(Lines& in, Contents& contents) {
  const auto header = in.tokens("Entities", 4, "the numbers of points, curves, surfaces and volumes");
  std::array<std::int64_t, 4> n{};
  for (std::size_t d = 0; d < 4; ++d) n[d] = non_negative(header[d], in, "number of entities");
  for (std::int64_t k = 0; k < n[0] + n[1]; ++k) static_cast<void>(in.next("Entities"));
  for (std::int64_t k = 0; k < n[2]; ++k) {
    const auto words = in.tokens("Entities", 8, "a surface: tag, bounding box, number of physical tags");
    const int tag = small_integer(words[0], in, "surface tag");
    const std::int64_t groups = non_negative(words[7], in, "number of physical tags");
    if (words.size() < 8 + static_cast<std::size_t>(groups))
      throw in.error("surface " + std::string(words[0]) + " announces " + std::to_string(groups) +
                     " physical tags but the line ends before them");
    std::vector<int>& tags = contents.surface_groups[tag];
    for (std::int64_t g = 0; g < groups; ++g)
      tags.push_back(small_integer(words[8 + static_cast<std::size_t>(g)], in, "physical tag"));
  }
  for (std::int64_t k = 0; k < n[3]; ++k) static_cast<void>(in.next("Entities"));
  contents.has_entities = true;
  in.expect_end("Entities");
}

// Blocks of: entity dim, entity tag, parametric, count; the node tags one per line; then
// their coordinates x y z (plus dim parametric coordinates when parametric).
void read_nodes(Lines& in, Contents& contents) {
  const auto header = in.tokens("Nodes", 4, "blocks, nodes, minimum and maximum node tag");
  const std::int64_t blocks = non_negative(header[0], in, "number of blocks");
  const std::int64_t total = non_negative(header[1], in, "number of nodes");
  std::int64_t found = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    const auto block = in.tokens("Nodes", 4, "a node block: entity dimension, entity tag, parametric, count");
    const std::int64_t dimension = non_negative(block[0], in, "entity dimension");
    const bool parametric = integer(block[2], in, "parametric flag") != 0;
    const std::int64_t n = non_negative(block[3], in, "number of nodes in the block");
    const std::size_t first = contents.node_tags.size();
    for (std::int64_t k = 0; k < n; ++k) {
      const auto words = in.tokens("Nodes", 1, "a node tag");
      const std::int64_t tag = integer(words[0], in, "node tag");
      if (tag <= 0) throw in.error("node tag " + std::string(words[0]) + " is not positive");
      const auto [it, inserted] = contents.node_index.try_emplace(tag, static_cast<int>(contents.node_tags.size()));
      if (!inserted) throw in.error("node tag " + std::to_string(tag) + " appears twice");
      contents.node_tags.push_back(tag);
    }
    const std::size_t expected = 3 + (parametric ? static_cast<std::size_t>(dimension) : 0);
    for (std::int64_t k = 0; k < n; ++k) {
      const auto words = in.tokens("Nodes", expected, "node coordinates");
      if (words.size() != expected)
        throw in.error("expected " + std::to_string(expected) + " numbers for node " +
                       std::to_string(contents.node_tags[first + static_cast<std::size_t>(k)]) + ", found " +
                       std::to_string(words.size()));
      contents.coordinates.emplace_back(real(words[0], in, "x"), real(words[1], in, "y"), real(words[2], in, "z"));
    }
    found += n;
  }
  if (found != total)
    throw in.error("the $Nodes header announces " + std::to_string(total) + " nodes but its blocks hold " +
                   std::to_string(found));
  in.expect_end("Nodes");
}

// Blocks of: entity dim, entity tag, element type, count; one element per line: tag,
// node tags. Only surface blocks are parsed.
void read_elements(Lines& in, Contents& contents) {
  const auto header = in.tokens("Elements", 4, "blocks, elements, minimum and maximum element tag");
  const std::int64_t blocks = non_negative(header[0], in, "number of blocks");
  const std::int64_t total = non_negative(header[1], in, "number of elements");
  std::int64_t found = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    const auto block = in.tokens("Elements", 4, "an element block: entity dimension, entity tag, type, count");
    const std::int64_t dimension = non_negative(block[0], in, "entity dimension");
    const int entity = small_integer(block[1], in, "entity tag");
    const std::int64_t type = integer(block[2], in, "element type");
    const std::int64_t n = non_negative(block[3], in, "number of elements in the block");
    found += n;
    if (dimension != surface_dimension) {
      for (std::int64_t k = 0; k < n; ++k) static_cast<void>(in.next("Elements"));
      continue;
    }
    if (type != triangle_type && type != quadrangle_type)
      throw in.error("element type " + std::string(block[2]) + " on surface " + std::string(block[1]) +
                     " is not supported: only 3-node triangles (2) and 4-node quadrangles (3); "
                     "mesh with Mesh.ElementOrder = 1");
    const int corners = type == triangle_type ? 3 : 4;
    for (std::int64_t k = 0; k < n; ++k) {
      const auto words = split(in.next("Elements"));
      if (words.size() != static_cast<std::size_t>(corners) + 1)
        throw in.error("expected an element tag and " + std::to_string(corners) + " node tags, found " +
                       std::to_string(words.size()) + " numbers");
      SurfaceElement element;
      element.corners = corners;
      element.surface = entity;
      element.line = in.line();
      for (std::size_t c = 0; c < static_cast<std::size_t>(corners); ++c)
        element.nodes[c] = integer(words[c + 1], in, "node tag");
      contents.elements.push_back(element);
    }
  }
  if (found != total)
    throw in.error("the $Elements header announces " + std::to_string(total) + " elements but its blocks hold " +
                   std::to_string(found));
  in.expect_end("Elements");
}

void skip_section(Lines& in, std::string_view name) {
  const std::string end = "$End" + std::string(name);
  for (std::string_view line = in.next(name); line != end; line = in.next(name)) continue;
}

Contents read_contents(Lines& in) {
  Contents contents;
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
      read_physical_names(in, contents);
    else if (name == "Entities")
      read_entities(in, contents);
    else if (name == "Nodes")
      read_nodes(in, contents);
    else if (name == "Elements")
      read_elements(in, contents);
    else
      skip_section(in, name);
  }
  if (first) throw in.error("empty file: expected $MeshFormat");
  return contents;
}

// Physical tags of the selected group names; an unknown name lists the known ones.
std::set<int> selected_tags(const Contents& contents, const std::vector<std::string>& groups, const Lines& in) {
  std::set<int> tags;
  for (const auto& group : groups) {
    const auto it = std::find_if(contents.names.begin(), contents.names.end(),
                                 [&](const auto& entry) { return entry.second == group; });
    if (it == contents.names.end()) {
      std::string known;
      for (const auto& [tag, name] : contents.names) known += (known.empty() ? "'" : ", '") + name + "'";
      throw in.error_at(0, "no two-dimensional physical group named '" + group + "' (the file has " +
                               (known.empty() ? std::string("none") : known) + ")");
    }
    tags.insert(it->first);
  }
  return tags;
}

// The physical tag an element is reported under, or nothing when it is not selected.
std::optional<int> element_group(const Contents& contents, const std::set<int>& selected,
                                 const SurfaceElement& element, const Lines& in) {
  static const std::vector<int> none;
  const std::vector<int>* tags = &none;
  if (contents.has_entities) {
    const auto it = contents.surface_groups.find(element.surface);
    if (it == contents.surface_groups.end())
      throw in.error_at(element.line, "surface entity " + std::to_string(element.surface) +
                                          " of this element is not listed in $Entities");
    tags = &it->second;
  }
  if (selected.empty()) return tags->empty() ? 0 : tags->front();
  for (const int tag : *tags)
    if (selected.contains(tag)) return tag;
  return std::nullopt;
}

}  // namespace

std::string GmshSurface::physical_name(int t) const {
  const auto it = physical_names.find(physical_tag[static_cast<std::size_t>(t)]);
  return it == physical_names.end() ? std::string() : it->second;
}

GmshSurface read_gmsh_surface(const std::filesystem::path& file, const std::vector<std::string>& physical_groups) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream)
    throw ConfigError(Origin{file.string(), 0}, "", std::string("cannot read Gmsh file: ") + std::strerror(errno));
  const std::string content((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  Lines in(content, file);
  const Contents contents = read_contents(in);
  const std::set<int> selected = selected_tags(contents, physical_groups, in);

  // Triangles in node indices of the file, then renumbered to the used nodes.
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> tags;
  for (const auto& element : contents.elements) {
    const auto group = element_group(contents, selected, element, in);
    if (!group) continue;
    std::array<int, 4> v{};
    for (std::size_t c = 0; c < static_cast<std::size_t>(element.corners); ++c) {
      const auto it = contents.node_index.find(element.nodes[c]);
      if (it == contents.node_index.end())
        throw in.error_at(element.line, "unknown node tag " + std::to_string(element.nodes[c]));
      v[c] = it->second;
    }
    const auto x = [&](std::size_t k) -> const Eigen::Vector3d& {
      return contents.coordinates[static_cast<std::size_t>(v[k])];
    };
    if (element.corners == 3) {
      triangles.push_back({v[0], v[1], v[2]});
    } else if ((x(0) - x(2)).squaredNorm() <= (x(1) - x(3)).squaredNorm()) {
      triangles.push_back({v[0], v[1], v[2]});
      triangles.push_back({v[0], v[2], v[3]});
    } else {
      triangles.push_back({v[0], v[1], v[3]});
      triangles.push_back({v[1], v[2], v[3]});
    }
    tags.resize(triangles.size(), *group);
  }
  if (triangles.empty())
    throw in.error_at(0, physical_groups.empty() ? "no triangles or quadrangles in the file"
                                                 : "no triangles or quadrangles in the selected physical groups");

  std::vector<int> vertex_of(contents.coordinates.size(), -1);
  GmshSurface surface;
  std::vector<Eigen::Vector3d> vertices;
  for (const auto& triangle : triangles)
    for (const int node : triangle) vertex_of[static_cast<std::size_t>(node)] = 0;
  for (std::size_t node = 0; node < vertex_of.size(); ++node) {
    if (vertex_of[node] < 0) continue;
    vertex_of[node] = static_cast<int>(vertices.size());
    vertices.push_back(contents.coordinates[node]);
    surface.node_tag.push_back(contents.node_tags[node]);
  }
  for (auto& triangle : triangles)
    for (int& node : triangle) node = vertex_of[static_cast<std::size_t>(node)];
  surface.mesh = TriangleMesh(std::move(vertices), std::move(triangles));
  surface.physical_tag = std::move(tags);
  surface.physical_names = contents.names;
  return surface;
}

}  // namespace tankfsi::sph
