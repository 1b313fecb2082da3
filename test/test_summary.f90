!> Tests of the JSON summary's solver record (doc/user_guide.md, "JSON summary"): the
!! preconditioner count and the per-iteration residual histories of both stages reach the
!! file, read back and checked against the counts and final residuals written beside them.
!! The driver runs in-process on small grids; files go to a unique directory under /tmp.
module test_summary
    use fc_kinds, only: dp
    use fc_testing, only: error_type, unittest_type, new_unittest, check, file_bytes
    use fc_test_driver, only: fresh_dir, run_namelist
    implicit none
    private

    public :: collect_summary

    character(len=*), parameter :: nl = new_line('a')

contains

    !> The summary suite.
    subroutine collect_summary(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('normal_history_and_precond', test_normal_history), &
            new_unittest('unpreconditioned_counts_zero', test_unpreconditioned), &
            new_unittest('tangential_history', test_tangential_history) &
            ]
    end subroutine collect_summary

    !> Hertz on 16×16 with BCCG: the history holds the relative residual at the start of
    !! every iteration and at the final check (iterations + 1 values), its last value is the
    !! residual written beside it, and it falls below the tolerance; the FFT preconditioner
    !! is applied at least once per iteration.
    subroutine test_normal_history(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, j
        real(dp), allocatable :: h(:)
        integer :: code, it
        call run_case(hertz_case('hz'), code, dir)
        call check(error, code == 0, 'exit code 0 expected')
        if (allocated(error)) return
        j = file_bytes(dir//'/hz.json')
        call json_list(j, 'history_normal', h)
        it = nint(json_num(j, 'iterations_normal'))
        call check(error, it > 0, 'iterations_normal > 0: '//j)
        if (allocated(error)) return
        call check(error, size(h) == it + 1, 'history_normal: iterations_normal + 1 values: '//j)
        if (allocated(error)) return
        call check(error, abs(h(size(h)) - json_num(j, 'residual_normal')) <= 1e-14_dp*json_num(j, 'residual_normal'), &
            'last history value = residual_normal')
        call check(error, h(size(h)) <= json_num(j, 'tol') .and. h(1) > h(size(h)), 'history falls below tol')
        call check(error, nint(json_num(j, 'precond_applications_normal')) >= it, &
            'precond_applications_normal >= iterations_normal: '//j)
        call cleanup(dir)
    end subroutine test_normal_history

    !> The same case with `&solver precondition = .false.`: no preconditioner product.
    subroutine test_unpreconditioned(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, j
        real(dp), allocatable :: h(:)
        integer :: code
        call run_case(hertz_case('hz0')//'&solver precondition = .false. /'//nl, code, dir)
        call check(error, code == 0, 'exit code 0 expected')
        if (allocated(error)) return
        j = file_bytes(dir//'/hz0.json')
        call check(error, nint(json_num(j, 'precond_applications_normal')) == 0, &
            'precond_applications_normal = 0 without preconditioner: '//j)
        call json_list(j, 'history_normal', h)
        call check(error, size(h) == nint(json_num(j, 'iterations_normal')) + 1, 'history length')
        call cleanup(dir)
    end subroutine test_unpreconditioned

    !> Cattaneo shift (K = 0: one round): TangCG stores the relative traction change of every
    !! iteration; the last one is the residual written beside it.
    subroutine test_tangential_history(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, j
        real(dp), allocatable :: h(:)
        integer :: code
        call run_case("&case name = 'cat', problem = 'normal+tangential' /"//nl// &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
            '&grid nx = 20, ny = 20, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /'//nl// &
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl// &
            '&normal fn = 9.1954 /'//nl// &
            '&tangential mu = 0.4, xi = 0.0, eta = 0.0015, phi = 0.0012 /'//nl, code, dir)
        call check(error, code == 0, 'exit code 0 expected')
        if (allocated(error)) return
        j = file_bytes(dir//'/cat.json')
        call check(error, nint(json_num(j, 'panagiotopoulos_rounds')) == 1, 'one round expected: '//j)
        call json_list(j, 'history_tangential', h)
        call check(error, size(h) == nint(json_num(j, 'iterations_tangential')) .and. size(h) > 0, &
            'history_tangential: one value per iteration: '//j)
        if (allocated(error)) return
        call check(error, abs(h(size(h)) - json_num(j, 'residual_tangential')) <= &
            1e-14_dp*json_num(j, 'residual_tangential'), 'last history value = residual_tangential')
        call json_list(j, 'history_normal', h)
        call check(error, size(h) == nint(json_num(j, 'iterations_normal')) + 1, 'history_normal length')
        call cleanup(dir)
    end subroutine test_tangential_history

    ! ---------------------------------------------------------------- helpers ----

    function hertz_case(name) result(text)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text
        text = "&case name = '"//name//"' /"//nl// &
            '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl// &
            "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"//nl// &
            '&normal approach = 0.1091 /'//nl
    end function hertz_case

    !> Write `text` to a fresh directory and run the driver on it with `--out` there.
    subroutine run_case(text, code, dir)
        character(len=*), intent(in) :: text
        integer, intent(out) :: code
        character(len=:), allocatable, intent(out) :: dir
        dir = fresh_dir('summary')
        call run_namelist(dir, text, code)
    end subroutine run_case

    subroutine cleanup(dir)
        character(len=*), intent(in) :: dir
        if (index(dir, '/tmp/fc_test_summary_') == 1) call execute_command_line("rm -rf '"//dir//"'")
    end subroutine cleanup

    !> Value of a numeric JSON key (huge() when absent or unreadable).
    real(dp) function json_num(text, key)
        character(len=*), intent(in) :: text, key
        integer :: p, q, ios
        json_num = huge(1.0_dp)
        p = index(text, '"'//key//'": ')
        if (p == 0) return
        p = p + len(key) + 4
        q = scan(text(p:), ','//nl//'}') + p - 2
        read (text(p:q), *, iostat=ios) json_num
        if (ios /= 0) json_num = huge(1.0_dp)
    end function json_num

    !> Values of a JSON list of numbers (size 0 when absent, empty or unreadable).
    subroutine json_list(text, key, vals)
        character(len=*), intent(in) :: text, key
        real(dp), allocatable, intent(out) :: vals(:)
        integer :: p, q, n, i, ios
        allocate (vals(0))
        p = index(text, '"'//key//'": [')
        if (p == 0) return
        p = p + len(key) + 5
        q = index(text(p:), ']') + p - 2
        if (q < p) return
        n = count([(text(i:i) == ',', i=p, q)]) + 1
        deallocate (vals); allocate (vals(n))
        read (text(p:q), *, iostat=ios) vals
        if (ios /= 0) then
            deallocate (vals); allocate (vals(0))
        end if
    end subroutine json_list

end module test_summary
