#pragma once
// The keys of a tankfsi case file. Sections: fluid, structure, coupling,
// excitation, output; plus a few top-level keys. Both programs validate the
// whole file against this one schema, so partners always agree on its meaning.
#include "common/config/schema.hpp"

namespace tankfsi {

const Schema& case_schema();

// One function per section, each in its own file.
std::vector<KeySpec> top_level_keys();
std::vector<KeySpec> fluid_keys();
std::vector<KeySpec> structure_keys();
std::vector<KeySpec> coupling_keys();
std::vector<KeySpec> excitation_keys();
std::vector<KeySpec> output_keys();

}  // namespace tankfsi
