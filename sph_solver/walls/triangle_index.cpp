#include "sph_solver/walls/triangle_index.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <stdexcept>

namespace tankfsi::sph {

namespace {

// Leaves of up to 4 triangles: fewer nodes than 1 per leaf, and 4 exact closest-point
// tests cost about as much as the box tests they would replace.
constexpr int leaf_size = 4;
// Median splits halve the range at every level: depth <= log2(n) + 1, far below this.
constexpr int max_depth = 64;

Eigen::AlignedBox3d triangle_box(const TriangleMesh& mesh, int t) {
  Eigen::AlignedBox3d box(mesh.corner(t, 0));
  box.extend(mesh.corner(t, 1));
  box.extend(mesh.corner(t, 2));
  return box;
}

}  // namespace

TriangleIndex::TriangleIndex(const TriangleMesh& mesh) : mesh_(&mesh) { rebuild(); }

void TriangleIndex::rebuild() {
  const int n = static_cast<int>(mesh_->triangle_count());
  order_.resize(static_cast<std::size_t>(n));
  std::iota(order_.begin(), order_.end(), 0);
  std::vector<Eigen::Vector3d> centroids(static_cast<std::size_t>(n));
  boxes_.resize(static_cast<std::size_t>(n));
  for (int t = 0; t < n; ++t) {
    centroids[static_cast<std::size_t>(t)] = (mesh_->corner(t, 0) + mesh_->corner(t, 1) + mesh_->corner(t, 2)) / 3.0;
    boxes_[static_cast<std::size_t>(t)] = triangle_box(*mesh_, t);
  }
  nodes_.clear();
  nodes_.reserve(static_cast<std::size_t>(2 * (n / leaf_size + 1)));
  if (n > 0) build(0, n, centroids);
  version_ = mesh_->geometry_version();
}

// Builds the subtree of order_[begin, end) in pre-order (a node before its children,
// the left child right after its parent), so that refit() can sweep the node array
// backwards and always meet children before parents.
int TriangleIndex::build(int begin, int end, std::vector<Eigen::Vector3d>& centroids) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  Eigen::AlignedBox3d box;
  Eigen::AlignedBox3d centre_box;
  for (int i = begin; i < end; ++i) {
    const int t = order_[static_cast<std::size_t>(i)];
    box.extend(boxes_[static_cast<std::size_t>(t)]);
    centre_box.extend(centroids[static_cast<std::size_t>(t)]);
  }
  nodes_[static_cast<std::size_t>(index)].box = box;
  if (end - begin <= leaf_size) {
    nodes_[static_cast<std::size_t>(index)].first = begin;
    nodes_[static_cast<std::size_t>(index)].count = end - begin;
    return index;
  }
  // Median split along the longest axis of the centroids' box.
  int axis = 0;
  centre_box.sizes().maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end, [&](int x, int y) {
    const double cx = centroids[static_cast<std::size_t>(x)][axis];
    const double cy = centroids[static_cast<std::size_t>(y)][axis];
    return cx < cy || (cx == cy && x < y);
  });
  build(begin, middle, centroids);
  const int right = build(middle, end, centroids);
  nodes_[static_cast<std::size_t>(index)].first = right;
  nodes_[static_cast<std::size_t>(index)].count = 0;
  return index;
}

void TriangleIndex::refit() {
  if (order_.size() != mesh_->triangle_count())
    throw std::logic_error("TriangleIndex::refit: the mesh's triangle count changed; rebuild instead");
  for (std::size_t t = 0; t < boxes_.size(); ++t) boxes_[t] = triangle_box(*mesh_, static_cast<int>(t));
  for (auto node = nodes_.rbegin(); node != nodes_.rend(); ++node) {
    if (node->count > 0) {
      node->box.setEmpty();
      for (int i = node->first; i < node->first + node->count; ++i)
        node->box.extend(boxes_[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])]);
    } else {
      const auto self = static_cast<std::size_t>(nodes_.rend() - node - 1);
      node->box = nodes_[self + 1].box.merged(nodes_[static_cast<std::size_t>(node->first)].box);
    }
  }
  version_ = mesh_->geometry_version();
}

