!> Normal contact problem: the LCP e = h + A p ≥ 0, p ≥ 0, e·p = 0 (thesis §2.2; doc/conventions.md).
!!
!! Two solvers share one operator object ([[fc_normal_operator]], built once per grid and
!! material and reused across calls):
!!
!! * `norm` — Kalker's NORM: active set + CG (thesis §2.3).  Each active-set iteration
!!   solves A_CC p_C = −h_C by conjugate gradients (optionally truncated to `inner_maxit`
!!   steps, thesis Table 2.8), then removes negative pressures and adds penetrating
!!   exterior elements.
!! * `bccg` — bound-constrained CG (NormCG): projected, preconditioned CG on the free set
!!   F = {p > 0} ∪ {e < 0}.  A step that drives a pressure negative clips it to zero; any
!!   change of F restarts from the preconditioned steepest-descent direction.  The
!!   preconditioner is the Toeplitz approximation M of A⁻¹ from the inverse Fourier symbol
!!   of A on the doubled grid (the construction of thesis §3.3.1 in 2D), applied to the
!!   residual masked to F — by default as M's Strang circulant on the grid itself
!!   (`prec_form = 'circulant'`, a quarter of the transform work; 'toeplitz': M itself), with
!!   an optional coarse correction on the indicator of the contact set.
!!
!! Prescribed total force: the Polonsky–Keer constraint inside the iteration — search
!! directions are projected onto Σ_F d = 0, pressures are rescaled to the force after a
!! clip, and the approach is the mean gap over the contact set.  NORM uses the same
!! constraint in its inner CG (Kalker solves p and δ together).
!!
!! Residual (both solvers): ‖g‖₂/‖h_F‖₂, g the gap on the free set — thesis (2.18) with
!! the norm taken over the free set.
!!
!! Size (~860 lines): the operator type and its lifetime, and the two normal solvers of
!! thesis ch. 2 (BCCG, NORM) that share its preconditioner, the force constraint and the
!! result type; kept in one home like CONTACT's `norm` while the solver internals are tuned.
module fc_norm
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use fc_kinds
    use fc_errors, only: FC_ERR_NO_CONTACT
    use fc_geometry, only: fc_grid, h_no_contact
    use fc_influence
    use, intrinsic :: iso_c_binding, only: c_loc, c_associated
    use fc_errors, only: FC_ERR_VALUE
    use fc_threads, only: omp_min_elements
    use fc_vector_ops, only: vdot, vsum
    implicit none
    private

    !> Settings of the normal solvers.
    type, public :: fc_normal_settings
        character(len=8) :: solver = 'bccg'  !! 'bccg' or 'norm'
        real(dp) :: tol = 1.0e-5_dp           !! relative gap residual ‖g‖/‖h_F‖
        integer :: maxit = 1000               !! BCCG iterations / NORM active-set iterations
        integer :: inner_maxit = 0            !! NORM: CG steps per active-set iteration (0: until converged)
        logical :: precondition = .true.      !! BCCG: FFT-based preconditioner
        !> How BCCG applies its preconditioner M — 'circulant' (Strang's circulant of M on
        !! the grid, periodic transforms of nx×ny points) or 'toeplitz' (M itself, transforms of
        !! the doubled grid); doc/solvers.md
        character(len=9) :: prec_form = 'circulant'
        logical :: deflation = .false.        !! BCCG: coarse correction on the contact indicator (measured: no gain)
        logical :: elastic_start = .true.     !! BCCG cold start: estimate −M(h0 − t), t by force bracket / energy
        !> Reading of NORM's active-set step (thesis §2.3, §2.4.1) — '' (ours: warm-started
        !! CG, drop p < 0 and add e < 0 in one step); research alternatives for thesis Table 2.8
        !! (bench/norm_table28.f90): 'restart' (CG from p = 0), 'keep_negative' (dropped
        !! elements keep p), 'add_if_no_drop', 'add_on_zero' (add e ≤ 0), 'continue_cg'
        !! (search direction kept across active-set steps), 'recompute_u' (e after the drop)
        character(len=16) :: norm_reading = ''
    end type fc_normal_settings

    !> Influence operator A^zz and the preconditioner for one grid and material; the two
    !! share one set of FFT plans and buffers.  Plans are released by `destroy` or when the
    !! operator is dropped; a copy (assignment) is independent of the original.
    type, public :: fc_normal_operator
        type(fc_grid) :: grid
        type(fc_material) :: material
        type(fc_bttb) :: a_zz     !! A^zz as an FFT product
        type(fc_bttb) :: precond  !! Toeplitz approximation M of (A^zz)⁻¹
        type(fc_bttb) :: precond_circulant  !! M's Strang circulant on the grid (made on first use)
        real(dp) :: setup_seconds = 0
    contains
        procedure :: destroy => normal_operator_destroy
        procedure :: matches => normal_operator_matches
        procedure, private :: normal_operator_assign
        generic :: assignment(=) => normal_operator_assign
    end type fc_normal_operator

    !> Result of a normal solve.
    type, public :: fc_normal_result
        real(dp), allocatable :: pn(:, :)   !! pressure per element [N/mm²]
        real(dp), allocatable :: gap(:, :)  !! deformed distance e = h0 − δ + A p [mm]
        real(dp) :: approach = 0            !! δ [mm]
        real(dp) :: fn = 0                  !! total normal force [N]
        real(dp) :: pmax = 0                !! maximum pressure [N/mm²]
        integer :: ncon = 0                 !! elements with p > 0
        integer :: status = FC_ERROR        !! FC_CONVERGED, FC_NOT_CONVERGED, FC_DIVERGED, FC_ERROR
        integer :: iterations = 0           !! CG iterations (BCCG) / total inner CG steps (NORM)
        integer :: outer_iterations = 0     !! NORM active-set iterations (BCCG: changes of the free set)
        integer :: matvecs = 0              !! products with A (FFT pairs), preconditioner not counted
        integer :: precond_applications = 0 !! products with the preconditioner
        real(dp) :: residual = huge(1.0_dp) !! final relative residual
        real(dp) :: cpu_seconds = 0         !! solve time (excludes operator set-up)
        character(len=msg_len) :: message = ''
        real(dp), allocatable :: history(:) !! residual per iteration
        logical :: touches_boundary = .false. !! contact reaches the edge of the potential area:
                                              !! the area may clip the true contact (enlarge it)
    end type fc_normal_result

    public :: build_normal_operator, solve_normal, contact_on_edge, prepare_precond_circulant

