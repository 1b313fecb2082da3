!> Strip model problems of the batch driver (`problem = 'strip_mp1'` … `'strip_mp3'`, thesis
!! §3.2.5): the case record's strip settings mapped onto [[fc_mg2d]], its result onto the
!! case summary, and the memory check of such a case.  Apart from [[fc_driver]] because
!! these problems have their own solvers, settings, memory and outputs.
module fc_driver_strip
    use fc_kinds, only: dp, i8, msg_len, FC_ERROR, status_name
    use fc_geometry, only: fc_grid
    use fc_tangcg_types, only: EL_EXTERIOR, EL_ADHESION
    use fc_mg2d, only: fc_strip_problem, fc_mg2d_settings, fc_mg2d_result, strip_model_problem, solve_strip_mg, &
        solve_strip_fft_rsm, strip_level_sizes
    use fc_fft_effort, only: use_fft_wisdom
    use fc_input, only: fc_case_input, strip_model_index, is_given
    use fc_input_scene, only: case_notes
    use fc_scene, only: fc_case
    use fc_strings, only: fmt_int
    use fc_errors, only: FC_ERR_VALUE, FC_ERR_ALLOC
    use fc_memory, only: memory_fits, format_bytes, memory_env, strip_bytes_per_element, case_memory_bytes
    use fc_output, only: fc_case_summary
    implicit none
    private

    public :: solve_strip_case, strip_memory_need, check_strip_memory

contains

    !> Estimated peak memory of a strip model problem [bytes] (fc_memory: bytes per element
    !! of its solver, nx elements).
    integer(i8) function strip_memory_need(state) result(need)
        type(fc_case_input), intent(in) :: state
        need = case_memory_bytes(int(state%nx, i8), strip_bytes_per_element(state%strip))
    end function strip_memory_need

    !> A strip model problem's estimate against what this process may use (its `share` of
    !! the available memory, plus what it holds): stat = FC_ERR_ALLOC naming `&grid nx` and
    !! `&solver strip`; FC_ERR_VALUE for an invalid `FASTCONTACT_AVAILABLE_MEMORY`.
    subroutine check_strip_memory(state, share, stat, errmsg)
        type(fc_case_input), intent(in) :: state
        integer, intent(in) :: share   !! processes sharing the available memory
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer(i8) :: need, limit
        logical :: fits
        character(len=:), allocatable :: source
        character(len=msg_len) :: m
        need = strip_memory_need(state)
        call memory_fits(need, share, 0_i8, .true., fits, limit, source, stat, m)
        errmsg = m
        if (stat /= 0 .or. fits) return
        stat = FC_ERR_ALLOC
        errmsg = '&grid nx = '//fmt_int(state%nx)//": the strip model problem (&solver strip = '"// &
            trim(state%strip)//"') needs about "//format_bytes(need)//' ('// &
            fmt_int(nint(strip_bytes_per_element(state%strip)))//' B per element), more than the '// &
            format_bytes(limit)//' this process may use ('//source//'); use a smaller nx, or set '//memory_env// &
            ' to override'
    end subroutine check_strip_memory

    !> Solve a strip model problem case (problem = 'strip_mp1' … 'strip_mp3', thesis §3.2.5):
    !! the no-slip tangential problem A^xx p = u on an nx×1 grid of [−4,4]×[−50,50] mm with
    !! `&solver strip` = 'mg-fft-rsm' / 'mg-fft-sd' (multigrid V-cycles `cycle` with the FFT+RSM
    !! / FFT+SD smoother) or 'fft-rsm' (one-grid FFT+RSM).  Returns the summary, the grid, the
    !! traction px per element and the element states (A on the contact strips, E elsewhere).
    !! tol is 1e−8 (thesis) unless `&solver tol` was given.  With `&solver fft_wisdom` the
    !! levels' FFT plans are measured once and kept in that file (fc_fft_effort).
    subroutine solve_strip_case(state, kase, s, grid, px, el, final_status, stat, errmsg)
        type(fc_case_input), intent(in) :: state
        type(fc_case), intent(in) :: kase
        type(fc_case_summary), intent(inout) :: s
        type(fc_grid), intent(out) :: grid
        real(dp), allocatable, intent(out) :: px(:, :)
        integer, allocatable, intent(out) :: el(:, :)
        integer, intent(out) :: final_status
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: t
        type(fc_mg2d_result) :: r
        integer :: n
        final_status = FC_ERROR
        call strip_model_problem(strip_model_index(state), state%nx, prob, stat, errmsg)
        if (stat /= 0) then
            errmsg = '&grid nx = '//fmt_int(state%nx)//": problem = '"//trim(state%problem)//"': "//trim(errmsg); return
        end if
        t%tol = 1.0e-8_dp
        if (is_given(state, 'solver', 'tol')) t%tol = kase%settings%normal%tol
        t%maxit = kase%settings%normal%maxit
        t%nu1 = kase%settings%fmg%nu1; t%nu2 = kase%settings%fmg%nu2
        if (len_trim(kase%fft_wisdom) > 0) then
            block
                logical :: new_plans
                call use_fft_wisdom(trim(kase%fft_wisdom), state%nx, 1, .false., new_plans, stat, errmsg, &
                    strip_sizes=strip_level_sizes(prob, t, state%strip /= 'fft-rsm'))
                if (stat /= 0) then
                    errmsg = "&solver fft_wisdom = '"//trim(kase%fft_wisdom)//"': "//trim(errmsg); return
                end if
            end block
        end if
        select case (state%strip)
        case ('mg-fft-rsm', 'mg-fft-sd')
            t%smoother = state%strip(4:)
            call solve_strip_mg(prob, t, r, stat, errmsg)
        case ('fft-rsm')
            call solve_strip_fft_rsm(prob, t, r, stat, errmsg)
        case default
            stat = FC_ERR_VALUE; errmsg = 'unknown strip solver'
        end select
        if (stat /= 0) then
            errmsg = "&solver strip = '"//trim(state%strip)//"': "//trim(errmsg); return
        end if
        grid = prob%grid
        n = grid%nx
        px = reshape(r%p, [n, 1])
        el = reshape(merge(EL_ADHESION, EL_EXTERIOR, prob%contact), [n, 1])
        final_status = r%status
        s%name = state%name; s%title = state%title; s%problem = state%problem; s%geometry = 'strip2d'
        s%outcome%material = prob%material; s%outcome%grid = grid; s%outcome%model = 'strip2d'
        allocate (s%outcome%reductions(0), s%outcome%warnings(0))
        s%notes = state%notes//case_notes(state)
        s%status = status_name(r%status); s%message = r%message
        s%solver = state%strip
        s%solver_normal = 'none'; s%status_normal = 'not_run'
        s%fx = sum(r%p)*grid%dx*grid%dy
        s%ncon = count(prob%contact); s%nadh = s%ncon; s%nslip = 0
        s%iterations = r%iterations; s%outer_iterations = r%iterations
        s%matvecs = nint(r%work_units); s%residual = r%residual; s%tol = t%tol
        s%work_units = r%work_units; s%convergence_factor = r%factor
        s%cycle = ''
        if (state%strip /= 'fft-rsm') s%cycle = state%cycle
        s%cpu_seconds_tangential = r%cpu_seconds
        stat = 0; errmsg = ''
    end subroutine solve_strip_case

end module fc_driver_strip
