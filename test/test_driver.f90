!> Tests of the batch driver (doc/namelist.md): good files with inheritance, and every kind of bad
!! input giving a non-zero exit code, a message naming group and key, and no outputs.
!! The driver runs in-process on small grids; files go to a unique directory under /tmp.
!!
!! Size (~1180 lines, 65 tests): one file per suite; most tests are a namelist text and the
!! message or outputs it must give.
module test_driver
    use fc_kinds, only: dp
    use fc_testing, only: error_type, unittest_type, new_unittest, check, read_all => file_lines
    use fc_driver, only: run_driver, parse_driver_arguments
    use fc_test_driver, only: fresh_dir, run_namelist, exists => file_exists
    use fc_namelist, only: fc_case_chunk, read_case_file
    use fc_input, only: fc_case_input, apply_case, max_dist_grid_elements
    use fc_input_validate, only: validate_case
    use fc_version, only: fc_version_string, fc_version_major, fc_version_minor, fc_version_patch
    use fc_fftw, only: fftw_forget_wisdom
    use fc_fft_effort, only: strip_plans_in_wisdom
    use fc_mg2d, only: fc_strip_problem, fc_mg2d_settings, strip_model_problem, strip_level_sizes
    implicit none
    private

    public :: collect_driver
    public :: without_times, json_num   ! shared with the suites `batch` and `auto`

    character(len=*), parameter :: nl = new_line('a')

