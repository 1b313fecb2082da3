!> One orchestrator for every contact solve: normal, tangential, coupled (Panagiotopoulos
!! process for dissimilar materials, K ≠ 0), transient steps (shift or rolling) and the
!! rolling sequences of a case ([[rolling_sequence]]: creep-force sweeps, transient rolling).
!!
!! The batch driver (through [[fc_auto]]), the flat API ([[fc_legacy]]) and the
!! `fastcontact` facade all call [[solve_contact]]; nothing else runs the
!! normal + tangential loop.  Its pieces:
!!
!! * [[fc_contact_loading]]: what is prescribed — the problem kind (normal, tangential), the
!!   [[fc_normal_loading]] (approach or total force, optional warm start), the
!!   [[fc_tangential_loading]] (friction, shifts or forces, spin), the transient mode.
!! * [[fc_contact_operators]]: the influence operators of one grid and material, built in one
!!   place ([[ensure_operators]]) and reused while [[fc_normal_operator]]'s and
!!   [[fc_tangential_operator]]'s `matches(grid, material)` hold.
!! * [[fc_contact_state]]: the previous solution of a sequence of calls — warm start and,
!!   in the transient modes, the previous displacements u' and tractions p' of the step.
!! * [[fc_contact_result]]: the normal and tangential results and the process counters.
!!
!! The types (problem kinds, transient modes, loadings, settings, operators, state, result)
!! are defined in [[fc_contact_types]] (so that the case description, the outputs and the
!! flat API's handle registry need not sit above the solvers) and re-exported here.
!!
!! Coupling (thesis §4.4): with K ≠ 0 the normal displacement A^zx·px + A^zy·py of the
!! tangential tractions enters the normal problem and the tangential displacement A^xz·pn of
!! the pressure enters the slip.  Rounds alternate normal and tangential solves until
!! pressure and tractions change by less than 10·max(tol_n, tol_t) (relative RMS), at most
!! [[max_rounds]] rounds.  With K = 0 one normal and one tangential solve.
!!
!! Size (~790 lines): the operators' construction, the rounds of both stages with their
!! transient bookkeeping, and the sequences of solves (loops of [[solve_contact]]) with their
!! predicted starts are the one orchestrator; its types are in [[fc_contact_types]].
module fc_contact
    use fc_kinds, only: dp, i8, pi, FC_CONVERGED, FC_NOT_CONVERGED, FC_ERROR
    use fc_errors, only: FC_ERR_VALUE, FC_ERR_NOT_READY, FC_ERR_SHAPE, FC_ERR_UNSUPPORTED, FC_ERR_FRICTION_BOUND
    use fc_geometry, only: fc_grid, h_no_contact
    use fc_influence, only: fc_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal, &
        prepare_precond_circulant
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_settings, fc_tangential_result, fc_tangential_loading, &
        build_tangential_operator, solve_tangential, coupling_displacements, EL_EXTERIOR, EL_ADHESION, EL_SLIP
    use fc_tangcg_force, only: solve_tangential_loading
    use fc_tangcg_operator, only: prepare_block_inverse_circulant
    use fc_fmg, only: fc_fmg_settings, fc_fmg_stats, fc_surface, solve_normal_fmg
    use fc_rolling, only: fc_rolling_loading, solve_rolling_loading, fc_rolling_case
    use fc_rolling_refsolvers, only: reference_solver   ! the reference solvers, passed to fc_rolling
    use fc_contact_types, only: FC_PROBLEM_NORMAL, FC_PROBLEM_TANGENTIAL, FC_PROBLEM_ROLLING, fc_normal_loading, &
        fc_contact_settings, fc_contact_result, fc_contact_loading, fc_contact_operators, fc_contact_state, &
        FC_FROM_REST, FC_TRANSIENT_SHIFT, FC_TRANSIENT_ROLLING, set_influence_coefficients, take_influence_coefficients, &
        clear_influence_coefficients
    use fc_influence, only: fc_ic_set, ic_set_kernel, ic_kernels_uncoupled, fc_bttb
    use fc_periodic, only: build_periodic_normal_operator, build_periodic_tangential_operator, check_periodic_grid, &
        check_periodic_problem, periodic_images_default
    use fc_threads, only: fc_thread_count
    use fc_strings, only: fmt_int, fmt_real
    implicit none
    private

    integer, parameter, public :: max_rounds = 50  !! most Panagiotopoulos rounds

    public :: FC_PROBLEM_NORMAL, FC_PROBLEM_TANGENTIAL, FC_PROBLEM_ROLLING, fc_normal_loading, fc_contact_settings, &
        fc_contact_result, fc_contact_loading, fc_contact_operators, fc_contact_state, &
        FC_FROM_REST, FC_TRANSIENT_SHIFT, FC_TRANSIENT_ROLLING
    public :: solve_contact, ensure_operators, solve_normal_tangential, shift_along_x, fc_tangential_loading
    public :: set_influence_coefficients, take_influence_coefficients, clear_influence_coefficients
    public :: rolling_sequence, continuation_factor, extrapolate_tractions, extrapolate_tractions_swap

contains

    !> Build the operators needed for `grid` and `material` unless the stored ones match;
    !! the stored grid is updated to `grid` (same spacing: a moved area keeps its operators).
    subroutine ensure_operators(ops, grid, material, normal, tangential, circulant_normal, circulant_tangential)
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_grid), intent(in) :: grid
        type(fc_material), intent(in) :: material
        logical, intent(in) :: normal, tangential   !! which operators are needed
        !> make BCCG's preconditioner circulant, TangCG's block-inverse circulants with the
        !! operators (with two threads beside the other build) rather than at their first use
        !! (default: at their first use)
        logical, intent(in), optional :: circulant_normal, circulant_tangential
        logical :: circ_n, circ_t
        logical :: build_n, build_t, shared_kernels
        real(dp), allocatable :: kzz(:, :), kxx(:, :), kxy(:, :), kyy(:, :)
        ops%setup_seconds_normal = 0; ops%setup_seconds_tangential = 0
        circ_n = .false.; circ_t = .false.
        if (present(circulant_normal)) circ_n = circulant_normal
        if (present(circulant_tangential)) circ_t = circulant_tangential
        build_n = .false.; build_t = .false.
        if (normal) build_n = .not. (ops%reuse .and. ops%normal%matches(grid, material) .and. &
            (ops%built_periodic .eqv. ops%periodic))
        if (tangential) build_t = .not. (ops%reuse .and. ops%tangential%matches(grid, material) .and. &
            (ops%tangential%periodic .eqv. ops%periodic))
        shared_kernels = .false.
        if (build_n .and. build_t .and. fc_thread_count() > 1) then
            ! The two builds are independent: with several threads they run side by side, each
            ! on one thread (the loops and transforms inside are nested regions).  Their serial
            ! parts (FFTW's first planning, allocation and first touch) then overlap; the same
            ! operators result (the element loops have no reductions, the plans are the same).
            ! The longer build (the tangential one) is the first section, which the thread
            ! that opens the region takes at once; the other thread may start late (a first
            ! parallel region waits 1–10 ms for its thread on this machine).
            !$omp parallel sections num_threads(2)
            !$omp section
            call build_tangential(.false.)
            !$omp section
            call build_normal()
            !$omp end parallel sections
        else
            ! both on the half-space, one after the other: the four uncoupled blocks'
            ! coefficients together (A^xx, A^yy share A^zz's 1/ρ term), the same numbers as
            ! each build's own.  (Side by side, each build evaluates its own: measured
            ! faster on two threads than computing them together first.)
            shared_kernels = build_n .and. build_t .and. .not. ops%periodic .and. .not. allocated(ops%ic%a)
            if (shared_kernels) call ic_kernels_uncoupled(material, grid, grid%nx, grid%ny, kzz, kxx, kxy, kyy)
            if (build_n) call build_normal()
            if (build_t) call build_tangential(normal)
        end if
        if (normal) ops%normal%grid = grid
        if (tangential) ops%tangential%grid = grid
    contains
        subroutine build_normal()
            integer :: stat
            character(len=256) :: errmsg   ! a periodic grid is checked by the callers ([[solve_contact]])
            if (ops%periodic) then
                call build_periodic_normal_operator(ops%normal, material, grid, stat, errmsg)
            else if (allocated(ops%ic%a)) then
                call build_normal_operator(ops%normal, material, grid, ops%ic)
            else if (shared_kernels) then
                call build_normal_operator(ops%normal, material, grid, kernel=kzz)
            else
                call build_normal_operator(ops%normal, material, grid)
            end if
            ops%built_periodic = ops%periodic
            ops%builds_normal = ops%builds_normal + 1
            ops%setup_seconds_normal = ops%normal%setup_seconds
            if (circ_n) call prepare_precond_circulant(ops%normal)
        end subroutine build_normal
        !> With `share_plans`, the tangential blocks share the normal operator's FFT plans and
        !! buffers when they are for the same sizes (built one after the other: their
        !! products never run at the same time), else they get their own.
        subroutine build_tangential(share_plans)
            logical, intent(in) :: share_plans
            integer :: stat
            character(len=256) :: errmsg   ! the cell and K = 0 are checked by [[solve_contact]]
            if (ops%periodic) then
                if (share_plans .and. ops%normal%a_zz%built() .and. ops%built_periodic) then
                    call build_periodic_tangential_operator(ops%tangential, material, grid, stat, errmsg, &
                        plans_from=ops%normal%a_zz)
                else
                    call build_periodic_tangential_operator(ops%tangential, material, grid, stat, errmsg)
                end if
            else if (share_plans .and. ops%normal%a_zz%built()) then
                call build_tangential_on(ops%normal%a_zz)
            else
                call build_tangential_on()
            end if
            ops%builds_tangential = ops%builds_tangential + 1
            ops%setup_seconds_tangential = ops%tangential%setup_seconds
            if (circ_t .and. ops%tangential%prec%built()) &
                call prepare_block_inverse_circulant(ops%tangential)
        end subroutine build_tangential
        subroutine build_tangential_on(plans_from)
            type(fc_bttb), intent(in), optional :: plans_from
            if (allocated(ops%ic%a)) then
                call build_tangential_operator(ops%tangential, material, grid, ops%ic, plans_from=plans_from)
            else if (shared_kernels) then
                call build_tangential_operator(ops%tangential, material, grid, kxx_in=kxx, kxy_in=kxy, kyy_in=kyy, &
                    plans_from=plans_from)
            else
                call build_tangential_operator(ops%tangential, material, grid, plans_from=plans_from)
            end if
        end subroutine build_tangential_on
    end subroutine ensure_operators

    !> Solve one contact problem on `grid` with undeformed distance `h0` [mm] (without the
    !! approach).  Operators in `ops` are built or reused.  With `state`, the previous
    !! solution warm-starts the solve (`state%warm_start`) and, in the transient modes of
    !! `load%transient`, is the previous state u', p' of the step; `state` advances when every
    !! stage converged.  An explicit start in `load` wins over the state's.  FMG
    !! (`settings%normal%solver = 'fmg'`) solves the normal stage from its own nested
    !! iteration; `surface` gives it h0 on the coarse grids.  stat ≠ 0: invalid input (no
    !! result); a solver that does not converge returns stat = 0 and its status.
    subroutine solve_contact(ops, grid, material, h0, load, settings, res, stat, errmsg, state, surface)
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_grid), intent(in) :: grid
        type(fc_material), intent(in) :: material   !! combined constants set
        real(dp), intent(in) :: h0(:, :)
        type(fc_contact_loading), intent(in) :: load
        type(fc_contact_settings), intent(in) :: settings
        type(fc_contact_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_contact_state), intent(inout), optional :: state
        class(fc_surface), intent(in), optional :: surface
        logical :: tangential, use_fmg
        stat = 0; errmsg = ''
        if (size(h0, 1) /= grid%nx .or. size(h0, 2) /= grid%ny) then
            stat = FC_ERR_SHAPE; errmsg = 'solve_contact: h0 does not match the grid'; return
        end if
        tangential = load%problem /= FC_PROBLEM_NORMAL
        use_fmg = settings%normal%solver == 'fmg'
        if (load%problem == FC_PROBLEM_ROLLING .and. load%transient /= FC_FROM_REST) then
            stat = FC_ERR_UNSUPPORTED
            errmsg = 'solve_contact: steady rolling has no transient mode (use FC_PROBLEM_TANGENTIAL with '// &
                'FC_TRANSIENT_ROLLING for transient rolling)'
            return
        end if
        if (use_fmg .and. tangential .and. material%k /= 0) then
            stat = FC_ERR_UNSUPPORTED
            errmsg = 'solve_contact: FMG is not available for dissimilar materials (K /= 0): the coupling alternates '// &
                'normal and tangential solves; use BCCG'
            return
        end if
        if (ops%periodic) then
            if (allocated(ops%ic%a)) then
                stat = FC_ERR_UNSUPPORTED
                errmsg = 'solve_contact: the periodic half-space and an influence-coefficient file exclude each other'
                return
            end if
            call check_periodic_grid(grid, periodic_images_default, stat, errmsg)
            if (stat == 0) call check_periodic_problem(use_fmg, tangential, &
                load%problem == FC_PROBLEM_ROLLING .or. load%transient == FC_TRANSIENT_ROLLING, &
                load%tangential%phi, settings%tangential%solver, stat, errmsg)
            if (stat /= 0) then
                errmsg = 'solve_contact: '//errmsg; return
            end if
        end if
        if (allocated(ops%ic%a)) then
            if (use_fmg) then
                stat = FC_ERR_UNSUPPORTED
                errmsg = 'solve_contact: FMG needs influence coefficients on every coarser grid, an influence-'// &
                    'coefficient file holds them for one grid: use BCCG or NORM'
                return
            end if
            block
                real(dp), allocatable :: k(:, :)
                call ic_set_kernel(ops%ic, 1, grid, k, stat, errmsg)   ! 1: any block; checks cells and offsets
            end block
            if (stat /= 0) return
        end if
        ! the preconditioner circulants BCCG and TangCG will apply are made with the operators
        call ensure_operators(ops, grid, material, normal=.not. use_fmg, tangential=tangential, &
            circulant_normal=settings%normal%solver == 'bccg' .and. settings%normal%precondition .and. &
                             settings%normal%prec_form == 'circulant', &
            circulant_tangential=load%problem /= FC_PROBLEM_ROLLING .and. settings%tangential%solver == 'tangcg' .and. &
                                 settings%tangential%precondition .and. settings%tangential%preconditioner == 'fft' .and. &
                                 settings%tangential%prec_form == 'circulant')
        call contact_rounds(ops%normal, ops%tangential, grid, material, h0, load, settings, res, stat, errmsg, &
                            state, surface)
        if (ops%periodic) then
            ! a periodic cell has no edge: the area cannot clip the contact
            res%normal%touches_boundary = .false.
            if (res%normal%status == FC_CONVERGED) res%normal%message = 'converged'
        end if
        res%setup_seconds_normal = ops%setup_seconds_normal
        res%setup_seconds_tangential = ops%setup_seconds_tangential
    end subroutine solve_contact

    !> Normal and tangential problems together on built operators: the compatibility entry
    !! point of the operator-level API ([[solve_contact]] builds the operators itself).
    !! `approach` or `fn` as in [[solve_normal]]; `rounds`: Panagiotopoulos rounds done.
    subroutine solve_normal_tangential(nop, top, h0, nsettings, tsettings, load, nres, tres, stat, errmsg, &
                                       approach, fn, rounds, p_start, px_start, py_start)
        type(fc_normal_operator), intent(inout) :: nop
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: h0(:, :)
        type(fc_normal_settings), intent(in) :: nsettings
        type(fc_tangential_settings), intent(in) :: tsettings
        type(fc_tangential_loading), intent(in) :: load
        type(fc_normal_result), intent(out) :: nres
        type(fc_tangential_result), intent(out) :: tres
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: approach, fn
        integer, intent(out), optional :: rounds
        real(dp), intent(in), optional :: p_start(:, :), px_start(:, :), py_start(:, :)  !! warm start
        type(fc_contact_loading) :: cload
        type(fc_contact_settings) :: settings
        type(fc_contact_result) :: res
        stat = 0; errmsg = ''
        if (.not. top%a_xx%built()) then
            stat = FC_ERR_NOT_READY; errmsg = 'solve_normal_tangential: tangential operator not built'; return
        end if
        if (size(h0, 1) /= top%grid%nx .or. size(h0, 2) /= top%grid%ny) then
            stat = FC_ERR_SHAPE; errmsg = 'solve_normal_tangential: h0 does not match the grid'; return
        end if
        cload%problem = FC_PROBLEM_TANGENTIAL
        cload%tangential = load
        cload%normal%force_prescribed = present(fn)
        if (present(fn)) cload%normal%fn = fn
        if (present(approach)) cload%normal%approach = approach
        if (present(p_start)) cload%normal%p_start = p_start
        if (present(px_start) .and. present(py_start)) then
            cload%px_start = px_start; cload%py_start = py_start
        end if
        settings%normal = nsettings; settings%tangential = tsettings
        call contact_rounds(nop, top, top%grid, top%material, h0, cload, settings, res, stat, errmsg)
        if (stat /= 0) return
        if (present(rounds)) rounds = res%rounds
        call move_alloc_normal(res%normal, nres)
        tres = res%tangential
    end subroutine solve_normal_tangential

    subroutine move_alloc_normal(from, to)
        type(fc_normal_result), intent(inout) :: from
        type(fc_normal_result), intent(out) :: to
        to = from
    end subroutine move_alloc_normal

    !> The rounds of [[solve_contact]] on built operators.
    subroutine contact_rounds(nop, top, grid, material, h0, load, settings, res, stat, errmsg, state, surface)
        type(fc_normal_operator), intent(inout) :: nop
        type(fc_tangential_operator), intent(inout) :: top
        type(fc_grid), intent(in) :: grid
        type(fc_material), intent(in) :: material
        real(dp), intent(in) :: h0(:, :)
        type(fc_contact_loading), intent(in) :: load
        type(fc_contact_settings), intent(in) :: settings
        type(fc_contact_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_contact_state), intent(inout), optional :: state
        class(fc_surface), intent(in), optional :: surface
        real(dp), allocatable :: uzt(:, :), uxn(:, :), uyn(:, :), uxp(:, :), uyp(:, :), pxs(:, :), pys(:, :)
        real(dp), allocatable :: p0(:, :), pn_old(:, :), px_old(:, :), py_old(:, :)
        logical :: tangential, coupled, use_fmg, lift_state, has_guess
        integer :: round, nx, ny, it_n, mv_n, pa_n, out_n, it_t, mv_t, out_t
        real(dp) :: cpu_n, cpu_t, dn, dt, guess_base(2), p0_total, p0_scale
        stat = 0; errmsg = ''
        nx = grid%nx; ny = grid%ny
        tangential = load%problem /= FC_PROBLEM_NORMAL
        coupled = tangential .and. material%k /= 0
        use_fmg = settings%normal%solver == 'fmg'
        ! coupling displacements only when coupled, u' only in the transient modes: an
        ! unallocated array passed to an optional argument is absent (no zero arrays per call)
        if (coupled) then
            allocate (uzt(nx, ny), uxn(nx, ny), uyn(nx, ny))
            uzt = 0; uxn = 0; uyn = 0
        end if
        ! ---- starts: an explicit start in `load`, else the state's
        lift_state = .false.; has_guess = .false.; guess_base = 0
        if (present(state)) call state_inputs(state)
        if (allocated(load%px_start) .and. allocated(load%py_start)) then
            pxs = load%px_start; pys = load%py_start
        end if
        if (.not. allocated(pxs)) then
            allocate (pxs(nx, ny), pys(nx, ny))
            pxs = 0; pys = 0
        end if
        if (allocated(load%normal%p_start)) then
            p0 = possible(load%normal%p_start)
        else if (present(state)) then
            if (state%warm_start .and. state%has_normal) then
                if (load%normal%force_prescribed) then
                    ! a force-constrained solve keeps the start's total force: scale it to Fn
                    ! (one pass for the sum, one for the start)
                    p0_total = sum(state%pn, mask=h0 < 0.5_dp*h_no_contact)
                    p0_scale = 1
                    if (p0_total > 0) p0_scale = load%normal%fn/(p0_total*grid%area())
                    p0 = merge(state%pn*p0_scale, 0.0_dp, h0 < 0.5_dp*h_no_contact)
                else
                    p0 = possible(state%pn)
                end if
            end if
        end if
        ! ---- rounds: normal, then tangential; repeated only when coupled
        it_n = 0; mv_n = 0; pa_n = 0; out_n = 0; cpu_n = 0; it_t = 0; mv_t = 0; out_t = 0; cpu_t = 0
        do round = 1, max_rounds
            if (round == 1 .and. .not. coupled) then
                call normal_stage(h0, p0)
            else if (round == 1) then
                call normal_stage(h0 + uzt, p0)
            else
                pn_old = res%normal%pn
                call normal_stage(h0 + uzt, pn_old)
            end if
            if (stat /= 0) return
            it_n = it_n + res%normal%iterations; mv_n = mv_n + res%normal%matvecs
            pa_n = pa_n + res%normal%precond_applications; out_n = out_n + res%normal%outer_iterations
            cpu_n = cpu_n + res%normal%cpu_seconds
            if (tangential) res%rounds = round
            if (res%normal%status /= FC_CONVERGED) exit
            if (.not. tangential) exit
            if (coupled) call coupling_displacements(top, res%normal%pn, pxs, pys, uxn, uyn, uzt)
            if (round > 1) then
                px_old = res%tangential%px; py_old = res%tangential%py
            end if
            if (round == 1 .and. lift_state) call lift_slip(res%normal%pn, state%el)
            if (round > 1 .and. load%problem == FC_PROBLEM_ROLLING) call lift_slip(res%normal%pn, res%tangential%state)
            call tangential_stage(res%normal%pn)
            if (stat /= 0) return
            res%tangential_run = .true.
            it_t = it_t + res%tangential%iterations; mv_t = mv_t + res%tangential%matvecs
            out_t = out_t + res%tangential%outer_iterations; cpu_t = cpu_t + res%tangential%cpu_seconds
            if (.not. coupled .or. res%tangential%status /= FC_CONVERGED) exit
            pxs = res%tangential%px; pys = res%tangential%py
            call coupling_displacements(top, res%normal%pn, res%tangential%px, res%tangential%py, &
                                        uxn, uyn, uzt)
            if (round > 1) then
                dn = sqrt(sum((res%normal%pn - pn_old)**2)/max(sum(res%normal%pn**2), tiny(1.0_dp)))
                dt = sqrt(sum((res%tangential%px - px_old)**2 + (res%tangential%py - py_old)**2)/ &
                          max(sum(res%tangential%px**2 + res%tangential%py**2), tiny(1.0_dp)))
                if (max(dn, dt) < 10*max(settings%normal%tol, settings%tangential%tol)) exit
            end if
            if (round == max_rounds) then
                res%tangential%status = FC_NOT_CONVERGED
                write (res%tangential%message, '(a,i0,a)') 'Panagiotopoulos process not converged in ', max_rounds, &
                    ' rounds'
            end if
        end do
        res%normal%iterations = it_n; res%normal%matvecs = mv_n; res%normal%precond_applications = pa_n
        res%normal%outer_iterations = out_n; res%normal%cpu_seconds = cpu_n
        if (res%tangential_run) then
            res%tangential%iterations = it_t; res%tangential%matvecs = mv_t
            res%tangential%outer_iterations = out_t; res%tangential%cpu_seconds = cpu_t
            res%status = max(res%normal%status, res%tangential%status)
        else
            if (tangential) call no_tangential_stage(res)
            res%status = res%normal%status
        end if
        if (present(state) .and. res%status == FC_CONVERGED) call advance_state(state)
    contains

        !> Start values from the previous state: u', p' of a transient step, or a warm start.
        subroutine state_inputs(st)
            type(fc_contact_state), intent(in) :: st
            if (.not. (tangential .and. st%has_tangential)) return
            select case (load%transient)
            case (FC_TRANSIENT_SHIFT)
                uxp = st%ux; uyp = st%uy; pxs = st%px; pys = st%py
            case (FC_TRANSIENT_ROLLING)
                allocate (uxp(nx, ny), uyp(nx, ny), pxs(nx, ny), pys(nx, ny))
                call shift_along_x(st%ux, load%dq/grid%dx, uxp)
                call shift_along_x(st%uy, load%dq/grid%dx, uyp)
                call shift_along_x(st%px, load%dq/grid%dx, pxs)
                call shift_along_x(st%py, load%dq/grid%dx, pys)
            case default
                if (st%warm_start) then
                    pxs = st%px; pys = st%py
                end if
            end select
            lift_state = load%transient /= FC_TRANSIENT_ROLLING .and. (st%warm_start .or. load%transient == FC_TRANSIENT_SHIFT)
            ! prescribed forces: predict the shift from the previous one (from rest) or from a zero
            ! increment (transient), corrected by the force change over the initial stiffness
            if (load%tangential%force_prescribed) then
                if (load%transient == FC_FROM_REST .and. st%warm_start) then
                    has_guess = .true.; guess_base = [st%xi, st%eta]
                else if (load%transient /= FC_FROM_REST) then
                    has_guess = .true.; guess_base = 0
                end if
            end if
        end subroutine state_inputs

        !> `p` zeroed where contact is impossible (a solver would keep a start pressure there).
        function possible(p) result(q)
            real(dp), intent(in) :: p(:, :)
            real(dp), allocatable :: q(:, :)
            q = merge(p, 0.0_dp, h0 < 0.5_dp*h_no_contact)
        end function possible

        !> The normal stage: one solve of the LCP for the undeformed distance `h`.
        subroutine normal_stage(h, start)
            real(dp), intent(in) :: h(:, :)
            real(dp), allocatable, intent(in) :: start(:, :)
            type(fc_fmg_stats) :: st
            if (use_fmg) then
                if (load%normal%force_prescribed) then
                    call solve_normal_fmg(material, grid, h, settings%fmg, res%normal, stat, errmsg, fn=load%normal%fn, &
                                          surface=surface, stats=st)
                else
                    call solve_normal_fmg(material, grid, h, settings%fmg, res%normal, stat, errmsg, &
                                          approach=load%normal%approach, surface=surface, stats=st)
                end if
                if (stat == 0) then
                    res%work_units = st%work_units; res%convergence_factor = st%convergence_factor
                end if
            else if (load%normal%force_prescribed) then
                call solve_normal(nop, h, settings%normal, res%normal, stat, errmsg, fn=load%normal%fn, &
                                  p_start=start)
            else
                call solve_normal(nop, h, settings%normal, res%normal, stat, errmsg, &
                                  approach=load%normal%approach, p_start=start)
            end if
        end subroutine normal_stage

        !> The tangential stage for pressure `pn`: the one dispatch on the problem kind.
        subroutine tangential_stage(pn)
            real(dp), intent(in) :: pn(:, :)
            real(dp) :: k0, a, guess(2), flimit
            select case (load%problem)
            case (FC_PROBLEM_TANGENTIAL)
                if (load%tangential%force_prescribed) then
                    flimit = load%tangential%mu*sum(max(pn, 0.0_dp))*grid%area()
                    if (.not. (hypot(load%tangential%fx, load%tangential%fy) < flimit)) then
                        stat = FC_ERR_FRICTION_BOUND
                        write (errmsg, '(a,es12.5,a,es12.5,a)') '|(fx, fy)| = ', &
                            hypot(load%tangential%fx, load%tangential%fy), ' must be < mu*fn = ', flimit, &
                            ' (full slip has no unique shift)'
                        return
                    end if
                end if
                if (.not. load%tangential%force_prescribed) then
                    ! prescribed shifts: one solve; unallocated arrays are absent arguments
                    call solve_tangential(top, pn, load%tangential%mu, settings%tangential, res%tangential, stat, &
                        errmsg, load%tangential%xi, load%tangential%eta, load%tangential%phi, ux_prev=uxp, &
                        uy_prev=uyp, px_start=pxs, py_start=pys, offset_x=uxn, offset_y=uyn)
                else if (has_guess) then
                    ! initial stiffness 8Ga/(2−ν) of Mindlin, a from the contact area
                    a = sqrt(count(pn > 0)*grid%area()/pi)
                    k0 = 8*material%g*a/(2 - material%nu)
                    guess = guess_base - ([load%tangential%fx, load%tangential%fy] - [state%fx, state%fy])/k0
                    call solve_tangential_loading(top, pn, load%tangential, settings%tangential, &
                        res%tangential, stat, errmsg, ux_prev=uxp, uy_prev=uyp, px_start=pxs, py_start=pys, &
                        offset_x=uxn, offset_y=uyn, xi_start=guess(1), eta_start=guess(2))
                else
                    call solve_tangential_loading(top, pn, load%tangential, settings%tangential, &
                        res%tangential, stat, errmsg, ux_prev=uxp, uy_prev=uyp, px_start=pxs, py_start=pys, &
                        offset_x=uxn, offset_y=uyn)
                end if
            case (FC_PROBLEM_ROLLING)
                call rolling_stage(pn)
            case default
                stat = FC_ERR_VALUE
                write (errmsg, '(a,i0,a)') 'solve_contact: problem kind ', load%problem, ' has no tangential stage'
            end select
        end subroutine tangential_stage

        !> Steady rolling (creepages or creep forces); a warm start from the state also
        !! starts the creep-force loop from the previous creepages.
        subroutine rolling_stage(pn)
            real(dp), intent(in) :: pn(:, :)
            type(fc_rolling_loading) :: rl
            rl%mu = load%tangential%mu; rl%mu_kinetic = load%mu_kinetic
            rl%xi = load%tangential%xi; rl%eta = load%tangential%eta; rl%phi = load%tangential%phi
            rl%fx = load%tangential%fx; rl%fy = load%tangential%fy
            rl%force_prescribed = load%tangential%force_prescribed
            if (has_guess) then
                call solve_rolling_loading(top, pn, rl, settings%rolling, res%tangential, stat, errmsg, &
                    px_start=pxs, py_start=pys, offset_x=uxn, offset_y=uyn, xi_start=guess_base(1), &
                    eta_start=guess_base(2), reference=reference_solver)
            else
                call solve_rolling_loading(top, pn, rl, settings%rolling, res%tangential, stat, errmsg, &
                    px_start=pxs, py_start=pys, offset_x=uxn, offset_y=uyn, reference=reference_solver)
            end if
        end subroutine rolling_stage

        !> Elements in slip in `el` (the previous state, or the previous Panagiotopoulos round
        !! of steady rolling) start just above the new static bound μs·pn in their previous
        !! direction, so that the solver starts them in slip (TangCG on its bound, the rolling
        !! solver on the kinetic circle) although the pressure under them changed; without
        !! this a converged start loses its subdivision to rounding, and the rounds of rolling
        !! with μk < μs cycled (doc/rolling.md).
        subroutine lift_slip(pn, el)
            real(dp), intent(in) :: pn(:, :)
            integer, intent(in) :: el(:, :)
            real(dp) :: mag
            integer :: i, j
            do j = 1, size(pn, 2)                 ! |p| only where needed: slip elements
                do i = 1, size(pn, 1)
                    if (el(i, j) /= EL_SLIP .or. .not. pn(i, j) > 0) cycle
                    mag = hypot(pxs(i, j), pys(i, j))
                    if (.not. mag > 0) cycle
                    pxs(i, j) = (1 + 1e-10_dp)*load%tangential%mu*pn(i, j)*pxs(i, j)/mag
                    pys(i, j) = (1 + 1e-10_dp)*load%tangential%mu*pn(i, j)*pys(i, j)/mag
                end do
            end do
        end subroutine lift_slip

        subroutine advance_state(st)
            type(fc_contact_state), intent(inout) :: st
            st%pn = res%normal%pn; st%has_normal = .true.
            if (res%tangential_run) then
                st%px = res%tangential%px; st%py = res%tangential%py; st%el = res%tangential%state
                if (coupled) then
                    st%ux = res%tangential%ux + uxn; st%uy = res%tangential%uy + uyn
                else
                    st%ux = res%tangential%ux; st%uy = res%tangential%uy
                end if
                st%xi = res%tangential%xi; st%eta = res%tangential%eta
                st%fx = res%tangential%fx; st%fy = res%tangential%fy
                st%has_tangential = .true.
            end if
        end subroutine advance_state
    end subroutine contact_rounds

    !> Tangential fields of a tangential problem whose tangential stage did not run (the
    !! normal stage failed): zero tractions and slip, adhesion where pn > 0.
    subroutine no_tangential_stage(res)
        type(fc_contact_result), intent(inout) :: res
        if (.not. allocated(res%normal%pn)) return
        associate (pn => res%normal%pn, t => res%tangential)
            allocate (t%px, t%py, t%sx, t%sy, t%ux, t%uy, mold=pn)
            t%px = 0; t%py = 0; t%sx = 0; t%sy = 0; t%ux = 0; t%uy = 0
            allocate (t%state(size(pn, 1), size(pn, 2)))
            t%state = merge(EL_ADHESION, EL_EXTERIOR, pn > 0)
            t%ncon = res%normal%ncon; t%nadh = res%normal%ncon; t%nslip = 0
        end associate
    end subroutine no_tangential_stage

    !> g(i, j) = f at x_i + shift·dx: linear interpolation between element centres along x;
    !! samples beyond the grid are 0 (undeformed material enters the area).  A whole-element
    !! shift moves values exactly.
    pure subroutine shift_along_x(f, shift, g)
        real(dp), intent(in) :: f(:, :)
        real(dp), intent(in) :: shift   !! shift in elements (dq/dx)
        real(dp), intent(out) :: g(:, :)
        integer :: i, k, nx, i0
        real(dp) :: w
        nx = size(f, 1)
        g = 0
        if (.not. abs(shift) < nx + 1) return
        k = floor(shift)
        w = shift - k
        do i = 1, nx
            i0 = i + k
            if (i0 >= 1 .and. i0 <= nx) g(i, :) = g(i, :) + (1 - w)*f(i0, :)
            if (w > 0 .and. i0 + 1 >= 1 .and. i0 + 1 <= nx) g(i, :) = g(i, :) + w*f(i0 + 1, :)
        end do
    end subroutine shift_along_x

    !> Run the rolling sequence `seq` (a creep-force sweep or transient rolling, from the
    !! case's [[fc_rolling_case]]) with the loading and settings prepared for one solve
    !! (`load_in%problem` = FC_PROBLEM_ROLLING for a sweep, its creepages `load_in%tangential`;
    !! the transient run sets its own shifts creepage·dq).  `res`: the last point or step; `rows`: one row per point/step
    !! (last column: the status code; written as its name).  Transient rolling stops at its
    !! first step that does not converge (the later steps would start from it).  A sweep goes
    !! on: the next point starts from the last converged one (cold when there is none yet),
    !! and `res` carries the worst status of the points, with a message naming how many did
    !! not converge and the first of them.
    subroutine rolling_sequence(seq, ops, grid, mat, h0, load_in, settings, res, rows, stat, errmsg)
        type(fc_rolling_case), intent(in) :: seq
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_grid), intent(in) :: grid
        type(fc_material), intent(in) :: mat
        real(dp), intent(in) :: h0(:, :)
        type(fc_contact_loading), intent(in) :: load_in
        type(fc_contact_settings), intent(in) :: settings
        type(fc_contact_result), intent(out) :: res
        real(dp), allocatable, intent(out) :: rows(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_contact_loading) :: load
        type(fc_contact_state) :: state, good, before
        real(dp) :: dq, value, mufn, secs, first_failed
        integer :: k, n, nfailed, worst
        logical :: two_good   !! the last two points converged (a predictor may use them)
        logical :: prev_ok    !! the point before converged
        integer(i8) :: t0, t1, rate
        stat = 0; errmsg = ''
        load = load_in
        state%warm_start = .true.
        good = state
        two_good = .false.; prev_ok = .false.
        nfailed = 0; worst = FC_CONVERGED; first_failed = 0
        if (seq%transient) then
            dq = seq%dq
            if (dq == 0) dq = grid%dx
            n = seq%nsteps
            if (n == 0) n = max(1, ceiling(4*(grid%xmax - grid%xmin)/dq))
            load%problem = FC_PROBLEM_TANGENTIAL
            load%transient = FC_TRANSIENT_ROLLING
            load%dq = dq
            load%tangential%force_prescribed = .false.
            load%tangential%xi = load_in%tangential%xi*dq; load%tangential%eta = load_in%tangential%eta*dq
            load%tangential%phi = load_in%tangential%phi*dq
            allocate (rows(n, 13))
        else
            n = seq%sweep_n
            allocate (rows(n, 15))
        end if
        rows = 0
        do k = 1, n
            if (.not. seq%transient) then
                value = seq%sweep_from + (seq%sweep_to - seq%sweep_from)*(k - 1)/real(n - 1, dp)
                select case (seq%sweep)
                case ('xi'); load%tangential%xi = value
                case ('eta'); load%tangential%eta = value
                case ('phi'); load%tangential%phi = value
                case ('fx'); load%tangential%fx = value
                case ('fy'); load%tangential%fy = value
                end select
                ! creepage sweeps, equally spaced points: the tractions extrapolated linearly
                ! from the two converged points before (2·p_k − p_k−1) are a closer start than
                ! p_k; the warm start then sorts them (beyond the bound: slip, projected), and
                ! the slip elements of p_k are lifted to the new bound as for any warm start.
                ! Not for force sweeps: their first solve runs at the previous creepages, which
                ! the predicted tractions do not match (measured: 24 % more Krylov iterations),
                ! and creepages extrapolated as well overshoot near saturation (doc/rolling.md)
                if (two_good .and. settings%rolling%sweep_predictor .and. .not. load%tangential%force_prescribed) &
                    call extrapolate_tractions(state%px, state%py, before%px, before%py, 1.0_dp)
            end if
            call system_clock(t0, rate)
            call solve_contact(ops, grid, mat, h0, load, settings, res, stat, errmsg, state=state)
            call system_clock(t1)
            if (stat /= 0) then
                rows = rows(1:k - 1, :)
                return
            end if
            secs = real(t1 - t0, dp)/rate
            mufn = load%tangential%mu*res%normal%fn
            if (.not. mufn > 0) mufn = 1
            associate (t => res%tangential)
                if (seq%transient) then
                    rows(k, :) = [real(k, dp), k*dq, t%fx, t%fy, t%mz, t%fx/mufn, t%fy/mufn, t%dissipation, real(t%nadh, dp), &
                                  real(t%nslip, dp), real(t%iterations, dp), secs, real(res%status, dp)]
                else
                    rows(k, :) = [value, t%xi, t%eta, t%phi, t%fx, t%fy, t%mz, t%fx/mufn, t%fy/mufn, t%dissipation, &
                                  real(t%nadh, dp), real(t%nslip, dp), real(t%iterations, dp), secs, real(res%status, dp)]
                end if
            end associate
            if (res%status == FC_CONVERGED) then
                if (.not. seq%transient) then
                    two_good = prev_ok
                    if (two_good) before = good
                    good = state
                    prev_ok = .true.
                end if
            else if (seq%transient) then
                rows = rows(1:k, :)
                exit
            else
                ! the failed point's row carries its status; the next point starts from the
                ! last converged solution, not from this one
                nfailed = nfailed + 1
                if (nfailed == 1) first_failed = value
                worst = max(worst, res%status)
                state = good
                two_good = .false.; prev_ok = .false.
            end if
        end do
        if (nfailed > 0) then
            res%status = max(res%status, worst)
            res%tangential%status = max(res%tangential%status, worst)
            res%tangential%message = fmt_int(nfailed)//' of '//fmt_int(n)//' sweep points did not converge '// &
                '(statuses in the creep table; the first at '//trim(seq%sweep)//' = '//fmt_real(first_failed)//')'
        end if
        if (seq%transient) then
            ! report the creepages (the steps used creepage·dq as shifts)
            res%tangential%xi = load_in%tangential%xi; res%tangential%eta = load_in%tangential%eta
            res%tangential%phi = load_in%tangential%phi
        end if
    end subroutine rolling_sequence

    !> Tractions of a start predicted along a sequence of solves: p ← p + α·(p − p_before),
    !! the linear extrapolation from the converged tractions of the step before over α steps,
    !! in place.  The warm start of [[solve_contact]] sorts them as any start (slip lifted to
    !! the new bound; beyond the static bound: slip, projected).
    pure subroutine extrapolate_tractions(px, py, px_before, py_before, alpha)
        real(dp), intent(inout) :: px(:, :), py(:, :)
        real(dp), intent(in) :: px_before(:, :), py_before(:, :)
        real(dp), intent(in) :: alpha
        px = px + alpha*(px - px_before)
        py = py + alpha*(py - py_before)
    end subroutine extrapolate_tractions

    !> [[extrapolate_tractions]] that also hands back the tractions before the step: on return
    !! px_before, py_before hold the px, py given (one pass, no copy of them).
    pure subroutine extrapolate_tractions_swap(px, py, px_before, py_before, alpha)
        real(dp), intent(inout) :: px(:, :), py(:, :), px_before(:, :), py_before(:, :)
        real(dp), intent(in) :: alpha
        real(dp) :: t
        integer :: i, j
        do j = 1, size(px, 2)
            do i = 1, size(px, 1)
                t = px(i, j); px(i, j) = t + alpha*(t - px_before(i, j)); px_before(i, j) = t
                t = py(i, j); py(i, j) = t + alpha*(t - py_before(i, j)); py_before(i, j) = t
            end do
        end do
    end subroutine extrapolate_tractions_swap

    !> How many of the last input steps d1 the new step d2 amounts to (inputs scaled to be
    !! comparable, see the callers): α = d2·d1/|d1|² when d2 continues d1 — α in (0, 2] and
    !! the part of d2 across d1 at most half of |d2| — else 0 (no prediction: a reversal, a
    !! jump or a turn of the inputs).
    pure real(dp) function continuation_factor(d1, d2) result(alpha)
        real(dp), intent(in) :: d1(:), d2(:)
        real(dp) :: n1
        alpha = 0
        n1 = sum(d1**2)
        if (.not. n1 > 0) return
        alpha = sum(d1*d2)/n1
        if (.not. (alpha > 0 .and. alpha <= 2)) then
            alpha = 0
        else if (sum((d2 - alpha*d1)**2) > 0.25_dp*sum(d2**2)) then
            alpha = 0
        end if
    end function continuation_factor

end module fc_contact
