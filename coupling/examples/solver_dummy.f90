! solver_dummy_fortran: the structure side of the two-mass oscillator
! (two_mass_oscillator.hpp) in Fortran, through the tankfsi_coupling module:
! at each vertex a mass m2 on a spring k2, loaded by the fluid's force.
!
!   mpirun -np 1 solver_dummy --side fluid case.yaml --check 2e-3 : -np 1 solver_dummy_fortran case.yaml
program solver_dummy_fortran
  use mpi
  use tankfsi_coupling
  implicit none
  integer, parameter :: vertices = 12
  type(c_ptr) :: p
  character(len=512) :: case_file
  integer :: ierr, rank, ranks, local, k, n
  integer(c_int64_t), allocatable :: ids(:)
  integer(c_int64_t) :: no_triangles(1)
  real(c_double), allocatable :: xyz(:), u(:), v(:), a(:), saved(:, :), f(:), stiffness(:)
  real(c_double) :: dt, predictor, a_new, scale

  call MPI_Init(ierr)
  call get_command_argument(1, case_file)
  if (tankfsi_participant_create_f(TANKFSI_STRUCTURE, trim(case_file)//c_null_char, MPI_COMM_WORLD, p) /= 0) &
    call tankfsi_abort("solver_dummy_fortran: could not join the coupled job"//c_null_char, 1)
  local = tankfsi_local_comm_f(p)
  call MPI_Comm_rank(local, rank, ierr)
  call MPI_Comm_size(local, ranks, ierr)

  ! 1. This rank's vertices: k = rank, rank + ranks, ... (ids as the other dummies).
  n = 0
  do k = rank, vertices - 1, ranks
    n = n + 1
  end do
  allocate(ids(n), xyz(3 * n), u(n), v(n), a(n), saved(3, n), f(3 * n), stiffness(n))
  n = 0
  do k = rank, vertices - 1, ranks
    n = n + 1
    ids(n) = k
    xyz(3 * n - 2:3 * n) = [0.01d0 * k, 0d0, 0d0]
  end do
  call check(tankfsi_set_interface(p, int(n, c_size_t), ids, xyz, 0_c_size_t, no_triangles), "set_interface")
  call check(tankfsi_exchange_interface(p), "exchange_interface")

  ! 2. At rest, loaded by kc x1(0) (kc = 20 scaled like the stiffnesses).
  do k = 1, n
    scale = 1d0 + 0.01d0 * mod(ids(k), 7_c_int64_t)
    stiffness(k) = 60d0 * scale
    u(k) = 0d0
    v(k) = 0d0
    a(k) = 20d0 * scale
  end do
  f = 0d0
  call check(tankfsi_write(p, TANKFSI_DISPLACEMENT, f, int(3 * n, c_size_t)), "initial data")
  call check(tankfsi_initialize(p), "initialize")

  ! 3. Newmark (average acceleration) with the force read at each step's end.
  do while (tankfsi_is_ongoing(p) /= 0)
    if (tankfsi_requires_writing_checkpoint(p) /= 0) then
      saved(1, :) = u
      saved(2, :) = v
      saved(3, :) = a
    end if
    dt = min(0.0025d0, tankfsi_max_time_step(p))
    call check(tankfsi_read(p, TANKFSI_FORCE, dt, f, int(3 * n, c_size_t)), "read")
    do k = 1, n
      predictor = u(k) + dt * v(k) + 0.25d0 * dt * dt * a(k)
      a_new = (f(3 * k - 2) - stiffness(k) * predictor) / (1d0 + 0.25d0 * dt * dt * stiffness(k))
      u(k) = predictor + 0.25d0 * dt * dt * a_new
      v(k) = v(k) + 0.5d0 * dt * (a(k) + a_new)
      a(k) = a_new
    end do
    f = 0d0
    f(1:3 * n:3) = u
    call check(tankfsi_write(p, TANKFSI_DISPLACEMENT, f, int(3 * n, c_size_t)), "write")
    call check(tankfsi_advance(p, dt), "advance")
    if (tankfsi_requires_reading_checkpoint(p) /= 0) then
      u = saved(1, :)
      v = saved(2, :)
      a = saved(3, :)
    end if
  end do
  call check(tankfsi_finalize(p), "finalize")
  if (rank == 0) print '(a, f8.4, a, es16.8)', "solver_dummy_fortran (structure): t = ", tankfsi_time(p), &
                                               " s, vertex 0 at ", u(1)
  call tankfsi_participant_destroy(p)
  call MPI_Finalize(ierr)

contains

  subroutine check(status, what)
    integer(c_int), intent(in) :: status
    character(len=*), intent(in) :: what
    if (status /= 0) call tankfsi_abort("solver_dummy_fortran: "//what//" failed"//c_null_char, 1)
  end subroutine

end program solver_dummy_fortran