contains

    !> The driver suite.
    subroutine collect_driver(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('two_cases_inheritance', test_two_cases), &
            new_unittest('fn_clears_approach', test_fn_clears_approach), &
            new_unittest('error_then_good_case', test_error_then_good), &
            new_unittest('failed_case_not_inherited', test_failed_not_inherited), &
            new_unittest('not_converged_status', test_not_converged), &
            new_unittest('unknown_key', test_unknown_key), &
            new_unittest('fft_preconditioner_key', test_fft_preconditioner_key), &
            new_unittest('unknown_group', test_unknown_group), &
            new_unittest('wrong_type', test_wrong_type), &
            new_unittest('grid_limit_serial_and_distributed', test_grid_limit), &
            new_unittest('missing_geometry_kind', test_missing_kind), &
            new_unittest('missing_load', test_missing_load), &
            new_unittest('g_not_positive', test_g_not_positive), &
            new_unittest('nu_out_of_range', test_nu_range), &
            new_unittest('nx_zero', test_nx_zero), &
            new_unittest('empty_grid', test_empty_grid), &
            new_unittest('oversized_grid', test_oversized), &
            new_unittest('no_contact_possible', test_no_contact), &
            new_unittest('automatic_area_too_fine', test_auto_area_too_fine), &
            new_unittest('fn_not_positive', test_fn_not_positive), &
            new_unittest('approach_and_fn', test_approach_and_fn), &
            new_unittest('unknown_solver', test_unknown_solver), &
            new_unittest('unknown_problem', test_unknown_problem), &
            new_unittest('tangential_case', test_tangential_case), &
            new_unittest('tangential_prescribed_force', test_tangential_force), &
            new_unittest('tangcg_vs_convexgs', test_tangcg_vs_convexgs), &
            new_unittest('fft_wisdom_file', test_fft_wisdom_file), &
            new_unittest('strip_fft_wisdom_file', test_strip_fft_wisdom_file), &
            new_unittest('tangential_normal_not_converged', test_tangential_normal_not_converged), &
            new_unittest('tangential_ignored_for_normal', test_tangential_ignored), &
            new_unittest('tangential_same_as_normal_plus', test_tangential_synonym), &
            new_unittest('dissimilar_panagiotopoulos', test_dissimilar), &
            new_unittest('mu_negative', test_mu_negative), &
            new_unittest('mu_missing', test_mu_missing), &
            new_unittest('mu_zero_with_forces', test_mu_zero_forces), &
            new_unittest('shift_and_force', test_shift_and_force), &
            new_unittest('unknown_tangential_solver', test_unknown_tangential_solver), &
            new_unittest('inner_k_zero', test_inner_k_zero), &
            new_unittest('force_above_limit_fn', test_force_limit_fn), &
            new_unittest('force_above_limit_approach', test_force_limit_approach), &
            new_unittest('strip2d_needs_ny_1', test_strip2d_ny), &
            new_unittest('missing_table_file', test_missing_table), &
            new_unittest('lengths_below_the_limit', test_tiny_lengths), &
            new_unittest('bad_command_line', test_bad_command_line), &
            new_unittest('version_option_and_json', test_version_option), &
            new_unittest('version_matches_manifest', test_version_manifest), &
            new_unittest('fmg_hertz_matches_bccg', test_fmg_hertz), &
            new_unittest('fmg_each_cycle', test_fmg_cycles), &
            new_unittest('fmg_bad_cycle', test_fmg_bad_cycle), &
            new_unittest('fmg_omega_not_positive', test_fmg_bad_omega), &
            new_unittest('fmg_bad_smoother', test_fmg_bad_smoother), &
            new_unittest('fmg_coarsest_too_large', test_fmg_coarsest), &
            new_unittest('punch_below_one_element_names_geometry', test_punch_too_small), &
            new_unittest('line_contact_automatic_area_refused', test_line_auto_area), &
            new_unittest('fmg_dissimilar_rejected', test_fmg_dissimilar), &
            new_unittest('fmg_tangential_k0', test_fmg_tangential), &
            new_unittest('strip_mp1_three_solvers', test_strip_mp1), &
            new_unittest('strip_mp3_contact_strips', test_strip_mp3), &
            new_unittest('strip_unknown_solver', test_strip_unknown_solver), &
            new_unittest('strip_nx_not_power_of_2', test_strip_bad_nx), &
            new_unittest('strip_needs_strip2d', test_strip_needs_kind), &
            new_unittest('radius_above_limit', test_radius_limit), &
            new_unittest('real_beyond_double_range', test_real_overflow), &
            new_unittest('transient_rolling_cost_bound', test_transient_cost), &
            new_unittest('case_selection', test_case_selection) &
            ]
    end subroutine collect_driver

    ! ---------------------------------------------------------------- helpers ----

    !> A valid Hertz case on a 16×16 grid, named `name`.
    function base_case(name) result(text)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text
        text = "&case name = '"//name//"' /"//nl// &
            '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl// &
            "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"//nl// &
            '&normal approach = 0.1091 /'//nl
    end function base_case

    !> `text` with the first occurrence of `old` replaced by `new`.
    function replace(text, old, new) result(out)
        character(len=*), intent(in) :: text, old, new
        character(len=:), allocatable :: out
        integer :: p
        p = index(text, old)
        if (p == 0) then
            out = text//'!! replace failed: '//old
        else
            out = text(1:p - 1)//new//text(p + len(old):)
        end if
    end function replace

    !> Write `text` to a fresh directory, run the driver with `--out` that directory and
    !! return the exit code, the error output and the directory.
    subroutine run_text(text, code, errors, dir)
        character(len=*), intent(in) :: text
        integer, intent(out) :: code
        character(len=:), allocatable, intent(out) :: errors
        character(len=:), allocatable, intent(out) :: dir
        dir = new_dir()
        call run_again(dir, text, code, errors)
    end subroutine run_text

    !> A fresh, unique scratch directory under /tmp.
    function new_dir() result(dir)
        character(len=:), allocatable :: dir
        dir = fresh_dir('driver')
    end function new_dir

    subroutine cleanup(dir)
        character(len=*), intent(in) :: dir
        if (index(dir, '/tmp/fc_test_driver_') == 1) call execute_command_line("rm -rf '"//dir//"'")
    end subroutine cleanup

    !> Run `text` (one bad case named 'bad') and check: non-zero exit, message with every
    !! word of `words`, no bad.json / bad.csv (a stale bad.json is removed).
    subroutine expect_bad(error, text, words)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: text
        character(len=*), intent(in) :: words(:)
        integer :: code, i, u
        character(len=:), allocatable :: errors, dir
        ! plant a stale output from an "earlier run" in the directory the driver will use
        dir = new_dir()
        open (newunit=u, file=dir//'/bad.json', status='replace', action='write')
        write (u, '(a)') '{"status": "converged"}'
        close (u)
        call run_again(dir, text, code, errors)
        call check(error, code /= 0, 'exit code must be non-zero for bad input')
        do i = 1, size(words)
            call check(error, index(errors, trim(words(i))) > 0, "message must contain '"//trim(words(i))// &
                "', got: "//errors)
        end do
        call check(error, .not. exists(dir//'/bad.json'), 'bad.json must not exist (stale file removed)')
        call check(error, .not. exists(dir//'/bad.csv'), 'bad.csv must not exist')
        call cleanup(dir)
    end subroutine expect_bad

    !> Run `text` in an existing directory.
    subroutine run_again(dir, text, code, errors)
        character(len=*), intent(in) :: dir, text
        integer, intent(out) :: code
        character(len=:), allocatable, intent(out) :: errors
        call run_namelist(dir, text, code, errors)
    end subroutine run_again

    ! ---------------------------------------------------------------- good input ----

    subroutine test_two_cases(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j1, j2, csv
        call run_text(base_case('good1')//"&case name = 'good2' /"//nl//'&grid nx = 20, ny = 12 /'//nl, &
            code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        call check(error, exists(dir//'/good1.json') .and. exists(dir//'/good1.csv'), 'good1.json/csv missing')
        call check(error, exists(dir//'/good2.json') .and. exists(dir//'/good2.csv'), 'good2.json/csv missing')
        if (allocated(error)) return
        j1 = read_all(dir//'/good1.json')
        j2 = read_all(dir//'/good2.json')
        call check(error, index(j1, '"status": "converged"') > 0, 'good1 not converged: '//j1)
        call check(error, index(j2, '"status": "converged"') > 0, 'good2 not converged: '//j2)
        call check(error, index(j2, '"nx": 20,') > 0 .and. index(j2, '"ny": 12,') > 0, 'good2 grid not 20x12: '//j2)
        call check(error, index(j1, '"nx": 16,') > 0, 'good1 grid not 16x16')
        call check(error, index(j2, '"approach": 1.091000000000000E-001') > 0, 'good2 did not inherit the approach')
        call check(error, index(j2, '"hertz": {') > 0, 'hertz block missing for quadratic geometry')
        csv = read_all(dir//'/good2.csv')
        call check(error, index(csv, 'ix,iy,x,y,status,pn,px,py,sx,sy,gap') == 1, 'CSV header')
        call check(error, count_lines(csv) == 1 + 20*12, 'CSV must have 1 + nx*ny lines')
        call cleanup(dir)
    end subroutine test_two_cases

    !> `--case NAME[,NAME]`: only the named cases are solved, each exactly as in the whole
    !! run (inheriting from the cases before it, with operators built afresh); unknown names
    !! and a missing name are input errors before anything is solved; `--check` checks only
    !! the named cases; the MPI drivers' command line (no `selected`) refuses the option.
    subroutine test_case_selection(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, text, rejected, whole, one, report, case_file, out_dir, action, errtext
        character(len=256) :: names(4)
        integer :: i
        names = [character(len=256) :: 'n1', 't2', 'r3', 'n4']
        text = base_case('n1')// &
            "&case name = 't2', problem = 'normal+tangential' /"//nl//'&grid nx = 20, ny = 14 /'//nl// &
            '&tangential mu = 0.3, xi = 0.001, eta = 0.0, phi = 0.0 /'//nl// &
            "&case name = 'r3', problem = 'rolling' /"//nl// &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
            '&grid nx = 20, ny = 16, xmin = -1.3, xmax = 1.3, ymin = -1.3, ymax = 1.3 /'//nl// &
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl//'&normal fn = 9.1954 /'//nl// &
            "&tangential mu = 0.4, xi = 0.001, eta = 0.001, phi = 0.003, sweep = 'xi', sweep_from = 0.0, "// &
            'sweep_to = 0.004, sweep_n = 3 /'//nl// &
            "&case name = 'n4', problem = 'normal' /"//nl//"&tangential sweep = '' /"//nl
        whole = new_dir(); one = new_dir()
        call run_namelist(whole, text, code, errors)
        call check(error, code == 0, 'whole file: exit 0 expected, errors: '//errors)
        if (allocated(error)) return
        call run_namelist(one, text, code, errors, extra=[character(len=16) :: '--case', 'r3,t2'])
        call check(error, code == 0, '--case r3,t2: exit 0 expected, errors: '//errors)
        if (allocated(error)) return
        call check(error, .not. exists(one//'/n1.json') .and. .not. exists(one//'/n4.json'), 'cases not named were solved')
        do i = 2, 3
            call check(error, read_all(one//'/'//trim(names(i))//'.csv') == read_all(whole//'/'//trim(names(i))//'.csv'), &
                trim(names(i))//': element table differs from the whole run''s')
            call check(error, same_json_values(trim(names(i))), trim(names(i))//': summary differs from the whole run''s')
        end do
        call check(error, exists(one//'/r3_creep.csv'), 'r3: creep-force curve missing')
        report = read_all(one//'/report.txt')
        call check(error, index(report, '2 case(s) chosen by --case: 2 converged') > 0, 'summary line: '//report)
        if (allocated(error)) return
        call cleanup(one); one = new_dir()
        call run_namelist(one, text, code, errors, extra=[character(len=16) :: '--case=n4'])
        call check(error, code == 0 .and. exists(one//'/n4.json') .and. .not. exists(one//'/t2.json'), '--case=n4: '//errors)
        call check(error, same_json_values('n4'), 'n4: summary differs from the whole run''s')
        ! a case rejected only while solving (prescribed approach, a force beyond mu*Fn) still
        ! passes its values on, in the whole run as when it is only read (here: rx)
        call cleanup(whole); call cleanup(one); whole = new_dir(); one = new_dir()
        rejected = base_case('s1')//"&case name = 'e2', problem = 'normal+tangential' /"//nl// &
            "&geometry kind = 'quadratic', rx = 200.0, ry = 163.0 /"//nl// &
            '&tangential mu = 0.3, fx = 1.0e9, fy = 0.0 /'//nl// &
            "&case name = 'f3', problem = 'normal' /"//nl
        call run_namelist(whole, rejected, code, errors)
        call check(error, code == 1 .and. index(errors, "'e2'") > 0 .and. index(errors, 'mu*fn') > 0, &
            'e2 must be rejected while solving: '//errors)
        call run_namelist(one, rejected, code, errors, extra=[character(len=16) :: '--case', 'f3'])
        call check(error, code == 0, '--case f3: '//errors)
        call check(error, same_json_values('f3'), 'f3 after a case rejected while solving: summary differs')
        ! with rx = 200 instead of s1's 300 the same approach gives another force
        call check(error, abs(json_num(read_all(whole//'/f3.json'), 'fn') - json_num(read_all(whole//'/s1.json'), 'fn')) > &
            1e-3_dp*json_num(read_all(whole//'/s1.json'), 'fn'), 'f3 must inherit rx = 200 from e2')
        if (allocated(error)) return
        ! an unknown name: nothing solved, the file's names listed
        call cleanup(one); one = new_dir()
        call run_namelist(one, text, code, errors, extra=[character(len=16) :: '--case', 't2,nosuch'])
        call check(error, code == 1, '--case nosuch: exit 1 expected')
        call check(error, index(errors, "--case 'nosuch': no case of that name") > 0 .and. &
            index(errors, '(its cases: n1, t2, r3, n4)') > 0, 'message must name nosuch and list the cases: '//errors)
        call check(error, .not. exists(one//'/t2.json'), 'nothing may be solved when a name is unknown')
        call run_namelist(one, text, code, errors, extra=[character(len=16) :: '--case'])
        call check(error, code == 1 .and. index(errors, '--case needs a case name') > 0, '--case without a name: '//errors)
        call run_namelist(one, text, code, errors, extra=[character(len=16) :: '--case', 'n1,,t2'])
        call check(error, code == 1 .and. index(errors, 'empty case name') > 0, '--case n1,,t2: '//errors)
        ! --check of one case
        call run_namelist(one, text, code, errors, check_only=.true., extra=[character(len=16) :: '--case', 't2'])
        report = read_all(one//'/report.txt')
        call check(error, code == 0 .and. index(report, ' case t2: ') > 0 .and. index(report, ' case n1: ') == 0 .and. &
            index(report, '1 case(s) chosen by --case: 1 to solve') > 0, '--check --case t2: '//report//errors)
        ! the MPI drivers' command line has no --case
        call parse_driver_arguments([character(len=16) :: 'x.nml', '--case', 'n1'], 'fastcontact-mpi', 'usage', &
            case_file, out_dir, action, errtext)
        call check(error, action == 'error' .and. index(errtext, "unexpected argument '--case'") > 0, &
            'without selected, --case must be refused: '//errtext)
        call cleanup(one); call cleanup(whole)
    contains
        !> The summary of case `nm` in both runs, without its times and its operator-reuse flags.
        logical function same_json_values(nm)
            character(len=*), intent(in) :: nm
            same_json_values = without_times(read_all(one//'/'//nm//'.json')) == without_times(read_all(whole//'/'//nm//'.json'))
        end function same_json_values
    end subroutine test_case_selection

    !> `text` without its lines that hold seconds or the operator-reuse flags.
    function without_times(text) result(out)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: out
        integer :: a, b
        out = ''
        a = 1
        do while (a <= len(text))
            b = index(text(a:), nl)
            b = merge(len(text), a + b - 1, b == 0)
            if (index(text(a:b), 'seconds') == 0 .and. index(text(a:b), 'operator_built') == 0) out = out//text(a:b)
            a = b + 1
        end do
    end function without_times

    integer function count_lines(text)
        character(len=*), intent(in) :: text
        integer :: i
        count_lines = 0
        do i = 1, len(text)
            if (text(i:i) == nl) count_lines = count_lines + 1
        end do
    end function count_lines

    subroutine test_fn_clears_approach(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j2, j3
        call run_text(base_case('a1')//"&case name = 'f2' /"//nl//'&normal fn = 82004.0 /'//nl// &
            "&case name = 'a3' /"//nl//'&normal approach = 0.05 /'//nl, code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j2 = read_all(dir//'/f2.json')
        j3 = read_all(dir//'/a3.json')
        call check(error, index(j2, '"load": "fn"') > 0, 'f2 must prescribe the force')
        call check(error, index(j2, '"fn": 8.200400000000') > 0, 'f2 force must be 82004: '//j2)
        call check(error, index(j3, '"load": "approach"') > 0 .and. index(j3, '"approach": 5.0000000000') > 0, &
            'a3 must prescribe approach 0.05: '//j3)
        call cleanup(dir)
    end subroutine test_fn_clears_approach

    subroutine test_error_then_good(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir
        call run_text(replace(base_case('bad'), 'nx = 16', 'nx = 16, nz = 4')//base_case('good'), code, errors, dir)
        call check(error, code /= 0, 'exit code must be non-zero when a case has an error')
        call check(error, index(errors, 'nz') > 0, 'message must name nz: '//errors)
        call check(error, .not. exists(dir//'/bad.json'), 'no bad.json')
        call check(error, exists(dir//'/good.json') .and. exists(dir//'/good.csv'), 'the next case must still run')
        call cleanup(dir)
    end subroutine test_error_then_good

    !> A case with an input error does not change the inherited state.
    subroutine test_failed_not_inherited(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir
        call run_text(base_case('first')//"&case name = 'broken' /"//nl//'&material g2 = 0.0 /'//nl// &
            "&case name = 'third' /"//nl, code, errors, dir)
        call check(error, code /= 0, 'exit code must be non-zero')
        call check(error, index(errors, '&material g2') > 0, 'message must name &material g2: '//errors)
        call check(error, .not. exists(dir//'/broken.json'), 'no broken.json')
        call check(error, exists(dir//'/third.json'), 'third case must inherit from the first (good) case')
        call cleanup(dir)
    end subroutine test_failed_not_inherited

    subroutine test_not_converged(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j
        call run_text(base_case('slow')//"&solver normal = 'norm', maxit = 1, inner_maxit = 1 /"//nl, code, errors, dir)
        call check(error, code /= 0, 'exit code must be non-zero when the solver does not converge')
        call check(error, exists(dir//'/slow.json'), 'JSON must be written with the solver status')
        if (allocated(error)) return
        j = read_all(dir//'/slow.json')
        call check(error, index(j, '"status": "not_converged"') > 0 .or. index(j, '"status": "diverged"') > 0, &
            'status must be not_converged: '//j)
        call check(error, index(read_all(dir//'/report.txt'), 'NOT CONVERGED') > 0, 'report must say NOT CONVERGED')
        call cleanup(dir)
    end subroutine test_not_converged

    ! ---------------------------------------------------------------- bad input ----

    !> A radius above 1e8 mm (the Hertz estimate of the automatic area would need an ellipse
    !! thinner than double precision) is refused with the limit; the automatic area is used.
    subroutine test_radius_limit(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        text = replace(base_case('bad'), 'ry = 163.0', 'ry = 1e30')
        text = replace(text, '&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /', &
            '&grid auto = .true. /')
        call expect_bad(error, text, [character(len=16) :: '&geometry', 'ry', 'E+30', 'at most'])
    end subroutine test_radius_limit

    !> A real literal beyond 1e308 is refused before conversion (it would overflow to +Inf).
    subroutine test_real_overflow(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'g1 = 82000.0', 'g1 = 1d400'), &
            [character(len=16) :: '&material', 'g1', '1d400', '1e308'])
    end subroutine test_real_overflow

    !> Transient rolling: steps x elements above 1e7 is refused before any step is taken.
    subroutine test_transient_cost(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        text = replace(base_case('bad'), "&case name = 'bad' /", "&case name = 'bad', problem = 'transient_rolling' /")
        text = replace(text, '&normal approach = 0.1091 /', &
            '&normal approach = 0.1091 /'//nl//'&tangential mu = 0.3, xi = 0.001, nsteps = 50000 /')
        call expect_bad(error, text, [character(len=16) :: '&tangential', 'nsteps', '50000', '1e7'])
    end subroutine test_transient_cost

    subroutine test_unknown_key(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'nx = 16', 'nx = 16, nz = 4'), &
            [character(len=16) :: '&grid', 'nz', '4'])
    end subroutine test_unknown_key

    !> `&solver fft_preconditioner`: both forms run the Cattaneo case to the same forces
    !! (tol 1e−5: 1e−4 of μFn) with the preconditioner applied; another value is refused
    !! naming the group, key and value.
    subroutine test_fft_preconditioner_key(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, jc, jt
        call run_text(cattaneo_case('pf')//"&solver fft_preconditioner = 'circulant' /"//nl, code, errors, dir)
        call check(error, code == 0, 'circulant: exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        jc = read_all(dir//'/pf.json')
        call run_text(cattaneo_case('pf')//"&solver fft_preconditioner = 'toeplitz' /"//nl, code, errors, dir)
        call check(error, code == 0, 'toeplitz: exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        jt = read_all(dir//'/pf.json')
        call check(error, json_num(jc, 'precond_applications_normal') > 0 .and. &
            json_num(jt, 'precond_applications_normal') > 0, 'preconditioned in both forms')
        call check(error, index(jc, '"fft_preconditioner": "circulant"') > 0 .and. &
            index(jt, '"fft_preconditioner": "toeplitz"') > 0, 'form recorded in the JSON')
        call check(error, abs(json_num(jc, 'fy') - json_num(jt, 'fy')) <= 1e-4_dp*0.4_dp*9.1954_dp .and. &
            abs(json_num(jc, 'mz') - json_num(jt, 'mz')) <= 1e-4_dp*0.4_dp*9.1954_dp, 'same forces')
        if (allocated(error)) return
        call expect_bad(error, cattaneo_case('bad')//"&solver fft_preconditioner = 'doubled' /"//nl, &
            [character(len=20) :: '&solver', 'fft_preconditioner', 'doubled'])
    end subroutine test_fft_preconditioner_key

    subroutine test_unknown_group(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, base_case('bad')//'&grdi nx = 32 /'//nl, [character(len=16) :: 'grdi', 'nx', '32'])
    end subroutine test_unknown_group

    subroutine test_wrong_type(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'nx = 16', "nx = 'sixteen'"), &
            [character(len=16) :: '&grid', 'nx', 'sixteen'])
    end subroutine test_wrong_type

    subroutine test_missing_kind(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), "kind = 'quadratic', ", ''), &
            [character(len=16) :: '&geometry', 'kind', 'missing'])
    end subroutine test_missing_kind

    subroutine test_missing_load(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), '&normal approach = 0.1091 /', ''), &
            [character(len=16) :: '&normal', 'approach', 'fn', 'missing'])
    end subroutine test_missing_load

    subroutine test_g_not_positive(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'g1 = 82000.0', 'g1 = -82000.0'), &
            [character(len=16) :: '&material', 'g1', '-82000'])
    end subroutine test_g_not_positive

    subroutine test_nu_range(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'nu2 = 0.28', 'nu2 = 0.5'), &
            [character(len=16) :: '&material', 'nu2', '0.5'])
    end subroutine test_nu_range

    subroutine test_nx_zero(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'nx = 16', 'nx = 0'), [character(len=16) :: '&grid', 'nx', '0'])
    end subroutine test_nx_zero

    subroutine test_empty_grid(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'xmax = 10.0', 'xmax = -10.0'), &
            [character(len=16) :: '&grid', 'xmax', '-10.0'])
    end subroutine test_empty_grid

    subroutine test_oversized(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'nx = 16, ny = 16', 'nx = 5000, ny = 5000'), &
            [character(len=16) :: '&grid', 'nx', '5000', 'oversized'])
    end subroutine test_oversized

    subroutine test_no_contact(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'approach = 0.1091', 'approach = -0.01'), &
            [character(len=16) :: '&normal', 'approach', '-0.01', 'no contact'])
    end subroutine test_no_contact

    !> An automatic area the grid builder rejects (FC_ERR_AREA: a contact of 1.6e-8 mm, 64
    !! elements across it are below the 1e-9 mm element size) names what the area was sized
    !! from; the driver chooses that context by the error code.
    subroutine test_auto_area_too_fine(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, "&case name = 'bad' /"//nl// &
            '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            '&grid auto = .true., n_across = 64 /'//nl//"&geometry kind = 'quadratic', rx = 1e-6, ry = 1e-6 /"//nl// &
            '&normal fn = 1e-12 /'//nl, &
            [character(len=40) :: '&grid (automatic, sized from &normal fn', 'rx = 1.00000000E-06', &
            'element size dx, dy', 'below the limit'])
    end subroutine test_auto_area_too_fine

    subroutine test_fn_not_positive(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'approach = 0.1091', 'fn = 0.0'), &
            [character(len=16) :: '&normal', 'fn', '0.0'])
    end subroutine test_fn_not_positive

    subroutine test_approach_and_fn(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'approach = 0.1091', 'approach = 0.1091, fn = 1000.0'), &
            [character(len=16) :: '&normal', 'approach', 'fn', '1000.0'])
    end subroutine test_approach_and_fn

    subroutine test_unknown_solver(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, base_case('bad')//"&solver normal = 'magic_solver_x', tol = 1e-6 /"//nl, &
            [character(len=16) :: '&solver', 'normal', 'magic_solver_x'])
    end subroutine test_unknown_solver

    subroutine test_unknown_problem(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), "name = 'bad'", "name = 'bad', problem = 'sliding'"), &
            [character(len=20) :: '&case', 'problem', 'sliding', 'unknown'])
    end subroutine test_unknown_problem

    ! ---------------------------------------------------------------- tangential ----

    !> Cattaneo (doc/conventions.md) on 30×25, Table 4.1 case 3 shifts, named `name`.
    function cattaneo_case(name) result(text)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text
        text = "&case name = '"//name//"', problem = 'normal+tangential' /"//nl// &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
            '&grid nx = 30, ny = 25, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /'//nl// &
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl// &
            '&normal fn = 9.1954 /'//nl// &
            '&tangential mu = 0.4, xi = 0.0, eta = 0.0015, phi = 0.0012 /'//nl
    end function cattaneo_case

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

    !> Sums over the CSV table: Σ px, Σ py, Σ (x py − y px) (times dx·dy by the caller),
    !! and the number of rows with status A, S, E.
    subroutine csv_sums(path, spx, spy, smz, na, ns, ne)
        character(len=*), intent(in) :: path
        real(dp), intent(out) :: spx, spy, smz
        integer, intent(out) :: na, ns, ne
        character(len=1024) :: line
        character(len=1) :: st
        integer :: u, ios, ix, iy
        real(dp) :: x, y, pn, px, py, sx, sy, gap
        spx = 0; spy = 0; smz = 0; na = 0; ns = 0; ne = 0
        open (newunit=u, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        read (u, '(a)', iostat=ios) line
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            read (line, *) ix, iy, x, y, st, pn, px, py, sx, sy, gap
            spx = spx + px; spy = spy + py; smz = smz + (x*py - y*px)
            select case (st)
            case ('A'); na = na + 1
            case ('S'); ns = ns + 1
            case ('E'); ne = ne + 1
            end select
        end do
        close (u)
    end subroutine csv_sums

    subroutine test_tangential_case(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code, na, ns, ne
        character(len=:), allocatable :: errors, dir, j, rep
        real(dp) :: spx, spy, smz, da, fx, fy, mz, fscale
        call run_text(cattaneo_case('cat3'), code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j = read_all(dir//'/cat3.json')
        call check(error, index(j, '"status": "converged"') > 0, 'not converged: '//j)
        call check(error, index(j, '"status_tangential": "converged"') > 0, 'tangential stage not converged')
        call check(error, index(j, '"solver": "bccg+tangcg"') > 0, 'solver must name both stages')
        call check(error, json_num(j, 'iterations_normal') > 0 .and. json_num(j, 'iterations_tangential') > 0 &
            .and. json_num(j, 'matvecs_tangential') > 0 .and. json_num(j, 'outer_iterations_tangential') > 0 &
            .and. json_num(j, 'panagiotopoulos_rounds') == 1 .and. json_num(j, 'cpu_seconds_tangential') < huge(1.0_dp), &
            'per-stage JSON keys missing: '//j)
        call check(error, json_num(j, 'eta') == 0.0015_dp .and. json_num(j, 'phi') == 0.0012_dp, 'shifts used')
        call csv_sums(dir//'/cat3.csv', spx, spy, smz, na, ns, ne)
        call check(error, na > 0 .and. ns > 0 .and. ne > 0, 'CSV must have A, S and E rows')
        call check(error, na + ns == nint(json_num(j, 'ncon')) .and. na == nint(json_num(j, 'nadh')) .and. &
            ns == nint(json_num(j, 'nslip')), 'CSV status counts must match ncon/nadh/nslip')
        da = json_num(j, 'dx')*json_num(j, 'dy')
        fx = json_num(j, 'fx'); fy = json_num(j, 'fy'); mz = json_num(j, 'mz')
        fscale = hypot(fx, fy)
        call check(error, fscale > 0.1_dp, 'tangential force expected for case 3')
        call check(error, abs(spx*da - fx) <= 1e-10_dp*fscale, 'CSV sum px dx dy must equal fx')
        call check(error, abs(spy*da - fy) <= 1e-10_dp*fscale, 'CSV sum py dx dy must equal fy')
        call check(error, abs(smz*da - mz) <= 1e-10_dp*abs(mz), 'CSV moment must equal mz')
        ! thesis Table 4.1 case 3: 20 % slip (120 x 100); a 30 x 25 grid gives roughly the same
        call check(error, ns > 0.1_dp*(na + ns) .and. ns < 0.3_dp*(na + ns), 'case 3 slip fraction near 20 %')
        rep = read_all(dir//'/report.txt')
        call check(error, index(rep, "'A' adhesion, 'S' slip") > 0 .and. index(rep, 'nslip') > 0, 'report map legend')
        call cleanup(dir)
    end subroutine test_tangential_case

    subroutine test_tangential_force(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j
        real(dp), parameter :: fx_target = 3.218390_dp, mu = 0.4_dp, fn = 9.1954_dp, tol = 1.0e-5_dp
        call run_text(replace(cattaneo_case('catf'), 'xi = 0.0, eta = 0.0015, phi = 0.0012', &
            'fx = 3.218390, phi = 0.0'), code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j = read_all(dir//'/catf.json')
        call check(error, index(j, '"tangential_load": "forces"') > 0, 'forces must be prescribed: '//j)
        call check(error, abs(json_num(j, 'fx') - fx_target) <= 2*tol*mu*fn, 'fx must hit the prescribed force')
        call check(error, abs(json_num(j, 'fy')) <= 2*tol*mu*fn, 'fy must be 0')
        call check(error, json_num(j, 'xi') < -0.006_dp .and. json_num(j, 'xi') > -0.010_dp, &
            'shift used must be near -0.0082 (tractions oppose the motion of body 1)')
        call check(error, json_num(j, 'fx_prescribed') == fx_target, 'fx_prescribed in the JSON')
        call cleanup(dir)
    end subroutine test_tangential_force

    !> Same case with TangCG and ConvexGS (inherited, only the solver changes; the
    !! tangential operator is reused).
    subroutine test_tangcg_vs_convexgs(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j1, j2
        real(dp) :: f1, f2
        call run_text(replace(cattaneo_case('cg'), 'xi = 0.0, eta = 0.0015, phi = 0.0012', &
            'xi = 0.0021, eta = 0.0010, phi = 0.003')//"&solver tol = 1e-8, maxit = 5000 /"//nl// &
            "&case name = 'gs' /"//nl//"&solver tangential = 'convexgs' /"//nl, code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j1 = read_all(dir//'/cg.json'); j2 = read_all(dir//'/gs.json')
        call check(error, index(j2, '"solver_tangential": "convexgs"') > 0, 'second case must use convexgs')
        f1 = json_num(j1, 'fx'); f2 = json_num(j2, 'fx')
        call check(error, abs(f1 - f2) <= 1e-4_dp*abs(f1), 'fx of tangcg and convexgs must agree to 1e-4')
        f1 = json_num(j1, 'fy'); f2 = json_num(j2, 'fy')
        call check(error, abs(f1 - f2) <= 1e-4_dp*abs(f1), 'fy of tangcg and convexgs must agree to 1e-4')
        call check(error, index(j1, '"operator_built_tangential": true') > 0, 'first case builds the tangential operator')
        call check(error, index(j2, '"operator_built_tangential": false') > 0 .and. &
            index(j2, '"operator_built": false') > 0, 'second case (same grid and material) reuses both operators')
        call check(error, json_num(j1, 'nslip') == json_num(j2, 'nslip'), 'same slip area')
        call cleanup(dir)
    end subroutine test_tangcg_vs_convexgs

    !> `&solver fft_wisdom`: the first run measures the grid's plans and writes the file, a
    !! second run reads it and measures nothing (the file is unchanged); the forces equal a
    !! run without wisdom to rounding; a file that is not wisdom, and a file that cannot be
    !! created, are errors naming the key, the value and the reason.
    subroutine test_fft_wisdom_file(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, plain, first, w1
        real(dp) :: scale
        call run_text(cattaneo_case('plain'), code, errors, dir)
        call check(error, code == 0, 'without wisdom: exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        plain = read_all(dir//'/plain.json')
        call run_again(dir, cattaneo_case('first')//"&solver fft_wisdom = '"//dir//"/plans.fftw' /"//nl, code, errors)
        call check(error, code == 0 .and. exists(dir//'/plans.fftw'), 'first run: exit 0 and the file written, errors: '//errors)
        if (allocated(error)) return
        w1 = read_all(dir//'/plans.fftw')
        call check(error, index(w1, '(fftw-3') == 1, 'the file holds FFTW wisdom')
        first = read_all(dir//'/first.json')
        scale = 0.4_dp*json_num(plain, 'fn')
        call check(error, abs(json_num(first, 'fx') - json_num(plain, 'fx')) <= 1e-10_dp*scale .and. &
            abs(json_num(first, 'fy') - json_num(plain, 'fy')) <= 1e-10_dp*scale, 'measured plans: forces equal to rounding')
        call check_wisdom_rerun(dir, cattaneo_case('again'), cattaneo_case('bad'), 'plans.fftw', first, w1, error)
        call run_again(dir, cattaneo_case('nodir')//"&solver fft_wisdom = '"//dir//"/no/such/dir/p.fftw' /"//nl, &
            code, errors)
        call check(error, code == 1 .and. index(errors, 'cannot create the wisdom file') > 0, &
            'unwritable path: exit 1, got: '//errors)
        call fftw_forget_wisdom()
        call cleanup(dir)
    end subroutine test_fft_wisdom_file

    !> `&solver fft_wisdom` on a strip model problem (MP1, 1024×1, MG FFT+RSM V(1,1)): the first run measures
    !! the plans of every level's products and writes them to the file, a second run reads
    !! it and measures nothing; cycles and force equal a run without wisdom (to rounding); a
    !! file that is not wisdom is an error naming the key and the value.
    subroutine test_strip_fft_wisdom_file(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, plain, first, w1
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: t
        integer :: stat
        character(len=256) :: msg
        call run_text(strip_case('plain', '1', '1024', 'mg-fft-rsm'), code, errors, dir)
        call check(error, code == 0, 'strip without wisdom: exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        plain = read_all(dir//'/plain.json')
        call run_again(dir, strip_case('first', '1', '1024', 'mg-fft-rsm')//"&solver fft_wisdom = '"//dir// &
            "/strip.fftw' /"//nl, code, errors)
        call check(error, code == 0 .and. exists(dir//'/strip.fftw'), 'first run: exit 0 and the file written, errors: '// &
            errors)
        if (allocated(error)) return
        call strip_model_problem(1, 1024, prob, stat, msg)
        call check(error, strip_plans_in_wisdom(strip_level_sizes(prob, t, .true.)), &
            "the process holds measured plans for every level's products")
        w1 = read_all(dir//'/strip.fftw')
        first = read_all(dir//'/first.json')
        call check(error, json_num(first, 'iterations') == json_num(plain, 'iterations') .and. &
            abs(json_num(first, 'fx') - json_num(plain, 'fx')) <= 1e-10_dp*abs(json_num(plain, 'fx')), &
            'measured plans: same cycles, force equal to rounding')
        call check_wisdom_rerun(dir, strip_case('again', '1', '1024', 'mg-fft-rsm'), &
            strip_case('bad', '1', '1024', 'mg-fft-rsm'), 'strip.fftw', first, w1, error)
        call fftw_forget_wisdom()
        call cleanup(dir)
    end subroutine test_strip_fft_wisdom_file

    !> Second run with the wisdom file `path` (in `dir`) of a case whose first run wrote
    !! `first` and the file `w1`: after FFTW forgets its wisdom, the run reads the file,
    !! measures nothing (the file is unchanged) and gives the same fx; then a file that is
    !! not wisdom is an error (exit 1) naming the key and the value.
    subroutine check_wisdom_rerun(dir, again_case, bad_case, path, first, w1, error)
        character(len=*), intent(in) :: dir, again_case, bad_case, path, first, w1
        type(error_type), allocatable, intent(inout) :: error
        integer :: code
        character(len=:), allocatable :: errors, again, w2
        call fftw_forget_wisdom()
        call run_again(dir, again_case//"&solver fft_wisdom = '"//dir//'/'//path//"' /"//nl, code, errors)
        w2 = read_all(dir//'/'//path)
        again = read_all(dir//'/again.json')
        call check(error, code == 0 .and. w1 == w2, 'second run: read, nothing measured, the file unchanged')
        call check(error, json_num(again, 'fx') == json_num(first, 'fx'), 'second run: the same plans, the same forces')
        call execute_command_line("echo 'not wisdom' > '"//dir//"/bad.fftw'")
        call run_again(dir, bad_case//"&solver fft_wisdom = '"//dir//"/bad.fftw' /"//nl, code, errors)
        call check(error, code == 1 .and. index(errors, "&solver fft_wisdom = '"//dir//"/bad.fftw'") > 0 .and. &
            index(errors, 'cannot read it as wisdom') > 0, 'not wisdom: exit 1 naming key and value, got: '//errors)
    end subroutine check_wisdom_rerun

    !> The normal stage fails: JSON and CSV written, status not_converged, tangential not run.
    subroutine test_tangential_normal_not_converged(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j
        call run_text(cattaneo_case('nc')//'&solver maxit = 2 /'//nl, code, errors, dir)
        call check(error, code == 2, 'exit code 2 expected for not converged')
        j = read_all(dir//'/nc.json')
        call check(error, index(j, '"status": "not_converged"') > 0, 'status must be not_converged: '//j)
        call check(error, index(j, '"status_tangential": "not_run"') > 0 .or. &
            index(j, '"status_tangential": "not_converged"') > 0, 'tangential status: '//j)
        call check(error, exists(dir//'/nc.csv'), 'CSV written with the failed status')
        call cleanup(dir)
    end subroutine test_tangential_normal_not_converged

    subroutine test_tangential_ignored(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j
        call run_text(replace(cattaneo_case('n'), "problem = 'normal+tangential'", "problem = 'normal'"), &
            code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j = read_all(dir//'/n.json')
        call check(error, json_num(j, 'fx') == 0 .and. json_num(j, 'eta') == 0, 'normal problem: no tangential results')
        call check(error, index(read_all(dir//'/report.txt'), '&tangential ignored') > 0, 'report must note it')
        call cleanup(dir)
    end subroutine test_tangential_ignored

    !> problem = 'tangential' runs the same pipeline as 'normal+tangential'.
    subroutine test_tangential_synonym(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j1, j2
        call run_text(cattaneo_case('nt')//"&case name = 't', problem = 'tangential' /"//nl, code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j1 = read_all(dir//'/nt.json'); j2 = read_all(dir//'/t.json')
        call check(error, json_num(j1, 'fy') == json_num(j2, 'fy') .and. json_num(j1, 'nslip') == json_num(j2, 'nslip'), &
            "'tangential' and 'normal+tangential' must give the same result")
        call cleanup(dir)
    end subroutine test_tangential_synonym

    !> Rigid sphere on an elastic plane (K /= 0): coupled by Panagiotopoulos rounds.
    subroutine test_dissimilar(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j
        call run_text(replace(cattaneo_case('k'), 'g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42', &
            'g1 = 1.0e30, g2 = 200.0, nu1 = 0.3, nu2 = 0.3'), code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j = read_all(dir//'/k.json')
        call check(error, json_num(j, 'k') /= 0, 'K must be non-zero')
        call check(error, json_num(j, 'panagiotopoulos_rounds') > 1, 'K /= 0 needs more than one round: '//j)
        call check(error, index(j, '"status": "converged"') > 0, 'coupled case must converge')
        call check(error, index(read_all(dir//'/report.txt'), 'without the tangential coupling') == 0, &
            'no decoupling note for a tangential problem')
        call cleanup(dir)
    end subroutine test_dissimilar

    subroutine test_mu_negative(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(cattaneo_case('bad'), 'mu = 0.4', 'mu = -0.1'), &
            [character(len=16) :: '&tangential', 'mu', '-0.1'])
    end subroutine test_mu_negative

    subroutine test_mu_missing(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(cattaneo_case('bad'), 'mu = 0.4, ', ''), &
            [character(len=16) :: '&tangential', 'mu', 'missing'])
    end subroutine test_mu_missing

    subroutine test_mu_zero_forces(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(cattaneo_case('bad'), 'mu = 0.4, xi = 0.0, eta = 0.0015', 'mu = 0.0, fx = 1.0'), &
            [character(len=16) :: '&tangential', 'mu', '0.0', 'fx'])
    end subroutine test_mu_zero_forces

    subroutine test_shift_and_force(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(cattaneo_case('bad'), 'xi = 0.0', 'xi = 0.0, fx = 1.5'), &
            [character(len=16) :: '&tangential', 'xi', 'fx', '1.5', 'not both'])
    end subroutine test_shift_and_force

    subroutine test_unknown_tangential_solver(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, cattaneo_case('bad')//"&solver tangential = 'magic_tangential_x' /"//nl, &
            [character(len=20) :: '&solver', 'tangential', 'magic_tangential_x'])
    end subroutine test_unknown_tangential_solver

    subroutine test_inner_k_zero(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, cattaneo_case('bad')//'&solver inner_k = 0 /'//nl, &
            [character(len=16) :: '&solver', 'inner_k', '0'])
    end subroutine test_inner_k_zero

    !> |fx| >= mu fn with fn prescribed: caught by the input check.
    subroutine test_force_limit_fn(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(cattaneo_case('bad'), 'xi = 0.0, eta = 0.0015', 'fx = 3.7'), &
            [character(len=16) :: '&tangential', 'fx', '3.7', 'mu*fn'])
    end subroutine test_force_limit_fn

    !> |fx| >= mu fn with the approach prescribed: caught by the library after the normal
    !! solve, reported as a case error.
    subroutine test_force_limit_approach(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(replace(cattaneo_case('bad'), 'xi = 0.0, eta = 0.0015', 'fx = 3.7'), &
            'fn = 9.1954', 'approach = 0.02'), [character(len=16) :: '&tangential', 'fx', '3.7', 'mu*fn'])
    end subroutine test_force_limit_approach

    subroutine test_strip2d_ny(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), "kind = 'quadratic'", "kind = 'strip2d'"), &
            [character(len=16) :: '&grid', 'ny', '16', 'strip2d'])
    end subroutine test_strip2d_ny

    !> A cylinder length or a wavelength near the smallest double (the driver fuzz: 4.9e−324)
    !! is an input error naming the key and the limit 1e−9 mm; before, the line load Fn/length
    !! and the phase 2πx/λ overflowed (SIGFPE in the sanitizer build, or a grid of infinite
    !! extent reported as a grid error).
    subroutine test_tiny_lengths(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), "kind = 'quadratic', rx = 300.0, ry = 163.0", &
            "kind = 'cylinder', rx = 100.0, length = 4.9e-324"), [character(len=20) :: '&geometry', 'length', &
            'at least', '1.0E-09'])
        if (allocated(error)) return
        call expect_bad(error, replace(base_case('bad'), "kind = 'quadratic', rx = 300.0, ry = 163.0", &
            "kind = 'wavy', amplitude = 0.001, wavelength_x = 4.9e-324, wavelength_y = 1.0"), &
            [character(len=20) :: '&geometry', 'wavelength_x', 'at least', '1.0E-09'])
    end subroutine test_tiny_lengths

    subroutine test_missing_table(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), "kind = 'quadratic', rx = 300.0, ry = 163.0", &
            "kind = 'table', file = '/nonexistent/h0.txt'"), [character(len=20) :: '&geometry', 'file', &
            '/nonexistent/h0.txt'])
    end subroutine test_missing_table

    subroutine test_bad_command_line(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code, u
        open (newunit=u, status='scratch')
        call run_driver([character(len=64) :: '/nonexistent/cases.nml'], code, report_unit=u, error_unit=u)
        call check(error, code /= 0, 'missing case file must give a non-zero exit code')
        call run_driver([character(len=64) :: 'a.nml', '--bogus'], code, report_unit=u, error_unit=u)
        call check(error, code /= 0, 'unknown option must give a non-zero exit code')
        call run_driver([character(len=64) :: '--help'], code, report_unit=u, error_unit=u)
        call check(error, code == 0, '--help must exit 0')
        close (u)
    end subroutine test_bad_command_line

    !> `--version` prints one line with the package version and exits 0 without solving;
    !! every JSON summary and report records the same version.
    subroutine test_version_option(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code, u, ios
        character(len=256) :: line
        character(len=:), allocatable :: errors, dir, json
        open (newunit=u, status='scratch')
        call run_driver([character(len=64) :: '--version'], code, report_unit=u, error_unit=u)
        call check(error, code == 0, '--version must exit 0')
        rewind (u)
        read (u, '(a)', iostat=ios) line
        call check(error, ios == 0 .and. index(line, 'fastcontact '//fc_version_string//' (') == 1, &
            '--version printed: '//trim(line))
        read (u, '(a)', iostat=ios) line
        call check(error, is_iostat_end(ios), '--version must print one line, then: '//trim(line))
        close (u)
        if (allocated(error)) return
        call run_text(base_case('versioned'), code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        json = read_all(dir//'/versioned.json')
        call check(error, index(json, '"version": "'//fc_version_string//'"') > 0, 'no version in the JSON: '//json)
    end subroutine test_version_option

    !> The version the code reports is fpm.toml's (and the MPI package's), and its three
    !! numbers are those of the string.
    subroutine test_version_manifest(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=32) :: numbers
        call check(error, manifest_version('fpm.toml') == fc_version_string, &
            'fpm.toml version "'//manifest_version('fpm.toml')//'" differs from fc_version_string '//fc_version_string)
        call check(error, manifest_version('mpi/fpm.toml') == fc_version_string, &
            'mpi/fpm.toml version "'//manifest_version('mpi/fpm.toml')//'" differs from '//fc_version_string)
        write (numbers, '(i0,".",i0,".",i0)') fc_version_major, fc_version_minor, fc_version_patch
        call check(error, trim(numbers) == fc_version_string, 'major.minor.patch '//trim(numbers)// &
            ' differs from '//fc_version_string)
    end subroutine test_version_manifest

    !> The top-level `version = "..."` of a manifest ('' when there is none).
    function manifest_version(path) result(v)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: v
        character(len=512) :: line
        integer :: u, ios, q1, q2
        v = ''
        open (newunit=u, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (line(1:1) == '[') exit      ! tables start: the package keys are above
            if (index(adjustl(line), 'version') /= 1) cycle
            q1 = index(line, '"'); q2 = index(line, '"', back=.true.)
            if (q2 > q1 + 1) v = line(q1 + 1:q2 - 1)
            exit
        end do
        close (u)
    end function manifest_version

    ! ---------------------------------------------------------------- multigrid ----

    !> Hertz Test I on 32² (the base case's area at 32²) with tolerance 1e-8.
    function hertz32(name) result(text)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text
        text = replace(base_case(name), 'nx = 16, ny = 16', 'nx = 32, ny = 32')//'&solver tol = 1e-8 /'//nl
    end function hertz32

    !> FMG V(1,1) and BCCG agree in fn to 1e-4 (relative) on Hertz 32², approach and force.
    subroutine test_fmg_hertz(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, jb, jf, jff
        real(dp) :: fb, ff
        call run_text(hertz32('b')//"&case name = 'f' /"//nl//"&solver normal = 'fmg' /"//nl// &
            "&case name = 'ff' /"//nl//'&normal fn = 82000.0 /'//nl, code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        jb = read_all(dir//'/b.json'); jf = read_all(dir//'/f.json'); jff = read_all(dir//'/ff.json')
        call check(error, index(jf, '"status": "converged"') > 0 .and. index(jf, '"solver": "fmg"') > 0, &
            'fmg case must converge with solver fmg: '//jf)
        call check(error, index(jf, '"cycle": "V(1,1)"') > 0, 'default cycle V(1,1) expected in the JSON')
        fb = json_num(jb, 'fn'); ff = json_num(jf, 'fn')
        call check(error, abs(ff - fb) <= 1.0e-4_dp*fb, 'fmg and bccg fn differ: '//jf)
        call check(error, json_num(jf, 'iterations') >= 1 .and. json_num(jf, 'iterations') <= 20, &
            'fmg V(1,1) target-grid cycles not in [1, 20]')
        call check(error, json_num(jf, 'work_units') > 0 .and. json_num(jf, 'work_units') < 200, &
            'fmg work units not in (0, 200)')
        call check(error, index(jff, '"status": "converged"') > 0 .and. abs(json_num(jff, 'fn') - 82000) < 1.0e-3_dp, &
            'fmg with prescribed fn must meet it: '//jff)
        call check(error, exists(dir//'/f.csv'), 'fmg CSV missing')
        call cleanup(dir)
    end subroutine test_fmg_hertz

    !> Every cycle name converges on Hertz 32².
    subroutine test_fmg_cycles(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code, k
        character(len=:), allocatable :: errors, dir, j
        character(len=6), parameter :: cycles(3) = ['V(1,1)', 'V(1,0)', 'V(0,1)']
        character(len=2), parameter :: names(3) = ['11', '10', '01']
        character(len=:), allocatable :: text
        text = hertz32('b')
        do k = 1, 3
            text = text//"&case name = 'c"//names(k)//"' /"//nl//"&solver normal = 'fmg', cycle = '"//cycles(k)//"' /"//nl
        end do
        call run_text(text, code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        do k = 1, 3
            j = read_all(dir//'/c'//names(k)//'.json')
            call check(error, index(j, '"status": "converged"') > 0, cycles(k)//' must converge: '//j)
            call check(error, index(j, '"cycle": "'//cycles(k)//'"') > 0, cycles(k)//' not reported: '//j)
            call check(error, abs(json_num(j, 'fn') - json_num(read_all(dir//'/b.json'), 'fn')) < &
                1.0e-4_dp*json_num(j, 'fn'), cycles(k)//': fn differs from bccg')
            if (allocated(error)) return
        end do
        call cleanup(dir)
    end subroutine test_fmg_cycles

    subroutine test_fmg_bad_cycle(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, base_case('bad')//"&solver normal = 'fmg', cycle = 'W(2,1)' /"//nl, &
            [character(len=16) :: '&solver', 'cycle', 'W(2,1)'])
    end subroutine test_fmg_bad_cycle

    subroutine test_fmg_bad_omega(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, base_case('bad')//"&solver normal = 'fmg', omega = -0.5 /"//nl, &
            [character(len=16) :: '&solver', 'omega', '-0.5'])
        if (allocated(error)) return
        call expect_bad(error, base_case('bad')//"&solver normal = 'fmg', omega = 0.0 /"//nl, &
            [character(len=16) :: '&solver', 'omega', '0.0'])
    end subroutine test_fmg_bad_omega

    subroutine test_fmg_bad_smoother(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, base_case('bad')//"&solver normal = 'fmg', smoother = 'sor' /"//nl, &
            [character(len=16) :: '&solver', 'smoother', 'sor'])
    end subroutine test_fmg_bad_smoother

    !> 250² coarsens only to 125² (> 4096 cells for the direct coarsest solve): a case error.
    subroutine test_fmg_coarsest(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), 'nx = 16, ny = 16', 'nx = 250, ny = 250')// &
            "&solver normal = 'fmg' /"//nl, [character(len=16) :: '&grid', 'nx = 250', 'ny = 250', &
            '&solver normal', 'fmg'])
    end subroutine test_fmg_coarsest

    !> A punch narrower than an element touches nowhere: the library's FC_ERR_GEOMETRY, which
    !! the driver reports under &geometry with the kind (context chosen by the code).
    subroutine test_punch_too_small(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(base_case('bad'), "kind = 'quadratic', rx = 300.0, ry = 163.0", &
            "kind = 'punch_rough', diameter = 0.5, sigma = 0.0"), &
            [character(len=16) :: '&geometry', "'punch_rough'", 'no element'])
    end subroutine test_punch_too_small

    !> ry = 0 (a line contact, reduced to a strip) with an automatic area: the length is
    !! unknown, refused by the &grid validator before any solve.
    subroutine test_line_auto_area(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, "&case name = 'bad' /"//nl// &
            '&material g1 = 82000.0, g2 = 82000.0 /'//nl// &
            "&geometry kind = 'quadratic', rx = 300.0, ry = 0.0 /"//nl// &
            '&normal approach = 0.01 /'//nl, [character(len=16) :: '&geometry', 'ry = 0', 'automatic grid'])
    end subroutine test_line_auto_area

    !> K ≠ 0 needs the Panagiotopoulos loop on the BCCG path: FMG is rejected.
    subroutine test_fmg_dissimilar(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(replace(cattaneo_case('bad'), 'g2 = 200.0', 'g2 = 400.0'), 'nu2 = 0.42', &
            'nu2 = 0.3')//"&solver normal = 'fmg' /"//nl, [character(len=16) :: '&solver normal', 'fmg', 'K ='])
    end subroutine test_fmg_dissimilar

    !> K = 0: FMG for the normal stage, then TangCG; same forces as BCCG + TangCG.
    subroutine test_fmg_tangential(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, jb, jf
        call run_text(replace(cattaneo_case('b'), 'nx = 30, ny = 25', 'nx = 32, ny = 32')//'&solver tol = 1e-8 /'//nl// &
            "&case name = 'f' /"//nl// &
            "&solver normal = 'fmg' /"//nl, code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        jb = read_all(dir//'/b.json'); jf = read_all(dir//'/f.json')
        call check(error, index(jf, '"solver": "fmg+tangcg"') > 0, 'solver fmg+tangcg expected: '//jf)
        call check(error, abs(json_num(jf, 'fn') - json_num(jb, 'fn')) <= 1.0e-4_dp*abs(json_num(jb, 'fn')), 'fn differs')
        call check(error, abs(json_num(jf, 'fx') - json_num(jb, 'fx')) <= 1.0e-4_dp*abs(json_num(jb, 'fx')) + 1.0e-9_dp, &
            'fx differs: '//jf)
        call cleanup(dir)
    end subroutine test_fmg_tangential

    !> A strip model problem case.
    function strip_case(name, which, nx, solver) result(text)
        character(len=*), intent(in) :: name, which, nx, solver
        character(len=:), allocatable :: text
        text = "&case name = '"//name//"', problem = 'strip_mp"//which//"' /"//nl// &
            "&geometry kind = 'strip2d' /"//nl//'&grid nx = '//nx//' /'//nl//"&solver strip = '"//solver//"' /"//nl
    end function strip_case

    !> MP1 at 2^10 with the three strip solvers: converged, counts near doc/multigrid.md
    !! (MG FFT+RSM V(1,1): 5 cycles at 2^10; FFT+SD V(1,0): 6 at 2^14; one-grid FFT+RSM: 28
    !! at 2^16, fewer on smaller grids), same traction.
    subroutine test_strip_mp1(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j1, j2, j3, csv
        real(dp) :: it
        call run_text(strip_case('rsm', '1', '1024', 'mg-fft-rsm')//strip_case('sd', '1', '1024', 'mg-fft-sd')// &
            "&solver cycle = 'V(1,0)' /"//nl//strip_case('one', '1', '1024', 'fft-rsm'), code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j1 = read_all(dir//'/rsm.json'); j2 = read_all(dir//'/sd.json'); j3 = read_all(dir//'/one.json')
        call check(error, index(j1, '"status": "converged"') > 0 .and. index(j2, '"status": "converged"') > 0 .and. &
            index(j3, '"status": "converged"') > 0, 'all three must converge')
        it = json_num(j1, 'iterations')
        call check(error, it >= 4 .and. it <= 7, 'MG FFT+RSM V(1,1) cycles not in [4, 7]: '//j1)
        it = json_num(j2, 'iterations')
        call check(error, it >= 4 .and. it <= 9, 'MG FFT+SD V(1,0) cycles not in [4, 9]: '//j2)
        it = json_num(j3, 'iterations')
        call check(error, it >= 20 .and. it <= 32, 'FFT+RSM iterations not in [20, 32]: '//j3)
        call check(error, json_num(j1, 'residual') <= 1.0e-8_dp .and. json_num(j1, 'tol') == 1.0e-8_dp, &
            'tol 1e-8 by default for strip problems')
        call check(error, json_num(j1, 'convergence_factor') < 0.2_dp .and. json_num(j1, 'work_units') > 0, &
            'factor and work units expected')
        call check(error, abs(json_num(j1, 'fx') - json_num(j3, 'fx')) <= 1.0e-6_dp*abs(json_num(j1, 'fx')), &
            'MG and one-grid solutions differ in fx')
        csv = read_all(dir//'/rsm.csv')
        call check(error, count_lines(csv) == 1 + 1024, 'CSV must have 1 + 1024 lines')
        call check(error, index(csv, ',A,') > 0 .and. index(csv, ',E,') == 0, 'MP1: every element A')
        call cleanup(dir)
    end subroutine test_strip_mp1

    !> MP3: elements outside the strips [−4,−2] ∪ [0,4] are exterior with zero traction.
    subroutine test_strip_mp3(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: code
        character(len=:), allocatable :: errors, dir, j
        call run_text(strip_case('mp3', '3', '256', 'mg-fft-rsm'), code, errors, dir)
        call check(error, code == 0, 'exit code 0 expected, errors: '//errors)
        if (allocated(error)) return
        j = read_all(dir//'/mp3.json')
        call check(error, json_num(j, 'ncon') == 192, 'MP3 at 256: 192 elements on the strips: '//j)
        call check(error, index(read_all(dir//'/mp3.csv'), ',E,0.000000000000000E+000,0.000000000000000E+000,') > 0, &
            'exterior rows with zero traction expected')
        call cleanup(dir)
    end subroutine test_strip_mp3

    subroutine test_strip_unknown_solver(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, strip_case('bad', '1', '64', 'fft-magic'), [character(len=16) :: '&solver', 'strip', &
            'fft-magic'])
    end subroutine test_strip_unknown_solver

    subroutine test_strip_bad_nx(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, strip_case('bad', '2', '1000', 'mg-fft-rsm'), [character(len=16) :: '&grid', 'nx', '1000', &
            'power of 2'])
        if (allocated(error)) return
        ! the most negative integer: the power-of-2 test must not overflow (found by the
        ! sanitized fuzz run, UBSan: nx − 1)
        call expect_bad(error, strip_case('bad', '2', '-2147483648', 'mg-fft-rsm'), [character(len=16) :: '&grid', 'nx', &
            '-2147483648', 'power of 2'])
    end subroutine test_strip_bad_nx

    subroutine test_strip_needs_kind(error)
        type(error_type), allocatable, intent(out) :: error
        call expect_bad(error, replace(strip_case('bad', '1', '64', 'fft-rsm'), "'strip2d'", "'quadratic'"), &
            [character(len=16) :: '&geometry', 'kind', 'quadratic', 'strip2d'])
    end subroutine test_strip_needs_kind

    !> The grid bound: the serial driver refuses nx·ny > 4096², a distributed solve
    !! (`grid_limit = max_dist_grid_elements`) accepts 5000 × 4000 and refuses 40000², each
    !! message naming the key, the values and the limit.
    subroutine test_grid_limit(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_case_chunk), allocatable :: cases(:)
        type(fc_case_input) :: state
        character(len=64) :: name
        character(len=512) :: msg
        integer :: u, stat
        character(len=*), parameter :: path = 'build/test_driver_grid_limit.nml'
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') "&case name = 'big' /"
        write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
        write (u, '(a)') "&grid nx = 5000, ny = 4000, xmin = 0.0, xmax = 1.0, ymin = 0.0, ymax = 1.0, periodic = .true. /"
        write (u, '(a)') "&geometry kind = 'punch_rough', diameter = 2.0, sigma = 1.0e-3 /"
        write (u, '(a)') "&normal fn = 200.0 /"
        close (u, status='keep')
        call read_case_file(path, cases, stat, msg)
        call check(error, stat == 0, 'read: '//trim(msg))
        if (allocated(error)) return
        call apply_case(cases(1), 1, state, name, stat, msg)
        call check(error, stat == 0, 'apply: '//trim(msg))
        if (allocated(error)) return
        call validate_case(state, stat, msg)
        call check(error, stat /= 0 .and. index(msg, '&grid nx = 5000, ny = 4000: oversized grid (nx*ny > 4096*4096)') == 1, &
            'serial bound: '//trim(msg))
        call validate_case(state, stat, msg, grid_limit=max_dist_grid_elements)
        call check(error, stat == 0, 'distributed bound refuses 5000 x 4000: '//trim(msg))
        state%nx = 40000; state%ny = 40000
        call validate_case(state, stat, msg, grid_limit=max_dist_grid_elements)
        call check(error, stat /= 0 .and. index(msg, 'oversized grid (nx*ny > 32768*32768)') > 0, &
            'distributed bound: '//trim(msg))
    end subroutine test_grid_limit

end module test_driver
