!> The flat API's calculation (doc/legacy_api.md): `fc_calculate` checks that a handle's
!! inputs are complete, checks memory before operators are built for a new grid, predicts
!! the start of a rolling or tangential call from the calls before, and solves through the
!! library's orchestrator [[solve_contact]], reusing the handle's operators while the grid
!! and the material are unchanged.
!!
!! `bind(C)` with an integer error code `ierr` (the `FCL_*` constants of
!! [[fc_legacy_registry]]); ierr = 4/5 (not converged / diverged) still leaves the result
!! readable ([[fc_legacy_results]]).
module fc_legacy_calculate
    use, intrinsic :: iso_c_binding, only: c_int
    use fc_kinds
    use fc_geometry
    use fc_contact_types
    use fc_contact, only: solve_contact, continuation_factor, extrapolate_tractions_swap
    use fc_strings, only: fmt_int
    use fc_legacy_registry
    use fc_threads, only: set_thread_count, fc_thread_count
    use fc_memory, only: memory_fits, serial_bytes_per_element, case_memory_bytes, format_bytes, memory_env, &
        memory_base_bytes
    use fc_fft_effort, only: prime_fft_plans, use_fft_wisdom
    implicit none
    private

    public :: fc_calculate

contains

    ! =====================================================================================
    ! calculation
    ! =====================================================================================

    !> Solve the normal problem and, if shifts or forces were set, the tangential problem.
    !! ierr = 4/5 (not converged / diverged) still leaves the result readable; the previous
    !! state (warm start, u', p') advances only on ierr = 0.
    subroutine fc_calculate(handle, ierr) bind(C, name='fc_calculate')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        logical :: taken
        call lookup(handle, 'fc_calculate', s, ierr)
        if (ierr /= FCL_OK) return
        !$omp critical (fc_legacy_busy)
        taken = s%busy
        s%busy = .true.
        !$omp end critical (fc_legacy_busy)
        if (taken) then
            ierr = FCL_ORDER   ! the message slot belongs to the running calculation: left alone
            return
        end if
        call calculate(s, ierr)
        s%busy = .false.
    end subroutine fc_calculate

    subroutine calculate(s, ierr)
        type(legacy_state), intent(inout) :: s
        integer(c_int), intent(out) :: ierr
        integer :: stat
        character(len=msg_len) :: msg
        real(dp) :: key(8)
        logical :: kept, predicted
        ierr = FCL_OK
        ! --- required data ---
        if (.not. s%has_material) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: material not set (call fc_set_material)'); return
        end if
        if (.not. s%has_grid) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: grid not set (call fc_set_grid)'); return
        end if
        if (s%gap_kind == GAP_NONE) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: undeformed distance not set for the current grid '// &
                '(call fc_set_gap_array or fc_set_gap_quadratic)'); return
        end if
        if (.not. s%has_normal) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: normal loading not set (call fc_set_normal_force or '// &
                'fc_set_normal_approach)'); return
        end if
        if (s%load%problem /= FC_PROBLEM_NORMAL .and. .not. s%has_friction) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: shifts or forces set but no friction (call fc_set_friction)')
            return
        end if
        if (s%ops%periodic .and. .not. s%load%normal%force_prescribed) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: the periodic half-space needs the normal force (mean '// &
                'pressure x cell area, fc_set_normal_force)'); return
        end if
        s%has_result = .false.
        call set_thread_count(s%threads)
        call check_memory(s, stat, msg)
        if (stat /= 0) then
            call fail(s, ierr, flat_code(stat), 'fc_calculate: '//trim(msg)); return
        end if
        if (allocated(s%fft_wisdom)) then
            call wisdom_plans(s, stat, msg)
            if (stat /= 0) then
                call fail(s, ierr, FCL_INVALID_VALUE, "fc_calculate: FFT wisdom file '"//s%fft_wisdom//"': "//trim(msg))
                return
            end if
        else if (s%fft_effort == 1) then
            call measure_plans(s)
        end if
        if (s%heap_cells /= s%grid%nx*s%grid%ny) call keep_work_arrays(s)
        ! --- the solve: operators reused while grid spacing and material match; the previous
        !     state (warm start, u', p') advances only when every stage converged.  The
        !     quadratic gap is evaluated again only when the grid or the radii change.
        if (s%gap_kind == GAP_QUADRATIC) then
            key = [real(s%grid%nx, dp), real(s%grid%ny, dp), s%grid%xmin, s%grid%xmax, s%grid%ymin, s%grid%ymax, s%rx, s%ry]
            if (.not. allocated(s%hq) .or. any(key /= s%hq_key)) then
                s%hq = quadratic_gap(s%grid, s%rx, s%ry)
                s%hq_key = key
            end if
        end if
        call rolling_start(s, kept, predicted)
        if (s%gap_kind == GAP_QUADRATIC) then
            call solve_contact(s%ops, s%grid, s%mat, s%hq, s%load, s%settings, s%result, stat, msg, state=s%prev)
        else
            call solve_contact(s%ops, s%grid, s%mat, s%h0, s%load, s%settings, s%result, stat, msg, state=s%prev)
        end if
        call rolling_advance(s, kept, predicted, stat == 0 .and. s%result%status == FC_CONVERGED)
        if (stat /= 0) then
            call fail(s, ierr, flat_code(stat), 'fc_calculate: '//trim(msg)); return
        end if
        s%calculations = s%calculations + 1
        s%has_result = .true.
        if (s%result%normal%status /= FC_CONVERGED) then
            call fail(s, ierr, status_code(s%result%normal%status), 'fc_calculate: normal problem: '// &
                trim(s%result%normal%message))
        else if (s%result%tangential_run .and. s%result%tangential%status /= FC_CONVERGED) then
            call fail(s, ierr, status_code(s%result%tangential%status), 'fc_calculate: tangential problem: '// &
                trim(s%result%tangential%message))
        end if
    end subroutine calculate

    !> Before operators are built for a new grid (or a first tangential solve): the
    !! estimated peak memory of the solve (doc/reliability.md, "Memory": bytes per element of
    !! the problem kind and thread count) against the memory this process may still use plus
    !! what the handle's current operators hold, which the rebuild releases.  stat =
    !! FC_ERR_ALLOC when it does not fit (nothing is built; the handle keeps its state),
    !! FC_ERR_VALUE for an invalid `FASTCONTACT_AVAILABLE_MEMORY`.  Unknown available memory
    !! checks nothing.  A multibody code sets its grids once, so this runs once per handle.
    subroutine check_memory(s, stat, msg)
        type(legacy_state), intent(in) :: s
        integer, intent(out) :: stat
        character(len=msg_len), intent(out) :: msg
        integer(i8) :: need, held, limit
        character(len=:), allocatable :: source, kind
        real(dp) :: bpe
        logical :: tangential, fits, coupled, fmg_rsm
        stat = 0; msg = ''
        tangential = s%load%problem /= FC_PROBLEM_NORMAL
        if (s%ops%normal%matches(s%grid, s%mat) .and. &
            (.not. tangential .or. s%ops%tangential%matches(s%grid, s%mat))) return
        kind = 'tangential'
        if (.not. tangential) kind = 'normal'
        if (s%load%problem == FC_PROBLEM_ROLLING) kind = 'rolling'
        if (tangential .and. s%load%transient /= FC_FROM_REST) kind = 'transient'
        ! the coupling blocks are built when K ≠ 0; a coefficient set is loaded already
        ! (fc_set_influence_file checked its memory) and is not part of this estimate
        coupled = tangential .and. s%mat%k /= 0
        fmg_rsm = s%settings%normal%solver == 'fmg' .and. s%settings%fmg%smoother == 'fft-rsm'
        bpe = serial_bytes_per_element(kind, fc_thread_count(), coupled, fmg_rsm)
        if (coupled) kind = kind//' (dissimilar materials)'
        need = case_memory_bytes(int(s%grid%nx, i8)*s%grid%ny, bpe)
        ! what the current operators release, counted low: the one-thread estimate of a
        ! normal, or normal + tangential, solve on their grid
        held = 0
        if (s%ops%normal%a_zz%built()) held = case_memory_bytes(int(s%ops%normal%grid%nx, i8)*s%ops%normal%grid%ny, &
            serial_bytes_per_element(merge('tangential', 'normal    ', s%ops%tangential%a_xx%built()), 1)) - &
            memory_base_bytes
        ! the host's own memory is not the library's to release: no resident size added
        call memory_fits(need, 1, held, .false., fits, limit, source, stat, msg)
        if (stat /= 0 .or. fits) return
        stat = FC_ERR_ALLOC
        msg = 'grid nx = '//fmt_int(s%grid%nx)//', ny = '//fmt_int(s%grid%ny)//': the '//kind//' solve on '// &
            fmt_int(fc_thread_count())//' thread(s) needs about '//format_bytes(need)//', more than the '// &
            format_bytes(limit)//' this process may use ('//source//'); use a coarser grid, or set '// &
            memory_env//' to override'
    end subroutine check_memory

    !> Steady rolling with prescribed creepages, or the shift problem with prescribed shifts
    !! (from rest), warm-started: when the two converged calls before this one moved the
    !! inputs (ξ, η, φ, Fn or δ, μ) along one direction and this call continues it, the start
    !! is extrapolated from their solutions ([[continuation_factor]],
    !! [[extrapolate_tractions_swap]]), as a multibody code's time steps do.  The previous
    !! converged tractions move to px2, py2 (`kept`: the call is predictable), where
    !! [[rolling_advance]] finds them.  Measured: doc/rolling.md, "Flat API".
    subroutine rolling_start(s, kept, predicted)
        type(legacy_state), intent(inout) :: s
        logical, intent(out) :: kept, predicted
        real(dp) :: v(5), sc(5), alpha
        kept = .false.; predicted = .false.
        if (.not. (predictable(s) .and. s%prev%has_tangential)) return
        kept = .true.
        if (s%converged_in_row >= 2 .and. allocated(s%px2) .and. s%load%problem == s%inputs_problem) then
            if (all(shape(s%px2) == shape(s%prev%px))) then
                v = rolling_inputs(s)
                ! creepages on one scale (φ times the half length of the area), Fn or δ and μ
                ! relative, each scale the largest magnitude of the three calls (1 where all
                ! are zero), so that every scaled difference lies in [−2, 2]
                sc(1:3) = max(maxval(abs(v(1:3))), maxval(abs(s%inputs1(1:3))), maxval(abs(s%inputs2(1:3))))
                sc(4:5) = max(abs(v(4:5)), abs(s%inputs1(4:5)), abs(s%inputs2(4:5)))
                where (.not. sc > 0) sc = 1
                alpha = continuation_factor((s%inputs1 - s%inputs2)/sc, (v - s%inputs1)/sc)
                if (alpha > 0) then
                    call extrapolate_tractions_swap(s%prev%px, s%prev%py, s%px2, s%py2, alpha)
                    predicted = .true.
                    return
                end if
            end if
        end if
        s%px2 = s%prev%px; s%py2 = s%prev%py      ! in place when the shapes agree
    end subroutine rolling_start

    !> After the solve: a converged call becomes the newest of the two the predictor uses
    !! (px2, py2 already hold the one before); a call that did not converge leaves the
    !! previous converged tractions as the warm start (undoing a prediction) and restarts
    !! the count.
    subroutine rolling_advance(s, kept, predicted, converged)
        type(legacy_state), intent(inout) :: s
        logical, intent(in) :: kept, predicted, converged
        if (.not. predictable(s)) then
            s%converged_in_row = 0
        else if (converged) then
            if (s%load%problem /= s%inputs_problem) s%converged_in_row = 0   ! shifts are not creepages
            s%inputs_problem = s%load%problem
            s%inputs2 = s%inputs1; s%inputs1 = rolling_inputs(s)
            s%converged_in_row = min(2, s%converged_in_row + 1)
        else
            if (predicted .and. kept) then
                s%prev%px = s%px2; s%prev%py = s%py2
            end if
            s%converged_in_row = 0
        end if
    end subroutine rolling_advance

    logical function predictable(s)
        type(legacy_state), intent(in) :: s
        predictable = (s%load%problem == FC_PROBLEM_ROLLING .or. s%load%problem == FC_PROBLEM_TANGENTIAL) .and. &
            s%load%transient == FC_FROM_REST .and. &
            .not. s%load%tangential%force_prescribed .and. s%prev%warm_start
    end function predictable

    !> (ξ, η, φ·half length of the area in x, Fn [N] or δ [mm], μ) of the current loading:
    !! creepages [–] or shifts [mm], spin creepage [1/mm] or spin shift [rad].
    function rolling_inputs(s) result(v)
        type(legacy_state), intent(in) :: s
        real(dp) :: v(5)
        v(1) = s%load%tangential%xi; v(2) = s%load%tangential%eta
        v(3) = s%load%tangential%phi*0.5_dp*(s%grid%xmax - s%grid%xmin)
        v(4) = merge(s%load%normal%fn, s%load%normal%approach, s%load%normal%force_prescribed)
        v(5) = s%load%tangential%mu
    end function rolling_inputs

    !> Let the C heap keep the solvers' per-call work arrays.  The solvers allocate some 30
    !! arrays of nx·ny reals per call and free them on return; glibc returns freed memory at
    !! the top of its heap to the system once it exceeds a threshold (128 KB by default) and
    !! the next call faults it in again — about half of the per-call time outside the
    !! solvers at 60×50 (doc/legacy_api.md).  glibc raises that threshold to the size of any
    !! freed block it had to map separately (up to 32 MB), so one block of the working-set
    !! size, allocated and freed once per grid size, stops the round trips.  With another
    !! allocator this costs one allocation per grid and changes nothing.
    subroutine keep_work_arrays(s)
        type(legacy_state), intent(inout) :: s
        real(dp), allocatable :: block(:)
        integer(i8) :: words
        words = max(32768_i8, min(4194304_i8, 48_i8*s%grid%nx*s%grid%ny))   ! 256 KB … 32 MB
        allocate (block(words))
        block(1) = 0                        ! one page touched: the block is real
        deallocate (block)
        s%heap_cells = s%grid%nx*s%grid%ny
    end subroutine keep_work_arrays

    !> Plans of the handle's grid from its wisdom file (measured and written when the file
    !! lacks them), once per grid shape; operators built before are dropped so that they
    !! are rebuilt on the plans.
    subroutine wisdom_plans(s, stat, msg)
        type(legacy_state), intent(inout) :: s
        integer, intent(out) :: stat
        character(len=*), intent(out) :: msg
        logical :: new_plans
        stat = 0; msg = ''
        if (s%fft_primed(1) == s%grid%nx .and. s%fft_primed(2) == s%grid%ny .and. &
            (s%fft_primed(3) == 1 .eqv. s%ops%periodic)) return
        call use_fft_wisdom(s%fft_wisdom, s%grid%nx, s%grid%ny, s%ops%periodic, new_plans, stat, msg)
        if (stat /= 0) return
        s%fft_primed = [s%grid%nx, s%grid%ny, merge(1, 0, s%ops%periodic)]
        call s%ops%normal%destroy()
        call s%ops%tangential%destroy()
    end subroutine wisdom_plans

    !> FFTW_MEASURE plans for the handle's grid shape, once per shape; operators built on
    !! estimated plans are dropped so that they are rebuilt on the measured ones.
    subroutine measure_plans(s)
        type(legacy_state), intent(inout) :: s
        if (s%fft_primed(1) == s%grid%nx .and. s%fft_primed(2) == s%grid%ny .and. &
            (s%fft_primed(3) == 1 .eqv. s%ops%periodic)) return
        call prime_fft_plans(s%grid%nx, s%grid%ny, s%ops%periodic)
        s%fft_primed = [s%grid%nx, s%grid%ny, merge(1, 0, s%ops%periodic)]
        call s%ops%normal%destroy()
        call s%ops%tangential%destroy()
    end subroutine measure_plans

end module fc_legacy_calculate
