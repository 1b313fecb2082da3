!> The flat API's handles and their inputs (doc/legacy_api.md): `fc_init`, `fc_finalize`
!! and every `fc_set_*` routine, each with its argument checks.
!!
!! Every routine has a `bind(C)` name, takes its arguments by reference and ends with an
!! integer error code `ierr` (the `FCL_*` constants of [[fc_legacy_registry]]); a failing
!! call leaves a message naming the routine and the offending value.  A setter only records
!! its input in the handle's state; [[fc_legacy_calculate]] solves, [[fc_legacy_results]]
!! reads the solution, and [[fc_legacy]] gathers the three.
!!
!! Size (~560 lines): one routine per documented input of the API (23 entries) with its checks.
module fc_legacy_setup
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_null_char
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use fc_kinds
    use fc_limits
    use fc_geometry
    use fc_influence
    use fc_contact_types
    use fc_tangcg_types
    use fc_contact_types, only: take_influence_coefficients, clear_influence_coefficients
    use fc_strings, only: fmt_int, fmt_g6
    use fc_legacy_registry
    use fc_icfile, only: fc_ic_set
    use fc_icfile_load, only: load_influence_source, ic_source_header
    use fc_memory, only: memory_fits, format_bytes, memory_env, ic_set_bytes, ic_case_memory_bytes, memory_base_bytes
    use fc_threads, only: max_threads_allowed
    implicit none
    private

    public :: fc_init, fc_finalize, fc_set_material, fc_set_grid, fc_set_gap_array, fc_set_gap_quadratic
    public :: fc_set_normal_approach, fc_set_normal_force, fc_set_friction, fc_set_shifts, fc_set_forces
    public :: fc_set_solver, fc_set_transient, fc_set_rolling_step, fc_set_reuse
    public :: fc_set_rolling, fc_set_rolling_forces, fc_set_rolling_options
    public :: fc_set_influence_file, fc_set_periodic, fc_set_threads, fc_set_fft_effort, fc_set_fft_wisdom

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
        call check_load_memory(p1, p2, stat, msg)
        if (stat /= 0) then
            call fail(s, ierr, flat_code(stat), 'fc_set_influence_file: '//trim(msg)); return
        end if
        call load_influence_source(p1, p2, s%mat%g1, s%mat%nu1, s%mat%g2, s%mat%nu2, ic, stat, msg)
        if (stat == 0) call take_influence_coefficients(s%ops, ic, stat, msg)
        if (stat /= 0) then
            call fail(s, ierr, FCL_INVALID_VALUE, 'fc_set_influence_file: '//trim(msg)); return
        end if
    end subroutine fc_set_influence_file

    !> Before coefficient files are loaded: the load holds body 1's set and body 2's (each
    !! [[ic_set_bytes]] at the files' largest offsets, read from their headers) and the
    !! checks' temporaries, about half a set ([[ic_case_memory_bytes]]); stat = FC_ERR_ALLOC when that exceeds the memory
    !! this process may use (nothing is loaded), FC_ERR_VALUE for an invalid
    !! `FASTCONTACT_AVAILABLE_MEMORY`.  A header that cannot be read is left to the load,
    !! which reports it in full.
    subroutine check_load_memory(p1, p2, stat, msg)
        character(len=*), intent(in) :: p1, p2
        integer, intent(out) :: stat
        character(len=msg_len), intent(out) :: msg
        type(fc_ic_set) :: h
        integer(i8) :: set, need, limit
        character(len=:), allocatable :: source
        logical :: fits
        call ic_source_header(p1, p2, h, stat, msg)
        if (stat /= 0) then
            stat = 0; msg = ''; return
        end if
        set = ic_set_bytes(h%mx, h%my)
        need = ic_case_memory_bytes(0_i8, 0.0_dp, set) - memory_base_bytes   ! the load alone, no grid yet
        ! the host's own memory is not the library's to release: no resident size added
        call memory_fits(need, 1, 0_i8, .false., fits, limit, source, stat, msg)
        if (stat /= 0 .or. fits) return
        stat = FC_ERR_ALLOC
        msg = 'the coefficient files reach offsets '//fmt_int(h%mx)//' x '//fmt_int(h%my)//': loading them needs about '// &
            format_bytes(need)//', more than the '//format_bytes(limit)//' this process may use ('//source// &
            '); use files that reach no farther than the grid needs (nx-1, ny-1), or set '//memory_env//' to override'
    end subroutine check_load_memory

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
    !! in x and y (even nx, ny; a prescribed normal force; tangential problems by TangCG,
    !! without spin or rolling).
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

end module fc_legacy_setup
