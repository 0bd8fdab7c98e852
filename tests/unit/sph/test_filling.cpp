// Initial particles: exact counts of the paper's 2D tank (200 × 69) and of a dam-break
// column (50 × 100), lattice order and values (mass, zero velocity, hydrostatic
// pressure), 2D front/back faces ignored, the clearance L₀/2 from every wall checked by
// brute force over all triangles, and a 3D cylinder whose count is predicted layer by
// layer from the inscribed polygon.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "sph_solver/particles/filling.hpp"
#include "sph_solver/walls/closest_point.hpp"
#include "sph_solver/walls/primitive_meshes.hpp"
#include "sph_solver/walls/tank_meshes.hpp"

using namespace tankfsi::sph;
using Catch::Matchers::Contains;
using Eigen::Vector3d;

namespace {

constexpr double g = 9.81;

FillSpec water_2d(double spacing, double level) {
  FillSpec spec;
  spec.spacing = spacing;
  spec.density = 1000.0;
  spec.fill_level = level;
  spec.dimension = 2;
  return spec;
}

// Signed distance to the nearest triangle by brute force (lowest index among equals,
// like the index), independent of the TriangleIndex used by fill_tank.
double brute_signed_distance(const TriangleMesh& mesh, const Vector3d& p) {
  int best = -1;
  ClosestPoint best_point;
  for (int t = 0; t < static_cast<int>(mesh.triangle_count()); ++t) {
    const ClosestPoint cp = closest_point_on_triangle(p, mesh, t);
    if (best < 0 || cp.squared_distance < best_point.squared_distance) {
      best = t;
      best_point = cp;
    }
  }
  return signed_distance(p, mesh, best, best_point);
}

// Every particle inside and at least L₀/2 (less the fill's 1e-6 L₀ tolerance) from
// every wall triangle.
void check_clearance(const TriangleMesh& mesh, const Particles& particles, double spacing) {
  double closest = std::numeric_limits<double>::infinity();
  for (const auto& x : particles.position) closest = std::min(closest, brute_signed_distance(mesh, x));
  CHECK(closest >= (0.5 - 1e-6) * spacing);
  CHECK(closest == Approx(0.5 * spacing));  // the first layer touches the clearance
}

/// Water filled in rings (FillSpec::cylinder_radius) in a cylinder of `radius`.
FillSpec water_in_rings(double radius, double level, double spacing) {
  FillSpec spec;
  spec.spacing = spacing;
  spec.density = 1000.0;
  spec.fill_level = level;
  spec.cylinder_radius = radius;  // the smooth wall the facets approximate
  return spec;
}

/// Particles of one layer of rings (filling.hpp): ring m at R - (m + 1/2) L0
/// holds max(1, round(2 pi r_m / L0)).
std::size_t ring_layer_size(double radius, double spacing) {
  std::size_t count = 0;
  for (int m = 0; radius - (m + 0.5) * spacing > 0.0; ++m)
    count += static_cast<std::size_t>(
        std::max(1L, std::lround(2.0 * std::numbers::pi * (radius - (m + 0.5) * spacing) / spacing)));
  return count;
}

}  // namespace

