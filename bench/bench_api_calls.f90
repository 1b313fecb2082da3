!> fastcontact-bench-api-calls: repeated flat-API calls on one handle (Cattaneo problem:
!! normal force + tangential shift, as fastcontact-bench-legacy).
!!
!! Part `effort`: FFT planning effort (fc_set_fft_effort 0 = FFTW_ESTIMATE, 1 = FFTW_MEASURE)
!! on 60×50 and 240×200.  Per grid and effort: CPU seconds of the first call (operators
!! built, plans measured with effort 1) and CPU ms per following call (Fn and ξ varying by
!! ±5 %, warm start); break-even = extra first-call cost / saving per call.  Effort 0 runs
!! first and FFTW's wisdom is forgotten after each grid, so every row starts cold.
!!
!! Part `overhead`: 60×50, `--calls` calls with tiny creepage changes (ξ·(1 + 1e-4·sin k));
!! per call the wall time of fc_calculate against the solvers' own time (normal + tangential
!! solve as they report it); the difference is the API's per-call overhead.  It runs first,
!! in a fresh process heap (see doc/legacy_api.md on glibc's heap trimming).
!!
!!   fpm run --profile release fastcontact-bench-api-calls [-- --calls N] [--overhead-only] [--out FILE]
!!   ... -- --single G E    one effort row in its own process (G 1: 60×50, 2: 240×200; E 0/1),
!!                          printed only: for alternating runs in fresh processes
!!
!! Writes doc/bench_api_calls.csv (default) and prints the rows.
program bench_api_calls
    use, intrinsic :: iso_c_binding, only: c_int
    use fc_kinds, only: dp
    use fc_legacy
    use fc_legacy_registry, only: legacy_state, lookup
    use fc_fftw, only: fftw_forget_wisdom
    implicit none
    integer, parameter :: grids(2, 2) = reshape([60, 50, 240, 200], [2, 2])
    real(dp), parameter :: l = 1.2857_dp, fn0 = 9.1954_dp, xi0 = 0.0021_dp, eta0 = 0.0010_dp, phi0 = 0.003_dp
    integer :: ncalls, ncalls_grid(2), g, e, unit, iarg, ios
    logical :: overhead_only
    integer :: only_grid, only_effort
    logical :: return_early = .false.
    character(len=512) :: out_file, arg
    real(dp) :: first(0:1), per_call(0:1), itn(0:1), itt(0:1), be

    ncalls = 1000
    overhead_only = .false.
    only_grid = 0; only_effort = -1
    out_file = 'doc/bench_api_calls.csv'
    iarg = 1
    do while (iarg <= command_argument_count())
        call get_command_argument(iarg, arg)
        select case (trim(arg))
        case ('--calls')
            iarg = iarg + 1; call get_command_argument(iarg, arg)
            read (arg, *, iostat=ios) ncalls
            if (ios /= 0 .or. ncalls < 10 .or. ncalls > 1000000) then
                write (*, '(a)') 'fastcontact-bench-api-calls: --calls needs an integer in [10, 1000000]'; stop 2
            end if
        case ('--out')
            iarg = iarg + 1; call get_command_argument(iarg, out_file)
        case ('--overhead-only')
            overhead_only = .true.
        case ('--single')
            ! one effort row in this process: --single G E (G = 1: 60x50, 2: 240x200; E = 0, 1)
            iarg = iarg + 1; call get_command_argument(iarg, arg)
            read (arg, *, iostat=ios) only_grid
            if (ios /= 0 .or. only_grid < 1 .or. only_grid > 2) then
                write (*, '(a)') 'fastcontact-bench-api-calls: --single G E needs G = 1 or 2'; stop 2
            end if
            iarg = iarg + 1; call get_command_argument(iarg, arg)
            read (arg, *, iostat=ios) only_effort
            if (ios /= 0 .or. only_effort < 0 .or. only_effort > 1) then
                write (*, '(a)') 'fastcontact-bench-api-calls: --single G E needs E = 0 or 1'; stop 2
            end if
        case default
            write (*, '(a)') 'usage: fastcontact-bench-api-calls [--calls N] [--overhead-only] [--out FILE]'; stop 2
        end select
        iarg = iarg + 1
    end do
    ncalls_grid = [ncalls, max(10, ncalls/20)]

    open (newunit=unit, file=trim(out_file), status='replace', action='write', iostat=ios)
    if (ios /= 0) then
        write (*, '(a)') 'fastcontact-bench-api-calls: cannot write '//trim(out_file); stop 2
    end if
    write (unit, '(a)') 'part,grid,effort,calls,first_call_s,per_call_ms,normal_it_per_call,tangential_it_per_call,'// &
        'break_even_calls,call_us,solve_us,overhead_us,overhead_pct'
    write (*, '(a)') 'part      grid     effort calls  first[s]  ms/call  it_n  it_t  break-even'
    if (only_grid > 0) then
        g = only_grid; e = only_effort
        call effort_run(grids(1, g), grids(2, g), e, ncalls_grid(g), first(e), per_call(e), itn(e), itt(e))
        write (*, '(a,i4,a,i4,i6,i7,f10.4,f9.3,2f6.1)') 'effort   ', grids(1, g), 'x', grids(2, g), e, ncalls_grid(g), &
            first(e), 1000*per_call(e), itn(e), itt(e)
        close (unit, status='delete')
        return_early = .true.
    end if
    if (.not. return_early) call all_rows()

contains

    subroutine all_rows()
        ! first, in a fresh heap: earlier large allocations change glibc's trimming thresholds
        call overhead_run(60, 50, ncalls)
        do g = 1, merge(0, 2, overhead_only)
            do e = 0, 1
                call effort_run(grids(1, g), grids(2, g), e, ncalls_grid(g), first(e), per_call(e), itn(e), itt(e))
            end do
            call fftw_forget_wisdom()
            be = -1
            if (per_call(0) > per_call(1)) be = (first(1) - first(0))/(per_call(0) - per_call(1))
            do e = 0, 1
                write (unit, '(a,i0,a,i0,a,i0,a,i0,a,f0.4,a,f0.4,a,f0.2,a,f0.2,a,f0.0,a)') 'effort,', grids(1, g), 'x', &
                    grids(2, g), ',', e, ',', ncalls_grid(g), ',', first(e), ',', 1000*per_call(e), ',', itn(e), ',', &
                    itt(e), ',', merge(be, -1.0_dp, e == 1), ',,,,'
                write (*, '(a,i4,a,i4,i6,i7,f10.4,f9.3,2f6.1,f12.0)') 'effort   ', grids(1, g), 'x', grids(2, g), e, &
                    ncalls_grid(g), first(e), 1000*per_call(e), itn(e), itt(e), merge(be, -1.0_dp, e == 1)
            end do
        end do
        close (unit)
        write (*, '(a)') 'wrote '//trim(out_file)
    end subroutine all_rows

    subroutine new_handle(nx, ny, h)
        integer, intent(in) :: nx, ny
        integer(c_int), intent(out) :: h
        integer(c_int) :: ierr
        call fc_init(h, ierr)
        call fc_set_material(h, 200.0_dp, 200.0_dp, 0.42_dp, 0.42_dp, ierr)
        call fc_set_grid(h, nx, ny, -l, l, -l, l, ierr)
        call fc_set_gap_quadratic(h, 50.0_dp, 50.0_dp, ierr)
        call fc_set_friction(h, 0.4_dp, ierr)
        call fc_set_threads(h, 1, ierr)
    end subroutine new_handle

    subroutine calc(h, fn, xi)
        integer(c_int), intent(in) :: h
        real(dp), intent(in) :: fn, xi
        integer(c_int) :: ierr
        call fc_set_normal_force(h, fn, ierr)
        call fc_set_shifts(h, xi, eta0, phi0, ierr)
        call fc_calculate(h, ierr)
        if (ierr /= 0) then
            write (*, '(a,i0)') 'fc_calculate failed, ierr = ', ierr; error stop 1
        end if
    end subroutine calc

    !> First-call CPU time and CPU time per following call for one grid and effort.
    subroutine effort_run(nx, ny, effort, n, t_first, t_call, it_n, it_t)
        integer, intent(in) :: nx, ny, effort, n
        real(dp), intent(out) :: t_first, t_call, it_n, it_t
        integer(c_int) :: h, ierr, a, b
        integer :: k, sn, st
        real(dp) :: c0, c1, fac
        call new_handle(nx, ny, h)
        call fc_set_fft_effort(h, effort, ierr)
        call cpu_time(c0)
        call calc(h, fn0, xi0)
        call cpu_time(c1)
        t_first = c1 - c0
        sn = 0; st = 0
        call cpu_time(c0)
        do k = 1, n
            fac = 1 + 0.05_dp*sin(0.1_dp*k)
            call calc(h, fn0*fac, xi0*fac)
            call fc_get_iterations(h, a, b, ierr)
            sn = sn + a; st = st + b
        end do
        call cpu_time(c1)
        t_call = (c1 - c0)/n
        it_n = real(sn, dp)/n; it_t = real(st, dp)/n
        call fc_finalize(h, ierr)
    end subroutine effort_run

    !> Per-call overhead of fc_calculate over the solvers' own time (wall clock of both).
    subroutine overhead_run(nx, ny, n)
        integer, intent(in) :: nx, ny, n
        integer(c_int) :: h, ierr
        type(legacy_state), pointer :: s
        integer(8) :: t0, t1, rate
        integer :: k
        real(dp) :: call_s, solve_s
        call new_handle(nx, ny, h)
        call calc(h, fn0, xi0)                          ! operators built, state warm
        call lookup(h, 'bench', s, ierr)
        call_s = 0; solve_s = 0
        do k = 1, n
            call system_clock(t0, rate)
            call calc(h, fn0, xi0*(1 + 1.0e-4_dp*sin(real(k, dp))))
            call system_clock(t1)
            call_s = call_s + real(t1 - t0, dp)/rate
            solve_s = solve_s + s%result%normal%cpu_seconds + s%result%tangential%cpu_seconds
        end do
        call fc_finalize(h, ierr)
        write (unit, '(a,i0,a,i0,a,i0,a,f0.3,a,f0.3,a,f0.3,a,f0.2)') 'overhead,', nx, 'x', ny, ',0,', n, ',,,,,,', &
            1.0e6_dp*call_s/n, ',', 1.0e6_dp*solve_s/n, ',', 1.0e6_dp*(call_s - solve_s)/n, ',', &
            100*(call_s - solve_s)/solve_s
        write (*, '(a,i4,a,i4,i7,a,f10.2,a,f10.2,a,f8.2,a,f6.2,a)') 'overhead ', nx, 'x', ny, n, ' calls: call', &
            1.0e6_dp*call_s/n, ' us, solve', 1.0e6_dp*solve_s/n, ' us, overhead', 1.0e6_dp*(call_s - solve_s)/n, ' us (', &
            100*(call_s - solve_s)/solve_s, ' % of the solve)'
    end subroutine overhead_run

end program bench_api_calls
