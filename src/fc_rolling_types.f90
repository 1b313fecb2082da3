!> The value types of steady and transient rolling — solver settings, loading, and what a
!! rolling case adds to a contact case — apart from the solvers ([[fc_rolling]],
!! [[fc_rolling_refsolvers]], [[fc_rolling_base]] re-exports them), so that the
!! orchestrator's types ([[fc_contact_types]]) and the case description ([[fc_scene]]) hold
!! them without depending on the solvers.
module fc_rolling_types
    use fc_kinds, only: dp
    implicit none
    private

    !> Settings of the steady rolling solvers.
    type, public :: fc_rolling_settings
        character(len=8) :: solver = 'gmres'   !! 'gmres' (Newton–GMRES), 'march' or 'steadygs' (references)
        real(dp) :: tol = 1.0e-5_dp            !! relative traction change (thesis eq. 4.49)
        integer :: maxit = 2000                !! GMRES: Krylov iterations in all; SteadyGS: sweeps
        integer :: restart = 40                !! GMRES restart length
        real(dp) :: forcing = 0.1_dp           !! GMRES: relative residual reduction per Newton step
        !> GMRES left preconditioner of the adhesion rows: 'fft' (run sums along x, then TangCG's
        !! FFT block inverse of A on the adhesion area) or 'runsum' (run sums, diagonal scaling)
        character(len=8) :: preconditioner = 'fft'
        !> 'fft': applied as the Strang circulant of the block inverse on the grid ('circulant')
        !! or as the block inverse itself on the doubled grid ('toeplitz'), as TangCG's
        character(len=9) :: prec_form = 'circulant'
        !> Eisenstat–Walker's superlinear forcing term of GMRES once the subdivision has settled
        !! (.false.: the constant `forcing` throughout)
        logical :: adaptive_forcing = .true.
        !> GMRES without starting tractions: 'fastsim' (the simplified theory's tractions on
        !! the grid, [[fastsim_on_grid]]: the slip area starts near its place) or 'adhesion'
        !! (zero tractions, every contact element in adhesion)
        character(len=8) :: start = 'fastsim'
        !> Creep-force sweeps ([[rolling_sequence]]): start a point from the linear
        !! extrapolation of the two converged points before it instead of from the last one
        logical :: sweep_predictor = .true.
        !> GMRES, circulant form: apply the FFT block inverse in every Newton step of a solve
        !! started from given tractions (a previous solution: sweep points, flat-API calls,
        !! the inner solves of a creep-force loop), whatever the adhesion share; .false.: only
        !! from 50 % adhesion, as from a cold start
        logical :: fft_resumed = .true.
    end type fc_rolling_settings

    !> Loading of a steady rolling problem.
    type, public :: fc_rolling_loading
        real(dp) :: mu = 0                !! static coefficient of friction μs
        real(dp) :: mu_kinetic = -1       !! kinetic coefficient μk (< 0: equal to μs)
        real(dp) :: xi = 0, eta = 0       !! longitudinal and lateral creepage [-]
        real(dp) :: phi = 0               !! spin creepage [1/mm]
        real(dp) :: fx = 0, fy = 0        !! prescribed creep forces [N] (force_prescribed)
        logical :: force_prescribed = .false.
    end type fc_rolling_loading

    !> What a rolling case adds to a contact case: the kinetic friction of steady rolling,
    !! and a sequence — a creep-force sweep of one loading value, or transient rolling steps.
    type, public :: fc_rolling_case
        real(dp) :: mu_kinetic = -1        !! steady rolling: kinetic friction in slip (< 0: = mu)
        logical :: transient = .false.     !! transient rolling: steps of dq from rest
        real(dp) :: dq = 0                 !! transient: distance per step [mm] (0: dx)
        integer :: nsteps = 0              !! transient: steps (0: the area length travelled 4 times)
        character(len=8) :: sweep = ''     !! steady: swept value 'xi', 'eta', 'phi', 'fx', 'fy' ('': none)
        real(dp) :: sweep_from = 0, sweep_to = 0  !! range of the swept value (ends included)
        integer :: sweep_n = 20            !! points of the sweep
        logical :: fastsim = .false.       !! steady: Kalker's simplified theory on the Hertz ellipse, no grid
    end type fc_rolling_case

end module fc_rolling_types
