#pragma once
// Topology checks of a triangle mesh given as vertex positions and index triples:
// out-of-range indices, degenerate (zero-area) triangles, open and non-manifold
// edges, and inconsistent orientation between neighbours. Each problem is reported
// with a message naming the triangles and vertices involved, so a bad wall mesh can
// be fixed in the modelling tool rather than debugged in the solver.
//
// Conventions shared by the walls module: edge k of a triangle joins its vertices
// k and (k+1) mod 3. Two neighbours are consistently oriented when they traverse
// their shared edge in opposite directions (right-hand rule normals then point to
// the same side of the surface).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace tankfsi::sph {

/// One use of an undirected edge by a triangle, as that triangle traverses it.
struct HalfEdge {
  int from = 0;      ///< first vertex, in the triangle's order
  int to = 0;        ///< second vertex
  int triangle = 0;  ///< triangle index
  int edge = 0;      ///< local edge index k (vertices k and k+1 mod 3)
};

/// Calls visit(uses) once per undirected edge with every half-edge using it, in
/// ascending order of (min vertex, max vertex) and then of triangle. Triangles with an
/// out-of-range index are skipped. O(n log n) (sort of 3n half-edges).
void for_each_edge(std::span<const std::array<int, 3>> triangles, std::size_t vertex_count,
                   const std::function<void(std::span<const HalfEdge>)>& visit);

enum class TopologyIssueKind {
  index_out_of_range,
  degenerate_triangle,
  open_edge,             ///< an edge used by one triangle only
  non_manifold_edge,     ///< an edge used by three or more triangles
  inconsistent_orientation,
};

struct TopologyIssue {
  TopologyIssueKind kind;
  int triangle = -1;                ///< the (first) triangle involved
  std::array<int, 2> edge{-1, -1};  ///< the edge involved, if any (vertex indices)
  std::string message;
};

struct TopologyOptions {
  /// Report edges used by a single triangle. Off for walls that are open by design
  /// (an open-top tank); use TriangleMesh::boundary_edges() to see them.
  bool report_open_edges = true;
  /// A triangle is degenerate when |e1 x e2| <= degenerate_sine * (longest edge)^2,
  /// i.e. its smallest angle is below ~this many radians (also: a repeated index).
  /// 1e-12 catches zero-area triangles up to round-off and nothing a mesher would
  /// produce on purpose.
  double degenerate_sine = 1e-12;
};

struct TopologyReport {
  std::vector<TopologyIssue> issues;

  [[nodiscard]] bool ok() const { return issues.empty(); }
  [[nodiscard]] std::size_t count(TopologyIssueKind kind) const;
  /// All messages, one per line.
  [[nodiscard]] std::string summary() const;
};

[[nodiscard]] TopologyReport check_topology(std::span<const Eigen::Vector3d> vertices,
                                            std::span<const std::array<int, 3>> triangles,
                                            const TopologyOptions& options = {});

}  // namespace tankfsi::sph
