!> MPI batch driver `fastcontact-mpi CASES.nml [--out DIR]`: the cases of one namelist file
!! (sweeps included — each is one case of the file) spread over the ranks of a communicator.
!!
!! Each case is solved by the serial driver's own routine ([[run_driver]] with `only_case`):
!! the cases before it are read and checked only, for what it inherits, so every rank writes
!! exactly the JSON and CSV files the serial driver writes for that case.  Its report and
!! error messages are captured as text and gathered on rank 0 at the end, which prints them in
!! case order followed by the serial driver's closing line; the exit status follows the serial
!! rules (1 if a case had an input error, else 2 if a solver failed, else 0).  A failing case
!! only marks its own status; the other cases finish.
!!
!! Dynamic load balance by guided self-scheduling: the cases are grouped in chunks of
!! consecutive cases whose sizes shrink along the file (⌈remaining / 2P⌉ cases, at least 1),
!! and every rank, rank 0 included, takes the next chunk from a shared counter
!! (MPI-3 passive-target `MPI_Fetch_and_op` on a one-integer window of rank 0), so no rank
!! waits for another to hand out work and the last chunks, being small, finish close
!! together.  Each rank keeps one set of influence operators across its chunks, reused while
!! grid and material match, as the serial driver reuses them across consecutive cases.
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
    use fc_contact, only: fc_contact_operators
    use fc_namelist, only: fc_case_chunk, read_case_file
    use fc_driver, only: run_driver, EXIT_OK, EXIT_INPUT_ERROR, EXIT_NOT_CONVERGED
    use fc_driver_common, only: STATUS_SKIPPED
    use fc_strings, only: fmt_int
    implicit none
    private

    integer, parameter :: TAG_SIZES = 11, TAG_HEADS = 12, TAG_STATUS = 13, TAG_TEXT = 14

    interface
        integer(c_int) function c_usleep(us) bind(C, name='usleep')
            import :: c_int
            integer(c_int), value :: us
        end function c_usleep
    end interface

    !> Outcome of one chunk of consecutive cases.
    type :: case_outcome
        !> per case: 0 converged, 1 input error, 2 solver failure; + STATUS_SKIPPED when
        !! `--resume` found it done in an earlier run
        integer, allocatable :: statuses(:)
        character(len=:), allocatable :: report     !! report text
        character(len=:), allocatable :: errors     !! error messages
        integer :: rank = -1                        !! rank that solved it
    end type case_outcome

    public :: run_mpi_batch, guided_chunks

