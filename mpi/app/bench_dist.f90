!> Benchmark of the distributed normal solver (doc/parallel.md):
!!
!!   fastcontact-mpi-bench --n N [--case hertz|rough|periodic] [--serial] [--save FILE]
!!                         [--compare FILE] [--tol T] [--csv FILE]
!!
!! `--serial` solves with the serial library (one process, [[fc_norm]] / [[fc_periodic]]);
!! otherwise with [[fcm_norm]] on all ranks of MPI_COMM_WORLD.  `--save` writes the pressure
!! (raw doubles, x fastest) and `--compare` reads such a file and reports the largest
!! pressure difference relative to pmax and the force difference relative to the force.
!! One CSV row per run: peak resident memory per rank (VmHWM, taken before any
!! comparison), set-up and solve wall time, iterations and products.
program bench_dist
    use mpi
    use, intrinsic :: iso_fortran_env, only: int64
    use fc_kinds, only: dp, FC_CONVERGED, status_name
    use fc_geometry, only: fc_grid, make_grid, fc_rough_params, quadratic_gap, punch_rough_gap, rough_heights_rows
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_periodic, only: build_periodic_normal_operator
    use fcm_fftw_mpi, only: fftw_mpi_init
    use fc_threads, only: set_thread_count
    use fcm_norm
    use fcm_geometry
    implicit none
    integer :: provided, ierr, rank, nprocs, n, stat, i, u, nthreads, j0, j1
    character(len=256) :: arg, kind, save_file, compare_file, csv_file, em
    logical :: serial
    real(dp) :: tol, t0, t1, t2, fn_target, fn_other, dpmax, dfn, c1, c2, cpu_solve, load1
    real(dp), allocatable :: h0(:, :), pfull(:, :), pother(:, :), z(:, :)
    type(fc_material) :: mat
    type(fc_grid) :: grid
    type(fc_normal_operator) :: nop
    type(fcm_normal_operator) :: dop
    type(fc_normal_settings) :: set
    type(fc_normal_result) :: res
    type(fc_rough_params) :: par
    integer(int64) :: hwm, hwm_max
    integer :: iters, products
    call mpi_init_thread(MPI_THREAD_FUNNELED, provided, ierr)   ! OpenMP regions make no MPI calls
    call set_thread_count(0)   ! OMP_NUM_THREADS if set, else 1 thread per rank
    call fftw_mpi_init()
    call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
    call mpi_comm_size(MPI_COMM_WORLD, nprocs, ierr)
    n = 256; kind = 'hertz'; serial = .false.; save_file = ''; compare_file = ''; csv_file = ''
    tol = 1.0e-5_dp
    i = 1
    do while (i <= command_argument_count())
        call get_command_argument(i, arg)
        select case (trim(arg))
        case ('--n'); i = i + 1; call get_command_argument(i, arg); read (arg, *) n
        case ('--case'); i = i + 1; call get_command_argument(i, kind)
        case ('--serial'); serial = .true.
        case ('--save'); i = i + 1; call get_command_argument(i, save_file)
        case ('--compare'); i = i + 1; call get_command_argument(i, compare_file)
        case ('--csv'); i = i + 1; call get_command_argument(i, csv_file)
        case ('--tol'); i = i + 1; call get_command_argument(i, arg); read (arg, *) tol
        case default
            if (rank == 0) write (*, '(a)') 'unknown argument '//trim(arg)
            call mpi_abort(MPI_COMM_WORLD, 1, ierr)
        end select
        i = i + 1
    end do
    if (n < 8 .or. n > 65536) then
        if (rank == 0) write (*, '(a)') '--n must lie in [8, 65536]'
        call mpi_abort(MPI_COMM_WORLD, 1, ierr)
    end if
    if (serial .and. nprocs > 1) then
        if (rank == 0) write (*, '(a)') '--serial runs on one rank'
        call mpi_abort(MPI_COMM_WORLD, 1, ierr)
    end if
    nthreads = 1
    !$ block
    !$ use omp_lib, only: omp_get_max_threads
    !$ nthreads = omp_get_max_threads()
    !$ end block
    mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
    call combine_material(mat, stat, em)
    set%tol = tol
    ! the distributed BCCG applies its preconditioner in the Toeplitz form: the serial run
    ! takes the same form, so that both are one algorithm and agree to round-off
    set%prec_form = 'toeplitz'
    par%sigma = 1.0e-3_dp
    select case (trim(kind))
    case ('hertz')
        call make_grid(grid, n, n, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, stat, em)
    case ('rough')
        call make_grid(grid, n, n, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, stat, em)
    case ('periodic')
        call make_grid(grid, n, n, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, stat, em)
        par%m_modes = 24; par%n_modes = 24; par%gamma = 0.9_dp
    case default
        if (rank == 0) write (*, '(a)') "--case must be 'hertz', 'rough' or 'periodic'"
        call mpi_abort(MPI_COMM_WORLD, 1, ierr)
    end select
    fn_target = 4000.0_dp
    t0 = mpi_wtime()
    if (serial) then
        j0 = 1; j1 = n
    else
        call build_dist_normal_operator(dop, mat, grid, MPI_COMM_WORLD, stat, em, periodic=trim(kind) == 'periodic')
        if (stat /= 0) then
            write (*, '(a)') trim(em); call mpi_abort(MPI_COMM_WORLD, 1, ierr)
        end if
        j0 = dop%lay%y0 + 1; j1 = dop%lay%y0 + dop%lay%nyl
    end if
    allocate (h0(n, j0:j1))
    select case (trim(kind))
    case ('hertz'); call quadratic_gap_rows(grid, 2.0_dp, 2.0_dp, j0, j1, h0)
    case ('rough'); call punch_rough_gap_rows(grid, 1.8_dp, par, j0, j1, h0)
    case ('periodic')
        allocate (z(n, j0:j1))
        call rough_heights_rows(grid, par, j0, j1, z)
        h0 = -z
        deallocate (z)
    end select
    if (serial) then
        if (trim(kind) == 'periodic') then
            call build_periodic_normal_operator(nop, mat, grid, stat, em)
        else
            call build_normal_operator(nop, mat, grid)
        end if
    end if
    t1 = mpi_wtime()
    call cpu_time(c1)
    if (serial) then
        if (trim(kind) == 'hertz') then
            call solve_normal(nop, h0, set, res, stat, em, approach=0.1_dp)
        else
            call solve_normal(nop, h0, set, res, stat, em, fn=fn_target)
        end if
        products = res%matvecs + res%precond_applications
    else
        if (trim(kind) == 'hertz') then
            call solve_dist_normal(dop, h0, set, res, stat, em, approach=0.1_dp)
        else
            call solve_dist_normal(dop, h0, set, res, stat, em, fn=fn_target)
        end if
        products = res%matvecs + res%precond_applications
    end if
    t2 = mpi_wtime()
    call cpu_time(c2)
    call mpi_allreduce(c2 - c1, cpu_solve, 1, MPI_DOUBLE_PRECISION, MPI_MAX, MPI_COMM_WORLD, ierr)
    if (stat /= 0) then
        write (*, '(a)') trim(em); call mpi_abort(MPI_COMM_WORLD, 1, ierr)
    end if
    iters = res%iterations
    hwm = peak_rss_kb()
    call mpi_allreduce(hwm, hwm_max, 1, MPI_INTEGER8, MPI_MAX, MPI_COMM_WORLD, ierr)
    if (serial) then
        call move_alloc(res%pn, pfull)
    else
        call gather_rows(dop, res%pn, pfull, 0)
    end if
    dpmax = -1; dfn = -1
    if (rank == 0 .and. len_trim(save_file) > 0) then
        open (newunit=u, file=trim(save_file), access='stream', form='unformatted', status='replace')
        write (u) res%fn, pfull
        close (u)
    end if
    if (rank == 0 .and. len_trim(compare_file) > 0) then
        allocate (pother(n, n))
        open (newunit=u, file=trim(compare_file), access='stream', form='unformatted', status='old')
        read (u) fn_other, pother
        close (u)
        dpmax = maxval(abs(pother - pfull))/maxval(pother)
        dfn = abs(fn_other - res%fn)/fn_other
    end if
    load1 = -1
    if (rank == 0) then
        open (newunit=u, file='/proc/loadavg', action='read', iostat=i)
        if (i == 0) then
            read (u, *, iostat=i) load1
            close (u)
        end if
        write (arg, '(a)') 'case,n,mode,ranks,threads,status,iterations,products,fn,setup_s,solve_s,peak_rss_mb_per_rank,'// &
            'dp_rel,dfn_rel,solve_cpu_s_max_rank,load1'
        if (len_trim(csv_file) > 0) then
            open (newunit=u, file=trim(csv_file), position='append', action='write')
        else
            u = 6
        end if
        if (u == 6) write (u, '(a)') trim(arg)
        write (u, '(a,",",i0,",",a,2(",",i0),",",a,2(",",i0),",",es22.15,2(",",f0.3),",",f0.1,2(",",es10.3),",",f0.3,",",f0.2)') &
            trim(kind), n, trim(merge('serial     ', 'distributed', serial)), nprocs, nthreads, &
            status_name(res%status), iters, products, res%fn, t1 - t0, t2 - t1, real(hwm_max, dp)/1024, dpmax, dfn, cpu_solve, load1
        if (u /= 6) close (u)
    end if
    call mpi_finalize(ierr)

contains

    !> Peak resident set size of this process [kB] (VmHWM of /proc/self/status; 0 if absent).
    function peak_rss_kb() result(kb)
        integer(int64) :: kb
        character(len=256) :: line
        integer :: uu, ios
        kb = 0
        open (newunit=uu, file='/proc/self/status', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (uu, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (line(1:6) == 'VmHWM:') then
                read (line(7:), *, iostat=ios) kb
                exit
            end if
        end do
        close (uu)
    end function peak_rss_kb

end program bench_dist
