!> Steady-state rolling contact (Kalker's steady formulation, thesis eq. 4.1 in a frame that
!! moves with the contact): a reference block Gauss–Seidel solver and a fast Newton–GMRES
!! solver in TangCG's variables.
!!
!! Body 1 rolls in +x over body 2; the contact area travels in +x relative to the material,
!! so material enters at the leading edge x = xmax.  With the creepages ξ, η (dimensionless)
!! and the spin φ [1/mm], the slip velocity over the rolling velocity is
!!
!!   s_I = w_I + (u_I − u_{I+x})/δx,   w_I = [ξ − φ·y_I, η + φ·x_I],   u = A p (+ offset),
!!
!! where I+x is the element ahead of I (the next column in +x; the material in front of the
!! grid is undeformed, u = 0).  This is exactly the fixed point of the transient rolling step
!! s = δq·w + u − u'(x + δq) with the travelled distance δq = δx, so transient rolling with
!! that step converges to this solution.  Coulomb's law with a static coefficient μs for
!! adhesion (|p_I| ≤ μs·pn_I, s_I = 0) and a kinetic one μk in slip (p_I = −μk·pn_I·s_I/|s_I|).
!! Forces act on body 1: a positive ξ gives a negative Fx, a positive φ a negative Mz.
!!
!! * SteadyGS (`'steadygs'`): nonlinear block Gauss–Seidel marching from the leading edge;
!!   per element the 2×2 adhesion solve or the Newton solve for the angle on the friction
!!   circle (shared with ConvexGS).  Displacements maintained by O(n) column updates: a sweep
!!   costs O(n_c·n).  The simple, trusted reference.
!! * Newton–GMRES (`'gmres'`): TangCG's active set (tractions in adhesion, angles in slip,
!!   elements moved between the areas after each Newton step) with the non-symmetric
!!   Jacobian solved by restarted GMRES, left-preconditioned: adhesion rows summed along
!!   each run of adhesion in x (the exact inverse of the convective difference there),
!!   then, when adhesion covers ≥ 50 % of the contact (≥ 90 % in the Toeplitz form), TangCG's
!!   FFT block inverse of A (`preconditioner = 'fft'`); slip rows by TangCG's diagonal
!!   scaling (thesis eq. 4.43 with the steady operator's diagonal).  Every Krylov step costs one FFT product of the
!!   tangential operator (two with the block inverse); the Krylov vectors hold the active
!!   set's unknowns only (x of adhesion and slip, y of adhesion).  Forcing term constant until the
!!   subdivision settles, then Eisenstat–Walker's superlinear choice.  A cold solve starts
!!   from FASTSIM's tractions on the grid ([[fastsim_on_grid]], `start = 'fastsim'`).
!!
!! Stopping criterion as TangCG's (thesis eq. 4.49): relative RMS traction change of the last
!! Newton step / sweep below `tol` with an unchanged subdivision.
!!
!! Size (~770 lines): the Newton–GMRES loop keeps its GMRES, preconditioner and Jacobian
!! product as contained procedures on the loop's work arrays (no allocation per Krylov step);
!! the reference solvers live in [[fc_rolling_refsolvers]] and come in as an argument
!! (`reference`, which the orchestrator [[fc_contact]] passes), so that this module does
!! not depend on them.
module fc_rolling
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
    use fc_kinds
    use fc_limits, only: max_creepage, min_mu_kinetic
    use fc_geometry, only: fc_grid
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_result, EL_EXTERIOR, EL_ADHESION, EL_SLIP, &
        finish_force_loop, finish_status, traction_change
    use fc_tangcg_operator, only: apply_block_inverse
    use fc_rolling_base
    use fc_force_newton, only: fc_force_newton_t
    use fc_fastsim, only: fastsim_on_grid
    use fc_threads, only: omp_min_elements
    implicit none
    private

    ! the types of fc_rolling_base are part of this module's interface
    public :: fc_rolling_settings, fc_rolling_loading, fc_rolling_case


    public :: solve_rolling, solve_rolling_loading, convective_difference, rolling_slip

contains

    !> Steady slip (sx, sy) [-] of tractions (px, py) for the creepages (ξ, η, φ):
    !! s = w + (u − u_{+x})/δx with u = A p + offset.  For checks and tests.
    subroutine rolling_slip(top, px, py, xi, eta, phi, sx, sy, offset_x, offset_y)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: px(:, :), py(:, :), xi, eta, phi
        real(dp), intent(out) :: sx(:, :), sy(:, :)
        real(dp), intent(in), optional :: offset_x(:, :), offset_y(:, :)
        real(dp), allocatable :: ux(:, :), uy(:, :), dx(:, :), dy(:, :)
        allocate (ux, uy, dx, dy, mold=px)
        call top%apply(px, py, ux, uy)
        if (present(offset_x)) ux = ux + offset_x
        if (present(offset_y)) uy = uy + offset_y
        call convective_difference(ux, top%grid%dx, dx)
        call convective_difference(uy, top%grid%dx, dy)
        call rigid_creepage(top%grid, xi, eta, phi, sx, sy)
        sx = sx + dx; sy = sy + dy
    end subroutine rolling_slip

    !> Steady rolling with prescribed creepages (ξ, η, φ) on pressure `pn` [N/mm²].
    !! Optional: starting tractions (warm start) and a known displacement offset (e.g. the
    !! coupling A^xz·pn for dissimilar materials), whose convective difference enters the slip.
    !! Result: tractions on body 1, slip velocity over rolling velocity (sx, sy) [-],
    !! displacement differences (ux, uy) = A p, element states, forces, moment, counts.
    subroutine solve_rolling(top, pn, load, settings, res, stat, errmsg, px_start, py_start, offset_x, offset_y, &
                             reference)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: pn(:, :)
        type(fc_rolling_loading), intent(in) :: load
        type(fc_rolling_settings), intent(in) :: settings
        type(fc_tangential_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: px_start(:, :), py_start(:, :), offset_x(:, :), offset_y(:, :)
        !> the reference solvers ('march', 'steadygs'): [[reference_solver]] of fc_rolling_refsolvers
        procedure(rolling_reference_solver), optional :: reference
        real(dp), allocatable :: wx(:, :), wy(:, :), gs(:, :), gk(:, :), ox(:, :), oy(:, :), dox(:, :), doy(:, :)
        real(dp) :: muk
        integer :: nx, ny
        logical :: resumed   !! started from given tractions (a previous solution), not FASTSIM's
        integer(i8) :: t0, t1, rate   ! 64-bit: a µs clock (default integers tick in ms)
        stat = 0; errmsg = ''
        nx = top%grid%nx; ny = top%grid%ny
        if (.not. top%a_xx%built()) then
            stat = FC_ERR_NOT_READY; errmsg = 'solve_rolling: operator not built'; return
        end if
        if (top%a_xx%periodic) then
            stat = FC_ERR_UNSUPPORTED; errmsg = 'solve_rolling: steady rolling needs a non-periodic operator'; return
        end if
        if (size(pn, 1) /= nx .or. size(pn, 2) /= ny) then
            stat = FC_ERR_SHAPE; errmsg = 'solve_rolling: pn does not match the grid'; return
        end if
        muk = load%mu_kinetic
        if (muk < 0) muk = load%mu
        if (.not. (load%mu >= 0 .and. load%mu < huge(1.0_dp))) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.6,a)') 'rolling: mu = ', load%mu, ' must be >= 0 and finite'; return
        end if
        if (.not. (muk <= load%mu)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.6,a,g0.6,a)') 'rolling: mu_kinetic = ', muk, ' must be <= mu = ', &
                load%mu, ' (static)'; return
        end if
        ! slip without friction has no traction direction (the angles of the slip elements are
        ! undefined): a kinetic coefficient needs the static one's lower bound
        if (load%mu > 0 .and. .not. (muk >= min_mu_kinetic)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.6,a,g0.6,a,es7.1,a)') 'rolling: mu_kinetic = ', muk, &
                ' with mu = ', load%mu, ' > 0 must be >= ', min_mu_kinetic, &
                ' (slip without friction has no direction); mu = 0 for frictionless contact'; return
        end if
        if (.not. (abs(load%xi) <= max_creepage .and. abs(load%eta) <= max_creepage .and. abs(load%phi) < 1.0e6_dp)) then
            stat = FC_ERR_VALUE; errmsg = 'rolling: creepages xi, eta (|.| <= 1e3) and phi (|.| < 1e6 1/mm) must be finite'
            return
        end if
        if (.not. (settings%tol > 0 .and. settings%tol < 1)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.6,a)') 'solver: tol = ', settings%tol, ' must be in (0, 1)'; return
        end if
        if (settings%maxit < 1 .or. settings%maxit > 10000000) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a)') 'solver: maxit = ', settings%maxit, ' must be in [1, 10000000]'; return
        end if
        if (settings%restart < 2 .or. settings%restart > 500) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a)') 'solver: restart = ', settings%restart, ' must be in [2, 500]'; return
        end if
        if (.not. (settings%forcing > 0 .and. settings%forcing < 1)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.6,a)') 'solver: forcing = ', settings%forcing, ' must be in (0, 1)'; return
        end if
        if (settings%prec_form /= 'circulant' .and. settings%prec_form /= 'toeplitz') then
            stat = FC_ERR_VALUE
            errmsg = "solver: prec_form = '"//trim(settings%prec_form)//"' is not one of 'circulant', 'toeplitz'"; return
        end if
        if (settings%solver /= 'gmres' .and. settings%solver /= 'steadygs' .and. settings%solver /= 'march') then
            stat = FC_ERR_VALUE
            errmsg = "solver: rolling = '"//trim(settings%solver)//"' is not one of 'gmres', 'march', 'steadygs'"
            return
        end if
        if (settings%start /= 'fastsim' .and. settings%start /= 'adhesion') then
            stat = FC_ERR_VALUE; errmsg = "solver: rolling start = '"//trim(settings%start)// &
                "' is not one of 'fastsim', 'adhesion'"
            return
        end if
        if (settings%preconditioner /= 'fft' .and. settings%preconditioner /= 'runsum') then
            stat = FC_ERR_VALUE; errmsg = "solver: rolling preconditioner = '"//trim(settings%preconditioner)// &
                "' is not one of 'fft', 'runsum'"
            return
        end if
        if (settings%solver /= 'gmres' .and. .not. present(reference)) then
            stat = FC_ERR_UNSUPPORTED; errmsg = "solver: rolling = '"//trim(settings%solver)//"' is a reference solver: "// &
                'pass reference = reference_solver (fc_rolling_refsolvers), or solve through solve_contact'
            return
        end if
        if (settings%solver == 'march' .and. muk /= load%mu) then
            stat = FC_ERR_UNSUPPORTED; errmsg = "solver: rolling = 'march' needs mu_kinetic = mu (the transient step has one mu)"
            return
        end if
        allocate (wx(nx, ny), wy(nx, ny), gs(nx, ny), gk(nx, ny), ox(nx, ny), oy(nx, ny), dox(nx, ny), doy(nx, ny))
        call rigid_creepage(top%grid, load%xi, load%eta, load%phi, wx, wy)
        ox = 0; oy = 0
        if (present(offset_x)) ox = offset_x
        if (present(offset_y)) oy = offset_y
        call convective_difference(ox, top%grid%dx, dox)
        call convective_difference(oy, top%grid%dx, doy)
        wx = wx + dox; wy = wy + doy
        gs = load%mu*max(pn, 0.0_dp)
        gk = muk*max(pn, 0.0_dp)
        allocate (res%px(nx, ny), res%py(nx, ny), res%sx(nx, ny), res%sy(nx, ny), res%ux(nx, ny), res%uy(nx, ny))
        allocate (res%state(nx, ny))
        res%px = 0; res%py = 0
        if (present(px_start)) res%px = px_start
        if (present(py_start)) res%py = py_start
        where (.not. pn > 0)
            res%px = 0; res%py = 0
        end where
        ! a cold Newton–GMRES start (no tractions given, or all zero) from FASTSIM: from all
        ! adhesion the slip area of a slip-dominated case forms over ~10 Newton steps
        ! (doc/rolling.md)
        resumed = any(res%px /= 0 .or. res%py /= 0)
        if (settings%solver == 'gmres' .and. settings%start == 'fastsim' .and. .not. resumed) &
            call fastsim_on_grid(top%grid, pn > 0, gk, top%material%g, top%material%nu, load%xi, load%eta, load%phi, &
                                 res%px, res%py)
        res%xi = load%xi; res%eta = load%eta; res%phi = load%phi
        top%nproducts = 0
        call system_clock(t0, rate)
        if (settings%solver == 'gmres') then
            call run_newton_gmres(top, pn > 0, gs, gk, wx, wy, settings, res, resumed)
        else
            call reference(top, pn, load%mu, gs, gk, wx, wy, settings, res, stat, errmsg)
            if (stat /= 0) return
        end if
        call system_clock(t1)
        res%cpu_seconds = real(t1 - t0, dp)/rate
        if (settings%solver /= 'march') res%matvecs = top%nproducts
        call rolling_summary(top%grid, res)
        res%dissipation = steady_dissipation(top%grid, res, ox, oy)
    end subroutine solve_rolling

    !> Steady rolling for a [[fc_rolling_loading]]: creepages go to [[solve_rolling]];
    !! prescribed creep forces (Fx, Fy) are met by a Broyden iteration on (ξ, η) started
    !! from the initial creep stiffness of a circular contact of the same area (Kalker's
    !! linear theory, C11 ≈ C22 ≈ π²/(4(1−ν/2)) as a rough, safe guess) and
    !! safeguarded by step halving; each solve starts from the previous tractions.
    !! |(Fx, Fy)| must be below μk·Fn.  Force tolerance: tol·μk·Fn.
    subroutine solve_rolling_loading(top, pn, load, settings, res, stat, errmsg, px_start, py_start, &
                                     offset_x, offset_y, xi_start, eta_start, reference)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: pn(:, :)
        type(fc_rolling_loading), intent(in) :: load
        type(fc_rolling_settings), intent(in) :: settings
        type(fc_tangential_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: px_start(:, :), py_start(:, :), offset_x(:, :), offset_y(:, :)
        real(dp), intent(in), optional :: xi_start, eta_start   !! first guess of the creepages
        procedure(rolling_reference_solver), optional :: reference   !! as for [[solve_rolling]]
        real(dp), allocatable :: qx(:, :), qy(:, :), ox(:, :), oy(:, :)
        type(fc_tangential_result) :: trial
        type(fc_rolling_settings) :: inner
        type(fc_rolling_loading) :: cur
        type(fc_force_newton_t) :: nw
        real(dp) :: fn, flimit, k0, area, jac(2, 2), x(2), muk
        real(dp), parameter :: creep_max = 1   !! largest |ξ|, |η| the creep-force loop tries
        integer :: nx, ny
        logical :: accepted, done
        nx = size(pn, 1); ny = size(pn, 2)
        allocate (qx(nx, ny), qy(nx, ny), ox(nx, ny), oy(nx, ny))
        qx = 0; qy = 0; ox = 0; oy = 0
        if (present(px_start)) qx = px_start
        if (present(py_start)) qy = py_start
        if (present(offset_x)) ox = offset_x
        if (present(offset_y)) oy = offset_y
        if (.not. load%force_prescribed) then
            call solve_rolling(top, pn, load, settings, res, stat, errmsg, qx, qy, ox, oy, reference)
            return
        end if
        stat = 0; errmsg = ''
        muk = load%mu_kinetic
        if (muk < 0) muk = load%mu
        fn = sum(max(pn, 0.0_dp))*top%grid%area()
        flimit = muk*fn
        if (.not. (hypot(load%fx, load%fy) < flimit)) then
            stat = FC_ERR_FRICTION_BOUND
            write (errmsg, '(a,es12.5,a,es12.5,a)') 'rolling: |(fx, fy)| = ', hypot(load%fx, load%fy), &
                ' must be < mu_kinetic*fn = ', flimit, ' (full slip has no unique creepage)'
            return
        end if
        area = count(pn > 0)*top%grid%area()
        k0 = top%material%g*area/pi*pi**2/(4*(1 - top%material%nu/2))   ! G·ab·C11, ab = area/π
        jac = 0; jac(1, 1) = -k0; jac(2, 2) = -k0
        x = [-load%fx/k0, -load%fy/k0]
        if (present(xi_start)) x(1) = xi_start
        if (present(eta_start)) x(2) = eta_start
        cur = load; cur%force_prescribed = .false.
        inner = settings
        call nw%start(x, jac, settings%tol, hypot(load%fx, load%fy), flimit)
        do
            inner%tol = nw%tol_inner
            if (.not. all(abs(nw%x_trial) <= creep_max)) then
                ! a Broyden step beyond creepage 1 (slip as fast as rolling) is not taken: it
                ! counts as a worse trial, so the step is halved (before, the step went on to
                ! infinite creepages and the case ended as an input error)
                call nw%update([10*flimit, 10*flimit], accepted, done, 0, 0, 0.0_dp)
                if (done) exit
                cycle
            end if
            cur%xi = nw%x_trial(1); cur%eta = nw%x_trial(2)
            call solve_rolling(top, pn, cur, inner, trial, stat, errmsg, qx, qy, ox, oy, reference)
            if (stat /= 0) return
            qx = trial%px; qy = trial%py          ! warm start of the next solve
            call nw%update([trial%fx - load%fx, trial%fy - load%fy], accepted, done, &
                           trial%iterations, trial%matvecs, trial%cpu_seconds)
            if (accepted) res = trial
            if (done) exit
        end do
        call finish_force_loop(res, nw, 'creep-force loop')
    end subroutine solve_rolling_loading

    !> Newton–GMRES with TangCG's active set and variables.
    subroutine run_newton_gmres(top, contact, gs, gk, wx, wy, settings, res, resumed)
        type(fc_tangential_operator), intent(inout) :: top
        logical, intent(in) :: resumed   !! res%px, res%py hold a previous solution (warm start)
        logical, intent(in) :: contact(:, :)
        real(dp), intent(in) :: gs(:, :), gk(:, :), wx(:, :), wy(:, :)
        type(fc_rolling_settings), intent(in) :: settings
        type(fc_tangential_result), intent(inout) :: res
        integer :: nx, ny, m
        real(dp), dimension(size(gs, 1), size(gs, 2)) :: px, py, sx, sy, ux, uy, cx, cy, dx_, dy_, mx, my, &
            pox, poy, tnorm, ex, ey
        logical, dimension(size(gs, 1), size(gs, 2)) :: adh, slp
        real(dp), allocatable :: vb(:, :), hess(:, :), cs(:), sn(:), gvec(:), yv(:), hist(:)
        ! GMRES works on the unknowns of the active set only (x of adhesion and slip, y of
        ! adhesion: a quarter to a third of the grid's 2·nx·ny values), gathered at positions
        ! iu (column-major element index); the Jacobian product reads and writes whole arrays
        real(dp), allocatable :: solc(:), ec(:), tvx(:, :), tvy(:, :), tqx(:, :), tqy(:, :)
        integer, allocatable :: iu(:)
        integer :: nax, nact   !! unknowns of the active set: x components, all
        real(dp), allocatable :: wkx(:, :), wky(:, :), qsx(:, :), qsy(:, :), zx(:, :), zy(:, :)
        real(dp) :: dxx, dyy, axx, gdx, yscale, change, dnorm, beta, rnorm, tol_in, h, tmp, pscale, eta_k, dnorm_prev, gscale
        real(dp) :: adhesion_share   !! smallest adhesion share of the contact for the FFT block inverse
        integer :: it_total, newton, k, kk, nit, idle
        logical :: changed, converged, stagnated, fft_prec, fft_prev, warm, circulant
        logical :: par   !! thread the element loops (above omp_min_elements)
        real(dp), parameter :: bound_slack = 1.0e-12_dp  !! relative slack on |p|² > g²
        integer, parameter :: max_idle = 20               !! Newton steps without a Krylov step
        nx = size(gs, 1); ny = size(gs, 2)
        m = settings%restart
        allocate (vb(2*nx*ny, m + 1), hess(m + 1, m), cs(m), sn(m), gvec(m + 1), yv(m))
        allocate (solc(2*nx*ny), ec(2*nx*ny), iu(2*nx*ny), tvx(nx, ny), tvy(nx, ny), tqx(nx, ny), tqy(nx, ny))
        allocate (wkx(nx, ny), wky(nx, ny), qsx(nx, ny), qsy(nx, ny), zx(nx, ny), zy(nx, ny))
        allocate (hist(max(1, settings%maxit)))
        call steady_diagonal(top, dxx, dyy)
        axx = top%a_xx%kernel(0, 0); yscale = axx/top%a_yy%kernel(0, 0); gdx = top%grid%dx
        ! 'fft': the preconditioned adhesion rows are tractions (M ≈ A⁻¹), 'runsum': displacements
        ! scaled to A^xx_II; slip rows follow the same measure
        changed = .false.; dnorm_prev = 1; fft_prec = .false.
        ! the traction change is relative to |p|, floored at 1e−6 of the traction bound (RMS):
        ! a warm start towards zero creepage, whose solution is p = 0, converges instead of
        ! dividing by a vanishing |p| (it was reported diverged)
        gscale = 1.0e-12_dp*sum(gk**2)
        warm = any(contact .and. (res%px /= 0 .or. res%py /= 0))
        circulant = settings%prec_form == 'circulant'
        par = nx*ny > omp_min_elements
        px = res%px; py = res%py
        adh = contact; slp = .false.
        ! a warm start whose traction reaches the kinetic bound starts in slip (1e−8 slack
        ! keeps a converged start's subdivision)
        where (contact .and. gk > 0 .and. (px**2 + py**2 >= (1 - 1.0e-8_dp)*gk**2 .and. &
               px**2 + py**2 <= (1 + 1.0e-8_dp)*gk**2 .or. px**2 + py**2 > gs**2*(1 + bound_slack)))
            slp = .true.; adh = .false.
        end where
        where (slp)
            tnorm = sqrt(px**2 + py**2)
            px = gk*px/tnorm; py = gk*py/tnorm
        end where
        where (contact .and. .not. gs > 0)
            adh = .false.; slp = .false.; px = 0; py = 0
        end where
        call exact_slip()
        ! ... and one whose traction does not oppose its slip under the new creepages starts
        ! in adhesion, by the same rule as after every Newton step (kept in slip, such an
        ! element makes the Jacobian's slip row indefinite, and GMRES stalled on the first
        ! Newton step of warm-started sweep points: doc/rolling.md)
        where (slp .and. px*sx + py*sy > 0)
            adh = .true.; slp = .false.
        end where
        it_total = 0
        converged = .false.
        res%status = FC_NOT_CONVERGED
        change = huge(1.0_dp)
        res%outer_iterations = 0
        newton = 0; idle = 0; stagnated = .false.
        do
            newton = newton + 1
            ! defect d = −F: adhesion −s, slip −(px·sy − py·sx)
            where (adh)
                ex = -sx; ey = -sy
            elsewhere (slp)
                ex = -(px*sy - py*sx); ey = 0
            elsewhere
                ex = 0; ey = 0
            end where
            ! the FFT block inverse pays where the adhesion area is large: as the Toeplitz
            ! inverse (as costly as a product per Krylov iteration) from 90 % adhesion, as its
            ! circulant on the grid (a quarter of that) from 50 % (measured, doc/rolling.md:
            ! below, the active set's path from a cold start lengthens case 5 and the
            ! slip-dominated cases pay more products than they save) and in every step of a
            ! solve resumed from a previous solution, whose subdivision is nearly right (sweeps
            ! and flat-API calls: 17–21 % fewer Krylov iterations, measured); not in the first
            ! step of a cold start, whose all-adhesion subdivision is a guess (a more accurate
            ! full-adhesion step moved too many elements to slip, and they came back one layer
            ! per Newton step)
            fft_prev = fft_prec
            if (circulant) then
                adhesion_share = merge(0.0_dp, 0.5_dp, resumed .and. settings%fft_resumed)
            else
                adhesion_share = 0.9_dp
            end if
            fft_prec = settings%preconditioner == 'fft' .and. top%prec%built() .and. &
                count(adh) >= adhesion_share*count(contact) .and. (newton > 1 .or. warm)
            pscale = axx
            if (fft_prec) pscale = 1
            ! slip rows of the left preconditioner: TangCG's diagonal scaling (thesis eq. 4.43
            ! with the steady diagonal) to the measure A^xx_II of the adhesion rows
            where (slp)
                mx = pscale/(px**2*dyy + py**2*dxx + max(0.0_dp, -(px*sx + py*sy)))
            elsewhere
                mx = 0
            end where
            call precondition(ex, ey)
            dnorm = sqrt(sum(ex**2 + ey**2))
            if (dnorm == 0) then
                dx_ = 0; dy_ = 0; nit = 0; tol_in = 0
            else
                ! inexact Newton with an absolute floor tied to the outer tolerance: a residual
                ! worth a traction error of 0.3·tol needs no further Krylov work
                ! forcing term: constant, or once the subdivision has settled (no change in the
                ! last step, same preconditioner) Eisenstat–Walker's superlinear choice
                ! 0.9·(‖d_k‖/‖d_{k−1}‖)², floored at 1e−3
                eta_k = settings%forcing
                if (settings%adaptive_forcing .and. .not. changed .and. newton > 1 .and. dnorm_prev > 0 .and. &
                    (fft_prec .eqv. fft_prev)) &
                    eta_k = max(1.0e-3_dp, min(settings%forcing, 0.9_dp*(dnorm/dnorm_prev)**2))
                tol_in = max(eta_k*dnorm, 0.3_dp*settings%tol*pscale*sqrt(sum(px**2 + py**2)))
                call gmres(nit)
            end if
            it_total = it_total + nit
            dnorm_prev = dnorm
            ! a defect within the step's tolerance moves nothing: the tractions, their slip and
            ! the active set are those checked after the last step (saves one product per solve)
            if (nit == 0 .and. dnorm <= tol_in) then
                if (newton <= size(hist)) hist(newton) = 0
                res%outer_iterations = newton
                change = 0
                converged = .true.
                exit
            end if
            ! update: adhesion tractions, slip angles (rotation on the circle by the angle
            ! change, on the traction's unit vector: one sine and cosine per slip element
            ! instead of the angle's atan2 and the new angle's cosine and sine)
            call update_tractions()
            change = traction_change(px, py, pox, poy, floor=gscale)
            if (newton <= size(hist)) hist(newton) = change
            if (ieee_is_nan(change) .or. change > 1.0e12_dp) then
                res%status = FC_DIVERGED
                res%message = 'Newton-GMRES diverged (traction change not finite)'
                exit
            end if
            ! active set (TangCG step 11): adhesion above the static bound → slip on the
            ! kinetic circle; slip whose traction does not oppose the slip → adhesion
            ! (the relative slack keeps an element projected onto the circle by rounding from
            ! flipping between the sets without a Newton step)
            changed = .false.
            if (any(adh .and. px**2 + py**2 > gs**2*(1 + bound_slack))) then
                where (adh .and. px**2 + py**2 > gs**2*(1 + bound_slack))
                    slp = .true.; adh = .false.
                    tnorm = sqrt(px**2 + py**2)
                    px = gk*px/tnorm; py = gk*py/tnorm
                end where
                changed = .true.
            end if
            call exact_slip()
            if (any(slp .and. px*sx + py*sy > 0)) then
                where (slp .and. px*sx + py*sy > 0)
                    adh = .true.; slp = .false.
                end where
                changed = .true.
            end if
            res%outer_iterations = newton
            if (.not. changed .and. change < settings%tol) then
                converged = .true.
                exit
            end if
            if (it_total >= settings%maxit) exit
            ! stagnation: active-set changes that no Krylov step follows, or more Newton steps
            ! than the Krylov budget, cannot converge
            if (changed .and. nit == 0) then
                idle = idle + 1
            else
                idle = 0
            end if
            if (idle >= max_idle .or. newton >= max(max_idle, settings%maxit)) then
                write (res%message, '(a,i0,a,i0,a)') 'Newton-GMRES stagnated: ', newton, &
                    ' Newton steps, the active set keeps changing without a Krylov step (', idle, ' in a row)'
                stagnated = .true.
                exit
            end if
        end do
        res%iterations = it_total
        if (stagnated) then
            res%residual = change
        else
            call finish_status(res, converged, 'Newton-GMRES', settings%maxit, 'Krylov iterations', change)
        end if
        ! no non-finite traction is reported as a solution, whatever the path out of the loop
        if (.not. (all(ieee_is_finite(px)) .and. all(ieee_is_finite(py)))) then
            res%status = FC_DIVERGED
            res%message = 'Newton-GMRES diverged (tractions not finite)'
        end if
        res%px = px; res%py = py; res%ux = ux; res%uy = uy; res%sx = sx; res%sy = sy
        res%state = EL_EXTERIOR
        where (adh) res%state = EL_ADHESION
        where (slp) res%state = EL_SLIP
        where (.not. contact)
            res%sx = 0; res%sy = 0
        end where
        allocate (res%history(min(newton, size(hist))), source=hist(1:min(newton, size(hist))))
    contains
        !> The Newton update, old tractions kept in (pox, poy): adhesion p + δp; slip p turned
        !! on its circle |p| = g_k by the angle change δθ, as g_k·R(δθ)·p/|p| (a traction at 0
        !! starts from the angle 0, as atan2(0, 0) did).
        subroutine update_tractions()
            integer :: i, j
            real(dp) :: r, c, s, t, qx, qy
            !$omp parallel do default(shared) private(i, r, c, s, t, qx, qy) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    qx = px(i, j); qy = py(i, j)
                    pox(i, j) = qx; poy(i, j) = qy
                    if (adh(i, j)) then
                        px(i, j) = qx + dx_(i, j); py(i, j) = qy + dy_(i, j)
                    else if (slp(i, j)) then
                        c = cos(dx_(i, j)); s = sin(dx_(i, j))
                        r = sqrt(qx**2 + qy**2)
                        if (r > 0) then
                            t = gk(i, j)/r
                            px(i, j) = t*(qx*c - qy*s); py(i, j) = t*(qx*s + qy*c)
                        else
                            px(i, j) = gk(i, j)*c; py(i, j) = gk(i, j)*s
                        end if
                    end if
                end do
            end do
            !$omp end parallel do
        end subroutine update_tractions

        !> u = A p, s = w + (u − u_{+x})/δx (one FFT product).
        subroutine exact_slip()
            call top%apply(px, py, ux, uy)
            call convective_difference(ux, top%grid%dx, cx)
            call convective_difference(uy, top%grid%dx, cy)
            sx = wx + cx; sy = wy + cy
        end subroutine exact_slip

        !> Left preconditioner P, in place.  Adhesion: along each run of consecutive adhesion
        !! elements in x, the sum from the run's front (leading side) down to the element,
        !! times δx — the exact inverse of the convective difference on the run, it turns the
        !! steady adhesion rows (u_I − u_{I+x})/δx into u_I − u_front+x, TangCG's shift
        !! operator A minus one value per run.  Then 'fft': TangCG's FFT block inverse of A
        !! (fc_tangprec) on the adhesion area (masked), so that P·J ≈ I − M·(one value per
        !! run); 'runsum': y rows scaled by A^xx_II/A^yy_II.  Slip: the diagonal scaling in mx.
        subroutine precondition(rx, ry)
            real(dp), intent(inout) :: rx(:, :), ry(:, :)
            integer :: i, j
            real(dp) :: accx, accy, ys
            ys = yscale
            if (fft_prec) ys = 1
            ! columns are independent (the run sums go along x)
            !$omp parallel do default(shared) private(i, accx, accy) schedule(static) if(par)
            do j = 1, ny
                accx = 0; accy = 0
                do i = nx, 1, -1
                    if (adh(i, j)) then
                        accx = accx + rx(i, j)*gdx; accy = accy + ry(i, j)*gdx
                        rx(i, j) = accx; ry(i, j) = accy*ys
                    else
                        accx = 0; accy = 0
                        rx(i, j) = mx(i, j)*rx(i, j); ry(i, j) = 0
                    end if
                end do
            end do
            !$omp end parallel do
            if (fft_prec) then
                where (adh)
                    zx = rx; zy = ry
                elsewhere
                    zx = 0; zy = 0
                end where
                call block_inverse(zx, zy, qsx, qsy)
                where (adh)
                    rx = qsx; ry = qsy
                end where
            end if
        end subroutine precondition

        !> (zx, zy) = M (dx, dy), M TangCG's FFT block inverse of A (top%prec) in the form of
        !! `settings%prec_form`.
        subroutine block_inverse(dx, dy, rzx, rzy)
            real(dp), intent(in) :: dx(:, :), dy(:, :)
            real(dp), intent(out) :: rzx(:, :), rzy(:, :)
            call apply_block_inverse(top, dx, dy, rzx, rzy, circulant)
            top%nproducts = top%nproducts + 1   ! counted with the products
        end subroutine block_inverse

        !> q = P·J·v for a direction v in primary variables, into (qx, qy).  One pass builds
        !! the traction direction, one the convective difference and the rows (the hot loop of
        !! the solver: no array temporaries).
        subroutine jacobian_product(vx, vy, qx, qy)
            real(dp), intent(in) :: vx(:, :), vy(:, :)
            real(dp), intent(out) :: qx(:, :), qy(:, :)
            integer :: i, j
            real(dp) :: cxv, cyv
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    if (adh(i, j)) then
                        wkx(i, j) = vx(i, j); wky(i, j) = vy(i, j)
                    else if (slp(i, j)) then
                        wkx(i, j) = -vx(i, j)*py(i, j); wky(i, j) = vx(i, j)*px(i, j)
                    else
                        wkx(i, j) = 0; wky(i, j) = 0
                    end if
                end do
            end do
            !$omp end parallel do
            call top%apply(wkx, wky, qsx, qsy)
            !$omp parallel do default(shared) private(i, cxv, cyv) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    ! convective difference (f_i − f_{i+1})/δx, f_{nx+1} = 0
                    if (i < nx) then
                        cxv = (qsx(i, j) - qsx(i + 1, j))/gdx; cyv = (qsy(i, j) - qsy(i + 1, j))/gdx
                    else
                        cxv = qsx(i, j)/gdx; cyv = qsy(i, j)/gdx
                    end if
                    if (adh(i, j)) then
                        qx(i, j) = cxv; qy(i, j) = cyv
                    else if (slp(i, j)) then
                        qx(i, j) = px(i, j)*cyv - py(i, j)*cxv + sy(i, j)*wkx(i, j) - sx(i, j)*wky(i, j); qy(i, j) = 0
                    else
                        qx(i, j) = 0; qy(i, j) = 0
                    end if
                end do
            end do
            !$omp end parallel do
            call precondition(qx, qy)
        end subroutine jacobian_product

        !> Restarted GMRES(m) on J M z = d, δ = M z, from z = 0; at most the iterations left
        !! in maxit.  Result in (dx_, dy_); `nit` Krylov iterations.  The Krylov vectors hold the
        !! active set's unknowns only (fixed during the call).
        subroutine gmres(nit)
            integer, intent(out) :: nit
            integer :: j, i
            call active_unknowns()
            tvx = 0; tvy = 0      ! zero outside the active set for the whole call
            call gather(ex, ey, ec)
            solc(1:nact) = 0
            nit = 0
            do
                ! residual r = d − J M z
                if (nit == 0) then
                    vb(1:nact, 1) = ec(1:nact)
                else
                    call product(solc, vb(:, 1))
                    vb(1:nact, 1) = ec(1:nact) - vb(1:nact, 1)
                end if
                beta = sqrt(pdot(vb(:, 1), vb(:, 1), nact))
                if (beta <= tol_in .or. beta == 0) exit
                call pdivide(vb(:, 1), beta, nact)
                gvec = 0; gvec(1) = beta
                kk = 0
                do k = 1, m
                    if (it_total + nit >= settings%maxit) exit
                    nit = nit + 1
                    kk = k
                    call product(vb(:, k), vb(:, k + 1))
                    do j = 1, k      ! modified Gram–Schmidt
                        h = pdot(vb(:, j), vb(:, k + 1), nact)
                        hess(j, k) = h
                        call paxpy(-h, vb(:, j), vb(:, k + 1), nact)
                    end do
                    hess(k + 1, k) = sqrt(pdot(vb(:, k + 1), vb(:, k + 1), nact))
                    if (hess(k + 1, k) > 0) call pdivide(vb(:, k + 1), hess(k + 1, k), nact)
                    do j = 1, k - 1   ! previous Givens rotations
                        tmp = cs(j)*hess(j, k) + sn(j)*hess(j + 1, k)
                        hess(j + 1, k) = -sn(j)*hess(j, k) + cs(j)*hess(j + 1, k)
                        hess(j, k) = tmp
                    end do
                    rnorm = hypot(hess(k, k), hess(k + 1, k))
                    if (rnorm == 0) then
                        cs(k) = 1; sn(k) = 0
                    else
                        cs(k) = hess(k, k)/rnorm; sn(k) = hess(k + 1, k)/rnorm
                    end if
                    hess(k, k) = rnorm; hess(k + 1, k) = 0
                    gvec(k + 1) = -sn(k)*gvec(k); gvec(k) = cs(k)*gvec(k)
                    if (abs(gvec(k + 1)) <= tol_in .or. rnorm == 0) exit
                end do
                if (kk == 0) exit
                ! y = H⁻¹ g (upper triangular), z += V y
                do i = kk, 1, -1
                    if (hess(i, i) == 0) then
                        yv(i) = 0
                    else
                        yv(i) = (gvec(i) - dot_product(hess(i, i + 1:kk), yv(i + 1:kk)))/hess(i, i)
                    end if
                end do
                do i = 1, kk
                    call paxpy(yv(i), vb(:, i), solc, nact)
                end do
                if (abs(gvec(kk + 1)) <= tol_in .or. it_total + nit >= settings%maxit) exit
            end do
            dx_ = 0; dy_ = 0
            call scatter(solc, dx_, dy_)
        end subroutine gmres

        !> The active set's unknowns: x of adhesion and slip elements (nax), then y of
        !! adhesion elements, each by its column-major element index.
        subroutine active_unknowns()
            integer :: i, j
            nax = 0
            do j = 1, ny
                do i = 1, nx
                    if (adh(i, j) .or. slp(i, j)) then
                        nax = nax + 1; iu(nax) = (j - 1)*nx + i
                    end if
                end do
            end do
            nact = nax
            do j = 1, ny
                do i = 1, nx
                    if (adh(i, j)) then
                        nact = nact + 1; iu(nact) = (j - 1)*nx + i
                    end if
                end do
            end do
        end subroutine active_unknowns

        !> c = the active unknowns of the pair (fx, fy) (arrays of nx·ny elements).
        subroutine gather(fx, fy, c)
            real(dp), intent(in) :: fx(*), fy(*)
            real(dp), intent(out) :: c(*)
            integer :: k
            do k = 1, nax
                c(k) = fx(iu(k))
            end do
            do k = nax + 1, nact
                c(k) = fy(iu(k))
            end do
        end subroutine gather

        !> The active unknowns c into the pair (fx, fy); other elements are left as they are.
        subroutine scatter(c, fx, fy)
            real(dp), intent(in) :: c(*)
            real(dp), intent(inout) :: fx(*), fy(*)
            integer :: k
            do k = 1, nax
                fx(iu(k)) = c(k)
            end do
            do k = nax + 1, nact
                fy(iu(k)) = c(k)
            end do
        end subroutine scatter

        !> q = P·J·v on the active unknowns (the Jacobian product and the preconditioner
        !! give zero outside them).
        subroutine product(v, q)
            real(dp), intent(in) :: v(*)
            real(dp), intent(out) :: q(*)
            call scatter(v, tvx, tvy)
            call jacobian_product(tvx, tvy, tqx, tqy)
            call gather(tqx, tqy, q)
        end subroutine product
    end subroutine run_newton_gmres

end module fc_rolling
