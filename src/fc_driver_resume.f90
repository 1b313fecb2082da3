!> Batches that outlive one job: the drivers' `--resume` and `--part K/N` (doc/parallel.md,
!! "Long batches on a cluster").
!!
!! A case's *input fingerprint* is a 64-bit hash of what decides its answer as far as the
!! case file shows it: fastcontact's version and the text of every group of this case and of
!! all cases before it (later cases inherit their values; comments and blank lines between
!! groups do not count).  The drivers write it into the case's JSON.  `--resume` skips a case
!! whose JSON, written last of its outputs, records a final solver status (converged,
!! not_converged, diverged) and the same fingerprint: an interrupted run (a job's time limit, a
!! lost node) goes on where it stopped, and a case whose inputs (or any earlier case's) have
!! changed since is solved again.  The contents of the files a case reads (its geometry table,
!! its coefficient files) are part of its own fingerprint too ([[with_files]]): a case whose
!! table was edited between two runs is solved again.
!!
!! `--part K/N` keeps the cases k with mod(k − 1, N) = K − 1: N processes (a Slurm job array)
!! share a file without MPI, round robin so that neighbouring cases of a sweep spread out.
module fc_driver_resume
    use, intrinsic :: iso_fortran_env, only: int64
    use fc_kinds, only: FC_ERR_VALUE
    use fc_namelist, only: fc_case_chunk
    use fc_input, only: fc_case_input
    use fc_version, only: fc_version_string
    implicit none
    private

    integer, parameter, public :: fingerprint_len = 16   !! hexadecimal digits of a fingerprint
    integer, parameter, public :: max_parts = 10000      !! N of `--part K/N`, at most (the case limit)

    public :: case_fingerprints, with_files, case_files, previous_outcome, parse_part

contains

    !> The input fingerprint of every case of a file: fp(k) hashes the version and the group
    !! texts of cases 1 … k.  Two FNV-1a hashes of 32 bits with different offset bases, kept in
    !! 64-bit integers so that no product overflows.
    function case_fingerprints(cases) result(fp)
        type(fc_case_chunk), intent(in) :: cases(:)
        character(len=fingerprint_len) :: fp(size(cases))
        integer(int64) :: h(2)
        integer :: k, g
        h = [2166136261_int64, 3735928559_int64]
        call fnv_feed(h, fc_version_string)
        do k = 1, size(cases)
            if (allocated(cases(k)%groups)) then
                do g = 1, size(cases(k)%groups)
                    if (allocated(cases(k)%groups(g)%text)) call fnv_feed(h, cases(k)%groups(g)%text)
                    call fnv_feed(h, new_line('a'))
                end do
            end if
            call fnv_feed(h, '&&')   ! the case boundary
            write (fp(k), '(2z8.8)') h
        end do
    end function case_fingerprints

    !> The fingerprint `fp` continued over the contents of the files in `paths` (blank names
    !! skipped): a case's fingerprint with the files it reads.  Without files it is `fp`
    !! itself.  A file that cannot be read adds a marker in place of its contents, so that its
    !! case matches no finished run (the solve then reports the missing file).
    function with_files(fp, paths) result(fpf)
        character(len=*), intent(in) :: fp
        character(len=*), intent(in) :: paths(:)
        character(len=fingerprint_len) :: fpf
        integer, parameter :: chunk = 65536
        character(len=chunk) :: buf
        integer(int64) :: h(2), size_bytes, pos
        integer :: i, u, ios, n
        fpf = fp
        if (all(len_trim(paths) == 0)) return
        read (fp, '(2z8)', iostat=ios) h
        if (ios /= 0) return
        do i = 1, size(paths)
            if (len_trim(paths(i)) == 0) cycle
            call fnv_feed(h, '&file')
            size_bytes = -1
            open (newunit=u, file=trim(paths(i)), status='old', action='read', access='stream', &
                  form='unformatted', iostat=ios)
            if (ios == 0) inquire (unit=u, size=size_bytes)
            if (ios /= 0 .or. size_bytes < 0) then
                call fnv_feed(h, '<unreadable>')
                if (ios == 0) close (u)
                cycle
            end if
            pos = 0
            do while (pos < size_bytes)
                n = int(min(int(chunk, int64), size_bytes - pos))
                read (u, iostat=ios) buf(1:n)
                if (ios /= 0) then
                    call fnv_feed(h, '<unreadable>'); exit
                end if
                call fnv_feed(h, buf(1:n))
                pos = pos + n
            end do
            close (u)
        end do
        write (fpf, '(2z8.8)') h
    end function with_files

    !> The files case `c` reads, as [[with_files]] takes them: its coefficient files and, for
    !! a table geometry, its table ('' where there is none).
    function case_files(c) result(paths)
        type(fc_case_input), intent(in) :: c
        character(len=len(c%file)) :: paths(3)
        paths = [character(len=len(c%file)) :: c%ic_file, c%ic_file2, '']
        if (trim(c%kind) == 'table') paths(3) = c%file
    end function case_files

    !> Feed `text` to the two 32-bit FNV-1a hashes `h`.
    pure subroutine fnv_feed(h, text)
        integer(int64), intent(inout) :: h(2)
        character(len=*), intent(in) :: text
        integer(int64), parameter :: prime = 16777619_int64, mask = 4294967295_int64
        integer(int64) :: c
        integer :: i
        do i = 1, len(text)
            c = int(ichar(text(i:i)), int64)
            h(1) = iand(ieor(h(1), c)*prime, mask)
            h(2) = iand(ieor(h(2), c)*prime, mask)
        end do
    end subroutine fnv_feed

    !> Whether the JSON at `path` is a finished run of the case with `fingerprint`: it records
    !! that fingerprint and a final solver status.  `status`: 0 converged, 2 not converged or
    !! diverged (the drivers' case statuses); `what` names the status for the report.
    logical function previous_outcome(path, fingerprint, status, what) result(done)
        character(len=*), intent(in) :: path, fingerprint
        integer, intent(out) :: status
        character(len=:), allocatable, intent(out) :: what
        character(len=:), allocatable :: text
        done = .false.; status = 0; what = ''
        call read_head(path, text)
        if (len(text) == 0) return
        if (string_value(text, 'input_fingerprint') /= fingerprint) return
        what = string_value(text, 'status')
        select case (what)
        case ('converged'); status = 0
        case ('not_converged', 'diverged'); status = 2
        case default; return
        end select
        done = .true.
    end function previous_outcome

    !> The first lines of a JSON file (its scalar keys come first; the arrays after them can be
    !! long): '' when it cannot be read.
    subroutine read_head(path, text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: text
        character(len=1024) :: line
        integer :: u, ios, n
        text = ''
        open (newunit=u, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do n = 1, 200
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            text = text//trim(line)//new_line('a')
        end do
        close (u)
    end subroutine read_head

    !> The value of `"key": "value"` in `text` ('' when absent).
    function string_value(text, key) result(v)
        character(len=*), intent(in) :: text, key
        character(len=:), allocatable :: v
        integer :: a, b
        v = ''
        a = index(text, '"'//key//'": "')
        if (a == 0) return
        a = a + len(key) + 5
        b = index(text(a:), '"')
        if (b == 0) return
        v = text(a:a + b - 2)
    end function string_value

    !> `--part K/N` → k, n with 1 ≤ K ≤ N ≤ [[max_parts]]; stat ≠ 0 and a message naming the
    !! option, the value and the limit otherwise.
    subroutine parse_part(text, k, n, stat, errmsg)
        character(len=*), intent(in) :: text
        integer, intent(out) :: k, n, stat
        character(len=:), allocatable, intent(out) :: errmsg
        integer :: s, ios1, ios2
        character(len=16) :: lim
        k = 0; n = 0; stat = FC_ERR_VALUE; errmsg = ''
        write (lim, '(i0)') max_parts
        s = index(text, '/')
        if (s > 1 .and. s < len(text) .and. len(text) <= 12 .and. verify(text, '0123456789/') == 0 .and. &
            index(text(s + 1:), '/') == 0) then
            read (text(1:s - 1), *, iostat=ios1) k
            read (text(s + 1:), *, iostat=ios2) n
            if (ios1 == 0 .and. ios2 == 0 .and. n >= 1 .and. n <= max_parts .and. k >= 1 .and. k <= n) then
                stat = 0; return
            end if
        end if
        errmsg = "--part '"//text//"': must be K/N with 1 <= K <= N <= "//trim(lim)//' (this process solves cases '// &
            'K, K + N, K + 2N, ...)'
        k = 0; n = 0
    end subroutine parse_part

end module fc_driver_resume
