!> A contact case in library terms: the two bodies, the potential contact area, the
!! geometry of the undeformed distance, the loading, the solver settings and what the
!! automatic layer ([[fc_auto]]) may decide.  The namelist input builds it
!! ([[fc_input_scene]]); a program can fill it directly and call [[solve_case_auto]].
!!
!! [[case_setup]] turns it into the material, grid and undeformed distance of one solve.
module fc_scene
    use fc_kinds, only: dp, i8, msg_len
    use fc_memory, only: serial_bytes_per_element, case_memory_bytes, memory_fits, format_bytes, ic_set_bytes, &
        ic_case_memory_bytes, memory_base_bytes
    use fc_threads, only: fc_default_threads
    use fc_errors, only: FC_ERR_ALLOC, FC_ERR_IO, FC_ERR_GEOMETRY, FC_ERR_NO_CONTACT, FC_ERR_IC_FILE
    use fc_strings, only: fmt_int, fmt_real
    use fc_geometry, only: fc_grid, fc_rough_params, make_grid, quadratic_gap, punch_rough_gap, wavy_gap, &
        read_gap_table, h_no_contact
    use fc_influence, only: fc_material, combine_material, fc_ic_set, check_ic_set_grid
    use fc_tangcg_types, only: fc_tangential_loading
    use fc_contact_types, only: fc_normal_loading, fc_contact_settings, FC_PROBLEM_NORMAL, FC_PROBLEM_TANGENTIAL, &
        FC_PROBLEM_ROLLING
    use fc_rolling_types, only: fc_rolling_case
    implicit none
    private

    integer, parameter, public :: path_len = 256  !! longest file name

    !> One contact case.
    type, public :: fc_case
        integer :: problem = FC_PROBLEM_NORMAL       !! FC_PROBLEM_NORMAL or FC_PROBLEM_TANGENTIAL
        logical :: analytic = .false.                !! answer by the analytic Hertz solution, no grid
        type(fc_material) :: material                !! g1, g2, nu1, nu2 (combined when solved)
        character(len=path_len) :: ic_file = ''      !! influence coefficients of body 1 (or combined) from a file
        character(len=path_len) :: ic_file2 = ''     !! body 2's coefficients from a file ('': half-space g2, nu2)
        !> the coefficient files' headers ([[ic_source_header]]: body 1's cell size, the
        !! largest offsets of the two; no coefficients), read with the namelist input; dx = 0
        !! when not read: the memory estimate then assumes offsets nx, ny (the least a file
        !! must reach) and nothing is checked before the load
        type(fc_ic_set) :: ic_header
        ! ---- potential contact area
        integer :: nx = 0, ny = 0                    !! elements per direction
        real(dp) :: xmin = 0, xmax = 0, ymin = 0, ymax = 0  !! outer edges [mm]
        logical :: grid_auto = .false.               !! size the area from the Hertz estimate
        real(dp) :: margin = 0.25_dp                 !! automatic area: margin around the estimate (fraction)
        integer :: n_across = 0                      !! automatic area: elements across the contact (0: default)
        logical :: periodic = .false.                !! the area is one cell of a periodic surface ([[fc_periodic]])
        ! ---- geometry of the undeformed distance
        character(len=16) :: kind = ''               !! quadratic, cylinder, strip2d, punch_rough, wavy, table
        real(dp) :: rx = 0, ry = 0                   !! radii of the quadratic profile [mm] (ry = 0: flat in y)
        real(dp) :: length = 0                       !! cylinder length along y [mm]
        real(dp) :: diameter = 0                     !! punch diameter [mm]
        type(fc_rough_params) :: rough               !! roughness of the punch
        real(dp) :: amplitude = 0                    !! wavy amplitude [mm]
        real(dp) :: wavelength_x = 0, wavelength_y = 0  !! wavy wavelengths [mm] (0: flat)
        character(len=path_len) :: file = ''         !! table of h0 (nx·ny values, x fastest)
        ! ---- loading
        type(fc_normal_loading) :: normal            !! approach or total force
        type(fc_tangential_loading) :: tangential    !! friction, shifts or forces, spin
        logical :: tangential_given = .false.        !! analytic answer: shifts or forces were given
        type(fc_rolling_case) :: rolling             !! the rolling part: kinetic friction, sweep or transient steps
        ! ---- solvers and the automatic layer
        type(fc_contact_settings) :: settings        !! both stages (and FMG)
        real(dp) :: target = 0                       !! accuracy target (relative error; 0: none)
        logical :: target_pmax = .false.             !! the target also covers pmax
        integer :: max_levels = 5                    !! most grids visited by the accuracy target
        logical :: reduce = .true.                   !! model reductions allowed
        integer :: threads = 0                       !! threads of the solve (0: OMP_NUM_THREADS, else 1)
        character(len=path_len) :: fft_wisdom = ''   !! FFTW wisdom file ('': FFTW_ESTIMATE plans only)
        !> processes sharing the available memory (the ranks of an MPI batch on one node):
        !! each may use its share ([[case_fits_memory]])
        integer :: memory_share = 1
    end type fc_case

    public :: case_setup, is_line_contact, is_tangential, is_rolling_sequence, case_memory, case_fits_memory
    public :: check_case_ic_header

