!> fastcontact-mpi — the batch driver over MPI ranks: `mpirun -np P fastcontact-mpi CASES.nml
!! [--out DIR]`.  Same arguments, outputs and exit status as `fastcontact`; the cases are
!! spread over the ranks ([[run_mpi_batch]]).  With `--distributed` every case is solved by
!! all ranks together instead ([[run_dist_driver]]: normal problems on grids too large for
!! one machine).
program fastcontact_mpi_main
    use mpi
    use fcm_batch, only: run_mpi_batch
    use fcm_dist_driver, only: run_dist_driver
    use fcm_fftw_mpi, only: fftw_mpi_init
    use fc_threads, only: set_thread_count
    implicit none
    character(len=4096), allocatable :: args(:)
    integer :: i, exit_code, ierr, provided
    logical :: distributed
    call mpi_init_thread(MPI_THREAD_FUNNELED, provided, ierr)   ! OpenMP regions make no MPI calls
    allocate (args(0))
    distributed = .false.
    do i = 1, command_argument_count()
        block
            character(len=4096) :: a
            call get_command_argument(i, a)
            if (trim(a) == '--distributed') then
                distributed = .true.
            else
                args = [args, a]
            end if
        end block
    end do
    if (distributed) then
        call set_thread_count(0)   ! OMP_NUM_THREADS if set, else 1 thread per rank
        call fftw_mpi_init()
        call run_dist_driver(args, MPI_COMM_WORLD, exit_code)
    else
        call run_mpi_batch(args, MPI_COMM_WORLD, exit_code)
    end if
    call mpi_finalize(ierr)
    if (exit_code /= 0) stop exit_code, quiet=.true.
end program fastcontact_mpi_main
