#include "sph_solver/neighbours/cell_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tankfsi::sph {

namespace {

// Beyond this spread (in search radii) the cell coordinates would lose the exactness
// the margin below relies on; no live simulation gets near it.
constexpr double largest_spread_in_radii = 1099511627776.0;  // 2^40

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument("cell list: " + message);
}

}  // namespace

CellList::CellList(int dimension) : dimension_(dimension) {
  require(dimension == 2 || dimension == 3, "dimension must be 2 or 3, got " + std::to_string(dimension));
}

void CellList::build(std::span<const Eigen::Vector3d> points, double radius) {
  require(std::isfinite(radius) && radius > 0.0, "search radius must be positive and finite");
  require(points.size() < static_cast<std::size_t>(std::numeric_limits<int>::max()), "too many points");
  const int count = static_cast<int>(points.size());
  const auto axes = static_cast<Eigen::Index>(dimension_);

  // 1. Bounding box of the points, checked on the way.
  Eigen::Vector3d lower = Eigen::Vector3d::Zero();
  Eigen::Vector3d upper = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d& x = points[at(i)];
    require(x.allFinite(), "point " + std::to_string(i) + " has a coordinate that is not finite");
    require(dimension_ == 3 || x.z() == 0.0, "point " + std::to_string(i) + " of a 2D search has z != 0");
    if (i == 0) {
      lower = x;
      upper = x;
    } else {
      lower = lower.cwiseMin(x);
      upper = upper.cwiseMax(x);
    }
  }
  double spread = 0.0;
  for (Eigen::Index axis = 0; axis < axes; ++axis) spread = std::max(spread, upper[axis] - lower[axis]);
  const double spread_in_radii = spread / radius;
  require(spread_in_radii <= largest_spread_in_radii,
          "the points spread over more than 2^40 search radii (has the run blown up?)");

  // 2. Cell size. The computed cell coordinate floor((x - lower) / cell_size) carries a
  // rounding error of at most ~2 eps times the largest quotient Q ~ spread_in_radii.
  // Two points closer than the radius along an axis differ by less than
  // radius / cell_size in exact quotients; enlarging the cell by
  // 1 + 16 eps Q keeps the computed difference below 1, so they are at most one cell apart.
  radius_ = radius;
  radius_squared_ = radius * radius;
  cell_size_ = radius * (1.0 + 1e-12 + 16.0 * std::numeric_limits<double>::epsilon() * spread_in_radii);

  // 3. Occupied cells, numbered in order of first appearance, and their point counts.
  cell_index_.clear();
  cell_of_point_.resize(at(count));
  std::vector<CellCoordinates> cells_by_appearance;
  std::vector<int> points_per_cell;
  for (int i = 0; i < count; ++i) {
    CellCoordinates cell{0, 0, 0};
    for (Eigen::Index axis = 0; axis < axes; ++axis) {
      cell[static_cast<std::size_t>(axis)] =
          static_cast<std::int64_t>(std::floor((points[at(i)][axis] - lower[axis]) / cell_size_));
    }
    const int index = cell_index_.find_or_insert(cell, static_cast<int>(cells_by_appearance.size()));
    if (index == static_cast<int>(cells_by_appearance.size())) {
      cells_by_appearance.push_back(cell);
      points_per_cell.push_back(0);
    }
    ++points_per_cell[at(index)];
    cell_of_point_[at(i)] = index;
  }
  const int cells = static_cast<int>(cells_by_appearance.size());

  // 4. Z-order of the occupied cells (a sort of the cells, not of the points: there
  // are several points per cell). rank[appearance index] = Z-order index.
  std::vector<int> by_z_order(at(cells));
  std::iota(by_z_order.begin(), by_z_order.end(), 0);
  std::sort(by_z_order.begin(), by_z_order.end(), [&](int a, int b) {
    return morton_less(cells_by_appearance[at(a)], cells_by_appearance[at(b)]);
  });
  std::vector<int> rank(at(cells));
  cell_coordinates_.resize(at(cells));
  cell_begin_.assign(at(cells) + 1, 0);
  for (int c = 0; c < cells; ++c) {
    rank[at(by_z_order[at(c)])] = c;
    cell_coordinates_[at(c)] = cells_by_appearance[at(by_z_order[at(c)])];
    cell_begin_[at(c) + 1] = cell_begin_[at(c)] + points_per_cell[at(by_z_order[at(c)])];
  }

  // 5. Counting sort of the points by cell: stable, so a cell's points keep index order.
  std::vector<int> next_position(cell_begin_.begin(), cell_begin_.end() - 1);
  sorted_points_.resize(at(count));
  sorted_to_original_.resize(at(count));
  original_to_sorted_.resize(at(count));
  for (int i = 0; i < count; ++i) {
    const int cell = rank[at(cell_of_point_[at(i)])];
    cell_of_point_[at(i)] = cell;
    const int position = next_position[at(cell)]++;
    sorted_points_[at(position)] = points[at(i)];
    sorted_to_original_[at(position)] = i;
    original_to_sorted_[at(i)] = position;
  }

  // 6. The occupied cells around each cell (3x3 in 2D, 3x3x3 in 3D), ascending so a
  // search walks the sorted points forwards.
  const int z_reach = dimension_ == 3 ? 1 : 0;
  adjacent_cell_begin_.assign(1, 0);
  adjacent_cells_.clear();
  for (int c = 0; c < cells; ++c) {
    const std::size_t first = adjacent_cells_.size();
    const CellCoordinates& centre = cell_coordinates_[at(c)];
    for (int dz = -z_reach; dz <= z_reach; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int found = cell_index_.find({centre[0] + dx, centre[1] + dy, centre[2] + dz});
          if (found >= 0) adjacent_cells_.push_back(rank[at(found)]);
        }
      }
    }
    std::sort(adjacent_cells_.begin() + static_cast<std::ptrdiff_t>(first), adjacent_cells_.end());
    adjacent_cell_begin_.push_back(static_cast<int>(adjacent_cells_.size()));
  }
}

