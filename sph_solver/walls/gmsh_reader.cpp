#include "sph_solver/walls/gmsh_reader.hpp"

#include <array>
#include <optional>
#include <set>
#include <utility>

#include "common/io/gmsh_msh.hpp"

namespace tankfsi::sph {

namespace {

constexpr int surface_dimension = 2;

// Physical tags of the selected group names; an unknown name lists the known ones.
std::set<int> selected_tags(const gmsh::MshFile& msh, const std::vector<std::string>& groups) {
  std::set<int> tags;
  for (const auto& group : groups) {
    const int tag = msh.physical_tag(surface_dimension, group);
    if (tag < 0)
      throw msh.error_at(0, "no two-dimensional physical group named '" + group + "' (the file has " +
                                msh.listed_names(surface_dimension) + ")");
    tags.insert(tag);
  }
  return tags;
}

// The physical tag a surface's elements are reported under, or nothing when it is not selected.
std::optional<int> surface_group(const gmsh::MshFile& msh, const std::set<int>& selected, int surface, int line) {
  const std::vector<int>& tags = msh.groups_of(surface_dimension, surface, line);
  if (selected.empty()) return tags.empty() ? 0 : tags.front();
  for (const int tag : tags)
    if (selected.contains(tag)) return tag;
  return std::nullopt;
}

}  // namespace

std::string GmshSurface::physical_name(int t) const {
  const auto it = physical_names.find(physical_tag[static_cast<std::size_t>(t)]);
  return it == physical_names.end() ? std::string() : it->second;
}

GmshSurface read_gmsh_surface(const std::filesystem::path& file, const std::vector<std::string>& physical_groups) {
  const gmsh::MshFile msh = gmsh::read_msh(file, [](const gmsh::MshFile& in, const gmsh::MshElementBlock& block) {
    if (block.dimension == surface_dimension && block.type != gmsh::triangle_3_node &&
        block.type != gmsh::quadrangle_4_node)
      throw in.error_at(block.line, "element type " + std::to_string(block.type) + " on surface " +
                                        std::to_string(block.entity) +
                                        " is not supported: only 3-node triangles (2) and 4-node quadrangles (3); "
                                        "mesh with Mesh.ElementOrder = 1");
  });
  const std::set<int> selected = selected_tags(msh, physical_groups);

  // Triangles in node indices of the file, then renumbered to the used nodes.
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> tags;
  for (const auto& block : msh.blocks) {
    if (block.dimension != surface_dimension) continue;  // points, curves and volumes are not walls
    for (const auto& element : block.elements) {
      const auto group = surface_group(msh, selected, block.entity, element.line);
      if (!group) continue;
      std::array<int, 4> v{};
      for (std::size_t c = 0; c < element.nodes.size(); ++c) v[c] = msh.node(element.nodes[c], element.line);
      const auto x = [&](std::size_t k) -> const Eigen::Vector3d& {
        return msh.nodes[static_cast<std::size_t>(v[k])].position;
      };
      if (element.nodes.size() == 3) {
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
  }
  if (triangles.empty())
    throw msh.error_at(0, physical_groups.empty() ? "no triangles or quadrangles in the file"
                                                  : "no triangles or quadrangles in the selected physical groups");

  std::vector<int> vertex_of(msh.nodes.size(), -1);
  GmshSurface surface;
  std::vector<Eigen::Vector3d> vertices;
  for (const auto& triangle : triangles)
    for (const int node : triangle) vertex_of[static_cast<std::size_t>(node)] = 0;
  for (std::size_t node = 0; node < vertex_of.size(); ++node) {
    if (vertex_of[node] < 0) continue;
    vertex_of[node] = static_cast<int>(vertices.size());
    vertices.push_back(msh.nodes[node].position);
    surface.node_tag.push_back(msh.nodes[node].tag);
  }
  for (auto& triangle : triangles)
    for (int& node : triangle) node = vertex_of[static_cast<std::size_t>(node)];
  surface.mesh = TriangleMesh(std::move(vertices), std::move(triangles));
  surface.physical_tag = std::move(tags);
  for (const auto& [key, name] : msh.physical_names)
    if (key.first == surface_dimension) surface.physical_names[key.second] = name;
  return surface;
}

}  // namespace tankfsi::sph
