!> The tangential problem of a [[fc_tangential_loading]] ([[solve_tangential_loading]]):
!! prescribed shifts are one [[solve_tangential]]; prescribed forces (Fx, Fy) are met by the
!! outer Broyden loop of [[fc_force_newton]] on the rigid shift (ξ, η), each inner solve
!! TangCG (or ConvexGS) warm-started from the last.  A periodic cell ([[fc_periodic]]) needs
!! more: its many small contacts are stiffer than Mindlin's first guess, and a cell in
!! contact everywhere is singular (uniform tractions displace nothing), which three rules
!! here handle — full stick solved directly, the first shift shrunk until something sticks,
!! and a radial search of the shift along the force when the loop stops short
!! (doc/parallel.md, "A cell in contact everywhere").
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
        real(dp) :: fn, flimit, k0, a, jac(2, 2), x(2), probe_s
        integer :: nx, ny, k, probe_it, probe_mv
        real(dp) :: rs_d(2), rs_fref, rs_secs   ! radial search (periodic cell in contact everywhere)
        integer :: rs_its, rs_mvs, outer0
        logical :: rs_ok, found, probed
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
        jac = 0; jac(1, 1) = -k0; jac(2, 2) = -k0       ! dF/d(ξ,η): traction opposes the shift
        x = [-load%fx/k0, -load%fy/k0]
        if (present(xi_start)) x(1) = xi_start
        if (present(eta_start)) x(2) = eta_start
        if (top%periodic .and. .not. (present(xi_start) .and. present(eta_start))) then
            ! many small contacts are stiffer than Mindlin's one patch of their total area,
            ! and a cell in contact everywhere far stiffer: a shift that slips every element
            ! leaves the loop no slope to follow.  Shrink it until some element sticks.
            do k = 1, 12
                call solve_tangential(top, pn, load%mu, settings, trial, stat, errmsg, x(1), x(2), &
                                      load%phi, zx, zy, qx, qy, ox, oy)
                if (stat /= 0) return
                probe_it = probe_it + trial%iterations; probe_mv = probe_mv + trial%matvecs
                probe_s = probe_s + trial%cpu_seconds
                if (trial%nadh > 0) then
                    probed = .true.; exit
                end if
                x = x/8; k0 = 8*k0
            end do
            ! the probe's secant from zero shift (zero force in partial contact) is a better
            ! stiffness than Mindlin's, which the many contacts of a cell exceed severalfold
            ! (480 random cells: 17 % fewer TangCG iterations than with Mindlin's)
            if (probed) k0 = hypot(trial%fx, trial%fy)/norm2(x)
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
        if (top%periodic .and. all(pn > 0) .and. res%status /= FC_CONVERGED) then
            call radial_search(x, jac, found)
            if (found) then
                ! the loop once more, from the radial point with the Jacobian of a force that
                ! follows the shift's direction; the totals of everything before carried on
                outer0 = nw%outer
                probe_it = nw%iterations + rs_its; probe_mv = nw%matvecs + rs_mvs; probe_s = nw%cpu_seconds + rs_secs
                call nw%start(x, jac, settings%tol, hypot(load%fx, load%fy), flimit)
                nw%iterations = probe_it; nw%matvecs = probe_mv; nw%cpu_seconds = probe_s
                call broyden_loop()
                if (stat /= 0) return
                call finish_force_loop(res, nw, 'force loop')
                res%outer_iterations = res%outer_iterations + outer0
            end if
        end if
    contains
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

        !> A periodic cell in contact everywhere whose force loop stopped short: near zero
        !! shift the force there has about the friction capacity of adhesion everywhere and the
        !! shift's direction, whatever the shift's size, so the loop's Jacobian is nearly
        !! singular.  Search the shift's size along the force's direction instead (regula falsi,
        !! Illinois rule, on the force component along it), each solve warm-started.  Its last
        !! solve is the answer when it meets the force tolerance in both components (`found`
        !! false); else `found` with that shift in `xr` and, in `jr`, the Jacobian of a force
        !! −φ(|x|)·x/|x| (radial slope measured, φ/|x| across) for the loop to finish from.
        subroutine radial_search(xr, jr, found)
            real(dp), intent(out) :: xr(2), jr(2, 2)
            logical, intent(out) :: found
            real(dp) :: r_lo, r_hi, g_lo, g_hi, r, g, ftol, slope
            integer :: it, side
            found = .false.
            rs_fref = hypot(load%fx, load%fy)
            ftol = settings%tol*flimit
            rs_d = -[load%fx, load%fy]/rs_fref
            rs_its = 0; rs_mvs = 0; rs_secs = 0
            r_hi = max(norm2(nw%x_trial), tiny(1.0_dp))
            call along(r_hi, g_hi); if (.not. rs_ok) return
            do it = 1, 60
                if (g_hi > 0) exit
                r_hi = 2*r_hi
                call along(r_hi, g_hi); if (.not. rs_ok) return
            end do
            r_lo = r_hi
            g_lo = g_hi
            do it = 1, 80
                if (g_lo < 0) exit
                r_lo = r_lo/4
                call along(r_lo, g_lo); if (.not. rs_ok) return
            end do
            if (.not. (g_lo < 0 .and. g_hi > 0)) return
            side = 0
            do it = 1, 100
                r = (r_lo*g_hi - r_hi*g_lo)/(g_hi - g_lo)
                slope = (g_hi - g_lo)/(r_hi - r_lo)
                call along(r, g); if (.not. rs_ok) return
                if (abs(g) <= 0.25_dp*ftol .or. r_hi - r_lo <= 1.0e-14_dp*r_hi) exit
                if (g < 0) then
                    r_lo = r; g_lo = g
                    if (side == -1) g_hi = g_hi/2
                    side = -1
                else
                    r_hi = r; g_hi = g
                    if (side == 1) g_lo = g_lo/2
                    side = 1
                end if
            end do
            if (hypot(trial%fx - load%fx, trial%fy - load%fy) <= ftol) then
                call move_alloc_result(trial, res)
                res%outer_iterations = nw%outer + 1
                res%iterations = nw%iterations + rs_its; res%matvecs = nw%matvecs + rs_mvs
                res%cpu_seconds = nw%cpu_seconds + rs_secs
                return
            end if
            found = .true.
            xr = r*rs_d
            ! F = −φ(|x|)·x̂: dF/dx = −(φ' x̂x̂ᵀ + (φ/|x|)(I − x̂x̂ᵀ)), x̂ = rs_d
            jr(:, 1) = -(slope*rs_d(1)*rs_d + (rs_fref/r)*([1.0_dp, 0.0_dp] - rs_d(1)*rs_d))
            jr(:, 2) = -(slope*rs_d(2)*rs_d + (rs_fref/r)*([0.0_dp, 1.0_dp] - rs_d(2)*rs_d))
        end subroutine radial_search

        !> Radial search: solve at the shift r·rs_d; g = the force along the prescribed one
        !! minus its size (rs_ok: the solve converged; a failed one leaves the loop's result).
        subroutine along(r, g)
            real(dp), intent(in) :: r
            real(dp), intent(out) :: g
            g = 0
            ! the force's direction near zero shift needs the inner solve 100 times tighter
            ! than the tolerance (at the tolerance it wanders by ~1e−4 rad)
            inner%tol = 1.0e-2_dp*settings%tol
            call solve_tangential(top, pn, load%mu, inner, trial, stat, errmsg, r*rs_d(1), r*rs_d(2), &
                                  load%phi, zx, zy, qx, qy, ox, oy)
            rs_ok = stat == 0 .and. trial%status == FC_CONVERGED
            if (stat /= 0) then
                stat = 0; errmsg = ''
            end if
            if (.not. rs_ok) return
            qx = trial%px; qy = trial%py
            rs_its = rs_its + trial%iterations; rs_mvs = rs_mvs + trial%matvecs; rs_secs = rs_secs + trial%cpu_seconds
            g = -(trial%fx*rs_d(1) + trial%fy*rs_d(2)) - rs_fref
        end subroutine along

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
