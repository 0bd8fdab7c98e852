! tankfsi coupling library: Fortran bindings of include/tankfsi/coupling.h
! (ISO_C_BINDING). MPI communicators are Fortran handles (integer), as
! `use mpi` gives them. See coupling.h for what each call does.
module tankfsi_coupling
  use, intrinsic :: iso_c_binding
  implicit none

  integer(c_int), parameter :: TANKFSI_FLUID = 0, TANKFSI_STRUCTURE = 1
  integer(c_int), parameter :: TANKFSI_FORCE = 0, TANKFSI_DISPLACEMENT = 1, TANKFSI_VELOCITY = 2

  interface
    integer(c_int) function tankfsi_participant_create_f(side, case_file, world, participant) bind(C)
      import :: c_int, c_char, c_ptr
      integer(c_int), value :: side
      character(kind=c_char), dimension(*) :: case_file  ! NUL-terminated: trim(name)//c_null_char
      integer(c_int), value :: world
      type(c_ptr) :: participant
    end function
    subroutine tankfsi_participant_destroy(participant) bind(C)
      import :: c_ptr
      type(c_ptr), value :: participant
    end subroutine
    type(c_ptr) function tankfsi_last_error(participant) bind(C)
      import :: c_ptr
      type(c_ptr), value :: participant
    end function
    subroutine tankfsi_abort(message, status) bind(C)
      import :: c_char, c_int
      character(kind=c_char), dimension(*) :: message
      integer(c_int), value :: status
    end subroutine
    integer(c_int) function tankfsi_local_comm_f(participant) bind(C)
      import :: c_ptr, c_int
      type(c_ptr), value :: participant
    end function
    integer(c_int) function tankfsi_set_interface(participant, vertex_count, ids, coordinates, triangle_count, &
                                                  triangles) bind(C)
      import :: c_ptr, c_int, c_size_t, c_int64_t, c_double
      type(c_ptr), value :: participant
      integer(c_size_t), value :: vertex_count, triangle_count
      integer(c_int64_t), dimension(*) :: ids, triangles
      real(c_double), dimension(*) :: coordinates
    end function
    integer(c_int) function tankfsi_exchange_interface(participant) bind(C)
      import :: c_ptr, c_int
      type(c_ptr), value :: participant
    end function
    integer(c_size_t) function tankfsi_vertex_count(participant) bind(C)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: participant
    end function
    integer(c_int) function tankfsi_initialize(participant) bind(C)
      import :: c_ptr, c_int
      type(c_ptr), value :: participant
    end function
    integer(c_int) function tankfsi_is_ongoing(participant) bind(C)
      import :: c_ptr, c_int
      type(c_ptr), value :: participant
    end function
    real(c_double) function tankfsi_time(participant) bind(C)
      import :: c_ptr, c_double
      type(c_ptr), value :: participant
    end function
    real(c_double) function tankfsi_max_time_step(participant) bind(C)
      import :: c_ptr, c_double
      type(c_ptr), value :: participant
    end function
    integer(c_int) function tankfsi_read(participant, field, relative_dt, values, count) bind(C)
      import :: c_ptr, c_int, c_double, c_size_t
      type(c_ptr), value :: participant
      integer(c_int), value :: field
      real(c_double), value :: relative_dt
      real(c_double), dimension(*) :: values
      integer(c_size_t), value :: count
    end function
    integer(c_int) function tankfsi_write(participant, field, values, count) bind(C)
      import :: c_ptr, c_int, c_double, c_size_t
      type(c_ptr), value :: participant
      integer(c_int), value :: field
      real(c_double), dimension(*) :: values
      integer(c_size_t), value :: count
    end function
    integer(c_int) function tankfsi_advance(participant, dt) bind(C)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: participant
      real(c_double), value :: dt
    end function
    integer(c_int) function tankfsi_requires_writing_checkpoint(participant) bind(C)
      import :: c_ptr, c_int
      type(c_ptr), value :: participant
    end function
    integer(c_int) function tankfsi_requires_reading_checkpoint(participant) bind(C)
      import :: c_ptr, c_int
      type(c_ptr), value :: participant
    end function
    integer(c_int) function tankfsi_finalize(participant) bind(C)
      import :: c_ptr, c_int
      type(c_ptr), value :: participant
    end function
    ! Added mass (coupling.added_mass: computed; PROTOCOL.md, "Added mass").
    integer(c_int) function tankfsi_interface_normals(participant, normals, count) bind(C)
      import :: c_ptr, c_int, c_double, c_size_t
      type(c_ptr), value :: participant
      real(c_double), dimension(*) :: normals
      integer(c_size_t), value :: count
    end function
    integer(c_int) function tankfsi_write_added_mass(participant, matrix, count) bind(C)
      import :: c_ptr, c_int, c_double, c_size_t
      type(c_ptr), value :: participant
      real(c_double), dimension(*) :: matrix
      integer(c_size_t), value :: count
    end function
    integer(c_int) function tankfsi_added_mass(participant, normals, normal_count, rows, row_count) bind(C)
      import :: c_ptr, c_int, c_double, c_size_t
      type(c_ptr), value :: participant
      real(c_double), dimension(*) :: normals
      integer(c_size_t), value :: normal_count
      real(c_double), dimension(*) :: rows
      integer(c_size_t), value :: row_count
    end function
  end interface
end module tankfsi_coupling
