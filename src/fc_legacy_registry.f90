!> The handle registry of the flat API ([[fc_legacy]]): the state of each contact problem
!! behind an integer handle, the documented `ierr` codes, and the lookups and error records
!! every flat routine shares.
!!
!! The registry is the only mutable module state of the library.  Slots hold pointers, so
!! growing the registry never copies an operator (FFTW plans stay with their buffers).
!! It is changed and read under a lock (named OpenMP critical section, a mutex also for
!! threads the host created itself), so different handles may be used from different
!! threads; a handle's own state is its caller's (one thread at a time, `busy` guard).
module fc_legacy_registry
    use, intrinsic :: iso_c_binding, only: c_int
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fc_kinds, only: dp, msg_len, FC_CONVERGED, FC_NOT_CONVERGED, FC_DIVERGED
    use fc_errors
    use fc_strings, only: fmt_int
    use fc_geometry, only: fc_grid
    use fc_influence, only: fc_material
    use fc_contact_types, only: fc_contact_loading, fc_contact_settings, fc_contact_operators, fc_contact_state, &
        fc_contact_result
    use fc_threads, only: set_thread_count
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
    !> not enough memory for the grid (the estimate of the solve exceeds the memory the
    !! process may still use; the message gives both)
    integer(c_int), parameter, public :: FCL_MEMORY = 8

    !> Transient modes of [[fc_set_transient]].
    integer(c_int), parameter, public :: FCL_FROM_REST = 0   !! u' = 0: every call is a steady (static) problem
    integer(c_int), parameter, public :: FCL_CONTINUE = 1    !! u', p' = previous step (shift sequence)
    integer(c_int), parameter, public :: FCL_ROLLING = 2     !! u', p' = previous step moved by the rolling step

    integer, parameter, public :: GAP_NONE = 0, GAP_ARRAY = 1, GAP_QUADRATIC = 2

    !> State of one contact problem behind a handle.
    type, public :: legacy_state
        ! --- input ---
        logical :: has_material = .false., has_grid = .false., has_normal = .false., has_friction = .false.
        type(fc_material) :: mat
        type(fc_grid) :: grid
        integer :: gap_kind = GAP_NONE
        real(dp), allocatable :: h0(:, :)          !! undeformed distance (GAP_ARRAY)
        real(dp) :: rx = 0, ry = 0                 !! radii (GAP_QUADRATIC)
        real(dp), allocatable :: hq(:, :)          !! GAP_QUADRATIC evaluated on the grid (cache)
        real(dp) :: hq_key(8) = -huge(1.0_dp)      !! nx, ny, xmin, xmax, ymin, ymax, rx, ry of hq
        type(fc_contact_loading) :: load           !! normal and tangential loading, transient mode
        type(fc_contact_settings) :: settings      !! solver choice and tolerances
        ! --- reusable operators and previous state (warm start, u' and p' of transient steps) ---
        type(fc_contact_operators) :: ops
        type(fc_contact_state) :: prev
        !> steady rolling with prescribed creepages or shifts from rest: the converged tractions
        !! before `prev`'s and the inputs of both, for the start predicted from them
        !! ([[fc_legacy]]'s rolling_start)
        real(dp), allocatable :: px2(:, :), py2(:, :)  !! the tractions of the call before `prev`
        real(dp) :: inputs1(5) = 0, inputs2(5) = 0   !! (ξ, η, φ, Fn or δ, μ) of `prev` and the call before
        integer :: converged_in_row = 0              !! such calls of one problem kind converged in a row (≤ 2 counted)
        integer :: inputs_problem = -1               !! the problem kind of those calls
        integer :: calculations = 0
        integer :: threads = 0                     !! threads of the solves (0: OMP_NUM_THREADS, else 1)
        logical :: busy = .false.                  !! fc_calculate running (guards against a second caller)
        integer :: fft_effort = 0                  !! 0: FFTW_ESTIMATE, 1: FFTW_MEASURE (fc_set_fft_effort)
        integer :: fft_primed(3) = -1              !! nx, ny, periodic of the last measured plans
        character(len=:), allocatable :: fft_wisdom  !! FFTW wisdom file (fc_set_fft_wisdom; unallocated: none)
        integer :: heap_cells = -1                 !! nx·ny for which the heap was told to keep work arrays
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


    public :: lookup, lookup_result, fail, check_size, finite, flat_code, status_code, same_spacing, same_area
    public :: open_handle, close_handle, live_handles, last_message

contains

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
        !$omp critical (fc_legacy_registry)
        call ensure_registry()
        s => null()
        ierr = FCL_OK
        if (handle >= 1 .and. handle <= ubound(registry, 1)) s => registry(handle)%s
        if (.not. associated(s)) then
            ierr = FCL_INVALID_HANDLE
            write (registry(0)%s%message, '(a,i0,a)') trim(caller)//': invalid handle ', handle, &
                ' (not initialised by fc_init or already finalised)'
        end if
        !$omp end critical (fc_legacy_registry)
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

    logical function finite(x)
        real(dp), intent(in) :: x
        finite = ieee_is_finite(x)
    end function finite

    !> A new handle ≥ 1 with a fresh state; slots of finalised handles are reused (lowest first).
    subroutine open_handle(handle)
        integer(c_int), intent(out) :: handle
        type(state_slot), allocatable :: bigger(:)
        integer :: i, n
        !$omp critical (fc_legacy_registry)
        call set_thread_count(0)   ! the first call makes FFTW's planner thread-safe
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
        !$omp end critical (fc_legacy_registry)
    end subroutine open_handle

    !> Release the state of a valid `handle` (operators, FFT plans, arrays).
    subroutine close_handle(handle)
        integer(c_int), intent(in) :: handle
        type(legacy_state), pointer :: s
        !$omp critical (fc_legacy_registry)
        s => registry(handle)%s
        registry(handle)%s => null()
        !$omp end critical (fc_legacy_registry)
        call s%ops%destroy()
        ! Through a local pointer: gfortran 12 has an internal compiler error on deallocating
        ! the registry component directly once the operators carry final bindings.
        deallocate (s)
    end subroutine close_handle

    !> Number of handles in use.
    integer function live_handles() result(n)
        integer :: i
        !$omp critical (fc_legacy_registry)
        call ensure_registry()
        n = 0
        do i = 1, ubound(registry, 1)
            if (associated(registry(i)%s)) n = n + 1
        end do
        !$omp end critical (fc_legacy_registry)
    end function live_handles

    !> Message of the last failing call on `handle`; for an invalid handle, that of the
    !! last call that failed with an invalid handle.
    function last_message(handle) result(msg)
        integer(c_int), intent(in) :: handle
        character(len=msg_len) :: msg
        !$omp critical (fc_legacy_registry)
        call ensure_registry()
        msg = registry(0)%s%message
        if (handle >= 1 .and. handle <= ubound(registry, 1)) then
            if (associated(registry(handle)%s)) msg = registry(handle)%s%message
        end if
        !$omp end critical (fc_legacy_registry)
    end function last_message

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
        if (n < s%grid%n()) call fail(s, ierr, FCL_ARRAY_SIZE, caller//': n = '//fmt_int(n)// &
            ' is smaller than nx*ny = '//fmt_int(s%grid%n()))
    end subroutine check_size

    !> The flat API's `ierr` for a library error code.
    pure integer(c_int) function flat_code(stat)
        integer, intent(in) :: stat
        select case (stat)
        case (FC_OK); flat_code = FCL_OK
        case (FC_ERR_NOT_READY); flat_code = FCL_ORDER
        case (FC_ERR_ALLOC); flat_code = FCL_MEMORY
        case (FC_ERR_SHAPE, FC_ERR_INTERNAL); flat_code = FCL_INTERNAL
        case default; flat_code = FCL_INVALID_VALUE
        end select
    end function flat_code

    pure integer(c_int) function status_code(status)
        integer, intent(in) :: status
        select case (status)
        case (FC_CONVERGED); status_code = FCL_OK
        case (FC_NOT_CONVERGED); status_code = FCL_NOT_CONVERGED
        case (FC_DIVERGED); status_code = FCL_DIVERGED
        case default; status_code = FCL_INTERNAL
        end select
    end function status_code

end module fc_legacy_registry
