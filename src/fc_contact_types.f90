!> The types of a contact solve — problem kinds, transient modes, loadings, settings of both
!! stages, the operators and state kept between solves, the result — apart from the
!! orchestrator [[fc_contact]] that uses them, so that the case description ([[fc_scene]]),
!! the outputs ([[fc_case_result]]) and the flat API's handle registry depend on the solver
!! types only, not on the solve; and the coefficient sets the operators use (set, taken or
!! cleared here, beside the operators type).  [[fc_contact]] re-exports everything here.
module fc_contact_types
    use fc_kinds, only: dp, FC_ERROR, FC_ERR_VALUE
    use fc_influence, only: fc_ic_set
    use fc_norm, only: fc_normal_settings, fc_normal_result, fc_normal_operator
    use fc_tangcg_operator, only: fc_tangential_operator
    use fc_tangcg_types, only: fc_tangential_settings, fc_tangential_result, fc_tangential_loading
    use fc_fmg_types, only: fc_fmg_settings
    use fc_rolling_types, only: fc_rolling_settings
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

    !> Transient modes: how the previous state of a sequence enters the step.
    integer, parameter, public :: FC_FROM_REST = 0          !! u' = 0: a steady (static) problem; warm start only
    integer, parameter, public :: FC_TRANSIENT_SHIFT = 1    !! u', p' = previous step (shift sequence)
    integer, parameter, public :: FC_TRANSIENT_ROLLING = 2  !! u', p' = previous step moved by the rolling step dq

    !> Everything prescribed for one solve.
    type, public :: fc_contact_loading
        integer :: problem = FC_PROBLEM_NORMAL            !! FC_PROBLEM_NORMAL or FC_PROBLEM_TANGENTIAL
        type(fc_normal_loading) :: normal                 !! approach or force
        type(fc_tangential_loading) :: tangential         !! friction, shifts or forces, spin
        real(dp), allocatable :: px_start(:, :), py_start(:, :)  !! tangential warm start [N/mm²] (both or none)
        integer :: transient = FC_FROM_REST               !! how a [[fc_contact_state]] enters the step
        real(dp) :: dq = 0                                !! rolling step [mm] (FC_TRANSIENT_ROLLING)
        real(dp) :: mu_kinetic = -1                       !! FC_PROBLEM_ROLLING: kinetic friction (< 0: = mu)
    end type fc_contact_loading

    !> Influence operators of one grid and material, reused while they match.
    type, public :: fc_contact_operators
        type(fc_normal_operator) :: normal          !! A^zz and its preconditioner
        type(fc_tangential_operator) :: tangential  !! tangential (and coupling) blocks
        logical :: reuse = .true.                   !! .false.: rebuild at every solve (checks, benchmarks)
        logical :: periodic = .false.               !! operators of the periodic half-space ([[fc_periodic]])
        logical :: built_periodic = .false.         !! the normal operator held is the periodic one
        integer :: builds_normal = 0                !! normal operator builds so far
        integer :: builds_tangential = 0            !! tangential operator builds so far
        real(dp) :: setup_seconds_normal = 0        !! set-up time of the last [[ensure_operators]] (0: reused)
        real(dp) :: setup_seconds_tangential = 0    !! same for the tangential operator
        !> combined influence coefficients from a file ([[set_influence_coefficients]]); when
        !! allocated they replace the half-space kernels for every block
        type(fc_ic_set) :: ic
        !> where `ic` came from, as its loader names it (the driver: the files and the
        !! materials), so that a later case naming the same source keeps the set and the
        !! operators built on it; '' when the caller set `ic` without a name
        character(len=:), allocatable :: ic_source
    contains
        procedure :: destroy => operators_destroy
    end type fc_contact_operators

    !> Previous solution of a sequence of solves.
    type, public :: fc_contact_state
        logical :: warm_start = .true.              !! start from the previous solution
        logical :: has_normal = .false.             !! pn holds a converged previous pressure
        logical :: has_tangential = .false.         !! px … fy hold a converged previous tangential state
        real(dp), allocatable :: pn(:, :)           !! previous pressure [N/mm²]
        real(dp), allocatable :: px(:, :), py(:, :) !! previous tractions p' [N/mm²]
        real(dp), allocatable :: ux(:, :), uy(:, :) !! previous tangential displacement differences u' [mm]
        integer, allocatable :: el(:, :)            !! previous element states
        real(dp) :: xi = 0, eta = 0                 !! previous shift [mm]
        real(dp) :: fx = 0, fy = 0                  !! previous tangential forces [N]
    contains
        procedure :: reset => state_reset
    end type fc_contact_state

    public :: set_influence_coefficients, take_influence_coefficients, clear_influence_coefficients

contains

    subroutine operators_destroy(self)
        class(fc_contact_operators), intent(inout) :: self
        call self%normal%destroy()
        call self%tangential%destroy()
    end subroutine operators_destroy

    !> Use the combined coefficients `ic` (content 'combined', validated) for every block
    !! from now on; the operators are rebuilt at the next solve.  FMG, which needs
    !! coefficients on coarser grids, is refused while a set is in use.
    subroutine set_influence_coefficients(ops, ic, stat, errmsg)
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_ic_set), intent(in) :: ic
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        call check_combined(ic, stat, errmsg)
        if (stat /= 0) return
        ops%ic = ic
        ops%ic_source = ''
        call ops%normal%destroy(); call ops%tangential%destroy()
    end subroutine set_influence_coefficients

    !> [[set_influence_coefficients]] without a copy: the coefficients move from `ic` (left
    !! unallocated) to `ops`, so that a large set is not held twice.  `source` names where
    !! they came from ([[fc_contact_operators]]%ic_source; default '').
    subroutine take_influence_coefficients(ops, ic, stat, errmsg, source)
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_ic_set), intent(inout) :: ic
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=*), intent(in), optional :: source
        real(dp), allocatable :: a(:, :, :, :)
        call check_combined(ic, stat, errmsg)
        if (stat /= 0) return
        if (allocated(ops%ic%a)) deallocate (ops%ic%a)
        call ops%normal%destroy(); call ops%tangential%destroy()
        call move_alloc(ic%a, a)
        ops%ic = ic
        call move_alloc(a, ops%ic%a)
        ops%ic_source = ''
        if (present(source)) ops%ic_source = source
    end subroutine take_influence_coefficients

    !> stat = FC_ERR_VALUE unless `ic` is a combined set with coefficients.
    subroutine check_combined(ic, stat, errmsg)
        type(fc_ic_set), intent(in) :: ic
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (ic%content /= 'combined' .or. .not. allocated(ic%a)) then
            stat = FC_ERR_VALUE; errmsg = "influence coefficients: a set of content 'combined' is needed (combine the bodies first)"
        end if
    end subroutine check_combined

    !> Return to the half-space coefficients (operators rebuilt at the next solve).
    subroutine clear_influence_coefficients(ops)
        type(fc_contact_operators), intent(inout) :: ops
        if (allocated(ops%ic%a)) deallocate (ops%ic%a)
        ops%ic_source = ''
        call ops%normal%destroy(); call ops%tangential%destroy()
    end subroutine clear_influence_coefficients

    !> Forget the previous solution (keeps `warm_start`).
    subroutine state_reset(self)
        class(fc_contact_state), intent(inout) :: self
        self%has_normal = .false.; self%has_tangential = .false.
    end subroutine state_reset

end module fc_contact_types
