!> fastcontact-bench-table-io: cost of the element tables and of reading a text table
!! (issue 14), against the run-time library's formatted I/O that the package used before.
!!
!! Rows (CSV on stdout and in --out FILE):  what,n_values,bytes,seconds_new,seconds_runtime,speedup
!!
!! * csv_512      the 512² Hertz normal table (262 144 rows) by write_case_csv, and the same
!!                rows written with the run-time library (`ES23.15E3` through internal and
!!                sequential formatted writes: the previous implementation, byte-identical output);
!! * csv_240x200  a tangential 240×200 table (all eight numbers per row non-trivial);
!! * npy_512      the same 512² table as .npy (write_case_npy; no run-time counterpart);
!! * read_1024    a 1024² text table of h0 (8 values per line, 24 MB) by read_gap_table, and
!!                by the previous reader (4096-character lines, every token checked by a
!!                list-directed READ, then the line READ again);
!! seconds: CPU time (cpu_time), median of --repeat runs (default 5).
!!
!! Usage: fastcontact-bench-table-io [--repeat N] [--out FILE] [--dir DIR]
program fastcontact_bench_table_io
    use fc_kinds, only: dp
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap, read_gap_table
    use fc_output, only: write_case_csv, write_case_npy
    use fc_table_io, only: put_real
    implicit none
    integer :: repeat, iarg, unit, stat, k
    character(len=512) :: out_file, dir, arg
    character(len=256) :: msg
    type(fc_grid) :: g512, g240, g1024
    real(dp), allocatable :: pn(:, :), gap(:, :), px(:, :), py(:, :), sx(:, :), sy(:, :), h(:, :)
    integer, allocatable :: st(:, :)
    real(dp), allocatable :: tn(:), tr(:)

    repeat = 5; out_file = 'doc/bench_table_io.csv'; dir = '/tmp'
    iarg = 1
    do while (iarg <= command_argument_count())
        call get_command_argument(iarg, arg)
        select case (trim(arg))
        case ('--repeat'); iarg = iarg + 1; call get_command_argument(iarg, arg); read (arg, *) repeat
        case ('--out'); iarg = iarg + 1; call get_command_argument(iarg, out_file)
        case ('--dir'); iarg = iarg + 1; call get_command_argument(iarg, dir)
        case default
            write (*, '(a)') 'usage: fastcontact-bench-table-io [--repeat N] [--out FILE] [--dir DIR]'; error stop 1
        end select
        iarg = iarg + 1
    end do
    allocate (tn(repeat), tr(repeat))
    open (newunit=unit, file=trim(out_file), status='replace', action='write')
    call emit('what,n_values,bytes,seconds_new,seconds_runtime,speedup')

    ! Hertz-like normal table 512²
    call make_grid(g512, 512, 512, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
    gap = quadratic_gap(g512, 300.0_dp, 163.0_dp) - 0.1091_dp
    pn = max(0.0_dp, -1.0e4_dp*gap)
    gap = max(gap, 0.0_dp)
    do k = 1, repeat
        tn(k) = timed_csv(g512, .false.)
        tr(k) = timed_runtime(g512, .false.)
    end do
    call row('csv_512', 8*size(pn), file_bytes(trim(dir)//'/fc_bench_table.csv'))
    do k = 1, repeat
        tn(k) = timed_npy(g512)
        tr(k) = -1
    end do
    call row('npy_512', 8*size(pn), file_bytes(trim(dir)//'/fc_bench_table.npy'))

    ! tangential 240×200
    call make_grid(g240, 240, 200, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
    gap = quadratic_gap(g240, 50.0_dp, 50.0_dp) - 0.02_dp
    pn = max(0.0_dp, -200*gap)
    px = -0.3_dp*pn; py = 0.1_dp*pn; sx = 1.0e-4_dp*gap; sy = -3.0e-5_dp*gap
    allocate (st(240, 200))
    st = merge(1, 0, pn > 0)
    where (pn > 0 .and. pn < 2) st = 2
    do k = 1, repeat
        tn(k) = timed_csv(g240, .true.)
        tr(k) = timed_runtime(g240, .true.)
    end do
    call row('csv_240x200', 8*size(pn), file_bytes(trim(dir)//'/fc_bench_table.csv'))

    ! reading a 1024² text table
    call make_grid(g1024, 1024, 1024, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
    call write_text_table(g1024, trim(dir)//'/fc_bench_h0.txt')
    allocate (h(1024, 1024))
    do k = 1, repeat
        tn(k) = timed_read_new(g1024)
        tr(k) = timed_read_runtime(g1024)
    end do
    call row('read_1024', size(h), file_bytes(trim(dir)//'/fc_bench_h0.txt'))
    close (unit)
    call delete(trim(dir)//'/fc_bench_table.csv'); call delete(trim(dir)//'/fc_bench_table.npy')
    call delete(trim(dir)//'/fc_bench_h0.txt')

contains

    subroutine emit(line)
        character(len=*), intent(in) :: line
        write (*, '(a)') line
        write (unit, '(a)') line
    end subroutine emit

    subroutine row(what, nvalues, bytes)
        character(len=*), intent(in) :: what
        integer, intent(in) :: nvalues
        integer, intent(in) :: bytes
        character(len=256) :: line
        real(dp) :: a, b
        a = median(tn); b = median(tr)
        if (b > 0) then
            write (line, '(a,",",i0,",",i0,",",f0.4,",",f0.4,",",f0.1)') what, nvalues, bytes, a, b, b/a
        else
            write (line, '(a,",",i0,",",i0,",",f0.4,",,")') what, nvalues, bytes, a
        end if
        call emit(trim(line))
    end subroutine row

    real(dp) function median(t)
        real(dp), intent(in) :: t(:)
        real(dp) :: s(size(t)), x
        integer :: i, j
        s = t
        do i = 2, size(s)
            x = s(i); j = i - 1
            do while (j >= 1)
                if (s(j) <= x) exit
                s(j + 1) = s(j); j = j - 1
            end do
            s(j + 1) = x
        end do
        median = s((size(s) + 1)/2)
    end function median

    real(dp) function timed_csv(g, tang) result(t)
        type(fc_grid), intent(in) :: g
        logical, intent(in) :: tang
        real(dp) :: t0, t1
        call cpu_time(t0)
        if (tang) then
            call write_case_csv(trim(dir)//'/fc_bench_table.csv', g, pn, gap, stat, msg, st, px, py, sx, sy)
        else
            call write_case_csv(trim(dir)//'/fc_bench_table.csv', g, pn, gap, stat, msg)
        end if
        call cpu_time(t1)
        t = t1 - t0
        if (stat /= 0) error stop 'write_case_csv failed'
    end function timed_csv

    real(dp) function timed_npy(g) result(t)
        type(fc_grid), intent(in) :: g
        real(dp) :: t0, t1
        call cpu_time(t0)
        call write_case_npy(trim(dir)//'/fc_bench_table.npy', g, pn, gap, stat, msg)
        call cpu_time(t1)
        t = t1 - t0
        if (stat /= 0) error stop 'write_case_npy failed'
    end function timed_npy

    !> The previous writer: each number through an internal ES23.15E3 write, each row one
    !! sequential formatted record.
    real(dp) function timed_runtime(g, tang) result(t)
        type(fc_grid), intent(in) :: g
        logical, intent(in) :: tang
        real(dp) :: t0, t1
        integer :: u, i, j
        character(len=1) :: c
        call cpu_time(t0)
        open (newunit=u, file=trim(dir)//'/fc_bench_table.csv', status='replace', action='write')
        write (u, '(a)') 'ix,iy,x,y,status,pn,px,py,sx,sy,gap'
        do j = 1, g%ny
            do i = 1, g%nx
                c = merge('A', 'E', pn(i, j) > 0)
                write (u, '(i0,a,i0,a)', advance='no') i, ',', j, ','
                if (tang) then
                    write (u, '(a)') rt(g%x(i))//','//rt(g%y(j))//','//c//','//rt(pn(i, j))//','//rt(px(i, j))//','// &
                        rt(py(i, j))//','//rt(sx(i, j))//','//rt(sy(i, j))//','//rt(gap(i, j))
                else
                    write (u, '(a)') rt(g%x(i))//','//rt(g%y(j))//','//c//','//rt(pn(i, j))//',0,0,0,0,'//rt(gap(i, j))
                end if
            end do
        end do
        close (u)
        call cpu_time(t1)
        t = t1 - t0
    end function timed_runtime

    function rt(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: b
        write (b, '(es23.15e3)') x
        s = trim(adjustl(b))
    end function rt

    subroutine write_text_table(g, path)
        type(fc_grid), intent(in) :: g
        character(len=*), intent(in) :: path
        integer :: u, i, j, pos
        character(len=256) :: line
        real(dp) :: v(8)
        integer :: n, m
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') '# h0 of a 1024 x 1024 grid, x fastest'
        n = 0
        do j = 1, g%ny
            do i = 1, g%nx
                n = n + 1
                v(mod(n - 1, 8) + 1) = g%x(i)**2/600 + g%y(j)**2/326
                if (mod(n, 8) == 0) then
                    pos = 0
                    do m = 1, 8
                        call put_real(v(m), line, pos)
                        line(pos + 1:pos + 1) = ' '; pos = pos + 1
                    end do
                    write (u, '(a)') line(1:pos - 1)
                end if
            end do
        end do
        close (u)
    end subroutine write_text_table

    real(dp) function timed_read_new(g) result(t)
        type(fc_grid), intent(in) :: g
        real(dp) :: t0, t1
        call cpu_time(t0)
        call read_gap_table(trim(dir)//'/fc_bench_h0.txt', g, h, stat, msg)
        call cpu_time(t1)
        t = t1 - t0
        if (stat /= 0) error stop 'read_gap_table failed'
    end function timed_read_new

    !> The previous reader (until issue 14): lines of up to 4096 characters, each token
    !! checked by a list-directed READ (count_numbers), then the line read again.
    real(dp) function timed_read_runtime(g) result(t)
        type(fc_grid), intent(in) :: g
        real(dp) :: t0, t1, buf(512), hh(g%nx*g%ny)
        integer :: u, ios, n, nline, k
        character(len=4096) :: line
        call cpu_time(t0)
        open (newunit=u, file=trim(dir)//'/fc_bench_h0.txt', status='old', action='read')
        n = 0
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            line = adjustl(line)
            if (len_trim(line) == 0) cycle
            if (line(1:1) == '#' .or. line(1:1) == '!') cycle
            nline = count_numbers(line)
            read (line, *) (buf(k), k=1, nline)
            hh(n + 1:n + nline) = buf(1:nline); n = n + nline
        end do
        close (u)
        call cpu_time(t1)
        t = t1 - t0
        if (any(abs(hh - reshape(h, [size(h)])) > 0)) error stop 'readers disagree'
    end function timed_read_runtime

    integer function count_numbers(line) result(cnt)
        character(len=*), intent(in) :: line
        integer :: i, start, ios
        real(dp) :: v
        logical :: in_tok
        cnt = 0; in_tok = .false.; start = 1
        do i = 1, len_trim(line) + 1
            if (i <= len_trim(line)) then
                if (line(i:i) /= ' ' .and. line(i:i) /= ',' .and. line(i:i) /= char(9)) then
                    if (.not. in_tok) then
                        in_tok = .true.; start = i
                    end if
                    cycle
                end if
            end if
            if (in_tok) then
                read (line(start:i - 1), *, iostat=ios) v
                if (ios /= 0) then
                    cnt = -1; return
                end if
                cnt = cnt + 1; in_tok = .false.
            end if
        end do
    end function count_numbers

    integer function file_bytes(path)
        character(len=*), intent(in) :: path
        inquire (file=path, size=file_bytes)
    end function file_bytes

    subroutine delete(path)
        character(len=*), intent(in) :: path
        integer :: u, ios
        open (newunit=u, file=path, status='old', iostat=ios)
        if (ios == 0) close (u, status='delete')
    end subroutine delete

end program fastcontact_bench_table_io
