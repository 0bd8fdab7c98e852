/* tankfsi coupling library: the C interface.
 *
 * One program's end of a partitioned fluid-structure coupling (coupling/PROTOCOL.md).
 * Usable from C, C++ and, through ISO_C_BINDING, Fortran (the _f functions take
 * and give Fortran MPI handles). A partner written against this header alone
 * can take the place of either tankfsi program.
 *
 *   MPI_Init(&argc, &argv);
 *   tankfsi_participant* p;
 *   if (tankfsi_participant_create(TANKFSI_STRUCTURE, "case.yaml", MPI_COMM_WORLD, &p))
 *     { fprintf(stderr, "%s\n", tankfsi_last_error(NULL)); MPI_Abort(MPI_COMM_WORLD, 2); }
 *   MPI_Comm mine = tankfsi_local_comm(p);       // this program's ranks (use it, not the world)
 *   tankfsi_set_interface(p, n, ids, xyz, nt, triangles);
 *   tankfsi_exchange_interface(p);
 *   tankfsi_write(p, TANKFSI_DISPLACEMENT, u0, 3 * n);   // optional initial data
 *   tankfsi_initialize(p);
 *   while (tankfsi_is_ongoing(p)) {
 *     if (tankfsi_requires_writing_checkpoint(p)) save();
 *     double dt = fmin(my_dt, tankfsi_max_time_step(p));
 *     tankfsi_read(p, TANKFSI_FORCE, dt, f, 3 * n);
 *     solve(dt);
 *     tankfsi_write(p, TANKFSI_DISPLACEMENT, u, 3 * n);
 *     tankfsi_advance(p, dt);
 *     if (tankfsi_requires_reading_checkpoint(p)) restore();
 *   }
 *   tankfsi_finalize(p);
 *   tankfsi_participant_destroy(p);
 *   MPI_Finalize();
 *
 * Every function that can fail returns 0 on success and non-zero on failure;
 * tankfsi_last_error() then says why. A coupling failure is fatal for the
 * job: call tankfsi_abort() so that the partner does not wait.
 */
#ifndef TANKFSI_COUPLING_H
#define TANKFSI_COUPLING_H

#include <mpi.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tankfsi_participant tankfsi_participant;

enum tankfsi_side { TANKFSI_FLUID = 0, TANKFSI_STRUCTURE = 1 };
/* Forces (N) are the force of the fluid on each interface vertex;
 * displacements (m) are relative to the tank base; velocities in m/s;
 * 3 values per vertex, global axes. */
enum tankfsi_field { TANKFSI_FORCE = 0, TANKFSI_DISPLACEMENT = 1, TANKFSI_VELOCITY = 2 };

/* Collective over `world`: splits it into the two programs of the job and
 * joins this one to its partner, reading the coupling settings from the case
 * file (its coupling section and end_time). */
int tankfsi_participant_create(int side, const char* case_file, MPI_Comm world, tankfsi_participant** participant);
int tankfsi_participant_create_f(int side, const char* case_file, MPI_Fint world, tankfsi_participant** participant);
void tankfsi_participant_destroy(tankfsi_participant* participant);

/* The error of the last failed call on `participant` (NULL: of the last failed
 * tankfsi_participant_create). */
const char* tankfsi_last_error(const tankfsi_participant* participant);
/* Ends the whole job (both programs) with `message` on standard error. */
void tankfsi_abort(const char* message, int status);

MPI_Comm tankfsi_local_comm(const tankfsi_participant* participant);
MPI_Fint tankfsi_local_comm_f(const tankfsi_participant* participant);

/* Structure side: this rank's vertices (each on exactly one rank) and triangles
 * (3 vertex ids each). */
int tankfsi_set_interface(tankfsi_participant* participant, size_t vertex_count, const int64_t* ids,
                          const double* coordinates, size_t triangle_count, const int64_t* triangles);
int tankfsi_exchange_interface(tankfsi_participant* participant);
/* After the exchange: fluid, the whole mesh in ascending id order; structure,
 * its own vertices. Triangles (fluid side) as vertex indices, 3 per triangle. */
size_t tankfsi_vertex_count(const tankfsi_participant* participant);
const int64_t* tankfsi_vertex_ids(const tankfsi_participant* participant);
const double* tankfsi_vertex_coordinates(const tankfsi_participant* participant);
size_t tankfsi_triangle_count(const tankfsi_participant* participant);
int tankfsi_triangles(const tankfsi_participant* participant, int* vertex_indices);

int tankfsi_initialize(tankfsi_participant* participant);
int tankfsi_is_ongoing(const tankfsi_participant* participant);
double tankfsi_time(const tankfsi_participant* participant);
double tankfsi_max_time_step(const tankfsi_participant* participant);
int tankfsi_read(const tankfsi_participant* participant, int field, double relative_dt, double* values, size_t count);
int tankfsi_write(tankfsi_participant* participant, int field, const double* values, size_t count);
int tankfsi_advance(tankfsi_participant* participant, double dt);
int tankfsi_requires_writing_checkpoint(tankfsi_participant* participant);
int tankfsi_requires_reading_checkpoint(tankfsi_participant* participant);
int tankfsi_window_completed(const tankfsi_participant* participant);
int tankfsi_finalize(tankfsi_participant* participant);

/* Added mass (coupling.added_mass: computed; PROTOCOL.md, "Added mass").
 * The whole interface's n vertices in ascending id order throughout.
 * Fluid, after the exchange: the unit normal of each vertex (3n values).
 * Fluid, before initialize: the operator A (n x n, row-major, kg; each rank
 * its partial sums). Structure, after initialize: the normals (3n values) and
 * the rows of A for its own vertices (own x n values, declaration order). */
int tankfsi_interface_normals(const tankfsi_participant* participant, double* normals, size_t count);
int tankfsi_write_added_mass(tankfsi_participant* participant, const double* matrix, size_t count);
int tankfsi_added_mass(const tankfsi_participant* participant, double* normals, size_t normal_count, double* rows,
                       size_t row_count);

#ifdef __cplusplus
}
#endif

#endif /* TANKFSI_COUPLING_H */
