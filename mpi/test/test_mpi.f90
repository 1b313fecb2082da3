!> Tests of the MPI package; run with `mpirun -np 2` (any number of ranks ≥ 1 works).
!! Every rank also runs the serial solver on the whole (small) grid and compares its own
!! rows, so the distributed code is checked against the serial one, and the serial
!! periodic cell against the wavy surface's analytic full-contact pressure.
!! Ends with `N passed, N failed` (counted over all ranks) and exit status 1 on failure.
program test_mpi
    use mpi
    use fc_kinds, only: dp, pi, FC_CONVERGED
    use fc_geometry, only: fc_grid, make_grid, fc_rough_params, quadratic_gap, punch_rough_gap, wavy_gap, &
        rough_heights
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_periodic, only: build_periodic_normal_operator
    use fcm_fftw_mpi, only: fftw_mpi_init
    use fc_threads, only: set_thread_count
    use fcm_norm
    use fcm_geometry
    use fcm_batch_tests, only: batch_tests
    use fcm_test_support, only: mpi_test_procedure, run_mpi_test
    use fcm_dist_tests, only: dist_driver_tests
    implicit none
    integer :: provided, ierr, rank, nprocs, npass, nfail, tot(2)
    character(len=32) :: only
    call mpi_init_thread(MPI_THREAD_FUNNELED, provided, ierr)   ! OpenMP regions make no MPI calls
    call set_thread_count(0)   ! OMP_NUM_THREADS if set, else 1 thread per rank
    call fftw_mpi_init()
    call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
    call mpi_comm_size(MPI_COMM_WORLD, nprocs, ierr)
    only = ''
    if (command_argument_count() >= 1) call get_command_argument(1, only)
    npass = 0; nfail = 0
    call run('dist_product_equals_serial', test_products)
    call run('dist_bccg_equals_serial_hertz_approach', test_hertz_approach)
    call run('dist_bccg_equals_serial_rough_force', test_rough_force)
    call run('dist_rough_rows_bitwise', test_rough_rows)
    call run('dist_uneven_rows', test_uneven)
    call run('dist_grid_too_small_rejected', test_too_small)
    call run('periodic_wavy_full_contact', test_wavy_full_contact)
    call run('dist_periodic_equals_serial', test_periodic_dist)
    call batch_tests(only, npass, nfail)
    call dist_driver_tests(only, npass, nfail)
    tot = [npass, nfail]
    call mpi_allreduce(MPI_IN_PLACE, tot, 2, MPI_INTEGER, MPI_MIN, MPI_COMM_WORLD, ierr)
    npass = tot(1)
    call mpi_allreduce(MPI_IN_PLACE, nfail, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD, ierr)
    if (rank == 0) write (*, '(i0,a,i0,a,i0,a)') npass, ' passed, ', nfail, ' failed (', nprocs, ' ranks)'
    call mpi_finalize(ierr)
    if (nfail > 0 .or. npass == 0) stop 1

