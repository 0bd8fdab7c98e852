#include "common/config/case_schema.hpp"

namespace tankfsi {

namespace {

std::vector<KeySpec> structure_mesh_keys() {
  const std::vector<std::string> round{"cylinder", "sphere", "tank"};
  return {
      choice_key("structure.mesh.type", {"cylinder", "sphere", "plate", "tank", "gmsh"},
                 "Shell mesh: a generated cylinder or sphere patch (region 'shell'; node sets phi_start, "
                 "phi_end, z_start, z_end or theta_start, theta_end, phi_start, phi_end), a generated flat "
                 "plate (region 'plate'; node sets u_start, u_end, v_start, v_end), the generated "
                 "tank (regions wall, roof, bottom; element set wetted; node sets base, wall_top), or a Gmsh "
                 "file (regions and element sets from its surface groups, node sets from its curve and point "
                 "groups). Required by fem_solver."),
      input_path_key("structure.mesh.file",
                     "Gmsh .msh 4.1 ASCII shell mesh: 3-node triangles and 4-node quadrangles, oriented alike.")
          .is_required().only_when("structure.mesh.type", {"gmsh"}),
      text_key("structure.mesh.regions",
               "Gmsh: the surface physical groups that are element regions (each element in exactly one), "
               "separated by commas; the other surface groups become element sets. Empty: every surface group.")
          .default_is("''").only_when("structure.mesh.type", {"gmsh"}),
      real_key("structure.mesh.radius", "Radius of the cylinder, sphere or tank wall (mid-surface).")
          .unit_is("m").is_required().above(0).only_when("structure.mesh.type", round),
      real_key("structure.mesh.length", "Cylinder: length along z, from z = 0.")
          .unit_is("m").is_required().above(0).only_when("structure.mesh.type", {"cylinder"}),
      real_vector_key("structure.mesh.phi_range",
                      "Cylinder or sphere: azimuth range [start, end] from the x axis (360 wide: a full circle).")
          .unit_is("degree").with_length(2).default_is("[0, 90]").only_when("structure.mesh.type", {"cylinder", "sphere"}),
      real_vector_key("structure.mesh.theta_range", "Sphere: polar range [start, end] from the +z axis, start > 0.")
          .unit_is("degree").with_length(2).default_is("[18, 90]").only_when("structure.mesh.type", {"sphere"}),
      real_vector_key("structure.mesh.divisions",
                      "Cylinder: elements [around, along z]; sphere: elements [along theta, along phi]; plate: "
                      "elements [along u, along v].")
          .with_length(2).is_required().at_least(1).only_when("structure.mesh.type", {"cylinder", "sphere", "plate"}),
      real_vector_key("structure.mesh.corner", "Plate: the corner at u = v = 0.")
          .unit_is("m").with_length(3).is_required().only_when("structure.mesh.type", {"plate"}),
      real_vector_key("structure.mesh.side_u", "Plate: the side from the corner along u; normal side_u x side_v.")
          .unit_is("m").with_length(3).is_required().only_when("structure.mesh.type", {"plate"}),
      real_vector_key("structure.mesh.side_v", "Plate: the side from the corner along v.")
          .unit_is("m").with_length(3).is_required().only_when("structure.mesh.type", {"plate"}),
      boolean_key("structure.mesh.wetted", "Plate: the whole plate is the element set 'wetted' (a coupled interface).")
          .default_is("false").only_when("structure.mesh.type", {"plate"}),
      real_key("structure.mesh.wall_height", "Tank: height of the cylindrical wall above the bottom plate.")
          .unit_is("m").is_required().above(0).only_when("structure.mesh.type", {"tank"}),
      real_key("structure.mesh.dome_radius",
               "Tank: radius of the spherical dome roof (at least the tank radius); 0: an open top, no roof.")
          .unit_is("m").is_required().at_least(0).only_when("structure.mesh.type", {"tank"}),
      real_key("structure.mesh.element_size",
               "Tank: target element edge length. In a coupled run the wetted surface is the fluid's wall: the "
               "fluid program warns when its facets lie far from the smooth wall (fluid.geometry.element_size).")
          .unit_is("m").is_required().above(0).only_when("structure.mesh.type", {"tank"}),
      real_key("structure.mesh.liquid_level",
               "Tank: height of the still liquid; wall elements below it and the bottom form the set 'wetted'.")
          .unit_is("m").default_is("0").at_least(0).only_when("structure.mesh.type", {"tank"}),
  };
}

std::vector<KeySpec> structure_support_and_load_keys() {
  return {
      record_list_key("structure.boundary_conditions", "Supports, applied in order (a later one wins on a DOF).")
          .default_is("[]")
          .with_fields({
              text_key("nodes", "Node set, or element region / set whose nodes are supported (or give position)."),
              real_vector_key("position", "A single supported node: the one nearest this point (or give nodes).")
                  .unit_is("m").with_length(3),
              choice_key("type", {"fixed", "pinned", "symmetry", "prescribed"},
                         "fixed: all 6 DOFs zero; pinned: translations zero; symmetry: the translation "
                         "along plane_normal and the rotations about the two in-plane axes zero; "
                         "prescribed: the listed components take the given values.")
                  .is_required(),
              choice_key("plane_normal", {"x", "y", "z"}, "Symmetry: normal axis of the symmetry plane.")
                  .is_required().only_when("type", {"symmetry"}),
              text_key("components", "Prescribed: components among ux uy uz rx ry rz, separated by spaces.")
                  .is_required().only_when("type", {"prescribed"}),
              real_vector_key("values", "Prescribed: value of each component (m or rad); omitted for zeros.")
                  .only_when("type", {"prescribed"}),
          }),
      record_list_key("structure.loads",
                      "Constant loads: the static load case, or loads held from t = 0 in a dynamic run.")
          .default_is("[]")
          .with_fields({
              choice_key("type", {"pressure", "traction", "hydrostatic", "gravity", "point"},
                         "pressure pushes along the mesh normal (outward on generated meshes); traction "
                         "is a force per area in global axes; hydrostatic is rho g (level - z) below the "
                         "level; gravity is the self-weight rho t a; point acts on the nearest node.")
                  .is_required(),
              text_key("elements", "Element region or set loaded.")
                  .is_required().only_when("type", {"pressure", "traction", "hydrostatic"}),
              real_key("pressure", "Pressure value.").unit_is("Pa").is_required().only_when("type", {"pressure"}),
              real_vector_key("traction", "Force per unit area.").unit_is("Pa").with_length(3).is_required()
                  .only_when("type", {"traction"}),
              real_key("density", "Liquid density.").unit_is("kg/m^3").is_required().above(0)
                  .only_when("type", {"hydrostatic"}),
              real_key("level", "Liquid surface height.").unit_is("m").is_required().only_when("type", {"hydrostatic"}),
              real_key("gravity", "Magnitude of gravity (along -z).").unit_is("m/s^2").default_is("9.81").above(0)
                  .only_when("type", {"hydrostatic"}),
              real_vector_key("acceleration", "Gravity vector.").unit_is("m/s^2").with_length(3)
                  .default_is("[0, 0, -9.81]").only_when("type", {"gravity"}),
              real_vector_key("position", "Point: where the load acts (nearest node).").unit_is("m").with_length(3)
                  .is_required().only_when("type", {"point"}),
              real_vector_key("force", "Point: force.").unit_is("N").with_length(3).default_is("[0, 0, 0]")
                  .only_when("type", {"point"}),
              real_vector_key("moment", "Point: moment.").unit_is("N m").with_length(3).default_is("[0, 0, 0]")
                  .only_when("type", {"point"}),
          }),
  };
}

}  // namespace

// Structure: FEM shells (METHOD.md section 3).
std::vector<KeySpec> structure_keys() {
  std::vector<KeySpec> keys{
      choice_key("structure.analysis", {"static", "modal", "dynamic"}, "Kind of structural analysis.").is_required(),
      real_key("structure.material.young_modulus", "Young's modulus of the shell material.")
          .unit_is("Pa").is_required().above(0),
      real_key("structure.material.poisson_ratio", "Poisson's ratio of the shell material.")
          .is_required().at_least(0).below(0.5),
      real_key("structure.material.density", "Density of the shell material.").unit_is("kg/m^3").is_required().above(0),
      real_key("structure.thickness", "Shell thickness of every region a structure.regions record does not set.")
          .unit_is("m").above(0),
      real_vector_key("structure.reference_axis",
                      "Axis whose projection on the shell is local direction 1 of the stress resultants.")
          .with_length(3).default_is("[0, 0, 1]"),
      record_list_key("structure.regions", "Per-region thickness, material and orientation (mesh regions by name).")
          .default_is("[]")
          .with_fields({
              text_key("name", "Mesh region name (wall, roof, bottom, or a Gmsh physical surface).").is_required(),
              real_key("thickness", "Shell thickness of the region.").unit_is("m").is_required().above(0),
              real_key("young_modulus", "Young's modulus; omitted for structure.material's.").unit_is("Pa").above(0),
              real_key("poisson_ratio", "Poisson's ratio; omitted for structure.material's.").at_least(0).below(0.5),
              real_key("density", "Density; omitted for structure.material's.").unit_is("kg/m^3").above(0),
              real_vector_key("reference_axis", "Local direction 1; omitted for structure.reference_axis.")
                  .with_length(3),
          }),
      real_key("structure.drilling_stiffness",
               "Drilling penalty as a fraction of G t (rotation about the normal against the membrane's "
               "in-plane rotation).")
          .default_is("0.001").above(0).at_most(1),
      text_key("structure.solver_options",
               "PETSc options for the structural solve (prefix -shell_) and the eigensolver (-eps_, -st_), "
               "applied before the command line's.")
          .default_is("''"),
      choice_key("structure.kinematics", {"linear", "corotational"},
                 "Linear: small displacements (K u). Corotational: large rotations with small strains (each "
                 "element's rigid motion taken out by a frame that follows it, Newton iterations in every step or "
                 "load step; fem_solver/analysis/corotational_newmark.hpp) for a gate or plate that swings or "
                 "bends far; static and dynamic analyses, not modal or a coupled added mass.")
          .default_is("linear"),
      integer_key("structure.load_steps",
                  "Corotational static analysis: the load is applied in this many equal increments, each "
                  "solved to equilibrium.")
          .default_is("10").at_least(1).only_when("structure.analysis", {"static"}),
      integer_key("structure.modes", "Number of lowest natural modes a modal analysis computes.")
          .default_is("10").at_least(1).only_when("structure.analysis", {"modal", "dynamic"}),
      real_key("structure.time_step", "Structural time step of the Newmark integration.")
          .unit_is("s").is_required().above(0).only_when("structure.analysis", {"dynamic"}),
      real_key("structure.time_integration.spectral_radius",
               "Generalized-alpha spectral radius rho_inf at infinite frequency (Chung & Hulbert 1993): 1 is "
               "the average-acceleration Newmark rule of the paper (no numerical damping); below 1 the modes a "
               "step cannot resolve lose (1 - rho_inf) of their amplitude per step while the resolved ones keep "
               "second order (0.8: a damping ratio of 0.002 % at 20 steps per period, 0.3 % at 3, 7 % in the "
               "limit).")
          .default_is("1").at_least(0).at_most(1).only_when("structure.analysis", {"dynamic"}),
      choice_key("structure.initial_state", {"rest", "equilibrium"},
                 "Dynamic: start undeformed at rest, or at rest in static equilibrium with the loads at t = 0 "
                 "(K u = F(0): the liquid's hydrostatic load before the shaking). A coupled fluid then sees the "
                 "displacements from that state.")
          .default_is("rest").only_when("structure.analysis", {"dynamic"}),
      real_key("structure.damping.ratio", "Rayleigh damping ratio reached at the first target mode.")
          .default_is("0.03").at_least(0).below(1).only_when("structure.analysis", {"dynamic"}),
      real_key("structure.damping.second_ratio",
               "Rayleigh damping ratio at the second target mode; omitted for damping.ratio.")
          .at_least(0).below(1).only_when("structure.analysis", {"dynamic"}),
      real_vector_key("structure.damping.target_modes",
                      "The two modes (1-based, ascending frequency) whose ratios C = alpha M + beta K meets; "
                      "they must differ in frequency (an axisymmetric shell's modes come in equal pairs).")
          .with_length(2).default_is("[1, 3]").at_least(1).only_when("structure.analysis", {"dynamic"}),
      record_list_key("structure.probes",
                      "Nodes sampled every output.probe_interval into probes/<name>.csv (nearest node).")
          .default_is("[]")
          .with_fields({
              text_key("name", "Probe name; its file is probes/<name>.csv.").is_required(),
              choice_key("quantity", {"displacement", "velocity", "acceleration", "rotation"},
                         "Nodal displacement (m), velocity (m/s), acceleration (m/s^2) relative to the "
                         "base, or rotation (rad).")
                  .is_required(),
              real_vector_key("position", "The sampled point (nearest node).").unit_is("m").with_length(3).is_required(),
              real_vector_key("direction",
                              "The quantity's component along this direction, one column (displacement_m, ...); "
                              "omitted: the x, y and z components.")
                  .with_length(3),
          }),
  };
  for (auto group : {structure_mesh_keys, structure_support_and_load_keys})
    for (auto& key : group()) keys.push_back(std::move(key));
  return keys;
}

}  // namespace tankfsi
