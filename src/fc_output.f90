!> Output of the batch driver (doc/user_guide.md): per case a JSON summary, a CSV table of
!! the element values and a readable text report with a character map of the contact area
!! in the style of Kalker's CONTACT.  It writes results only: the summary of a case and the
!! outcome of the automatic layer ([[fc_case_result]]), never computing them.
!!
!! Size (~640 lines): the 60-field summary type and its three writers (JSON, report with
!! the contact map, tables through [[fc_table_io]]), which share the summary's fields.
module fc_output
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fc_kinds, only: dp, msg_len
    use fc_strings, only: upper
    use fc_geometry, only: fc_grid
    use fc_influence, only: fc_material
    use fc_hertz, only: fc_hertz_solution, fc_cattaneo_solution
    use fc_version, only: fc_version_string, fc_build_info
    use fc_case_result, only: fc_auto_outcome
    use fc_table_io, only: write_element_table_csv, write_element_table_npy
    implicit none
    private

    !> Everything the JSON summary and the report state about one case.
    type, public :: fc_case_summary
        character(len=64) :: name = ''               !! case name (file stem)
        character(len=128) :: title = ''             !! free text
        character(len=32) :: problem = 'normal'      !! problem type
        !> hash of the version and of the groups of this and all earlier cases of the file
        !! ([[fc_driver_resume]]: `--resume` skips a case whose JSON has the same)
        character(len=16) :: input_fingerprint = ''
        character(len=16) :: geometry = ''           !! geometry kind
        character(len=16) :: status = 'error'        !! converged, not_converged, diverged, error
        character(len=24) :: solver = ''             !! solver(s) used: 'bccg' or 'bccg+tangcg'
        character(len=16) :: solver_normal = ''      !! normal solver
        character(len=16) :: fft_preconditioner = '' !! form of the FFT preconditioners ('circulant', 'toeplitz')
        character(len=16) :: solver_tangential = ''  !! tangential solver ('' for problem = normal)
        logical :: tangential = .false.              !! tangential problem solved (results below valid)
        logical :: tangential_run = .false.          !! tangential stage was reached
        character(len=16) :: status_normal = 'error' !! status of the normal stage
        character(len=16) :: status_tangential = 'not_run' !! status of the tangential stage
        logical :: force_prescribed = .false.        !! fn prescribed (else approach)
        real(dp) :: fn = 0, fx = 0, fy = 0, mz = 0   !! total forces [N] and moment [N mm]
        !> frictional dissipation −Σ p·s·δA: [N·mm] over a shift or transient step, [N] (per mm
        !! rolled, Tγ) in steady rolling; FASTSIM: the creepage work −(Fx ξ + Fy η + Mz φ)
        real(dp) :: dissipation = 0
        real(dp) :: approach = 0                     !! approach δ used [mm]
        real(dp) :: pmax = 0                         !! maximum pressure [N/mm²]
        integer :: ncon = 0, nadh = 0, nslip = 0     !! elements in contact / adhesion / slip
        integer :: iterations = 0                    !! solver iterations
        integer :: outer_iterations = 0              !! active-set iterations / free-set changes
        integer :: matvecs = 0                       !! products with A
        real(dp) :: residual = 0                     !! final relative residual
        real(dp) :: tol = 0                          !! requested tolerance
        real(dp) :: cpu_seconds = 0                  !! whole case
        real(dp) :: cpu_seconds_normal = 0           !! operator set-up + normal solve
        real(dp) :: cpu_seconds_tangential = 0       !! tangential operator set-up + tangential solve
        real(dp) :: setup_seconds = 0                !! normal operator set-up (0 when reused)
        real(dp) :: xi = 0, eta = 0, phi = 0         !! rigid shift used [mm, mm, rad]
        real(dp) :: mu = 0                           !! coefficient of friction
        logical :: tforce_prescribed = .false.       !! tangential forces prescribed (else shifts)
        real(dp) :: fx_prescribed = 0, fy_prescribed = 0  !! prescribed tangential forces [N]
        integer :: iterations_normal = 0, iterations_tangential = 0  !! per stage (all rounds)
        integer :: outer_iterations_normal = 0, outer_iterations_tangential = 0
        integer :: matvecs_normal = 0, matvecs_tangential = 0
        integer :: panagiotopoulos_rounds = 0        !! normal–tangential rounds (1 when K = 0)
        real(dp) :: residual_normal = 0, residual_tangential = 0
        real(dp) :: setup_seconds_tangential = 0     !! tangential operator set-up (0 when reused)
        logical :: operator_built = .false.          !! the case built the normal operator (else reused)
        logical :: operator_built_tangential = .false.  !! the case built the tangential operator
        logical :: has_hertz = .false.               !! quadratic geometry: analytic comparison
        type(fc_hertz_solution) :: hertz             !! analytic Hertz solution
        character(len=msg_len) :: message = ''       !! solver message
        character(len=:), allocatable :: notes       !! remarks (ignored keys)
        !> what the automatic layer decided and computed (grid, material, grids visited,
        !! accuracy, reductions, warnings, analytic answers) and the final solution; strip
        !! model problems fill grid, material and model only
        type(fc_auto_outcome) :: outcome
        ! ---- multigrid
        real(dp) :: work_units = -1                  !! FMG / strip solvers: work units (−1: not a multigrid solve)
        real(dp) :: convergence_factor = -1          !! FMG / strip solvers: convergence factor (−1: n/a)
        character(len=16) :: cycle = ''              !! multigrid cycle used ('' for one-grid solvers)
    end type fc_case_summary

    integer, parameter, public :: map_max_cols = 100  !! widest contact map
    integer, parameter, public :: map_max_rows = 50   !! tallest contact map

    public :: write_case_json, write_case_csv, write_case_npy, write_case_report, json_string, contact_map, state_map

