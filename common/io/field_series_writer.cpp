#include "common/io/field_series_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "common/parallel/collective.hpp"
#include "common/io/exact_number.hpp"
#include "common/io/xdmf_grid_json.hpp"

namespace tankfsi {

namespace {

constexpr const char* step_prefix = "step_";
constexpr const char* grid_record_attribute = "xdmf_grid";
// The datasets (and XDMF attributes) of the points' own ids: no field may take these names.
constexpr const char* particle_ids_name = "ids";
constexpr const char* vertex_ids_name = "vertex_ids";

/// Names become HDF5 link names, XML attribute values and file names: a
/// plain alphabet keeps them valid and unambiguous in all three.
std::string name_problem(const std::string& what, const std::string& name) {
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  const auto plain = [&](char c) { return letter(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; };
  const bool starts_well = !name.empty() && letter(name[0]);
  if (starts_well && std::all_of(name.begin(), name.end(), plain)) return {};
  return what + " name '" + name + "' must start with a letter or '_' and hold only letters, digits, '_', '-', '.'";
}

std::string step_group(std::int64_t step) {
  char text[32];
  std::snprintf(text, sizeof text, "/%s%07lld", step_prefix, static_cast<long long>(step));
  return text;
}

/// The step number of a root member named like step_group(), if it is one.
std::optional<std::int64_t> step_number(const std::string& member) {
  const std::string prefix = step_prefix;
  if (member.size() <= prefix.size() || member.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  std::int64_t step = 0;
  const auto* end = member.data() + member.size();
  const auto [ptr, error] = std::from_chars(member.data() + prefix.size(), end, step);
  if (error != std::errc() || ptr != end) return std::nullopt;
  return step;
}

const char* kind_text(bool mesh) { return mesh ? "mesh" : "particles"; }

/// Problems of one list of fields of `rows` rows each; `reserved` is a name
/// the writer itself gives an attribute of the same centering.
std::string fields_problem(std::span<const NamedField> fields, std::int64_t rows, const std::string& what,
                           const std::string& reserved) {
  std::set<std::string> seen;
  for (const auto& field : fields) {
    if (auto problem = name_problem(what, field.name); !problem.empty()) return problem;
    if (field.name == reserved) return what + " name '" + reserved + "' is taken by the writer's own ids";
    if (!seen.insert(field.name).second) return what + " '" + field.name + "' is given twice";
    if (field.components != 1 && field.components != 3)
      return what + " '" + field.name + "' has " + std::to_string(field.components) +
             " components; 1 (scalar) or 3 (vector) are written";
    const auto expected = static_cast<std::size_t>(rows) * static_cast<std::size_t>(field.components);
    if (field.values.size() != expected)
      return what + " '" + field.name + "' has " + std::to_string(field.values.size()) + " values, not " +
             std::to_string(expected) + " (" + std::to_string(rows) + " rows × " +
             std::to_string(field.components) + ")";
  }
  return {};
}

/// What must be equal on all ranks for a collective write of the fields.
std::string fields_signature(std::span<const NamedField> fields) {
  std::string signature;
  for (const auto& field : fields) signature += field.name + ":" + std::to_string(field.components) + ",";
  return signature;
}

std::string positions_problem(std::span<const double> positions, std::size_t id_count, const std::string& ids) {
  if (positions.size() % 3 != 0)
    return std::to_string(positions.size()) + " position values are not whole rows of (x, y, z)";
  if (positions.size() / 3 != id_count)
    return std::to_string(positions.size() / 3) + " positions but " + std::to_string(id_count) + " " + ids;
  return {};
}

std::string cells_problem(const SurfaceCells& cells, std::int64_t total_vertices) {
  if (cells.triangles.size() % 3 != 0)
    return std::to_string(cells.triangles.size()) + " triangle indices are not whole triangles of 3";
  if (cells.quads.size() % 4 != 0)
    return std::to_string(cells.quads.size()) + " quadrilateral indices are not whole quadrilaterals of 4";
  for (const auto& list : {cells.triangles, cells.quads})
    for (const auto index : list)
      if (index < 0 || index >= total_vertices)
        return "a cell names vertex " + std::to_string(index) + ", outside the file's " +
               std::to_string(total_vertices) + " vertices";
  return {};
}

/// True on the ranks whose `text` differs from rank 0's.
bool differs_from_rank0(MPI_Comm comm, const std::string& text) { return broadcast_text(comm, text) != text; }

std::filesystem::path checked_h5_path(MPI_Comm comm, const std::filesystem::path& folder, const std::string& name) {
  std::string problem = name_problem("series", name);
  std::error_code unreadable;  // not the throwing overload: a throw on one rank alone would hang the others
  if (problem.empty() && !std::filesystem::is_directory(folder, unreadable))
    problem = "output folder " + folder.string() + " does not exist";
  throw_if_any_rank_failed(comm, "opening field series", problem);
  return folder / (name + ".h5");
}

}  // namespace

FieldSeriesWriter::FieldSeriesWriter(MPI_Comm comm, const std::filesystem::path& folder, const std::string& name,
                                     FileMode mode, std::optional<double> keep_until)
    : name_(name), xdmf_path_(folder / (name + ".xdmf")), file_(comm, checked_h5_path(comm, folder, name), mode) {
  if (mode == FileMode::read) throw std::invalid_argument("FieldSeriesWriter: a series is written, not read");
  if (mode == FileMode::append) resume_from_file(keep_until);
}

std::int64_t FieldSeriesWriter::first_vertex_index(std::int64_t owned_vertices) const {
  return rank_order_rows(file_.comm(), owned_vertices).first;
}

void FieldSeriesWriter::write_particles(double time, const ParticleSnapshot& snapshot) {
  const auto rows = static_cast<std::int64_t>(snapshot.ids.size());
  std::string problem = positions_problem(snapshot.positions, snapshot.ids.size(), "ids");
  if (problem.empty()) problem = fields_problem(snapshot.fields, rows, "particle field", particle_ids_name);
  check_snapshot(time, Kind::particles, problem, fields_signature(snapshot.fields));

  const auto group = begin_step(time, Kind::particles);
  auto grid = write_points(group, time, particle_ids_name, snapshot.ids, snapshot.positions);
  grid.topology = {XdmfTopologyType::polyvertex, grid.geometry.dimensions[0], std::nullopt};
  write_fields(group + "/fields", snapshot.fields, XdmfCenter::node, grid.attributes);
  finish_step(group, std::move(grid));
}

void FieldSeriesWriter::write_mesh(double time, const MeshSnapshot& snapshot) {
  const auto local_vertices = static_cast<std::int64_t>(snapshot.vertex_ids.size());
  const auto vertices = rank_order_rows(file_.comm(), local_vertices);

  std::string problem = positions_problem(snapshot.positions, snapshot.vertex_ids.size(), "vertex ids");
  std::int64_t local_cells = 0;
  if (problem.empty()) {
    if (snapshot.cells) {
      problem = cells_problem(*snapshot.cells, vertices.total);
      local_cells =
          static_cast<std::int64_t>(snapshot.cells->triangles.size() / 3 + snapshot.cells->quads.size() / 4);
    } else if (!cells_) {
      problem = "no cells to reuse: the first mesh snapshot (and the first after reopening a series) must carry cells";
    } else if (local_vertices != cells_->local_vertices) {
      problem = "reusing the cells needs the " + std::to_string(cells_->local_vertices) +
                " owned vertices they were written with, not " + std::to_string(local_vertices);
    } else {
      local_cells = cells_->local_cells;
    }
  }
  if (problem.empty()) problem = fields_problem(snapshot.node_fields, local_vertices, "node field", vertex_ids_name);
  if (problem.empty()) problem = fields_problem(snapshot.cell_fields, local_cells, "cell field", "");
  check_snapshot(time, Kind::mesh, problem,
                 std::string(snapshot.cells ? "new cells" : "same cells") + "|" +
                     fields_signature(snapshot.node_fields) + "|" + fields_signature(snapshot.cell_fields));

  const auto group = begin_step(time, Kind::mesh);
  if (snapshot.cells) cells_ = write_cells(group, *snapshot.cells, local_vertices);
  auto grid = write_points(group, time, vertex_ids_name, snapshot.vertex_ids, snapshot.positions);
  grid.topology = cells_->topology;
  write_fields(group + "/node_fields", snapshot.node_fields, XdmfCenter::node, grid.attributes);
  write_fields(group + "/cell_fields", snapshot.cell_fields, XdmfCenter::cell, grid.attributes);
  finish_step(group, std::move(grid));
}

void FieldSeriesWriter::check_snapshot(double time, Kind kind, const std::string& local_problem,
                                       const std::string& layout_signature) const {
  std::string problem = local_problem;
  if (problem.empty() && !std::isfinite(time)) problem = "time " + exact_text(time) + " is not finite";
  if (problem.empty() && kind_ != Kind::none && kind != kind_)
    problem = std::string("the series holds ") + kind_text(kind_ == Kind::mesh) + ", not " +
              kind_text(kind == Kind::mesh);
  if (problem.empty() && !grids_.empty() && !(time > grids_.back().time))
    problem = "time " + exact_text(time) + " does not follow the last snapshot's time " +
              exact_text(grids_.back().time);
  // Every rank must make the same collective calls: same time, same fields.
  const auto signature = "time " + exact_text(time) + "|" + layout_signature;
  if (differs_from_rank0(file_.comm(), signature) && problem.empty())
    problem = "time or fields differ from rank 0's: " + signature;
  throw_if_any_rank_failed(file_.comm(), "writing a snapshot of " + file_.path().string(), problem);
}

std::string FieldSeriesWriter::begin_step(double time, Kind kind) {
  // The step number is used up even if writing fails, so a retry never meets a half-written group.
  const auto group = step_group(next_step_++);
  kind_ = kind;
  file_.create_group(group);
  file_.write_attribute(group, "time", time);
  file_.write_attribute(group, "kind", std::string(kind_text(kind == Kind::mesh)));
  return group;
}

XdmfGrid FieldSeriesWriter::write_points(const std::string& group, double time, const std::string& ids_name,
                                         std::span<const std::int64_t> ids, std::span<const double> positions) {
  XdmfGrid grid;
  grid.name = group.substr(1);
  grid.time = time;
  const auto points = file_.write_distributed_2d(group + "/position", positions, 3);
  grid.geometry = {group + "/position", {points.total, 3}, XdmfNumber::float64};
  file_.write_distributed_1d(group + "/" + ids_name, ids);
  grid.attributes.push_back({ids_name, XdmfCenter::node, {group + "/" + ids_name, {points.total}, XdmfNumber::int64}});
  return grid;
}

void FieldSeriesWriter::write_fields(const std::string& group, std::span<const NamedField> fields, XdmfCenter center,
                                     std::vector<XdmfAttribute>& attributes) {
  for (const auto& field : fields) {
    const auto dataset = group + "/" + field.name;
    if (field.components == 1) {
      const auto rows = file_.write_distributed_1d(dataset, field.values);
      attributes.push_back({field.name, center, {dataset, {rows.total}, XdmfNumber::float64}});
    } else {
      const auto rows = file_.write_distributed_2d(dataset, field.values, 3);
      attributes.push_back({field.name, center, {dataset, {rows.total, 3}, XdmfNumber::float64}});
    }
  }
}

FieldSeriesWriter::WrittenCells FieldSeriesWriter::write_cells(const std::string& group, const SurfaceCells& cells,
                                                               std::int64_t local_vertices) {
  std::vector<std::int64_t> connectivity;
  connectivity.reserve(cells.triangles.size() / 3 * 4 + cells.quads.size() / 4 * 5);
  const auto append = [&](std::span<const std::int64_t> indices, std::size_t per_cell, std::int64_t type_code) {
    for (std::size_t first = 0; first < indices.size(); first += per_cell) {
      const auto cell = indices.subspan(first, per_cell);
      connectivity.push_back(type_code);
      connectivity.insert(connectivity.end(), cell.begin(), cell.end());
    }
  };
  append(cells.triangles, 3, xdmf_triangle_code);
  append(cells.quads, 4, xdmf_quadrilateral_code);
  const auto dataset = group + "/topology/connectivity";
  const auto length = file_.write_distributed_1d(dataset, connectivity);
  WrittenCells written;
  written.local_vertices = local_vertices;
  written.local_cells = static_cast<std::int64_t>(cells.triangles.size() / 3 + cells.quads.size() / 4);
  const auto total_cells = rank_order_rows(file_.comm(), written.local_cells).total;
  written.topology = {XdmfTopologyType::mixed, total_cells, XdmfDataItem{dataset, {length.total}, XdmfNumber::int64}};
  return written;
}

void FieldSeriesWriter::finish_step(const std::string& group, XdmfGrid grid) {
  // Written last: a step group without its record is a snapshot cut short, which resuming skips.
  file_.write_attribute(group, grid_record_attribute, xdmf_grid_to_json(grid));
  grids_.push_back(std::move(grid));
  publish_xdmf();
}

void FieldSeriesWriter::publish_xdmf() {
  // The data must be on disk before the XDMF names it.
  file_.flush();
  int rank = 0;
  MPI_Comm_rank(file_.comm(), &rank);
  std::string problem;
  if (rank == 0) {
    try {
      replace_file_atomically(xdmf_path_, xdmf_document(name_, file_.path().filename().string(), grids_));
    } catch (const std::exception& error) {
      problem = error.what();
    }
  }
  // Rank 0 alone writes the XDMF, but all ranks must learn that it failed, or they would run on without it.
  if (const auto failure = first_problem_on_any_rank(file_.comm(), problem); !failure.empty())
    throw std::runtime_error("writing " + xdmf_path_.string() + ": " + failure);
}

void FieldSeriesWriter::resume_from_file(std::optional<double> keep_until) {
  std::vector<std::pair<std::int64_t, std::string>> steps;
  for (const auto& member : file_.group_members("/"))
    if (const auto step = step_number(member)) steps.emplace_back(*step, "/" + member);
  std::sort(steps.begin(), steps.end());
  for (const auto& [step, group] : steps) {
    if (keep_until && (!file_.has_attribute(group, "time") || file_.read_double_attribute(group, "time") > *keep_until)) {
      file_.remove(group);  // the step number is free again: no gap in the names
      continue;
    }
    next_step_ = step + 1;
    if (!file_.has_attribute(group, grid_record_attribute)) continue;  // cut short: never in the XDMF
    grids_.push_back(xdmf_grid_from_json(file_.read_string_attribute(group, grid_record_attribute)));
    kind_ = file_.read_string_attribute(group, "kind") == "mesh" ? Kind::mesh : Kind::particles;
  }
  // Restores the XDMF too if it was lost, and drops from it any snapshot the file does not complete.
  if (!grids_.empty() || keep_until) publish_xdmf();
}

}  // namespace tankfsi
