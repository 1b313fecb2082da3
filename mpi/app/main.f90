!> fastcontact-mpi — the batch driver over MPI ranks: `mpirun -np P fastcontact-mpi CASES.nml
!! [--out DIR]`.  Same arguments, outputs and exit status as `fastcontact`; the cases are
!! spread over the ranks ([[run_mpi_batch]]).
program fastcontact_mpi_main
    use mpi
    use fcm_batch, only: run_mpi_batch
    implicit none
    character(len=4096), allocatable :: args(:)
    integer :: i, exit_code, ierr, provided
    call mpi_init_thread(MPI_THREAD_FUNNELED, provided, ierr)   ! OpenMP regions make no MPI calls
    allocate (args(command_argument_count()))
    do i = 1, size(args)
        call get_command_argument(i, args(i))
    end do
    call run_mpi_batch(args, MPI_COMM_WORLD, exit_code)
    call mpi_finalize(ierr)
    if (exit_code /= 0) stop exit_code, quiet=.true.
end program fastcontact_mpi_main
