!> The tangential problem of a [[fc_tangential_loading]] ([[solve_tangential_loading]]):
!! prescribed shifts are one [[solve_tangential]]; prescribed forces (Fx, Fy) are met by the
!! outer Broyden loop of [[fc_force_newton]] on the rigid shift (ξ, η), each inner solve
!! TangCG (or ConvexGS) warm-started from the last.  A periodic cell ([[fc_periodic]]) needs
!! more: its many small contacts are stiffer than Mindlin's first guess (the first shift is
!! scaled until something sticks: shrunk while its force exceeds the target, grown while
!! the force falls short, as when the pressure of dissimilar bodies alone slips every
!! element), and a cell in contact everywhere is singular (uniform
!! tractions displace nothing): full stick is solved directly, and otherwise the loop runs
!! on an operator whose uniform mode has the compliance of Mindlin's patch of the cell's
!! size, with the shift converted back (doc/parallel.md, "A cell in contact everywhere").
module fc_tangcg_force
    use fc_kinds
    use fc_tangcg_operator, only: fc_tangential_operator, apply_block_inverse
    use fc_tangcg_types
    use fc_tangcg, only: solve_tangential, finish_force_loop
    use fc_force_newton, only: fc_force_newton_t
    implicit none
    private

    public :: solve_tangential_loading

