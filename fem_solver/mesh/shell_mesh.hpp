#pragma once
// ShellMesh: the mid-surface mesh of a shell structure — nodes, 3- and 4-node
// elements, and the named sets the case file refers to: element regions
// (each element belongs to exactly one: wall, roof, bottom, ...; they carry
// thickness and material), extra element sets (wetted), and node sets (edges,
// base, symmetry lines). Every rank holds the whole mesh: the meshes of this
// program (a tank of ~10^4 nodes) are small next to the factorised matrix.
#include <Eigen/Core>

#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace tankfsi::fem {

struct MeshElement {
  std::array<int, 4> nodes{-1, -1, -1, -1};  ///< counter-clockwise about the normal; nodes[3] = -1 for a triangle
  int region = 0;                            ///< index into ShellMesh::region_names

  [[nodiscard]] int node_count() const { return nodes[3] < 0 ? 3 : 4; }
};

struct ShellMesh {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<MeshElement> elements;
  std::vector<std::string> region_names;
  std::map<std::string, std::vector<int>> element_sets;  ///< sorted element indices
  std::map<std::string, std::vector<int>> node_sets;     ///< sorted node indices
  /// Exact surface normals a generator knows (empty, or one per node; a zero
  /// vector where unknown). Directors use them: averaged element normals are
  /// one-sided, hence tilted, on edges and symmetry planes.
  std::vector<Eigen::Vector3d> node_normals;
  /// Unit normals of the mirror-symmetry planes nodes lie on (a case's
  /// symmetry supports), node -> plane normal. Directors there are kept in
  /// the plane, as the averaged normal of the mirrored, whole mesh would be.
  std::multimap<int, Eigen::Vector3d> symmetry_planes;

  /// Index of region `name`, added if new.
  int region_index(const std::string& name);
  [[nodiscard]] std::size_t quad_count() const;
  [[nodiscard]] std::size_t triangle_count() const;
  /// Node set `name`, or the nodes of element region / element set `name`;
  /// throws std::out_of_range when there is no such set.
  [[nodiscard]] std::vector<int> nodes_of(const std::string& name) const;
  /// Elements of region or element set `name`; throws std::out_of_range.
  [[nodiscard]] std::vector<int> elements_of(const std::string& name) const;
  /// The node closest to `point` (lowest index on ties).
  [[nodiscard]] int nearest_node(const Eigen::Vector3d& point) const;
  /// Throws MeshDefect on out-of-range or repeated element nodes, degenerate
  /// (zero-area) or inverted (folded) elements, two elements oriented
  /// oppositely across a shared edge, and nodes of no element;
  /// std::invalid_argument for a mesh without elements.
  void check() const;
};

/// What ShellMesh::check() found wrong, and where: the elements (mesh
/// indices) or the node, so that a reader can name them as its file does.
class MeshDefect : public std::invalid_argument {
 public:
  MeshDefect(std::vector<int> elements_in, int node_in, const std::string& problem_in);
  std::vector<int> elements;  ///< one, or two for an orientation defect
  int node = -1;              ///< for a node of no element
  std::string problem;        ///< the text after the subject: "is degenerate (zero area at a corner)"
};

/// Per element node, the shell director: the node's exact normal when the mesh
/// has one within `crease_angle` of this element's own normal; otherwise the
/// average of the unit normals of the elements around the node that lie
/// within `crease_angle` of this element's — smooth over a curved shell,
/// separate on each side of a kink (wall-roof and wall-bottom junctions).
/// At a node on a symmetry plane the director's component along the plane's
/// normal is removed when it is small (below sin(crease_angle)): an averaged
/// normal there is one-sided, tilted by half the facet angle.
using Directors = std::vector<std::array<Eigen::Vector3d, 4>>;
[[nodiscard]] Directors compute_directors(const ShellMesh& mesh, double crease_angle_degrees = 20.0);

}  // namespace tankfsi::fem
