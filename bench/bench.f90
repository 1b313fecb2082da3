!> fastcontact-bench: accuracy and cost of the normal solvers on Hertz Test I (thesis §2.5.1).
!!
!! For each grid n×n (64² … 1024²) and each solver (BCCG, NORM) the program builds the
!! influence operator, solves the normal problem with the prescribed approach and compares
!! the pressure with the analytic elliptic Hertz solution.  One CSV row per run:
!!
!!   case,solver,nx,ny,unknowns,error_rms,error_vs,fn,fn_error_rel,ncon,iterations,matvecs,
!!   residual,status,setup_seconds,solve_seconds,total_seconds
!!
!! error_rms     RMS over all elements of (p − p_Hertz) [N/mm²], p_Hertz at element centres
!! fn_error_rel  (F − F_Hertz)/F_Hertz, F_Hertz the analytic force for the approach
!! setup_seconds influence coefficients + FFT symbols + preconditioner (build_normal_operator)
!! solve_seconds solve_normal's own clock (res%cpu_seconds)
!! total_seconds wall clock from grid creation to the end of the solve (the whole job of a
!!               one-shot run, operator set-up included)
!!
!! Usage: fastcontact-bench [--quick] [--all] [--min N] [--max N] [--solver S] [--out FILE]
!!   --quick   64² and 128² only (CI sanity check)
!!   --all     also run NORM above 512²
!!   --min N   smallest grid size n (default 64)
!!   --max N   largest grid size n (default 1024)
!!   --solver S  only solver S ('bccg' or 'norm'; default both)
!!   --out F   CSV file (default doc/bench_normal.csv)
program fastcontact_bench
    use, intrinsic :: iso_fortran_env, only: int64
    use fc_kinds, only: dp, status_name, FC_CONVERGED
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result
    use fc_norm, only: build_normal_operator, solve_normal
    use fc_hertz, only: fc_hertz_solution, hertz_from_approach
    implicit none

    ! Hertz Test I (thesis §2.5.1)
    real(dp), parameter :: rx = 300, ry = 163, approach = 0.1091_dp
    real(dp), parameter :: xmin = -10, xmax = 10, ymin = -6, ymax = 6
    real(dp), parameter :: gmod = 82000, poisson = 0.28_dp
    real(dp), parameter :: tol = 1.0e-5_dp
    integer, parameter :: sizes(5) = [64, 128, 256, 512, 1024]
    integer, parameter :: norm_limit = 512

    character(len=512) :: out_file, arg
    logical :: quick, run_all
    character(len=8) :: only_solver
    character(len=4) :: solver
    integer :: nmin, nmax, iarg, nargs, ios, unit, k, isol, nfail
    type(fc_material) :: mat
    type(fc_hertz_solution) :: hz
    character(len=256) :: msg
    integer :: stat

    out_file = 'doc/bench_normal.csv'
    quick = .false.; run_all = .false.; nmin = 1; nmax = 1024; only_solver = ''
    nargs = command_argument_count()
    iarg = 1
    do while (iarg <= nargs)
        call get_command_argument(iarg, arg)
        select case (trim(arg))
        case ('--quick')
            quick = .true.
        case ('--all')
            run_all = .true.
        case ('--max', '--min')
            iarg = iarg + 1
            call get_command_argument(iarg, msg)
            read (msg, *, iostat=ios) k
            if (ios /= 0 .or. k < 1) call usage(trim(arg)//' needs a positive integer, got "'//trim(msg)//'"')
            if (arg == '--max') then
                nmax = k
            else
                nmin = k
            end if
        case ('--solver')
            iarg = iarg + 1
            call get_command_argument(iarg, only_solver)
            if (only_solver /= 'bccg' .and. only_solver /= 'norm') &
                call usage('--solver must be bccg or norm, got "'//trim(only_solver)//'"')
        case ('--out')
            iarg = iarg + 1
            if (iarg > nargs) call usage('--out needs a file name')
            call get_command_argument(iarg, out_file)
        case ('-h', '--help')
            call usage('')
        case default
            call usage('unknown argument "'//trim(arg)//'"')
        end select
        iarg = iarg + 1
    end do
    if (quick) nmax = min(nmax, 128)

    mat%g1 = gmod; mat%g2 = gmod; mat%nu1 = poisson; mat%nu2 = poisson
    call combine_material(mat, stat, msg)
    if (stat /= 0) error stop 'fastcontact-bench: '//trim(msg)
    hz = hertz_from_approach(0.5_dp/rx, 0.5_dp/ry, mat%g/(1 - mat%nu), approach)

    open (newunit=unit, file=trim(out_file), status='replace', action='write', iostat=ios)
    if (ios /= 0) then
        write (*, '(a)') 'fastcontact-bench: cannot open '//trim(out_file)
        error stop 2
    end if
    write (unit, '(a)') 'case,solver,nx,ny,unknowns,error_rms,error_vs,fn,fn_error_rel,ncon,iterations,matvecs,' // &
        'residual,status,setup_seconds,solve_seconds,total_seconds'

    write (*, '(a)') 'fastcontact-bench: Hertz Test I, approach 0.1091 mm, tol 1e-5'
    write (*, '(a,f8.4,a,f8.4,a,f9.2,a,f10.2)') 'analytic Hertz: a =', hz%a, ' b =', hz%b, ' p0 =', hz%p0, ' F =', hz%fn
    write (*, '(a)') 'CSV: '//trim(out_file)
    write (*, '(a)') ''
    write (*, '(a6,1x,a9,1x,a10,1x,a10,1x,a6,1x,a6,1x,a7,1x,a9,1x,a13,1x,a8,1x,a8,1x,a8)') &
        'solver', 'grid', 'err_rms', 'F_err_rel', 'ncon', 'iter', 'matvecs', 'residual', 'status', &
        'setup_s', 'solve_s', 'total_s'

    nfail = 0
    do k = 1, size(sizes)
        if (sizes(k) > nmax) exit
        if (sizes(k) < nmin) cycle
        do isol = 1, 2
            solver = merge('bccg', 'norm', isol == 1)
            if (len_trim(only_solver) > 0 .and. solver /= only_solver) cycle
            if (solver == 'norm' .and. sizes(k) > norm_limit .and. .not. run_all) cycle
            call run_case(sizes(k), solver)
        end do
    end do
    close (unit)
    if (nfail > 0) then
        write (*, '(i0,a)') nfail, ' run(s) did not converge'
        error stop 1
    end if

contains

    !> Build, solve and report one (grid, solver) run.
    subroutine run_case(n, solver)
        integer, intent(in) :: n
        character(len=*), intent(in) :: solver
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: settings
        type(fc_normal_result) :: res
        real(dp), allocatable :: h0(:, :), pa(:, :)
        real(dp) :: err, ferr, total
        integer :: i, j, st
        integer(int64) :: t0, t1, rate
        character(len=256) :: emsg
        character(len=16) :: gname

        call system_clock(t0, rate)
        call make_grid(grid, n, n, xmin, xmax, ymin, ymax, st, emsg)
        if (st /= 0) error stop 'fastcontact-bench: '//trim(emsg)
        h0 = quadratic_gap(grid, rx, ry)
        call build_normal_operator(nop, mat, grid)
        settings%solver = solver
        settings%tol = tol
        call solve_normal(nop, h0, settings, res, st, emsg, approach=approach)
        call system_clock(t1)
        total = real(t1 - t0, dp)/rate
        if (st /= 0) then
            write (*, '(a)') 'fastcontact-bench: '//trim(emsg)
            nfail = nfail + 1
            call nop%destroy()
            return
        end if

        allocate (pa(n, n))
        do j = 1, n
            do i = 1, n
                pa(i, j) = hz%pressure(grid%x(i), grid%y(j))
            end do
        end do
        err = sqrt(sum((res%pn - pa)**2)/real(n, dp)**2)
        ferr = (res%fn - hz%fn)/hz%fn
        if (res%status /= FC_CONVERGED) nfail = nfail + 1

        write (unit, '(a,",",a,3(",",i0),",",a,",",a,",",a,",",a,3(",",i0),",",a,",",a,3(",",a))') &
            'hertz_test1', solver, n, n, n*n, num(err, '(es14.7)'), 'hertz_analytic', num(res%fn, '(es16.9)'), &
            num(ferr, '(es12.5)'), res%ncon, res%iterations, res%matvecs, num(res%residual, '(es12.5)'), &
            status_name(res%status), num(nop%setup_seconds, '(f0.4)'), num(res%cpu_seconds, '(f0.4)'), &
            num(total, '(f0.4)')
        flush (unit)
        write (gname, '(i0,"x",i0)') n, n
        write (*, '(a6,1x,a9,1x,f10.4,1x,es10.3,1x,i6,1x,i6,1x,i7,1x,es9.2,1x,a13,1x,f8.3,1x,f8.3,1x,f8.3)') &
            solver, gname, err, ferr, res%ncon, res%iterations, res%matvecs, res%residual, &
            status_name(res%status), nop%setup_seconds, res%cpu_seconds, total
        call nop%destroy()
    end subroutine run_case

    !> A real formatted with `fmt`, without blanks and with a leading zero (".5" → "0.5").
    function num(x, fmt) result(str)
        real(dp), intent(in) :: x
        character(len=*), intent(in) :: fmt
        character(len=:), allocatable :: str
        character(len=40) :: buf
        write (buf, fmt) x
        str = trim(adjustl(buf))
        if (str(1:1) == '.') str = '0'//str
        if (len(str) > 1) then
            if (str(1:2) == '-.') str = '-0'//str(2:)
        end if
    end function num

    subroutine usage(problem)
        character(len=*), intent(in) :: problem
        if (len(problem) > 0) write (*, '(a)') 'fastcontact-bench: '//problem
        write (*, '(a)') 'usage: fastcontact-bench [--quick] [--all] [--min N] [--max N] [--solver bccg|norm] [--out FILE]'
        if (len(problem) > 0) error stop 2
        stop
    end subroutine usage

end program fastcontact_bench
