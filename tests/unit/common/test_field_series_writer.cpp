// FieldSeriesWriter and Hdf5File on 1 and 2 ranks: every rank writes known,
// rank-dependent particles (with a rank holding none at one snapshot) and a
// mesh of triangles and quads whose cells are written, reused, then replaced.
// Rank 0 reads the files back with the serial HDF5 API and compares every
// array bit for bit with what the ranks wrote; then the independent Python
// check (tests/tools/check_field_series.py) reads the XDMF as ParaView would
// and compares what it names with an "expected" JSON file written here.
#include <catch2/catch.hpp>
#include <hdf5.h>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <bit>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/mpi_world.hpp"
#include "support/scratch_folder.hpp"
#include "common/io/field_series_writer.hpp"
#include "common/io/hdf5_file.hpp"

using namespace tankfsi;

namespace {

using testing::world_rank;
using testing::world_size;

// ---------------------------------------------------------------- what is written

/// Rank-dependent particles. At snapshot 1 the last rank (when there are
/// several) holds none, as after all its particles migrated or left.
struct ParticleBlock {
  std::vector<std::int64_t> ids;
  std::vector<double> positions, velocity, pressure, density;
};

ParticleBlock particle_block(int rank, int size, int step) {
  const int count = step == 1 && size > 1 && rank == size - 1 ? 0 : 2 + 3 * rank + step;
  ParticleBlock block;
  for (int i = 0; i < count; ++i) {
    block.ids.push_back(1000 * rank + 100 * step + i);
    block.positions.insert(block.positions.end(), {rank + i / 7.0, 0.1 * step + 1.0 / 3.0, 1e-3 * i});
    block.velocity.insert(block.velocity.end(), {-i / 3.0, 2.5 * rank, 1.0 / (step + 1)});
    block.pressure.push_back(1000.0 * rank + i + step / 7.0);
    block.density.push_back(998.2 + i * 1e-7 + rank);
  }
  // Values that only survive an exact round trip: signed zero, a subnormal, the largest double.
  if (rank == 0 && count > 0) {
    block.positions[2] = -0.0;
    block.pressure[0] = 5e-324;
    block.density[0] = 1.7976931348623157e308;
  }
  return block;
}

std::vector<NamedField> particle_fields(const ParticleBlock& block, int step) {
  std::vector<NamedField> fields = {{"velocity", 3, block.velocity}, {"pressure", 1, block.pressure}};
  if (step == 2) fields.push_back({"density", 1, block.density});  // fields may change between snapshots
  return fields;
}

/// Rank r owns a 2 × (3 + r) grid of vertices; its cells: quads and pairs of
/// triangles alternating along the strip, plus (layout A) one triangle reaching
/// the first vertex of the next rank, so that cells cross rank boundaries.
/// Snapshots 0 and 1 use layout A (1 reuses the cells of 0), snapshot 2 a new layout B.
int mesh_width(int rank) { return 3 + rank; }

std::int64_t mesh_first_vertex(int rank) {
  std::int64_t first = 0;
  for (int q = 0; q < rank; ++q) first += 2 * mesh_width(q);
  return first;
}

struct MeshBlock {
  std::vector<std::int64_t> vertex_ids;
  std::vector<double> positions, displacement, pressure;
  std::vector<std::int64_t> triangles, quads;
  std::vector<double> thickness;  ///< per cell: triangles first, then quads
};

MeshBlock mesh_block(int rank, int size, int step) {
  const int width = mesh_width(rank);
  const std::int64_t first = mesh_first_vertex(rank);
  const auto vertex = [&](int row, int column) { return first + row * width + column; };
  MeshBlock block;
  for (int row = 0; row < 2; ++row) {
    for (int column = 0; column < width; ++column) {
      const double bulge = 0.01 * step * (column + 1);
      block.vertex_ids.push_back(7 * vertex(row, column) + 3);
      block.positions.insert(block.positions.end(), {1.0 * column, 2.0 * rank + row, row / 3.0 + bulge});
      block.displacement.insert(block.displacement.end(), {0.0, -0.0, bulge});
      block.pressure.push_back(1000.0 * rank + row * width + column + step / 7.0);
    }
  }
  const bool layout_b = step == 2;
  for (int column = 0; column + 1 < width; ++column) {
    const auto a = vertex(0, column), b = vertex(0, column + 1), c = vertex(1, column + 1), d = vertex(1, column);
    if ((column % 2 == 0) != layout_b)
      block.quads.insert(block.quads.end(), {a, b, c, d});
    else
      block.triangles.insert(block.triangles.end(), {a, b, c, a, c, d});
  }
  if (!layout_b && rank + 1 < size)
    block.triangles.insert(block.triangles.end(), {vertex(1, 0), vertex(1, 1), first + 2 * width});
  const auto cells = block.triangles.size() / 3 + block.quads.size() / 4;
  for (std::size_t cell = 0; cell < cells; ++cell) block.thickness.push_back(0.01 * (rank + 1) + 1e-3 * cell + step);
  return block;
}

const std::vector<double> snapshot_times = {0.0, 0.1, 0.1 + 0.2};  // 0.30000000000000004: needs all 17 digits

// ---------------------------------------------------------------- what the files must hold

/// One dataset as it must be in the file, assembled from all ranks' blocks.
struct ExpectedDataset {
  std::string path;
  std::vector<std::uint64_t> dims;
  std::vector<double> doubles;     ///< for float datasets
  std::vector<std::int64_t> ints;  ///< for integer datasets
  bool integer = false;
};

ExpectedDataset doubles_dataset(std::string path, std::vector<double> values, std::uint64_t columns) {
  const auto rows = values.size() / columns;
  return {std::move(path), columns == 1 ? std::vector<std::uint64_t>{rows} : std::vector<std::uint64_t>{rows, columns},
          std::move(values), {}, false};
}

ExpectedDataset ints_dataset(std::string path, std::vector<std::int64_t> values) {
  const std::uint64_t rows = values.size();
  return {std::move(path), {rows}, {}, std::move(values), true};
}

struct ExpectedAttribute {
  std::string name;
  std::string center;  ///< "Node" or "Cell", as in the XDMF
  ExpectedDataset data;
};

struct ExpectedStep {
  std::string group;
  double time = 0.0;
  std::string topology;  ///< "Polyvertex" or "Mixed"
  std::int64_t elements = 0;
  ExpectedDataset geometry;
  std::optional<ExpectedDataset> connectivity;
  std::vector<ExpectedAttribute> attributes;
};

std::string step_group(int step) {
  std::string digits = std::to_string(step);
  return "/step_" + std::string(7 - digits.size(), '0') + digits;
}

template <class T, class Block, class Member>
std::vector<T> gathered(const std::vector<Block>& blocks, Member member) {
  std::vector<T> all;
  for (const auto& block : blocks) all.insert(all.end(), (block.*member).begin(), (block.*member).end());
  return all;
}

ExpectedStep expected_header(int step, double time, const std::string& topology) {
  ExpectedStep expected;
  expected.group = step_group(step);
  expected.time = time;
  expected.topology = topology;
  return expected;
}

ExpectedStep expected_particle_step(int step, int size, double time) {
  std::vector<ParticleBlock> blocks;
  for (int rank = 0; rank < size; ++rank) blocks.push_back(particle_block(rank, size, step));
  ExpectedStep expected = expected_header(step, time, "Polyvertex");
  const auto& group = expected.group;
  expected.geometry = doubles_dataset(group + "/position", gathered<double>(blocks, &ParticleBlock::positions), 3);
  expected.elements = static_cast<std::int64_t>(expected.geometry.dims[0]);
  expected.attributes.push_back(
      {"ids", "Node", ints_dataset(group + "/ids", gathered<std::int64_t>(blocks, &ParticleBlock::ids))});
  expected.attributes.push_back({"velocity", "Node",
                                 doubles_dataset(group + "/fields/velocity",
                                                 gathered<double>(blocks, &ParticleBlock::velocity), 3)});
  expected.attributes.push_back({"pressure", "Node",
                                 doubles_dataset(group + "/fields/pressure",
                                                 gathered<double>(blocks, &ParticleBlock::pressure), 1)});
  if (step == 2)
    expected.attributes.push_back({"density", "Node",
                                   doubles_dataset(group + "/fields/density",
                                                   gathered<double>(blocks, &ParticleBlock::density), 1)});
  return expected;
}

ExpectedStep expected_mesh_step(int step, int size, double time) {
  std::vector<MeshBlock> blocks;
  for (int rank = 0; rank < size; ++rank) blocks.push_back(mesh_block(rank, size, step));
  ExpectedStep expected = expected_header(step, time, "Mixed");
  const auto& group = expected.group;
  expected.geometry = doubles_dataset(group + "/position", gathered<double>(blocks, &MeshBlock::positions), 3);
  // XDMF Mixed connectivity, rank after rank: 4 a b c per triangle, then 5 a b c d per quad.
  std::vector<std::int64_t> connectivity;
  for (const auto& block : blocks) {
    for (std::size_t t = 0; t < block.triangles.size(); t += 3)
      connectivity.insert(connectivity.end(), {4, block.triangles[t], block.triangles[t + 1], block.triangles[t + 2]});
    for (std::size_t q = 0; q < block.quads.size(); q += 4)
      connectivity.insert(connectivity.end(),
                          {5, block.quads[q], block.quads[q + 1], block.quads[q + 2], block.quads[q + 3]});
    expected.elements += static_cast<std::int64_t>(block.triangles.size() / 3 + block.quads.size() / 4);
  }
  // Snapshot 1 reuses the cells written with snapshot 0.
  expected.connectivity = ints_dataset(step_group(step == 1 ? 0 : step) + "/topology/connectivity", connectivity);
  expected.attributes.push_back({"vertex_ids", "Node",
                                 ints_dataset(group + "/vertex_ids", gathered<std::int64_t>(blocks, &MeshBlock::vertex_ids))});
  expected.attributes.push_back({"displacement", "Node",
                                 doubles_dataset(group + "/node_fields/displacement",
                                                 gathered<double>(blocks, &MeshBlock::displacement), 3)});
  expected.attributes.push_back({"pressure", "Node",
                                 doubles_dataset(group + "/node_fields/pressure",
                                                 gathered<double>(blocks, &MeshBlock::pressure), 1)});
  expected.attributes.push_back({"thickness", "Cell",
                                 doubles_dataset(group + "/cell_fields/thickness",
                                                 gathered<double>(blocks, &MeshBlock::thickness), 1)});
  return expected;
}

// ---------------------------------------------------------------- reading back (rank 0, serial HDF5)

/// An HDF5 identifier closed at the end of scope; a negative id fails the read.
class Id {
 public:
  Id(hid_t id, herr_t (*closer)(hid_t), const std::string& what) : id_(id), closer_(closer) {
    if (id < 0) throw std::runtime_error("HDF5 could not open " + what);
  }
  ~Id() { closer_(id_); }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  [[nodiscard]] hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*closer_)(hid_t);
};

