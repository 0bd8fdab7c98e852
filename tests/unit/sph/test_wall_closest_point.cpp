// Point-triangle closest point and the signed distance of wall meshes, each checked
// against an independent reference: a plane-projection + segment computation in long
// double, dense sampling of the triangle, and analytic inside tests of closed shapes
// (a cube, an icosphere via its face planes, a thin tetrahedron, and an L-shaped
// polycube with concave edges and a saddle corner).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "sph_solver/walls/closest_point.hpp"
#include "sph_solver/walls/mesh_topology.hpp"
#include "sph_solver/walls/primitive_meshes.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;

namespace {

using Vec3L = Eigen::Matrix<long double, 3, 1>;

Vec3L wide(const Vector3d& x) { return x.cast<long double>(); }

Vec3L closest_on_segment(const Vec3L& p, const Vec3L& a, const Vec3L& b) {
  const Vec3L d = b - a;
  const long double l2 = d.squaredNorm();
  long double s = l2 > 0 ? (p - a).dot(d) / l2 : 0;
  s = std::clamp(s, static_cast<long double>(0), static_cast<long double>(1));
  return a + s * d;
}

// Reference: project on the plane, keep the projection if its barycentrics (from
// signed sub-areas) are all >= 0, else the best of the three segments. Long double,
// so that it stays accurate for slivers. Returns the squared distance and the point.
std::pair<double, Vector3d> reference_closest(const Vector3d& pd, const Vector3d& ad, const Vector3d& bd,
                                              const Vector3d& cd) {
  const Vec3L p = wide(pd), a = wide(ad), b = wide(bd), c = wide(cd);
  const Vec3L n = (b - a).cross(c - a);
  const long double n2 = n.squaredNorm();
  std::vector<Vec3L> candidates{closest_on_segment(p, a, b), closest_on_segment(p, b, c), closest_on_segment(p, c, a)};
  if (n2 > 0) {
    const Vec3L q = p - ((p - a).dot(n) / n2) * n;
    const long double u = (c - b).cross(q - b).dot(n) / n2;
    const long double v = (a - c).cross(q - c).dot(n) / n2;
    const long double w = (b - a).cross(q - a).dot(n) / n2;
    if (u >= 0 && v >= 0 && w >= 0) candidates.push_back(q);
  }
  Vec3L best = candidates[0];
  for (const auto& q : candidates)
    if ((p - q).squaredNorm() < (p - best).squaredNorm()) best = q;
  return {static_cast<double>((p - best).squaredNorm()), best.cast<double>()};
}

struct Triangle {
  Vector3d a, b, c;
};

Triangle random_triangle(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
}

// Needle: c close to the line ab (relative offset `thinness`), possibly beyond b or a.
Triangle sliver_triangle(std::mt19937_64& rng, double thinness) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> along(-0.2, 1.2);
  const Vector3d a(u(rng), u(rng), u(rng));
  const Vector3d b(u(rng), u(rng), u(rng));
  const Vector3d side = (b - a).cross(Vector3d(u(rng), u(rng), u(rng))).normalized();
  return {a, b, a + along(rng) * (b - a) + thinness * (b - a).norm() * side};
}

int region_id(const ClosestPoint& cp) {
  switch (cp.feature) {
    case TriangleFeature::face:
      return 0;
    case TriangleFeature::edge:
      return 1 + cp.feature_index;
    case TriangleFeature::vertex:
      return 4 + cp.feature_index;
  }
  return -1;
}

struct Errors {
  double distance = 0.0;  // |d - d_ref| / L
  double point = 0.0;     // |q - q_ref| / L
  double rebuild = 0.0;   // |Σ w_k x_k - q| / L
  std::array<int, 7> regions{};
};

