!> The settings of the FMG / MG + active-set solver of normal contact (thesis §2.4), apart
!! from the hierarchy ([[fc_fmg_levels]]) and the solver ([[fc_fmg]]), so that the
!! orchestrator's types ([[fc_contact_types]]) and the case description hold them without
!! depending on the multigrid procedures.
module fc_fmg_types
    use fc_kinds, only: dp
    implicit none
    private

    !> Settings of the FMG / MG + active-set solver.
    type, public :: fc_fmg_settings
        integer :: nu1 = 1                 !! pre-smoothing sweeps (V(nu1,nu2))
        integer :: nu2 = 1                 !! post-smoothing sweeps
        real(dp) :: omega = 0.8_dp         !! damping of the smoother (thesis Table 2.1)
        real(dp) :: beta = 0.003_dp        !! initial-area parameter of eq. (2.17)
        real(dp) :: tol = 1.0e-6_dp        !! stopping rule (2.18) on the target grid
        integer :: maxit = 100             !! active-set iterations (cycles) on the target grid
        integer :: maxit_level = 50        !! active-set iterations on intermediate grids
        integer :: coarsest = 4            !! stop coarsening below this many cells per direction
        logical :: nested = .true.         !! .true.: FMG; .false.: MG + active set from {h ≤ 0}
        character(len=8) :: smoother = 'gs'  !! 'gs' (thesis), 'jacobi' (fails), 'fft-rsm' (§6.3)
        logical :: keep_history = .false.  !! store the pressure after every target-grid cycle
        real(dp) :: rsm_floor = 0.8_dp     !! 'fft-rsm': diagonal of M̄ floored at rsm_floor/A_ii (0: thesis RSM)
    end type fc_fmg_settings

end module fc_fmg_types
