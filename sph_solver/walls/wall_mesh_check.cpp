#include "sph_solver/walls/wall_mesh_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "common/geometry/segment_triangle.hpp"
#include "sph_solver/walls/mesh_topology.hpp"
#include "sph_solver/walls/triangle_index.hpp"

namespace tankfsi::sph {
namespace {

constexpr int max_reported = 5;

std::string point_text(const Eigen::Vector3d& p) {
  std::ostringstream text;
  text << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return text.str();
}

/// The first `max_reported` lines of a list of problems, with the count of the rest.
std::string listed(const std::string& heading, const std::vector<std::string>& lines) {
  std::string text = heading;
  for (std::size_t k = 0; k < lines.size() && k < max_reported; ++k) text += "\n  " + lines[k];
  if (lines.size() > max_reported) text += "\n  ... and " + std::to_string(lines.size() - max_reported) + " more";
  return text;
}

std::string topology_problem(const TriangleMesh& mesh) {
  TopologyOptions options;
  options.report_open_edges = false;  // judged against the fill level below
  const TopologyReport report = check_topology(mesh.vertices(), mesh.triangles(), options);
  if (report.ok()) return "";
  std::vector<std::string> lines;
  for (const auto& issue : report.issues) lines.push_back(issue.message);
  return listed("the wall mesh is not a valid surface:", lines);
}

/// Open edges through which the liquid would leak (see the header).
std::string open_edge_problem(const TriangleMesh& mesh, const WallCheckOptions& options, double tolerance) {
  const int up = options.dimension == 2 ? 1 : 2;
  const Eigen::AlignedBox3d box = mesh.bounding_box();
  // An edge along the front or back face (both ends on the same plane), not one
  // across the section such as the rim's.
  const auto on_open_plane = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const auto on = [&](double z) { return std::abs(a.z() - z) <= tolerance && std::abs(b.z() - z) <= tolerance; };
    return options.dimension == 2 && (on(box.min().z()) || on(box.max().z()));
  };
  std::vector<std::string> lines;
  for (const auto& edge : mesh.boundary_edges()) {
    const Eigen::Vector3d& a = mesh.vertices()[static_cast<std::size_t>(edge.vertices[0])];
    const Eigen::Vector3d& b = mesh.vertices()[static_cast<std::size_t>(edge.vertices[1])];
    if (on_open_plane(a, b)) continue;
    if (std::min(a[up], b[up]) >= options.fill_level - tolerance) continue;
    lines.push_back("edge (" + std::to_string(edge.vertices[0]) + ", " + std::to_string(edge.vertices[1]) + ") from " +
                    point_text(a) + " to " + point_text(b) + " is used by triangle " + std::to_string(edge.triangle) +
                    " only");
  }
  if (lines.empty()) return "";
  std::ostringstream heading;
  heading << "the walls are open below the fill level " << options.fill_level << " m (" << lines.size()
          << " open edge" << (lines.size() == 1 ? "" : "s") << "), where the liquid would leak out:";
  return listed(heading.str(), lines);
}

std::string orientation_problem(const TriangleMesh& mesh) {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  std::size_t count = 0;
  for (const auto& edge : mesh.boundary_edges()) {
    origin += mesh.vertices()[static_cast<std::size_t>(edge.vertices[0])];
    ++count;
  }
  if (count == 0) {
    for (const auto& v : mesh.vertices()) origin += v;
    count = mesh.vertex_count();
  }
  origin /= static_cast<double>(count);
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const int k = static_cast<int>(t);
    volume += (mesh.corner(k, 0) - origin).dot((mesh.corner(k, 1) - origin).cross(mesh.corner(k, 2) - origin)) / 6.0;
  }
  if (volume < 0.0) return "";
  std::ostringstream text;
  text << "the walls are inverted: their normals point out of the liquid (the right-hand-rule normal of each "
          "triangle must point into it; the surface's signed volume is +"
       << volume << " m^3, negative for inward normals): reverse the vertex order of every triangle";
  return text.str();
}

// --- Self-intersection ------------------------------------------------------

/// The two axes of the plane most nearly normal to n.
std::array<int, 2> plane_axes(const Eigen::Vector3d& n) {
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  return {(drop + 1) % 3, (drop + 2) % 3};
}

struct Flat {
  Eigen::Vector2d a, b, c;
};

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

