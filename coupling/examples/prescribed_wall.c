/* prescribed_wall: a structure partner in C whose interface is a rigid flat
 * wall moved along a given direction with a prescribed law: a piston
 * wavemaker, or a tank floor shaken vertically. It declares the wall as a
 * parallelogram of n_u x n_v cells (two triangles each),
 *
 *   x = corner + s side_u + t side_v,  s, t in [0, 1],
 *   u(t) = A e sin(2 pi t / T) r(t),  r(t) = min(t / T_ramp, 1)^2 (3 - 2 min(t / T_ramp, 1)),
 *
 * (e the unit direction; the smooth ramp r starts the motion from rest with no
 * jump in velocity), one step per coupling window. For each window it writes
 * the force on the wall (the sum over its vertices of the load the library
 * hands it at the window's end: with coupling.structure_load window_average
 * the fluid's window-average force) with the wall's displacement and
 * acceleration at the window's middle to a CSV file: the fluid's reaction to
 * a known motion, to compare with a closed form (added mass, wavemaker theory).
 *
 *   mpirun -np 1 sph_solver case.yaml : -np 1 prescribed_wall case.yaml CORNER SIDE_U SIDE_V N_U N_V
 *          DIRECTION AMPLITUDE PERIOD RAMP_TIME FORCES.csv
 *
 * CORNER, SIDE_U, SIDE_V and DIRECTION are three comma-separated numbers (m),
 * e.g. 0,0,-0.2. The fluid's wall vertices within half a particle spacing of
 * this wall move with it. Runs on one rank.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tankfsi/coupling.h"

static void check(tankfsi_participant* p, int status, const char* what) {
  if (status == 0) return;
  char message[1024];
  snprintf(message, sizeof message, "prescribed_wall: %s: %s", what, p ? tankfsi_last_error(p) : tankfsi_last_error(NULL));
  tankfsi_abort(message, 1);
}

static void vector_argument(const char* text, const char* name, double out[3]) {
  char* end = NULL;
  const char* at = text;
  for (int k = 0; k < 3; ++k) {
    out[k] = strtod(at, &end);
    if (end == at || (k < 2 && *end != ',') || (k == 2 && *end != '\0') || !isfinite(out[k])) {
      char message[256];
      snprintf(message, sizeof message, "prescribed_wall: %s must be three comma-separated numbers, got '%s'", name, text);
      tankfsi_abort(message, 2);
    }
    at = end + 1;
  }
}

typedef struct {
  double amplitude, omega, ramp_time, direction[3];
} Motion;

/* Displacement factor f(t) along e and its second derivative (u = A e f, a = A e f''). */
static void law(const Motion* m, double t, double* f, double* f2) {
  const double s = m->ramp_time > 0 ? fmin(t / m->ramp_time, 1.0) : 1.0;
  const double r = s * s * (3.0 - 2.0 * s);
  const double r1 = s < 1.0 && m->ramp_time > 0 ? 6.0 * s * (1.0 - s) / m->ramp_time : 0.0;
  const double r2 = s < 1.0 && m->ramp_time > 0 ? (6.0 - 12.0 * s) / (m->ramp_time * m->ramp_time) : 0.0;
  const double sn = sin(m->omega * t), cs = cos(m->omega * t);
  *f = sn * r;
  *f2 = -m->omega * m->omega * sn * r + 2.0 * m->omega * cs * r1 + sn * r2;
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  if (argc != 12)
    tankfsi_abort("usage: prescribed_wall CASE.yaml CORNER SIDE_U SIDE_V N_U N_V DIRECTION AMPLITUDE PERIOD RAMP_TIME "
                  "FORCES.csv", 2);
  double corner[3], side_u[3], side_v[3];
  Motion motion;
  vector_argument(argv[2], "CORNER", corner);
  vector_argument(argv[3], "SIDE_U", side_u);
  vector_argument(argv[4], "SIDE_V", side_v);
  const int n_u = atoi(argv[5]), n_v = atoi(argv[6]);
  vector_argument(argv[7], "DIRECTION", motion.direction);
  motion.amplitude = atof(argv[8]);
  const double period = atof(argv[9]);
  motion.ramp_time = atof(argv[10]);
  const double length = sqrt(motion.direction[0] * motion.direction[0] + motion.direction[1] * motion.direction[1] +
                             motion.direction[2] * motion.direction[2]);
  if (n_u < 1 || n_v < 1 || !(length > 0) || !(period > 0) || !(motion.ramp_time >= 0))
    tankfsi_abort("prescribed_wall: need N_U, N_V >= 1, a non-zero DIRECTION, PERIOD > 0 and RAMP_TIME >= 0", 2);
  for (int k = 0; k < 3; ++k) motion.direction[k] /= length;
  motion.omega = 2.0 * M_PI / period;

  tankfsi_participant* p = NULL;
  check(NULL, tankfsi_participant_create(TANKFSI_STRUCTURE, argv[1], MPI_COMM_WORLD, &p), "create");
  int size = 1;
  MPI_Comm_size(tankfsi_local_comm(p), &size);
  if (size != 1) tankfsi_abort("prescribed_wall: runs on one rank", 2);
  FILE* out = fopen(argv[11], "w");
  if (!out) {
    char message[1024];
    snprintf(message, sizeof message, "prescribed_wall: cannot write %s", argv[11]);
    tankfsi_abort(message, 2);
  }

  /* 1. The wall: vertex (i, j) at corner + (i / n_u) side_u + (j / n_v) side_v. */
  const size_t n = (size_t)(n_u + 1) * (size_t)(n_v + 1);
  int64_t* ids = malloc(n * sizeof(int64_t));
  double* xyz = malloc(3 * n * sizeof(double));
  int64_t* triangles = malloc(6 * (size_t)n_u * (size_t)n_v * sizeof(int64_t));
  for (int j = 0; j <= n_v; ++j)
    for (int i = 0; i <= n_u; ++i) {
      const size_t v = (size_t)j * (size_t)(n_u + 1) + (size_t)i;
      ids[v] = (int64_t)v;
      for (int k = 0; k < 3; ++k) xyz[3 * v + k] = corner[k] + side_u[k] * i / n_u + side_v[k] * j / n_v;
    }
  size_t t = 0;
  for (int j = 0; j < n_v; ++j)
    for (int i = 0; i < n_u; ++i) {
      const int64_t a = j * (n_u + 1) + i, b = a + 1, c = a + (n_u + 1), d = c + 1;
      const int64_t cells[6] = {a, b, d, a, d, c};
      memcpy(&triangles[6 * t++], cells, sizeof cells);
    }
  check(p, tankfsi_set_interface(p, n, ids, xyz, 2 * (size_t)n_u * (size_t)n_v, triangles), "set_interface");
  check(p, tankfsi_exchange_interface(p), "exchange_interface");

  /* 2. At rest at t = 0; then each window in one step, the motion's value at its end. */
  double* force = calloc(3 * n, sizeof(double));
  double* u = calloc(3 * n, sizeof(double));
  check(p, tankfsi_write(p, TANKFSI_DISPLACEMENT, u, 3 * n), "initial data");
  check(p, tankfsi_initialize(p), "initialize");
  fprintf(out, "time_s,force_x_N,force_y_N,force_z_N,displacement_m,acceleration_m_s2\n");
  while (tankfsi_is_ongoing(p)) {
    const double start = tankfsi_time(p), dt = tankfsi_max_time_step(p);
    /* The load of this window (eq 17's ramp at the step's end, or the held
     * window average): its vertex sum is the fluid's force on the wall. */
    check(p, tankfsi_read(p, TANKFSI_FORCE, dt, force, 3 * n), "read");
    double f, f2;
    law(&motion, start + dt, &f, &f2);
    for (size_t v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k) u[3 * v + k] = motion.amplitude * f * motion.direction[k];
    check(p, tankfsi_write(p, TANKFSI_DISPLACEMENT, u, 3 * n), "write");
    check(p, tankfsi_advance(p, dt), "advance");
    if (!tankfsi_window_completed(p)) continue; /* an implicit window again: the same motion */
    double total[3] = {0, 0, 0};
    for (size_t v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k) total[k] += force[3 * v + k];
    const double middle = start + 0.5 * dt;
    law(&motion, middle, &f, &f2);
    fprintf(out, "%.9g,%.9e,%.9e,%.9e,%.9e,%.9e\n", middle, total[0], total[1], total[2], motion.amplitude * f,
            motion.amplitude * f2);
  }
  check(p, tankfsi_finalize(p), "finalize");
  fclose(out);
  free(ids); free(xyz); free(triangles); free(force); free(u);
  tankfsi_participant_destroy(p);
  MPI_Finalize();
  return 0;
}
