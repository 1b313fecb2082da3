!> MPI batch driver `fastcontact-mpi CASES.nml [--out DIR]`: the cases of one namelist file
!! (sweeps included — each is one case of the file) spread over the ranks of a communicator.
!!
!! Each case is solved by the serial driver's own routine ([[run_driver]] with `only_case`):
!! the cases before it are read and checked only, for what it inherits, so every rank writes
!! exactly the JSON and CSV files the serial driver writes for that case.  Its report and
!! error messages go to scratch files and travel to rank 0, which prints them in case order
!! followed by the serial driver's closing line; the exit status follows the serial rules
!! (1 if a case had an input error, else 2 if a solver failed, else 0).  A failing case
!! only marks its own status; the other cases finish.
!!
!! Dynamic load balance: the cases are grouped in chunks of consecutive cases (about four
!! chunks per rank, so that a rank reuses its operators across the cases of a chunk as the
!! serial driver does across consecutive cases) and rank 0 hands out chunk indices.  Every
!! rank, rank 0 included, solves chunks; a worker holds one chunk in reserve and asks for the
!! next one when it starts one, so it rarely waits while rank 0 is busy with its own chunk
!! (rank 0 answers requests between its chunks).  Waiting ranks poll with short sleeps rather
!! than spin, so that an idle rank does not take a core from a busy one.
!!
!! Difference from the serial driver (documented in doc/parallel.md): a case whose input is
!! rejected only while solving (e.g. a tangential force above μ·Fn) is, for the inheritance
!! of later cases, treated like a good case; the serial driver lets later cases inherit from
!! the case before it.  Input errors found by the input checks are handled identically.
module fcm_batch
    use mpi
    use, intrinsic :: iso_c_binding, only: c_int
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use fc_kinds, only: msg_len
    use fc_namelist, only: fc_case_chunk, read_case_file
    use fc_driver, only: run_driver, EXIT_OK, EXIT_INPUT_ERROR, EXIT_NOT_CONVERGED
    implicit none
    private

    integer, parameter :: TAG_ASSIGN = 11, TAG_RESULT = 12, TAG_TEXT = 13

    interface
        integer(c_int) function c_usleep(us) bind(C, name='usleep')
            import :: c_int
            integer(c_int), value :: us
        end function c_usleep
    end interface

    !> Outcome of one chunk of consecutive cases.
    type :: case_outcome
        integer, allocatable :: statuses(:)         !! per case: 0 converged, 1 input error, 2 solver failure
        character(len=:), allocatable :: report     !! report text
        character(len=:), allocatable :: errors     !! error messages
        integer :: rank = -1                        !! rank that solved it
    end type case_outcome

    public :: run_mpi_batch

