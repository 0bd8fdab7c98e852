#include "common/io/hdf5_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

#include "common/parallel/collective.hpp"

namespace tankfsi {

static_assert(std::is_same_v<hid_t, std::int64_t>, "Hdf5File stores a hid_t as std::int64_t");

namespace {

/// The outermost and innermost descriptions on HDF5's error stack: what the
/// call could not do, and the root cause (often an errno text from the OS).
std::string hdf5_error_stack_summary() {
  struct Found {
    std::string outermost;
    std::string innermost;
  } found;
  const auto collect = [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
    auto* f = static_cast<Found*>(data);
    const std::string description = error->desc != nullptr ? error->desc : "";
    if (f->outermost.empty()) f->outermost = description;
    f->innermost = description;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect, &found);
  if (found.innermost.empty() || found.innermost == found.outermost) return found.outermost;
  return found.outermost + ": " + found.innermost;
}

[[noreturn]] void fail(const std::string& call, const std::string& object, const std::filesystem::path& file) {
  std::string message = call + " failed";
  if (!object.empty()) message += " for '" + object + "'";
  message += " in " + file.string();
  if (const auto details = hdf5_error_stack_summary(); !details.empty()) message += ": " + details;
  throw std::runtime_error(message);
}

/// Owns one HDF5 identifier and closes it with the function of its kind.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Handle& operator=(Handle&&) = delete;
  [[nodiscard]] hid_t get() const { return id_; }

 private:
  hid_t id_;
  Closer closer_;
};

/// Runs HDF5 calls for one object of one file and turns failures into exceptions.
class Checked {
 public:
  Checked(const std::filesystem::path& file, std::string object) : file_(file), object_(std::move(object)) {}
  /// For calls returning an identifier to be closed with `closer`.
  Handle open(hid_t id, Handle::Closer closer, const char* call) const {
    if (id < 0) fail(call, object_, file_);
    return {id, closer};
  }
  /// For calls returning a status (herr_t) or a non-negative value (htri_t, ssize_t...).
  template <class Result>
  Result status(Result result, const char* call) const {
    if (result < 0) fail(call, object_, file_);
    return result;
  }

 private:
  const std::filesystem::path& file_;
  std::string object_;
};

/// Link creation properties that create missing parent groups.
Handle parents_creating_lcpl(const Checked& checked) {
  auto lcpl = checked.open(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "H5Pcreate(H5P_LINK_CREATE)");
  checked.status(H5Pset_create_intermediate_group(lcpl.get(), 1), "H5Pset_create_intermediate_group");
  return lcpl;
}

bool exists_on_rank0(MPI_Comm comm, const std::filesystem::path& path) {
  // One rank decides, so every rank makes the same (collective) open-or-create call.
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::error_code unreadable;  // the throwing overload would leave the other ranks waiting in MPI_Bcast
  int exists = rank == 0 && std::filesystem::exists(path, unreadable) ? 1 : 0;
  MPI_Bcast(&exists, 1, MPI_INT, 0, comm);
  return exists != 0;
}

/// A collective transfer's row selection: rows [first, first + count) of the
/// file's dataset and the memory block of `count` rows; a rank without rows
/// still takes part, selecting nothing. Returns the memory space.
Handle select_rows(const Checked& checked, hid_t file_space, int dataset_rank, std::int64_t first,
                   std::int64_t count, std::size_t columns) {
  const hsize_t local_dims[2] = {static_cast<hsize_t>(count), columns};
  auto memory_space = checked.open(H5Screate_simple(dataset_rank, local_dims, nullptr), H5Sclose, "H5Screate_simple");
  if (count > 0) {
    const hsize_t start[2] = {static_cast<hsize_t>(first), 0};
    checked.status(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, local_dims, nullptr),
                   "H5Sselect_hyperslab");
  } else {
    checked.status(H5Sselect_none(file_space), "H5Sselect_none");
    checked.status(H5Sselect_none(memory_space.get()), "H5Sselect_none");
  }
  return memory_space;
}

