// Stress resultants of a membrane state against statics (hoop force p R),
// and the consistent loads against their totals.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "fem_solver/analysis/static_analysis.hpp"
#include "fem_solver/mesh/shell_surfaces.hpp"
#include "fem_solver/mesh/tank_mesh.hpp"
#include "patch_meshes.hpp"

using namespace tankfsi::fem;

TEST_CASE("pressurised cylinder: hoop force p R, no axial force or bending", "[fem][resultants]") {
  // A quarter of an open cylinder, symmetric about x = 0, y = 0 and z = 0,
  // free at z = L: the exact state is pure hoop tension N22 = p R (local
  // direction 1 is the reference axis z projected: axial; 2 is the hoop).
  CylinderPatch c;
  c.radius = 1.0;
  c.length = 0.5;
  c.divisions_phi = 12;
  c.divisions_z = 4;
  ShellSection s = testing::steel_plate(0.01);
  s.young_modulus = 2e11;
  const ShellMesh mesh = cylinder_patch(c);
  std::vector<DofConstraint> supports;
  for (const int n : mesh.node_sets.at("z_start"))
    for (const int k : {2, 3, 4}) supports.push_back({n, k, 0.0});
  for (const int n : mesh.node_sets.at("phi_start"))
    for (const int k : {1, 3, 5}) supports.push_back({n, k, 0.0});
  for (const int n : mesh.node_sets.at("phi_end"))
    for (const int k : {0, 4, 5}) supports.push_back({n, k, 0.0});
  const double p = 1e5;
  LoadSet loads;
  loads.surfaces.push_back(SurfaceLoad{"shell", p, Eigen::Vector3d::Zero()});
  StructureSystem system(MPI_COMM_WORLD, ShellModel(mesh, {s}), supports);
  const StaticResult result = solve_static(system, loads);
  const ShellModel& model = system.model();
  // Statics of the faceted section: a node takes p times a chord c = 2 R
  // sin(a) (a = half the element angle) along its radius, less cos(a), so
  // 2 T sin(a) = p c cos(a) gives T = p R cos(a): the hoop force the
  // elements must carry, to 5e-4 (the fanned directors measure the
  // thickness of a curved shell, not of the flat facet). What should be zero
  // is bounded by 1e-3 of p R.
  const double hoop = p * c.radius * std::cos(std::numbers::pi / 4.0 / c.divisions_phi);
  for (std::size_t e = 0; e < model.mesh.elements.size(); ++e) {
    const StressResultants r = element_stress_resultants(model.element_nodes(e), model.section_of(e),
                                                         system.assembler().element_values(e, result.displacement));
    CHECK(r.membrane(1) == Approx(hoop).epsilon(5e-4));
    CHECK(std::abs(r.membrane(0)) <= 1e-3 * p * c.radius);
    CHECK(std::abs(r.membrane(2)) <= 1e-3 * p * c.radius);
    CHECK(r.bending.norm() <= 1e-3 * p * c.radius * s.thickness);
    // Uniaxial hoop stress: von Mises is |sigma_22|. Through the thickness it
    // falls as 1/(R + z) (a curved shell's fibres lengthen outwards): the
    // faces differ from N/t by -+ t/(2R) = 0.5 %, their mean is N/t (to 1e-4).
    CHECK(0.5 * (r.von_mises_top + r.von_mises_bottom) == Approx(r.membrane(1) / s.thickness).epsilon(1e-4));
    CHECK(r.von_mises_top == Approx(r.membrane(1) / s.thickness * (1.0 - 0.5 * s.thickness / c.radius)).epsilon(1e-3));
    CHECK(r.von_mises_bottom == Approx(r.membrane(1) / s.thickness * (1.0 + 0.5 * s.thickness / c.radius)).epsilon(1e-3));
  }
}

TEST_CASE("hydrostatic and gravity loads sum to their totals", "[fem][loads]") {
  TankSpec t;
  t.radius = 5.0;
  t.wall_height = 6.0;
  t.dome_radius = 8.0;
  t.element_size = 1.0;
  t.liquid_level = 4.0;
  const ShellMesh mesh = tank_mesh(t);
  const ShellModel model(mesh, {testing::steel_plate(0.01), testing::steel_plate(0.01), testing::steel_plate(0.01)});
  auto total = [&](const LoadSet& loads) {
    const NodalValues f = nodal_loads(model, loads);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < f.size(); i += 6) sum += Eigen::Vector3d(f[i], f[i + 1], f[i + 2]);
    return sum;
  };
  // Liquid on the bottom plate: rho g H over its area, pushing down. The
  // plate is the polygon of the wall's n = 32 foot nodes: area
  // pi R^2 sin(2 pi/n)/(2 pi/n).
  LoadSet liquid;
  liquid.hydrostatic.push_back(HydrostaticLoad{"bottom", 1000.0, 9.81, 4.0});
  double bottom_area = 0.0;
  for (const int e : mesh.elements_of("bottom")) bottom_area += element_area(model.element_nodes(static_cast<std::size_t>(e)));
  const Eigen::Vector3d on_bottom = total(liquid);
  CHECK(on_bottom.z() == Approx(-1000.0 * 9.81 * 4.0 * bottom_area).epsilon(1e-12));
  const double angle = 2.0 * std::numbers::pi / static_cast<double>(mesh.node_sets.at("wall_top").size());
  CHECK(bottom_area == Approx(std::numbers::pi * 25.0 * std::sin(angle) / angle).epsilon(1e-12));
  // On the closed wall the pressure's resultant vanishes (to round-off of the
  // largest nodal force, times the node count).
  LoadSet on_wall;
  on_wall.hydrostatic.push_back(HydrostaticLoad{"wall", 1000.0, 9.81, 4.0});
  CHECK(total(on_wall).norm() <= 1e-9 * 1000.0 * 9.81 * 4.0 * 2.0 * std::numbers::pi * 5.0 * 4.0);
  // Self-weight: rho t g times the whole area.
  LoadSet weight;
  weight.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  CHECK(total(weight).z() == Approx(-9.81 * model.total_mass()).epsilon(1e-12));
}
