// Which triangles are walls for a particle (wall_contacts.hpp), round the top of
// a plate: the inner plate of the overflow tank (interior x < 2, top face y = 0.74,
// 2 L0 thick). A particle beside the inner face just below the top is behind the top
// face's plane but not behind the top face itself: the inner face is its only wall.
// One that crossed a face by less than L0/2 touches it; one over the top sees the top.
// Just outside a faceted cylinder, beside its facets and behind every wall near it,
// a particle has crossed the wall and still touches it. At a box's corner the three
// walls, their pairs' overlaps and the octant complete the lattice.
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "sph_solver/isph/wall_contacts.hpp"
#include "sph_solver/walls/primitive_meshes.hpp"
#include "sph_solver/walls/tank_meshes.hpp"
#include "tests/unit/sph/still_tank.hpp"
#include "tests/unit/sph/two_sided_sheet.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;

TEST_CASE("wall contacts round a plate's top (a convex edge)", "[wall_geometry]") {
  const FluidModel model = tankfsi::test::water();  // L0 = 0.02 m
  const Kernel kernel(model.kernel, 2, model.smoothing_length);
  const WallModel walls(make_overflow_tank_2d(OverflowTank2d{.plate_thickness = 0.04, .target_edge = 0.02}), model,
                        kernel);
  const std::vector<Vector3d> x{
      {1.998, 0.735, 0.0},  // beside the inner face, 5 mm below the top's plane
      {2.003, 0.500, 0.0},  // 3 mm into the inner face (< L0/2)
      {2.020, 0.750, 0.0},  // 1 cm over the middle of the top
  };
  const WallContacts contacts = find_wall_contacts(walls, x, 2);

  const auto beside = contacts.of(0);
  REQUIRE(beside.size() == 1);
  CHECK(beside[0].normal.isApprox(Vector3d(-1, 0, 0), 1e-12));
  CHECK(beside[0].distance == Approx(0.002).epsilon(1e-9));

  const auto crossed = contacts.of(1);
  REQUIRE(crossed.size() == 1);
  CHECK(crossed[0].normal.isApprox(Vector3d(-1, 0, 0), 1e-12));
  CHECK(crossed[0].distance == 0.0);

  const auto over = contacts.of(2);
  REQUIRE(over.size() == 1);
  CHECK(over[0].normal.isApprox(Vector3d(0, 1, 0), 1e-12));
  CHECK(over[0].distance == Approx(0.01).epsilon(1e-9));
}

TEST_CASE("wall contacts just outside a faceted cylinder's edge: crossed, touching", "[wall_geometry]") {
  // R = 1 m in 32 facets: the vertical edge at angle 0 is at (1, 0, z). A particle 3 mm
  // outside it projects beyond both facets' edges (beside them) and is behind both.
  FluidModel model = tankfsi::test::water();
  model.dimension = 3;
  const Kernel kernel(model.kernel, 3, model.smoothing_length);
  const WallModel walls(make_cylindrical_tank(1.0, 1.0, 32, 8, 4), model, kernel);
  const std::vector<Vector3d> x{{1.003, 0.0, 0.5}};
  const WallContacts contacts = find_wall_contacts(walls, x, 3);
  const auto touching = contacts.of(0);
  REQUIRE(touching.size() == 1);  // the two facets are one wall (same_wall_cosine)
  CHECK(touching[0].distance == 0.0);
  CHECK(touching[0].normal.x() < -0.99);  // into the tank
}

