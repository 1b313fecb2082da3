!> Suite `stability`: the package REPORTS each failure (status code with a message, or
!! stat /= 0 with errmsg) instead of handing it back as a converged result.
!! A handful of representative scenarios of `fastcontact-stability` on small grids.
module test_stability
    use fc_kinds, only: dp, FC_CONVERGED, FC_NOT_CONVERGED, FC_DIVERGED
    use fc_testing, only: error_type, unittest_type, new_unittest, check
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_settings, fc_tangential_result
    use fc_tangcg, only: fc_tangential_loading, build_tangential_operator
    use fc_tangcg_force, only: solve_tangential_loading
    use fc_fmg, only: fc_fmg_settings, fc_quadratic_surface, solve_normal_fmg
    use fc_mg2d, only: fc_strip_problem, fc_mg2d_settings, fc_mg2d_result, strip_model_problem, solve_strip_mg
    implicit none
    private

    public :: collect_stability

contains

    subroutine collect_stability(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('normal_maxit_reported', test_normal_maxit), &
            new_unittest('no_contact_is_an_error', test_no_contact), &
            new_unittest('invalid_input_is_an_error', test_invalid_input), &
            new_unittest('fmg_jacobi_and_maxit_reported', test_fmg_failures), &
            new_unittest('mg_fft_smoother_diverged_reported', test_strip_diverged), &
            new_unittest('tangential_failures_reported', test_tangential_failures), &
            new_unittest('hard_materials_converge_to_valid_states', test_hard_materials) &
            ]
    end subroutine collect_stability

    !> Hertz Test I on an n×n grid for material (G, ν) of both bodies.
    subroutine hertz_setup(n, g, nu, mat, grid, h0)
        integer, intent(in) :: n
        real(dp), intent(in) :: g, nu
        type(fc_material), intent(out) :: mat
        type(fc_grid), intent(out) :: grid
        real(dp), allocatable, intent(out) :: h0(:, :)
        integer :: stat
        character(len=256) :: msg
        mat%g1 = g; mat%g2 = g; mat%nu1 = nu; mat%nu2 = nu
        call combine_material(mat, stat, msg)
        call make_grid(grid, n, n, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
        h0 = quadratic_gap(grid, 300.0_dp, 163.0_dp)
    end subroutine hertz_setup

    !> BCCG and NORM with maxit = 2 on Hertz 32²: not_converged, a message naming maxit,
    !! finite non-negative pressures (the last iterate, flagged), never FC_CONVERGED.
    subroutine test_normal_maxit(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        integer :: stat, s
        character(len=256) :: msg
        character(len=4), parameter :: solvers(2) = ['bccg', 'norm']
        call hertz_setup(32, 82000.0_dp, 0.28_dp, mat, grid, h0)
        call build_normal_operator(nop, mat, grid)
        do s = 1, 2
            set = fc_normal_settings(); set%solver = solvers(s); set%maxit = 2
            call solve_normal(nop, h0, set, res, stat, msg, approach=0.1091_dp)
            call check(error, stat == 0, solvers(s)//': a not-converged solve is not an input error')
            call check(error, res%status == FC_NOT_CONVERGED, solvers(s)//' maxit = 2: status not_converged')
            call check(error, index(res%message, 'maxit') > 0, solvers(s)//' message names maxit: '//trim(res%message))
            call check(error, all(res%pn >= 0 .and. res%pn == res%pn), solvers(s)//' last iterate finite and >= 0')
        end do
        call nop%destroy()
    end subroutine test_normal_maxit

    !> An approach that gives no contact ends BCCG, NORM and FMG with stat /= 0 and a message.
    subroutine test_no_contact(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_fmg_settings) :: fset
        type(fc_quadratic_surface) :: surf
        integer :: stat, s
        character(len=256) :: msg
        character(len=4), parameter :: solvers(2) = ['bccg', 'norm']
        call hertz_setup(32, 82000.0_dp, 0.28_dp, mat, grid, h0)
        call build_normal_operator(nop, mat, grid)
        do s = 1, 2
            set%solver = solvers(s)
            call solve_normal(nop, h0, set, res, stat, msg, approach=-0.1_dp)
            call check(error, stat /= 0, solvers(s)//': no contact gives stat /= 0')
            call check(error, index(msg, 'no contact') > 0, solvers(s)//': message says no contact: '//trim(msg))
        end do
        call nop%destroy()
        surf%rx = 300; surf%ry = 163
        call solve_normal_fmg(mat, grid, h0, fset, res, stat, msg, approach=-0.1_dp, surface=surf)
        call check(error, stat /= 0 .and. index(msg, 'no contact') > 0, 'fmg: no contact is an error: '//trim(msg))
    end subroutine test_no_contact

    !> Non-physical material, tol = 0, ω outside (0, 2): stat /= 0 with the offending value named.
    subroutine test_invalid_input(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat, bad
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        type(fc_fmg_settings) :: fset
        integer :: stat
        character(len=256) :: msg
        bad%g1 = 82000; bad%g2 = 82000; bad%nu1 = 0.5_dp; bad%nu2 = 0.28_dp
        call combine_material(bad, stat, msg)
        call check(error, stat /= 0, 'nu = 0.5 is rejected')
        bad%nu1 = 0.28_dp; bad%g1 = -1
        call combine_material(bad, stat, msg)
        call check(error, stat /= 0, 'G < 0 is rejected')
        call hertz_setup(32, 82000.0_dp, 0.28_dp, mat, grid, h0)
        call build_normal_operator(nop, mat, grid)
        set%tol = 0
        call solve_normal(nop, h0, set, res, stat, msg, approach=0.1091_dp)
        call check(error, stat /= 0 .and. index(msg, 'tol') > 0, 'tol = 0 is an error naming tol: '//trim(msg))
        call nop%destroy()
        fset%omega = 2.5_dp
        call solve_normal_fmg(mat, grid, h0, fset, res, stat, msg, approach=0.1091_dp)
        call check(error, stat /= 0 .and. index(msg, 'omega') > 0, 'omega = 2.5 is an error naming omega: '//trim(msg))
    end subroutine test_invalid_input

    !> FMG with the damped Jacobi smoother (thesis Fig. 2.6) and FMG with maxit = 1: reported
    !! as not converged or diverged with a message; no NaN handed back.
    subroutine test_fmg_failures(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        type(fc_fmg_settings) :: fset
        type(fc_quadratic_surface) :: surf
        type(fc_normal_result) :: res
        integer :: stat
        character(len=256) :: msg
        call hertz_setup(64, 82000.0_dp, 0.28_dp, mat, grid, h0)
        surf%rx = 300; surf%ry = 163
        fset%smoother = 'jacobi'
        call solve_normal_fmg(mat, grid, h0, fset, res, stat, msg, approach=0.1091_dp, surface=surf)
        call check(error, stat == 0, 'jacobi: runs')
        call check(error, res%status == FC_NOT_CONVERGED .or. res%status == FC_DIVERGED, &
            'jacobi smoother failure reported: '//trim(res%message))
        call check(error, len_trim(res%message) > 0 .and. res%message /= 'converged', 'jacobi: a message')
        call check(error, all(res%pn == res%pn), 'jacobi: no NaN returned')
        fset = fc_fmg_settings(); fset%maxit = 1
        call solve_normal_fmg(mat, grid, h0, fset, res, stat, msg, approach=0.1091_dp, surface=surf)
        call check(error, res%status == FC_NOT_CONVERGED .and. index(res%message, 'maxit') > 0, &
            'fmg maxit = 1 reported: '//trim(res%message))
    end subroutine test_fmg_failures

    !> MG with the plain FFT smoother on MP1 (thesis Table 3.1): FC_DIVERGED, a message, and
    !! no diverged iterate handed back (p = 0).
    subroutine test_strip_diverged(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        integer :: stat
        character(len=256) :: msg
        call strip_model_problem(1, 256, prob, stat, msg)
        set%smoother = 'fft'
        call solve_strip_mg(prob, set, res, stat, msg)
        call check(error, stat == 0, 'mg fft: runs')
        call check(error, res%status == FC_DIVERGED, 'mg fft on MP1 256: diverged reported: '//trim(res%message))
        call check(error, index(res%message, 'diverged') > 0, 'message says diverged')
        call check(error, all(res%p == 0), 'no diverged iterate returned')
        set%smoother = 'fft-rsm'; set%maxit = 1
        call solve_strip_mg(prob, set, res, stat, msg)
        call check(error, res%status == FC_NOT_CONVERGED, 'mg fft-rsm maxit = 1: not_converged: '//trim(res%message))
    end subroutine test_strip_diverged

    !> Cattaneo case 5 at 30×25: TangCG(3), TangCG without preconditioner and ConvexGS with
    !! maxit = 3 report not_converged; a prescribed force above μ·Fn is an input error.
    subroutine test_tangential_failures(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: ns
        type(fc_normal_result) :: nr
        type(fc_tangential_operator) :: top
        type(fc_tangential_settings) :: ts
        type(fc_tangential_result) :: tr
        type(fc_tangential_loading) :: load
        integer :: stat, s
        character(len=256) :: msg
        character(len=8), parameter :: solver(3) = ['tangcg  ', 'tangcg  ', 'convexgs']
        logical, parameter :: pre(3) = [.true., .false., .true.]
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, 30, 25, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
        call build_normal_operator(nop, mat, grid)
        ns%tol = 1e-10_dp
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, nr, stat, msg, fn=9.1954_dp)
        call check(error, nr%status == FC_CONVERGED, 'normal stage converged')
        call build_tangential_operator(top, mat, grid)
        load%mu = 0.4_dp; load%xi = 0.0037_dp; load%eta = 0.0048_dp; load%phi = 0.004_dp
        do s = 1, 3
            ts = fc_tangential_settings(); ts%solver = solver(s); ts%precondition = pre(s); ts%maxit = 3
            call solve_tangential_loading(top, nr%pn, load, ts, tr, stat, msg)
            call check(error, stat == 0, trim(solver(s))//': runs')
            call check(error, tr%status == FC_NOT_CONVERGED, trim(solver(s))//' maxit = 3: not_converged')
            call check(error, index(tr%message, 'maxit') > 0, trim(solver(s))//' message names maxit: '//trim(tr%message))
            call check(error, all(tr%px == tr%px .and. tr%py == tr%py), trim(solver(s))//': no NaN')
        end do
        load = fc_tangential_loading(); load%mu = 0.4_dp; load%force_prescribed = .true.
        load%fx = 1.01_dp*0.4_dp*nr%fn
        call solve_tangential_loading(top, nr%pn, load, fc_tangential_settings(), tr, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'mu*fn') > 0, 'Fx > mu Fn is an error: '//trim(msg))
        call top%destroy()
        call nop%destroy()
    end subroutine test_tangential_failures

    !> Near-incompressible (ν = 0.49999) and rubber (G = 0.3): when BCCG and NORM say
    !! converged, the state is one (p ≥ 0, penetration within the tolerance's scale) and the
    !! pressure scales with G/(1−ν) as the physics says.
    subroutine test_hard_materials(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        real(dp), allocatable :: h0(:, :)
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res, ref
        integer :: stat, s, k
        character(len=256) :: msg
        character(len=4), parameter :: solvers(2) = ['bccg', 'norm']
        real(dp), parameter :: g(3) = [82000.0_dp, 82000.0_dp, 0.3_dp], nu(3) = [0.28_dp, 0.49999_dp, 0.49_dp]
        do k = 1, 3
            call hertz_setup(32, g(k), nu(k), mat, grid, h0)
            call build_normal_operator(nop, mat, grid)
            do s = 1, 2
                set%solver = solvers(s); set%tol = 1e-8_dp
                call solve_normal(nop, h0, set, res, stat, msg, approach=0.1091_dp)
                call check(error, stat == 0 .and. res%status == FC_CONVERGED, solvers(s)//' converged')
                if (allocated(error)) return
                call check(error, all(res%pn >= 0), solvers(s)//' p >= 0')
                call check(error, sqrt(sum(min(res%gap, 0.0_dp)**2)) <= 1e-6_dp*sqrt(sum((h0 - 0.1091_dp)**2, &
                    mask=res%pn > 0)), solvers(s)//' no penetration beyond the tolerance')
                if (k == 1 .and. s == 1) then
                    ref = res
                else
                    call check(error, maxval(abs(res%pn*(mat%g/(1 - mat%nu))**(-1) - ref%pn*(82000.0_dp/0.72_dp)**(-1))) &
                        <= 1e-6_dp*maxval(ref%pn)/(82000.0_dp/0.72_dp), solvers(s)//' p scales with G/(1-nu)')
                end if
            end do
            call nop%destroy()
        end do
    end subroutine test_hard_materials

end module test_stability
