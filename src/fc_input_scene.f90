!> From a validated case record ([[fc_case_input]]) to the library's [[fc_case]]: typed
!! solver settings from the solver names and the cycle text, the loading, the potential
!! area with the values other keys imply ([[effective_record]]); and the report notes on
!! keys the case does not use.
module fc_input_scene
    use fc_kinds, only: dp, msg_len
    use fc_fmg_levels, only: fmg_cycle_from_name
    use fc_contact_types, only: FC_PROBLEM_NORMAL, FC_PROBLEM_TANGENTIAL, FC_PROBLEM_ROLLING
    use fc_scene, only: fc_case
    use fc_icfile_load, only: ic_source_header
    use fc_influence, only: fc_ic_set
    use fc_input, only: fc_case_input, is_given, grid_is_auto, is_tangential, strip_model_index
    use fc_input_validate, only: effective_record
    use fc_strings, only: fmt_real
    implicit none
    private

    public :: build_case, case_notes

contains

    !> The library case of a validated record.
    function build_case(record) result(c)
        type(fc_case_input), intent(in) :: record
        type(fc_case) :: c
        type(fc_case_input) :: s
        integer :: stat
        character(len=msg_len) :: msg
        s = effective_record(record)
        c%problem = merge(FC_PROBLEM_TANGENTIAL, FC_PROBLEM_NORMAL, is_tangential(s))
        c%analytic = s%problem == 'hertz'
        c%material%g1 = s%g1; c%material%g2 = s%g2; c%material%nu1 = s%nu1; c%material%nu2 = s%nu2
        c%ic_file = s%ic_file; c%ic_file2 = s%ic_file2
        ! the files' extents for the memory estimate; a header that cannot be read leaves
        ! them unknown, and loading the file reports why
        if (len_trim(c%ic_file) > 0) then
            call ic_source_header(c%ic_file, c%ic_file2, c%ic_header, stat, msg)
            if (stat /= 0) c%ic_header = fc_ic_set()
        end if
        ! potential contact area
        c%nx = s%nx; c%ny = s%ny
        c%xmin = s%xmin; c%xmax = s%xmax; c%ymin = s%ymin; c%ymax = s%ymax
        c%grid_auto = grid_is_auto(s)
        c%margin = s%margin; c%n_across = s%n_across; c%periodic = s%periodic
        ! geometry
        c%kind = s%kind; c%rx = s%rx; c%ry = s%ry; c%length = s%length
        c%diameter = s%diameter; c%rough = s%rough
        c%amplitude = s%amplitude; c%wavelength_x = s%wavelength_x; c%wavelength_y = s%wavelength_y
        c%file = s%file
        ! loading
        c%normal%force_prescribed = s%force_prescribed
        c%normal%approach = s%approach; c%normal%fn = s%fn
        c%tangential%mu = s%mu; c%tangential%phi = s%phi
        c%tangential%force_prescribed = s%tforce_prescribed
        if (s%tforce_prescribed) then
            c%tangential%fx = s%fx; c%tangential%fy = s%fy
        else
            c%tangential%xi = s%xi; c%tangential%eta = s%eta
        end if
        c%tangential_given = is_given(s, 'tangential', 'fx') .or. is_given(s, 'tangential', 'fy') .or. &
            is_given(s, 'tangential', 'xi') .or. is_given(s, 'tangential', 'eta')
        ! solvers: tol and maxit apply to both stages and to FMG
        associate (ns => c%settings%normal, ts => c%settings%tangential, fmg => c%settings%fmg)
            ns%solver = trim(s%normal_solver)
            ns%tol = s%tol; ns%maxit = s%maxit; ns%inner_maxit = s%inner_maxit
            ns%precondition = s%precondition; ns%deflation = s%deflation
            ts%solver = trim(s%tangential)
            ts%tol = s%tol; ts%maxit = s%maxit; ts%inner_k = s%inner_k
            ts%precondition = s%precondition_tangential
            ns%prec_form = trim(s%fft_preconditioner); ts%prec_form = trim(s%fft_preconditioner)
            call fmg_cycle_from_name(s%cycle, fmg%nu1, fmg%nu2, stat, msg)
            fmg%omega = s%omega; fmg%beta = s%beta; fmg%smoother = trim(s%smoother)
            fmg%tol = s%tol; fmg%maxit = s%maxit
        end associate
        c%target = s%target; c%target_pmax = s%target_pmax; c%max_levels = s%max_levels
        c%reduce = s%model == 'auto'
        ! rolling: steady ('rolling', possibly swept) or transient steps of the shift pipeline
        if (s%problem == 'rolling') c%problem = FC_PROBLEM_ROLLING
        c%rolling%transient = s%problem == 'transient_rolling'
        c%rolling%mu_kinetic = s%mu_kinetic
        c%rolling%dq = s%dq; c%rolling%nsteps = s%nsteps
        if (s%problem == 'rolling') c%rolling%sweep = s%sweep
        c%rolling%sweep_from = s%sweep_from; c%rolling%sweep_to = s%sweep_to; c%rolling%sweep_n = s%sweep_n
        c%rolling%fastsim = s%model == 'fastsim'
        c%settings%rolling%solver = trim(s%rolling)
        c%settings%rolling%tol = s%tol; c%settings%rolling%maxit = s%maxit
        c%settings%rolling%prec_form = trim(s%fft_preconditioner)
        c%settings%rolling%start = trim(s%rolling_start)
        c%threads = s%threads
        c%fft_wisdom = s%fft_wisdom
    end function build_case

    !> Report notes on keys a validated case gives but does not use.
    function case_notes(s) result(notes)
        type(fc_case_input), intent(in) :: s
        character(len=:), allocatable :: notes
        notes = ''
        if (strip_model_index(s) > 0) then
            notes = 'model problem MP'//s%problem(9:9)//' (thesis 3.2.5) fixes the material, the potential '// &
                'area [-4,4]x[-50,50] mm and the loading; &material, &grid xmin..ymax, &normal, &tangential are not used. '
            if (s%strip == 'fft-rsm' .and. is_given(s, 'solver', 'cycle')) &
                notes = notes//"&solver cycle: not used by the one-grid solver strip = 'fft-rsm'. "
            return
        end if
        if (s%normal_solver /= 'fmg' .and. (is_given(s, 'solver', 'cycle') .or. is_given(s, 'solver', 'omega') .or. &
            is_given(s, 'solver', 'beta') .or. is_given(s, 'solver', 'smoother'))) &
            notes = notes//"&solver cycle, omega, beta, smoother: used only by normal = 'fmg' (not by '"// &
            trim(s%normal_solver)//"'). "
        ! FMG's Gauss–Seidel sweeps are O(n²) (dense influence coefficients): say so where it costs
        if (s%normal_solver == 'fmg' .and. s%smoother /= 'fft-rsm' .and. .not. grid_is_auto(s)) then
            if (real(s%nx, dp)*s%ny > 128.0_dp**2) notes = notes//"normal = 'fmg' with smoother = '"// &
                trim(s%smoother)//"' costs O(n^2) per sweep: a prescribed-force Hertz case took 12.6 s on 256^2 "// &
                "and 340 s on 512^2, where BCCG took 0.08 s and 0.25 s (doc/multigrid.md); smoother = 'fft-rsm' "// &
                "is O(n log n). "
        end if
        if (s%periodic) notes = notes//'periodic half-space: the grid is one cell of a surface repeated in x and y; '// &
            'mean pressure fn/area = '//fmt_real(s%fn/((s%xmax - s%xmin)*(s%ymax - s%ymin)))//' N/mm2. '
        ! a sequence writes every point to its table; the summary holds the last solve
        if (s%problem == 'transient_rolling') notes = notes//'transient rolling: forces, counts and stage times '// &
            'are those of the last step; '//trim(s%name)//'_steps.csv has every step. '
        if (s%problem == 'rolling' .and. len_trim(s%sweep) > 0) notes = notes//'creep-force sweep over '// &
            trim(s%sweep)//': forces, counts and stage times are those of the last point; '//trim(s%name)// &
            '_creep.csv has every point. '
    end function case_notes

end module fc_input_scene
