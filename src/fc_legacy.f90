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
    use fc_contact
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

    !> State of one contact problem behind a handle.
    type :: legacy_state
        ! --- input ---
        logical :: has_material = .false., has_grid = .false., has_normal = .false., has_friction = .false.
        type(fc_material) :: mat
        type(fc_grid) :: grid
        integer :: gap_kind = GAP_NONE
        real(dp), allocatable :: h0(:, :)          !! undeformed distance (GAP_ARRAY)
        real(dp) :: rx = 0, ry = 0                 !! radii (GAP_QUADRATIC)
        type(fc_contact_loading) :: load           !! normal and tangential loading, transient mode
        type(fc_contact_settings) :: settings      !! solver choice and tolerances
        ! --- reusable operators and previous state (warm start, u' and p' of transient steps) ---
        type(fc_contact_operators) :: ops
        type(fc_contact_state) :: prev
        integer :: calculations = 0
        ! --- result of the last calculation ---
        logical :: has_result = .false.
        type(fc_contact_result) :: result
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
        call s%ops%destroy()
        deallocate (registry(handle)%s)
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
                call s%prev%reset()
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
        s%load%normal%approach = approach; s%load%normal%force_prescribed = .false.; s%has_normal = .true.
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
        s%load%normal%fn = fn; s%load%normal%force_prescribed = .true.; s%has_normal = .true.
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
        s%load%tangential%mu = mu; s%has_friction = .true.
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
        s%load%tangential%xi = xi; s%load%tangential%eta = eta; s%load%tangential%phi = phi
        s%load%tangential%force_prescribed = .false.; s%load%problem = FC_PROBLEM_TANGENTIAL
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
        s%load%tangential%fx = fx; s%load%tangential%fy = fy; s%load%tangential%phi = phi
        s%load%tangential%force_prescribed = .true.; s%load%problem = FC_PROBLEM_TANGENTIAL
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
        associate (ns => s%settings%normal, ts => s%settings%tangential)
            ns%solver = merge('norm    ', 'bccg    ', normal_solver == 2)
            ts%solver = merge('convexgs', 'tangcg  ', tangential_solver == 2)
            ns%tol = tol; ts%tol = tol
            ns%maxit = maxit; ts%maxit = maxit
            ts%inner_k = inner_k
            ns%precondition = precondition == 1
            ts%precondition = precondition == 1
        end associate
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
        select case (mode)
        case (FCL_CONTINUE); s%load%transient = FC_TRANSIENT_SHIFT
        case (FCL_ROLLING);  s%load%transient = FC_TRANSIENT_ROLLING
        case default;        s%load%transient = FC_FROM_REST
        end select
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
        s%load%dq = dq
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
        s%ops%reuse = reuse_operators == 1
        s%prev%warm_start = warm_start == 1
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
        real(dp), allocatable :: h0(:, :)
        integer :: stat
        character(len=msg_len) :: msg
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
        if (s%load%problem == FC_PROBLEM_TANGENTIAL .and. .not. s%has_friction) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: shifts or forces set but no friction (call fc_set_friction)')
            return
        end if
        s%has_result = .false.
        if (s%gap_kind == GAP_QUADRATIC) then
            h0 = quadratic_gap(s%grid, s%rx, s%ry)
        else
            h0 = s%h0
        end if
        ! --- the solve: operators reused while grid spacing and material match; the previous
        !     state (warm start, u', p') advances only when every stage converged
        call solve_contact(s%ops, s%grid, s%mat, h0, s%load, s%settings, s%result, stat, msg, state=s%prev)
        if (stat /= 0) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_calculate: '//trim(msg)); return
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

    pure integer(c_int) function status_code(status)
        integer, intent(in) :: status
        select case (status)
        case (FC_CONVERGED); status_code = FCL_OK
        case (FC_NOT_CONVERGED); status_code = FCL_NOT_CONVERGED
        case (FC_DIVERGED); status_code = FCL_DIVERGED
        case default; status_code = FCL_INTERNAL
        end select
    end function status_code

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
        fn = s%result%normal%fn; fx = s%result%tangential%fx; fy = s%result%tangential%fy; mz = s%result%tangential%mz
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
        approach = s%result%normal%approach
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
        pmax = s%result%normal%pmax
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
        xi = s%result%tangential%xi; eta = s%result%tangential%eta; phi = s%result%tangential%phi
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
        if (allocated(s%result%tangential%state)) then
            ncon = s%result%tangential%ncon; nadh = s%result%tangential%nadh; nslip = s%result%tangential%nslip
        else
            ! no tangential loading: zero tractions, full adhesion is the exact solution
            ncon = s%result%normal%ncon; nadh = ncon; nslip = 0
        end if
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
        pn(1:m) = reshape(s%result%normal%pn, [m])
        if (allocated(s%result%tangential%px)) then
            px(1:m) = reshape(s%result%tangential%px, [m]); py(1:m) = reshape(s%result%tangential%py, [m])
        else
            px(1:m) = 0; py(1:m) = 0
        end if
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
        if (allocated(s%result%tangential%sx)) then
            sx(1:m) = reshape(s%result%tangential%sx, [m]); sy(1:m) = reshape(s%result%tangential%sy, [m])
        else
            sx(1:m) = 0; sy(1:m) = 0
        end if
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
        gap(1:m) = reshape(s%result%normal%gap, [m])
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
        if (allocated(s%result%tangential%state)) then
            status(1:m) = int(reshape(s%result%tangential%state, [m]), c_int)
        else
            status(1:m) = int(reshape(merge(EL_ADHESION, EL_EXTERIOR, s%result%normal%pn > 0), [m]), c_int)
        end if
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
        it_normal = s%result%normal%iterations; it_tangential = s%result%tangential%iterations
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
        n_normal = s%ops%builds_normal; n_tangential = s%ops%builds_tangential; n_calculations = s%calculations
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
