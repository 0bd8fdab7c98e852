// segment_meets_triangle: through the face, past an edge, parallel, touching
// within the tolerance, and a degenerate triangle.
#include <catch2/catch.hpp>

#include "common/geometry/segment_triangle.hpp"

using tankfsi::segment_meets_triangle;
using V = Eigen::Vector3d;

TEST_CASE("segments meet a triangle where they pass through it", "[geometry]") {
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  CHECK(segment_meets_triangle(V(0.2, 0.2, 1), V(0.2, 0.2, -1), a, b, c, 0.0));   // through the face
  CHECK(segment_meets_triangle(V(0.2, 0.2, -1), V(0.3, 0.1, 1), a, b, c, 0.0));   // either direction
  CHECK_FALSE(segment_meets_triangle(V(0.6, 0.6, 1), V(0.6, 0.6, -1), a, b, c, 0.0));  // past the hypotenuse
  CHECK_FALSE(segment_meets_triangle(V(0.2, 0.2, 1), V(0.2, 0.2, 0.1), a, b, c, 0.0)); // stops short
  CHECK_FALSE(segment_meets_triangle(V(-1, 0.2, 0.5), V(2, 0.2, 0.5), a, b, c, 0.0));  // parallel above
  // On the border (the edge x = 0) it counts; just outside only within the tolerance.
  CHECK(segment_meets_triangle(V(0, 0.5, 1), V(0, 0.5, -1), a, b, c, 0.0));
  CHECK_FALSE(segment_meets_triangle(V(-1e-3, 0.5, 1), V(-1e-3, 0.5, -1), a, b, c, 0.0));
  CHECK(segment_meets_triangle(V(-1e-3, 0.5, 1), V(-1e-3, 0.5, -1), a, b, c, 2e-3));
  // Ending within the tolerance of the plane touches it.
  CHECK(segment_meets_triangle(V(0.2, 0.2, 1), V(0.2, 0.2, 1e-4), a, b, c, 1e-3));
  // A triangle with no area is met by nothing.
  CHECK_FALSE(segment_meets_triangle(V(0.5, 0, 1), V(0.5, 0, -1), a, b, V(2, 0, 0), 0.0));
}