contains

    !> Solve the tangential problem for a [[fc_tangential_loading]]: prescribed shifts go
    !! straight to [[solve_tangential]]; prescribed forces (Fx, Fy) are met by an outer
    !! Broyden iteration on (ξ, η), started from Mindlin's initial stiffness 8Ga/(2−ν)
    !! (a from the contact area) and safeguarded by step halving.  Each inner solve starts
    !! from the previous tractions.  |(Fx, Fy)| must be below μ·Fn (full slip has no unique
    !! shift).  Force tolerance: tol·μ·Fn.
    subroutine solve_tangential_loading(top, pn, load, settings, res, stat, errmsg, ux_prev, uy_prev, &
                                        px_start, py_start, offset_x, offset_y, xi_start, eta_start)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: pn(:, :)
        type(fc_tangential_loading), intent(in) :: load
        type(fc_tangential_settings), intent(in) :: settings
        type(fc_tangential_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: ux_prev(:, :), uy_prev(:, :), px_start(:, :), py_start(:, :)
        real(dp), intent(in), optional :: offset_x(:, :), offset_y(:, :)
        real(dp), intent(in), optional :: xi_start, eta_start  !! first guess of the shift (force mode)
        real(dp), allocatable :: zx(:, :), zy(:, :), ox(:, :), oy(:, :), qx(:, :), qy(:, :)
        type(fc_tangential_result) :: trial
        type(fc_tangential_settings) :: inner
        type(fc_force_newton_t) :: nw
        real(dp) :: fn, flimit, k0, a, jac(2, 2), x(2), probe_s, beta, cell, qbar(2)
        real(dp) :: k0_mindlin, x0(2), s, s_lo, s_hi, xnorm, fnorm
        real(dp), parameter :: max_secant = 1000   !! the probes' secant stiffness, at most, over Mindlin's
        integer :: nx, ny, k, probe_it, probe_mv
        logical :: probed
        logical :: accepted, done
        nx = size(pn, 1); ny = size(pn, 2)
        if (.not. load%force_prescribed) then
            ! prescribed shifts: one solve.  The optional arrays go on as allocatables, absent
            ! when unallocated: passed on as optional dummies, gfortran's bounds checking
            ! computes a descriptor from an absent one (signed overflow on garbage under
            ! UBSan).  The orchestrator calls solve_tangential itself and copies nothing.
            if (present(ux_prev)) zx = ux_prev
            if (present(uy_prev)) zy = uy_prev
            if (present(px_start)) qx = px_start
            if (present(py_start)) qy = py_start
            if (present(offset_x)) ox = offset_x
            if (present(offset_y)) oy = offset_y
            call solve_tangential(top, pn, load%mu, settings, res, stat, errmsg, load%xi, load%eta, load%phi, &
                                  zx, zy, qx, qy, ox, oy)
            return
        end if
        allocate (zx(nx, ny), zy(nx, ny), ox(nx, ny), oy(nx, ny), qx(nx, ny), qy(nx, ny))
        zx = 0; zy = 0; ox = 0; oy = 0
        if (present(ux_prev)) zx = ux_prev
        if (present(uy_prev)) zy = uy_prev
        if (present(offset_x)) ox = offset_x
        if (present(offset_y)) oy = offset_y
        qx = 0; qy = 0
        if (present(px_start)) qx = px_start
        if (present(py_start)) qy = py_start
        stat = 0; errmsg = ''
        probe_it = 0; probe_mv = 0; probe_s = 0; probed = .false.
        fn = sum(max(pn, 0.0_dp))*top%grid%area()
        flimit = load%mu*fn
        if (.not. (hypot(load%fx, load%fy) < flimit)) then
            stat = FC_ERR_FRICTION_BOUND
            write (errmsg, '(a,es12.5,a,es12.5,a)') 'tangential: |(fx, fy)| = ', hypot(load%fx, load%fy), &
                ' must be < mu*fn = ', flimit, ' (full slip has no unique shift)'
            return
        end if
        if (top%periodic .and. all(pn > 0)) then
            call periodic_full_stick(done)
            if (done) return
        end if
        a = sqrt(count(pn > 0)*top%grid%area()/pi)
        k0 = 8*top%material%g*a/(2 - top%material%nu)
        k0_mindlin = k0
        ! a cell in contact everywhere: the uniform traction mode, which displaces nothing, gets
        ! the compliance of Mindlin's patch of the cell's size (A_β, fc_tangcg_operator), so
        ! that the force follows the shift as for one contact; the loop's shifts are then
        ! w_β = w − β·q̄ (q̄ the mean traction)
        cell = size(pn)*top%grid%area()
        beta = 0
        if (top%periodic .and. all(pn > 0)) beta = cell/k0
        top%mean_compliance = beta
        call loop_on_shift()
        top%mean_compliance = 0
        if (beta > 0 .and. stat == 0 .and. allocated(res%ux)) then
            ! the physical shift and displacements
            qbar = [sum(res%px), sum(res%py)]/size(pn)
            res%xi = res%xi + beta*qbar(1); res%eta = res%eta + beta*qbar(2)
            res%ux = res%ux - beta*qbar(1); res%uy = res%uy - beta*qbar(2)
        end if
    contains
        !> The force loop on the shift (ξ, η) (w_β with a mean compliance), with the periodic
        !! cell's probes.
        subroutine loop_on_shift()
            jac = 0; jac(1, 1) = -k0; jac(2, 2) = -k0       ! dF/d(ξ,η): traction opposes the shift
            x = [-load%fx/k0, -load%fy/k0]
            if (present(xi_start)) x(1) = xi_start - beta*load%fx/cell
            if (present(eta_start)) x(2) = eta_start - beta*load%fy/cell
            if (top%periodic .and. .not. (present(xi_start) .and. present(eta_start))) then
                ! many small contacts are stiffer than Mindlin's one patch of their total area:
                ! a shift that slips every element leaves the loop no slope to follow.  Shrink
                ! it until some element sticks.  Between dissimilar bodies the pressure alone
                ! can slip every element (two narrow contacts' sides in opposite directions),
                ! so that small shifts slip everything too, with a force short of the target:
                ! then grow it.  Once both kinds were seen, bisect the scale (geometrically).
                s_lo = 0; s_hi = huge(1.0_dp); s = 1
                x0 = x
                do k = 1, 12
                    call solve_tangential(top, pn, load%mu, settings, trial, stat, errmsg, x(1), x(2), &
                                          load%phi, zx, zy, qx, qy, ox, oy)
                    if (stat /= 0) return
                    probe_it = probe_it + trial%iterations; probe_mv = probe_mv + trial%matvecs
                    probe_s = probe_s + trial%cpu_seconds
                    if (trial%nadh > 0) then
                        probed = .true.; exit
                    end if
                    if (hypot(trial%fx, trial%fy) < hypot(load%fx, load%fy)) then
                        s_lo = s
                    else
                        s_hi = s
                    end if
                    if (s_lo == 0) then
                        s = s/8
                    else if (s_hi == huge(1.0_dp)) then
                        s = s*8
                    else
                        s = sqrt(s_lo*s_hi)
                    end if
                    x = s*x0; k0 = k0_mindlin/s
                end do
                ! the probe's secant from zero shift (zero force in partial contact) is a better
                ! stiffness than Mindlin's, which the many contacts of a cell exceed severalfold
                ! (480 random cells: 17 % fewer TangCG iterations than with Mindlin's).  Not
                ! from a zero shift or force, nor above 1000 times Mindlin's stiffness: a
                ! prescribed force far below the loop's tolerance (1e−20 N … 5e−324 N) gives a
                ! shift near 0, or 0, where dissimilar bodies' cells still carry the force that
                ! the pressure's coupling leaves at zero shift; the secant through the origin
                ! then exceeded Mindlin's by up to 1e300 (its Jacobian's determinant overflowed,
                ! or the loop's steps came to nothing), and Mindlin's stiffness stays.  (hypot:
                ! gfortran's norm2 squares unscaled and gave 0 for shifts near 1e−305 mm.)
                if (probed) then
                    xnorm = hypot(x(1), x(2)); fnorm = hypot(trial%fx, trial%fy)
                    if (xnorm > 0 .and. fnorm > 0 .and. fnorm <= max_secant*k0_mindlin*xnorm) k0 = fnorm/xnorm
                end if
                jac = 0; jac(1, 1) = -k0; jac(2, 2) = -k0
            end if
            inner = settings
            call nw%start(x, jac, settings%tol, hypot(load%fx, load%fy), flimit)
            ! the probes' cost counts with the loop's
            nw%iterations = probe_it; nw%matvecs = probe_mv; nw%cpu_seconds = probe_s
            done = .false.
            if (probed) then
                ! the last probe, at x, is the loop's first point: solved already
                qx = trial%px; qy = trial%py
                call nw%update([trial%fx - load%fx, trial%fy - load%fy], accepted, done, 0, 0, 0.0_dp)
                if (accepted) call move_alloc_result(trial, res)
            end if
            if (.not. done) call broyden_loop()
            if (stat /= 0) return
            call finish_force_loop(res, nw, 'force loop')
        end subroutine loop_on_shift

        !> The Broyden iteration of [[fc_force_newton]] from its state in `nw`.
        subroutine broyden_loop()
            do
                inner%tol = nw%tol_inner
                call solve_tangential(top, pn, load%mu, inner, trial, stat, errmsg, nw%x_trial(1), nw%x_trial(2), &
                                      load%phi, zx, zy, qx, qy, ox, oy)
                if (stat /= 0) return
                qx = trial%px; qy = trial%py          ! warm start of the next solve
                call nw%update([trial%fx - load%fx, trial%fy - load%fy], accepted, done, &
                               trial%iterations, trial%matvecs, trial%cpu_seconds)
                if (accepted) call move_alloc_result(trial, res)
                if (done) exit
            end do
        end subroutine broyden_loop

        !> A periodic cell in contact everywhere: uniform tractions displace nothing, so while
        !! the whole cell can carry the force in adhesion the shift is not found by the force
        !! loop (the force jumps across the target at one shift).  Adhesion everywhere needs
        !! A·q = −(w + r) on the whole cell (r: spin, previous displacements, offset): the shift
        !! w is minus the mean of r, q = A⁺(−(r − mean r)) + F/(cell area) by the exact inverse.
        !! `found` when that q lies within every bound; the solve from it (converged at once)
        !! then fills the result.  Otherwise some element slips and the loop takes over.
        subroutine periodic_full_stick(found)
            logical, intent(out) :: found
            real(dp), allocatable :: rx(:, :), ry(:, :), tx(:, :), ty(:, :)
            real(dp) :: xi0, eta0, xc(nx), cell
            integer :: i, j
            found = .false.
            allocate (rx(nx, ny), ry(nx, ny), tx(nx, ny), ty(nx, ny))
            xc = top%grid%x([(i, i=1, nx)])
            do j = 1, ny
                rx(:, j) = -load%phi*top%grid%y(j) - zx(:, j) + ox(:, j)
                ry(:, j) = load%phi*xc - zy(:, j) + oy(:, j)
            end do
            xi0 = -sum(rx)/size(rx); eta0 = -sum(ry)/size(ry)
            rx = -(rx + xi0); ry = -(ry + eta0)
            call apply_block_inverse(top, rx, ry, tx, ty, circulant=.true.)
            cell = real(nx, dp)*real(ny, dp)*top%grid%area()
            tx = tx + load%fx/cell; ty = ty + load%fy/cell
            if (any(tx**2 + ty**2 > (load%mu*pn)**2)) return
            call solve_tangential(top, pn, load%mu, settings, res, stat, errmsg, xi0, eta0, load%phi, &
                                  zx, zy, tx, ty, ox, oy)
            found = stat /= 0 .or. res%status == FC_CONVERGED
            if (found) res%outer_iterations = 1
        end subroutine periodic_full_stick
    end subroutine solve_tangential_loading

    subroutine move_alloc_result(from, to)
        type(fc_tangential_result), intent(inout) :: from
        type(fc_tangential_result), intent(inout) :: to
        to = from
    end subroutine move_alloc_result

end module fc_tangcg_force
