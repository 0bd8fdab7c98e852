#pragma once
// CellList: fixed-radius neighbour search by linked cells (Hockney & Eastwood 1988,
// "Computer Simulation Using Particles"; Allen & Tildesley 2017, "Computer Simulation
// of Liquids", ch. 5),
// rebuilt from scratch by every build() in O(N) expected time.
//
// Space is cut into square (2D) or cubic (3D) cells of edge >= the search radius,
// counted from the lower corner of the points' bounding box, so a neighbour of a
// point lies in its own cell or one of the 8 (2D) / 26 (3D) around it. Only occupied
// cells exist (hashed, see CellIndexMap): memory grows with the number of points,
// never with the size of the bounding box. Occupied cells are numbered in Z-order
// and the points are stored cell after cell in that order, so the points a search
// visits are contiguous in memory; cell_order() gives that order to the solver,
// which keeps its particles sorted the same way.
//
// Neighbour criterion: j != i and |x_i - x_j|^2 < radius^2 (a point exactly at the
// radius is not a neighbour, as W vanishes there; coincident points are neighbours).
#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "sph_solver/neighbours/cell_coordinates.hpp"
#include "sph_solver/neighbours/cell_index_map.hpp"
#include "sph_solver/kernels/kernel.hpp"
#include "sph_solver/neighbours/neighbour_list.hpp"

namespace tankfsi::sph {

class CellList {
 public:
  /// Throws std::invalid_argument unless dimension is 2 or 3. In 2D the points lie in z = 0.
  explicit CellList(int dimension);

  /// Sorts the points into cells for searches within radius. The points are copied:
  /// the span need not outlive the call. Throws std::invalid_argument if radius is not
  /// positive and finite, a coordinate is not finite, a 2D point has z != 0, or the
  /// points spread over more than 2^40 radii (only a run that has already blown up does).
  void build(std::span<const Eigen::Vector3d> points, double radius);

  /// The neighbours of points 0 .. rows-1 (all points when rows < 0), rows in point
  /// order, each row in cell order (cells ascending in Z-order, a cell's points in
  /// index order), with each pair's distance and, given a kernel, its value and
  /// slope there. A solver asks only for the rows of its own particles: its ghosts
  /// are neighbours, never rows.
  [[nodiscard]] NeighbourList neighbour_list(const Kernel* kernel = nullptr, int rows = -1) const;

  /// The same rows with the neighbours' indices only (no distances): what a
  /// Verlet list of candidates keeps (NeighbourCandidates).
  [[nodiscard]] NeighbourList neighbour_indices(int rows = -1) const;

  /// The points' indices sorted by cell (cells in Z-order, points of a cell by index):
  /// order[k] is the index of the point that comes k-th. A permutation of 0 .. N-1.
  [[nodiscard]] const std::vector<int>& cell_order() const { return sorted_to_original_; }

  /// The cell holding point i.
  [[nodiscard]] CellCoordinates cell_of(int i) const;

  [[nodiscard]] int dimension() const { return dimension_; }
  [[nodiscard]] int point_count() const { return static_cast<int>(sorted_to_original_.size()); }
  [[nodiscard]] int cell_count() const { return static_cast<int>(cell_coordinates_.size()); }
  [[nodiscard]] double radius() const { return radius_; }
  /// Edge of a cell: the radius enlarged by a few rounding errors, see build().
  [[nodiscard]] double cell_size() const { return cell_size_; }

 private:
  static std::size_t at(int index) { return static_cast<std::size_t>(index); }
  [[nodiscard]] NeighbourList neighbour_rows(int rows, bool with_distances) const;
  template <bool with_distances>
  [[nodiscard]] NeighbourList gather_rows(int row_count) const;

  int dimension_;
  double radius_ = 0.0;
  double radius_squared_ = 0.0;
  double cell_size_ = 0.0;
  CellIndexMap cell_index_;                 ///< cell -> index in order of first appearance
  std::vector<Eigen::Vector3d> sorted_points_;  ///< positions in cell order
  std::vector<int> sorted_to_original_;     ///< cell_order()
  std::vector<int> original_to_sorted_;
  std::vector<int> cell_of_point_;          ///< Z-order cell index of each point (original indexing)
  std::vector<int> cell_begin_;             ///< points of cell c: sorted positions cell_begin_[c] .. [c+1)
  std::vector<CellCoordinates> cell_coordinates_;  ///< by Z-order cell index
  std::vector<int> adjacent_cell_begin_;    ///< occupied cells around cell c (itself included):
  std::vector<int> adjacent_cells_;         ///< adjacent_cells_[adjacent_cell_begin_[c] .. [c+1)), ascending
};

}  // namespace tankfsi::sph
