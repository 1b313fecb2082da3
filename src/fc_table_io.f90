!> Fast table input and output: the element table as CSV or as a NumPy `.npy` file, and
!! the reading of large text tables of reals.
!!
!! Numbers are formatted and parsed here rather than through the run-time library's
!! formatted I/O, which costs about 1 µs per number and dominated the batch driver's run
!! time on large grids.
!!
!! * Output: [[put_real]] writes exactly what the edit descriptor `ES23.15E3` writes
!!   (16 significant digits, correctly rounded, ties to even), without the leading blanks.
!!   x·10^p is formed in double-double arithmetic (Dekker's exact product, powers of ten as
!!   a pair of doubles rounded at compile time from quad precision), which is accurate to
!!   about 1e−31 relative, so the rounding to 16 digits is the correctly rounded one unless
!!   the exact decimal expansion lies within ~1e−15 units of the last digit of a tie.
!!   Magnitudes outside [1e−280, 1e280) and non-finite values go through the run-time
!!   library (`null` for NaN and ±Inf, as in the JSON summary).
!!   Lines are assembled in a 1 MiB buffer and written with unformatted stream access.
!! * Input: [[parse_real]] reads a decimal number with the fast path of Clinger (integer
!!   significand below 2^53 and |exponent| ≤ 22: one correctly rounded operation); any
!!   other token is handed to the run-time list-directed read, so the values are always
!!   those the run-time library would have produced.
!!
!! Size (~650 lines): the number formatter, the parser and the two table writers share the
!! buffered stream writer and the status letters; the formatter and the parser are each
!! about 150 lines of their own, kept here beside the writers that are their only users.
module fc_table_io
    use, intrinsic :: iso_fortran_env, only: int32, int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fc_kinds, only: dp, FC_ERR_IO
    implicit none
    private

    integer, parameter :: qp = selected_real_kind(33, 4931)
    integer, parameter :: pmin = -285, pmax = 300
    real(dp), parameter :: log10_2 = 0.30102999566398119521_dp
    real(dp), parameter :: fast_lo = 1.0e-280_dp, fast_hi = 1.0e280_dp
    integer, parameter :: buffer_bytes = 2**20

    !> Buffered writer on an unformatted stream unit.
    type, public :: fc_stream_writer
        integer :: unit = -1
        integer :: pos = 0                          !! bytes in the buffer
        character(len=:), allocatable :: buf
    contains
        procedure :: open => writer_open
        procedure :: put => writer_put
        procedure :: flush => writer_flush
        procedure :: close => writer_close
        procedure :: reserve => writer_reserve
    end type fc_stream_writer

    integer, parameter, public :: table_state_exterior = 0, table_state_adhesion = 1, table_state_slip = 2

    public :: put_real, put_int, real_text, parse_real
    public :: write_element_table_csv, write_element_table_npy, read_real_table