/// Transfer properties of every read and write: collective MPI-IO.
Handle collective_transfer(const Checked& checked) {
  auto dxpl = checked.open(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate(H5P_DATASET_XFER)");
  checked.status(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio");
  return dxpl;
}

}  // namespace

RowBlock rank_order_rows(MPI_Comm comm, std::int64_t local_rows) {
  RowBlock block;
  block.local = local_rows;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Exscan(&local_rows, &block.first, 1, MPI_INT64_T, MPI_SUM, comm);
  if (rank == 0) block.first = 0;  // MPI_Exscan leaves rank 0's result undefined
  MPI_Allreduce(&local_rows, &block.total, 1, MPI_INT64_T, MPI_SUM, comm);
  return block;
}

Hdf5File::Hdf5File(MPI_Comm comm, std::filesystem::path path, FileMode mode) : path_(std::move(path)) {
  // A private communicator keeps this file's collective calls apart from the caller's messages.
  MPI_Comm_dup(comm, &comm_);
  try {
    const Checked checked(path_, "");
    auto fapl = checked.open(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate(H5P_FILE_ACCESS)");
    checked.status(H5Pset_fapl_mpio(fapl.get(), comm_, MPI_INFO_NULL), "H5Pset_fapl_mpio");
    if (mode == FileMode::read) {
      file_ = checked.status(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, fapl.get()), "H5Fopen");
    } else if (mode == FileMode::append && exists_on_rank0(comm_, path_)) {
      file_ = checked.status(H5Fopen(path_.c_str(), H5F_ACC_RDWR, fapl.get()), "H5Fopen");
    } else {
      file_ = checked.status(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), "H5Fcreate");
    }
  } catch (...) {
    MPI_Comm_free(&comm_);
    throw;
  }
}

Hdf5File::~Hdf5File() {
  H5Fclose(file_);  // a failure here cannot be reported from a destructor; flush() can report it
  MPI_Comm_free(&comm_);
}