contains

    subroutine run(name, test)
        character(len=*), intent(in) :: name
        procedure(mpi_test_procedure) :: test
        call run_mpi_test(name, only, test, npass, nfail)
    end subroutine run

    subroutine check(msg, cond, text)
        character(len=:), allocatable, intent(inout) :: msg
        logical, intent(in) :: cond
        character(len=*), intent(in) :: text
        if (allocated(msg)) return
        if (.not. cond) msg = text
    end subroutine check

    function num(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: b
        write (b, '(es12.4)') x
        s = trim(adjustl(b))
    end function num

    subroutine steel(mat)
        type(fc_material), intent(out) :: mat
        integer :: stat
        character(len=200) :: m
        mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, m)
    end subroutine steel

    !> Distributed products with A and with the preconditioner equal the serial FFT products
    !! (same operator, different FFT sizes and order of sums): 1e−12 relative.
    subroutine test_products(msg)
        character(len=:), allocatable, intent(out) :: msg
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fcm_normal_operator) :: dop
        real(dp), allocatable :: x(:, :), ys(:, :), yd(:, :)
        integer :: stat, j0, j1
        character(len=256) :: em
        call steel(mat)
        call make_grid(grid, 48, 40, -3.0_dp, 2.0_dp, -1.5_dp, 2.5_dp, stat, em)
        call build_normal_operator(nop, mat, grid)
        call build_dist_normal_operator(dop, mat, grid, MPI_COMM_WORLD, stat, em)
        call check(msg, stat == 0, 'build: '//trim(em))
        if (allocated(msg)) return
        allocate (x(48, 40), ys(48, 40))
        call deterministic(x)
        j0 = dop%lay%y0 + 1; j1 = dop%lay%y0 + dop%lay%nyl
        allocate (yd(48, dop%lay%nyl))
        call nop%a_zz%apply(x, ys)
        call dop%lay%apply(dop%sym_a, x(:, j0:j1), yd)
        call check(msg, maxval(abs(yd - ys(:, j0:j1))) <= 1e-12_dp*maxval(abs(ys)), &
            'A x differs from serial by '//num(maxval(abs(yd - ys(:, j0:j1)))/maxval(abs(ys))))
        call nop%precond%apply(x, ys)
        call dop%lay%apply(dop%sym_m, x(:, j0:j1), yd)
        call check(msg, maxval(abs(yd - ys(:, j0:j1))) <= 1e-11_dp*maxval(abs(ys)), &
            'M x differs from serial by '//num(maxval(abs(yd - ys(:, j0:j1)))/maxval(abs(ys))))
    end subroutine test_products

    !> Reproducible values in [−0.3, 0.7) independent of the compiler's random generator.
    subroutine deterministic(x)
        real(dp), intent(out) :: x(:, :)
        integer :: i, j
        do j = 1, size(x, 2)
            do i = 1, size(x, 1)
                x(i, j) = modulo(0.6180339887_dp*(i + 37*j) + 0.1_dp*sin(real(i*j, dp)), 1.0_dp) - 0.3_dp
            end do
        end do
    end subroutine deterministic

    !> Serial and distributed results on one grid: pressures to 1e−8 of pmax, force, approach
    !! and contact count (solved to tol 1e−10, so that both are the same solution to
    !! round-off whatever the path).
    subroutine compare(msg, grid, h0, approach, fn)
        character(len=:), allocatable, intent(inout) :: msg
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: h0(:, :)
        real(dp), intent(in), optional :: approach, fn
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fcm_normal_operator) :: dop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: rs, rd
        integer :: stat, j0, j1
        character(len=256) :: em
        call steel(mat)
        set%tol = 1e-10_dp
        call build_normal_operator(nop, mat, grid)
        call build_dist_normal_operator(dop, mat, grid, MPI_COMM_WORLD, stat, em)
        call check(msg, stat == 0, 'build: '//trim(em))
        if (allocated(msg)) return
        j0 = dop%lay%y0 + 1; j1 = dop%lay%y0 + dop%lay%nyl
        if (present(approach)) then
            call solve_normal(nop, h0, set, rs, stat, em, approach=approach)
            call solve_dist_normal(dop, h0(:, j0:j1), set, rd, stat, em, approach=approach)
        else
            call solve_normal(nop, h0, set, rs, stat, em, fn=fn)
            call solve_dist_normal(dop, h0(:, j0:j1), set, rd, stat, em, fn=fn)
        end if
        call check(msg, stat == 0, 'solve: '//trim(em))
        call check(msg, rs%status == FC_CONVERGED .and. rd%status == FC_CONVERGED, 'not converged: '//trim(rd%message))
        if (allocated(msg)) return
        call check(msg, maxval(abs(rd%pn - rs%pn(:, j0:j1))) <= 1e-8_dp*rs%pmax, &
            'pressure differs by '//num(maxval(abs(rd%pn - rs%pn(:, j0:j1)))/rs%pmax))
        call check(msg, abs(rd%fn - rs%fn) <= 1e-10_dp*rs%fn, 'force '//num(rd%fn)//' vs serial '//num(rs%fn))
        call check(msg, abs(rd%approach - rs%approach) <= 1e-9_dp*abs(rs%approach), &
            'approach '//num(rd%approach)//' vs serial '//num(rs%approach))
        call check(msg, rd%ncon == rs%ncon, 'contact counts differ')
        call check(msg, abs(rd%pmax - rs%pmax) <= 1e-8_dp*rs%pmax, 'pmax differs')
    end subroutine compare

    subroutine test_hertz_approach(msg)
        character(len=:), allocatable, intent(out) :: msg
        type(fc_grid) :: grid
        integer :: stat
        character(len=256) :: em
        call make_grid(grid, 64, 64, -2.0_dp, 2.0_dp, -1.6_dp, 1.6_dp, stat, em)
        call compare(msg, grid, quadratic_gap(grid, 30.0_dp, 20.0_dp), approach=0.05_dp)
    end subroutine test_hertz_approach

    subroutine test_rough_force(msg)
        character(len=:), allocatable, intent(out) :: msg
        type(fc_grid) :: grid
        type(fc_rough_params) :: par
        real(dp), allocatable :: h0(:, :)
        integer :: stat
        character(len=256) :: em
        call make_grid(grid, 64, 64, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, stat, em)
        par%sigma = 1e-3_dp
        allocate (h0(64, 64))
        call punch_rough_gap(grid, 1.9_dp, par, h0)
        call compare(msg, grid, h0, fn=2000.0_dp)
    end subroutine test_rough_force

    !> Rows generated where they are used equal the whole-grid surface bit for bit.
    subroutine test_rough_rows(msg)
        character(len=:), allocatable, intent(out) :: msg
        type(fc_grid) :: grid
        type(fc_rough_params) :: par
        real(dp), allocatable :: z(:, :), hq(:, :), hw(:, :), hp(:, :), hl(:, :)
        integer :: stat, j0, j1
        character(len=256) :: em
        call make_grid(grid, 40, 36, -1.0_dp, 1.2_dp, -0.9_dp, 1.0_dp, stat, em)
        j0 = 1 + (36*rank)/nprocs; j1 = (36*(rank + 1))/nprocs
        allocate (z(40, 36), hp(40, 36), hl(40, j0:j1))
        par%seed = 77
        call punch_rough_gap(grid, 1.5_dp, par, hp)
        call punch_rough_gap_rows(grid, 1.5_dp, par, j0, j1, hl)
        call check(msg, all(hl == hp(:, j0:j1)), 'rough punch rows differ from the serial surface')
        hq = quadratic_gap(grid, 3.0_dp, 5.0_dp)
        call quadratic_gap_rows(grid, 3.0_dp, 5.0_dp, j0, j1, hl)
        call check(msg, all(hl == hq(:, j0:j1)), 'quadratic rows differ')
        hw = wavy_gap(grid, 0.01_dp, 0.7_dp, 0.9_dp)
        call wavy_gap_rows(grid, 0.01_dp, 0.7_dp, 0.9_dp, j0, j1, hl)
        call check(msg, all(hl == hw(:, j0:j1)), 'wavy rows differ')
        call rough_heights(grid, par, z)
        call check(msg, abs(sqrt(sum(z**2)/size(z)) - par%sigma) < 0.3_dp*par%sigma, 'rough sigma off')
    end subroutine test_rough_rows

    !> Rows not divisible by the ranks, nx ≠ ny, force prescribed on a Hertz profile.
    subroutine test_uneven(msg)
        character(len=:), allocatable, intent(out) :: msg
        type(fc_grid) :: grid
        integer :: stat
        character(len=256) :: em
        call make_grid(grid, 50, 45, -2.0_dp, 2.0_dp, -1.6_dp, 1.6_dp, stat, em)
        call compare(msg, grid, quadratic_gap(grid, 30.0_dp, 20.0_dp), fn=500.0_dp)
    end subroutine test_uneven

    subroutine test_too_small(msg)
        character(len=:), allocatable, intent(out) :: msg
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fcm_normal_operator) :: dop
        integer :: stat
        character(len=256) :: em
        call steel(mat)
        call make_grid(grid, 8, 1, -2.0_dp, 2.0_dp, -1.6_dp, 1.6_dp, stat, em)
        call build_dist_normal_operator(dop, mat, grid, MPI_COMM_WORLD, stat, em)
        call check(msg, stat /= 0 .and. index(em, 'ny = 1') > 0, 'ny = 1 must be rejected naming ny: '//trim(em))
        call make_grid(grid, 9, 8, -2.0_dp, 2.0_dp, -1.6_dp, 1.6_dp, stat, em)
        call build_dist_normal_operator(dop, mat, grid, MPI_COMM_WORLD, stat, em, periodic=.true.)
        call check(msg, stat /= 0 .and. index(em, 'even') > 0, 'odd nx must be rejected for periodic: '//trim(em))
    end subroutine test_too_small

    !> Wavy surface h0 = A(1 − cos 2πx/λ) on a periodic cell of one wavelength, mean pressure
    !! p̄ above p* = π E* A/λ: full contact, p = p̄ + p* cos 2πx/λ (Johnson §13.2, E* = G/(1−ν)
    !! for Kalker's combined constants).  64 elements per wavelength: the piecewise-constant
    !! discretisation changes the amplitude by O((π/64)²) ≈ 0.3 %; tolerance 1 % of p*.
    subroutine test_wavy_full_contact(msg)
        character(len=:), allocatable, intent(out) :: msg
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        real(dp), allocatable :: h0(:, :), pex(:, :)
        real(dp) :: lam, amp, pstar, pbar
        integer :: stat, i
        character(len=256) :: em
        call steel(mat)
        lam = 1.0_dp; amp = 1e-4_dp
        call make_grid(grid, 64, 4, 0.0_dp, lam, 0.0_dp, 4*lam/64, stat, em)
        h0 = wavy_gap(grid, amp, lam, 0.0_dp)
        pstar = pi*mat%g/(1 - mat%nu)*amp/lam
        pbar = 1.5_dp*pstar
        call build_periodic_normal_operator(nop, mat, grid, stat, em)
        call check(msg, stat == 0, 'build: '//trim(em))
        if (allocated(msg)) return
        set%tol = 1e-10_dp
        call solve_normal(nop, h0, set, res, stat, em, fn=pbar*lam*grid%ymax)
        call check(msg, stat == 0 .and. res%status == FC_CONVERGED, 'solve: '//trim(em)//' '//trim(res%message))
        if (allocated(msg)) return
        allocate (pex(64, 4))
        do i = 1, 64
            pex(i, :) = pbar + pstar*cos(2*pi*grid%x(i)/lam)
        end do
        call check(msg, res%ncon == 64*4, 'not in full contact')
        call check(msg, maxval(abs(res%pn - pex)) <= 0.01_dp*pstar, &
            'pressure differs from Johnson by '//num(maxval(abs(res%pn - pex))/pstar)//' p*')
        ! below p̄ = p* the contact must open (the analytic full-contact bound)
        call solve_normal(nop, h0, set, res, stat, em, fn=0.9_dp*pstar*lam*grid%ymax)
        call check(msg, res%ncon < 64*4, 'p̄ = 0.9 p* must not be full contact')
    end subroutine test_wavy_full_contact

    !> Distributed periodic cell equals the serial periodic operator (rough cell, force).
    subroutine test_periodic_dist(msg)
        character(len=:), allocatable, intent(out) :: msg
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fcm_normal_operator) :: dop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: rs, rd
        type(fc_rough_params) :: par
        real(dp), allocatable :: z(:, :), x(:, :), ys(:, :), yd(:, :)
        integer :: stat, j0, j1
        character(len=256) :: em
        call steel(mat)
        call make_grid(grid, 64, 48, 0.0_dp, 1.0_dp, 0.0_dp, 0.75_dp, stat, em)
        call build_periodic_normal_operator(nop, mat, grid, stat, em)
        call build_dist_normal_operator(dop, mat, grid, MPI_COMM_WORLD, stat, em, periodic=.true.)
        call check(msg, stat == 0, 'build: '//trim(em))
        if (allocated(msg)) return
        j0 = dop%lay%y0 + 1; j1 = dop%lay%y0 + dop%lay%nyl
        allocate (x(64, 48), ys(64, 48), yd(64, dop%lay%nyl), z(64, 48))
        call deterministic(x)
        call nop%a_zz%apply(x, ys)
        call dop%lay%apply(dop%sym_a, x(:, j0:j1), yd)
        call check(msg, maxval(abs(yd - ys(:, j0:j1))) <= 1e-12_dp*maxval(abs(ys)), &
            'periodic A x differs from serial by '//num(maxval(abs(yd - ys(:, j0:j1)))/maxval(abs(ys))))
        par%sigma = 2e-3_dp; par%seed = 5
        call rough_heights(grid, par, z)
        set%tol = 1e-10_dp
        call solve_normal(nop, -z, set, rs, stat, em, fn=100.0_dp)
        call solve_dist_normal(dop, -z(:, j0:j1), set, rd, stat, em, fn=100.0_dp)
        call check(msg, rs%status == FC_CONVERGED .and. rd%status == FC_CONVERGED, 'not converged: '//trim(rd%message))
        if (allocated(msg)) return
        call check(msg, rd%ncon == rs%ncon .and. rs%ncon < 64*48 .and. rs%ncon > 0, 'partial contact expected, same count')
        call check(msg, maxval(abs(rd%pn - rs%pn(:, j0:j1))) <= 1e-8_dp*rs%pmax, &
            'periodic pressure differs by '//num(maxval(abs(rd%pn - rs%pn(:, j0:j1)))/rs%pmax))
        call check(msg, abs(rd%approach - rs%approach) <= 1e-9_dp*abs(rs%approach), 'periodic approach differs')
    end subroutine test_periodic_dist

end program test_mpi
