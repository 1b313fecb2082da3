!> Flat, handle-based "legacy-style" API for multibody codes (doc/legacy_api.md).
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
!! Error codes (`ierr`): the `FCL_*` constants of [[fc_legacy_registry]], re-exported here
!! (doc/legacy_api.md); library error codes map onto them in one place ([[flat_code]]).  A failing
!! call leaves a message naming the routine and the offending value, retrievable with
!! [[fc_get_error_message]] (for an invalid handle: with any handle, e.g. 0).
!!
!! Reuse: the influence operators (kernels and FFT plans) of a handle are kept while the
!! grid size/spacing and the material are unchanged; the previous solution warm-starts the
!! next call and, in the transient modes, is the previous state (u', p') of the step.
!!
!! Size (~1100 lines): one bind(C) routine with its argument checks per entry of the
!! documented API (39 entries), kept together so that this module, include/fc_legacy.h and
!! doc/legacy_api.md list the same surface (.ci/run checks the header and the F77 aliases), plus the start predicted across calls
!! ([[rolling_start]], [[rolling_advance]], ~80 lines) and the memory check before a build
!! ([[check_memory]], ~40 lines), which need both the handle's state
!! and the orchestrator: in a module of its own it would add a layer to the module graph
!! (doc/architecture.md).  The handles live in [[fc_legacy_registry]]; every calculation goes
!! through the library's orchestrator [[solve_contact]].
!! Fortran-77 callers link through [[fc_legacy_f77]].
module fc_legacy
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_null_char
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
    use fc_kinds
    use fc_geometry
    use fc_influence
    use fc_norm
    use fc_tangcg
    use fc_contact
    use fc_strings, only: fmt_int, fmt_g6
    use fc_errors
    use fc_version, only: fc_version_major, fc_version_minor, fc_version_patch
    use fc_legacy_registry
    use fc_limits
    use fc_icfile, only: fc_ic_set
    use fc_icfile_load, only: load_influence_source
    use fc_threads, only: set_thread_count, max_threads_allowed, fc_thread_count
    use fc_memory, only: memory_fits, serial_bytes_per_element, case_memory_bytes, format_bytes, memory_env, &
        memory_base_bytes
    use fc_fft_effort, only: prime_fft_plans, use_fft_wisdom
    implicit none
    private

    public :: fc_init, fc_finalize, fc_set_material, fc_set_grid, fc_set_gap_array, fc_set_gap_quadratic
    public :: fc_set_normal_approach, fc_set_normal_force, fc_set_friction, fc_set_shifts, fc_set_forces
    public :: fc_set_solver, fc_set_transient, fc_set_rolling_step, fc_set_reuse, fc_calculate
    public :: fc_set_rolling, fc_set_rolling_forces, fc_set_rolling_options
    public :: fc_get_forces, fc_get_approach, fc_get_pmax, fc_get_shifts, fc_get_contact_stats, fc_get_edge_contact
    public :: fc_get_tractions, fc_get_slip, fc_get_gap, fc_get_status_array, fc_get_iterations
    public :: fc_get_rebuilds, fc_get_grid_size, fc_get_error_message, fc_get_nhandles, fc_get_version
    public :: fc_set_influence_file
    public :: fc_set_periodic, fc_set_threads, fc_set_fft_effort, fc_set_fft_wisdom
    public :: shift_along_x
    public :: FCL_OK, FCL_INVALID_HANDLE, FCL_ORDER, FCL_INVALID_VALUE, FCL_NOT_CONVERGED, FCL_DIVERGED
    public :: FCL_ARRAY_SIZE, FCL_INTERNAL, FCL_MEMORY, FCL_FROM_REST, FCL_CONTINUE, FCL_ROLLING

