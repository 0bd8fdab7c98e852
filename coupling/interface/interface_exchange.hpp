#pragma once
// InterfaceExchange: moves nodal arrays (3 values per interface vertex)
// between the structure's ranks and the fluid's ranks without passing them
// through one rank (PROTOCOL.md, "Communication pattern").
//
// Ownership: each structure rank owns the vertices it declared. The fluid
// ranks hold the whole mesh and split the id-sorted vertex list into
// contiguous slices, slice f on fluid rank f. Every window:
//   fluid -> structure (forces): the fluid ranks' partial sums are reduced
//     onto the slices (MPI_Reduce_scatter), and each fluid rank sends each
//     structure rank the values of the vertices in both its slice and that
//     rank's ownership;
//   structure -> fluid (displacements): the reverse, then MPI_Allgatherv
//     among the fluid ranks gives every fluid rank the whole array.
// The pairs that exchange and the order of their vertices are set once,
// when the mesh is handed over.
#include <cstdint>
#include <span>
#include <vector>

#include "coupling/interface/interface_mesh.hpp"
#include "coupling/partnership/partner_link.hpp"

namespace tankfsi::coupling {

class InterfaceExchange {
 public:
  /// Structure side, collective over the structure ranks and paired with the
  /// fluid's constructor: hands this rank's declared vertices and triangles
  /// (vertex ids, not indices) over. Each vertex on exactly one rank.
  InterfaceExchange(PartnerLink& link, const std::vector<std::int64_t>& ids, const std::vector<double>& coordinates,
                    const std::vector<std::array<std::int64_t, 3>>& triangles);
  /// Fluid side: receives the whole mesh on every rank.
  explicit InterfaceExchange(PartnerLink& link);

  /// Fluid: the whole mesh, id-sorted; structure: this rank's declared vertices
  /// (in declaration order) and no triangles.
  [[nodiscard]] const InterfaceMesh& mesh() const { return mesh_; }
  /// Number of values (3 per vertex) this rank holds in its distributed part:
  /// fluid: its slice; structure: its declared vertices.
  [[nodiscard]] std::size_t part_size() const { return part_size_; }
  /// Fluid: offset of this rank's slice in the whole array (values).
  [[nodiscard]] std::size_t slice_offset() const { return slice_offset_; }
  /// Vertices of the whole interface (both sides).
  [[nodiscard]] std::size_t global_vertex_count() const { return global_vertices_; }

  /// Fluid: sums the ranks' whole arrays of partial values onto the slices.
  [[nodiscard]] std::vector<double> reduce_to_slice(std::span<const double> partial_whole) const;
  /// Fluid: gathers the slices into the whole array on every rank.
  [[nodiscard]] std::vector<double> gather_slices(std::span<const double> slice) const;

  /// Posts the sends of this rank's part (slice or declared vertices) to the
  /// partner ranks that need them; complete with finish_sends(). A part has
  /// `values_per_vertex` values per vertex (3 for nodal vectors).
  void post_sends(std::span<const double> part, int tag, std::size_t values_per_vertex = 3);
  /// Receives this rank's part from the partner ranks (blocking, timed).
  [[nodiscard]] std::vector<double> receive_part(int tag, const std::string& what, std::size_t values_per_vertex = 3);
  void finish_sends(const std::string& what);

 private:
  void build_plan_structure();
  void build_plan_fluid(const std::vector<int>& owner_of_sorted_vertex);

  PartnerLink& link_;
  InterfaceMesh mesh_;
  std::size_t part_size_ = 0;
  std::size_t slice_offset_ = 0;
  std::size_t global_vertices_ = 0;
  std::vector<int> slice_counts_;   ///< fluid: values per slice (all fluid ranks)
  std::vector<int> slice_offsets_;  ///< fluid: value offset of each slice
  /// Per partner rank: positions (vertex indices within this rank's part) in
  /// the agreed order; empty when the pair exchanges nothing.
  std::vector<std::vector<int>> pair_vertices_;
  std::vector<std::vector<double>> send_buffers_;
  std::vector<MPI_Request> send_requests_;
};

}  // namespace tankfsi::coupling
