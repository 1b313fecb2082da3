!> Influence-coefficient sets: kernels A^ab(offset) read from files (FE or other sources),
!! their validation, the combination of two bodies and the fastcontact file format.  The set
!! type [[fc_ic_set]] and the kernel of one block for a grid ([[ic_set_kernel]]) live in
!! [[fc_influence]], beside the analytic kernels, so that the operators need not depend on
!! the file formats; they are re-exported here.
!!
!! A set holds, for every offset (ix, iy) with |ix| ≤ mx, |iy| ≤ my, the 3×3 coefficients
!! a(ix, iy, i, j): displacement component i (1 = x, 2 = y, 3 = z) at a cell centre due to a
!! unit traction component j on a cell of size dx×dy centred at offset (−ix·dx, −iy·dy)
!! from it [mm per N/mm²].  Signs follow the library (doc/ic_file_format.md): z is the
!! normal into body 1, a positive pressure pushes the bodies apart.
!!
!! * content 'body': one body's coefficients (what one FE run gives); two bodies combine as
!!   the analytic path does: A = A1 + A2 for zz, xx, xy, yx, yy and A = A1 − A2 for the
!!   coupling blocks xz, zx, yz, zy (body 2's frame is body 1's mirrored in z).  A body
!!   that is an elastic half-space (G2, ν2) has exactly the analytic one-body kernel.
!! * content 'combined': displacement differences, ready for the solvers.
!!
!! Validation (before any solver sees a set): the blocks the solvers treat as symmetric
!! (zz, xx, yy, and xy = yx) must be even in the offset, and the FFT symbols of A^zz and of
!! the 2×2 tangential block must be positive definite (A SPD); otherwise a clear error.
module fc_icfile
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fc_kinds, only: dp, i8, msg_len, FC_ERR_VALUE, FC_ERR_IO
    use fc_geometry_grid, only: fc_grid
    use fc_influence, only: fc_material, combine_material, ic_kernel_extended, rigid_modulus, &
        IC_ZZ, IC_XX, IC_YY, IC_XY, IC_XZ, IC_ZX, IC_YZ, IC_ZY, fc_ic_set, ic_set_allocate, ic_block_index, &
        ic_set_kernel, same_size => same_cell_size
    use fc_fftw
    use, intrinsic :: iso_c_binding, only: c_char, c_null_char
    implicit none
    private

    integer, parameter, public :: ic_format_version = 1  !! version written by [[write_ic_file]]
    integer, parameter, public :: ic_max_offset = 4096   !! largest mx, my accepted from a file

    character(len=2), parameter :: comp_name(3) = ['x ', 'y ', 'z ']

    public :: fc_ic_set, ic_set_allocate, ic_block_index, ic_set_kernel   ! (from [[fc_influence]])
    public :: validate_ic_set, combine_ic_sets, combine_ic_sets_in_place, analytic_body_set, move_ic_set
    public :: write_ic_file, read_ic_file, hash_text, is_fastcontact_ic_file
    public :: rename_file, temp_name, end_of_header