TEST_CASE("filling: the paper's 2D tank gets 200 × 69 = 13,800 particles in lattice order", "[geometry]") {
  const TriangleMesh tank = make_rectangular_tank_2d(2.0, 0.74, 0.02, 0.01);
  FillSpec spec = water_2d(0.01, 0.69);
  spec.hydrostatic_pressure = true;
  spec.gravity = g;
  const Particles p = fill_tank(tank, spec);
  REQUIRE(p.size() == 13800);
  for (std::size_t n = 0; n < p.size(); ++n) {
    const auto i = static_cast<double>(n % 200), j = static_cast<double>(n / 200);  // x fastest
    CHECK(p.id[n] == static_cast<std::int64_t>(n));
    CHECK(p.position[n].x() == Approx(0.005 + 0.01 * i).margin(1e-12));
    CHECK(p.position[n].y() == Approx(0.005 + 0.01 * j).margin(1e-12));
    CHECK(p.position[n].z() == 0.0);
    CHECK(p.velocity[n] == Vector3d::Zero());
    CHECK(p.mass[n] == Approx(0.1));  // 1000 kg/m³ × (0.01 m)²
    CHECK(p.pressure[n] == Approx(1000.0 * g * (0.69 - p.position[n].y())));
  }
  CHECK(p.pressure.back() == Approx(1000.0 * g * 0.005));  // top layer: half a layer of water

  SECTION("without hydrostatic pressure every pressure is zero") {
    spec.hydrostatic_pressure = false;
    const Particles q = fill_tank(tank, spec);
    CHECK(std::all_of(q.pressure.begin(), q.pressure.end(), [](double x) { return x == 0.0; }));
  }
  SECTION("the same tank as a closed thin box: front and back faces are ignored in 2D") {
    // 4 mm deep: were the front and back faces used, every particle would be 2 mm < L₀/2
    // from them and none would be kept.
    const TriangleMesh box = make_box(Vector3d(0.0, 0.0, -0.002), Vector3d(2.0, 0.74, 0.002), NormalSide::inward);
    const Particles q = fill_tank(box, spec);
    CHECK(q.size() == 13800);
    CHECK(q.position == p.position);
  }
  SECTION("the level rounds to whole layers by the layer centres") {
    CHECK(fill_tank(tank, water_2d(0.01, 0.694)).size() == 13800);
    const Particles q = fill_tank(tank, water_2d(0.01, 0.696));
    CHECK(q.size() == 200 * 70);
    spec.fill_level = 0.696;
    CHECK(fill_tank(tank, spec).pressure.back() == Approx(1000.0 * g * 0.005));  // surface at 0.70
  }
  SECTION("a shifted lattice origin loses the column that comes too close to the right wall") {
    spec.lattice_origin = Vector3d(0.0025, 0.0, 0.0);
    const Particles q = fill_tank(tank, spec);
    CHECK(q.size() == 199 * 69);
    CHECK(q.position.front().x() == Approx(0.0075));
  }
}

TEST_CASE("filling: the overflow set-up, inner tank only or with the catch tank", "[geometry]") {
  OverflowTank2d coarse;
  coarse.target_edge = 0.05;  // fewer triangles for the brute-force check
  const TriangleMesh tank = make_overflow_tank_2d(coarse);
  FillSpec spec = water_2d(0.01, 0.69);
  spec.region = Eigen::AlignedBox3d(Vector3d(0.0, 0.0, -1.0), Vector3d(2.0, 0.74, 1.0));
  // Default origin (-0.52, 0): the inner tank's walls are whole numbers of L₀ from it.
  const Particles inner = fill_tank(tank, spec);
  CHECK(inner.size() == 13800);
  check_clearance(tank, inner, spec.spacing);

  // Without the region the catch tank fills too: 50 columns on either side.
  spec.region.reset();
  const Particles all = fill_tank(tank, spec);
  CHECK(all.size() == 13800 + 2 * 50 * 69);
  check_clearance(tank, all, spec.spacing);
  const auto in_plate = [](const Vector3d& x) {
    return (x.x() > -0.02 && x.x() < 0.0) || (x.x() > 2.0 && x.x() < 2.02);
  };
  CHECK(std::none_of(all.position.begin(), all.position.end(), in_plate));
}

TEST_CASE("filling: a dam-break column of 1 × 2 m at 0.02 m is 50 × 100 particles", "[geometry]") {
  const TriangleMesh tank = make_rectangular_tank_2d(4.0, 3.0, 0.02, 0.05);
  FillSpec spec = water_2d(0.02, 10.0);  // the region, not the level, bounds the column
  spec.region = Eigen::AlignedBox3d(Vector3d(0.0, 0.0, 0.0), Vector3d(1.0, 2.0, 0.0));  // z ignored in 2D
  spec.hydrostatic_pressure = true;
  spec.gravity = g;
  const Particles p = fill_tank(tank, spec);
  REQUIRE(p.size() == 5000);
  for (const auto& x : p.position) {
    CHECK(x.x() > 0.0);
    CHECK(x.x() < 1.0);
    CHECK(x.y() < 2.0);
  }
  CHECK(p.mass.front() == Approx(0.4));                    // 1000 × 0.02²
  CHECK(p.pressure.front() == Approx(1000.0 * g * 1.99));  // surface at the column's top, 2.00 m
  check_clearance(tank, p, spec.spacing);
}

