!> Memory a case will need, and memory this process may use: the drivers compare the two
!! before they build operators, so that a grid too large for the machine (or for the
!! job's share of it) ends as an input error with the numbers, not as a process killed by
!! the operating system halfway through (doc/reliability.md, "Memory").
!!
!! Available memory is the smallest of
!! * `MemAvailable` of `/proc/meminfo` (memory the kernel can give without swapping),
!! * the limit minus the usage of every memory cgroup of the process and its parents
!!   (cgroup v2 `memory.max`, `memory.current`; v1 `memory.limit_in_bytes`,
!!   `memory.usage_in_bytes`), the reclaimable page cache not counted as used: a batch
!!   system (Slurm) confines a job there,
!! or, when it is set, the environment variable `FASTCONTACT_AVAILABLE_MEMORY` (bytes, with
!! an optional decimal suffix k, M, G, T), which replaces them (to check on another machine's
!! terms, or to switch the check off with a large value).  Where none can be read the size
!! is unknown and nothing is checked.
!!
!! Sizes are bytes; messages print decimal units (1 GB = 10⁹ bytes).
module fc_memory
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fc_kinds, only: dp, i8, msg_len, FC_ERR_VALUE
    implicit none
    private

    !> environment variable that replaces the detected available memory
    character(len=*), parameter, public :: memory_env = 'FASTCONTACT_AVAILABLE_MEMORY'
    !> Peak memory of the serial driver per grid element [bytes], fitted to measured peak
    !! resident memory (doc/reliability.md, "Memory": 256² … 1024² grids of the Cattaneo
    !! sphere) with a margin of a few per cent.  Rows: the kind of problem ('normal',
    !! 'tangential' (shift), 'transient' (transient rolling: TangCG with the previous
    !! state), 'rolling' (steady rolling and creep-force sweeps: Newton–GMRES, counted with
    !! its whole Krylov basis of 41 vectors, 656 B per element, which a long GMRES cycle on a
    !! grid full of contact touches)).  Columns: one thread; two or more (the side-by-side
    !! builds' own plan sets, the lanes' buffers); the same with dissimilar materials (K ≠ 0:
    !! the coupling blocks and the Panagiotopoulos rounds).  The process itself and FFTW add
    !! `memory_base_bytes`.
    real(dp), parameter, public :: bytes_per_element_table(4, 4) = reshape([ &
        270.0_dp, 800.0_dp, 880.0_dp, 1550.0_dp, &      ! one thread
        270.0_dp, 1020.0_dp, 1100.0_dp, 1750.0_dp, &    ! two or more threads
        270.0_dp, 1080.0_dp, 1150.0_dp, 1850.0_dp, &    ! K ≠ 0, one thread
        270.0_dp, 1320.0_dp, 1370.0_dp, 2100.0_dp], [4, 4])   ! K ≠ 0, two or more threads
    !> added per element by FMG with the 'fft-rsm' smoother (its hierarchy and the FFT
    !! preconditioner of every level; measured 89 B)
    real(dp), parameter, public :: bytes_per_element_fmg_rsm = 110
    integer(i8), parameter, public :: memory_base_bytes = 10000000_i8    !! process, libraries, FFTW
    integer(i8), parameter :: unlimited = 2_i8**60                       !! cgroup v1 "no limit" is ~2^63

    public :: available_memory, case_memory_bytes, serial_bytes_per_element, parse_byte_size, format_bytes, memory_fits
    public :: strip_bytes_per_element, ic_set_bytes, ic_case_memory_bytes
    public :: kb_field, process_resident_bytes, cgroup_headroom

contains

    !> Memory this process may still use [bytes], −1 when unknown, and where the number comes
    !! from ('MemAvailable', 'cgroup limit', or the environment variable).  stat =
    !! FC_ERR_VALUE when `FASTCONTACT_AVAILABLE_MEMORY` is set but not a size.
    subroutine available_memory(bytes, source, stat, errmsg)
        integer(i8), intent(out) :: bytes
        character(len=:), allocatable, intent(out) :: source
        integer, intent(out) :: stat
        character(len=msg_len), intent(out) :: errmsg
        character(len=256) :: env
        integer :: n, st
        integer(i8) :: b
        logical :: ok
        stat = 0; errmsg = ''
        bytes = -1; source = 'unknown'
        call get_environment_variable(memory_env, env, n, st)
        if (st == 0 .and. n > 0) then
            call parse_byte_size(env(1:n), bytes, ok)
            if (.not. ok) then
                bytes = -1
                stat = FC_ERR_VALUE
                errmsg = memory_env//" = '"//env(1:min(n, 64))//"': not a size in bytes from 1 to 1e18 "// &
                    '(e.g. 24G, 512M or 1.5e9)'
                return
            end if
            source = memory_env
            return
        end if
        b = kb_field(read_text('/proc/meminfo'), 'MemAvailable')
        if (b >= 0) then
            bytes = b; source = 'MemAvailable'
        end if
        b = cgroup_headroom(read_text('/proc/self/cgroup'), '')
        if (b >= 0 .and. (bytes < 0 .or. b < bytes)) then
            bytes = b; source = 'cgroup limit'
        end if
    end subroutine available_memory

    !> Whether `need` bytes fit in what this process may use: the available memory
    !! ([[available_memory]]) divided by `share` (processes sharing it), plus `held` bytes
    !! the caller releases before it allocates, plus — with `resident` and unless the
    !! environment variable gives the size — what the process holds now (VmRSS: a driver's
    !! operators of the case before).  Unknown available memory fits.  `limit` is the
    !! compared size [bytes] and `source` where it comes from, for the caller's message.
    !! stat = FC_ERR_VALUE (errmsg) for an invalid `FASTCONTACT_AVAILABLE_MEMORY`.
    subroutine memory_fits(need, share, held, resident, fits, limit, source, stat, errmsg)
        integer(i8), intent(in) :: need, held
        integer, intent(in) :: share
        logical, intent(in) :: resident
        logical, intent(out) :: fits
        integer(i8), intent(out) :: limit
        character(len=:), allocatable, intent(out) :: source
        integer, intent(out) :: stat
        character(len=msg_len), intent(out) :: errmsg
        integer(i8) :: avail
        character(len=16) :: nbuf
        fits = .true.; limit = -1
        call available_memory(avail, source, stat, errmsg)
        if (stat /= 0 .or. avail < 0) return
        limit = avail/max(1, share) + max(0_i8, held)
        if (resident .and. source /= memory_env) limit = limit + max(0_i8, process_resident_bytes())
        if (share > 1) then
            write (nbuf, '(i0)') share
            source = source//' of a node shared by '//trim(nbuf)//' processes'
        end if
        fits = need <= limit
    end subroutine memory_fits

    !> Bytes per grid element of a serial solve of `kind` ('normal', 'tangential',
    !! 'transient', 'rolling') on `threads` threads, with dissimilar materials (`coupled`,
    !! K ≠ 0) and FMG's 'fft-rsm' hierarchy (`fmg_rsm`): [[bytes_per_element_table]].
    pure real(dp) function serial_bytes_per_element(kind, threads, coupled, fmg_rsm) result(b)
        character(len=*), intent(in) :: kind
        integer, intent(in) :: threads
        logical, intent(in), optional :: coupled, fmg_rsm
        integer :: row, col
        select case (kind)
        case ('tangential'); row = 2
        case ('transient'); row = 3
        case ('rolling'); row = 4
        case default; row = 1
        end select
        col = merge(2, 1, threads > 1)
        if (present(coupled)) then
            if (coupled) col = col + 2
        end if
        b = bytes_per_element_table(row, col)
        if (present(fmg_rsm)) then
            if (fmg_rsm) b = b + bytes_per_element_fmg_rsm
        end if
    end function serial_bytes_per_element

    !> Bytes per grid element of a strip model problem (nx × 1) by its solver ('mg-fft-rsm',
    !! 'mg-fft-sd', 'fft-rsm'): measured 207, 264–278 and 125–135 B at 2^20 and 2^22 elements,
    !! one or two threads, with a margin (doc/reliability.md, "Memory").
    pure real(dp) function strip_bytes_per_element(solver) result(b)
        character(len=*), intent(in) :: solver
        select case (solver)
        case ('mg-fft-sd'); b = 300
        case ('fft-rsm'); b = 150
        case default; b = 225
        end select
    end function strip_bytes_per_element

    !> Estimated peak memory of a serial solve [bytes]: `memory_base_bytes` plus
    !! `bytes_per_element` for each of `nelements` grid elements.
    pure integer(i8) function case_memory_bytes(nelements, bytes_per_element) result(b)
        integer(i8), intent(in) :: nelements
        real(dp), intent(in) :: bytes_per_element
        b = memory_base_bytes + int(bytes_per_element*real(nelements, dp), i8)
    end function case_memory_bytes

    !> Bytes of a set of tabulated influence coefficients reaching offsets ±mx, ±my: nine
    !! blocks of (2mx + 1)(2my + 1) reals, 72 B per offset pair (about 290 B per element of
    !! the grid it serves when mx, my = nx, ny).
    pure integer(i8) function ic_set_bytes(mx, my) result(b)
        integer, intent(in) :: mx, my
        b = 72_i8*(2_i8*mx + 1)*(2_i8*my + 1)
    end function ic_set_bytes

    !> Estimated peak memory [bytes] of a solve whose coefficients come from a file: the
    !! larger of the load (body 1's set and body 2's while they are read and combined, plus
    !! the checks' FFT symbols and temporaries, about half a set) and the solve (the combined
    !! set beside the operators and work arrays, `bytes_per_element`).  Measured peaks
    !! (doc/reliability.md, "Memory"): a normal case 18.5, 49.9 and 176.1 MB on 128², 256²,
    !! 512² with one file (estimates 21.9, 57.4, 199.0 MB), 53.9 MB on 256² with two.
    pure integer(i8) function ic_case_memory_bytes(nelements, bytes_per_element, set_bytes) result(b)
        integer(i8), intent(in) :: nelements
        real(dp), intent(in) :: bytes_per_element
        integer(i8), intent(in) :: set_bytes
        b = memory_base_bytes + set_bytes + max(set_bytes + set_bytes/2, int(bytes_per_element*real(nelements, dp), i8))
    end function ic_case_memory_bytes

    !> Bytes of a size such as '24G', '512 M', '1.5e9', '2000000000' (decimal suffixes k, M,
    !! G, T, an optional 'B'); ok = .false. unless it is a finite number in [1, 1e18].
    subroutine parse_byte_size(text, bytes, ok)
        character(len=*), intent(in) :: text
        integer(i8), intent(out) :: bytes
        logical, intent(out) :: ok
        character(len=:), allocatable :: t
        real(dp) :: x, scale
        integer :: n, ios
        ok = .false.; bytes = -1
        t = trim(adjustl(text))
        n = len(t)
        if (n == 0 .or. n > 64) return
        if (t(n:n) == 'B' .or. t(n:n) == 'b') n = n - 1
        if (n == 0) return
        scale = 1
        select case (t(n:n))
        case ('k', 'K'); scale = 1.0e3_dp
        case ('m', 'M'); scale = 1.0e6_dp
        case ('g', 'G'); scale = 1.0e9_dp
        case ('t', 'T'); scale = 1.0e12_dp
        end select
        if (scale > 1) n = n - 1
        if (n == 0) return
        if (verify(t(1:n), '0123456789.eE+- ') /= 0) return   ! no list-directed separators or names
        read (t(1:n), *, iostat=ios) x
        if (ios /= 0) return
        if (.not. ieee_is_finite(x)) return
        x = x*scale
        if (x < 1 .or. x > 1.0e18_dp) return
        bytes = int(x, i8); ok = .true.
    end subroutine parse_byte_size

    !> '71.5 GB', '850 MB', '12 kB' (decimal units).
    function format_bytes(bytes) result(s)
        integer(i8), intent(in) :: bytes
        character(len=:), allocatable :: s
        character(len=32) :: buf
        real(dp) :: x
        x = real(bytes, dp)
        if (x >= 1.0e9_dp) then
            write (buf, '(f0.1,a)') x/1.0e9_dp, ' GB'
        else if (x >= 1.0e6_dp) then
            write (buf, '(i0,a)') nint(x/1.0e6_dp), ' MB'
        else
            write (buf, '(i0,a)') nint(x/1.0e3_dp), ' kB'
        end if
        s = trim(buf)
    end function format_bytes

    !> The value of a `key:  N kB` line of /proc/meminfo or /proc/self/status text [bytes],
    !! −1 when absent (e.g. `key = 'MemAvailable'`).
    pure integer(i8) function kb_field(text, key) result(b)
        character(len=*), intent(in) :: text, key
        integer :: i, j, ios
        integer(i8) :: kb
        b = -1
        i = index(new_line('a')//text, new_line('a')//key//':')
        if (i == 0) return
        i = i + len(key) + 1
        j = index(text(i:), new_line('a'))
        if (j == 0) then
            j = len(text)
        else
            j = i + j - 2
        end if
        j = index(text(i:j), 'kB') + i - 2
        if (j < i) return
        read (text(i:j), *, iostat=ios) kb
        if (ios /= 0 .or. kb < 0) return
        b = 1024*kb
    end function kb_field

    !> Resident memory of this process [bytes] (`VmRSS`), −1 when unknown.  What the process
    !! holds already (operators kept from an earlier case) counts towards what it may use.
    function process_resident_bytes() result(b)
        integer(i8) :: b
        b = kb_field(read_text('/proc/self/status'), 'VmRSS')
    end function process_resident_bytes

    !> The least headroom over the memory cgroups named in `text` (the text of
    !! /proc/self/cgroup) and their parents [bytes], −1 when no cgroup sets a limit.  The
    !! headroom of a cgroup is its limit minus its usage, where the usage leaves out the page
    !! cache that the kernel reclaims before it fails an allocation (`active_file`,
    !! `inactive_file` of memory.stat; a batch job that has read large files would else look
    !! full).  `root` prefixes /sys/fs/cgroup (tests build a tree elsewhere; '' in use).
    function cgroup_headroom(text, root) result(b)
        character(len=*), intent(in) :: text, root
        integer(i8) :: b
        character(len=:), allocatable :: rest, line, path, base, fmax, fcur, pre
        integer :: i, k
        integer(i8) :: lim, use, cache, room
        b = -1
        rest = text
        do while (len(rest) > 0)
            i = index(rest, new_line('a'))
            if (i == 0) i = len(rest) + 1
            line = rest(1:i - 1)
            rest = rest(min(i + 1, len(rest) + 1):)
            k = index(line, ':', back=.true.)
            if (k == 0) cycle
            path = trim(line(k + 1:))
            if (line(1:k) == '0::') then                          ! cgroup v2
                base = root//'/sys/fs/cgroup'; fmax = 'memory.max'; fcur = 'memory.current'; pre = ''
            else if (index(','//line(index(line, ':') + 1:k - 1)//',', ',memory,') > 0) then   ! v1
                base = root//'/sys/fs/cgroup/memory'; fmax = 'memory.limit_in_bytes'; fcur = 'memory.usage_in_bytes'
                pre = 'total_'                                     ! hierarchical counters
            else
                cycle
            end if
            do
                lim = read_number(base//path//'/'//fmax)
                use = read_number(base//path//'/'//fcur)
                if (lim > 0 .and. lim < unlimited .and. use >= 0) then
                    cache = reclaimable(read_text(base//path//'/memory.stat'), pre)
                    room = max(0_i8, lim - max(0_i8, use - cache))
                    if (b < 0 .or. room < b) b = room
                end if
                if (len(path) <= 1) exit
                k = index(path, '/', back=.true.)
                path = path(1:max(1, k - 1))
            end do
        end do
    contains
        !> active_file + inactive_file of a memory.stat text (with the v1 prefix), 0 if absent.
        pure integer(i8) function reclaimable(stat, prefix) result(r)
            character(len=*), intent(in) :: stat, prefix
            r = max(0_i8, stat_field(stat, prefix//'active_file')) + max(0_i8, stat_field(stat, prefix//'inactive_file'))
        end function reclaimable
    end function cgroup_headroom

    !> The value of a `key value` line of a memory.stat text [bytes], −1 when absent.
    pure integer(i8) function stat_field(text, key) result(v)
        character(len=*), intent(in) :: text, key
        integer :: i, j, ios
        v = -1
        i = index(new_line('a')//text, new_line('a')//key//' ')
        if (i == 0) return
        i = i + len(key) + 1
        j = index(text(i:)//new_line('a'), new_line('a'))
        read (text(i:i + j - 2), *, iostat=ios) v
        if (ios /= 0) v = -1
    end function stat_field

    !> The integer in a one-line file, −1 when the file is missing or holds no integer ('max').
    function read_number(file) result(x)
        character(len=*), intent(in) :: file
        integer(i8) :: x
        character(len=:), allocatable :: t
        integer :: ios
        x = -1
        t = read_text(file)
        t = trim(adjustl(t(1:index(t//new_line('a'), new_line('a')) - 1)))   ! first line
        if (len(t) == 0 .or. len(t) > 19) return
        if (verify(t, '0123456789') /= 0) return
        read (t, *, iostat=ios) x
        if (ios /= 0) x = -1
    end function read_number

    !> The text of a small file (pseudo-files of /proc and /sys report size 0, so it is read
    !! line by line), '' when it cannot be read; at most 64 kB.
    function read_text(file) result(text)
        character(len=*), intent(in) :: file
        character(len=:), allocatable :: text
        character(len=1024) :: line
        integer :: u, ios
        text = ''
        open (newunit=u, file=file, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            text = text//trim(line)//new_line('a')
            if (len(text) > 65536) exit
        end do
        close (u)
    end function read_text

end module fc_memory
