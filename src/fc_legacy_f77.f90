!> Fortran-77 linkage of the flat API: `call fc_init(h, ierr)` without [[fc_legacy]]'s
!! interfaces refers to the symbol fc_init_ (gfortran, ifort, ifx, flang on Linux); these
!! aliases forward to the bind(C) routines, so old codes link against the same library
!! unchanged.  One alias per routine of [[fc_legacy]], same arguments.
module fc_legacy_f77
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char
    ! the three parts of [[fc_legacy]], not the module itself: one layer less in the module graph
    use fc_legacy_setup
    use fc_legacy_calculate
    use fc_legacy_results
    implicit none
    private

contains

    subroutine fc_init_f77(handle, ierr) bind(C, name='fc_init_')
        integer(c_int), intent(out) :: handle
        integer(c_int), intent(out) :: ierr
        call fc_init(handle, ierr)
    end subroutine fc_init_f77

    subroutine fc_finalize_f77(handle, ierr) bind(C, name='fc_finalize_')
        integer(c_int), intent(inout) :: handle
        integer(c_int), intent(out) :: ierr
        call fc_finalize(handle, ierr)
    end subroutine fc_finalize_f77

    subroutine fc_get_nhandles_f77(nhandles, ierr) bind(C, name='fc_get_nhandles_')
        integer(c_int), intent(out) :: nhandles
        integer(c_int), intent(out) :: ierr
        call fc_get_nhandles(nhandles, ierr)
    end subroutine fc_get_nhandles_f77

    subroutine fc_get_version_f77(major, minor, patch, ierr) bind(C, name='fc_get_version_')
        integer(c_int), intent(out) :: major, minor, patch
        integer(c_int), intent(out) :: ierr
        call fc_get_version(major, minor, patch, ierr)
    end subroutine fc_get_version_f77

    subroutine fc_set_material_f77(handle, g1, g2, nu1, nu2, ierr) bind(C, name='fc_set_material_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: g1, g2
        real(c_double), intent(in) :: nu1, nu2
        integer(c_int), intent(out) :: ierr
        call fc_set_material(handle, g1, g2, nu1, nu2, ierr)
    end subroutine fc_set_material_f77

    subroutine fc_set_grid_f77(handle, nx, ny, xmin, xmax, ymin, ymax, ierr) bind(C, name='fc_set_grid_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: nx, ny
        real(c_double), intent(in) :: xmin, xmax, ymin, ymax
        integer(c_int), intent(out) :: ierr
        call fc_set_grid(handle, nx, ny, xmin, xmax, ymin, ymax, ierr)
    end subroutine fc_set_grid_f77

    subroutine fc_set_gap_array_f77(handle, n, h0, ierr) bind(C, name='fc_set_gap_array_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(in) :: h0(*)
        integer(c_int), intent(out) :: ierr
        call fc_set_gap_array(handle, n, h0, ierr)
    end subroutine fc_set_gap_array_f77

    subroutine fc_set_gap_quadratic_f77(handle, rx, ry, ierr) bind(C, name='fc_set_gap_quadratic_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: rx, ry
        integer(c_int), intent(out) :: ierr
        call fc_set_gap_quadratic(handle, rx, ry, ierr)
    end subroutine fc_set_gap_quadratic_f77

    subroutine fc_set_normal_approach_f77(handle, approach, ierr) bind(C, name='fc_set_normal_approach_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: approach
        integer(c_int), intent(out) :: ierr
        call fc_set_normal_approach(handle, approach, ierr)
    end subroutine fc_set_normal_approach_f77

    subroutine fc_set_normal_force_f77(handle, fn, ierr) bind(C, name='fc_set_normal_force_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: fn
        integer(c_int), intent(out) :: ierr
        call fc_set_normal_force(handle, fn, ierr)
    end subroutine fc_set_normal_force_f77

    subroutine fc_set_friction_f77(handle, mu, ierr) bind(C, name='fc_set_friction_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: mu
        integer(c_int), intent(out) :: ierr
        call fc_set_friction(handle, mu, ierr)
    end subroutine fc_set_friction_f77

    subroutine fc_set_shifts_f77(handle, xi, eta, phi, ierr) bind(C, name='fc_set_shifts_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: xi, eta
        real(c_double), intent(in) :: phi
        integer(c_int), intent(out) :: ierr
        call fc_set_shifts(handle, xi, eta, phi, ierr)
    end subroutine fc_set_shifts_f77

    subroutine fc_set_forces_f77(handle, fx, fy, phi, ierr) bind(C, name='fc_set_forces_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: fx, fy
        real(c_double), intent(in) :: phi
        integer(c_int), intent(out) :: ierr
        call fc_set_forces(handle, fx, fy, phi, ierr)
    end subroutine fc_set_forces_f77

    subroutine fc_set_solver_f77(handle, normal_solver, tangential_solver, tol, maxit, inner_k, precondition, ierr) &
        bind(C, name='fc_set_solver_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: normal_solver, tangential_solver
        real(c_double), intent(in) :: tol
        integer(c_int), intent(in) :: maxit, inner_k, precondition
        integer(c_int), intent(out) :: ierr
        call fc_set_solver(handle, normal_solver, tangential_solver, tol, maxit, inner_k, precondition, ierr)
    end subroutine fc_set_solver_f77

    subroutine fc_set_transient_f77(handle, mode, ierr) bind(C, name='fc_set_transient_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: mode
        integer(c_int), intent(out) :: ierr
        call fc_set_transient(handle, mode, ierr)
    end subroutine fc_set_transient_f77

    subroutine fc_set_rolling_step_f77(handle, dq, ierr) bind(C, name='fc_set_rolling_step_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: dq
        integer(c_int), intent(out) :: ierr
        call fc_set_rolling_step(handle, dq, ierr)
    end subroutine fc_set_rolling_step_f77

    subroutine fc_set_reuse_f77(handle, reuse_operators, warm_start, ierr) bind(C, name='fc_set_reuse_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: reuse_operators, warm_start
        integer(c_int), intent(out) :: ierr
        call fc_set_reuse(handle, reuse_operators, warm_start, ierr)
    end subroutine fc_set_reuse_f77

    subroutine fc_set_fft_effort_f77(handle, effort, ierr) bind(C, name='fc_set_fft_effort_')
        integer(c_int), intent(in) :: handle, effort
        integer(c_int), intent(out) :: ierr
        call fc_set_fft_effort(handle, effort, ierr)
    end subroutine fc_set_fft_effort_f77

    subroutine fc_set_periodic_f77(handle, periodic, ierr) bind(C, name='fc_set_periodic_')
        integer(c_int), intent(in) :: handle, periodic
        integer(c_int), intent(out) :: ierr
        call fc_set_periodic(handle, periodic, ierr)
    end subroutine fc_set_periodic_f77

    subroutine fc_set_threads_f77(handle, nthreads, ierr) bind(C, name='fc_set_threads_')
        integer(c_int), intent(in) :: handle, nthreads
        integer(c_int), intent(out) :: ierr
        call fc_set_threads(handle, nthreads, ierr)
    end subroutine fc_set_threads_f77

    subroutine fc_calculate_f77(handle, ierr) bind(C, name='fc_calculate_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: ierr
        call fc_calculate(handle, ierr)
    end subroutine fc_calculate_f77

    subroutine fc_get_forces_f77(handle, fn, fx, fy, mz, ierr) bind(C, name='fc_get_forces_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: fn, fx, fy, mz
        integer(c_int), intent(out) :: ierr
        call fc_get_forces(handle, fn, fx, fy, mz, ierr)
    end subroutine fc_get_forces_f77

    subroutine fc_get_dissipation_f77(handle, dissipation, ierr) bind(C, name='fc_get_dissipation_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: dissipation
        integer(c_int), intent(out) :: ierr
        call fc_get_dissipation(handle, dissipation, ierr)
    end subroutine fc_get_dissipation_f77

    subroutine fc_get_approach_f77(handle, approach, ierr) bind(C, name='fc_get_approach_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: approach
        integer(c_int), intent(out) :: ierr
        call fc_get_approach(handle, approach, ierr)
    end subroutine fc_get_approach_f77

    subroutine fc_get_pmax_f77(handle, pmax, ierr) bind(C, name='fc_get_pmax_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: pmax
        integer(c_int), intent(out) :: ierr
        call fc_get_pmax(handle, pmax, ierr)
    end subroutine fc_get_pmax_f77

    subroutine fc_get_shifts_f77(handle, xi, eta, phi, ierr) bind(C, name='fc_get_shifts_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: xi, eta, phi
        integer(c_int), intent(out) :: ierr
        call fc_get_shifts(handle, xi, eta, phi, ierr)
    end subroutine fc_get_shifts_f77

    subroutine fc_get_contact_stats_f77(handle, ncon, nadh, nslip, ierr) bind(C, name='fc_get_contact_stats_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: ncon, nadh, nslip
        integer(c_int), intent(out) :: ierr
        call fc_get_contact_stats(handle, ncon, nadh, nslip, ierr)
    end subroutine fc_get_contact_stats_f77

    subroutine fc_get_edge_contact_f77(handle, touches, ierr) bind(C, name='fc_get_edge_contact_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: touches
        integer(c_int), intent(out) :: ierr
        call fc_get_edge_contact(handle, touches, ierr)
    end subroutine fc_get_edge_contact_f77

    subroutine fc_get_tractions_f77(handle, n, pn, px, py, ierr) bind(C, name='fc_get_tractions_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(out) :: pn(*), px(*), py(*)
        integer(c_int), intent(out) :: ierr
        call fc_get_tractions(handle, n, pn, px, py, ierr)
    end subroutine fc_get_tractions_f77

    subroutine fc_get_slip_f77(handle, n, sx, sy, ierr) bind(C, name='fc_get_slip_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(out) :: sx(*), sy(*)
        integer(c_int), intent(out) :: ierr
        call fc_get_slip(handle, n, sx, sy, ierr)
    end subroutine fc_get_slip_f77

    subroutine fc_get_gap_f77(handle, n, gap, ierr) bind(C, name='fc_get_gap_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(out) :: gap(*)
        integer(c_int), intent(out) :: ierr
        call fc_get_gap(handle, n, gap, ierr)
    end subroutine fc_get_gap_f77

    subroutine fc_get_status_array_f77(handle, n, status, ierr) bind(C, name='fc_get_status_array_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        integer(c_int), intent(out) :: status(*)
        integer(c_int), intent(out) :: ierr
        call fc_get_status_array(handle, n, status, ierr)
    end subroutine fc_get_status_array_f77

    subroutine fc_get_iterations_f77(handle, it_normal, it_tangential, ierr) bind(C, name='fc_get_iterations_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: it_normal, it_tangential
        integer(c_int), intent(out) :: ierr
        call fc_get_iterations(handle, it_normal, it_tangential, ierr)
    end subroutine fc_get_iterations_f77

    subroutine fc_get_rebuilds_f77(handle, n_normal, n_tangential, n_calculations, ierr) bind(C, name='fc_get_rebuilds_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: n_normal, n_tangential, n_calculations
        integer(c_int), intent(out) :: ierr
        call fc_get_rebuilds(handle, n_normal, n_tangential, n_calculations, ierr)
    end subroutine fc_get_rebuilds_f77

    subroutine fc_get_grid_size_f77(handle, nx, ny, ierr) bind(C, name='fc_get_grid_size_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: nx, ny
        integer(c_int), intent(out) :: ierr
        call fc_get_grid_size(handle, nx, ny, ierr)
    end subroutine fc_get_grid_size_f77

    subroutine fc_get_error_message_f77(handle, buffer, buflen, ierr) bind(C, name='fc_get_error_message_')
        integer(c_int), intent(in) :: handle
        character(kind=c_char), intent(out) :: buffer(*)
        integer(c_int), intent(in) :: buflen
        integer(c_int), intent(out) :: ierr
        call fc_get_error_message(handle, buffer, buflen, ierr)
    end subroutine fc_get_error_message_f77

    subroutine fc_set_rolling_f77(handle, xi, eta, phi, ierr) bind(C, name='fc_set_rolling_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: xi, eta, phi
        integer(c_int), intent(out) :: ierr
        call fc_set_rolling(handle, xi, eta, phi, ierr)
    end subroutine fc_set_rolling_f77

    subroutine fc_set_rolling_forces_f77(handle, fx, fy, phi, ierr) bind(C, name='fc_set_rolling_forces_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: fx, fy, phi
        integer(c_int), intent(out) :: ierr
        call fc_set_rolling_forces(handle, fx, fy, phi, ierr)
    end subroutine fc_set_rolling_forces_f77

    subroutine fc_set_rolling_options_f77(handle, solver, mu_kinetic, ierr) bind(C, name='fc_set_rolling_options_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: solver
        real(c_double), intent(in) :: mu_kinetic
        integer(c_int), intent(out) :: ierr
        call fc_set_rolling_options(handle, solver, mu_kinetic, ierr)
    end subroutine fc_set_rolling_options_f77

    !> The file names must end with CHAR(0), as for the C entry (the hidden length arguments
    !! of a Fortran 77 call are not read).
    subroutine fc_set_influence_file_f77(handle, path, path2, ierr) bind(C, name='fc_set_influence_file_')
        integer(c_int), intent(in) :: handle
        character(kind=c_char), intent(in) :: path(*), path2(*)
        integer(c_int), intent(out) :: ierr
        call fc_set_influence_file(handle, path, path2, ierr)
    end subroutine fc_set_influence_file_f77

    !> The file name must end with CHAR(0) (see [[fc_set_influence_file_f77]]).
    subroutine fc_set_fft_wisdom_f77(handle, path, ierr) bind(C, name='fc_set_fft_wisdom_')
        integer(c_int), intent(in) :: handle
        character(kind=c_char), intent(in) :: path(*)
        integer(c_int), intent(out) :: ierr
        call fc_set_fft_wisdom(handle, path, ierr)
    end subroutine fc_set_fft_wisdom_f77

end module fc_legacy_f77
