!> fastcontact-bench-convexgs: why our ConvexGS needs about twice the thesis' sweeps (Table 4.4).
!!
!! An independent ConvexGS (the library's element step, [[circle_newton]], the same O(n)
!! column updates) with a relaxation factor ω and an optional alternating (forward/backward)
!! sweep order, on a Table 4.1 case (Fn = 9.1954 N, μ = 0.4, normal tol 1e−8), started from
!! zero.  After each sweep it evaluates four stopping measures of the traction change and
!! prints the first sweep at which each is below 1e−5:
!!   rms   ‖Δp‖₂/‖p‖₂ (eq. 4.49, the library's rule)      max  max|Δp_I|/max|p_I|
!!   rel-g ‖Δp‖₂/‖μ pn‖₂ (change relative to the bound)   l1   Σ|Δp_I|/Σ|p_I|
!! Results and their reading: doc/solvers.md (ConvexGS).
!!
!! Usage: fastcontact-bench-convexgs NX NY CASE OMEGA ALTERNATE(0/1)
!!   e.g. fastcontact-bench-convexgs 120 100 1 1.0 0     (about 30 s per case at 120×100)
program fastcontact_bench_convexgs
    use fc_kinds, only: dp
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_tangcg, only: fc_tangential_operator, build_tangential_operator, circle_newton
    implicit none
    real(dp), parameter :: xi(7) = [0.0_dp, 1.5e-5_dp, 0.0_dp, 0.0021_dp, 0.0037_dp, 0.0_dp, 0.0044_dp]
    real(dp), parameter :: eta(7) = [0.0_dp, 0.0_dp, 0.0015_dp, 0.0010_dp, 0.0048_dp, 0.005_dp, 0.0_dp]
    real(dp), parameter :: phi(7) = [5e-7_dp, 1e-5_dp, 0.0012_dp, 0.003_dp, 0.004_dp, 0.009_dp, 0.08_dp]
    type(fc_grid) :: grid
    type(fc_material) :: mat
    type(fc_normal_operator) :: nop
    type(fc_normal_settings) :: ns
    type(fc_normal_result) :: nr
    type(fc_tangential_operator) :: top
    integer :: stat, c, nx, ny, isym
    character(len=256) :: msg, arg
    real(dp) :: omega
    if (command_argument_count() /= 5) then
        write (*, '(a)') 'usage: fastcontact-bench-convexgs NX NY CASE OMEGA ALTERNATE(0/1)'
        stop 2
    end if
    call get_command_argument(1, arg); read (arg, *) nx
    call get_command_argument(2, arg); read (arg, *) ny
    call get_command_argument(3, arg); read (arg, *) c
    call get_command_argument(4, arg); read (arg, *) omega
    call get_command_argument(5, arg); read (arg, *) isym
    if (c < 1 .or. c > 7 .or. nx < 2 .or. ny < 2 .or. nx > 1024 .or. ny > 1024 .or. .not. (omega > 0 .and. omega < 2)) then
        write (*, '(a)') 'CASE in 1..7, NX and NY in 2..1024, 0 < OMEGA < 2'
        stop 2
    end if
    mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
    call combine_material(mat, stat, msg)
    call make_grid(grid, nx, ny, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
    call build_normal_operator(nop, mat, grid)
    ns%tol = 1e-8_dp
    call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, nr, stat, msg, fn=9.1954_dp)
    call build_tangential_operator(top, mat, grid)
    call run(c)
contains
    subroutine run(c)
        integer, intent(in) :: c
        real(dp), allocatable :: px(:, :), py(:, :), sx(:, :), sy(:, :), pox(:, :), poy(:, :), g(:, :)
        real(dp) :: axx, ayy, stx, sty, tx, ty, dpx, dpy, ch_rms, ch_max, ch_g, ch_l1, t
        integer :: sweep, i, j, l, ii, jj, first(4)
        logical :: contact(nx, ny)
        allocate (px(nx, ny), py(nx, ny), sx(nx, ny), sy(nx, ny), pox(nx, ny), poy(nx, ny), g(nx, ny))
        contact = nr%pn > 0
        g = 0.4_dp*max(nr%pn, 0.0_dp)
        axx = top%a_xx%kernel(0, 0); ayy = top%a_yy%kernel(0, 0)
        px = 0; py = 0
        do j = 1, ny
            do i = 1, nx
                sx(i, j) = xi(c) - phi(c)*grid%y(j)
                sy(i, j) = eta(c) + phi(c)*grid%x(i)
            end do
        end do
        first = -1
        do sweep = 1, 400
            pox = px; poy = py
            do jj = 1, ny
                j = jj; if (isym == 1 .and. mod(sweep, 2) == 0) j = ny + 1 - jj
                do ii = 1, nx
                    i = ii; if (isym == 1 .and. mod(sweep, 2) == 0) i = nx + 1 - ii
                    if (.not. contact(i, j)) cycle
                    stx = sx(i, j) - axx*px(i, j); sty = sy(i, j) - ayy*py(i, j)
                    tx = -stx/axx; ty = -sty/ayy
                    if (tx**2 + ty**2 > g(i, j)**2) call circle_newton(g(i, j), axx, ayy, stx, sty, tx, ty)
                    tx = px(i, j) + omega*(tx - px(i, j)); ty = py(i, j) + omega*(ty - py(i, j))
                    t = hypot(tx, ty)
                    if (t > g(i, j)) then
                        tx = g(i, j)*tx/t; ty = g(i, j)*ty/t
                    end if
                    dpx = tx - px(i, j); dpy = ty - py(i, j)
                    if (dpx == 0 .and. dpy == 0) cycle
                    px(i, j) = tx; py(i, j) = ty
                    do l = 1, ny
                        sx(:, l) = sx(:, l) + dpx*top%a_xx%kernel(1 - i:nx - i, l - j) + dpy*top%a_xy%kernel(1 - i:nx - i, l - j)
                        sy(:, l) = sy(:, l) + dpx*top%a_xy%kernel(1 - i:nx - i, l - j) + dpy*top%a_yy%kernel(1 - i:nx - i, l - j)
                    end do
                end do
            end do
            ch_rms = sqrt(sum((px - pox)**2 + (py - poy)**2)/sum(px**2 + py**2))
            ch_max = maxval(hypot(px - pox, py - poy))/maxval(hypot(px, py))
            ch_g = sqrt(sum((px - pox)**2 + (py - poy)**2)/sum(g**2))
            ch_l1 = sum(hypot(px - pox, py - poy))/sum(hypot(px, py))
            if (first(1) < 0 .and. ch_rms < 1e-5_dp) first(1) = sweep
            if (first(2) < 0 .and. ch_max < 1e-5_dp) first(2) = sweep
            if (first(3) < 0 .and. ch_g < 1e-5_dp) first(3) = sweep
            if (first(4) < 0 .and. ch_l1 < 1e-5_dp) first(4) = sweep
            if (all(first > 0) .or. (first(1) > 0 .and. sweep >= first(1) + 60)) exit
        end do
        write (*, '(a,i2,a,f5.2,a,i2,a,4i5)') 'case', c, ' omega', omega, ' sym', isym, &
            ' sweeps rms/max/rel-g/l1 <1e-5:', first
    end subroutine run
end program fastcontact_bench_convexgs