void Hdf5File::create_group(const std::string& group) {
  const Checked checked(path_, group);
  const auto lcpl = parents_creating_lcpl(checked);
  checked.open(H5Gcreate2(file_, group.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "H5Gcreate2");
}

std::vector<std::string> Hdf5File::group_members(const std::string& group) const {
  const Checked checked(path_, group);
  const auto handle = checked.open(H5Gopen2(file_, group.c_str(), H5P_DEFAULT), H5Gclose, "H5Gopen2");
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  checked.status(H5Literate(handle.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names), "H5Literate");
  return names;
}

void Hdf5File::remove(const std::string& object) {
  Checked(path_, object).status(H5Ldelete(file_, object.c_str(), H5P_DEFAULT), "H5Ldelete");
}

bool Hdf5File::exists(const std::string& object) const {
  // H5Lexists needs every parent to exist: walk the path one link at a time.
  std::string prefix;
  std::size_t from = 1;
  while (from <= object.size()) {
    const std::size_t slash = object.find('/', from);
    prefix = object.substr(0, slash);
    if (Checked(path_, prefix).status(H5Lexists(file_, prefix.c_str(), H5P_DEFAULT), "H5Lexists") <= 0) return false;
    if (slash == std::string::npos) break;
    from = slash + 1;
  }
  return true;
}

Hdf5File::Shape Hdf5File::shape(const std::string& dataset) const {
  const Checked checked(path_, dataset);
  const auto handle = checked.open(H5Dopen2(file_, dataset.c_str(), H5P_DEFAULT), H5Dclose, "H5Dopen2");
  const auto space = checked.open(H5Dget_space(handle.get()), H5Sclose, "H5Dget_space");
  const int rank = checked.status(H5Sget_simple_extent_ndims(space.get()), "H5Sget_simple_extent_ndims");
  if (rank < 1 || rank > 2)
    throw std::runtime_error("dataset '" + dataset + "' in " + path_.string() + " is not 1-D or 2-D");
  hsize_t dims[2] = {0, 1};
  checked.status(H5Sget_simple_extent_dims(space.get(), dims, nullptr), "H5Sget_simple_extent_dims");
  return {static_cast<std::int64_t>(dims[0]), rank == 2 ? static_cast<std::int64_t>(dims[1]) : 1};
}

std::vector<double> Hdf5File::read_rows_double(const std::string& dataset, std::int64_t first,
                                               std::int64_t count) const {
  std::vector<double> values(static_cast<std::size_t>(std::max<std::int64_t>(count, 0) * shape(dataset).columns));
  read_rows(dataset, Element::float64, first, count, values.data());
  return values;
}

std::vector<std::int64_t> Hdf5File::read_rows_int64(const std::string& dataset, std::int64_t first,
                                                    std::int64_t count) const {
  std::vector<std::int64_t> values(
      static_cast<std::size_t>(std::max<std::int64_t>(count, 0) * shape(dataset).columns));
  read_rows(dataset, Element::int64, first, count, values.data());
  return values;
}

void Hdf5File::read_rows(const std::string& dataset, Element element, std::int64_t first, std::int64_t count,
                         void* buffer) const {
  const Shape whole = shape(dataset);
  std::string problem;
  if (first < 0 || count < 0 || first + count > whole.rows)
    problem = "rows [" + std::to_string(first) + ", " + std::to_string(first + count) + ") beyond its " +
              std::to_string(whole.rows);
  throw_if_any_rank_failed(comm_, "reading '" + dataset + "' from " + path_.string(), problem);
  // An empty dataset has no storage to read from (HDF5 1.10 fails on the attempt), as when written.
  if (whole.rows == 0) return;
  const Checked checked(path_, dataset);
  const auto handle = checked.open(H5Dopen2(file_, dataset.c_str(), H5P_DEFAULT), H5Dclose, "H5Dopen2");
  const auto file_space = checked.open(H5Dget_space(handle.get()), H5Sclose, "H5Dget_space");
  const int rank = checked.status(H5Sget_simple_extent_ndims(file_space.get()), "H5Sget_simple_extent_ndims");
  const auto memory_space =
      select_rows(checked, file_space.get(), rank, first, count, static_cast<std::size_t>(whole.columns));
  const auto dxpl = collective_transfer(checked);
  static std::int64_t no_rows = 0;
  const hid_t memory_type = element == Element::float64 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
  checked.status(H5Dread(handle.get(), memory_type, memory_space.get(), file_space.get(), dxpl.get(),
                         count > 0 ? buffer : &no_rows),
                 "H5Dread");
}

RowBlock Hdf5File::write_distributed_1d(const std::string& dataset, std::span<const double> local) {
  return write_distributed(dataset, Element::float64, local.data(), local.size(), 1, 1);
}
RowBlock Hdf5File::write_distributed_1d(const std::string& dataset, std::span<const std::int64_t> local) {
  return write_distributed(dataset, Element::int64, local.data(), local.size(), 1, 1);
}
RowBlock Hdf5File::write_distributed_2d(const std::string& dataset, std::span<const double> local,
                                        std::size_t columns) {
  return write_distributed(dataset, Element::float64, local.data(), local.size(), columns, 2);
}
RowBlock Hdf5File::write_distributed_2d(const std::string& dataset, std::span<const std::int64_t> local,
                                        std::size_t columns) {
  return write_distributed(dataset, Element::int64, local.data(), local.size(), columns, 2);
}

RowBlock Hdf5File::write_distributed(const std::string& dataset, Element element, const void* local_data,
                                     std::size_t local_values, std::size_t columns, int dataset_rank) {
  std::string problem;
  if (columns == 0)
    problem = "a 2-D dataset needs at least one column";
  else if (local_values % columns != 0)
    problem = std::to_string(local_values) + " values are not whole rows of " + std::to_string(columns);
  throw_if_any_rank_failed(comm_, "writing '" + dataset + "' to " + path_.string(), problem);

  const auto block = rank_order_rows(comm_, static_cast<std::int64_t>(local_values / columns));
  const Checked checked(path_, dataset);

  // Fixed little-endian types in the file, whatever the machine: the files outlive it.
  const hid_t file_type = element == Element::float64 ? H5T_IEEE_F64LE : H5T_STD_I64LE;
  const hid_t memory_type = element == Element::float64 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;

  const hsize_t total_dims[2] = {static_cast<hsize_t>(block.total), columns};
  const auto file_space =
      checked.open(H5Screate_simple(dataset_rank, total_dims, nullptr), H5Sclose, "H5Screate_simple");
  const auto lcpl = parents_creating_lcpl(checked);
  const auto handle = checked.open(
      H5Dcreate2(file_, dataset.c_str(), file_type, file_space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose, "H5Dcreate2");

  // An empty dataset has no storage to write to (HDF5 1.10 fails on the attempt): creating it is all.
  if (block.total == 0) return block;

  const auto memory_space = select_rows(checked, file_space.get(), dataset_rank, block.first, block.local, columns);
  const auto dxpl = collective_transfer(checked);
  // An empty std::span may hold a null pointer; HDF5 wants a buffer even when it reads none of it.
  static const std::int64_t no_rows = 0;
  const void* buffer = local_data != nullptr ? local_data : &no_rows;
  checked.status(H5Dwrite(handle.get(), memory_type, memory_space.get(), file_space.get(), dxpl.get(), buffer),
                 "H5Dwrite");
  return block;
}

namespace {

void write_scalar_attribute(hid_t file, const std::filesystem::path& path, const std::string& object,
                            const std::string& name, hid_t file_type, hid_t memory_type, const void* value) {
  const Checked checked(path, object + "@" + name);
  const auto target = checked.open(H5Oopen(file, object.c_str(), H5P_DEFAULT), H5Oclose, "H5Oopen");
  if (checked.status(H5Aexists(target.get(), name.c_str()), "H5Aexists") > 0)
    checked.status(H5Adelete(target.get(), name.c_str()), "H5Adelete");
  const auto space = checked.open(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate(H5S_SCALAR)");
  const auto attribute = checked.open(
      H5Acreate2(target.get(), name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
      "H5Acreate2");
  checked.status(H5Awrite(attribute.get(), memory_type, value), "H5Awrite");
}

}  // namespace

void Hdf5File::write_attribute(const std::string& object, const std::string& name, double value) {
  write_scalar_attribute(file_, path_, object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  write_scalar_attribute(file_, path_, object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, const std::string& value) {
  // A fixed-length, null-terminated string: the simplest kind for every reader (h5py gives bytes).
  const Checked checked(path_, object + "@" + name);
  const auto type = checked.open(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy");
  checked.status(H5Tset_size(type.get(), value.size() + 1), "H5Tset_size");
  checked.status(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "H5Tset_strpad");
  write_scalar_attribute(file_, path_, object, name, type.get(), type.get(), value.c_str());
}

bool Hdf5File::has_attribute(const std::string& object, const std::string& name) const {
  const Checked checked(path_, object + "@" + name);
  return checked.status(H5Aexists_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT), "H5Aexists_by_name") > 0;
}

std::string Hdf5File::read_string_attribute(const std::string& object, const std::string& name) const {
  const Checked checked(path_, object + "@" + name);
  const auto attribute = checked.open(H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                                      H5Aclose, "H5Aopen_by_name");
  const auto type = checked.open(H5Aget_type(attribute.get()), H5Tclose, "H5Aget_type");
  if (H5Tget_class(type.get()) != H5T_STRING || checked.status(H5Tis_variable_str(type.get()), "H5Tis_variable_str") > 0)
    throw std::runtime_error("attribute '" + object + "@" + name + "' in " + path_.string() +
                             " is not a fixed-length string");
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0) fail("H5Tget_size", object + "@" + name, path_);
  std::string value(size, '\0');
  checked.status(H5Aread(attribute.get(), type.get(), value.data()), "H5Aread");
  value.resize(value.find('\0') == std::string::npos ? value.size() : value.find('\0'));
  return value;
}

void Hdf5File::read_numeric_attribute(const std::string& object, const std::string& name, Element element,
                                      void* value) const {
  const Checked checked(path_, object + "@" + name);
  const auto attribute = checked.open(H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                                      H5Aclose, "H5Aopen_by_name");
  const auto type = checked.open(H5Aget_type(attribute.get()), H5Tclose, "H5Aget_type");
  const H5T_class_t kind = H5Tget_class(type.get());
  if (kind != H5T_INTEGER && kind != H5T_FLOAT)
    throw std::runtime_error("attribute '" + object + "@" + name + "' in " + path_.string() + " is not a number");
  checked.status(H5Aread(attribute.get(), element == Element::float64 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, value),
                 "H5Aread");
}

double Hdf5File::read_double_attribute(const std::string& object, const std::string& name) const {
  double value = 0.0;
  read_numeric_attribute(object, name, Element::float64, &value);
  return value;
}

std::int64_t Hdf5File::read_int64_attribute(const std::string& object, const std::string& name) const {
  std::int64_t value = 0;
  read_numeric_attribute(object, name, Element::int64, &value);
  return value;
}

void Hdf5File::flush() { Checked(path_, "").status(H5Fflush(file_, H5F_SCOPE_GLOBAL), "H5Fflush"); }

}  // namespace tankfsi
