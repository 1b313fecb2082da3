!> Flat, handle-based "legacy-style" API for multibody codes (SPEC §6).
!!
!! Every routine has a `bind(C)` name, takes its arguments by reference (plain `int`,
!! `double` and explicit-size arrays) and ends with an integer error code `ierr`, so it can
!! be called from Fortran (with or without this module's interfaces), from C and from
!! Python ctypes.  A contact problem lives behind an integer handle:
!!
!! ```
!! fc_init → fc_set_material → fc_set_grid → fc_set_gap_quadratic | fc_set_gap_array
!!         → fc_set_normal_force | fc_set_normal_approach
!!         [→ fc_set_friction → fc_set_shifts | fc_set_forces] [→ fc_set_solver, fc_set_transient]
!!         → fc_calculate → fc_get_* … (repeat set/calculate every time step) → fc_finalize
!! ```
!!
!! Error codes (`ierr`): see the `FCL_*` constants below and doc/legacy_api.md.  A failing
!! call leaves a message naming the routine and the offending value, retrievable with
!! [[fc_get_error_message]] (for an invalid handle: with any handle, e.g. 0).
!!
!! Reuse: the influence operators (kernels and FFT plans) of a handle are kept while the
!! grid size/spacing and the material are unchanged; the previous solution warm-starts the
!! next call and, in the transient modes, is the previous state (u', p') of the step.
!!
!! The registry of handles is the only mutable module state.  Slots hold pointers, so
!! growing the registry never copies an operator (FFTW plans stay with their buffers).
module fc_legacy
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_null_char
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
    use fc_kinds
    use fc_geometry
    use fc_influence
    use fc_norm
    use fc_tangcg
    implicit none
    private

    !> Error codes returned in `ierr`.
    integer(c_int), parameter, public :: FCL_OK = 0              !! success
    integer(c_int), parameter, public :: FCL_INVALID_HANDLE = 1  !! handle not initialised or finalised
    integer(c_int), parameter, public :: FCL_ORDER = 2           !! wrong call order / required data missing
    integer(c_int), parameter, public :: FCL_INVALID_VALUE = 3   !! argument out of range (message names it)
    integer(c_int), parameter, public :: FCL_NOT_CONVERGED = 4   !! solver stopped before the tolerance
    integer(c_int), parameter, public :: FCL_DIVERGED = 5        !! solver diverged / non-physical state
    integer(c_int), parameter, public :: FCL_ARRAY_SIZE = 6      !! caller's array smaller than nx·ny
    integer(c_int), parameter, public :: FCL_INTERNAL = 7        !! unexpected internal error

    !> Transient modes of [[fc_set_transient]].
    integer(c_int), parameter, public :: FCL_FROM_REST = 0   !! u' = 0: every call is a steady (static) problem
    integer(c_int), parameter, public :: FCL_CONTINUE = 1    !! u', p' = previous step (shift sequence)
    integer(c_int), parameter, public :: FCL_ROLLING = 2     !! u', p' = previous step moved by the rolling step

    integer, parameter :: GAP_NONE = 0, GAP_ARRAY = 1, GAP_QUADRATIC = 2
    integer, parameter :: TANG_NONE = 0, TANG_SHIFTS = 1, TANG_FORCES = 2
    integer, parameter :: max_rounds = 50   !! Panagiotopoulos rounds (dissimilar materials)

    !> State of one contact problem behind a handle.
    type :: legacy_state
        ! --- input ---
        logical :: has_material = .false., has_grid = .false., has_normal = .false., has_friction = .false.
        type(fc_material) :: mat
        type(fc_grid) :: grid
        integer :: gap_kind = GAP_NONE
        real(dp), allocatable :: h0(:, :)          !! undeformed distance (GAP_ARRAY)
        real(dp) :: rx = 0, ry = 0                 !! radii (GAP_QUADRATIC)
        logical :: force_mode = .false.
        real(dp) :: approach = 0, fn = 0
        real(dp) :: mu = 0
        integer :: tang_kind = TANG_NONE
        real(dp) :: xi = 0, eta = 0, phi = 0, fx = 0, fy = 0
        type(fc_normal_settings) :: ns
        type(fc_tangential_settings) :: ts
        integer :: transient = FCL_FROM_REST
        real(dp) :: dq = 0
        logical :: reuse_operators = .true., warm_start = .true.
        ! --- reusable operators ---
        type(fc_normal_operator) :: nop
        type(fc_tangential_operator) :: top
        logical :: nop_ok = .false., top_ok = .false.
        integer :: rebuilds_normal = 0, rebuilds_tangential = 0, calculations = 0
        ! --- previous state (warm start, u' and p' of transient steps) ---
        logical :: has_prev_n = .false., has_prev_t = .false.
        real(dp), allocatable :: pn_prev(:, :), px_prev(:, :), py_prev(:, :), ux_prev(:, :), uy_prev(:, :)
        integer, allocatable :: st_prev(:, :)       !! element status of the previous state
        real(dp) :: xi_prev = 0, eta_prev = 0, fx_prev = 0, fy_prev = 0
        ! --- results of the last calculation ---
        logical :: has_result = .false., tang_solved = .false.
        real(dp), allocatable :: pn(:, :), gap(:, :), px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer, allocatable :: status(:, :)
        real(dp) :: r_fn = 0, r_fx = 0, r_fy = 0, r_mz = 0, r_approach = 0, r_pmax = 0
        real(dp) :: r_xi = 0, r_eta = 0, r_phi = 0
        integer :: r_ncon = 0, r_nadh = 0, r_nslip = 0, r_it_n = 0, r_it_t = 0, r_rounds = 0
        ! --- last error ---
        character(len=msg_len) :: message = ''
    end type legacy_state

    type :: state_slot
        type(legacy_state), pointer :: s => null()
    end type state_slot

    !> Handle registry; slot 0 keeps the message of calls with an invalid handle.
    type(state_slot), allocatable, save :: registry(:)

    public :: fc_init, fc_finalize, fc_set_material, fc_set_grid, fc_set_gap_array, fc_set_gap_quadratic
    public :: fc_set_normal_approach, fc_set_normal_force, fc_set_friction, fc_set_shifts, fc_set_forces
    public :: fc_set_solver, fc_set_transient, fc_set_rolling_step, fc_set_reuse, fc_calculate
    public :: fc_get_forces, fc_get_approach, fc_get_pmax, fc_get_shifts, fc_get_contact_stats
    public :: fc_get_tractions, fc_get_slip, fc_get_gap, fc_get_status_array, fc_get_iterations
    public :: fc_get_rebuilds, fc_get_grid_size, fc_get_error_message, fc_get_nhandles
    public :: shift_along_x

contains

    ! =====================================================================================
    ! registry helpers
    ! =====================================================================================

    !> Make sure slot 0 (registry messages) exists.
    subroutine ensure_registry()
        if (.not. allocated(registry)) then
            allocate (registry(0:7))
            allocate (registry(0)%s)
        end if
    end subroutine ensure_registry

    !> Pointer to the state of `handle`, or an FCL_INVALID_HANDLE error in slot 0.
    subroutine lookup(handle, caller, s, ierr)
        integer(c_int), intent(in) :: handle
        character(len=*), intent(in) :: caller
        type(legacy_state), pointer, intent(out) :: s
        integer(c_int), intent(out) :: ierr
        call ensure_registry()
        s => null()
        ierr = FCL_OK
        if (handle >= 1 .and. handle <= ubound(registry, 1)) s => registry(handle)%s
        if (.not. associated(s)) then
            ierr = FCL_INVALID_HANDLE
            write (registry(0)%s%message, '(a,i0,a)') trim(caller)//': invalid handle ', handle, &
                ' (not initialised by fc_init or already finalised)'
        end if
    end subroutine lookup

    !> Record an error on a state.
    subroutine fail(s, ierr, code, msg)
        type(legacy_state), intent(inout) :: s
        integer(c_int), intent(out) :: ierr
        integer(c_int), intent(in) :: code
        character(len=*), intent(in) :: msg
        ierr = code
        s%message = msg
    end subroutine fail

    !> Format a real for messages.
    function num(x) result(str)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: str
        character(len=32) :: buf
        write (buf, '(g0.6)') x
        str = trim(adjustl(buf))
    end function num

    !> Format an integer for messages.
    function inum(i) result(str)
        integer, intent(in) :: i
        character(len=:), allocatable :: str
        character(len=16) :: buf
        write (buf, '(i0)') i
        str = trim(buf)
    end function inum

    logical function finite(x)
        real(dp), intent(in) :: x
        finite = ieee_is_finite(x)
    end function finite

    ! =====================================================================================
    ! life cycle
    ! =====================================================================================

    !> Create a contact problem; `handle` ≥ 1 on success.  Slots of finalised handles are
    !! reused (lowest first).
    subroutine fc_init(handle, ierr) bind(C, name='fc_init')
        integer(c_int), intent(out) :: handle   !! new handle
        integer(c_int), intent(out) :: ierr     !! error code
        type(state_slot), allocatable :: bigger(:)
        integer :: i, n
        call ensure_registry()
        handle = 0
        do i = 1, ubound(registry, 1)
            if (.not. associated(registry(i)%s)) then
                handle = i; exit
            end if
        end do
        if (handle == 0) then
            n = ubound(registry, 1)
            allocate (bigger(0:2*n + 1))
            bigger(0:n) = registry(0:n)          ! copies pointers only
            call move_alloc(bigger, registry)
            handle = n + 1
        end if
        allocate (registry(handle)%s)
        ierr = FCL_OK
    end subroutine fc_init

    !> Release a handle (operators, FFT plans, arrays); `handle` is set to 0.
    subroutine fc_finalize(handle, ierr) bind(C, name='fc_finalize')
        integer(c_int), intent(inout) :: handle  !! handle to release; 0 on return
        integer(c_int), intent(out) :: ierr      !! error code
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_finalize', s, ierr)
        if (ierr /= FCL_OK) return
        call s%nop%destroy()
        call s%top%destroy()
        deallocate (s)
        registry(handle)%s => null()
        handle = 0
    end subroutine fc_finalize

    !> Number of handles currently in use (leak checks in tests and host codes).
    subroutine fc_get_nhandles(nhandles, ierr) bind(C, name='fc_get_nhandles')
        integer(c_int), intent(out) :: nhandles  !! live handles
        integer(c_int), intent(out) :: ierr      !! error code (always 0)
        integer :: i
        call ensure_registry()
        nhandles = 0
        do i = 1, ubound(registry, 1)
            if (associated(registry(i)%s)) nhandles = nhandles + 1
        end do
        ierr = FCL_OK
    end subroutine fc_get_nhandles

    ! =====================================================================================
    ! input
    ! =====================================================================================

    !> Elastic constants of body 1 and 2 [N/mm²]; g ≥ 1e29 is a rigid body.  Changing the
    !! combined constants rebuilds the operators at the next calculation.
    subroutine fc_set_material(handle, g1, g2, nu1, nu2, ierr) bind(C, name='fc_set_material')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: g1, g2    !! shear moduli [N/mm²]
        real(c_double), intent(in) :: nu1, nu2  !! Poisson ratios, 0 ≤ ν < 0.5
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        type(fc_material) :: m
        integer :: stat
        character(len=msg_len) :: msg
        call lookup(handle, 'fc_set_material', s, ierr)
        if (ierr /= FCL_OK) return
        m%g1 = g1; m%g2 = g2; m%nu1 = nu1; m%nu2 = nu2
        call combine_material(m, stat, msg)
        if (stat /= 0) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_material: '//trim(msg)); return
        end if
        s%mat = m
        s%has_material = .true.
    end subroutine fc_set_material

    !> Potential contact area [xmin,xmax]×[ymin,ymax] [mm] with nx×ny elements.  A changed
    !! element count or size rebuilds the operators and drops the previous state; moving
    !! the area with unchanged nx, ny, dx, dy keeps both.  An array gap must be set again.
    subroutine fc_set_grid(handle, nx, ny, xmin, xmax, ymin, ymax, ierr) bind(C, name='fc_set_grid')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: nx, ny                  !! elements in x and y
        real(c_double), intent(in) :: xmin, xmax, ymin, ymax  !! outer edges [mm]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        type(fc_grid) :: g
        integer :: stat
        character(len=msg_len) :: msg
        call lookup(handle, 'fc_set_grid', s, ierr)
        if (ierr /= FCL_OK) return
        if (nx > 4096 .or. ny > 4096) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_grid: nx = '//inum(nx)//', ny = '//inum(ny)// &
                ' exceeds the limit 4096'); return
        end if
        call make_grid(g, nx, ny, xmin, xmax, ymin, ymax, stat, msg)
        if (stat /= 0 .or. .not. (finite(xmin) .and. finite(xmax) .and. finite(ymin) .and. finite(ymax))) then
            if (stat == 0) msg = 'grid: xmin, xmax, ymin, ymax must be finite'
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_grid: '//trim(msg)); return
        end if
        if (s%has_grid) then
            if (same_spacing(s%grid, g)) then
                if (s%gap_kind == GAP_ARRAY .and. .not. same_area(s%grid, g)) s%gap_kind = GAP_NONE
            else
                s%has_prev_n = .false.; s%has_prev_t = .false.
                if (s%gap_kind == GAP_ARRAY) s%gap_kind = GAP_NONE
                s%has_result = .false.
            end if
        end if
        s%grid = g
        s%has_grid = .true.
    end subroutine fc_set_grid

    !> Same element count and size (relative 1e−12): the operators can be reused.
    pure logical function same_spacing(a, b)
        type(fc_grid), intent(in) :: a, b
        same_spacing = a%nx == b%nx .and. a%ny == b%ny .and. abs(a%dx - b%dx) <= 1e-12_dp*b%dx &
            .and. abs(a%dy - b%dy) <= 1e-12_dp*b%dy
    end function same_spacing

    pure logical function same_area(a, b)
        type(fc_grid), intent(in) :: a, b
        same_area = same_spacing(a, b) .and. a%xmin == b%xmin .and. a%ymin == b%ymin
    end function same_area

    !> Undeformed distance h0 [mm] per element, x running fastest (h0(ix + (iy−1)·nx)),
    !! without the approach.  Requires the grid; n must equal nx·ny.  Values ≥ 1e20 keep an
    !! element out of contact.
    subroutine fc_set_gap_array(handle, n, h0, ierr) bind(C, name='fc_set_gap_array')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n          !! number of values, nx·ny
        real(c_double), intent(in) :: h0(*)      !! undeformed distance [mm]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        integer :: k
        call lookup(handle, 'fc_set_gap_array', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. s%has_grid) then
            call fail(s, ierr, FCL_ORDER, 'fc_set_gap_array: call fc_set_grid first'); return
        end if
        if (n /= s%grid%n()) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_gap_array: n = '//inum(n)//' but the grid has nx*ny = ' &
                //inum(s%grid%n())//' elements'); return
        end if
        do k = 1, n
            if (ieee_is_nan(h0(k))) then
                call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_gap_array: h0('//inum(k)//') is NaN'); return
            end if
        end do
        s%h0 = reshape(h0(1:n), [s%grid%nx, s%grid%ny])
        s%gap_kind = GAP_ARRAY
    end subroutine fc_set_gap_array

    !> Quadratic undeformed distance h0 = x²/(2 rx) + y²/(2 ry) [mm], re-evaluated on the
    !! current grid at each calculation; a radius ≤ 0 means flat in that direction.
    subroutine fc_set_gap_quadratic(handle, rx, ry, ierr) bind(C, name='fc_set_gap_quadratic')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: rx, ry   !! relative radii of curvature [mm]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_gap_quadratic', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. (finite(rx) .and. finite(ry)) .or. .not. (rx > 0 .or. ry > 0)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_gap_quadratic: rx = '//num(rx)//', ry = '//num(ry)// &
                ': at least one radius must be > 0 and both finite'); return
        end if
        s%rx = rx; s%ry = ry
        s%gap_kind = GAP_QUADRATIC
    end subroutine fc_set_gap_quadratic

    !> Prescribe the approach δ [mm] (the gap is h0 − δ).
    subroutine fc_set_normal_approach(handle, approach, ierr) bind(C, name='fc_set_normal_approach')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: approach  !! approach δ [mm]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_normal_approach', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. finite(approach)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_normal_approach: approach = '//num(approach)// &
                ' is not finite'); return
        end if
        s%approach = approach; s%force_mode = .false.; s%has_normal = .true.
    end subroutine fc_set_normal_approach

    !> Prescribe the total normal force Fn > 0 [N].
    subroutine fc_set_normal_force(handle, fn, ierr) bind(C, name='fc_set_normal_force')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: fn   !! total normal force [N]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_normal_force', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. (fn > 0 .and. finite(fn))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_normal_force: fn = '//num(fn)//' must be > 0'); return
        end if
        s%fn = fn; s%force_mode = .true.; s%has_normal = .true.
    end subroutine fc_set_normal_force

    !> Coefficient of friction μ ≥ 0 (required before a tangential problem is solved).
    subroutine fc_set_friction(handle, mu, ierr) bind(C, name='fc_set_friction')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: mu   !! coefficient of friction
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_friction', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. (mu >= 0 .and. finite(mu))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_friction: mu = '//num(mu)//' must be >= 0'); return
        end if
        s%mu = mu; s%has_friction = .true.
    end subroutine fc_set_friction

    !> Prescribe the rigid shift (ξ, η) [mm] and spin φ [rad] of body 1 relative to body 2.
    !! Transient modes: these are the increments of the current step (the rigid slip over
    !! the step).  Switches the tangential problem on.
    subroutine fc_set_shifts(handle, xi, eta, phi, ierr) bind(C, name='fc_set_shifts')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: xi, eta   !! shifts [mm]
        real(c_double), intent(in) :: phi       !! spin shift [rad]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_shifts', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. (finite(xi) .and. finite(eta) .and. finite(phi))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_shifts: xi = '//num(xi)//', eta = '//num(eta)//', phi = ' &
                //num(phi)//' must be finite'); return
        end if
        s%xi = xi; s%eta = eta; s%phi = phi; s%tang_kind = TANG_SHIFTS
    end subroutine fc_set_shifts

    !> Prescribe the total tangential forces (Fx, Fy) [N] on body 1, |F| < μ·Fn, and the
    !! spin φ [rad] (an increment in the transient modes).  Switches the tangential problem on.
    subroutine fc_set_forces(handle, fx, fy, phi, ierr) bind(C, name='fc_set_forces')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: fx, fy    !! tangential forces [N]
        real(c_double), intent(in) :: phi       !! spin shift [rad]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_forces', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. (finite(fx) .and. finite(fy) .and. finite(phi))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_forces: fx = '//num(fx)//', fy = '//num(fy)//', phi = ' &
                //num(phi)//' must be finite'); return
        end if
        s%fx = fx; s%fy = fy; s%phi = phi; s%tang_kind = TANG_FORCES
    end subroutine fc_set_forces

    !> Solver choice and tolerances.  normal_solver: 0 or 1 = BCCG, 2 = NORM; tangential_solver:
    !! 0 or 1 = TangCG, 2 = ConvexGS; tol > 0 (both problems); maxit ≥ 1; inner_k ≥ 1
    !! (TangCG); precondition 0/1 (BCCG and TangCG).
    subroutine fc_set_solver(handle, normal_solver, tangential_solver, tol, maxit, inner_k, precondition, ierr) &
        bind(C, name='fc_set_solver')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: normal_solver, tangential_solver
        real(c_double), intent(in) :: tol
        integer(c_int), intent(in) :: maxit, inner_k, precondition
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_solver', s, ierr)
        if (ierr /= FCL_OK) return
        if (normal_solver < 0 .or. normal_solver > 2) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: normal_solver = '//inum(normal_solver)// &
                ' is not 0/1 (BCCG) or 2 (NORM)'); return
        end if
        if (tangential_solver < 0 .or. tangential_solver > 2) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: tangential_solver = '//inum(tangential_solver)// &
                ' is not 0/1 (TangCG) or 2 (ConvexGS)'); return
        end if
        if (.not. (tol > 0 .and. tol < 1)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: tol = '//num(tol)//' must lie in (0, 1)'); return
        end if
        if (maxit < 1) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: maxit = '//inum(maxit)//' must be >= 1'); return
        end if
        if (inner_k < 1) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: inner_k = '//inum(inner_k)//' must be >= 1'); return
        end if
        if (precondition /= 0 .and. precondition /= 1) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: precondition = '//inum(precondition)// &
                ' must be 0 or 1'); return
        end if
        s%ns%solver = merge('norm    ', 'bccg    ', normal_solver == 2)
        s%ts%solver = merge('convexgs', 'tangcg  ', tangential_solver == 2)
        s%ns%tol = tol; s%ts%tol = tol
        s%ns%maxit = maxit; s%ts%maxit = maxit
        s%ts%inner_k = inner_k
        s%ns%precondition = precondition == 1
        s%ts%precondition = precondition == 1
    end subroutine fc_set_solver

    !> Transient mode: 0 from rest (u' = 0), 1 continue from the previous step's u' and p',
    !! 2 rolling (u', p' of the previous step moved by the rolling step, [[fc_set_rolling_step]]).
    subroutine fc_set_transient(handle, mode, ierr) bind(C, name='fc_set_transient')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: mode   !! 0, 1 or 2
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_transient', s, ierr)
        if (ierr /= FCL_OK) return
        if (mode < 0 .or. mode > 2) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_transient: mode = '//inum(mode)// &
                ' is not 0 (from rest), 1 (continue) or 2 (rolling)'); return
        end if
        s%transient = mode
    end subroutine fc_set_transient

    !> Rolling step dq [mm] of mode 2: the contact area moves by dq along +x relative to the
    !! material, so the previous state is sampled at x + dq (linear interpolation between
    !! element centres; material entering the grid is undeformed).
    subroutine fc_set_rolling_step(handle, dq, ierr) bind(C, name='fc_set_rolling_step')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: dq   !! rolling step [mm]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_rolling_step', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. finite(dq)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_rolling_step: dq = '//num(dq)//' is not finite'); return
        end if
        s%dq = dq
    end subroutine fc_set_rolling_step

    !> Reuse switches (both 1 by default): reuse_operators = 0 rebuilds kernels and FFT plans
    !! at every calculation; warm_start = 0 starts every solve from zero tractions (the
    !! transient state u', p' is still used in modes 1 and 2).  For benchmarks and checks.
    subroutine fc_set_reuse(handle, reuse_operators, warm_start, ierr) bind(C, name='fc_set_reuse')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: reuse_operators, warm_start   !! 0 or 1
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_reuse', s, ierr)
        if (ierr /= FCL_OK) return
        if (reuse_operators /= 0 .and. reuse_operators /= 1 .or. warm_start /= 0 .and. warm_start /= 1) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_reuse: reuse_operators = '//inum(reuse_operators)// &
                ', warm_start = '//inum(warm_start)//' must be 0 or 1'); return
        end if
        s%reuse_operators = reuse_operators == 1
        s%warm_start = warm_start == 1
    end subroutine fc_set_reuse

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
        call lookup(handle, 'fc_calculate', s, ierr)
        if (ierr /= FCL_OK) return
        call calculate(s, ierr)
    end subroutine fc_calculate

    subroutine calculate(s, ierr)
        type(legacy_state), intent(inout) :: s
        integer(c_int), intent(out) :: ierr
        real(dp), allocatable :: h0(:, :), uzt(:, :), uxn(:, :), uyn(:, :), uxp(:, :), uyp(:, :), pxs(:, :), pys(:, :)
        real(dp), allocatable :: ox(:, :), oy(:, :), pn_old(:, :), px_old(:, :), py_old(:, :)
        type(fc_normal_result) :: nres
        type(fc_tangential_result) :: tres
        type(fc_tangential_loading) :: load
        integer :: stat, nx, ny, round
        character(len=msg_len) :: msg
        logical :: tangential, coupled, lift_slip
        real(dp) :: cx, cy, k0, a, dn, dt
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
        tangential = s%tang_kind /= TANG_NONE
        if (tangential .and. .not. s%has_friction) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: shifts or forces set but no friction (call fc_set_friction)')
            return
        end if
        nx = s%grid%nx; ny = s%grid%ny
        s%has_result = .false.
        ! --- operators: rebuilt only when grid spacing or material changed ---
        if (.not. s%reuse_operators) then
            s%nop_ok = .false.; s%top_ok = .false.
        end if
        if (s%nop_ok) s%nop_ok = same_spacing(s%nop%grid, s%grid) .and. same_material(s%nop%material, s%mat)
        if (.not. s%nop_ok) then
            call build_normal_operator(s%nop, s%mat, s%grid)
            s%rebuilds_normal = s%rebuilds_normal + 1
            s%nop_ok = .true.
        end if
        s%nop%grid = s%grid
        if (tangential) then
            if (s%top_ok) s%top_ok = same_spacing(s%top%grid, s%grid) .and. same_material(s%top%material, s%mat)
            if (.not. s%top_ok) then
                call build_tangential_operator(s%top, s%mat, s%grid)
                s%rebuilds_tangential = s%rebuilds_tangential + 1
                s%top_ok = .true.
            end if
            s%top%grid = s%grid          ! coordinates of a moved area (same spacing)
        end if
        coupled = tangential .and. s%mat%k /= 0
        ! --- undeformed distance ---
        if (s%gap_kind == GAP_QUADRATIC) then
            h0 = quadratic_gap(s%grid, s%rx, s%ry)
        else
            h0 = s%h0
        end if
        allocate (uzt(nx, ny), uxn(nx, ny), uyn(nx, ny))
        uzt = 0; uxn = 0; uyn = 0
        ! --- previous state u', p' of the step ---
        allocate (uxp(nx, ny), uyp(nx, ny), pxs(nx, ny), pys(nx, ny))
        uxp = 0; uyp = 0; pxs = 0; pys = 0
        lift_slip = .false.
        if (tangential .and. s%has_prev_t) then
            select case (s%transient)
            case (FCL_CONTINUE)
                uxp = s%ux_prev; uyp = s%uy_prev
                pxs = s%px_prev; pys = s%py_prev
            case (FCL_ROLLING)
                call shift_along_x(s%ux_prev, s%dq/s%grid%dx, uxp)
                call shift_along_x(s%uy_prev, s%dq/s%grid%dx, uyp)
                call shift_along_x(s%px_prev, s%dq/s%grid%dx, pxs)
                call shift_along_x(s%py_prev, s%dq/s%grid%dx, pys)
            case default
                if (s%warm_start) then
                    pxs = s%px_prev; pys = s%py_prev
                end if
            end select
            lift_slip = s%transient /= FCL_ROLLING .and. (s%warm_start .or. s%transient == FCL_CONTINUE)
        end if
        if (s%transient == FCL_FROM_REST .and. .not. s%warm_start) then
            pxs = 0; pys = 0
        end if
        ! --- normal (+ tangential) solve; Panagiotopoulos rounds only for K ≠ 0 ---
        allocate (pn_old(nx, ny), px_old(nx, ny), py_old(nx, ny))
        s%r_it_n = 0; s%r_it_t = 0
        do round = 1, max_rounds
            s%r_rounds = round
            if (round == 1 .and. .not. (s%warm_start .and. s%has_prev_n)) then
                call normal_solve(h0 + uzt)
            else if (round == 1) then
                call normal_solve(h0 + uzt, s%pn_prev)
            else
                pn_old = nres%pn
                call normal_solve(h0 + uzt, pn_old)
            end if
            if (stat /= 0) then
                call fail(s, ierr, FCL_INVALID_VALUE, 'fc_calculate: '//trim(msg)); return
            end if
            s%r_it_n = s%r_it_n + nres%iterations
            if (nres%status /= FC_CONVERGED) exit
            if (.not. tangential) exit
            if (coupled) call coupling_displacements(s%top, nres%pn, pxs, pys, uxn, uyn, uzt)
            if (round > 1) then
                px_old = tres%px; py_old = tres%py
            end if
            if (round == 1 .and. lift_slip) call lift_slip_start(nres%pn)
            ox = uxn; oy = uyn
            if (s%tang_kind == TANG_SHIFTS) then
                call solve_tangential(s%top, nres%pn, s%mu, s%ts, tres, stat, msg, s%xi, s%eta, s%phi, &
                                      ux_prev=uxp, uy_prev=uyp, px_start=pxs, py_start=pys, offset_x=ox, offset_y=oy)
                cx = 0; cy = 0
            else
                ! Start the force loop from the predicted shift: the previous shift (mode 0) or
                ! zero increment (modes 1, 2) corrected by the force change over the initial
                ! stiffness k0 = 8Ga/(2−ν).  The library's loop starts at −F/k0, so the guess
                ! enters as a constant slip offset c and the shift used is ξ + c.
                a = sqrt(count(nres%pn > 0)*s%grid%area()/pi)
                k0 = 8*s%mat%g*a/(2 - s%mat%nu)
                if (s%transient == FCL_FROM_REST .and. s%has_prev_t .and. s%warm_start) then
                    cx = s%xi_prev - (s%fx - s%fx_prev)/k0 + s%fx/k0
                    cy = s%eta_prev - (s%fy - s%fy_prev)/k0 + s%fy/k0
                else if (s%transient /= FCL_FROM_REST .and. s%has_prev_t) then
                    cx = -(s%fx - s%fx_prev)/k0 + s%fx/k0
                    cy = -(s%fy - s%fy_prev)/k0 + s%fy/k0
                else
                    cx = 0; cy = 0
                end if
                ox = ox + cx; oy = oy + cy
                load%mu = s%mu; load%fx = s%fx; load%fy = s%fy; load%phi = s%phi; load%force_prescribed = .true.
                call solve_tangential_loading(s%top, nres%pn, load, s%ts, tres, stat, msg, ux_prev=uxp, uy_prev=uyp, &
                                              px_start=pxs, py_start=pys, offset_x=ox, offset_y=oy)
            end if
            if (stat /= 0) then
                call fail(s, ierr, FCL_INVALID_VALUE, 'fc_calculate: '//trim(msg)); return
            end if
            tres%xi = tres%xi + cx; tres%eta = tres%eta + cy
            s%r_it_t = s%r_it_t + tres%iterations
            if (.not. coupled .or. tres%status /= FC_CONVERGED) exit
            pxs = tres%px; pys = tres%py
            call coupling_displacements(s%top, nres%pn, tres%px, tres%py, uxn, uyn, uzt)
            if (round > 1) then
                dn = sqrt(sum((nres%pn - pn_old)**2)/max(sum(nres%pn**2), tiny(1.0_dp)))
                dt = sqrt(sum((tres%px - px_old)**2 + (tres%py - py_old)**2)/max(sum(tres%px**2 + tres%py**2), tiny(1.0_dp)))
                if (max(dn, dt) < 10*max(s%ns%tol, s%ts%tol)) exit
            end if
            if (round == max_rounds) then
                tres%status = FC_NOT_CONVERGED
                tres%message = 'Panagiotopoulos process not converged in 50 rounds'
            end if
        end do
        s%calculations = s%calculations + 1
        ! --- results ---
        s%pn = nres%pn; s%gap = nres%gap
        s%r_fn = nres%fn; s%r_approach = nres%approach; s%r_pmax = nres%pmax
        s%tang_solved = tangential .and. allocated(tres%px)
        if (s%tang_solved) then
            s%px = tres%px; s%py = tres%py; s%sx = tres%sx; s%sy = tres%sy
            s%status = tres%state
            s%r_fx = tres%fx; s%r_fy = tres%fy; s%r_mz = tres%mz
            s%r_xi = tres%xi; s%r_eta = tres%eta; s%r_phi = tres%phi
            s%r_ncon = tres%ncon; s%r_nadh = tres%nadh; s%r_nslip = tres%nslip
        else
            ! no tangential loading: zero tractions, full adhesion is the exact solution
            s%px = 0*nres%pn; s%py = s%px; s%sx = s%px; s%sy = s%px
            s%status = merge(EL_ADHESION, EL_EXTERIOR, nres%pn > 0)
            s%r_fx = 0; s%r_fy = 0; s%r_mz = 0; s%r_xi = 0; s%r_eta = 0; s%r_phi = 0
            s%r_ncon = nres%ncon; s%r_nadh = nres%ncon; s%r_nslip = 0
        end if
        s%has_result = .true.
        if (nres%status /= FC_CONVERGED) then
            call fail(s, ierr, status_code(nres%status), 'fc_calculate: normal problem: '//trim(nres%message))
            return
        end if
        if (s%tang_solved) then
            if (tres%status /= FC_CONVERGED) then
                call fail(s, ierr, status_code(tres%status), 'fc_calculate: tangential problem: '//trim(tres%message))
                return
            end if
        end if
        ! --- advance the previous state ---
        s%pn_prev = nres%pn; s%has_prev_n = .true.
        if (s%tang_solved) then
            s%px_prev = tres%px; s%py_prev = tres%py; s%st_prev = tres%state
            s%ux_prev = tres%ux + uxn; s%uy_prev = tres%uy + uyn
            s%xi_prev = tres%xi; s%eta_prev = tres%eta
            s%fx_prev = tres%fx; s%fy_prev = tres%fy
            s%has_prev_t = .true.
        end if
    contains
        !> Warm start: elements that slipped in the previous state start on the new traction
        !! bound (slightly outside, so that TangCG starts them in slip) in their previous
        !! direction; without this a converged start loses its subdivision to rounding.
        subroutine lift_slip_start(pn)
            real(dp), intent(in) :: pn(:, :)
            real(dp), allocatable :: mag(:, :)
            mag = hypot(pxs, pys)
            where (s%st_prev == EL_SLIP .and. mag > 0 .and. pn > 0)
                pxs = (1 + 1e-10_dp)*s%mu*pn*pxs/mag
                pys = (1 + 1e-10_dp)*s%mu*pn*pys/mag
            end where
        end subroutine lift_slip_start

        subroutine normal_solve(h, p_start)
            real(dp), intent(in) :: h(:, :)
            real(dp), intent(in), optional :: p_start(:, :)
            real(dp), allocatable :: p0(:, :)
            if (s%force_mode) then
                if (present(p_start)) then
                    ! fc_norm keeps the sum of a warm start in force mode: scale it to Fn
                    p0 = max(p_start, 0.0_dp)
                    if (sum(p0) > 0) p0 = p0*(s%fn/(sum(p0)*s%grid%area()))
                    call solve_normal(s%nop, h, s%ns, nres, stat, msg, fn=s%fn, p_start=p0)
                else
                    call solve_normal(s%nop, h, s%ns, nres, stat, msg, fn=s%fn)
                end if
            else
                call solve_normal(s%nop, h, s%ns, nres, stat, msg, approach=s%approach, p_start=p_start)
            end if
        end subroutine normal_solve
    end subroutine calculate

    pure logical function same_material(a, b)
        type(fc_material), intent(in) :: a, b
        same_material = a%g == b%g .and. a%nu == b%nu .and. a%k == b%k
    end function same_material

    pure integer(c_int) function status_code(status)
        integer, intent(in) :: status
        select case (status)
        case (FC_CONVERGED); status_code = FCL_OK
        case (FC_NOT_CONVERGED); status_code = FCL_NOT_CONVERGED
        case (FC_DIVERGED); status_code = FCL_DIVERGED
        case default; status_code = FCL_INTERNAL
        end select
    end function status_code

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

    ! =====================================================================================
    ! results
    ! =====================================================================================

    !> Lookup plus "a result exists".
    subroutine lookup_result(handle, caller, s, ierr)
        integer(c_int), intent(in) :: handle
        character(len=*), intent(in) :: caller
        type(legacy_state), pointer, intent(out) :: s
        integer(c_int), intent(out) :: ierr
        call lookup(handle, caller, s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. s%has_result) call fail(s, ierr, FCL_ORDER, caller//': no result (call fc_calculate first)')
    end subroutine lookup_result

    !> Array getters: n must be ≥ nx·ny; the first nx·ny entries are written, x fastest.
    subroutine check_size(s, caller, n, ierr)
        type(legacy_state), intent(inout) :: s
        character(len=*), intent(in) :: caller
        integer(c_int), intent(in) :: n
        integer(c_int), intent(out) :: ierr
        ierr = FCL_OK
        if (n < s%grid%n()) call fail(s, ierr, FCL_ARRAY_SIZE, caller//': n = '//inum(n)// &
            ' is smaller than nx*ny = '//inum(s%grid%n()))
    end subroutine check_size

    !> Total forces Fn, Fx, Fy [N] on body 1 and moment Mz = Σ(x·py − y·px)·dx·dy [N·mm].
    subroutine fc_get_forces(handle, fn, fx, fy, mz, ierr) bind(C, name='fc_get_forces')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: fn, fx, fy, mz
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        fn = 0; fx = 0; fy = 0; mz = 0
        call lookup_result(handle, 'fc_get_forces', s, ierr)
        if (ierr /= FCL_OK) return
        fn = s%r_fn; fx = s%r_fx; fy = s%r_fy; mz = s%r_mz
    end subroutine fc_get_forces

    !> Approach δ [mm] (prescribed or found for the prescribed force).
    subroutine fc_get_approach(handle, approach, ierr) bind(C, name='fc_get_approach')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: approach
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        approach = 0
        call lookup_result(handle, 'fc_get_approach', s, ierr)
        if (ierr /= FCL_OK) return
        approach = s%r_approach
    end subroutine fc_get_approach

    !> Maximum pressure [N/mm²].
    subroutine fc_get_pmax(handle, pmax, ierr) bind(C, name='fc_get_pmax')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: pmax
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        pmax = 0
        call lookup_result(handle, 'fc_get_pmax', s, ierr)
        if (ierr /= FCL_OK) return
        pmax = s%r_pmax
    end subroutine fc_get_pmax

    !> Rigid shift (ξ, η, φ) actually used, also when forces are prescribed (transient
    !! modes: the increment of the step).
    subroutine fc_get_shifts(handle, xi, eta, phi, ierr) bind(C, name='fc_get_shifts')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: xi, eta, phi
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        xi = 0; eta = 0; phi = 0
        call lookup_result(handle, 'fc_get_shifts', s, ierr)
        if (ierr /= FCL_OK) return
        xi = s%r_xi; eta = s%r_eta; phi = s%r_phi
    end subroutine fc_get_shifts

    !> Elements in contact, in adhesion and in slip.
    subroutine fc_get_contact_stats(handle, ncon, nadh, nslip, ierr) bind(C, name='fc_get_contact_stats')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: ncon, nadh, nslip
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        ncon = 0; nadh = 0; nslip = 0
        call lookup_result(handle, 'fc_get_contact_stats', s, ierr)
        if (ierr /= FCL_OK) return
        ncon = s%r_ncon; nadh = s%r_nadh; nslip = s%r_nslip
    end subroutine fc_get_contact_stats

    !> Pressure and tangential tractions [N/mm²] per element (x fastest).
    subroutine fc_get_tractions(handle, n, pn, px, py, ierr) bind(C, name='fc_get_tractions')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n          !! size of the caller's arrays, ≥ nx·ny
        real(c_double), intent(out) :: pn(*), px(*), py(*)
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        integer :: m
        call lookup_result(handle, 'fc_get_tractions', s, ierr)
        if (ierr /= FCL_OK) return
        call check_size(s, 'fc_get_tractions', n, ierr)
        if (ierr /= FCL_OK) return
        m = s%grid%n()
        pn(1:m) = reshape(s%pn, [m]); px(1:m) = reshape(s%px, [m]); py(1:m) = reshape(s%py, [m])
    end subroutine fc_get_tractions

    !> Slip s = w + u − u' [mm] per element (0 outside the contact area).
    subroutine fc_get_slip(handle, n, sx, sy, ierr) bind(C, name='fc_get_slip')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(out) :: sx(*), sy(*)
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        integer :: m
        call lookup_result(handle, 'fc_get_slip', s, ierr)
        if (ierr /= FCL_OK) return
        call check_size(s, 'fc_get_slip', n, ierr)
        if (ierr /= FCL_OK) return
        m = s%grid%n()
        sx(1:m) = reshape(s%sx, [m]); sy(1:m) = reshape(s%sy, [m])
    end subroutine fc_get_slip

    !> Deformed distance e = h0 − δ + A p [mm] per element (1e20 where contact is excluded).
    subroutine fc_get_gap(handle, n, gap, ierr) bind(C, name='fc_get_gap')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(out) :: gap(*)
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        integer :: m
        call lookup_result(handle, 'fc_get_gap', s, ierr)
        if (ierr /= FCL_OK) return
        call check_size(s, 'fc_get_gap', n, ierr)
        if (ierr /= FCL_OK) return
        m = s%grid%n()
        gap(1:m) = reshape(s%gap, [m])
    end subroutine fc_get_gap

    !> Element status: 0 exterior, 1 adhesion, 2 slip.
    subroutine fc_get_status_array(handle, n, status, ierr) bind(C, name='fc_get_status_array')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        integer(c_int), intent(out) :: status(*)
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        integer :: m
        call lookup_result(handle, 'fc_get_status_array', s, ierr)
        if (ierr /= FCL_OK) return
        call check_size(s, 'fc_get_status_array', n, ierr)
        if (ierr /= FCL_OK) return
        m = s%grid%n()
        status(1:m) = int(reshape(s%status, [m]), c_int)
    end subroutine fc_get_status_array

    !> Iterations of the last calculation: normal (BCCG iterations / NORM inner CG steps)
    !! and tangential (TangCG iterations / ConvexGS sweeps, all force-loop steps), summed
    !! over Panagiotopoulos rounds.
    subroutine fc_get_iterations(handle, it_normal, it_tangential, ierr) bind(C, name='fc_get_iterations')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: it_normal, it_tangential
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        it_normal = 0; it_tangential = 0
        call lookup_result(handle, 'fc_get_iterations', s, ierr)
        if (ierr /= FCL_OK) return
        it_normal = s%r_it_n; it_tangential = s%r_it_t
    end subroutine fc_get_iterations

    !> Reuse counters: operator builds (normal, tangential) and calculations on this handle.
    subroutine fc_get_rebuilds(handle, n_normal, n_tangential, n_calculations, ierr) bind(C, name='fc_get_rebuilds')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: n_normal, n_tangential, n_calculations
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        n_normal = 0; n_tangential = 0; n_calculations = 0
        call lookup(handle, 'fc_get_rebuilds', s, ierr)
        if (ierr /= FCL_OK) return
        n_normal = s%rebuilds_normal; n_tangential = s%rebuilds_tangential; n_calculations = s%calculations
    end subroutine fc_get_rebuilds

    !> Grid size of the handle (to size result arrays).
    subroutine fc_get_grid_size(handle, nx, ny, ierr) bind(C, name='fc_get_grid_size')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: nx, ny
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        nx = 0; ny = 0
        call lookup(handle, 'fc_get_grid_size', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. s%has_grid) then
            call fail(s, ierr, FCL_ORDER, 'fc_get_grid_size: grid not set (call fc_set_grid)'); return
        end if
        nx = s%grid%nx; ny = s%grid%ny
    end subroutine fc_get_grid_size

    !> Message of the last failing call on `handle` as a NUL-terminated string (truncated to
    !! buflen − 1 characters, rest blank-filled).  For an invalid handle (e.g. 0) the message
    !! of the last call that failed with ierr = 1.  Empty if nothing failed.
    subroutine fc_get_error_message(handle, buffer, buflen, ierr) bind(C, name='fc_get_error_message')
        integer(c_int), intent(in) :: handle
        character(kind=c_char), intent(out) :: buffer(*)   !! receives the message
        integer(c_int), intent(in) :: buflen               !! size of buffer (≥ 1)
        integer(c_int), intent(out) :: ierr
        character(len=msg_len) :: msg
        integer :: i, m
        call ensure_registry()
        ierr = FCL_OK
        msg = registry(0)%s%message
        if (handle >= 1 .and. handle <= ubound(registry, 1)) then
            if (associated(registry(handle)%s)) msg = registry(handle)%s%message
        end if
        if (buflen < 1) then
            ierr = FCL_ARRAY_SIZE; return
        end if
        m = min(len_trim(msg), buflen - 1)
        do i = 1, m
            buffer(i) = msg(i:i)
        end do
        buffer(m + 1) = c_null_char
        do i = m + 2, buflen
            buffer(i) = ' '
        end do
    end subroutine fc_get_error_message

    ! =====================================================================================
    ! Fortran-77 linkage: `call fc_init(h, ierr)` without this module's interfaces refers to
    ! the symbol fc_init_ (gfortran, ifort, ifx, flang on Linux); these aliases forward to
    ! the bind(C) routines, so old codes link against the same library unchanged.
    ! =====================================================================================

    subroutine fc_init_f77(handle, ierr) bind(C, name='fc_init_')
        integer(c_int), intent(out) :: handle
        integer(c_int), intent(out) :: ierr
        call fc_init(handle, ierr)
    end subroutine fc_init_f77

    subroutine fc_finalize_f77(handle, ierr) bind(C, name='fc_finalize_')
        integer(c_int), intent(inout) :: handle
        integer(c_int), intent(out) :: ierr
        call fc_finalize(handle, ierr)
    end subroutine fc_finalize_f77

    subroutine fc_get_nhandles_f77(nhandles, ierr) bind(C, name='fc_get_nhandles_')
        integer(c_int), intent(out) :: nhandles
        integer(c_int), intent(out) :: ierr
        call fc_get_nhandles(nhandles, ierr)
    end subroutine fc_get_nhandles_f77

    subroutine fc_set_material_f77(handle, g1, g2, nu1, nu2, ierr) bind(C, name='fc_set_material_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: g1, g2
        real(c_double), intent(in) :: nu1, nu2
        integer(c_int), intent(out) :: ierr
        call fc_set_material(handle, g1, g2, nu1, nu2, ierr)
    end subroutine fc_set_material_f77

    subroutine fc_set_grid_f77(handle, nx, ny, xmin, xmax, ymin, ymax, ierr) bind(C, name='fc_set_grid_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: nx, ny
        real(c_double), intent(in) :: xmin, xmax, ymin, ymax
        integer(c_int), intent(out) :: ierr
        call fc_set_grid(handle, nx, ny, xmin, xmax, ymin, ymax, ierr)
    end subroutine fc_set_grid_f77

    subroutine fc_set_gap_array_f77(handle, n, h0, ierr) bind(C, name='fc_set_gap_array_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(in) :: h0(*)
        integer(c_int), intent(out) :: ierr
        call fc_set_gap_array(handle, n, h0, ierr)
    end subroutine fc_set_gap_array_f77

    subroutine fc_set_gap_quadratic_f77(handle, rx, ry, ierr) bind(C, name='fc_set_gap_quadratic_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: rx, ry
        integer(c_int), intent(out) :: ierr
        call fc_set_gap_quadratic(handle, rx, ry, ierr)
    end subroutine fc_set_gap_quadratic_f77

    subroutine fc_set_normal_approach_f77(handle, approach, ierr) bind(C, name='fc_set_normal_approach_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: approach
        integer(c_int), intent(out) :: ierr
        call fc_set_normal_approach(handle, approach, ierr)
    end subroutine fc_set_normal_approach_f77

    subroutine fc_set_normal_force_f77(handle, fn, ierr) bind(C, name='fc_set_normal_force_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: fn
        integer(c_int), intent(out) :: ierr
        call fc_set_normal_force(handle, fn, ierr)
    end subroutine fc_set_normal_force_f77

    subroutine fc_set_friction_f77(handle, mu, ierr) bind(C, name='fc_set_friction_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: mu
        integer(c_int), intent(out) :: ierr
        call fc_set_friction(handle, mu, ierr)
    end subroutine fc_set_friction_f77

    subroutine fc_set_shifts_f77(handle, xi, eta, phi, ierr) bind(C, name='fc_set_shifts_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: xi, eta
        real(c_double), intent(in) :: phi
        integer(c_int), intent(out) :: ierr
        call fc_set_shifts(handle, xi, eta, phi, ierr)
    end subroutine fc_set_shifts_f77

    subroutine fc_set_forces_f77(handle, fx, fy, phi, ierr) bind(C, name='fc_set_forces_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: fx, fy
        real(c_double), intent(in) :: phi
        integer(c_int), intent(out) :: ierr
        call fc_set_forces(handle, fx, fy, phi, ierr)
    end subroutine fc_set_forces_f77

    subroutine fc_set_solver_f77(handle, normal_solver, tangential_solver, tol, maxit, inner_k, precondition, ierr) &
        bind(C, name='fc_set_solver_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: normal_solver, tangential_solver
        real(c_double), intent(in) :: tol
        integer(c_int), intent(in) :: maxit, inner_k, precondition
        integer(c_int), intent(out) :: ierr
        call fc_set_solver(handle, normal_solver, tangential_solver, tol, maxit, inner_k, precondition, ierr)
    end subroutine fc_set_solver_f77

    subroutine fc_set_transient_f77(handle, mode, ierr) bind(C, name='fc_set_transient_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: mode
        integer(c_int), intent(out) :: ierr
        call fc_set_transient(handle, mode, ierr)
    end subroutine fc_set_transient_f77

    subroutine fc_set_rolling_step_f77(handle, dq, ierr) bind(C, name='fc_set_rolling_step_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: dq
        integer(c_int), intent(out) :: ierr
        call fc_set_rolling_step(handle, dq, ierr)
    end subroutine fc_set_rolling_step_f77

    subroutine fc_set_reuse_f77(handle, reuse_operators, warm_start, ierr) bind(C, name='fc_set_reuse_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: reuse_operators, warm_start
        integer(c_int), intent(out) :: ierr
        call fc_set_reuse(handle, reuse_operators, warm_start, ierr)
    end subroutine fc_set_reuse_f77

    subroutine fc_calculate_f77(handle, ierr) bind(C, name='fc_calculate_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: ierr
        call fc_calculate(handle, ierr)
    end subroutine fc_calculate_f77

    subroutine fc_get_forces_f77(handle, fn, fx, fy, mz, ierr) bind(C, name='fc_get_forces_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: fn, fx, fy, mz
        integer(c_int), intent(out) :: ierr
        call fc_get_forces(handle, fn, fx, fy, mz, ierr)
    end subroutine fc_get_forces_f77

    subroutine fc_get_approach_f77(handle, approach, ierr) bind(C, name='fc_get_approach_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: approach
        integer(c_int), intent(out) :: ierr
        call fc_get_approach(handle, approach, ierr)
    end subroutine fc_get_approach_f77

    subroutine fc_get_pmax_f77(handle, pmax, ierr) bind(C, name='fc_get_pmax_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: pmax
        integer(c_int), intent(out) :: ierr
        call fc_get_pmax(handle, pmax, ierr)
    end subroutine fc_get_pmax_f77

    subroutine fc_get_shifts_f77(handle, xi, eta, phi, ierr) bind(C, name='fc_get_shifts_')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: xi, eta, phi
        integer(c_int), intent(out) :: ierr
        call fc_get_shifts(handle, xi, eta, phi, ierr)
    end subroutine fc_get_shifts_f77

    subroutine fc_get_contact_stats_f77(handle, ncon, nadh, nslip, ierr) bind(C, name='fc_get_contact_stats_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: ncon, nadh, nslip
        integer(c_int), intent(out) :: ierr
        call fc_get_contact_stats(handle, ncon, nadh, nslip, ierr)
    end subroutine fc_get_contact_stats_f77

    subroutine fc_get_tractions_f77(handle, n, pn, px, py, ierr) bind(C, name='fc_get_tractions_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(out) :: pn(*), px(*), py(*)
        integer(c_int), intent(out) :: ierr
        call fc_get_tractions(handle, n, pn, px, py, ierr)
    end subroutine fc_get_tractions_f77

    subroutine fc_get_slip_f77(handle, n, sx, sy, ierr) bind(C, name='fc_get_slip_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(out) :: sx(*), sy(*)
        integer(c_int), intent(out) :: ierr
        call fc_get_slip(handle, n, sx, sy, ierr)
    end subroutine fc_get_slip_f77

    subroutine fc_get_gap_f77(handle, n, gap, ierr) bind(C, name='fc_get_gap_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        real(c_double), intent(out) :: gap(*)
        integer(c_int), intent(out) :: ierr
        call fc_get_gap(handle, n, gap, ierr)
    end subroutine fc_get_gap_f77

    subroutine fc_get_status_array_f77(handle, n, status, ierr) bind(C, name='fc_get_status_array_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: n
        integer(c_int), intent(out) :: status(*)
        integer(c_int), intent(out) :: ierr
        call fc_get_status_array(handle, n, status, ierr)
    end subroutine fc_get_status_array_f77

    subroutine fc_get_iterations_f77(handle, it_normal, it_tangential, ierr) bind(C, name='fc_get_iterations_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: it_normal, it_tangential
        integer(c_int), intent(out) :: ierr
        call fc_get_iterations(handle, it_normal, it_tangential, ierr)
    end subroutine fc_get_iterations_f77

    subroutine fc_get_rebuilds_f77(handle, n_normal, n_tangential, n_calculations, ierr) bind(C, name='fc_get_rebuilds_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: n_normal, n_tangential, n_calculations
        integer(c_int), intent(out) :: ierr
        call fc_get_rebuilds(handle, n_normal, n_tangential, n_calculations, ierr)
    end subroutine fc_get_rebuilds_f77

    subroutine fc_get_grid_size_f77(handle, nx, ny, ierr) bind(C, name='fc_get_grid_size_')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: nx, ny
        integer(c_int), intent(out) :: ierr
        call fc_get_grid_size(handle, nx, ny, ierr)
    end subroutine fc_get_grid_size_f77

    subroutine fc_get_error_message_f77(handle, buffer, buflen, ierr) bind(C, name='fc_get_error_message_')
        integer(c_int), intent(in) :: handle
        character(kind=c_char), intent(out) :: buffer(*)
        integer(c_int), intent(in) :: buflen
        integer(c_int), intent(out) :: ierr
        call fc_get_error_message(handle, buffer, buflen, ierr)
    end subroutine fc_get_error_message_f77

end module fc_legacy
