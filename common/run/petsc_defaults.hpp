#pragma once
// Default PETSc options from a case file or from code ("-shell_ksp_type cg
// -shell_pc_type gamg"): each is set only if the command line did not give
// it, so the command line always overrides (DESIGN.md conventions).
#include <string>

namespace tankfsi {

/// Throws std::invalid_argument if a token that should be an option name does
/// not start with '-'.
void apply_default_petsc_options(const std::string& options);

}  // namespace tankfsi
