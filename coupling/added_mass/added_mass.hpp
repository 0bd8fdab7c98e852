#pragma once
// The liquid's added-mass operator on the interface (METHOD.md §4, beyond the
// paper; PROTOCOL.md, "Added mass").
//
// A thin wall in heavy liquid meets the liquid's inertia as an added mass far
// above its own; a staggered scheme hands that inertia to the structure a
// window late, and the wall's acceleration then grows from window to window
// (Causin, Gerbeau & Nobile 2005). The remedy of added-mass partitioned
// schemes (Banks, Henshaw & Schwendeman 2014): the structure carries an
// estimate of the added mass in its own inertia, where it acts at once, and
// the fluid's forces hold back what the estimate already supplies, so only
// the remainder between the liquid's true response and the estimate is late.
//
// The estimate here is the fluid's own discrete operator: A_ij, the impulse
// the liquid's pressure puts on vertex i (its component along the vertex
// normal n_i, against the motion) when vertex j starts moving along n_j at
// unit speed from rest — one pressure Poisson solve per vertex j, at t = 0.
// The structure's added mass is the block n_i A_ij n_j^T between the
// translations of vertices i and j; the fluid's window forces get back
// n_i sum_j A_ij n_j . (V_j - V'_j) / dt_c, V and V' the wall velocities of
// this window and the last (eq 18): the impulse -A dV its pressure gave when
// the wall's velocity changed at the window start.
#include <cstddef>
#include <span>
#include <vector>

#include "coupling/interface/interface_mesh.hpp"

namespace tankfsi::coupling {

/// Unit vertex normals (3 per vertex) of a mesh: the area-weighted mean of its
/// triangles' normals, oriented as the triangles (right-hand rule); zero for
/// a vertex of no triangle. Both sides take the operator's directions from it.
[[nodiscard]] std::vector<double> vertex_normals(const InterfaceMesh& mesh);

/// (A + A^T) / 2 of a square row-major matrix, in place: the operator the
/// partners use is symmetric whatever round-off the fluid's solves left.
void symmetrise(std::span<double> matrix, std::size_t size);

/// Adds the impulse the estimate supplies back to window averages:
/// values_i += n_i sum_j A_ij (n_j . change_j) / window for the rows
/// first_row .. first_row + values.size()/3 of A (row-major, `columns` wide),
/// `normals` and `change` (3 per vertex) over all columns.
void add_added_mass_reaction(std::span<const double> rows, std::size_t first_row, std::size_t columns,
                             std::span<const double> normals, std::span<const double> change, double window,
                             std::span<double> values);

}  // namespace tankfsi::coupling
