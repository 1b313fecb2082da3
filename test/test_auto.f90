!> Suite `auto`: accuracy-targeted refinement against analytic Hertz, Cattaneo and a
!! finer rough-punch reference; the automatic potential contact area; model reductions against
!! the full model; and the user guide's key tables against the keys the reader accepts.
!! Cases are read from namelist text exactly as the driver reads them ([[fc_input]]), built into
!! the library's [[fc_case]] and solved
!! by [[solve_case_auto]] in-process.
!!
!! Size (~820 lines, 22 tests): one file per suite.
module test_auto
    use fc_kinds, only: dp, msg_len, pi
    use fc_testing, only: error_type, unittest_type, new_unittest, check, read_all => file_lines
    use fc_namelist, only: fc_case_chunk, read_case_file
    use fc_input, only: fc_case_input, apply_case, namelist_keys
    use fc_input_validate, only: validate_case
    use fc_input_scene, only: build_case
    use fc_scene, only: fc_case
    use fc_contact, only: fc_contact_operators
    use fc_hertz, only: fc_hertz_solution, hertz_from_approach, hertz_from_force
    use fc_auto, only: fc_auto_outcome, solve_case_auto, richardson_estimate, plane_strain_hertz
    use fc_test_driver, only: fresh_dir, run_namelist, exists => file_exists
    use test_driver, only: json_num
    implicit none
    private

    public :: collect_auto

    character(len=*), parameter :: nl = new_line('a')
    character(len=*), parameter :: hertz_scene = &
        '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
        "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"//nl// &
        '&normal approach = 0.1091 /'//nl
    character(len=*), parameter :: cattaneo_scene = &
        "&case problem = 'normal+tangential' /"//nl// &
        '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
        '&grid nx = 16, ny = 16, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /'//nl// &
        "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl// &
        '&normal approach = 0.02 /'//nl// &
        '&tangential mu = 0.4, xi = -0.0081724, eta = 0.0, phi = 0.0 /'//nl
    character(len=*), parameter :: punch_scene = &
        '&material g1 = 1.0e30, g2 = 40000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
        '&grid nx = 16, ny = 16, xmin = -6.0, xmax = 6.0, ymin = -5.0, ymax = 5.0 /'//nl// &
        "&geometry kind = 'punch_rough', diameter = 8.97 /"//nl// &
        '&normal approach = 0.01 /'//nl

