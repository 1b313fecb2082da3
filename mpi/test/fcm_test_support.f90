!> What the MPI test suites share: running one test on every rank (it passes when it passes
!! on all of them; rank 0 prints PASS, each failing rank its message) and reading a file.
module fcm_test_support
    use mpi
    implicit none
    private

    abstract interface
        !> A test: `msg` stays unallocated when it passes on this rank.
        subroutine mpi_test_procedure(msg)
            character(len=:), allocatable, intent(out) :: msg
        end subroutine mpi_test_procedure
    end interface

    public :: mpi_test_procedure, run_mpi_test, slurp_file

contains

    !> Run `test` on all ranks of MPI_COMM_WORLD unless `only` names another test; count it.
    subroutine run_mpi_test(name, only, test, npass, nfail)
        character(len=*), intent(in) :: name, only
        procedure(mpi_test_procedure) :: test
        integer, intent(inout) :: npass, nfail
        character(len=:), allocatable :: msg
        logical :: ok
        integer :: rank, ierr
        if (len_trim(only) > 0 .and. trim(only) /= name) return
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        call test(msg)
        ok = .not. allocated(msg)
        call mpi_allreduce(MPI_IN_PLACE, ok, 1, MPI_LOGICAL, MPI_LAND, MPI_COMM_WORLD, ierr)
        if (ok) then
            npass = npass + 1
            if (rank == 0) write (*, '(a)') '  PASS  mpi/'//name
        else
            nfail = nfail + 1
            if (allocated(msg)) write (*, '(a,i0,a)') '  FAIL  mpi/'//name//' (rank ', rank, '): '//msg
        end if
    end subroutine run_mpi_test

    !> The bytes of a file ('<missing PATH>' when it cannot be read).
    function slurp_file(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        integer :: u, sz, ios
        open (newunit=u, file=path, access='stream', form='unformatted', action='read', iostat=ios)
        if (ios /= 0) then
            text = '<missing '//path//'>'; return
        end if
        inquire (unit=u, size=sz)
        allocate (character(len=sz) :: text)
        if (sz > 0) read (u) text
        close (u)
    end function slurp_file

end module fcm_test_support
