!> fastcontact-bench-rolling: cost of steady rolling (Newton–GMRES and SteadyGS) against
!! TangCG on the shift problem with the same numbers (thesis Table 4.1 cases, used as
!! creepages ξ, η [-], φ [1/mm] for rolling and as shifts [mm, mm, rad] for TangCG).
!!
!! Cattaneo-size set-up: sphere R = 50, G = 200, ν = 0.42, Fn = 9.1954,
!! area [−1.2857, 1.2857]², μ = 0.4; normal problem once per grid (BCCG, tol 1e−8).
!! One CSV row per run:
!!   case,solver,nx,ny,ncon,nslip,iterations,matvecs,status,fx,fy,mz,seconds
!!
!! Usage: fastcontact-bench-rolling [--grids N] [--gs N] [--out FILE]
!!   --grids N  number of grids from 30×25 up (1..4, default 3: up to 120×100)
!!   --gs N     SteadyGS on the first N grids only (default 2)
program fastcontact_bench_rolling
    use fc_kinds, only: dp, status_name
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_settings, fc_tangential_result
    use fc_tangcg, only: build_tangential_operator, solve_tangential
    use fc_rolling, only: fc_rolling_settings, fc_rolling_loading, solve_rolling
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
    integer :: stat, ig, c, ngrids, ngs, u, k
    character(len=256) :: msg, arg, outfile
    ngrids = 3; ngs = 2; outfile = ''
    k = 1
    do while (k <= command_argument_count())
        call get_command_argument(k, arg)
        select case (trim(arg))
        case ('--grids'); k = k + 1; call get_command_argument(k, arg); read (arg, *) ngrids
        case ('--gs'); k = k + 1; call get_command_argument(k, arg); read (arg, *) ngs
        case ('--out'); k = k + 1; call get_command_argument(k, outfile)
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
    write (u, '(a)') 'case,solver,nx,ny,ncon,nslip,iterations,matvecs,status,fx,fy,mz,seconds'
    mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
    call combine_material(mat, stat, msg)
    do ig = 1, ngrids
        call make_grid(grid, gx(ig), gy(ig), -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
        call build_normal_operator(nop, mat, grid)
        ns%tol = 1e-8_dp
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, nr, stat, msg, fn=9.1954_dp)
        call nop%destroy()
        call build_tangential_operator(top, mat, grid)
        do c = 1, 7
            call solve_tangential(top, nr%pn, 0.4_dp, ts, tr, stat, msg, xi(c), eta(c), phi(c))
            call row('tangcg-shift')
            rl%mu = 0.4_dp; rl%xi = xi(c); rl%eta = eta(c); rl%phi = phi(c)
            rs%solver = 'gmres'
            call solve_rolling(top, nr%pn, rl, rs, tr, stat, msg)
            call row('gmres')
            if (ig <= ngs) then
                rs%solver = 'march'; rs%maxit = 5000
                call solve_rolling(top, nr%pn, rl, rs, tr, stat, msg)
                call row('march'); rs%maxit = 2000
            end if
        end do
        call top%destroy()
    end do
    if (u /= 6) close (u)
contains
    subroutine row(name)
        character(len=*), intent(in) :: name
        if (stat /= 0) then
            write (*, '(a)') trim(msg); stop 1
        end if
        write (u, '(i0,",",a,",",i0,",",i0,",",i0,",",i0,",",i0,",",i0,",",a,",",3(es14.6,","),f10.4)') c, name, &
            gx(ig), gy(ig), tr%ncon, tr%nslip, tr%iterations, tr%matvecs, trim(status_name(tr%status)), tr%fx, tr%fy, &
            tr%mz, tr%cpu_seconds
        flush (u)
    end subroutine row
end program fastcontact_bench_rolling
