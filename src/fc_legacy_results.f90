!> The flat API's queries (doc/legacy_api.md): the solution of a handle's last calculation
!! (forces, approach, tractions, slip, gap, element states, iteration counts), the handle's
!! grid and rebuild counters, the last error message, the live handles and the library
!! version.
!!
!! `bind(C)` with an integer error code `ierr` (the `FCL_*` constants of
!! [[fc_legacy_registry]]); arrays are the caller's, of at least nx·ny elements in the
!! grid's column order (x fastest), checked against the size the caller passes.
module fc_legacy_results
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_null_char
    use fc_kinds
    use fc_tangcg_types
    use fc_version, only: fc_version_major, fc_version_minor, fc_version_patch
    use fc_legacy_registry
    implicit none
    private

    public :: fc_get_forces, fc_get_dissipation, fc_get_approach, fc_get_pmax, fc_get_shifts, fc_get_contact_stats
    public :: fc_get_edge_contact
    public :: fc_get_tractions, fc_get_slip, fc_get_gap, fc_get_status_array, fc_get_iterations
    public :: fc_get_rebuilds, fc_get_grid_size, fc_get_error_message, fc_get_nhandles, fc_get_version

contains

    !> Number of handles currently in use (leak checks in tests and host codes).
    subroutine fc_get_nhandles(nhandles, ierr) bind(C, name='fc_get_nhandles')
        integer(c_int), intent(out) :: nhandles  !! live handles
        integer(c_int), intent(out) :: ierr      !! error code (always 0)
        nhandles = live_handles()
        ierr = FCL_OK
    end subroutine fc_get_nhandles

    !> Version of the library the host code is linked against (semantic versioning, as
    !! `fastcontact --version` prints and every JSON summary records): a host code that
    !! depends on a routine or behaviour of a given version checks it here at run time.
    subroutine fc_get_version(major, minor, patch, ierr) bind(C, name='fc_get_version')
        integer(c_int), intent(out) :: major, minor, patch
        integer(c_int), intent(out) :: ierr      !! error code (always 0)
        major = fc_version_major; minor = fc_version_minor; patch = fc_version_patch
        ierr = FCL_OK
    end subroutine fc_get_version

    ! =====================================================================================
    ! results
    ! =====================================================================================

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

    !> Frictional dissipation −Σ (px·sx + py·sy)·dx·dy of the last calculation: the work of
    !! friction over the shift or the transient step [N·mm]; in steady rolling the work per
    !! mm rolled [N] (the wear number Tγ).  0 without a tangential problem.
    subroutine fc_get_dissipation(handle, dissipation, ierr) bind(C, name='fc_get_dissipation')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(out) :: dissipation
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        dissipation = 0
        call lookup_result(handle, 'fc_get_dissipation', s, ierr)
        if (ierr /= FCL_OK) return
        dissipation = s%result%tangential%dissipation
    end subroutine fc_get_dissipation

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

    !> 1 when the contact of the last calculation reaches the first or last row or column of
    !! the grid, else 0.  The potential contact area then clips the contact and the solution
    !! is not the one of the unbounded half-space: enlarge the area (`fc_set_grid`).  Always 0
    !! for a periodic cell, which has no edge.
    subroutine fc_get_edge_contact(handle, touches, ierr) bind(C, name='fc_get_edge_contact')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(out) :: touches   !! 0 or 1
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        touches = 0
        call lookup_result(handle, 'fc_get_edge_contact', s, ierr)
        if (ierr /= FCL_OK) return
        if (s%result%normal%touches_boundary) touches = 1
    end subroutine fc_get_edge_contact

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
        ierr = FCL_OK
        msg = last_message(handle)
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

end module fc_legacy_results