contains

    ! ------------------------------------------------------------ number formatting ----

    !> Append `x` to `buf` after position `pos` (updated) in the format of `ES23.15E3`
    !! without leading blanks, e.g. `-1.234567890123457E-003`; `null` if not finite.
    !! `buf` must have at least 24 characters free.
    subroutine put_real(x, buf, pos)
        real(dp), intent(in) :: x
        character(len=*), intent(inout) :: buf
        integer, intent(inout) :: pos
        real(dp) :: ax
        integer(int64) :: n, rest, hi7
        integer(int32) :: lo8, top, k
        integer :: e, ae
        character(len=32) :: tmp
        integer :: ik
        real(qp), parameter :: pow_q(pmin:pmax) = [(10.0_qp**ik, ik = pmin, pmax)]
        real(dp), parameter :: pow_hi(pmin:pmax) = real(pow_q, dp)
        character(len=2), parameter :: pairs(0:99) = [(achar(48 + ik/10)//achar(48 + mod(ik, 10)), ik = 0, 99)]
        if (.not. ieee_is_finite(x)) then
            buf(pos + 1:pos + 4) = 'null'; pos = pos + 4; return
        end if
        ax = abs(x)
        if (ax == 0) then
            if (sign(1.0_dp, x) < 0) then
                buf(pos + 1:pos + 1) = '-'; pos = pos + 1
            end if
            buf(pos + 1:pos + 22) = '0.000000000000000E+000'; pos = pos + 22; return
        end if
        if (ax < fast_lo .or. ax >= fast_hi) then
            write (tmp, '(es23.15e3)') x
            tmp = adjustl(tmp)
            buf(pos + 1:pos + len_trim(tmp)) = tmp(1:len_trim(tmp)); pos = pos + len_trim(tmp); return
        end if
        e = floor((exponent(ax) - 1)*log10_2)
        if (ax >= pow_hi(e + 1)) e = e + 1
        n = scaled16(ax, 15 - e)
        if (n >= 10000000000000000_int64) then
            e = e + 1; n = scaled16(ax, 15 - e)
        else if (n < 1000000000000000_int64) then
            e = e - 1; n = scaled16(ax, 15 - e)
        end if
        if (n == 1000000000000000_int64) then
            ! 1.000…: either x ≥ 10^e or x rounds up to it from below 10^e; the first
            ! decision above compared x with a rounded power of ten
            rest = scaled16(ax, 16 - e)
            if (rest < 10000000000000000_int64) then
                e = e - 1; n = rest
            end if
        end if
        if (x < 0) then
            buf(pos + 1:pos + 1) = '-'; pos = pos + 1
        end if
        top = int(n/1000000000000000_int64, int32)
        rest = n - int(top, int64)*1000000000000000_int64      ! 15 digits
        hi7 = rest/100000000_int64
        lo8 = int(rest - hi7*100000000_int64, int32)
        buf(pos + 1:pos + 2) = achar(48 + top)//'.'
        k = int(hi7, int32)
        buf(pos + 3:pos + 3) = achar(48 + k/1000000)
        k = mod(k, 1000000)
        buf(pos + 4:pos + 5) = pairs(k/10000)
        buf(pos + 6:pos + 7) = pairs(mod(k/100, 100))
        buf(pos + 8:pos + 9) = pairs(mod(k, 100))
        buf(pos + 10:pos + 11) = pairs(lo8/1000000)
        buf(pos + 12:pos + 13) = pairs(mod(lo8/10000, 100))
        buf(pos + 14:pos + 15) = pairs(mod(lo8/100, 100))
        buf(pos + 16:pos + 17) = pairs(mod(lo8, 100))
        buf(pos + 18:pos + 18) = 'E'
        if (e < 0) then
            buf(pos + 19:pos + 19) = '-'
        else
            buf(pos + 19:pos + 19) = '+'
        end if
        ae = abs(e)
        buf(pos + 20:pos + 20) = achar(48 + ae/100)
        buf(pos + 21:pos + 22) = pairs(mod(ae, 100))
        pos = pos + 22
    end subroutine put_real

    !> round(ax·10^p) to an integer (ties to even), ax·10^p formed in double-double.
    pure integer(int64) function scaled16(ax, p) result(n)
        real(dp), intent(in) :: ax
        integer, intent(in) :: p
        real(dp) :: h, l, ph, pl, r, rr, f
        integer(int64) :: k
        integer :: ik
        !> Powers of ten as double-double pairs, rounded at compile time.
        real(qp), parameter :: pow_q(pmin:pmax) = [(10.0_qp**ik, ik = pmin, pmax)]
        real(dp), parameter :: pow_hi(pmin:pmax) = real(pow_q, dp)
        real(dp), parameter :: pow_lo(pmin:pmax) = real(pow_q - real(pow_hi, qp), dp)
        h = pow_hi(p); l = pow_lo(p)
        call two_prod(ax, h, ph, pl)
        pl = pl + ax*l
        k = int(ph, int64)
        r = (ph - real(k, dp)) + pl
        rr = r + 0.5_dp
        f = floor(rr)
        n = k + int(f, int64)
        if (rr == f .and. mod(n, 2_int64) == 1) n = n - 1
    end function scaled16

    !> Dekker's exact product: p + e = a·b exactly (no FMA needed).
    pure subroutine two_prod(a, b, p, e)
        real(dp), intent(in) :: a, b
        real(dp), intent(out) :: p, e
        real(dp), parameter :: splitter = 134217729.0_dp   ! 2^27 + 1
        real(dp) :: c, ah, al, bh, bl
        p = a*b
        c = splitter*a; ah = c - (c - a); al = a - ah
        c = splitter*b; bh = c - (c - b); bl = b - bh
        e = ((ah*bh - p) + ah*bl + al*bh) + al*bl
    end subroutine two_prod

    !> Append the decimal digits of `i` (no blanks) to `buf` after position `pos`.
    pure subroutine put_int(i, buf, pos)
        integer, intent(in) :: i
        character(len=*), intent(inout) :: buf
        integer, intent(inout) :: pos
        character(len=12) :: t
        integer :: k, m
        integer(int64) :: v
        v = abs(int(i, int64))
        k = len(t)
        do
            t(k:k) = achar(48 + int(mod(v, 10_int64)))
            v = v/10
            k = k - 1
            if (v == 0) exit
        end do
        if (i < 0) then
            t(k:k) = '-'; k = k - 1
        end if
        m = len(t) - k
        buf(pos + 1:pos + m) = t(k + 1:)
        pos = pos + m
    end subroutine put_int

    !> `x` as the text [[put_real]] writes.
    function real_text(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=40) :: b
        integer :: pos
        pos = 0
        call put_real(x, b, pos)
        s = b(1:pos)
    end function real_text

    ! ------------------------------------------------------------ buffered writer ----

    !> Open `path` for writing: replaced, or with `append` extended at its end (it must exist).
    subroutine writer_open(self, path, stat, errmsg, append)
        class(fc_stream_writer), intent(inout) :: self
        character(len=*), intent(in) :: path
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        logical, intent(in), optional :: append
        character(len=256) :: iomsg
        logical :: app
        errmsg = ''
        app = .false.
        if (present(append)) app = append
        if (app) then
            open (newunit=self%unit, file=path, access='stream', form='unformatted', status='old', &
                  position='append', action='write', iostat=stat, iomsg=iomsg)
        else
            open (newunit=self%unit, file=path, access='stream', form='unformatted', status='replace', &
                  action='write', iostat=stat, iomsg=iomsg)
        end if
        if (stat /= 0) then
            self%unit = -1
            errmsg = "cannot write '"//trim(path)//"': "//trim(iomsg); return
        end if
        if (.not. allocated(self%buf)) allocate (character(len=buffer_bytes) :: self%buf)
        self%pos = 0
    end subroutine writer_open

    !> Make room for `nbytes` more bytes (flushes the buffer when needed).
    subroutine writer_reserve(self, nbytes, stat)
        class(fc_stream_writer), intent(inout) :: self
        integer, intent(in) :: nbytes
        integer, intent(out) :: stat
        stat = 0
        if (self%pos + nbytes > len(self%buf)) call self%flush(stat)
    end subroutine writer_reserve

    subroutine writer_put(self, text, stat)
        class(fc_stream_writer), intent(inout) :: self
        character(len=*), intent(in) :: text
        integer, intent(out) :: stat
        stat = 0
        if (len(text) > len(self%buf)) then
            call self%flush(stat)
            if (stat /= 0) return
            write (self%unit, iostat=stat) text
            return
        end if
        call self%reserve(len(text), stat)
        if (stat /= 0) return
        self%buf(self%pos + 1:self%pos + len(text)) = text
        self%pos = self%pos + len(text)
    end subroutine writer_put

    subroutine writer_flush(self, stat)
        class(fc_stream_writer), intent(inout) :: self
        integer, intent(out) :: stat
        stat = 0
        if (self%pos > 0) write (self%unit, iostat=stat) self%buf(1:self%pos)
        self%pos = 0
    end subroutine writer_flush

    subroutine writer_close(self, stat, errmsg)
        class(fc_stream_writer), intent(inout) :: self
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: st2
        character(len=256) :: iomsg
        errmsg = ''
        call self%flush(stat)
        if (stat /= 0) errmsg = 'write error (disk full?)'
        close (self%unit, iostat=st2, iomsg=iomsg)
        if (stat == 0 .and. st2 /= 0) then
            stat = st2; errmsg = trim(iomsg)
        end if
        self%unit = -1
        if (allocated(self%buf)) deallocate (self%buf)
    end subroutine writer_close

    ! ------------------------------------------------------------ element table ----

    !> Status letter of an element state: E exterior (0), A adhesion (1), S slip (2).
    pure character function state_letter(state)
        integer, intent(in) :: state
        select case (state)
        case (table_state_adhesion); state_letter = 'A'
        case (table_state_slip); state_letter = 'S'
        case default; state_letter = 'E'
        end select
    end function state_letter

    !> Write the element table `ix,iy,x,y,status,pn,px,py,sx,sy,gap` (one row per element,
    !! x running fastest) to `path`.  With the tangential solution (`state`, `px`, `py`, `sx`,
    !! `sy` all present) the status is E exterior, A adhesion, S slip from `state`; without,
    !! A where pn > 0 and E elsewhere, and px..sy are written as 0.
    !!
    !! A table may be written in consecutive blocks of rows (the ranks of a distributed
    !! solve, in order): `y` and the arrays hold the block's rows, `iy_first` is the grid
    !! index of its first row (default 1), and `append` extends the file instead of
    !! replacing it, without the header.  The blocks together are byte for byte the table
    !! written at once.
    subroutine write_element_table_csv(path, x, y, pn, gap, stat, errmsg, state, px, py, sx, sy, iy_first, append)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: x(:), y(:)               !! element centres [mm]
        real(dp), intent(in) :: pn(:, :), gap(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer, intent(in), optional :: state(:, :)
        real(dp), intent(in), optional :: px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer, intent(in), optional :: iy_first   !! grid index of the first row of `y` (default 1)
        logical, intent(in), optional :: append     !! append the rows to `path`, no header
        type(fc_stream_writer) :: w
        character(len=:), allocatable :: xs(:)
        integer, allocatable :: xl(:)
        character(len=32) :: ys
        integer :: nx, ny, i, j, yl, pos, j0
        character(len=1) :: st
        logical :: tang, app
        character(len=*), parameter :: zero4 = ',0,0,0,0,'
        character(len=1), parameter :: nl = achar(10)
        nx = size(x); ny = size(y)
        j0 = 0
        if (present(iy_first)) j0 = iy_first - 1
        app = .false.
        if (present(append)) app = append
        tang = present(state) .and. present(px) .and. present(py) .and. present(sx) .and. present(sy)
        call w%open(path, stat, errmsg, append=app)
        if (stat /= 0) return
        ! the coordinates repeat on every row and column: format them once
        allocate (character(len=32) :: xs(nx))
        allocate (xl(nx))
        do i = 1, nx
            xl(i) = 0
            call put_real(x(i), xs(i), xl(i))
        end do
        if (.not. app) call w%put('ix,iy,x,y,status,pn,px,py,sx,sy,gap'//nl, stat)
        do j = 1, ny
            yl = 0
            call put_real(y(j), ys, yl)
            do i = 1, nx
                call w%reserve(320, stat)
                if (stat /= 0) exit
                pos = w%pos
                associate (b => w%buf)
                    call put_int(i, b, pos)
                    b(pos + 1:pos + 1) = ','; pos = pos + 1
                    call put_int(j0 + j, b, pos)
                    b(pos + 1:pos + 1) = ','
                    b(pos + 2:pos + 1 + xl(i)) = xs(i)(1:xl(i)); pos = pos + 1 + xl(i)
                    b(pos + 1:pos + 1) = ','
                    b(pos + 2:pos + 1 + yl) = ys(1:yl); pos = pos + 1 + yl
                    if (tang) then
                        st = state_letter(state(i, j))
                    else
                        st = 'E'
                        if (pn(i, j) > 0) st = 'A'
                    end if
                    b(pos + 1:pos + 3) = ','//st//','; pos = pos + 3
                    call put_real(pn(i, j), b, pos)
                    if (tang) then
                        b(pos + 1:pos + 1) = ','; pos = pos + 1
                        call put_real(px(i, j), b, pos)
                        b(pos + 1:pos + 1) = ','; pos = pos + 1
                        call put_real(py(i, j), b, pos)
                        b(pos + 1:pos + 1) = ','; pos = pos + 1
                        call put_real(sx(i, j), b, pos)
                        b(pos + 1:pos + 1) = ','; pos = pos + 1
                        call put_real(sy(i, j), b, pos)
                        b(pos + 1:pos + 1) = ','; pos = pos + 1
                    else
                        b(pos + 1:pos + len(zero4)) = zero4; pos = pos + len(zero4)
                    end if
                    call put_real(gap(i, j), b, pos)
                    b(pos + 1:pos + 1) = nl; pos = pos + 1
                end associate
                w%pos = pos
            end do
            if (stat /= 0) exit
        end do
        if (stat /= 0) then
            errmsg = "cannot write '"//trim(path)//"' (disk full?)"
            close (w%unit)
            return
        end if
        call w%close(stat, errmsg)
        if (stat /= 0) errmsg = "cannot close '"//trim(path)//"': "//trim(errmsg)
    end subroutine write_element_table_csv

    !> Write the element table as a NumPy `.npy` file (format 1.0): a one-dimensional
    !! structured array with one record per element in the order of the CSV rows and the
    !! fields ix, iy (int32), x, y (float64), status (1 byte: 'E', 'A', 'S'), pn, px, py,
    !! sx, sy, gap (float64), in the machine's byte order (declared in the header).
    !! `numpy.load(path)['pn']` gives the pressure column.  Same optional arguments as
    !! [[write_element_table_csv]].
    !!
    !! In blocks of rows as [[write_element_table_csv]]: `iy_first`, `append`, and for the
    !! first block `ny_total`, the rows of the whole table, which the header's shape counts.
    subroutine write_element_table_npy(path, x, y, pn, gap, stat, errmsg, state, px, py, sx, sy, iy_first, append, &
                                       ny_total)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: x(:), y(:)
        real(dp), intent(in) :: pn(:, :), gap(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer, intent(in), optional :: state(:, :)
        real(dp), intent(in), optional :: px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer, intent(in), optional :: iy_first   !! grid index of the first row of `y` (default 1)
        logical, intent(in), optional :: append     !! append the records to `path`, no header
        integer, intent(in), optional :: ny_total   !! rows of the whole table (default size(y))
        integer, parameter :: rec = 73    ! 2·4 + 2·8 + 1 + 6·8 bytes
        type(fc_stream_writer) :: w
        character(len=:), allocatable :: header
        character(len=1) :: bo, st
        character(len=8) :: r8
        character(len=4) :: i4
        character(len=24) :: shape
        integer :: nx, ny, i, j, pos, hlen, total, j0, nyt
        logical :: tang, app
        real(dp) :: v(6)
        nx = size(x); ny = size(y)
        j0 = 0
        if (present(iy_first)) j0 = iy_first - 1
        app = .false.
        if (present(append)) app = append
        nyt = ny
        if (present(ny_total)) nyt = ny_total
        tang = present(state) .and. present(px) .and. present(py) .and. present(sx) .and. present(sy)
        bo = '<'
        if (iachar(transfer(1_int32, 'a')) == 0) bo = '>'
        write (shape, '(i0)') int(nx, int64)*nyt
        header = "{'descr': [('ix', '"//bo//"i4'), ('iy', '"//bo//"i4'), ('x', '"//bo//"f8'), ('y', '"//bo// &
            "f8'), ('status', '|S1'), ('pn', '"//bo//"f8'), ('px', '"//bo//"f8'), ('py', '"//bo//"f8'), ('sx', '"// &
            bo//"f8'), ('sy', '"//bo//"f8'), ('gap', '"//bo//"f8')], 'fortran_order': False, 'shape': ("// &
            trim(shape)//",), }"
        ! pad with blanks and a newline so that the data start on a multiple of 64 bytes
        total = 10 + len(header) + 1
        hlen = len(header) + 1 + modulo(-total, 64)
        header = header//repeat(' ', hlen - len(header) - 1)//achar(10)
        call w%open(path, stat, errmsg, append=app)
        if (stat /= 0) return
        if (.not. app) then
            call w%put(achar(147)//'NUMPY'//achar(1)//achar(0)//achar(modulo(hlen, 256))//achar(hlen/256), stat)
            if (stat == 0) call w%put(header, stat)
        end if
        do j = 1, ny
            if (stat /= 0) exit
            do i = 1, nx
                call w%reserve(rec, stat)
                if (stat /= 0) exit
                pos = w%pos
                if (tang) then
                    st = state_letter(state(i, j))
                    v = [pn(i, j), px(i, j), py(i, j), sx(i, j), sy(i, j), gap(i, j)]
                else
                    st = 'E'
                    if (pn(i, j) > 0) st = 'A'
                    v = [pn(i, j), 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, gap(i, j)]
                end if
                i4 = transfer(int(i, int32), i4); w%buf(pos + 1:pos + 4) = i4
                i4 = transfer(int(j0 + j, int32), i4); w%buf(pos + 5:pos + 8) = i4
                r8 = transfer(x(i), r8); w%buf(pos + 9:pos + 16) = r8
                r8 = transfer(y(j), r8); w%buf(pos + 17:pos + 24) = r8
                w%buf(pos + 25:pos + 25) = st
                w%buf(pos + 26:pos + 73) = transfer(v, repeat(' ', 48))
                w%pos = pos + rec
            end do
        end do
        if (stat /= 0) then
            errmsg = "cannot write '"//trim(path)//"' (disk full?)"
            close (w%unit)
            return
        end if
        call w%close(stat, errmsg)
        if (stat /= 0) errmsg = "cannot close '"//trim(path)//"': "//trim(errmsg)
    end subroutine write_element_table_npy

    ! ------------------------------------------------------------ reading ----

    !> Parse one decimal real token (no blanks).  Tokens of the form [sign] digits [. digits]
    !! [e|E|d|D [sign] digits] with at most 19 significant digits, an integer significand
    !! below 2^53 and a decimal scale of at most 22 are converted directly (exactly rounded);
    !! anything else is converted by the run-time list-directed read.  `ok` is false when the
    !! token is not a number.
    subroutine parse_real(tok, v, ok)
        character(len=*), intent(in) :: tok
        real(dp), intent(out) :: v
        logical, intent(out) :: ok
        integer :: ios
        ok = .false.; v = 0
        if (len(tok) == 0) return
        ok = .true.
        if (exact_decimal(tok, v)) return
        read (tok, *, iostat=ios) v
        ok = ios == 0 .and. index(tok, '/') == 0 .and. index(tok, '*') == 0
    end subroutine parse_real

    !> The direct conversion of [[parse_real]]: .false. (v undefined) for a token outside its
    !! form or range, which the caller hands to the run-time library.
    logical function exact_decimal(tok, v) result(done)
        character(len=*), intent(in) :: tok
        real(dp), intent(out) :: v
        integer :: i, n, c, ndig, scale, ex, exsign
        integer(int64) :: m
        logical :: neg, seen_dot, any_digit
        integer :: ik
        real(dp), parameter :: exact_pow(0:22) = [(10.0_dp**ik, ik = 0, 22)]   ! exact in binary
        done = .false.; v = 0
        n = len(tok)
        i = 1; neg = .false.
        c = iachar(tok(1:1))
        if (c == 43 .or. c == 45) then       ! + -
            neg = (c == 45); i = 2
        end if
        m = 0; ndig = 0; scale = 0; seen_dot = .false.; any_digit = .false.
        do while (i <= n)
            c = iachar(tok(i:i))
            if (c >= 48 .and. c <= 57) then
                any_digit = .true.
                if (m == 0 .and. c == 48) then
                    if (seen_dot) scale = scale - 1      ! leading zeros after the point
                else
                    ndig = ndig + 1
                    if (ndig > 18) return                 ! let the run-time library decide
                    m = 10*m + (c - 48)
                    if (seen_dot) scale = scale - 1
                end if
            else if (c == 46 .and. .not. seen_dot) then
                seen_dot = .true.
            else
                exit
            end if
            i = i + 1
        end do
        if (.not. any_digit) return
        if (i <= n) then
            c = iachar(tok(i:i))
            if (c /= 69 .and. c /= 101 .and. c /= 68 .and. c /= 100) return   ! E e D d
            i = i + 1
            if (i > n) return
            exsign = 1
            c = iachar(tok(i:i))
            if (c == 43 .or. c == 45) then
                if (c == 45) exsign = -1
                i = i + 1
            end if
            if (i > n) return
            ex = 0
            do while (i <= n)
                c = iachar(tok(i:i))
                if (c < 48 .or. c > 57) return
                ex = 10*ex + (c - 48)
                if (ex > 100000) return
                i = i + 1
            end do
            scale = scale + exsign*ex
        end if
        if (m == 0) then
            v = 0
        else if (m < 9007199254740992_int64 .and. abs(scale) <= 22) then
            if (scale >= 0) then
                v = real(m, dp)*exact_pow(scale)
            else
                v = real(m, dp)/exact_pow(-scale)
            end if
        else
            return
        end if
        if (neg) v = -v
        done = .true.
    end function exact_decimal

    !> Read `size(vals)` reals from the text file `filename`: blank, comma or tab separated,
    !! any number per line; blank lines and lines whose first non-blank character is '#' or
    !! '!' are skipped.  Errors name the file and the line.
    subroutine read_real_table(filename, vals, stat, errmsg)
        character(len=*), intent(in) :: filename
        real(dp), intent(out) :: vals(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=:), allocatable :: text
        integer :: unit, ios, nread, lineno, i, n, start, c, k
        integer(int64) :: fsize
        logical :: ok, at_line_start, comment
        real(dp) :: v
        stat = 0; errmsg = ''
        open (newunit=unit, file=filename, status='old', action='read', access='stream', form='unformatted', &
              iostat=ios)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = "cannot open table file '"//trim(filename)//"'"; return
        end if
        inquire (unit=unit, size=fsize)
        if (fsize < 0 .or. fsize > 2_int64**31 - 2) then
            stat = FC_ERR_IO; errmsg = "table file '"//trim(filename)//"': cannot determine its size or larger than 2 GB"
            close (unit); return
        end if
        allocate (character(len=int(fsize)) :: text)
        if (fsize > 0) read (unit, iostat=ios) text
        close (unit)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = "cannot read table file '"//trim(filename)//"'"; return
        end if
        n = len(text)
        nread = 0; lineno = 1; i = 1
        at_line_start = .true.; comment = .false.
        do while (i <= n)
            c = iachar(text(i:i))
            if (c == 10) then
                lineno = lineno + 1; at_line_start = .true.; comment = .false.; i = i + 1; cycle
            end if
            if (comment .or. c == 32 .or. c == 44 .or. c == 9 .or. c == 13) then
                i = i + 1; cycle
            end if
            if (at_line_start .and. (c == 35 .or. c == 33)) then     ! '#' or '!'
                comment = .true.; i = i + 1; cycle
            end if
            at_line_start = .false.
            start = i
            do while (i <= n)
                c = iachar(text(i:i))
                if (c == 32 .or. c == 44 .or. c == 9 .or. c == 13 .or. c == 10) exit
                i = i + 1
            end do
            call parse_real(text(start:i - 1), v, ok)
            if (.not. ok) then
                stat = FC_ERR_IO; write (errmsg, '(a,i0,a)') "table file '"//trim(filename)//"', line ", lineno, &
                    ": not a number: '"//text(start:min(i - 1, start + 39))//"'"
                return
            end if
            if (nread >= size(vals)) then
                stat = FC_ERR_IO; write (errmsg, '(a,i0,a)') "table file '"//trim(filename)//"' has more than nx*ny = ", &
                    size(vals), ' values'
                return
            end if
            nread = nread + 1
            vals(nread) = v
        end do
        k = nread
        if (k /= size(vals)) then
            stat = FC_ERR_IO; write (errmsg, '(a,i0,a,i0)') "table file '"//trim(filename)//"' has ", k, &
                ' values, expected nx*ny = ', size(vals)
        end if
    end subroutine read_real_table

end module fc_table_io