void TriangleIndex::require_current() const {
  if (version_ != mesh_->geometry_version())
    throw std::logic_error("TriangleIndex: the wall mesh moved since the index was built; call refit()");
}

std::optional<WallHit> TriangleIndex::nearest(const Eigen::Vector3d& p, double max_distance) const {
  require_current();
  std::optional<WallHit> best;
  double best2 = max_distance * max_distance;
  if (nodes_.empty() || !(max_distance > 0.0)) return best;
  std::array<int, max_depth> stack{};
  int top = 0;
  stack[static_cast<std::size_t>(top++)] = 0;
  while (top > 0) {
    const Node& node = nodes_[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
    // Prune only boxes strictly farther than the best so far: a triangle at exactly
    // the best distance may win the tie on its lower index.
    const double box2 = node.box.squaredExteriorDistance(p);
    if (best ? box2 > best2 : box2 >= best2) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int t = order_[static_cast<std::size_t>(i)];
        const ClosestPoint closest = closest_point_on_triangle(p, *mesh_, t);
        const double d2 = closest.squared_distance;
        const bool better = best ? (d2 < best2 || (d2 == best2 && t < best->triangle)) : d2 < best2;
        if (better) {
          best = WallHit{t, closest};
          best2 = d2;
        }
      }
      continue;
    }
    // Visit the nearer child first (pushed last), so the bound tightens early.
    const int left = static_cast<int>(&node - nodes_.data()) + 1;
    const int right = node.first;
    const bool left_nearer = nodes_[static_cast<std::size_t>(left)].box.squaredExteriorDistance(p) <=
                             nodes_[static_cast<std::size_t>(right)].box.squaredExteriorDistance(p);
    stack[static_cast<std::size_t>(top++)] = left_nearer ? right : left;
    stack[static_cast<std::size_t>(top++)] = left_nearer ? left : right;
  }
  return best;
}

// Depth-first over the boxes that `near` (a squared distance of a box) keeps within
// radius2, calling leaf(t) for every triangle of the leaves reached.
template <class Distance, class Leaf>
void TriangleIndex::descend(double radius2, Distance&& near, Leaf&& leaf) const {
  std::array<int, max_depth> stack{};
  int top = 0;
  stack[static_cast<std::size_t>(top++)] = 0;
  while (top > 0) {
    const int index = stack[static_cast<std::size_t>(--top)];
    const Node& node = nodes_[static_cast<std::size_t>(index)];
    if (near(node.box) >= radius2) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) leaf(order_[static_cast<std::size_t>(i)]);
      continue;
    }
    stack[static_cast<std::size_t>(top++)] = node.first;
    stack[static_cast<std::size_t>(top++)] = index + 1;
  }
}

void TriangleIndex::visit_within(const Eigen::Vector3d& p, double radius, void (*visit)(void*, const WallHit&),
                                 void* context) const {
  require_current();
  if (nodes_.empty() || !(radius > 0.0)) return;
  const double radius2 = radius * radius;
  descend(
      radius2, [&p](const Eigen::AlignedBox3d& box) { return box.squaredExteriorDistance(p); },
      [&](int t) {
        if (const auto closest = closest_point_within(p, *mesh_, t, radius2)) visit(context, WallHit{t, *closest});
      });
}

void TriangleIndex::near_box(const Eigen::AlignedBox3d& region, double radius, std::vector<int>& triangles) const {
  require_current();
  if (nodes_.empty() || !(radius > 0.0)) return;
  const double radius2 = radius * radius;
  const auto distance = [&region](const Eigen::AlignedBox3d& box) { return box.squaredExteriorDistance(region); };
  descend(radius2, distance, [&](int t) {
    if (distance(boxes_[static_cast<std::size_t>(t)]) < radius2) triangles.push_back(t);
  });
}

}  // namespace tankfsi::sph