void check_triangle(const Triangle& tri, std::mt19937_64& rng, int points, Errors& errors) {
  const double size = std::max({(tri.b - tri.a).norm(), (tri.c - tri.b).norm(), (tri.a - tri.c).norm()});
  Eigen::AlignedBox3d box(tri.a);
  box.extend(tri.b);
  box.extend(tri.c);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < points; ++i) {
    const Vector3d r(u(rng), u(rng), u(rng));
    const Vector3d p = box.min() - Vector3d::Constant(size) +
                       r.cwiseProduct(box.sizes() + Vector3d::Constant(2.0 * size));
    const ClosestPoint cp = closest_point_on_triangle(p, tri.a, tri.b, tri.c);
    const auto [d2_ref, q_ref] = reference_closest(p, tri.a, tri.b, tri.c);
    errors.distance = std::max(errors.distance, std::abs(std::sqrt(cp.squared_distance) - std::sqrt(d2_ref)) / size);
    errors.point = std::max(errors.point, (cp.point - q_ref).norm() / size);
    const Vector3d rebuilt = cp.barycentric[0] * tri.a + cp.barycentric[1] * tri.b + cp.barycentric[2] * tri.c;
    errors.rebuild = std::max(errors.rebuild, (rebuilt - cp.point).norm() / size);
    REQUIRE(cp.barycentric.minCoeff() >= 0.0);
    REQUIRE(std::abs(cp.barycentric.sum() - 1.0) <= 4e-16);
    REQUIRE(cp.squared_distance == (p - cp.point).squaredNorm());
    if (cp.feature == TriangleFeature::vertex) REQUIRE(cp.barycentric == Vector3d::Unit(cp.feature_index));
    if (cp.feature == TriangleFeature::edge) REQUIRE(cp.barycentric[(cp.feature_index + 2) % 3] == 0.0);
    ++errors.regions[static_cast<std::size_t>(region_id(cp))];
  }
}

// Triangle soup -> mesh, plus the inside test of a convex closed mesh from its face
// planes: inside iff behind every face plane.
bool inside_convex(const TriangleMesh& mesh, const Vector3d& p) {
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    if ((p - mesh.corner(static_cast<int>(t), 0)).dot(mesh.face_normals()[t]) >= 0.0) return false;
  return true;
}

// Nearest triangle by brute force (lowest index on ties) and its signed distance.
double brute_signed_distance(const TriangleMesh& mesh, const Vector3d& p, bool pseudo_normals) {
  int best = 0;
  ClosestPoint best_cp = closest_point_on_triangle(p, mesh, 0);
  for (int t = 1; t < static_cast<int>(mesh.triangle_count()); ++t) {
    const ClosestPoint cp = closest_point_on_triangle(p, mesh, t);
    if (cp.squared_distance < best_cp.squared_distance) {
      best = t;
      best_cp = cp;
    }
  }
  if (pseudo_normals) return signed_distance(p, mesh, best, best_cp);
  // The naive rule, for comparison: the face normal of whichever triangle won.
  const double side = (p - best_cp.point).dot(mesh.face_normals()[static_cast<std::size_t>(best)]);
  return side < 0.0 ? -std::sqrt(best_cp.squared_distance) : std::sqrt(best_cp.squared_distance);
}

// 2x2x2 unit voxels minus the voxel [1,2]^3: three concave edges meeting at the saddle
// corner (1,1,1). Boundary quads between filled and empty voxels, outward normals.
bool polycube_filled(int i, int j, int k) {
  if (i < 0 || j < 0 || k < 0 || i > 1 || j > 1 || k > 1) return false;
  return !(i == 1 && j == 1 && k == 1);
}

TriangleMesh make_polycube() {
  std::vector<Vector3d> vertices;
  for (int z = 0; z <= 2; ++z)
    for (int y = 0; y <= 2; ++y)
      for (int x = 0; x <= 2; ++x) vertices.emplace_back(x, y, z);
  const auto id = [](const Eigen::Vector3i& x) { return x[0] + 3 * x[1] + 9 * x[2]; };
  std::vector<std::array<int, 3>> triangles;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        if (!polycube_filled(i, j, k)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (const int sign : {-1, 1}) {
            Eigen::Vector3i next(i, j, k);
            next[axis] += sign;
            if (polycube_filled(next[0], next[1], next[2])) continue;
            // e_b x e_c = e_axis: corners base, +e_b, +e_b+e_c, +e_c turn about +e_axis.
            const Eigen::Vector3i eb = Eigen::Vector3i::Unit((axis + 1) % 3);
            const Eigen::Vector3i ec = Eigen::Vector3i::Unit((axis + 2) % 3);
            Eigen::Vector3i base(i, j, k);
            if (sign > 0) base[axis] += 1;
            std::array<int, 4> q{id(base), id(base + eb), id(base + eb + ec), id(base + ec)};
            if (sign < 0) std::swap(q[1], q[3]);
            triangles.push_back({q[0], q[1], q[2]});
            triangles.push_back({q[0], q[2], q[3]});
          }
      }
  // Drop the unused vertices (the centre (1,1,1) is used; the inside ones are not).
  std::vector<int> renumber(vertices.size(), -1);
  std::vector<Vector3d> used;
  for (auto& t : triangles)
    for (int& v : t) {
      if (renumber[static_cast<std::size_t>(v)] < 0) {
        renumber[static_cast<std::size_t>(v)] = static_cast<int>(used.size());
        used.push_back(vertices[static_cast<std::size_t>(v)]);
      }
      v = renumber[static_cast<std::size_t>(v)];
    }
  return TriangleMesh(std::move(used), std::move(triangles));
}

