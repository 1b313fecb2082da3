!> fastcontact-bench-parallel: the same cases with 1 and with N threads, alternating
!! (doc/parallel.md).  Each run is one batch-driver run of a one-case namelist (operator
!! set-up, solve and JSON included; no CSV table), after [[set_thread_count]].
!!
!!   fastcontact-bench-parallel [--threads N] [--repeats R] [--quick] [--out FILE]
!!
!! Cases: Hertz Test I on 1024² (BCCG, prescribed approach) and the Cattaneo sphere of
!! thesis Table 4.1 case 4 on 240×200 (BCCG + TangCG); --quick: 256² and 120×100.
!! One CSV row per run: case, threads, repeat, wall seconds, process CPU seconds (all
!! threads), the driver's exit status.  Speed-up = median wall(1) / median wall(N),
!! printed at the end.
program bench_parallel
    use, intrinsic :: iso_fortran_env, only: int64, output_unit
    use fc_kinds, only: dp
    use fc_driver, only: run_driver
    use fc_threads, only: fc_openmp_enabled
    implicit none
    integer :: nthreads, repeats, i, r, c, t, u, code, nul
    logical :: quick
    character(len=256) :: arg, out_file
    character(len=*), parameter :: dir = 'build/bench-parallel'
    character(len=16), parameter :: cases(2) = [character(len=16) :: 'hertz', 'cattaneo']
    real(dp), allocatable :: wall(:, :, :)
    integer(int64) :: t0, t1, rate
    real(dp) :: c0, c1
    character(len=128) :: args(3)
    nthreads = 2; repeats = 3; quick = .false.; out_file = 'doc/bench_parallel_threads.csv'
    i = 1
    do while (i <= command_argument_count())
        call get_command_argument(i, arg)
        select case (trim(arg))
        case ('--threads'); i = i + 1; call get_command_argument(i, arg); read (arg, *) nthreads
        case ('--repeats'); i = i + 1; call get_command_argument(i, arg); read (arg, *) repeats
        case ('--quick'); quick = .true.
        case ('--out'); i = i + 1; call get_command_argument(i, out_file)
        case default
            write (*, '(a)') 'usage: fastcontact-bench-parallel [--threads N] [--repeats R] [--quick] [--out FILE]'
            stop 1
        end select
        i = i + 1
    end do
    if (nthreads < 1 .or. nthreads > 256 .or. repeats < 1 .or. repeats > 100) then
        write (*, '(a)') '--threads must lie in [1, 256] and --repeats in [1, 100]'
        stop 1
    end if
    if (.not. fc_openmp_enabled()) write (*, '(a)') 'note: built without OpenMP: every run uses one thread'
    call execute_command_line('mkdir -p '//dir)
    call write_cases(1)
    call write_cases(nthreads)
    allocate (wall(2, 2, repeats))
    open (newunit=u, file=trim(out_file), status='replace', action='write')
    write (u, '(a)') 'case,threads,repeat,wall_s,cpu_s,exit'
    open (newunit=nul, file='/dev/null', action='write')
    do r = 1, repeats
        do c = 1, 2
            do t = 1, 2
                call system_clock(t0, rate); call cpu_time(c0)
                write (args(1), '(a,i0,a)') dir//'/'//trim(cases(c))//'_', merge(1, nthreads, t == 1), '.nml'
                args(2) = '--out'; args(3) = dir//'/out'
                call run_driver(args, code, nul, nul)
                call system_clock(t1); call cpu_time(c1)
                wall(t, c, r) = real(t1 - t0, dp)/rate
                write (u, '(a,",",i0,",",i0,",",f0.4,",",f0.4,",",i0)') trim(cases(c)), merge(1, nthreads, t == 1), r, &
                    wall(t, c, r), c1 - c0, code
                flush (u)
            end do
        end do
    end do
    close (u); close (nul)
    do c = 1, 2
        write (output_unit, '(a,a,f8.3,a,f8.3,a,f6.2)') trim(cases(c)), ': median wall 1 thread ', &
            median(wall(1, c, :)), ' s, threads ', median(wall(2, c, :)), ' s, speed-up ', &
            median(wall(1, c, :))/median(wall(2, c, :))
    end do

contains

    subroutine write_cases(nt)
        integer, intent(in) :: nt
        integer :: v
        character(len=64) :: solver
        write (solver, '(a,i0,a)') '&solver threads = ', nt, ' /'
        open (newunit=v, file=dir//'/hertz_'//itoa(nt)//'.nml', status='replace', action='write')
        write (v, '(a)') "&case name = 'hertz' /"
        write (v, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
        if (quick) then
            write (v, '(a)') "&grid nx = 256, ny = 256, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /"
        else
            write (v, '(a)') "&grid nx = 1024, ny = 1024, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /"
        end if
        write (v, '(a)') "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"
        write (v, '(a)') "&normal approach = 0.1091 /"
        write (v, '(a)') "&output table = .false. /"
        write (v, '(a)') trim(solver)
        close (v)
        open (newunit=v, file=dir//'/cattaneo_'//itoa(nt)//'.nml', status='replace', action='write')
        write (v, '(a)') "&case name = 'cattaneo', problem = 'normal+tangential' /"
        write (v, '(a)') "&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /"
        if (quick) then
            write (v, '(a)') "&grid nx = 120, ny = 100, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /"
        else
            write (v, '(a)') "&grid nx = 240, ny = 200, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /"
        end if
        write (v, '(a)') "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"
        write (v, '(a)') "&normal fn = 9.1954 /"
        write (v, '(a)') "&tangential mu = 0.4, xi = 0.0021, eta = 0.0010, phi = 0.003 /"
        write (v, '(a)') "&output table = .false. /"
        write (v, '(a)') trim(solver)
        close (v)
    end subroutine write_cases

    function itoa(i) result(t)
        integer, intent(in) :: i
        character(len=:), allocatable :: t
        character(len=12) :: b
        write (b, '(i0)') i
        t = trim(b)
    end function itoa

    real(dp) function median(x)
        real(dp), intent(in) :: x(:)
        real(dp) :: y(size(x)), tmp
        integer :: a, b
        y = x
        do a = 2, size(y)
            tmp = y(a); b = a - 1
            do while (b >= 1)
                if (y(b) <= tmp) exit
                y(b + 1) = y(b); b = b - 1
            end do
            y(b + 1) = tmp
        end do
        median = y((size(y) + 1)/2)
        if (mod(size(y), 2) == 0) median = (y(size(y)/2) + y(size(y)/2 + 1))/2
    end function median

end program bench_parallel