TEST_CASE("a box's corner: the walls' kernel sums complete the lattice, with the octant", "[wall_geometry]") {
  // The 12-triangle box (two per face): particles on the fluid lattice near a floor
  // corner. Fluid neighbours + each wall's Z0 - each orthogonal pair's overlap + the
  // octant of the three must be the full lattice's kernel sum: 1 % short at the
  // corner particle without the octant, 7 % over everywhere when the box's edges
  // passed for curvature. Tolerance: the tables' linear interpolation, 1e-4.
  FluidModel model = tankfsi::test::water();
  model.dimension = 3;
  model.kernel = KernelType::quartic_spline;
  const double l0 = model.spacing;
  const Kernel kernel(model.kernel, 3, model.smoothing_length);
  const WallModel walls(make_box(Vector3d::Zero(), Vector3d(0.4, 0.4, 0.3), NormalSide::inward), model, kernel);
  const int reach = static_cast<int>(kernel.support_radius() / l0) + 1;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c) {
        const Vector3d x_i = l0 * Vector3d(a + 0.5, b + 0.5, c + 0.5);
        const WallContacts contacts = find_wall_contacts(walls, std::vector<Vector3d>{x_i}, 3);
        double sum = 0.0, full = 0.0;
        for (int i = -reach; i <= reach; ++i)
          for (int j = -reach; j <= reach; ++j)
            for (int k = -reach; k <= reach; ++k) {
              const Vector3d x_j = x_i + l0 * Vector3d(i, j, k);
              const double w = l0 * l0 * l0 * kernel.value((x_j - x_i).norm());
              full += w;
              if (x_j.minCoeff() > 0.0) sum += w;
            }
        for (const WallContact& w : contacts.of(0)) sum += w.values.z0;
        for (const BoundaryOverlap& o : contacts.overlaps_of(0)) sum -= o.values.q0;
        for (const CornerOctant& o : contacts.octants_of(0)) sum += o.values.q0;
        INFO("particle at (" << a + 0.5 << ", " << b + 0.5 << ", " << c + 0.5 << ") L0");
        CHECK(contacts.of(0).size() == 3);
        CHECK(std::abs(sum - full) < 1e-4 * full);
      }
  const auto corner = find_wall_contacts(walls, std::vector<Vector3d>{0.5 * l0 * Vector3d::Ones()}, 3);
  CHECK(corner.octants_of(0).size() == 1);
}

namespace {

// Each wall vertex's share of the particle's contact with the cylinder's wall.
std::vector<double> vertex_shares(const WallModel& walls, const Vector3d& x) {
  const WallContacts contacts = find_wall_contacts(walls, std::vector<Vector3d>{x}, 3);
  std::vector<double> shares(walls.mesh().vertex_count(), 0.0);
  for (const WallContact& c : contacts.of(0))
    if (c.normal.z() < 0.5)  // the side wall, not the floor
      for_each_vertex_share(walls.mesh(), c, [&shares](int v, double s) { shares[static_cast<std::size_t>(v)] += s; });
  return shares;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double largest = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v) largest = std::max(largest, std::abs(a[v] - b[v]));
  return largest;
}

}  // namespace