bool inside_polycube(const Vector3d& p) {
  if ((p.array() <= 0.0).any() || (p.array() >= 2.0).any()) return false;
  return !((p.array() >= 1.0).all());
}

struct SignCount {
  int checked = 0;
  int wrong = 0;
  int naive_wrong = 0;
};

template <class Inside>
SignCount check_signs(const TriangleMesh& mesh, const std::vector<Vector3d>& points, Inside inside) {
  SignCount count;
  for (const auto& p : points) {
    const double d = brute_signed_distance(mesh, p, true);
    if (std::abs(d) < 1e-9) continue;  // on the surface: no side to check
    ++count.checked;
    if ((d < 0.0) != inside(p)) ++count.wrong;
    if ((brute_signed_distance(mesh, p, false) < 0.0) != inside(p)) ++count.naive_wrong;
  }
  return count;
}

std::vector<Vector3d> random_points(std::mt19937_64& rng, const Eigen::AlignedBox3d& box, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vector3d> points;
  for (int i = 0; i < n; ++i)
    points.push_back(box.min() + Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(box.sizes()));
  return points;
}

// Points close to every vertex and edge midpoint of a mesh: the edge and vertex
// regions, where the sign needs the pseudo-normals.
std::vector<Vector3d> points_near_features(std::mt19937_64& rng, const TriangleMesh& mesh, double spread, int per) {
  std::uniform_real_distribution<double> u(-spread, spread);
  std::vector<Vector3d> points;
  std::vector<Vector3d> features(mesh.vertices());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k)
      features.push_back(0.5 * (mesh.corner(static_cast<int>(t), k) + mesh.corner(static_cast<int>(t), (k + 1) % 3)));
  for (const auto& x : features)
    for (int i = 0; i < per; ++i) points.push_back(x + Vector3d(u(rng), u(rng), u(rng)));
  return points;
}

}  // namespace

TEST_CASE("closest point on random triangles matches the long-double reference, all regions hit",
          "[wall_geometry]") {
  std::mt19937_64 rng(20240611);
  Errors errors;
  for (int n = 0; n < 200; ++n) check_triangle(random_triangle(rng), rng, 100, errors);
  INFO("max |d - d_ref|/L = " << errors.distance << ", max |q - q_ref|/L = " << errors.point
                              << ", max |sum w x - q|/L = " << errors.rebuild);
  CHECK(errors.distance <= 1e-14);
  CHECK(errors.point <= 1e-13);
  CHECK(errors.rebuild <= 1e-15);
  for (std::size_t r = 0; r < 7; ++r) {
    INFO("region " << r << " (0 face, 1-3 edges, 4-6 vertices) hit " << errors.regions[r] << " times");
    CHECK(errors.regions[r] > 100);
  }
}

TEST_CASE("closest point on sliver and degenerate triangles", "[wall_geometry]") {
  std::mt19937_64 rng(77);
  for (const double thinness : {1e-3, 1e-6, 1e-9}) {
    Errors errors;
    for (int n = 0; n < 100; ++n) check_triangle(sliver_triangle(rng, thinness), rng, 100, errors);
    INFO("thinness " << thinness << ": max |d - d_ref|/L = " << errors.distance << ", max |q - q_ref|/L = "
                     << errors.point << ", max |sum w x - q|/L = " << errors.rebuild);
    CHECK(errors.distance <= 1e-14);
    CHECK(errors.point <= 1e-12);
    CHECK(errors.rebuild <= 1e-15);
    for (std::size_t r = 1; r < 7; ++r) CHECK(errors.regions[r] > 0);  // the face is too thin to hit at 1e-9
  }
  SECTION("collinear and coincident vertices: the closest point of the segments") {
    Errors errors;
    const Vector3d a(0.1, -0.3, 0.2), b(0.9, 0.5, -0.4);
    check_triangle({a, b, a + 0.3 * (b - a)}, rng, 2000, errors);
    check_triangle({a, b, a + 1.7 * (b - a)}, rng, 2000, errors);
    check_triangle({a, b, b}, rng, 2000, errors);
    check_triangle({a, a, a}, rng, 2000, errors);
    INFO("max |d - d_ref|/L = " << errors.distance);
    CHECK(errors.distance <= 1e-15);
    CHECK(errors.regions[0] == 0);
  }
}

