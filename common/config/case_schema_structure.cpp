#include "common/config/case_schema.hpp"

namespace tankfsi {

// Structure: FEM shells (METHOD.md section 3).
std::vector<KeySpec> structure_keys() {
  return {
      choice_key("structure.analysis", {"static", "modal", "dynamic"}, "Kind of structural analysis.").is_required(),
      real_key("structure.material.young_modulus", "Young's modulus of the shell material.")
          .unit_is("Pa").is_required().above(0),
      real_key("structure.material.poisson_ratio", "Poisson's ratio of the shell material.")
          .is_required().at_least(0).below(0.5),
      real_key("structure.material.density", "Density of the shell material.").unit_is("kg/m^3").is_required().above(0),
      integer_key("structure.modes", "Number of lowest natural modes a modal analysis computes.")
          .default_is("10").at_least(1).only_when("structure.analysis", {"modal", "dynamic"}),
      real_key("structure.time_step", "Structural time step of the Newmark integration.")
          .unit_is("s").is_required().above(0).only_when("structure.analysis", {"dynamic"}),
      real_key("structure.damping.ratio", "Rayleigh damping ratio reached at the two target modes.")
          .default_is("0.03").at_least(0).below(1).only_when("structure.analysis", {"dynamic"}),
  };
}

}  // namespace tankfsi