contains

    !> Run the batch on `comm` (collective).  `exit_code` is the same on every rank.
    !! `report_unit`, `err_unit` (rank 0) default to stdout and stderr; `case_ranks`
    !! (rank 0, optional) returns which rank solved each case.
    subroutine run_mpi_batch(args, comm, exit_code, report_unit, err_unit, case_ranks)
        character(len=*), intent(in) :: args(:)
        integer, intent(in) :: comm
        integer, intent(out) :: exit_code
        integer, intent(in), optional :: report_unit, err_unit
        integer, allocatable, intent(out), optional :: case_ranks(:)
        integer :: rank, nprocs, ierr, ncases, rep, err, k, nerr, nfail
        type(case_outcome), allocatable :: out(:)
        type(fc_case_chunk), allocatable :: cases(:)
        character(len=msg_len) :: errmsg
        character(len=:), allocatable :: case_file
        integer :: stat, next, csize, nchunks
        call mpi_comm_rank(comm, rank, ierr)
        call mpi_comm_size(comm, nprocs, ierr)
        rep = output_unit; err = error_unit
        if (present(report_unit)) rep = report_unit
        if (present(err_unit)) err = err_unit
        ! ---- rank 0 checks the command line and the file exactly as the serial driver does
        ncases = -1
        if (rank == 0) then
            call run_driver(args, exit_code, report_unit=rep, error_unit=err, only_case=0)
            case_file = case_file_argument(args)
            if (exit_code == EXIT_OK .and. len(case_file) > 0 .and. .not. asks_help(args)) then
                call read_case_file(case_file, cases, stat, errmsg)
                ncases = -1 - EXIT_INPUT_ERROR
                if (stat == 0) ncases = size(cases)
            else
                ncases = -1 - exit_code   ! nothing to solve: −1 (help) or −1 − exit code
            end if
        end if
        call mpi_bcast(ncases, 1, MPI_INTEGER, 0, comm, ierr)
        if (ncases < 0) then
            exit_code = -1 - ncases
            return
        end if
        csize = max(1, ncases/(4*nprocs))
        nchunks = (ncases + csize - 1)/csize
        allocate (out(nchunks))
        if (rank == 0) then
            call master(out)
            nerr = count([(out(k)%statuses == 1, k=1, nchunks)])
            nfail = count([(out(k)%statuses >= 2 .or. out(k)%statuses < 0, k=1, nchunks)])
            do k = 1, nchunks
                call write_lines(rep, out(k)%report)
                call write_lines(err, out(k)%errors)
            end do
            flush (err)
            write (rep, '(a,i0,a,i0,a,i0,a,i0,a)') 'fastcontact: ', ncases, ' case(s): ', ncases - nerr - nfail, &
                ' converged, ', nfail, ' not converged, ', nerr, ' with input errors'
            exit_code = EXIT_OK
            if (nerr > 0) then
                exit_code = EXIT_INPUT_ERROR
            else if (nfail > 0) then
                exit_code = EXIT_NOT_CONVERGED
            end if
            if (present(case_ranks)) then
                allocate (case_ranks(ncases))
                do k = 1, nchunks
                    case_ranks((k - 1)*csize + 1:min(k*csize, ncases)) = out(k)%rank
                end do
            end if
        else
            call worker()
        end if
        call mpi_bcast(exit_code, 1, MPI_INTEGER, 0, comm, ierr)

    contains

        !> Rank 0: hand out cases, solve cases itself between requests, collect outcomes.
        subroutine master(out)
            type(case_outcome), intent(inout) :: out(:)
            integer :: received, r, st(MPI_STATUS_SIZE), first(2)
            logical :: flag
            next = 1
            ! two chunks per worker to start with (the second one is the reserve)
            do r = 1, nprocs - 1
                first = 0
                if (next <= nchunks) then
                    first(1) = next; next = next + 1
                end if
                if (next <= nchunks) then
                    first(2) = next; next = next + 1
                end if
                call mpi_send(first, 2, MPI_INTEGER, r, TAG_ASSIGN, comm, ierr)
            end do
            received = 0
            do while (received < nchunks)
                ! answer every request that has arrived
                do
                    call mpi_iprobe(MPI_ANY_SOURCE, TAG_RESULT, comm, flag, st, ierr)
                    if (.not. flag) exit
                    call receive_outcome(st(MPI_SOURCE), out)
                    received = received + 1
                    call mpi_send(take_next(), 1, MPI_INTEGER, st(MPI_SOURCE), TAG_ASSIGN, comm, ierr)
                end do
                if (next <= nchunks) then
                    k = take_next()
                    call solve_case(k, out(k))
                    out(k)%rank = 0
                    received = received + 1
                else if (received < nchunks) then
                    ierr = c_usleep(2000_c_int)
                end if
            end do
        end subroutine master

        integer function take_next()
            take_next = 0
            if (next <= nchunks) then
                take_next = next; next = next + 1
            end if
        end function take_next

        !> Other ranks: solve the cases handed out, send each outcome (which also asks for
        !! the next case), keep one case in reserve.
        subroutine worker()
            integer :: queue(2), nq, k, req, nextk, st(MPI_STATUS_SIZE), head(4), sreq(3)
            integer, allocatable :: sbuf(:)
            type(case_outcome) :: o
            character(len=:), allocatable :: text
            logical :: pending, sending
            call mpi_recv(queue, 2, MPI_INTEGER, 0, TAG_ASSIGN, comm, st, ierr)
            nq = count(queue > 0)
            pending = .false.; sending = .false.
            do while (nq > 0)
                k = queue(1); queue(1) = queue(2); queue(2) = 0; nq = nq - 1
                call solve_case(k, o)
                if (pending) then
                    call wait_politely(req)
                    pending = .false.
                    if (nextk > 0) then
                        nq = nq + 1; queue(nq) = nextk
                    end if
                end if
                ! outcome (also the request for the next case), sent without waiting for rank 0
                if (sending) call wait_politely(sreq(1))
                if (sending) call wait_politely(sreq(2))
                if (sending) call wait_politely(sreq(3))
                head = [k, size(o%statuses), len(o%report), len(o%errors)]
                sbuf = [o%statuses, 0]
                text = o%report//o%errors//' '
                call mpi_isend(head, 4, MPI_INTEGER, 0, TAG_RESULT, comm, sreq(1), ierr)
                call mpi_isend(sbuf, size(sbuf), MPI_INTEGER, 0, TAG_TEXT, comm, sreq(2), ierr)
                call mpi_isend(text, len(text), MPI_CHARACTER, 0, TAG_TEXT, comm, sreq(3), ierr)
                sending = .true.
                call mpi_irecv(nextk, 1, MPI_INTEGER, 0, TAG_ASSIGN, comm, req, ierr)
                pending = .true.
                if (nq == 0) then
                    call wait_politely(req)
                    pending = .false.
                    if (nextk > 0) then
                        nq = 1; queue(1) = nextk
                    end if
                end if
            end do
            if (pending) call wait_politely(req)
            if (sending) call wait_politely(sreq(1))
            if (sending) call wait_politely(sreq(2))
            if (sending) call wait_politely(sreq(3))
        end subroutine worker

        subroutine wait_politely(req)
            integer, intent(inout) :: req
            integer :: st(MPI_STATUS_SIZE)
            logical :: flag
            do
                call mpi_test(req, flag, st, ierr)
                if (flag) exit
                ierr = c_usleep(2000_c_int)
            end do
        end subroutine wait_politely

        !> Solve chunk k with the serial driver; report and errors captured as text.
        subroutine solve_case(k, o)
            integer, intent(in) :: k
            type(case_outcome), intent(out) :: o
            integer :: ur, ue, code
            open (newunit=ur, status='scratch', action='readwrite', form='formatted')
            open (newunit=ue, status='scratch', action='readwrite', form='formatted')
            call run_driver(args, code, report_unit=ur, error_unit=ue, only_case=(k - 1)*csize + 1, &
                last_case=min(k*csize, ncases), statuses=o%statuses)
            o%report = slurp(ur)
            o%errors = slurp(ue)
            close (ur); close (ue)
        end subroutine solve_case

        subroutine receive_outcome(src, out)
            integer, intent(in) :: src
            type(case_outcome), intent(inout) :: out(:)
            integer :: head(4), st(MPI_STATUS_SIZE), kk
            integer, allocatable :: sbuf(:)
            character(len=:), allocatable :: text
            call mpi_recv(head, 4, MPI_INTEGER, src, TAG_RESULT, comm, st, ierr)
            kk = head(1)
            allocate (sbuf(head(2) + 1))
            call mpi_recv(sbuf, size(sbuf), MPI_INTEGER, src, TAG_TEXT, comm, st, ierr)
            out(kk)%statuses = sbuf(1:head(2))
            allocate (character(len=head(3) + head(4) + 1) :: text)   ! one trailing blank: never empty
            call mpi_recv(text, len(text), MPI_CHARACTER, src, TAG_TEXT, comm, st, ierr)
            out(kk)%report = text(1:head(3))
            out(kk)%errors = text(head(3) + 1:head(3) + head(4))
            out(kk)%rank = src
        end subroutine receive_outcome

    end subroutine run_mpi_batch

    !> Write text holding newline-terminated lines, one record per line.
    subroutine write_lines(u, text)
        integer, intent(in) :: u
        character(len=*), intent(in) :: text
        integer :: i, j
        i = 1
        do while (i <= len(text))
            j = index(text(i:), new_line('a'))
            if (j == 0) then
                write (u, '(a)') text(i:)
                exit
            end if
            write (u, '(a)') text(i:i + j - 2)
            i = i + j
        end do
    end subroutine write_lines

    !> Everything written to a scratch unit, lines joined with newlines.
    function slurp(u) result(text)
        integer, intent(in) :: u
        character(len=:), allocatable :: text
        character(len=4096) :: line
        integer :: ios, sz
        text = ''
        rewind (u)
        do
            read (u, '(a)', advance='no', iostat=ios, size=sz) line
            if (is_iostat_end(ios)) exit
            text = text//line(1:sz)
            if (is_iostat_eor(ios)) text = text//new_line('a')
            if (ios /= 0 .and. .not. is_iostat_eor(ios)) exit
        end do
    end function slurp

    !> The case file named on the command line ('' if none): the first argument that is
    !! not an option or the value of --out / -o.
    function case_file_argument(args) result(f)
        character(len=*), intent(in) :: args(:)
        character(len=:), allocatable :: f
        integer :: i
        f = ''
        i = 1
        do while (i <= size(args))
            if (trim(args(i)) == '--out' .or. trim(args(i)) == '-o') then
                i = i + 2; cycle
            end if
            if (args(i)(1:1) /= '-') then
                f = trim(args(i)); return
            end if
            i = i + 1
        end do
    end function case_file_argument

    logical function asks_help(args)
        character(len=*), intent(in) :: args(:)
        asks_help = any(args == '-h') .or. any(args == '--help')
    end function asks_help

end module fcm_batch
