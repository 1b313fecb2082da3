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
!! changed since is solved again.  Files a case names (geometry tables, coefficient files) are
!! not part of the fingerprint.
!!
!! `--part K/N` keeps the cases k with mod(k − 1, N) = K − 1: N processes (a Slurm job array)
!! share a file without MPI, round robin so that neighbouring cases of a sweep spread out.
module fc_driver_resume
    use, intrinsic :: iso_fortran_env, only: int64
    use fc_kinds, only: FC_ERR_VALUE
    use fc_namelist, only: fc_case_chunk
    use fc_version, only: fc_version_string
    implicit none
    private

    integer, parameter, public :: fingerprint_len = 16   !! hexadecimal digits of a fingerprint
    integer, parameter, public :: max_parts = 10000      !! N of `--part K/N`, at most (the case limit)

    public :: case_fingerprints, previous_outcome, parse_part

contains

    !> The input fingerprint of every case of a file: fp(k) hashes the version and the group
    !! texts of cases 1 … k.  Two FNV-1a hashes of 32 bits with different offset bases, kept in
    !! 64-bit integers so that no product overflows.
    function case_fingerprints(cases) result(fp)
        type(fc_case_chunk), intent(in) :: cases(:)
        character(len=fingerprint_len) :: fp(size(cases))
        integer(int64) :: h1, h2
        integer :: k, g
        h1 = 2166136261_int64; h2 = 3735928559_int64
        call feed(fc_version_string)
        do k = 1, size(cases)
            if (allocated(cases(k)%groups)) then
                do g = 1, size(cases(k)%groups)
                    if (allocated(cases(k)%groups(g)%text)) call feed(cases(k)%groups(g)%text)
                    call feed(new_line('a'))
                end do
            end if
            call feed('&&')   ! the case boundary
            write (fp(k), '(2z8.8)') h1, h2
        end do
    contains
        subroutine feed(text)
            character(len=*), intent(in) :: text
            integer(int64), parameter :: prime = 16777619_int64, mask = 4294967295_int64
            integer :: i
            do i = 1, len(text)
                h1 = iand(ieor(h1, int(ichar(text(i:i)), int64))*prime, mask)
                h2 = iand(ieor(h2, int(ichar(text(i:i)), int64))*prime, mask)
            end do
        end subroutine feed
    end function case_fingerprints

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
