!> Suite `batch`: batches that outlive one job — the driver's `--resume` (skip the cases an
!! earlier run finished with the same input) and `--part K/N` (one of N processes sharing a
!! file), and the input fingerprint they rest on ([[fc_driver_resume]]).
module test_batch
    use fc_kinds, only: dp
    use fc_test_driver, only: fresh_dir, run_namelist
    use fc_driver, only: parse_driver_arguments
    use fc_driver_resume, only: parse_part, with_files
    use test_driver, only: without_times, json_num
    use fc_testing, only: error_type, unittest_type, new_unittest, check, read_all => file_lines
    implicit none
    private
    public :: collect_batch

    character(len=*), parameter :: nl = new_line('a')

contains

    subroutine collect_batch(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('resume_skips_finished_cases', test_resume), &
            new_unittest('resume_reads_named_files', test_resume_files), &
            new_unittest('parts_make_the_whole_run', test_parts), &
            new_unittest('part_and_resume_arguments', test_arguments) ]
    end subroutine collect_batch

    !> Four cases: Hertz on 16², the same with a tangential shift, a rolling sweep, and a
    !! tangential case whose solver stops after one iteration (not converged).
    function four_cases(xi2) result(text)
        character(len=*), intent(in) :: xi2   !! the shift of case t2
        character(len=:), allocatable :: text
        text = "&case name = 'n1' /"//nl// &
            '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl// &
            "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"//nl//'&normal approach = 0.1091 /'//nl// &
            "! a comment between groups is not part of the input"//nl// &
            "&case name = 't2', problem = 'normal+tangential' /"//nl// &
            '&tangential mu = 0.3, xi = '//xi2//', eta = 0.0, phi = 0.0 /'//nl// &
            "&case name = 'r3', problem = 'rolling' /"//nl// &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
            '&grid nx = 20, ny = 16, xmin = -1.3, xmax = 1.3, ymin = -1.3, ymax = 1.3 /'//nl// &
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl//'&normal fn = 9.1954 /'//nl// &
            "&tangential mu = 0.4, xi = 0.001, eta = 0.001, phi = 0.003, sweep = 'xi', sweep_from = 0.0, "// &
            'sweep_to = 0.004, sweep_n = 3 /'//nl// &
            "&case name = 'f4', problem = 'normal+tangential' /"//nl// &
            "&tangential sweep = '' /"//nl//'&solver maxit = 1 /'//nl
    end function four_cases

    !> `--resume`: a second run of the same file solves nothing, reports every case as done
    !! before (with its status: f4 did not converge, so the exit status stays 2) and leaves the
    !! outputs as they were; after t2's input changes, n1 is skipped and t2 and everything
    !! after it (which inherit from it) are solved again; a case whose JSON was lost (an
    !! interrupted run) is solved again, to the same summary; a comment changed between groups
    !! changes nothing.  Fails when the fingerprint leaves out the earlier cases (r3 would be
    !! skipped after t2 changed) or when `--resume` is ignored.
    subroutine test_resume(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, errors, report, t2_before, r3_before, n1_before
        integer :: code
        dir = fresh_dir('batch')
        call run_namelist(dir, four_cases('0.001'), code, errors)
        call check(error, code == 2 .and. index(errors, "'f4': solver not_converged") > 0, &
            'first run: exit 2 (f4 not converged): '//errors)
        if (allocated(error)) return
        call check(error, index(read_all(dir//'/n1.json'), '"input_fingerprint": "') > 0, 'JSON: input_fingerprint')
        n1_before = read_all(dir//'/n1.json'); t2_before = read_all(dir//'/t2.json'); r3_before = read_all(dir//'/r3.json')
        call run_namelist(dir, four_cases('0.001'), code, errors, extra=[character(len=16) :: '--resume'])
        report = read_all(dir//'/report.txt')
        call check(error, code == 2, 'resume: the exit status of the cases done before (2: f4), got something else')
        call check(error, count_of(report, 'skipped (--resume)') == 4 .and. &
            index(report, 'case f4: done in an earlier run with the same input (not_converged)') > 0 .and. &
            index(report, '4 case(s): 3 converged, 1 not converged, 0 with input errors (4 of them done in an earlier run') &
            > 0, 'resume: every case skipped: '//report)
        call check(error, read_all(dir//'/t2.json') == t2_before .and. read_all(dir//'/r3.json') == r3_before, &
            'resume: outputs rewritten')
        if (allocated(error)) return
        ! t2 changed: n1 kept, t2 and the cases after it solved again
        call run_namelist(dir, four_cases('0.0012'), code, errors, extra=[character(len=16) :: '--resume'])
        report = read_all(dir//'/report.txt')
        call check(error, count_of(report, 'skipped (--resume)') == 1 .and. index(report, 'case n1: done in an earlier') > 0, &
            't2 changed: only n1 skipped: '//report)
        call check(error, read_all(dir//'/n1.json') == n1_before .and. read_all(dir//'/t2.json') /= t2_before .and. &
            read_all(dir//'/r3.json') /= r3_before, 't2 changed: n1 kept, t2 and r3 solved again')
        if (allocated(error)) return
        ! a lost output: only that case again, to the same summary
        call run_namelist(dir, four_cases('0.001'), code, errors)
        t2_before = read_all(dir//'/t2.json')
        call execute_command_line("rm -f '"//dir//"/t2.json'")
        call run_namelist(dir, replace(four_cases('0.001'), 'not part of', 'NOT part of'), code, errors, &
            extra=[character(len=16) :: '--resume'])
        report = read_all(dir//'/report.txt')
        call check(error, count_of(report, 'skipped (--resume)') == 3 .and. index(report, 'case t2: done') == 0, &
            'lost t2.json: t2 alone solved again (and a comment edit ignored): '//report)
        call check(error, without_times(read_all(dir//'/t2.json')) == without_times(t2_before), &
            't2 solved again after the others were skipped: summary differs')
        call execute_command_line("rm -rf '"//dir//"'")
    end subroutine test_resume

    !> `--resume` and the files a case reads: a table geometry's case is skipped while its
    !! table is unchanged and solved again once the table is edited (the namelist the same),
    !! to the answer of the new table; a quadratic case in the same file is skipped
    !! throughout.  [[with_files]] leaves a fingerprint without files as it is and tells an
    !! unreadable file from a readable one.  Fails when the fingerprint ignores the files.
    subroutine test_resume_files(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, errors, report, text, tab_before
        character(len=256) :: path(1), other(1)
        integer :: code
        dir = fresh_dir('batch')
        text = "&case name = 'q1' /"//nl// &
            '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl// &
            "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"//nl//'&normal approach = 0.1091 /'//nl// &
            "&case name = 'tab' /"//nl//"&geometry kind = 'table', file = '"//dir//"/h0.txt' /"//nl
        call write_table(dir//'/h0.txt', 1.0_dp)
        call run_namelist(dir, text, code, errors)
        call check(error, code == 0, 'first run: '//errors)
        if (allocated(error)) return
        tab_before = read_all(dir//'/tab.json')
        call run_namelist(dir, text, code, errors, extra=[character(len=16) :: '--resume'])
        report = read_all(dir//'/report.txt')
        call check(error, count_of(report, 'skipped (--resume)') == 2, 'table unchanged: both cases skipped: '//report)
        if (allocated(error)) return
        call write_table(dir//'/h0.txt', 1.25_dp)   ! a flatter body: a larger contact
        call run_namelist(dir, text, code, errors, extra=[character(len=16) :: '--resume'])
        report = read_all(dir//'/report.txt')
        call check(error, count_of(report, 'skipped (--resume)') == 1 .and. index(report, 'case q1: done in an earlier') > 0, &
            'table edited: only q1 skipped: '//report)
        call check(error, read_all(dir//'/tab.json') /= tab_before .and. &
            json_num(read_all(dir//'/tab.json'), 'fn') > 1.1_dp*json_num(tab_before, 'fn'), &
            'table edited: tab solved again with the new table (a larger force at the same approach)')
        call run_namelist(dir, text, code, errors, extra=[character(len=16) :: '--resume'])
        call check(error, count_of(read_all(dir//'/report.txt'), 'skipped (--resume)') == 2, &
            'after the new solve: both cases skipped again')
        call check(error, with_files('0123456789ABCDEF', [character(len=8) :: '', '']) == '0123456789ABCDEF', &
            'no files: the fingerprint unchanged')
        path(1) = dir//'/h0.txt'; other(1) = dir//'/none.txt'   ! (no constructors of dir: gfortran)
        call check(error, with_files('0123456789ABCDEF', path) /= with_files('0123456789ABCDEF', other), &
            'a readable and an unreadable file give different fingerprints')
        call execute_command_line("rm -rf '"//dir//"'")
    contains
        !> h0 of the Hertz body of q1 (rx = 300, ry = 163) on its 16 × 16 grid, radii times `scale`.
        subroutine write_table(path, scale)
            character(len=*), intent(in) :: path
            real(dp), intent(in) :: scale
            integer :: u, i, j
            real(dp) :: x, y
            open (newunit=u, file=path, status='replace', action='write')
            write (u, '(a)') '# h0 [mm], x fastest'
            do j = 1, 16
                do i = 1, 16
                    x = -10.0_dp + (i - 0.5_dp)*20.0_dp/16; y = -6.0_dp + (j - 0.5_dp)*12.0_dp/16
                    write (u, '(es24.16)') x**2/(2*300.0_dp*scale) + y**2/(2*163.0_dp*scale)
                end do
            end do
            close (u)
        end subroutine write_table
    end subroutine test_resume_files

    !> `--part K/N`: three processes' parts of the file in one directory give every case, each
    !! with the summary of the whole run (but the operator-reuse flags and the times); each
    !! part's closing line counts its own cases.
    subroutine test_parts(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: whole, parts, errors, report
        character(len=2), parameter :: names(4) = ['n1', 't2', 'r3', 'f4']
        character(len=8) :: p
        integer :: code, k
        whole = fresh_dir('batch'); parts = fresh_dir('batch')
        call run_namelist(whole, four_cases('0.001'), code, errors)
        do k = 1, 3
            write (p, '(i0,a)') k, '/3'
            call run_namelist(parts, four_cases('0.001'), code, errors, extra=[character(len=16) :: '--part', p])
            report = read_all(parts//'/report.txt')
            call check(error, index(report, merge('2 case(s) of part 1/3', '1 case(s) of part '//trim(p)//'', k == 1)) > 0, &
                'part '//trim(p)//': closing line: '//report)
        end do
        do k = 1, 4
            call check(error, without_times(read_all(parts//'/'//names(k)//'.json')) == &
                without_times(read_all(whole//'/'//names(k)//'.json')), names(k)//': the parts differ from the whole run')
        end do
        call check(error, read_all(parts//'/r3_creep.csv') /= '' .and. count_of(read_all(parts//'/r3_creep.csv'), nl) == 4, &
            'r3: creep curve of 3 points from part 3/3')
        call execute_command_line("rm -rf '"//whole//"' '"//parts//"'")
    end subroutine test_parts

    !> Bad `--part` values are refused naming the option, the value and the limit (exit 1,
    !! nothing solved); the MPI batch's command line refuses `--part`, and a caller that takes
    !! neither refuses `--resume`.
    subroutine test_arguments(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, errors, case_file, out_dir, action, errtext
        character(len=12), parameter :: bad(7) = [character(len=12) :: '0/3', '4/3', '1/10001', 'x', '1/2/3', '/2', '-1/2']
        integer :: code, k, kk, n, stat
        character(len=:), allocatable :: msg
        logical :: resume
        integer :: part(2)
        dir = fresh_dir('batch')
        do k = 1, size(bad)
            call run_namelist(dir, four_cases('0.001'), code, errors, extra=[character(len=16) :: '--part', bad(k)])
            call check(error, code == 1 .and. index(errors, "--part '"//trim(bad(k))//"': must be K/N with 1 <= K <= N <= 10000") &
                > 0, '--part '//trim(bad(k))//': '//errors)
            call check(error, .not. file_exists(dir//'/n1.json'), '--part '//trim(bad(k))//': something was solved')
        end do
        call run_namelist(dir, four_cases('0.001'), code, errors, extra=[character(len=16) :: '--part'])
        call check(error, code == 1 .and. index(errors, '--part needs K/N') > 0, '--part without a value: '//errors)
        call parse_part('7/10000', kk, n, stat, msg)
        call check(error, stat == 0 .and. kk == 7 .and. n == 10000, 'parse_part 7/10000')
        call parse_driver_arguments([character(len=16) :: 'x.nml', '--resume', '--part', '2/5'], 'fastcontact', 'usage', &
            case_file, out_dir, action, errtext, resume=resume, part=part)
        call check(error, action == 'run' .and. resume .and. all(part == [2, 5]), 'serial driver: --resume --part 2/5')
        call parse_driver_arguments([character(len=16) :: 'x.nml', '--part', '1/2'], 'fastcontact-mpi', 'usage', &
            case_file, out_dir, action, errtext, resume=resume)
        call check(error, action == 'error' .and. index(errtext, "unexpected argument '--part'") > 0, &
            'the MPI batch has no --part: '//errtext)
        call parse_driver_arguments([character(len=16) :: 'x.nml', '--resume'], 'fastcontact-mpi', 'usage', &
            case_file, out_dir, action, errtext)
        call check(error, action == 'error' .and. index(errtext, "unexpected argument '--resume'") > 0, &
            'a caller that takes no --resume refuses it: '//errtext)
        call execute_command_line("rm -rf '"//dir//"'")
    end subroutine test_arguments

    integer function count_of(text, what) result(n)
        character(len=*), intent(in) :: text, what
        integer :: a, b
        n = 0; a = 1
        do
            b = index(text(a:), what)
            if (b == 0) exit
            n = n + 1; a = a + b + len(what) - 1
            if (a > len(text)) exit
        end do
    end function count_of

    !> `text` with the first `old` replaced by `new`.
    function replace(text, old, new) result(out)
        character(len=*), intent(in) :: text, old, new
        character(len=:), allocatable :: out
        integer :: a
        a = index(text, old)
        out = text
        if (a > 0) out = text(1:a - 1)//new//text(a + len(old):)
    end function replace

    logical function file_exists(path)
        character(len=*), intent(in) :: path
        inquire (file=path, exist=file_exists)
    end function file_exists

end module test_batch