contains

    !> Build A^zz and its preconditioner for `grid` and `material` (combined constants
    !! already set by [[combine_material]]); with `ic`, from that set's coefficients (checked
    !! against the grid by the caller, see [[ic_set_kernel]]) instead of the half-space ones;
    !! with `kernel`, from the half-space coefficients the caller computed already.
    subroutine build_normal_operator(nop, material, grid, ic, kernel)
        type(fc_normal_operator), intent(inout) :: nop
        type(fc_material), intent(in) :: material
        type(fc_grid), intent(in) :: grid
        type(fc_ic_set), intent(in), optional :: ic
        !> A^zz for offsets −nx…nx, −ny…ny ([[ic_kernels_uncoupled]]); taken (deallocated)
        real(dp), allocatable, intent(inout), optional :: kernel(:, :)
        integer :: stat
        integer(i8) :: t0, t1, rate   ! 64-bit: a µs clock (default integers tick in ms)
        real(dp), allocatable :: kext(:, :)
        character(len=msg_len) :: msg
        call system_clock(t0, rate)
        call nop%destroy()
        nop%grid = grid
        nop%material = material
        ! one coefficient evaluation serves both A (offsets < n) and M (offsets ≤ n)
        if (present(ic)) then
            call ic_set_kernel(ic, IC_ZZ, grid, kext, stat, msg)
        else if (present(kernel)) then
            call move_alloc(kernel, kext)
        else
            call ic_kernel_extended(IC_ZZ, material, grid, grid%nx, grid%ny, kext)
        end if
        ! A takes the coefficients (no copy); M reads them there and shares A's FFT plans and
        ! buffers (one set per grid)
        call build_bttb_taking_kernel(nop%a_zz, kext, grid%nx, grid%ny)
        call inverse_toeplitz_from_kernel(nop%a_zz%kernel, grid%nx, grid%ny, nop%precond, plans_from=nop%a_zz, &
            keep_kernel=.false.)
        call system_clock(t1)
        nop%setup_seconds = real(t1 - t0, dp)/rate
    end subroutine build_normal_operator

    !> Whether the built operator serves `grid` and `material`: same element count and size
    !! (relative 1e−12; the position of the area does not matter) and the same G and ν.
    pure logical function normal_operator_matches(self, grid, material) result(ok)
        class(fc_normal_operator), intent(in) :: self
        type(fc_grid), intent(in) :: grid
        type(fc_material), intent(in) :: material
        ok = self%a_zz%built() .and. self%grid%nx == grid%nx .and. self%grid%ny == grid%ny .and. &
            abs(self%grid%dx - grid%dx) <= 1e-12_dp*grid%dx .and. abs(self%grid%dy - grid%dy) <= 1e-12_dp*grid%dy &
            .and. self%material%g == material%g .and. self%material%nu == material%nu
    end function normal_operator_matches

    subroutine normal_operator_destroy(self)
        class(fc_normal_operator), intent(inout) :: self
        call self%a_zz%destroy()
        call self%precond%destroy()
        call self%precond_circulant%destroy()
    end subroutine normal_operator_destroy

    !> `lhs = rhs`: deep copy; the copy's two blocks share their own new plan set.
    !! (Explicit rather than component-wise: gfortran 12 finalizes a shallow temporary in
    !! the intrinsic assignment of a type with finalizable components.)
    subroutine normal_operator_assign(lhs, rhs)
        class(fc_normal_operator), intent(inout) :: lhs
        type(fc_normal_operator), intent(in) :: rhs
        if (same_object(lhs, rhs)) return
        lhs%grid = rhs%grid
        lhs%material = rhs%material
        lhs%setup_seconds = rhs%setup_seconds
        call copy_bttb(lhs%a_zz, rhs%a_zz)
        call copy_bttb(lhs%precond, rhs%precond, plans_from=lhs%a_zz)
        call copy_bttb(lhs%precond_circulant, rhs%precond_circulant)
    contains
        logical function same_object(a, b)
            class(fc_normal_operator), intent(in), target :: a
            type(fc_normal_operator), intent(in), target :: b
            same_object = c_associated(c_loc(a%setup_seconds), c_loc(b%setup_seconds))
        end function same_object
    end subroutine normal_operator_assign

    !> Make M's Strang circulant on the grid (BCCG's preconditioner in the circulant form)
    !! unless it exists; M's symbol is real by construction (were it not, M itself is
    !! applied and nothing is made).  On BCCG's first use, or ahead of the solve inside the
    !! orchestrator's operator build, where it overlaps the tangential build.
    subroutine prepare_precond_circulant(nop)
        type(fc_normal_operator), intent(inout) :: nop
        ! a periodic cell's M is already a circulant on the grid
        if (nop%precond_circulant%built() .or. nop%precond%parity /= SYMBOL_EVEN .or. nop%precond%periodic) return
        call strang_circulant_of_symbol(nop%a_zz, nop%precond%rsymbol, nop%precond_circulant, keep_kernel=.false.)
    end subroutine prepare_precond_circulant

    !> Solve the normal contact problem for undeformed distance h0 (without approach) with
    !! either a prescribed `approach` δ [mm] or a prescribed total force `fn` [N].
    !! `p_start` (optional) warm-starts the iteration.
    subroutine solve_normal(nop, h0, settings, res, stat, errmsg, approach, fn, p_start)
        type(fc_normal_operator), intent(inout) :: nop
        real(dp), intent(in) :: h0(:, :)
        type(fc_normal_settings), intent(in) :: settings
        type(fc_normal_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: approach, fn
        real(dp), intent(in), optional :: p_start(:, :)
        integer :: nx, ny
        integer(i8) :: t0, t1, rate   ! 64-bit: a µs clock (default integers tick in ms)
        logical :: force_mode, started
        real(dp) :: delta, fn_sum
        stat = 0; errmsg = ''
        nx = nop%grid%nx; ny = nop%grid%ny
        if (.not. nop%a_zz%built()) then
            stat = FC_ERR_NOT_READY; errmsg = 'solve_normal: operator not built'; return
        end if
        if (size(h0, 1) /= nx .or. size(h0, 2) /= ny) then
            stat = FC_ERR_SHAPE; write (errmsg, '(a,2(i0,1x),a,2(i0,1x))') 'solve_normal: h0 has shape ', shape(h0), &
                'but the grid is ', nx, ny
            return
        end if
        if (present(approach) .eqv. present(fn)) then
            stat = FC_ERR_VALUE; errmsg = 'solve_normal: give exactly one of approach and fn'; return
        end if
        force_mode = present(fn)
        if (force_mode) then
            if (.not. (fn > 0)) then
                stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a)') 'normal: fn = ', fn, ' must be > 0'; return
            end if
            if (.not. any(h0 < 0.5_dp*h_no_contact)) then
                stat = FC_ERR_NO_CONTACT
                errmsg = 'normal: no element can come into contact (h0 >= 1e20 everywhere): fn cannot be carried'
                return
            end if
            delta = 0
        else
            delta = approach
            if (.not. any(h0 - delta <= 0 .and. h0 < 0.5_dp*h_no_contact)) then
                stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a)') 'normal: approach = ', approach, &
                    ' gives no contact (h0 − approach > 0 everywhere)'
                return
            end if
        end if
        call check_iteration_settings(settings%tol, settings%maxit, stat, errmsg)
        if (stat /= 0) return
        select case (settings%norm_reading)
        case ('', 'restart', 'keep_negative', 'add_if_no_drop', 'add_on_zero', 'continue_cg', 'recompute_u')
        case default
            stat = FC_ERR_VALUE; errmsg = "solve_normal: norm_reading = '"//trim(settings%norm_reading)//"' is not one of '', "// &
                "'restart', 'keep_negative', 'add_if_no_drop', 'add_on_zero', 'continue_cg', 'recompute_u'"
            return
        end select
        select case (settings%prec_form)
        case ('circulant')
            ! M's symbol is real by construction; were it not, M itself is applied
            if (settings%precondition .and. settings%solver == 'bccg') call prepare_precond_circulant(nop)
        case ('toeplitz')
        case default
            stat = FC_ERR_VALUE
            errmsg = "solve_normal: prec_form = '"//trim(settings%prec_form)//"' is not one of 'circulant', 'toeplitz'"
            return
        end select
        allocate (res%pn(nx, ny), res%gap(nx, ny))
        started = .false.
        if (present(p_start)) started = all(shape(p_start) == [nx, ny])
        if (started) then
            ! no start pressure where contact is impossible (outside a punch): it would count
            ! toward the force and never be released by the iteration
            res%pn = merge(max(0.0_dp, p_start), 0.0_dp, h0 < 0.5_dp*h_no_contact)
        else
            res%pn = 0
        end if
        nop%a_zz%nproducts = 0; nop%precond%nproducts = 0; nop%precond_circulant%nproducts = 0
        call system_clock(t0, rate)
        select case (settings%solver)
        case ('bccg')
            call run_bccg(nop, h0, settings, force_mode, delta, fn_or_zero(), res)
        case ('norm')
            call run_norm(nop, h0, settings, force_mode, delta, fn_or_zero(), res)
        case default
            stat = FC_ERR_VALUE; errmsg = "solver: normal = '"//trim(settings%solver)//"' is not one of 'bccg', 'norm'"
            return
        end select
        call system_clock(t1)
        res%cpu_seconds = real(t1 - t0, dp)/rate
        res%matvecs = nop%a_zz%nproducts
        res%precond_applications = nop%precond%nproducts + nop%precond_circulant%nproducts
        call pressure_summary(res%pn, fn_sum, res%pmax, res%ncon)
        res%fn = fn_sum*nop%grid%area()
        res%touches_boundary = contact_on_edge(res%pn)
        if (res%touches_boundary .and. res%status == FC_CONVERGED) &
            res%message = 'converged; contact reaches the edge of the potential contact area (enlarge it)'
    contains
        real(dp) function fn_or_zero()
            fn_or_zero = 0
            if (present(fn)) fn_or_zero = fn
        end function fn_or_zero
    end subroutine solve_normal

    !> Bound-constrained preconditioned CG (see module header).
    subroutine run_bccg(nop, h0, settings, force_mode, delta_in, fn, res)
        type(fc_normal_operator), intent(inout) :: nop
        real(dp), intent(in) :: h0(:, :)
        type(fc_normal_settings), intent(in) :: settings
        logical, intent(in) :: force_mode
        real(dp), intent(in) :: delta_in, fn
        type(fc_normal_result), intent(inout) :: res
        real(dp), dimension(size(h0, 1), size(h0, 2)) :: p, u, g, z, d, q, e0, aone
        logical, dimension(size(h0, 1), size(h0, 2)) :: free, free_old, allowed
        real(dp) :: delta, area, alpha, beta, gz, gz_old, dq, hnorm, rnorm, r0, best, dden, eone, sone
        real(dp) :: e0sum, hsq, rsq
        integer :: it, since_best, nfree, nclip, max_sparse, npos, i, j, nx, ny
        logical :: restart, par, have_u
        real(dp) :: scale
        real(dp), allocatable :: hist(:)
        area = nop%grid%area()
        have_u = .false.
        nx = size(h0, 1); ny = size(h0, 2)
        ! element loops below: OpenMP over columns on large grids (fc_threads), element order
        ! otherwise; sums as the intrinsics compute them (same results serially)
        par = nx*ny > omp_min_elements
        allowed = h0 < 0.5_dp*h_no_contact
        p = res%pn
        delta = delta_in
        if (sum(p) <= 0 .and. settings%precondition .and. settings%elastic_start) call elastic_start()
        if (force_mode) then
            ! start from a uniform pressure on the elements that can touch, or from the given
            ! start scaled to the prescribed force (the iteration keeps Σp fixed)
            if (sum(p) <= 0) then
                where (allowed) p = 1
            end if
            p = p*fn/(area*sum(p))
        end if
        if (.not. have_u) call nop%a_zz%apply(p, u)
        allocate (hist(settings%maxit))
        ! break-even between a direct column update (n flops each) and an FFT product
        max_sparse = max(8, 2*ceiling(log(4.0_dp*size(h0))/log(2.0_dp)))
        free_old = .false.
        d = 0; gz_old = 1; r0 = -1; best = huge(1.0_dp); since_best = 0
        res%status = FC_NOT_CONVERGED
        res%outer_iterations = 0
        do it = 1, settings%maxit
            ! e0 = h0 + u; force mode: δ = mean of e0 over p > 0
            npos = 0; e0sum = 0
            !$omp parallel do default(shared) private(i) reduction(+:npos, e0sum) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    e0(i, j) = h0(i, j) + u(i, j)
                    if (p(i, j) > 0) then
                        npos = npos + 1; e0sum = e0sum + e0(i, j)
                    end if
                end do
            end do
            !$omp end parallel do
            if (force_mode) then
                if (npos > 0) delta = e0sum/npos
            end if
            ! gap g on the free set F = allowed ∩ (p > 0 ∪ g < 0), ‖h_F‖², ‖g‖², change of F
            nfree = 0; hsq = 0; rsq = 0; restart = .false.
            !$omp parallel do default(shared) private(i) reduction(+:nfree, hsq, rsq) reduction(.or.:restart) &
            !$omp schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    g(i, j) = e0(i, j) - delta
                    free(i, j) = allowed(i, j) .and. (p(i, j) > 0 .or. g(i, j) < 0)
                    if (free(i, j)) then
                        nfree = nfree + 1
                        hsq = hsq + (h0(i, j) - delta)**2
                        rsq = rsq + g(i, j)**2
                    else
                        g(i, j) = 0
                    end if
                    restart = restart .or. (free(i, j) .neqv. free_old(i, j))
                end do
            end do
            !$omp end parallel do
            hnorm = sqrt(hsq)
            rnorm = sqrt(rsq)
            if (nfree == 0 .or. hnorm <= 0) then
                res%message = 'no element in contact'
                res%status = FC_NOT_CONVERGED
                exit
            end if
            res%residual = rnorm/hnorm
            hist(it) = res%residual
            res%iterations = it - 1
            if (ieee_is_nan(res%residual) .or. res%residual > 1.0e8_dp) then
                res%status = FC_DIVERGED
                res%message = 'BCCG diverged (residual not finite or > 1e8)'
                exit
            end if
            if (res%residual <= settings%tol) then
                res%status = FC_CONVERGED
                res%message = 'converged'
                exit
            end if
            if (res%residual < 0.999_dp*best) then
                best = res%residual; since_best = 0
            else
                since_best = since_best + 1
                if (since_best > 100) then
                    res%message = 'BCCG stagnated: no residual decrease in 100 iterations'
                    exit
                end if
            end if
            if (it == settings%maxit) then
                write (res%message, '(a,i0,a)') 'BCCG not converged in maxit = ', settings%maxit, ' iterations'
                exit
            end if
            if (restart) res%outer_iterations = res%outer_iterations + 1
            ! preconditioned gradient z = P M P g (P: projection onto Σ_F = 0 in force mode)
            if (force_mode) call project_mean(g, free)
            if (settings%precondition) then
                call precondition(g, z)
                !$omp parallel do default(shared) private(i) schedule(static) if(par)
                do j = 1, ny
                    do i = 1, nx
                        if (.not. free(i, j)) z(i, j) = 0
                    end do
                end do
                !$omp end parallel do
                if (settings%deflation .and. .not. force_mode) then
                    ! coarse correction on the contact indicator: z += 1_F (1_Fᵀ g)/(1_Fᵀ A 1_F)
                    if (restart) then
                        where (free)
                            aone = 1
                        elsewhere
                            aone = 0
                        end where
                        sone = sum(aone)
                        call nop%a_zz%apply(aone, q)
                        eone = sum(q, mask=free)
                    end if
                    where (free) z = z + sum(g)/eone
                end if
            else
                z = g
            end if
            if (force_mode) call project_mean(z, free)
            gz = vdot(g, z)
            if (restart .or. it == 1) then
                beta = 0
            else
                beta = max(0.0_dp, gz/gz_old)
            end if
            ! d = −z (restart) or −z + β d on F, 0 elsewhere
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    if (restart .or. it == 1) then
                        d(i, j) = -z(i, j)
                    else if (free(i, j)) then
                        d(i, j) = -z(i, j) + beta*d(i, j)
                    else
                        d(i, j) = 0
                    end if
                end do
            end do
            !$omp end parallel do
            free_old = free
            gz_old = gz
            call nop%a_zz%apply(d, q)
            dq = vdot(d, q)
            if (.not. (dq > 0)) then
                res%status = FC_DIVERGED
                res%message = 'BCCG: search direction with non-positive curvature'
                exit
            end if
            dden = vdot(g, d)
            alpha = -dden/dq
            nclip = 0
            !$omp parallel do default(shared) private(i) reduction(+:nclip) schedule(static) if(par)
            do j = 1, ny
                do i = 1, nx
                    p(i, j) = p(i, j) + alpha*d(i, j)
                    u(i, j) = u(i, j) + alpha*q(i, j)
                    if (p(i, j) < 0) nclip = nclip + 1
                end do
            end do
            !$omp end parallel do
            if (nclip > 0) then
                ! A·max(p,0) = A·p − A·min(p,0): few clipped elements are corrected column by
                ! column (O(n) each), many by one more FFT product.
                if (nclip <= max_sparse) call subtract_sparse_columns(nop%a_zz, p, u)
                !$omp parallel do default(shared) private(i) schedule(static) if(par)
                do j = 1, ny
                    do i = 1, nx
                        p(i, j) = max(p(i, j), 0.0_dp)
                    end do
                end do
                !$omp end parallel do
                if (nclip > max_sparse) call nop%a_zz%apply(p, u)
                if (force_mode) then
                    scale = vsum(p)
                    if (scale > 0) then
                        scale = fn/(area*scale)
                        !$omp parallel do default(shared) private(i) schedule(static) if(par)
                        do j = 1, ny
                            do i = 1, nx
                                p(i, j) = scale*p(i, j); u(i, j) = scale*u(i, j)     ! u = A p is linear in p
                            end do
                        end do
                        !$omp end parallel do
                    end if
                end if
            end if
        end do
        res%approach = delta
        res%pn = p
        res%gap = h0 - delta + u
        where (.not. allowed) res%gap = h_no_contact
        allocate (res%history(max(0, min(it, settings%maxit))), source=hist(1:max(0, min(it, settings%maxit))))
    contains
        !> Cold start from the elastic estimate p = max(0, −M (h0 − δ)) on the penetration
        !! set (one preconditioner product).  With a prescribed force δ is first estimated by
        !! bisection on the force of that estimate (a few more products) and the start is
        !! then scaled to the force.
        subroutine elastic_start()
            real(dp) :: lo, hi, mid, hmin, hmax, f, flo, fhi
            integer :: k
            if (.not. force_mode) then
                call approach_start()
                return
            end if
            ! bracket δ (the estimate's force is 0 at δ = min h0 and grows with δ), then a
            ! few steps of the Illinois variant of regula falsi to about 1 % of the force.
            ! The estimates use M itself whatever the form of the iteration: their force is
            ! what sets δ, and the circulant's truncated coefficients would shift it (measured:
            ! 10 BCCG iterations instead of 8 on the Cattaneo cases).
            hmin = minval(h0, mask=allowed); hmax = maxval(h0, mask=allowed)
            lo = hmin; flo = 0
            hi = hmin + 0.25_dp*(hmax - hmin)
            call estimate(hi, fhi, toeplitz=.true.)
            do k = 1, 20
                if (fhi >= fn) exit
                lo = hi; flo = fhi
                hi = hmin + 2*(hi - hmin)
                call estimate(hi, fhi, toeplitz=.true.)
            end do
            do k = 1, 4
                if (.not. (fhi > flo)) exit
                mid = lo + (fn - flo)*(hi - lo)/(fhi - flo)
                call estimate(mid, f, toeplitz=.true.)
                if (abs(f - fn) <= 0.01_dp*fn) return
                if (f > fn) then
                    hi = mid; fhi = f; flo = 0.5_dp*flo
                else
                    lo = mid; flo = f; fhi = 0.5_dp*fhi
                end if
            end do
        end subroutine elastic_start
        !> Prescribed approach: the estimate on the penetration set {h0 < δ} is positive on
        !! all of it, a far larger set than the contact area (Hertz: twice its area), and BCCG
        !! then clips one ring of elements per iteration.  Instead, estimates e(t) from
        !! shallower levels t = h_min + f·(δ − h_min), f = 1, 3/4, 1/2 and the vertex of the
        !! parabola through them, each scaled by its energy-optimal factor
        !! c = −eᵀ(h0 − δ)/eᵀAe, are compared by the energy ½pᵀAp + pᵀ(h0 − δ) (the
        !! functional BCCG minimises over p ≥ 0), and the lowest is kept together with
        !! u = A p.  Cost: four products with M and four with A.
        subroutine approach_start()
            real(dp) :: hmin, fr(4), jv(4), jbest, den, f0
            integer :: k
            ! the best candidate is kept in d and q (free until the iteration starts)
            hmin = minval(h0, mask=allowed)
            fr(1:3) = [1.0_dp, 0.75_dp, 0.5_dp]
            jbest = 0
            do k = 1, 4
                if (k == 4) then
                    ! vertex of the parabola through the three energies (equally spaced f),
                    ! kept inside [1/4, 1]
                    den = jv(1) - 2*jv(2) + jv(3)
                    if (.not. (den > 0)) exit     ! not convex in f: keep the best of three
                    fr(4) = fr(2) + 0.25_dp*(jv(3) - jv(1))/(2*den)
                    fr(4) = min(1.0_dp, max(0.25_dp, fr(4)))
                    if (minval(abs(fr(1:3) - fr(4))) < 0.05_dp) exit
                end if
                call scaled_estimate(hmin + fr(k)*(delta - hmin), jv(k))
                if (jv(k) < jbest) then
                    jbest = jv(k); d = p; q = u
                end if
            end do
            if (jbest < 0) then
                p = d; u = q; have_u = .true.
            else
                call estimate(delta, f0)   ! no candidate lowers the energy: the plain estimate
            end if
        end subroutine approach_start
        !> p = c·e(t) and u = A p with the energy-optimal c; energy in `jv` (0 if e(t) is useless).
        subroutine scaled_estimate(t, jv)
            real(dp), intent(in) :: t
            real(dp), intent(out) :: jv
            real(dp) :: force, pau, pg, c
            jv = 0
            call estimate(t, force)
            if (.not. force > 0) return
            call nop%a_zz%apply(p, u)
            pau = sum(p*u)
            pg = sum(p*(h0 - delta), mask=allowed)
            if (.not. (pau > 0 .and. pg < 0)) return
            c = -pg/pau
            p = c*p; u = c*u
            jv = -0.5_dp*pg**2/pau
        end subroutine scaled_estimate
        !> p = max(0, −M (h0 − dlt)) on the penetration set, its force; M in the iteration's
        !! form, or itself with `toeplitz`.
        subroutine estimate(dlt, force, toeplitz)
            real(dp), intent(in) :: dlt
            real(dp), intent(out) :: force
            logical, intent(in), optional :: toeplitz
            where (allowed .and. h0 - dlt < 0)
                g = h0 - dlt
            elsewhere
                g = 0
            end where
            if (present(toeplitz)) then
                call nop%precond%apply(-g, z)
            else
                call precondition(-g, z)
            end if
            where (allowed .and. h0 - dlt < 0)
                p = max(z, 0.0_dp)
            elsewhere
                p = 0
            end where
            force = sum(p)*area
        end subroutine estimate
        !> y = M x in the form the settings ask for.
        subroutine precondition(x, y)
            real(dp), intent(in) :: x(:, :)
            real(dp), intent(out) :: y(:, :)
            if (settings%prec_form == 'circulant' .and. nop%precond_circulant%built()) then
                call nop%precond_circulant%apply(x, y)
            else
                call nop%precond%apply(x, y)
            end if
        end subroutine precondition
    end subroutine run_bccg

    !> True when a pressure is positive in the first or last column (x) or, for grids with
    !! more than one row, in the first or last row (y).
    pure logical function contact_on_edge(p) result(edge)
        real(dp), intent(in) :: p(:, :)
        integer :: nx, ny
        nx = size(p, 1); ny = size(p, 2)
        edge = any(p(1, :) > 0) .or. any(p(nx, :) > 0)
        if (ny > 1) edge = edge .or. any(p(:, 1) > 0) .or. any(p(:, ny) > 0)
    end function contact_on_edge

    !> u ← u − A·min(p, 0) for the few elements where p < 0, using A's coefficients
    !! directly (one kernel column per element).  A periodic operator (a circulant on the
    !! grid, its coefficients stored for offsets 0 … n−1) takes the offsets modulo the grid.
    subroutine subtract_sparse_columns(op, p, u)
        type(fc_bttb), intent(in) :: op
        real(dp), intent(in) :: p(:, :)
        real(dp), intent(inout) :: u(:, :)
        integer :: k, l, j, nx, ny, dj
        nx = op%nx; ny = op%ny
        do l = 1, ny
            do k = 1, nx
                if (p(k, l) < 0) then
                    if (op%periodic) then
                        ! offsets i − k wrap at k: the column in two pieces
                        !$omp parallel do default(shared) private(dj) schedule(static) if(nx*ny > omp_min_elements)
                        do j = 1, ny
                            dj = modulo(j - l, op%my)
                            u(k:nx, j) = u(k:nx, j) - p(k, l)*op%kernel(0:nx - k, dj)
                            u(1:k - 1, j) = u(1:k - 1, j) - p(k, l)*op%kernel(op%mx - k + 1:op%mx - 1, dj)
                        end do
                        !$omp end parallel do
                    else
                        !$omp parallel do default(shared) schedule(static) if(nx*ny > omp_min_elements)
                        do j = 1, ny
                            u(:, j) = u(:, j) - p(k, l)*op%kernel(1 - k:nx - k, j - l)
                        end do
                        !$omp end parallel do
                    end if
                end if
            end do
        end do
    end subroutine subtract_sparse_columns

    !> Subtract the mean over the free set (projection onto Σ_F x = 0).
    pure subroutine project_mean(x, free)
        real(dp), intent(inout) :: x(:, :)
        logical, intent(in) :: free(:, :)
        integer :: nf
        nf = count(free)
        if (nf > 0) then
            where (free)
                x = x - sum(x, mask=free)/nf
            elsewhere
                x = 0
            end where
        end if
    end subroutine project_mean

    !> Kalker's NORM: active set + CG (thesis §2.3).
    subroutine run_norm(nop, h0, settings, force_mode, delta_in, fn, res)
        type(fc_normal_operator), intent(inout) :: nop
        real(dp), intent(in) :: h0(:, :)
        type(fc_normal_settings), intent(in) :: settings
        logical, intent(in) :: force_mode
        real(dp), intent(in) :: delta_in, fn
        type(fc_normal_result), intent(inout) :: res
        real(dp), dimension(size(h0, 1), size(h0, 2)) :: p, u, r, d, q, h
        logical, dimension(size(h0, 1), size(h0, 2)) :: con, con_new, allowed
        real(dp) :: delta, area, alpha, beta, rr, rr_old, dq, hnorm, rnorm, inner_tol, e, rr_keep, best
        integer :: outer, inner, inner_max, ncon, total_inner, i, j, ndrop, since_best
        logical :: changed
        !> Outer iterations without an active-set change and without a 0.1 % residual decrease
        !! after which NORM reports stagnation (the tolerance is below what rounding allows).
        integer, parameter :: stagnation_window = 5
        real(dp), allocatable :: hist(:)
        area = nop%grid%area()
        allowed = h0 < 0.5_dp*h_no_contact
        delta = delta_in
        p = res%pn
        if (force_mode) then
            con = allowed
            if (any(p > 0)) con = p > 0
        else
            con = allowed .and. (h0 - delta <= 0)
            if (any(p > 0)) con = p > 0 .or. con
        end if
        where (.not. con) p = 0
        ncon = count(con)
        inner_max = settings%inner_maxit
        if (inner_max <= 0) inner_max = max(50, ncon)
        ! the inner CG cannot resolve the residual below rounding: floor its tolerance
        inner_tol = max(0.1_dp*settings%tol, 10*epsilon(1.0_dp))
        allocate (hist(settings%maxit))
        total_inner = 0
        best = huge(1.0_dp); since_best = 0
        rr_keep = 0; d = 0
        res%status = FC_NOT_CONVERGED
        do outer = 1, settings%maxit
            res%outer_iterations = outer
            ncon = count(con)
            if (ncon == 0) then
                res%message = 'NORM: contact area became empty'
                exit
            end if
            if (settings%norm_reading == 'restart') p = 0
            if (force_mode) then
                where (con)
                    p = max(p, 0.0_dp)
                end where
                if (sum(p) <= 0) then
                    where (con) p = 1
                end if
                p = p*fn/(area*sum(p))
            end if
            ! --- CG on A_CC p_C = −h_C (force mode: on Σ_C p = fn/area, δ = mean gap) ---
            call nop%a_zz%apply(p, u)
            if (force_mode) delta = sum(h0 + u, mask=con)/ncon
            h = h0 - delta
            r = 0
            where (con) r = -(h + u)
            if (force_mode) call project_mean(r, con)
            hnorm = sqrt(sum(h**2, mask=con))
            rr = sum(r*r)
            if (settings%norm_reading == 'continue_cg' .and. outer > 1 .and. rr_keep > 0) then
                where (.not. con) d = 0
                d = r + (rr/rr_keep)*d
            else
                d = r
            end if
            do inner = 1, inner_max
                if (sqrt(rr) <= inner_tol*hnorm) exit
                call nop%a_zz%apply(d, q)
                where (.not. con) q = 0
                if (force_mode) call project_mean(q, con)
                dq = sum(d*q)
                if (.not. (dq > 0)) exit
                alpha = rr/dq
                p = p + alpha*d
                r = r - alpha*q
                rr_old = rr
                rr = sum(r*r)
                beta = rr/rr_old
                d = r + beta*d
                total_inner = total_inner + 1
            end do
            rr_keep = rr
            call nop%a_zz%apply(p, u)
            if (force_mode) delta = sum(h0 + u, mask=con)/ncon
            h = h0 - delta
            ! residual over the contact set and sign conditions
            rnorm = sqrt(sum((h + u)**2, mask=con .and. p >= 0))
            hnorm = sqrt(sum(h**2, mask=con))
            res%residual = rnorm/max(hnorm, tiny(1.0_dp))
            hist(outer) = res%residual
            if (ieee_is_nan(res%residual) .or. res%residual > 1.0e8_dp) then
                res%status = FC_DIVERGED
                res%message = 'NORM diverged (residual not finite or > 1e8)'
                exit
            end if
            ! active-set update (thesis §2.4.1 step 4): (a) drop negative pressures,
            ! (b) add exterior elements that penetrate
            con_new = con
            ndrop = 0
            do j = 1, size(h0, 2)
                do i = 1, size(h0, 1)
                    if (con(i, j) .and. p(i, j) < 0) then
                        con_new(i, j) = .false.; ndrop = ndrop + 1
                        if (settings%norm_reading /= 'keep_negative') p(i, j) = 0
                    end if
                end do
            end do
            changed = ndrop > 0
            if (settings%norm_reading == 'recompute_u' .and. ndrop > 0) call nop%a_zz%apply(p, u)
            if (.not. (settings%norm_reading == 'add_if_no_drop' .and. ndrop > 0)) then
                do j = 1, size(h0, 2)
                    do i = 1, size(h0, 1)
                        if (.not. con(i, j) .and. allowed(i, j)) then
                            e = h(i, j) + u(i, j)
                            if (e < 0 .or. (settings%norm_reading == 'add_on_zero' .and. e <= 0)) then
                                con_new(i, j) = .true.; changed = .true.
                            end if
                        end if
                    end do
                end do
            end if
            con = con_new
            if (.not. changed .and. res%residual <= settings%tol) then
                res%status = FC_CONVERGED
                res%message = 'converged'
                exit
            end if
            if (changed .or. res%residual < 0.999_dp*best) then
                best = res%residual; since_best = 0    ! a new active set restarts the count
            else
                since_best = since_best + 1
                if (since_best >= stagnation_window) then
                    write (res%message, '(a,i0,a,es11.3e3,a,es11.3e3)') 'NORM stagnated: no residual decrease in ', &
                        stagnation_window, ' active-set iterations (residual ', res%residual, ' > tol = ', settings%tol
                    res%message = trim(res%message)//')'
                    exit
                end if
            end if
            if (outer == settings%maxit) then
                write (res%message, '(a,i0,a)') 'NORM not converged in maxit = ', settings%maxit, ' active-set iterations'
            end if
        end do
        if (res%status /= FC_CONVERGED .and. len_trim(res%message) == 0) res%message = 'NORM not converged'
        res%iterations = total_inner
        p = max(p, 0.0_dp)
        call nop%a_zz%apply(p, u)
        if (force_mode) then
            if (count(p > 0) > 0) delta = sum(h0 + u, mask=p > 0)/count(p > 0)
        end if
        res%approach = delta
        res%pn = p
        res%gap = h0 - delta + u
        where (.not. allowed) res%gap = h_no_contact
        allocate (res%history(min(res%outer_iterations, settings%maxit)), source=hist(1:min(res%outer_iterations, settings%maxit)))
    end subroutine run_norm

    !> Σp, max p and the count of p > 0 in one pass; the sum runs in element order, as
    !! `sum` does.
    pure subroutine pressure_summary(p, total, pmax, n)
        real(dp), intent(in) :: p(:, :)
        real(dp), intent(out) :: total, pmax
        integer, intent(out) :: n
        integer :: i, j
        total = 0; pmax = -huge(1.0_dp); n = 0
        do j = 1, size(p, 2)
            do i = 1, size(p, 1)
                total = total + p(i, j)
                if (p(i, j) > pmax) pmax = p(i, j)
                if (p(i, j) > 0) n = n + 1
            end do
        end do
    end subroutine pressure_summary

end module fc_norm
