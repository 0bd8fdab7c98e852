#include "fem_solver/mesh/gmsh_shell_mesh.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

#include "common/io/gmsh_msh.hpp"

namespace tankfsi::fem {
namespace {

constexpr int surface_dimension = 2;

std::string group_name(const gmsh::MshFile& msh, int dimension, int tag) {
  const auto it = msh.physical_names.find({dimension, tag});
  return it == msh.physical_names.end() ? std::to_string(tag) : it->second;
}

// Refuses, at its header line, a block the shells cannot use.
void check_block(const gmsh::MshFile& msh, const gmsh::MshElementBlock& block) {
  if (block.dimension > surface_dimension)
    throw msh.error_at(block.line, "volume elements (" + gmsh::element_type_name(block.type) + ") on volume " +
                                       std::to_string(block.entity) +
                                       ": a shell mesh has surfaces only (mesh with gmsh -2, or keep the volumes "
                                       "out of the physical groups)");
  if (block.dimension == surface_dimension && block.type != gmsh::triangle_3_node &&
      block.type != gmsh::quadrangle_4_node)
    throw msh.error_at(block.line, "element type " + std::to_string(block.type) + " (" +
                                       gmsh::element_type_name(block.type) + ") on surface " +
                                       std::to_string(block.entity) +
                                       " is not supported: the shells are 3-node triangles (2) and 4-node "
                                       "quadrangles (3); mesh with Mesh.ElementOrder = 1");
}

// The surface groups that are regions, by tag.
std::map<int, std::string> region_groups(const gmsh::MshFile& msh, const std::vector<std::string>& regions) {
  std::map<int, std::string> out;
  if (regions.empty()) {
    for (const auto& [key, name] : msh.physical_names)
      if (key.first == surface_dimension) out[key.second] = name;
    // Groups named only in $Entities (no $PhysicalNames entry) count too.
    for (const auto& [entity, tags] : msh.entity_groups)
      if (entity.first == surface_dimension)
        for (const int tag : tags) out.emplace(tag, group_name(msh, surface_dimension, tag));
    return out;
  }
  for (const auto& name : regions) {
    const int tag = msh.physical_tag(surface_dimension, name);
    if (tag < 0)
      throw std::out_of_range(msh.file.string() + " has no two-dimensional physical group named '" + name +
                              "' (it has " + msh.listed_names(surface_dimension) + ")");
    out[tag] = name;
  }
  return out;
}

std::string quoted_list(const std::map<int, std::string>& groups) {
  std::string out;
  for (const auto& [tag, name] : groups) out += (out.empty() ? "'" : ", '") + name + "'";
  return out;
}

struct Reading {
  ShellMesh mesh;
  std::vector<int> element_line;  ///< per mesh element: its line in the file
  std::vector<std::int64_t> element_tag;
};

// The shell elements of the surface blocks, with file node indices for now.
void read_surfaces(const gmsh::MshFile& msh, const std::map<int, std::string>& regions, Reading& r) {
  std::map<std::string, std::vector<int>> sets;
  for (const auto& block : msh.blocks) {
    if (block.dimension != surface_dimension || block.elements.empty()) continue;
    const std::vector<int>& tags = msh.groups_of(surface_dimension, block.entity, block.elements.front().line);
    std::vector<std::string> in_regions, in_sets;
    for (const int tag : tags)
      (regions.count(tag) != 0 ? in_regions : in_sets).push_back(group_name(msh, surface_dimension, tag));
    if (in_regions.size() > 1)
      throw msh.error_at(block.line, "surface " + std::to_string(block.entity) + " is in two regions, '" +
                                         in_regions[0] + "' and '" + in_regions[1] +
                                         "': an element belongs to one region (name the regions in "
                                         "structure.mesh.regions; the other surface groups become element sets)");
    if (in_regions.empty() && !regions.empty())
      throw msh.error_at(block.elements.front().line,
                         "element " + std::to_string(block.elements.front().tag) + " on surface " +
                             std::to_string(block.entity) + " is in none of the regions (" + quoted_list(regions) +
                             "): add its surface to one of them");
    const int region = r.mesh.region_index(in_regions.empty() ? std::string("shell") : in_regions.front());
    for (const auto& element : block.elements) {
      MeshElement e;
      for (std::size_t k = 0; k < element.nodes.size(); ++k) e.nodes[k] = msh.node(element.nodes[k], element.line);
      e.region = region;
      for (const auto& set : in_sets) sets[set].push_back(static_cast<int>(r.mesh.elements.size()));
      r.mesh.elements.push_back(e);
      r.element_line.push_back(element.line);
      r.element_tag.push_back(element.tag);
    }
  }
  if (r.mesh.elements.empty()) throw msh.error_at(0, "no triangles or quadrangles in the file: not a shell mesh");
  for (auto& [name, elements] : sets) {
    if (std::find(r.mesh.region_names.begin(), r.mesh.region_names.end(), name) != r.mesh.region_names.end()) continue;
    r.mesh.element_sets[name] = std::move(elements);
  }
}

// Node sets from the curve and point groups, in file node indices for now.
std::map<std::string, std::set<int>> read_node_groups(const gmsh::MshFile& msh) {
  std::map<std::string, std::set<int>> out;
  for (const auto& block : msh.blocks) {
    if (block.dimension >= surface_dimension || block.elements.empty()) continue;
    const std::vector<int>& tags = msh.groups_of(block.dimension, block.entity, block.elements.front().line);
    for (const int tag : tags) {
      std::set<int>& nodes = out[group_name(msh, block.dimension, tag)];
      for (const auto& element : block.elements)
        for (const std::int64_t node : element.nodes) nodes.insert(msh.node(node, element.line));
    }
  }
  return out;
}

// Numbers the used nodes in file order; refuses loose ones.
void number_nodes(const gmsh::MshFile& msh, const std::map<std::string, std::set<int>>& groups, Reading& r) {
  std::vector<int> mesh_node(msh.nodes.size(), -1);
  for (const auto& e : r.mesh.elements)
    for (int k = 0; k < e.node_count(); ++k) mesh_node[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(k)])] = 0;
  for (const auto& [name, nodes] : groups)
    for (const int node : nodes)
      if (mesh_node[static_cast<std::size_t>(node)] < 0) {
        const gmsh::MshNode& n = msh.nodes[static_cast<std::size_t>(node)];
        throw msh.error_at(n.line, "node " + std::to_string(n.tag) + " of physical group '" + name +
                                       "' belongs to no shell element");
      }
  for (std::size_t node = 0; node < msh.nodes.size(); ++node) {
    if (mesh_node[node] < 0) {
      if (msh.nodes[node].entity_dimension == 0) continue;  // a geometric point's node (a circle's centre)
      throw msh.error_at(msh.nodes[node].line, "node " + std::to_string(msh.nodes[node].tag) +
                                                   " belongs to no shell element: remove the loose node, or mesh "
                                                   "the surface around it");
    }
    mesh_node[node] = static_cast<int>(r.mesh.nodes.size());
    r.mesh.nodes.push_back(msh.nodes[node].position);
  }
  for (auto& e : r.mesh.elements)
    for (int k = 0; k < e.node_count(); ++k) {
      int& node = e.nodes[static_cast<std::size_t>(k)];
      node = mesh_node[static_cast<std::size_t>(node)];
    }
  for (const auto& [name, nodes] : groups) {
    const bool surface_name = r.mesh.element_sets.count(name) != 0 ||
                              std::find(r.mesh.region_names.begin(), r.mesh.region_names.end(), name) !=
                                  r.mesh.region_names.end();
    if (surface_name)
      throw msh.error_at(0, "the physical group name '" + name +
                                "' is used by a curve or point group and a surface group: rename one");
    std::vector<int>& set = r.mesh.node_sets[name];
    for (const int node : nodes) set.push_back(mesh_node[static_cast<std::size_t>(node)]);
    std::sort(set.begin(), set.end());
  }
}

// ShellMesh::check with the file's element tags and lines.
void check_geometry(const gmsh::MshFile& msh, const Reading& r) {
  try {
    r.mesh.check();
  } catch (const MeshDefect& defect) {
    if (defect.elements.empty()) throw msh.error_at(0, defect.what());
    const auto at = [&](std::size_t k) { return static_cast<std::size_t>(defect.elements[k]); };
    std::string subject = "element " + std::to_string(r.element_tag[at(0)]);
    if (defect.elements.size() > 1)
      subject = "elements " + std::to_string(r.element_tag[at(0)]) + " and " + std::to_string(r.element_tag[at(1)]) +
                " (line " + std::to_string(r.element_line[at(1)]) + ")";
    throw msh.error_at(r.element_line[at(0)], subject + " " + defect.problem);
  }
}

}  // namespace

ShellMesh read_gmsh_shell_mesh(const std::filesystem::path& file, const std::vector<std::string>& regions) {
  const gmsh::MshFile msh = gmsh::read_msh(file, check_block);
  Reading r;
  read_surfaces(msh, region_groups(msh, regions), r);
  number_nodes(msh, read_node_groups(msh), r);
  check_geometry(msh, r);
  return std::move(r.mesh);
}

}  // namespace tankfsi::fem
