!> Model no more than a scene needs: accuracy-targeted grid refinement, the
!! automatic potential contact area and automatic model reduction, for one [[fc_case]]
!! (built by the batch driver's input layer or by a program).
!!
!! * **Accuracy target** (`&solver target`): solve on a coarse grid, refine by factors of two
!!   in each direction (the coarse pressure and tractions, copied to the 2×2 children, start
!!   the next solve; a direction whose elements are already at most half as long as in the
!!   other waits until the other has caught up, [[refinement_factors]]), and estimate the
!!   relative discretisation error of the computed loads —
!!   `fn` (approach prescribed) or the approach (fn prescribed); |(Fx, Fy)| (shifts
!!   prescribed, relative to max(|Ft|, 0.1·mu·Fn)) or |(xi, eta)| (forces prescribed); `pmax`
!!   with `target_pmax` — from successive grids.  With d_k the relative change from grid k−1
!!   to grid k and r = d_{k−1}/d_k the observed ratio (4 for O(h²)):
!!
!!       est_k = s · max( |d_k| / (min(r, 4) − 1),  |d_{k−1}| / 12 ),   s = 1.5 if 3 ≤ r ≤ 6, else 2
!!
!!   i.e. Richardson for the O(h²) force error measured on Hertz Test I, never less
!!   pessimistic than the observed rate, never below the O(h²) prediction from the previous
!!   difference (protects against a lucky small change), with a safety factor because the
!!   measured ratios of successive true errors scatter: 3.3–5.0 on Hertz Test I (16²–512²),
!!   2.0–4.9 on the Cattaneo sphere (16²–64², contact radius 6–25 elements).  The factor is
!!   1.5 when the observed ratio is that of the O(h²) regime (4 ± 50 %), 2 otherwise; both
!!   were chosen on replays of the reference sequences from every given grid (doc/benchmarks.md).
!!   If r ≤ 1 (differences change sign or grow) convergence is
!!   **non-monotone**: no extrapolation, est_k = max(|d_k|, |d_{k−1}|), and the outcome is
!!   flagged unreliable.  Differences below the solver noise 10·tol count as converged.
!!   With only two grids no rate is known: est_2 = 2·|d_2|, which assumes only that the error
!!   at least halves per level (the slowest ratio measured).
!!   The refinement starts one level below the given grid (a *probe* grid, a quarter of its
!!   cost; skipped when the given grid has fewer than 16 elements or an odd count in a
!!   direction), so that the given grid itself can be the answer, and stops at the first grid
!!   k ≥ 2 with est_k ≤ target, or after `max_levels` grids beyond the probe (target not met:
!!   reported).  The coarsest grid visited whose bound through the finest grid,
!!   max |q_j − q_n| + est_n, meets the target is then reported as the grid the scene needs
!!   (`sufficient`; the solve returns the finest grid's, more accurate, solution).
!! * **Automatic potential contact area** (`&grid auto`): the Hertz estimate of the scene
!!   (elliptic Hertz for quadratic profiles, plane-strain Hertz per unit length for line
!!   contacts) plus `margin`, with `n_across` elements across the contact.  After the solve,
!!   contact in the first or last row or column means the area was too small: enlarged ×1.5
!!   (same element size) and solved again when automatic; a warning when the user fixed it.
!! * **Model reduction** (`&solver model = 'auto'`): `problem = 'hertz'` → analytic Hertz (and
!!   Cattaneo–Mindlin for a circular contact with a prescribed tangential force), no grid; a
!!   line contact → the 2D strip (n×1 grid, the element spanning the cylinder length); no
!!   tangential loading → no tangential solve; K = 0 → one normal and one tangential solve.
!!
!! This module holds the decisions and the refinement loop; the area's sizing is in
!! [[fc_auto_area]], the answers without a grid (analytic Hertz, FASTSIM) in
!! [[fc_auto_answers]], the error estimate in [[fc_auto_estimate]].
!!
!! Size (~650 lines, a sixth of them comments): the case's plan (model, grid), the
!! refinement loop and the one solve it repeats share the outcome they fill, the
!! prolongation of a coarse solution and the coefficient file's use.
module fc_auto
    use fc_kinds, only: dp, i8, msg_len, FC_CONVERGED, status_name
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_result
    use fc_tangcg_types, only: fc_tangential_result, fc_tangential_loading
    use fc_contact, only: take_influence_coefficients, clear_influence_coefficients, &
        fc_contact_operators, fc_contact_loading, fc_contact_settings, fc_contact_result, &
        solve_contact, rolling_sequence, FC_PROBLEM_TANGENTIAL, FC_PROBLEM_ROLLING
    use fc_fmg, only: fc_quadratic_surface, fc_punch_rough_surface, fc_wavy_surface
    use fc_icfile, only: fc_ic_set
    use fc_icfile_load, only: load_influence_source
    use fc_errors, only: FC_ERR_UNSUPPORTED, FC_ERR_IC_FILE, FC_ERR_ALLOC
    use fc_limits, only: max_grid_elements
    use fc_strings, only: fmt_int, fmt_real, append_line
    use fc_scene, only: fc_case, case_setup, is_tangential, is_line_contact, is_rolling_sequence, case_fits_memory
    use fc_case_result, only: fc_level, fc_auto_outcome
    use fc_auto_estimate, only: richardson_estimate, level_estimate, certify_coarsest, target_quantities, &
        estimate_safety, estimate_safety_h2, h2_ratio_low, h2_ratio_high
    use fc_threads, only: set_thread_count
    use fc_fft_effort, only: use_fft_wisdom
    use fc_auto_area, only: auto_area, line_indentation, plane_strain_hertz, contact_touches_boundary, even_up
    use fc_auto_answers, only: analytic_answer, fastsim_answer
    use fc_fastsim, only: fastsim_error_bound
    implicit none
    private

    real(dp), parameter, public :: enlarge_factor = 1.5_dp   !! growth of a clipped automatic area
    integer, parameter :: max_enlargements = 6

    public :: fc_level, fc_auto_outcome
    public :: estimate_safety, estimate_safety_h2, h2_ratio_low, h2_ratio_high
    public :: solve_case_auto, case_grid, auto_area, richardson_estimate, prolong_copy, contact_touches_boundary
    public :: plane_strain_hertz, level_estimate, certify_coarsest, target_quantities

contains

    !> Solve one validated case with the automatic layer: model choice, potential area,
    !! accuracy target.  The operators in `ops` are reused when grid and material match.  stat ≠ 0:
    !! input-type error with a message naming group and key.
    subroutine solve_case_auto(s_in, ops, out, stat, errmsg)
        type(fc_case), intent(in) :: s_in
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_auto_outcome), intent(out) :: out
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_case) :: s
        logical :: tang, line
        integer :: attempt, nx_old, ny_old, nx_new, ny_new
        logical :: fits
        character(len=:), allocatable :: what
        real(dp) :: cx, cy, hx, hy
        s = s_in
        stat = 0; errmsg = ''
        call set_thread_count(s%threads, elements=s%nx*s%ny)   ! before any FFT plan of this case is made
        if (len_trim(s%fft_wisdom) > 0 .and. .not. s%grid_auto .and. s%nx*s%ny > 1) then
            ! measured plans for the case's grid (the thread count above is part of the wisdom);
            ! operators built from here on use them
            block
                logical :: new_plans
                call use_fft_wisdom(trim(s%fft_wisdom), s%nx, s%ny, s%periodic, new_plans, stat, errmsg)
                if (stat /= 0) return
                if (new_plans) then
                    call ops%normal%destroy(); call ops%tangential%destroy()
                end if
            end block
        end if
        allocate (out%reductions(0), out%warnings(0), out%levels(0))
        out%material = s%material
        call combine_material(out%material, stat, errmsg)
        if (stat == 0) call use_ic_file(s, ops, stat, errmsg)
        if (stat /= 0) return
        ! ---- analytic answer (or FASTSIM on the Hertz ellipse): no grid at all
        if (s%rolling%fastsim) then
            call fastsim_answer(s, out, stat, errmsg)
            return
        end if
        ! ---- the FASTSIM rung: steady rolling of a Hertzian scene whose accuracy target FASTSIM
        !      meets by its measured error bound (doc/rolling.md)
        if (fastsim_meets_target(s, out)) return
        if (s%analytic) then
            call analytic_answer(s, out, stat, errmsg)
            return
        end if
        call plan_grid(s, out, tang, line, stat, errmsg)
        if (stat /= 0) return
        ops%periodic = s%periodic
        if (out%grid_auto) then
            ! the automatic grid is checked here, before anything is built (a given grid is
            ! the caller's to check)
            if (int(s%nx, i8)*s%ny > max_grid_elements) then
                stat = FC_ERR_ALLOC
                errmsg = 'automatic potential contact area of '//fmt_int(s%nx)//' x '//fmt_int(s%ny)// &
                    ' elements: more than the 4096^2 elements of a grid'
                return
            end if
            call case_fits_memory(s, s%nx, s%ny, fits, what, stat, errmsg)
            if (stat /= 0) return
            if (.not. fits) then
                stat = FC_ERR_ALLOC
                errmsg = 'automatic potential contact area of '//fmt_int(s%nx)//' x '//fmt_int(s%ny)//' elements: '//what
                return
            end if
        end if
        if (s%target > 0 .and. s%settings%normal%tol > 0.01_dp*s%target) then
            s%settings%normal%tol = 0.01_dp*s%target
            s%settings%tangential%tol = s%settings%normal%tol
            call append_line(out%reductions, 'solver tol tightened to '//fmt_real(s%settings%normal%tol)// &
                ' = target/100 (solver '// &
                'error below the discretisation error)')
        end if
        out%tol = s%settings%normal%tol
        do attempt = 1, max_enlargements + 1
            call solve_levels(s, tang, ops, out, stat, errmsg)
            if (stat /= 0) return
            out%touches_boundary = contact_touches_boundary(out%result%normal%pn, out%model == 'strip2d' .or. &
                s%kind == 'cylinder' .or. (s%kind == 'quadratic' .and. s%ry == 0)) .and. .not. s%periodic
            if (.not. out%touches_boundary) exit
            if (.not. out%grid_auto .or. attempt == max_enlargements + 1) then
                if (out%grid_auto) then
                    call append_line(out%warnings, 'contact still reaches the boundary of the potential contact area after '// &
                        'the largest automatic enlargement: the solution is clipped')
                else
                    call append_line(out%warnings, 'CONTACT REACHES THE BOUNDARY of the potential contact area (first or '// &
                        'last row or column): the area given in &grid is too small and the solution is clipped; '// &
                        'enlarge xmin..ymax or use &grid auto = .true.')
                end if
                exit
            end if
            ! enlarge ×1.5 about the centre, same element size; an enlarged grid beyond the
            ! grid bound or the memory leaves the clipped solution, with a warning
            nx_old = s%nx; ny_old = s%ny
            nx_new = even_up(s%nx*enlarge_factor); ny_new = s%ny
            if (s%ny > 1 .and. .not. (s%kind == 'cylinder')) ny_new = even_up(s%ny*enlarge_factor)
            if (int(nx_new, i8)*ny_new > max_grid_elements) then
                call append_line(out%warnings, 'contact reaches the boundary of the automatic potential contact area, '// &
                    'and its enlargement to '//fmt_int(nx_new)//' x '//fmt_int(ny_new)//' elements would exceed 4096^2: '// &
                    'the solution is clipped')
                exit
            end if
            call case_fits_memory(s, nx_new, ny_new, fits, what, stat, errmsg)
            if (stat /= 0) return
            if (.not. fits) then
                call append_line(out%warnings, 'contact reaches the boundary of the automatic potential contact area, '// &
                    'and its enlargement to '//fmt_int(nx_new)//' x '//fmt_int(ny_new)//' elements does not fit in '// &
                    'memory ('//what//'): the solution is clipped')
                exit
            end if
            out%enlargements = out%enlargements + 1
            cx = 0.5_dp*(s%xmin + s%xmax); hx = 0.5_dp*(s%xmax - s%xmin)
            cy = 0.5_dp*(s%ymin + s%ymax); hy = 0.5_dp*(s%ymax - s%ymin)
            s%nx = nx_new
            s%xmin = cx - hx*s%nx/nx_old; s%xmax = cx + hx*s%nx/nx_old
            if (ny_new /= ny_old) then
                s%ny = ny_new
                s%ymin = cy - hy*s%ny/ny_old; s%ymax = cy + hy*s%ny/ny_old
            end if
            call append_line(out%reductions, 'automatic area enlarged x1.5: contact reached its boundary')
            deallocate (out%levels); allocate (out%levels(0))
        end do
    end subroutine solve_case_auto

    !> The model and the grid of a case after its reductions (the stages needed; a line
    !! contact as an n × 1 strip; a cylinder's full model) and, for `&grid auto`, the
    !! automatic potential contact area (s%nx, s%ny, xmin … ymax set): the first grid the
    !! case is solved on, before any enlargement or refinement.  Notes go to
    !! out%reductions; out%material must be combined.
    subroutine plan_grid(s, out, tang, line, stat, errmsg)
        type(fc_case), intent(inout) :: s
        type(fc_auto_outcome), intent(inout) :: out
        logical, intent(out) :: tang, line   !! tangential stage needed; reduced to a strip
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        ! ---- which stages are needed
        tang = is_tangential(s)
        if (tang .and. s%reduce) then
            if (s%tangential%mu == 0) then
                tang = .false.
                call append_line(out%reductions, 'mu = 0: frictionless, no tangential solve (tractions are zero)')
            else if (out%material%k == 0 .and. no_tangential_loading(s%tangential) .and. &
                     .not. is_rolling_sequence(s)) then
                tang = .false.
                call append_line(out%reductions, 'no tangential loading (zero shifts or forces, K = 0): no tangential solve '// &
                    '(tractions are zero)')
            end if
        end if
        if (tang .and. out%material%k == 0 .and. s%reduce) call append_line(out%reductions, 'quasi-identical '// &
            'materials (K = 0): one normal and one tangential solve, no Panagiotopoulos loop')
        out%tangential = tang
        ! ---- line contact → 2D strip
        line = is_line_contact(s) .and. s%kind /= 'strip2d' .and. .not. s%periodic
        if (line .and. s%reduce) then
            if (s%kind == 'quadratic' .and. s%ry > 0) then
                ! elongated ellipse: only a strip when the y curvature is negligible over the area
                if (s%grid_auto) then
                    call append_line(out%reductions, 'not reduced: ry >= 1e3 rx but the automatic area would be sized by the '// &
                        'elliptic Hertz solution (give a fixed grid or ry = 0 for a line contact)')
                    line = .false.
                else if (max(s%ymin**2, s%ymax**2)/(2*s%ry) > 0.01_dp*line_indentation(s, out%material)) then
                    call append_line(out%reductions, 'not reduced: ry >= 1e3 rx but the y curvature over the grid exceeds '// &
                        '1 % of the indentation')
                    line = .false.
                end if
            end if
            if (line) then
                if (s%kind == 'quadratic' .and. s%grid_auto) then
                    stat = FC_ERR_UNSUPPORTED
                    errmsg = "ry = 0 (line contact) with an automatic area: the length is unknown; use "// &
                        "kind = 'cylinder' with a length, or give the area's ymin, ymax"
                    return
                end if
                out%model = 'strip2d'
                s%ny = 1
                call append_line(out%reductions, 'line contact ('//trim(s%kind)//'): 2D strip model, n x 1 grid, one element '// &
                    'over the length '//fmt_real(s%ymax - s%ymin)//' mm (plane strain)')
            end if
        end if
        if (s%kind == 'strip2d') out%model = 'strip2d'
        if (s%kind == 'cylinder' .and. .not. (line .and. s%reduce) .and. s%grid_auto) then
            ! full model of a cylinder: elements about as long as wide, at most 512 along y
            s%ny = -1
        end if
        ! ---- potential contact area
        out%grid_auto = s%grid_auto
        out%target = s%target
        if (out%grid_auto) call auto_area(s, out%material, stat, errmsg)
    end subroutine plan_grid

    !> The first grid `s` is solved on ([[plan_grid]]: after the model reductions, the
    !! automatic area sized), without solving or building anything: nx = ny = 0 when no
    !! grid is solved (the analytic Hertz answer, FASTSIM).  For the drivers' `--check`.
    subroutine case_grid(s_in, nx, ny, stat, errmsg)
        type(fc_case), intent(in) :: s_in
        integer, intent(out) :: nx, ny
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_case) :: s
        type(fc_auto_outcome) :: out
        logical :: tang, line
        nx = 0; ny = 0
        s = s_in
        allocate (out%reductions(0), out%warnings(0), out%levels(0))
        out%material = s%material
        call combine_material(out%material, stat, errmsg)
        if (stat /= 0) return
        if (s%rolling%fastsim .or. s%analytic) return
        if (fastsim_meets_target(s, out)) return
        call plan_grid(s, out, tang, line, stat, errmsg)
        if (stat /= 0) return
        nx = s%nx; ny = s%ny
    end subroutine case_grid

    !> Solve on the grid of `s` or, with a target, on a sequence of grids refined by two.
    subroutine solve_levels(s, tang, ops, out, stat, errmsg)
        type(fc_case), intent(inout) :: s
        logical, intent(in) :: tang
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_auto_outcome), intent(inout) :: out
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_case) :: sl
        real(dp), allocatable :: p0(:, :), px0(:, :), py0(:, :)
        integer :: k, nlev, fx, fy
        real(dp) :: est, ratio, noise
        logical :: monotone, probe
        character(len=64) :: qname
        character(len=:), allocatable :: what
        character(len=msg_len) :: merr
        integer :: mstat
        logical :: fits
        nlev = 1
        if (s%target > 0) nlev = s%max_levels
        call refinement_factors(s, s%nx, s%ny, fx, fy)
        out%total_seconds = 0
        out%estimate = -1; out%target_met = .false.; out%reliable = .true.
        out%sufficient = 0; out%sufficient_bound = -1
        noise = 10*s%settings%normal%tol
        sl = s
        ! probe grid: with a target, start one level below the given grid (a quarter of its
        ! cost) so that the given grid itself can be the answer when it already meets the target
        ! (coarsened by the factors that refine the given grid)
        probe = s%target > 0 .and. (fx == 1 .or. (mod(s%nx, 2) == 0 .and. s%nx >= 16)) .and. &
            (fy == 1 .or. (mod(s%ny, 2) == 0 .and. s%ny >= 16))
        if (probe) then
            sl%nx = s%nx/fx; sl%ny = s%ny/fy
            nlev = nlev + 1
        end if
        do k = 1, nlev
            if (k > 1) then
                if (.not. (probe .and. k == 2)) call refinement_factors(s, sl%nx, sl%ny, fx, fy)
                sl%nx = fx*sl%nx; sl%ny = fy*sl%ny
                call prolong_copy(out%result%normal%pn, fx, fy, p0)
                if (out%result%tangential_run) then
                    call prolong_copy(out%result%tangential%px, fx, fy, px0)
                    call prolong_copy(out%result%tangential%py, fx, fy, py0)
                end if
            end if
            if (int(sl%nx, i8)*sl%ny > max_grid_elements) then
                call append_line(out%warnings, 'accuracy target: the next grid would exceed 4096^2 elements; stopped')
                exit
            end if
            ! a refinement the process has no memory for ends the sequence with the grids
            ! solved so far (the first grid is the caller's to check, or solve_case_auto's)
            if (k > 1) then
                call case_fits_memory(s, sl%nx, sl%ny, fits, what, mstat, merr)
                if (.not. fits) then
                    call append_line(out%warnings, 'accuracy target: the next grid ('//fmt_int(sl%nx)//' x '// &
                        fmt_int(sl%ny)//') does not fit in memory ('//what//'); stopped')
                    exit
                end if
            end if
            call solve_one(sl, tang, ops, out, p0, px0, py0, stat, errmsg)
            if (stat /= 0) return
            if (out%result%normal%status /= FC_CONVERGED) exit
            if (out%result%tangential_run) then
                if (out%result%tangential%status /= FC_CONVERGED) exit
            end if
            if (s%target > 0 .and. k >= 2) then
                call level_estimate(out%levels, s, tang, noise, est, ratio, monotone, qname)
                out%levels(k)%estimate = est; out%levels(k)%ratio = ratio; out%levels(k)%monotone = monotone
                out%estimate = est; out%reliable = monotone; out%quantities = qname
                out%target_met = est <= s%target
                if (out%target_met) exit
            end if
        end do
        if (s%target > 0) then
            if (size(out%levels) < 2) out%target_met = .false.
            if (out%target_met) call certify_coarsest(out%levels, s, tang, out%estimate, s%target, out%sufficient, &
                out%sufficient_bound)
            if (size(out%levels) == 2 .and. out%target_met) call append_line(out%warnings, 'accuracy target: estimate from '// &
                'two grids: 2|d|, assuming only that the error at least halves per level (a third grid would '// &
                'measure the rate)')
            if (.not. out%reliable) call append_line(out%warnings, 'accuracy target: convergence is non-monotone (successive '// &
                'differences change sign or grow); the estimate is the conservative bound max(|d_k|, |d_k-1|) without '// &
                'extrapolation')
            if (.not. out%target_met) call append_line(out%warnings, 'accuracy target '//fmt_real(s%target)// &
                ' NOT MET: estimated error '//fmt_real(out%estimate)//' after '//fmt_int(size(out%levels))//' grids')
        end if
    end subroutine solve_levels

    !> Solve the case on the grid of `sl` (warm start from p0, px0, py0 when allocated);
    !! append a level record; keep the solution in `out`.
    subroutine solve_one(sl, tang, ops, out, p0, px0, py0, stat, errmsg)
        type(fc_case), intent(in) :: sl
        logical, intent(in) :: tang
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_auto_outcome), intent(inout) :: out
        real(dp), allocatable, intent(in) :: p0(:, :), px0(:, :), py0(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_material) :: mat
        type(fc_level) :: lev
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: settings
        type(fc_contact_result) :: res
        integer(i8) :: t0, t1, rate
        logical :: use_fmg, decoupled
        call system_clock(t0, rate)
        call case_setup(sl, mat, out%grid, out%h0, stat, errmsg)
        if (stat /= 0) return
        use_fmg = sl%settings%normal%solver == 'fmg'
        settings = sl%settings
        load%normal = sl%normal
        if (tang) then
            load%problem = sl%problem        ! shift or steady rolling
            load%tangential = sl%tangential
            load%mu_kinetic = sl%rolling%mu_kinetic
        end if
        ! warm starts from the previous grid: the normal stage (not FMG, which starts from its
        ! own nested iteration) of normal and decoupled problems, the tangential stage of
        ! decoupled ones; coupled problems and model = 'full' solve each grid from zero
        decoupled = tang .and. mat%k == 0 .and. (sl%reduce .or. use_fmg)
        if (allocated(p0) .and. .not. use_fmg .and. (decoupled .or. .not. tang)) load%normal%p_start = p0
        if (decoupled .and. allocated(px0) .and. allocated(py0)) then
            load%px_start = px0; load%py_start = py0
        end if
        if (tang .and. is_rolling_sequence(sl)) then
            call rolling_sequence(sl%rolling, ops, out%grid, mat, out%h0, load, settings, res, out%sequence, stat, errmsg)
        else if (use_fmg) then
            call fmg_solve()
        else
            call solve_contact(ops, out%grid, mat, out%h0, load, settings, res, stat, errmsg)
        end if
        if (stat /= 0) return
        call move_result(res, out%result)
        call system_clock(t1)
        lev%nx = out%grid%nx; lev%ny = out%grid%ny
        lev%fn = out%result%normal%fn; lev%approach = out%result%normal%approach
        lev%pmax = out%result%normal%pmax; lev%ncon = out%result%normal%ncon
        lev%iterations = out%result%normal%iterations
        lev%status = status_name(out%result%normal%status)
        if (out%result%tangential_run) then
            lev%fx = out%result%tangential%fx; lev%fy = out%result%tangential%fy
            lev%xi = out%result%tangential%xi; lev%eta = out%result%tangential%eta
            lev%iterations = lev%iterations + out%result%tangential%iterations
            lev%status = status_name(max(out%result%normal%status, out%result%tangential%status))
        end if
        lev%seconds = real(t1 - t0, dp)/rate
        out%total_seconds = out%total_seconds + lev%seconds
        out%levels = [out%levels, lev]
    contains
        !> The solve with the normal stage by FMG; the geometry gives h0 on the coarse levels
        !! (tables: averaged).
        subroutine fmg_solve()
            type(fc_quadratic_surface) :: quad
            type(fc_punch_rough_surface) :: punch
            type(fc_wavy_surface) :: wavy
            select case (sl%kind)
            case ('quadratic', 'strip2d', 'cylinder')
                quad%rx = sl%rx; quad%ry = 0
                if (sl%kind == 'quadratic') quad%ry = sl%ry
                call solve_contact(ops, out%grid, mat, out%h0, load, settings, res, stat, errmsg, surface=quad)
            case ('punch_rough')
                punch%diameter = sl%diameter; punch%rough = sl%rough
                call solve_contact(ops, out%grid, mat, out%h0, load, settings, res, stat, errmsg, surface=punch)
            case ('wavy')
                wavy%amplitude = sl%amplitude; wavy%wavelength_x = sl%wavelength_x; wavy%wavelength_y = sl%wavelength_y
                call solve_contact(ops, out%grid, mat, out%h0, load, settings, res, stat, errmsg, surface=wavy)
            case default
                call solve_contact(ops, out%grid, mat, out%h0, load, settings, res, stat, errmsg)
            end select
        end subroutine fmg_solve
    end subroutine solve_one

    !> to = from, moving the arrays.
    subroutine move_result(from, to)
        type(fc_contact_result), intent(inout) :: from
        type(fc_contact_result), intent(out) :: to
        to%tangential_run = from%tangential_run; to%rounds = from%rounds; to%status = from%status
        to%setup_seconds_normal = from%setup_seconds_normal
        to%setup_seconds_tangential = from%setup_seconds_tangential
        to%work_units = from%work_units; to%convergence_factor = from%convergence_factor
        call move_normal(from%normal, to%normal)
        call move_tangential(from%tangential, to%tangential)
    end subroutine move_result

    subroutine move_normal(from, to)
        type(fc_normal_result), intent(inout) :: from
        type(fc_normal_result), intent(out) :: to
        call move_alloc(from%pn, to%pn); call move_alloc(from%gap, to%gap); call move_alloc(from%history, to%history)
        to%approach = from%approach; to%fn = from%fn; to%pmax = from%pmax; to%ncon = from%ncon
        to%status = from%status; to%iterations = from%iterations; to%outer_iterations = from%outer_iterations
        to%matvecs = from%matvecs; to%precond_applications = from%precond_applications
        to%residual = from%residual; to%cpu_seconds = from%cpu_seconds; to%message = from%message
        to%touches_boundary = from%touches_boundary
    end subroutine move_normal

    subroutine move_tangential(from, to)
        type(fc_tangential_result), intent(inout) :: from
        type(fc_tangential_result), intent(out) :: to
        call move_alloc(from%px, to%px); call move_alloc(from%py, to%py)
        call move_alloc(from%sx, to%sx); call move_alloc(from%sy, to%sy)
        call move_alloc(from%ux, to%ux); call move_alloc(from%uy, to%uy)
        call move_alloc(from%state, to%state); call move_alloc(from%history, to%history)
        to%xi = from%xi; to%eta = from%eta; to%phi = from%phi; to%fx = from%fx; to%fy = from%fy; to%mz = from%mz
        to%dissipation = from%dissipation
        to%ncon = from%ncon; to%nadh = from%nadh; to%nslip = from%nslip; to%status = from%status
        to%iterations = from%iterations; to%outer_iterations = from%outer_iterations; to%matvecs = from%matvecs
        to%residual = from%residual; to%cpu_seconds = from%cpu_seconds; to%message = from%message
    end subroutine move_tangential

    !> Refinement factors (1 or 2 per direction) of the accuracy target for an nx×ny grid on
    !! the area of `s`: two, except in a direction whose elements are already at most half
    !! as long as in the other, which waits until the other has caught up — the elements
    !! tend to squares, and the error, set by the longer side, halves its h each level.  A
    !! strip (ny = 1) refines in x only.  (Both directions doubled a 16×4097 grid, whose
    !! elements were 256 times longer in x than in y, to 64×16388: 1 GB for nothing.)
    pure subroutine refinement_factors(s, nx, ny, fx, fy)
        type(fc_case), intent(in) :: s
        integer, intent(in) :: nx, ny
        integer, intent(out) :: fx, fy
        real(dp) :: dx, dy
        fx = 2; fy = 2
        if (ny == 1) then
            fy = 1
            return
        end if
        dx = (s%xmax - s%xmin)/nx; dy = (s%ymax - s%ymin)/ny
        if (dx <= 0.5_dp*dy) fx = 1
        if (dy <= 0.5_dp*dx) fy = 1
    end subroutine refinement_factors

    !> Copy interpolation of a coarse field to a grid refined by fx × fy (each coarse
    !! element's value on its children).
    pure subroutine prolong_copy(pc, fx, fy, pf)
        real(dp), intent(in) :: pc(:, :)
        integer, intent(in) :: fx, fy
        real(dp), allocatable, intent(out) :: pf(:, :)
        integer :: i, j
        allocate (pf(fx*size(pc, 1), fy*size(pc, 2)))
        do j = 1, size(pf, 2)
            do i = 1, size(pf, 1)
                pf(i, j) = pc((i - 1)/fx + 1, (j - 1)/fy + 1)
            end do
        end do
    end subroutine prolong_copy

    !> With model = 'auto' and a target: steady rolling of a quadratic geometry with prescribed
    !! creepages (K = 0, no sequence) is answered by FASTSIM when its error bound
    !! [[fastsim_error_bound]]·μFn / max(|F|, 0.1·μFn) meets the target (|F| of FASTSIM);
    !! otherwise a reduction note gives the bound and the full theory is solved.
    logical function fastsim_meets_target(s, out) result(used)
        type(fc_case), intent(in) :: s
        type(fc_auto_outcome), intent(inout) :: out
        type(fc_auto_outcome) :: fs
        real(dp) :: bound, mufn
        integer :: stat
        character(len=256) :: msg
        used = .false.
        if (.not. (s%problem == FC_PROBLEM_ROLLING .and. s%reduce .and. s%target > 0)) return
        if (s%kind /= 'quadratic' .or. .not. (s%rx > 0 .and. s%ry > 0) .or. s%tangential%force_prescribed) return
        if (is_rolling_sequence(s) .or. out%material%k /= 0) return
        fs%material = out%material
        allocate (fs%reductions(0), fs%warnings(0), fs%levels(0))
        call fastsim_answer(s, fs, stat, msg)
        if (stat /= 0) return
        mufn = s%tangential%mu*fs%hertz%fn
        bound = fastsim_error_bound(fs%hertz%a/fs%hertz%b, s%tangential%xi, s%tangential%eta, s%tangential%phi)
        if (bound < huge(1.0_dp)) bound = bound*mufn/max(hypot(fs%fx, fs%fy), 0.1_dp*mufn)
        if (bound <= s%target) then
            call append_line(fs%reductions, 'accuracy target '//fmt_real(s%target)//': FASTSIM meets it (error bound '// &
                fmt_real(bound)//' from its measured error against the full theory)')
            out = fs
            out%target = s%target; out%estimate = bound; out%target_met = .true.
            used = .true.
        else if (bound < huge(1.0_dp)) then
            call append_line(out%reductions, 'FASTSIM not used: error bound '//fmt_real(bound)//' > target '//fmt_real(s%target))
        end if
    end function fastsim_meets_target

    ! ---------------------------------------------------------------- helpers ----

    !> Zero spin and zero shifts (or forces, when prescribed).
    pure logical function no_tangential_loading(t)
        type(fc_tangential_loading), intent(in) :: t
        if (t%force_prescribed) then
            no_tangential_loading = t%phi == 0 .and. t%fx == 0 .and. t%fy == 0
        else
            no_tangential_loading = t%phi == 0 .and. t%xi == 0 .and. t%eta == 0
        end if
    end function no_tangential_loading

    !> Influence coefficients of the case: a file (`ic_file`, body 2 from `ic_file2` or the
    !! half-space) replaces the half-space kernels in `ops`; without one the half-space
    !! kernels are (re)used.  Modes that need coefficients on other grids are refused.  The
    !! files are read once: while later cases name the same files and materials, `ops`
    !! keeps the set and the operators built on it (a file rewritten during a run is not
    !! read again).
    subroutine use_ic_file(s, ops, stat, errmsg)
        type(fc_case), intent(in) :: s
        type(fc_contact_operators), intent(inout) :: ops
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_ic_set) :: ic
        character(len=:), allocatable :: source
        stat = 0; errmsg = ''
        if (len_trim(s%ic_file) == 0) then
            if (allocated(ops%ic%a)) call clear_influence_coefficients(ops)
            return
        end if
        stat = FC_ERR_IC_FILE
        if (s%grid_auto) then
            errmsg = "ic_file with an automatic potential area: the area chooses its own element size, the file "// &
                "holds coefficients for one; give a fixed grid (nx, ny, xmin, xmax, ymin, ymax) matching the file"
            return
        end if
        if (s%target > 0) then
            errmsg = "ic_file with an accuracy target: the target refines the grid, the file holds coefficients "// &
                "for one grid; remove the target"
            return
        end if
        ! the files and the materials they are checked against, exactly
        source = 'files '//trim(s%ic_file)//' | '//trim(s%ic_file2)//'; materials '// &
            real_key([s%material%g1, s%material%nu1, s%material%g2, s%material%nu2])
        if (allocated(ops%ic%a) .and. allocated(ops%ic_source)) then
            if (ops%ic_source == source) then
                stat = 0; return
            end if
        end if
        call load_influence_source(s%ic_file, s%ic_file2, s%material%g1, s%material%nu1, s%material%g2, &
            s%material%nu2, ic, stat, errmsg)
        if (stat /= 0) then
            stat = FC_ERR_IC_FILE; return
        end if
        call take_influence_coefficients(ops, ic, stat, errmsg, source)
        if (stat /= 0) stat = FC_ERR_IC_FILE
    end subroutine use_ic_file

    !> The values, each written exactly (hexadecimal bits), as one key.
    pure function real_key(v) result(key)
        real(dp), intent(in) :: v(:)
        character(len=:), allocatable :: key
        character(len=17) :: one
        integer :: i
        key = ''
        do i = 1, size(v)
            write (one, '(z16.16,a)') v(i), ' '
            key = key//one
        end do
    end function real_key

end module fc_auto