contains

    !> Last case of each chunk under guided self-scheduling: chunk sizes ⌈remaining / 2P⌉,
    !! at least 1, so the first chunks are large (few operator set-ups and re-reads of the
    !! file) and the last ones single cases (the ranks finish close together).
    pure function guided_chunks(ncases, nprocs) result(last)
        integer, intent(in) :: ncases   !! cases in the file
        integer, intent(in) :: nprocs   !! ranks
        integer, allocatable :: last(:)
        integer :: done, n, s
        integer :: buf(ncases)
        done = 0; n = 0
        do while (done < ncases)
            s = max(1, (ncases - done + 2*nprocs - 1)/(2*nprocs))
            n = n + 1
            done = done + s
            buf(n) = done
        end do
        last = buf(1:n)
    end function guided_chunks

    !> Run the batch on `comm` (collective).  `exit_code` is the same on every rank.
    !! `report_unit`, `err_unit` (rank 0) default to stdout and stderr; `case_ranks`
    !! (rank 0, optional) returns which rank solved each case.
    subroutine run_mpi_batch(args, comm, exit_code, report_unit, err_unit, case_ranks)
        character(len=*), intent(in) :: args(:)
        integer, intent(in) :: comm
        integer, intent(out) :: exit_code
        integer, intent(in), optional :: report_unit, err_unit
        integer, allocatable, intent(out), optional :: case_ranks(:)
        integer :: rank, nprocs, ierr, ncases, rep, err, k, nerr, nfail, nskip, r, win, nchunks
        type(case_outcome), allocatable :: out(:)
        type(fc_case_chunk), allocatable :: cases(:)
        type(fc_contact_operators) :: ops
        character(len=msg_len) :: errmsg
        character(len=:), allocatable :: case_file
        integer, allocatable :: last(:), mine(:)
        integer :: stat, nmine, zero, req, nodecomm, pernode
        integer(MPI_ADDRESS_KIND) :: base, wsize
        call mpi_comm_rank(comm, rank, ierr)
        call mpi_comm_size(comm, nprocs, ierr)
        ! the ranks on one node share its memory: each case is checked against a rank's share
        call mpi_comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, nodecomm, ierr)
        call mpi_comm_size(nodecomm, pernode, ierr)
        call mpi_comm_free(nodecomm, ierr)
        rep = output_unit; err = error_unit
        if (present(report_unit)) rep = report_unit
        if (present(err_unit)) err = err_unit
        ! ---- rank 0 checks the command line and the file exactly as the serial driver does
        ncases = -1
        if (rank == 0) then
            call run_driver(args, exit_code, report_unit=rep, error_unit=err, only_case=0, memory_share=pernode)
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
        last = guided_chunks(ncases, nprocs)
        nchunks = size(last)
        allocate (out(nchunks), mine(nchunks))
        ! ---- the shared chunk counter: one integer on rank 0, starting at 0
        wsize = 0
        if (rank == 0) wsize = storage_size(0)/8
        call mpi_win_allocate(wsize, storage_size(0)/8, MPI_INFO_NULL, comm, base, win, ierr)
        if (rank == 0) then
            zero = 0   ! origin buffers stay valid until the unlock: variables, not constants
            call mpi_win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, win, ierr)
            call mpi_put(zero, 1, MPI_INTEGER, 0, 0_MPI_ADDRESS_KIND, 1, MPI_INTEGER, win, ierr)
            call mpi_win_unlock(0, win, ierr)
        end if
        call mpi_barrier(comm, ierr)
        ! ---- every rank takes chunks until the counter passes the last one
        nmine = 0
        do
            k = next_chunk()
            if (k > nchunks) exit
            call solve_chunk(k, out(k))
            out(k)%rank = rank
            nmine = nmine + 1; mine(nmine) = k
        end do
        call ops%destroy()
        ! wait for the others without spinning (MPI_Win_free's own barrier would), so that a
        ! rank done early leaves its core to ranks still solving on an oversubscribed node
        call mpi_ibarrier(comm, req, ierr)
        call wait_politely(req)
        call mpi_win_free(win, ierr)
        ! ---- outcomes to rank 0, printed in case order
        if (rank == 0) then
            do r = 1, nprocs - 1
                call receive_outcomes(r, out)
            end do
            nskip = count([(out(k)%statuses >= STATUS_SKIPPED, k=1, nchunks)])
            nerr = count([(out(k)%statuses == 1, k=1, nchunks)])
            nfail = count([(mod(out(k)%statuses, STATUS_SKIPPED) >= 2 .or. out(k)%statuses < 0, k=1, nchunks)])
            do k = 1, nchunks
                call write_lines(rep, out(k)%report)
                call write_lines(err, out(k)%errors)
            end do
            flush (err)
            write (rep, '(a,i0,a,i0,a,i0,a,i0,a)') 'fastcontact: ', ncases, ' case(s): ', ncases - nerr - nfail, &
                ' converged, ', nfail, ' not converged, ', nerr, ' with input errors'//skipped_note()
            exit_code = EXIT_OK
            if (nerr > 0) then
                exit_code = EXIT_INPUT_ERROR
            else if (nfail > 0) then
                exit_code = EXIT_NOT_CONVERGED
            end if
            if (present(case_ranks)) then
                allocate (case_ranks(ncases))
                do k = 1, nchunks
                    case_ranks(first_case(k):last(k)) = out(k)%rank
                end do
            end if
        else
            call send_outcomes()
        end if
        call mpi_bcast(exit_code, 1, MPI_INTEGER, 0, comm, ierr)

    contains

        integer function first_case(k)
            integer, intent(in) :: k
            first_case = 1
            if (k > 1) first_case = last(k - 1) + 1
        end function first_case

        !> Next chunk index (1-based) from the shared counter; > nchunks when all are taken.
        integer function next_chunk()
            integer :: taken, one
            one = 1
            call mpi_win_lock(MPI_LOCK_SHARED, 0, 0, win, ierr)
            call mpi_fetch_and_op(one, taken, MPI_INTEGER, 0, 0_MPI_ADDRESS_KIND, MPI_SUM, win, ierr)
            call mpi_win_unlock(0, win, ierr)
            next_chunk = taken + 1
        end function next_chunk

        !> Solve chunk k with the serial driver; report and errors captured as text.
        !> End of the closing line with `--resume` (as the serial driver's).
        function skipped_note() result(note)
            character(len=:), allocatable :: note
            note = ''
            if (any(args == '--resume')) note = ' ('//fmt_int(nskip)//' of them done in an earlier run: skipped)'
        end function skipped_note

        subroutine solve_chunk(k, o)
            integer, intent(in) :: k
            type(case_outcome), intent(out) :: o
            integer :: ur, ue, code
            open (newunit=ur, status='scratch', action='readwrite', form='formatted')
            open (newunit=ue, status='scratch', action='readwrite', form='formatted')
            call run_driver(args, code, report_unit=ur, error_unit=ue, only_case=first_case(k), &
                last_case=last(k), statuses=o%statuses, operators=ops, memory_share=pernode)
            o%report = slurp(ur)
            o%errors = slurp(ue)
            close (ur); close (ue)
        end subroutine solve_chunk

        !> A rank other than 0: its outcomes in four messages (sizes first), sent without
        !! spinning while rank 0 is still solving.
        subroutine send_outcomes()
            integer :: sizes(3), req(4), j, nst
            integer, allocatable :: heads(:), sts(:)
            character(len=:), allocatable :: text
            allocate (heads(max(1, 4*nmine)))
            heads = 0; nst = 0; text = ''
            do j = 1, nmine
                associate (o => out(mine(j)))
                    heads(4*j - 3:4*j) = [mine(j), size(o%statuses), len(o%report), len(o%errors)]
                    nst = nst + size(o%statuses)
                    text = text//o%report//o%errors
                end associate
            end do
            allocate (sts(max(1, nst)))
            sts = 0; nst = 0
            do j = 1, nmine
                associate (o => out(mine(j)))
                    sts(nst + 1:nst + size(o%statuses)) = o%statuses
                    nst = nst + size(o%statuses)
                end associate
            end do
            text = text//' '   ! never empty
            sizes = [nmine, size(sts), len(text)]
            call mpi_isend(sizes, 3, MPI_INTEGER, 0, TAG_SIZES, comm, req(1), ierr)
            call mpi_isend(heads, size(heads), MPI_INTEGER, 0, TAG_HEADS, comm, req(2), ierr)
            call mpi_isend(sts, size(sts), MPI_INTEGER, 0, TAG_STATUS, comm, req(3), ierr)
            call mpi_isend(text, len(text), MPI_CHARACTER, 0, TAG_TEXT, comm, req(4), ierr)
            do j = 1, 4
                call wait_politely(req(j))
            end do
        end subroutine send_outcomes

        !> Rank 0: the outcomes of rank `src`.
        subroutine receive_outcomes(src, out)
            integer, intent(in) :: src
            type(case_outcome), intent(inout) :: out(:)
            integer :: sizes(3), st(MPI_STATUS_SIZE), req, j, kk, ist, itx
            integer, allocatable :: heads(:), sts(:)
            character(len=:), allocatable :: text
            call mpi_irecv(sizes, 3, MPI_INTEGER, src, TAG_SIZES, comm, req, ierr)
            call wait_politely(req)
            allocate (heads(max(1, 4*sizes(1))), sts(sizes(2)))
            allocate (character(len=sizes(3)) :: text)
            call mpi_recv(heads, size(heads), MPI_INTEGER, src, TAG_HEADS, comm, st, ierr)
            call mpi_recv(sts, size(sts), MPI_INTEGER, src, TAG_STATUS, comm, st, ierr)
            call mpi_recv(text, len(text), MPI_CHARACTER, src, TAG_TEXT, comm, st, ierr)
            ist = 0; itx = 0
            do j = 1, sizes(1)
                kk = heads(4*j - 3)
                out(kk)%statuses = sts(ist + 1:ist + heads(4*j - 2))
                ist = ist + heads(4*j - 2)
                out(kk)%report = text(itx + 1:itx + heads(4*j - 1))
                itx = itx + heads(4*j - 1)
                out(kk)%errors = text(itx + 1:itx + heads(4*j))
                itx = itx + heads(4*j)
                out(kk)%rank = src
            end do
        end subroutine receive_outcomes

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

    !> --help, --version or --check: rank 0's driver call has printed its text (for --check:
    !! each case's memory against a rank's share of the node) and nothing is solved.
    logical function asks_help(args)
        character(len=*), intent(in) :: args(:)
        asks_help = any(args == '-h') .or. any(args == '--help') .or. any(args == '-V') .or. any(args == '--version') &
            .or. any(args == '--check')
    end function asks_help

end module fcm_batch
