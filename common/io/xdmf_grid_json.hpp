#pragma once
// An XdmfGrid as JSON text, stored with each snapshot in the HDF5 file (the
// step group's attribute "xdmf_grid"). The HDF5 file is thereby the whole
// record of a series: the XDMF can be rebuilt from it when a series is
// continued (FileMode::append) or when the XDMF file was lost.
#include <string>

#include "common/io/xdmf_writer.hpp"

namespace tankfsi {

[[nodiscard]] std::string xdmf_grid_to_json(const XdmfGrid& grid);
/// Throws std::runtime_error if `json_text` is not what xdmf_grid_to_json writes.
[[nodiscard]] XdmfGrid xdmf_grid_from_json(const std::string& json_text);

}  // namespace tankfsi
