!> Namelist input of the batch driver (SPEC §5): splitting a case file into cases,
!! pre-parsing and reading the namelist groups, inheritance from case to case, validation,
!! and building the grid, material and undeformed distance of one case.
!!
!! A case starts at each `&case` group; the groups up to the next `&case` belong to it
!! (groups before the first `&case` belong to the first case; a file without `&case` is
!! one case).  Each case chunk is pre-parsed here — groups `&name ... /`, keys before `=`,
!! case-insensitive, text in quotes and after `!` ignored — so that unknown groups and keys
!! are reported by name, and each group is then read with a namelist READ from an internal
!! unit holding that group only.
!!
!! Groups, keys and defaults (see also doc/namelist.md):
!!
!! * `&case name, title, problem` — name: file stem of the outputs, not inherited, default
!!   `case<N>`; title: ''; problem: 'normal' (default), 'normal+tangential' or 'tangential'
!!   (the same pipeline: the normal problem is solved as the prerequisite of the tangential one).
!! * `&material g1, g2, nu1, nu2, ic_file` — g1, g2 required (≥ 1e29: rigid);
!!   nu1 = nu2 = 0.28; ic_file: not yet supported.
!! * `&grid nx, ny, xmin, xmax, ymin, ymax` — all required (outer edges of the potential
!!   contact area); strip2d: ny defaults to 1 and must be 1.  nx·ny ≤ 4096².
!! * `&geometry kind, ...` — kind required: 'quadratic' (rx > 0, ry ≥ 0; 0 = flat),
!!   'strip2d' (rx > 0, ny = 1), 'punch_rough' (diameter > 0, sigma = 0.1, gamma = 0.8,
!!   m_modes = 12, n_modes = 10, seed = 2015), 'wavy' (amplitude > 0, wavelength_x = 0,
!!   wavelength_y = 0; 0 = flat), 'table' (file: nx·ny values, x fastest).
!! * `&normal approach | fn` — exactly one required; giving one clears the inherited other.
!! * `&tangential mu, xi, eta, phi | mu, fx, fy, phi` — mu required for tangential problems
!!   (≥ 0; > 0 with forces); xi = eta = phi = 0; giving fx or fy switches to prescribed
!!   forces and clears inherited xi, eta (and vice versa); both kinds in one group: error.
!!   Ignored (noted) for problem = 'normal'.
!! * `&solver normal, tangential, tol, maxit, inner_maxit, inner_k, precondition,
!!   precondition_tangential, deflation` (normal = 'bccg', tangential = 'tangcg', tol = 1e-5,
!!   maxit = 1000, inner_maxit = 0, inner_k = 3, precondition = .true. for both stages,
!!   precondition_tangential overrides it for TangCG, deflation: library default); tol and
!!   maxit apply to both stages.  normal = 'fmg' (FMG + active set, thesis §2.4) uses
!!   cycle = 'V(1,1)' ('V(n1,n2)'), omega = 0.8 ∈ (0, 2), beta = 0.003 ≥ 0 and
!!   smoother = 'gs' ('gs', 'jacobi', 'fft-rsm'); strip = 'mg-fft-rsm' ('mg-fft-sd', 'fft-rsm')
!!   selects the solver of the strip model problems (cycle applies to the multigrid ones).
!! * `&case problem = 'strip_mp1' | 'strip_mp2' | 'strip_mp3'` — the 2D no-slip model problems
!!   MP1–MP3 of thesis §3.2.5 (A^xx p = u on an nx×1 grid of [−4,4]×[−50,50] mm) with
!!   `&geometry kind = 'strip2d'` and `&grid nx` (power of 2, ≥ 4); the model problem fixes
!!   material, area and loading; tol defaults to 1e-8 (thesis) unless given.
!! * `&case problem = 'rolling' | 'transient_rolling'` — body 1 rolls in +x (doc/rolling.md):
!!   `&tangential xi, eta` are creepages [-] and phi the spin creepage [1/mm] (or fx, fy
!!   prescribed, steady only); mu_kinetic (≤ mu, default mu) in slip; `&solver rolling =
!!   'gmres'` ('march', 'steadygs': references).  'rolling' may sweep one loading value:
!!   `&tangential sweep = 'xi' | 'eta' | 'phi' | 'fx' | 'fy', sweep_from, sweep_to,
!!   sweep_n = 20` (2 … 1000 points, warm-started, one CSV row each in NAME_creep.csv).
!!   'transient_rolling': dq (travelled distance per step, default dx) and nsteps (default:
!!   four times the area length travelled, ≤ 100000); per step the shift is creepage·dq; one
!!   CSV row per step in NAME_steps.csv.
!! * `&output dir, table` — dir = 'out' (the command line `--out` wins), table = .true.
!!
!! Every value persists from case to case except `name`.  A case with an input error does
!! not change the inherited state: the next case inherits from the last good case.
module fc_input
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
    use fc_kinds, only: dp, i8, msg_len
    use fc_geometry, only: fc_grid, fc_rough_params, make_grid, quadratic_gap, punch_rough_gap, wavy_gap, &
        read_gap_table, h_no_contact
    use fc_influence, only: fc_material, combine_material, rigid_modulus
    use fc_norm, only: fc_normal_settings
    use fc_fmg, only: fc_fmg_settings, fmg_cycle_from_name
    use fc_tangcg, only: fc_tangential_settings, fc_tangential_loading
    use fc_rolling, only: fc_rolling_settings
    implicit none
    private

    integer, parameter :: key_len = 32    !! longest key name kept
    integer, parameter :: val_len = 512   !! longest value text kept
    integer, parameter :: path_len = 256  !! file and directory names

    !> Largest grid accepted (nx·ny).
    integer(i8), parameter, public :: max_grid_elements = 4096_i8*4096_i8

    !> One `key = value` of a group as written in the file.
    type, public :: fc_nml_item
        character(len=key_len) :: key = ''     !! lower-case key (subscripts removed)
        character(len=val_len) :: value = ''   !! value text, trimmed
    end type fc_nml_item

    !> One namelist group as written in the file (comments removed, lines joined).
    type, public :: fc_nml_group
        character(len=key_len) :: name = ''          !! lower-case group name
        integer :: line = 0                          !! line of the `&name`
        character(len=:), allocatable :: text        !! `&name ... /` ready for a namelist READ
        type(fc_nml_item), allocatable :: items(:)   !! keys in order of appearance
    end type fc_nml_group

    !> The groups of one case.
    type, public :: fc_case_chunk
        integer :: line = 0                          !! line of its `&case` (or first group)
        type(fc_nml_group), allocatable :: groups(:)
    end type fc_case_chunk

    !> All input values of a case (inherited state); defaults as in the module header.
    type, public :: fc_case_input
        integer :: index = 0                       !! position of the case in the file
        integer :: line = 0                        !! line where the case starts
        ! &case
        character(len=64) :: name = ''             !! output file stem (not inherited)
        character(len=128) :: title = ''           !! free text for the report
        character(len=32) :: problem = 'normal'    !! 'normal', 'tangential', 'normal+tangential'
        ! &material
        real(dp) :: g1 = 0, g2 = 0                 !! shear moduli [N/mm²] (≥ 1e29: rigid)
        real(dp) :: nu1 = 0.28_dp, nu2 = 0.28_dp   !! Poisson ratios
        character(len=path_len) :: ic_file = ''    !! influence coefficients from file (not yet)
        ! &grid
        integer :: nx = 0, ny = 0                  !! elements per direction
        real(dp) :: xmin = 0, xmax = 0, ymin = 0, ymax = 0  !! outer edges [mm]
        logical :: grid_auto = .false.             !! &grid auto as given (see [[grid_is_auto]])
        real(dp) :: margin = 0.25_dp               !! auto grid: margin around the Hertz estimate (fraction)
        integer :: n_across = 0                    !! auto grid: elements across the contact (0: 32, or 8 with a target)
        ! &geometry
        character(len=16) :: kind = ''             !! quadratic, punch_rough, wavy, strip2d, table
        real(dp) :: rx = 0, ry = 0                 !! radii of the quadratic profile [mm]
        real(dp) :: diameter = 0                   !! punch diameter [mm]
        type(fc_rough_params) :: rough             !! sigma, gamma, m_modes, n_modes, seed
        real(dp) :: amplitude = 0                  !! wavy amplitude [mm]
        real(dp) :: wavelength_x = 0, wavelength_y = 0  !! wavy wavelengths [mm] (0: flat)
        character(len=path_len) :: file = ''       !! table file of h0
        real(dp) :: length = 0                     !! cylinder length along y [mm]
        ! &normal
        logical :: force_prescribed = .false.      !! fn given (else approach)
        real(dp) :: approach = 0                   !! prescribed approach δ [mm]
        real(dp) :: fn = 0                         !! prescribed normal force [N]
        ! &tangential
        real(dp) :: mu = 0                         !! coefficient of friction
        real(dp) :: xi = 0, eta = 0                !! prescribed rigid shift [mm] (tforce_prescribed false)
        real(dp) :: phi = 0                        !! spin shift [rad]
        real(dp) :: fx = 0, fy = 0                 !! prescribed tangential forces [N] (tforce_prescribed)
        logical :: tforce_prescribed = .false.     !! fx or fy given (else xi, eta)
        real(dp) :: mu_kinetic = -1                !! rolling: kinetic friction (< 0: = mu)
        real(dp) :: dq = 0                         !! transient rolling: distance per step [mm] (0: dx)
        integer :: nsteps = 0                      !! transient rolling: steps (0: area length travelled 4 times)
        character(len=8) :: sweep = ''             !! rolling: swept value 'xi', 'eta', 'phi', 'fx', 'fy' ('' none)
        real(dp) :: sweep_from = 0, sweep_to = 0   !! rolling: range of the swept value
        integer :: sweep_n = 20                    !! rolling: points of the sweep
        character(len=16) :: rolling = 'gmres'     !! &solver rolling as given (checked, then copied)
        type(fc_rolling_settings) :: rsettings     !! steady rolling solver settings
        ! &solver
        type(fc_normal_settings) :: settings       !! normal solver settings
        character(len=32) :: normal_solver = 'bccg'  !! &solver normal as given (checked, then copied)
        type(fc_tangential_settings) :: tsettings  !! tangential solver settings (tol, maxit from &solver)
        character(len=32) :: tangential = 'tangcg' !! &solver tangential as given (checked, then copied)
        integer :: inner_k = 3                     !! TangCG inner iterations K
        logical :: precondition_tangential = .true.  !! TangCG diagonal preconditioner
        character(len=16) :: cycle = 'V(1,1)'      !! multigrid cycle 'V(n1,n2)' (fmg and strip MG)
        real(dp) :: omega = 0.8_dp                 !! fmg: damping of the Gauss–Seidel smoother, (0, 2)
        real(dp) :: beta = 0.003_dp                !! fmg: initial-area parameter of eq. (2.17), ≥ 0
        character(len=8) :: smoother = 'gs'        !! fmg smoother: 'gs', 'jacobi', 'fft-rsm'
        character(len=16) :: strip = 'mg-fft-rsm'  !! strip model problems: 'mg-fft-rsm', 'mg-fft-sd', 'fft-rsm'
        type(fc_fmg_settings) :: fmg               !! FMG settings (filled by validate_case)
        real(dp) :: target = 0                     !! accuracy target (relative error of the forces; 0: off)
        logical :: target_pmax = .false.           !! the target also applies to pmax
        integer :: max_levels = 5                  !! most grids visited by the accuracy target
        character(len=16) :: model = 'auto'        !! 'auto': apply model reductions; 'full': never
        ! &output
        character(len=path_len) :: dir = 'out'     !! output directory
        logical :: table = .true.                  !! write the CSV table
        ! bookkeeping
        character(len=2*key_len + 1), allocatable :: given(:)  !! 'group:key' given so far
        character(len=:), allocatable :: notes     !! remarks for the report (ignored keys)
    end type fc_case_input

    character(len=*), parameter :: known_groups = 'case material grid geometry normal tangential solver output'

    public :: read_case_file, split_cases, apply_case, validate_case, setup_case, is_given, fmt_real
    public :: is_tangential, tangential_loading, namelist_keys, grid_is_auto, is_line_contact, strip_model_index

