!> Value types of the tangential problem (thesis ch. 4): solver settings, loading, result and
!! the element states.  Kept apart from the solvers ([[fc_tangcg]]) so that the case
!! description, the orchestrator's types and the rolling solvers' types can use them
!! without depending on TangCG's procedures; [[fc_tangcg]] re-exports everything here.
module fc_tangcg_types
    use fc_kinds, only: dp, msg_len, FC_ERROR
    implicit none
    private

    integer, parameter, public :: EL_EXTERIOR = 0, EL_ADHESION = 1, EL_SLIP = 2  !! element states

    !> Settings of the tangential solvers.
    type, public :: fc_tangential_settings
        character(len=8) :: solver = 'tangcg'   !! 'tangcg' or 'convexgs'
        real(dp) :: tol = 1.0e-5_dp              !! relative traction change, eq. (4.49)
        integer :: maxit = 2000                  !! TangCG inner iterations / ConvexGS sweeps
        integer :: inner_k = 3                   !! (TangCG) NLCG iterations between subdivision checks
        logical :: precondition = .true.         !! (TangCG) preconditioner on
        character(len=8) :: preconditioner = 'fft'  !! (TangCG) 'fft' (block Toeplitz inverse on adhesion,
                                                 !! diagonal on slip, elastic start) or 'diagonal' (eq. 4.43)
        !> 'fft' preconditioner applied as its Strang circulant on the grid ('circulant',
        !! periodic transforms of nx×ny points) or as the block Toeplitz inverse itself on the
        !! doubled grid ('toeplitz'); doc/solvers.md
        character(len=9) :: prec_form = 'circulant'
    end type fc_tangential_settings

    !> Result of a tangential solve.
    type, public :: fc_tangential_result
        real(dp), allocatable :: px(:, :), py(:, :)  !! tangential tractions on body 1 [N/mm²]
        real(dp), allocatable :: sx(:, :), sy(:, :)  !! slip s = w + u − u' + offset [mm]
        real(dp), allocatable :: ux(:, :), uy(:, :)  !! tangential displacement differences A·p [mm]
        integer, allocatable :: state(:, :)          !! EL_EXTERIOR, EL_ADHESION, EL_SLIP
        real(dp) :: xi = 0, eta = 0, phi = 0         !! rigid shift used [mm, mm, rad]
        real(dp) :: fx = 0, fy = 0                   !! tangential forces [N]
        real(dp) :: mz = 0                           !! moment Σ (x·py − y·px)·dx·dy [N·mm]
        !> frictional dissipation −Σ (px·sx + py·sy)·dx·dy ≥ 0: the work of friction over a
        !! shift or a transient step [N·mm]; in steady rolling, where the slip is a velocity
        !! over the rolling velocity, the work per mm rolled [N] (the wear number Tγ)
        real(dp) :: dissipation = 0
        integer :: ncon = 0, nadh = 0, nslip = 0
        integer :: status = FC_ERROR
        integer :: iterations = 0        !! TangCG inner iterations / ConvexGS sweeps (all force steps)
        integer :: outer_iterations = 0  !! subdivision checks (TangCG) / force-loop steps
        integer :: matvecs = 0           !! combined 2×2 block products by FFT
        real(dp) :: residual = huge(1.0_dp)  !! final relative traction change (4.49)
        real(dp) :: cpu_seconds = 0
        character(len=msg_len) :: message = ''
        real(dp), allocatable :: history(:)  !! relative traction change per iteration
    end type fc_tangential_result

    !> Tangential loading: friction and either the rigid shift (ξ, η) or the forces (Fx, Fy);
    !! the spin φ is always prescribed (doc/namelist.md `&tangential`).
    type, public :: fc_tangential_loading
        real(dp) :: mu = 0                    !! coefficient of friction
        real(dp) :: xi = 0, eta = 0           !! prescribed shifts [mm] (force_prescribed = .false.)
        real(dp) :: phi = 0                   !! spin shift [rad]
        real(dp) :: fx = 0, fy = 0            !! prescribed tangential forces [N] (force_prescribed)
        logical :: force_prescribed = .false.
    end type fc_tangential_loading

    public :: frictional_dissipation

contains

    !> Frictional dissipation of a solution, −Σ (px·sx + py·sy)·`area` (`area` = dx·dy of
    !! one element [mm²]): ≥ 0, as the tractions oppose the slip; zero in adhesion.  [N·mm]
    !! for slips in mm (shift, transient step), [N] for slip velocities over the rolling
    !! velocity (steady rolling).  0 when the result has no slip.
    pure real(dp) function frictional_dissipation(res, area) result(d)
        type(fc_tangential_result), intent(in) :: res
        real(dp), intent(in) :: area
        integer :: i, j
        d = 0
        if (.not. (allocated(res%sx) .and. allocated(res%sy) .and. allocated(res%px) .and. allocated(res%py))) return
        do j = 1, size(res%px, 2)
            do i = 1, size(res%px, 1)
                d = d - (res%px(i, j)*res%sx(i, j) + res%py(i, j)*res%sy(i, j))
            end do
        end do
        d = d*area
    end function frictional_dissipation

end module fc_tangcg_types
