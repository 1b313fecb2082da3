!> What the MPI test suites share: running one test on every rank (it passes when it passes
!! on all of them; rank 0 prints PASS, each failing rank its message), reading a file, and
!! setting environment variables (the serial suites' fc_testing is not part of the library).
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

    public :: mpi_test_procedure, run_mpi_test, slurp_file, set_env, unset_env, rank0_failed

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

    !> Set the environment variable `name` to `value` in this process (C `setenv`).
    subroutine set_env(name, value)
        use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
        character(len=*), intent(in) :: name, value
        interface
            integer(c_int) function c_setenv(n, v, o) bind(C, name='setenv')
                import :: c_char, c_int
                character(kind=c_char), intent(in) :: n(*), v(*)
                integer(c_int), value :: o
            end function c_setenv
        end interface
        integer(c_int) :: rc
        rc = c_setenv(name//c_null_char, value//c_null_char, 1_c_int)
    end subroutine set_env

    !> Remove the environment variable `name` from this process (C `unsetenv`).
    subroutine unset_env(name)
        use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
        character(len=*), intent(in) :: name
        interface
            integer(c_int) function c_unsetenv(n) bind(C, name='unsetenv')
                import :: c_char, c_int
                character(kind=c_char), intent(in) :: n(*)
            end function c_unsetenv
        end interface
        integer(c_int) :: rc
        rc = c_unsetenv(name//c_null_char)
    end subroutine unset_env

    !> After checks that only rank 0 makes: whether they failed, on every rank (collective), so
    !! that all ranks leave a test together instead of the others waiting in its next
    !! collective call; the other ranks' `msg` then names rank 0.
    logical function rank0_failed(msg) result(failed)
        character(len=:), allocatable, intent(inout) :: msg
        integer :: rank, ierr
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        failed = allocated(msg)
        call mpi_bcast(failed, 1, MPI_LOGICAL, 0, MPI_COMM_WORLD, ierr)
        if (failed .and. .not. allocated(msg)) msg = 'rank 0 failed (its message above)'
    end function rank0_failed

end module fcm_test_support