NeighbourList CellList::neighbour_list(const Kernel* kernel, int rows) const {
  NeighbourList list = neighbour_rows(rows, true);
  if (kernel != nullptr) add_kernel_values(list, *kernel);
  return list;
}

NeighbourList CellList::neighbour_indices(int rows) const { return neighbour_rows(rows, false); }

NeighbourList CellList::neighbour_rows(int rows, bool with_distances) const {
  require(rows <= point_count(), "more rows asked for than there are points");
  return with_distances ? gather_rows<true>(rows < 0 ? point_count() : rows)
                        : gather_rows<false>(rows < 0 ? point_count() : rows);
}

// Every point of the cells around i is written to the list and kept (the count
// advanced) only when it is a neighbour: the support's share of the cells around
// is a third in 2D and a sixth in 3D, in no order a branch predictor could learn,
// so the test is arithmetic, not a branch.
// The squared distances are kept and their roots taken in one pass at the end.
template <bool with_distances>
NeighbourList CellList::gather_rows(int row_count) const {
  NeighbourList list;
  list.offsets.reserve(at(row_count) + 1);
  list.offsets.push_back(0);
  std::size_t used = 0;
  const auto make_room = [&](std::size_t more) {
    if (list.indices.size() >= used + more) return;
    const std::size_t size = std::max(2 * list.indices.size(), used + more);
    list.indices.resize(size);
    if constexpr (with_distances) list.distances.resize(size);
  };
  for (int i = 0; i < row_count; ++i) {
    const int own_position = original_to_sorted_[at(i)];
    const Eigen::Vector3d x_i = sorted_points_[at(own_position)];
    const int cell = cell_of_point_[at(i)];
    const int first_adjacent = adjacent_cell_begin_[at(cell)];
    const int end_adjacent = adjacent_cell_begin_[at(cell) + 1];
    std::size_t candidates = 0;
    for (int a = first_adjacent; a < end_adjacent; ++a) {
      const int adjacent = adjacent_cells_[at(a)];
      candidates += at(cell_begin_[at(adjacent) + 1] - cell_begin_[at(adjacent)]);
    }
    make_room(candidates);
    int* const indices = list.indices.data();
    double* const squared = with_distances ? list.distances.data() : nullptr;
    for (int a = first_adjacent; a < end_adjacent; ++a) {
      const int adjacent = adjacent_cells_[at(a)];
      for (int position = cell_begin_[at(adjacent)]; position < cell_begin_[at(adjacent) + 1]; ++position) {
        const double r_squared = (x_i - sorted_points_[at(position)]).squaredNorm();
        indices[used] = sorted_to_original_[at(position)];
        if constexpr (with_distances) squared[used] = r_squared;
        used += static_cast<std::size_t>((r_squared < radius_squared_) & (position != own_position));
      }
    }
    list.offsets.push_back(static_cast<int>(used));
  }
  list.indices.resize(used);
  if constexpr (with_distances) {
    list.distances.resize(used);
    for (double& r : list.distances) r = std::sqrt(r);
  }
  return list;
}

CellCoordinates CellList::cell_of(int i) const {
  require(i >= 0 && i < point_count(), "point index out of range");
  return cell_coordinates_[at(cell_of_point_[at(i)])];
}

}  // namespace tankfsi::sph
