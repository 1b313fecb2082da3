!> Error codes returned in `stat` by every library routine (0: success) and mapped onto the
!! flat API's documented `ierr` codes (doc/legacy_api.md) by [[fc_legacy_registry]].
!!
!! Library messages (`errmsg`) speak library terms (argument names of the routine); the
!! callers that know more — the batch driver knows the namelist group, key and value —
!! choose their context from the code, never by reading the message.  Solver outcomes
!! (converged, not converged, diverged) are statuses in the results (fc_kinds), not errors.
module fc_errors
    implicit none
    private

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

    public :: error_name

contains

    !> Name of an error code (for logs and tests).
    pure function error_name(code) result(name)
        integer, intent(in) :: code
        character(len=:), allocatable :: name
        select case (code)
        case (FC_OK);                 name = 'ok'
        case (FC_ERR_VALUE);          name = 'invalid_value'
        case (FC_ERR_NOT_READY);      name = 'not_ready'
        case (FC_ERR_SHAPE);          name = 'shape'
        case (FC_ERR_UNSUPPORTED);    name = 'unsupported'
        case (FC_ERR_IO);             name = 'io'
        case (FC_ERR_NO_CONTACT);     name = 'no_contact'
        case (FC_ERR_FRICTION_BOUND); name = 'friction_bound'
        case (FC_ERR_GRID);           name = 'grid'
        case (FC_ERR_ALLOC);          name = 'alloc'
        case (FC_ERR_GEOMETRY);       name = 'geometry'
        case default;                 name = 'internal'
        end select
    end function error_name

end module fc_errors