/// p inside triangle (a, b, c) of either orientation, by at least `margin`
/// (a length; negative includes the border band).
bool inside_flat(const Flat& t, const Eigen::Vector2d& p, double margin) {
  const double area = cross2(t.b - t.a, t.c - t.a);
  const double sign = area >= 0.0 ? 1.0 : -1.0;
  const std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, 3> edges{
      {{t.a, t.b}, {t.b, t.c}, {t.c, t.a}}};
  for (const auto& [u, v] : edges) {
    const double length = (v - u).norm();
    if (sign * cross2(v - u, p - u) < margin * length) return false;
  }
  return true;
}

/// Segments pq and uv cross or touch (within `tolerance`).
bool segments_meet(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& u,
                   const Eigen::Vector2d& v, double tolerance) {
  const auto side = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& x) {
    const double length = (b - a).norm();
    return length > 0.0 ? cross2(b - a, x - a) / length : 0.0;
  };
  const double s1 = side(p, q, u), s2 = side(p, q, v), s3 = side(u, v, p), s4 = side(u, v, q);
  return s1 * s2 <= tolerance * tolerance && s3 * s4 <= tolerance * tolerance &&
         std::max(std::min(p.x(), q.x()), std::min(u.x(), v.x())) <=
             std::min(std::max(p.x(), q.x()), std::max(u.x(), v.x())) + tolerance &&
         std::max(std::min(p.y(), q.y()), std::min(u.y(), v.y())) <=
             std::min(std::max(p.y(), q.y()), std::max(u.y(), v.y())) + tolerance;
}

class IntersectionTest {
 public:
  IntersectionTest(const TriangleMesh& mesh, double tolerance) : mesh_(mesh), tolerance_(tolerance) {}

  /// Triangles s and t (s != t, sharing no edge) meet somewhere they should not.
  [[nodiscard]] bool meet(int s, int t) const {
    const auto shared = shared_vertex(s, t);
    if (coplanar(s, t)) return shared ? coplanar_sectors_overlap(s, t, *shared) : coplanar_overlap(s, t);
    if (shared) return segment_hits(opposite_edge(s, *shared), t) || segment_hits(opposite_edge(t, *shared), s);
    for (int k = 0; k < 3; ++k)
      if (segment_hits(edge(s, k), t) || segment_hits(edge(t, k), s)) return true;
    return false;
  }

 private:
  using Segment = std::pair<Eigen::Vector3d, Eigen::Vector3d>;

  [[nodiscard]] std::optional<int> shared_vertex(int s, int t) const {
    for (const int a : tri(s))
      for (const int b : tri(t))
        if (a == b) return a;
    return std::nullopt;
  }
  [[nodiscard]] const std::array<int, 3>& tri(int t) const { return mesh_.triangles()[static_cast<std::size_t>(t)]; }
  [[nodiscard]] const Eigen::Vector3d& vertex(int v) const { return mesh_.vertices()[static_cast<std::size_t>(v)]; }
  [[nodiscard]] Segment edge(int t, int k) const { return {mesh_.corner(t, k), mesh_.corner(t, (k + 1) % 3)}; }
  [[nodiscard]] Segment opposite_edge(int t, int v) const {
    for (int k = 0; k < 3; ++k)
      if (tri(t)[static_cast<std::size_t>(k)] == v) return edge(t, (k + 1) % 3);
    return edge(t, 0);
  }
  [[nodiscard]] double plane_distance(int t, const Eigen::Vector3d& x) const {
    return mesh_.face_normals()[static_cast<std::size_t>(t)].dot(x - mesh_.corner(t, 0));
  }
  [[nodiscard]] bool coplanar(int s, int t) const {
    for (int k = 0; k < 3; ++k)
      if (std::abs(plane_distance(t, mesh_.corner(s, k))) > tolerance_) return false;
    return true;
  }
  [[nodiscard]] Flat flat(int t, const std::array<int, 2>& axes) const {
    const auto f = [&](int k) { return project(mesh_.corner(t, k), axes); };
    return {f(0), f(1), f(2)};
  }
  static Eigen::Vector2d project(const Eigen::Vector3d& x, const std::array<int, 2>& axes) {
    return {x[axes[0]], x[axes[1]]};
  }

  /// A segment through the plane of t at a point of t (its border included).
  [[nodiscard]] bool segment_hits(const Segment& segment, int t) const {
    return segment_meets_triangle(segment.first, segment.second, mesh_.corner(t, 0), mesh_.corner(t, 1),
                                  mesh_.corner(t, 2), tolerance_);
  }

