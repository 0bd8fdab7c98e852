#include "fem_solver/mesh/shell_mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace tankfsi::fem {
namespace {

/// Unit normal of element `e` at its local corner `k` (from its two edges
/// there); not finite where the corner has no area.
Eigen::Vector3d corner_normal(const ShellMesh& mesh, const MeshElement& e, int k) {
  const int n = e.node_count();
  const auto at = [&](int i) { return mesh.nodes[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>((i + n) % n)])]; };
  const Eigen::Vector3d next = at(k + 1) - at(k);
  const Eigen::Vector3d previous = at(k - 1) - at(k);
  const Eigen::Vector3d cross = next.cross(previous);
  // Edges at an angle below ~1e-10 rad are collinear to round-off: the
  // direction of their cross product is noise, not a normal.
  if (!(cross.norm() > 1e-10 * next.norm() * previous.norm())) return Eigen::Vector3d::Constant(std::nan(""));
  return cross.normalized();
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

namespace {

std::string defect_subject(const std::vector<int>& elements, int node) {
  if (elements.empty()) return "node " + std::to_string(node);
  if (elements.size() == 1) return "element " + std::to_string(elements[0]);
  return "elements " + std::to_string(elements[0]) + " and " + std::to_string(elements[1]);
}

// Two elements sharing an edge must run along it in opposite directions (both
// counter-clockwise about one side's normal): otherwise their normals point to
// opposite sides, and a pressure pushes one of them the wrong way. Edges of
// three or more elements (T-junctions) have no such rule.
void check_orientation(const ShellMesh& mesh) {
  struct Use {
    int element;
    bool forward;  ///< runs from the lower to the higher node index
  };
  std::unordered_map<std::uint64_t, std::vector<Use>> edges;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const MeshElement& element = mesh.elements[e];
    const int n = element.node_count();
    for (int k = 0; k < n; ++k) {
      const auto a = static_cast<std::uint32_t>(element.nodes[static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::uint32_t>(element.nodes[static_cast<std::size_t>((k + 1) % n)]);
      const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      edges[key].push_back(Use{static_cast<int>(e), a < b});
    }
  }
  std::vector<std::pair<int, int>> opposite;
  for (const auto& [key, uses] : edges)
    if (uses.size() == 2 && uses[0].forward == uses[1].forward)
      opposite.emplace_back(std::min(uses[0].element, uses[1].element), std::max(uses[0].element, uses[1].element));
  if (opposite.empty()) return;
  const auto first = *std::min_element(opposite.begin(), opposite.end());  // the same report on every run
  throw MeshDefect({first.first, first.second}, -1,
                   "are oriented oppositely across their shared edge (their normals point to opposite sides): "
                   "orient every surface of the shell alike");
}

}  // namespace

MeshDefect::MeshDefect(std::vector<int> elements_in, int node_in, const std::string& problem_in)
    : std::invalid_argument(defect_subject(elements_in, node_in) + " " + problem_in),
      elements(std::move(elements_in)),
      node(node_in),
      problem(problem_in) {}

void ShellMesh::check() const {
  if (elements.empty()) throw std::invalid_argument("the mesh has no elements");
  std::vector<char> used(nodes.size(), 0);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const MeshElement& element = elements[e];
    const int index = static_cast<int>(e);
    const int n = element.node_count();
    for (int k = 0; k < n; ++k) {
      const int node = element.nodes[static_cast<std::size_t>(k)];
      if (node < 0 || static_cast<std::size_t>(node) >= nodes.size())
        throw MeshDefect({index}, -1, "names node " + std::to_string(node) + ", which does not exist");
      for (int j = 0; j < k; ++j)
        if (element.nodes[static_cast<std::size_t>(j)] == node)
          throw MeshDefect({index}, -1, "repeats node " + std::to_string(node));
      used[static_cast<std::size_t>(node)] = 1;
    }
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d normal = corner_normal(*this, element, k);
      if (!normal.allFinite()) throw MeshDefect({index}, -1, "is degenerate (zero area at a corner)");
      sum += normal;
    }
    // A quadrangle whose corners turn different ways (listed a b d c, or one
    // corner pushed across the opposite diagonal) has no consistent normal.
    for (int k = 0; k < n; ++k)
      if (corner_normal(*this, element, k).dot(sum) <= 0.0)
        throw MeshDefect({index}, -1, "is inverted: its corners turn different ways (a folded or self-crossing quadrangle)");
    if (element.region < 0 || static_cast<std::size_t>(element.region) >= region_names.size())
      throw MeshDefect({index}, -1, "has no region");
  }
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (used[i] == 0) throw MeshDefect({}, static_cast<int>(i), "belongs to no element");
  check_orientation(*this);
}

Directors compute_directors(const ShellMesh& mesh, double crease_angle_degrees) {
  const double cos_crease = std::cos(crease_angle_degrees * std::numbers::pi / 180.0);
  const double sin_crease = std::sin(crease_angle_degrees * std::numbers::pi / 180.0);
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
      Eigen::Vector3d director = sum.normalized();
      const auto [first, last] = mesh.symmetry_planes.equal_range(element.nodes[slot]);
      for (auto it = first; it != last; ++it)
        if (std::abs(director.dot(it->second)) < sin_crease) director = (director - director.dot(it->second) * it->second).normalized();
      directors[e][slot] = director;
    }
  }
  return directors;
}

}  // namespace tankfsi::fem