TEST_CASE("closest point is never farther than any point of a dense sampling of the triangle",
          "[wall_geometry]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  constexpr int n = 150;  // samples per side: n(n+1)/2 points of the triangle
  for (int trial = 0; trial < 12; ++trial) {
    const Triangle tri = trial % 3 == 2 ? sliver_triangle(rng, 1e-4) : random_triangle(rng);
    const double size = std::max({(tri.b - tri.a).norm(), (tri.c - tri.b).norm(), (tri.a - tri.c).norm()});
    for (int i = 0; i < 25; ++i) {
      const Vector3d p(u(rng), u(rng), u(rng));
      const ClosestPoint cp = closest_point_on_triangle(p, tri.a, tri.b, tri.c);
      const double d = std::sqrt(cp.squared_distance);
      double sampled = std::numeric_limits<double>::infinity();
      for (int s = 0; s <= n; ++s)
        for (int t = 0; s + t <= n; ++t) {
          const double ws = static_cast<double>(s) / n, wt = static_cast<double>(t) / n;
          const Vector3d x = (1.0 - ws - wt) * tri.a + ws * tri.b + wt * tri.c;
          sampled = std::min(sampled, (p - x).norm());
        }
      // Optimal: not beaten by any sample; and the samples come within their spacing.
      REQUIRE(d <= sampled + 1e-15);
      REQUIRE(sampled - d <= size / n);
    }
  }
}

TEST_CASE("signed distance: the sign matches analytic inside tests of closed meshes", "[wall_geometry]") {
  std::mt19937_64 rng(99);

  SECTION("cube: sign and value against the analytic box distance") {
    const TriangleMesh cube = make_box(Vector3d(-1, -1, -1), Vector3d(1, 1, 1), NormalSide::outward);
    auto points = random_points(rng, Eigen::AlignedBox3d(Vector3d::Constant(-2.0), Vector3d::Constant(2.0)), 3000);
    const auto near = points_near_features(rng, cube, 0.2, 20);
    points.insert(points.end(), near.begin(), near.end());
    double worst = 0.0;
    for (const auto& p : points) {
      const Vector3d outside = (p.cwiseAbs() - Vector3d::Ones()).cwiseMax(0.0);
      const double exact = outside.squaredNorm() > 0.0 ? outside.norm() : -(Vector3d::Ones() - p.cwiseAbs()).minCoeff();
      worst = std::max(worst, std::abs(brute_signed_distance(cube, p, true) - exact));
    }
    INFO("max |signed distance - exact| = " << worst);
    CHECK(worst <= 1e-15);
  }

  SECTION("icosphere: inside test by the face planes (convex)") {
    const TriangleMesh sphere = make_icosphere(1.0, 2);
    auto points = random_points(rng, Eigen::AlignedBox3d(Vector3d::Constant(-1.5), Vector3d::Constant(1.5)), 3000);
    const auto near = points_near_features(rng, sphere, 0.05, 2);
    points.insert(points.end(), near.begin(), near.end());
    const SignCount count = check_signs(sphere, points, [&](const Vector3d& p) { return inside_convex(sphere, p); });
    CHECK(count.checked > 4000);
    CHECK(count.wrong == 0);
  }

  SECTION("thin tetrahedron: sharp edges, where face normals alone give wrong signs") {
    const TriangleMesh tetra({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 0.08}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
    REQUIRE(check_topology(tetra.vertices(), tetra.triangles()).ok());
    auto points = random_points(rng, Eigen::AlignedBox3d(Vector3d(-0.3, -0.3, -0.3), Vector3d(1.3, 1.3, 0.4)), 4000);
    const auto near = points_near_features(rng, tetra, 0.05, 200);
    points.insert(points.end(), near.begin(), near.end());
    const SignCount count = check_signs(tetra, points, [&](const Vector3d& p) { return inside_convex(tetra, p); });
    INFO("points " << count.checked << ", wrong with face normals only: " << count.naive_wrong);
    CHECK(count.wrong == 0);
    CHECK(count.naive_wrong > 0);  // the test reaches the cases the pseudo-normals are for
  }

  SECTION("L-shaped polycube: concave edges and a saddle corner") {
    const TriangleMesh polycube = make_polycube();
    REQUIRE(check_topology(polycube.vertices(), polycube.triangles()).ok());
    auto points = random_points(rng, Eigen::AlignedBox3d(Vector3d::Constant(-0.5), Vector3d::Constant(2.5)), 4000);
    const auto near = points_near_features(rng, polycube, 0.2, 30);
    points.insert(points.end(), near.begin(), near.end());
    const SignCount count = check_signs(polycube, points, inside_polycube);
    INFO("points " << count.checked << ", wrong with face normals only: " << count.naive_wrong);
    CHECK(count.checked > 8000);
    CHECK(count.wrong == 0);
  }
}
