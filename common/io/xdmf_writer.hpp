#pragma once
// The XDMF text that lets ParaView open a time series whose arrays live in an
// HDF5 file: the light data (structure, names, dimensions) in XML, the heavy
// data referred to as "FILE.h5:/path/to/dataset".
//
// Layout (XDMF 3; read by ParaView's "Xdmf3 Reader" and "XDMF Reader"):
//
//   <Xdmf Version="3.0"><Domain>
//     <Grid Name=SERIES GridType="Collection" CollectionType="Temporal">
//       <Grid Name="step_0000000" GridType="Uniform">
//         <Time Value="0.25"/>
//         <Topology TopologyType="Polyvertex" NumberOfElements="N" NodesPerElement="1"/>   particles
//         <Topology TopologyType="Mixed" NumberOfElements="C"> <DataItem .../> </Topology> meshes
//         <Geometry GeometryType="XYZ"> <DataItem Dimensions="N 3" .../> </Geometry>
//         <Attribute Name=... AttributeType="Scalar|Vector" Center="Node|Cell"> <DataItem/> </Attribute>
//       </Grid> ...
//
// A Mixed topology is one integer array holding, cell after cell, the XDMF cell
// type code followed by the cell's vertex indices (rows of the geometry):
// 4 a b c for a triangle, 5 a b c d for a quadrilateral. One grid then holds
// triangles and quads together, so a mesh stays one block in ParaView.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tankfsi {

/// XDMF cell type codes used in Mixed connectivity.
inline constexpr std::int64_t xdmf_triangle_code = 4;
inline constexpr std::int64_t xdmf_quadrilateral_code = 5;

enum class XdmfNumber { float64, int64 };

/// One HDF5 dataset as XDMF sees it.
struct XdmfDataItem {
  std::string dataset;                   ///< path inside the HDF5 file: "/step_0000000/position"
  std::vector<std::int64_t> dimensions;  ///< {rows} or {rows, columns}
  XdmfNumber number = XdmfNumber::float64;
};

enum class XdmfCenter { node, cell };

/// Scalar when the data is 1-D, Vector when it has 3 columns.
struct XdmfAttribute {
  std::string name;
  XdmfCenter center = XdmfCenter::node;
  XdmfDataItem data;
};

enum class XdmfTopologyType { polyvertex, mixed };

struct XdmfTopology {
  XdmfTopologyType type = XdmfTopologyType::polyvertex;
  std::int64_t elements = 0;                ///< points (Polyvertex) or cells (Mixed)
  std::optional<XdmfDataItem> connectivity;  ///< Mixed only: codes and vertex indices
};

/// One snapshot: a uniform grid at one time.
struct XdmfGrid {
  std::string name;
  double time = 0.0;
  XdmfTopology topology;
  XdmfDataItem geometry;  ///< vertex or particle positions, {n, 3}
  std::vector<XdmfAttribute> attributes;
};

/// The whole document: a temporal collection named `series_name` of `grids`,
/// whose datasets are in `h5_file_name` (a name relative to the XDMF file's
/// folder, so that the pair can be moved together).
/// Throws std::invalid_argument for a grid XDMF cannot express (an attribute
/// that is neither 1-D nor 3 columns, a Mixed topology without connectivity).
[[nodiscard]] std::string xdmf_document(const std::string& series_name, const std::string& h5_file_name,
                                        std::span<const XdmfGrid> grids);

/// Replaces `target` by a file holding `text` so that readers only ever see
/// the old or the new whole file: written to a temporary name in the same
/// folder, then renamed over the target. Throws std::runtime_error on failure.
void replace_file_atomically(const std::filesystem::path& target, const std::string& text);

}  // namespace tankfsi
