!> What the automatic layer ([[fc_auto]]) decided and computed for one case: the grids
!! visited, the accuracy estimate, the model reductions and warnings, and the final
!! solution.  A module of its own so that the outputs can write it without depending on
!! the layer that computes it.
module fc_case_result
    use fc_kinds, only: dp
    use fc_geometry, only: fc_grid
    use fc_influence, only: fc_material
    use fc_hertz, only: fc_hertz_solution, fc_cattaneo_solution
    use fc_contact_types, only: fc_contact_result
    implicit none
    private

    !> One grid visited by the solve.
    type, public :: fc_level
        integer :: nx = 0, ny = 0                 !! grid size
        real(dp) :: fn = 0, approach = 0          !! normal load and approach [N, mm]
        real(dp) :: fx = 0, fy = 0                !! tangential forces [N]
        real(dp) :: xi = 0, eta = 0               !! rigid shift used [mm]
        real(dp) :: pmax = 0                      !! maximum pressure [N/mm²]
        integer :: ncon = 0                       !! elements in contact
        integer :: iterations = 0                 !! solver iterations (both stages)
        real(dp) :: seconds = 0                   !! operator set-up + solve [s]
        real(dp) :: estimate = -1                 !! estimated relative error (−1: not yet known)
        real(dp) :: ratio = 0                     !! observed ratio of successive differences (0: n/a)
        logical :: monotone = .true.              !! successive differences decrease with one sign
        character(len=16) :: status = ''         !! solver status
    end type fc_level

    !> Everything the automatic layer decided and computed for one case.
    type, public :: fc_auto_outcome
        character(len=32) :: model = 'full'                !! 'full', 'strip2d', 'hertz_analytic'
        character(len=256), allocatable :: reductions(:)   !! model reductions applied (one line each)
        character(len=512), allocatable :: warnings(:)     !! warnings (boundary, unreliable estimate, ...)
        type(fc_level), allocatable :: levels(:)           !! grids visited (coarse to fine)
        real(dp) :: target = 0                             !! accuracy target (0: none)
        real(dp) :: estimate = -1                          !! estimated relative error of the final grid
        logical :: reliable = .true.                       !! convergence was monotone
        logical :: target_met = .false.                    !! estimate ≤ target
        character(len=64) :: quantities = ''               !! quantities the estimate covers
        !> Index in `levels` of the coarsest grid visited that is certified to meet the target
        !! (0: none): its error bound max_q |q_j − q_n| + estimate uses the finest grid n
        integer :: sufficient = 0
        real(dp) :: sufficient_bound = -1                  !! that certified bound (relative)
        logical :: grid_auto = .false.                     !! potential area sized automatically
        integer :: enlargements = 0                        !! automatic enlargements of the area
        logical :: touches_boundary = .false.              !! final contact reaches the area's edge
        real(dp) :: total_seconds = 0                      !! all solves incl. set-up [s]
        real(dp) :: tol = 0                                !! solver tolerance used (tightened for a target)
        type(fc_material) :: material                      !! combined constants
        type(fc_grid) :: grid                              !! final grid
        real(dp), allocatable :: h0(:, :)                  !! final undeformed distance
        type(fc_contact_result) :: result                  !! final grid's solution, counters, set-up times
        logical :: tangential = .false.                    !! a tangential solve was planned (not reduced away)
        logical :: analytic = .false.                      !! answered by the analytic Hertz solution
        type(fc_hertz_solution) :: hertz                   !! analytic Hertz (problem = 'hertz')
        logical :: has_cattaneo = .false.                  !! Cattaneo–Mindlin part present
        type(fc_cattaneo_solution) :: cattaneo             !! analytic Cattaneo–Mindlin
        real(dp) :: fx = 0, fy = 0                         !! analytic tangential forces [N]
        real(dp) :: mz = 0                                 !! FASTSIM spin moment [N·mm]
        real(dp), allocatable :: sequence(:, :)            !! rolling sweep / transient steps: one row each
    end type fc_auto_outcome

end module fc_case_result
