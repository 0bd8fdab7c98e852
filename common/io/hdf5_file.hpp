#pragma once
// Hdf5File: one HDF5 file opened by every rank of a communicator through
// MPI-IO, into which each rank writes its own block of rows of shared datasets.
//
// Every member function is collective: all ranks of the communicator call it,
// in the same order, with the same dataset, group and attribute names (and the
// same attribute values); only the row blocks differ between ranks. Errors of
// the HDF5 library throw std::runtime_error naming the call, the object and the
// file; inconsistent arguments throw std::invalid_argument on every rank.
//
// <hdf5.h> stays out of this header: callers see std::int64_t where HDF5 has
// hid_t (the same type, checked in the .cpp).
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace tankfsi {

/// What to do with a file that already exists.
enum class FileMode {
  truncate,  ///< start a new, empty file (any old one is lost)
  append,    ///< keep what the file holds (create it if it is missing)
  read,      ///< read only; the file must exist
};

/// Where one rank's rows sit in a dataset made of the blocks of all ranks in
/// rank order: rank r's rows start after those of ranks 0..r-1.
struct RowBlock {
  std::int64_t first = 0;  ///< global index of this rank's first row
  std::int64_t local = 0;  ///< rows this rank holds
  std::int64_t total = 0;  ///< rows over all ranks
};

/// Collective: the rank-order layout of blocks of `local_rows` rows each
/// (MPI_Exscan for the offsets, MPI_Allreduce for the total).
RowBlock rank_order_rows(MPI_Comm comm, std::int64_t local_rows);

class Hdf5File {
 public:
  /// Opens or creates `path` on every rank of `comm`. The folder must exist.
  Hdf5File(MPI_Comm comm, std::filesystem::path path, FileMode mode);
  /// Closes the file. Must run before MPI_Finalize (like every MPI object).
  ~Hdf5File();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  Hdf5File(Hdf5File&&) = delete;
  Hdf5File& operator=(Hdf5File&&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// The file's own duplicate of the communicator it was opened on.
  [[nodiscard]] MPI_Comm comm() const { return comm_; }

  /// Creates a group, and any missing parent groups ("/a/b/c").
  void create_group(const std::string& group);
  /// Names of the links directly under `group`, in name order.
  [[nodiscard]] std::vector<std::string> group_members(const std::string& group) const;

  /// Writes a new 1-D dataset of all ranks' `local` blocks in rank order.
  /// Missing parent groups are created. A rank may hold no rows.
  RowBlock write_distributed_1d(const std::string& dataset, std::span<const double> local);
  RowBlock write_distributed_1d(const std::string& dataset, std::span<const std::int64_t> local);
  /// Writes a new 2-D dataset (total rows × columns); `local` holds this
  /// rank's rows one after the other (row-major, local.size() = rows × columns).
  RowBlock write_distributed_2d(const std::string& dataset, std::span<const double> local, std::size_t columns);
  RowBlock write_distributed_2d(const std::string& dataset, std::span<const std::int64_t> local,
                                std::size_t columns);

  /// Removes a group or dataset (its link; HDF5 does not shrink the file).
  void remove(const std::string& object);
  [[nodiscard]] bool exists(const std::string& object) const;

  /// Rows and columns of a 1-D (columns 1) or 2-D dataset.
  struct Shape {
    std::int64_t rows = 0;
    std::int64_t columns = 1;
  };
  [[nodiscard]] Shape shape(const std::string& dataset) const;
  /// Reads rows [first, first + count) of a 1-D or 2-D dataset, row after row
  /// (count × columns values). Each rank may read its own range (count 0
  /// too); a range beyond the dataset throws std::invalid_argument on every rank.
  [[nodiscard]] std::vector<double> read_rows_double(const std::string& dataset, std::int64_t first,
                                                     std::int64_t count) const;
  [[nodiscard]] std::vector<std::int64_t> read_rows_int64(const std::string& dataset, std::int64_t first,
                                                          std::int64_t count) const;

  /// Scalar attributes of a group or dataset; an attribute of the same name is replaced.
  void write_attribute(const std::string& object, const std::string& name, double value);
  void write_attribute(const std::string& object, const std::string& name, std::int64_t value);
  void write_attribute(const std::string& object, const std::string& name, const std::string& value);
  [[nodiscard]] bool has_attribute(const std::string& object, const std::string& name) const;
  /// Reads a string attribute written by write_attribute.
  [[nodiscard]] std::string read_string_attribute(const std::string& object, const std::string& name) const;
  /// Reads a numeric scalar attribute (converted to the type asked for).
  [[nodiscard]] double read_double_attribute(const std::string& object, const std::string& name) const;
  [[nodiscard]] std::int64_t read_int64_attribute(const std::string& object, const std::string& name) const;

  /// Pushes everything written so far to the file system, so that other
  /// programs (a viewer, a post-processing script) can read it.
  void flush();

 private:
  enum class Element { float64, int64 };
  RowBlock write_distributed(const std::string& dataset, Element element, const void* local_data,
                             std::size_t local_values, std::size_t columns, int dataset_rank);
  void read_rows(const std::string& dataset, Element element, std::int64_t first, std::int64_t count,
                 void* buffer) const;
  void read_numeric_attribute(const std::string& object, const std::string& name, Element element,
                              void* value) const;

  std::filesystem::path path_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  std::int64_t file_ = -1;  ///< hid_t of the open file
};

}  // namespace tankfsi
