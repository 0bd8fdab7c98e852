#include "fem_solver/mesh/shell_mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>

namespace tankfsi::fem {
namespace {

/// Unit normal of element `e` at its local corner `k` (from its two edges there).
Eigen::Vector3d corner_normal(const ShellMesh& mesh, const MeshElement& e, int k) {
  const int n = e.node_count();
  const auto at = [&](int i) { return mesh.nodes[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>((i + n) % n)])]; };
  return (at(k + 1) - at(k)).cross(at(k - 1) - at(k)).normalized();
}

}  // namespace

int ShellMesh::region_index(const std::string& name) {
  const auto found = std::find(region_names.begin(), region_names.end(), name);
  if (found != region_names.end()) return static_cast<int>(found - region_names.begin());
  region_names.push_back(name);
  return static_cast<int>(region_names.size()) - 1;
}

std::size_t ShellMesh::quad_count() const {
  return static_cast<std::size_t>(std::count_if(elements.begin(), elements.end(), [](const MeshElement& e) { return e.node_count() == 4; }));
}

std::size_t ShellMesh::triangle_count() const { return elements.size() - quad_count(); }

std::vector<int> ShellMesh::elements_of(const std::string& name) const {
  if (const auto set = element_sets.find(name); set != element_sets.end()) return set->second;
  const auto region = std::find(region_names.begin(), region_names.end(), name);
  if (region == region_names.end()) throw std::out_of_range("the mesh has no element region or set '" + name + "'");
  const int index = static_cast<int>(region - region_names.begin());
  std::vector<int> out;
  for (std::size_t e = 0; e < elements.size(); ++e)
    if (elements[e].region == index) out.push_back(static_cast<int>(e));
  return out;
}

std::vector<int> ShellMesh::nodes_of(const std::string& name) const {
  if (const auto set = node_sets.find(name); set != node_sets.end()) return set->second;
  std::set<int> found;
  for (const int e : elements_of(name))
    for (int k = 0; k < elements[static_cast<std::size_t>(e)].node_count(); ++k)
      found.insert(elements[static_cast<std::size_t>(e)].nodes[static_cast<std::size_t>(k)]);
  return {found.begin(), found.end()};
}

int ShellMesh::nearest_node(const Eigen::Vector3d& point) const {
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double d = (nodes[i] - point).squaredNorm();
    if (d < best_distance) {
      best_distance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

void ShellMesh::check() const {
  if (elements.empty()) throw std::invalid_argument("the mesh has no elements");
  std::vector<char> used(nodes.size(), 0);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const MeshElement& element = elements[e];
    const int n = element.node_count();
    for (int k = 0; k < n; ++k) {
      const int node = element.nodes[static_cast<std::size_t>(k)];
      if (node < 0 || static_cast<std::size_t>(node) >= nodes.size())
        throw std::invalid_argument("element " + std::to_string(e) + " names node " + std::to_string(node) +
                                    ", which does not exist");
      for (int j = 0; j < k; ++j)
        if (element.nodes[static_cast<std::size_t>(j)] == node)
          throw std::invalid_argument("element " + std::to_string(e) + " repeats node " + std::to_string(node));
      used[static_cast<std::size_t>(node)] = 1;
    }
    for (int k = 0; k < n; ++k)
      if (!corner_normal(*this, element, k).allFinite())
        throw std::invalid_argument("element " + std::to_string(e) + " is degenerate (zero area at a corner)");
    if (element.region < 0 || static_cast<std::size_t>(element.region) >= region_names.size())
      throw std::invalid_argument("element " + std::to_string(e) + " has no region");
  }
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (used[i] == 0) throw std::invalid_argument("node " + std::to_string(i) + " belongs to no element");
}

Directors compute_directors(const ShellMesh& mesh, double crease_angle_degrees) {
  const double cos_crease = std::cos(crease_angle_degrees * std::numbers::pi / 180.0);
  // Element normals at each node, gathered per node.
  std::vector<std::vector<Eigen::Vector3d>> around(mesh.nodes.size());
  Directors directors(mesh.elements.size());
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const auto& element = mesh.elements[e];
    for (int k = 0; k < element.node_count(); ++k) {
      const Eigen::Vector3d n = corner_normal(mesh, element, k);
      directors[e][static_cast<std::size_t>(k)] = n;
      around[static_cast<std::size_t>(element.nodes[static_cast<std::size_t>(k)])].push_back(n);
    }
  }
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const auto& element = mesh.elements[e];
    for (int k = 0; k < element.node_count(); ++k) {
      const auto slot = static_cast<std::size_t>(k);
      const Eigen::Vector3d own = directors[e][slot];
      const auto node = static_cast<std::size_t>(element.nodes[slot]);
      if (node < mesh.node_normals.size() && mesh.node_normals[node].squaredNorm() > 0.0) {
        Eigen::Vector3d exact = mesh.node_normals[node].normalized();
        if (exact.dot(own) < 0.0) exact = -exact;
        if (exact.dot(own) >= cos_crease) {
          directors[e][slot] = exact;
          continue;
        }
      }
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const auto& n : around[static_cast<std::size_t>(element.nodes[slot])])
        if (n.dot(own) >= cos_crease) sum += n;
      directors[e][slot] = sum.normalized();
    }
  }
  return directors;
}

}  // namespace tankfsi::fem