TEST_CASE("filling: a 3D cylinder, predicted layer by layer from the smooth cylinder", "[geometry]") {
  const double radius = 1.0, level = 0.8, spacing = 0.05;
  const int segments = 96;
  const TriangleMesh tank = make_cylindrical_tank(radius, 1.2, segments, 12, 8, DomeRoof{1.5, 6});
  FillSpec spec;
  spec.spacing = spacing;
  spec.density = 860.0;
  spec.fill_level = level;
  spec.hydrostatic_pressure = true;
  spec.gravity = g;
  const Particles p = fill_tank(tank, spec);

  // The wall is the circle the regular 96-gon approximates (the smooth wall behind
  // the facets); a lattice column (x, y) is kept when it is at least L₀/2 inside it.
  // The bottom corner costs nothing (first layer at L₀/2 from the floor), so all
  // level / L₀ = 16 layers hold the same columns.
  int columns = 0;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const double x = -radius + (i + 0.5) * spacing, y = -radius + (j + 0.5) * spacing;
      if (std::hypot(x, y) <= radius - 0.5 * spacing) ++columns;
    }
  CHECK(p.size() == static_cast<std::size_t>(16 * columns));

  // Against the continuum π R² h / L₀³ = 20,106: the particles fill the cylinder of
  // radius R − L₀/2 (the clearance), a fraction (1 − L₀/2R)² = 0.951 of it: the boundary
  // layer's share is L₀/R = 5 %. Round this: the number of lattice points in a disc of radius r L₀ deviates
  // from π r² by O(r^(2/3)) (the Gauss circle problem), ~7 of the ~1,190 columns here
  // (0.6 %). So the count is (1 − L₀/2R)² π R² h / L₀³ within 2 %, well below the
  // continuum.
  const double continuum = std::numbers::pi * radius * radius * level / std::pow(spacing, 3);
  const double fraction = static_cast<double>(p.size()) / continuum;
  CHECK(fraction == Approx(std::pow(1.0 - 0.5 * spacing / radius, 2)).margin(0.02));
  CHECK(fraction < 0.97);

  CHECK(p.mass.front() == Approx(860.0 * std::pow(spacing, 3)));
  CHECK(p.position.front().z() == Approx(0.5 * spacing));
  CHECK(p.pressure.front() == Approx(860.0 * g * (level - 0.5 * spacing)));
  for (std::size_t n = 1; n < p.size(); ++n) CHECK(p.position[n].z() >= p.position[n - 1].z());  // z slowest
}

