!> Suite `legacy`: the flat handle-based API (fc_legacy, doc/legacy_api.md).
!!
!! Size (~860 lines, 15 tests): one file per suite, as pFUnit organises suites; each test
!! drives a handle through its own sequence of flat-API calls, which reads best in place.
module test_legacy
    use, intrinsic :: iso_c_binding, only: c_null_char
    use fc_kinds
    use fc_geometry
    use fc_influence
    use fc_norm
    use fc_tangcg
    use fc_tangcg_force, only: solve_tangential_loading
    use fc_hertz
    use fc_legacy
    use fc_contact, only: solve_normal_tangential
    use fc_driver, only: run_driver
    use fc_testing
    use fc_fftw, only: fftw_forget_wisdom
    use fc_version, only: fc_version_string
    use fc_memory, only: memory_env
    implicit none
    private
    public :: collect_legacy

    real(dp), parameter :: g_cat = 200, nu_cat = 0.42_dp, r_cat = 50, mu_cat = 0.4_dp, fn_cat = 9.1954_dp
    real(dp), parameter :: l_cat = 1.2857_dp
    !> Thesis Table 4.1 shifts (cases 1–7).
    real(dp), parameter :: case_xi(7) = [0.0_dp, 1.5e-5_dp, 0.0_dp, 0.0021_dp, 0.0037_dp, 0.0_dp, 0.0044_dp]
    real(dp), parameter :: case_eta(7) = [0.0_dp, 0.0_dp, 0.0015_dp, 0.0010_dp, 0.0048_dp, 0.005_dp, 0.0_dp]
    real(dp), parameter :: case_phi(7) = [5e-7_dp, 1e-5_dp, 0.0012_dp, 0.003_dp, 0.004_dp, 0.009_dp, 0.08_dp]

