!> In-process runs of the batch driver for the test suites: a namelist text written to a
!! directory, the driver run on it with `--out` there, and what it wrote read back.
module fc_test_driver
    use fc_driver, only: run_driver
    use fc_memory, only: memory_env
    use fc_testing, only: set_env, unset_env, file_lines
    implicit none
    private

    public :: fresh_dir, run_namelist, file_exists

    integer, save :: runs = 0   !! directories made so far: unique names within one clock tick

contains

    !> A new, empty directory /tmp/fc_test_<prefix>_<clock>_<n>.
    function fresh_dir(prefix) result(dir)
        character(len=*), intent(in) :: prefix
        character(len=:), allocatable :: dir
        character(len=48) :: tag
        integer :: count
        runs = runs + 1
        call system_clock(count)
        write (tag, '(i0,a,i0)') count, '_', runs
        dir = '/tmp/fc_test_'//prefix//'_'//trim(tag)
        call execute_command_line("rm -rf '"//dir//"' && mkdir -p '"//dir//"'")
    end function fresh_dir

    !> Write `text` to DIR/cases.nml (DIR exists) and run the driver on it with `--out DIR`
    !! (`check_only`: `--check` too); its report goes to DIR/report.txt, its messages to
    !! DIR/errors.txt, returned in `errors` (lines ended by new lines).  `memory` sets
    !! FASTCONTACT_AVAILABLE_MEMORY for the run (unset after it); `share` is the driver's
    !! `memory_share`; `extra` are more command-line arguments (e.g. `--case NAME`).
    subroutine run_namelist(dir, text, code, errors, memory, share, check_only, extra)
        character(len=*), intent(in) :: dir, text
        integer, intent(out) :: code
        character(len=:), allocatable, intent(out), optional :: errors
        character(len=*), intent(in), optional :: memory
        integer, intent(in), optional :: share
        logical, intent(in), optional :: check_only
        character(len=*), intent(in), optional :: extra(:)
        character(len=256), allocatable :: args(:)
        integer :: u, urep, uerr, i
        character(len=256) :: arg
        open (newunit=u, file=dir//'/cases.nml', status='replace', action='write')
        write (u, '(a)') text
        close (u)
        args = [character(len=256) :: dir//'/cases.nml', '--out', dir]
        if (present(check_only)) then
            if (check_only) args = [args, [character(len=256) :: '--check']]
        end if
        if (present(extra)) then
            do i = 1, size(extra)
                arg = extra(i)   ! (a constructor of extra(i) itself trips gfortran over the lengths)
                args = [args, arg]
            end do
        end if
        if (present(memory)) call set_env(memory_env, memory)
        open (newunit=urep, file=dir//'/report.txt', status='replace', action='write')
        open (newunit=uerr, file=dir//'/errors.txt', status='replace', action='write')
        call run_driver(args, code, report_unit=urep, error_unit=uerr, memory_share=share)
        close (urep); close (uerr)
        if (present(memory)) call unset_env(memory_env)
        if (present(errors)) errors = file_lines(dir//'/errors.txt')
    end subroutine run_namelist

    !> Whether `path` exists.
    logical function file_exists(path)
        character(len=*), intent(in) :: path
        inquire (file=path, exist=file_exists)
    end function file_exists

end module fc_test_driver
