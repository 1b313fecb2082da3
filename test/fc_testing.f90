!> Minimal in-tree test harness shaped like test-drive / pFUnit suites.
!!
!! A suite is a list of named tests (procedures with an `error` argument).  `check`
!! records the first failure with a message; the runner prints one line per test and a
!! closing `N passed, N failed` line.
module fc_testing
    use fc_kinds, only: dp
    implicit none
    private

    !> Failure record; allocated when a check fails.
    type, public :: error_type
        character(len=:), allocatable :: message
    end type error_type

    abstract interface
        subroutine test_procedure(error)
            import :: error_type
            type(error_type), allocatable, intent(out) :: error
        end subroutine test_procedure
    end interface
    public :: test_procedure

    !> A named test.
    type, public :: unittest_type
        character(len=:), allocatable :: name
        procedure(test_procedure), pointer, nopass :: test => null()
    end type unittest_type

    interface check
        module procedure check_logical, check_real
    end interface check

    public :: check, new_unittest, run_suite, rel_diff, file_lines, file_bytes, delete_file, set_env, unset_env

contains

    function new_unittest(name, test) result(t)
        character(len=*), intent(in) :: name
        procedure(test_procedure) :: test
        type(unittest_type) :: t
        t%name = name
        t%test => test
    end function new_unittest

    !> Fail with `message` unless `condition`.
    subroutine check_logical(error, condition, message)
        type(error_type), allocatable, intent(inout) :: error
        logical, intent(in) :: condition
        character(len=*), intent(in) :: message
        if (allocated(error)) return
        if (.not. condition) then
            allocate (error)
            error%message = message
        end if
    end subroutine check_logical

    !> Fail unless |actual − expected| ≤ rel·|expected| + abs (NaN always fails).
    subroutine check_real(error, actual, expected, message, rel, abs)
        type(error_type), allocatable, intent(inout) :: error
        real(dp), intent(in) :: actual, expected
        character(len=*), intent(in) :: message
        real(dp), intent(in), optional :: rel, abs
        real(dp) :: tol
        character(len=200) :: buf
        if (allocated(error)) return
        tol = 0
        if (present(rel)) tol = tol + rel*system_abs(expected)
        if (present(abs)) tol = tol + abs
        if (.not. (system_abs(actual - expected) <= tol)) then
            write (buf, '(3(a,es14.6))') ': got ', actual, ', expected ', expected, ', tolerance ', tol
            allocate (error)
            error%message = message//trim(buf)
        end if
    contains
        elemental real(dp) function system_abs(x)
            real(dp), intent(in) :: x
            system_abs = merge(x, -x, x >= 0)
        end function system_abs
    end subroutine check_real

    !> Relative difference ‖a − b‖₂/‖b‖₂.
    pure real(dp) function rel_diff(a, b)
        real(dp), intent(in) :: a(:), b(:)
        rel_diff = sqrt(sum((a - b)**2))/max(sqrt(sum(b**2)), tiny(1.0_dp))
    end function rel_diff

    !> Run the tests of one suite whose name matches `only` (empty: all).
    subroutine run_suite(suite_name, tests, only, npass, nfail)
        character(len=*), intent(in) :: suite_name
        type(unittest_type), intent(in) :: tests(:)
        character(len=*), intent(in) :: only
        integer, intent(inout) :: npass, nfail
        type(error_type), allocatable :: error
        integer :: i, t0, t1, rate
        do i = 1, size(tests)
            if (len_trim(only) > 0 .and. trim(only) /= tests(i)%name) cycle
            call system_clock(t0, rate)
            call tests(i)%test(error)
            call system_clock(t1)
            if (allocated(error)) then
                nfail = nfail + 1
                write (*, '(a)') '  FAIL  '//suite_name//' :: '//tests(i)%name//' — '//error%message
            else
                npass = npass + 1
                write (*, '(a,f7.2,a)') '  ok    '//suite_name//' :: '//tests(i)%name//'  (', real(t1 - t0)/rate, ' s)'
            end if
            if (allocated(error)) deallocate (error)
        end do
    end subroutine run_suite

    !> A text file's lines (trailing blanks trimmed, at most 4096 characters each), each
    !! ended by a newline; '' when the file cannot be opened.
    function file_lines(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        character(len=4096) :: line
        integer :: u, ios
        text = ''
        open (newunit=u, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            text = text//trim(line)//new_line('a')
        end do
        close (u)
    end function file_lines

    !> The whole file, lines of any length included ('' when it cannot be read).
    function file_bytes(path) result(s)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: s
        integer :: u, n, ios
        s = ''
        open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read', iostat=ios)
        if (ios /= 0) return
        inquire (unit=u, size=n)
        deallocate (s); allocate (character(len=max(0, n)) :: s)
        if (n > 0) read (u, iostat=ios) s
        if (ios /= 0) s = ''
        close (u)
    end function file_bytes

    !> Delete a file if it exists.
    subroutine delete_file(path)
        character(len=*), intent(in) :: path
        integer :: u, ios
        open (newunit=u, file=path, status='old', iostat=ios)
        if (ios == 0) close (u, status='delete')
    end subroutine delete_file

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

end module fc_testing