contains

    ! ---------------------------------------------------------------- file splitting ----

    !> Read `filename` and split it into cases.  stat ≠ 0 for an unreadable file or a
    !! syntax error (unterminated group, text that is not `key = value`).
    subroutine read_case_file(filename, cases, stat, errmsg)
        character(len=*), intent(in) :: filename
        type(fc_case_chunk), allocatable, intent(out) :: cases(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=:), allocatable :: text
        integer, allocatable :: lines(:)
        integer :: unit, ios, lineno, n
        character(len=4096) :: buf
        character(len=256) :: iomsg
        logical :: in_quote
        character :: quote
        stat = 0; errmsg = ''
        open (newunit=unit, file=filename, status='old', action='read', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = 1; errmsg = "cannot open case file '"//trim(filename)//"': "//trim(iomsg); return
        end if
        text = ''
        allocate (lines(0))
        lineno = 0; in_quote = .false.; quote = ' '
        do
            read (unit, '(a)', iostat=ios) buf
            if (ios /= 0) exit
            lineno = lineno + 1
            call strip_comment(buf, in_quote, quote)
            n = len_trim(buf)
            text = text//buf(1:n)//' '
            lines = [lines, spread(lineno, 1, n + 1)]
        end do
        close (unit)
        call split_cases(text, lines, cases, stat, errmsg)
    end subroutine read_case_file

    !> Blank the part of `line` after a `!` that is outside quotes; quote state carries over.
    subroutine strip_comment(line, in_quote, quote)
        character(len=*), intent(inout) :: line
        logical, intent(inout) :: in_quote
        character, intent(inout) :: quote
        integer :: i
        do i = 1, len_trim(line)
            if (line(i:i) == char(9)) line(i:i) = ' '
            if (in_quote) then
                if (line(i:i) == quote) in_quote = .false.
            else if (line(i:i) == '"' .or. line(i:i) == "'") then
                in_quote = .true.; quote = line(i:i)
            else if (line(i:i) == '!') then
                line(i:) = ''
                return
            end if
        end do
    end subroutine strip_comment

    !> Split comment-free `text` (one string, `lines(k)` = file line of character k) into
    !! groups, and the groups into cases at each `&case`.
    subroutine split_cases(text, lines, cases, stat, errmsg)
        character(len=*), intent(in) :: text
        integer, intent(in) :: lines(:)
        type(fc_case_chunk), allocatable, intent(out) :: cases(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_nml_group), allocatable :: groups(:)
        type(fc_nml_group) :: g
        integer :: i, n, start, gstart, k, ncase, j
        integer, allocatable :: starts(:)
        logical :: in_quote
        character :: quote, c
        stat = 0; errmsg = ''
        allocate (groups(0))
        n = len(text)
        i = 1
        do while (i <= n)
            c = text(i:i)
            if (c == ' ' .or. c == ',') then
                i = i + 1; cycle
            end if
            if (c /= '&' .and. c /= '$') then
                ! gfortran skips text between groups; we do the same but only up to a '&'
                i = i + 1; cycle
            end if
            gstart = i
            start = i + 1
            k = start
            do while (k <= n)
                if (.not. is_ident_char(text(k:k))) exit
                k = k + 1
            end do
            if (allocated(g%items)) deallocate (g%items)
            g%name = lower(text(start:k - 1))
            g%line = lines(min(gstart, size(lines)))
            if (len_trim(g%name) == 0) then
                stat = 1; write (errmsg, '(a,i0)') "'&' not followed by a group name at line ", g%line; return
            end if
            if (g%name == 'end') then
                i = k; cycle
            end if
            ! find the closing '/' (or '&end' / '$end') outside quotes
            in_quote = .false.; quote = ' '
            j = k
            do while (j <= n)
                c = text(j:j)
                if (in_quote) then
                    if (c == quote) in_quote = .false.
                else if (c == '"' .or. c == "'") then
                    in_quote = .true.; quote = c
                else if (c == '/') then
                    exit
                else if (c == '&' .or. c == '$') then
                    if (lower(text(j + 1:min(n, j + 3))) == 'end') exit
                    stat = 1
                    write (errmsg, '(a,i0,a,i0)') 'group &'//trim(g%name)//' (line ', g%line, &
                        ") is not terminated by '/' before the next group at line ", lines(j)
                    return
                end if
                j = j + 1
            end do
            if (j > n) then
                stat = 1
                write (errmsg, '(a,i0,a)') 'group &'//trim(g%name)//' (line ', g%line, ") is not terminated by '/'"
                return
            end if
            g%text = '&'//trim(g%name)//' '//text(k:j - 1)//' /'
            call parse_items(g, text(k:j - 1), stat, errmsg)
            if (stat /= 0) return
            groups = [groups, g]
            if (text(j:j) == '/') then
                i = j + 1
            else
                i = j + 4
            end if
        end do
        ! cases: one per &case; groups before the first &case belong to the first case
        if (size(groups) == 0) then
            stat = 1; errmsg = 'no namelist groups found in the case file'; return
        end if
        ncase = max(1, count(groups%name == 'case'))
        allocate (cases(ncase), starts(ncase + 1))
        k = 0
        do i = 1, size(groups)
            if (groups(i)%name == 'case') then
                k = k + 1; starts(k) = i
            end if
        end do
        starts(1) = 1
        starts(ncase + 1) = size(groups) + 1
        do k = 1, ncase
            cases(k)%groups = groups(starts(k):starts(k + 1) - 1)
            cases(k)%line = groups(starts(k))%line
        end do
    end subroutine split_cases

    !> Find the `key = value` items in the body of a group.
    subroutine parse_items(g, body, stat, errmsg)
        type(fc_nml_group), intent(inout) :: g
        character(len=*), intent(in) :: body
        integer, intent(inout) :: stat
        character(len=*), intent(inout) :: errmsg
        integer :: i, n, k, kstart, depth, nitem
        integer, allocatable :: kpos(:), epos(:)
        logical :: in_quote
        character :: quote, c
        n = len(body)
        allocate (kpos(0), epos(0))
        in_quote = .false.; quote = ' '
        do i = 1, n
            c = body(i:i)
            if (in_quote) then
                if (c == quote) in_quote = .false.
                cycle
            end if
            if (c == '"' .or. c == "'") then
                in_quote = .true.; quote = c; cycle
            end if
            if (c /= '=') cycle
            ! walk back: blanks, optional (subscript), identifier
            k = i - 1
            do while (k >= 1)
                if (body(k:k) /= ' ') exit
                k = k - 1
            end do
            if (k >= 1) then
                if (body(k:k) == ')') then
                    depth = 0
                    do while (k >= 1)
                        if (body(k:k) == ')') depth = depth + 1
                        if (body(k:k) == '(') depth = depth - 1
                        k = k - 1
                        if (depth == 0) exit
                    end do
                    do while (k >= 1)
                        if (body(k:k) /= ' ') exit
                        k = k - 1
                    end do
                end if
            end if
            kstart = k
            do while (kstart >= 1)
                if (.not. (is_ident_char(body(kstart:kstart)) .or. body(kstart:kstart) == '%')) exit
                kstart = kstart - 1
            end do
            kstart = kstart + 1
            if (kstart > k) then
                stat = 1
                write (errmsg, '(a,i0,a)') 'group &'//trim(g%name)//' (line ', g%line, &
                    "): '=' without a key name in '"//trim(shorten(body))//"'"
                return
            end if
            kpos = [kpos, kstart]
            epos = [epos, i]
        end do
        nitem = size(kpos)
        allocate (g%items(nitem))
        if (nitem == 0) then
            if (len_trim(body) > 0) then
                stat = 1
                write (errmsg, '(a,i0,a)') 'group &'//trim(g%name)//' (line ', g%line, &
                    "): expected 'key = value', got '"//trim(shorten(adjustl(body)))//"'"
            end if
            return
        end if
        if (len_trim(body(1:kpos(1) - 1)) > 0) then
            stat = 1
            write (errmsg, '(a,i0,a)') 'group &'//trim(g%name)//' (line ', g%line, &
                "): expected 'key = value', got '"//trim(shorten(adjustl(body(1:kpos(1) - 1))))//"'"
            return
        end if
        do k = 1, nitem
            g%items(k)%key = key_of(body(kpos(k):epos(k) - 1))
            if (k < nitem) then
                g%items(k)%value = trim_value(body(epos(k) + 1:kpos(k + 1) - 1))
            else
                g%items(k)%value = trim_value(body(epos(k) + 1:))
            end if
        end do
    contains
        function key_of(s) result(key)
            character(len=*), intent(in) :: s
            character(len=key_len) :: key
            integer :: p
            p = index(s, '(')
            if (p > 0) then
                key = lower(adjustl(s(1:p - 1)))
            else
                key = lower(adjustl(s))
            end if
        end function key_of
        function trim_value(s) result(v)
            character(len=*), intent(in) :: s
            character(len=val_len) :: v
            integer :: m
            v = adjustl(s)
            m = len_trim(v)
            do while (m > 0)
                if (v(m:m) /= ',' .and. v(m:m) /= ' ') exit
                v(m:m) = ' '
                m = m - 1
            end do
        end function trim_value
    end subroutine parse_items

    ! ---------------------------------------------------------------- applying a case ----

    !> Apply the groups of `chunk` on top of the inherited `state`.  On error `state` is
    !! unchanged, `errmsg` names group, key and value, and `name` still returns the case
    !! name when the `&case` group could be read (for removing stale outputs).
    subroutine apply_case(chunk, icase, state, name, stat, errmsg)
        type(fc_case_chunk), intent(in) :: chunk
        integer, intent(in) :: icase              !! position of the case in the file
        type(fc_case_input), intent(inout) :: state
        character(len=*), intent(out) :: name
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_case_input) :: s
        integer :: ig, k, ios
        character(len=256) :: iomsg
        character(len=msg_len) :: where
        logical :: has_fn, has_approach, has_shift, has_force, tangential_group
        stat = 0; errmsg = ''
        tangential_group = .false.
        s = state
        if (.not. allocated(s%given)) allocate (s%given(0))
        s%index = icase
        s%line = chunk%line
        s%name = ''
        s%notes = ''
        write (name, '(a,i0)') 'case', icase
        do ig = 1, size(chunk%groups)
            associate (g => chunk%groups(ig))
                write (where, '(a,i0,a)') '&'//trim(g%name)//' (line ', g%line, ')'
                if (index(' '//known_groups//' ', ' '//trim(g%name)//' ') == 0) then
                    stat = 1
                    if (size(g%items) > 0) then
                        errmsg = 'unknown group '//trim(where)//" with key '"//trim(g%items(1)%key)//"' = "// &
                            trim(g%items(1)%value)//'; known groups: '//known_groups
                    else
                        errmsg = 'unknown group '//trim(where)//'; known groups: '//known_groups
                    end if
                    return
                end if
                do k = 1, size(g%items)
                    if (.not. known_key(g%name, g%items(k)%key)) then
                        stat = 1
                        errmsg = trim(where)//": unknown key '"//trim(g%items(k)%key)//"' (value "// &
                            trim(g%items(k)%value)//'); known keys: '//keys_of(g%name)
                        return
                    end if
                end do
                if (g%name == 'normal') then
                    has_fn = any(g%items%key == 'fn')
                    has_approach = any(g%items%key == 'approach')
                    if (has_fn .and. has_approach) then
                        stat = 1
                        errmsg = trim(where)//': give either approach or fn, not both (approach = '// &
                            trim(item_value(g, 'approach'))//', fn = '//trim(item_value(g, 'fn'))//')'
                        return
                    end if
                end if
                if (g%name == 'tangential') then
                    has_shift = any(g%items%key == 'xi') .or. any(g%items%key == 'eta')
                    has_force = any(g%items%key == 'fx') .or. any(g%items%key == 'fy')
                    if (has_shift .and. has_force) then
                        stat = 1
                        errmsg = trim(where)//': give either the shifts xi, eta or the forces fx, fy, not both ('// &
                            trim(given_list(g, ['xi ', 'eta', 'fx ', 'fy ']))//')'
                        return
                    end if
                end if
                call read_group(g%name, g%text, s, ios, iomsg)
                if (ios /= 0) then
                    stat = 1
                    call blame_item(g, s, where, iomsg, errmsg)
                    return
                end if
                do k = 1, size(g%items)
                    call mark_given(s, g%name, g%items(k)%key)
                end do
                if (g%name == 'case' .and. len_trim(s%name) > 0) name = s%name
                if (g%name == 'normal') then
                    if (any(g%items%key == 'fn')) then
                        s%force_prescribed = .true.; s%approach = 0
                        call unmark_given(s, 'normal', 'approach')
                    else if (any(g%items%key == 'approach')) then
                        s%force_prescribed = .false.; s%fn = 0
                        call unmark_given(s, 'normal', 'fn')
                    end if
                end if
                if (g%name == 'tangential') then
                    tangential_group = .true.
                    if (any(g%items%key == 'fx') .or. any(g%items%key == 'fy')) then
                        s%tforce_prescribed = .true.; s%xi = 0; s%eta = 0
                        call unmark_given(s, 'tangential', 'xi'); call unmark_given(s, 'tangential', 'eta')
                    else if (any(g%items%key == 'xi') .or. any(g%items%key == 'eta')) then
                        s%tforce_prescribed = .false.; s%fx = 0; s%fy = 0
                        call unmark_given(s, 'tangential', 'fx'); call unmark_given(s, 'tangential', 'fy')
                    end if
                end if
                if (g%name == 'solver') then
                    ! precondition sets both stages unless precondition_tangential is given too
                    if (any(g%items%key == 'precondition') .and. .not. any(g%items%key == 'precondition_tangential')) &
                        s%precondition_tangential = s%settings%precondition
                end if
            end associate
        end do
        if (tangential_group .and. .not. is_tangential(s) .and. s%problem /= 'hertz' .and. strip_model_index(s) == 0) &
            s%notes = s%notes//"&tangential ignored for problem = 'normal'. "
        if (len_trim(s%name) == 0) s%name = name
        name = s%name
        state = s
    end subroutine apply_case

    !> `key = value` of those `keys` that appear in group `g`, comma separated.
    function given_list(g, keys) result(list)
        type(fc_nml_group), intent(in) :: g
        character(len=*), intent(in) :: keys(:)
        character(len=:), allocatable :: list
        integer :: k
        list = ''
        do k = 1, size(keys)
            if (any(g%items%key == keys(k))) then
                if (len(list) > 0) list = list//', '
                list = list//trim(keys(k))//' = '//trim(item_value(g, keys(k)))
            end if
        end do
    end function given_list

    !> Whether the case solves the tangential problem too.
    pure logical function is_tangential(s)
        type(fc_case_input), intent(in) :: s
        is_tangential = s%problem == 'tangential' .or. s%problem == 'normal+tangential' .or. &
            s%problem == 'rolling' .or. s%problem == 'transient_rolling'
    end function is_tangential

    !> The tangential loading of a validated case.
    pure function tangential_loading(s) result(load)
        type(fc_case_input), intent(in) :: s
        type(fc_tangential_loading) :: load
        load%mu = s%mu; load%phi = s%phi
        load%force_prescribed = s%tforce_prescribed
        if (s%tforce_prescribed) then
            load%fx = s%fx; load%fy = s%fy
        else
            load%xi = s%xi; load%eta = s%eta
        end if
    end function tangential_loading

    !> Value text of `key` in group `g` ('' if absent).
    function item_value(g, key) result(v)
        type(fc_nml_group), intent(in) :: g
        character(len=*), intent(in) :: key
        character(len=val_len) :: v
        integer :: k
        v = ''
        do k = 1, size(g%items)
            if (g%items(k)%key == key) v = g%items(k)%value
        end do
    end function item_value

    !> After a failed READ of a group, read its items one by one to find the bad one.
    subroutine blame_item(g, s, where, iomsg, errmsg)
        type(fc_nml_group), intent(in) :: g
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(in) :: where, iomsg
        character(len=*), intent(out) :: errmsg
        type(fc_case_input) :: tmp
        integer :: k, ios
        character(len=256) :: msg
        do k = 1, size(g%items)
            tmp = s
            call read_group(g%name, '&'//trim(g%name)//' '//trim(g%items(k)%key)//' = '// &
                trim(g%items(k)%value)//' /', tmp, ios, msg)
            if (ios /= 0) then
                errmsg = trim(where)//': cannot read '//trim(g%items(k)%key)//' = '//trim(g%items(k)%value)// &
                    ' (wrong type or malformed value; gfortran: '//trim(msg)//')'
                return
            end if
        end do
        errmsg = trim(where)//': namelist read failed (gfortran: '//trim(iomsg)//')'
    end subroutine blame_item

    !> Dispatch a namelist READ of one group's text into the state.
    subroutine read_group(name, text, s, ios, iomsg)
        character(len=*), intent(in) :: name, text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        ios = 0; iomsg = ''
        select case (name)
        case ('case');       call read_case_group(text, s, ios, iomsg)
        case ('material');   call read_material_group(text, s, ios, iomsg)
        case ('grid');       call read_grid_group(text, s, ios, iomsg)
        case ('geometry');   call read_geometry_group(text, s, ios, iomsg)
        case ('normal');     call read_normal_group(text, s, ios, iomsg)
        case ('tangential'); call read_tangential_group(text, s, ios, iomsg)
        case ('solver');     call read_solver_group(text, s, ios, iomsg)
        case ('output');     call read_output_group(text, s, ios, iomsg)
        case default
            ios = 1; iomsg = 'unknown group &'//trim(name)
        end select
    end subroutine read_group

    subroutine read_case_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        character(len=64) :: name
        character(len=128) :: title
        character(len=32) :: problem
        namelist /case/ name, title, problem
        name = s%name; title = s%title; problem = s%problem
        read (text, nml=case, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%name = name; s%title = title; s%problem = lower(problem)
    end subroutine read_case_group

    subroutine read_material_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        real(dp) :: g1, g2, nu1, nu2
        character(len=path_len) :: ic_file
        namelist /material/ g1, g2, nu1, nu2, ic_file
        g1 = s%g1; g2 = s%g2; nu1 = s%nu1; nu2 = s%nu2; ic_file = s%ic_file
        read (text, nml=material, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%g1 = g1; s%g2 = g2; s%nu1 = nu1; s%nu2 = nu2; s%ic_file = ic_file
    end subroutine read_material_group

    subroutine read_grid_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        integer :: nx, ny, n_across
        real(dp) :: xmin, xmax, ymin, ymax, margin
        logical :: auto
        namelist /grid/ nx, ny, xmin, xmax, ymin, ymax, auto, margin, n_across
        nx = s%nx; ny = s%ny; xmin = s%xmin; xmax = s%xmax; ymin = s%ymin; ymax = s%ymax
        auto = s%grid_auto; margin = s%margin; n_across = s%n_across
        read (text, nml=grid, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%nx = nx; s%ny = ny; s%xmin = xmin; s%xmax = xmax; s%ymin = ymin; s%ymax = ymax
        s%grid_auto = auto; s%margin = margin; s%n_across = n_across
    end subroutine read_grid_group

    subroutine read_geometry_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        character(len=16) :: kind
        real(dp) :: rx, ry, diameter, sigma, gamma, amplitude, wavelength_x, wavelength_y, length
        integer :: m_modes, n_modes, seed
        character(len=path_len) :: file
        namelist /geometry/ kind, rx, ry, diameter, sigma, gamma, m_modes, n_modes, seed, amplitude, &
            wavelength_x, wavelength_y, file, length
        kind = s%kind; rx = s%rx; ry = s%ry; diameter = s%diameter
        sigma = s%rough%sigma; gamma = s%rough%gamma; m_modes = s%rough%m_modes; n_modes = s%rough%n_modes
        seed = s%rough%seed; amplitude = s%amplitude; wavelength_x = s%wavelength_x; wavelength_y = s%wavelength_y
        file = s%file; length = s%length
        read (text, nml=geometry, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%kind = lower(kind); s%rx = rx; s%ry = ry; s%diameter = diameter
        s%rough%sigma = sigma; s%rough%gamma = gamma; s%rough%m_modes = m_modes; s%rough%n_modes = n_modes
        s%rough%seed = seed; s%amplitude = amplitude; s%wavelength_x = wavelength_x; s%wavelength_y = wavelength_y
        s%file = file; s%length = length
    end subroutine read_geometry_group

    subroutine read_normal_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        real(dp) :: approach, fn
        namelist /normal/ approach, fn
        approach = s%approach; fn = s%fn
        read (text, nml=normal, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%approach = approach; s%fn = fn
    end subroutine read_normal_group

    subroutine read_tangential_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        real(dp) :: mu, xi, eta, phi, fx, fy, mu_kinetic, dq, sweep_from, sweep_to
        integer :: nsteps, sweep_n
        character(len=8) :: sweep
        namelist /tangential/ mu, xi, eta, phi, fx, fy, mu_kinetic, dq, nsteps, sweep, sweep_from, sweep_to, sweep_n
        mu = s%mu; xi = s%xi; eta = s%eta; phi = s%phi; fx = s%fx; fy = s%fy
        mu_kinetic = s%mu_kinetic; dq = s%dq; nsteps = s%nsteps; sweep = s%sweep; sweep_from = s%sweep_from
        sweep_to = s%sweep_to; sweep_n = s%sweep_n
        read (text, nml=tangential, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%mu = mu; s%xi = xi; s%eta = eta; s%phi = phi; s%fx = fx; s%fy = fy
        s%mu_kinetic = mu_kinetic; s%dq = dq; s%nsteps = nsteps; s%sweep = lower(sweep); s%sweep_from = sweep_from
        s%sweep_to = sweep_to; s%sweep_n = sweep_n
    end subroutine read_tangential_group

    subroutine read_solver_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        character(len=32) :: normal
        character(len=32) :: tangential
        character(len=16) :: cycle
        character(len=8) :: smoother
        character(len=16) :: strip
        real(dp) :: tol, omega, beta, target
        integer :: maxit, inner_maxit, inner_k, max_levels
        logical :: precondition, precondition_tangential, deflation, target_pmax
        character(len=16) :: model, rolling
        namelist /solver/ normal, tangential, tol, maxit, inner_maxit, precondition, precondition_tangential, &
            deflation, inner_k, cycle, omega, beta, target, target_pmax, max_levels, model, smoother, strip, rolling
        normal = s%normal_solver; tangential = s%tangential; tol = s%settings%tol; maxit = s%settings%maxit
        inner_maxit = s%settings%inner_maxit; precondition = s%settings%precondition
        precondition_tangential = s%precondition_tangential
        deflation = s%settings%deflation; inner_k = s%inner_k; cycle = s%cycle; omega = s%omega; beta = s%beta
        target = s%target; target_pmax = s%target_pmax; max_levels = s%max_levels; model = s%model
        smoother = s%smoother; strip = s%strip; rolling = s%rolling
        read (text, nml=solver, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%normal_solver = lower(normal); s%tangential = lower(tangential); s%settings%tol = tol
        s%settings%maxit = maxit; s%settings%inner_maxit = inner_maxit; s%settings%precondition = precondition
        s%precondition_tangential = precondition_tangential
        s%settings%deflation = deflation; s%inner_k = inner_k; s%cycle = cycle; s%omega = omega; s%beta = beta
        s%target = target; s%target_pmax = target_pmax; s%max_levels = max_levels; s%model = lower(model)
        s%smoother = lower(smoother); s%strip = lower(strip); s%rolling = lower(rolling)
    end subroutine read_solver_group

    subroutine read_output_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        character(len=path_len) :: dir
        logical :: table
        namelist /output/ dir, table
        dir = s%dir; table = s%table
        read (text, nml=output, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%dir = dir; s%table = table
    end subroutine read_output_group

    !> Keys of a group, blank separated.
    function keys_of(group) result(keys)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: keys
        select case (group)
        case ('case');       keys = 'name title problem'
        case ('material');   keys = 'g1 g2 nu1 nu2 ic_file'
        case ('grid');       keys = 'nx ny xmin xmax ymin ymax auto margin n_across'
        case ('geometry')
            keys = 'kind rx ry diameter sigma gamma m_modes n_modes seed amplitude wavelength_x wavelength_y file length'
        case ('normal');     keys = 'approach fn'
        case ('tangential'); keys = 'mu xi eta phi fx fy mu_kinetic dq nsteps sweep sweep_from sweep_to sweep_n'
        case ('solver')
            keys = 'normal tangential tol maxit inner_maxit inner_k precondition precondition_tangential deflation '// &
                'cycle omega beta smoother strip target target_pmax max_levels model rolling'
        case ('output');     keys = 'dir table'
        case default;        keys = ''
        end select
    end function keys_of

    !> Every key the reader accepts, as 'group key' (lower case), group by group in the
    !! order of `known_groups`: the list the user guide's key tables are checked against.
    function namelist_keys() result(list)
        character(len=2*key_len + 1), allocatable :: list(:)
        character(len=:), allocatable :: groups, keys
        character(len=key_len) :: group, key
        integer :: p, q
        allocate (list(0))
        groups = known_groups//' '
        do while (len_trim(groups) > 0)
            groups = adjustl(groups)
            p = index(groups, ' ')
            group = groups(1:p - 1)
            groups = groups(p + 1:)
            keys = keys_of(trim(group))//' '
            do while (len_trim(keys) > 0)
                keys = adjustl(keys)
                q = index(keys, ' ')
                key = keys(1:q - 1)
                keys = keys(q + 1:)
                list = [character(len=2*key_len + 1) :: list, trim(group)//' '//trim(key)]
            end do
        end do
    end function namelist_keys

    !> Whether the potential contact area is sized automatically: `&grid auto` as given,
    !! else automatic when no `&grid` key fixing the area (nx, ny, xmin … ymax) was given.
    logical function grid_is_auto(s)
        type(fc_case_input), intent(in) :: s
        integer :: k
        character(len=4), parameter :: keys(6) = ['nx  ', 'ny  ', 'xmin', 'xmax', 'ymin', 'ymax']
        if (is_given(s, 'grid', 'auto')) then
            grid_is_auto = s%grid_auto
            return
        end if
        grid_is_auto = .true.
        do k = 1, 6
            if (is_given(s, 'grid', trim(keys(k)))) grid_is_auto = .false.
        end do
        if (s%kind == 'cylinder' .and. .not. is_given(s, 'grid', 'nx')) grid_is_auto = .true.
    end function grid_is_auto

    !> Whether the scene is a line contact: kind 'cylinder' or 'strip2d', or a quadratic
    !! profile that is flat in y (ry = 0) or whose radii differ by a factor ≥ 1e3.
    pure logical function is_line_contact(s)
        type(fc_case_input), intent(in) :: s
        is_line_contact = .false.
        select case (s%kind)
        case ('cylinder', 'strip2d')
            is_line_contact = .true.
        case ('quadratic')
            if (s%rx > 0 .and. s%ry == 0) is_line_contact = .true.
            if (s%rx > 0 .and. s%ry > 0) is_line_contact = s%ry >= 1.0e3_dp*s%rx
        end select
    end function is_line_contact

    logical function known_key(group, key)
        character(len=*), intent(in) :: group, key
        known_key = index(' '//keys_of(group)//' ', ' '//trim(key)//' ') > 0 .and. len_trim(key) > 0
    end function known_key

    subroutine mark_given(s, group, key)
        type(fc_case_input), intent(inout) :: s
        character(len=*), intent(in) :: group, key
        character(len=2*key_len + 1), allocatable :: tmp(:)
        integer :: n
        if (is_given(s, group, key)) return
        n = 0
        if (allocated(s%given)) n = size(s%given)
        allocate (tmp(n + 1))
        if (n > 0) tmp(1:n) = s%given
        tmp(n + 1) = tag(group, key)
        call move_alloc(tmp, s%given)
    end subroutine mark_given

    subroutine unmark_given(s, group, key)
        type(fc_case_input), intent(inout) :: s
        character(len=*), intent(in) :: group, key
        character(len=2*key_len + 1), allocatable :: tmp(:)
        if (.not. allocated(s%given)) return
        allocate (tmp(count(s%given /= tag(group, key))))
        tmp = pack(s%given, s%given /= tag(group, key))
        call move_alloc(tmp, s%given)
    end subroutine unmark_given

    !> Whether `group:key` was given in this case or an earlier one.
    logical function is_given(s, group, key)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(in) :: group, key
        is_given = .false.
        if (allocated(s%given)) is_given = any(s%given == tag(group, key))
    end function is_given

    function tag(group, key) result(t)
        character(len=*), intent(in) :: group, key
        character(len=2*key_len + 1) :: t
        t = trim(group)//':'//trim(key)
    end function tag

    ! ---------------------------------------------------------------- validation ----

    !> Check the values of a case; the message names group, key and value.
    subroutine validate_case(s, stat, errmsg)
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: i
        stat = 1; errmsg = ''
        ! &case
        if (len_trim(s%name) == 0 .or. verify(trim(s%name), &
            'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.+') /= 0 .or. s%name(1:1) == '.') then
            errmsg = "&case name = '"//trim(s%name)//"': use letters, digits, '_', '-', '.', '+' only (file name)"
            return
        end if
        select case (s%problem)
        case ('normal', 'tangential', 'normal+tangential', 'hertz', 'strip_mp1', 'strip_mp2', 'strip_mp3', 'rolling', &
              'transient_rolling')
        case default
            errmsg = "&case problem = '"//trim(s%problem)//"': unknown problem; use 'normal', 'normal+tangential', "// &
                "'tangential', 'rolling', 'transient_rolling', 'hertz' or 'strip_mp1', 'strip_mp2', 'strip_mp3'"
            return
        end select
        if (strip_model_index(s) > 0) then
            call validate_strip(s, stat, errmsg)
            return
        end if
        ! &material
        if (.not. is_given(s, 'material', 'g1')) then
            errmsg = '&material g1: missing required value (shear modulus of body 1; >= 1e29 for rigid)'; return
        end if
        if (.not. is_given(s, 'material', 'g2')) then
            errmsg = '&material g2: missing required value (shear modulus of body 2; >= 1e29 for rigid)'; return
        end if
        if (.not. (s%g1 > 0)) then
            errmsg = '&material g1 = '//fmt_real(s%g1)//': must be > 0'; return
        end if
        if (.not. (s%g2 > 0)) then
            errmsg = '&material g2 = '//fmt_real(s%g2)//': must be > 0'; return
        end if
        if (.not. (s%nu1 >= 0 .and. s%nu1 < 0.5_dp)) then
            errmsg = '&material nu1 = '//fmt_real(s%nu1)//': must lie in [0, 0.5)'; return
        end if
        if (.not. (s%nu2 >= 0 .and. s%nu2 < 0.5_dp)) then
            errmsg = '&material nu2 = '//fmt_real(s%nu2)//': must lie in [0, 0.5)'; return
        end if
        if (s%g1 >= rigid_modulus .and. s%g2 >= rigid_modulus) then
            errmsg = '&material g1 = '//fmt_real(s%g1)//', g2 = '//fmt_real(s%g2)//': both bodies rigid'; return
        end if
        if (len_trim(s%ic_file) > 0) then
            errmsg = "&material ic_file = '"//trim(s%ic_file)//"': not yet supported"; return
        end if
        ! &geometry kind first: strip2d decides ny
        if (.not. is_given(s, 'geometry', 'kind')) then
            errmsg = "&geometry kind: missing required value ('quadratic', 'cylinder', 'punch_rough', 'wavy', "// &
                "'strip2d', 'table')"
            return
        end if
        select case (s%kind)
        case ('quadratic', 'cylinder', 'punch_rough', 'wavy', 'strip2d', 'table')
        case default
            errmsg = "&geometry kind = '"//trim(s%kind)//"': unknown; use 'quadratic', 'cylinder', 'punch_rough', "// &
                "'wavy', 'strip2d' or 'table'"
            return
        end select
        if (s%problem == 'hertz') then
            if (s%kind /= 'quadratic' .or. .not. (s%rx > 0 .and. s%ry > 0)) then
                errmsg = "&case problem = 'hertz': needs &geometry kind = 'quadratic' with rx > 0 and ry > 0 (got kind = '"// &
                    trim(s%kind)//"', rx = "//fmt_real(s%rx)//', ry = '//fmt_real(s%ry)//')'
                return
            end if
        end if
        if (s%kind == 'cylinder') then
            if (.not. (s%length > 0)) then
                errmsg = '&geometry length = '//fmt_real(s%length)//": must be > 0 for kind = 'cylinder' "// &
                    '(cylinder length along y [mm])'
                return
            end if
            ! the cylinder spans the potential area in y
            s%ymin = -0.5_dp*s%length; s%ymax = 0.5_dp*s%length
            if (.not. is_given(s, 'grid', 'ny')) s%ny = 1
        end if
        ! &grid auto / accuracy-target keys
        if (.not. (s%margin >= 0 .and. s%margin <= 10)) then
            errmsg = '&grid margin = '//fmt_real(s%margin)//': must lie in [0, 10] (fraction added around the '// &
                'Hertz estimate)'
            return
        end if
        if (s%n_across < 0 .or. s%n_across > 4096) then
            errmsg = '&grid n_across = '//fmt_int(s%n_across)//': must lie in [0, 4096] (0: default)'; return
        end if
        if (.not. (s%target >= 0 .and. s%target < 1)) then
            errmsg = '&solver target = '//fmt_real(s%target)//': must lie in [0, 1) (relative error; 0: off)'; return
        end if
        if (s%max_levels < 2 .or. s%max_levels > 12) then
            errmsg = '&solver max_levels = '//fmt_int(s%max_levels)//': must lie in [2, 12]'; return
        end if
        select case (s%model)
        case ('auto', 'full')
        case default
            errmsg = "&solver model = '"//trim(s%model)//"': use 'auto' (reduce the model where possible) or 'full'"
            return
        end select
        if (grid_is_auto(s) .or. s%problem == 'hertz') then
            if (.not. any(s%kind == [character(len=16) :: 'quadratic', 'cylinder', 'strip2d']) .and. &
                s%problem /= 'hertz') then
                errmsg = "&grid auto = .true.: the automatic potential contact area needs a Hertzian geometry "// &
                    "(kind = 'quadratic', 'cylinder' or 'strip2d'); give nx, ny, xmin, xmax, ymin, ymax for kind = '"// &
                    trim(s%kind)//"'"
                return
            end if
            ! placeholders, replaced by the automatic sizing before the solve
            if (s%kind == 'strip2d' .and. .not. is_given(s, 'grid', 'ymin')) then
                s%ymin = -50; s%ymax = 50
            end if
        end if
        ! &grid
        if (grid_is_auto(s) .or. s%problem == 'hertz') then
            ! skip the fixed-grid checks: sized automatically (or no grid at all)
        else if (s%kind == 'strip2d') then
            if (.not. is_given(s, 'grid', 'ny')) s%ny = 1
            if (s%ny /= 1) then
                errmsg = '&grid ny = '//fmt_int(s%ny)//": must be 1 for &geometry kind = 'strip2d'"; return
            end if
        end if
        if (.not. (grid_is_auto(s) .or. s%problem == 'hertz')) then
            do i = 1, 6
                associate (key => grid_keys(i))
                    if (.not. is_given(s, 'grid', trim(key)) .and. .not. (key == 'ny' .and. s%kind == 'strip2d') &
                        .and. .not. (s%kind == 'cylinder' .and. key /= 'nx' .and. key /= 'xmin' .and. key /= 'xmax')) then
                        errmsg = '&grid '//trim(key)//': missing required value'; return
                    end if
                end associate
            end do
            if (s%nx < 1) then
                errmsg = '&grid nx = '//fmt_int(s%nx)//': must be >= 1'; return
            end if
            if (s%ny < 1) then
                errmsg = '&grid ny = '//fmt_int(s%ny)//': must be >= 1'; return
            end if
            if (.not. (s%xmax > s%xmin)) then
                errmsg = '&grid xmax = '//fmt_real(s%xmax)//': must be > xmin = '//fmt_real(s%xmin)//' (empty grid)'; return
            end if
            if (.not. (s%ymax > s%ymin)) then
                errmsg = '&grid ymax = '//fmt_real(s%ymax)//': must be > ymin = '//fmt_real(s%ymin)//' (empty grid)'; return
            end if
            if (int(s%nx, i8)*int(s%ny, i8) > max_grid_elements) then
                errmsg = '&grid nx = '//fmt_int(s%nx)//', ny = '//fmt_int(s%ny)//': oversized grid (nx*ny > 4096*4096)'
                return
            end if
        end if
        ! &geometry parameters
        select case (s%kind)
        case ('quadratic', 'strip2d', 'cylinder')
            if (.not. is_given(s, 'geometry', 'rx')) then
                errmsg = "&geometry rx: missing required value for kind = '"//trim(s%kind)//"'"; return
            end if
            if (.not. (s%rx > 0)) then
                errmsg = '&geometry rx = '//fmt_real(s%rx)//': must be > 0'; return
            end if
            if (s%kind == 'quadratic') then
                if (.not. is_given(s, 'geometry', 'ry')) then
                    errmsg = "&geometry ry: missing required value for kind = 'quadratic' (0: flat in y)"; return
                end if
                if (.not. (s%ry >= 0)) then
                    errmsg = '&geometry ry = '//fmt_real(s%ry)//': must be >= 0 (0: flat in y)'; return
                end if
            end if
        case ('punch_rough')
            if (.not. is_given(s, 'geometry', 'diameter')) then
                errmsg = "&geometry diameter: missing required value for kind = 'punch_rough'"; return
            end if
            if (.not. (s%diameter > 0)) then
                errmsg = '&geometry diameter = '//fmt_real(s%diameter)//': must be > 0'; return
            end if
            if (.not. (s%rough%sigma >= 0)) then
                errmsg = '&geometry sigma = '//fmt_real(s%rough%sigma)//': must be >= 0'; return
            end if
            if (.not. (s%rough%gamma > 0 .and. s%rough%gamma <= 1)) then
                errmsg = '&geometry gamma = '//fmt_real(s%rough%gamma)//': must lie in (0, 1]'; return
            end if
            if (s%rough%m_modes < 1) then
                errmsg = '&geometry m_modes = '//fmt_int(s%rough%m_modes)//': must be >= 1'; return
            end if
            if (s%rough%n_modes < 1) then
                errmsg = '&geometry n_modes = '//fmt_int(s%rough%n_modes)//': must be >= 1'; return
            end if
        case ('wavy')
            if (.not. is_given(s, 'geometry', 'amplitude')) then
                errmsg = "&geometry amplitude: missing required value for kind = 'wavy'"; return
            end if
            if (.not. (s%amplitude > 0)) then
                errmsg = '&geometry amplitude = '//fmt_real(s%amplitude)//': must be > 0'; return
            end if
        case ('table')
            if (len_trim(s%file) == 0) then
                errmsg = "&geometry file: missing required value for kind = 'table'"; return
            end if
            if (.not. file_exists(s%file)) then
                errmsg = "&geometry file = '"//trim(s%file)//"': file not found"; return
            end if
        end select
        ! &normal
        if (.not. (is_given(s, 'normal', 'approach') .or. is_given(s, 'normal', 'fn'))) then
            errmsg = '&normal approach, fn: missing required value (give approach or fn)'; return
        end if
        if (s%force_prescribed) then
            if (.not. (s%fn > 0)) then
                errmsg = '&normal fn = '//fmt_real(s%fn)//': must be > 0'; return
            end if
        else
            if (.not. ieee_is_finite(s%approach)) then
                errmsg = '&normal approach = '//fmt_real(s%approach)//': not a finite number'; return
            end if
        end if
        ! &tangential: values are checked whenever given; requirements only for tangential problems
        if (.not. (s%mu >= 0 .and. ieee_is_finite(s%mu))) then
            errmsg = '&tangential mu = '//fmt_real(s%mu)//': must be >= 0 (coefficient of friction)'; return
        end if
        if (.not. all(ieee_is_finite([s%xi, s%eta, s%phi, s%fx, s%fy]))) then
            errmsg = '&tangential xi = '//fmt_real(s%xi)//', eta = '//fmt_real(s%eta)//', phi = '//fmt_real(s%phi)// &
                ', fx = '//fmt_real(s%fx)//', fy = '//fmt_real(s%fy)//': not finite numbers'
            return
        end if
        if (is_tangential(s)) then
            if (.not. is_given(s, 'tangential', 'mu')) then
                errmsg = "&tangential mu: missing required value for problem = '"//trim(s%problem)// &
                    "' (coefficient of friction, >= 0)"
                return
            end if
            if (s%tforce_prescribed) then
                if (.not. (s%mu > 0)) then
                    errmsg = '&tangential mu = '//fmt_real(s%mu)//': must be > 0 when the forces fx, fy are prescribed'
                    return
                end if
                if (s%force_prescribed) then
                    if (.not. (hypot(s%fx, s%fy) < s%mu*s%fn)) then
                        errmsg = '&tangential fx = '//fmt_real(s%fx)//', fy = '//fmt_real(s%fy)//': |(fx, fy)| = '// &
                            fmt_real(hypot(s%fx, s%fy))//' must be < mu*fn = '//fmt_real(s%mu*s%fn)// &
                            ' (mu = '//fmt_real(s%mu)//', &normal fn = '//fmt_real(s%fn)//'; full slip has no unique shift)'
                        return
                    end if
                end if
            end if
        end if
        ! &solver
        select case (s%normal_solver)
        case ('bccg', 'norm', 'fmg')
            s%settings%solver = trim(s%normal_solver)
        case default
            errmsg = "&solver normal = '"//trim(s%normal_solver)//"': unknown solver; use 'bccg', 'norm' or 'fmg'"; return
        end select
        call validate_iteration_keys(s, errmsg)
        if (len_trim(errmsg) > 0) return
        if (s%settings%inner_maxit < 0) then
            errmsg = '&solver inner_maxit = '//fmt_int(s%settings%inner_maxit)//': must be >= 0 (0: no limit)'; return
        end if
        call validate_multigrid(s, errmsg)
        if (len_trim(errmsg) > 0) return
        s%fmg%tol = s%settings%tol
        s%fmg%maxit = s%settings%maxit
        if (s%normal_solver /= 'fmg' .and. (is_given(s, 'solver', 'cycle') .or. is_given(s, 'solver', 'omega') .or. &
            is_given(s, 'solver', 'beta') .or. is_given(s, 'solver', 'smoother'))) &
            s%notes = s%notes//"&solver cycle, omega, beta, smoother: used only by normal = 'fmg' (not by '"// &
            trim(s%normal_solver)//"'). "
        select case (s%tangential)
        case ('tangcg', 'convexgs')
            s%tsettings%solver = trim(s%tangential)
        case default
            errmsg = "&solver tangential = '"//trim(s%tangential)//"': unknown solver; use 'tangcg' or 'convexgs'"; return
        end select
        if (s%inner_k < 1) then
            errmsg = '&solver inner_k = '//fmt_int(s%inner_k)//': must be >= 1 (TangCG iterations between '// &
                'subdivision checks)'
            return
        end if
        s%tsettings%inner_k = s%inner_k
        s%tsettings%tol = s%settings%tol
        s%tsettings%maxit = s%settings%maxit
        s%tsettings%precondition = s%precondition_tangential
        call validate_rolling(s, errmsg)
        if (len_trim(errmsg) > 0) return
        ! &output
        if (len_trim(s%dir) == 0) then
            errmsg = "&output dir = '': must not be empty"; return
        end if
        stat = 0
    contains
        function grid_keys(k) result(key)
            integer, intent(in) :: k
            character(len=4) :: key
            character(len=4), parameter :: keys(6) = ['nx  ', 'ny  ', 'xmin', 'xmax', 'ymin', 'ymax']
            key = keys(k)
        end function grid_keys
    end subroutine validate_case

    !> Check the multigrid keys of `&solver` (cycle, omega, beta, smoother, strip) whenever
    !! given and copy them into `s%fmg`; errmsg ≠ '' on a bad value.
    !> Rolling keys: &tangential mu_kinetic, dq, nsteps, sweep*, &solver rolling (checked
    !! whenever given; noted when the problem does not use them); fills s%rsettings.
    subroutine validate_rolling(s, errmsg)
        type(fc_case_input), intent(inout) :: s
        character(len=*), intent(out) :: errmsg
        logical :: steady, transient
        errmsg = ''
        steady = s%problem == 'rolling'
        transient = s%problem == 'transient_rolling'
        select case (s%rolling)
        case ('gmres', 'march', 'steadygs')
            s%rsettings%solver = trim(s%rolling)
        case default
            errmsg = "&solver rolling = '"//trim(s%rolling)//"': unknown solver; use 'gmres', 'march' or 'steadygs'"
            return
        end select
        s%rsettings%tol = s%settings%tol
        s%rsettings%maxit = s%settings%maxit
        if (is_given(s, 'tangential', 'mu_kinetic')) then
            if (.not. (s%mu_kinetic >= 0 .and. s%mu_kinetic <= s%mu)) then
                errmsg = '&tangential mu_kinetic = '//fmt_real(s%mu_kinetic)//': must be in [0, mu = '//fmt_real(s%mu)// &
                    '] (kinetic friction in slip)'
                return
            end if
            if (.not. steady) s%notes = s%notes//"&tangential mu_kinetic: used only by problem = 'rolling'. "
        end if
        if (is_given(s, 'tangential', 'dq')) then
            if (.not. (s%dq > 0 .and. s%dq < huge(1.0_dp))) then
                errmsg = '&tangential dq = '//fmt_real(s%dq)//': must be > 0 (travelled distance per step, mm)'; return
            end if
            if (.not. transient) s%notes = s%notes//"&tangential dq: used only by problem = 'transient_rolling'. "
        end if
        if (is_given(s, 'tangential', 'nsteps')) then
            if (s%nsteps < 0 .or. s%nsteps > 100000) then
                errmsg = '&tangential nsteps = '//fmt_int(s%nsteps)//': must be in [0, 100000] (0: automatic)'; return
            end if
            if (.not. transient) s%notes = s%notes//"&tangential nsteps: used only by problem = 'transient_rolling'. "
        end if
        if (transient .and. s%tforce_prescribed) then
            errmsg = "&tangential fx, fy: problem = 'transient_rolling' takes creepages xi, eta, phi"; return
        end if
        if ((transient .or. (steady .and. len_trim(s%sweep) > 0)) .and. s%target > 0) then
            errmsg = '&solver target = '//fmt_real(s%target)//": not available for a creep-force sweep or "// &
                "problem = 'transient_rolling' (give a fixed grid)"
            return
        end if
        if (len_trim(s%sweep) > 0) then
            select case (s%sweep)
            case ('xi', 'eta', 'phi', 'fx', 'fy')
            case default
                errmsg = "&tangential sweep = '"//trim(s%sweep)//"': use 'xi', 'eta', 'phi', 'fx' or 'fy' "// &
                    "(or '' for none)"
                return
            end select
            if (.not. steady) then
                errmsg = "&tangential sweep = '"//trim(s%sweep)//"': only for problem = 'rolling'"; return
            end if
            if (.not. (is_given(s, 'tangential', 'sweep_from') .and. is_given(s, 'tangential', 'sweep_to'))) then
                errmsg = "&tangential sweep = '"//trim(s%sweep)//"': sweep_from and sweep_to are required"; return
            end if
            if (.not. (abs(s%sweep_from) < 1e6_dp .and. abs(s%sweep_to) < 1e6_dp)) then
                errmsg = '&tangential sweep_from = '//fmt_real(s%sweep_from)//', sweep_to = '//fmt_real(s%sweep_to)// &
                    ': must be finite, |value| < 1e6'
                return
            end if
            if (s%sweep_n < 2 .or. s%sweep_n > 1000) then
                errmsg = '&tangential sweep_n = '//fmt_int(s%sweep_n)//': must be in [2, 1000]'; return
            end if
            if ((s%sweep == 'fx' .or. s%sweep == 'fy') .neqv. s%tforce_prescribed) then
                errmsg = "&tangential sweep = '"//trim(s%sweep)//"': sweep 'fx'/'fy' with prescribed forces (give fx "// &
                    "or fy), 'xi'/'eta' with creepages"
                if (s%sweep == 'phi') errmsg = ''
                if (len_trim(errmsg) > 0) return
            end if
        end if
    end subroutine validate_rolling

    !> &solver tol > 0 and maxit >= 1 (shared by every problem kind).
    subroutine validate_iteration_keys(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (.not. (s%settings%tol > 0)) then
            errmsg = '&solver tol = '//fmt_real(s%settings%tol)//': must be > 0'
        else if (s%settings%maxit < 1) then
            errmsg = '&solver maxit = '//fmt_int(s%settings%maxit)//': must be >= 1'
        end if
    end subroutine validate_iteration_keys

    subroutine validate_multigrid(s, errmsg)
        type(fc_case_input), intent(inout) :: s
        character(len=*), intent(out) :: errmsg
        integer :: stat
        character(len=msg_len) :: msg
        errmsg = ''
        call fmg_cycle_from_name(s%cycle, s%fmg%nu1, s%fmg%nu2, stat, msg)
        if (stat /= 0) then
            errmsg = "&solver cycle = '"//trim(s%cycle)//"': not 'V(n1,n2)' with n1, n2 >= 0 and n1 + n2 > 0 "// &
                "(e.g. 'V(1,1)', 'V(1,0)', 'V(0,1)')"
            return
        end if
        if (.not. (s%omega > 0 .and. s%omega < 2)) then
            errmsg = '&solver omega = '//fmt_real(s%omega)//': must lie in (0, 2) (damping of the FMG smoother)'; return
        end if
        if (.not. (s%beta >= 0 .and. ieee_is_finite(s%beta))) then
            errmsg = '&solver beta = '//fmt_real(s%beta)//': must be >= 0 (FMG initial contact area e <= beta*max(u))'
            return
        end if
        select case (s%smoother)
        case ('gs', 'jacobi', 'fft-rsm')
        case default
            errmsg = "&solver smoother = '"//trim(s%smoother)//"': unknown FMG smoother; use 'gs', 'jacobi' or 'fft-rsm'"
            return
        end select
        select case (s%strip)
        case ('mg-fft-rsm', 'mg-fft-sd', 'fft-rsm')
        case default
            errmsg = "&solver strip = '"//trim(s%strip)//"': unknown strip solver; use 'mg-fft-rsm', 'mg-fft-sd' "// &
                "or 'fft-rsm'"
            return
        end select
        s%fmg%omega = s%omega
        s%fmg%beta = s%beta
        s%fmg%smoother = trim(s%smoother)
    end subroutine validate_multigrid

    !> Model problem number of a strip case: 1, 2, 3 for problem = 'strip_mp1' … 'strip_mp3',
    !! else 0.
    pure integer function strip_model_index(s) result(which)
        type(fc_case_input), intent(in) :: s
        select case (s%problem)
        case ('strip_mp1'); which = 1
        case ('strip_mp2'); which = 2
        case ('strip_mp3'); which = 3
        case default; which = 0
        end select
    end function strip_model_index

    !> Validation of a strip model problem case (problem = 'strip_mp1' … 'strip_mp3'):
    !! kind = 'strip2d', nx a power of 2 ≥ 4, ny = 1, the solver keys.  Material, potential
    !! area and loading come from the model problem (thesis §3.2.5).
    subroutine validate_strip(s, stat, errmsg)
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 1; errmsg = ''
        if (.not. is_given(s, 'geometry', 'kind')) then
            errmsg = "&geometry kind: missing required value for problem = '"//trim(s%problem)//"' (use 'strip2d')"
            return
        end if
        if (s%kind /= 'strip2d') then
            errmsg = "&geometry kind = '"//trim(s%kind)//"': problem = '"//trim(s%problem)//"' needs kind = 'strip2d'"
            return
        end if
        if (.not. is_given(s, 'grid', 'nx')) then
            errmsg = "&grid nx: missing required value for problem = '"//trim(s%problem)//"' (a power of 2, >= 4)"
            return
        end if
        if (s%nx < 4 .or. iand(s%nx, s%nx - 1) /= 0 .or. int(s%nx, i8) > max_grid_elements) then
            errmsg = '&grid nx = '//fmt_int(s%nx)//": must be a power of 2 in [4, 4096^2] for problem = '"// &
                trim(s%problem)//"'"
            return
        end if
        if (is_given(s, 'grid', 'ny') .and. s%ny /= 1) then
            errmsg = '&grid ny = '//fmt_int(s%ny)//": must be 1 for &geometry kind = 'strip2d'"; return
        end if
        s%ny = 1
        ! tol: 1e-8 (thesis) unless given; applied by the driver, the inherited state keeps its tol
        call validate_iteration_keys(s, errmsg)
        if (len_trim(errmsg) > 0) return
        call validate_multigrid(s, errmsg)
        if (len_trim(errmsg) > 0) return
        if (len_trim(s%dir) == 0) then
            errmsg = "&output dir = '': must not be empty"; return
        end if
        s%notes = s%notes//'model problem MP'//s%problem(9:9)//' (thesis 3.2.5) fixes the material, the potential '// &
            'area [-4,4]x[-50,50] mm and the loading; &material, &grid xmin..ymax, &normal, &tangential are not used. '
        if (s%strip == 'fft-rsm' .and. is_given(s, 'solver', 'cycle')) &
            s%notes = s%notes//"&solver cycle: not used by the one-grid solver strip = 'fft-rsm'. "
        stat = 0
    end subroutine validate_strip

    !> Build material, grid and undeformed distance h0 (without approach) of a validated
    !! case, and check that contact is possible.
    subroutine setup_case(s, material, grid, h0, stat, errmsg)
        type(fc_case_input), intent(in) :: s
        type(fc_material), intent(out) :: material
        type(fc_grid), intent(out) :: grid
        real(dp), allocatable, intent(out) :: h0(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=msg_len) :: msg
        real(dp) :: hmin
        material%g1 = s%g1; material%g2 = s%g2; material%nu1 = s%nu1; material%nu2 = s%nu2
        call combine_material(material, stat, msg)
        if (stat /= 0) then
            errmsg = '&'//trim(msg); return
        end if
        call make_grid(grid, s%nx, s%ny, s%xmin, s%xmax, s%ymin, s%ymax, stat, msg)
        if (stat /= 0) then
            errmsg = '&'//trim(msg); return
        end if
        allocate (h0(grid%nx, grid%ny), stat=stat)
        if (stat /= 0) then
            errmsg = '&grid nx = '//fmt_int(s%nx)//', ny = '//fmt_int(s%ny)//': cannot allocate the grid'; return
        end if
        select case (s%kind)
        case ('quadratic')
            h0 = quadratic_gap(grid, s%rx, s%ry)
        case ('strip2d', 'cylinder')
            h0 = quadratic_gap(grid, s%rx, 0.0_dp)
        case ('punch_rough')
            call punch_rough_gap(grid, s%diameter, s%rough, h0)
        case ('wavy')
            h0 = wavy_gap(grid, s%amplitude, s%wavelength_x, s%wavelength_y)
        case ('table')
            call read_gap_table(s%file, grid, h0, stat, msg)
            if (stat /= 0) then
                errmsg = "&geometry file = '"//trim(s%file)//"': "//trim(msg); return
            end if
        end select
        if (.not. any(h0 < 0.5_dp*h_no_contact)) then
            stat = 1
            errmsg = '&geometry kind = '''//trim(s%kind)//''': no element can come into contact '// &
                '(e.g. punch diameter smaller than an element)'
            return
        end if
        if (.not. s%force_prescribed) then
            hmin = minval(h0, mask=h0 < 0.5_dp*h_no_contact)
            if (.not. (hmin - s%approach <= 0)) then
                stat = 1
                errmsg = '&normal approach = '//fmt_real(s%approach)//': no contact possible (h0 - approach > 0 '// &
                    'everywhere; min h0 = '//fmt_real(hmin)//')'
                return
            end if
        end if
        stat = 0; errmsg = ''
    end subroutine setup_case

    ! ---------------------------------------------------------------- helpers ----

    logical function file_exists(path)
        character(len=*), intent(in) :: path
        inquire (file=trim(path), exist=file_exists)
    end function file_exists

    !> Short text of a real for messages.
    function fmt_real(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=40) :: buf
        if (ieee_is_nan(x)) then
            s = 'NaN'; return
        end if
        if (.not. ieee_is_finite(x)) then
            s = merge('+Inf', '-Inf', x > 0); return
        end if
        if (x == 0 .or. (abs(x) >= 1.0e-3_dp .and. abs(x) < 1.0e7_dp)) then
            write (buf, '(f0.8)') x
            buf = adjustl(buf)
            s = trim(buf)
            do while (len(s) > 1 .and. s(len(s):len(s)) == '0')
                s = s(1:len(s) - 1)
            end do
            if (s(len(s):len(s)) == '.') s = s//'0'
            if (s(1:1) == '.') s = '0'//s
            if (len(s) >= 2) then
                if (s(1:2) == '-.') s = '-0'//s(2:)
            end if
        else
            write (buf, '(es15.8)') x
            s = trim(adjustl(buf))
        end if
    end function fmt_real

    function fmt_int(i) result(s)
        integer, intent(in) :: i
        character(len=:), allocatable :: s
        character(len=20) :: buf
        write (buf, '(i0)') i
        s = trim(buf)
    end function fmt_int

    pure logical function is_ident_char(c)
        character, intent(in) :: c
        is_ident_char = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. (c >= '0' .and. c <= '9') &
            .or. c == '_'
    end function is_ident_char

    pure function lower(s) result(t)
        character(len=*), intent(in) :: s
        character(len=len(s)) :: t
        integer :: i
        t = s
        do i = 1, len(s)
            if (s(i:i) >= 'A' .and. s(i:i) <= 'Z') t(i:i) = achar(iachar(s(i:i)) + 32)
        end do
    end function lower

    function shorten(s) result(t)
        character(len=*), intent(in) :: s
        character(len=:), allocatable :: t
        if (len_trim(s) > 60) then
            t = s(1:57)//'...'
        else
            t = trim(s)
        end if
    end function shorten

end module fc_input
