!> Multibody-style loop through the flat API (fc_legacy): a sphere (R = 50 mm) pressed on
!! a plane, shifted tangentially, then unloaded while the shift is held — the Cattaneo
!! setting of doc/conventions.md, "Reference cases" (G = 200 N/mm², ν = 0.42, μ = 0.4).
!! Every step is one fc_calculate call on the same handle in transient mode 1: the previous
!! step's displacements and tractions are the state (u', p'), the shifts are the increments
!! of the step.
!!
!! Build and run (see doc/legacy_api.md):
!!   scripts/build_shared.sh --examples && build/legacy_sphere_f
!! The C (example/legacy_sphere.c) and Python (example/legacy_sphere.py) versions print
!! the same table.
program legacy_sphere
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_null_char
    use fc_legacy
    implicit none
    integer, parameter :: wp = c_double
    integer, parameter :: nx = 40, ny = 40, nsteps = 12
    real(wp), parameter :: l = 1.2857_wp, fmax = 9.1954_wp
    integer(c_int) :: h, ierr, ncon, nadh, nslip, itn, itt, k
    real(wp) :: fn_step(nsteps), dxi(nsteps), fn, fx, fy, mz, xi, eta, phi, shift
    character(len=8) :: phase(nsteps)
    character(len=256) :: msg

    ! load in 4 steps, shift in 4 steps (total 0.006 mm), unload to 25 % in 4 steps
    fn_step = [0.25_wp, 0.5_wp, 0.75_wp, 1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 0.8125_wp, 0.625_wp, 0.4375_wp, 0.25_wp]*fmax
    dxi = [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -0.0015_wp, -0.0015_wp, -0.0015_wp, -0.0015_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
    phase = [character(len=8) :: 'load', 'load', 'load', 'load', 'shift', 'shift', 'shift', 'shift', &
        'unload', 'unload', 'unload', 'unload']

    call fc_init(h, ierr)
    call fc_set_material(h, 200.0_wp, 200.0_wp, 0.42_wp, 0.42_wp, ierr)
    call fc_set_grid(h, nx, ny, -l, l, -l, l, ierr)
    call fc_set_gap_quadratic(h, 50.0_wp, 50.0_wp, ierr)
    call fc_set_friction(h, 0.4_wp, ierr)
    call fc_set_solver(h, 1, 1, 1.0e-8_wp, 1000, 3, 1, ierr)
    call fc_set_transient(h, FCL_CONTINUE, ierr)
    call stop_on_error('set-up')

    write (*, '(a)') 'step phase        Fn [N]    Fx [N]    shift [mm]  ncon  nadh nslip'
    shift = 0
    do k = 1, nsteps
        call fc_set_normal_force(h, fn_step(k), ierr)
        call fc_set_shifts(h, dxi(k), 0.0_wp, 0.0_wp, ierr)
        call fc_calculate(h, ierr)
        call stop_on_error('fc_calculate')
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call fc_get_shifts(h, xi, eta, phi, ierr)
        call fc_get_contact_stats(h, ncon, nadh, nslip, ierr)
        call fc_get_iterations(h, itn, itt, ierr)
        shift = shift + xi
        write (*, '(i4,1x,a6,f12.4,f10.5,f14.6,3i6)') k, phase(k), fn, fx, shift, ncon, nadh, nslip
    end do
    call fc_finalize(h, ierr)

contains

    subroutine stop_on_error(where)
        character(len=*), intent(in) :: where
        if (ierr == 0) return
        call fc_get_error_message(h, msg, len(msg), ierr)
        write (*, '(a)') where//' failed: '//msg(1:index(msg, c_null_char) - 1)
        error stop 1
    end subroutine stop_on_error

end program legacy_sphere
