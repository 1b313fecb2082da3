!> fastcontact — the public modern API (doc/legacy_api.md describes the flat one).
!!
!! A contact problem is a [[fc_problem]]: material, grid, undeformed distance, loading and
!! solver settings.  [[solve]] builds (or reuses) the influence operators and solves it
!! through the one orchestrator [[solve_contact]] (also public here, with its loading,
!! settings, operator, state and result types): normal contact, or normal + tangential
!! (Panagiotopoulos coupling for K ≠ 0) when `prob%load%problem = FC_PROBLEM_TANGENTIAL`.
!! A whole case — scene, loading, settings and an accuracy target — is an [[fc_case]] solved
!! by [[solve_case_auto]] (automatic potential area, grid refinement to the target, model
!! reduction), as the batch driver does.
!! Errors come back through `stat`/`errmsg` (codes of [[fc_errors]]), never by stopping.  `prob%destroy()` releases the
!! operators (FFT plans).  The operator-level routines of [[fc_norm]] and [[fc_tangcg]]
!! stay available for callers that manage operators themselves.
!!
!! ```fortran
!! use fastcontact
!! type(fc_problem) :: prob
!! type(fc_normal_result) :: res
!! call set_material(prob, 82000.0_dp, 82000.0_dp, 0.28_dp, 0.28_dp, stat, errmsg)
!! call make_grid(prob%grid, 64, 64, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, errmsg)
!! prob%h0 = quadratic_gap(prob%grid, 300.0_dp, 163.0_dp)
!! prob%load%normal%approach = 0.1091_dp
!! call solve(prob, res, stat, errmsg)
!! call prob%destroy()
!! ```
module fastcontact
    use fc_kinds
    use fc_geometry
    use fc_influence
    use fc_norm
    use fc_hertz
    use fc_tangcg
    use fc_tangcg_force
    use fc_fmg
    use fc_mg2d
    use fc_contact
    use fc_errors
    use fc_version, only: fc_version_string, fc_version_major, fc_version_minor, fc_version_patch, fc_build_info
    use fc_scene, only: fc_case, case_setup
    use fc_auto, only: fc_auto_outcome, fc_level, solve_case_auto
    implicit none
    private

    public :: fc_version_string, fc_version_major, fc_version_minor, fc_version_patch, fc_build_info
    public :: dp, pi, msg_len, FC_CONVERGED, FC_NOT_CONVERGED, FC_DIVERGED, FC_ERROR, status_name
    public :: FC_OK, FC_ERR_VALUE, FC_ERR_NOT_READY, FC_ERR_SHAPE, FC_ERR_UNSUPPORTED, FC_ERR_IO, FC_ERR_NO_CONTACT
    public :: FC_ERR_FRICTION_BOUND, FC_ERR_GRID, FC_ERR_ALLOC, FC_ERR_INTERNAL, FC_ERR_GEOMETRY, FC_ERR_IC_FILE
    public :: FC_ERR_MODEL_RANGE, FC_ERR_FFT_WISDOM, FC_ERR_AREA, error_name
    public :: fc_grid, make_grid, quadratic_gap, punch_rough_gap, wavy_gap, read_gap_table, rough_heights
    public :: fc_rough_params, h_no_contact
    public :: fc_material, combine_material, rigid_modulus
    public :: fc_normal_settings, fc_normal_result, fc_normal_operator, build_normal_operator, solve_normal
    public :: fc_hertz_solution, hertz_from_approach, hertz_from_force, elliptic_ke
    public :: fc_cattaneo_solution, cattaneo_mindlin
    public :: fc_tangential_settings, fc_tangential_loading, fc_tangential_operator, fc_tangential_result
    public :: build_tangential_operator, solve_tangential, solve_tangential_loading, solve_normal_tangential
    public :: coupling_displacements, EL_EXTERIOR, EL_ADHESION, EL_SLIP
    ! multigrid (thesis ch. 2 and 3)
    public :: fc_surface, fc_quadratic_surface, fc_punch_rough_surface, fc_wavy_surface
    public :: fc_fmg_settings, fc_fmg_stats, fc_fmg_hierarchy
    public :: solve_normal_fmg, build_fmg_hierarchy, fmg_solve_lcp, fmg_cycle_from_name
    public :: fc_strip_problem, fc_mg2d_settings, fc_mg2d_result
    public :: strip_model_problem, solve_strip_mg, solve_strip_fft_rsm
    ! the orchestrator
    public :: fc_normal_loading, fc_contact_loading, fc_contact_settings, fc_contact_operators, fc_contact_state
    public :: fc_contact_result, solve_contact, ensure_operators
    public :: FC_PROBLEM_NORMAL, FC_PROBLEM_TANGENTIAL, FC_FROM_REST, FC_TRANSIENT_SHIFT, FC_TRANSIENT_ROLLING
    ! a whole case with the automatic layer (accuracy target, automatic area, model reduction)
    public :: fc_case, case_setup, fc_auto_outcome, fc_level, solve_case_auto

    !> One contact problem, its reusable operators and its previous solution.
    type, public :: fc_problem
        type(fc_material) :: material            !! body constants (combined by set_material)
        type(fc_grid) :: grid                    !! potential contact area
        real(dp), allocatable :: h0(:, :)        !! undeformed distance without approach [mm]
        type(fc_contact_loading) :: load         !! normal (and tangential) loading
        type(fc_contact_settings) :: settings    !! solver choice and tolerances
        type(fc_contact_operators) :: operators  !! cached influence operators
        type(fc_contact_state) :: state          !! previous solution (warm start, transient steps)
    contains
        procedure :: destroy => problem_destroy
    end type fc_problem

    public :: set_material, solve

contains

    !> Set and combine the constants of both bodies (g ≥ 1e29: rigid).
    subroutine set_material(prob, g1, g2, nu1, nu2, stat, errmsg)
        type(fc_problem), intent(inout) :: prob
        real(dp), intent(in) :: g1, g2, nu1, nu2
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        prob%material%g1 = g1; prob%material%g2 = g2
        prob%material%nu1 = nu1; prob%material%nu2 = nu2
        call combine_material(prob%material, stat, errmsg)
    end subroutine set_material

    !> Solve the contact problem of `prob`.  The operators are rebuilt only when the grid
    !! spacing or the material changed since the previous call; the previous solution
    !! warm-starts the next (`prob%state%warm_start`).
    subroutine solve(prob, res, stat, errmsg)
        type(fc_problem), intent(inout) :: prob
        type(fc_contact_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        if (.not. allocated(prob%h0)) then
            stat = FC_ERR_NOT_READY; errmsg = 'solve: undeformed distance h0 not set'; return
        end if
        if (prob%material%g <= 0) then
            call combine_material(prob%material, stat, errmsg)
            if (stat /= 0) return
        end if
        call solve_contact(prob%operators, prob%grid, prob%material, prob%h0, prob%load, prob%settings, res, &
                           stat, errmsg, state=prob%state)
    end subroutine solve

    !> Release the operators (FFT plans and buffers) and the previous solution of `prob`.
    subroutine problem_destroy(prob)
        class(fc_problem), intent(inout) :: prob
        call prob%operators%destroy()
        call prob%state%reset()
    end subroutine problem_destroy

end module fastcontact