contains

    !> Whether the case is a rolling sequence (creep-force sweep or transient rolling).
    pure logical function is_rolling_sequence(c)
        type(fc_case), intent(in) :: c
        is_rolling_sequence = c%rolling%transient .or. (c%problem == FC_PROBLEM_ROLLING .and. len_trim(c%rolling%sweep) > 0)
    end function is_rolling_sequence

    !> Estimated peak memory of a solve of `c` on an nx × ny grid [bytes] (fc_memory: bytes per
    !! element of its kind of problem, more with two or more threads, with dissimilar
    !! materials and with FMG's 'fft-rsm' hierarchy; coefficients from a file add their sets,
    !! [[ic_case_memory_bytes]]), with the kind as the messages name it ('normal',
    !! 'tangential', 'transient', 'rolling', qualified by '(dissimilar materials)', '(FMG
    !! fft-rsm)' or '(coefficients from a file)'), the bytes per element (all of the estimate
    !! above the process's base, per element) and the threads it assumed.
    subroutine case_memory(c, nx, ny, need, kind, bpe, threads, set_bytes)
        type(fc_case), intent(in) :: c
        integer, intent(in) :: nx, ny
        integer(i8), intent(out) :: need
        character(len=:), allocatable, intent(out) :: kind
        real(dp), intent(out) :: bpe
        integer, intent(out) :: threads
        integer(i8), intent(out), optional :: set_bytes   !! one coefficient set (0 without a file)
        integer(i8) :: set
        type(fc_material) :: m
        integer :: st
        integer(i8) :: n
        character(len=msg_len) :: msg
        logical :: coupled, fmg_rsm
        threads = c%threads
        if (threads <= 0) threads = fc_default_threads()
        kind = 'tangential'
        if (c%problem == FC_PROBLEM_NORMAL) kind = 'normal'
        if (c%problem == FC_PROBLEM_ROLLING) kind = 'rolling'
        if (c%rolling%transient) kind = 'transient'
        m = c%material
        call combine_material(m, st, msg)
        ! the coupling blocks are built when K ≠ 0, with or without a coefficient file
        coupled = kind /= 'normal' .and. st == 0 .and. m%k /= 0
        fmg_rsm = c%settings%normal%solver == 'fmg' .and. c%settings%fmg%smoother == 'fft-rsm'
        bpe = serial_bytes_per_element(kind, threads, coupled, fmg_rsm)
        if (coupled) kind = kind//' (dissimilar materials)'
        if (fmg_rsm) kind = kind//' (FMG fft-rsm)'
        n = int(nx, i8)*ny
        set = 0
        if (len_trim(c%ic_file) > 0) then
            set = ic_set_bytes(max(c%ic_header%mx, nx), max(c%ic_header%my, ny))
            need = ic_case_memory_bytes(n, bpe, set)
            kind = kind//' (coefficients from a file)'
            bpe = real(need - memory_base_bytes, dp)/real(n, dp)
        else
            need = case_memory_bytes(n, bpe)
        end if
        if (present(set_bytes)) set_bytes = set
    end subroutine case_memory

    !> Whether a solve of `c` on an nx × ny grid fits in the memory this process may use: the
    !! estimate of [[case_memory]] against the available memory (fc_memory) divided by
    !! `c%memory_share`, plus what the process holds already (not when the environment
    !! variable gives the size).  Unknown available memory fits.  When it does not fit,
    !! `what` says so in library terms ('a KIND case on T thread(s) needs about …, more than
    !! the … this process may use (SOURCE)'); the callers add the grid and the remedy.
    !! stat = FC_ERR_VALUE (errmsg) for an invalid `FASTCONTACT_AVAILABLE_MEMORY`.
    subroutine case_fits_memory(c, nx, ny, fits, what, stat, errmsg)
        type(fc_case), intent(in) :: c
        integer, intent(in) :: nx, ny
        logical, intent(out) :: fits
        character(len=:), allocatable, intent(out) :: what
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer(i8) :: need, limit, set
        character(len=:), allocatable :: source, kind, detail
        character(len=msg_len) :: m
        real(dp) :: bpe
        integer :: threads
        what = ''
        call case_memory(c, nx, ny, need, kind, bpe, threads, set)
        call memory_fits(need, c%memory_share, 0_i8, .true., fits, limit, source, stat, m)
        errmsg = m
        if (fits) return
        if (set > 0) then
            detail = 'coefficient sets of '//format_bytes(set)//': two while the files are loaded, one beside the solve'
        else
            detail = fmt_int(nint(bpe))//' B per element'
        end if
        what = 'a '//kind//' case on '//fmt_int(threads)//' thread(s) needs about '//format_bytes(need)//' ('// &
            detail//'), more than the '//format_bytes(limit)//' this process may use ('//source//')'
    end subroutine case_fits_memory

    !> Whether the coefficient files of `c`, by their headers ([[fc_case]]%ic_header), serve
    !! its grid: the same cells and offsets reaching nx−1, ny−1 ([[check_ic_set_grid]]), so
    !! that a wrong file is reported before anything is loaded or estimated.  Nothing is
    !! checked without a file, without a header read, or with an automatic area.
    !! stat = FC_ERR_IC_FILE with the sizes in `errmsg` when they do not.
    subroutine check_case_ic_header(c, stat, errmsg)
        type(fc_case), intent(in) :: c
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_grid) :: g
        stat = 0; errmsg = ''
        if (len_trim(c%ic_file) == 0 .or. .not. c%ic_header%dx > 0 .or. c%grid_auto) return
        call make_grid(g, c%nx, c%ny, c%xmin, c%xmax, c%ymin, c%ymax, stat, errmsg)
        if (stat /= 0) then
            stat = 0; errmsg = ''; return   ! the grid's own error is reported by the solve
        end if
        call check_ic_set_grid(c%ic_header, g, stat, errmsg)
        if (stat /= 0) stat = FC_ERR_IC_FILE
    end subroutine check_case_ic_header

    !> Whether the case solves the tangential problem too.
    pure logical function is_tangential(c)
        type(fc_case), intent(in) :: c
        is_tangential = c%problem /= FC_PROBLEM_NORMAL    ! shift or rolling
    end function is_tangential

    !> Whether the scene is a line contact: kind 'cylinder' or 'strip2d', or a quadratic
    !! profile that is flat in y (ry = 0) or whose radii differ by a factor ≥ 1e3.
    pure logical function is_line_contact(c)
        type(fc_case), intent(in) :: c
        is_line_contact = .false.
        select case (c%kind)
        case ('cylinder', 'strip2d')
            is_line_contact = .true.
        case ('quadratic')
            if (c%rx > 0 .and. c%ry == 0) is_line_contact = .true.
            if (c%rx > 0 .and. c%ry > 0) is_line_contact = c%ry >= 1.0e3_dp*c%rx
        end select
    end function is_line_contact

    !> Material (combined), grid and undeformed distance h0 [mm] (without approach) of `c`,
    !! and a check that contact is possible.  Errors: FC_ERR_ALLOC (grid too large for
    !! memory), FC_ERR_IO (table file), FC_ERR_GEOMETRY (no element can touch),
    !! FC_ERR_NO_CONTACT (the prescribed approach brings no element into contact), else the
    !! codes of combine_material and make_grid.
    subroutine case_setup(c, material, grid, h0, stat, errmsg)
        type(fc_case), intent(in) :: c
        type(fc_material), intent(out) :: material
        type(fc_grid), intent(out) :: grid
        real(dp), allocatable, intent(out) :: h0(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=msg_len) :: msg
        real(dp) :: hmin
        material = c%material
        call combine_material(material, stat, errmsg)
        if (stat /= 0) return
        call make_grid(grid, c%nx, c%ny, c%xmin, c%xmax, c%ymin, c%ymax, stat, errmsg)
        if (stat /= 0) return
        allocate (h0(grid%nx, grid%ny), stat=stat)
        if (stat /= 0) then
            stat = FC_ERR_ALLOC
            errmsg = 'nx = '//fmt_int(c%nx)//', ny = '//fmt_int(c%ny)//': cannot allocate the grid'; return
        end if
        select case (c%kind)
        case ('quadratic')
            h0 = quadratic_gap(grid, c%rx, c%ry)
        case ('strip2d', 'cylinder')
            h0 = quadratic_gap(grid, c%rx, 0.0_dp)
        case ('punch_rough')
            call punch_rough_gap(grid, c%diameter, c%rough, h0)
        case ('wavy')
            h0 = wavy_gap(grid, c%amplitude, c%wavelength_x, c%wavelength_y)
        case ('table')
            call read_gap_table(c%file, grid, h0, stat, msg)
            if (stat /= 0) then
                stat = FC_ERR_IO
                errmsg = "file = '"//trim(c%file)//"': "//trim(msg); return
            end if
        end select
        if (.not. any(h0 < 0.5_dp*h_no_contact)) then
            stat = FC_ERR_GEOMETRY
            errmsg = 'kind = '''//trim(c%kind)//''': no element can come into contact '// &
                '(e.g. punch diameter smaller than an element)'
            return
        end if
        if (.not. c%normal%force_prescribed) then
            hmin = minval(h0, mask=h0 < 0.5_dp*h_no_contact)
            if (.not. (hmin - c%normal%approach <= 0)) then
                stat = FC_ERR_NO_CONTACT
                errmsg = 'approach = '//fmt_real(c%normal%approach)//': no contact possible (h0 - approach > 0 '// &
                    'everywhere; min h0 = '//fmt_real(hmin)//')'
                return
            end if
        end if
        stat = 0; errmsg = ''
    end subroutine case_setup

end module fc_scene
