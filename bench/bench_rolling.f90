!> fastcontact-bench-rolling: cost of steady rolling (Newton–GMRES and SteadyGS) against
!! TangCG on the shift problem with the same numbers (thesis Table 4.1 cases, used as
!! creepages ξ, η [-], φ [1/mm] for rolling and as shifts [mm, mm, rad] for TangCG).
!!
!! Cattaneo-size set-up: sphere R = 50, G = 200, ν = 0.42, Fn = 9.1954,
!! area [−1.2857, 1.2857]², μ = 0.4; normal problem once per grid (BCCG, tol 1e−8).
!! One CSV row per run:
!!   case,solver,nx,ny,ncon,nslip,iterations,matvecs,status,fx,fy,mz,seconds
!!
!! After the table: per grid the sums over the 7 cases (time and matvecs) of each solver and
!! the exponents of time against unknowns fitted by least squares.
!!
!! Other modes (one CSV each):
!!   --kalker   Kalker's C11, C22, C23 from full adhesion (μ = 1e6, creepage 1e−4, G = 1,
!!              ν = 0.25, flat pressure on the ellipse, ab from the discrete area) for
!!              a/b = 1, 0.5, 2 on grids of n = 20 … 320 elements along x, the first-order
!!              Richardson extrapolation 2C(h) − C(2h), and the error against the table.
!!   --fastsim  FASTSIM (100 × 100 strips) against the full theory (Newton–GMRES, 80 elements
!!              along the longer axis, Hertz pressure) over the normalised creepage
!!              ξ* = G·ab·C11·ξ/(3μFn) (and η*, φ* alike) and a/b = 0.2 … 5: error of the creep
!!              force over μFn.
!!   --curve    a 20-point ξ sweep (0 … 0.006, η = 0.001, φ = 0.003) at 120×100 with warm
!!              starts, against one cold solve of each point: total times and ratio.
!!
!! Usage: fastcontact-bench-rolling [--grids N] [--gs N] [--kalker | --fastsim | --curve] [--out FILE]
!!   --grids N  number of grids from 30×25 up (1..4, default 3: up to 120×100)
!!   --gs N     the reference 'march' on the first N grids only (default 2)
!!   --case C   only case C of the seven
!!   --forcing F  Newton–GMRES forcing term (default 0.1)
!!   --prec P     Newton–GMRES preconditioner 'fft' (default) or 'runsum' (the earlier one)
!!   --const-forcing  constant forcing term (the earlier rule; default: Eisenstat–Walker once settled)
!!   --prec-form F  form of the FFT preconditioners of TangCG and GMRES: 'circulant' (default) or 'toeplitz'
!!   --only S     run only solver S ('tangcg', 'gmres' or 'none': set-up only), for whole-process timing
!!   --first G    start at grid G (1..4; with --grids N: grids G..N)
!!   --repeat R   solve each case R times (the row shows the last solve, seconds summed)
!!   --start S    cold start of Newton–GMRES: 'fastsim' (default) or 'adhesion'
program fastcontact_bench_rolling
    use fc_kinds, only: dp, status_name
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_settings, fc_tangential_result
    use fc_tangcg, only: build_tangential_operator, solve_tangential
    use fc_rolling, only: fc_rolling_settings, fc_rolling_loading, solve_rolling
    use fc_rolling_refsolvers, only: reference_solver
    use fc_rolling_ref, only: kalker_coefficients
    use fc_fastsim, only: fastsim, fc_fastsim_result
    use fc_hertz, only: fc_hertz_solution, hertz_from_force
    use fc_kinds, only: pi
    implicit none
    real(dp), parameter :: xi(7) = [0.0_dp, 1.5e-5_dp, 0.0_dp, 0.0021_dp, 0.0037_dp, 0.0_dp, 0.0044_dp]
    real(dp), parameter :: eta(7) = [0.0_dp, 0.0_dp, 0.0015_dp, 0.0010_dp, 0.0048_dp, 0.005_dp, 0.0_dp]
    real(dp), parameter :: phi(7) = [5e-7_dp, 1e-5_dp, 0.0012_dp, 0.003_dp, 0.004_dp, 0.009_dp, 0.08_dp]
    integer, parameter :: gx(4) = [30, 60, 120, 240], gy(4) = [25, 50, 100, 200]
    type(fc_grid) :: grid
    type(fc_material) :: mat
    type(fc_normal_operator) :: nop
    type(fc_normal_settings) :: ns
    type(fc_normal_result) :: nr
    type(fc_tangential_operator) :: top
    type(fc_tangential_settings) :: ts
    type(fc_tangential_result) :: tr
    type(fc_rolling_settings) :: rs
    type(fc_rolling_loading) :: rl
    integer :: stat, ig, c, ngrids, ngs, u, k, only_case
    character(len=256) :: msg, arg, outfile
    character(len=16) :: mode
    character(len=8) :: prec = 'fft', only = ''
    character(len=9) :: prec_form = 'circulant'
    logical :: ew = .true.
    integer :: nrep = 1, irep, gfirst = 1
    character(len=8) :: start = 'fastsim'
    real(dp) :: tacc
    real(dp) :: tsum(3, 4), msum(3, 4), unk(4), forcing
    ngrids = 3; ngs = 2; outfile = ''; mode = 'perf'; only_case = 0; forcing = 0.1_dp
    tsum = 0; msum = 0; unk = 0
    k = 1
    do while (k <= command_argument_count())
        call get_command_argument(k, arg)
        select case (trim(arg))
        case ('--grids'); k = k + 1; call get_command_argument(k, arg); read (arg, *) ngrids
        case ('--gs'); k = k + 1; call get_command_argument(k, arg); read (arg, *) ngs
        case ('--out'); k = k + 1; call get_command_argument(k, outfile)
        case ('--kalker', '--fastsim', '--curve'); mode = arg(3:)
        case ('--case'); k = k + 1; call get_command_argument(k, arg); read (arg, *) only_case
        case ('--forcing'); k = k + 1; call get_command_argument(k, arg); read (arg, *) forcing
        case ('--prec'); k = k + 1; call get_command_argument(k, arg); prec = arg(1:8)
        case ('--const-forcing'); ew = .false.
        case ('--prec-form'); k = k + 1; call get_command_argument(k, arg); prec_form = arg(1:9)
        case ('--first'); k = k + 1; call get_command_argument(k, arg); read (arg, *) gfirst
        case ('--only'); k = k + 1; call get_command_argument(k, arg); only = arg(1:8)
        case ('--repeat'); k = k + 1; call get_command_argument(k, arg); read (arg, *) nrep
        case ('--start'); k = k + 1; call get_command_argument(k, arg); start = arg(1:8)
        case default; write (*, '(a)') 'usage: fastcontact-bench-rolling [--grids N] [--gs N] [--out FILE]'; stop 2
        end select
        k = k + 1
    end do
    ngrids = max(1, min(4, ngrids))
    if (len_trim(outfile) > 0) then
        open (newunit=u, file=trim(outfile), status='replace', action='write')
    else
        u = 6
    end if
    select case (mode)
    case ('kalker'); call kalker_study(); stop
    case ('fastsim'); call fastsim_study(); stop
    case ('curve'); call curve_study(); stop
    end select
    write (u, '(a)') 'case,solver,nx,ny,ncon,nslip,iterations,matvecs,status,fx,fy,mz,seconds'
    ts%prec_form = prec_form
    mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
    call combine_material(mat, stat, msg)
    do ig = max(1, gfirst), ngrids
        call make_grid(grid, gx(ig), gy(ig), -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
        call build_normal_operator(nop, mat, grid)
        ns%tol = 1e-8_dp
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, nr, stat, msg, fn=9.1954_dp)
        call nop%destroy()
        call build_tangential_operator(top, mat, grid)
        do c = 1, 7
            if (only_case > 0 .and. c /= only_case) cycle
            if (only == '' .or. only == 'tangcg') then
                tacc = 0
                do irep = 1, nrep
                    call solve_tangential(top, nr%pn, 0.4_dp, ts, tr, stat, msg, xi(c), eta(c), phi(c))
                    tacc = tacc + tr%cpu_seconds
                end do
                tr%cpu_seconds = tacc
                call row('tangcg-shift', 1)
            end if
            rl%mu = 0.4_dp; rl%xi = xi(c); rl%eta = eta(c); rl%phi = phi(c)
            rs%solver = 'gmres'; rs%forcing = forcing; rs%preconditioner = prec; rs%adaptive_forcing = ew
            rs%prec_form = prec_form; rs%start = start
            if (only == '' .or. only == 'gmres') then
                tacc = 0
                do irep = 1, nrep
                    call solve_rolling(top, nr%pn, rl, rs, tr, stat, msg)
                    tacc = tacc + tr%cpu_seconds
                end do
                tr%cpu_seconds = tacc
                call row('gmres', 2)
            end if
            if (ig <= ngs) then
                rs%solver = 'march'; rs%maxit = 5000
                call solve_rolling(top, nr%pn, rl, rs, tr, stat, msg, reference=reference_solver)
                call row('march', 3); rs%maxit = 2000
            end if
        end do
        unk(ig) = 2*count(nr%pn > 0)
        call top%destroy()
    end do
    write (u, '(a)') '# sums over the 7 cases: grid,unknowns,tangcg_s,gmres_s,march_s,tangcg_mv,gmres_mv,march_mv'
    do ig = 1, ngrids
        write (u, '(a,i0,"x",i0,",",i0,6(",",g0.5))') '# ', gx(ig), gy(ig), nint(unk(ig)), tsum(:, ig), msum(:, ig)
    end do
    write (u, '(a,3(f6.2,1x))') '# fitted exponent of time vs unknowns (tangcg, gmres, march): ', &
        slope(unk(1:ngrids), tsum(1, 1:ngrids)), slope(unk(1:ngrids), tsum(2, 1:ngrids)), &
        slope(unk(1:min(ngs, ngrids)), tsum(3, 1:min(ngs, ngrids)))
    write (u, '(a,2(f6.2,1x))') '# fitted exponent of matvecs vs unknowns (tangcg, gmres): ', &
        slope(unk(1:ngrids), msum(1, 1:ngrids)), slope(unk(1:ngrids), msum(2, 1:ngrids))
    if (u /= 6) close (u)
