!> fastcontact-bench-tangential: cost of TangCG(3) (with and without preconditioner) and
!! ConvexGS on the seven Cattaneo cases of thesis Table 4.1 (thesis §4.4).
!!
!! For every grid (30×25, 60×50, 120×100, 240×200) the normal problem (Fn = 9.1954, BCCG,
!! tol 1e−8) is solved once, then each case with each tangential solver (tol 1e−5, eq. 4.49).
!! One CSV row per run:
!!
!!   case,solver,precondition,nx,ny,unknowns,slip_pct,iterations,matvecs,status,fx,fy,mz,
!!   normal_seconds,setup_seconds,solve_seconds,total_seconds
!!
!! unknowns       2 × contact elements (traction unknowns, as thesis Table 4.4)
!! normal_seconds normal operator set-up + normal solve
!! setup_seconds  tangential influence blocks and FFT symbols
!! solve_seconds  the tangential solve alone
!! total_seconds  normal + tangential set-up + tangential solve: a one-shot
!!                normal+tangential job (the issue's whole-process target)
!!
!! After the table: speed-ups ConvexGS/TangCG(3) per case and grid, and complexity
!! exponents fitted by least squares to log(solve_seconds) against log(unknowns).
!!
!! Usage: fastcontact-bench-tangential [--quick] [--all] [--out FILE]
!!   --quick  30×25 and 60×50 only
!!   --all    ConvexGS also at 240×200 (slow: O(n²) per sweep)
program fastcontact_bench_tangential
    use fc_kinds, only: dp, status_name
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_settings, fc_tangential_result
    use fc_tangcg, only: build_tangential_operator, solve_tangential
    implicit none

    real(dp), parameter :: xi(7) = [0.0_dp, 1.5e-5_dp, 0.0_dp, 0.0021_dp, 0.0037_dp, 0.0_dp, 0.0044_dp]
    real(dp), parameter :: eta(7) = [0.0_dp, 0.0_dp, 0.0015_dp, 0.0010_dp, 0.0048_dp, 0.005_dp, 0.0_dp]
    real(dp), parameter :: phi(7) = [5e-7_dp, 1e-5_dp, 0.0012_dp, 0.003_dp, 0.004_dp, 0.009_dp, 0.08_dp]
    integer, parameter :: gx(4) = [30, 60, 120, 240], gy(4) = [25, 50, 100, 200]
    character(len=*), parameter :: label(3) = ['tangcg  ', 'tangcg  ', 'convexgs']
    logical, parameter :: precond(3) = [.true., .false., .true.]

    real(dp) :: seconds(3, 7, 4), unknowns(7, 4)
    integer :: iters(3, 7, 4)
    character(len=512) :: out_file, arg
    logical :: quick, run_all
    integer :: ngrids, k, c, s, unit, iarg, stat
    character(len=256) :: msg

    out_file = 'doc/bench_tangential.csv'
    quick = .false.; run_all = .false.
    iarg = 1
    do while (iarg <= command_argument_count())
        call get_command_argument(iarg, arg)
        select case (trim(arg))
        case ('--quick'); quick = .true.
        case ('--all'); run_all = .true.
        case ('--out')
            iarg = iarg + 1
            call get_command_argument(iarg, out_file)
        case default
            write (*, '(a)') 'usage: fastcontact-bench-tangential [--quick] [--all] [--out FILE]'
            error stop 1
        end select
        iarg = iarg + 1
    end do
    ngrids = 4
    if (quick) ngrids = 2
    seconds = -1; iters = -1; unknowns = 0

    open (newunit=unit, file=out_file, status='replace', action='write', iostat=stat)
    if (stat /= 0) then
        write (*, '(a)') 'cannot open '//trim(out_file)
        error stop 1
    end if
    write (unit, '(a)') 'case,solver,precondition,nx,ny,unknowns,slip_pct,iterations,matvecs,status,fx,fy,mz,' // &
        'normal_seconds,setup_seconds,solve_seconds,total_seconds'
    write (*, '(a)') 'case solver    pre   grid      unknowns  slip%   iter  matvec status        solve[s]  total[s]'
    do k = 1, ngrids
        call run_grid(k)
    end do
    close (unit)

    write (*, '(/,a)') 'speed-up ConvexGS / TangCG(3) (tangential solve times)'
    write (*, '(a)') 'case  ' // '  30x25    60x50   120x100  240x200'
    do c = 1, 7
        write (*, '(i4,2x,4f9.1)') c, (merge(seconds(3, c, k)/seconds(1, c, k), -1.0_dp, &
            seconds(3, c, k) > 0 .and. seconds(1, c, k) > 0), k=1, 4)
    end do
    write (*, '(/,a)') 'fitted exponents: solve_seconds ~ unknowns^e (least squares over the grids run)'
    write (*, '(a)') 'case   tangcg(3)  tangcg-noprec  convexgs'
    do c = 1, 7
        write (*, '(i4,3f12.2)') c, (fit(seconds(s, c, :), unknowns(c, :)), s=1, 3)
    end do
    write (*, '(/,a)') 'CSV written to '//trim(out_file)

contains

    subroutine run_grid(k)
        integer, intent(in) :: k
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: ns
        type(fc_normal_result) :: nr
        type(fc_tangential_operator) :: top
        type(fc_tangential_settings) :: ts
        type(fc_tangential_result) :: tr
        integer :: t0, t1, rate
        real(dp) :: normal_seconds
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, gx(k), gy(k), -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
        call system_clock(t0, rate)
        call build_normal_operator(nop, mat, grid)
        ns%tol = 1e-8_dp
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, nr, stat, msg, fn=9.1954_dp)
        call system_clock(t1)
        normal_seconds = real(t1 - t0, dp)/rate
        call nop%destroy()
        call build_tangential_operator(top, mat, grid)
        do c = 1, 7
            unknowns(c, k) = 2*nr%ncon
            do s = 1, 3
                if (s == 3 .and. k == 4 .and. .not. run_all) cycle
                ts = fc_tangential_settings()
                ts%solver = label(s)
                ts%precondition = precond(s)
                call solve_tangential(top, nr%pn, 0.4_dp, ts, tr, stat, msg, xi(c), eta(c), phi(c))
                if (stat /= 0) then
                    write (*, '(a)') trim(msg)
                    error stop 1
                end if
                seconds(s, c, k) = tr%cpu_seconds
                iters(s, c, k) = tr%iterations
                write (unit, '(i0,",",a,",",l1,",",i0,",",i0,",",i0,",",f0.2,",",i0,",",i0,",",a,3(",",es15.7),' // &
                    '4(",",f0.4))') c, trim(label(s)), precond(s), gx(k), gy(k), 2*nr%ncon, 100.0_dp*tr%nslip/tr%ncon, &
                    tr%iterations, tr%matvecs, status_name(tr%status), tr%fx, tr%fy, tr%mz, normal_seconds, &
                    top%setup_seconds, tr%cpu_seconds, normal_seconds + top%setup_seconds + tr%cpu_seconds
                write (*, '(i4,1x,a9,l3,i6,"x",i0,i10,f7.1,2i7,1x,a14,2f10.3)') c, label(s), precond(s), gx(k), gy(k), &
                    2*nr%ncon, 100.0_dp*tr%nslip/tr%ncon, tr%iterations, tr%matvecs, status_name(tr%status), &
                    tr%cpu_seconds, normal_seconds + top%setup_seconds + tr%cpu_seconds
            end do
        end do
        call top%destroy()
    end subroutine run_grid

    !> Least-squares slope of log(t) against log(n) over the entries with t > 0.
    real(dp) function fit(t, n)
        real(dp), intent(in) :: t(:), n(:)
        real(dp) :: sx, sy, sxx, sxy
        integer :: i, m
        sx = 0; sy = 0; sxx = 0; sxy = 0; m = 0
        do i = 1, size(t)
            if (t(i) <= 0 .or. n(i) <= 0) cycle
            m = m + 1
            sx = sx + log(n(i)); sy = sy + log(t(i))
            sxx = sxx + log(n(i))**2; sxy = sxy + log(n(i))*log(t(i))
        end do
        fit = -1
        if (m >= 2) fit = (m*sxy - sx*sy)/(m*sxx - sx**2)
    end function fit

end program fastcontact_bench_tangential
