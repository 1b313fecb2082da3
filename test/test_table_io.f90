!> Suite `table_io`: the fast number formatter and parser, the element table as CSV and
!! as `.npy`, and the reader of text tables.
module test_table_io
    use, intrinsic :: iso_fortran_env, only: int32, int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
    use fc_kinds, only: dp
    use fc_table_io
    use fc_geometry, only: fc_grid, make_grid
    use fc_output, only: write_case_csv, write_case_npy
    use fc_driver, only: run_driver
    use fc_testing
    implicit none
    private
    public :: collect_table_io

contains

    subroutine collect_table_io(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('format_equals_runtime_es23', test_format), &
            new_unittest('parse_equals_runtime_read', test_parse), &
            new_unittest('csv_parses_back_to_printed_precision', test_csv_roundtrip), &
            new_unittest('tables_in_row_blocks_equal_whole', test_csv_blocks), &
            new_unittest('npy_roundtrip', test_npy_roundtrip), &
            new_unittest('read_table_layout_and_errors', test_read_table), &
            new_unittest('driver_table_format_keys', test_driver_format) ]
    end subroutine collect_table_io

    !> put_real gives the run-time library's ES23.15E3 text (without blanks) exactly, for
    !! random bit patterns (every exponent), values near powers of ten, exact ties at the
    !! 17th digit (rounded to even), signed zeros and the magnitudes handed to the run time.
    subroutine test_format(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: k, nbad
        real(dp) :: x, r
        integer(int64) :: bits
        character(len=40) :: a
        character(len=:), allocatable :: first
        nbad = 0
        do k = 1, 30000
            call random_number(r)
            select case (mod(k, 5))
            case (0)
                bits = int(r*real(huge(1_int64), dp), int64)
                x = transfer(bits, 1.0_dp)
                ! NaN and Inf (exponent bits all set) replaced without comparing: a signalling
                ! NaN would trap in the sanitizer run
                if (iand(shiftr(bits, 52), int(z'7FF', int64)) == int(z'7FF', int64)) x = 1.5_dp
            case (1)
                x = (r - 0.5_dp)*10.0_dp**(mod(k, 41) - 20)
            case (2)
                x = 1.0e15_dp + 0.5_dp*mod(k, 97)        ! exact ties at the 17th digit
            case (3)
                x = 10.0_dp**(mod(k, 601) - 300)*(1 + (r - 0.5_dp)*1.0e-15_dp)
            case default
                x = -real(mod(k, 1000), dp)/1024
            end select
            call compare(x)
        end do
        call compare(0.0_dp); call compare(-0.0_dp); call compare(huge(1.0_dp)); call compare(-tiny(1.0_dp))
        call compare(1.0e-300_dp); call compare(9.9999999999999999e22_dp); call compare(0.1_dp)
        if (.not. allocated(first)) first = ''
        call check(error, nbad == 0, 'put_real differs from the run-time ES23.15E3 in some cases, first: '//first)
        if (allocated(error)) return
        x = ieee_value(x, ieee_positive_inf)   ! (not huge*2: the sanitizer run traps overflow)
        call check(error, real_text(x) == 'null', 'Inf is written as null')
    contains
        subroutine compare(v)
            real(dp), intent(in) :: v
            write (a, '(es23.15e3)') v
            a = adjustl(a)
            if (real_text(v) /= trim(a)) then
                nbad = nbad + 1
                if (.not. allocated(first)) first = trim(a)//' written as '//real_text(v)
            end if
        end subroutine compare
    end subroutine test_format

    !> parse_real returns exactly what a list-directed READ returns, and rejects non-numbers.
    subroutine test_parse(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=32), parameter :: good(14) = [character(len=32) :: '1', '-2.5', '+0.125', '.5', '5.', &
            '1e3', '1.5D-3', '-0.0', '3.14159265358979323846', '123456789012345678901', '1e-300', &
            '0.000001234', '7.0E+022', '2.2250738585072014e-308']
        character(len=16), parameter :: bad(5) = [character(len=16) :: 'abc', '1.2.3', '1e', '--1', 'x1']
        integer :: k, nbad
        real(dp) :: v, ref, x
        logical :: ok
        character(len=40) :: a
        do k = 1, size(good)
            call parse_real(trim(good(k)), v, ok)
            a = good(k)
            read (a, *) ref
            call check(error, ok .and. v == ref .and. (sign(1.0_dp, v) == sign(1.0_dp, ref)), &
                'parse_real('//trim(good(k))//') = run-time read')
        end do
        do k = 1, size(bad)
            call parse_real(trim(bad(k)), v, ok)
            call check(error, .not. ok, 'parse_real rejects '//trim(bad(k)))
        end do
        nbad = 0
        do k = 1, 20000
            call random_number(x)
            x = (x - 0.3_dp)*10.0_dp**(mod(k, 31) - 15)
            select case (mod(k, 3))
            case (0); write (a, '(g0)') x
            case (1); write (a, '(es14.6)') x
            case default; write (a, '(f30.8)') x
            end select
            a = adjustl(a)
            call parse_real(trim(a), v, ok)
            read (a, *) ref
            if (.not. ok .or. v /= ref) nbad = nbad + 1
        end do
        call check(error, nbad == 0, 'parse_real = run-time read on 20000 formatted randoms')
    end subroutine test_parse

    !> The element table written in consecutive blocks of rows (as the ranks of a distributed
    !! solve write it: the first block replaces the file with the header, the others append
    !! their rows numbered from `iy_first`) is byte for byte the table written at once, for
    !! the tangential and the normal form and for the `.npy` form (whose first block's
    !! header counts the whole table); appending to a missing file is an error.
    subroutine test_csv_blocks(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        real(dp), allocatable :: pn(:, :), gap(:, :), px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer, allocatable :: st(:, :)
        real(dp), allocatable :: xc(:), yc(:)
        integer :: stat, i, j, b, form
        integer, parameter :: cuts(4) = [0, 2, 3, 5]   ! blocks of rows 1–2, 3, 4–5
        character(len=512) :: msg
        character(len=:), allocatable :: whole, blocks
        character(len=*), parameter :: p1 = 'build/test_table_io_whole.csv', p2 = 'build/test_table_io_blocks.csv'
        call make_grid(grid, 7, 5, -1.0_dp, 2.0_dp, -3.0_dp, 0.5_dp, stat, msg)
        call sample(grid, pn, gap, px, py, sx, sy, st)
        xc = [(grid%x(i), i=1, grid%nx)]; yc = [(grid%y(j), j=1, grid%ny)]
        do form = 1, 2
            if (form == 1) then
                call write_element_table_csv(p1, xc, yc, pn, gap, stat, msg, st, px, py, sx, sy)
            else
                call write_element_table_csv(p1, xc, yc, pn, gap, stat, msg)
            end if
            call check(error, stat == 0, 'whole table: '//trim(msg))
            if (allocated(error)) return
            do b = 1, size(cuts) - 1
                associate (j0 => cuts(b) + 1, j1 => cuts(b + 1))
                    if (form == 1) then
                        call write_element_table_csv(p2, xc, yc(j0:j1), pn(:, j0:j1), gap(:, j0:j1), stat, msg, &
                            st(:, j0:j1), px(:, j0:j1), py(:, j0:j1), sx(:, j0:j1), sy(:, j0:j1), iy_first=j0, append=b > 1)
                    else
                        call write_element_table_csv(p2, xc, yc(j0:j1), pn(:, j0:j1), gap(:, j0:j1), stat, msg, &
                            iy_first=j0, append=b > 1)
                    end if
                end associate
                call check(error, stat == 0, 'block: '//trim(msg))
                if (allocated(error)) return
            end do
            whole = file_bytes(p1); blocks = file_bytes(p2)
            call check(error, len(whole) > 0 .and. whole == blocks, merge('tangential', 'normal    ', form == 1)// &
                ' table in blocks differs from the whole table')
            if (allocated(error)) return
        end do
        ! the .npy form: the first block's header counts the whole table
        call write_element_table_npy(p1, xc, yc, pn, gap, stat, msg, st, px, py, sx, sy)
        do b = 1, size(cuts) - 1
            associate (j0 => cuts(b) + 1, j1 => cuts(b + 1))
                call write_element_table_npy(p2, xc, yc(j0:j1), pn(:, j0:j1), gap(:, j0:j1), stat, msg, &
                    st(:, j0:j1), px(:, j0:j1), py(:, j0:j1), sx(:, j0:j1), sy(:, j0:j1), iy_first=j0, append=b > 1, &
                    ny_total=grid%ny)
            end associate
        end do
        whole = file_bytes(p1); blocks = file_bytes(p2)
        call check(error, len(whole) > 0 .and. whole == blocks, '.npy table in blocks differs from the whole table')
        if (allocated(error)) return
        call delete_file(p1); call delete_file(p2)
        call write_element_table_csv(p2, xc, yc, pn, gap, stat, msg, iy_first=1, append=.true.)
        call check(error, stat /= 0 .and. index(msg, p2) > 0, 'appending to a missing file: an error naming it')
    end subroutine test_csv_blocks

    !> A tangential table written by write_case_csv parses back (run-time read) to the values
    !! to the printed precision (16 significant digits: 5e-16 relative), with the rows, the
    !! coordinates and the status letters in place; the normal form writes zeros for px..sy.
    subroutine test_csv_roundtrip(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        real(dp), allocatable :: pn(:, :), gap(:, :), px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer, allocatable :: st(:, :)
        integer :: stat, u, i, j, ix, iy, nrow, ios
        character(len=512) :: msg, line
        character(len=1) :: letter
        real(dp) :: v(9)
        character(len=*), parameter :: path = 'build/test_table_io.csv'
        logical :: values_ok, rows_ok
        call make_grid(grid, 7, 5, -1.0_dp, 2.0_dp, -3.0_dp, 0.5_dp, stat, msg)
        call sample(grid, pn, gap, px, py, sx, sy, st)
        call write_case_csv(path, grid, pn, gap, stat, msg, st, px, py, sx, sy)
        call check(error, stat == 0, 'write_case_csv: '//trim(msg))
        if (allocated(error)) return
        open (newunit=u, file=path, status='old', action='read')
        read (u, '(a)') line
        call check(error, trim(line) == 'ix,iy,x,y,status,pn,px,py,sx,sy,gap', 'header')
        values_ok = .true.; rows_ok = .true.; nrow = 0
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            nrow = nrow + 1
            call split_row(line, ix, iy, letter, v)
            i = mod(nrow - 1, grid%nx) + 1; j = (nrow - 1)/grid%nx + 1
            if (ix /= i .or. iy /= j) rows_ok = .false.
            if (letter /= 'EAS'(st(i, j) + 1:st(i, j) + 1)) rows_ok = .false.
            if (.not. close16(v(1), grid%x(i)) .or. .not. close16(v(2), grid%y(j))) values_ok = .false.
            if (.not. close16(v(3), pn(i, j)) .or. .not. close16(v(4), px(i, j)) .or. .not. close16(v(5), py(i, j)) &
                .or. .not. close16(v(6), sx(i, j)) .or. .not. close16(v(7), sy(i, j)) &
                .or. .not. close16(v(8), gap(i, j))) values_ok = .false.
        end do
        close (u)
        call check(error, nrow == grid%nx*grid%ny, 'one row per element')
        call check(error, rows_ok, 'ix, iy and status letters of every row')
        call check(error, values_ok, 'every value parses back to 16 significant digits')
        ! normal form: status from pn, px..sy written as 0
        call write_case_csv(path, grid, pn, gap, stat, msg)
        open (newunit=u, file=path, status='old', action='read')
        read (u, '(a)') line
        read (u, '(a)') line
        close (u, status='delete')
        call split_row(line, ix, iy, letter, v)
        call check(error, letter == merge('A', 'E', pn(1, 1) > 0) .and. all(v(4:7) == 0) .and. close16(v(8), gap(1, 1)), &
            'normal form of the first row: '//trim(line))
    contains
        subroutine split_row(text, ix, iy, letter, v)
            character(len=*), intent(in) :: text
            integer, intent(out) :: ix, iy
            character(len=1), intent(out) :: letter
            real(dp), intent(out) :: v(9)
            character(len=512) :: t
            integer :: c
            ! status letter is the 5th field: replace it by 0 so that one list-directed read works
            t = text
            c = index(t, ',E,') + index(t, ',A,') + index(t, ',S,')
            letter = t(c + 1:c + 1)
            t(c + 1:c + 1) = '0'
            read (t, *) ix, iy, v(1), v(2), v(9), v(3), v(4), v(5), v(6), v(7), v(8)
        end subroutine split_row
    end subroutine test_csv_roundtrip

    pure logical function close16(a, b)
        real(dp), intent(in) :: a, b
        close16 = abs(a - b) <= 5.0e-16_dp*abs(b)*1.0000001_dp
    end function close16

    !> The .npy file has the format-1.0 header (magic, version, 64-byte aligned header with
    !! the field list and the shape) and records that read back bit for bit.
    subroutine test_npy_roundtrip(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        real(dp), allocatable :: pn(:, :), gap(:, :), px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer, allocatable :: st(:, :)
        integer :: stat, u, hlen, i, j
        character(len=512) :: msg
        character(len=10) :: pre
        character(len=:), allocatable :: header
        integer(int32) :: ix, iy
        real(dp) :: x, y, v(6)
        character(len=1) :: letter
        logical :: same
        character(len=*), parameter :: path = 'build/test_table_io.npy'
        call make_grid(grid, 6, 4, 0.0_dp, 1.0_dp, 0.0_dp, 2.0_dp, stat, msg)
        call sample(grid, pn, gap, px, py, sx, sy, st)
        call write_case_npy(path, grid, pn, gap, stat, msg, st, px, py, sx, sy)
        call check(error, stat == 0, 'write_case_npy: '//trim(msg))
        if (allocated(error)) return
        open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read')
        read (u) pre
        hlen = iachar(pre(9:9)) + 256*iachar(pre(10:10))
        allocate (character(len=hlen) :: header)
        read (u) header
        call check(error, pre(1:8) == achar(147)//'NUMPY'//achar(1)//achar(0), 'magic and version 1.0')
        call check(error, mod(10 + hlen, 64) == 0 .and. header(hlen:hlen) == achar(10), 'header aligned, ends in newline')
        call check(error, index(header, "'shape': (24,)") > 0 .and. index(header, "'fortran_order': False") > 0, &
            'shape and order: '//header)
        call check(error, index(header, "('ix', '<i4'), ('iy', '<i4'), ('x', '<f8'), ('y', '<f8'), ('status', '|S1'), "// &
            "('pn', '<f8'), ('px', '<f8'), ('py', '<f8'), ('sx', '<f8'), ('sy', '<f8'), ('gap', '<f8')") > 0, &
            'fields: '//header)
        same = .true.
        do j = 1, grid%ny
            do i = 1, grid%nx
                read (u) ix, iy, x, y, letter, v
                same = same .and. ix == i .and. iy == j .and. x == grid%x(i) .and. y == grid%y(j) .and. &
                    letter == 'EAS'(st(i, j) + 1:st(i, j) + 1) .and. &
                    all(v == [pn(i, j), px(i, j), py(i, j), sx(i, j), sy(i, j), gap(i, j)])
            end do
        end do
        read (u, iostat=stat) letter
        close (u, status='delete')
        call check(error, same, 'records read back bit for bit')
        call check(error, stat /= 0, 'nothing after the last record')
    end subroutine test_npy_roundtrip

    !> Text tables: several values per line, comma/tab/blank separators, CRLF line ends,
    !! comment and blank lines; wrong counts and non-numbers are errors naming the file
    !! and the line.
    subroutine test_read_table(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = 'build/test_table_io.txt'
        real(dp) :: vals(6)
        integer :: u, stat
        character(len=512) :: msg
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') '# heights'
        write (u, '(a)') '  ! another comment'
        write (u, '(a)') '1.0, 2.5e-3'//achar(9)//'-3'//achar(13)
        write (u, '(a)') ''
        write (u, '(a)') '  4.25D0 .5 1234567890123456789012'
        close (u)
        call read_real_table(path, vals, stat, msg)
        call check(error, stat == 0, 'read: '//trim(msg))
        call check(error, all(vals == [1.0_dp, 2.5e-3_dp, -3.0_dp, 4.25_dp, 0.5_dp, 1234567890123456789012.0_dp]), &
            'values in order')
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') '1 2 3'
        write (u, '(a)') '4 five 6'
        close (u)
        call read_real_table(path, vals, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'line 2') > 0 .and. index(msg, 'five') > 0, 'bad token: '//trim(msg))
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') '1 2 3 4 5'
        close (u)
        call read_real_table(path, vals, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'has 5 values, expected nx*ny = 6') > 0, 'too few: '//trim(msg))
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') '1 2 3 4 5 6 7'
        close (u, status='keep')
        call read_real_table(path, vals, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'more than nx*ny = 6') > 0, 'too many: '//trim(msg))
        open (newunit=u, file=path, status='old')
        close (u, status='delete')
        call read_real_table(path, vals, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'cannot open') > 0, 'missing file: '//trim(msg))
    end subroutine test_read_table

    !> The batch driver's `&output table_format`: 'both' writes the CSV and the .npy with the
    !! same pressures, 'npy' only the .npy, a bad value is an input error naming the key.
    subroutine test_driver_format(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: dir = 'build/test_table_io_driver'
        character(len=1), parameter :: nl = achar(10)
        character(len=:), allocatable :: base
        character(len=256) :: args(3), line
        character(len=512) :: errors
        integer :: code, u, uerr, ios, k, hlen, ix, iy
        logical :: has_csv, has_npy, same
        character(len=10) :: pre
        character(len=:), allocatable :: header
        character(len=1) :: letter
        real(dp) :: x, y, v(6), pcsv(256)
        call execute_command_line("rm -rf '"//dir//"' && mkdir -p '"//dir//"'")
        base = '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl// &
            "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"//nl//'&normal approach = 0.1091 /'//nl
        call run("&case name = 'both' /"//nl//base//"&output table_format = 'both' /"//nl// &
            "&case name = 'onlynpy' /"//nl//"&output table_format = 'NPY' /"//nl, code)
        call check(error, code == 0, 'driver exit code 0: '//trim(errors))
        inquire (file=dir//'/both.csv', exist=has_csv); inquire (file=dir//'/both.npy', exist=has_npy)
        call check(error, has_csv .and. has_npy, "table_format = 'both' writes both.csv and both.npy")
        inquire (file=dir//'/onlynpy.csv', exist=has_csv); inquire (file=dir//'/onlynpy.npy', exist=has_npy)
        call check(error, has_npy .and. .not. has_csv, "table_format = 'NPY' writes only onlynpy.npy")
        if (allocated(error)) return
        ! CSV pressures (column 6) against the .npy records
        open (newunit=u, file=dir//'/both.csv', status='old', action='read')
        read (u, '(a)') line
        do k = 1, 256
            read (u, '(a)') line
            line = line(1:index(line, ',A,') + index(line, ',E,'))//line(index(line, ',A,') + index(line, ',E,') + 3:)
            read (line, *) ix, iy, x, y, pcsv(k)
        end do
        close (u)
        open (newunit=u, file=dir//'/both.npy', access='stream', form='unformatted', status='old', action='read')
        read (u) pre
        hlen = iachar(pre(9:9)) + 256*iachar(pre(10:10))
        allocate (character(len=hlen) :: header)
        read (u) header
        same = index(header, "'shape': (256,)") > 0
        do k = 1, 256
            read (u, iostat=ios) ix, iy, x, y, letter, v
            same = same .and. ios == 0 .and. close16(pcsv(k), v(1)) .and. (letter == 'A' .eqv. v(1) > 0)
        end do
        close (u)
        call check(error, same, 'the .npy pressures equal the CSV pressures (16 digits), status from pn > 0')
        call run("&case name = 'bad' /"//nl//base//"&output table_format = 'xls' /"//nl, code)
        call check(error, code == 1 .and. index(errors, "&output table_format = 'xls'") > 0, &
            'bad table_format: exit 1 and a message naming the key: '//trim(errors))
        call execute_command_line("rm -rf '"//dir//"'")
    contains
        subroutine run(text, code)
            character(len=*), intent(in) :: text
            integer, intent(out) :: code
            integer :: uin
            open (newunit=uin, file=dir//'/cases.nml', status='replace', action='write')
            write (uin, '(a)') text
            close (uin)
            open (newunit=u, file=dir//'/report.txt', status='replace', action='write')
            open (newunit=uerr, file=dir//'/errors.txt', status='replace', action='write')
            args(1) = dir//'/cases.nml'; args(2) = '--out'; args(3) = dir
            call run_driver(args, code, report_unit=u, error_unit=uerr)
            close (u)
            close (uerr)
            errors = ''
            open (newunit=uerr, file=dir//'/errors.txt', status='old', action='read')
            read (uerr, '(a)', iostat=ios) errors
            close (uerr)
        end subroutine run
    end subroutine test_driver_format

    !> A sample tangential solution with every kind of value: zeros, negatives, tiny and
    !! large magnitudes, all three states.
    subroutine sample(grid, pn, gap, px, py, sx, sy, st)
        type(fc_grid), intent(in) :: grid
        real(dp), allocatable, intent(out) :: pn(:, :), gap(:, :), px(:, :), py(:, :), sx(:, :), sy(:, :)
        integer, allocatable, intent(out) :: st(:, :)
        integer :: i, j
        allocate (pn(grid%nx, grid%ny), gap(grid%nx, grid%ny), px(grid%nx, grid%ny), py(grid%nx, grid%ny), &
                  sx(grid%nx, grid%ny), sy(grid%nx, grid%ny))
        allocate (st(grid%nx, grid%ny))
        do j = 1, grid%ny
            do i = 1, grid%nx
                st(i, j) = mod(i + j, 3)
                pn(i, j) = merge(0.0_dp, 1234.5678_dp/(i + 0.37_dp*j), st(i, j) == 0)
                px(i, j) = -0.1_dp*pn(i, j)/3
                py(i, j) = 1.0e-12_dp*i - 7.0e-13_dp*j
                sx(i, j) = merge(0.0_dp, 2.0e-7_dp*(i - j)/7, st(i, j) /= 2)
                sy(i, j) = -1.0e5_dp/(i*j)
                gap(i, j) = 1.0e-3_dp*(i - 3.5_dp)**2/9 - 2.0e-4_dp*j
            end do
        end do
    end subroutine sample

end module test_table_io