TEST_CASE("filling: rings in a cylinder hold the liquid's mass exactly and leave no gap at the wall", "[geometry]") {
  const double radius = 0.5, level = 0.5, spacing = 0.05;
  const int segments = 32;
  const TriangleMesh tank = make_cylindrical_tank(radius, 0.7, segments, 7, 5, std::nullopt);
  FillSpec spec = water_in_rings(radius, level, spacing);
  const Particles p = fill_tank(tank, spec);
  // The annuli partition the disc: the masses sum to rho pi R^2 H.
  double mass = 0.0;
  for (const double m : p.mass) mass += m;
  CHECK(mass == Approx(1000.0 * std::numbers::pi * radius * radius * level).epsilon(1e-12));
  // Every annulus kept whole: no particle lost to the facets, which come closer
  // than the smooth cylinder by up to the sagitta, R (1 - cos(pi/32)) = 0.048 L0.
  CHECK(p.size() == ring_layer_size(radius, spacing) * 10);  // ten layers below the level
  // L0/2 clear of the smooth cylinder and the bottom, the outer ring and the
  // first layer touching it; inside every facet.
  double closest_side = std::numeric_limits<double>::infinity(), closest_bottom = closest_side;
  for (const auto& x : p.position) {
    closest_side = std::min(closest_side, radius - std::hypot(x.x(), x.y()));
    closest_bottom = std::min(closest_bottom, x.z());
  }
  CHECK(closest_side == Approx(0.5 * spacing).epsilon(1e-12));
  CHECK(closest_bottom == Approx(0.5 * spacing).epsilon(1e-12));
  double closest_facet = std::numeric_limits<double>::infinity();
  for (const auto& x : p.position) closest_facet = std::min(closest_facet, brute_signed_distance(tank, x));
  CHECK(closest_facet >= 0.5 * spacing - (1.0 - std::cos(std::numbers::pi / segments)) * radius - 1e-12);
  CHECK(closest_facet < 0.5 * spacing);
  // No gap: every wall vertex below the level has a particle within 0.9 L0, as
  // at a flat wall (the corner of a lattice cell is sqrt(3)/2 L0 from its
  // centre); the cubic lattice leaves more than L0 at this curved wall.
  const auto largest_gap = [&](const Particles& particles) {
    double largest = 0.0;
    for (const auto& v : tank.vertices()) {
      if (!(v.z() > 0.0 && v.z() < level) || std::hypot(v.x(), v.y()) < 0.99 * radius) continue;
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& x : particles.position) nearest = std::min(nearest, (x - v).norm());
      largest = std::max(largest, nearest);
    }
    return largest;
  };
  CHECK(largest_gap(p) < 0.9 * spacing);
  FillSpec cubic = spec;
  cubic.cylinder_radius.reset();
  CHECK(largest_gap(fill_tank(tank, cubic)) > spacing);
  // Each particle's volume is near L0^3 (its share of its annulus).
  for (const double m : p.mass) {
    CHECK(m > 0.75 * 1000.0 * std::pow(spacing, 3));
    CHECK(m < 1.25 * 1000.0 * std::pow(spacing, 3));
  }
  spec.dimension = 2;
  CHECK_THROWS_AS(fill_tank(tank, spec), std::invalid_argument);
}

// Twelve facets round a cylinder of R = 10 L0 lie up to R (1 - cos(pi/12)) =
// 0.34 L0 inside it; the smooth wall's depth behind a facet's middle is short of
// the circle's by sagitta^2 / (2R) = 0.0058 L0 there, three times the clearance's
// round-off tolerance: without the allowance for it the outer ring lost its
// particles by the facets' middles (240 of its 600).
TEST_CASE("filling: rings in a coarsely faceted cylinder are kept whole", "[geometry]") {
  const double radius = 0.5, level = 0.5, spacing = 0.05;
  const int segments = 12;
  const TriangleMesh tank = make_cylindrical_tank(radius, 0.7, segments, 7, 5, std::nullopt);
  const Particles p = fill_tank(tank, water_in_rings(radius, level, spacing));
  CHECK(p.size() == ring_layer_size(radius, spacing) * 10);
  double closest_facet = std::numeric_limits<double>::infinity();
  for (const auto& x : p.position) closest_facet = std::min(closest_facet, brute_signed_distance(tank, x));
  const double sagitta = (1.0 - std::cos(std::numbers::pi / segments)) * radius;
  CHECK(closest_facet >= 0.5 * spacing - sagitta - 1e-12);

  // At R = 20 L0 the twelve facets lie 0.68 L0 inside the smooth cylinder: the
  // outer ring, L0/2 inside it, lies behind their middles, and only the
  // particles in front of a facet are filled (none of them behind one, from
  // where the first step would count it as having crossed the wall).
  const double wide = 1.0;
  const TriangleMesh coarse = make_cylindrical_tank(wide, 0.7, segments, 7, 5, std::nullopt);
  const Particles q = fill_tank(coarse, water_in_rings(wide, level, spacing));
  const auto outer_ring_size = static_cast<std::size_t>(std::lround(2.0 * std::numbers::pi * (wide - 0.5 * spacing) / spacing));
  std::size_t outer = 0;
  closest_facet = std::numeric_limits<double>::infinity();
  for (const auto& x : q.position) {
    closest_facet = std::min(closest_facet, brute_signed_distance(coarse, x));
    if (std::hypot(x.x(), x.y()) > wide - spacing) ++outer;
  }
  CHECK(closest_facet >= 2e-3 * spacing);
  CHECK(outer > 0);
  CHECK(outer < outer_ring_size * 10);  // the outer ring's particles by the facets' middles are not filled
}

