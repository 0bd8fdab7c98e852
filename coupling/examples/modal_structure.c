/* modal_structure: a structure partner written in C against the C interface
 * alone, to show how another FEM code takes fem_solver's place. It models the
 * wall of an upright cylindrical tank by one vibration mode,
 *
 *   u_i = q(t) phi_i,   phi_i = sin(pi z_i / (2 H)) cos(theta_i) e_r(theta_i),
 *   m* q'' + 2 zeta omega m* q' + omega^2 m* q = f*(t),   f* = sum_i phi_i . F_i,
 *
 * the cantilever-like first bulging mode (circumferential wave number 1) that
 * a lateral earthquake excites, with the modal mass, frequency and damping
 * given on the command line. It declares its own wall mesh (a grid of
 * n_theta x n_z vertices, two triangles per cell), reads the fluid's forces,
 * integrates q with Newmark's average acceleration and writes u_i.
 *
 *   mpirun -np 2 sph_solver case.yaml : -np 1 modal_structure case.yaml 15 18 64 30 5.0 1e5 0.03
 *   modal_structure CASE.yaml RADIUS HEIGHT N_THETA N_Z FREQUENCY_HZ MODAL_MASS DAMPING [--check-step FX TOL]
 *
 * --check-step FX TOL: the partner applies a constant force FX (N, along x) at
 * every vertex from t = 0 (solver_dummy --constant-force FX); the program then
 * compares q at the end with the closed-form step response of the damped mode
 * and exits 1 if they differ by more than TOL relative to the static value.
 * Runs on one rank (a modal model has one unknown).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tankfsi/coupling.h"

static void check(tankfsi_participant* p, int status, const char* what) {
  if (status == 0) return;
  char message[1024];
  snprintf(message, sizeof message, "modal_structure: %s: %s", what, p ? tankfsi_last_error(p) : tankfsi_last_error(NULL));
  tankfsi_abort(message, 1);
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  if (argc != 9 && argc != 12)
    tankfsi_abort("usage: modal_structure CASE.yaml RADIUS HEIGHT N_THETA N_Z FREQUENCY_HZ MODAL_MASS DAMPING "
                  "[--check-step FX TOL]", 2);
  const double radius = atof(argv[2]), height = atof(argv[3]);
  const int n_theta = atoi(argv[4]), n_z = atoi(argv[5]);
  const double omega = 2.0 * M_PI * atof(argv[6]), modal_mass = atof(argv[7]), zeta = atof(argv[8]);
  const int checking = argc == 12 && strcmp(argv[9], "--check-step") == 0;
  const double step_force = checking ? atof(argv[10]) : 0.0, tolerance = checking ? atof(argv[11]) : 0.0;
  if (radius <= 0 || height <= 0 || n_theta < 3 || n_z < 1 || omega <= 0 || modal_mass <= 0 || zeta < 0 || zeta >= 1)
    tankfsi_abort("modal_structure: need RADIUS, HEIGHT > 0, N_THETA >= 3, N_Z >= 1, FREQUENCY, MODAL_MASS > 0, "
                  "0 <= DAMPING < 1", 2);

  tankfsi_participant* p = NULL;
  check(NULL, tankfsi_participant_create(TANKFSI_STRUCTURE, argv[1], MPI_COMM_WORLD, &p), "create");
  int size = 1;
  MPI_Comm_size(tankfsi_local_comm(p), &size);
  if (size != 1) tankfsi_abort("modal_structure: runs on one rank", 2);

  /* 1. The wall mesh: vertex (j, k) at angle 2 pi j / n_theta, height H k / n_z. */
  const size_t n = (size_t)n_theta * (size_t)(n_z + 1);
  int64_t* ids = malloc(n * sizeof(int64_t));
  double* xyz = malloc(3 * n * sizeof(double));
  double* phi = malloc(3 * n * sizeof(double));
  int64_t* triangles = malloc(6 * (size_t)n_theta * (size_t)n_z * sizeof(int64_t));
  for (int k = 0; k <= n_z; ++k)
    for (int j = 0; j < n_theta; ++j) {
      const size_t i = (size_t)k * (size_t)n_theta + (size_t)j;
      const double theta = 2.0 * M_PI * j / n_theta, z = height * k / n_z;
      ids[i] = (int64_t)i;
      xyz[3 * i] = radius * cos(theta);
      xyz[3 * i + 1] = radius * sin(theta);
      xyz[3 * i + 2] = z;
      const double shape = sin(M_PI * z / (2.0 * height)) * cos(theta);
      phi[3 * i] = shape * cos(theta);
      phi[3 * i + 1] = shape * sin(theta);
      phi[3 * i + 2] = 0.0;
    }
  size_t t = 0;
  for (int k = 0; k < n_z; ++k)
    for (int j = 0; j < n_theta; ++j) {
      const int64_t a = k * n_theta + j, b = k * n_theta + (j + 1) % n_theta;
      const int64_t c = a + n_theta, d = b + n_theta;
      /* Normals point inwards, to the liquid. */
      const int64_t cells[6] = {a, c, b, b, c, d};
      memcpy(&triangles[6 * t++], cells, sizeof cells);
    }
  check(p, tankfsi_set_interface(p, n, ids, xyz, 2 * (size_t)n_theta * (size_t)n_z, triangles), "set_interface");
  check(p, tankfsi_exchange_interface(p), "exchange_interface");

  /* 2. The mode at rest, balanced with the initial load. */
  double* force = calloc(3 * n, sizeof(double));
  double* u = calloc(3 * n, sizeof(double));
  check(p, tankfsi_write(p, TANKFSI_DISPLACEMENT, u, 3 * n), "initial data");
  check(p, tankfsi_initialize(p), "initialize");
  check(p, tankfsi_read(p, TANKFSI_FORCE, 0.0, force, 3 * n), "read");
  double generalised = 0.0;
  for (size_t i = 0; i < 3 * n; ++i) generalised += phi[i] * force[i];
  double q = 0.0, v = 0.0, a = generalised / modal_mass;
  double saved[3] = {q, v, a};

  /* 3. Newmark on q, one structure step per 1/4 of the coupling window. */
  const double k_modal = omega * omega * modal_mass, c_modal = 2.0 * zeta * omega * modal_mass;
  while (tankfsi_is_ongoing(p)) {
    if (tankfsi_requires_writing_checkpoint(p)) { saved[0] = q; saved[1] = v; saved[2] = a; }
    const double dt = fmin(tankfsi_max_time_step(p), 2.5e-3);
    check(p, tankfsi_read(p, TANKFSI_FORCE, dt, force, 3 * n), "read");
    generalised = 0.0;
    for (size_t i = 0; i < 3 * n; ++i) generalised += phi[i] * force[i];
    const double q_predictor = q + dt * v + 0.25 * dt * dt * a, v_predictor = v + 0.5 * dt * a;
    const double a_new = (generalised - k_modal * q_predictor - c_modal * v_predictor) /
                         (modal_mass + 0.5 * dt * c_modal + 0.25 * dt * dt * k_modal);
    q = q_predictor + 0.25 * dt * dt * a_new;
    v = v_predictor + 0.5 * dt * a_new;
    a = a_new;
    for (size_t i = 0; i < 3 * n; ++i) u[i] = q * phi[i];
    check(p, tankfsi_write(p, TANKFSI_DISPLACEMENT, u, 3 * n), "write");
    check(p, tankfsi_advance(p, dt), "advance");
    if (tankfsi_requires_reading_checkpoint(p)) { q = saved[0]; v = saved[1]; a = saved[2]; }
  }
  check(p, tankfsi_finalize(p), "finalize");

  int status = 0;
  /* The last force read, summed radially: for a liquid at rest the ring load
   * rho g pi R H^2 of the wetted height H. */
  double radial = 0.0;
  for (size_t i = 0; i < n; ++i) radial += (force[3 * i] * xyz[3 * i] + force[3 * i + 1] * xyz[3 * i + 1]) / radius;
  printf("modal_structure: t = %.4f s, modal displacement q = %.9e m, radial force on the wall %.6e N\n",
         tankfsi_time(p), q, radial);
  if (checking) {
    /* Step response of the damped mode from rest under f* = FX sum_i phi_i . e_x. */
    double f_star = 0.0;
    for (size_t i = 0; i < n; ++i) f_star += step_force * phi[3 * i];
    const double q_static = f_star / k_modal, time = tankfsi_time(p);
    const double omega_d = omega * sqrt(1.0 - zeta * zeta);
    const double exact = q_static * (1.0 - exp(-zeta * omega * time) *
                                                (cos(omega_d * time) + zeta / sqrt(1.0 - zeta * zeta) * sin(omega_d * time)));
    const double error = fabs(q - exact) / fabs(q_static);
    printf("modal_structure: step response %.9e m (closed form), error %.2e of the static %.6e m\n", exact, error,
           q_static);
    if (!(error <= tolerance)) {
      fprintf(stderr, "modal_structure: step response error %.2e above %.2e\n", error, tolerance);
      status = 1;
    }
  }
  free(ids); free(xyz); free(phi); free(triangles); free(force); free(u);
  tankfsi_participant_destroy(p);
  MPI_Finalize();
  return status;
}
