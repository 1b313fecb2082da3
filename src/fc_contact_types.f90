!> The value types of a contact solve — problem kinds, normal loading, settings of both
!! stages, result — apart from the orchestrator [[fc_contact]] that uses them, so that the
!! case description ([[fc_scene]]) and the outputs ([[fc_case_result]]) depend on the solver
!! types only, not on the solve.  [[fc_contact]] re-exports everything here.
module fc_contact_types
    use fc_kinds, only: dp, FC_ERROR
    use fc_norm, only: fc_normal_settings, fc_normal_result
    use fc_tangcg, only: fc_tangential_settings, fc_tangential_result
    use fc_fmg_levels, only: fc_fmg_settings
    use fc_rolling_base, only: fc_rolling_settings
    implicit none
    private

    !> Problem kinds: what the tangential stage solves (one dispatch point in fc_contact's tangential stage).
    integer, parameter, public :: FC_PROBLEM_NORMAL = 1      !! normal contact only
    integer, parameter, public :: FC_PROBLEM_TANGENTIAL = 2  !! normal, then tangential (shifts or forces)
    !> normal, then steady-state rolling in +x (`tangential%xi, eta, phi` are creepages [-, -, 1/mm])
    integer, parameter, public :: FC_PROBLEM_ROLLING = 3


    !> Normal loading: prescribed approach δ or total force Fn, and an optional start pressure.
    type, public :: fc_normal_loading
        logical :: force_prescribed = .false.   !! .true.: fn, else approach
        real(dp) :: approach = 0                !! prescribed approach δ [mm]
        real(dp) :: fn = 0                      !! prescribed total normal force [N]
        real(dp), allocatable :: p_start(:, :)  !! warm start [N/mm²] (zeroed where contact is impossible)
    end type fc_normal_loading


    !> Solver settings of both stages.
    type, public :: fc_contact_settings
        type(fc_normal_settings) :: normal          !! solver 'bccg', 'norm' or 'fmg'
        type(fc_tangential_settings) :: tangential  !! solver 'tangcg' or 'convexgs'
        type(fc_fmg_settings) :: fmg                !! used when normal%solver = 'fmg'
        type(fc_rolling_settings) :: rolling        !! FC_PROBLEM_ROLLING: 'gmres', 'march' or 'steadygs'
    end type fc_contact_settings


    !> Result of a contact solve ([[solve_contact]]).
    type, public :: fc_contact_result
        type(fc_normal_result) :: normal            !! pressure, gap, approach, force (iterations: all rounds)
        !> tractions, slip, states (iterations: all rounds); unallocated for a normal problem;
        !! when the normal stage of a tangential problem failed: zero tractions and slip,
        !! adhesion where pn > 0
        type(fc_tangential_result) :: tangential
        logical :: tangential_run = .false.         !! the tangential stage was solved
        integer :: rounds = 0                       !! Panagiotopoulos rounds (0 for a normal problem)
        integer :: status = FC_ERROR                !! worst status of the stages run
        real(dp) :: setup_seconds_normal = 0        !! operator set-up of this solve (0: reused)
        real(dp) :: setup_seconds_tangential = 0
        real(dp) :: work_units = -1                 !! FMG: thesis work units (−1: not FMG)
        real(dp) :: convergence_factor = -1         !! FMG: convergence factor (−1: not FMG)
    end type fc_contact_result


end module fc_contact_types
