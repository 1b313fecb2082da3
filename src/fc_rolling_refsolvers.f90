!> Reference solvers of steady rolling ([[reference_solver]], which the orchestrator passes
!! to [[fc_rolling]]'s [[solve_rolling]]): the transient
!! march ('march': rolling steps δq = δx solved by TangCG until the tractions stop changing)
!! and SteadyGS ('steadygs': under-relaxed nonlinear block Gauss–Seidel from the leading
!! edge; small grids only).  Simple and trusted, slow; see doc/rolling.md.
module fc_rolling_refsolvers
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use fc_kinds
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_result, EL_EXTERIOR, EL_ADHESION, EL_SLIP, &
                         circle_newton, fc_tangential_settings, solve_tangential, finish_status, traction_change
    use fc_rolling_base
    implicit none
    private

    real(dp), parameter :: relax = 0.5_dp   !! SteadyGS under-relaxation factor

    public :: run_steadygs, run_march, reference_solver

contains

    !> The reference solver `settings%solver` names ('march' or 'steadygs'), with the
    !! interface [[rolling_reference_solver]]: what [[solve_rolling]] is given to run them.
    subroutine reference_solver(top, pn, mu, gs, gk, wx, wy, settings, res, stat, errmsg)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: pn(:, :), mu, gs(:, :), gk(:, :), wx(:, :), wy(:, :)
        type(fc_rolling_settings), intent(in) :: settings
        type(fc_tangential_result), intent(inout) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (settings%solver == 'march') then
            call run_march(top, pn, mu, wx, wy, settings, res, stat, errmsg)
        else
            call run_steadygs(top, pn > 0, gs, gk, wx, wy, settings, res)
        end if
    end subroutine reference_solver

    !> SteadyGS, nonlinear block Gauss–Seidel, columns from the leading edge (x = xmax)
    !! backwards, elements in contact only.  An adhesion element I in a run of adhesion
    !! elements whose front (leading) element is F satisfies the summed steady equations
    !! u_I − u_{F+x} = −δx·Σ_{K=I..F} w_K (the sum of s_K = 0 over the run); it is solved for
    !! p_I with the local coefficient A_II − A_{F+x,I}.  Summing along the run is what makes
    !! the sweeps converge: the element-wise equation s_I = 0 couples I to the element
    !! ahead as strongly as to itself, and Gauss–Seidel on it diverges.  A slip element
    !! solves p_I = −μk·pn_I·s_I/|s_I| on its friction circle with the local coefficient
    !! (A_II − A_{I+x,I})/δx (shared Newton solve of ConvexGS).  Updates are under-relaxed
    !! by `relax` (the summed equations are not symmetric; unrelaxed sweeps oscillate).
    subroutine run_steadygs(top, contact, gs, gk, wx, wy, settings, res)
        type(fc_tangential_operator), intent(inout) :: top
        logical, intent(in) :: contact(:, :)
        real(dp), intent(in) :: gs(:, :), gk(:, :), wx(:, :), wy(:, :)
        type(fc_rolling_settings), intent(in) :: settings
        type(fc_tangential_result), intent(inout) :: res
        real(dp), dimension(size(gs, 1), size(gs, 2)) :: px, py, ux, uy, pox, poy, cx, cy
        integer, dimension(size(gs, 1), size(gs, 2)) :: state
        real(dp) :: dxx, dyy, rdx, gdx, sx, sy, stx, sty, tx, ty, dpx, dpy, change, uxf, uyf, cxx, cyy, tnorm
        real(dp) :: accx(size(gs, 2)), accy(size(gs, 2))
        integer :: front(size(gs, 2))
        integer :: sweep, i, j, l, nx, ny, f
        real(dp), allocatable :: hist(:)
        logical :: converged
        nx = size(gs, 1); ny = size(gs, 2)
        gdx = top%grid%dx; rdx = 1/gdx
        call steady_diagonal(top, dxx, dyy)
        px = res%px; py = res%py
        call top%apply(px, py, ux, uy)
        state = EL_EXTERIOR
        where (contact) state = EL_ADHESION
        allocate (hist(settings%maxit))
        converged = .false.
        res%status = FC_NOT_CONVERGED
        change = huge(1.0_dp)
        do sweep = 1, settings%maxit
            pox = px; poy = py
            front = 0
            do i = nx, 1, -1
                do j = 1, ny
                    if (.not. contact(i, j)) then
                        front(j) = 0
                        cycle
                    end if
                    ! run of adhesion elements ahead of I (updated in this sweep)
                    if (front(j) == 0) then
                        front(j) = i; accx(j) = 0; accy(j) = 0
                    end if
                    f = front(j)
                    accx(j) = accx(j) + wx(i, j)*gdx; accy(j) = accy(j) + wy(i, j)*gdx
                    uxf = 0; uyf = 0
                    if (f < nx) then
                        uxf = ux(f + 1, j); uyf = uy(f + 1, j)
                    end if
                    ! adhesion trial from the run equation
                    cxx = top%a_xx%kernel(0, 0); cyy = top%a_yy%kernel(0, 0)
                    if (f < nx) then
                        cxx = cxx - top%a_xx%kernel(f + 1 - i, 0); cyy = cyy - top%a_yy%kernel(f + 1 - i, 0)
                    end if
                    tx = px(i, j) - (ux(i, j) - uxf + accx(j))/cxx
                    ty = py(i, j) - (uy(i, j) - uyf + accy(j))/cyy
                    if (tx**2 + ty**2 <= gs(i, j)**2) then
                        state(i, j) = EL_ADHESION
                    else
                        state(i, j) = EL_SLIP
                        uxf = 0; uyf = 0
                        if (i < nx) then
                            uxf = ux(i + 1, j); uyf = uy(i + 1, j)
                        end if
                        sx = wx(i, j) + (ux(i, j) - uxf)*rdx
                        sy = wy(i, j) + (uy(i, j) - uyf)*rdx
                        stx = sx - dxx*px(i, j)
                        sty = sy - dyy*py(i, j)
                        call circle_newton(gk(i, j), dxx, dyy, stx, sty, tx, ty)
                    end if
                    ! under-relaxation (slip: back onto the kinetic circle)
                    tx = px(i, j) + relax*(tx - px(i, j)); ty = py(i, j) + relax*(ty - py(i, j))
                    if (state(i, j) == EL_SLIP .and. tx**2 + ty**2 > 0) then
                        tnorm = gk(i, j)/hypot(tx, ty); tx = tx*tnorm; ty = ty*tnorm
                    end if
                    dpx = tx - px(i, j); dpy = ty - py(i, j)
                    if (state(i, j) == EL_SLIP) front(j) = 0   ! the next element starts a new run
                    if (dpx == 0 .and. dpy == 0) cycle
                    px(i, j) = tx; py(i, j) = ty
                    ! u_J += A_JI Δp_I for every J: O(n) column update
                    do l = 1, ny
                        ux(:, l) = ux(:, l) + dpx*top%a_xx%kernel(1 - i:nx - i, l - j) &
                            + dpy*top%a_xy%kernel(1 - i:nx - i, l - j)
                        uy(:, l) = uy(:, l) + dpx*top%a_xy%kernel(1 - i:nx - i, l - j) &
                            + dpy*top%a_yy%kernel(1 - i:nx - i, l - j)
                    end do
                end do
            end do
            change = traction_change(px, py, pox, poy)
            hist(sweep) = change
            res%iterations = sweep
            if (ieee_is_nan(change) .or. change > 1.0e12_dp) then
                res%status = FC_DIVERGED
                res%message = 'SteadyGS diverged (traction change not finite)'
                exit
            end if
            if (change < settings%tol) then
                converged = .true.
                exit
            end if
        end do
        call finish_status(res, converged, 'SteadyGS', settings%maxit, 'sweeps', change)
        res%outer_iterations = res%iterations
        ! report the exact slip of the final tractions (one FFT product)
        call top%apply(px, py, ux, uy)
        call convective_difference(ux, top%grid%dx, cx)
        call convective_difference(uy, top%grid%dx, cy)
        res%px = px; res%py = py; res%ux = ux; res%uy = uy
        res%sx = wx + cx; res%sy = wy + cy
        where (.not. contact)
            res%sx = 0; res%sy = 0
        end where
        res%state = state
        allocate (res%history(res%iterations), source=hist(1:res%iterations))
    end subroutine run_steadygs

    !> Reference 'march': transient rolling with the travelled distance δq = δx per step
    !! (previous displacements and tractions moved by one column, thesis eq. 4.10), each
    !! step solved by TangCG to tol/10 from the moved tractions, until the tractions change
    !! by less than `tol` from one step to the next.  Its fixed point is the steady state by
    !! construction; it converges as the physical transient does (the contact must travel
    !! a few times its length).  `maxit` bounds the number of steps.
    subroutine run_march(top, pn, mu, wx, wy, settings, res, stat, errmsg)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: pn(:, :), mu, wx(:, :), wy(:, :)
        type(fc_rolling_settings), intent(in) :: settings
        type(fc_tangential_result), intent(inout) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_tangential_settings) :: ts
        type(fc_tangential_result) :: step
        real(dp), dimension(size(pn, 1), size(pn, 2)) :: upx, upy, ppx, ppy, ox, oy, cx, cy
        real(dp), allocatable :: hist(:)
        real(dp) :: change, gdx
        integer :: k, nx, its, mvs
        logical :: converged
        nx = size(pn, 1); gdx = top%grid%dx
        ts%tol = settings%tol/10; ts%maxit = 10000
        ox = gdx*wx; oy = gdx*wy
        ppx = res%px; ppy = res%py
        call top%apply(ppx, ppy, upx, upy)
        allocate (hist(settings%maxit))
        converged = .false.; change = huge(1.0_dp); its = 0; mvs = 0
        res%status = FC_NOT_CONVERGED
        do k = 1, settings%maxit
            ! the material now at x_i was at x_{i+1} one step earlier; new material is undeformed
            upx(1:nx - 1, :) = upx(2:nx, :); upx(nx, :) = 0
            upy(1:nx - 1, :) = upy(2:nx, :); upy(nx, :) = 0
            call solve_tangential(top, pn, mu, ts, step, stat, errmsg, 0.0_dp, 0.0_dp, 0.0_dp, ux_prev=upx, &
                                  uy_prev=upy, px_start=ppx, py_start=ppy, offset_x=ox, offset_y=oy)
            if (stat /= 0) return
            its = its + step%iterations; mvs = mvs + step%matvecs
            if (step%status /= FC_CONVERGED) then
                res%status = step%status
                res%message = 'march: step solve: '//trim(step%message)
                exit
            end if
            change = traction_change(step%px, step%py, ppx, ppy)
            hist(k) = change
            res%outer_iterations = k
            ppx = step%px; ppy = step%py; upx = step%ux; upy = step%uy
            if (change < settings%tol) then
                converged = .true.
                exit
            end if
        end do
        call finish_status(res, converged, 'march', settings%maxit, 'steps', change)
        res%iterations = its; res%matvecs = mvs
        res%px = ppx; res%py = ppy
        call top%apply(ppx, ppy, res%ux, res%uy)
        call convective_difference(res%ux, gdx, cx)
        call convective_difference(res%uy, gdx, cy)
        res%sx = wx + cx; res%sy = wy + cy
        where (.not. pn > 0)
            res%sx = 0; res%sy = 0
        end where
        res%state = step%state
        allocate (res%history(res%outer_iterations), source=hist(1:res%outer_iterations))
    end subroutine run_march

end module fc_rolling_refsolvers