/// Silences HDF5's own printing of its error stack while a failure is provoked on purpose.
class QuietHdf5Errors {
 public:
  QuietHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
  return true;
}

double read_double_attribute(hid_t file, const std::string& object, const std::string& name) {
  const Id attribute(H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                     object + "@" + name);
  double value = 0.0;
  if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0) throw std::runtime_error("reading " + name);
  return value;
}

/// Checks one dataset of the file: its shape, its element type and every value, bit for bit.
void check_dataset(hid_t file, const ExpectedDataset& expected) {
  INFO("dataset " << expected.path);
  const Id dataset(H5Dopen2(file, expected.path.c_str(), H5P_DEFAULT), H5Dclose, expected.path);
  const Id space(H5Dget_space(dataset.get()), H5Sclose, expected.path + " dataspace");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  REQUIRE(rank == static_cast<int>(expected.dims.size()));
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  CHECK(std::vector<std::uint64_t>(dims.begin(), dims.end()) == expected.dims);

  const Id type(H5Dget_type(dataset.get()), H5Tclose, expected.path + " type");
  CHECK(H5Tget_class(type.get()) == (expected.integer ? H5T_INTEGER : H5T_FLOAT));
  CHECK(H5Tget_size(type.get()) == 8);
  CHECK(H5Tget_order(type.get()) == H5T_ORDER_LE);

  const auto count = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.get()));
  double unused = 0.0;  // HDF5 wants a buffer even for an empty dataset
  if (expected.integer) {
    std::vector<std::int64_t> values(count);
    void* buffer = count > 0 ? static_cast<void*>(values.data()) : &unused;
    REQUIRE(H5Dread(dataset.get(), H5T_NATIVE_INT64, space.get(), space.get(), H5P_DEFAULT, buffer) >= 0);
    CHECK(values == expected.ints);
  } else {
    std::vector<double> values(count);
    void* buffer = count > 0 ? static_cast<void*>(values.data()) : &unused;
    REQUIRE(H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, space.get(), space.get(), H5P_DEFAULT, buffer) >= 0);
    CHECK(same_bits(values, expected.doubles));
  }
}

