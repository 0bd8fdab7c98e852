/* solver_dummy_c: either side of a coupled job through the C interface
 * (include/tankfsi/coupling.h), with the two-mass oscillator of
 * two_mass_oscillator.hpp as physics: at each vertex the fluid side is a mass
 * m1 on a spring k1, joined by a spring kc to the structure side's mass m2 on
 * a spring k2. Prints the final displacement of vertex 0 and the window count.
 *
 *   mpirun -np 1 solver_dummy_c fluid case.yaml : -np 1 solver_dummy_c structure case.yaml
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tankfsi/coupling.h"

enum { vertices = 12 };

typedef struct {
  double mass, stiffness, u, v, a;
} dof;

/* Newmark average acceleration, load at the step end. */
static void step(dof* d, double dt, double load) {
  const double predictor = d->u + dt * d->v + 0.25 * dt * dt * d->a;
  const double a = (load - d->stiffness * predictor) / (d->mass + 0.25 * dt * dt * d->stiffness);
  d->u = predictor + 0.25 * dt * dt * a;
  d->v += 0.5 * dt * (d->a + a);
  d->a = a;
}

static void check(tankfsi_participant* p, int status, const char* what) {
  if (status == 0) return;
  char message[1024];
  snprintf(message, sizeof message, "solver_dummy_c: %s: %s", what, tankfsi_last_error(p));
  tankfsi_abort(message, 1);
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  if (argc != 3 || (strcmp(argv[1], "fluid") != 0 && strcmp(argv[1], "structure") != 0))
    tankfsi_abort("usage: solver_dummy_c fluid|structure CASE.yaml", 2);
  const int fluid = strcmp(argv[1], "fluid") == 0;
  tankfsi_participant* p = NULL;
  if (tankfsi_participant_create(fluid ? TANKFSI_FLUID : TANKFSI_STRUCTURE, argv[2], MPI_COMM_WORLD, &p) != 0)
    check(NULL, 1, "create");
  int rank = 0, size = 1;
  MPI_Comm_rank(tankfsi_local_comm(p), &rank);
  MPI_Comm_size(tankfsi_local_comm(p), &size);

  /* 1. The structure declares its vertices (round robin over its ranks). */
  if (!fluid) {
    int64_t ids[vertices];
    double xyz[3 * vertices];
    size_t n = 0;
    for (int k = rank; k < vertices; k += size, ++n) {
      ids[n] = k;
      xyz[3 * n] = 0.01 * k;
      xyz[3 * n + 1] = xyz[3 * n + 2] = 0.0;
    }
    check(p, tankfsi_set_interface(p, n, ids, xyz, 0, NULL), "set_interface");
  }
  check(p, tankfsi_exchange_interface(p), "exchange_interface");

  /* 2. One oscillator per vertex held; stiffnesses vary with the id. */
  const size_t n = tankfsi_vertex_count(p);
  const int64_t* ids = tankfsi_vertex_ids(p);
  dof* dofs = calloc(n, sizeof(dof));
  dof* saved = calloc(n, sizeof(dof));
  double* values = calloc(3 * n, sizeof(double));
  double* start = calloc(3 * n, sizeof(double));
  double* end = calloc(3 * n, sizeof(double));
  double* kc = calloc(n, sizeof(double));
  for (size_t k = 0; k < n; ++k) {
    const double s = 1.0 + 0.01 * (double)(ids[k] % 7);
    kc[k] = 20.0 * s;
    if (fluid) {
      dofs[k] = (dof){1.0, (40.0 + 20.0) * s, 1.0, 0.0, -(40.0 + 20.0) * s};
      values[3 * k] = (int)(k % (size_t)size) == rank ? kc[k] : 0.0; /* kc (x1 - x2) at t = 0 */
    } else {
      dofs[k] = (dof){1.0, 60.0 * s, 0.0, 0.0, kc[k]};
    }
  }
  check(p, tankfsi_write(p, fluid ? TANKFSI_FORCE : TANKFSI_DISPLACEMENT, values, 3 * n), "initial data");
  check(p, tankfsi_initialize(p), "initialize");

  /* 3. The participant loop. */
  int windows = 0;
  while (tankfsi_is_ongoing(p)) {
    if (tankfsi_requires_writing_checkpoint(p)) memcpy(saved, dofs, n * sizeof(dof));
    const double window_step = fluid ? 0.01 / 3 : 0.01 / 4;
    const double dt = fmin(window_step, tankfsi_max_time_step(p));
    if (fluid) {
      check(p, tankfsi_read(p, TANKFSI_DISPLACEMENT, 0.0, start, 3 * n), "read");
      check(p, tankfsi_read(p, TANKFSI_DISPLACEMENT, dt, end, 3 * n), "read");
      for (size_t k = 0; k < n; ++k) {
        const double before = dofs[k].u;
        step(&dofs[k], dt, kc[k] * end[3 * k]);
        values[3 * k] = (int)(k % (size_t)size) == rank
                            ? kc[k] * (0.5 * (before + dofs[k].u) - 0.5 * (start[3 * k] + end[3 * k]))
                            : 0.0;
      }
      check(p, tankfsi_write(p, TANKFSI_FORCE, values, 3 * n), "write");
    } else {
      check(p, tankfsi_read(p, TANKFSI_FORCE, dt, end, 3 * n), "read");
      for (size_t k = 0; k < n; ++k) {
        step(&dofs[k], dt, end[3 * k]);
        values[3 * k] = dofs[k].u;
      }
      check(p, tankfsi_write(p, TANKFSI_DISPLACEMENT, values, 3 * n), "write");
    }
    check(p, tankfsi_advance(p, dt), "advance");
    if (tankfsi_requires_reading_checkpoint(p)) memcpy(dofs, saved, n * sizeof(dof));
    windows += tankfsi_window_completed(p);
  }
  check(p, tankfsi_finalize(p), "finalize");
  if (rank == 0 && n > 0)
    printf("solver_dummy_c (%s): %d windows, t = %.6f s, vertex %lld at %.9f\n", argv[1], windows, tankfsi_time(p),
           (long long)ids[0], dofs[0].u);
  free(dofs); free(saved); free(values); free(start); free(end); free(kc);
  tankfsi_participant_destroy(p);
  MPI_Finalize();
  return 0;
}
