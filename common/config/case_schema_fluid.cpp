#include "common/config/case_schema.hpp"

namespace tankfsi {

// Fluid: incompressible SPH (METHOD.md section 1). In 2D the particles lie in the
// plane z = 0 with gravity along -y; in 3D gravity acts along -z.
std::vector<KeySpec> fluid_keys() {
  return {
      integer_key("fluid.dimension", "Spatial dimension of the particle model: 2 or 3.").is_required().at_least(2).at_most(3),
      choice_key("fluid.kernel", {"auto", "quintic_spline", "quartic_spline", "wendland_c2"},
                 "Smoothing kernel; auto takes the quintic spline in 2D and the quartic spline in 3D.")
          .default_is("auto"),
      real_key("fluid.spacing", "Initial particle spacing (L0); also the spacing of the wall kernel tables.")
          .unit_is("m").is_required().above(0),
      real_key("fluid.smoothing_length_ratio",
               "Smoothing length h as a multiple of the particle spacing; when not given, the kernel's: "
               "1.2 for the quintic spline, 1.1 for the quartic spline (at 1.2 it is in its pairing "
               "instability), 1.5 for Wendland C2 (the least at which it sums to 1 on the lattice).")
          .above(0.5).at_most(3),
      real_key("fluid.density", "Reference density of the liquid.").unit_is("kg/m^3").is_required().above(0),
      real_key("fluid.viscosity", "Dynamic viscosity of the liquid.").unit_is("Pa s").is_required().at_least(0),
      real_key("fluid.gravity", "Magnitude of gravity (acts along -y in 2D, -z in 3D).")
          .unit_is("m/s^2").default_is("9.81").at_least(0),
      choice_key("fluid.time_step.mode", {"fixed", "adaptive"},
                 "Fixed time step, or adaptive from the CFL, viscous and body-force limits.")
          .default_is("adaptive"),
      real_key("fluid.time_step.value", "The fixed fluid time step.")
          .unit_is("s").is_required().above(0).only_when("fluid.time_step.mode", {"fixed"}),
      real_key("fluid.time_step.cfl", "Courant number C of the limit C h / |v|max.")
          .default_is("0.2").above(0).at_most(1).only_when("fluid.time_step.mode", {"adaptive"}),
      real_key("fluid.time_step.max", "Largest time step the adaptive controller may take.")
          .unit_is("s").default_is("0.001").above(0).only_when("fluid.time_step.mode", {"adaptive"}),
      real_key("fluid.time_step.breach_courant",
               "A step after which |v|max dt / h exceeds this Courant number stops the run as diverging "
               "(CFL breach: a particle crossed more of its kernel support than the neighbour search and "
               "the halo allow for); the last good state is kept.")
          .default_is("1").above(0),
      real_key("fluid.ppe.density_error_weight",
               "Weight gamma of the density-error part of the pressure Poisson source term, "
               "gamma (rho0 - rho*) / dt^2. Its pressure answer to a density error e is about "
               "gamma rho0 e L0^2 / dt^2 and each step moves particles by about gamma e L0: with steps "
               "far below the fluid's own (a short coupling window), lower it, or the filling's "
               "kernel-sum errors at curved walls start the liquid moving (case READMEs of "
               "tank3d_fixed_roof_coarse and flexible_cylinder_3d).")
          .default_is("0.01").at_least(0).at_most(1),
      real_key("fluid.ppe.free_surface_threshold",
               "Particles with density below this fraction of the reference density (or a kernel support "
               "that is not full) are counted as free-surface particles and are not shifted; the pressure "
               "condition P = 0 itself is imposed on the surface plane beyond them.")
          .default_is("0.97").above(0).below(1),
      real_key("fluid.ppe.preconditioner_radius",
               "BoomerAMG (the default preconditioner) is built on a sparser twin of the pressure operator: "
               "the particle pairs within this many particle spacings (at least 1; 1.8: the lattice's first "
               "two shells), their weights scaled so that the twin's Laplacian of a quadratic field is the "
               "operator's. 0: on the operator itself. The solution is the operator's either way (to the "
               "operator's own residual); the twin's hierarchy costs less (alternating pairs: the 2D dam "
               "break's solve 1-20 % less in three pairs, the 3D cylinder's at 115,000 particles 30-45 % less), "
               "and a step where it fails is solved again with the operator's (README.md).")
          .default_is("1.8").at_least(0).at_most(10),
      boolean_key("fluid.ppe.keep_hierarchy",
                  "Keep BoomerAMG's hierarchy from step to step, applied through the particles' ids, and build "
                  "a new one only when a solve takes 1.5 times the iterations of the first on it, or fails: its "
                  "set-up is then paid every few dozen steps instead of every step (the 2D dam break's solves "
                  "16 % shorter, a 3D cylinder's a third; README.md). Checkpoints hold the rows it was built on, "
                  "so a restart on as many ranks goes on bit for bit. false: a new hierarchy every step.")
          .default_is("true"),
      text_key("fluid.ppe.solver_options",
               "PETSc options for the pressure solver (prefix -ppe_; without them CG with hypre BoomerAMG, "
               "-ppe_ksp_rtol 1e-6), applied before the command line's.")
          .default_is("''"),
      boolean_key("fluid.shifting.enabled", "Fickian particle shifting (Lind et al. 2012).").default_is("true"),
      real_key("fluid.shifting.coefficient",
               "Shifting coefficient A of D = A h |v| dt; D is held to at most 0.6 h^2, the shift's "
               "stable range measured on the dam break (from a Courant number of 0.3 on with A = 2).")
          .default_is("2").at_least(0).only_when("fluid.shifting.enabled", {"true"}),
      real_key("fluid.shifting.close_pair_distance",
               "Pairs of particles closer than this many particle spacings after the shift are parted, each "
               "moved away from the other by half the shortfall (0: never). Where the shift is skipped (at and "
               "next to the free surface) this is what keeps a thin jet's particles from collapsing onto each "
               "other (cases/dam_break_2d/README.md).")
          .default_is("0.5").at_least(0).at_most(1).only_when("fluid.shifting.enabled", {"true"}),
      integer_key("fluid.rebalance_interval",
                  "Steps between re-partitions of the particles over the ranks (and re-sorts in cell order).")
          .default_is("20").at_least(1),
      real_key("fluid.section_depth",
               "2D: depth (along z) of the section whose walls are extruded from the 2D geometry; 0 takes the "
               "least, four kernel supports. Forces on a coupled 2D structure are those on this depth.")
          .unit_is("m").default_is("0").at_least(0),
      choice_key("fluid.geometry.type", {"rectangular_tank", "overflow_tank", "cylindrical_tank", "stl", "gmsh"},
                 "Wall geometry (required by sph_solver): a generated tank, or a surface mesh file whose "
                 "triangle normals point into the liquid."),
      real_key("fluid.geometry.width", "Inner width of a rectangular (2D) tank, along x.")
          .unit_is("m").is_required().above(0).only_when("fluid.geometry.type", {"rectangular_tank", "overflow_tank"}),
      real_key("fluid.geometry.wall_height", "Height of the tank's side walls above the floor.")
          .unit_is("m").is_required().above(0)
          .only_when("fluid.geometry.type", {"rectangular_tank", "overflow_tank", "cylindrical_tank"}),
      real_key("fluid.geometry.catch_margin",
               "Overflow tank: gap between the inner tank's walls and the outer catch tank's walls.")
          .unit_is("m").default_is("0.5").above(0).only_when("fluid.geometry.type", {"overflow_tank"}),
      real_key("fluid.geometry.radius", "Inner radius of an upright cylindrical tank.")
          .unit_is("m").is_required().above(0).only_when("fluid.geometry.type", {"cylindrical_tank"}),
      real_key("fluid.geometry.dome_radius",
               "Radius of the spherical dome roof of a cylindrical tank; 0 for an open top.")
          .unit_is("m").default_is("0").at_least(0).only_when("fluid.geometry.type", {"cylindrical_tank"}),
      real_key("fluid.geometry.element_size",
               "Target edge length of the generated wall triangles; 0 for 2 L0. The run logs how far the facets of "
               "a curved wall lie from the smooth wall they stand for and warns beyond 0.05 L0 (2D), 0.45 L0 (3D).")
          .unit_is("m").default_is("0").at_least(0)
          .only_when("fluid.geometry.type", {"rectangular_tank", "overflow_tank", "cylindrical_tank"}),
      input_path_key("fluid.geometry.file",
                     "STL (ASCII or binary) or Gmsh .msh v4.1 ASCII surface mesh. Mesh curved walls finely: the run "
                     "warns of facets more than 0.05 L0 (2D), 0.45 L0 (3D) from the smooth wall they stand for.")
          .is_required().only_when("fluid.geometry.type", {"stl", "gmsh"}),
      real_key("fluid.fill.level",
               "Height of the still liquid surface (y in 2D, z in 3D) up to which the tank is filled.")
          .unit_is("m").above(0),
      real_vector_key("fluid.fill.region",
                      "Box [x0, y0, z0, x1, y1, z1] the initial liquid is confined to (a dam-break column); "
                      "omitted for the whole tank.")
          .unit_is("m").with_length(6),
      boolean_key("fluid.fill.hydrostatic", "Start from the hydrostatic pressure rho g (level - height).")
          .default_is("true"),
      choice_key("fluid.initial_velocity.type", {"rest", "standing_wave"},
                 "Initial velocity of the liquid: at rest, or the linear standing sloshing wave of a "
                 "rectangular tank (rectangular_tank, filled whole) that starts from the still surface at its "
                 "largest velocity: eta = a cos(n pi x / L) sin(omega t), omega^2 = g (n pi / L) tanh(n pi H / L).")
          .default_is("rest"),
      real_key("fluid.initial_velocity.amplitude",
               "Amplitude a of the standing wave's surface elevation at the side walls; linear theory, so at "
               "most 10 % of the depth.")
          .unit_is("m").is_required().above(0).only_when("fluid.initial_velocity.type", {"standing_wave"}),
      integer_key("fluid.initial_velocity.mode", "Mode number n of the standing wave (1: the first sloshing mode).")
          .default_is("1").at_least(1).only_when("fluid.initial_velocity.type", {"standing_wave"}),
      real_vector_key("fluid.domain",
                      "Box [x0, y0, z0, x1, y1, z1] outside which particles are removed (overflow); "
                      "omitted for the walls' bounding box grown by one kernel support.")
          .unit_is("m").with_length(6),
      record_list_key("fluid.probes", "Points and boxes sampled every output.probe_interval into probes/<name>.csv.")
          .default_is("[]")
          .with_fields({
              text_key("name", "Probe name; its file is probes/<name>.csv.").is_required(),
              choice_key("quantity", {"pressure", "wave_height", "velocity", "front", "volume"},
                         "pressure (Pa) at the point, wave height (m) of the free surface above the point, "
                         "velocity (m/s) at the point, the surge front: the largest x - x_point of the "
                         "particles within 2 L0 above the point, or the liquid volume inside a box and "
                         "outside it (the overflowed liquid; removed particles not counted; per metre of "
                         "depth in 2D).")
                  .is_required(),
              real_vector_key("position", "The sampled point.").unit_is("m").with_length(3).is_required()
                  .only_when("quantity", {"pressure", "wave_height", "velocity", "front"}),
              real_vector_key("region", "Box [x0, y0, z0, x1, y1, z1] of a volume probe.")
                  .unit_is("m").with_length(6).is_required().only_when("quantity", {"volume"}),
          }),
  };
}

}  // namespace tankfsi
