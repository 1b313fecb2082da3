!> Error codes returned in `stat` by every library routine (0: success; the values live in
!! [[fc_kinds]], the bottom of the module graph, and are re-exported here) and mapped onto the
!! flat API's documented `ierr` codes (doc/legacy_api.md) by [[fc_legacy_registry]].
!!
!! Library messages (`errmsg`) speak library terms (argument names of the routine); the
!! callers that know more — the batch driver knows the namelist group, key and value —
!! choose their context from the code, never by reading the message.  Solver outcomes
!! (converged, not converged, diverged) are statuses in the results (fc_kinds), not errors.
module fc_errors
    use fc_kinds, only: FC_OK, FC_ERR_VALUE, FC_ERR_NOT_READY, FC_ERR_SHAPE, FC_ERR_UNSUPPORTED, FC_ERR_IO, &
        FC_ERR_NO_CONTACT, FC_ERR_FRICTION_BOUND, FC_ERR_GRID, FC_ERR_ALLOC, FC_ERR_INTERNAL, FC_ERR_GEOMETRY, &
        FC_ERR_IC_FILE, FC_ERR_MODEL_RANGE, FC_ERR_FFT_WISDOM, FC_ERR_AREA
    implicit none
    private

    public :: FC_OK, FC_ERR_VALUE, FC_ERR_NOT_READY, FC_ERR_SHAPE, FC_ERR_UNSUPPORTED, FC_ERR_IO, FC_ERR_NO_CONTACT
    public :: FC_ERR_FRICTION_BOUND, FC_ERR_GRID, FC_ERR_ALLOC, FC_ERR_INTERNAL, FC_ERR_GEOMETRY
    public :: FC_ERR_IC_FILE, FC_ERR_MODEL_RANGE, FC_ERR_FFT_WISDOM, FC_ERR_AREA
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
        case (FC_ERR_IC_FILE);        name = 'ic_file'
        case (FC_ERR_MODEL_RANGE);    name = 'model_range'
        case (FC_ERR_FFT_WISDOM);     name = 'fft_wisdom'
        case (FC_ERR_AREA);           name = 'area'
        case default;                 name = 'internal'
        end select
    end function error_name

end module fc_errors
