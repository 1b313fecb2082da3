!> Tangential (frictional) contact problem: TangCG(K) and ConvexGS (thesis ch. 4; conventions in doc/conventions.md).
!!
!! Given the pressure pn on the contact area C and the Coulomb bound g = μ·pn, find the
!! tangential tractions p = (px, py) on C with slip s = w + (u − u') + offset,
!! u = A p (blocks A^xx, A^xy = A^yx, A^yy), rigid shift w_I = [ξ − φ·y_I, η + φ·x_I], and
!!   adhesion:  s_I = 0,   |p_I| ≤ g_I,
!!   slip:      |p_I| = g_I,  p_I = −g_I s_I/|s_I|            (thesis eqs. 4.10–4.13).
!! `offset` carries known displacement differences (the normal–tangential coupling A^xz·pn
!! for dissimilar materials, or anything else a caller adds).
!!
!! * TangCG(K) (thesis §4.3.3): active set with angle variables on slip elements,
!!   nonlinear CG with Polak–Ribière (β ≥ 0), restart on a change of subdivision, diagonal
!!   preconditioner scaling the reduced Jacobian's diagonal to A^xx_II (eq. 4.43), K inner
!!   iterations between subdivision checks with early exit when the tolerance is met
!!   (Remark 4.2).  All products with A by FFT (one forward transform per component
!!   shared by the three blocks).
!! * ConvexGS (thesis §4.2.4, ref. [95]): block Gauss–Seidel over the contact elements;
!!   per element the 2×2 adhesion solve, or a Newton solve for the angle on the traction
!!   circle.  Maintains the slip with O(n) column updates, so a sweep costs O(n_c·n): the
!!   reference solver, not a fast one.  Threads share the column updates row by row, with
!!   the one-thread result bit for bit.
!!
!! Stopping criterion (thesis eq. 4.49): ‖p^k − p^{k−1}‖_rms/‖p^k‖_rms < tol, with an
!! unchanged subdivision.
!!
!! Size (~850 lines): TangCG and ConvexGS share the loading, the result, the status and the
!! slip bookkeeping of thesis ch. 4 (also used by the rolling solvers); kept in one home like
!! CONTACT's `tangcg` (the operator is in [[fc_tangcg_operator]], the preconditioner in
!! [[fc_tangprec]], the prescribed-force loop in [[fc_force_newton]] and
!! [[fc_tangcg_force]]).  TangCG's element
!! loops (iteration, elastic start, subdivision checks) and ConvexGS's row-wise column
!! updates are written out as loops so that OpenMP can share them (doc/parallel.md); that
!! is most of the length beyond 600.
module fc_tangcg
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use fc_kinds
    use fc_geometry, only: fc_grid
    use fc_influence
    use fc_tangcg_operator, only: fc_tangential_operator, build_tangential_operator, coupling_displacements, &
        apply_block_inverse
    use fc_tangcg_types
    use fc_threads, only: omp_min_elements, fc_thread_count
    use fc_force_newton, only: fc_force_newton_t
    implicit none
    private

    ! the value types (fc_tangcg_types) and the operator (fc_tangcg_operator) are part of this
    ! module's interface
    public :: EL_EXTERIOR, EL_ADHESION, EL_SLIP
    public :: fc_tangential_settings, fc_tangential_result, fc_tangential_loading
    public :: fc_tangential_operator, build_tangential_operator, coupling_displacements
    public :: solve_tangential
    public :: circle_newton   ! shared with the steady rolling solver (fc_rolling)
    public :: finish_force_loop, finish_status, traction_change   ! shared with the rolling solvers

    !> TangCG's step: a direction whose curvature v·Jv is below this fraction of A^xx_II·|v|²
    !! has none (a periodic cell's uniform tractions): the step goes to the first traction
    !! bound instead of num/denom.  The half-space's smallest curvatures are ~1/n of A^xx_II.
    real(dp), parameter :: zero_curvature = 1.0e-13_dp

contains

    !> Solve the tangential problem for pressure `pn` [N/mm²] and friction `mu`, with the
    !! rigid shift (ξ, η, φ) prescribed.  Optional: previous displacements (ux_prev, uy_prev)
    !! for a transient step (u'), starting tractions (px_start, py_start), and a known
    !! displacement offset (offset_x, offset_y) added to the slip.
    subroutine solve_tangential(top, pn, mu, settings, res, stat, errmsg, xi, eta, phi, &
                                ux_prev, uy_prev, px_start, py_start, offset_x, offset_y)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: pn(:, :)
        real(dp), intent(in) :: mu
        type(fc_tangential_settings), intent(in) :: settings
        type(fc_tangential_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in) :: xi, eta, phi
        real(dp), intent(in), optional :: ux_prev(:, :), uy_prev(:, :), px_start(:, :), py_start(:, :)
        real(dp), intent(in), optional :: offset_x(:, :), offset_y(:, :)
        real(dp), allocatable :: wx(:, :), wy(:, :), g(:, :)
        real(dp) :: xc(size(pn, 1)), yj
        integer :: nx, ny, i, j
        integer(i8) :: t0, t1, rate   ! 64-bit: a µs clock (default integers tick in ms)
        stat = 0; errmsg = ''
        nx = top%grid%nx; ny = top%grid%ny
        if (.not. top%a_xx%built()) then
            stat = FC_ERR_NOT_READY; errmsg = 'solve_tangential: operator not built'; return
        end if
        if (size(pn, 1) /= nx .or. size(pn, 2) /= ny) then
            stat = FC_ERR_SHAPE; errmsg = 'solve_tangential: pn does not match the grid'; return
        end if
        if (.not. (mu >= 0)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.6,a)') 'tangential: mu = ', mu, ' must be >= 0'; return
        end if
        call check_iteration_settings(settings%tol, settings%maxit, stat, errmsg)
        if (stat /= 0) return
        if (settings%inner_k < 1) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a)') 'solver: inner_k = ', settings%inner_k, ' must be >= 1'; return
        end if
        if (settings%solver /= 'tangcg' .and. settings%solver /= 'convexgs') then
            stat = FC_ERR_VALUE; errmsg = "solver: tangential = '"//trim(settings%solver)//"' is not one of 'tangcg', 'convexgs'"
            return
        end if
        if (settings%preconditioner /= 'fft' .and. settings%preconditioner /= 'diagonal') then
            stat = FC_ERR_VALUE
            errmsg = "solver: preconditioner = '"//trim(settings%preconditioner)//"' is not one of 'fft', 'diagonal'"
            return
        end if
        if (settings%prec_form /= 'circulant' .and. settings%prec_form /= 'toeplitz') then
            stat = FC_ERR_VALUE
            errmsg = "solver: prec_form = '"//trim(settings%prec_form)//"' is not one of 'circulant', 'toeplitz'"
            return
        end if
        ! one pass for the rigid slip, the bound and the start (a flat-API call at 60×50 spends
        ! about as long here as in two solver iterations when each is a pass of its own)
        allocate (wx(nx, ny), wy(nx, ny), g(nx, ny))
        allocate (res%px(nx, ny), res%py(nx, ny), res%sx(nx, ny), res%sy(nx, ny), res%ux(nx, ny), res%uy(nx, ny))
        allocate (res%state(nx, ny))
        xc = top%grid%x([(i, i=1, nx)])
        do j = 1, ny
            yj = top%grid%y(j)
            do i = 1, nx
                wx(i, j) = xi - phi*yj
                wy(i, j) = eta + phi*xc(i)
                g(i, j) = mu*max(pn(i, j), 0.0_dp)
            end do
            if (present(px_start) .and. present(py_start)) then
                do i = 1, nx     ! no start traction outside the contact
                    res%px(i, j) = merge(px_start(i, j), 0.0_dp, pn(i, j) > 0)
                    res%py(i, j) = merge(py_start(i, j), 0.0_dp, pn(i, j) > 0)
                end do
            else
                res%px(:, j) = 0; res%py(:, j) = 0
                if (present(px_start)) res%px(:, j) = merge(px_start(:, j), 0.0_dp, pn(:, j) > 0)
                if (present(py_start)) res%py(:, j) = merge(py_start(:, j), 0.0_dp, pn(:, j) > 0)
            end if
        end do
        if (present(ux_prev)) wx = wx - ux_prev
        if (present(uy_prev)) wy = wy - uy_prev
        if (present(offset_x)) wx = wx + offset_x
        if (present(offset_y)) wy = wy + offset_y
        res%xi = xi; res%eta = eta; res%phi = phi
        top%nproducts = 0
        call system_clock(t0, rate)
        if (settings%solver == 'tangcg') then
            call run_tangcg(top, pn > 0, g, wx, wy, settings, res)
        else
            call run_convexgs(top, pn > 0, g, wx, wy, settings, res)
        end if
        call system_clock(t1)
        res%cpu_seconds = real(t1 - t0, dp)/rate
        res%matvecs = top%nproducts
        call tangential_summary(top%grid, res)
    end subroutine solve_tangential

    !> Totals of a prescribed-force loop ([[fc_force_newton]]) into its last accepted result:
    !! iterations, products and CPU seconds summed over every inner solve; a loop that did
    !! not converge turns a converged inner status into not_converged with the force error.
    subroutine finish_force_loop(res, nw, what)
        type(fc_tangential_result), intent(inout) :: res
        type(fc_force_newton_t), intent(in) :: nw
        character(len=*), intent(in) :: what    !! name of the loop in the message
        res%outer_iterations = nw%outer
        res%iterations = nw%iterations
        res%matvecs = nw%matvecs
        res%cpu_seconds = nw%cpu_seconds
        if (res%status == FC_CONVERGED .and. .not. nw%converged) then
            res%status = FC_NOT_CONVERGED
            write (res%message, '(a,a,es10.3,a)') what, ' not converged: force error ', norm2(nw%r), ' N'
        end if
    end subroutine finish_force_loop

    !> Forces, moment and element counts of a tangential solution.
    subroutine tangential_summary(grid, res)
        type(fc_grid), intent(in) :: grid
        type(fc_tangential_result), intent(inout) :: res
        integer :: i, j
        real(dp) :: xc(grid%nx)
        real(dp) :: fx, fy, column_x, column_y
        integer :: nadh, nslip
        ! one pass; every sum runs in element order, as the intrinsics' would
        xc = grid%x([(i, i=1, grid%nx)])
        fx = 0; fy = 0; res%mz = 0; nadh = 0; nslip = 0
        do j = 1, grid%ny
            column_x = 0; column_y = 0
            do i = 1, grid%nx
                fx = fx + res%px(i, j); fy = fy + res%py(i, j)
                column_y = column_y + xc(i)*res%py(i, j)
                column_x = column_x + res%px(i, j)
                if (res%state(i, j) == EL_ADHESION) nadh = nadh + 1
                if (res%state(i, j) == EL_SLIP) nslip = nslip + 1
            end do
            res%mz = res%mz + (column_y - grid%y(j)*column_x)
        end do
        res%fx = fx*grid%area(); res%fy = fy*grid%area()
        res%mz = res%mz*grid%area()
        res%dissipation = frictional_dissipation(res, grid%area())
        res%nadh = nadh; res%nslip = nslip
        res%ncon = res%nadh + res%nslip
    end subroutine tangential_summary

    !> Relative RMS change of the traction vector (eq. 4.49).
    real(dp) function traction_change(px, py, qx, qy, floor)
        real(dp), intent(in) :: px(:, :), py(:, :), qx(:, :), qy(:, :)
        !> lower bound of the denominator Σ|p|² [(N/mm²)²], so that the change of tractions
        !! that go to zero (a zero creepage) stays finite
        real(dp), intent(in), optional :: floor
        real(dp) :: num, den
        integer :: i, j
        num = 0; den = 0
        !$omp parallel do default(shared) private(i) reduction(+:num, den) schedule(static) if(size(px) > omp_min_elements)
        do j = 1, size(px, 2)
            do i = 1, size(px, 1)
                num = num + ((px(i, j) - qx(i, j))**2 + (py(i, j) - qy(i, j))**2)
                den = den + (px(i, j)**2 + py(i, j)**2)
            end do
        end do
        !$omp end parallel do
        if (present(floor)) den = max(den, floor)
        if (den > 0) then
            traction_change = sqrt(num/den)
        else if (num > 0) then
            traction_change = huge(1.0_dp)
        else
            traction_change = 0
        end if
    end function traction_change

    !> TangCG(K), thesis §4.3.3 with the early exit of Remark 4.2.
    subroutine run_tangcg(top, contact, g, wx, wy, settings, res)
        type(fc_tangential_operator), intent(inout) :: top
        logical, intent(in) :: contact(:, :)
        real(dp), intent(in) :: g(:, :), wx(:, :), wy(:, :)
        type(fc_tangential_settings), intent(in) :: settings
        type(fc_tangential_result), intent(inout) :: res
        real(dp), dimension(size(g, 1), size(g, 2)) :: px, py, sx, sy, ux, uy, dax, day, zx, zy, vax, vay, &
            vsx, vsy, qsx, qsy, qax, qay, pox, poy, dox, doy, mx, my
        logical, dimension(size(g, 1), size(g, 2)) :: adh, slp
        real(dp) :: axx, ayy, alpha, beta, zd_old, zd, denom, change, num, t, vv
        integer :: it, inner, nmoved, i, j, nx, ny
        logical :: changed, converged, check_now, fft_prec, par, circulant
        real(dp), allocatable :: hist(:)
        logical, allocatable :: badh(:, :), bslp(:, :)  ! subdivision of the best cold-start candidate
        real(dp) :: jbest
        axx = top%a_xx%kernel(0, 0); ayy = top%a_yy%kernel(0, 0)
        nx = size(g, 1); ny = size(g, 2)
        ! the iteration's element loops: OpenMP over columns on large grids (fc_threads),
        ! element order otherwise; sums as the intrinsics compute them (same results serially)
        par = nx*ny > omp_min_elements
        px = res%px; py = res%py
        fft_prec = settings%precondition .and. settings%preconditioner == 'fft'
        circulant = settings%prec_form == 'circulant'
        if (fft_prec .and. .not. any(contact .and. (px /= 0 .or. py /= 0))) then
            call cold_start()
        else
            ! initial subdivision (step 0): adhesion everywhere in contact; a warm start whose
            ! traction reaches the bound starts in slip
            call subdivide_start()
            call top%apply(px, py, ux, uy)
            call set_slip()
        end if
        allocate (hist(settings%maxit))
        changed = .true.; converged = .false.
        zd_old = 1; vax = 0; vay = 0; dox = 0; doy = 0
        ! with the FFT preconditioner's elastic start the subdivision is nearly right: check it
        ! after the first iteration already (the elements the start put wrongly are found
        ! before CG builds up directions), then every K iterations
        inner = 0
        if (fft_prec) inner = settings%inner_k - 1
        res%status = FC_NOT_CONVERGED
        res%outer_iterations = 0
        change = huge(1.0_dp)
        do it = 1, settings%maxit
            ! step 2: primary defect (and, for the FFT preconditioner, its adhesion part m)
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    if (adh(i, j)) then
                        dax(i, j) = -sx(i, j); day(i, j) = -sy(i, j)
                    else if (slp(i, j)) then
                        dax(i, j) = -(px(i, j)*sy(i, j) - py(i, j)*sx(i, j)); day(i, j) = 0
                    else
                        dax(i, j) = 0; day(i, j) = 0
                    end if
                    if (fft_prec) then
                        if (adh(i, j)) then
                            mx(i, j) = dax(i, j); my(i, j) = day(i, j)
                        else
                            mx(i, j) = 0; my(i, j) = 0
                        end if
                    end if
                end do
            end do
            !$omp end parallel do
            ! step 3: preconditioner
            if (fft_prec) then
                ! adhesion: block Toeplitz inverse of A (masked); slip: the inverse of the
                ! reduced Jacobian's diagonal (as below, without the scaling to A^xx_II)
                call apply_block_inverse(top, mx, my, zx, zy, circulant)
                !$omp parallel do default(shared) private(i) schedule(static) if(par)
                do j = 1, ny
                    do i = 1, nx
                        if (slp(i, j)) then
                            zx(i, j) = dax(i, j)/(px(i, j)**2*ayy + py(i, j)**2*axx &
                                + max(0.0_dp, -(px(i, j)*sx(i, j) + py(i, j)*sy(i, j))))
                            zy(i, j) = 0
                        else if (.not. adh(i, j)) then
                            zx(i, j) = 0; zy(i, j) = 0
                        end if
                    end do
                end do
                !$omp end parallel do
            else
                ! diagonal preconditioner, eq. (4.43), scaled to A^xx_II, or none (the identity
                ! on the unknowns): z = M d
                !$omp parallel do default(shared) private(i) schedule(static) if(par)
                do j = 1, ny
                    do i = 1, nx
                        if (adh(i, j)) then
                            mx(i, j) = 1; my(i, j) = 1
                            if (settings%precondition) my(i, j) = axx/ayy
                        else if (slp(i, j)) then
                            ! diagonal of the reduced Jacobian, px²A^yy + py²A^xx − p·s; −p·s = g|s| > 0
                            ! once p opposes s, but an element just moved to slip may not yet: keep
                            ! the part that is positive so that M stays positive definite
                            mx(i, j) = 1; my(i, j) = 0
                            if (settings%precondition) mx(i, j) = axx/(px(i, j)**2*ayy + py(i, j)**2*axx &
                                + max(0.0_dp, -(px(i, j)*sx(i, j) + py(i, j)*sy(i, j))))
                        else
                            mx(i, j) = 0; my(i, j) = 0
                        end if
                        zx(i, j) = mx(i, j)*dax(i, j); zy(i, j) = my(i, j)*day(i, j)
                    end do
                end do
                !$omp end parallel do
            end if
            zd = 0; num = 0
            !$omp parallel do default(shared) private(i) reduction(+:zd, num) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    zd = zd + (zx(i, j)*dax(i, j) + zy(i, j)*day(i, j))
                    num = num + (zx(i, j)*(dax(i, j) - dox(i, j)) + zy(i, j)*(day(i, j) - doy(i, j)))
                end do
            end do
            !$omp end parallel do
            ! step 4: search direction (Polak–Ribière, β ≥ 0; restart on a new subdivision)
            beta = 0
            if (.not. changed) beta = max(0.0_dp, num/zd_old)
            zd_old = zd
            ! steps 4–5: search direction v_a, auxiliary direction v_s
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    if (changed) then
                        vax(i, j) = zx(i, j); vay(i, j) = zy(i, j)
                    else
                        vax(i, j) = zx(i, j) + beta*vax(i, j); vay(i, j) = zy(i, j) + beta*vay(i, j)
                    end if
                    dox(i, j) = dax(i, j); doy(i, j) = day(i, j)
                    if (adh(i, j)) then
                        vsx(i, j) = vax(i, j); vsy(i, j) = vay(i, j)
                    else if (slp(i, j)) then
                        vsx(i, j) = -vax(i, j)*py(i, j); vsy(i, j) = vax(i, j)*px(i, j)
                    else
                        vsx(i, j) = 0; vsy(i, j) = 0
                    end if
                end do
            end do
            !$omp end parallel do
            ! steps 6–7: change of slip and of the primary defect
            call top%apply(vsx, vsy, qsx, qsy)
            ! step 8 (sums): denominator and numerator of the step length
            denom = 0; num = 0; vv = 0
            !$omp parallel do default(shared) private(i) reduction(+:denom, num, vv) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    vv = vv + (vsx(i, j)**2 + vsy(i, j)**2)
                    if (adh(i, j)) then
                        qax(i, j) = qsx(i, j); qay(i, j) = qsy(i, j)
                    else if (slp(i, j)) then
                        qax(i, j) = px(i, j)*qsy(i, j) - py(i, j)*qsx(i, j) + sy(i, j)*vsx(i, j) - sx(i, j)*vsy(i, j)
                        qay(i, j) = 0
                    else
                        qax(i, j) = 0; qay(i, j) = 0
                    end if
                    denom = denom + (qax(i, j)*vax(i, j) + qay(i, j)*vay(i, j))
                    num = num + (dax(i, j)*vax(i, j) + day(i, j)*vay(i, j))
                end do
            end do
            !$omp end parallel do
            ! step 8: step length
            if (abs(denom) > zero_curvature*axx*vv) then
                alpha = num/denom
            else if (zd == 0) then      ! nothing to do: the defect vanishes
                change = 0
                alpha = 0
            else if (maxval(abs(dax)) + maxval(abs(day)) <= settings%tol*axx*maxval(g)) then
                ! no curvature and a defect below the slip one bound traction makes at this
                ! tolerance: nothing to gain (a periodic cell in adhesion everywhere carries any
                ! uniform traction at no slip)
                change = 0
                alpha = 0
            else
                ! no curvature along the direction: the elastic energy does not grow, only the
                ! traction bounds stop the step (the periodic half-space's uniform tractions,
                ! whose displacement is defined up to a constant).  Step to the first bound an
                ! adhesion element reaches, just past it, and check the subdivision at once.
                alpha = step_to_bound()
                if (.not. (alpha > 0 .and. alpha < huge(1.0_dp))) then
                    res%status = FC_DIVERGED
                    res%message = 'TangCG: zero curvature along the search direction'
                    exit
                end if
                inner = settings%inner_k
            end if
            ! step 9: update and project slip tractions on the circle
            !$omp parallel do default(shared) private(i, t) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    pox(i, j) = px(i, j); poy(i, j) = py(i, j)
                    px(i, j) = px(i, j) + alpha*vsx(i, j); py(i, j) = py(i, j) + alpha*vsy(i, j)
                    if (slp(i, j)) then
                        t = sqrt(px(i, j)**2 + py(i, j)**2)
                        px(i, j) = g(i, j)*px(i, j)/t; py(i, j) = g(i, j)*py(i, j)/t
                    end if
                end do
            end do
            !$omp end parallel do
            change = traction_change(px, py, pox, poy)
            if (ieee_is_nan(change) .or. change > 1.0e12_dp) then
                res%status = FC_DIVERGED
                res%message = 'TangCG diverged (traction change not finite)'
                exit
            end if
            hist(it) = change
            res%iterations = it
            inner = inner + 1
            ! u = A p is linear: u + α·q_s is exact on adhesion.  The projection on the circle
            ! moves slip tractions by O(α²|v_s|²/g) more; that second-order part is picked up
            ! by the exact product at each subdivision check (at least every K iterations).
            check_now = inner >= settings%inner_k .or. change < settings%tol
            if (check_now .and. any(slp)) then
                call top%apply(px, py, ux, uy)
                call set_slip()
            else
                !$omp parallel do default(shared) private(i) schedule(static) if(par)
                do j = 1, ny
                    do i = 1, nx
                        ux(i, j) = ux(i, j) + alpha*qsx(i, j); uy(i, j) = uy(i, j) + alpha*qsy(i, j)
                        sx(i, j) = wx(i, j) + ux(i, j); sy(i, j) = wy(i, j) + uy(i, j)
                    end do
                end do
                !$omp end parallel do
            end if
            changed = .false.
            if (check_now) then
                inner = 0
                res%outer_iterations = res%outer_iterations + 1
                ! thesis step 11.1: adhesion elements above the bound go to slip (a rounding
                ! excess of 1e−12 relative is not a violation: an element on the circle with
                ! s = 0 would otherwise alternate between the two sets)
                nmoved = 0
                !$omp parallel do default(shared) private(i, t) reduction(+:nmoved) schedule(static) if(par)
                do j = 1, ny
                    do i = 1, nx
                        if (adh(i, j) .and. px(i, j)**2 + py(i, j)**2 > (1 + 1.0e-12_dp)*g(i, j)**2) then
                            slp(i, j) = .true.; adh(i, j) = .false.
                            t = sqrt(px(i, j)**2 + py(i, j)**2)
                            px(i, j) = g(i, j)*px(i, j)/t; py(i, j) = g(i, j)*py(i, j)/t
                            nmoved = nmoved + 1
                        end if
                    end do
                end do
                !$omp end parallel do
                if (nmoved > 0) then
                    call top%apply(px, py, ux, uy)
                    call set_slip()
                    changed = .true.
                end if
                ! thesis step 11.2: slip elements whose traction does not oppose the slip go to adhesion
                nmoved = 0
                !$omp parallel do default(shared) private(i) reduction(+:nmoved) schedule(static) if(par)
                do j = 1, ny
                    do i = 1, nx
                        if (slp(i, j) .and. px(i, j)*sx(i, j) + py(i, j)*sy(i, j) > 0) then
                            adh(i, j) = .true.; slp(i, j) = .false.
                            nmoved = nmoved + 1
                        end if
                    end do
                end do
                !$omp end parallel do
                if (nmoved > 0) changed = .true.
                ! thesis step 11.3: convergence
                if (.not. changed .and. change < settings%tol) then
                    converged = .true.
                    exit
                end if
            end if
        end do
        call finish_status(res, converged, 'TangCG', settings%maxit, 'iterations', change)
        res%px = px; res%py = py
        res%ux = ux; res%uy = uy
        res%sx = sx; res%sy = sy
        res%state = EL_EXTERIOR
        where (adh) res%state = EL_ADHESION
        where (slp) res%state = EL_SLIP
        where (.not. contact)
            res%sx = 0; res%sy = 0
        end where
        allocate (res%history(res%iterations), source=hist(1:res%iterations))
    contains
        !> Initial subdivision of (px, py): elements whose traction reaches the bound start in
        !! slip, projected on the circle (1e−8 slack: a converged start has its slip
        !! tractions on the bound up to rounding); a zero bound carries no traction.
        subroutine subdivide_start()
            real(dp) :: tn
            !$omp parallel do default(shared) private(i, tn) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    adh(i, j) = contact(i, j); slp(i, j) = .false.
                    if (.not. contact(i, j)) cycle
                    if (.not. g(i, j) > 0) then
                        adh(i, j) = .false.; px(i, j) = 0; py(i, j) = 0
                    else if (px(i, j)**2 + py(i, j)**2 >= (1 - 1.0e-8_dp)*g(i, j)**2) then
                        slp(i, j) = .true.; adh(i, j) = .false.
                        tn = sqrt(px(i, j)**2 + py(i, j)**2)
                        px(i, j) = g(i, j)*px(i, j)/tn; py(i, j) = g(i, j)*py(i, j)/tn
                    end if
                end do
            end do
            !$omp end parallel do
        end subroutine subdivide_start

        !> Cold start with the FFT preconditioner.  The full-adhesion estimate e = −M w (M the
        !! block Toeplitz inverse, see [[fc_tangprec]]) has the right shape but, on a bounded
        !! contact area, an energy-optimal scale c = −wᵀe/eᵀAe of only 0.26–0.37 on the
        !! Table 4.1 cases (M inverts the operator of the unbounded grid).  Candidates:
        !!  1. e, projected on the circles where it exceeds the bound, slip elements then
        !!     re-solved locally (the angle opposing the slip of the others, as ConvexGS);
        !!  2. the same from c·e (adhesion-dominated cases: fewer spurious slip elements);
        !!  3. candidate 1 with every contact element re-decided locally (full slip: the
        !!     elements near the spin pole that the estimate puts in adhesion).
        !! The candidate with the lowest energy J = ½pᵀAp + wᵀp (the functional the
        !! tangential problem minimises on |p_I| ≤ g_I) is kept.  Cost: one product with M
        !! and six with A.
        !> The smallest α > 0 at which an adhesion traction p + α·v reaches its bound g, times
        !! (1 + 1e−9) so that the element is past it (huge when no adhesion element moves).
        real(dp) function step_to_bound() result(a)
            real(dp) :: pv, v2, pp, ai
            a = huge(1.0_dp)
            do j = 1, ny
                do i = 1, nx
                    if (.not. adh(i, j)) cycle
                    v2 = vsx(i, j)**2 + vsy(i, j)**2
                    if (.not. (v2 > 0)) cycle
                    pv = px(i, j)*vsx(i, j) + py(i, j)*vsy(i, j)
                    pp = px(i, j)**2 + py(i, j)**2
                    ai = (-pv + sqrt(max(0.0_dp, pv**2 + v2*(g(i, j)**2 - pp))))/v2
                    a = min(a, max(ai, 0.0_dp))
                end do
            end do
            if (a < huge(1.0_dp)) a = a*(1 + 1.0e-9_dp) + tiny(1.0_dp)
        end function step_to_bound

        subroutine cold_start()
            logical, allocatable :: qadh(:, :), qslp(:, :)
            real(dp) :: c, scl, zu, zw
            integer :: cand
            ! work arrays of the iteration, free until it starts, hold the candidates:
            ! estimate (zx, zy), candidate 1 before its local step (vsx, vsy; u: qsx, qsy),
            ! best so far (qax, qay; u: pox, poy)
            allocate (badh, bslp, qadh, qslp, mold=adh)
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    if (contact(i, j)) then
                        dax(i, j) = -wx(i, j); day(i, j) = -wy(i, j)
                    else
                        dax(i, j) = 0; day(i, j) = 0
                    end if
                end do
            end do
            !$omp end parallel do
            call apply_block_inverse(top, dax, day, zx, zy, circulant=.false.)
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    if (.not. contact(i, j)) then
                        zx(i, j) = 0; zy(i, j) = 0
                    end if
                end do
            end do
            !$omp end parallel do
            call top%apply(zx, zy, ux, uy)
            zu = 0; zw = 0
            !$omp parallel do default(shared) private(i) reduction(+:zu, zw) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    zu = zu + (zx(i, j)*ux(i, j) + zy(i, j)*uy(i, j))
                    zw = zw + (zx(i, j)*wx(i, j) + zy(i, j)*wy(i, j))
                end do
            end do
            !$omp end parallel do
            c = 1
            if (zu > 0) c = -zw/zu
            if (.not. (c > 0 .and. c < 1)) c = 1
            jbest = huge(1.0_dp)
            do cand = 1, 2
                scl = 1
                if (cand == 2) scl = c
                !$omp parallel do default(shared) private(i) schedule(static) if(par)
                do j = 1, ny
                    do i = 1, nx
                        px(i, j) = scl*zx(i, j); py(i, j) = scl*zy(i, j)
                    end do
                end do
                !$omp end parallel do
                call subdivide_start()
                call top%apply(px, py, ux, uy)
                call set_slip()
                if (cand == 1) then
                    call copy_pair(px, py, vsx, vsy); call copy_pair(ux, uy, qsx, qsy)
                    qadh = adh; qslp = slp
                    call local_decision(.true.)
                    call keep()
                    call copy_pair(vsx, vsy, px, py); call copy_pair(qsx, qsy, ux, uy)
                    adh = qadh; slp = qslp
                    call set_slip()
                end if
                call local_decision(.false.)
                call keep()
            end do
            call copy_pair(qax, qay, px, py); call copy_pair(pox, poy, ux, uy)
            adh = badh; slp = bslp
            call set_slip()
        end subroutine cold_start

        !> Keep (px, py) as the best cold-start candidate if its energy is the lowest so far.
        subroutine keep()
            real(dp) :: jv
            jv = 0
            !$omp parallel do default(shared) private(i) reduction(+:jv) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    jv = jv + (0.5_dp*(px(i, j)*ux(i, j) + py(i, j)*uy(i, j)) + px(i, j)*wx(i, j) + py(i, j)*wy(i, j))
                end do
            end do
            !$omp end parallel do
            if (jv < jbest) then
                jbest = jv; badh = adh; bslp = slp
                call copy_pair(px, py, qax, qay); call copy_pair(ux, uy, pox, poy)
            end if
        end subroutine keep

        !> Slip elements (with `all`, every contact element with a positive bound) re-decided
        !! by the element's own problem with the other tractions fixed (ConvexGS's local
        !! step): slip with the angle of [[circle_newton]] when the local adhesion traction
        !! exceeds the bound, else adhesion (keeping its traction); then u and s recomputed.
        subroutine local_decision(all)
            logical, intent(in) :: all
            real(dp) :: stx, sty, tx, ty
            !$omp parallel do default(shared) private(i, stx, sty, tx, ty) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    if (.not. (slp(i, j) .or. (all .and. adh(i, j) .and. g(i, j) > 0))) cycle
                    stx = sx(i, j) - axx*px(i, j); sty = sy(i, j) - ayy*py(i, j)
                    tx = -stx/axx; ty = -sty/ayy
                    if (tx**2 + ty**2 > g(i, j)**2) then
                        call circle_newton(g(i, j), axx, ayy, stx, sty, px(i, j), py(i, j))
                        slp(i, j) = .true.; adh(i, j) = .false.
                    else if (slp(i, j)) then
                        slp(i, j) = .false.; adh(i, j) = .true.
                    end if
                end do
            end do
            !$omp end parallel do
            call top%apply(px, py, ux, uy)
            call set_slip()
        end subroutine local_decision

        !> s = w + u (elementwise; threaded on large grids).
        subroutine set_slip()
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    sx(i, j) = wx(i, j) + ux(i, j); sy(i, j) = wy(i, j) + uy(i, j)
                end do
            end do
            !$omp end parallel do
        end subroutine set_slip

        !> (bx, by) = (ax, ay) (threaded on large grids).
        subroutine copy_pair(ax, ay, bx, by)
            real(dp), intent(in) :: ax(:, :), ay(:, :)
            real(dp), intent(out) :: bx(:, :), by(:, :)
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    bx(i, j) = ax(i, j); by(i, j) = ay(i, j)
                end do
            end do
            !$omp end parallel do
        end subroutine copy_pair
    end subroutine run_tangcg

    !> ConvexGS, block Gauss–Seidel over the contact elements (thesis §4.2.4).
    !! Each element's change updates the slip of every element (A's column).  Within row j
    !! the row's own slips are updated at once (the next element of the row needs them); the
    !! other rows receive row j's changes after the row, in the same order, each row by one
    !! thread: every slip gets the same sums in the same order as element by element, so
    !! the result does not depend on the thread count (bit for bit).
    subroutine run_convexgs(top, contact, g, wx, wy, settings, res)
        type(fc_tangential_operator), intent(inout) :: top
        logical, intent(in) :: contact(:, :)
        real(dp), intent(in) :: g(:, :), wx(:, :), wy(:, :)
        type(fc_tangential_settings), intent(in) :: settings
        type(fc_tangential_result), intent(inout) :: res
        real(dp), dimension(size(g, 1), size(g, 2)) :: px, py, sx, sy, ux, uy, pox, poy
        integer, dimension(size(g, 1), size(g, 2)) :: state
        real(dp) :: axx, ayy, stx, sty, tx, ty, dpx, dpy, change
        real(dp) :: dx_row(size(g, 1)), dy_row(size(g, 1))
        integer :: i_row(size(g, 1))
        integer :: sweep, i, j, nx, ny, nd
        real(dp), allocatable :: hist(:)
        logical :: converged, par
        nx = size(g, 1); ny = size(g, 2)
        par = fc_thread_count() > 1
        axx = top%a_xx%kernel(0, 0); ayy = top%a_yy%kernel(0, 0)
        px = res%px; py = res%py
        call top%apply(px, py, ux, uy)
        sx = wx + ux; sy = wy + uy
        state = EL_EXTERIOR
        where (contact) state = EL_ADHESION
        allocate (hist(settings%maxit))
        converged = .false.
        res%status = FC_NOT_CONVERGED
        change = huge(1.0_dp)
        do sweep = 1, settings%maxit
            pox = px; poy = py
            do j = 1, ny
                nd = 0
                do i = 1, nx
                    if (.not. contact(i, j)) cycle
                    ! slip without the element's own contribution (A^xy_II = 0 by symmetry)
                    stx = sx(i, j) - axx*px(i, j)
                    sty = sy(i, j) - ayy*py(i, j)
                    tx = -stx/axx; ty = -sty/ayy
                    if (tx**2 + ty**2 <= g(i, j)**2) then
                        state(i, j) = EL_ADHESION
                    else
                        state(i, j) = EL_SLIP
                        call circle_newton(g(i, j), axx, ayy, stx, sty, tx, ty)
                    end if
                    dpx = tx - px(i, j); dpy = ty - py(i, j)
                    if (dpx == 0 .and. dpy == 0) cycle
                    px(i, j) = tx; py(i, j) = ty
                    call add_column(j, i, dpx, dpy)
                    nd = nd + 1
                    i_row(nd) = i; dx_row(nd) = dpx; dy_row(nd) = dpy
                end do
                if (nd == 0) cycle
                ! s_J += A_JI Δp_I for the rows J below and above: O(n) per changed element.
                ! One thread calls the loop outside a parallel region (no region per row)
                if (par .and. int(nd, i8)*nx*ny > omp_min_elements) then
                    !$omp parallel default(shared)
                    call spread_row_changes()
                    !$omp end parallel
                else
                    call spread_row_changes()
                end if
            end do
            change = traction_change(px, py, pox, poy)
            hist(sweep) = change
            res%iterations = sweep
            if (ieee_is_nan(change)) then
                res%status = FC_DIVERGED
                res%message = 'ConvexGS diverged (traction change not finite)'
                exit
            end if
            if (change < settings%tol) then
                converged = .true.
                exit
            end if
        end do
        call finish_status(res, converged, 'ConvexGS', settings%maxit, 'sweeps', change)
        res%outer_iterations = res%iterations
        ! report the exact slip of the final tractions (one FFT product)
        call top%apply(px, py, ux, uy)
        res%px = px; res%py = py
        res%ux = ux; res%uy = uy
        res%sx = wx + ux; res%sy = wy + uy
        where (.not. contact)
            res%sx = 0; res%sy = 0
        end where
        res%state = state
        allocate (res%history(res%iterations), source=hist(1:res%iterations))
    contains
        !> The changes of row j's tractions reach the slips of the other rows, in element
        !! order; the rows are shared among the threads of an enclosing parallel region.
        subroutine spread_row_changes()
            integer :: k, l
            !$omp do schedule(static)
            do l = 1, ny
                if (l == j) cycle
                do k = 1, nd
                    call add_column(l, i_row(k), dx_row(k), dy_row(k))
                end do
            end do
            !$omp end do
        end subroutine spread_row_changes

        !> Row l of the slip gets the change (dx, dy) of the traction of element (i, j).
        subroutine add_column(l, i, dx, dy)
            integer, intent(in) :: l, i
            real(dp), intent(in) :: dx, dy
            sx(:, l) = sx(:, l) + dx*top%a_xx%kernel(1 - i:nx - i, l - j) + dy*top%a_xy%kernel(1 - i:nx - i, l - j)
            sy(:, l) = sy(:, l) + dx*top%a_xy%kernel(1 - i:nx - i, l - j) + dy*top%a_yy%kernel(1 - i:nx - i, l - j)
        end subroutine add_column
    end subroutine run_convexgs

    !> Final status and message of a tangential solve; `change` is the last traction change.
    subroutine finish_status(res, converged, solver, maxit, unit_name, change)
        type(fc_tangential_result), intent(inout) :: res
        logical, intent(in) :: converged
        character(len=*), intent(in) :: solver, unit_name
        integer, intent(in) :: maxit
        real(dp), intent(in) :: change
        if (converged) then
            res%status = FC_CONVERGED
            res%message = 'converged'
        else if (res%status == FC_NOT_CONVERGED) then
            write (res%message, '(a,i0,1x,a,a,es10.3)') solver//' not converged in maxit = ', maxit, unit_name, &
                '; last traction change ', change
        end if
        res%residual = change
    end subroutine finish_status

    !> Traction on the circle |p| = g opposing the slip s = s̃ + diag(axx, ayy)·p:
    !! Newton on the angle θ of F(θ) = px·sy − py·sx = 0, started opposite to s̃.
    pure subroutine circle_newton(g, axx, ayy, stx, sty, px, py)
        real(dp), intent(in) :: g, axx, ayy, stx, sty
        real(dp), intent(out) :: px, py
        real(dp) :: th, f, df, c, s, dth
        integer :: it
        th = atan2(-sty, -stx)
        do it = 1, 50
            c = cos(th); s = sin(th)
            f = g*(c*sty - s*stx) + g**2*(ayy - axx)*s*c
            df = g*(-s*sty - c*stx) + g**2*(ayy - axx)*(c**2 - s**2)
            if (df == 0) exit
            dth = -f/df
            th = th + dth
            if (abs(dth) < 1.0e-15_dp) exit
        end do
        px = g*cos(th); py = g*sin(th)
    end subroutine circle_newton

end module fc_tangcg