TEST_CASE("inside a faceted cylinder the contact changes continuously across two facets' bisector",
          "[wall_geometry]") {
  // R = 1 m in 32 facets; the vertical edge at angle 0 is at (1, 0, z), the bisector
  // of its two facets the plane y = 0. A particle 1.5 L0 inside the edge, moving
  // across that plane: the nearest facet changes there and its closest point jumps
  // by 2 d tan(5.6°) = 3 mm (about 1.5 % of a facet's width). The contact blends the
  // two (wall_contacts.hpp), so its vertex shares (the wall force's distribution and
  // the wall velocity's interpolation) and its normal change continuously.
  FluidModel model = tankfsi::test::water();  // L0 = 0.02 m
  model.dimension = 3;
  const Kernel kernel(model.kernel, 3, model.smoothing_length);
  const WallModel walls(make_cylindrical_tank(1.0, 1.0, 32, 8, 4), model, kernel);
  const double z = 0.47;  // between the wall's horizontal edges
  const auto at = [z](double y) { return Vector3d(0.97, y, z); };

  // Across the plane by 2e-9 m: the same shares to round-off (a jump was 1e-2).
  const double eps = 1e-9;
  CHECK(largest_difference(vertex_shares(walls, at(-eps)), vertex_shares(walls, at(eps))) < 1e-6);
  const WallContacts across = find_wall_contacts(walls, std::vector<Vector3d>{at(-eps), at(eps)}, 3);
  REQUIRE(across.of(0).size() == across.of(1).size());
  for (std::size_t c = 0; c < across.of(0).size(); ++c) {
    CHECK((across.of(0)[c].normal - across.of(1)[c].normal).norm() < 1e-6);
    CHECK(across.of(0)[c].distance == Approx(across.of(1)[c].distance).margin(1e-8));
  }
  // On the plane the two facets weigh alike.
  const WallContacts on = find_wall_contacts(walls, std::vector<Vector3d>{at(0.0)}, 3);
  const auto side = std::find_if(on.of(0).begin(), on.of(0).end(), [](const WallContact& c) { return c.normal.z() < 0.5; });
  REQUIRE(side != on.of(0).end());
  REQUIRE(side->foot_count >= 2);
  CHECK(side->feet[0].weight == Approx(side->feet[1].weight).epsilon(1e-6));

  // Along a sweep of ±L0 in steps of L0/200 the shares sum to 1 (the feet's weights
  // are normalised) wherever feet enter or leave the blend.
  for (int k = -200; k <= 200; ++k) {
    double total = 0.0;
    for (double s : vertex_shares(walls, at(1e-4 * k))) total += s;
    CHECK(total == Approx(1.0).epsilon(1e-12));
  }

  // In the middle of a facet, far from its edges, the nearest triangle alone.
  const WallContacts middle = find_wall_contacts(walls, std::vector<Vector3d>{Vector3d(0.97 * std::cos(0.098), 0.97 * std::sin(0.098), z)}, 3);
  for (const WallContact& c : middle.of(0)) CHECK(c.foot_count == 1);
}

TEST_CASE("a two-sided sheet is a wall from behind, except beside its free edge", "[wall_geometry]") {
  // The sheet faces -x; flagged two-sided, a particle at x > 0.3 sees it with +x.
  const FluidModel model = tankfsi::test::water();  // L0 = 0.02 m
  const Kernel kernel(model.kernel, 2, model.smoothing_length);
  WallModel walls(tankfsi::test::vertical_sheet(10), model, kernel);
  const std::vector<Vector3d> x{
      {0.290, 0.30, 0.0},  // 1 cm in front
      {0.315, 0.30, 0.0},  // 1.5 cm behind (deeper than L0/2)
      {0.305, 0.08, 0.0},  // behind the plane, below the free edge (closest point on it)
  };
  const WallContacts one_sided = find_wall_contacts(walls, x, 2);
  REQUIRE(one_sided.of(0).size() == 1);
  CHECK(one_sided.of(0)[0].normal.isApprox(Vector3d(-1, 0, 0), 1e-12));
  CHECK(one_sided.of(1).empty());  // it would have crossed the wall

  walls.replace_mesh(tankfsi::test::vertical_sheet(10),
                     std::vector<char>(walls.mesh().triangle_count(), 1));
  const WallContacts two_sided = find_wall_contacts(walls, x, 2);
  REQUIRE(two_sided.of(0).size() == 1);
  CHECK(two_sided.of(0)[0].normal.isApprox(Vector3d(-1, 0, 0), 1e-12));
  CHECK(two_sided.of(0)[0].distance == Approx(0.01).epsilon(1e-9));
  REQUIRE(two_sided.of(1).size() == 1);
  CHECK(two_sided.of(1)[0].normal.isApprox(Vector3d(1, 0, 0), 1e-12));
  CHECK(two_sided.of(1)[0].distance == Approx(0.015).epsilon(1e-9));
  // The same table values as a particle as far in front (the sheet is flat).
  CHECK(two_sided.of(1)[0].values.z0 == Approx(walls.table().at(0.015).z0).epsilon(1e-12));
  // Below the free edge and behind the plane: round the sheet's edge, no contact
  // (one-sided, it touched the sheet at distance 0, having crossed it by 0.5 cm < L0/2).
  CHECK(two_sided.of(2).empty());
  REQUIRE(one_sided.of(2).size() == 1);
  CHECK(one_sided.of(2)[0].distance == 0.0);
}
