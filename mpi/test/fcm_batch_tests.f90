!> Tests of the MPI batch driver: the same outputs as the serial driver (JSON identical up
!! to timing values, CSV byte for byte, report identical up to timing lines, same error
!! messages and exit status), a failing case does not stop the others, the cases are
!! actually spread over the ranks, a bad command line gives the serial exit status.
module fcm_batch_tests
    use mpi
    use fc_driver, only: run_driver
    use fcm_batch, only: run_mpi_batch, guided_chunks
    use fc_strings, only: fmt_int
    use fcm_test_support, only: run_mpi_test, slurp_file, set_env, unset_env, rank0_failed
    implicit none
    private
    public :: batch_tests

    character(len=*), parameter :: dir = 'build/test-mpi-batch'
    character(len=16), parameter :: names(9) = [character(len=16) :: 'hz_a', 'hz_b', 'hz_force', 'bad_modulus', &
        'hz_maxit', 'cat_shift', 'cat_force', 'hz_after_bad', 'mp1']

contains

    subroutine batch_tests(only, npass, nfail)
        character(len=*), intent(in) :: only
        integer, intent(inout) :: npass, nfail
        call run_mpi_test('batch_equals_serial_driver', only, test_equal, npass, nfail)
        call run_mpi_test('batch_bad_command_line', only, test_bad_args, npass, nfail)
        call run_mpi_test('batch_guided_chunks', only, test_guided, npass, nfail)
        call run_mpi_test('batch_shared_wisdom_file', only, test_shared_wisdom, npass, nfail)
        call run_mpi_test('batch_memory_share', only, test_memory_share, npass, nfail)
        call run_mpi_test('batch_resume', only, test_resume, npass, nfail)
    end subroutine batch_tests

    !> The ranks of a batch on one node share its memory: with 30 MB available (given by
    !! FASTCONTACT_AVAILABLE_MEMORY) a normal case of 15.4 MB (10 MB + 270 B × 20 000),
    !! which one process alone could solve, is an input error on each of two ranks of a node.
    subroutine test_memory_share(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: code, u, urep, uerr, rank, nprocs, ierr
        character(len=256) :: args(3)
        character(len=256), allocatable :: args2(:)
        character(len=:), allocatable :: e
        logical :: there
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        call mpi_comm_size(MPI_COMM_WORLD, nprocs, ierr)
        if (rank == 0) then
            call execute_command_line('mkdir -p '//dir//'/mem')
            open (newunit=u, file=dir//'/mem.nml', status='replace', action='write')
            write (u, '(a)') "&case name = 'm' /"
            write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
            write (u, '(a)') "&grid nx = 200, ny = 100, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /"
            write (u, '(a)') "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"
            write (u, '(a)') "&normal approach = 0.1091 /"
            write (u, '(a)') "&output table = .false. /"
            write (u, '(a)') "&solver threads = 1 /"
            close (u)
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        call set_env('FASTCONTACT_AVAILABLE_MEMORY', '30M')
        args(1) = dir//'/mem.nml'; args(2) = '--out'; args(3) = dir//'/mem'
        call run_batch(args, 'mem', rank, code)
        call unset_env('FASTCONTACT_AVAILABLE_MEMORY')
        if (nprocs < 2) return          ! one process has the whole node
        if (code /= 1) then
            msg = 'exit status of a case beyond its share of the node (expected 1)'; return
        end if
        if (rank == 0) then
            r0_6: block
                e = slurp_file(dir//'/mem.err0')
                if (index(e, 'more than the 15 MB this process may use (FASTCONTACT_AVAILABLE_MEMORY of a node shared by 2') &
                    == 0) then
                    msg = 'no error naming the share in: '//e; exit r0_6
                end if
            end block r0_6
        end if
        if (rank0_failed(msg)) return
        ! --check: rank 0 estimates against a rank's share; nothing is solved
        call set_env('FASTCONTACT_AVAILABLE_MEMORY', '30M')
        args2 = [character(len=256) :: dir//'/mem.nml', '--check', '--out', dir//'/memc']
        call run_batch(args2, 'memc', rank, code)
        call unset_env('FASTCONTACT_AVAILABLE_MEMORY')
        if (code /= 1) then
            msg = '--check: exit status of a case beyond its share (expected 1)'; return
        end if
        if (rank == 0) then
            r0_7: block
                e = slurp_file(dir//'/memc.rep0')
                if (index(e, ' case m: normal, 200 x 100, 1 thread(s): about 15 MB of 15 MB available '// &
                    '(FASTCONTACT_AVAILABLE_MEMORY of a node shared by 2 processes): TOO LARGE') == 0) then
                    msg = '--check: '//e; exit r0_7
                end if
            end block r0_7
        end if
        if (rank0_failed(msg)) return
        ! --check of a file whose cases fit: exit status 0 and still nothing solved
        call set_env('FASTCONTACT_AVAILABLE_MEMORY', '100G')
        call run_batch(args2, 'memc2', rank, code)
        call unset_env('FASTCONTACT_AVAILABLE_MEMORY')
        if (code /= 0) then
            msg = '--check of cases that fit: exit status (expected 0)'; return
        end if
        if (rank == 0) then
            inquire (file=dir//'/memc/m.json', exist=there)
            if (there) msg = '--check solved the case'
        end if
        if (rank0_failed(msg)) return
    contains
        subroutine run_batch(a, tag, r, c)
            character(len=*), intent(in) :: a(:), tag
            integer, intent(in) :: r
            integer, intent(out) :: c
            integer :: ur, ue
            open (newunit=ur, file=dir//'/'//tag//'.rep'//fmt_int(r), status='replace')
            open (newunit=ue, file=dir//'/'//tag//'.err'//fmt_int(r), status='replace')
            call run_mpi_batch(a, MPI_COMM_WORLD, c, ur, ue)
            close (ur); close (ue)
        end subroutine run_batch
    end subroutine test_memory_share

    !> `--resume` on the MPI batch: a second run of the file of [[test_equal]] skips the 8
    !! cases with outputs (the input error and the duplicate name are met again: exit status 1,
    !! as the first run), says so in its report and closing line, and rewrites no output; after
    !! one JSON is deleted, only that case is solved again.
    subroutine test_resume(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: rank, ierr, code1, code2, code3, ur, ue
        character(len=64) :: args(4)
        character(len=:), allocatable :: before, rep
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        if (rank == 0) then
            call execute_command_line('rm -rf '//dir//'/resume && mkdir -p '//dir//'/resume')
            call write_cases(dir//'/resume/cases.nml')
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        args(1) = dir//'/resume/cases.nml'; args(2) = '--out'; args(3) = dir//'/resume/out'; args(4) = '--resume'
        call run_batch(args(1:3), 'first', code1)
        if (rank == 0) before = slurp_file(dir//'/resume/out/cat_force.json')
        call run_batch(args, 'again', code2)
        if (rank == 0) then
            call execute_command_line('rm -f '//dir//'/resume/out/hz_b.json')
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        call run_batch(args, 'lost', code3)
        if (rank /= 0) return
        if (code1 /= 1 .or. code2 /= 1 .or. code3 /= 1) then
            msg = 'exit status: '//fmt_int(code1)//', '//fmt_int(code2)//', '//fmt_int(code3)//' (1 expected: one input error)'
            return
        end if
        rep = slurp_file(dir//'/resume/again.rep0')
        if (count_of(rep, 'skipped (--resume)') /= 8 .or. index(rep, '10 case(s): 7 converged, 1 not converged, '// &
            '2 with input errors (8 of them done in an earlier run: skipped)') == 0) then
            msg = 'second run: 8 cases skipped expected: '//rep; return
        end if
        if (slurp_file(dir//'/resume/out/cat_force.json') /= before) then
            msg = 'second run: cat_force.json rewritten'; return
        end if
        rep = slurp_file(dir//'/resume/lost.rep0')
        if (count_of(rep, 'skipped (--resume)') /= 7 .or. index(rep, 'case hz_b: done') > 0) then
            msg = 'after hz_b.json was deleted: 7 skipped and hz_b solved expected: '//rep; return
        end if
    contains
        subroutine run_batch(a, tag, c)
            character(len=*), intent(in) :: a(:), tag
            integer, intent(out) :: c
            if (rank == 0) then
                open (newunit=ur, file=dir//'/resume/'//tag//'.rep0', status='replace')
                open (newunit=ue, file=dir//'/resume/'//tag//'.err0', status='replace')
                call run_mpi_batch(a, MPI_COMM_WORLD, c, ur, ue)
                close (ur); close (ue)
            else
                call run_mpi_batch(a, MPI_COMM_WORLD, c)
            end if
        end subroutine run_batch
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
    end subroutine test_resume

    subroutine write_cases(path)
        character(len=*), intent(in) :: path
        integer :: u
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') "&case name = 'hz_a', title = 'Hertz, approach' /"
        write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
        write (u, '(a)') "&grid nx = 24, ny = 20, xmin = -1.2, xmax = 1.2, ymin = -1.0, ymax = 1.0 /"
        write (u, '(a)') "&geometry kind = 'quadratic', rx = 40.0, ry = 30.0 /"
        write (u, '(a)') "&normal approach = 0.004 /"
        write (u, '(a)') "&case name = 'hz_b' /"
        write (u, '(a)') "&normal approach = 0.006 /"
        write (u, '(a)') "&case name = 'hz_force' /"
        write (u, '(a)') "&normal fn = 300.0 /"
        write (u, '(a)') "&case name = 'bad_modulus' /"
        write (u, '(a)') "&material g1 = -5.0 /"
        write (u, '(a)') "&case name = 'hz_maxit' /"
        write (u, '(a)') "&solver maxit = 2 /"
        write (u, '(a)') "&case name = 'cat_shift', problem = 'normal+tangential' /"
        write (u, '(a)') "&solver maxit = 1000 /"
        write (u, '(a)') "&tangential mu = 0.3, xi = 2.0e-4 /"
        write (u, '(a)') "&case name = 'cat_force', problem = 'normal+tangential' /"
        write (u, '(a)') "&tangential mu = 0.3, fx = 40.0 /"
        write (u, '(a)') "&case name = 'hz_after_bad', problem = 'normal' /"
        write (u, '(a)') "&grid nx = 30, ny = 24 /"
        write (u, '(a)') "&case name = 'hz_a' /"
        write (u, '(a)') "&case name = 'mp1', problem = 'strip_mp1' /"
        write (u, '(a)') "&geometry kind = 'strip2d' /"
        write (u, '(a)') "&grid nx = 64, ny = 1 /"
        close (u)
    end subroutine write_cases

    !> Serial driver and MPI batch on the same file (9 names, 10 cases: one input error, one
    !! duplicate name, one solver not converged, inheritance across all of them).
    subroutine test_equal(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: rank, nprocs, ierr, code_s, code_m, urs, ues, urm, uem, k, nused
        integer, allocatable :: ranks(:)
        character(len=:), allocatable :: a, b
        character(len=64) :: args(3)
        logical :: ea, eb
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        call mpi_comm_size(MPI_COMM_WORLD, nprocs, ierr)
        if (rank == 0) then
            call execute_command_line('rm -rf '//dir//' && mkdir -p '//dir)
            call write_cases(dir//'/cases.nml')
            open (newunit=urs, file=dir//'/serial.rep', status='replace')
            open (newunit=ues, file=dir//'/serial.err', status='replace')
            args(1) = dir//'/cases.nml'; args(2) = '--out'; args(3) = dir//'/serial'
            call run_driver(args, code_s, urs, ues)
            close (urs); close (ues)
            open (newunit=urm, file=dir//'/mpi.rep', status='replace')
            open (newunit=uem, file=dir//'/mpi.err', status='replace')
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        args(1) = dir//'/cases.nml'; args(2) = '--out'; args(3) = dir//'/mpi'
        if (rank == 0) then
            call run_mpi_batch(args, MPI_COMM_WORLD, code_m, urm, uem, ranks)
            close (urm); close (uem)
        else
            call run_mpi_batch(args, MPI_COMM_WORLD, code_m)
        end if
        call mpi_bcast(code_s, 1, MPI_INTEGER, 0, MPI_COMM_WORLD, ierr)
        if (code_m /= code_s) msg = 'exit status differs from the serial driver'
        if (rank /= 0 .or. allocated(msg)) return
        if (code_s /= 1) msg = 'serial exit status should be 1 (one input error)'
        nused = 0
        do k = 1, size(names)
            inquire (file=dir//'/serial/'//trim(names(k))//'.json', exist=ea)
            inquire (file=dir//'/mpi/'//trim(names(k))//'.json', exist=eb)
            if (ea .neqv. eb) then
                msg = trim(names(k))//'.json exists in one output only'; return
            end if
            if (trim(names(k)) == 'bad_modulus' .and. ea) then
                msg = 'the failing case wrote a JSON'; return
            end if
            if (.not. ea) cycle
            nused = nused + 1
            a = timing_free(slurp_file(dir//'/serial/'//trim(names(k))//'.json'))
            b = timing_free(slurp_file(dir//'/mpi/'//trim(names(k))//'.json'))
            if (a /= b) then
                msg = trim(names(k))//'.json differs (beyond timings)'; return
            end if
            inquire (file=dir//'/serial/'//trim(names(k))//'.csv', exist=ea)
            inquire (file=dir//'/mpi/'//trim(names(k))//'.csv', exist=eb)
            if (ea .neqv. eb) then
                msg = trim(names(k))//'.csv exists in one output only'; return
            end if
            if (ea) then
                if (slurp_file(dir//'/serial/'//trim(names(k))//'.csv') /= slurp_file(dir//'/mpi/'//trim(names(k))//'.csv')) then
                    msg = trim(names(k))//'.csv differs'; return
                end if
            end if
        end do
        if (nused /= size(names) - 1) then
            msg = 'expected 8 cases with outputs'; return
        end if
        if (report_free(slurp_file(dir//'/serial.rep')) /= report_free(slurp_file(dir//'/mpi.rep'))) then
            msg = 'report differs (beyond timing lines)'; return
        end if
        if (slurp_file(dir//'/serial.err') /= slurp_file(dir//'/mpi.err')) then
            msg = 'error messages differ'; return
        end if
        if (index(slurp_file(dir//'/mpi.err'), 'g1') == 0) msg = 'the input error is not reported'
        if (nprocs > 1 .and. .not. allocated(msg)) then
            if (all(ranks == 0) .or. all(ranks /= 0)) msg = 'all cases solved by one kind of rank: no distribution'
        end if
    end subroutine test_equal

    !> Ranks sharing one `&solver fft_wisdom` file: every case (24 on a 30×25 grid, each of
    !! which rereads the file and rewrites it, three batches from no file) reads a complete
    !! file.  Before the file was written to a temporary name and renamed over the old one,
    !! a rank read another's half-written file in 4 of 5 such batches, and those cases
    !! failed as "not wisdom"; no temporary file is left behind.
    subroutine test_shared_wisdom(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: rank, ierr, code, u, ur, k, rep, ios
        logical :: failed
        character(len=64) :: args(3)
        character(len=*), parameter :: wdir = dir//'-wisdom'
        character(len=256) :: line
        character(len=40) :: head
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        do rep = 1, 3
            if (rank == 0) then
                call execute_command_line('rm -rf '//wdir//' && mkdir -p '//wdir)
                open (newunit=u, file=wdir//'/cases.nml', status='replace', action='write')
                do k = 1, 24
                    write (u, '(a,i0,a)') "&case name = 'w", k, "', problem = 'normal+tangential' /"
                    if (k > 1) cycle
                    write (u, '(a)') "&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /"
                    write (u, '(a)') "&grid nx = 30, ny = 25, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /"
                    write (u, '(a)') "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"
                    write (u, '(a)') "&normal fn = 9.1954 /"
                    write (u, '(a)') "&tangential mu = 0.4, eta = 0.0015, phi = 0.0012 /"
                    write (u, '(a)') "&solver fft_wisdom = '"//wdir//"/shared.fftw' /"
                    write (u, '(a)') "&output table = .false. /"
                end do
                close (u)
            end if
            call mpi_barrier(MPI_COMM_WORLD, ierr)
            args(1) = wdir//'/cases.nml'; args(2) = '--out'; args(3) = wdir//'/out'
            if (rank == 0) then
                open (newunit=u, file=wdir//'/err.txt', status='replace')
                open (newunit=ur, file=wdir//'/report.txt', status='replace')
                call run_mpi_batch(args, MPI_COMM_WORLD, code, report_unit=ur, err_unit=u)
                close (u); close (ur)
            else
                call run_mpi_batch(args, MPI_COMM_WORLD, code)
            end if
            failed = .false.
            if (rank == 0 .and. code /= 0) then
                open (newunit=u, file=wdir//'/err.txt', status='old')
                read (u, '(a)', iostat=ios) line
                close (u)
                write (head, '(a,i0,a)') 'batch ', rep, ': exit status not 0: '
                msg = trim(head)//' '//trim(line); failed = .true.
            else if (rank == 0) then
                call execute_command_line('ls '//wdir//" | grep -c 'fftw[.]tmp' > "//wdir//'/count.txt || true')
                open (newunit=u, file=wdir//'/count.txt', status='old')
                read (u, *, iostat=ios) k
                close (u)
                if (ios /= 0 .or. k /= 0) then
                    msg = 'a temporary wisdom file was left behind'; failed = .true.
                end if
            end if
            ! every rank leaves the loop together (the next batch starts with collectives)
            call mpi_bcast(failed, 1, MPI_LOGICAL, 0, MPI_COMM_WORLD, ierr)
            if (failed) exit
        end do
    end subroutine test_shared_wisdom

    !> Guided self-scheduling: the chunks cover every case once, in order, never grow, the
    !! first is ⌈n / 2P⌉ cases and the last ones single cases; their number stays small
    !! (each chunk re-reads the file up to its first case).
    subroutine test_guided(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer, allocatable :: last(:), sizes(:)
        integer :: n, p, k
        last = guided_chunks(40, 2)
        if (size(last) /= 11 .or. any(last /= [10, 18, 24, 28, 31, 34, 36, 37, 38, 39, 40])) then
            msg = 'guided_chunks(40, 2) /= [10, 18, 24, 28, 31, 34, 36, 37, 38, 39, 40]'; return
        end if
        do p = 1, 9
            do n = 1, 2000, 37
                last = guided_chunks(n, p)
                sizes = last - [0, last(1:size(last) - 1)]
                if (last(size(last)) /= n .or. any(sizes < 1)) then
                    msg = 'chunks do not cover the cases once'; return
                end if
                do k = 2, size(sizes)
                    if (sizes(k) > sizes(k - 1)) then
                        msg = 'a chunk is larger than the one before it'; return
                    end if
                end do
                if (sizes(1) /= (n + 2*p - 1)/(2*p)) then
                    msg = 'first chunk is not ceiling(n / 2P)'; return
                end if
                if (real(size(last)) > 2*p*(1 + log(real(n))) + 1) then   ! about 2P·ln(n / 2P) + 2P
                    msg = 'too many chunks'; return
                end if
                if (n >= 2*p .and. sizes(size(sizes)) /= 1) then
                    msg = 'the last chunk is not a single case'; return
                end if
            end do
        end do
    end subroutine test_guided

    !> A missing case file: exit status 1 on every rank, as the serial driver.
    subroutine test_bad_args(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: code, u, rank, ierr
        character(len=64) :: args(1)
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        open (newunit=u, status='scratch')
        args(1) = 'does/not/exist.nml'
        call run_mpi_batch(args, MPI_COMM_WORLD, code, u, u)
        close (u)
        if (code /= 1) msg = 'missing case file must give exit status 1'
    end subroutine test_bad_args

    !> JSON text with every number after a key ending in "seconds…" replaced by X.
    !> JSON text with the values that depend on where and when a case ran masked: timings
    !! (`…seconds`) and whether the case built its operators or reused a previous case's
    !! (`operator_built…`: a rank starts its chunks with other operators than the serial run).
    function timing_free(text) result(t)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: t
        t = masked(masked(text, 'seconds'), 'operator_built')
    end function timing_free

    !> `text` with the value of every key containing `key` replaced by X.
    function masked(text, key) result(t)
        character(len=*), intent(in) :: text, key
        character(len=:), allocatable :: t
        integer :: i, j
        t = ''
        i = 1
        do
            j = index(text(i:), key)
            if (j == 0) exit
            j = i + j - 1 + len(key)
            do while (j <= len(text))
                if (text(j:j) == ':') exit
                j = j + 1
            end do
            t = t//text(i:j)//'X'
            i = j + 1
            do while (i <= len(text))
                if (scan(text(i:i), ',}') > 0 .or. text(i:i) == new_line('a')) exit
                i = i + 1
            end do
        end do
        t = t//text(i:)
    end function masked

    !> Report without the lines that carry timings.
    function report_free(text) result(t)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: t
        integer :: i, j
        t = ''
        i = 1
        do while (i <= len(text))
            j = index(text(i:), new_line('a'))
            if (j == 0) then
                j = len(text)
            else
                j = i + j - 1
            end if
            if (index(text(i:j), 'cpu time') == 0 .and. index(text(i:j), 'operator set-up') == 0 .and. &
                index(text(i:j), ' s)') == 0) t = t//text(i:j)
            i = j + 1
        end do
    end function report_free

end module fcm_batch_tests