void check_h5_file(const std::filesystem::path& h5, const std::vector<ExpectedStep>& steps) {
  const Id file(H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, h5.string());
  for (const auto& step : steps) {
    INFO("step group " << step.group);
    CHECK(std::bit_cast<std::uint64_t>(read_double_attribute(file.get(), step.group, "time")) ==
          std::bit_cast<std::uint64_t>(step.time));
    check_dataset(file.get(), step.geometry);
    if (step.connectivity) check_dataset(file.get(), *step.connectivity);
    for (const auto& attribute : step.attributes) check_dataset(file.get(), attribute.data);
  }
}

// ---------------------------------------------------------------- the independent Python check

nlohmann::json dataset_json(const ExpectedDataset& dataset) {
  nlohmann::json values = dataset.integer ? nlohmann::json(dataset.ints) : nlohmann::json(dataset.doubles);
  return {{"shape", dataset.dims}, {"values", values}};
}

/// The expected file read by check_field_series.py (format in its docstring).
void write_expected_json(const std::filesystem::path& path, const std::vector<ExpectedStep>& steps) {
  nlohmann::json all_steps = nlohmann::json::array();
  for (const auto& step : steps) {
    nlohmann::json attributes = nlohmann::json::object();
    for (const auto& attribute : step.attributes) {
      auto entry = dataset_json(attribute.data);
      entry["center"] = attribute.center;
      attributes[attribute.name] = entry;
    }
    nlohmann::json entry = {{"time", step.time},
                            {"topology", step.topology},
                            {"elements", step.elements},
                            {"geometry", dataset_json(step.geometry)},
                            {"attributes", attributes}};
    if (step.connectivity) entry["connectivity"] = dataset_json(*step.connectivity);
    all_steps.push_back(entry);
  }
  std::ofstream(path) << nlohmann::json{{"steps", all_steps}}.dump(1) << '\n';
}