contains

    ! =====================================================================================
    ! life cycle
    ! =====================================================================================

    !> Create a contact problem; `handle` ≥ 1 on success.  Slots of finalised handles are
    !! reused (lowest first).
    subroutine fc_init(handle, ierr) bind(C, name='fc_init')
        integer(c_int), intent(out) :: handle   !! new handle
        integer(c_int), intent(out) :: ierr     !! error code
        call open_handle(handle)
        ierr = FCL_OK
    end subroutine fc_init

    !> Release a handle (operators, FFT plans, arrays); `handle` is set to 0.
    subroutine fc_finalize(handle, ierr) bind(C, name='fc_finalize')
        integer(c_int), intent(inout) :: handle  !! handle to release; 0 on return
        integer(c_int), intent(out) :: ierr      !! error code
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_finalize', s, ierr)
        if (ierr /= FCL_OK) return
        if (s%busy) then
            call fail(s, ierr, FCL_ORDER, 'fc_finalize: the handle is calculating in another thread'); return
        end if
        call close_handle(handle)
        handle = 0
    end subroutine fc_finalize

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

    !> Influence coefficients from files instead of the half-space ones (doc/numerical_ic.md):
    !! `path` body 1's (written by `fastcontact-ic`) or combined ones (either format),
    !! `path2` body 2's ('' : the half-space of fc_set_material's g2, nu2).  Null-terminated
    !! strings; path = '' returns to the half-space kernels.  Call after fc_set_material;
    !! the grid must have the file's element size.  The operators are rebuilt at the next
    !! calculation.
    subroutine fc_set_influence_file(handle, path, path2, ierr) bind(C, name='fc_set_influence_file')
        integer(c_int), intent(in) :: handle
        character(kind=c_char), intent(in) :: path(*), path2(*)
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        type(fc_ic_set) :: ic
        integer :: stat
        character(len=msg_len) :: msg
        character(len=:), allocatable :: p1, p2
        call lookup(handle, 'fc_set_influence_file', s, ierr)
        if (ierr /= FCL_OK) return
        p1 = c_string(path); p2 = c_string(path2)
        if (len(p1) == 0) then
            call clear_influence_coefficients(s%ops); return
        end if
        if (.not. s%has_material) then
            call fail(s, ierr, FCL_ORDER, 'fc_set_influence_file: material not set (call fc_set_material first)')
            return
        end if
        call load_influence_source(p1, p2, s%mat%g1, s%mat%nu1, s%mat%g2, s%mat%nu2, ic, stat, msg)
        if (stat == 0) call set_influence_coefficients(s%ops, ic, stat, msg)
        if (stat /= 0) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_influence_file: '//trim(msg)); return
        end if
    end subroutine fc_set_influence_file

    !> A null-terminated C string (at most 4096 characters) as a Fortran string.
    function c_string(c) result(f)
        character(kind=c_char), intent(in) :: c(*)
        character(len=:), allocatable :: f
        integer :: n
        n = 0
        do while (c(n + 1) /= c_null_char .and. n < 4096)
            n = n + 1
        end do
        allocate (character(len=n) :: f)
        f = transfer(c(1:n), f)
    end function c_string

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
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_grid: nx = '//fmt_int(nx)//', ny = '//fmt_int(ny)// &
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
                s%converged_in_row = 0
                if (allocated(s%px2)) deallocate (s%px2, s%py2)
                if (s%gap_kind == GAP_ARRAY) s%gap_kind = GAP_NONE
                s%has_result = .false.
            end if
        end if
        s%grid = g
        s%has_grid = .true.
    end subroutine fc_set_grid

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
        logical :: ok
        call lookup(handle, 'fc_set_gap_array', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. s%has_grid) then
            call fail(s, ierr, FCL_ORDER, 'fc_set_gap_array: call fc_set_grid first'); return
        end if
        if (n /= s%grid%n()) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_gap_array: n = '//fmt_int(n)//' but the grid has nx*ny = ' &
                //fmt_int(s%grid%n())//' elements'); return
        end if
        do k = 1, n
            ! finite within ±max_length, or ≥ 1e20 / +Inf (element excluded); NaN and −Inf rejected
            ok = real_in_range(h0(k), -max_length, max_length)
            if (.not. ok .and. .not. ieee_is_nan(h0(k))) ok = h0(k) >= h_no_contact   ! NaN never compared
            if (.not. ok) then
                call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_gap_array: h0('//fmt_int(k)//') = '//fmt_g6(h0(k))// &
                    ' must be finite with |h0| <= '//fmt_limit(max_length)//' mm, or >= 1e20 (element excluded)')
                return
            end if
        end do
        s%h0 = reshape(min(h0(1:n), h_no_contact), [s%grid%nx, s%grid%ny])
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
        if (.not. s%has_grid) then
            call fail(s, ierr, FCL_ORDER, 'fc_set_gap_quadratic: call fc_set_grid first'); return
        end if
        ! a radius <= 0 is flat in that direction; a positive one at least min_radius
        if (.not. (real_in_range(rx, -huge(1.0_dp), 0.0_dp) .or. real_in_range(rx, min_radius, huge(1.0_dp))) .or. &
            .not. (real_in_range(ry, -huge(1.0_dp), 0.0_dp) .or. real_in_range(ry, min_radius, huge(1.0_dp)))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_gap_quadratic: rx = '//fmt_g6(rx)//', ry = '//fmt_g6(ry)// &
                ': each radius must be finite, <= 0 (flat) or >= '//fmt_limit(min_radius)//' mm'); return
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
        if (.not. real_in_range(approach, -max_length, max_length)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_normal_approach: approach = '//fmt_g6(approach)// &
                ' must be finite with |approach| <= '//fmt_limit(max_length)//' mm'); return
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
        if (.not. real_in_range(fn, min_force, max_force)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_normal_force: fn = '//fmt_g6(fn)//' must be > 0 (in ['// &
                fmt_limit(min_force)//', '//fmt_limit(max_force)//'] N)'); return
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
        if (.not. (real_in_range(mu, min_friction, max_friction) .or. mu == 0)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_friction: mu = '//fmt_g6(mu)//' must be >= 0 (0, or in ['// &
                fmt_limit(min_friction)//', '//fmt_limit(max_friction)//'])'); return
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
        if (.not. (real_in_range(xi, -max_length, max_length) .and. real_in_range(eta, -max_length, max_length) &
            .and. real_in_range(phi, -max_spin, max_spin))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_shifts: xi = '//fmt_g6(xi)//', eta = '//fmt_g6(eta)//', phi = ' &
                //fmt_g6(phi)//' must be finite with |xi|, |eta| <= '//fmt_limit(max_length)//' mm, |phi| <= '// &
                fmt_limit(max_spin)); return
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
        if (.not. (real_in_range(fx, -max_force, max_force) .and. real_in_range(fy, -max_force, max_force) &
            .and. real_in_range(phi, -max_spin, max_spin))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_forces: fx = '//fmt_g6(fx)//', fy = '//fmt_g6(fy)//', phi = ' &
                //fmt_g6(phi)//' must be finite with |fx|, |fy| <= '//fmt_limit(max_force)//' N, |phi| <= '// &
                fmt_limit(max_spin)); return
        end if
        s%load%tangential%fx = fx; s%load%tangential%fy = fy; s%load%tangential%phi = phi
        s%load%tangential%force_prescribed = .true.; s%load%problem = FC_PROBLEM_TANGENTIAL
    end subroutine fc_set_forces

    !> Steady-state rolling of body 1 in +x with creepages ξ, η [-] and spin φ [1/mm]
    !! (doc/rolling.md): every calculation is a steady state (transient mode must be 0; the
    !! previous solution warm-starts the next one).  Creep forces from [[fc_get_forces]],
    !! creepages used from [[fc_get_shifts]].  Switches the rolling problem on.
    subroutine fc_set_rolling(handle, xi, eta, phi, ierr) bind(C, name='fc_set_rolling')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: xi, eta   !! creepages [-]
        real(c_double), intent(in) :: phi       !! spin creepage [1/mm]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_rolling', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. (finite(xi) .and. finite(eta) .and. finite(phi))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_rolling: xi = '//fmt_g6(xi)//', eta = '//fmt_g6(eta)//', phi = ' &
                //fmt_g6(phi)//' must be finite'); return
        end if
        s%load%tangential%xi = xi; s%load%tangential%eta = eta; s%load%tangential%phi = phi
        s%load%tangential%force_prescribed = .false.; s%load%problem = FC_PROBLEM_ROLLING
    end subroutine fc_set_rolling

    !> Steady-state rolling with prescribed creep forces (Fx, Fy) [N], |F| < μk·Fn, and spin
    !! creepage φ [1/mm]; the creepages found are returned by [[fc_get_shifts]].
    subroutine fc_set_rolling_forces(handle, fx, fy, phi, ierr) bind(C, name='fc_set_rolling_forces')
        integer(c_int), intent(in) :: handle
        real(c_double), intent(in) :: fx, fy    !! creep forces [N]
        real(c_double), intent(in) :: phi       !! spin creepage [1/mm]
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_rolling_forces', s, ierr)
        if (ierr /= FCL_OK) return
        if (.not. (finite(fx) .and. finite(fy) .and. finite(phi))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_rolling_forces: fx = '//fmt_g6(fx)//', fy = '//fmt_g6(fy)// &
                ', phi = '//fmt_g6(phi)//' must be finite'); return
        end if
        s%load%tangential%fx = fx; s%load%tangential%fy = fy; s%load%tangential%phi = phi
        s%load%tangential%force_prescribed = .true.; s%load%problem = FC_PROBLEM_ROLLING
    end subroutine fc_set_rolling_forces

    !> Steady rolling options: solver 0 or 1 = Newton–GMRES (default), 2 = transient march,
    !! 3 = SteadyGS (references); kinetic friction mu_kinetic ≤ μ in slip (< 0: equal to μ).
    subroutine fc_set_rolling_options(handle, solver, mu_kinetic, ierr) bind(C, name='fc_set_rolling_options')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: solver
        real(c_double), intent(in) :: mu_kinetic
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_rolling_options', s, ierr)
        if (ierr /= FCL_OK) return
        if (solver < 0 .or. solver > 3) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_rolling_options: solver = '//fmt_int(solver)// &
                ' is not 0/1 (GMRES), 2 (march) or 3 (SteadyGS)'); return
        end if
        if (.not. finite(mu_kinetic)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_rolling_options: mu_kinetic = '//fmt_g6(mu_kinetic)// &
                ' must be finite'); return
        end if
        select case (solver)
        case (2); s%settings%rolling%solver = 'march'
        case (3); s%settings%rolling%solver = 'steadygs'
        case default; s%settings%rolling%solver = 'gmres'
        end select
        s%load%mu_kinetic = mu_kinetic
    end subroutine fc_set_rolling_options

    !> Solver choice and tolerances.  normal_solver: 0 or 1 = BCCG, 2 = NORM; tangential_solver:
    !! 0 or 1 = TangCG, 2 = ConvexGS; tol > 0 (both problems); maxit ≥ 1; inner_k ≥ 1
    !! (TangCG); precondition 0 (off), 1 (BCCG's and TangCG's FFT preconditioners as their
    !! circulants on the grid, the default) or 2 (as the Toeplitz inverses on the doubled
    !! grid); doc/solvers.md, "Preconditioner form".
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
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: normal_solver = '//fmt_int(normal_solver)// &
                ' is not 0/1 (BCCG) or 2 (NORM)'); return
        end if
        if (tangential_solver < 0 .or. tangential_solver > 2) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: tangential_solver = '//fmt_int(tangential_solver)// &
                ' is not 0/1 (TangCG) or 2 (ConvexGS)'); return
        end if
        if (.not. real_in_range(tol, tiny(1.0_dp), nearest(1.0_dp, -1.0_dp))) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: tol = '//fmt_g6(tol)//' must lie in (0, 1)'); return
        end if
        if (maxit < 1 .or. maxit > max_iterations) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: maxit = '//fmt_int(maxit)//' must lie in [1, '// &
                fmt_int(max_iterations)//']'); return
        end if
        if (inner_k < 1 .or. inner_k > max_iterations) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: inner_k = '//fmt_int(inner_k)//' must lie in [1, '// &
                fmt_int(max_iterations)//']'); return
        end if
        if (precondition < 0 .or. precondition > 2) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_solver: precondition = '//fmt_int(precondition)// &
                ' is not 0 (off), 1 (on, circulant form) or 2 (on, Toeplitz form)'); return
        end if
        associate (ns => s%settings%normal, ts => s%settings%tangential)
            ns%solver = merge('norm    ', 'bccg    ', normal_solver == 2)
            ts%solver = merge('convexgs', 'tangcg  ', tangential_solver == 2)
            ns%tol = tol; ts%tol = tol; s%settings%rolling%tol = tol
            ns%maxit = maxit; ts%maxit = maxit; s%settings%rolling%maxit = maxit
            ts%inner_k = inner_k
            ns%precondition = precondition >= 1
            ts%precondition = precondition >= 1
            ns%prec_form = merge('toeplitz ', 'circulant', precondition == 2)
            ts%prec_form = ns%prec_form
            s%settings%rolling%prec_form = ns%prec_form
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
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_transient: mode = '//fmt_int(mode)// &
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
        if (.not. real_in_range(dq, -max_length, max_length)) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_rolling_step: dq = '//fmt_g6(dq)//' must be finite with |dq| <= '// &
                fmt_limit(max_length)//' mm'); return
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
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_reuse: reuse_operators = '//fmt_int(reuse_operators)// &
                ', warm_start = '//fmt_int(warm_start)//' must be 0 or 1'); return
        end if
        s%ops%reuse = reuse_operators == 1
        s%prev%warm_start = warm_start == 1
    end subroutine fc_set_reuse

    !> FFT planning effort: 0 = FFTW_ESTIMATE (default, no planning cost), 1 = FFTW_MEASURE
    !! for this handle's grid, measured once per grid shape at the next calculation (the
    !! operators are then rebuilt on the measured plans).  Pays only over many calls on one
    !! grid: break-even and gains in doc/legacy_api.md.
    subroutine fc_set_fft_effort(handle, effort, ierr) bind(C, name='fc_set_fft_effort')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: effort   !! 0 or 1
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_fft_effort', s, ierr)
        if (ierr /= FCL_OK) return
        if (effort /= 0 .and. effort /= 1) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_fft_effort: effort = '//fmt_int(effort)// &
                ' must be 0 (estimate) or 1 (measure)'); return
        end if
        s%fft_effort = effort
    end subroutine fc_set_fft_effort

    !> FFTW wisdom file (null-terminated path; '' : none): at the next calculation on a grid
    !! the file is read, the grid's plans are measured when it lacks them and the file is
    !! written; the operators are rebuilt once on the measured plans.  So only the first
    !! simulation on a machine pays for the measurement (~1 s at 240×200), later ones read
    !! the plans.  Errors (a file that is not wisdom, a path that cannot be created) come at
    !! that calculation, FCL_INVALID_VALUE naming the file.  Takes precedence over
    !! fc_set_fft_effort.
    subroutine fc_set_fft_wisdom(handle, path, ierr) bind(C, name='fc_set_fft_wisdom')
        integer(c_int), intent(in) :: handle
        character(kind=c_char), intent(in) :: path(*)
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_fft_wisdom', s, ierr)
        if (ierr /= FCL_OK) return
        s%fft_wisdom = c_string(path)
        if (len(s%fft_wisdom) == 0) deallocate (s%fft_wisdom)
        s%fft_primed = -1
    end subroutine fc_set_fft_wisdom

    !> Periodic half-space (1) or not (0, default): the grid is one cell of a surface repeated
    !! in x and y (even nx, ny; normal contact with a prescribed force).
    subroutine fc_set_periodic(handle, periodic, ierr) bind(C, name='fc_set_periodic')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: periodic   !! 0 or 1
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_periodic', s, ierr)
        if (ierr /= FCL_OK) return
        if (periodic /= 0 .and. periodic /= 1) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_periodic: periodic = '//fmt_int(periodic)//' must be 0 or 1')
            return
        end if
        s%ops%periodic = periodic == 1
    end subroutine fc_set_periodic

    !> Threads of this handle's solves: 0 (default: OMP_NUM_THREADS if set, else 1) … 1024.
    !! The FFT thread count is process-wide: hosts calculating handles concurrently keep 1.
    subroutine fc_set_threads(handle, nthreads, ierr) bind(C, name='fc_set_threads')
        integer(c_int), intent(in) :: handle
        integer(c_int), intent(in) :: nthreads
        integer(c_int), intent(out) :: ierr
        type(legacy_state), pointer :: s
        call lookup(handle, 'fc_set_threads', s, ierr)
        if (ierr /= FCL_OK) return
        if (nthreads < 0 .or. nthreads > max_threads_allowed) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_threads: nthreads = '//fmt_int(nthreads)// &
                ' must lie in [0, '//fmt_int(max_threads_allowed)//'] (0: OMP_NUM_THREADS, else 1)'); return
        end if
        s%threads = nthreads
    end subroutine fc_set_threads

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
        logical :: taken
        call lookup(handle, 'fc_calculate', s, ierr)
        if (ierr /= FCL_OK) return
        !$omp critical (fc_legacy_busy)
        taken = s%busy
        s%busy = .true.
        !$omp end critical (fc_legacy_busy)
        if (taken) then
            ierr = FCL_ORDER   ! the message slot belongs to the running calculation: left alone
            return
        end if
        call calculate(s, ierr)
        s%busy = .false.
    end subroutine fc_calculate

    subroutine calculate(s, ierr)
        type(legacy_state), intent(inout) :: s
        integer(c_int), intent(out) :: ierr
        integer :: stat
        character(len=msg_len) :: msg
        real(dp) :: key(8)
        logical :: kept, predicted
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
        if (s%load%problem /= FC_PROBLEM_NORMAL .and. .not. s%has_friction) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: shifts or forces set but no friction (call fc_set_friction)')
            return
        end if
        if (s%ops%periodic .and. .not. s%load%normal%force_prescribed) then
            call fail(s, ierr, FCL_ORDER, 'fc_calculate: the periodic half-space needs the normal force (mean '// &
                'pressure x cell area, fc_set_normal_force)'); return
        end if
        s%has_result = .false.
        call set_thread_count(s%threads)
        call check_memory(s, stat, msg)
        if (stat /= 0) then
            call fail(s, ierr, flat_code(stat), 'fc_calculate: '//trim(msg)); return
        end if
        if (allocated(s%fft_wisdom)) then
            call wisdom_plans(s, stat, msg)
            if (stat /= 0) then
                call fail(s, ierr, FCL_INVALID_VALUE, "fc_calculate: FFT wisdom file '"//s%fft_wisdom//"': "//trim(msg))
                return
            end if
        else if (s%fft_effort == 1) then
            call measure_plans(s)
        end if
        if (s%heap_cells /= s%grid%nx*s%grid%ny) call keep_work_arrays(s)
        ! --- the solve: operators reused while grid spacing and material match; the previous
        !     state (warm start, u', p') advances only when every stage converged.  The
        !     quadratic gap is evaluated again only when the grid or the radii change.
        if (s%gap_kind == GAP_QUADRATIC) then
            key = [real(s%grid%nx, dp), real(s%grid%ny, dp), s%grid%xmin, s%grid%xmax, s%grid%ymin, s%grid%ymax, s%rx, s%ry]
            if (.not. allocated(s%hq) .or. any(key /= s%hq_key)) then
                s%hq = quadratic_gap(s%grid, s%rx, s%ry)
                s%hq_key = key
            end if
        end if
        call rolling_start(s, kept, predicted)
        if (s%gap_kind == GAP_QUADRATIC) then
            call solve_contact(s%ops, s%grid, s%mat, s%hq, s%load, s%settings, s%result, stat, msg, state=s%prev)
        else
            call solve_contact(s%ops, s%grid, s%mat, s%h0, s%load, s%settings, s%result, stat, msg, state=s%prev)
        end if
        call rolling_advance(s, kept, predicted, stat == 0 .and. s%result%status == FC_CONVERGED)
        if (stat /= 0) then
            call fail(s, ierr, flat_code(stat), 'fc_calculate: '//trim(msg)); return
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

    !> Before operators are built for a new grid (or a first tangential solve): the
    !! estimated peak memory of the solve (doc/reliability.md, "Memory": bytes per element of
    !! the problem kind and thread count) against the memory this process may still use plus
    !! what the handle's current operators hold, which the rebuild releases.  stat =
    !! FC_ERR_ALLOC when it does not fit (nothing is built; the handle keeps its state),
    !! FC_ERR_VALUE for an invalid `FASTCONTACT_AVAILABLE_MEMORY`.  Unknown available memory
    !! checks nothing.  A multibody code sets its grids once, so this runs once per handle.
    subroutine check_memory(s, stat, msg)
        type(legacy_state), intent(in) :: s
        integer, intent(out) :: stat
        character(len=msg_len), intent(out) :: msg
        integer(i8) :: need, held, limit
        character(len=:), allocatable :: source, kind
        real(dp) :: bpe
        logical :: tangential, fits, coupled, fmg_rsm
        stat = 0; msg = ''
        tangential = s%load%problem /= FC_PROBLEM_NORMAL
        if (s%ops%normal%matches(s%grid, s%mat) .and. &
            (.not. tangential .or. s%ops%tangential%matches(s%grid, s%mat))) return
        kind = 'tangential'
        if (.not. tangential) kind = 'normal'
        if (s%load%problem == FC_PROBLEM_ROLLING) kind = 'rolling'
        if (tangential .and. s%load%transient /= FC_FROM_REST) kind = 'transient'
        coupled = tangential .and. (s%mat%k /= 0 .or. allocated(s%ops%ic%a))
        fmg_rsm = s%settings%normal%solver == 'fmg' .and. s%settings%fmg%smoother == 'fft-rsm'
        bpe = serial_bytes_per_element(kind, fc_thread_count(), coupled, fmg_rsm)
        if (coupled) kind = kind//' (dissimilar materials)'
        need = case_memory_bytes(int(s%grid%nx, i8)*s%grid%ny, bpe)
        ! what the current operators release, counted low: the one-thread estimate of a
        ! normal, or normal + tangential, solve on their grid
        held = 0
        if (s%ops%normal%a_zz%built()) held = case_memory_bytes(int(s%ops%normal%grid%nx, i8)*s%ops%normal%grid%ny, &
            serial_bytes_per_element(merge('tangential', 'normal    ', s%ops%tangential%a_xx%built()), 1)) - &
            memory_base_bytes
        ! the host's own memory is not the library's to release: no resident size added
        call memory_fits(need, 1, held, .false., fits, limit, source, stat, msg)
        if (stat /= 0 .or. fits) return
        stat = FC_ERR_ALLOC
        msg = 'grid nx = '//fmt_int(s%grid%nx)//', ny = '//fmt_int(s%grid%ny)//': the '//kind//' solve on '// &
            fmt_int(fc_thread_count())//' thread(s) needs about '//format_bytes(need)//', more than the '// &
            format_bytes(limit)//' this process may use ('//source//'); use a coarser grid, or set '// &
            memory_env//' to override'
    end subroutine check_memory

    !> Steady rolling with prescribed creepages, or the shift problem with prescribed shifts
    !! (from rest), warm-started: when the two converged calls before this one moved the
    !! inputs (ξ, η, φ, Fn or δ, μ) along one direction and this call continues it, the start
    !! is extrapolated from their solutions ([[continuation_factor]],
    !! [[extrapolate_tractions_swap]]), as a multibody code's time steps do.  The previous
    !! converged tractions move to px2, py2 (`kept`: the call is predictable), where
    !! [[rolling_advance]] finds them.  Measured: doc/rolling.md, "Flat API".
    subroutine rolling_start(s, kept, predicted)
        type(legacy_state), intent(inout) :: s
        logical, intent(out) :: kept, predicted
        real(dp) :: v(5), sc(5), alpha
        kept = .false.; predicted = .false.
        if (.not. (predictable(s) .and. s%prev%has_tangential)) return
        kept = .true.
        if (s%converged_in_row >= 2 .and. allocated(s%px2) .and. s%load%problem == s%inputs_problem) then
            if (all(shape(s%px2) == shape(s%prev%px))) then
                v = rolling_inputs(s)
                ! creepages on one scale (φ times the half length of the area), Fn or δ and μ
                ! relative, each scale the largest magnitude of the three calls (1 where all
                ! are zero), so that every scaled difference lies in [−2, 2]
                sc(1:3) = max(maxval(abs(v(1:3))), maxval(abs(s%inputs1(1:3))), maxval(abs(s%inputs2(1:3))))
                sc(4:5) = max(abs(v(4:5)), abs(s%inputs1(4:5)), abs(s%inputs2(4:5)))
                where (.not. sc > 0) sc = 1
                alpha = continuation_factor((s%inputs1 - s%inputs2)/sc, (v - s%inputs1)/sc)
                if (alpha > 0) then
                    call extrapolate_tractions_swap(s%prev%px, s%prev%py, s%px2, s%py2, alpha)
                    predicted = .true.
                    return
                end if
            end if
        end if
        s%px2 = s%prev%px; s%py2 = s%prev%py      ! in place when the shapes agree
    end subroutine rolling_start

    !> After the solve: a converged call becomes the newest of the two the predictor uses
    !! (px2, py2 already hold the one before); a call that did not converge leaves the
    !! previous converged tractions as the warm start (undoing a prediction) and restarts
    !! the count.
    subroutine rolling_advance(s, kept, predicted, converged)
        type(legacy_state), intent(inout) :: s
        logical, intent(in) :: kept, predicted, converged
        if (.not. predictable(s)) then
            s%converged_in_row = 0
        else if (converged) then
            if (s%load%problem /= s%inputs_problem) s%converged_in_row = 0   ! shifts are not creepages
            s%inputs_problem = s%load%problem
            s%inputs2 = s%inputs1; s%inputs1 = rolling_inputs(s)
            s%converged_in_row = min(2, s%converged_in_row + 1)
        else
            if (predicted .and. kept) then
                s%prev%px = s%px2; s%prev%py = s%py2
            end if
            s%converged_in_row = 0
        end if
    end subroutine rolling_advance

    logical function predictable(s)
        type(legacy_state), intent(in) :: s
        predictable = (s%load%problem == FC_PROBLEM_ROLLING .or. s%load%problem == FC_PROBLEM_TANGENTIAL) .and. &
            s%load%transient == FC_FROM_REST .and. &
            .not. s%load%tangential%force_prescribed .and. s%prev%warm_start
    end function predictable

    !> (ξ, η, φ·half length of the area in x, Fn [N] or δ [mm], μ) of the current loading:
    !! creepages [–] or shifts [mm], spin creepage [1/mm] or spin shift [rad].
    function rolling_inputs(s) result(v)
        type(legacy_state), intent(in) :: s
        real(dp) :: v(5)
        v(1) = s%load%tangential%xi; v(2) = s%load%tangential%eta
        v(3) = s%load%tangential%phi*0.5_dp*(s%grid%xmax - s%grid%xmin)
        v(4) = merge(s%load%normal%fn, s%load%normal%approach, s%load%normal%force_prescribed)
        v(5) = s%load%tangential%mu
    end function rolling_inputs

    !> Let the C heap keep the solvers' per-call work arrays.  The solvers allocate some 30
    !! arrays of nx·ny reals per call and free them on return; glibc returns freed memory at
    !! the top of its heap to the system once it exceeds a threshold (128 KB by default) and
    !! the next call faults it in again — about half of the per-call time outside the
    !! solvers at 60×50 (doc/legacy_api.md).  glibc raises that threshold to the size of any
    !! freed block it had to map separately (up to 32 MB), so one block of the working-set
    !! size, allocated and freed once per grid size, stops the round trips.  With another
    !! allocator this costs one allocation per grid and changes nothing.
    subroutine keep_work_arrays(s)
        type(legacy_state), intent(inout) :: s
        real(dp), allocatable :: block(:)
        integer(i8) :: words
        words = max(32768_i8, min(4194304_i8, 48_i8*s%grid%nx*s%grid%ny))   ! 256 KB … 32 MB
        allocate (block(words))
        block(1) = 0                        ! one page touched: the block is real
        deallocate (block)
        s%heap_cells = s%grid%nx*s%grid%ny
    end subroutine keep_work_arrays

    !> Plans of the handle's grid from its wisdom file (measured and written when the file
    !! lacks them), once per grid shape; operators built before are dropped so that they
    !! are rebuilt on the plans.
    subroutine wisdom_plans(s, stat, msg)
        type(legacy_state), intent(inout) :: s
        integer, intent(out) :: stat
        character(len=*), intent(out) :: msg
        logical :: new_plans
        stat = 0; msg = ''
        if (s%fft_primed(1) == s%grid%nx .and. s%fft_primed(2) == s%grid%ny .and. &
            (s%fft_primed(3) == 1 .eqv. s%ops%periodic)) return
        call use_fft_wisdom(s%fft_wisdom, s%grid%nx, s%grid%ny, s%ops%periodic, new_plans, stat, msg)
        if (stat /= 0) return
        s%fft_primed = [s%grid%nx, s%grid%ny, merge(1, 0, s%ops%periodic)]
        call s%ops%normal%destroy()
        call s%ops%tangential%destroy()
    end subroutine wisdom_plans

    !> FFTW_MEASURE plans for the handle's grid shape, once per shape; operators built on
    !! estimated plans are dropped so that they are rebuilt on the measured ones.
    subroutine measure_plans(s)
        type(legacy_state), intent(inout) :: s
        if (s%fft_primed(1) == s%grid%nx .and. s%fft_primed(2) == s%grid%ny .and. &
            (s%fft_primed(3) == 1 .eqv. s%ops%periodic)) return
        call prime_fft_plans(s%grid%nx, s%grid%ny, s%ops%periodic)
        s%fft_primed = [s%grid%nx, s%grid%ny, merge(1, 0, s%ops%periodic)]
        call s%ops%normal%destroy()
        call s%ops%tangential%destroy()
    end subroutine measure_plans

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

end module fc_legacy
