!> fastcontact-api-soak — resident memory of a long flat-API session (doc/reliability.md).
!!
!!     fastcontact-api-soak [--calls N] [--n NX] [--no-rss]
!!
!! One handle, N calculations (default 100000) of a small Hertz contact (NX × NX elements,
!! default 8) through the flat API: each step sets a new normal force, calculates, reads
!! forces and tractions; every 1000th step changes the grid spacing (operators and FFT plans
!! are rebuilt), every 500th step adds a tangential shift (tangential operator), and every
!! 100th step a second handle is created, used and finalised.  The resident set size
!! (VmRSS) is sampled after 10 % of the steps and at the end: it must not grow by more than
!! 2 MB (exit status 1 otherwise, or on any error code other than 0); --no-rss skips that
!! check (under valgrind the resident size is valgrind's own).
program api_soak
    use, intrinsic :: iso_c_binding, only: c_int, c_double
    use fc_legacy
    implicit none
    integer :: ncalls, n, k, i
    integer(c_int) :: h, h2, ierr, nh
    real(c_double) :: fn, fx, fy, mz, scale
    real(c_double), allocatable :: pn(:), px(:), py(:)
    integer :: rss_start, rss_end, rss_peak, rss
    logical :: check_rss = .true.
    character(len=32) :: arg
    ncalls = 100000; n = 8
    do i = 1, command_argument_count()
        call get_command_argument(i, arg)
        if (arg == '--calls') then
            call get_command_argument(i + 1, arg); read (arg, *) ncalls
        else if (arg == '--no-rss') then
            check_rss = .false.
        else if (arg == '--n') then
            call get_command_argument(i + 1, arg); read (arg, *) n
        end if
    end do
    allocate (pn(n*n), px(n*n), py(n*n))
    call fc_init(h, ierr); call ok('fc_init')
    call fc_set_material(h, 82000.0_c_double, 82000.0_c_double, 0.28_c_double, 0.28_c_double, ierr)
    call ok('fc_set_material')
    call fc_set_friction(h, 0.3_c_double, ierr); call ok('fc_set_friction')
    rss_start = 0; rss_peak = 0
    do k = 1, ncalls
        if (mod(k, 1000) == 1) then
            scale = 1 + 0.01_c_double*mod(k/1000, 2)       ! alternate the spacing: rebuild
            call fc_set_grid(h, n, n, -10*scale, 10*scale, -6*scale, 6*scale, ierr); call ok('fc_set_grid')
            call fc_set_gap_quadratic(h, 300.0_c_double, 163.0_c_double, ierr); call ok('fc_set_gap_quadratic')
        end if
        call fc_set_normal_force(h, 80000 + mod(k, 7)*100.0_c_double, ierr); call ok('fc_set_normal_force')
        if (mod(k, 500) == 0) then
            call fc_set_shifts(h, -1.0e-4_c_double, 0.0_c_double, 0.0_c_double, ierr); call ok('fc_set_shifts')
        end if
        call fc_calculate(h, ierr); call ok('fc_calculate')
        call fc_get_forces(h, fn, fx, fy, mz, ierr); call ok('fc_get_forces')
        call fc_get_tractions(h, n*n, pn, px, py, ierr); call ok('fc_get_tractions')
        if (mod(k, 100) == 0) then
            call fc_init(h2, ierr); call ok('fc_init (second handle)')
            call fc_set_material(h2, 200.0_c_double, 200.0_c_double, 0.42_c_double, 0.42_c_double, ierr)
            call fc_set_grid(h2, n, n, -1.3_c_double, 1.3_c_double, -1.3_c_double, 1.3_c_double, ierr)
            call fc_set_gap_quadratic(h2, 50.0_c_double, 50.0_c_double, ierr)
            call fc_set_normal_force(h2, 9.0_c_double, ierr)
            call fc_calculate(h2, ierr); call ok('fc_calculate (second handle)')
            call fc_finalize(h2, ierr); call ok('fc_finalize (second handle)')
        end if
        if (k == max(1, ncalls/10)) rss_start = resident_kb()
        rss = resident_kb(); if (mod(k, 1000) == 0) rss_peak = max(rss_peak, rss)
    end do
    rss_end = resident_kb()
    rss_peak = max(rss_peak, rss_end)
    call fc_finalize(h, ierr); call ok('fc_finalize')
    deallocate (pn, px, py)
    call fc_get_nhandles(nh, ierr)
    write (*, '(7(a,i0))') 'api-soak: ', ncalls, ' calculations on ', n, 'x', n, &
        ': VmRSS after 10 % ', rss_start, ' kB, peak ', rss_peak, ' kB, end ', rss_end, ' kB; live handles ', nh
    if ((check_rss .and. rss_end - rss_start > 2048) .or. nh /= 0) then
        write (*, '(a)') 'api-soak: FAILED (resident memory grew by more than 2 MB or handles left)'
        stop 1
    end if
    write (*, '(a,i0,a)') 'api-soak: ok (growth ', rss_end - rss_start, ' kB)'
contains
    subroutine ok(what)
        character(len=*), intent(in) :: what
        character(len=512) :: msg
        character :: buf(512)
        integer(c_int) :: e
        integer :: j
        if (ierr == FCL_OK) return
        call fc_get_error_message(h, buf, 512_c_int, e)
        msg = ''
        do j = 1, 512
            if (buf(j) == char(0)) exit
            msg(j:j) = buf(j)
        end do
        write (*, '(a,i0,a,i0,a)') 'api-soak: step ', k, ': '//what//' returned ', ierr, ': '//trim(msg)
        stop 1
    end subroutine ok

    integer function resident_kb()
        character(len=128) :: line
        integer :: u, ios
        resident_kb = -1
        open (newunit=u, file='/proc/self/status', action='read', status='old', iostat=ios)
        if (ios /= 0) return
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (line(1:6) == 'VmRSS:') then
                read (line(7:), *, iostat=ios) resident_kb
                exit
            end if
        end do
        close (u)
    end function resident_kb
end program api_soak