contains

    !> Write the JSON summary of a case to `path`.
    subroutine write_case_json(path, s, stat, errmsg)
        character(len=*), intent(in) :: path
        type(fc_case_summary), intent(in) :: s
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u
        character(len=256) :: iomsg
        open (newunit=u, file=path, status='replace', action='write', iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            errmsg = "cannot write '"//trim(path)//"': "//trim(iomsg); return
        end if
        write (u, '(a)') '{'
        call kv_str('name', s%name)
        call kv_str('version', fc_version_string)
        if (len_trim(s%input_fingerprint) > 0) call kv_str('input_fingerprint', s%input_fingerprint)
        call kv_str('title', s%title)
        call kv_str('problem', s%problem)
        call kv_str('geometry', s%geometry)
        call kv_str('status', s%status)
        call kv_str('message', s%message)
        call kv_str('solver', s%solver)
        call kv_str('load', merge('fn      ', 'approach', s%force_prescribed))
        call kv_real('fn', s%fn)
        call kv_real('fx', s%fx)
        call kv_real('fy', s%fy)
        call kv_real('mz', s%mz)
        call kv_real('dissipation', s%dissipation)
        call kv_real('approach', s%approach)
        call kv_real('xi', s%xi)
        call kv_real('eta', s%eta)
        call kv_real('phi', s%phi)
        call kv_real('pmax', s%pmax)
        call kv_int('ncon', s%ncon)
        call kv_int('nadh', s%nadh)
        call kv_int('nslip', s%nslip)
        call kv_int('iterations', s%iterations)
        call kv_int('outer_iterations', s%outer_iterations)
        call kv_int('matvecs', s%matvecs)
        call kv_real('residual', s%residual)
        call kv_real('tol', s%tol)
        call kv_real('cpu_seconds', s%cpu_seconds)
        call kv_real('cpu_seconds_normal', s%cpu_seconds_normal)
        call kv_real('cpu_seconds_tangential', s%cpu_seconds_tangential)
        call kv_real('setup_seconds', s%setup_seconds)
        call kv_bool('operator_built', s%operator_built)
        call kv_str('solver_normal', s%solver_normal)
        call kv_str('fft_preconditioner', s%fft_preconditioner)
        call kv_str('status_normal', s%status_normal)
        call kv_int('iterations_normal', s%iterations_normal)
        call kv_int('outer_iterations_normal', s%outer_iterations_normal)
        call kv_int('matvecs_normal', s%matvecs_normal)
        call kv_real('residual_normal', s%residual_normal)
        call kv_int('precond_applications_normal', s%outcome%result%normal%precond_applications)
        call kv_reals('history_normal', s%outcome%result%normal%history)
        if (s%work_units >= 0) then
            call kv_real('work_units', s%work_units)
            call kv_real('convergence_factor', s%convergence_factor)
            call kv_str('cycle', s%cycle)
        end if
        if (s%tangential) then
            call kv_str('solver_tangential', s%solver_tangential)
            call kv_str('status_tangential', s%status_tangential)
            call kv_real('mu', s%mu)
            if ((s%problem == 'rolling' .or. s%problem == 'transient_rolling') .and. s%mu*s%fn > 0) then
                ! creep forces over mu*Fn (xi, eta, phi above are creepages [-, -, 1/mm] here)
                call kv_real('fx_over_mu_fn', s%fx/(s%mu*s%fn))
                call kv_real('fy_over_mu_fn', s%fy/(s%mu*s%fn))
            end if
            call kv_str('tangential_load', merge('forces', 'shifts', s%tforce_prescribed))
            if (s%tforce_prescribed) then
                call kv_real('fx_prescribed', s%fx_prescribed)
                call kv_real('fy_prescribed', s%fy_prescribed)
            end if
            call kv_int('iterations_tangential', s%iterations_tangential)
            call kv_int('outer_iterations_tangential', s%outer_iterations_tangential)
            call kv_int('matvecs_tangential', s%matvecs_tangential)
            call kv_real('residual_tangential', s%residual_tangential)
            call kv_reals('history_tangential', s%outcome%result%tangential%history)
            call kv_int('panagiotopoulos_rounds', s%panagiotopoulos_rounds)
            call kv_real('setup_seconds_tangential', s%setup_seconds_tangential)
            call kv_bool('operator_built_tangential', s%operator_built_tangential)
        end if
        call kv_int('nx', s%outcome%grid%nx)
        call kv_int('ny', s%outcome%grid%ny)
        call kv_real('dx', s%outcome%grid%dx)
        call kv_real('dy', s%outcome%grid%dy)
        call kv_real('xmin', s%outcome%grid%xmin)
        call kv_real('xmax', s%outcome%grid%xmax)
        call kv_real('ymin', s%outcome%grid%ymin)
        call kv_real('ymax', s%outcome%grid%ymax)
        call kv_real('g', s%outcome%material%g)
        call kv_real('nu', s%outcome%material%nu)
        call kv_str('model', s%outcome%model)
        call kv_list('reductions', s%outcome%reductions)
        call kv_list('warnings', s%outcome%warnings)
        ! the report's note line (keys without effect, what a sequence's summary holds)
        if (allocated(s%notes)) then
            call kv_str('notes', s%notes)
        else
            call kv_str('notes', '')
        end if
        write (u, '(a)') '  "grid_auto": '//trim(merge('true ', 'false', s%outcome%grid_auto))//','
        call kv_int('enlargements', s%outcome%enlargements)
        write (u, '(a)') '  "touches_boundary": '//trim(merge('true ', 'false', s%outcome%touches_boundary))//','
        if (s%outcome%target > 0) then
            write (u, '(a)') '  "accuracy": {"target": '//json_real(s%outcome%target)//', "estimate": '// &
                json_real(s%outcome%estimate)// &
                ', "target_met": '//trim(merge('true ', 'false', s%outcome%target_met))//', "reliable": '// &
                trim(merge('true ', 'false', s%outcome%reliable))//', "quantities": '//json_string(trim(s%outcome%quantities))// &
                ', "seconds": '//json_real(s%outcome%total_seconds)//', "coarsest_sufficient": '//sufficient_json()//'},'
        end if
        if (allocated(s%outcome%levels)) call kv_levels()
        if (s%outcome%has_cattaneo) then
            write (u, '(a)') '  "cattaneo": {"a": '//json_real(s%outcome%cattaneo%a)//', "c": '// &
                json_real(s%outcome%cattaneo%c)// &
                ', "shift": '//json_real(s%outcome%cattaneo%shift)//', "mu": '//json_real(s%outcome%cattaneo%mu)//'},'
        end if
        call kv_real('k', s%outcome%material%k, last=.not. s%has_hertz)
        if (s%has_hertz) then
            write (u, '(a)') '  "hertz": {"a": '//json_real(s%hertz%a)//', "b": '//json_real(s%hertz%b)// &
                ', "p0": '//json_real(s%hertz%p0)//', "fn": '//json_real(s%hertz%fn)// &
                ', "approach": '//json_real(s%hertz%approach)//'}'
        end if
        write (u, '(a)') '}'
        close (u, iostat=stat, iomsg=iomsg)
        if (stat /= 0) errmsg = "cannot close '"//trim(path)//"': "//trim(iomsg)
    contains
        subroutine kv_str(key, val)
            character(len=*), intent(in) :: key, val
            write (u, '(a)') '  "'//key//'": '//json_string(trim(val))//','
        end subroutine kv_str
        subroutine kv_real(key, val, last)
            character(len=*), intent(in) :: key
            real(dp), intent(in) :: val
            logical, intent(in), optional :: last
            character(len=1) :: comma
            comma = ','
            if (present(last)) then
                if (last) comma = ' '
            end if
            write (u, '(a)') '  "'//key//'": '//json_real(val)//trim(comma)
        end subroutine kv_real
        subroutine kv_bool(key, val)
            character(len=*), intent(in) :: key
            logical, intent(in) :: val
            write (u, '(a)') '  "'//key//'": '//trim(merge('true ', 'false', val))//','
        end subroutine kv_bool
        subroutine kv_int(key, val)
            character(len=*), intent(in) :: key
            integer, intent(in) :: val
            character(len=20) :: buf
            write (buf, '(i0)') val
            write (u, '(a)') '  "'//key//'": '//trim(buf)//','
        end subroutine kv_int
        !> A real array as a JSON list ([] when not allocated).
        subroutine kv_reals(key, vals)
            character(len=*), intent(in) :: key
            real(dp), allocatable, intent(in) :: vals(:)
            integer :: k
            write (u, '(a)', advance='no') '  "'//key//'": ['
            if (allocated(vals)) then
                do k = 1, size(vals)
                    if (k > 1) write (u, '(a)', advance='no') ', '
                    write (u, '(a)', advance='no') json_real(vals(k))
                end do
            end if
            write (u, '(a)') '],'
        end subroutine kv_reals
        subroutine kv_list(key, list)
            character(len=*), intent(in) :: key
            character(len=*), allocatable, intent(in) :: list(:)
            character(len=:), allocatable :: line
            integer :: k
            line = '  "'//key//'": ['
            if (allocated(list)) then
                do k = 1, size(list)
                    if (k > 1) line = line//', '
                    line = line//json_string(trim(list(k)))
                end do
            end if
            write (u, '(a)') line//'],'
        end subroutine kv_list
        function sufficient_json() result(text)
            character(len=:), allocatable :: text
            character(len=40) :: buf
            if (s%outcome%sufficient == 0) then
                text = 'null'
            else
                associate (l => s%outcome%levels(s%outcome%sufficient))
                    write (buf, '(i0,a,i0)') l%nx, ', "ny": ', l%ny
                end associate
                text = '{"nx": '//trim(buf)//', "bound": '//json_real(s%outcome%sufficient_bound)//'}'
            end if
        end function sufficient_json
        subroutine kv_levels()
            integer :: k
            character(len=40) :: buf
            write (u, '(a)') '  "levels": ['
            do k = 1, size(s%outcome%levels)
                associate (l => s%outcome%levels(k))
                    write (buf, '(i0,a,i0,a,i0)') l%nx, ', "ny": ', l%ny, ', "ncon": ', l%ncon
                    write (u, '(a)') '    {"nx": '//trim(buf)//', "fn": '//json_real(l%fn)//', "approach": '// &
                        json_real(l%approach)//', "fx": '//json_real(l%fx)//', "fy": '//json_real(l%fy)//', "xi": '// &
                        json_real(l%xi)//', "eta": '//json_real(l%eta)//', "pmax": '//json_real(l%pmax)// &
                        ', "estimate": '//json_real(l%estimate)//', "ratio": '//json_real(l%ratio)//', "monotone": '// &
                        trim(merge('true ', 'false', l%monotone))//', "seconds": '//json_real(l%seconds)// &
                        ', "status": '//json_string(trim(l%status))//'}'//trim(merge(',', ' ', k < size(s%outcome%levels)))
                end associate
            end do
            write (u, '(a)') '  ],'
        end subroutine kv_levels
    end subroutine write_case_json

    !> A real as a JSON number at full precision (null for NaN/Inf).
    function json_real(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        if (.not. ieee_is_finite(x)) then
            s = 'null'; return
        end if
        write (buf, '(es23.15e3)') x
        s = trim(adjustl(buf))
    end function json_real

    !> A JSON string literal with escapes.
    function json_string(text) result(s)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: s
        integer :: i, c
        character(len=6) :: esc
        s = '"'
        do i = 1, len(text)
            c = iachar(text(i:i))
            select case (c)
            case (34); s = s//'\"'
            case (92); s = s//'\\'
            case (0:31)
                write (esc, '(a,z4.4)') '\u', c
                s = s//esc
            case default; s = s//text(i:i)
            end select
        end do
        s = s//'"'
    end function json_string

    !> Write the element table `ix,iy,x,y,status,pn,px,py,sx,sy,gap`.  With the tangential
    !! solution (`state`, `px`, `py`, `sx`, `sy` all present): status E exterior, A adhesion,
    !! S slip from `state`.  Without (normal problem): status A in contact, E exterior;
    !! px..sy = 0.
    subroutine write_case_csv(path, grid, pn, gap, stat, errmsg, state, px, py, sx, sy)
        character(len=*), intent(in) :: path
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: pn(:, :), gap(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer, intent(in), optional :: state(:, :)        !! EL_EXTERIOR, EL_ADHESION, EL_SLIP
        real(dp), intent(in), optional :: px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer :: i, j
        if (present(state) .and. present(px) .and. present(py) .and. present(sx) .and. present(sy)) then
            call write_element_table_csv(path, [(grid%x(i), i=1, grid%nx)], [(grid%y(j), j=1, grid%ny)], pn, gap, &
                stat, errmsg, state, px, py, sx, sy)
        else
            call write_element_table_csv(path, [(grid%x(i), i=1, grid%nx)], [(grid%y(j), j=1, grid%ny)], pn, gap, &
                stat, errmsg)
        end if
    end subroutine write_case_csv

    !> Write the element table of [[write_case_csv]] as a NumPy `.npy` structured array
    !! (fields ix, iy, x, y, status, pn, px, py, sx, sy, gap; see fc_table_io).
    subroutine write_case_npy(path, grid, pn, gap, stat, errmsg, state, px, py, sx, sy)
        character(len=*), intent(in) :: path
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: pn(:, :), gap(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer, intent(in), optional :: state(:, :)
        real(dp), intent(in), optional :: px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer :: i, j
        if (present(state) .and. present(px) .and. present(py) .and. present(sx) .and. present(sy)) then
            call write_element_table_npy(path, [(grid%x(i), i=1, grid%nx)], [(grid%y(j), j=1, grid%ny)], pn, gap, &
                stat, errmsg, state, px, py, sx, sy)
        else
            call write_element_table_npy(path, [(grid%x(i), i=1, grid%nx)], [(grid%y(j), j=1, grid%ny)], pn, gap, &
                stat, errmsg)
        end if
    end subroutine write_case_npy

    !> Status letter of an element state: E exterior (0), A adhesion (1), S slip (2).
    pure character function state_char(state)
        integer, intent(in) :: state
        select case (state)
        case (1); state_char = 'A'
        case (2); state_char = 'S'
        case default; state_char = 'E'
        end select
    end function state_char

    !> Character map of the adhesion and slip areas: 'A' adhesion, 'S' slip, '.' exterior,
    !! rows with y decreasing from the top.  Subsampled as [[contact_map]]: a block gets the
    !! letter of its majority contact state (ties: S), upper case when at least half of the
    !! block is in contact, lower case when only part of it is, '.' when none.
    subroutine state_map(state, lines, sx, sy)
        integer, intent(in) :: state(:, :)
        character(len=:), allocatable, intent(out) :: lines(:)
        integer, intent(out) :: sx, sy
        integer :: nx, ny, mx, my, i, j, nadh, nslip, ntot
        character :: c
        nx = size(state, 1); ny = size(state, 2)
        sx = (nx + map_max_cols - 1)/map_max_cols
        sy = (ny + map_max_rows - 1)/map_max_rows
        mx = (nx + sx - 1)/sx
        my = (ny + sy - 1)/sy
        allocate (character(len=mx) :: lines(my))
        do j = 1, my
            do i = 1, mx
                associate (blk => state((i - 1)*sx + 1:min(nx, i*sx), (my - j)*sy + 1:min(ny, (my - j + 1)*sy)))
                    nadh = count(blk == 1); nslip = count(blk == 2); ntot = size(blk)
                end associate
                if (nadh + nslip == 0) then
                    c = '.'
                else
                    c = merge('A', 'S', nadh > nslip)
                    if (2*(nadh + nslip) < ntot) c = merge('a', 's', nadh > nslip)
                end if
                lines(j)(i:i) = c
            end do
        end do
    end subroutine state_map

    !> Character map of the contact area: one character per element ('.' exterior, '*'
    !! contact), rows with y decreasing from the top.  Grids wider than `map_max_cols` or
    !! taller than `map_max_rows` are subsampled in blocks of sx×sy elements: '*' when at
    !! least half of the block is in contact, '+' when some, '.' when none.
    subroutine contact_map(pn, lines, sx, sy)
        real(dp), intent(in) :: pn(:, :)
        character(len=:), allocatable, intent(out) :: lines(:)
        integer, intent(out) :: sx, sy   !! block size (1, 1 when not subsampled)
        integer :: nx, ny, mx, my, i, j, ncon, ntot
        nx = size(pn, 1); ny = size(pn, 2)
        sx = (nx + map_max_cols - 1)/map_max_cols
        sy = (ny + map_max_rows - 1)/map_max_rows
        mx = (nx + sx - 1)/sx
        my = (ny + sy - 1)/sy
        allocate (character(len=mx) :: lines(my))
        do j = 1, my
            do i = 1, mx
                associate (blk => pn((i - 1)*sx + 1:min(nx, i*sx), (my - j)*sy + 1:min(ny, (my - j + 1)*sy)))
                    ncon = count(blk > 0); ntot = size(blk)
                end associate
                if (ncon == 0) then
                    lines(j)(i:i) = '.'
                else if (2*ncon >= ntot) then
                    lines(j)(i:i) = '*'
                else
                    lines(j)(i:i) = '+'
                end if
            end do
        end do
    end subroutine contact_map

    !> Readable report of one case on `unit`.  `pn` may be empty (no solution); `state`
    !! (tangential problems) gives the adhesion/slip map instead of the contact map.
    subroutine write_case_report(unit, s, pn, state)
        integer, intent(in) :: unit
        type(fc_case_summary), intent(in) :: s
        real(dp), intent(in) :: pn(:, :)
        integer, intent(in), optional :: state(:, :)
        character(len=:), allocatable :: lines(:)
        integer :: sx, sy, j
        real(dp) :: pct, pct_adh, pct_slip
        logical :: rolling   !! steady or transient rolling: creepages, not rigid shifts
        logical :: gridless  !! a model without elements (FASTSIM on the Hertz ellipse, analytic answers)
        character(len=*), parameter :: rule = &
            '------------------------------------------------------------------------------------------'
        write (unit, '(a)') rule
        write (unit, '(a)') ' case '//trim(s%name)//'   '//trim(s%title)
        write (unit, '(a)') rule
        write (unit, '(a,a)') ' program      ', fc_build_info()
        write (unit, '(a,a)') ' problem      ', trim(s%problem)//', geometry '//trim(s%geometry)
        write (unit, '(a,4(1x,es12.5))') ' material     G1, G2, nu1, nu2 =', s%outcome%material%g1, s%outcome%material%g2, &
            s%outcome%material%nu1, s%outcome%material%nu2
        write (unit, '(a,es12.5,a,f8.5,a,es12.5)') ' combined     G = ', s%outcome%material%g, '   nu = ', &
            s%outcome%material%nu, &
            '   K = ', s%outcome%material%k
        gridless = s%outcome%grid%nx*s%outcome%grid%ny == 0
        if (gridless) then
            write (unit, '(a)') ' grid         none (a model without elements: no element counts, no map)'
        else
            write (unit, '(a,i0,a,i0,a,4(1x,g0.6),a)') ' grid         ', s%outcome%grid%nx, ' x ', s%outcome%grid%ny, &
                ' elements on [xmin,xmax]x[ymin,ymax] =', s%outcome%grid%xmin, s%outcome%grid%xmax, &
                s%outcome%grid%ymin, s%outcome%grid%ymax, ''
            write (unit, '(a,es12.5,a,es12.5)') '              dx = ', s%outcome%grid%dx, '   dy = ', s%outcome%grid%dy
        end if
        if (s%force_prescribed) then
            write (unit, '(a)') ' load         prescribed total normal force fn'
        else
            write (unit, '(a)') ' load         prescribed approach'
        end if
        write (unit, '(a,es16.8,a,es12.5,a,es12.5,a,es12.5)') ' forces       Fn = ', s%fn, '   Fx = ', s%fx, &
            '   Fy = ', s%fy, '   Mz = ', s%mz
        write (unit, '(a,es16.8,a,es16.8)') ' approach     ', s%approach, '      pmax = ', s%pmax
        pct = 0
        if (s%outcome%grid%nx*s%outcome%grid%ny > 0) pct = 100.0_dp*s%ncon/(real(s%outcome%grid%nx, dp)*s%outcome%grid%ny)
        if (.not. gridless) write (unit, '(a,i0,a,f6.2,a,i0,a,i0)') ' contact      ncon = ', s%ncon, ' (', pct, &
            ' % of the grid)   nadh = ', s%nadh, '   nslip = ', s%nslip
        if (s%has_hertz) then
            write (unit, '(a,4(a,es12.5))') ' Hertz        ', 'a = ', s%hertz%a, '   b = ', s%hertz%b, '   p0 = ', &
                s%hertz%p0, '   Fn = ', s%hertz%fn
        end if
        if (s%tangential) then
            rolling = s%problem == 'rolling' .or. s%problem == 'transient_rolling'
            if (rolling) then
                write (unit, '(a,es12.5,a)') ' friction     mu = ', s%mu, &
                    trim(merge('   prescribed creep forces', '   prescribed creepages   ', s%tforce_prescribed))
            else
                write (unit, '(a,es12.5,a)') ' friction     mu = ', s%mu, &
                    trim(merge('   prescribed tangential forces', '   prescribed rigid shifts     ', s%tforce_prescribed))
            end if
            if (s%tforce_prescribed) write (unit, '(a,es12.5,a,es12.5,a,es12.5,a)') '              Fx = ', &
                s%fx_prescribed, '   Fy = ', s%fy_prescribed, '   (mu*Fn = ', s%mu*s%fn, ')'
            if (rolling) then
                write (unit, '(a,es14.6,a,es14.6,a,es14.6,a)') ' creepages    xi = ', s%xi, '   eta = ', s%eta, &
                    '   phi = ', s%phi, ' /mm'
            else
                write (unit, '(a,es14.6,a,es14.6,a,es14.6)') ' shifts used  xi = ', s%xi, '   eta = ', s%eta, &
                    '   phi = ', s%phi
            end if
            write (unit, '(a,es14.6,a,es14.6,a,es14.6)') ' tangential   Fx = ', s%fx, '   Fy = ', s%fy, '   Mz = ', s%mz
            if (s%mu*s%fn > 0) write (unit, '(a,f9.5,a,f9.5)') '              Fx/(mu Fn) = ', s%fx/(s%mu*s%fn), &
                '   Fy/(mu Fn) = ', s%fy/(s%mu*s%fn)
            if (s%problem == 'rolling') then
                write (unit, '(a,es14.6,a)') ' dissipation  D = ', s%dissipation, ' N per mm rolled (Tgamma)'
            else if (s%problem == 'transient_rolling') then
                write (unit, '(a,es14.6,a)') ' dissipation  D = ', s%dissipation, ' N mm over the last step'
            else
                write (unit, '(a,es14.6,a)') ' dissipation  D = ', s%dissipation, ' N mm over the shift'
            end if
            pct_adh = 0; pct_slip = 0
            if (s%nadh + s%nslip > 0) then
                pct_adh = 100.0_dp*s%nadh/(s%nadh + s%nslip); pct_slip = 100.0_dp*s%nslip/(s%nadh + s%nslip)
            end if
            if (.not. gridless) write (unit, '(a,i0,a,f6.2,a,i0,a,f6.2,a)') ' adhesion     nadh = ', s%nadh, ' (', &
                pct_adh, ' % of contact)   nslip = ', s%nslip, ' (', pct_slip, ' % of contact)'
            write (unit, '(a,a,a,i0,a,i0,a,i0,a,es10.3,a)') ' normal       ', trim(s%solver_normal), ':  iterations ', &
                s%iterations_normal, ' (outer ', s%outer_iterations_normal, ')   matvecs ', s%matvecs_normal, &
                '   residual ', s%residual_normal, '   '//trim(s%status_normal)
            write (unit, '(a,a,a,i0,a,i0,a,i0,a,es10.3,a)') ' tangential   ', trim(s%solver_tangential), ':  iterations ', &
                s%iterations_tangential, ' (outer ', s%outer_iterations_tangential, ')   matvecs ', s%matvecs_tangential, &
                '   residual ', s%residual_tangential, '   '//trim(s%status_tangential)
            if (s%panagiotopoulos_rounds > 0) then
                write (unit, '(a,i0,a,es10.3)') '              Panagiotopoulos rounds ', s%panagiotopoulos_rounds, &
                    '   (1: K = 0, decoupled)   tol ', s%tol
            else
                write (unit, '(a,es10.3)') '              tol ', s%tol
            end if
        else
            write (unit, '(a,a,a,i0,a,i0,a,i0,a,es10.3,a,es10.3)') ' solver       ', trim(s%solver), ':  iterations ', &
                s%iterations, ' (outer ', s%outer_iterations, ')   matvecs ', s%matvecs, '   residual ', s%residual, &
                '   tol ', s%tol
        end if
        if (s%work_units >= 0) then
            if (len_trim(s%cycle) > 0) then
                write (unit, '(a,f10.2,a,f8.5,a)') '              work units ', s%work_units, '   convergence factor ', &
                    s%convergence_factor, '   cycle '//trim(s%cycle)
            else
                write (unit, '(a,f10.2,a,f8.5)') '              work units ', s%work_units, '   convergence factor ', &
                    s%convergence_factor
            end if
        end if
        if (s%status == 'converged') then
            write (unit, '(a)') ' status       converged'
        else
            write (unit, '(a)') ' status       *** '//trim(upper(s%status))//' ***  '//trim(s%message)
            if (s%status /= 'error') write (unit, '(a)') '              *** NOT CONVERGED: the results of this case are '// &
                'not a solution to the requested tolerance ***'
        end if
        if (s%solver_normal == 'none') then
            write (unit, '(a,f10.4,a,f10.4,a)') ' cpu time     ', s%cpu_seconds, ' s  (solver incl. set-up ', &
                s%cpu_seconds_tangential, ' s)'
        else
            write (unit, '(a,f10.4,a,f10.4,a,f10.4,a)') ' cpu time     ', s%cpu_seconds, ' s  (normal ', &
                s%cpu_seconds_normal, ' s, of which operator set-up ', s%setup_seconds, ' s)'
        end if
        if (s%tangential) write (unit, '(a,f10.4,a,f10.4,a)') '              tangential ', s%cpu_seconds_tangential, &
            ' s, of which operator set-up ', s%setup_seconds_tangential, ' s'
        if (allocated(s%notes)) then
            if (len_trim(s%notes) > 0) write (unit, '(a)') ' note         '//trim(s%notes)
        end if
        call write_auto_report(unit, s)
        if (present(state)) then
            if (size(state) > 0) then
                call state_map(state, lines, sx, sy)
                if (sx > 1 .or. sy > 1) then
                    write (unit, '(a,i0,a,i0,a)') ' adhesion/slip (y up, x right; subsampled: one character per ', sx, &
                        ' x ', sy, " elements; 'A' adhesion, 'S' slip by majority, lower case: block partly in contact,"// &
                        " '.' exterior)"
                else
                    write (unit, '(a)') " adhesion/slip (y up, x right; one character per element, 'A' adhesion, 'S' slip, "// &
                        "'.' exterior)"
                end if
                do j = 1, size(lines)
                    write (unit, '(3x,a)') lines(j)
                end do
            end if
        else if (size(pn) > 0) then
            call contact_map(pn, lines, sx, sy)
            if (sx > 1 .or. sy > 1) then
                write (unit, '(a,i0,a,i0,a)') ' contact area (y up, x right; subsampled: one character per ', sx, &
                    ' x ', sy, " elements, '*' >= half in contact, '+' partly, '.' none)"
            else
                write (unit, '(a)') " contact area (y up, x right; one character per element, '*' contact, '.' exterior)"
            end if
            do j = 1, size(lines)
                write (unit, '(3x,a)') lines(j)
            end do
        end if
        write (unit, '(a)') ''
    end subroutine write_case_report

    !> The automatic layer's part of the report: model, reductions, grids visited with the
    !! error estimates and their cost, warnings (loud).
    subroutine write_auto_report(unit, s)
        integer, intent(in) :: unit
        type(fc_case_summary), intent(in) :: s
        integer :: k
        if (s%outcome%grid_auto) then
            write (unit, '(a)') ' model        '//trim(s%outcome%model)//' (potential area sized automatically)'
        else
            write (unit, '(a)') ' model        '//trim(s%outcome%model)
        end if
        if (allocated(s%outcome%reductions)) then
            do k = 1, size(s%outcome%reductions)
                write (unit, '(a)') ' reduction    '//trim(s%outcome%reductions(k))
            end do
        end if
        if (s%outcome%target > 0 .and. allocated(s%outcome%levels)) then
            write (unit, '(a,es10.3,a)') ' accuracy     target ', s%outcome%target, ' (relative error of '// &
                trim(s%outcome%quantities)//')'
            write (unit, '(a)') '              grid            fn               approach         pmax          '// &
                'estimate    ratio   seconds'
            do k = 1, size(s%outcome%levels)
                associate (l => s%outcome%levels(k))
                    write (unit, '(14x,i5,a,i5,3(1x,es16.8),1x,es10.3,1x,f7.2,1x,f9.4,a)') l%nx, ' x', l%ny, l%fn, &
                        l%approach, l%pmax, l%estimate, l%ratio, l%seconds, trim(merge('             ', ' non-monotone', &
                        l%monotone))
                end associate
            end do
            write (unit, '(a,es10.3,a,a,a,f9.4,a)') '              estimate ', s%outcome%estimate, '  target ', &
                trim(merge('met    ', 'NOT MET', s%outcome%target_met)), '   all grids ', s%outcome%total_seconds, ' s'
            if (s%outcome%sufficient > 0) write (unit, '(a,i0,a,i0,a,es10.3,a)') '              coarsest grid '// &
                'meeting the target: ', s%outcome%levels(s%outcome%sufficient)%nx, ' x ', &
                s%outcome%levels(s%outcome%sufficient)%ny, ' (error bound ', s%outcome%sufficient_bound, &
                ', certified by the finest grid; use it for further solves of this scene)'
        end if
        if (s%outcome%has_cattaneo) write (unit, '(a,3(a,es12.5))') ' Cattaneo     ', 'a = ', s%outcome%cattaneo%a, &
            '   c = ', s%outcome%cattaneo%c, '   shift = ', s%outcome%cattaneo%shift
        if (allocated(s%outcome%warnings)) then
            do k = 1, size(s%outcome%warnings)
                write (unit, '(a)') ' *** WARNING  '//trim(s%outcome%warnings(k))
            end do
        end if
    end subroutine write_auto_report

end module fc_output
