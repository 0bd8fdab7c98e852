#include "sph_solver/walls/mesh_topology.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace tankfsi::sph {

namespace {

bool in_range(const std::array<int, 3>& t, std::size_t vertex_count) {
  return std::all_of(t.begin(), t.end(), [&](int v) {
    return v >= 0 && static_cast<std::size_t>(v) < vertex_count;
  });
}

std::string triangle_text(int index, const std::array<int, 3>& t) {
  std::ostringstream out;
  out << "triangle " << index << " (vertices " << t[0] << ", " << t[1] << ", " << t[2] << ")";
  return out.str();
}

std::string edge_text(int a, int b) {
  return "edge (" + std::to_string(std::min(a, b)) + ", " + std::to_string(std::max(a, b)) + ")";
}

}  // namespace

void for_each_edge(std::span<const std::array<int, 3>> triangles, std::size_t vertex_count,
                   const std::function<void(std::span<const HalfEdge>)>& visit) {
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!in_range(triangles[t], vertex_count)) continue;
    for (int k = 0; k < 3; ++k) {
      const auto& tri = triangles[t];
      half_edges.push_back({tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)],
                            static_cast<int>(t), k});
    }
  }
  const auto key = [](const HalfEdge& h) {
    return std::make_tuple(std::min(h.from, h.to), std::max(h.from, h.to), h.triangle, h.edge);
  };
  std::sort(half_edges.begin(), half_edges.end(),
            [&](const HalfEdge& x, const HalfEdge& y) { return key(x) < key(y); });
  for (std::size_t begin = 0; begin < half_edges.size();) {
    std::size_t end = begin + 1;
    const auto lo = std::min(half_edges[begin].from, half_edges[begin].to);
    const auto hi = std::max(half_edges[begin].from, half_edges[begin].to);
    while (end < half_edges.size() && std::min(half_edges[end].from, half_edges[end].to) == lo &&
           std::max(half_edges[end].from, half_edges[end].to) == hi)
      ++end;
    visit(std::span<const HalfEdge>(half_edges.data() + begin, end - begin));
    begin = end;
  }
}

std::size_t TopologyReport::count(TopologyIssueKind kind) const {
  return static_cast<std::size_t>(
      std::count_if(issues.begin(), issues.end(), [&](const TopologyIssue& i) { return i.kind == kind; }));
}

std::string TopologyReport::summary() const {
  std::string text;
  for (const auto& issue : issues) text += issue.message + "\n";
  return text;
}

TopologyReport check_topology(std::span<const Eigen::Vector3d> vertices,
                              std::span<const std::array<int, 3>> triangles,
                              const TopologyOptions& options) {
  TopologyReport report;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const int index = static_cast<int>(t);
    if (!in_range(tri, vertices.size())) {
      report.issues.push_back({TopologyIssueKind::index_out_of_range, index, {-1, -1},
                               triangle_text(index, tri) + ": vertex index out of range (the mesh has " +
                                   std::to_string(vertices.size()) + " vertices)"});
      continue;
    }
    const bool repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
    const Eigen::Vector3d& a = vertices[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3d& b = vertices[static_cast<std::size_t>(tri[1])];
    const Eigen::Vector3d& c = vertices[static_cast<std::size_t>(tri[2])];
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double twice_area = (b - a).cross(c - a).norm();
    if (repeated || twice_area <= options.degenerate_sine * longest2) {
      std::ostringstream message;
      message << triangle_text(index, tri) << " is degenerate: ";
      if (repeated)
        message << "a vertex index is repeated";
      else
        message << "zero area (area " << 0.5 * twice_area << ", longest edge " << std::sqrt(longest2) << ")";
      report.issues.push_back({TopologyIssueKind::degenerate_triangle, index, {-1, -1}, message.str()});
    }
  }

  for_each_edge(triangles, vertices.size(), [&](std::span<const HalfEdge> uses) {
    const HalfEdge& first = uses.front();
    const std::array<int, 2> edge{std::min(first.from, first.to), std::max(first.from, first.to)};
    if (edge[0] == edge[1]) return;  // inside a triangle with a repeated index: reported above
    if (uses.size() == 1) {
      if (options.report_open_edges)
        report.issues.push_back({TopologyIssueKind::open_edge, first.triangle, edge,
                                 edge_text(edge[0], edge[1]) + " is open: used by triangle " +
                                     std::to_string(first.triangle) + " only"});
    } else if (uses.size() > 2) {
      std::string list;
      for (const auto& h : uses) list += (list.empty() ? "" : ", ") + std::to_string(h.triangle);
      report.issues.push_back({TopologyIssueKind::non_manifold_edge, first.triangle, edge,
                               edge_text(edge[0], edge[1]) + " is non-manifold: used by " +
                                   std::to_string(uses.size()) + " triangles (" + list + ")"});
    } else if (uses[0].from == uses[1].from) {
      // Same direction in both triangles: one of them is flipped.
      report.issues.push_back(
          {TopologyIssueKind::inconsistent_orientation, first.triangle, edge,
           "triangles " + std::to_string(uses[0].triangle) + " and " + std::to_string(uses[1].triangle) +
               " have inconsistent orientation: both traverse " + edge_text(edge[0], edge[1]) + " as " +
               std::to_string(uses[0].from) + " -> " + std::to_string(uses[0].to)});
    }
  });
  return report;
}

}  // namespace tankfsi::sph