contains
    !> Least-squares slope of log(y) against log(x) (0 with fewer than two points).
    real(dp) function slope(x, y)
        real(dp), intent(in) :: x(:), y(:)
        real(dp) :: lx(size(x)), ly(size(y))
        slope = 0
        if (size(x) < 2) return
        lx = log(x); ly = log(max(y, 1e-12_dp))
        slope = sum((lx - sum(lx)/size(lx))*(ly - sum(ly)/size(ly)))/sum((lx - sum(lx)/size(lx))**2)
    end function slope

    subroutine row(name, isol)
        character(len=*), intent(in) :: name
        integer, intent(in) :: isol
        tsum(isol, ig) = tsum(isol, ig) + tr%cpu_seconds
        msum(isol, ig) = msum(isol, ig) + tr%matvecs
        if (stat /= 0) then
            write (*, '(a)') trim(msg); stop 1
        end if
        write (u, '(i0,",",a,",",i0,",",i0,",",i0,",",i0,",",i0,",",i0,",",a,",",3(es14.6,","),f10.4)') c, name, &
            gx(ig), gy(ig), tr%ncon, tr%nslip, tr%iterations, tr%matvecs, trim(status_name(tr%status)), tr%fx, tr%fy, &
            tr%mz, tr%cpu_seconds
        flush (u)
    end subroutine row

    !> Flat unit pressure on the ellipse (x/a)² + (y/b)² < 1, one free element around it.
    subroutine ellipse(n, a, b, nu, pn, top, area)
        integer, intent(in) :: n
        real(dp), intent(in) :: a, b, nu
        real(dp), allocatable, intent(out) :: pn(:, :)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(out) :: area
        type(fc_material) :: m
        integer :: i, j, mx, my
        mx = n; my = max(4, nint(n*b/a))
        m%g1 = 1; m%g2 = 1; m%nu1 = nu; m%nu2 = nu
        call combine_material(m, stat, msg)
        call make_grid(grid, mx, my, -a*mx/(mx - 2.0_dp), a*mx/(mx - 2.0_dp), -b*my/(my - 2.0_dp), b*my/(my - 2.0_dp), &
                       stat, msg)
        allocate (pn(mx, my))
        do j = 1, my
            do i = 1, mx
                pn(i, j) = merge(1.0_dp, 0.0_dp, (grid%x(i)/a)**2 + (grid%y(j)/b)**2 < 1)
            end do
        end do
        area = count(pn > 0)*grid%area()
        call build_tangential_operator(top, m, grid)
    end subroutine ellipse

    subroutine kalker_study()
        real(dp), parameter :: ratios(3) = [1.0_dp, 0.5_dp, 2.0_dp]
        integer, parameter :: ns(5) = [20, 40, 80, 160, 320]
        real(dp) :: cc(3, 5), k(3), ab, area, a, b, ext
        real(dp), allocatable :: pn(:, :)
        integer :: ir, in, q
        write (u, '(a)') 'a_over_b,n,nx,ny,coefficient,value,table,rel_error,richardson,richardson_error,iterations,seconds'
        do ir = 1, 3
            a = sqrt(ratios(ir)); b = 1/a
            call kalker_coefficients(0.25_dp, ratios(ir), k(1), k(2), k(3), stat)
            do in = 1, size(ns)
                if (ratios(ir) /= 1 .and. ns(in) > 160) cycle
                call ellipse(ns(in), a, b, 0.25_dp, pn, top, area)
                ab = area/pi
                rs = fc_rolling_settings(); rs%tol = 1e-8_dp; rs%maxit = 5000
                rl = fc_rolling_loading(); rl%mu = 1e6_dp
                do q = 1, 3
                    rl%xi = 0; rl%eta = 0; rl%phi = 0
                    select case (q)
                    case (1); rl%xi = 1e-4_dp
                    case (2); rl%eta = 1e-4_dp
                    case (3); rl%phi = 1e-4_dp
                    end select
                    call solve_rolling(top, pn, rl, rs, tr, stat, msg)
                    select case (q)
                    case (1); cc(q, in) = -tr%fx/(ab*rl%xi)
                    case (2); cc(q, in) = -tr%fy/(ab*rl%eta)
                    case (3); cc(q, in) = -tr%fy/(ab**1.5_dp*rl%phi)
                    end select
                    ext = 0
                    if (in > 1) ext = 2*cc(q, in) - cc(q, in - 1)
                    write (u, '(f5.2,",",i0,",",i0,",",i0,",C",i0,i0,",",f9.5,",",f6.3,",",es10.3,",",f9.5,",",es10.3,' &
                        //'",",i0,",",f8.3)') ratios(ir), ns(in), grid%nx, grid%ny, min(q, 2), merge(q, 3, q < 3), &
                        cc(q, in), k(q), cc(q, in)/k(q) - 1, ext, merge(ext/k(q) - 1, 0.0_dp, in > 1), tr%iterations, &
                        tr%cpu_seconds
                    flush (u)
                end do
                call top%destroy()
            end do
        end do
    end subroutine kalker_study

    subroutine fastsim_study()
        real(dp), parameter :: ratios(5) = [0.2_dp, 0.5_dp, 1.0_dp, 2.0_dp, 5.0_dp]
        real(dp), parameter :: stars(8) = [0.1_dp, 0.2_dp, 0.4_dp, 0.6_dp, 0.8_dp, 1.0_dp, 1.5_dp, 3.0_dp]
        character(len=3), parameter :: labels(3) = ['xi ', 'eta', 'phi']
        type(fc_material) :: m
        type(fc_hertz_solution) :: hz
        type(fc_fastsim_result) :: fr
        real(dp) :: a, b, c11, c22, c23, mufn, val, full(3), fast(3)
        real(dp), allocatable :: pn(:, :)
        integer :: ir, is, q, i, j, nxx, nyy
        write (u, '(a)') 'a_over_b,direction,creepage_star,creepage,full_fx_mufn,full_fy_mufn,fastsim_fx_mufn,'// &
            'fastsim_fy_mufn,error_mufn,full_seconds'
        m%g1 = 1; m%g2 = 1; m%nu1 = 0.25_dp; m%nu2 = 0.25_dp
        call combine_material(m, stat, msg)
        do ir = 1, size(ratios)
            ! Hertz contact with semi-axes a = √ratio, b = 1/√ratio for Fn = 1, G = 1
            a = sqrt(ratios(ir)); b = 1/a
            nxx = merge(80, max(8, nint(80*a/b)), a >= b); nyy = merge(80, max(8, nint(80*b/a)), b >= a)
            call make_grid(grid, nxx + 2, nyy + 2, -a*(nxx + 2)/real(nxx, dp), a*(nxx + 2)/real(nxx, dp), &
                           -b*(nyy + 2)/real(nyy, dp), b*(nyy + 2)/real(nyy, dp), stat, msg)
            allocate (pn(grid%nx, grid%ny))
            do j = 1, grid%ny
                do i = 1, grid%nx
                    pn(i, j) = 1.5_dp/(pi*a*b)*sqrt(max(0.0_dp, 1 - (grid%x(i)/a)**2 - (grid%y(j)/b)**2))
                end do
            end do
            mufn = 0.3_dp*sum(pn)*grid%area()
            call build_tangential_operator(top, m, grid)
            call kalker_coefficients(0.25_dp, a/b, c11, c22, c23, stat)
            do q = 1, 3
                do is = 1, size(stars)
                    rl = fc_rolling_loading(); rl%mu = 0.3_dp
                    select case (q)
                    case (1); val = stars(is)*3*mufn/(a*b*c11); rl%xi = val
                    case (2); val = stars(is)*3*mufn/(a*b*c22); rl%eta = val
                    case (3); val = stars(is)*3*mufn/((a*b)**1.5_dp*c23); rl%phi = val
                    end select
                    rs = fc_rolling_settings(); rs%tol = 1e-7_dp; rs%maxit = 5000
                    call solve_rolling(top, pn, rl, rs, tr, stat, msg)
                    call fastsim(a, b, mufn/0.3_dp, 0.3_dp, m%g, m%nu, rl%xi, rl%eta, rl%phi, 100, 100, fr, stat, msg)
                    full = [tr%fx, tr%fy, tr%mz]/mufn; fast = [fr%fx, fr%fy, fr%mz]/mufn
                    write (u, '(f4.1,",",a,",",f5.2,",",es11.4,5(",",f9.5),",",f8.3)') ratios(ir), &
                        trim(labels(q)), stars(is), val, full(1:2), &
                        fast(1:2), hypot(fast(1) - full(1), fast(2) - full(2)), tr%cpu_seconds
                    flush (u)
                end do
            end do
            call top%destroy()
            deallocate (pn)
        end do
        if (.false.) hz = hertz_from_force(1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp)
    end subroutine fastsim_study

    subroutine curve_study()
        real(dp), allocatable :: pxw(:, :), pyw(:, :)
        real(dp) :: warm, cold, val
        integer :: k2, rep
        call make_grid(grid, 120, 100, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, msg)
        call build_normal_operator(nop, mat, grid)
        ns%tol = 1e-8_dp
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, nr, stat, msg, fn=9.1954_dp)
        call build_tangential_operator(top, mat, grid)
        write (u, '(a)') 'repeat,point,xi,fx,nslip,iterations_warm,seconds_warm,iterations_cold,seconds_cold'
        do rep = 1, 3
            warm = 0; cold = 0
            allocate (pxw(120, 100), pyw(120, 100)); pxw = 0; pyw = 0
            do k2 = 1, 20
                val = 0.006_dp*(k2 - 1)/19.0_dp
                rl = fc_rolling_loading(); rl%mu = 0.4_dp; rl%xi = val; rl%eta = 0.001_dp; rl%phi = 0.003_dp
                rs = fc_rolling_settings(); rs%forcing = forcing; rs%preconditioner = prec; rs%adaptive_forcing = ew
                rs%prec_form = prec_form
                call solve_rolling(top, nr%pn, rl, rs, tr, stat, msg, pxw, pyw)
                pxw = tr%px; pyw = tr%py
                warm = warm + tr%cpu_seconds
                k = tr%iterations
                cold = tr%cpu_seconds
                call solve_rolling(top, nr%pn, rl, rs, tr, stat, msg)
                write (u, '(i0,",",i0,",",es11.4,",",es13.5,",",i0,",",i0,",",f8.4,",",i0,",",f8.4)') rep, k2, val, tr%fx, &
                    tr%nslip, k, cold, tr%iterations, tr%cpu_seconds
                cold = tr%cpu_seconds
            end do
            deallocate (pxw, pyw)
        end do
    end subroutine curve_study
end program fastcontact_bench_rolling