  /// Coplanar, no vertex shared: an edge of one crosses an edge of the other, or
  /// one lies inside the other.
  [[nodiscard]] bool coplanar_overlap(int s, int t) const {
    const auto axes = plane_axes(mesh_.face_normals()[static_cast<std::size_t>(t)]);
    const Flat fs = flat(s, axes), ft = flat(t, axes);
    const std::array<Eigen::Vector2d, 3> ps{fs.a, fs.b, fs.c}, pt{ft.a, ft.b, ft.c};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (segments_meet(ps[i], ps[(i + 1) % 3], pt[j], pt[(j + 1) % 3], tolerance_)) return true;
    return inside_flat(ft, fs.a, -tolerance_) || inside_flat(fs, ft.a, -tolerance_);
  }

  /// Coplanar, sharing vertex v: they overlap when a ray of one's corner at v (its
  /// two edges, its bisector) runs inside the other, or their opposite edges meet.
  [[nodiscard]] bool coplanar_sectors_overlap(int s, int t, int v) const {
    const auto axes = plane_axes(mesh_.face_normals()[static_cast<std::size_t>(t)]);
    const Flat fs = flat(s, axes), ft = flat(t, axes);
    const auto rays_enter = [&](int from, const Flat& other) {
      const Eigen::Vector2d apex = project(vertex(v), axes);
      std::vector<Eigen::Vector2d> directions;
      for (const int w : tri(from))
        if (w != v) directions.push_back((project(vertex(w), axes) - apex).normalized());
      directions.push_back((directions[0] + directions[1]).normalized());
      double shortest = std::numeric_limits<double>::infinity();
      for (const int w : tri(from))
        if (w != v) shortest = std::min(shortest, (project(vertex(w), axes) - apex).norm());
      for (const auto& d : directions)
        if (inside_flat(other, apex + 1e-3 * shortest * d, tolerance_)) return true;
      return false;
    };
    if (rays_enter(s, ft) || rays_enter(t, fs)) return true;
    const Segment es = opposite_edge(s, v), et = opposite_edge(t, v);
    return segments_meet(project(es.first, axes), project(es.second, axes), project(et.first, axes),
                         project(et.second, axes), tolerance_);
  }

  const TriangleMesh& mesh_;
  double tolerance_;
};

std::string intersection_problem(const TriangleMesh& mesh, double tolerance) {
  const TriangleIndex index(mesh);
  const IntersectionTest test(mesh, tolerance);
  std::vector<std::string> lines;
  for (int s = 0; s < static_cast<int>(mesh.triangle_count()); ++s) {
    const Eigen::Vector3d centre = (mesh.corner(s, 0) + mesh.corner(s, 1) + mesh.corner(s, 2)) / 3.0;
    double radius = 0.0;
    for (int k = 0; k < 3; ++k) radius = std::max(radius, (mesh.corner(s, k) - centre).norm());
    std::vector<int> candidates;
    index.within(centre, radius + 2.0 * tolerance, [&](const WallHit& hit) {
      if (hit.triangle > s) candidates.push_back(hit.triangle);
    });
    std::sort(candidates.begin(), candidates.end());
    for (const int t : candidates) {
      bool neighbours = false;
      for (int k = 0; k < 3; ++k) neighbours = neighbours || mesh.neighbour(s, k) == t;
      if (neighbours || !test.meet(s, t)) continue;
      lines.push_back("triangles " + std::to_string(s) + " and " + std::to_string(t) + " intersect near " +
                      point_text(centre));
    }
  }
  if (lines.empty()) return "";
  return listed("the wall mesh intersects itself (" + std::to_string(lines.size()) + " pair" +
                    (lines.size() == 1 ? "" : "s") + " of triangles):",
                lines);
}

}  // namespace

std::string wall_mesh_problem(const TriangleMesh& mesh, const WallCheckOptions& options) {
  if (mesh.triangle_count() == 0) return "the wall mesh has no triangles";
  const Eigen::AlignedBox3d box = mesh.bounding_box();
  const double tolerance = options.relative_tolerance * (box.max() - box.min()).norm();
  if (auto problem = topology_problem(mesh); !problem.empty()) return problem;
  if (auto problem = open_edge_problem(mesh, options, tolerance); !problem.empty()) return problem;
  if (auto problem = orientation_problem(mesh); !problem.empty()) return problem;
  return intersection_problem(mesh, tolerance);
}

}  // namespace tankfsi::sph
