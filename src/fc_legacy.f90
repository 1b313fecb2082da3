!> Flat, handle-based "legacy-style" API for multibody codes (doc/legacy_api.md).
!!
!! Every routine has a `bind(C)` name, takes its arguments by reference (plain `int`,
!! `double` and explicit-size arrays) and ends with an integer error code `ierr`, so it can
!! be called from Fortran (with or without this module's interfaces), from C and from
!! Python ctypes.  A contact problem lives behind an integer handle:
!!
!! ```
!! fc_init → fc_set_material → fc_set_grid → fc_set_gap_quadratic | fc_set_gap_array
!!         → fc_set_normal_force | fc_set_normal_approach
!!         [→ fc_set_friction → fc_set_shifts | fc_set_forces] [→ fc_set_solver, fc_set_transient]
!!         → fc_calculate → fc_get_* … (repeat set/calculate every time step) → fc_finalize
!! ```
!!
!! Error codes (`ierr`): the `FCL_*` constants of [[fc_legacy_registry]], re-exported here
!! (doc/legacy_api.md); library error codes map onto them in one place ([[flat_code]]).  A failing
!! call leaves a message naming the routine and the offending value, retrievable with
!! [[fc_get_error_message]] (for an invalid handle: with any handle, e.g. 0).
!!
!! Reuse: the influence operators (kernels and FFT plans) of a handle are kept while the
!! grid size/spacing and the material are unchanged; the previous solution warm-starts the
!! next call and, in the transient modes, is the previous state (u', p') of the step.
!!
!! The API is written in three modules, gathered here: [[fc_legacy_setup]] (handles and
!! inputs), [[fc_legacy_calculate]] (the solve) and [[fc_legacy_results]] (queries).  The
!! handles live in [[fc_legacy_registry]]; every calculation goes through the library's
!! orchestrator [[solve_contact]].  Fortran-77 callers link through [[fc_legacy_f77]];
!! .ci/run checks that every `bind(C)` routine of the three has its prototype in
!! include/fc_legacy.h and its F77 alias.
module fc_legacy
    use fc_legacy_registry, only: FCL_OK, FCL_INVALID_HANDLE, FCL_ORDER, FCL_INVALID_VALUE, FCL_NOT_CONVERGED, &
        FCL_DIVERGED, FCL_ARRAY_SIZE, FCL_INTERNAL, FCL_MEMORY, FCL_FROM_REST, FCL_CONTINUE, FCL_ROLLING
    use fc_legacy_setup
    use fc_legacy_calculate
    use fc_legacy_results
    use fc_contact, only: shift_along_x
    implicit none
    private

    public :: fc_init, fc_finalize, fc_set_material, fc_set_grid, fc_set_gap_array, fc_set_gap_quadratic
    public :: fc_set_normal_approach, fc_set_normal_force, fc_set_friction, fc_set_shifts, fc_set_forces
    public :: fc_set_solver, fc_set_transient, fc_set_rolling_step, fc_set_reuse, fc_calculate
    public :: fc_set_rolling, fc_set_rolling_forces, fc_set_rolling_options
    public :: fc_get_forces, fc_get_dissipation, fc_get_approach, fc_get_pmax, fc_get_shifts, fc_get_contact_stats
    public :: fc_get_edge_contact
    public :: fc_get_tractions, fc_get_slip, fc_get_gap, fc_get_status_array, fc_get_iterations
    public :: fc_get_rebuilds, fc_get_grid_size, fc_get_error_message, fc_get_nhandles, fc_get_version
    public :: fc_set_influence_file
    public :: fc_set_periodic, fc_set_threads, fc_set_fft_effort, fc_set_fft_wisdom
    public :: shift_along_x
    public :: FCL_OK, FCL_INVALID_HANDLE, FCL_ORDER, FCL_INVALID_VALUE, FCL_NOT_CONVERGED, FCL_DIVERGED
    public :: FCL_ARRAY_SIZE, FCL_INTERNAL, FCL_MEMORY, FCL_FROM_REST, FCL_CONTINUE, FCL_ROLLING
end module fc_legacy
