// Sections per mesh region: structure.thickness / material / reference_axis
// for every region, overridden by structure.regions records.
#include <algorithm>

#include "common/config/config_error.hpp"
#include "fem_solver/app/structure_case.hpp"

namespace tankfsi::fem {

std::vector<ShellSection> read_sections(const CaseConfig& config, const ShellMesh& mesh) {
  ShellSection base;
  base.young_modulus = config.real("structure.material.young_modulus");
  base.poisson_ratio = config.real("structure.material.poisson_ratio");
  base.density = config.real("structure.material.density");
  base.reference_axis = config.vector3("structure.reference_axis");
  if (base.reference_axis.norm() == 0.0) throw config.error_at("structure.reference_axis", "must not be zero");
  const bool default_thickness = config.has("structure.thickness");
  if (default_thickness) base.thickness = config.real("structure.thickness");
  std::vector<ShellSection> sections(mesh.region_names.size(), base);
  std::vector<bool> given(mesh.region_names.size(), default_thickness);
  for (const ConfigView& record : config.records("structure.regions")) {
    const std::string name = record.text("name");
    const auto found = std::find(mesh.region_names.begin(), mesh.region_names.end(), name);
    if (found == mesh.region_names.end()) {
      std::string known;
      for (const auto& r : mesh.region_names) known += (known.empty() ? "" : ", ") + r;
      throw record.error_at("name", "the mesh has no region '" + name + "' (regions: " + known + ")");
    }
    const auto index = static_cast<std::size_t>(found - mesh.region_names.begin());
    ShellSection& s = sections[index];
    s.thickness = record.real("thickness");
    if (record.has("young_modulus")) s.young_modulus = record.real("young_modulus");
    if (record.has("poisson_ratio")) s.poisson_ratio = record.real("poisson_ratio");
    if (record.has("density")) s.density = record.real("density");
    if (record.has("reference_axis")) {
      s.reference_axis = record.vector3("reference_axis");
      if (s.reference_axis.norm() == 0.0) throw record.error_at("reference_axis", "must not be zero");
    }
    given[index] = true;
  }
  for (std::size_t r = 0; r < given.size(); ++r)
    if (!given[r])
      throw config.error_at("structure.thickness", "region '" + mesh.region_names[r] +
                                                       "' has no thickness: give structure.thickness or a "
                                                       "structure.regions record for it");
  return sections;
}

}  // namespace tankfsi::fem
