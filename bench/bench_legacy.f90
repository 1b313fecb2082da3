!> Benchmark of the flat API (fc_legacy): per-call time of repeated Cattaneo calls
!! (normal force + tangential shift, thesis Table 4.1 case 4 shifts) on 30×25 and 60×50, with
!!   rebuild  — fc_set_reuse(h, 0, 0): kernels and FFT plans rebuilt, cold start, every call
!!   reuse    — operators kept, cold start
!!   reuse+ws — operators kept and the previous solution as warm start (the default)
!! for two call sequences: `same` (identical calls) and `varying` (Fn and ξ vary by ±5 %
!! from call to call, like a time-stepping multibody code).
!!
!!   fpm run --profile release fastcontact-bench-legacy [-- --calls N]
!!
!! Writes a Markdown table to standard output (doc/legacy_api.md quotes it).
program bench_legacy
    use, intrinsic :: iso_fortran_env, only: error_unit
    use fc_kinds, only: dp
    use fc_legacy
    implicit none
    integer :: ncalls, g, m, q, h, ierr, k, itn, itt, sum_n, sum_t, nb, tb, nc
    integer, parameter :: grids(2, 2) = reshape([30, 25, 60, 50], [2, 2])
    character(len=8), parameter :: modes(3) = ['rebuild ', 'reuse   ', 'reuse+ws']
    character(len=8), parameter :: seqs(2) = ['same    ', 'varying ']
    character(len=32) :: arg
    real(dp), parameter :: l = 1.2857_dp, fn0 = 9.1954_dp, xi0 = 0.0021_dp, eta0 = 0.0010_dp, phi0 = 0.003_dp
    real(dp) :: t, fac, fn, fx, fy, mz
    integer(8) :: c0, c1, rate
    ncalls = 1000
    k = 1
    do while (k <= command_argument_count())
        call get_command_argument(k, arg)
        if (arg == '--calls' .and. k < command_argument_count()) then
            k = k + 1
            call get_command_argument(k, arg)
            read (arg, *, iostat=ierr) ncalls
            if (ierr /= 0 .or. ncalls < 1 .or. ncalls > 1000000) then
                write (error_unit, '(a)') 'fastcontact-bench-legacy: --calls needs an integer in [1, 1000000]'
                stop 2
            end if
        else
            write (error_unit, '(a)') 'fastcontact-bench-legacy: unknown argument "'//trim(arg)//'"'
            write (error_unit, '(a)') 'usage: fastcontact-bench-legacy [--calls N]'
            stop 2
        end if
        k = k + 1
    end do
    write (*, '(a,i0,a)') '| grid | sequence | mode | ms/call | normal it/call | tangential it/call | builds |  (', &
        ncalls, ' calls)'
    write (*, '(a)') '|---|---|---|---:|---:|---:|---:|'
    do g = 1, 2
        do q = 1, 2
            do m = 1, 3
                call fc_init(h, ierr)
                call fc_set_material(h, 200.0_dp, 200.0_dp, 0.42_dp, 0.42_dp, ierr)
                call fc_set_grid(h, grids(1, g), grids(2, g), -l, l, -l, l, ierr)
                call fc_set_gap_quadratic(h, 50.0_dp, 50.0_dp, ierr)
                call fc_set_friction(h, 0.4_dp, ierr)
                call fc_set_solver(h, 1, 1, 1e-6_dp, 1000, 3, 1, ierr)
                call fc_set_reuse(h, merge(0, 1, m == 1), merge(1, 0, m == 3), ierr)
                sum_n = 0; sum_t = 0
                call system_clock(c0, rate)
                do k = 1, ncalls
                    fac = 1
                    if (q == 2) fac = 1 + 0.05_dp*sin(0.1_dp*k)
                    call fc_set_normal_force(h, fn0*fac, ierr)
                    call fc_set_shifts(h, xi0*fac, eta0, phi0, ierr)
                    call fc_calculate(h, ierr)
                    if (ierr /= 0) then
                        write (*, '(a,i0)') 'calculate failed, ierr = ', ierr
                        error stop 1
                    end if
                    call fc_get_iterations(h, itn, itt, ierr)
                    sum_n = sum_n + itn; sum_t = sum_t + itt
                end do
                call system_clock(c1)
                t = real(c1 - c0, dp)/rate
                call fc_get_forces(h, fn, fx, fy, mz, ierr)
                call fc_get_rebuilds(h, nb, tb, nc, ierr)
                write (*, '(a,i0,a,i0,a,f9.3,a,f7.1,a,f7.1,a,i0,a)') '| ', grids(1, g), 'x', grids(2, g), ' | ' &
                    //trim(seqs(q))//' | '//trim(modes(m))//' |', 1000*t/ncalls, ' |', real(sum_n, dp)/ncalls, ' |', &
                    real(sum_t, dp)/ncalls, ' | ', nb + tb, ' |'
                call fc_finalize(h, ierr)
            end do
        end do
    end do
end program bench_legacy
