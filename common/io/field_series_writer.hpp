#pragma once
// FieldSeriesWriter: a time series of particle sets or of surface meshes,
// written by all ranks of a communicator as FOLDER/NAME.h5 (parallel HDF5) and
// FOLDER/NAME.xdmf (which ParaView opens as a time series).
//
// File layout: snapshot k is the group /step_%07d (step_0000000, step_0000001...)
// with attributes time (double), kind ("particles" or "mesh") and xdmf_grid (the
// snapshot's XDMF entry as JSON, from which the XDMF can be rebuilt).
//   particles: ids (n) int64, position (n×3), fields/NAME (n or n×3)
//   meshes:    vertex_ids (n) int64, position (n×3), node_fields/NAME (n or n×3),
//              cell_fields/NAME (c or c×3), and, when the cells are written anew,
//              topology/connectivity: XDMF Mixed connectivity (see xdmf_writer.hpp)
// Rows are in rank order: rank 0's local rows, then rank 1's, ... All doubles
// are little-endian IEEE 64-bit, all integers little-endian 64-bit.
//
// Mesh vertex indices: vertex rows in the file are the ranks' owned vertices
// in rank order, so the file index of a rank's k-th owned vertex is
// first_vertex_index(owned) + k. Cells name their vertices by file index, also
// vertices owned by another rank (the caller learns their file indices with its
// usual ghost exchange). With PETSc-style numbering, where each rank owns a
// contiguous range of global indices and passes its vertices in that order,
// the file index is the global index.
//
// After each snapshot the HDF5 file is flushed and rank 0 replaces the XDMF file
// atomically, so a killed run leaves an XDMF that names only complete, flushed
// snapshots. (HDF5 1.10 itself does not journal: a run killed in the middle of
// writing a snapshot may still leave NAME.h5 damaged.)
// The constructor, first_vertex_index and the write functions are collective;
// their arguments are checked on every rank first, and a bad argument on any
// rank throws std::invalid_argument on all of them, before anything is written.
// HDF5 and file system failures throw std::runtime_error.
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/io/hdf5_file.hpp"
#include "common/io/xdmf_writer.hpp"

namespace tankfsi {

/// One named array of values per local particle, vertex or cell.
struct NamedField {
  std::string name;                ///< letters, digits, '_', '-', '.'; starts with a letter or '_'
  int components = 1;              ///< 1: scalar; 3: vector (x, y, z)
  std::span<const double> values;  ///< local rows × components, one row after the other
};

/// This rank's particles at one time. Fields must be the same (names, order,
/// components) on every rank; they may change from one snapshot to the next.
struct ParticleSnapshot {
  std::span<const std::int64_t> ids;  ///< n
  std::span<const double> positions;  ///< n × 3
  std::vector<NamedField> fields;     ///< n rows each
};

/// This rank's cells, by file vertex index (see above).
struct SurfaceCells {
  std::span<const std::int64_t> triangles;  ///< 3 indices per triangle
  std::span<const std::int64_t> quads;      ///< 4 indices per quadrilateral, in order around it
};

/// This rank's part of a surface mesh at one time.
struct MeshSnapshot {
  std::span<const std::int64_t> vertex_ids;  ///< n owned vertices: the caller's global ids
  std::span<const double> positions;         ///< n × 3
  /// Set: the cells are written with this snapshot (the first one, or a mesh
  /// that changed). Empty: the snapshot reuses the cells last written, which
  /// needs every rank to own the same vertices (same count) as then.
  std::optional<SurfaceCells> cells;
  std::vector<NamedField> node_fields;  ///< n rows each
  /// One row per local cell: this rank's triangles first, then its quads.
  std::vector<NamedField> cell_fields;
};

class FieldSeriesWriter {
 public:
  /// `folder` must exist (the run folder is made elsewhere). FileMode::append
  /// continues a series already in NAME.h5: its snapshots stay in the XDMF and
  /// new ones follow; the first mesh snapshot after reopening must carry cells.
  /// `keep_until` (append only): a restarted run continues the series from
  /// that time: later snapshots (the stopped run's, computed again) are
  /// removed from the file and the XDMF.
  FieldSeriesWriter(MPI_Comm comm, const std::filesystem::path& folder, const std::string& name,
                    FileMode mode = FileMode::truncate, std::optional<double> keep_until = std::nullopt);

  /// File index of this rank's first owned vertex when every rank owns
  /// `owned_vertices` (MPI_Exscan over the ranks).
  [[nodiscard]] std::int64_t first_vertex_index(std::int64_t owned_vertices) const;

  /// Times must increase from snapshot to snapshot and be equal on all ranks.
  /// A series holds one kind of data: particles or a mesh.
  void write_particles(double time, const ParticleSnapshot& snapshot);
  void write_mesh(double time, const MeshSnapshot& snapshot);

  [[nodiscard]] std::size_t snapshot_count() const { return grids_.size(); }
  [[nodiscard]] const std::filesystem::path& h5_path() const { return file_.path(); }
  [[nodiscard]] const std::filesystem::path& xdmf_path() const { return xdmf_path_; }

 private:
  enum class Kind { none, particles, mesh };
  /// The cells last written, for snapshots that reuse them.
  struct WrittenCells {
    XdmfTopology topology;
    std::int64_t local_vertices = 0;
    std::int64_t local_cells = 0;
  };

  void resume_from_file(std::optional<double> keep_until);
  void check_snapshot(double time, Kind kind, const std::string& local_problem,
                      const std::string& layout_signature) const;
  std::string begin_step(double time, Kind kind);
  /// Writes positions and ids, and starts the snapshot's XDMF grid with them.
  XdmfGrid write_points(const std::string& group, double time, const std::string& ids_name,
                        std::span<const std::int64_t> ids, std::span<const double> positions);
  /// Writes each field under `group` and adds its XDMF attribute to `attributes`.
  void write_fields(const std::string& group, std::span<const NamedField> fields, XdmfCenter center,
                    std::vector<XdmfAttribute>& attributes);
  WrittenCells write_cells(const std::string& group, const SurfaceCells& cells, std::int64_t local_vertices);
  void finish_step(const std::string& group, XdmfGrid grid);
  void publish_xdmf();

  std::string name_;
  std::filesystem::path xdmf_path_;
  Hdf5File file_;
  std::vector<XdmfGrid> grids_;  ///< the snapshots in the XDMF, in order
  std::int64_t next_step_ = 0;
  Kind kind_ = Kind::none;
  std::optional<WrittenCells> cells_;
};

}  // namespace tankfsi