/// Exit status of check_field_series.py on `xdmf` against `steps`.
int python_check(const std::filesystem::path& xdmf, const std::vector<ExpectedStep>& steps) {
  auto expected = xdmf;
  expected.replace_extension(".expected.json");
  write_expected_json(expected, steps);
  // TANKFSI_TEST_DATA is <source>/tests/data; the check lives beside it in tests/tools.
  const auto script = std::filesystem::path(TANKFSI_TEST_DATA).parent_path() / "tools" / "check_field_series.py";
  const char* python = std::getenv("TANKFSI_PYTHON");
  const std::string command = "'" + std::string(python != nullptr ? python : "/usr/bin/python3") + "' '" +
                              script.string() + "' '" + xdmf.string() + "' '" + expected.string() + "'";
  const int status = std::system(command.c_str());
  return status == -1 || !WIFEXITED(status) ? -1 : WEXITSTATUS(status);
}

void write_particle_snapshot(FieldSeriesWriter& writer, int step, double time) {
  const auto block = particle_block(world_rank(), world_size(), step);
  writer.write_particles(time, {block.ids, block.positions, particle_fields(block, step)});
}

std::string xdmf_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("particles and a deforming mesh round-trip through HDF5 and XDMF", "[hdf5]") {
  const int rank = world_rank();
  const int size = world_size();
  const tankfsi::testing::ScratchFolder folder(tankfsi::testing::ScratchFolder::Scope::shared);
  {
    FieldSeriesWriter fluid(MPI_COMM_WORLD, folder.path(), "fluid");
    FieldSeriesWriter wall(MPI_COMM_WORLD, folder.path(), "tank_wall");
    for (int step = 0; step < 3; ++step) {
      write_particle_snapshot(fluid, step, snapshot_times[static_cast<std::size_t>(step)]);

      const auto block = mesh_block(rank, size, step);
      CHECK(wall.first_vertex_index(2 * mesh_width(rank)) == mesh_first_vertex(rank));
      MeshSnapshot mesh{block.vertex_ids, block.positions, std::nullopt,
                        {{"displacement", 3, block.displacement}, {"pressure", 1, block.pressure}},
                        {{"thickness", 1, block.thickness}}};
      if (step != 1) mesh.cells = SurfaceCells{block.triangles, block.quads};
      wall.write_mesh(snapshot_times[static_cast<std::size_t>(step)], mesh);
    }
    CHECK(fluid.snapshot_count() == 3);
    CHECK(wall.snapshot_count() == 3);
    CHECK(fluid.xdmf_path() == folder.path() / "fluid.xdmf");
    CHECK(wall.h5_path() == folder.path() / "tank_wall.h5");
  }
  MPI_Barrier(MPI_COMM_WORLD);  // every rank has closed the files
  if (rank != 0) return;

  std::vector<ExpectedStep> particles, mesh;
  for (int step = 0; step < 3; ++step) {
    particles.push_back(expected_particle_step(step, size, snapshot_times[static_cast<std::size_t>(step)]));
    mesh.push_back(expected_mesh_step(step, size, snapshot_times[static_cast<std::size_t>(step)]));
  }
  if (size > 1) CHECK(particles[1].elements < particles[0].elements);  // the empty rank is in the test
  check_h5_file(folder.path() / "fluid.h5", particles);
  check_h5_file(folder.path() / "tank_wall.h5", mesh);
  CHECK_FALSE(std::filesystem::exists(folder.path() / "fluid.xdmf.tmp"));
  CHECK(xdmf_text(folder.path() / "fluid.xdmf").find("Value=\"0.30000000000000004\"") != std::string::npos);

  REQUIRE(python_check(folder.path() / "fluid.xdmf", particles) == 0);
  REQUIRE(python_check(folder.path() / "tank_wall.xdmf", mesh) == 0);
}

