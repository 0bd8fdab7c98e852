#pragma once
// TriangleIndex: a bounding-volume hierarchy (BVH) of axis-aligned boxes over the
// triangles of a wall mesh, for the nearest wall triangle of a particle and for all
// wall triangles within the kernel support.
//
// Why a BVH rather than a uniform grid of buckets: wall triangles differ a lot in
// size (a coarse floor, a fine shell near the base, long thin triangles on a
// cylinder), queries come with different radii (nearest within the support, or a
// far "where is the wall" query), and a grid needs a cell size tuned to both while
// large triangles straddle many cells. A median-split BVH adapts to the mesh with
// no parameter, answers in O(log n) per query, and — because the wall's topology is
// fixed — follows a deforming wall by refitting its boxes bottom-up in O(n) without
// re-sorting (refit()). Refitting keeps the tree valid for any motion; only the
// pruning efficiency drops if triangles travel far from their original neighbours,
// which shell deformations do not do; rebuild() re-sorts if they ever do.
//
// The index holds a pointer to the mesh: the mesh must outlive it and must not be
// moved in memory. Queries throw std::logic_error if the mesh's vertices were moved
// since the last build/refit (a stale index would silently give wrong walls).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "sph_solver/walls/closest_point.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

struct WallHit {
  int triangle = -1;
  ClosestPoint closest;
};

class TriangleIndex {
 public:
  explicit TriangleIndex(const TriangleMesh& mesh);

  /// Updates the boxes after mesh.move_vertices(): O(n), same tree.
  void refit();
  /// Rebuilds the tree from scratch: O(n log n).
  void rebuild();

  /// The closest triangle to p with distance < max_distance, or none. Among
  /// triangles at the same distance (a shared edge or vertex), the lowest index, so
  /// the answer does not depend on the tree's layout.
  [[nodiscard]] std::optional<WallHit> nearest(const Eigen::Vector3d& p, double max_distance) const;

  /// Calls visit(const WallHit&) for every triangle whose closest distance to p is
  /// < radius, in an unspecified but deterministic order.
  template <class Visit>
  void within(const Eigen::Vector3d& p, double radius, Visit&& visit) const {
    visit_within(p, radius, [](void* context, const WallHit& hit) { (*static_cast<Visit*>(context))(hit); },
                 &visit);
  }

  /// Appends to `triangles` every triangle whose bounding box comes within
  /// `radius` of `region`: a superset of those within `radius` of any point of
  /// the region, for a run of nearby points to share one descent of the tree.
  void near_box(const Eigen::AlignedBox3d& region, double radius, std::vector<int>& triangles) const;

  /// Triangle t's bounding box (as of the last build or refit).
  [[nodiscard]] const Eigen::AlignedBox3d& box(int t) const { return boxes_[static_cast<std::size_t>(t)]; }

  [[nodiscard]] std::size_t node_count() const { return nodes_.size(); }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0;   ///< leaf: first position in order_; inner: index of the right child
    int count = 0;   ///< leaf: number of triangles (> 0); inner: 0 (left child = this + 1)
  };

  int build(int begin, int end, std::vector<Eigen::Vector3d>& centroids);
  void require_current() const;
  void visit_within(const Eigen::Vector3d& p, double radius, void (*visit)(void*, const WallHit&),
                    void* context) const;
  template <class Distance, class Leaf>
  void descend(double radius2, Distance&& near, Leaf&& leaf) const;

  const TriangleMesh* mesh_;
  std::vector<Node> nodes_;
  std::vector<int> order_;  ///< triangle indices, leaves own contiguous ranges
  std::vector<Eigen::AlignedBox3d> boxes_;  ///< each triangle's box, by triangle index
  std::uint64_t version_ = 0;
};

}  // namespace tankfsi::sph
