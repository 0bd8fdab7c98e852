#pragma once
// The one parser of Gmsh MSH 4.1 ASCII files: what the file says, section by
// section, with the line each item came from — no interpretation. The fluid's
// wall reader (triangles of the surfaces) and the structure's shell-mesh reader
// (regions, element sets and node sets from physical groups) build on it.
//
// Read: $MeshFormat (must be 4.1, file type 0 = ASCII), $PhysicalNames (every
// dimension), $Entities (the physical tags of every point, curve, surface and
// volume), $Nodes (with or without parametric coordinates) and $Elements (every
// block, every dimension; the caller may refuse a block by its header). Other sections ($Periodic, $NodeData, $Comments, ...)
// are skipped. For the element types of Gmsh's table up to order 2 (and the
// point) the number of nodes on each element line is checked; other types are
// kept with whatever nodes their line lists, for the callers to refuse.
//
// Errors raise tankfsi::ConfigError naming the file and line: unreadable file, a
// first section other than $MeshFormat, versions other than 4.1 (v2.2: re-export
// as 4.1), binary files (re-export as ASCII), malformed or missing numbers,
// counts that disagree with their headers, a missing $End line, duplicate or
// non-positive node tags.
#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/config/config_error.hpp"

namespace tankfsi::gmsh {

// Gmsh element type numbers used by the readers.
inline constexpr int line_2_node = 1;
inline constexpr int triangle_3_node = 2;
inline constexpr int quadrangle_4_node = 3;
inline constexpr int point_1_node = 15;

/// Nodes of a Gmsh element type (first and second order, and the point), or 0
/// when the type is not in this table.
[[nodiscard]] int element_node_count(int type);
/// "6-node triangle", or "type N" for types outside the table.
[[nodiscard]] std::string element_type_name(int type);

struct MshNode {
  std::int64_t tag = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int entity_dimension = 0;  ///< dimension of the entity whose block lists the node
  int line = 0;              ///< line of the node's tag
};

struct MshElement {
  std::int64_t tag = 0;
  std::vector<std::int64_t> nodes;  ///< node tags, in the file's order
  int line = 0;
};

/// One $Elements block: the elements of one type on one entity.
struct MshElementBlock {
  int dimension = 0;
  int entity = 0;
  int type = 0;
  int line = 0;  ///< line of the block header
  std::vector<MshElement> elements;
};

struct MshFile {
  std::filesystem::path file;
  /// Physical group names by (dimension, tag).
  std::map<std::pair<int, int>, std::string> physical_names;
  bool has_entities = false;
  /// Physical tags of each entity, by (dimension, entity tag); from $Entities.
  std::map<std::pair<int, int>, std::vector<int>> entity_groups;
  std::vector<MshNode> nodes;                       ///< in file order
  std::unordered_map<std::int64_t, int> node_index; ///< node tag -> index into nodes
  std::vector<MshElementBlock> blocks;              ///< in file order

  /// A ConfigError located at `line` of this file (0: the file as a whole).
  [[nodiscard]] ConfigError error_at(int line, const std::string& message) const;
  /// Index of node `tag`; throws at `line` (the element's) for an unknown tag.
  [[nodiscard]] int node(std::int64_t tag, int line) const;
  /// Physical tags of entity (dimension, entity): empty for a file without
  /// $Entities; throws at `line` when the file has $Entities but not this entity.
  [[nodiscard]] const std::vector<int>& groups_of(int dimension, int entity, int line) const;
  /// Tag of the physical group `name` of `dimension`, or -1.
  [[nodiscard]] int physical_tag(int dimension, const std::string& name) const;
  /// The names of the physical groups of `dimension`: "'a', 'b'" or "none".
  [[nodiscard]] std::string listed_names(int dimension) const;
};

/// Called with each $Elements block's header (no elements yet) before its
/// elements are read; a reader refuses a block — element types it does not
/// support — by throwing msh.error_at(header.line, ...).
using BlockCheck = std::function<void(const MshFile& msh, const MshElementBlock& header)>;

/// Reads the whole file; throws ConfigError (file and line) when it is malformed.
[[nodiscard]] MshFile read_msh(const std::filesystem::path& file, const BlockCheck& check = {});

}  // namespace tankfsi::gmsh