contains

    !> The auto suite.
    subroutine collect_auto(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('richardson_rules', test_richardson), &
            new_unittest('hertz_target_auto_area', test_hertz_target_auto), &
            new_unittest('hertz_target_fixed_grid', test_hertz_target_fixed), &
            new_unittest('target_refines_the_longer_side', test_target_anisotropic), &
            new_unittest('hertz_target_with_pmax', test_hertz_target_pmax), &
            new_unittest('cattaneo_target', test_cattaneo_target), &
            new_unittest('loose_target_given_grid_suffices', test_loose_target), &
            new_unittest('target_bound_given_grids', test_target_bound_given_grids), &
            new_unittest('certified_grid_not_finer_than_needed', test_certified_grid), &
            new_unittest('target_sweep_bound_holds', test_target_sweep), &
            new_unittest('target_bound_untuned_scenes', test_target_untuned), &
            new_unittest('rough_punch_target_non_monotone', test_punch_target), &
            new_unittest('target_not_met_reported', test_target_not_met), &
            new_unittest('auto_area_covers_contact', test_auto_area), &
            new_unittest('auto_area_enlarged_when_clipped', test_enlarge), &
            new_unittest('fixed_grid_clipped_warns', test_fixed_warns), &
            new_unittest('target_outputs_json_report', test_target_outputs), &
            new_unittest('reduction_hertz_analytic', test_reduction_hertz), &
            new_unittest('reduction_cattaneo_analytic', test_reduction_cattaneo), &
            new_unittest('reduction_line_contact_strip', test_reduction_strip), &
            new_unittest('reduction_no_tangential_loading', test_reduction_no_tangential), &
            new_unittest('reduction_k0_decoupled', test_reduction_k0), &
            new_unittest('user_guide_keys_match_reader', test_guide_keys) ]
    end subroutine collect_auto

    ! ---------------------------------------------------------------- helpers ----

    !> Read namelist `text` as the driver does (every case applied in order, the last kept),
    !! validate it and solve it with the automatic layer.
    subroutine solve_text(text, out, error)
        character(len=*), intent(in) :: text
        type(fc_auto_outcome), intent(out) :: out
        type(error_type), allocatable, intent(inout) :: error
        type(fc_case_chunk), allocatable :: cases(:)
        type(fc_case_input) :: state
        type(fc_case) :: kase
        type(fc_contact_operators) :: ops
        character(len=64) :: name
        character(len=msg_len) :: msg
        integer :: u, stat, k
        character(len=*), parameter :: path = 'build/test_auto_case.nml'
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') text
        close (u)
        call read_case_file(path, cases, stat, msg)
        call check(error, stat == 0, 'read: '//trim(msg))
        if (allocated(error)) return
        do k = 1, size(cases)
            call apply_case(cases(k), k, state, name, stat, msg)
            call check(error, stat == 0, 'apply: '//trim(msg))
            if (allocated(error)) return
        end do
        call validate_case(state, stat, msg)
        call check(error, stat == 0, 'validate: '//trim(msg))
        if (allocated(error)) return
        kase = build_case(state)
        call solve_case_auto(kase, ops, out, stat, msg)
        call check(error, stat == 0, 'solve: '//trim(msg))
        call ops%destroy()
    end subroutine solve_text

    !> "N²" for a square grid of N elements per side.
    function fmt_grid(n) result(text)
        integer, intent(in) :: n
        character(len=:), allocatable :: text
        character(len=12) :: buf
        write (buf, '(i0)') n
        text = trim(buf)//'²'
    end function fmt_grid

    !> Analytic Hertz of the Cattaneo sphere (R = 50, G = 200, nu = 0.42 both bodies, approach 0.02).
    function cattaneo_hertz() result(hz)
        type(fc_hertz_solution) :: hz
        hz = hertz_from_approach(0.01_dp, 0.01_dp, 200.0_dp/0.58_dp, 0.02_dp)
    end function cattaneo_hertz

    !> Analytic Hertz of Test I.
    function test_i_hertz() result(hz)
        type(fc_hertz_solution) :: hz
        hz = hertz_from_approach(1/600.0_dp, 1/326.0_dp, 82000.0_dp/0.72_dp, 0.1091_dp)
    end function test_i_hertz

    function num(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(es11.4)') x
        s = trim(adjustl(buf))
    end function num

    logical function has_line(list, word)
        character(len=*), allocatable, intent(in) :: list(:)
        character(len=*), intent(in) :: word
        integer :: k
        has_line = .false.
        if (.not. allocated(list)) return
        do k = 1, size(list)
            if (index(list(k), word) > 0) has_line = .true.
        end do
    end function has_line

    ! ---------------------------------------------------------------- tests ----

    !> The estimator on synthetic sequences: clean O(h²) is extrapolated (estimate ≥ true
    !! error, within the safety factor of it); a sign change is flagged non-monotone with the
    !! bound max(|d_k|, |d_k−1|); slower convergence (ratio 2) is not extrapolated as O(h²);
    !! the safety factor is 1.5 for a ratio in [3, 6] and 2 outside; two grids give 2|d|.
    subroutine test_richardson(error)
        type(error_type), allocatable, intent(out) :: error
        real(dp) :: est, r, q(3)
        logical :: mono
        q = 1 + 0.01_dp*[1.0_dp, 0.25_dp, 0.0625_dp]
        call richardson_estimate(q/q(3), 1.0e-12_dp, est, r, mono)
        call check(error, mono .and. abs(r - 4) < 1e-9_dp, 'clean O(h^2): monotone, ratio 4')
        call check(error, est >= 0.0625e-2_dp/q(3) .and. est <= 2.01_dp*0.0625e-2_dp, 'clean O(h^2) estimate '//num(est))
        q = 1 + 0.01_dp*[1.0_dp, -0.5_dp, 0.2_dp]
        call richardson_estimate(q, 1.0e-12_dp, est, r, mono)
        call check(error, .not. mono, 'sign change must be non-monotone')
        call check(error, est, 0.015_dp, 'non-monotone bound max(|d_k|, |d_k-1|)', rel=1e-9_dp)
        q = 1 + 0.01_dp*[1.0_dp, 0.5_dp, 0.25_dp]
        call richardson_estimate(q, 1.0e-12_dp, est, r, mono)
        call check(error, mono .and. est >= 0.0025_dp, 'O(h) sequence: estimate '//num(est)//' >= true error 2.5e-3')
        ! safety factors: 1.5 for an observed ratio in [3, 6] (the O(h²) regime), 2 outside
        q = 1 + 0.01_dp*[1.0_dp, 0.2_dp, 0.04_dp]
        call richardson_estimate(q, 1.0e-12_dp, est, r, mono)
        call check(error, est, 1.5_dp*0.008_dp/12, 'ratio 5: 1.5 |d_k-1|/12 (> 1.5 |d_k|/3)', rel=1e-9_dp)
        q = 1 + 0.01_dp*[1.0_dp, 0.4_dp, 0.16_dp]
        call richardson_estimate(q, 1.0e-12_dp, est, r, mono)
        call check(error, est, 2*0.0024_dp/1.5_dp, 'ratio 2.5: 2 |d|/(r - 1)', rel=1e-9_dp)
        ! two grids: no rate known, the error is only assumed to at least halve per level
        call richardson_estimate([1.01_dp, 1.0_dp], 1.0e-12_dp, est, r, mono)
        call check(error, est, 0.02_dp, 'two grids: 2 |d|', rel=1e-9_dp)
    end subroutine test_richardson

    !> Hertz Test I, automatic area and grid, target 1e-3 on fn: the true error (analytic
    !! Hertz) lies within the estimate and the target; the grid one level coarser misses.
    subroutine test_hertz_target_auto(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        type(fc_hertz_solution) :: hz
        real(dp) :: err, err_coarse
        integer :: n
        call solve_text(hertz_scene//'&solver target = 1.0e-3 /'//nl, out, error)
        if (allocated(error)) return
        hz = test_i_hertz()
        n = size(out%levels)
        call check(error, out%grid_auto .and. n >= 3 .and. out%target_met .and. out%reliable, &
            'auto grid, >= 3 grids, target met, reliable')
        if (allocated(error)) return
        err = abs(out%result%normal%fn - hz%fn)/hz%fn
        err_coarse = abs(out%levels(n - 1)%fn - hz%fn)/hz%fn
        call check(error, err <= out%estimate, 'true error '//num(err)//' within the estimate '//num(out%estimate))
        call check(error, err <= 1.0e-3_dp, 'true error '//num(err)//' meets the target')
        call check(error, err_coarse > 1.0e-3_dp, 'one level coarser must miss the target: '//num(err_coarse))
    end subroutine test_hertz_target_auto

    !> Hertz Test I on its fixed area from 16² (probe 8²): target 5e-4 on fn stops at 64² (true
    !! error 1.5e-4); 32² has 5.5e-4 and misses.  The level records keep the grids and costs.
    subroutine test_hertz_target_fixed(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        type(fc_hertz_solution) :: hz
        real(dp) :: err, err_coarse
        integer :: n
        call solve_text(hertz_scene//'&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'// &
            nl//'&solver target = 5.0e-4 /'//nl, out, error)
        if (allocated(error)) return
        hz = test_i_hertz()
        n = size(out%levels)
        call check(error, .not. out%grid_auto .and. out%target_met, 'fixed grid, target met')
        call check(error, out%levels(1)%nx == 8 .and. out%levels(n)%nx == 8*2**(n - 1), 'probe 8, then 16, 32, ... by two')
        call check(error, all(out%levels%seconds >= 0) .and. out%total_seconds >= maxval(out%levels%seconds), &
            'cost recorded (the total covers every grid)')
        if (allocated(error)) return
        err = abs(out%result%normal%fn - hz%fn)/hz%fn
        err_coarse = abs(out%levels(n - 1)%fn - hz%fn)/hz%fn
        call check(error, err <= out%estimate .and. out%estimate <= 5.0e-4_dp, 'true error '//num(err)// &
            ' <= estimate '//num(out%estimate)//' <= target')
        call check(error, err_coarse > 5.0e-4_dp, 'one level coarser must miss the target: '//num(err_coarse))
    end subroutine test_hertz_target_fixed

    !> Hertz Test I on a 16×64 grid over 20×12 mm: elements 1.25 × 0.1875 mm.  The target
    !! refines x alone (probe 8×64, then 16, 32 × 64) until the elements are within a factor
    !! two of squares, then both directions; the estimate still bounds the true error.
    !! (Before, both directions doubled from the start: 32×128, 64×256, …)
    subroutine test_target_anisotropic(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        type(fc_hertz_solution) :: hz
        real(dp) :: err, dx, dy
        integer :: k, n
        logical :: ok
        call solve_text(hertz_scene//'&grid nx = 16, ny = 64, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'// &
            nl//'&solver target = 5.0e-4 /'//nl, out, error)
        if (allocated(error)) return
        n = size(out%levels)
        call check(error, out%target_met .and. n >= 3, 'target met after the probe and two grids at least')
        if (allocated(error)) return
        call check(error, out%levels(1)%nx == 8 .and. out%levels(1)%ny == 64, 'probe coarsened in x only')
        ok = .true.
        do k = 2, n
            dx = 20.0_dp/out%levels(k - 1)%nx; dy = 12.0_dp/out%levels(k - 1)%ny
            if (dy <= 0.5_dp*dx) then
                ok = ok .and. out%levels(k)%nx == 2*out%levels(k - 1)%nx .and. out%levels(k)%ny == out%levels(k - 1)%ny
            else
                ok = ok .and. out%levels(k)%nx == 2*out%levels(k - 1)%nx .and. out%levels(k)%ny == 2*out%levels(k - 1)%ny
            end if
        end do
        call check(error, ok, 'x alone while its elements are over twice as long as in y, then both')
        call check(error, out%levels(2)%ny == 64 .and. out%levels(3)%ny == 64, 'y kept at 64 on 16 and 32 in x')
        hz = test_i_hertz()
        err = abs(out%result%normal%fn - hz%fn)/hz%fn
        call check(error, err <= out%estimate .and. out%estimate <= 5.0e-4_dp, 'true error '//num(err)// &
            ' <= estimate '//num(out%estimate)//' <= target')
    end subroutine test_target_anisotropic

    !> With target_pmax the estimate covers the pmax error too (true errors vs analytic p0).
    subroutine test_hertz_target_pmax(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        type(fc_hertz_solution) :: hz
        real(dp) :: efn, ep
        call solve_text(hertz_scene//'&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'// &
            nl//'&solver target = 1.0e-3, target_pmax = .true. /'//nl, out, error)
        if (allocated(error)) return
        hz = test_i_hertz()
        efn = abs(out%result%normal%fn - hz%fn)/hz%fn
        ep = abs(out%result%normal%pmax - hz%p0)/hz%p0
        call check(error, out%target_met .and. index(out%quantities, 'pmax') > 0, 'target met on fn and pmax')
        call check(error, max(efn, ep) <= out%estimate, 'true errors fn '//num(efn)//', pmax '//num(ep)// &
            ' within the estimate '//num(out%estimate))
        call check(error, out%levels(size(out%levels) - 1)%estimate > 1.0e-3_dp, &
            'the previous grid could not stop (its estimate missed the target)')
    end subroutine test_hertz_target_pmax

    !> Cattaneo (shift prescribed, K = 0, approach 0.02): target 2e-4 on fn and (Fx, Fy).  True
    !! errors: fn vs analytic Hertz; Fx vs a finer (2×) solve of the same discretisation (the
    !! discrete Fx converges to 3.2222, 0.12 % above Cattaneo-Mindlin, whose slip-zone solution
    !! neglects the nu-coupling; checked separately to 1.5e-3).  One level coarser misses.
    subroutine test_cattaneo_target(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out, ref
        type(fc_hertz_solution) :: hz
        real(dp) :: efn, efx, efn_coarse, q
        integer :: n, nref
        character(len=16) :: buf
        call solve_text(cattaneo_scene//'&solver target = 2.0e-4 /'//nl, out, error)
        if (allocated(error)) return
        n = size(out%levels)
        call check(error, out%tangential .and. out%target_met, 'tangential solved, target met')
        if (allocated(error)) return
        nref = 2*out%levels(n)%nx
        write (buf, '(i0)') nref
        call solve_text(cattaneo_scene//'&grid nx = '//trim(buf)//', ny = '//trim(buf)//' /'//nl// &
            '&solver tol = 1.0e-8 /'//nl, ref, error)
        if (allocated(error)) return
        hz = cattaneo_hertz()
        efn = abs(out%result%normal%fn - hz%fn)/hz%fn
        efn_coarse = abs(out%levels(n - 1)%fn - hz%fn)/hz%fn
        efx = abs(out%result%tangential%fx - ref%result%tangential%fx)/abs(ref%result%tangential%fx)
        call check(error, max(efn, efx) <= out%estimate, 'true errors fn '//num(efn)//', Fx '//num(efx)// &
            ' within the estimate '//num(out%estimate))
        call check(error, out%estimate <= 2.0e-4_dp, 'estimate meets the target')
        call check(error, efn_coarse > 2.0e-4_dp, 'one level coarser misses the target: fn error '//num(efn_coarse))
        q = 0.875_dp*0.4_dp*hz%fn
        call check(error, abs(out%result%tangential%fx - q)/q < 1.5e-3_dp, 'Fx within 1.5e-3 of Cattaneo-Mindlin 0.875 mu Fn')
    end subroutine test_cattaneo_target

    !> Cattaneo from 16², target 3e-2: the probe grid 8² lets the given grid itself be the
    !! answer (two-grid estimate 2|d|, flagged as such); the true errors of 16² (fn vs
    !! analytic Hertz, Fx vs a 64² solve) lie within the estimate and the target.  (8² meets
    !! 3e-2 too: with est = 2|d| a two-grid stop can only be minimal when the probe is barely
    !! worse than the given grid, i.e. before the asymptotic regime.)
    subroutine test_loose_target(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out, ref
        type(fc_hertz_solution) :: hz
        real(dp) :: efn, efx
        call solve_text(cattaneo_scene//'&solver target = 3.0e-2 /'//nl, out, error)
        if (allocated(error)) return
        call solve_text(cattaneo_scene//'&grid nx = 64, ny = 64 /'//nl//'&solver tol = 1.0e-8 /'//nl, ref, error)
        if (allocated(error)) return
        call check(error, size(out%levels) == 2 .and. out%target_met, 'two grids (probe 8², given 16²), target met')
        if (allocated(error)) return
        call check(error, out%levels(1)%nx == 8 .and. out%grid%nx == 16, 'the answer is on the given 16² grid')
        call check(error, has_line(out%warnings, 'two grids'), 'two-grid estimate flagged')
        hz = cattaneo_hertz()
        efn = abs(out%result%normal%fn - hz%fn)/hz%fn
        efx = abs(out%result%tangential%fx - ref%result%tangential%fx)/abs(ref%result%tangential%fx)
        call check(error, max(efn, efx) <= out%estimate .and. out%estimate <= 3.0e-2_dp, 'true errors fn '//num(efn)// &
            ', Fx '//num(efx)//' <= estimate '//num(out%estimate)//' <= target')
    end subroutine test_loose_target

    !> The issue's "not finer than needed" on the coarsest grid certified by the finest one
    !! (JSON `coarsest_sufficient`), at 1e-3 for Hertz Test I and Cattaneo from 16² (the
    !! rough punch: in `rough_punch_target_non_monotone`, at 1e-2): its true error meets the
    !! target within the certified bound, and the grid one level below misses the target.
    !! Both solves go one grid beyond it (64²): seeing that grid is what certifies 32².
    subroutine test_certified_grid(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out, ref
        type(fc_hertz_solution) :: hz
        real(dp) :: e, e_below
        integer :: j
        call solve_text(hertz_scene//'&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'// &
            nl//'&solver target = 1.0e-3 /'//nl, out, error)
        if (allocated(error)) return
        hz = test_i_hertz()
        j = out%sufficient
        call check(error, out%target_met .and. j >= 2 .and. j < size(out%levels), 'Hertz: a grid coarser than the '// &
            'finest is certified')
        if (allocated(error)) return
        e = abs(out%levels(j)%fn - hz%fn)/hz%fn
        e_below = abs(out%levels(j - 1)%fn - hz%fn)/hz%fn
        call check(error, e <= out%sufficient_bound .and. out%sufficient_bound <= 1.0e-3_dp, 'Hertz: certified '// &
            fmt_grid(out%levels(j)%nx)//' true '//num(e)//' <= bound '//num(out%sufficient_bound)//' <= 1e-3')
        call check(error, e_below > 1.0e-3_dp, 'Hertz: one level below the certified grid misses: '//num(e_below))
        call solve_text(cattaneo_scene//'&solver target = 1.0e-3 /'//nl, out, error)
        if (allocated(error)) return
        call solve_text(cattaneo_scene//'&grid nx = 256, ny = 256 /'//nl//'&solver tol = 1.0e-8 /'//nl, ref, error)
        if (allocated(error)) return
        hz = cattaneo_hertz()
        j = out%sufficient
        call check(error, out%target_met .and. j >= 2 .and. j < size(out%levels), 'Cattaneo: a grid coarser than '// &
            'the finest is certified')
        if (allocated(error)) return
        e = max(abs(out%levels(j)%fn - hz%fn)/hz%fn, &
            abs(out%levels(j)%fx - ref%result%tangential%fx)/abs(ref%result%tangential%fx))
        e_below = max(abs(out%levels(j - 1)%fn - hz%fn)/hz%fn, &
            abs(out%levels(j - 1)%fx - ref%result%tangential%fx)/abs(ref%result%tangential%fx))
        call check(error, e <= out%sufficient_bound .and. out%sufficient_bound <= 1.0e-3_dp, 'Cattaneo: certified '// &
            fmt_grid(out%levels(j)%nx)//' true '//num(e)//' <= bound '//num(out%sufficient_bound)//' <= 1e-3')
        call check(error, e_below > 1.0e-3_dp, 'Cattaneo: one level below the certified grid misses: '//num(e_below))
    end subroutine test_certified_grid

    !> The bound from given grids where the two finest grids happen to err alike.  The former
    !! two-grid estimate 2|d|/3 (the O(h²) rate) failed on both: Cattaneo given 64² (probe 32²,
    !! fn error 1.2e-4, 1.4× that estimate) and a sphere (R = 20, Fn = 500) on the fixed area
    !! [−1, 1]² given 16² (probe 8², approach error 3.9e-3, 1.2×).  True errors: fn and approach
    !! vs analytic Hertz, Fx vs a 256² solve.
    subroutine test_target_bound_given_grids(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out, ref
        type(fc_hertz_solution) :: hz
        real(dp) :: e
        call solve_text(cattaneo_scene//'&grid nx = 64, ny = 64 /'//nl//'&solver target = 1.0e-3 /'//nl, out, error)
        if (allocated(error)) return
        call solve_text(cattaneo_scene//'&grid nx = 256, ny = 256 /'//nl//'&solver tol = 1.0e-8 /'//nl, ref, error)
        if (allocated(error)) return
        hz = cattaneo_hertz()
        e = max(abs(out%result%normal%fn - hz%fn)/hz%fn, &
            abs(out%result%tangential%fx - ref%result%tangential%fx)/abs(ref%result%tangential%fx))
        call check(error, out%levels(1)%nx == 32 .and. out%target_met, 'Cattaneo from 64² (probe 32²): target met')
        call check(error, e <= out%estimate .and. out%estimate <= 1.0e-3_dp, 'Cattaneo from 64²: true '//num(e)// &
            ' <= estimate '//num(out%estimate)//' <= 1e-3')
        call solve_text('&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            "&geometry kind = 'quadratic', rx = 20.0, ry = 20.0 /"//nl//'&normal fn = 500.0 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -1.0, xmax = 1.0, ymin = -1.0, ymax = 1.0 /'//nl// &
            '&solver target = 5.0e-3 /'//nl, out, error)
        if (allocated(error)) return
        hz = hertz_from_force(1/40.0_dp, 1/40.0_dp, 82000.0_dp/0.72_dp, 500.0_dp)
        e = abs(out%result%normal%approach - hz%approach)/hz%approach
        call check(error, out%levels(1)%nx == 8 .and. out%target_met, 'sphere from 16² (probe 8²): target met')
        call check(error, e <= out%estimate .and. out%estimate <= 5.0e-3_dp, 'sphere from 16²: true '//num(e)// &
            ' <= estimate '//num(out%estimate)//' <= 5e-3')
    end subroutine test_target_bound_given_grids

    !> Reliability over a sweep of targets (the property a user relies on): for every target
    !! from 1e-2 to 1e-4 (Hertz Test I from 16²) or 2e-4 (Cattaneo from 16², Fx against a 256²
    !! solve whose own Fx error is ~2e-6), the target is reported met and the true error lies
    !! within the estimate, which lies within the target; the coarsest grid certified by the
    !! finest one (`sufficient`) has its true error within its certified bound, which lies
    !! within the target.  (Whether a grid is the coarsest sufficient one is measured, not
    !! asserted, by fastcontact-bench-auto: the solved grid in 5 of 21 targets here and 23 %
    !! over its replay from every given grid; the certified grid in 90 % of the replay.)
    subroutine test_target_sweep(error)
        type(error_type), allocatable, intent(out) :: error
        real(dp), parameter :: targets(7) = [1.0e-2_dp, 5.0e-3_dp, 2.0e-3_dp, 1.0e-3_dp, 5.0e-4_dp, 2.0e-4_dp, 1.0e-4_dp]
        type(fc_auto_outcome) :: out, ref
        type(fc_hertz_solution) :: hz, hc
        real(dp) :: e
        integer :: t
        character(len=16) :: tb
        hz = test_i_hertz()
        hc = cattaneo_hertz()
        call solve_text(cattaneo_scene//'&grid nx = 256, ny = 256 /'//nl//'&solver tol = 1.0e-8 /'//nl, ref, error)
        if (allocated(error)) return
        do t = 1, size(targets)
            write (tb, '(es9.2)') targets(t)
            call solve_text(hertz_scene//'&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'// &
                nl//'&solver target = '//trim(adjustl(tb))//' /'//nl, out, error)
            if (allocated(error)) return
            e = abs(out%result%normal%fn - hz%fn)/hz%fn
            call check(error, out%target_met .and. e <= out%estimate .and. out%estimate <= targets(t), 'Hertz T = '// &
                trim(tb)//': true '//num(e)//' <= estimate '//num(out%estimate)//' <= T, met')
            if (allocated(error)) return
            call check(error, out%sufficient >= 1 .and. out%sufficient <= size(out%levels), 'Hertz T = '//trim(tb)// &
                ': a certified grid')
            if (allocated(error)) return
            e = abs(out%levels(out%sufficient)%fn - hz%fn)/hz%fn
            call check(error, e <= out%sufficient_bound .and. out%sufficient_bound <= targets(t), 'Hertz T = '// &
                trim(tb)//': certified grid true '//num(e)//' <= bound '//num(out%sufficient_bound)//' <= T')
            if (t == size(targets)) exit
            call solve_text(cattaneo_scene//'&solver target = '//trim(adjustl(tb))//' /'//nl, out, error)
            if (allocated(error)) return
            e = max(abs(out%result%normal%fn - hc%fn)/hc%fn, &
                abs(out%result%tangential%fx - ref%result%tangential%fx)/abs(ref%result%tangential%fx))
            call check(error, out%target_met .and. e <= out%estimate .and. out%estimate <= targets(t), 'Cattaneo T = '// &
                trim(tb)//': true '//num(e)//' <= estimate '//num(out%estimate)//' <= T, met')
            if (allocated(error)) return
            call check(error, out%sufficient >= 1, 'Cattaneo T = '//trim(tb)//': a certified grid')
            if (allocated(error)) return
            associate (l => out%levels(out%sufficient))
                e = max(abs(l%fn - hc%fn)/hc%fn, abs(l%fx - ref%result%tangential%fx)/abs(ref%result%tangential%fx))
            end associate
            call check(error, e <= out%sufficient_bound .and. out%sufficient_bound <= targets(t), 'Cattaneo T = '// &
                trim(tb)//': certified grid true '//num(e)//' <= bound '//num(out%sufficient_bound)//' <= T')
        end do
    end subroutine test_target_sweep

    !> Scenes not used to choose the estimator (force prescribed, so the estimated quantity is
    !! the approach; automatic area, probe 10²): an ellipse with rx/ry = 20 (Fn = 1e4) and a
    !! sphere R = 20 (Fn = 500), G = 82000, nu = 0.28.  For targets 1e-2 and 2e-3 the true
    !! approach error against analytic Hertz lies within the estimate and the target
    !! (measured: 1.1e-3 within 2.3e-3 at 20²; sphere 2.3e-4 within 5.5e-4 at 40²).
    subroutine test_target_untuned(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        type(fc_hertz_solution) :: hz
        real(dp) :: e
        integer :: c, t
        real(dp), parameter :: rx(2) = [1000.0_dp, 20.0_dp], ry(2) = [50.0_dp, 20.0_dp], fn(2) = [1.0e4_dp, 500.0_dp]
        character(len=*), parameter :: tnames(2) = ['1.0e-2', '2.0e-3'], scenes(2) = ['ellipse', 'sphere ']
        real(dp), parameter :: targets(2) = [1.0e-2_dp, 2.0e-3_dp]
        character(len=96) :: geo
        do c = 1, 2
            write (geo, '(a,f0.1,a,f0.1,a,f0.1,a)') "&geometry kind = 'quadratic', rx = ", rx(c), ', ry = ', ry(c), &
                ' /'//nl//'&normal fn = ', fn(c), ' /'
            hz = hertz_from_force(1/(2*rx(c)), 1/(2*ry(c)), 82000.0_dp/0.72_dp, fn(c))
            do t = 1, 2
                call solve_text('&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl//trim(geo)//nl// &
                    '&solver target = '//tnames(t)//' /'//nl, out, error)
                if (allocated(error)) return
                e = abs(out%result%normal%approach - hz%approach)/hz%approach
                call check(error, out%grid_auto .and. out%target_met .and. e <= out%estimate .and. &
                    out%estimate <= targets(t), trim(scenes(c))//' T = '//tnames(t)//': true '//num(e)// &
                    ' <= estimate '//num(out%estimate)//' <= T')
            end do
        end do
    end subroutine test_target_untuned

    !> Rough punch (delta = 0.01) from 16², target 1e-2: convergence of fn is non-monotone
    !! (punch-rim staircase); the outcome is flagged unreliable, the bound holds against a
    !! 256² reference, and the previous grid's estimate had missed the target (so the
    !! algorithm could not stop earlier — the coarser grid's TRUE error happens to be smaller,
    !! which no estimator can know from oscillating data).
    subroutine test_punch_target(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out, ref
        real(dp) :: err
        integer :: n
        call solve_text(punch_scene//'&solver target = 1.0e-2 /'//nl, out, error)
        if (allocated(error)) return
        call solve_text(punch_scene//'&grid nx = 256, ny = 256 /'//nl//'&solver tol = 1.0e-8 /'//nl, ref, error)
        if (allocated(error)) return
        n = size(out%levels)
        err = abs(out%result%normal%fn - ref%result%normal%fn)/ref%result%normal%fn
        call check(error, out%target_met .and. .not. out%reliable, 'target met by the bound, flagged non-monotone')
        call check(error, has_line(out%warnings, 'non-monotone'), 'non-monotone convergence warned about')
        call check(error, out%levels(n)%nx < 256, 'stopped before the reference grid')
        call check(error, err <= out%estimate .and. err <= 1.0e-2_dp, 'true error '//num(err)//' within the estimate '// &
            num(out%estimate)//' and the target')
        call check(error, out%levels(n - 1)%estimate > 1.0e-2_dp, 'previous grid estimate missed the target')
        if (allocated(error)) return
        ! the coarsest grid certified by the finest one: 32² (bound 4.3e-3), and 16² misses
        call check(error, out%sufficient >= 2 .and. out%sufficient < n, 'a coarser grid than the finest is certified')
        if (allocated(error)) return
        err = abs(out%levels(out%sufficient)%fn - ref%result%normal%fn)/ref%result%normal%fn
        call check(error, err <= out%sufficient_bound .and. out%sufficient_bound <= 1.0e-2_dp, 'certified '// &
            fmt_grid(out%levels(out%sufficient)%nx)//': true error '//num(err)//' <= bound '// &
            num(out%sufficient_bound)//' <= T')
        err = abs(out%levels(out%sufficient - 1)%fn - ref%result%normal%fn)/ref%result%normal%fn
        call check(error, err > 1.0e-2_dp, 'one level below the certified grid misses the target: '//num(err))
    end subroutine test_punch_target

    !> A target that max_levels cannot reach is reported as not met, with a warning.
    subroutine test_target_not_met(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        call solve_text(hertz_scene//'&grid nx = 8, ny = 8, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'// &
            nl//'&solver target = 1.0e-6, max_levels = 3 /'//nl, out, error)
        if (allocated(error)) return
        call check(error, size(out%levels) == 3 .and. .not. out%target_met, '3 grids, target not met')
        call check(error, has_line(out%warnings, 'NOT MET'), 'warning says NOT MET')
    end subroutine test_target_not_met

    !> Automatic area for an elliptic Hertz contact: half-widths (1 + margin)·(a, b), the
    !! analytic ellipse inside with its margin, no contact in the boundary rows or columns.
    subroutine test_auto_area(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        type(fc_hertz_solution) :: hz
        call solve_text(hertz_scene, out, error)
        if (allocated(error)) return
        hz = test_i_hertz()
        call check(error, out%grid_auto .and. out%enlargements == 0, 'auto, not enlarged')
        call check(error, out%grid%xmax, 1.25_dp*hz%a, 'xmax = 1.25 a', rel=1e-9_dp)
        call check(error, out%grid%ymax, 1.25_dp*hz%b, 'ymax = 1.25 b', rel=1e-9_dp)
        call check(error, -out%grid%xmin >= 1.25_dp*hz%a*(1 - 1e-9_dp), 'xmin covers a with the margin')
        call check(error, .not. out%touches_boundary, 'contact not clipped')
        call check(error, .not. any(out%result%normal%pn(1, :) > 0) .and. .not. any(out%result%normal%pn(:, out%grid%ny) > 0), &
            'no contact in the boundary elements')
        call check(error, out%grid%nx == 40, '32 elements across the contact x 1.25 = 40')
        call check(error, abs(out%result%normal%fn - hz%fn)/hz%fn < 2e-3_dp, 'fn within 2e-3 of Hertz')
    end subroutine test_auto_area

    !> margin = 0: the area is exactly the Hertz ellipse's box, contact reaches its boundary,
    !! and the area is enlarged ×1.5 (same element size) until it does not.
    subroutine test_enlarge(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        type(fc_hertz_solution) :: hz
        call solve_text(hertz_scene//'&grid auto = .true., margin = 0.0 /'//nl, out, error)
        if (allocated(error)) return
        hz = test_i_hertz()
        call check(error, out%enlargements >= 1, 'enlarged at least once')
        call check(error, .not. out%touches_boundary, 'final contact not clipped')
        call check(error, out%grid%xmax > 1.4_dp*hz%a, 'area grew by 1.5')
        call check(error, abs(out%grid%dx - 2*hz%a/32) < 1e-9_dp*hz%a, 'element size kept')
        call check(error, has_line(out%reductions, 'enlarged'), 'enlargement reported')
    end subroutine test_enlarge

    !> A user-fixed area that clips the contact: solved as given, warned in the JSON
    !! (`warnings`, `touches_boundary`) and in the report.
    subroutine test_fixed_warns(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: json, report
        integer :: code
        character(len=:), allocatable :: dir
        dir = run_in_tmp("&case name = 'clipped' /"//nl//hertz_scene// &
            '&grid nx = 16, ny = 16, xmin = -4.0, xmax = 4.0, ymin = -3.0, ymax = 3.0 /'//nl, code)
        json = read_all(dir//'/clipped.json')
        report = read_all(dir//'/report.txt')
        call check(error, code == 0, 'case solved')
        call check(error, index(json, '"touches_boundary": true') > 0, 'JSON touches_boundary true')
        call check(error, index(json, '"warnings": ["CONTACT REACHES THE BOUNDARY') > 0, 'JSON warnings: '//json)
        call check(error, index(report, '*** WARNING  CONTACT REACHES THE BOUNDARY') > 0, 'report warns loudly')
        call execute_command_line("rm -rf '"//dir//"'")
    end subroutine test_fixed_warns

    !> The driver's outputs of a targeted case: JSON `accuracy.coarsest_sufficient` (Hertz Test
    !! I, automatic area, target 1e-3: solved up to 40², 40² certified, see doc/benchmarks.md),
    !! `ncon` per level, and the report line naming the certified grid.
    subroutine test_target_outputs(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: json, report, dir
        integer :: code
        dir = run_in_tmp("&case name = 'tgt' /"//nl//hertz_scene//'&solver target = 1.0e-3 /'//nl, code)
        json = read_all(dir//'/tgt.json')
        report = read_all(dir//'/report.txt')
        call check(error, code == 0, 'case solved')
        call check(error, index(json, '"coarsest_sufficient": {"nx": 40, "ny": 40, "bound": ') > 0, &
            'JSON accuracy.coarsest_sufficient 40x40: '//json)
        call check(error, index(json, '{"nx": 10, "ny": 10, "ncon": ') > 0, 'JSON levels carry ncon')
        call check(error, index(report, 'coarsest grid meeting the target: 40 x 40') > 0, 'report names the certified grid')
        call execute_command_line("rm -rf '"//dir//"'")
    end subroutine test_target_outputs

    !> problem = 'hertz' (no grid) agrees with the full numerical model at target 1e-3 within
    !! 2e-3 in fn and pmax, and its JSON carries a, b, p0, fn, approach.
    subroutine test_reduction_hertz(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: ana, full
        character(len=:), allocatable :: json, dir
        integer :: code
        call solve_text("&case problem = 'hertz' /"//nl//hertz_scene, ana, error)
        if (allocated(error)) return
        call solve_text(hertz_scene//'&solver target = 1.0e-3 /'//nl, full, error)
        if (allocated(error)) return
        call check(error, ana%analytic .and. ana%model == 'hertz_analytic' .and. size(ana%levels) == 0, 'no grid')
        call check(error, full%result%normal%fn, ana%hertz%fn, 'fn: analytic vs full', rel=2e-3_dp)
        call check(error, full%result%normal%pmax, ana%hertz%p0, 'pmax: analytic vs full', rel=2e-3_dp)
        dir = run_in_tmp("&case name = 'ana', problem = 'hertz' /"//nl//hertz_scene, code)
        json = read_all(dir//'/ana.json')
        call check(error, code == 0 .and. index(json, '"model": "hertz_analytic"') > 0, 'JSON model')
        call check(error, index(json, '"hertz": {"a": 6.00199') > 0, 'JSON hertz a: '//json)
        call check(error, .not. exists(dir//'/ana.csv'), 'no table without a grid')
        call execute_command_line("rm -rf '"//dir//"'")
    end subroutine test_reduction_hertz

    !> problem = 'hertz' with a tangential force on a sphere: Cattaneo–Mindlin stick radius
    !! 0.5 mm and shift 0.008172 mm (doc/conventions.md); the numerical shift for the same force agrees
    !! within 2.5 % at 64² (the discrete problem converges 0.2 % away, Mindlin's approximation),
    !! and so does its frictional dissipation with Mindlin–Deresiewicz's (measured 0.8 %, ν = 0.42);
    !! the driver's JSON carries the analytic answer's dissipation.
    subroutine test_reduction_cattaneo(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: ana, full
        character(len=:), allocatable :: dir, json
        integer :: code
        character(len=*), parameter :: scene = &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl// &
            '&normal fn = 9.1954 /'//nl//'&tangential mu = 0.4, fx = 3.218390, fy = 0.0 /'//nl
        call solve_text("&case problem = 'hertz' /"//nl//scene, ana, error)
        if (allocated(error)) return
        call check(error, ana%has_cattaneo, 'Cattaneo-Mindlin computed')
        call check(error, ana%cattaneo%c, 0.5_dp, 'stick radius', rel=1e-3_dp)
        call check(error, ana%cattaneo%shift, 0.008172_dp, 'shift', rel=1e-3_dp)
        call solve_text("&case problem = 'normal+tangential' /"//nl//scene// &
            '&grid nx = 64, ny = 64, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /'//nl, full, error)
        if (allocated(error)) return
        call check(error, -full%result%tangential%xi, ana%cattaneo%shift, 'numerical shift vs Cattaneo-Mindlin', rel=2.5e-2_dp)
        write (*, '(a,2es12.4)') '    reduction_cattaneo: dissipation numerical, Mindlin-Deresiewicz [N mm] ', &
            full%result%tangential%dissipation, ana%cattaneo%dissipation
        call check(error, full%result%tangential%dissipation, ana%cattaneo%dissipation, &
            'dissipation: numerical vs Mindlin-Deresiewicz', rel=2.5e-2_dp)
        ! the driver reports the analytic answer's dissipation
        dir = run_in_tmp("&case name = 'cm', problem = 'hertz' /"//nl//scene, code)
        json = read_all(dir//'/cm.json')
        call check(error, code == 0 .and. abs(json_num(json, 'dissipation') - ana%cattaneo%dissipation) <= &
            1e-9_dp*ana%cattaneo%dissipation, 'JSON dissipation of the analytic answer: '//json(1:min(300, len(json))))
        call execute_command_line("rm -rf '"//dir//"'")
    end subroutine test_reduction_cattaneo

    !> A cylinder (line contact) becomes the 2D strip: n×1 grid, pmax and half-width within 1 %
    !! of plane-strain Hertz (what the line contact is), far cheaper than a 3D grid.
    subroutine test_reduction_strip(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: out
        real(dp) :: b, p0, width
        call solve_text('&material g1 = 82000.0, g2 = 82000.0 /'//nl// &
            "&geometry kind = 'cylinder', rx = 100.0, length = 100.0 /"//nl//'&normal fn = 1.0e5 /'//nl, out, error)
        if (allocated(error)) return
        call plane_strain_hertz(100.0_dp, 1000.0_dp, 82000.0_dp/0.72_dp, b, p0)
        call check(error, out%model == 'strip2d' .and. out%grid%ny == 1, 'strip model, n x 1')
        call check(error, has_line(out%reductions, 'line contact'), 'reduction reported')
        call check(error, out%result%normal%pmax, p0, 'pmax vs plane-strain Hertz', rel=1e-2_dp)
        width = count(out%result%normal%pn(:, 1) > 0)*out%grid%dx
        call check(error, width, 2*b, 'contact width vs 2b', rel=0.05_dp)
        call check(error, .not. out%touches_boundary, 'strip not clipped in x')
    end subroutine test_reduction_strip

    !> mu = 0, or zero shifts with K = 0: no tangential solve; the full model confirms zero
    !! tractions and the same normal answer.
    subroutine test_reduction_no_tangential(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: red, full
        character(len=*), parameter :: zero = "&case problem = 'normal+tangential' /"//nl//hertz_scene// &
            '&grid nx = 32, ny = 32, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl// &
            '&tangential mu = 0.3, xi = 0.0, eta = 0.0, phi = 0.0 /'//nl
        call solve_text(zero, red, error)
        if (allocated(error)) return
        call solve_text(zero//"&solver model = 'full' /"//nl, full, error)
        if (allocated(error)) return
        call check(error, .not. red%tangential .and. has_line(red%reductions, 'no tangential'), 'no tangential solve')
        call check(error, full%tangential, 'full model solves the tangential problem')
        call check(error, abs(full%result%tangential%fx) + abs(full%result%tangential%fy) <= &
            1e-8_dp*0.3_dp*full%result%normal%fn, 'full: zero forces')
        call check(error, red%result%normal%fn, full%result%normal%fn, 'same fn', rel=1e-6_dp)
        call solve_text(replace_mu(zero), red, error)
        if (allocated(error)) return
        call check(error, .not. red%tangential .and. has_line(red%reductions, 'mu = 0'), 'mu = 0: frictionless')
    contains
        function replace_mu(text) result(t)
            character(len=*), intent(in) :: text
            character(len=:), allocatable :: t
            integer :: p
            p = index(text, 'mu = 0.3, xi = 0.0')
            t = text(1:p - 1)//'mu = 0.0, xi = 1.0e-3'//text(p + len('mu = 0.3, xi = 0.0'):)
        end function replace_mu
    end subroutine test_reduction_no_tangential

    !> K = 0: the decoupled path (one normal, one tangential solve) equals the coupled
    !! pipeline solve_normal_tangential (model = 'full') to the solver tolerance.
    subroutine test_reduction_k0(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_auto_outcome) :: red, full
        call solve_text(cattaneo_scene//'&grid nx = 32, ny = 32 /'//nl//'&solver tol = 1.0e-8 /'//nl, red, error)
        if (allocated(error)) return
        call solve_text(cattaneo_scene//'&grid nx = 32, ny = 32 /'//nl//"&solver tol = 1.0e-8, model = 'full' /"//nl, &
            full, error)
        if (allocated(error)) return
        call check(error, has_line(red%reductions, 'K = 0'), 'K = 0 reduction reported')
        call check(error, red%result%tangential%fx, full%result%tangential%fx, 'Fx decoupled = coupled pipeline', rel=1e-6_dp)
        call check(error, red%result%normal%fn, full%result%normal%fn, 'fn decoupled = coupled pipeline', rel=1e-8_dp)
    end subroutine test_reduction_k0

    !> Every key in the user guide's key tables (doc/user_guide.md, section "Namelist
    !! reference": under each "### `&group`" heading, the back-quoted names in the first
    !! column) exists in the reader, and every key the reader accepts is in the guide.
    subroutine test_guide_keys(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=65), allocatable :: reader(:), guide(:)
        character(len=:), allocatable :: missing, extra
        integer :: k
        reader = namelist_keys()
        call guide_keys('doc/user_guide.md', guide)
        call check(error, size(guide) > 30, 'guide tables parsed')
        if (allocated(error)) return
        missing = ''; extra = ''
        do k = 1, size(reader)
            if (.not. any(guide == reader(k))) missing = missing//' '//trim(reader(k))//';'
        end do
        do k = 1, size(guide)
            if (.not. any(reader == guide(k))) extra = extra//' '//trim(guide(k))//';'
        end do
        call check(error, len(missing) == 0, 'keys of the reader missing from the guide:'//missing)
        call check(error, len(extra) == 0, 'keys in the guide the reader does not accept:'//extra)
    end subroutine test_guide_keys

    !> 'group key' of every key in the guide's namelist tables.
    subroutine guide_keys(path, keys)
        character(len=*), intent(in) :: path
        character(len=65), allocatable, intent(out) :: keys(:)
        character(len=1024) :: line
        character(len=32) :: group
        character(len=:), allocatable :: cell
        integer :: u, ios, p, q, bar
        logical :: in_ref
        allocate (keys(0))
        open (newunit=u, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        group = ''; in_ref = .false.
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (index(line, '## ') == 1) then
                in_ref = index(line, 'Namelist reference') > 0
                group = ''
            end if
            if (.not. in_ref) cycle
            if (index(line, '### `&') == 1) then
                p = index(line, '&')
                q = index(line(p:), '`') + p - 2
                group = line(p + 1:q)
                cycle
            end if
            if (len_trim(group) == 0 .or. line(1:1) /= '|') cycle
            bar = index(line(2:), '|') + 1
            cell = line(2:bar - 1)
            if (index(cell, '---') > 0) cycle
            do
                p = index(cell, '`')
                if (p == 0) exit
                q = index(cell(p + 1:), '`')
                if (q == 0) exit
                if (verify(cell(p + 1:p + q - 1), 'abcdefghijklmnopqrstuvwxyz0123456789_') == 0) &
                    keys = [character(len=65) :: keys, trim(group)//' '//cell(p + 1:p + q - 1)]
                cell = cell(p + q + 1:)
            end do
        end do
        close (u)
    end subroutine guide_keys

    ! ---------------------------------------------------------------- driver helpers ----

    function run_in_tmp(text, code) result(dir)
        character(len=*), intent(in) :: text
        integer, intent(out) :: code
        character(len=:), allocatable :: dir
        dir = fresh_dir('auto')
        call run_namelist(dir, text, code)
    end function run_in_tmp

end module test_auto
