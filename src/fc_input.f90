!> The case record of the batch driver's namelist input (doc/namelist.md): the values of
!! the groups as given, inherited from case to case, and the record of which keys were
!! given.  [[fc_namelist]] splits the file into cases; [[apply_case]] reads a case's groups
!! (a namelist READ per group) on top of the inherited record; [[fc_input_validate]] checks
!! it and [[fc_input_scene]] turns it into the library's [[fc_case]].  The record keeps the
!! values as written (solver names, cycle text); the typed settings exist only in the case.
!!
!! Size (~620 lines): one namelist group per block — its keys, defaults, the record of which
!! were given and the inheritance rules — most of it declarations that mirror
!! doc/namelist.md; validation and the scene are in their own modules.
!!
!! Groups, keys and defaults (see also doc/namelist.md):
!!
!! * `&case name, title, problem` — name: file stem of the outputs, not inherited, default
!!   `case<N>`; title: ''; problem: 'normal' (default), 'normal+tangential' or 'tangential'
!!   (the same pipeline: the normal problem is solved as the prerequisite of the tangential one).
!! * `&material g1, g2, nu1, nu2, ic_file, ic_file2` — g1, g2 required (≥ 1e29: rigid);
!!   nu1 = nu2 = 0.28; ic_file: influence coefficients of body 1 (or combined) from a file,
!!   ic_file2: body 2's (default: the half-space g2, nu2) — doc/numerical_ic.md.
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
!! * `&output dir, table, table_format` — dir = 'out' (the command line `--out` wins), table = .true.,
!!   table_format = 'csv' ('npy': NumPy structured array; 'both')
!!
!! Every value persists from case to case except `name`.  A case with an input error does
!! not change the inherited state: the next case inherits from the last good case.
!!
!! Size (~610 lines): the case record, its inheritance and one reader per namelist group
!! (the reader's keys are the documented keys); validation is in [[fc_input_validate]], the
!! scene builder in [[fc_input_scene]], the pre-parser in [[fc_namelist]].
module fc_input
    use fc_kinds, only: dp, i8, msg_len
    use fc_errors, only: FC_ERR_VALUE
    use fc_strings, only: lower
    use fc_geometry, only: fc_rough_params
    use fc_namelist, only: fc_nml_group, fc_case_chunk, key_len, val_len
    use fc_input_check, only: check_value
    use fc_limits, only: max_grid_elements
    implicit none
    private

    integer, parameter, public :: path_len = 256  !! file and directory names

    public :: max_grid_elements   !! largest grid accepted (nx·ny; fc_limits)
    !> Largest grid of a distributed solve (`fastcontact-mpi --distributed`, every rank holding
    !! a slab of rows): the largest size projected in doc/parallel.md (≈ 0.57 GB per rank on
    !! 256 ranks).
    integer(i8), parameter, public :: max_dist_grid_elements = 32768_i8*32768_i8

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
        character(len=path_len) :: ic_file = ''    !! influence coefficients of body 1 (or combined) from a file
        character(len=path_len) :: ic_file2 = ''   !! influence coefficients of body 2 from a file
        ! &grid
        integer :: nx = 0, ny = 0                  !! elements per direction
        real(dp) :: xmin = 0, xmax = 0, ymin = 0, ymax = 0  !! outer edges [mm]
        logical :: grid_auto = .false.             !! &grid auto as given (see [[grid_is_auto]])
        real(dp) :: margin = 0.25_dp               !! auto grid: margin around the Hertz estimate (fraction)
        integer :: n_across = 0                    !! auto grid: elements across the contact (0: 32, or 8 with a target)
        logical :: periodic = .false.              !! periodic half-space: the grid is one cell of a periodic surface
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
        character(len=16) :: rolling = 'gmres'     !! steady rolling solver: 'gmres', 'march', 'steadygs'
        character(len=16) :: rolling_start = 'fastsim'   !! Newton–GMRES cold start: 'fastsim', 'adhesion'
        ! &solver
        character(len=32) :: normal_solver = 'bccg'  !! normal solver: 'bccg', 'norm', 'fmg'
        character(len=32) :: tangential = 'tangcg' !! tangential solver: 'tangcg', 'convexgs'
        real(dp) :: tol = 1.0e-5_dp                !! tolerance of both stages
        integer :: maxit = 1000                    !! iteration limit of both stages
        integer :: inner_maxit = 0                 !! NORM: CG steps per active-set iteration (0: no limit)
        logical :: precondition = .true.           !! BCCG preconditioner (and TangCG's unless given apart)
        logical :: deflation = .false.             !! BCCG coarse correction
        integer :: inner_k = 3                     !! TangCG inner iterations K
        logical :: precondition_tangential = .true.  !! TangCG diagonal preconditioner
        character(len=16) :: fft_preconditioner = 'circulant'  !! form of the FFT preconditioners: 'circulant', 'toeplitz'
        character(len=16) :: cycle = 'V(1,1)'      !! multigrid cycle 'V(n1,n2)' (fmg and strip MG)
        real(dp) :: omega = 0.8_dp                 !! fmg: damping of the Gauss–Seidel smoother, (0, 2)
        real(dp) :: beta = 0.003_dp                !! fmg: initial-area parameter of eq. (2.17), ≥ 0
        character(len=8) :: smoother = 'gs'        !! fmg smoother: 'gs', 'jacobi', 'fft-rsm'
        character(len=16) :: strip = 'mg-fft-rsm'  !! strip model problems: 'mg-fft-rsm', 'mg-fft-sd', 'fft-rsm'
        real(dp) :: target = 0                     !! accuracy target (relative error of the forces; 0: off)
        logical :: target_pmax = .false.           !! the target also applies to pmax
        integer :: max_levels = 5                  !! most grids visited by the accuracy target
        character(len=16) :: model = 'auto'        !! 'auto': apply model reductions; 'full': never
        integer :: threads = 0                     !! threads (0: OMP_NUM_THREADS, else 1)
        character(len=path_len) :: fft_wisdom = ''  !! FFTW wisdom file: read, and written when plans are measured
        ! &output
        character(len=path_len) :: dir = 'out'     !! output directory
        logical :: table = .true.                  !! write the element table
        character(len=8) :: table_format = 'csv'   !! 'csv', 'npy' or 'both'
        ! bookkeeping
        character(len=2*key_len + 1), allocatable :: given(:)  !! 'group:key' given so far
        character(len=:), allocatable :: notes     !! remarks for the report (ignored keys)
    end type fc_case_input

    character(len=*), parameter :: known_groups = 'case material grid geometry normal tangential solver output'

    public :: apply_case, is_given, namelist_keys, grid_is_auto, is_tangential, strip_model_index, known_groups

contains

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
        character(len=msg_len) :: where, vmsg
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
                    stat = FC_ERR_VALUE
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
                        stat = FC_ERR_VALUE
                        errmsg = trim(where)//": unknown key '"//trim(g%items(k)%key)//"' (value "// &
                            trim(g%items(k)%value)//'); known keys: '//keys_of(g%name)
                        return
                    end if
                    ! one literal of the key's type, before the namelist READ (named message)
                    call check_value(g%name, g%items(k)%key, g%items(k)%value, vmsg)
                    if (len_trim(vmsg) > 0) then
                        stat = FC_ERR_VALUE
                        write (errmsg, '(a,i0,a)') trim(vmsg)//' (line ', g%line, ')'
                        return
                    end if
                end do
                if (g%name == 'normal') then
                    has_fn = any(g%items%key == 'fn')
                    has_approach = any(g%items%key == 'approach')
                    if (has_fn .and. has_approach) then
                        stat = FC_ERR_VALUE
                        errmsg = trim(where)//': give either approach or fn, not both (approach = '// &
                            trim(item_value(g, 'approach'))//', fn = '//trim(item_value(g, 'fn'))//')'
                        return
                    end if
                end if
                if (g%name == 'tangential') then
                    has_shift = any(g%items%key == 'xi') .or. any(g%items%key == 'eta')
                    has_force = any(g%items%key == 'fx') .or. any(g%items%key == 'fy')
                    if (has_shift .and. has_force) then
                        stat = FC_ERR_VALUE
                        errmsg = trim(where)//': give either the shifts xi, eta or the forces fx, fy, not both ('// &
                            trim(given_list(g, ['xi ', 'eta', 'fx ', 'fy ']))//')'
                        return
                    end if
                end if
                call read_group(g%name, g%text, s, ios, iomsg)
                if (ios /= 0) then
                    stat = FC_ERR_VALUE
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
                        s%precondition_tangential = s%precondition
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
        character(len=path_len) :: ic_file, ic_file2
        namelist /material/ g1, g2, nu1, nu2, ic_file, ic_file2
        g1 = s%g1; g2 = s%g2; nu1 = s%nu1; nu2 = s%nu2; ic_file = s%ic_file; ic_file2 = s%ic_file2
        read (text, nml=material, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%g1 = g1; s%g2 = g2; s%nu1 = nu1; s%nu2 = nu2; s%ic_file = ic_file; s%ic_file2 = ic_file2
    end subroutine read_material_group

    subroutine read_grid_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        integer :: nx, ny, n_across
        real(dp) :: xmin, xmax, ymin, ymax, margin
        logical :: auto, periodic
        namelist /grid/ nx, ny, xmin, xmax, ymin, ymax, auto, margin, n_across, periodic
        nx = s%nx; ny = s%ny; xmin = s%xmin; xmax = s%xmax; ymin = s%ymin; ymax = s%ymax
        auto = s%grid_auto; margin = s%margin; n_across = s%n_across; periodic = s%periodic
        read (text, nml=grid, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%nx = nx; s%ny = ny; s%xmin = xmin; s%xmax = xmax; s%ymin = ymin; s%ymax = ymax
        s%grid_auto = auto; s%margin = margin; s%n_across = n_across; s%periodic = periodic
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
        integer :: maxit, inner_maxit, inner_k, max_levels, threads
        logical :: precondition, precondition_tangential, deflation, target_pmax
        character(len=16) :: model, rolling, fft_preconditioner, rolling_start
        character(len=path_len) :: fft_wisdom
        namelist /solver/ normal, tangential, tol, maxit, inner_maxit, precondition, precondition_tangential, &
            deflation, inner_k, cycle, omega, beta, target, target_pmax, max_levels, model, smoother, strip, rolling, threads, &
            fft_wisdom, fft_preconditioner, rolling_start
        normal = s%normal_solver; tangential = s%tangential; tol = s%tol; maxit = s%maxit
        inner_maxit = s%inner_maxit; precondition = s%precondition
        precondition_tangential = s%precondition_tangential
        deflation = s%deflation; inner_k = s%inner_k; cycle = s%cycle; omega = s%omega; beta = s%beta
        target = s%target; target_pmax = s%target_pmax; max_levels = s%max_levels; model = s%model
        smoother = s%smoother; strip = s%strip; rolling = s%rolling; threads = s%threads; fft_wisdom = s%fft_wisdom
        fft_preconditioner = s%fft_preconditioner; rolling_start = s%rolling_start
        read (text, nml=solver, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%normal_solver = lower(normal); s%tangential = lower(tangential); s%tol = tol
        s%maxit = maxit; s%inner_maxit = inner_maxit; s%precondition = precondition
        s%precondition_tangential = precondition_tangential
        s%deflation = deflation; s%inner_k = inner_k; s%cycle = cycle; s%omega = omega; s%beta = beta
        s%target = target; s%target_pmax = target_pmax; s%max_levels = max_levels; s%model = lower(model)
        s%smoother = lower(smoother); s%strip = lower(strip); s%rolling = lower(rolling); s%threads = threads
        s%fft_wisdom = fft_wisdom; s%fft_preconditioner = lower(fft_preconditioner)
        s%rolling_start = lower(rolling_start)
    end subroutine read_solver_group

    subroutine read_output_group(text, s, ios, iomsg)
        character(len=*), intent(in) :: text
        type(fc_case_input), intent(inout) :: s
        integer, intent(out) :: ios
        character(len=*), intent(out) :: iomsg
        character(len=path_len) :: dir
        logical :: table
        character(len=8) :: table_format
        namelist /output/ dir, table, table_format
        dir = s%dir; table = s%table; table_format = s%table_format
        read (text, nml=output, iostat=ios, iomsg=iomsg)
        if (ios /= 0) return
        s%dir = dir; s%table = table; s%table_format = lower(table_format)
    end subroutine read_output_group

    !> Keys of a group, blank separated.
    function keys_of(group) result(keys)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: keys
        select case (group)
        case ('case');       keys = 'name title problem'
        case ('material');   keys = 'g1 g2 nu1 nu2 ic_file ic_file2'
        case ('grid');       keys = 'nx ny xmin xmax ymin ymax auto margin n_across periodic'
        case ('geometry')
            keys = 'kind rx ry diameter sigma gamma m_modes n_modes seed amplitude wavelength_x wavelength_y file length'
        case ('normal');     keys = 'approach fn'
        case ('tangential'); keys = 'mu xi eta phi fx fy mu_kinetic dq nsteps sweep sweep_from sweep_to sweep_n'
        case ('solver')
            keys = 'normal tangential tol maxit inner_maxit inner_k precondition precondition_tangential deflation '// &
                'cycle omega beta smoother strip target target_pmax max_levels model rolling threads fft_wisdom '// &
                'fft_preconditioner rolling_start'
        case ('output');     keys = 'dir table table_format'
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
    pure logical function grid_is_auto(s)
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
    pure logical function is_given(s, group, key)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(in) :: group, key
        is_given = .false.
        if (allocated(s%given)) is_given = any(s%given == tag(group, key))
    end function is_given

    pure function tag(group, key) result(t)
        character(len=*), intent(in) :: group, key
        character(len=2*key_len + 1) :: t
        t = trim(group)//':'//trim(key)
    end function tag

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

end module fc_input
