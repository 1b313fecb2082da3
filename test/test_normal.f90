!> Suite `normal`: NORM and BCCG on Hertz Test I and the rough punch (doc/conventions.md).
module test_normal
    use fc_kinds
    use fc_geometry
    use fc_influence
    use fc_norm
    use fc_hertz
    use fc_testing
    implicit none
    private
    public :: collect_normal

    real(dp), parameter :: test1_approach = 0.1091_dp

contains

    subroutine collect_normal(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('spec_selfcheck_32', test_selfcheck), &
            new_unittest('hertz_force_and_error_32_64_128', test_hertz_grids), &
            new_unittest('hertz_contact_area_matches_ellipse', test_contact_area), &
            new_unittest('norm_and_bccg_agree', test_agree), &
            new_unittest('prescribed_force', test_force), &
            new_unittest('preconditioner_forms_agree', test_prec_forms), &
            new_unittest('rough_punch_three_cases', test_rough_punch), &
            new_unittest('direct_oracle_complementarity', test_oracle), &
            new_unittest('strip2d_line_contact', test_strip), &
            new_unittest('errors_reported', test_errors), &
            new_unittest('not_converged_reported', test_not_converged), &
            new_unittest('norm_readings', test_norm_readings) ]
    end subroutine collect_normal

    !> BCCG with its preconditioner applied as the Strang circulant on the grid (default) and
    !! as the Toeplitz inverse on the doubled grid: Hertz Test I at 64² with a prescribed
    !! approach and a prescribed force.  Both converge to the same pressures (tol 1e−10:
    !! 1e−8 of pmax), and the circulant needs at most two iterations more at tol 1e−5
    !! (measured: the same counts) while being applied (precond_applications > 0).
    subroutine test_prec_forms(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: ns
        type(fc_normal_result) :: rc, rt
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        integer :: stat, mode
        character(len=200) :: msg
        character(len=32) :: label
        call test1_setup(64, nop, h0, grid)
        do mode = 1, 2
            label = merge('approach', 'force   ', mode == 1)
            ns = fc_normal_settings()
            call check(error, ns%prec_form == 'circulant', 'circulant is the default')
            call solve_mode(rc)
            ns%prec_form = 'toeplitz'
            call solve_mode(rt)
            call check(error, rc%status == FC_CONVERGED .and. rt%status == FC_CONVERGED, trim(label)//': both converged')
            call check(error, rc%precond_applications > 0 .and. rt%precond_applications > 0, trim(label)//': preconditioned')
            write (msg, '(a,i0,a,i0,a)') ': circulant iterations ', rc%iterations, ' <= toeplitz ', rt%iterations, ' + 2'
            call check(error, rc%iterations <= rt%iterations + 2, trim(label)//trim(msg))
            ns = fc_normal_settings(); ns%tol = 1e-10_dp
            call solve_mode(rc)
            ns%prec_form = 'toeplitz'
            call solve_mode(rt)
            call check(error, maxval(abs(rc%pn - rt%pn)) <= 1e-8_dp*maxval(rt%pn), trim(label)//': same pressures')
            if (allocated(error)) return
        end do
        ns%prec_form = 'fft'
        call solve_normal(nop, h0, ns, rc, stat, msg, approach=test1_approach)
        call check(error, stat /= 0 .and. index(msg, "prec_form = 'fft'") > 0, 'unknown form refused: '//trim(msg))
    contains
        subroutine solve_mode(r)
            type(fc_normal_result), intent(out) :: r
            if (mode == 1) then
                call solve_normal(nop, h0, ns, r, stat, msg, approach=test1_approach)
            else
                call solve_normal(nop, h0, ns, r, stat, msg, fn=60000.0_dp)
            end if
            call check(error, stat == 0, trim(label)//': stat 0 '//trim(msg))
        end subroutine solve_mode
    end subroutine test_prec_forms

    subroutine test1_setup(n, nop, h0, grid)
        integer, intent(in) :: n
        type(fc_normal_operator), intent(inout) :: nop
        real(dp), allocatable, intent(out) :: h0(:, :)
        type(fc_grid), intent(out) :: grid
        type(fc_material) :: mat
        integer :: stat
        character(len=200) :: msg
        mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, n, n, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
        h0 = quadratic_gap(grid, 300.0_dp, 163.0_dp)
        call build_normal_operator(nop, mat, grid)
    end subroutine test1_setup

    function test1_hertz() result(s)
        type(fc_hertz_solution) :: s
        s = hertz_from_approach(1/600.0_dp, 1/326.0_dp, 82000/0.72_dp, test1_approach)
    end function test1_hertz

    real(dp) function rms_error(grid, p, s)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: p(:, :)
        type(fc_hertz_solution), intent(in) :: s
        integer :: i, j
        rms_error = 0
        do j = 1, grid%ny
            do i = 1, grid%nx
                rms_error = rms_error + (p(i, j) - s%pressure(grid%x(i), grid%y(j)))**2
            end do
        end do
        rms_error = sqrt(rms_error/grid%n())
    end function rms_error

    !> Self-check of doc/conventions.md (dense solve): 32², approach 0.1091 → F = 82049.40, 332 contact
    !! cells, pmax = 1628.29.  Both solvers at tol 1e−8; tolerance 0.01 on F and pmax
    !! (the quoted digits).
    subroutine test_selfcheck(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        integer :: stat, k
        character(len=200) :: msg
        character(len=4), parameter :: solvers(2) = ['bccg', 'norm']
        call test1_setup(32, nop, h0, grid)
        set%tol = 1e-8_dp
        do k = 1, 2
            set%solver = solvers(k)
            call solve_normal(nop, h0, set, res, stat, msg, approach=test1_approach)
            call check(error, stat == 0 .and. res%status == FC_CONVERGED, solvers(k)//' converged: '//trim(res%message))
            call check(error, res%fn, 82049.40_dp, solvers(k)//' F', abs=0.01_dp)
            call check(error, res%ncon == 332, solvers(k)//' 332 contact cells')
            call check(error, res%pmax, 1628.29_dp, solvers(k)//' pmax', abs=0.01_dp)
        end do
    end subroutine test_selfcheck

    !> Hertz Test I on 32², 64², 128² with BCCG (tol 1e−5): total force within 0.5 % of the
    !! analytic force for the prescribed approach; RMS pressure error no larger than the
    !! thesis Table 2.4 discrete error + 10 % (16.59, 6.77, 3.70); the error falls by a
    !! factor 1.4–3 per refinement (O(h)).
    subroutine test_hertz_grids(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_grid) :: grid
        type(fc_hertz_solution) :: s
        real(dp), allocatable :: h0(:, :)
        real(dp) :: err(3)
        real(dp), parameter :: table24(3) = [16.59_dp, 6.77_dp, 3.70_dp]
        integer :: stat, k, n
        character(len=200) :: msg
        character(len=20) :: label
        s = test1_hertz()
        do k = 1, 3
            n = 32*2**(k - 1)
            write (label, '(i0,a,i0)') n, 'x', n
            call test1_setup(n, nop, h0, grid)
            call solve_normal(nop, h0, set, res, stat, msg, approach=test1_approach)
            call check(error, res%status == FC_CONVERGED, trim(label)//' converged')
            call check(error, res%fn, s%fn, trim(label)//' force vs Hertz', rel=0.005_dp)
            err(k) = rms_error(grid, res%pn, s)
            call check(error, err(k) <= 1.1_dp*table24(k), trim(label)//' RMS error within Table 2.4 + 10 %')
        end do
        call check(error, err(1)/err(2) > 1.4_dp .and. err(1)/err(2) < 3, 'error ratio 32→64 in (1.4, 3)')
        call check(error, err(2)/err(3) > 1.4_dp .and. err(2)/err(3) < 3, 'error ratio 64→128 in (1.4, 3)')
        call nop%destroy()
    end subroutine test_hertz_grids

    !> Contact elements match the analytic ellipse up to boundary cells: every element whose
    !! centre lies inside the ellipse shrunk by one cell diagonal is in contact, and none
    !! outside the ellipse grown by one cell diagonal (64²).
    subroutine test_contact_area(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_grid) :: grid
        type(fc_hertz_solution) :: s
        real(dp), allocatable :: h0(:, :)
        real(dp) :: diag, rin, rout
        integer :: stat, i, j, nbad
        character(len=200) :: msg
        s = test1_hertz()
        call test1_setup(64, nop, h0, grid)
        call solve_normal(nop, h0, set, res, stat, msg, approach=test1_approach)
        diag = hypot(grid%dx, grid%dy)
        nbad = 0
        do j = 1, grid%ny
            do i = 1, grid%nx
                rin = (grid%x(i)/(s%a - diag))**2 + (grid%y(j)/(s%b - diag))**2
                rout = (grid%x(i)/(s%a + diag))**2 + (grid%y(j)/(s%b + diag))**2
                if (rin < 1 .and. res%pn(i, j) <= 0) nbad = nbad + 1
                if (rout > 1 .and. res%pn(i, j) > 0) nbad = nbad + 1
            end do
        end do
        call check(error, nbad == 0, 'contact set differs from the ellipse beyond boundary cells')
        call check(error, .not. res%touches_boundary, 'Test I contact stays inside the potential area')
        ! a deeper approach pushes the contact to the edge of [−10,10]×[−6,6]: flagged
        call solve_normal(nop, h0, set, res, stat, msg, approach=0.3_dp)
        call check(error, res%touches_boundary .and. index(res%message, 'edge') > 0, &
            'contact reaching the edge is flagged: '//trim(res%message))
        call nop%destroy()
    end subroutine test_contact_area

    !> NORM and BCCG give the same solution: both at tol 1e−9, pressures agree to 1e−6
    !! relative (RMS) on 64² Hertz; contact sets identical.
    subroutine test_agree(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: r1, r2
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        integer :: stat
        character(len=200) :: msg
        call test1_setup(64, nop, h0, grid)
        set%tol = 1e-9_dp
        set%solver = 'bccg'
        call solve_normal(nop, h0, set, r1, stat, msg, approach=test1_approach)
        set%solver = 'norm'
        call solve_normal(nop, h0, set, r2, stat, msg, approach=test1_approach)
        call check(error, r1%status == FC_CONVERGED .and. r2%status == FC_CONVERGED, 'both converged')
        call check(error, all((r1%pn > 0) .eqv. (r2%pn > 0)), 'same contact set')
        call check(error, rel_diff(pack(r1%pn, .true.), pack(r2%pn, .true.)), 0.0_dp, 'pressures agree', abs=1e-6_dp)
        call nop%destroy()
    end subroutine test_agree

    !> NORM's research readings (thesis Table 2.8, bench/norm_table28.f90): the readings that
    !! converge reach the same solution as ours on Hertz Test I 32²; 'restart' with 4 CG steps
    !! per active-set step does not converge where ours does (each step starts from p = 0); an unknown reading
    !! is an error.
    subroutine test_norm_readings(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: r0, r1
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        integer :: stat, k
        character(len=200) :: msg
        character(len=16), parameter :: readings(3) = [character(len=16) :: 'add_if_no_drop', 'add_on_zero', &
            'recompute_u']
        call test1_setup(32, nop, h0, grid)
        set%solver = 'norm'; set%tol = 1e-8_dp
        call solve_normal(nop, h0, set, r0, stat, msg, approach=test1_approach)
        call check(error, r0%status == FC_CONVERGED, 'ours converged')
        do k = 1, size(readings)
            set%norm_reading = readings(k)
            call solve_normal(nop, h0, set, r1, stat, msg, approach=test1_approach)
            call check(error, stat == 0 .and. r1%status == FC_CONVERGED, trim(readings(k))//' converged')
            call check(error, rel_diff(pack(r1%pn, .true.), pack(r0%pn, .true.)), 0.0_dp, trim(readings(k))//' = ours', &
                abs=1e-6_dp)
        end do
        set%norm_reading = ''; set%inner_maxit = 4; set%maxit = 60; set%tol = 1e-6_dp
        call solve_normal(nop, h0, set, r1, stat, msg, approach=test1_approach)
        call check(error, stat == 0 .and. r1%status == FC_CONVERGED, 'ours with 4 CG steps converges')
        set%norm_reading = 'restart'
        call solve_normal(nop, h0, set, r1, stat, msg, approach=test1_approach)
        call check(error, stat == 0 .and. r1%status /= FC_CONVERGED, 'restart with 4 CG steps does not converge')
        set%norm_reading = 'bogus'
        call solve_normal(nop, h0, set, r1, stat, msg, approach=test1_approach)
        call check(error, stat /= 0 .and. index(msg, 'norm_reading') > 0, 'unknown reading rejected: '//trim(msg))
        call nop%destroy()
    end subroutine test_norm_readings

    !> Prescribed total force 82004 N (the Hertz force of approach 0.1091): both solvers hit
    !! the force to 1e−10 relative and find the approach within 0.5 % of Hertz's 0.1091.
    subroutine test_force(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        integer :: stat, k
        character(len=200) :: msg
        character(len=4), parameter :: solvers(2) = ['bccg', 'norm']
        call test1_setup(64, nop, h0, grid)
        do k = 1, 2
            set%solver = solvers(k)
            call solve_normal(nop, h0, set, res, stat, msg, fn=82004.0_dp)
            call check(error, res%status == FC_CONVERGED, solvers(k)//' converged: '//trim(res%message))
            call check(error, res%fn, 82004.0_dp, solvers(k)//' force', rel=1e-10_dp)
            call check(error, res%approach, test1_approach, solvers(k)//' approach', rel=0.005_dp)
            call check(error, minval(res%pn) >= 0, solvers(k)//' p >= 0')
            ! warm start from a solution of another load: the force is still the prescribed one
            call solve_normal(nop, h0, set, res, stat, msg, fn=82004.0_dp, p_start=0.5_dp*res%pn)
            call check(error, res%fn, 82004.0_dp, solvers(k)//' force after a warm start', rel=1e-10_dp)
        end do
        call nop%destroy()
    end subroutine test_force

    !> Rough punch (thesis §2.5.2) at 64²: contact fraction of the punch area grows
    !! with the approach and lies in a sane band around the thesis' 5.0 / 12.0 / 28.2 %
    !! (our random surface differs from theirs: bands 1–12 %, 5–25 %, 15–45 %); p ≥ 0,
    !! gap ≥ −1e−6·σ, complementarity Σ p·|gap| ≤ 1e−5·Σ p·σ; NORM and BCCG agree.
    subroutine test_rough_punch(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res, res_norm
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_rough_params) :: par
        real(dp), allocatable :: h0(:, :)
        real(dp) :: frac(3), punch_cells
        real(dp), parameter :: approach(3) = [-0.11_dp, 0.01_dp, 0.25_dp]
        real(dp), parameter :: lo(3) = [0.01_dp, 0.05_dp, 0.15_dp], hi(3) = [0.12_dp, 0.25_dp, 0.45_dp]
        integer :: stat, k
        character(len=200) :: msg
        character(len=40) :: label
        mat%g1 = 1.0e30_dp; mat%g2 = 40000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, 64, 64, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, stat, msg)
        allocate (h0(64, 64))
        call punch_rough_gap(grid, 8.97_dp, par, h0)
        punch_cells = count(h0 < 0.5_dp*h_no_contact)
        call build_normal_operator(nop, mat, grid)
        set%tol = 1e-8_dp
        do k = 1, 3
            write (label, '(a,i0)') 'case ', k
            set%solver = 'bccg'
            call solve_normal(nop, h0, set, res, stat, msg, approach=approach(k))
            call check(error, res%status == FC_CONVERGED, trim(label)//' bccg converged: '//trim(res%message))
            frac(k) = res%ncon/punch_cells
            call check(error, frac(k) >= lo(k) .and. frac(k) <= hi(k), trim(label)//' contact fraction in band')
            call check(error, minval(res%pn) >= 0, trim(label)//' p >= 0')
            call check(error, minval(res%gap) >= -1e-6_dp*par%sigma, trim(label)//' gap >= 0')
            call check(error, sum(res%pn*abs(res%gap), mask=res%gap < 1) <= 1e-5_dp*sum(res%pn)*par%sigma, &
                trim(label)//' complementarity')
            ! warm start with pressure everywhere (also outside the punch): the same solution
            call solve_normal(nop, h0, set, res_norm, stat, msg, approach=approach(k), p_start=0*h0 + 1.0e3_dp)
            call check(error, res_norm%status == FC_CONVERGED, trim(label)//' warm start converged')
            call check(error, res_norm%fn, res%fn, trim(label)//' warm start from p > 0 everywhere: same force', rel=1e-6_dp)
            set%solver = 'norm'
            call solve_normal(nop, h0, set, res_norm, stat, msg, approach=approach(k))
            call check(error, res_norm%status == FC_CONVERGED, trim(label)//' norm converged')
            call check(error, rel_diff(pack(res_norm%pn, .true.), pack(res%pn, .true.)), 0.0_dp, &
                trim(label)//' NORM = BCCG', abs=1e-5_dp)
        end do
        call check(error, frac(1) < frac(2) .and. frac(2) < frac(3), 'contact grows with approach')
        call nop%destroy()
    end subroutine test_rough_punch

    !> Against the O(n²) direct oracle: recompute e = h + A p with the direct product for
    !! a BCCG solution on 24×20 Hertz and check the LCP conditions independently of the FFT
    !! path (gap on contact ≤ 1e−7·δ, exterior gap ≥ −1e−7·δ).
    subroutine test_oracle(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_grid) :: grid
        type(fc_material) :: mat
        real(dp), allocatable :: h0(:, :), u(:, :)
        integer :: stat
        character(len=200) :: msg
        mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, 24, 20, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
        h0 = quadratic_gap(grid, 300.0_dp, 163.0_dp)
        call build_normal_operator(nop, mat, grid)
        set%tol = 1e-10_dp
        call solve_normal(nop, h0, set, res, stat, msg, approach=test1_approach)
        allocate (u(24, 20))
        call nop%a_zz%apply_direct(res%pn, u)
        call check(error, maxval(abs(h0 - test1_approach + u), mask=res%pn > 0) <= 1e-7_dp*test1_approach, &
            'gap zero on contact (direct product)')
        call check(error, minval(h0 - test1_approach + u) >= -1e-7_dp*test1_approach, 'no penetration (direct product)')
        call nop%destroy()
    end subroutine test_oracle

    !> 2D strip (n×1 grid, thesis §3.2.5): a cylinder R = 100 on a strip 100 mm long under
    !! P' = 1000 N/mm approximates plane-strain Hertz line contact, b² = 4RP'/(πE*),
    !! p0 = 2P'/(πb).  At 128×1: pmax within 1 %, RMS pressure error ≤ 1 % of p0 (the strip
    !! ends are 50 b away); NORM and BCCG agree to 1e−5.
    subroutine test_strip(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: r1, r2
        type(fc_grid) :: grid
        type(fc_material) :: mat
        real(dp), allocatable :: h0(:, :)
        real(dp) :: b, p0, err
        integer :: stat, i
        character(len=200) :: msg
        mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, msg)
        b = sqrt(4*100*1000*(1 - mat%nu)/(pi*mat%g)); p0 = 2*1000/(pi*b)
        call make_grid(grid, 128, 1, -2.0_dp, 2.0_dp, -50.0_dp, 50.0_dp, stat, msg)
        h0 = quadratic_gap(grid, 100.0_dp, 0.0_dp)
        call build_normal_operator(nop, mat, grid)
        set%tol = 1e-8_dp
        call solve_normal(nop, h0, set, r1, stat, msg, fn=1000*100.0_dp)
        call check(error, r1%status == FC_CONVERGED, 'bccg converged')
        call check(error, r1%pmax, p0, 'pmax vs plane-strain Hertz', rel=0.01_dp)
        err = 0
        do i = 1, grid%nx
            err = err + (r1%pn(i, 1) - p0*sqrt(max(0.0_dp, 1 - (grid%x(i)/b)**2)))**2
        end do
        call check(error, sqrt(err/grid%nx), 0.0_dp, 'RMS pressure error', abs=0.01_dp*p0)
        set%solver = 'norm'
        call solve_normal(nop, h0, set, r2, stat, msg, fn=1000*100.0_dp)
        call check(error, rel_diff(r2%pn(:, 1), r1%pn(:, 1)), 0.0_dp, 'NORM = BCCG', abs=1e-5_dp)
        call nop%destroy()
    end subroutine test_strip

    !> Invalid input returns stat ≠ 0 with a message naming the offending value.
    subroutine test_errors(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        integer :: stat
        character(len=200) :: msg
        call test1_setup(16, nop, h0, grid)
        call solve_normal(nop, h0, set, res, stat, msg, approach=-0.01_dp)
        call check(error, stat /= 0 .and. index(msg, 'approach') > 0, 'no contact possible: '//trim(msg))
        call solve_normal(nop, h0, set, res, stat, msg, fn=-5.0_dp)
        call check(error, stat /= 0 .and. index(msg, 'fn') > 0, 'fn <= 0: '//trim(msg))
        set%solver = 'xyz'
        call solve_normal(nop, h0, set, res, stat, msg, approach=0.1_dp)
        call check(error, stat /= 0 .and. index(msg, 'xyz') > 0, 'unknown solver: '//trim(msg))
        set%solver = 'bccg'; set%tol = -1
        call solve_normal(nop, h0, set, res, stat, msg, approach=0.1_dp)
        call check(error, stat /= 0 .and. index(msg, 'tol') > 0, 'tol <= 0: '//trim(msg))
        call nop%destroy()
    end subroutine test_errors

    !> A too small iteration budget is reported as not converged, never as converged.
    subroutine test_not_converged(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        integer :: stat
        character(len=200) :: msg
        call test1_setup(64, nop, h0, grid)
        set%maxit = 3
        call solve_normal(nop, h0, set, res, stat, msg, approach=test1_approach)
        call check(error, stat == 0 .and. res%status == FC_NOT_CONVERGED, 'bccg maxit=3 not converged')
        call check(error, index(res%message, 'maxit') > 0, 'message names maxit: '//trim(res%message))
        set%solver = 'norm'; set%maxit = 1
        call solve_normal(nop, h0, set, res, stat, msg, approach=test1_approach)
        call check(error, res%status == FC_NOT_CONVERGED, 'norm maxit=1 not converged')
        call nop%destroy()
    end subroutine test_not_converged

end module test_normal