TEST_CASE("append continues a series, truncate starts it anew", "[hdf5]") {
  const int size = world_size();
  const tankfsi::testing::ScratchFolder folder(tankfsi::testing::ScratchFolder::Scope::shared);
  {
    FieldSeriesWriter first_run(MPI_COMM_WORLD, folder.path(), "fluid", FileMode::append);  // no file yet: made
    CHECK(first_run.snapshot_count() == 0);
    write_particle_snapshot(first_run, 0, snapshot_times[0]);
    write_particle_snapshot(first_run, 1, snapshot_times[1]);
  }
  {
    FieldSeriesWriter continued(MPI_COMM_WORLD, folder.path(), "fluid", FileMode::append);
    CHECK(continued.snapshot_count() == 2);
    REQUIRE_THROWS_AS(write_particle_snapshot(continued, 2, snapshot_times[0]), std::invalid_argument);
    write_particle_snapshot(continued, 2, snapshot_times[2]);
    CHECK(continued.snapshot_count() == 3);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) {
    std::vector<ExpectedStep> steps;
    for (int step = 0; step < 3; ++step)
      steps.push_back(expected_particle_step(step, size, snapshot_times[static_cast<std::size_t>(step)]));
    check_h5_file(folder.path() / "fluid.h5", steps);
    REQUIRE(python_check(folder.path() / "fluid.xdmf", steps) == 0);
  }
  {
    FieldSeriesWriter new_run(MPI_COMM_WORLD, folder.path(), "fluid", FileMode::truncate);
    CHECK(new_run.snapshot_count() == 0);
    write_particle_snapshot(new_run, 2, 7.5);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) {
    auto only = expected_particle_step(2, size, 7.5);
    REQUIRE(python_check(folder.path() / "fluid.xdmf", {only}) == 0);
  }
}

