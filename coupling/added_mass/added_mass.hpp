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
// the fluid holds back from its forces the impulse its liquid gave for the
// wall's velocity change at the window start, which that inertia stands for.
//
// The estimate here is the fluid's own discrete operator: A_ij, the impulse
// the liquid's pressure puts on vertex i (its component along the vertex
// normal n_i, against the motion) when vertex j starts moving along n_j at
// unit speed from rest — one pressure Poisson solve per vertex j, at t = 0.
// The structure's added mass is the block n_i A_ij n_j^T between the
// translations of vertices i and j.
//
// What is held back is measured, not estimated: the fluid solves its pressure
// Poisson equation once more at the window's first step with the velocity
// change V - V' of its wall (eq 18) as the only source, and takes the normal
// part of that pressure's impulse on each interface vertex out of the
// window's force. Holding back A (V - V') instead — the estimate's impulse —
// leaves the liquid's true response less A a window late: where the liquid's
// added mass has fallen below A (a wall the sloshing liquid has drained near
// its surface), that lagged remainder pushes along the last window's
// acceleration: by a scalar model of the scheme a negative damping of about
// (A - A_true) / (M + A) × w dt_c / 2 for a wall mode of angular frequency w.
// On the coarse tank (cases/tank3d_fixed_roof_coarse) a 55 ms wall mode grew
// until the run diverged at 6.7 s; with the measured impulse held back it
// runs its 20 s. The structure then meets the liquid's inertia once,
// implicitly, as A: an estimate that is off shifts a wall mode's period
// (sqrt((M + A) / (M + A_true))) but does not feed it.
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

}  // namespace tankfsi::coupling
