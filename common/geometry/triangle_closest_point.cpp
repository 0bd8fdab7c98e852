#include "common/geometry/triangle_closest_point.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tankfsi {

namespace {

ClosestPoint at_vertex(const Eigen::Vector3d& p, const Eigen::Vector3d& x, int k) {
  ClosestPoint r;
  r.point = x;
  r.barycentric = Eigen::Vector3d::Unit(k);
  r.squared_distance = (p - x).squaredNorm();
  r.feature = TriangleFeature::vertex;
  r.feature_index = k;
  return r;
}

// Point on edge k at parameter s in (0, 1) from x_k to x_{k+1}.
ClosestPoint on_edge(const Eigen::Vector3d& p, const Eigen::Vector3d& from, const Eigen::Vector3d& to, int k,
                     double s) {
  ClosestPoint r;
  r.point = from + s * (to - from);
  r.barycentric = Eigen::Vector3d::Zero();
  r.barycentric[k] = 1.0 - s;
  r.barycentric[(k + 1) % 3] = s;
  r.squared_distance = (p - r.point).squaredNorm();
  r.feature = TriangleFeature::edge;
  r.feature_index = k;
  return r;
}

// Closest point of a segment, as edge k (or an end vertex). Used for degenerate
// triangles, where the face region does not exist.
ClosestPoint on_segment(const Eigen::Vector3d& p, const std::array<const Eigen::Vector3d*, 3>& x, int k) {
  const Eigen::Vector3d& from = *x[static_cast<std::size_t>(k)];
  const Eigen::Vector3d& to = *x[static_cast<std::size_t>((k + 1) % 3)];
  const Eigen::Vector3d d = to - from;
  const double length2 = d.squaredNorm();
  const double s = length2 > 0.0 ? (p - from).dot(d) / length2 : 0.0;
  if (s <= 0.0) return at_vertex(p, from, k);
  if (s >= 1.0) return at_vertex(p, to, (k + 1) % 3);
  return on_edge(p, from, to, k, s);
}

}  // namespace

ClosestPoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  // Ericson §5.1.5, ClosestPtPointTriangle, region by region. d1..d6 are projections
  // of p - vertex on the edge vectors ab and ac; va, vb, vc are (scaled) barycentric
  // coordinates of p's projection on the plane (signed areas).
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const Eigen::Vector3d ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return at_vertex(p, a, 0);

  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return at_vertex(p, b, 1);

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return on_edge(p, a, b, 0, d1 / (d1 - d3));

  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return at_vertex(p, c, 2);

  const double vb = d5 * d2 - d1 * d6;
  // Ericson's edge ac runs a -> c; ours (edge 2) runs c -> a, so the parameter is 1 - w.
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return on_edge(p, c, a, 2, 1.0 - d2 / (d2 - d6));

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return on_edge(p, b, c, 1, (d4 - d3) / ((d4 - d3) + (d5 - d6)));

  // Face region. va + vb + vc = |ab x ac|^2 = |ab|^2 |ac|^2 sin^2(A) in exact
  // arithmetic, while the round-off of each of va, vb, vc is ~eps |ab|^2 |ac|^2. For a
  // well-shaped triangle the weights are accurate; for a needle or a collinear
  // (degenerate) one they are noise. They still give a point of the triangle (weights
  // >= 0, sum 1), but maybe not the closest: then compare with the three edges, which
  // are well conditioned, and keep the face point only if clearly nearer.
  const double sum = va + vb + vc;
  const bool weights_valid = sum > 0.0 && va >= 0.0 && vb >= 0.0 && vc >= 0.0;
  ClosestPoint face;
  if (weights_valid) {
    face.barycentric = Eigen::Vector3d(va, vb, vc) / sum;
    face.point = face.barycentric[0] * a + face.barycentric[1] * b + face.barycentric[2] * c;
    face.squared_distance = (p - face.point).squaredNorm();
    face.feature = TriangleFeature::face;
    face.feature_index = 0;
    // sin(A) > 1e-3: relative error of the weights below ~1e-10.
    constexpr double min_sine_squared = 1e-6;
    if (sum > min_sine_squared * ab.squaredNorm() * ac.squaredNorm()) return face;
  }
  const std::array<const Eigen::Vector3d*, 3> x{&a, &b, &c};
  ClosestPoint best = on_segment(p, x, 0);
  for (int k = 1; k < 3; ++k) {
    const ClosestPoint candidate = on_segment(p, x, k);
    if (candidate.squared_distance < best.squared_distance) best = candidate;
  }
  // "Clearly": within 1e-12 relative both answers are equally accurate; prefer the
  // edge's, so that a degenerate triangle never reports its (non-existent) face.
  if (weights_valid && face.squared_distance < (1.0 - 1e-12) * best.squared_distance) return face;
  return best;
}

}  // namespace tankfsi