TEST_CASE("bad snapshots throw on every rank and leave the series intact", "[hdf5]") {
  const int rank = world_rank();
  const int size = world_size();
  const tankfsi::testing::ScratchFolder folder(tankfsi::testing::ScratchFolder::Scope::shared);
  const std::string last_rank = "(on rank " + std::to_string(size - 1) + ")";

  REQUIRE_THROWS_AS(FieldSeriesWriter(MPI_COMM_WORLD, folder.path() / "missing", "fluid"), std::invalid_argument);
  REQUIRE_THROWS_AS(FieldSeriesWriter(MPI_COMM_WORLD, folder.path(), "a/b"), std::invalid_argument);

  FieldSeriesWriter fluid(MPI_COMM_WORLD, folder.path(), "fluid");
  auto block = particle_block(rank, size, 0);
  auto fields = particle_fields(block, 0);
  // Only the last rank gets it wrong; every rank must throw, naming that rank.
  if (rank == size - 1) fields[1].values = fields[1].values.first(fields[1].values.size() - 1);
  REQUIRE_THROWS_WITH(fluid.write_particles(0.0, {block.ids, block.positions, fields}), Catch::Contains(last_rank));
  fields = particle_fields(block, 0);
  if (rank == size - 1) fields[0].name = size > 1 ? "speed" : "bad name";  // names must agree across ranks
  REQUIRE_THROWS_AS(fluid.write_particles(0.0, {block.ids, block.positions, fields}), std::invalid_argument);
  fields = particle_fields(block, 0);
  fields[0].components = 2;
  REQUIRE_THROWS_AS(fluid.write_particles(0.0, {block.ids, block.positions, fields}), std::invalid_argument);
  fields = particle_fields(block, 0);
  fields.push_back({"ids", 1, block.pressure});  // the writer's own name
  REQUIRE_THROWS_AS(fluid.write_particles(0.0, {block.ids, block.positions, fields}), std::invalid_argument);
  CHECK(fluid.snapshot_count() == 0);

  write_particle_snapshot(fluid, 0, 1.0);
  REQUIRE_THROWS_AS(write_particle_snapshot(fluid, 1, 1.0), std::invalid_argument);  // time must increase
  const auto mesh = mesh_block(rank, size, 0);
  REQUIRE_THROWS_AS(fluid.write_mesh(2.0, {mesh.vertex_ids, mesh.positions, SurfaceCells{mesh.triangles, mesh.quads},
                                           {}, {}}),
                    std::invalid_argument);  // a series holds one kind
  CHECK(fluid.snapshot_count() == 1);

  FieldSeriesWriter wall(MPI_COMM_WORLD, folder.path(), "wall");
  REQUIRE_THROWS_AS(wall.write_mesh(0.0, {mesh.vertex_ids, mesh.positions, std::nullopt, {}, {}}),
                    std::invalid_argument);  // no cells to reuse yet
  auto out_of_range = mesh.quads;
  if (rank == 0) out_of_range[0] = 1'000'000;
  REQUIRE_THROWS_WITH(
      wall.write_mesh(0.0, {mesh.vertex_ids, mesh.positions, SurfaceCells{mesh.triangles, out_of_range}, {}, {}}),
      Catch::Contains("outside the file's"));
  REQUIRE_THROWS_AS(wall.write_mesh(0.0, {mesh.vertex_ids, mesh.positions, SurfaceCells{mesh.triangles, mesh.quads},
                                          {}, {{"thickness", 1, mesh.pressure}}}),
                    std::invalid_argument);  // a cell field with one value per vertex
  wall.write_mesh(0.0, {mesh.vertex_ids, mesh.positions, SurfaceCells{mesh.triangles, mesh.quads}, {}, {}});
  const auto fewer = std::span<const std::int64_t>(mesh.vertex_ids).first(mesh.vertex_ids.size() - 1);
  REQUIRE_THROWS_AS(
      wall.write_mesh(1.0, {fewer, std::span<const double>(mesh.positions).first(3 * fewer.size()), std::nullopt,
                            {}, {}}),
      std::invalid_argument);  // reused cells need the same owned vertices
  CHECK(wall.snapshot_count() == 1);
}

