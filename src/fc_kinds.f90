!> Kinds, constants and status codes shared by every fastcontact module.
module fc_kinds
    use, intrinsic :: iso_fortran_env, only: real64, int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    implicit none
    private

    integer, parameter, public :: dp = real64   !! working real kind
    integer, parameter, public :: i8 = int64    !! counters that may exceed 2^31
    real(dp), parameter, public :: pi = 3.141592653589793238462643383279502884_dp

    !> Solver status codes (the JSON `status`, doc/user_guide.md); errors are [[fc_errors]] codes.
    integer, parameter, public :: FC_CONVERGED = 0      !! solution meets the tolerance
    integer, parameter, public :: FC_NOT_CONVERGED = 1  !! maxit reached or stagnation detected
    integer, parameter, public :: FC_DIVERGED = 2       !! residual grew without bound / NaN
    integer, parameter, public :: FC_ERROR = 3          !! invalid input or internal error

    integer, parameter, public :: msg_len = 512         !! length of error messages

    !> Largest iteration limit (`maxit`) any solver accepts: bounds the per-iteration history
    !! buffers (8 bytes per iteration) and the run time of a solve that never converges.
    integer, parameter, public :: max_iterations = 1000000

    !> Error codes returned in `stat` (0: success); use them through [[fc_errors]].
    integer, parameter, public :: FC_OK = 0                 !! success
    integer, parameter, public :: FC_ERR_VALUE = 1          !! an argument is out of range or invalid
    integer, parameter, public :: FC_ERR_NOT_READY = 2      !! required data missing (operator not built, order)
    integer, parameter, public :: FC_ERR_SHAPE = 3          !! an array does not match the grid
    integer, parameter, public :: FC_ERR_UNSUPPORTED = 4    !! a valid combination the solvers do not offer
    integer, parameter, public :: FC_ERR_IO = 5             !! a file cannot be read or written
    integer, parameter, public :: FC_ERR_NO_CONTACT = 6     !! the loading brings no element into contact
    integer, parameter, public :: FC_ERR_FRICTION_BOUND = 7 !! prescribed |(Fx, Fy)| ≥ μ·Fn: no unique shift
    integer, parameter, public :: FC_ERR_GRID = 8           !! the grid does not suit the chosen solver
    integer, parameter, public :: FC_ERR_ALLOC = 9          !! memory allocation failed
    integer, parameter, public :: FC_ERR_INTERNAL = 10      !! unexpected internal error
    integer, parameter, public :: FC_ERR_GEOMETRY = 11      !! the geometry cannot touch on this grid
    integer, parameter, public :: FC_ERR_IC_FILE = 12       !! an influence-coefficient file cannot be used
    integer, parameter, public :: FC_ERR_MODEL_RANGE = 13   !! the case lies outside a simplified model's range
    integer, parameter, public :: FC_ERR_FFT_WISDOM = 14    !! an FFTW wisdom file cannot be read or written
    integer, parameter, public :: FC_ERR_AREA = 15          !! the potential contact area (its grid) is not valid


    public :: status_name, check_iteration_settings

contains

    !> Name of a status code as written to the JSON summary.
    pure function status_name(status) result(name)
        integer, intent(in) :: status
        character(len=:), allocatable :: name
        select case (status)
        case (FC_CONVERGED);     name = 'converged'
        case (FC_NOT_CONVERGED); name = 'not_converged'
        case (FC_DIVERGED);      name = 'diverged'
        case default;            name = 'error'
        end select
    end function status_name

    !> Validate the tolerance and iteration limit shared by every solver (stat = FC_ERR_VALUE
    !! with a message naming the argument and its value).
    subroutine check_iteration_settings(tol, maxit, stat, errmsg)
        real(dp), intent(in) :: tol
        integer, intent(in) :: maxit
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (ieee_is_nan(tol)) then      ! before any comparison: quiet under floating-point traps
            stat = FC_ERR_VALUE; errmsg = 'tol = NaN must be > 0'
        else if (.not. (tol > 0)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a)') 'tol = ', tol, ' must be > 0'
        else if (maxit < 1 .or. maxit > max_iterations) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a,i0,a)') 'maxit = ', maxit, ' must lie in [1, ', max_iterations, ']'
        end if
    end subroutine check_iteration_settings

end module fc_kinds
