!> fastcontact-bench-omp-loops: cost of the solvers' vector operations with 1 and 2 OpenMP
!! threads against the grid size, to choose the threshold below which they stay serial
!! (fc_threads `omp_min_elements`, doc/parallel.md §5.3).
!!
!!   fastcontact-bench-omp-loops [--threads N] [--reps R] [--out FILE]
!!
!! One "step" is the vector work of a CG iteration in miniature: an axpy (y ← y + a x) and a
!! dot product over an n-element array.  Three variants per size, alternating:
!! `serial` (plain loops), `region` (one `parallel do` per loop, as in the solvers) and
!! `orphaned` (one parallel region around all repetitions, `omp do` worksharing inside).
!! CSV: n, variant, threads, nanoseconds per step, nanoseconds per element and step.
program bench_omp_loops
    use, intrinsic :: iso_fortran_env, only: int64, output_unit
    use fc_kinds, only: dp
    !$ use omp_lib, only: omp_set_num_threads
    implicit none
    integer, parameter :: sizes(*) = [1024, 2048, 4096, 8192, 16384, 32768, 65536, 131072, 262144, 1048576]
    integer :: nthreads, reps, i, k, r, n, u, v
    character(len=256) :: arg, out_file
    real(dp), allocatable :: x(:), y(:)
    real(dp) :: s, acc, ns(3)
    integer(int64) :: t0, t1, rate
    character(len=8), parameter :: names(3) = [character(len=8) :: 'serial', 'region', 'orphaned']
    nthreads = 2; reps = 0; out_file = 'doc/bench_omp_loops.csv'
    i = 1
    do while (i <= command_argument_count())
        call get_command_argument(i, arg)
        select case (trim(arg))
        case ('--threads'); i = i + 1; call get_command_argument(i, arg); read (arg, *) nthreads
        case ('--reps'); i = i + 1; call get_command_argument(i, arg); read (arg, *) reps
        case ('--out'); i = i + 1; call get_command_argument(i, out_file)
        case default
            write (*, '(a)') 'usage: fastcontact-bench-omp-loops [--threads N] [--reps R] [--out FILE]'
            stop 1
        end select
        i = i + 1
    end do
    if (nthreads < 1 .or. nthreads > 64 .or. reps < 0 .or. reps > 10**7) then
        write (*, '(a)') '--threads must lie in [1, 64], --reps in [0, 1e7] (0: about 2e8 element operations per size)'
        stop 1
    end if
    !$ call omp_set_num_threads(nthreads)
    open (newunit=u, file=trim(out_file), status='replace', action='write')
    write (u, '(a)') 'n,variant,threads,ns_per_step,ns_per_element'
    acc = 0
    do k = 1, size(sizes)
        n = sizes(k)
        r = reps
        if (r == 0) r = max(20, 200000000/n)
        allocate (x(n), y(n))
        x = 1.0e-3_dp; y = 1
        do v = 1, 3
            call system_clock(t0, rate)
            select case (v)
            case (1); call run_serial()
            case (2); call run_region()
            case (3); call run_orphaned()
            end select
            call system_clock(t1)
            ns(v) = 1.0e9_dp*real(t1 - t0, dp)/rate/r
            write (u, '(i0,",",a,",",i0,",",f0.1,",",f0.4)') n, trim(names(v)), merge(1, nthreads, v == 1), ns(v), ns(v)/n
        end do
        write (output_unit, '(a,i8,a,3f12.1,a,2f7.2)') 'n =', n, '  ns/step serial, region, orphaned:', ns, &
            '  speed-up:', ns(1)/ns(2), ns(1)/ns(3)
        deallocate (x, y)
    end do
    close (u)
    if (acc == 12345) write (*, *) acc   ! keep the sums alive

contains

    subroutine run_serial()
        integer :: it, j
        do it = 1, r
            do j = 1, n
                y(j) = y(j) + 1.0e-9_dp*x(j)
            end do
            s = 0
            do j = 1, n
                s = s + x(j)*y(j)
            end do
            acc = acc + s
        end do
    end subroutine run_serial

    subroutine run_region()
        integer :: it, j
        do it = 1, r
            !$omp parallel do schedule(static)
            do j = 1, n
                y(j) = y(j) + 1.0e-9_dp*x(j)
            end do
            !$omp end parallel do
            s = 0
            !$omp parallel do schedule(static) reduction(+:s)
            do j = 1, n
                s = s + x(j)*y(j)
            end do
            !$omp end parallel do
            acc = acc + s
        end do
    end subroutine run_region

    subroutine run_orphaned()
        integer :: it, j
        !$omp parallel private(it, j)
        do it = 1, r
            !$omp do schedule(static)
            do j = 1, n
                y(j) = y(j) + 1.0e-9_dp*x(j)
            end do
            !$omp end do
            !$omp single
            s = 0
            !$omp end single
            !$omp do schedule(static) reduction(+:s)
            do j = 1, n
                s = s + x(j)*y(j)
            end do
            !$omp end do
            !$omp single
            acc = acc + s
            !$omp end single
        end do
        !$omp end parallel
    end subroutine run_orphaned

end program bench_omp_loops