TEST_CASE("Hdf5File writes rank blocks, empty blocks and attributes collectively", "[hdf5]") {
  const int rank = world_rank();
  const int size = world_size();
  const tankfsi::testing::ScratchFolder folder(tankfsi::testing::ScratchFolder::Scope::shared);
  const auto path = folder.path() / "blocks.h5";

  {
    const QuietHdf5Errors quiet;
    REQUIRE_THROWS_WITH(Hdf5File(MPI_COMM_WORLD, folder.path() / "missing" / "x.h5", FileMode::truncate),
                        Catch::Contains("H5Fcreate") && Catch::Contains("missing/x.h5"));
  }
  {
    Hdf5File file(MPI_COMM_WORLD, path, FileMode::truncate);
    // Rank r holds r rows: rank 0 none.
    std::vector<std::int64_t> ints(static_cast<std::size_t>(rank), 10 * rank);
    const auto block = file.write_distributed_1d("/a/b/ints", ints);
    CHECK(block.first == rank * (rank - 1) / 2);
    CHECK(block.local == rank);
    CHECK(block.total == size * (size - 1) / 2);
    std::vector<double> rows(static_cast<std::size_t>(2 * (rank + 1)), rank + 0.5);
    CHECK(file.write_distributed_2d("/rows", rows, 2).total == size * (size + 1) / 2);
    CHECK(file.write_distributed_2d("/nothing", std::span<const double>(), 3).total == 0);
    REQUIRE_THROWS_AS(file.write_distributed_2d("/ragged", std::span<const double>(rows).first(rank == 0 ? 1 : 2), 2),
                      std::invalid_argument);
    file.create_group("/g/h");
    file.write_attribute("/g/h", "x", 0.1);
    file.write_attribute("/g/h", "n", std::int64_t{-3});
    file.write_attribute("/g/h", "s", std::string("tank wall"));
    file.write_attribute("/g/h", "s", std::string("replaced"));
    CHECK(file.read_string_attribute("/g/h", "s") == "replaced");
    CHECK(file.has_attribute("/g/h", "x"));
    CHECK_FALSE(file.has_attribute("/g/h", "y"));
    CHECK(file.group_members("/") == std::vector<std::string>{"a", "g", "nothing", "rows"});
    file.flush();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank != 0) return;
  std::vector<std::int64_t> ints;
  std::vector<double> rows;
  for (int r = 0; r < size; ++r) {
    ints.insert(ints.end(), static_cast<std::size_t>(r), 10 * r);
    rows.insert(rows.end(), static_cast<std::size_t>(2 * (r + 1)), r + 0.5);
  }
  const Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, path.string());
  check_dataset(file.get(), ints_dataset("/a/b/ints", ints));
  check_dataset(file.get(), doubles_dataset("/rows", rows, 2));
  check_dataset(file.get(), {"/nothing", {0, 3}, {}, {}, false});
  CHECK(read_double_attribute(file.get(), "/g/h", "x") == 0.1);
}