TEST_CASE("filling: a closed dome tank filled to the top keeps clear of roof, wall and bottom",
          "[geometry]") {
  const TriangleMesh tank = make_cylindrical_tank(1.0, 1.0, 32, 4, 3, DomeRoof{1.2, 4});
  FillSpec spec;
  spec.spacing = 0.1;
  spec.density = 1000.0;
  spec.fill_level = std::numeric_limits<double>::infinity();
  const Particles p = fill_tank(tank, spec);
  // The boundary layer L₀/2 thick over the walls' area (wall 2π, bottom π, cap
  // 2π R_d rise = 4.05 m²) is 0.67 m³ of the 4.07 m³: expect 84 % of V / L₀³, give or take
  // the lattice's fluctuations at this coarse spacing (±5 %).
  const double rise = 1.2 - std::sqrt(1.2 * 1.2 - 1.0);
  const double volume = std::numbers::pi + std::numbers::pi * rise * rise * (3.6 - rise) / 3.0;
  const double area = 3.0 * std::numbers::pi + 2.0 * std::numbers::pi * 1.2 * rise;
  CHECK(static_cast<double>(p.size()) * 1e-3 == Approx(volume - 0.05 * area).epsilon(0.05));
  // Clear of the smooth walls the facets approximate (the dome's facets come up to
  // 0.09 L0 closer than its sphere): the cylinder R = 1, the bottom z = 0 and the
  // sphere of radius 1.2 about (0, 0, 1 - sqrt(1.2^2 - 1)), measured analytically.
  const double centre = 1.0 - std::sqrt(1.2 * 1.2 - 1.0);
  double closest = std::numeric_limits<double>::infinity();
  for (const auto& x : p.position) {
    double d = std::min(1.0 - std::hypot(x.x(), x.y()), x.z());
    if (x.z() > 1.0) d = std::min(d, 1.2 - (x - Vector3d(0.0, 0.0, centre)).norm());
    closest = std::min(closest, d);
  }
  INFO("closest " << closest / spec.spacing << " L0");
  CHECK(closest >= (0.5 - 1e-9) * spec.spacing);
  const double top = tank.bounding_box().max().z();
  CHECK(std::any_of(p.position.begin(), p.position.end(), [&](const Vector3d& x) { return x.z() > 1.0; }));
  CHECK(std::all_of(p.position.begin(), p.position.end(), [&](const Vector3d& x) { return x.z() < top; }));
}

TEST_CASE("filling rejects bad specs and empty fills", "[geometry]") {
  const TriangleMesh tank = make_rectangular_tank_2d(1.0, 1.0, 0.02, 0.1);
  CHECK_THROWS_AS(fill_tank(tank, water_2d(0.0, 0.5)), std::invalid_argument);
  FillSpec wrong = water_2d(0.01, 0.5);
  wrong.dimension = 4;
  CHECK_THROWS_AS(fill_tank(tank, wrong), std::invalid_argument);
  wrong = water_2d(0.01, std::numeric_limits<double>::quiet_NaN());
  CHECK_THROWS_AS(fill_tank(tank, wrong), std::invalid_argument);
  CHECK_THROWS_WITH(fill_tank(tank, water_2d(0.01, -0.5)), Contains("no lattice point"));
  CHECK_THROWS_WITH(fill_tank(tank, water_2d(0.01, 0.004)), Contains("no lattice point"));  // below the first layer

  const TriangleMesh off_plane = make_box(Vector3d(0.0, 0.0, 0.1), Vector3d(1.0, 1.0, 0.2), NormalSide::inward);
  CHECK_THROWS_WITH(fill_tank(off_plane, water_2d(0.01, 0.5)), Contains("straddle the plane z = 0"));
  const TriangleMesh lid = make_rectangle(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(), 2);
  CHECK_THROWS_WITH(fill_tank(lid, water_2d(0.01, 0.5)), Contains("no face with an in-plane normal"));
}
