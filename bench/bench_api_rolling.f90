!> Steady rolling through the flat API as a multibody code calls it: one handle, one call
!! per time step, creepages (and optionally Fn) varying smoothly from step to step.
!!
!! The Cattaneo-size sphere (G = 200 N/mm², ν = 0.42, R = 50 mm, Fn = 9.1954 N, μ = 0.4) on
!! an nx×ny grid over [−1.2857, 1.2857]² mm; step k at t = k/25: ξ = 1e−3·(1 + a·sin t),
!! η = 4e−4·(1 + a·cos 1.3t), φ = 1e−3·(1 + a·sin 0.7t) /mm and, with `--fn-vary`,
!! Fn·(1 + a/2·sin 2.1t).  Two handles side by side, step by step:
!!   predicted — each step called once: from the third call on, the flat API extrapolates
!!               the start from the two calls before (doc/rolling.md, "Flat API");
!!   plain     — each step called twice (the repeat has a zero input step, so no call ever
!!               continues one): the first call of a step warm-starts plainly from the
!!               previous step's solution; only first calls are timed and counted.
!! Per handle: CPU ms per call and Krylov / BCCG iterations per call over the steps
!! (the first two steps excluded).  With `--mode predicted` only the first handle runs (for
!! whole-process timing against another build).
!!
!!   fpm run --profile release fastcontact-bench-api-rolling -- [--nx 60 --ny 50] [--steps 100]
!!       [--amp 0.02] [--fn-vary] [--mode both|predicted] [--out FILE]
program fastcontact_bench_api_rolling
    use, intrinsic :: iso_c_binding, only: c_int, c_double
    use fc_legacy
    implicit none
    integer, parameter :: dp = c_double
    integer(c_int) :: ha, hb, ierr, itn, itt, nx, ny
    integer :: k, nsteps, i, u, nargs, rep
    real(dp) :: amp, t, xi, eta, phi, fn, c0, c1
    real(dp) :: ms(2), kry(2), nor(2)
    logical :: fn_vary, both
    character(len=256) :: arg, outfile
    real(dp), parameter :: l = 1.2857_dp, g = 200, nu = 0.42_dp, r = 50, fn0 = 9.1954_dp, mu = 0.4_dp
    nx = 60; ny = 50; nsteps = 100; amp = 0.02_dp; fn_vary = .false.; both = .true.; outfile = ''
    nargs = command_argument_count()
    i = 1
    do while (i <= nargs)
        call get_command_argument(i, arg)
        select case (trim(arg))
        case ('--nx'); i = i + 1; call get_command_argument(i, arg); read (arg, *) nx
        case ('--ny'); i = i + 1; call get_command_argument(i, arg); read (arg, *) ny
        case ('--steps'); i = i + 1; call get_command_argument(i, arg); read (arg, *) nsteps
        case ('--amp'); i = i + 1; call get_command_argument(i, arg); read (arg, *) amp
        case ('--fn-vary'); fn_vary = .true.
        case ('--mode'); i = i + 1; call get_command_argument(i, arg); both = trim(arg) /= 'predicted'
        case ('--out'); i = i + 1; call get_command_argument(i, outfile)
        case default
            write (*, '(a)') 'usage: fastcontact-bench-api-rolling [--nx N --ny N] [--steps N] [--amp A] [--fn-vary] '// &
                '[--mode both|predicted] [--out FILE]'
            stop 2
        end select
        i = i + 1
    end do
    if (nx < 2 .or. nx > 4096 .or. ny < 2 .or. ny > 4096 .or. nsteps < 3 .or. nsteps > 100000 .or. &
        .not. (abs(amp) <= 0.5_dp)) then
        write (*, '(a)') 'fastcontact-bench-api-rolling: bad arguments: 2 <= nx, ny <= 4096, 3 <= steps <= 1e5, |amp| <= 0.5'
        stop 2
    end if
    call open_case(ha)
    if (both) call open_case(hb)
    ms = 0; kry = 0; nor = 0
    do k = 0, nsteps - 1
        t = real(k, dp)/25
        xi = 1.0e-3_dp*(1 + amp*sin(t)); eta = 4.0e-4_dp*(1 + amp*cos(1.3_dp*t)); phi = 1.0e-3_dp*(1 + amp*sin(0.7_dp*t))
        fn = fn0
        if (fn_vary) fn = fn0*(1 + 0.5_dp*amp*sin(2.1_dp*t))
        call step(ha, 1, 1)
        if (both) call step(hb, 2, 2)
    end do
    ms = 1e3_dp*ms/(nsteps - 2); kry = kry/(nsteps - 2); nor = nor/(nsteps - 2)
    write (*, '(a,i0,a,i0,a,f6.3,a,l1)') 'grid ', nx, ' x ', ny, ', amp ', amp, ', Fn varying ', fn_vary
    write (*, '(a,f8.3,a,f6.1,a,f5.1)') 'predicted: ms/call ', ms(1), ', Krylov/call ', kry(1), ', BCCG/call ', nor(1)
    if (both) then
        write (*, '(a,f8.3,a,f6.1,a,f5.1)') 'plain:     ms/call ', ms(2), ', Krylov/call ', kry(2), ', BCCG/call ', nor(2)
        write (*, '(a,f6.3)') 'predicted / plain, CPU per call: ', ms(1)/ms(2)
    end if
    if (len_trim(outfile) > 0) then
        open (newunit=u, file=trim(outfile), status='replace', action='write')
        write (u, '(a)') 'nx,ny,steps,amp,fn_vary,start,ms_per_call,krylov_per_call,bccg_per_call'
        write (u, '(i0,",",i0,",",i0,",",f6.3,",",l1,",predicted,",f8.3,",",f7.2,",",f6.2)') nx, ny, nsteps, amp, fn_vary, &
            ms(1), kry(1), nor(1)
        if (both) write (u, '(i0,",",i0,",",i0,",",f6.3,",",l1,",plain,",f8.3,",",f7.2,",",f6.2)') nx, ny, nsteps, amp, &
            fn_vary, ms(2), kry(2), nor(2)
        close (u)
    end if
    call fc_finalize(ha, ierr)
    if (both) call fc_finalize(hb, ierr)
contains
    subroutine open_case(h)
        integer(c_int), intent(out) :: h
        call fc_init(h, ierr)
        call fc_set_material(h, g, g, nu, nu, ierr)
        call fc_set_grid(h, nx, ny, -l, l, -l, l, ierr)
        call fc_set_gap_quadratic(h, r, r, ierr)
        call fc_set_friction(h, mu, ierr)
    end subroutine open_case

    !> One time step on handle h (called `calls` times; the first is timed), sums into slot j.
    subroutine step(h, calls, j)
        integer(c_int), intent(in) :: h
        integer, intent(in) :: calls, j
        do rep = 1, calls
            call fc_set_normal_force(h, fn, ierr)
            call fc_set_rolling(h, xi, eta, phi, ierr)
            call cpu_time(c0)
            call fc_calculate(h, ierr)
            call cpu_time(c1)
            if (ierr /= 0) error stop 'fc_calculate failed'
            if (rep == 1 .and. k >= 2) then
                call fc_get_iterations(h, itn, itt, ierr)
                ms(j) = ms(j) + (c1 - c0); kry(j) = kry(j) + itt; nor(j) = nor(j) + itn
            end if
        end do
    end subroutine step
end program fastcontact_bench_api_rolling
