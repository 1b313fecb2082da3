!> fastcontact-bench-mg2d: one 2D strip solve (thesis ch. 3) per process, for whole-process
!! CPU timing (`/usr/bin/time -f %U`) of the strip multigrid at large n.
!!
!! Usage: fastcontact-bench-mg2d [--mp 1|2|3] [--k K] [--cycle 11|10|01] [--one-grid] [--repeat R] [--threads N]
!!   --mp       model problem (default 1)
!!   --k        n = 2^K unknowns (default 20)
!!   --cycle    V(1,1) (11, default), V(1,0) (10) or V(0,1) (01)
!!   --one-grid the one-grid FFT+RSM solver instead of multigrid
!!   --repeat   solve R times in the process (default 1)
!!   --threads  threads for the FFTs and element loops (default 0: OMP_NUM_THREADS, else 1)
!! Prints one line per solve: mp, n, cycle, iterations, factor, residual, status and the
!! solver's own wall time (set-up included), then the process CPU time of all solves.
program fastcontact_bench_mg2d
    use fc_kinds, only: dp, status_name
    use fc_mg2d, only: fc_strip_problem, fc_mg2d_settings, fc_mg2d_result, strip_model_problem
    use fc_mg2d, only: solve_strip_mg, solve_strip_fft_rsm
    use fc_threads, only: set_thread_count
    implicit none
    type(fc_strip_problem) :: prob
    type(fc_mg2d_settings) :: set
    type(fc_mg2d_result) :: res
    character(len=256) :: arg, msg
    integer :: mp, k, cyc, rep, r, iarg, ios, stat, nthreads
    logical :: one_grid
    real :: c0, c1

    mp = 1; k = 20; cyc = 11; rep = 1; one_grid = .false.; nthreads = 0
    iarg = 1
    do while (iarg <= command_argument_count())
        call get_command_argument(iarg, arg)
        select case (trim(arg))
        case ('--mp'); call int_arg(mp, 1, 3)
        case ('--k'); call int_arg(k, 2, 24)
        case ('--cycle'); call int_arg(cyc, 1, 11)
        case ('--repeat'); call int_arg(rep, 1, 1000)
        case ('--threads'); call int_arg(nthreads, 0, 1024)
        case ('--one-grid'); one_grid = .true.
        case default
            write (*, '(a)') 'usage: fastcontact-bench-mg2d [--mp M] [--k K] [--cycle 11|10|01] [--one-grid] [--repeat R] '// &
                '[--threads N]'
            stop 2
        end select
        iarg = iarg + 1
    end do
    select case (cyc)
    case (11); set%nu1 = 1; set%nu2 = 1
    case (10); set%nu1 = 1; set%nu2 = 0
    case (1); set%nu1 = 0; set%nu2 = 1
    case default
        write (*, '(a,i0,a)') 'fastcontact-bench-mg2d: --cycle ', cyc, ' is not 11, 10 or 01'
        stop 2
    end select
    call set_thread_count(nthreads)
    call cpu_time(c0)
    do r = 1, rep
        call strip_model_problem(mp, 2**k, prob, stat, msg)
        if (stat /= 0) then
            write (*, '(a)') trim(msg); error stop 1
        end if
        if (one_grid) then
            call solve_strip_fft_rsm(prob, set, res, stat, msg)
        else
            call solve_strip_mg(prob, set, res, stat, msg)
        end if
        if (stat /= 0) then
            write (*, '(a)') trim(msg); error stop 1
        end if
        write (*, '(a,i0,a,i0,a,i0,i0,a,i0,a,es15.8,a,es15.8,a,a,a,f0.4)') 'mp', mp, ' n=', 2**k, ' V(', set%nu1, set%nu2, &
            ') cycles=', res%iterations, ' factor=', res%factor, ' residual=', res%residual, ' ', &
            status_name(res%status), ' seconds=', res%cpu_seconds
    end do
    call cpu_time(c1)
    write (*, '(a,f0.3)') 'process cpu seconds (solves): ', c1 - c0

contains

    subroutine int_arg(v, lo, hi)
        integer, intent(inout) :: v
        integer, intent(in) :: lo, hi
        character(len=64) :: val
        iarg = iarg + 1
        call get_command_argument(iarg, val)
        read (val, *, iostat=ios) v
        if (ios /= 0 .or. v < lo .or. v > hi) then
            write (*, '(a,i0,a,i0,a)') 'fastcontact-bench-mg2d: '//trim(arg)//' needs an integer in [', lo, ', ', hi, &
                '], got "'//trim(val)//'"'
            stop 2
        end if
    end subroutine int_arg

end program fastcontact_bench_mg2d