contains

    !> One body's analytic half-space set (G, ν): the combined kernel of that body against a
    !! rigid one, so that two half-space bodies sum to the library's analytic kernel.
    subroutine analytic_body_set(g, nu, dx, dy, mx, my, set, stat, errmsg)
        real(dp), intent(in) :: g, nu, dx, dy
        integer, intent(in) :: mx, my
        type(fc_ic_set), intent(inout) :: set
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_material) :: mat
        type(fc_grid) :: grid
        call ic_set_allocate(set, mx, my, dx, dy)
        set%content = 'body'; set%source = 'analytic'; set%g = g; set%nu = nu; set%load = 'constant'
        set%model = 'elastic half-space (Boussinesq-Cerruti)'
        stat = 0; errmsg = ''
        if (g >= rigid_modulus) return   ! rigid body: no displacement
        mat%g1 = g; mat%nu1 = nu; mat%g2 = rigid_modulus; mat%nu2 = 0
        call combine_material(mat, stat, errmsg)
        if (stat /= 0) return
        grid%nx = mx + 1; grid%ny = my + 1; grid%dx = dx; grid%dy = dy
        call put(IC_ZZ); call put(IC_XX); call put(IC_YY); call put(IC_XY)
        call put(IC_XZ); call put(IC_ZX); call put(IC_YZ); call put(IC_ZY)
        set%a(:, :, 2, 1) = set%a(:, :, 1, 2)
    contains
        subroutine put(block)
            integer, intent(in) :: block
            real(dp), allocatable :: k(:, :)
            integer :: i, j
            call ic_kernel_extended(block, mat, grid, mx, my, k)
            call ic_block_index(block, i, j)
            set%a(:, :, i, j) = k
        end subroutine put
    end subroutine analytic_body_set

    !> Combined (displacement-difference) set of body 1 and body 2, both content 'body' on
    !! the same cells; offsets are those common to both.
    subroutine combine_ic_sets(b1, b2, out, stat, errmsg)
        type(fc_ic_set), intent(in) :: b1, b2
        type(fc_ic_set), intent(inout) :: out
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: mx, my
        call check_combinable(b1, b2, stat, errmsg)
        if (stat /= 0) return
        mx = min(b1%mx, b2%mx); my = min(b1%my, b2%my)
        call ic_set_allocate(out, mx, my, b1%dx, b1%dy)
        out%a = b1%a(-mx:mx, -my:my, :, :)
        out%source = b1%source; out%load = b1%load; out%model = b1%model
        call add_second_body(out, b2)
    end subroutine combine_ic_sets

    !> [[combine_ic_sets]] into `b1`: body 1's set becomes the combined one, with the same
    !! values, without a third set in memory (a set is 72 B per offset pair, about 290 B per
    !! element of the grid it serves).  Only when b1 reaches farther than b2 is it cut to the
    !! common offsets through a copy.
    subroutine combine_ic_sets_in_place(b1, b2, stat, errmsg)
        type(fc_ic_set), intent(inout) :: b1
        type(fc_ic_set), intent(in) :: b2
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: mx, my
        real(dp), allocatable :: cut(:, :, :, :)
        call check_combinable(b1, b2, stat, errmsg)
        if (stat /= 0) return
        mx = min(b1%mx, b2%mx); my = min(b1%my, b2%my)
        if (mx /= b1%mx .or. my /= b1%my) then
            allocate (cut(-mx:mx, -my:my, 3, 3), source=b1%a(-mx:mx, -my:my, :, :))
            call move_alloc(cut, b1%a)
            b1%mx = mx; b1%my = my
        end if
        call add_second_body(b1, b2)
    end subroutine combine_ic_sets_in_place

    !> stat = FC_ERR_VALUE (errmsg) unless b1 and b2 are one body each on the same cells.
    subroutine check_combinable(b1, b2, stat, errmsg)
        type(fc_ic_set), intent(in) :: b1, b2
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = FC_ERR_VALUE
        if (b1%content /= 'body' .or. b2%content /= 'body') then
            errmsg = "influence coefficients: only sets of content 'body' can be combined"; return
        end if
        if (.not. same_size(b1%dx, b2%dx) .or. .not. same_size(b1%dy, b2%dy)) then
            write (errmsg, '(a,2es14.6,a,2es14.6)') 'influence coefficients: cell sizes differ between the bodies: ', &
                b1%dx, b1%dy, ' vs ', b2%dx, b2%dy
            return
        end if
        stat = 0; errmsg = ''
    end subroutine check_combinable

    !> out (body 1's coefficients on offsets out%mx, out%my, with its source, load and
    !! model) becomes the combined set: body 2's coefficients added, its coupling blocks
    !! mirrored in z.
    subroutine add_second_body(out, b2)
        type(fc_ic_set), intent(inout) :: out
        type(fc_ic_set), intent(in) :: b2
        integer :: mx, my, i, j
        real(dp) :: s
        mx = out%mx; my = out%my
        do j = 1, 3
            do i = 1, 3
                s = 1
                if ((i == 3) .neqv. (j == 3)) s = -1   ! coupling blocks: body 2 is mirrored in z
                out%a(:, :, i, j) = out%a(:, :, i, j) + s*b2%a(-mx:mx, -my:my, i, j)
            end do
        end do
        out%content = 'combined'
        out%source = trim(out%source)//'+'//trim(b2%source)
        out%model = 'body 1: '//trim(out%model)//'; body 2: '//trim(b2%model)
        out%hash = ''
        out%g = 0; out%nu = 0
    end subroutine add_second_body

    !> `to` = `from` without copying the coefficients: they move (`from%a` ends unallocated).
    subroutine move_ic_set(from, to)
        type(fc_ic_set), intent(inout) :: from, to
        real(dp), allocatable :: a(:, :, :, :)
        call move_alloc(from%a, a)
        to = from
        call move_alloc(a, to%a)
    end subroutine move_ic_set

    !> Check a set: finite values, even symmetric blocks with xy = yx, positive FFT symbols
    !! of A^zz and of the tangential 2×2 block.  `label` names the file in messages.
    subroutine validate_ic_set(set, label, stat, errmsg)
        type(fc_ic_set), intent(in) :: set
        character(len=*), intent(in) :: label
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: i, j, ix, iy
        real(dp) :: scale, tol
        real(dp), allocatable :: szz(:, :), sxx(:, :), syy(:, :), sxy(:, :), lam(:, :)
        integer :: loc(2)
        stat = FC_ERR_VALUE
        if (.not. allocated(set%a)) then
            errmsg = trim(label)//': no coefficients'; return
        end if
        if (.not. all(ieee_is_finite(set%a))) then
            errmsg = trim(label)//': coefficients contain NaN or Inf'; return
        end if
        do j = 1, 3
            do i = 1, 3
                if (i /= j .and. (i == 3 .or. j == 3)) cycle   ! coupling blocks: odd, not checked
                scale = maxval(abs(set%a(:, :, i, j)))
                tol = 1.0e-9_dp*max(scale, tiny(1.0_dp))
                do iy = -set%my, set%my
                    do ix = -set%mx, set%mx
                        if (abs(set%a(ix, iy, i, j) - set%a(-ix, -iy, i, j)) > tol) then
                            write (errmsg, '(5a,i0,a,i0,a,es12.4,a,i0,a,i0,a,es12.4,a)') trim(label), &
                                ': block ', trim(comp_name(i)), trim(comp_name(j)), ' is not symmetric: A(', ix, ',', iy, &
                                ') = ', set%a(ix, iy, i, j), ' but A(', -ix, ',', -iy, ') = ', set%a(-ix, -iy, i, j), &
                                ' (the solvers need A(d) = A(-d))'
                            return
                        end if
                    end do
                end do
            end do
        end do
        scale = max(maxval(abs(set%a(:, :, 1, 2))), maxval(abs(set%a(:, :, 2, 1))), tiny(1.0_dp))
        if (maxval(abs(set%a(:, :, 1, 2) - set%a(:, :, 2, 1))) > 1.0e-9_dp*scale) then
            loc = maxloc(abs(set%a(:, :, 1, 2) - set%a(:, :, 2, 1))) - [set%mx + 1, set%my + 1]
            write (errmsg, '(2a,i0,a,i0,a,es12.4,a,es12.4,a)') trim(label), ': blocks xy and yx differ at offset (', &
                loc(1), ',', loc(2), '): ', set%a(loc(1), loc(2), 1, 2), ' vs ', set%a(loc(1), loc(2), 2, 1), &
                ' (the tangential matrix must be symmetric)'
            return
        end if
        call kernel_symbol(set%a(:, :, 3, 3), set%mx, set%my, szz)
        if (.not. (minval(szz) > 0)) then
            loc = minloc(szz)
            write (errmsg, '(2a,es12.4,a,es12.4,a,i0,a,i0,a)') trim(label), &
                ': block zz is not positive definite: its FFT symbol has minimum ', minval(szz), ' (maximum ', &
                maxval(szz), ') at frequency (', loc(1) - 1, ',', loc(2) - 1, ')'
            return
        end if
        call kernel_symbol(set%a(:, :, 1, 1), set%mx, set%my, sxx)
        call kernel_symbol(set%a(:, :, 2, 2), set%mx, set%my, syy)
        call kernel_symbol(set%a(:, :, 1, 2), set%mx, set%my, sxy)
        ! smallest eigenvalue of [[sxx, sxy], [sxy, syy]] per frequency
        lam = (sxx + syy)/2 - sqrt(((sxx - syy)/2)**2 + sxy**2)
        if (.not. (minval(lam) > 0)) then
            loc = minloc(lam)
            write (errmsg, '(2a,es12.4,a,es12.4,a,i0,a,i0,a)') trim(label), &
                ': the tangential block [xx xy; yx yy] is not positive definite: smallest eigenvalue of its FFT symbol ', &
                minval(lam), ' (largest ', maxval(sxx + syy), ') at frequency (', loc(1) - 1, ',', loc(2) - 1, ')'
            return
        end if
        stat = 0; errmsg = ''
    end subroutine validate_ic_set

    !> Real FFT symbol of an even kernel k(−mx:mx, −my:my) embedded in the circulant of size
    !! 2mx × 2my (offsets −mx+1…mx; the wrap-around slot holds the coefficient at mx).
    subroutine kernel_symbol(k, mx, my, sym)
        integer, intent(in) :: mx, my
        real(dp), intent(in) :: k(-mx:, -my:)
        real(dp), allocatable, intent(out) :: sym(:, :)
        real(dp), allocatable :: r(:, :)
        complex(dp), allocatable :: c(:, :)
        type(c_ptr) :: plan
        integer :: nx, ny, i, j, di, dj
        nx = max(2*mx, 1); ny = max(2*my, 1)
        allocate (r(nx, ny), c(nx/2 + 1, ny))
        do j = 0, ny - 1
            dj = j; if (j > ny/2) dj = j - ny
            do i = 0, nx - 1
                di = i; if (i > nx/2) di = i - nx
                r(i + 1, j + 1) = k(di, dj)
            end do
        end do
        !$omp critical (fc_fftw_planner)
        plan = fftw_plan_dft_r2c_2d(int(ny, c_int), int(nx, c_int), r, c, FFTW_ESTIMATE)
        !$omp end critical (fc_fftw_planner)
        call fftw_execute_dft_r2c(plan, r, c)
        !$omp critical (fc_fftw_planner)
        call fftw_destroy_plan(plan)
        !$omp end critical (fc_fftw_planner)
        sym = real(c, dp)
    end subroutine kernel_symbol

    !> 64-bit FNV-1a hash of `text` as 16 hexadecimal digits (cache key).
    !! The product modulo 2^64 is formed from two 32-bit limbs held in 64-bit integers, so no
    !! signed arithmetic overflows (the prime is 2^40 + 435).
    function hash_text(text) result(h)
        character(len=*), intent(in) :: text
        character(len=16) :: h
        integer(i8), parameter :: mask32 = 4294967295_i8
        integer(i8), parameter :: prime_hi = 256_i8, prime_lo = 435_i8
        integer(i8) :: hi, lo, t
        integer :: i
        hi = int(z'CBF29CE4', i8)   ! FNV offset basis 0xcbf29ce484222325
        lo = int(z'84222325', i8)
        do i = 1, len(text)
            lo = ieor(lo, int(iachar(text(i:i)), i8))
            t = lo*prime_lo
            hi = iand(hi*prime_lo + lo*prime_hi + ishft(t, -32), mask32)
            lo = iand(t, mask32)
        end do
        write (h, '(z8.8,z8.8)') hi, lo
    end function hash_text

    !> Write a set in the fastcontact format (doc/ic_file_format.md) to `path`, atomically:
    !! a temporary file in the same directory renamed over `path` when complete.
    subroutine write_ic_file(path, set, stat, errmsg)
        character(len=*), intent(in) :: path
        type(fc_ic_set), intent(in) :: set
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=:), allocatable :: tmp
        integer :: u, ios, ix, iy
        character(len=msg_len) :: iomsg
        tmp = temp_name(path)
        open (newunit=u, file=tmp, status='replace', action='write', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = 'cannot write '//tmp//': '//trim(iomsg); return
        end if
        write (u, '(a)') '# fastcontact influence coefficients (doc/ic_file_format.md)'
        write (u, '(a)') 'format = fastcontact-ic'
        write (u, '(a,i0)') 'version = ', ic_format_version
        write (u, '(a)') 'content = '//trim(set%content)
        write (u, '(a)') 'source = '//trim(set%source)
        write (u, '(a,es25.17e3)') 'g = ', set%g
        write (u, '(a,es25.17e3)') 'nu = ', set%nu
        write (u, '(a,es25.17e3)') 'dx = ', set%dx
        write (u, '(a,es25.17e3)') 'dy = ', set%dy
        write (u, '(a,i0)') 'mx = ', set%mx
        write (u, '(a,i0)') 'my = ', set%my
        write (u, '(a)') 'load = '//trim(set%load)
        write (u, '(a)') 'model = '//trim(set%model)
        write (u, '(a)') 'hash = '//trim(set%hash)
        write (u, '(a)') 'units = mm per N/mm2 (displacement at a cell centre per unit traction on the source cell)'
        write (u, '(a)') 'columns = ix iy zz xx yy xy yx xz zx yz zy'
        write (u, '(a)') 'data'
        do iy = -set%my, set%my
            do ix = -set%mx, set%mx
                write (u, '(i0,1x,i0,9(1x,es25.17e3))', iostat=ios, iomsg=iomsg) ix, iy, set%a(ix, iy, 3, 3), &
                    set%a(ix, iy, 1, 1), set%a(ix, iy, 2, 2), set%a(ix, iy, 1, 2), set%a(ix, iy, 2, 1), &
                    set%a(ix, iy, 1, 3), set%a(ix, iy, 3, 1), set%a(ix, iy, 2, 3), set%a(ix, iy, 3, 2)
                if (ios /= 0) exit
            end do
            if (ios /= 0) exit
        end do
        if (ios == 0) close (u, iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            close (u, status='delete', iostat=ix)
            stat = FC_ERR_IO; errmsg = 'cannot write '//tmp//': '//trim(iomsg); return
        end if
        call rename_file(tmp, path, stat, errmsg)
    end subroutine write_ic_file

    !> Temporary name next to `path` (same directory, so that the rename is atomic).
    function temp_name(path) result(tmp)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: tmp
        character(len=24) :: pid
        interface
            integer(c_int) function c_getpid() bind(c, name='getpid')
                import :: c_int
            end function c_getpid
        end interface
        write (pid, '(i0)') c_getpid()
        tmp = trim(path)//'.tmp'//trim(pid)
    end function temp_name

    !> rename(2): replace `to` by `from` atomically.
    subroutine rename_file(from, to, stat, errmsg)
        character(len=*), intent(in) :: from, to
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        interface
            integer(c_int) function c_rename(a, b) bind(c, name='rename')
                import :: c_int, c_char
                character(kind=c_char), intent(in) :: a(*), b(*)
            end function c_rename
        end interface
        stat = 0; errmsg = ''
        if (c_rename(trim(from)//c_null_char, trim(to)//c_null_char) /= 0) then
            stat = FC_ERR_IO; errmsg = 'cannot rename '//trim(from)//' to '//trim(to)
        end if
    end subroutine rename_file


    !> True when `path` starts like a fastcontact influence-coefficient file.
    logical function is_fastcontact_ic_file(path)
        character(len=*), intent(in) :: path
        integer :: u, ios, n
        character(len=256) :: line
        is_fastcontact_ic_file = .false.
        open (newunit=u, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do n = 1, 5
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (index(line, 'format') == 1 .and. index(line, 'fastcontact-ic') > 0) then
                is_fastcontact_ic_file = .true.; exit
            end if
        end do
        close (u)
    end function is_fastcontact_ic_file

    !> After a checked header (both formats), before the coefficients are allocated and read:
    !! `done` (the reader returns, unit `u` closed) for a file too short for its `lines` data
    !! lines of at least 22 bytes each (eleven numbers of one digit and their separators:
    !! stat = FC_ERR_IO, a truncated file found before a set of up to 4.8 GB is allocated),
    !! or with `header_only` (stat = 0; `set` gets offsets mx, my and the cell size, no
    !! coefficients).  Else stat = FC_ERR_IO for the read that follows.
    subroutine end_of_header(u, path, lines, mx, my, dx, dy, set, header_only, done, stat, errmsg)
        integer, intent(in) :: u, mx, my
        character(len=*), intent(in) :: path
        integer(i8), intent(in) :: lines
        real(dp), intent(in) :: dx, dy
        type(fc_ic_set), intent(inout) :: set
        logical, intent(in), optional :: header_only
        logical, intent(out) :: done
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer(i8) :: bytes
        done = .true.; stat = FC_ERR_IO; errmsg = ''
        inquire (file=path, size=bytes)
        if (bytes >= 0 .and. bytes < 22*lines) then   ! size unknown (-1): the read finds it
            write (errmsg, '(2a,i0,a,i0,a)') trim(path), ': the header announces ', lines, ' lines of coefficients, '// &
                'at least 22 bytes each, but the file has only ', bytes, ' bytes (truncated?)'
            close (u); return
        end if
        if (present(header_only)) then
            if (header_only) then
                if (allocated(set%a)) deallocate (set%a)
                set%mx = mx; set%my = my; set%dx = dx; set%dy = dy
                close (u); stat = 0; return
            end if
        end if
        done = .false.
    end subroutine end_of_header

    !> Read a fastcontact influence-coefficient file (any version ≤ ic_format_version) and
    !! validate it ([[validate_ic_set]]).
    subroutine read_ic_file(path, set, stat, errmsg, header_only)
        character(len=*), intent(in) :: path
        type(fc_ic_set), intent(inout) :: set
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        !> read and check the header only: `set` gets its offsets, cell size and content, no
        !! coefficients (what a memory estimate needs before the file is loaded)
        logical, intent(in), optional :: header_only
        logical :: done
        integer :: u, ios, line, version, mx, my, ix, iy, jx, jy, p
        real(dp) :: v(9), dx, dy
        character(len=4096) :: buf
        character(len=64) :: key
        character(len=:), allocatable :: val
        character(len=msg_len) :: iomsg
        logical :: have_format
        stat = FC_ERR_IO
        open (newunit=u, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            errmsg = 'cannot open influence-coefficient file '//trim(path)//': '//trim(iomsg); return
        end if
        version = -1; mx = -1; my = -1; dx = 0; dy = 0; have_format = .false.
        set%content = ''; set%source = ''; set%g = 0; set%nu = 0; set%load = 'constant'; set%model = ''; set%hash = ''
        line = 0
        do
            read (u, '(a)', iostat=ios) buf
            if (ios /= 0) then
                errmsg = trim(path)//': header ends before the line "data"'; close (u); return
            end if
            line = line + 1
            if (buf(1:1) == '#' .or. len_trim(buf) == 0) cycle
            if (trim(adjustl(buf)) == 'data') exit
            p = index(buf, '=')
            if (p == 0) then
                write (errmsg, '(2a,i0,a)') trim(path), ': line ', line, ': expected "key = value"'; close (u); return
            end if
            key = adjustl(buf(:p - 1)); val = trim(adjustl(buf(p + 1:)))
            ios = 0
            select case (trim(key))
            case ('format'); have_format = val == 'fastcontact-ic'
            case ('version'); read (val, *, iostat=ios) version
            case ('content'); set%content = val
            case ('source'); set%source = val
            case ('g'); read (val, *, iostat=ios) set%g
            case ('nu'); read (val, *, iostat=ios) set%nu
            case ('dx'); read (val, *, iostat=ios) dx
            case ('dy'); read (val, *, iostat=ios) dy
            case ('mx'); read (val, *, iostat=ios) mx
            case ('my'); read (val, *, iostat=ios) my
            case ('load'); set%load = val
            case ('model'); set%model = val
            case ('hash'); set%hash = val
            case ('units', 'columns')
            case default   ! unknown keys of later minor additions are ignored
            end select
            if (ios /= 0) then
                write (errmsg, '(2a,i0,4a)') trim(path), ': line ', line, ': bad value for ', trim(key), ': ', val
                close (u); return
            end if
        end do
        if (.not. have_format) then
            errmsg = trim(path)//': not a fastcontact influence-coefficient file (no "format = fastcontact-ic")'
            close (u); return
        end if
        if (version < 1 .or. version > ic_format_version) then
            write (errmsg, '(2a,i0,a,i0)') trim(path), ': version = ', version, ' is not supported; this build reads 1 to ', &
                ic_format_version
            close (u); return
        end if
        if (set%content /= 'body' .and. set%content /= 'combined') then
            errmsg = trim(path)//": content = '"//trim(set%content)//"' must be 'body' or 'combined'"; close (u); return
        end if
        if (mx < 0 .or. my < 0 .or. mx > ic_max_offset .or. my > ic_max_offset) then
            write (errmsg, '(2a,i0,a,i0,a,i0)') trim(path), ': mx = ', mx, ', my = ', my, ' must lie in [0, ', ic_max_offset
            errmsg = trim(errmsg)//']'
            close (u); return
        end if
        if (.not. (dx > 0 .and. dy > 0)) then
            write (errmsg, '(2a,es12.4,a,es12.4,a)') trim(path), ': dx = ', dx, ', dy = ', dy, ' must be > 0'
            close (u); return
        end if
        if (set%content == 'body' .and. .not. (set%g > 0 .and. set%nu >= 0 .and. set%nu < 0.5_dp)) then
            write (errmsg, '(2a,es12.4,a,g0.6,a)') trim(path), ': g = ', set%g, ', nu = ', set%nu, &
                ' must satisfy g > 0, 0 <= nu < 0.5 for content body'
            close (u); return
        end if
        call end_of_header(u, path, (2_i8*mx + 1)*(2_i8*my + 1), mx, my, dx, dy, set, header_only, done, stat, errmsg)
        if (done) return
        call ic_set_allocate(set, mx, my, dx, dy)
        do iy = -my, my
            do ix = -mx, mx
                line = line + 1
                read (u, *, iostat=ios, iomsg=iomsg) jx, jy, v
                if (ios /= 0) then
                    write (errmsg, '(2a,i0,a,i0,a,i0,2a)') trim(path), ': line ', line, ': cannot read offset (', ix, ',', &
                        iy, '): ', trim(iomsg)
                    close (u); return
                end if
                if (jx /= ix .or. jy /= iy) then
                    write (errmsg, '(2a,i0,a,i0,a,i0,a,i0,a,i0,a)') trim(path), ': line ', line, ': offset (', jx, ',', jy, &
                        ') where (', ix, ',', iy, ') was expected'
                    close (u); return
                end if
                set%a(ix, iy, 3, 3) = v(1); set%a(ix, iy, 1, 1) = v(2); set%a(ix, iy, 2, 2) = v(3)
                set%a(ix, iy, 1, 2) = v(4); set%a(ix, iy, 2, 1) = v(5); set%a(ix, iy, 1, 3) = v(6)
                set%a(ix, iy, 3, 1) = v(7); set%a(ix, iy, 2, 3) = v(8); set%a(ix, iy, 3, 2) = v(9)
            end do
        end do
        close (u)
        call validate_ic_set(set, path, stat, errmsg)
    end subroutine read_ic_file

end module fc_icfile
