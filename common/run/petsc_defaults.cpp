#include "common/run/petsc_defaults.hpp"

#include <petscsys.h>

#include <cctype>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tankfsi {
namespace {

bool is_option_name(const std::string& token) {
  return token.size() > 1 && token[0] == '-' && !(std::isdigit(static_cast<unsigned char>(token[1])) || token[1] == '.');
}

}  // namespace

void apply_default_petsc_options(const std::string& options) {
  std::istringstream in(options);
  std::vector<std::string> tokens;
  for (std::string token; in >> token;) tokens.push_back(token);
  for (std::size_t k = 0; k < tokens.size(); ++k) {
    const std::string& name = tokens[k];
    if (!is_option_name(name))
      throw std::invalid_argument("'" + name + "' is not a PETSc option name (options start with '-')");
    std::string value;
    if (k + 1 < tokens.size() && !is_option_name(tokens[k + 1])) value = tokens[++k];
    PetscBool given = PETSC_FALSE;
    if (PetscOptionsHasName(nullptr, nullptr, name.c_str(), &given) != 0)
      throw std::runtime_error("PETSc could not look up option " + name);
    if (!given && PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()) != 0)
      throw std::runtime_error("PETSc could not set option " + name);
  }
}

}  // namespace tankfsi