contains

    subroutine collect_legacy(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('hertz_equals_modern_api', test_hertz), &
            new_unittest('get_version', test_get_version), &
            new_unittest('cattaneo_equals_modern_api', test_cattaneo), &
            new_unittest('forces_equal_modern_api', test_forces_modern), &
            new_unittest('dissimilar_equals_modern_api', test_dissimilar), &
            new_unittest('driver_equals_flat_api', test_driver_equal), &
            new_unittest('warm_start_and_reuse', test_warm_start), &
            new_unittest('rebuild_each_call_same_result', test_no_reuse), &
            new_unittest('fft_effort_measure_same_result', test_fft_effort), &
            new_unittest('fft_wisdom_file', test_fft_wisdom), &
            new_unittest('quadratic_gap_follows_new_radii', test_gap_radii), &
            new_unittest('hysteresis_load_unload_reload', test_hysteresis), &
            new_unittest('continue_zero_increment_keeps_state', test_continue_still), &
            new_unittest('rolling_shift_and_steady_state', test_rolling), &
            new_unittest('errors_and_handles', test_errors), &
            new_unittest('edge_contact_reported', test_edge_contact), &
            new_unittest('memory_check_before_build', test_memory_check) ]
    end subroutine collect_legacy

    !> FCL_MEMORY before a grid the process has no memory for is built (here an available
    !! memory of 20 MB given by the environment: 32² needs about 11 MB for a normal +
    !! tangential solve, 512² about 220 MB): nothing is built, the message gives both sizes,
    !! and the same handle solves again on the small grid, with the same forces.  An invalid
    !! override is FCL_INVALID_VALUE naming the variable.
    subroutine test_memory_check(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: h, ierr, builds(3), builds2(3)
        real(dp) :: fn, fx, fy, mz, fx0, fy0
        character(len=:), allocatable :: msg
        call set_env(memory_env, '20M')
        call cattaneo_handle(h, 32, 32, 1e-8_dp)
        call fc_set_threads(h, 1, ierr)
        call fc_set_shifts(h, case_xi(4), case_eta(4), case_phi(4), ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_OK, '32^2 fits in 20 MB: '//last_message(h))
        if (allocated(error)) goto 9
        call fc_get_forces(h, fn, fx0, fy0, mz, ierr)
        call fc_get_rebuilds(h, builds(1), builds(2), builds(3), ierr)
        call fc_set_grid(h, 512, 512, -l_cat, l_cat, -l_cat, l_cat, ierr)
        call fc_calculate(h, ierr)
        msg = last_message(h)
        call check(error, ierr == FCL_MEMORY, '512^2 in 20 MB -> FCL_MEMORY: '//msg)
        if (allocated(error)) goto 9
        call check(error, index(msg, 'nx = 512, ny = 512') > 0 .and. index(msg, '20 MB') > 0 .and. &
            index(msg, memory_env) > 0 .and. index(msg, 'tangential') > 0, 'message names grid, sizes, override: '//msg)
        if (allocated(error)) goto 9
        call fc_get_rebuilds(h, builds2(1), builds2(2), builds2(3), ierr)
        call check(error, all(builds2 == builds), 'nothing built or calculated for the refused grid')
        if (allocated(error)) goto 9
        call fc_set_grid(h, 32, 32, -l_cat, l_cat, -l_cat, l_cat, ierr)
        call fc_calculate(h, ierr)
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call check(error, ierr == FCL_OK .and. abs(fx - fx0) <= 1e-9_dp*abs(fx0) .and. abs(fy - fy0) <= 1e-9_dp*abs(fy0), &
            'the same handle solves 32^2 again, same forces')
        if (allocated(error)) goto 9
        ! dissimilar materials count their coupling blocks: 10 MB + 1080 B x 4096 = 14.4 MB,
        ! more than 13 MB plus the 0.8 MB the 32^2 operators release (800 B x 1024)
        call fc_set_material(h, g_cat, 0.5_dp*g_cat, 0.28_dp, nu_cat, ierr)
        call fc_set_grid(h, 64, 64, -l_cat, l_cat, -l_cat, l_cat, ierr)
        call set_env(memory_env, '13M')
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_MEMORY .and. index(last_message(h), 'the tangential (dissimilar materials) solve '// &
            'on 1 thread(s) needs about 14 MB') > 0, 'dissimilar materials: '//last_message(h))
        if (allocated(error)) goto 9
        call set_env(memory_env, 'lots')
        call fc_set_grid(h, 40, 40, -l_cat, l_cat, -l_cat, l_cat, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), memory_env) > 0, &
            'invalid override: '//last_message(h))
9       call unset_env(memory_env)
        call fc_finalize(h, ierr)
    end subroutine test_memory_check

    !> Handle with the Cattaneo scene of doc/conventions.md (no tangential loading yet).
    subroutine cattaneo_handle(h, nx, ny, tol)
        integer, intent(out) :: h
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: tol
        integer :: ierr
        call fc_init(h, ierr)
        call fc_set_material(h, g_cat, g_cat, nu_cat, nu_cat, ierr)
        call fc_set_grid(h, nx, ny, -l_cat, l_cat, -l_cat, l_cat, ierr)
        call fc_set_gap_quadratic(h, r_cat, r_cat, ierr)
        call fc_set_normal_force(h, fn_cat, ierr)
        call fc_set_friction(h, mu_cat, ierr)
        call fc_set_solver(h, 1, 1, tol, 2000, 3, 1, ierr)
    end subroutine cattaneo_handle

    !> Modern-API Cattaneo set-up with the same settings.
    subroutine cattaneo_modern(nx, ny, tol, grid, mat, nop, top, ns, ts, nres)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: tol
        type(fc_grid), intent(out) :: grid
        type(fc_material), intent(out) :: mat
        type(fc_normal_operator), intent(inout) :: nop
        type(fc_tangential_operator), intent(inout) :: top
        type(fc_normal_settings), intent(out) :: ns
        type(fc_tangential_settings), intent(out) :: ts
        type(fc_normal_result), intent(out) :: nres
        integer :: stat
        character(len=msg_len) :: msg
        mat%g1 = g_cat; mat%g2 = g_cat; mat%nu1 = nu_cat; mat%nu2 = nu_cat
        call combine_material(mat, stat, msg)
        call make_grid(grid, nx, ny, -l_cat, l_cat, -l_cat, l_cat, stat, msg)
        call build_normal_operator(nop, mat, grid)
        call build_tangential_operator(top, mat, grid)
        ns%tol = tol; ts%tol = tol
        call solve_normal(nop, quadratic_gap(grid, r_cat, r_cat), ns, nres, stat, msg, fn=fn_cat)
    end subroutine cattaneo_modern

    !> Message of the last error on h (C string → Fortran).
    function last_message(h) result(msg)
        integer, intent(in) :: h
        character(len=:), allocatable :: msg
        character(len=400) :: buf
        integer :: ierr, k
        call fc_get_error_message(h, buf, len(buf), ierr)
        k = index(buf, c_null_char)
        msg = buf(1:max(0, k - 1))
    end function last_message

    !> fc_get_version returns the three numbers of the version the driver and JSON report.
    subroutine test_get_version(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: major, minor, patch, ierr
        character(len=32) :: v
        major = -1; minor = -1; patch = -1; ierr = -1
        call fc_get_version(major, minor, patch, ierr)
        write (v, '(i0,".",i0,".",i0)') major, minor, patch
        call check(error, ierr == FCL_OK, 'fc_get_version: ierr /= FCL_OK')
        call check(error, trim(v) == fc_version_string, 'fc_get_version gave '//trim(v)//', the library is '// &
            fc_version_string)
    end subroutine test_get_version

    !> Hertz Test I (32², approach 0.1091): flat API = solve_normal to 1e−10, and the
    !! self-check values F = 82049.40, 332 contact cells, pmax = 1628.29; then force mode.
    subroutine test_hertz(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: ns
        type(fc_normal_result) :: nr
        real(dp) :: pn(32*32), px(32*32), py(32*32), fn, fx, fy, mz, pmax, appr
        integer :: h, ierr, stat, ncon, nadh, nslip, st(32*32)
        character(len=msg_len) :: msg
        mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, 32, 32, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
        call build_normal_operator(nop, mat, grid)
        ns%tol = 1e-10_dp
        call solve_normal(nop, quadratic_gap(grid, 300.0_dp, 163.0_dp), ns, nr, stat, msg, approach=0.1091_dp)
        call fc_init(h, ierr)
        call fc_set_material(h, 82000.0_dp, 82000.0_dp, 0.28_dp, 0.28_dp, ierr)
        call fc_set_grid(h, 32, 32, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, ierr)
        call fc_set_gap_quadratic(h, 300.0_dp, 163.0_dp, ierr)
        call fc_set_normal_approach(h, 0.1091_dp, ierr)
        call fc_set_solver(h, 1, 1, 1e-10_dp, 1000, 3, 1, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == 0, 'calculate: '//last_message(h))
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call fc_get_pmax(h, pmax, ierr)
        call fc_get_contact_stats(h, ncon, nadh, nslip, ierr)
        call fc_get_tractions(h, size(pn), pn, px, py, ierr)
        call fc_get_status_array(h, size(st), st, ierr)
        call check(error, rel_diff(pn, reshape(nr%pn, [32*32])) <= 1e-10_dp, 'pressure = modern API')
        call check(error, fn, nr%fn, 'Fn = modern API', rel=1e-10_dp)
        call check(error, fn, 82049.40_dp, 'Fn self-check', abs=0.01_dp)
        call check(error, pmax, 1628.29_dp, 'pmax self-check', abs=0.01_dp)
        call check(error, ncon == 332 .and. nadh == 332 .and. nslip == 0, 'contact 332 cells, all adhesion')
        call check(error, count(st == 1) == 332 .and. count(st == 2) == 0, 'status array')
        call check(error, fx == 0 .and. fy == 0 .and. mz == 0 .and. all(px == 0), 'no tangential loading')
        ! prescribed force
        call fc_set_normal_force(h, 82049.40_dp, ierr)
        call fc_calculate(h, ierr)
        call fc_get_approach(h, appr, ierr)
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call check(error, ierr == 0, 'force mode: '//last_message(h))
        call check(error, fn, 82049.40_dp, 'force mode Fn', rel=1e-10_dp)
        call check(error, appr, 0.1091_dp, 'force mode approach', rel=1e-6_dp)
        call fc_finalize(h, ierr)
        call check(error, ierr == 0 .and. h == 0, 'finalize')
        call nop%destroy()
    end subroutine test_hertz

    !> Cattaneo cases 1–7 on 30×25 (tol 1e−10): flat API without warm start = BCCG +
    !! solve_tangential to 1e−10 relative (tractions, slip, forces, moment); self-check
    !! of case 1 (364 cells, Mz = −2.67854e−4).
    subroutine test_cattaneo(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fc_tangential_operator) :: top
        type(fc_normal_settings) :: ns
        type(fc_tangential_settings) :: ts
        type(fc_normal_result) :: nres
        type(fc_tangential_result) :: tr
        integer, parameter :: n = 30*25
        real(dp) :: pn(n), px(n), py(n), sx(n), sy(n), fn, fx, fy, mz, xi, eta, phi, scale
        integer :: h, ierr, stat, c, st(n), ncon, nadh, nslip
        character(len=msg_len) :: msg
        character(len=8) :: label
        call cattaneo_modern(30, 25, 1e-10_dp, grid, mat, nop, top, ns, ts, nres)
        call cattaneo_handle(h, 30, 25, 1e-10_dp)
        call fc_set_reuse(h, 1, 0, ierr)
        scale = mu_cat*fn_cat
        do c = 1, 7
            write (label, '(a,i0)') 'case ', c
            call solve_tangential(top, nres%pn, mu_cat, ts, tr, stat, msg, case_xi(c), case_eta(c), case_phi(c))
            call fc_set_shifts(h, case_xi(c), case_eta(c), case_phi(c), ierr)
            call fc_calculate(h, ierr)
            call check(error, ierr == 0, trim(label)//' calculate: '//last_message(h))
            call fc_get_forces(h, fn, fx, fy, mz, ierr)
            call fc_get_tractions(h, n, pn, px, py, ierr)
            call fc_get_slip(h, n, sx, sy, ierr)
            call fc_get_status_array(h, n, st, ierr)
            call fc_get_contact_stats(h, ncon, nadh, nslip, ierr)
            call fc_get_shifts(h, xi, eta, phi, ierr)
            call check(error, rel_diff(pn, reshape(nres%pn, [n])) <= 1e-10_dp, trim(label)//' pn')
            call check(error, rel_diff([px, py], [reshape(tr%px, [n]), reshape(tr%py, [n])]) <= 1e-10_dp, &
                trim(label)//' px, py')
            if (c > 1) call check(error, rel_diff([sx, sy], [reshape(tr%sx, [n]), reshape(tr%sy, [n])]) <= 1e-10_dp, &
                trim(label)//' sx, sy')
            call check(error, all(st == reshape(tr%state, [n])), trim(label)//' status array')
            call check(error, ncon == tr%ncon .and. nadh == tr%nadh .and. nslip == tr%nslip, trim(label)//' counts')
            call check(error, fn, nres%fn, trim(label)//' Fn', rel=1e-10_dp)
            call check(error, fx, tr%fx, trim(label)//' Fx', abs=1e-10_dp*scale)
            call check(error, fy, tr%fy, trim(label)//' Fy', abs=1e-10_dp*scale)
            call check(error, mz, tr%mz, trim(label)//' Mz', abs=1e-10_dp*max(abs(tr%mz), 1e-3_dp))
            call check(error, xi == case_xi(c) .and. eta == case_eta(c) .and. phi == case_phi(c), trim(label)//' shifts')
            if (c == 1) then
                call check(error, ncon == 364 .and. nslip == 0, 'case 1: 364 cells in adhesion')
                call check(error, mz, -2.67854e-4_dp, 'case 1: Mz self-check', abs=0.000005e-4_dp)
            end if
        end do
        call fc_finalize(h, ierr)
        call nop%destroy(); call top%destroy()
    end subroutine test_cattaneo

    !> Prescribed forces (Fx = 0.5 μFn, Fy = 0.2 μFn, φ = 0.003): flat API = BCCG +
    !! solve_tangential_loading to 1e−10 (first call, no previous state).
    subroutine test_forces_modern(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fc_tangential_operator) :: top
        type(fc_normal_settings) :: ns
        type(fc_tangential_settings) :: ts
        type(fc_normal_result) :: nres
        type(fc_tangential_result) :: tr
        type(fc_tangential_loading) :: load
        integer, parameter :: n = 30*25
        real(dp) :: pn(n), px(n), py(n), fn, fx, fy, mz, xi, eta, phi
        integer :: h, ierr, stat
        character(len=msg_len) :: msg
        call cattaneo_modern(30, 25, 1e-10_dp, grid, mat, nop, top, ns, ts, nres)
        load%mu = mu_cat; load%force_prescribed = .true.
        load%fx = 0.5_dp*mu_cat*fn_cat; load%fy = 0.2_dp*mu_cat*fn_cat; load%phi = 0.003_dp
        call solve_tangential_loading(top, nres%pn, load, ts, tr, stat, msg)
        call cattaneo_handle(h, 30, 25, 1e-10_dp)
        call fc_set_forces(h, load%fx, load%fy, load%phi, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == 0, 'calculate: '//last_message(h))
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call fc_get_tractions(h, n, pn, px, py, ierr)
        call fc_get_shifts(h, xi, eta, phi, ierr)
        call check(error, rel_diff([px, py], [reshape(tr%px, [n]), reshape(tr%py, [n])]) <= 1e-10_dp, 'px, py')
        call check(error, xi, tr%xi, 'xi', rel=1e-10_dp)
        call check(error, eta, tr%eta, 'eta', rel=1e-10_dp)
        call check(error, fx, load%fx, 'Fx prescribed', abs=1e-9_dp*mu_cat*fn_cat)
        call check(error, fy, load%fy, 'Fy prescribed', abs=1e-9_dp*mu_cat*fn_cat)
        call check(error, mz, tr%mz, 'Mz', rel=1e-10_dp)
        call fc_finalize(h, ierr)
        call nop%destroy(); call top%destroy()
    end subroutine test_forces_modern

    !> Dissimilar bodies (G1 = 80000, ν1 = 0.28 on G2 = 200, ν2 = 0.42; K ≠ 0): the flat API's
    !! Panagiotopoulos rounds = solve_normal_tangential (32², Fn = 10, μ = 0.3, tol 1e−9) to 1e−8.
    subroutine test_dissimilar(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fc_tangential_operator) :: top
        type(fc_normal_settings) :: ns
        type(fc_tangential_settings) :: ts
        type(fc_tangential_loading) :: load
        type(fc_normal_result) :: nr
        type(fc_tangential_result) :: tr
        integer, parameter :: n = 32*32
        real(dp) :: pn(n), px(n), py(n), fn, fx, fy, mz
        integer :: h, ierr, stat
        character(len=msg_len) :: msg
        mat%g1 = 80000; mat%g2 = 200; mat%nu1 = 0.28_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, 32, 32, -1.3_dp, 1.3_dp, -1.3_dp, 1.3_dp, stat, msg)
        call build_normal_operator(nop, mat, grid)
        call build_tangential_operator(top, mat, grid)
        load%mu = 0.3_dp
        ns%tol = 1e-9_dp; ts%tol = 1e-9_dp
        call solve_normal_tangential(nop, top, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, ts, load, nr, tr, stat, msg, &
                                     fn=10.0_dp)
        call fc_init(h, ierr)
        call fc_set_material(h, 80000.0_dp, 200.0_dp, 0.28_dp, 0.42_dp, ierr)
        call fc_set_grid(h, 32, 32, -1.3_dp, 1.3_dp, -1.3_dp, 1.3_dp, ierr)
        call fc_set_gap_quadratic(h, 50.0_dp, 50.0_dp, ierr)
        call fc_set_normal_force(h, 10.0_dp, ierr)
        call fc_set_friction(h, 0.3_dp, ierr)
        call fc_set_shifts(h, 0.0_dp, 0.0_dp, 0.0_dp, ierr)
        call fc_set_solver(h, 1, 1, 1e-9_dp, 1000, 3, 1, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == 0, 'calculate: '//last_message(h))
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call fc_get_tractions(h, n, pn, px, py, ierr)
        call check(error, rel_diff(pn, reshape(nr%pn, [n])) <= 1e-8_dp, 'pn')
        call check(error, rel_diff([px, py], [reshape(tr%px, [n]), reshape(tr%py, [n])]) <= 1e-8_dp, 'px, py')
        call check(error, maxval(abs(px)) > 1e-3_dp*maxval(pn), 'pressing induces tangential tractions')
        call check(error, fn, 10.0_dp, 'Fn', rel=1e-9_dp)
        call fc_finalize(h, ierr)
        call nop%destroy(); call top%destroy()
    end subroutine test_dissimilar

    !> The batch driver (in-process run_driver, namelist case 4 of Table 4.1 at 30×25,
    !! tol 1e−10) and the flat API give the same JSON summary: Fn, Fx, Fy, Mz, approach,
    !! pmax to 1e−10 relative (the JSON carries 16 digits) and equal element counts.
    subroutine test_driver_equal(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: nl = new_line('a')
        character(len=:), allocatable :: dir, json
        character(len=256) :: args(3)
        real(dp) :: fn, fx, fy, mz, appr, pmax
        integer :: h, ierr, u, code, ncon, nadh, nslip, t0, rate, ios
        character(len=1000) :: line
        call system_clock(t0, rate)
        dir = '/tmp/fc_test_legacy_'//inum(t0)
        call execute_command_line("mkdir -p '"//dir//"'")
        open (newunit=u, file=dir//'/c.nml', status='replace', action='write')
        write (u, '(a)') "&case name = 'c4', problem = 'normal+tangential' /"//nl// &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
            '&grid nx = 30, ny = 25, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /'//nl// &
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl//'&normal fn = 9.1954 /'//nl// &
            '&tangential mu = 0.4, xi = 0.0021, eta = 0.0010, phi = 0.003 /'//nl// &
            "&solver normal = 'bccg', tangential = 'tangcg', inner_k = 3, tol = 1.0e-10, maxit = 1000 /"
        close (u)
        args(1) = dir//'/c.nml'; args(2) = '--out'; args(3) = dir
        open (newunit=u, file=dir//'/report.txt', status='replace', action='write')
        call run_driver(args, code, report_unit=u, error_unit=u)
        close (u)
        call check(error, code == 0, 'driver exit code 0')
        json = ''
        open (newunit=u, file=dir//'/c4.json', status='old', action='read', iostat=ios)
        call check(error, ios == 0, 'c4.json written')
        if (allocated(error)) return
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            json = json//trim(line)//nl
        end do
        close (u)
        call execute_command_line("rm -rf '"//dir//"'")
        call cattaneo_handle(h, 30, 25, 1e-10_dp)
        call fc_set_shifts(h, case_xi(4), case_eta(4), case_phi(4), ierr)
        call fc_calculate(h, ierr)
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call fc_get_approach(h, appr, ierr)
        call fc_get_pmax(h, pmax, ierr)
        call fc_get_contact_stats(h, ncon, nadh, nslip, ierr)
        call check(error, ierr == 0, 'flat API: '//last_message(h))
        call check(error, fn, json_real('fn'), 'Fn', rel=1e-10_dp)
        call check(error, fx, json_real('fx'), 'Fx', rel=1e-10_dp)
        call check(error, fy, json_real('fy'), 'Fy', rel=1e-10_dp)
        call check(error, mz, json_real('mz'), 'Mz', rel=1e-10_dp)
        call check(error, appr, json_real('approach'), 'approach', rel=1e-10_dp)
        call check(error, pmax, json_real('pmax'), 'pmax', rel=1e-10_dp)
        call check(error, ncon == nint(json_real('ncon')) .and. nadh == nint(json_real('nadh')) .and. &
            nslip == nint(json_real('nslip')), 'ncon, nadh, nslip')
        call fc_finalize(h, ierr)
    contains
        real(dp) function json_real(key)
            character(len=*), intent(in) :: key
            integer :: k, e, ios2
            json_real = huge(1.0_dp)
            k = index(json, '"'//key//'": ')
            if (k == 0) return
            k = k + len(key) + 4
            e = k + scan(json(k:), ','//nl) - 2
            read (json(k:e), *, iostat=ios2) json_real
        end function json_real
        function inum(i) result(s)
            integer, intent(in) :: i
            character(len=:), allocatable :: s
            character(len=16) :: b
            write (b, '(i0)') i
            s = trim(b)
        end function inum
    end subroutine test_driver_equal

    !> Warm start: a second identical call needs fewer normal and tangential iterations
    !! (shifts: < 1/4, measured 33 → 2 at 30×25; forces: < 1/2); operators are built once
    !! while grid and material stay; moving the
    !! area (same spacing) keeps them; a new material or grid rebuilds them.
    subroutine test_warm_start(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: h, ierr, itn1, itt1, itn2, itt2, nb, tb, nc
        real(dp) :: fn, fx1, fy, mz, fx2
        call cattaneo_handle(h, 30, 25, 1e-8_dp)
        call fc_set_shifts(h, case_xi(4), case_eta(4), case_phi(4), ierr)
        call fc_calculate(h, ierr)
        call fc_get_iterations(h, itn1, itt1, ierr)
        call fc_get_forces(h, fn, fx1, fy, mz, ierr)
        call fc_calculate(h, ierr)
        call fc_get_iterations(h, itn2, itt2, ierr)
        call fc_get_forces(h, fn, fx2, fy, mz, ierr)
        call check(error, ierr == 0, 'second call: '//last_message(h))
        call check(error, itn2 < itn1, 'shifts: normal warm start needs fewer iterations')
        call check(error, 4*itt2 <= itt1, 'shifts: tangential warm start needs < 1/4 of the iterations')
        call check(error, fx2, fx1, 'same Fx', rel=1e-6_dp)
        call fc_set_forces(h, 0.6_dp*mu_cat*fn_cat, 0.0_dp, 0.0_dp, ierr)
        call fc_calculate(h, ierr)
        call fc_get_iterations(h, itn1, itt1, ierr)
        call fc_calculate(h, ierr)
        call fc_get_iterations(h, itn2, itt2, ierr)
        call check(error, ierr == 0, 'forces: '//last_message(h))
        call check(error, 2*itt2 <= itt1, 'forces: tangential warm start needs < 1/2 of the iterations')
        call fc_get_rebuilds(h, nb, tb, nc, ierr)
        call check(error, nb == 1 .and. tb == 1 .and. nc == 4, 'operators built once in 4 calls')
        call fc_set_grid(h, 30, 25, -l_cat + 0.1_dp, l_cat + 0.1_dp, -l_cat, l_cat, ierr)
        call fc_calculate(h, ierr)
        call fc_get_rebuilds(h, nb, tb, nc, ierr)
        call check(error, nb == 1 .and. tb == 1, 'moved area, same spacing: no rebuild')
        call fc_set_material(h, 2*g_cat, 2*g_cat, nu_cat, nu_cat, ierr)
        call fc_calculate(h, ierr)
        call fc_get_rebuilds(h, nb, tb, nc, ierr)
        call check(error, nb == 2 .and. tb == 2, 'new material: rebuild')
        call fc_set_grid(h, 20, 20, -l_cat, l_cat, -l_cat, l_cat, ierr)
        call fc_calculate(h, ierr)
        call fc_get_rebuilds(h, nb, tb, nc, ierr)
        call check(error, ierr == 0 .and. nb == 3 .and. tb == 3 .and. nc == 7, 'new grid: rebuild')
        call fc_finalize(h, ierr)
    end subroutine test_warm_start

    !> fc_set_reuse(h, 0, 0): operators rebuilt at every call, results unchanged.
    subroutine test_no_reuse(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: h, ierr, k, nb, tb, nc
        real(dp) :: fn, fx(3), fy, mz
        call cattaneo_handle(h, 30, 25, 1e-10_dp)
        call fc_set_reuse(h, 0, 0, ierr)
        call fc_set_shifts(h, case_xi(5), case_eta(5), case_phi(5), ierr)
        do k = 1, 3
            call fc_calculate(h, ierr)
            call fc_get_forces(h, fn, fx(k), fy, mz, ierr)
        end do
        call fc_get_rebuilds(h, nb, tb, nc, ierr)
        call check(error, nb == 3 .and. tb == 3 .and. nc == 3, 'rebuilt at each of 3 calls')
        call check(error, fx(1) == fx(2) .and. fx(2) == fx(3), 'identical results without reuse')
        call fc_finalize(h, ierr)
    end subroutine test_no_reuse

    !> fc_set_fft_effort(h, 1): the measured plans give the same forces as the estimated
    !! ones to round-off (1e−10 relative; the CG iterations see only FFT rounding), the
    !! operators are rebuilt once when the effort is switched on; effort 2 is refused.
    subroutine test_fft_effort(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: h(0:1), ierr, e, nb, tb, nc, itn(0:1), itt(0:1)
        real(dp) :: fn(0:1), fx(0:1), fy(0:1), mz
        do e = 0, 1
            call cattaneo_handle(h(e), 16, 12, 1e-10_dp)
            call fc_set_fft_effort(h(e), e, ierr)
            call check(error, ierr == 0, 'fc_set_fft_effort accepted')
            call fc_set_shifts(h(e), case_xi(4), case_eta(4), case_phi(4), ierr)
            call fc_calculate(h(e), ierr)
            call check(error, ierr == 0, 'calculate')
            call fc_get_forces(h(e), fn(e), fx(e), fy(e), mz, ierr)
            call fc_get_iterations(h(e), itn(e), itt(e), ierr)
        end do
        call check(error, fn(1), fn(0), 'Fn measured = estimated', rel=1e-10_dp)
        call check(error, fx(1), fx(0), 'Fx measured = estimated', rel=1e-10_dp)
        call check(error, fy(1), fy(0), 'Fy measured = estimated', rel=1e-10_dp)
        call check(error, abs(itt(1) - itt(0)) <= 1, 'same TangCG iterations (±1)')
        ! switching the effort on after a calculation rebuilds the operators once
        call fc_set_fft_effort(h(0), 1, ierr)
        call fc_calculate(h(0), ierr)
        call fc_calculate(h(0), ierr)
        call fc_get_rebuilds(h(0), nb, tb, nc, ierr)
        call check(error, nb == 2 .and. tb == 2 .and. nc == 3, 'one rebuild after switching to measured plans')
        call fc_set_fft_effort(h(0), 2, ierr)
        call check(error, ierr == FCL_INVALID_VALUE, 'effort 2 refused')
        call check(error, index(last_message(h(0)), 'effort = 2') > 0, 'message names the value')
        call fc_finalize(h(0), ierr); call fc_finalize(h(1), ierr)
    end subroutine test_fft_effort

    !> fc_set_fft_wisdom: the first handle's calculation measures the grid's plans and writes
    !! the file (forces equal the estimated plans' to 1e−10); a second handle, the process
    !! wisdom forgotten, reads the file and measures nothing (file unchanged, same forces);
    !! a file that is not wisdom fails the calculation naming the file, and '' switches it off.
    subroutine test_fft_wisdom(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = 'build/test_legacy_wisdom.fftw', bad = 'build/test_legacy_bad.fftw'
        integer :: h(0:2), ierr, k, u
        real(dp) :: fn(0:2), fx(0:2), fy(0:2), mz
        character(len=:), allocatable :: w1, w2
        call execute_command_line('rm -f '//path)
        do k = 0, 2
            call cattaneo_handle(h(k), 16, 12, 1e-10_dp)
            if (k > 0) then
                call fc_set_fft_wisdom(h(k), path//c_null_char, ierr)
                call check(error, ierr == 0, 'fc_set_fft_wisdom accepted: '//last_message(h(k)))
            end if
            call fc_set_shifts(h(k), case_xi(4), case_eta(4), case_phi(4), ierr)
            if (k == 2) then
                w1 = file_lines(path)
                call fftw_forget_wisdom()
            end if
            call fc_calculate(h(k), ierr)
            call check(error, ierr == 0, 'calculate')
            call fc_get_forces(h(k), fn(k), fx(k), fy(k), mz, ierr)
        end do
        w2 = file_lines(path)
        call check(error, index(w1, '(fftw-3') == 1, 'first calculation wrote the wisdom file')
        call check(error, w1 == w2, 'second handle read the file and measured nothing')
        call check(error, fx(1), fx(0), 'Fx measured = estimated', rel=1e-10_dp)
        call check(error, fy(1), fy(0), 'Fy measured = estimated', rel=1e-10_dp)
        call check(error, fx(2) == fx(1) .and. fy(2) == fy(1), 'plans from the file: the same forces')
        open (newunit=u, file=bad, status='replace', action='write')
        write (u, '(a)') 'not wisdom'
        close (u)
        call fc_set_fft_wisdom(h(0), bad//c_null_char, ierr)
        call fc_calculate(h(0), ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h(0)), bad) > 0, &
            'a file that is not wisdom: FCL_INVALID_VALUE naming it, got: '//last_message(h(0)))
        call fc_set_fft_wisdom(h(0), c_null_char, ierr)
        call fc_calculate(h(0), ierr)
        call check(error, ierr == 0, "'' switches the file off")
        do k = 0, 2
            call fc_finalize(h(k), ierr)
        end do
        call fftw_forget_wisdom()
    end subroutine test_fft_wisdom

    !> The quadratic gap is cached per grid and radii: new radii after a calculation give the
    !! result of a fresh handle with those radii (approach for the same force).
    subroutine test_gap_radii(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: h, h2, ierr
        real(dp) :: d1, d2, d0
        call cattaneo_handle(h, 16, 12, 1e-10_dp)
        call fc_calculate(h, ierr)
        call fc_get_approach(h, d0, ierr)
        call fc_set_gap_quadratic(h, 30.0_dp, 30.0_dp, ierr)
        call fc_calculate(h, ierr)
        call fc_get_approach(h, d1, ierr)
        call cattaneo_handle(h2, 16, 12, 1e-10_dp)
        call fc_set_gap_quadratic(h2, 30.0_dp, 30.0_dp, ierr)
        call fc_calculate(h2, ierr)
        call fc_get_approach(h2, d2, ierr)
        call check(error, abs(d1 - d0) > 1e-3_dp*abs(d0), 'new radii change the approach')
        call check(error, d1, d2, 'approach = fresh handle with the new radii', rel=1e-8_dp)
        call fc_finalize(h, ierr); call fc_finalize(h2, ierr)
    end subroutine test_gap_radii

    !> Load–shift–unload–reload with the normal force fixed (transient mode 1, prescribed
    !! Fx): Q/μFn = 0.25, 0.5, 0.75 (loading), 0.5, 0, −0.5, −0.75 (unloading), −0.25, 0.75
    !! (reloading) on 48×48.  Per step: Fx to 1e−6 μFn; stick radius to one element size
    !! against Cattaneo–Mindlin (loading, c = a(1 − Q/μP)^{1/3}) and Mindlin–Deresiewicz
    !! (unloading from Q*: c' of (Q* − Q)/2) (measured ≤ 0.007 mm, dx = 0.054 mm); the
    !! accumulated shift against the analytic δ(Q) = δ_CM(Q), δ* − 2δ_CM((Q* − Q)/2),
    !! −δ* + 2δ_CM((Q + Q*)/2) within 0.5 % of δ* (measured ≤ 0.15 %) and against the same
    !! superposition of the discrete loading curve (steady solves) within 1 % of δ*; the
    !! tractions follow the superposition q* − 2q((Q* − Q)/2) to 3 % RMS; the reloaded state
    !! at Q* equals the first one at Q* to 1 %.
    subroutine test_hysteresis(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: nx = 48, n = nx*nx, nsteps = 9
        real(dp), parameter :: qs(nsteps) = [0.25_dp, 0.5_dp, 0.75_dp, 0.5_dp, 0.0_dp, -0.5_dp, -0.75_dp, -0.25_dp, 0.75_dp]
        integer, parameter :: branch(nsteps) = [0, 0, 0, 1, 1, 1, 1, 2, 2]   ! 0 load, 1 unload, 2 reload
        real(dp) :: pn(n), px(n), py(n), px_star(n), px_ref(n), px_first(n), pxl(n), pyl(n)
        real(dp) :: fn, fx, fy, mz, xi, eta, phi, shift, qstar, dx, rstick, c_exp, d_exp, d_disc, d_star, dd_star, a
        real(dp) :: x(n), y(n)
        integer :: h, hl, ierr, k, st(n), i, j
        type(fc_cattaneo_solution) :: cm
        character(len=24) :: label
        a = 1
        call cattaneo_handle(h, nx, nx, 1e-9_dp)
        call fc_set_transient(h, FCL_CONTINUE, ierr)
        call cattaneo_handle(hl, nx, nx, 1e-9_dp)      ! steady solves of the loading curve
        dx = 2*l_cat/nx
        do j = 1, nx
            do i = 1, nx
                x(i + (j - 1)*nx) = -l_cat + (i - 0.5_dp)*dx
                y(i + (j - 1)*nx) = -l_cat + (j - 0.5_dp)*dx
            end do
        end do
        qstar = 0.75_dp*mu_cat*fn_cat
        d_star = cm_shift(qstar)
        dd_star = disc_shift(qstar)
        shift = 0
        do k = 1, nsteps
            write (label, '(a,i0,a,f5.2)') 'step ', k, ' Q/muFn=', qs(k)
            call fc_set_forces(h, qs(k)*mu_cat*fn_cat, 0.0_dp, 0.0_dp, ierr)
            call fc_calculate(h, ierr)
            call check(error, ierr == 0, trim(label)//': '//last_message(h))
            if (allocated(error)) exit
            call fc_get_forces(h, fn, fx, fy, mz, ierr)
            call fc_get_shifts(h, xi, eta, phi, ierr)
            call fc_get_tractions(h, n, pn, px, py, ierr)
            call fc_get_status_array(h, n, st, ierr)
            shift = shift + xi
            call check(error, fx, qs(k)*mu_cat*fn_cat, trim(label)//' Fx', abs=1e-6_dp*mu_cat*fn_cat)
            rstick = maxval(hypot(x, y), mask=st == 1)
            select case (branch(k))
            case (0)
                cm = cattaneo_mindlin(a, 4.3905_dp, fn_cat, mu_cat, abs(qs(k))*mu_cat*fn_cat, g_cat, nu_cat)
                c_exp = cm%c
                d_exp = -cm_shift(qs(k)*mu_cat*fn_cat)
                d_disc = -disc_shift(qs(k)*mu_cat*fn_cat)
                if (k == 3) px_star = px
                if (k == 3) px_first = px
            case (1)   ! unloading from +Q*
                cm = cattaneo_mindlin(a, 4.3905_dp, fn_cat, mu_cat, (qstar - qs(k)*mu_cat*fn_cat)/2, g_cat, nu_cat)
                c_exp = cm%c
                d_exp = -(d_star - 2*cm_shift((qstar - qs(k)*mu_cat*fn_cat)/2))
                d_disc = disc_shift((qstar - qs(k)*mu_cat*fn_cat)/2)
                d_disc = -(dd_star - 2*d_disc)
                px_ref = px_star - 2*pxl
                if (k == 7) px_star = px
            case default   ! reloading from −Q*
                cm = cattaneo_mindlin(a, 4.3905_dp, fn_cat, mu_cat, (qstar + qs(k)*mu_cat*fn_cat)/2, g_cat, nu_cat)
                c_exp = cm%c
                d_exp = -(-d_star + 2*cm_shift((qstar + qs(k)*mu_cat*fn_cat)/2))
                d_disc = disc_shift((qstar + qs(k)*mu_cat*fn_cat)/2)
                d_disc = -(-dd_star + 2*d_disc)
                px_ref = px_star + 2*pxl
            end select
            call check(error, rstick, c_exp, trim(label)//' stick radius', abs=dx)
            call check(error, shift, d_exp, trim(label)//' shift vs analytic', abs=0.005_dp*d_star)
            call check(error, shift, d_disc, trim(label)//' shift vs discrete superposition', abs=0.01_dp*d_star)
            if (branch(k) > 0) call check(error, rel_diff(px, px_ref) <= 0.03_dp, trim(label)//' tractions q* - 2q')
        end do
        call check(error, rel_diff(px, px_first) <= 0.01_dp, 'reloaded state at Q* = first state at Q*')
        call fc_finalize(h, ierr); call fc_finalize(hl, ierr)
    contains
        !> Analytic Mindlin shift magnitude for tangential force q ≥ 0.
        real(dp) function cm_shift(q)
            real(dp), intent(in) :: q
            type(fc_cattaneo_solution) :: sol
            sol = cattaneo_mindlin(a, 4.3905_dp, fn_cat, mu_cat, abs(q), g_cat, nu_cat)
            cm_shift = sign(sol%shift, q)
        end function cm_shift
        !> Discrete loading curve: steady solve at force q (sets pxl, pyl); shift magnitude.
        real(dp) function disc_shift(q)
            real(dp), intent(in) :: q
            real(dp) :: f1, f2, f3, f4, x1, x2, x3, pp(n)
            integer :: ie
            if (q == 0) then
                disc_shift = 0; pxl = 0; pyl = 0; return
            end if
            call fc_set_forces(hl, q, 0.0_dp, 0.0_dp, ie)
            call fc_calculate(hl, ie)
            call fc_get_forces(hl, f1, f2, f3, f4, ie)
            call fc_get_shifts(hl, x1, x2, x3, ie)
            call fc_get_tractions(hl, n, pp, pxl, pyl, ie)
            disc_shift = -x1
        end function disc_shift
    end subroutine test_hysteresis

    !> Mode 1: a step with zero shift increment after a shifted state keeps that state
    !! (s = u − u' = 0, p = p'); with the increment the forces follow the steady solve
    !! of the total shift within 1 % (path dependence of Coulomb friction, see the
    !! tangential suite).
    subroutine test_continue_still(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: n = 30*25
        integer :: h, hs, ierr
        real(dp) :: pn(n), px1(n), py1(n), px2(n), py2(n), fn, fx, fy, mz, fxs
        call cattaneo_handle(h, 30, 25, 1e-10_dp)
        call fc_set_transient(h, FCL_CONTINUE, ierr)
        call fc_set_shifts(h, -0.003_dp, 0.0_dp, 0.0_dp, ierr)
        call fc_calculate(h, ierr)
        call fc_get_tractions(h, n, pn, px1, py1, ierr)
        call fc_set_shifts(h, 0.0_dp, 0.0_dp, 0.0_dp, ierr)
        call fc_calculate(h, ierr)
        call fc_get_tractions(h, n, pn, px2, py2, ierr)
        call check(error, ierr == 0, 'zero increment: '//last_message(h))
        call check(error, rel_diff([px2, py2], [px1, py1]) <= 1e-8_dp, 'zero increment keeps the state')
        call fc_set_shifts(h, -0.003_dp, 0.0_dp, 0.0_dp, ierr)
        call fc_calculate(h, ierr)
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call cattaneo_handle(hs, 30, 25, 1e-10_dp)
        call fc_set_shifts(hs, -0.006_dp, 0.0_dp, 0.0_dp, ierr)
        call fc_calculate(hs, ierr)
        call fc_get_forces(hs, fn, fxs, fy, mz, ierr)
        call check(error, fx, fxs, 'two increments ≈ one total shift', rel=0.01_dp)
        call fc_finalize(h, ierr); call fc_finalize(hs, ierr)
    end subroutine test_continue_still

    !> Rolling (mode 2): shift_along_x moves whole elements exactly and interpolates
    !! fractional ones; dq = 0 equals mode 1; rolling from rest with constant creepage
    !! (ξ = −0.002·dq per step, dq = 2·dx, 40 steps ≈ 3.4 contact diameters) approaches a
    !! steady state monotonically (measured: geometric decay, time constant ≈ 0.6 contact
    !! diameters; last step changes Fx by < 0.1 %), with adhesion at the leading edge (x > 0)
    !! and slip at the trailing edge, and Fx between 0 and μFn opposing the creepage.
    subroutine test_rolling(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: n = 30*25
        real(dp) :: f(4, 2), g(4, 2), fn, fx, fy, mz, fx_old, dx, px(n), py(n), pn(n), xs(n), xa, xsl
        integer :: h, h1, ierr, k, st(n), i, j
        real(dp) :: fx1, dfx_old
        f = reshape([1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp, 6.0_dp, 7.0_dp, 8.0_dp], [4, 2])
        call shift_along_x(f, 1.0_dp, g)
        call check(error, all(g(:, 1) == [2.0_dp, 3.0_dp, 4.0_dp, 0.0_dp]), 'whole-element shift')
        call shift_along_x(f, -0.5_dp, g)
        call check(error, all(g(:, 2) == [2.5_dp, 5.5_dp, 6.5_dp, 7.5_dp]), 'half-element shift backwards')
        call shift_along_x(f, 0.0_dp, g)
        call check(error, all(g == f), 'zero shift')
        ! dq = 0 equals mode 1
        call cattaneo_handle(h, 30, 25, 1e-10_dp)
        call cattaneo_handle(h1, 30, 25, 1e-10_dp)
        call fc_set_transient(h, FCL_ROLLING, ierr)
        call fc_set_rolling_step(h, 0.0_dp, ierr)
        call fc_set_transient(h1, FCL_CONTINUE, ierr)
        do k = 1, 2
            call fc_set_shifts(h, -0.002_dp, 0.0_dp, 0.0_dp, ierr)
            call fc_set_shifts(h1, -0.002_dp, 0.0_dp, 0.0_dp, ierr)
            call fc_calculate(h, ierr)
            call fc_calculate(h1, ierr)
        end do
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call fc_get_forces(h1, fn, fx1, fy, mz, ierr)
        call check(error, fx, fx1, 'dq = 0 equals mode 1', rel=1e-12_dp)
        call fc_finalize(h1, ierr)
        ! steady rolling: dq = 2 dx, creepage ξ/dq = −0.002
        dx = 2*l_cat/30
        call fc_finalize(h, ierr)
        call cattaneo_handle(h, 30, 25, 1e-10_dp)
        call fc_set_transient(h, FCL_ROLLING, ierr)
        call fc_set_rolling_step(h, 2*dx, ierr)
        fx = 0; fx_old = 0
        do k = 1, 40
            call fc_set_shifts(h, -0.002_dp*2*dx, 0.0_dp, 0.0_dp, ierr)
            call fc_calculate(h, ierr)
            if (ierr /= 0) exit
            dfx_old = fx - fx_old
            fx_old = fx
            call fc_get_forces(h, fn, fx, fy, mz, ierr)
            call check(error, k < 3 .or. fx - fx_old < dfx_old, 'Fx approaches its steady value monotonically')
        end do
        call check(error, ierr == 0, 'rolling steps: '//last_message(h))
        call check(error, fx, fx_old, 'steady state: last step changes Fx < 0.1 %', rel=1e-3_dp)
        call check(error, fx > 0 .and. fx < mu_cat*fn_cat, 'Fx opposes the creepage, below mu Fn')
        call fc_get_status_array(h, n, st, ierr)
        call fc_get_tractions(h, n, pn, px, py, ierr)
        do j = 1, 25
            do i = 1, 30
                xs(i + (j - 1)*30) = -l_cat + (i - 0.5_dp)*dx
            end do
        end do
        call check(error, count(st == 1) > 0 .and. count(st == 2) > 0, 'adhesion and slip present')
        xa = sum(xs, mask=st == 1)/max(1, count(st == 1))
        xsl = sum(xs, mask=st == 2)/max(1, count(st == 2))
        call check(error, xa > 0 .and. xsl < xa, 'adhesion at the leading edge, slip at the trailing edge')
        call fc_finalize(h, ierr)
    end subroutine test_rolling

    !> Invalid handles and wrong call order return error codes with messages; bad values
    !! name the routine and value; too-small arrays; non-convergence keeps a readable
    !! result; finalised slots are reused; no handle leaks.
    subroutine test_errors(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: h, h2, h3, ierr, nlive0, nlive, itn, itt
        real(dp) :: fn, fx, fy, mz, small(10), big(30*25), pn(30*25)
        character(len=8) :: tiny_buf
        call fc_get_nhandles(nlive0, ierr)
        call fc_calculate(0, ierr)
        call check(error, ierr == FCL_INVALID_HANDLE, 'handle 0 → 1')
        call check(error, index(last_message(0), 'fc_calculate: invalid handle 0') > 0, 'message: '//last_message(0))
        call fc_set_friction(12345, 0.3_dp, ierr)
        call check(error, ierr == FCL_INVALID_HANDLE .and. index(last_message(0), '12345') > 0, 'handle 12345 → 1')
        call fc_get_forces(-3, fn, fx, fy, mz, ierr)
        call check(error, ierr == FCL_INVALID_HANDLE, 'negative handle → 1')
        call fc_init(h, ierr)
        call check(error, ierr == 0 .and. h >= 1, 'init')
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_ORDER .and. index(last_message(h), 'material') > 0, 'calculate first: '//last_message(h))
        call fc_set_gap_array(h, 10, small, ierr)
        call check(error, ierr == FCL_ORDER .and. index(last_message(h), 'fc_set_grid') > 0, 'gap before grid')
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call check(error, ierr == FCL_ORDER .and. index(last_message(h), 'fc_calculate') > 0, 'get before calculate')
        call fc_set_material(h, -1.0_dp, 200.0_dp, 0.3_dp, 0.3_dp, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'g1') > 0, 'g1 < 0: '//last_message(h))
        call fc_set_material(h, 200.0_dp, 200.0_dp, 0.3_dp, 0.6_dp, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'nu2') > 0, 'nu2: '//last_message(h))
        call fc_set_grid(h, 0, 5, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'nx') > 0, 'nx = 0: '//last_message(h))
        call fc_set_normal_force(h, -2.0_dp, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'fn = -2') > 0, 'fn < 0: '//last_message(h))
        call fc_set_friction(h, -0.1_dp, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'mu') > 0, 'mu < 0')
        call fc_set_solver(h, 7, 1, 1e-8_dp, 100, 3, 1, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'normal_solver = 7') > 0, 'solver code')
        call fc_set_solver(h, 1, 1, 1e-8_dp, 100, 0, 1, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'inner_k') > 0, 'inner_k = 0')
        call fc_set_solver(h, 1, 1, 1e-8_dp, 100, 3, 3, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'precondition = 3') > 0, &
            'precondition = 3: '//last_message(h))
        call fc_set_solver(h, 1, 1, 1e-8_dp, 100, 3, 2, ierr)
        call check(error, ierr == FCL_OK, 'precondition = 2 (Toeplitz form) accepted')
        call fc_set_transient(h, 5, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'mode = 5') > 0, 'transient mode')
        call fc_set_material(h, g_cat, g_cat, nu_cat, nu_cat, ierr)
        call fc_set_grid(h, 30, 25, -l_cat, l_cat, -l_cat, l_cat, ierr)
        call fc_set_gap_array(h, 10, small, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'n = 10') > 0, 'gap size')
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_ORDER .and. index(last_message(h), 'undeformed') > 0, 'no gap: '//last_message(h))
        call fc_set_gap_quadratic(h, r_cat, r_cat, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_ORDER .and. index(last_message(h), 'normal') > 0, 'no normal loading')
        call fc_set_normal_force(h, fn_cat, ierr)
        call fc_set_shifts(h, 0.001_dp, 0.0_dp, 0.0_dp, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_ORDER .and. index(last_message(h), 'friction') > 0, 'no friction')
        call fc_set_friction(h, mu_cat, ierr)
        call fc_set_forces(h, 1.2_dp*mu_cat*fn_cat, 0.0_dp, 0.0_dp, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'mu*fn') > 0, '|F| > mu Fn: '// &
            last_message(h))
        call fc_set_normal_approach(h, -1.0_dp, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(last_message(h), 'no contact') > 0, 'no contact')
        ! not converged: readable result, error code 4
        call fc_set_normal_force(h, fn_cat, ierr)
        call fc_set_shifts(h, case_xi(5), case_eta(5), case_phi(5), ierr)
        call fc_set_solver(h, 1, 1, 1e-12_dp, 2, 3, 1, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_NOT_CONVERGED .and. index(last_message(h), 'not converged') > 0, &
            'maxit = 2 → 4: '//last_message(h))
        call fc_get_iterations(h, itn, itt, ierr)
        call check(error, ierr == 0 .and. itn > 0, 'result readable after non-convergence')
        call fc_set_solver(h, 1, 1, 1e-8_dp, 1000, 3, 1, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == 0, 'recovers: '//last_message(h))
        call fc_get_tractions(h, 10, small, small, small, ierr)
        call check(error, ierr == FCL_ARRAY_SIZE .and. index(last_message(h), 'n = 10') > 0, 'small array → 6')
        call fc_get_tractions(h, 30*25, pn, big, big, ierr)
        call check(error, ierr == 0, 'right-size array')
        call fc_get_error_message(h, tiny_buf, len(tiny_buf), ierr)
        call check(error, tiny_buf(8:8) == c_null_char, 'message truncated and NUL-terminated')
        ! finalise, stale handle, slot reuse
        h3 = h
        call fc_finalize(h, ierr)
        call fc_calculate(h3, ierr)
        call check(error, ierr == FCL_INVALID_HANDLE, 'finalised handle → 1')
        call fc_finalize(h3, ierr)
        call check(error, ierr == FCL_INVALID_HANDLE, 'double finalize → 1')
        call fc_init(h2, ierr)
        call check(error, h2 == h3, 'slot reused after finalize')
        call fc_finalize(h2, ierr)
        call fc_get_nhandles(nlive, ierr)
        call check(error, nlive == nlive0, 'no handle leaked')
    end subroutine test_errors

    !> fc_get_edge_contact: Hertz Test I (a = 6.0, b = 4.0 mm at approach 0.1091) inside
    !! ±10 × ±6 mm reports 0; on ±5 × ±3 mm, which clips the ellipse, 1 — also after a
    !! tangential calculation that reuses the normal solution; an unknown handle is an error.
    subroutine test_edge_contact(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: h, ierr, touches
        call fc_init(h, ierr)
        call fc_set_material(h, 82000.0_dp, 82000.0_dp, 0.28_dp, 0.28_dp, ierr)
        call fc_set_grid(h, 32, 32, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, ierr)
        call fc_set_gap_quadratic(h, 300.0_dp, 163.0_dp, ierr)
        call fc_set_normal_approach(h, 0.1091_dp, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == 0, 'calculate: '//last_message(h))
        if (allocated(error)) return
        call fc_get_edge_contact(h, touches, ierr)
        call check(error, ierr == 0 .and. touches == 0, 'contact inside the area: 0')
        call fc_set_grid(h, 32, 32, -5.0_dp, 5.0_dp, -3.0_dp, 3.0_dp, ierr)
        call fc_calculate(h, ierr)
        call fc_get_edge_contact(h, touches, ierr)
        call check(error, ierr == 0 .and. touches == 1, 'area clips the contact: 1')
        call fc_set_friction(h, 0.3_dp, ierr)
        call fc_set_shifts(h, 0.001_dp, 0.0_dp, 0.0_dp, ierr)
        call fc_calculate(h, ierr)
        call fc_get_edge_contact(h, touches, ierr)
        call check(error, ierr == 0 .and. touches == 1, 'still 1 after a tangential calculation')
        call fc_finalize(h, ierr)
        call fc_get_edge_contact(h, touches, ierr)
        call check(error, ierr /= 0 .and. touches == 0, 'released handle: an error, 0')
    end subroutine test_edge_contact

end module test_legacy
