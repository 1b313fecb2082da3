!> Suite `contact`: the orchestrator [[solve_contact]] and the `fastcontact` facade — operator
!! reuse through `matches`, the result of a tangential problem whose normal stage failed,
!! transient shift steps, and the facade's solve and destroy.
module test_contact
    use fastcontact
    use fc_threads, only: set_thread_count, fc_thread_count, fc_openmp_enabled
    use fc_testing
    implicit none
    private
    public :: collect_contact

contains

    subroutine collect_contact(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('operators_match_spacing_and_material', test_matches), &
            new_unittest('normal_tangential_one_plan_set', test_one_plan_set), &
            new_unittest('facade_equals_operator_api_and_reuses', test_facade), &
            new_unittest('normal_stage_failed_no_tangential_stage', test_not_run), &
            new_unittest('transient_shift_zero_increment_keeps_state', test_transient), &
            new_unittest('fmg_with_coupling_rejected', test_fmg_coupled), &
            new_unittest('facade_case_with_accuracy_target', test_facade_case) ]
    end subroutine collect_contact

    subroutine hertz_scene(mat, grid, n)
        type(fc_material), intent(out) :: mat
        type(fc_grid), intent(out) :: grid
        integer, intent(in) :: n
        integer :: stat
        character(len=msg_len) :: msg
        mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, n, n, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
    end subroutine hertz_scene

    !> A moved area with the same element count and size keeps the operators; another size,
    !! another ν rebuild them; K decides only the tangential (coupling) blocks.
    subroutine test_matches(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat, mat2
        type(fc_grid) :: grid, moved, finer
        type(fc_contact_operators) :: ops
        integer :: stat
        character(len=msg_len) :: msg
        call hertz_scene(mat, grid, 16)
        call make_grid(moved, 16, 16, -7.0_dp, 13.0_dp, -6.0_dp, 6.0_dp, stat, msg)
        call make_grid(finer, 32, 16, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
        call check(error, .not. ops%normal%matches(grid, mat), 'unbuilt operator matches nothing')
        call ensure_operators(ops, grid, mat, normal=.true., tangential=.true.)
        call check(error, ops%builds_normal == 1 .and. ops%builds_tangential == 1, 'built once each')
        call check(error, ops%normal%matches(moved, mat) .and. ops%tangential%matches(moved, mat), 'moved area matches')
        call check(error, .not. ops%normal%matches(finer, mat), 'other element size does not match')
        call ensure_operators(ops, moved, mat, normal=.true., tangential=.true.)
        call check(error, ops%builds_normal == 1 .and. ops%builds_tangential == 1, 'moved area: reused')
        call check(error, ops%tangential%grid%xmin == moved%xmin, 'moved area: coordinates updated')
        mat2 = mat; mat2%nu1 = 0.3_dp
        call combine_material(mat2, stat, msg)
        call check(error, .not. ops%normal%matches(grid, mat2), 'other nu does not match')
        mat2 = mat; mat2%k = 0.1_dp
        call check(error, ops%normal%matches(grid, mat2), 'K does not change A^zz')
        call check(error, .not. ops%tangential%matches(grid, mat2), 'K changes the tangential blocks')
        ops%reuse = .false.
        call ensure_operators(ops, grid, mat, normal=.true., tangential=.false.)
        call check(error, ops%builds_normal == 2 .and. ops%builds_tangential == 1, 'reuse off: rebuilt')
        call ops%destroy()
        call check(error, .not. ops%normal%matches(grid, mat), 'destroyed operator matches nothing')
    end subroutine test_matches

    !> Built one after the other (one thread), the normal and the tangential operators of a
    !! grid share one FFT plan set and its buffers; their products, interleaved, equal
    !! those of operators built on their own.  Built side by side (two threads), each has
    !! its own set.
    subroutine test_one_plan_set(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops, ops2
        type(fc_normal_operator) :: nop
        type(fc_tangential_operator) :: top
        real(dp), allocatable :: x(:, :), y(:, :), ux(:, :), uy(:, :), uz(:, :), vx(:, :), vy(:, :), vz(:, :)
        integer :: n0
        call hertz_scene(mat, grid, 24)
        allocate (x(24, 24), y(24, 24), ux(24, 24), uy(24, 24), uz(24, 24), vx(24, 24), vy(24, 24), vz(24, 24))
        call random_number(x); call random_number(y)
        n0 = fc_thread_count()
        call set_thread_count(1)
        call ensure_operators(ops, grid, mat, normal=.true., tangential=.true.)
        call check(error, ops%tangential%a_xx%shares_plans(ops%normal%a_zz), 'one plan set for both operators')
        call check(error, ops%normal%a_zz%fft%refs == 5, 'used by A^zz, its preconditioner and three tangential blocks')
        call build_normal_operator(nop, mat, grid)
        call build_tangential_operator(top, mat, grid)
        call ops%tangential%apply(x, y, ux, uy)
        call ops%normal%a_zz%apply(x, uz)
        call top%apply(x, y, vx, vy)
        call nop%a_zz%apply(x, vz)
        call check(error, maxval(abs(ux - vx)) + maxval(abs(uy - vy)) <= 1e-14_dp*maxval(abs(vx)), 'tangential product')
        call check(error, maxval(abs(uz - vz)) <= 1e-14_dp*maxval(abs(vz)), 'normal product after it')
        call ops%tangential%apply(x, y, ux, uy)
        call check(error, maxval(abs(ux - vx)) + maxval(abs(uy - vy)) <= 1e-14_dp*maxval(abs(vx)), &
            'tangential product after a normal one')
        call ops%normal%destroy()
        call ops%tangential%apply(x, y, ux, uy)
        call check(error, maxval(abs(ux - vx)) + maxval(abs(uy - vy)) <= 1e-14_dp*maxval(abs(vx)), &
            'tangential product with the normal operator gone')
        if (fc_openmp_enabled()) then
            call set_thread_count(2)
            call ensure_operators(ops2, grid, mat, normal=.true., tangential=.true.)
            call check(error, .not. ops2%tangential%a_xx%shares_plans(ops2%normal%a_zz), 'side by side: own sets')
            call ops2%destroy()
        end if
        call set_thread_count(n0)
        call ops%destroy(); call nop%destroy(); call top%destroy()
    end subroutine test_one_plan_set

    !> The facade solves Hertz Test I like the operator-level API (same path: identical
    !! pressure), reuses its operators on a second solve (warm-started: same solution to the
    !! tolerance) and releases them in destroy.
    subroutine test_facade(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_problem) :: prob
        type(fc_contact_result) :: res, res2
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: ns
        type(fc_normal_result) :: nr
        integer :: stat
        character(len=msg_len) :: msg
        call hertz_scene(prob%material, prob%grid, 32)
        prob%h0 = quadratic_gap(prob%grid, 300.0_dp, 163.0_dp)
        prob%load%normal%approach = 0.1091_dp
        prob%settings%normal%tol = 1e-10_dp
        call solve(prob, res, stat, msg)
        call check(error, stat == 0 .and. res%status == FC_CONVERGED, 'facade solve: '//trim(msg))
        if (allocated(error)) return
        call build_normal_operator(nop, prob%material, prob%grid)
        ns%tol = 1e-10_dp
        call solve_normal(nop, prob%h0, ns, nr, stat, msg, approach=0.1091_dp)
        call check(error, all(res%normal%pn == nr%pn), 'pressure identical to solve_normal')
        call check(error, res%normal%fn, 82049.40_dp, 'Fn self-check', abs=0.01_dp)
        call check(error, .not. res%tangential_run .and. .not. allocated(res%tangential%px), 'normal problem only')
        call solve(prob, res2, stat, msg)
        call check(error, stat == 0 .and. prob%operators%builds_normal == 1, 'second solve reuses the operator')
        call check(error, res2%normal%fn, res%normal%fn, 'second solve, same force', rel=1e-8_dp)
        call prob%destroy()
        call check(error, .not. prob%operators%normal%a_zz%built(), 'destroy releases the operator')
        call nop%destroy()
    end subroutine test_facade

    !> A tangential problem whose normal stage does not converge: no tangential solve, status
    !! of the normal stage, zero tractions and adhesion exactly where pn > 0.
    subroutine test_not_run(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: settings
        type(fc_contact_result) :: res
        integer :: stat
        character(len=msg_len) :: msg
        call hertz_scene(mat, grid, 16)
        load%problem = FC_PROBLEM_TANGENTIAL
        load%normal%approach = 0.1091_dp
        load%tangential%mu = 0.3_dp; load%tangential%xi = 1e-3_dp
        settings%normal%maxit = 3; settings%normal%tol = 1e-12_dp
        call solve_contact(ops, grid, mat, quadratic_gap(grid, 300.0_dp, 163.0_dp), load, settings, res, stat, msg)
        call check(error, stat == 0, 'no input error: '//trim(msg))
        if (allocated(error)) return
        call check(error, res%normal%status == FC_NOT_CONVERGED .and. res%status == FC_NOT_CONVERGED, &
            'status of the normal stage')
        call check(error, .not. res%tangential_run .and. res%rounds == 1, 'tangential stage not run, one round')
        call check(error, ops%builds_tangential == 1, 'tangential operator prepared')
        call check(error, all(res%tangential%px == 0) .and. all(res%tangential%py == 0), 'zero tractions')
        call check(error, count(res%normal%pn > 0) > 0, 'some pressure after the first iterations')
        call check(error, all((res%tangential%state == EL_ADHESION) .eqv. (res%normal%pn > 0)), &
            'adhesion exactly where pn > 0')
        call ops%destroy()
    end subroutine test_not_run

    !> Transient shift steps: a converged step with a zero increment leaves the tractions
    !! unchanged (the previous u' is the whole slip history), and the state advances.
    subroutine test_transient(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: settings
        type(fc_contact_state) :: state
        type(fc_contact_result) :: r1, r2
        real(dp), allocatable :: h0(:, :)
        integer :: stat
        character(len=msg_len) :: msg
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, 24, 24, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
        h0 = quadratic_gap(grid, 50.0_dp, 50.0_dp)
        load%problem = FC_PROBLEM_TANGENTIAL
        load%normal%force_prescribed = .true.; load%normal%fn = 9.1954_dp
        load%tangential%mu = 0.4_dp; load%tangential%force_prescribed = .true.; load%tangential%fx = 2.0_dp
        load%transient = FC_TRANSIENT_SHIFT
        settings%normal%tol = 1e-10_dp; settings%tangential%tol = 1e-10_dp
        call solve_contact(ops, grid, mat, h0, load, settings, r1, stat, msg, state=state)
        call check(error, stat == 0 .and. r1%status == FC_CONVERGED, 'first step: '//trim(msg))
        if (allocated(error)) return
        call check(error, state%has_normal .and. state%has_tangential, 'state advanced')
        call check(error, r1%tangential%fx, 2.0_dp, 'first step Fx', rel=1e-8_dp)
        load%tangential%fx = 2.0_dp   ! the same force: a zero increment of the shift
        call solve_contact(ops, grid, mat, h0, load, settings, r2, stat, msg, state=state)
        call check(error, stat == 0 .and. r2%status == FC_CONVERGED, 'second step: '//trim(msg))
        if (allocated(error)) return
        call check(error, abs(r2%tangential%xi) <= 1e-8_dp*abs(r1%tangential%xi), 'zero shift increment')
        call check(error, maxval(abs(r2%tangential%px - r1%tangential%px)) <= 1e-6_dp*maxval(abs(r1%tangential%px)), &
            'tractions kept')
        call check(error, ops%builds_normal == 1 .and. ops%builds_tangential == 1, 'operators reused')
        call ops%destroy()
    end subroutine test_transient

    !> FMG has no operator for the coupling rounds: dissimilar materials are an input error.
    subroutine test_fmg_coupled(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: settings
        type(fc_contact_result) :: res
        integer :: stat
        character(len=msg_len) :: msg
        mat%g1 = 82000; mat%g2 = 1e30_dp; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, 16, 16, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
        load%problem = FC_PROBLEM_TANGENTIAL
        load%normal%approach = 0.1091_dp
        load%tangential%mu = 0.3_dp
        settings%normal%solver = 'fmg'
        call solve_contact(ops, grid, mat, quadratic_gap(grid, 300.0_dp, 163.0_dp), load, settings, res, stat, msg)
        call check(error, mat%k /= 0 .and. stat /= 0 .and. index(msg, 'K /= 0') > 0, 'rejected: '//trim(msg))
        call check(error, ops%builds_normal == 0 .and. ops%builds_tangential == 0, 'nothing built')
    end subroutine test_fmg_coupled

    !> The automatic layer from the facade, without any namelist: Hertz Test I with an
    !! automatic area and a 1e−2 target on fn meets the target, and fn agrees with the
    !! analytic Hertz force to the target (the discrete error is O(h²), the estimate
    !! conservative: 1e−2 leaves a wide margin).
    subroutine test_facade_case(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_case) :: c
        type(fc_contact_operators) :: ops
        type(fc_auto_outcome) :: out
        type(fc_hertz_solution) :: hz
        integer :: stat
        character(len=msg_len) :: msg
        c%material%g1 = 82000; c%material%g2 = 82000; c%material%nu1 = 0.28_dp; c%material%nu2 = 0.28_dp
        c%kind = 'quadratic'; c%rx = 300; c%ry = 163
        c%grid_auto = .true.
        c%normal%approach = 0.1091_dp
        c%target = 1e-2_dp
        call solve_case_auto(c, ops, out, stat, msg)
        call check(error, stat == 0, 'solve: '//trim(msg))
        if (allocated(error)) return
        call check(error, out%target_met .and. out%grid_auto .and. size(out%levels) >= 2, 'target met on an automatic area')
        hz = hertz_from_approach(0.5_dp/300, 0.5_dp/163, out%material%g/(1 - out%material%nu), 0.1091_dp)
        call check(error, out%result%normal%fn, hz%fn, 'fn vs analytic Hertz', rel=1e-2_dp)
        call ops%destroy()
    end subroutine test_facade_case

end module test_contact
