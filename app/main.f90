!> fastcontact — namelist-driven batch driver (doc/user_guide.md): `fastcontact CASES.nml [--out DIR]`.
!! All the work is done by [[run_driver]]; this program only gathers the arguments and
!! turns the driver's exit code into the process exit status.
program fastcontact_main
    use fc_driver, only: run_driver
    implicit none
    character(len=4096), allocatable :: args(:)
    integer :: i, exit_code
    allocate (args(command_argument_count()))
    do i = 1, size(args)
        call get_command_argument(i, args(i))
    end do
    call run_driver(args, exit_code)
    deallocate (args)   ! main-program allocatables are never freed implicitly (leak checkers)
    if (exit_code /= 0) stop exit_code, quiet=.true.
end program fastcontact_main
