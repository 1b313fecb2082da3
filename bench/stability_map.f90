!> fastcontact-stability: every method over its hard cases ("failures are
!! detected and reported").  One row per (method, scenario):
!!
!!   method,scenario,grid,outcome,iterations,residual,expected,as_expected,message
!!
!! (method, scenario and message are quoted: they may hold commas.)
!!
!! `outcome` is what the package REPORTED: `converged`, `not_converged` (maxit or stagnation),
!! `diverged`, or `error` (the call returned stat /= 0 with a message: invalid input, no
!! contact, …).  `expected` is what the thesis or the physics predicts; `as_expected` compares
!! the two ("converged|not_converged" accepts either).  For converged normal solves the
!! program also checks the returned state itself (p ≥ 0, gap ≥ −1e−6·scale, finite numbers);
!! a converged status on a state that fails that check is written as `WRONG`.
!!
!! Writes doc/stability.csv and doc/stability.md (a table method × scenario).
!!
!! Usage: fastcontact-stability [--csv FILE] [--md FILE]
program fastcontact_stability
    use fc_kinds, only: dp, status_name, FC_CONVERGED, FC_NOT_CONVERGED, FC_DIVERGED
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap, punch_rough_gap, fc_rough_params, h_no_contact
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result
    use fc_norm, only: build_normal_operator, solve_normal
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_settings, fc_tangential_result
    use fc_tangcg, only: fc_tangential_loading
    use fc_tangcg, only: build_tangential_operator, solve_tangential
    use fc_tangcg_force, only: solve_tangential_loading
    use fc_fmg, only: fc_fmg_settings, fc_quadratic_surface, fc_punch_rough_surface, solve_normal_fmg
    use fc_mg2d, only: fc_strip_problem, fc_mg2d_settings, fc_mg2d_result
    use fc_mg2d, only: strip_model_problem, solve_strip_mg, solve_strip_fft_rsm
    implicit none

    character(len=512) :: csv_file, md_file, arg
    integer :: csv, iarg, ios, nrows, nunexpected
    character(len=24), allocatable :: r_method(:)
    character(len=60), allocatable :: r_scenario(:)
    character(len=16), allocatable :: r_grid(:)
    character(len=120), allocatable :: r_msg(:)
    character(len=16), allocatable :: r_outcome(:)
    character(len=32), allocatable :: r_expected(:)
    integer, allocatable :: r_iter(:)
    logical, allocatable :: r_ok(:)

    csv_file = 'doc/stability.csv'; md_file = 'doc/stability.md'
    iarg = 1
    do while (iarg <= command_argument_count())
        call get_command_argument(iarg, arg)
        select case (trim(arg))
        case ('--csv')
            iarg = iarg + 1
            call get_command_argument(iarg, csv_file)
        case ('--md')
            iarg = iarg + 1
            call get_command_argument(iarg, md_file)
        case default
            write (*, '(a)') 'usage: fastcontact-stability [--csv FILE] [--md FILE]'
            error stop 2
        end select
        iarg = iarg + 1
    end do
    open (newunit=csv, file=trim(csv_file), status='replace', action='write', iostat=ios)
    if (ios /= 0) error stop 'fastcontact-stability: cannot open the CSV file'
    write (csv, '(a)') 'method,scenario,grid,outcome,iterations,residual,expected,as_expected,message'
    allocate (r_method(0), r_scenario(0), r_grid(0), r_msg(0), r_outcome(0), r_expected(0), r_iter(0), r_ok(0))
    nrows = 0; nunexpected = 0

    call normal_scenarios()
    call fmg_scenarios()
    call tangential_scenarios()
    call strip_scenarios()
    close (csv)
    call write_markdown()
    write (*, '(/,i0,a,i0,a)') nrows, ' scenarios, ', nunexpected, ' not as expected; CSV '//trim(csv_file)// &
        ', table '//trim(md_file)

contains

    ! ---- normal solvers: BCCG, NORM --------------------------------------------------------

    subroutine normal_scenarios()
        character(len=4), parameter :: solvers(2) = ['bccg', 'norm']
        type(fc_normal_settings) :: set
        integer :: s
        character(len=20) :: m
        do s = 1, 2
            m = solvers(s)
            set = fc_normal_settings(); set%solver = solvers(s)
            call hertz(m, 'hertz', 32, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'converged')
            call hertz(m, 'hertz', 256, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'converged')
            if (s == 1) call hertz(m, 'hertz', 1024, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'converged')
            call hertz(m, 'near-incompressible nu=0.49999', 128, set, 82000.0_dp, 0.49999_dp, 0.1091_dp, 'converged')
            call hertz(m, 'rubber G=0.3 nu=0.49', 128, set, 0.3_dp, 0.49_dp, 0.1091_dp, 'converged')
            call hertz(m, 'contact touches the area boundary', 128, set, 82000.0_dp, 0.28_dp, 0.3_dp, 'converged')
            call hertz(m, 'no contact (approach -0.1)', 64, set, 82000.0_dp, 0.28_dp, -0.1_dp, 'error')
            call hertz(m, 'rigid-body approach far too large (50 mm)', 64, set, 82000.0_dp, 0.28_dp, 50.0_dp, 'converged')
            set%maxit = 3
            call hertz(m, 'maxit too small (3)', 128, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'not_converged')
            set = fc_normal_settings(); set%solver = solvers(s)
            set%tol = 1.0e-15_dp
            call hertz(m, 'tol below round-off (1e-15)', 64, set, 82000.0_dp, 0.28_dp, 0.1091_dp, &
                'converged|not_converged')
            set = fc_normal_settings(); set%solver = solvers(s); set%tol = 0
            call hertz(m, 'tol = 0 (invalid setting)', 32, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'error')
            set = fc_normal_settings(); set%solver = solvers(s)
            call rough(m, 'rough case 1 (5 % contact)', 128, set, 1, 'converged')
            call rough(m, 'rough case 3 (28 % contact)', 256, set, 3, 'converged')
        end do
        set = fc_normal_settings(); set%solver = 'bccg'; set%precondition = .false.
        call hertz('bccg no-precondition', 'hertz', 256, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'converged')
        call rough('bccg no-precondition', 'rough case 3 (28 % contact)', 256, set, 3, 'converged')
        set = fc_normal_settings(); set%solver = 'bccg'; set%deflation = .true.
        call hertz('bccg deflation', 'hertz', 256, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'converged')
        ! thesis Table 2.8: truncated CG converges up to 128² (14 active-set iterations), DIV at 256²
        set = fc_normal_settings(); set%solver = 'norm'; set%inner_maxit = 4; set%tol = 1.0e-6_dp
        call rough('norm inner_maxit=4', 'rough case 3 (28 % contact)', 128, set, 3, 'converged')
        call rough('norm inner_maxit=4', 'rough case 3 (28 % contact)', 256, set, 3, 'not_converged|diverged')
        call hertz('norm inner_maxit=4', 'hertz', 256, set, 82000.0_dp, 0.28_dp, 0.1091_dp, &
            'converged|not_converged|diverged')
    end subroutine normal_scenarios

    !> Hertz Test I geometry with material (G, ν) for both bodies and the given approach.
    subroutine hertz(method, scenario, n, set, g, nu, approach, expected)
        character(len=*), intent(in) :: method, scenario, expected
        integer, intent(in) :: n
        type(fc_normal_settings), intent(in) :: set
        real(dp), intent(in) :: g, nu, approach
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fc_normal_result) :: res
        integer :: st
        character(len=512) :: msg
        mat%g1 = g; mat%g2 = g; mat%nu1 = nu; mat%nu2 = nu
        call combine_material(mat, st, msg)
        if (st == 0) call make_grid(grid, n, n, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, st, msg)
        if (st /= 0) then
            call record(method, scenario, grid_name(n, n), -1, 0, 0.0_dp, msg, expected); return
        end if
        call build_normal_operator(nop, mat, grid)
        call solve_normal(nop, quadratic_gap(grid, 300.0_dp, 163.0_dp), set, res, st, msg, approach=approach)
        call normal_record(method, scenario, grid, st, msg, res, quadratic_gap(grid, 300.0_dp, 163.0_dp) - approach, &
            set%tol, expected)
        call nop%destroy()
    end subroutine hertz

    !> Rough punch (thesis §2.5.2) case 1–3.
    subroutine rough(method, scenario, n, set, c, expected)
        character(len=*), intent(in) :: method, scenario, expected
        integer, intent(in) :: n, c
        type(fc_normal_settings), intent(in) :: set
        real(dp), parameter :: approach(3) = [-0.11_dp, 0.01_dp, 0.25_dp]
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fc_normal_result) :: res
        type(fc_rough_params) :: par
        real(dp), allocatable :: h0(:, :)
        integer :: st
        character(len=512) :: msg
        mat%g1 = 1.0e30_dp; mat%g2 = 40000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, st, msg)
        call make_grid(grid, n, n, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, st, msg)
        allocate (h0(n, n))
        call punch_rough_gap(grid, 8.97_dp, par, h0)
        call build_normal_operator(nop, mat, grid)
        call solve_normal(nop, h0, set, res, st, msg, approach=approach(c))
        call normal_record(method, scenario, grid, st, msg, res, h0 - approach(c), set%tol, expected)
        call nop%destroy()
    end subroutine rough

    !> Record a normal solve, checking a "converged" state: p ≥ 0, finite, and the penetration
    !! ‖min(e, 0)‖₂ ≤ 10·tol·‖h‖₂ with h = h0 − δ over the contact set (the scale of the
    !! solvers' own residual ‖g‖/‖h_F‖).
    subroutine normal_record(method, scenario, grid, st, msg, res, h, tol, expected)
        character(len=*), intent(in) :: method, scenario, msg, expected
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: st
        type(fc_normal_result), intent(in) :: res
        real(dp), intent(in) :: h(:, :), tol
        character(len=512) :: note
        logical :: sane
        real(dp) :: pen, hn
        if (st /= 0) then
            call record(method, scenario, grid_name(grid%nx, grid%ny), -1, 0, 0.0_dp, msg, expected); return
        end if
        note = res%message
        pen = sqrt(sum(min(res%gap, 0.0_dp)**2))
        hn = sqrt(sum(h**2, mask=res%pn > 0))
        sane = all(res%pn >= 0) .and. all(abs(res%pn) <= huge(1.0_dp)) .and. pen <= 10*tol*hn
        if (res%status == FC_CONVERGED .and. .not. sane) write (note, '(a,es9.2,a,es9.2)') &
            'converged status on a state with p < 0 or penetration ', pen, ' > 10 tol ||h_C|| = ', 10*tol*hn
        if (res%status == FC_CONVERGED .and. any(res%pn(1, :) > 0 .or. res%pn(grid%nx, :) > 0 .or. &
            res%pn(:, 1) > 0 .or. res%pn(:, grid%ny) > 0)) &
            note = trim(note)//'; pressure on the edge of the potential area (not flagged by the solver)'
        call record(method, scenario, grid_name(grid%nx, grid%ny), res%status, res%iterations, res%residual, note, &
            expected, wrong=(res%status == FC_CONVERGED .and. .not. sane))
    end subroutine normal_record

    ! ---- FMG -------------------------------------------------------------------------------

    subroutine fmg_scenarios()
        type(fc_fmg_settings) :: set
        character(len=*), parameter :: m = 'fmg V(1,1) gs'
        set = fc_fmg_settings()
        call fmg_hertz(m, 'hertz', 32, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'converged')
        call fmg_hertz(m, 'hertz', 128, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'converged')
        call fmg_hertz(m, 'near-incompressible nu=0.49999', 64, set, 82000.0_dp, 0.49999_dp, 0.1091_dp, 'converged')
        call fmg_hertz(m, 'rubber G=0.3 nu=0.49', 64, set, 0.3_dp, 0.49_dp, 0.1091_dp, 'converged')
        call fmg_hertz(m, 'contact touches the area boundary', 64, set, 82000.0_dp, 0.28_dp, 0.3_dp, 'converged')
        call fmg_hertz(m, 'no contact (approach -0.1)', 64, set, 82000.0_dp, 0.28_dp, -0.1_dp, 'error')
        set%maxit = 1
        call fmg_hertz(m, 'maxit too small (1)', 128, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'not_converged')
        set = fc_fmg_settings(); set%omega = 1.2_dp
        call fmg_hertz('fmg V(1,1) gs omega=1.2', 'hertz (omega > 1)', 64, set, 82000.0_dp, 0.28_dp, 0.1091_dp, &
            'converged|not_converged')
        set%omega = 1.9_dp
        call fmg_hertz('fmg V(1,1) gs omega=1.9', 'hertz (omega > 1)', 64, set, 82000.0_dp, 0.28_dp, 0.1091_dp, &
            'converged|not_converged')
        set%omega = 2.5_dp
        call fmg_hertz('fmg V(1,1) gs omega=2.5', 'hertz (omega invalid)', 64, set, 82000.0_dp, 0.28_dp, &
            0.1091_dp, 'error')
        set = fc_fmg_settings(); set%smoother = 'jacobi'
        call fmg_hertz('fmg V(1,1) jacobi', 'hertz (Jacobi, thesis Fig. 2.6)', 64, set, 82000.0_dp, 0.28_dp, &
            0.1091_dp, 'not_converged|diverged')
        set = fc_fmg_settings(); set%nested = .false.
        call fmg_hertz('mg+active set V(1,1) gs', 'hertz (no nested iteration)', 128, set, 82000.0_dp, &
            0.28_dp, 0.1091_dp, 'converged')
        set = fc_fmg_settings(); set%smoother = 'fft-rsm'
        call fmg_hertz('fmg V(1,1) fft-rsm', 'hertz', 256, set, 82000.0_dp, 0.28_dp, 0.1091_dp, 'converged')
        call fmg_rough('fmg V(1,1) fft-rsm', 'rough case 1 (5 % contact)', 128, set, 1, 'converged')
        set = fc_fmg_settings()
        call fmg_rough(m, 'rough case 1 (5 % contact)', 128, set, 1, 'converged')
        call fmg_rough(m, 'rough case 3 (28 % contact)', 128, set, 3, 'converged')
    end subroutine fmg_scenarios

    subroutine fmg_hertz(method, scenario, n, set, g, nu, approach, expected)
        character(len=*), intent(in) :: method, scenario, expected
        integer, intent(in) :: n
        type(fc_fmg_settings), intent(in) :: set
        real(dp), intent(in) :: g, nu, approach
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_quadratic_surface) :: surf
        type(fc_normal_result) :: res
        integer :: st
        character(len=512) :: msg
        mat%g1 = g; mat%g2 = g; mat%nu1 = nu; mat%nu2 = nu
        call combine_material(mat, st, msg)
        call make_grid(grid, n, n, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, st, msg)
        surf%rx = 300; surf%ry = 163
        call solve_normal_fmg(mat, grid, quadratic_gap(grid, 300.0_dp, 163.0_dp), set, res, st, msg, &
            approach=approach, surface=surf)
        call normal_record(method, scenario, grid, st, msg, res, quadratic_gap(grid, 300.0_dp, 163.0_dp) - approach, &
            set%tol, expected)
    end subroutine fmg_hertz

    subroutine fmg_rough(method, scenario, n, set, c, expected)
        character(len=*), intent(in) :: method, scenario, expected
        integer, intent(in) :: n, c
        type(fc_fmg_settings), intent(in) :: set
        real(dp), parameter :: approach(3) = [-0.11_dp, 0.01_dp, 0.25_dp]
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_punch_rough_surface) :: surf
        type(fc_normal_result) :: res
        real(dp), allocatable :: h0(:, :)
        integer :: st
        character(len=512) :: msg
        mat%g1 = 1.0e30_dp; mat%g2 = 40000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, st, msg)
        call make_grid(grid, n, n, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, st, msg)
        allocate (h0(n, n))
        call surf%evaluate(grid, h0)
        call solve_normal_fmg(mat, grid, h0, set, res, st, msg, approach=approach(c), surface=surf)
        call normal_record(method, scenario, grid, st, msg, res, h0 - approach(c), set%tol, expected)
    end subroutine fmg_rough

    ! ---- tangential: TangCG(3) with/without preconditioner, ConvexGS ------------------------

    subroutine tangential_scenarios()
        real(dp), parameter :: xi(7) = [0.0_dp, 1.5e-5_dp, 0.0_dp, 0.0021_dp, 0.0037_dp, 0.0_dp, 0.0044_dp]
        real(dp), parameter :: eta(7) = [0.0_dp, 0.0_dp, 0.0015_dp, 0.0010_dp, 0.0048_dp, 0.005_dp, 0.0_dp]
        real(dp), parameter :: phi(7) = [5e-7_dp, 1e-5_dp, 0.0012_dp, 0.003_dp, 0.004_dp, 0.009_dp, 0.08_dp]
        character(len=*), parameter :: pct(7) = ['0 %  ', '0.2 %', '19 % ', '39 % ', '60 % ', '81 % ', '100 %']
        character(len=20) :: label(3)
        character(len=8) :: solver(3)
        logical :: pre(3)
        type(fc_tangential_settings) :: ts
        type(fc_tangential_loading) :: load
        integer :: s, c
        label = [character(len=20) :: 'tangcg(3)', 'tangcg(3) no-precond', 'convexgs']
        solver = [character(len=8) :: 'tangcg', 'tangcg', 'convexgs']
        pre = [.true., .false., .true.]
        do s = 1, 3
            ts = fc_tangential_settings(); ts%solver = solver(s); ts%precondition = pre(s)
            do c = 1, 7
                load = shift_load(xi(c), eta(c), phi(c))
                call cattaneo(label(s), 'cattaneo case '//achar(48 + c)//', slip '//trim(pct(c)), 60, 50, ts, &
                    200.0_dp, 0.42_dp, load, 'converged')
            end do
            if (s < 3) then
                call cattaneo(label(s), 'cattaneo case 3, slip 19 %', 240, 200, ts, 200.0_dp, 0.42_dp, &
                    shift_load(xi(3), eta(3), phi(3)), 'converged')
            end if
            call cattaneo(label(s), 'case 3, near-incompressible nu=0.49999', 60, 50, ts, 200.0_dp, 0.49999_dp, &
                shift_load(xi(3), eta(3), phi(3)), 'converged')
            call cattaneo(label(s), 'case 3, rubber G=0.3 nu=0.49', 60, 50, ts, 0.3_dp, 0.49_dp, &
                shift_load(xi(3), eta(3), phi(3)), 'converged')
            load = fc_tangential_loading(); load%mu = 0.4_dp; load%force_prescribed = .true.
            load%fx = 0.875_dp*0.4_dp*9.1954_dp
            call cattaneo(label(s), 'prescribed Fx = 0.875 mu Fn', 60, 50, ts, 200.0_dp, 0.42_dp, load, 'converged')
            load%fx = 1.01_dp*0.4_dp*9.1954_dp
            call cattaneo(label(s), 'prescribed Fx > mu Fn (no solution)', 60, 50, ts, 200.0_dp, 0.42_dp, load, 'error')
            ts%maxit = 3
            call cattaneo(label(s), 'case 5, maxit too small (3)', 60, 50, ts, 200.0_dp, 0.42_dp, &
                shift_load(xi(5), eta(5), phi(5)), 'not_converged')
            ts%maxit = 2000; ts%tol = 1.0e-16_dp
            call cattaneo(label(s), 'case 5, tol below round-off (1e-16)', 30, 25, ts, 200.0_dp, 0.42_dp, &
                shift_load(xi(5), eta(5), phi(5)), 'converged|not_converged')
        end do
        ts = fc_tangential_settings(); ts%inner_k = 1
        call cattaneo('tangcg(1)', 'cattaneo case 5, slip 60 %', 60, 50, ts, 200.0_dp, 0.42_dp, &
            shift_load(xi(5), eta(5), phi(5)), 'converged')
    end subroutine tangential_scenarios

    function shift_load(xi, eta, phi) result(load)
        real(dp), intent(in) :: xi, eta, phi
        type(fc_tangential_loading) :: load
        load%mu = 0.4_dp; load%xi = xi; load%eta = eta; load%phi = phi
    end function shift_load

    !> Cattaneo geometry (sphere R = 50, Fn scaled with G so that the contact is the same).
    subroutine cattaneo(method, scenario, nx, ny, ts, g, nu, load, expected)
        character(len=*), intent(in) :: method, scenario, expected
        integer, intent(in) :: nx, ny
        type(fc_tangential_settings), intent(in) :: ts
        real(dp), intent(in) :: g, nu
        type(fc_tangential_loading), intent(in) :: load
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: ns
        type(fc_normal_result) :: nr
        type(fc_tangential_operator) :: top
        type(fc_tangential_result) :: tr
        type(fc_tangential_loading) :: ld
        integer :: st
        character(len=512) :: msg
        mat%g1 = g; mat%g2 = g; mat%nu1 = nu; mat%nu2 = nu
        call combine_material(mat, st, msg)
        call make_grid(grid, nx, ny, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, st, msg)
        call build_normal_operator(nop, mat, grid)
        ns%tol = 1.0e-10_dp
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, nr, st, msg, &
            fn=9.1954_dp*(g/(1 - nu))/(200.0_dp/0.58_dp))
        call nop%destroy()
        if (st /= 0 .or. nr%status /= FC_CONVERGED) then
            call record(method, scenario, grid_name(nx, ny), -1, 0, 0.0_dp, 'normal stage: '//trim(msg)// &
                trim(nr%message), expected)
            return
        end if
        ld = load
        if (ld%force_prescribed) then   ! forces scale with G like Fn
            ld%fx = ld%fx*nr%fn/9.1954_dp; ld%fy = ld%fy*nr%fn/9.1954_dp
        end if
        call build_tangential_operator(top, mat, grid)
        call solve_tangential_loading(top, nr%pn, ld, ts, tr, st, msg)
        if (st /= 0) then
            call record(method, scenario, grid_name(nx, ny), -1, 0, 0.0_dp, msg, expected)
        else
            call record(method, scenario, grid_name(nx, ny), tr%status, tr%iterations, tr%residual, tr%message, &
                expected, wrong=(tr%status == FC_CONVERGED .and. .not. (all(abs(tr%px) <= huge(1.0_dp)) .and. &
                all(hypot(tr%px, tr%py) <= ld%mu*nr%pn*(1 + 1.0e-8_dp) + 1.0e-12_dp))))
        end if
        call top%destroy()
    end subroutine cattaneo

    ! ---- 2D strips: MG with FFT smoothers (thesis ch. 3) ----------------------------------

    subroutine strip_scenarios()
        character(len=8), parameter :: smoother(3) = ['fft     ', 'fft-sd  ', 'fft-rsm ']
        ! thesis: plain FFT diverges (Table 3.1); FFT+SD converges with V(1,0) on MP1/MP2 (Tables
        ! 3.2/3.3) but not with V(1,1); FFT+RSM converges everywhere (Tables 3.4, 3.5, 3.8)
        character(len=32), parameter :: expect(3) = [character(len=32) :: 'diverged', 'converged', 'converged']
        character(len=32) :: ex
        integer :: s, which, e, nu2
        character(len=48) :: scen
        character(len=24) :: meth
        do s = 1, 3
            nu2 = merge(0, 1, s == 2)
            write (meth, '(a,i0,a)') 'mg V(1,', nu2, ') '//trim(smoother(s))
            do which = 1, 3
                do e = 10, 16, 6
                    write (scen, '(a,i0,a,i0)') 'MP', which, ' n = 2^', e
                    ex = expect(s)
                    if (s == 2 .and. which == 3) ex = 'any'   ! no thesis prediction for SD on MP3
                    call strip(meth, scen, which, e, smoother(s), .true., 0.0_dp, 100, trim(ex), 1, nu2)
                end do
            end do
            call strip(meth, 'MP1 n = 2^12, nu = 0.49999', 1, 12, smoother(s), .true., 0.49999_dp, 100, trim(expect(s)), &
                1, nu2)
            call strip(meth, 'MP1 n = 2^12, maxit too small (2)', 1, 12, smoother(s), .true., 0.0_dp, 2, &
                trim(merge('diverged     ', 'not_converged', s == 1)), 1, nu2)
        end do
        call strip('mg V(1,1) fft-sd', 'MP1 n = 2^16 (thesis: V(1,1) fails)', 1, 16, 'fft-sd', .true., 0.0_dp, 30, &
            'not_converged|diverged', 1, 1)
        do which = 1, 3
            write (scen, '(a,i0,a)') 'MP', which, ' n = 2^16'
            call strip('fft-rsm one-grid', scen, which, 16, 'fft-rsm', .false., 0.0_dp, 200, 'converged', 1, 1)
        end do
    end subroutine strip_scenarios

    subroutine strip(method, scenario, which, e, smoother, multigrid, nu, maxit, expected, nu1, nu2)
        character(len=*), intent(in) :: method, scenario, smoother, expected
        integer, intent(in) :: which, e, maxit, nu1, nu2
        logical, intent(in) :: multigrid
        real(dp), intent(in) :: nu
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        integer :: st
        character(len=512) :: msg
        call strip_model_problem(which, 2**e, prob, st, msg)
        if (st == 0 .and. nu > 0) then
            prob%material%nu1 = nu; prob%material%nu2 = nu
            call combine_material(prob%material, st, msg)
        end if
        if (st /= 0) then
            call record(method, scenario, grid_name(2**e, 1), -1, 0, 0.0_dp, msg, expected); return
        end if
        set%smoother = smoother; set%maxit = maxit; set%nu1 = nu1; set%nu2 = nu2
        if (multigrid) then
            call solve_strip_mg(prob, set, res, st, msg)
        else
            call solve_strip_fft_rsm(prob, set, res, st, msg)
        end if
        if (st /= 0) then
            call record(method, scenario, grid_name(2**e, 1), -1, 0, 0.0_dp, msg, expected)
        else
            call record(method, scenario, grid_name(2**e, 1), res%status, res%iterations, res%residual, res%message, &
                expected, wrong=(res%status == FC_CONVERGED .and. .not. all(abs(res%p) <= huge(1.0_dp))))
        end if
    end subroutine strip

    ! ---- output ----------------------------------------------------------------------------

    function grid_name(nx, ny) result(s)
        integer, intent(in) :: nx, ny
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(i0,"x",i0)') nx, ny
        s = trim(buf)
    end function grid_name

    !> One row; status −1 means the call returned stat /= 0 (outcome `error`).
    subroutine record(method, scenario, grid, status, iterations, residual, message, expected, wrong)
        character(len=*), intent(in) :: method, scenario, grid, message, expected
        integer, intent(in) :: status, iterations
        real(dp), intent(in) :: residual
        logical, intent(in), optional :: wrong
        character(len=16) :: outcome
        character(len=512) :: clean
        logical :: ok
        integer :: i
        if (status < 0) then
            outcome = 'error'
        else
            outcome = status_name(status)
        end if
        if (present(wrong)) then
            if (wrong) outcome = 'WRONG'
        end if
        ok = index('|'//expected//'|', '|'//trim(outcome)//'|') > 0 .or. (expected == 'any' .and. outcome /= 'WRONG')
        clean = message
        do i = 1, len_trim(clean)
            if (clean(i:i) == ',' .or. clean(i:i) == '"') clean(i:i) = ';'
            if (clean(i:i) == '|') clean(i:i) = '/'
        end do
        write (csv, '(a,",",a,",",a,",",a,",",i0,",",es10.3,",",a,",",a,",",a)') '"'//trim(method)//'"', '"'//trim(scenario)//'"', &
            grid, &
            trim(outcome), max(iterations, 0), min(residual, 1.0e99_dp), expected, merge('yes', 'no ', ok), &
            '"'//trim(clean)//'"'
        flush (csv)
        write (*, '(a24,1x,a50,1x,a11,1x,a14,1x,i6,1x,a3,1x,a)') method, scenario, grid, outcome, max(iterations, 0), &
            merge('ok ', 'NO ', ok), trim(clean(1:70))
        nrows = nrows + 1
        if (.not. ok) nunexpected = nunexpected + 1
        r_method = [r_method, method]
        r_scenario = [character(len=60) :: r_scenario, scenario]
        r_grid = [character(len=16) :: r_grid, grid]
        r_msg = [character(len=120) :: r_msg, clean]
        r_outcome = [r_outcome, outcome]
        r_expected = [character(len=32) :: r_expected, expected]
        r_iter = [r_iter, max(iterations, 0)]
        r_ok = [r_ok, ok]
    end subroutine record

    !> Markdown: one table per method family (method rows × scenario) and the list of surprises.
    subroutine write_markdown()
        integer :: u, i
        character(len=16) :: cell
        open (newunit=u, file=trim(md_file), status='replace', action='write', iostat=ios)
        if (ios /= 0) error stop 'fastcontact-stability: cannot open the markdown file'
        write (u, '(a)') '# Stability map'
        write (u, '(a)') ''
        write (u, '(a)') 'Generated by `fpm run --profile release fastcontact-stability` (bench/stability_map.f90); ' // &
            'the same rows with the solvers'' messages are in `doc/stability.csv`. Discussion: ' // &
            '[benchmarks.md](benchmarks.md#stability-map).'
        write (u, '(a)') ''
        write (u, '(a)') 'Outcome = what the package *reported*: `converged`, `not_converged` (maxit or ' // &
            'stagnation detected), `diverged`, `error` (stat /= 0 with a message). `WRONG` would mark a ' // &
            '"converged" status on a state that fails the program''s own check (p < 0, penetration, |p_t| > mu p_n, ' // &
            'NaN); **expected** is the thesis'' or the physics'' prediction; iterations are the solver''s own count ' // &
            '(BCCG/NORM CG steps, FMG/MG cycles, TangCG inner iterations, ConvexGS sweeps).'
        write (u, '(a)') ''
        write (u, '(a)') '| method | scenario | grid | outcome | iterations | expected | as expected | message |'
        write (u, '(a)') '|---|---|---|---|---:|---|---|---|'
        do i = 1, size(r_method)
            cell = r_outcome(i)
            if (.not. r_ok(i)) cell = '**'//trim(cell)//'**'
            write (u, '(a,i0,a)') '| '//trim(r_method(i))//' | '//trim(r_scenario(i))//' | '//trim(r_grid(i))//' | '// &
                trim(cell)//' | ', r_iter(i), ' | '//trim(slashes(r_expected(i)))//' | '// &
                trim(merge('yes   ', '**no**', r_ok(i)))//' | '//trim(r_msg(i))//' |'
        end do
        write (u, '(a)') ''
        write (u, '(i0,a,i0,a)') size(r_method), ' scenarios, ', count(.not. r_ok), ' not as expected.'
        close (u)
    end subroutine write_markdown

    !> `s` with '|' replaced by '/' (markdown table cells).
    function slashes(s) result(t)
        character(len=*), intent(in) :: s
        character(len=:), allocatable :: t
        integer :: i
        t = trim(s)
        do i = 1, len(t)
            if (t(i:i) == '|') t(i:i) = '/'
        end do
    end function slashes

end program fastcontact_stability
