!> Undeformed distance as a formula that can be evaluated on any grid.
!!
!! Multigrid needs h0 on every level of a grid hierarchy.  A [[fc_surface]] evaluates its
!! formula at the element centres of whatever grid it is given, as the thesis does for the
!! rough surface (thesis Fig. 2.11), instead of averaging the finest grid's values.
!! Extend [[fc_surface]] (defined with the grid type in [[fc_geometry_grid]]) for your own
!! geometry.
module fc_geometry_surfaces
    use fc_kinds, only: dp
    use fc_geometry_grid, only: fc_surface
    use fc_geometry, only: fc_grid, quadratic_gap, punch_rough_gap, wavy_gap, fc_rough_params
    implicit none
    private

    ! the abstract surface lives beside the grid type (below the multigrid levels that hold
    ! one); the package's surfaces extend it here
    public :: fc_surface

    !> Quadratic (Hertzian) profile h0 = x²/(2 rx) + y²/(2 ry), thesis §2.5.1.
    type, extends(fc_surface), public :: fc_quadratic_surface
        real(dp) :: rx = 0, ry = 0   !! relative radii of curvature [mm] (0: flat)
    contains
        procedure :: evaluate => quadratic_evaluate
    end type fc_quadratic_surface

    !> Rigid flat punch on a random rough surface, thesis §2.5.2 (eqs. 2.13–2.16).
    type, extends(fc_surface), public :: fc_punch_rough_surface
        real(dp) :: diameter = 8.97_dp        !! punch diameter [mm]
        type(fc_rough_params) :: rough        !! σ, γ, M, N, seed
    contains
        procedure :: evaluate => punch_rough_evaluate
    end type fc_punch_rough_surface

    !> Wavy surface A·(1 − cos(2πx/λx)·cos(2πy/λy)).
    type, extends(fc_surface), public :: fc_wavy_surface
        real(dp) :: amplitude = 0, wavelength_x = 0, wavelength_y = 0  !! [mm]
    contains
        procedure :: evaluate => wavy_evaluate
    end type fc_wavy_surface


contains

    subroutine quadratic_evaluate(self, grid, h0)
        class(fc_quadratic_surface), intent(in) :: self
        type(fc_grid), intent(in) :: grid
        real(dp), intent(out) :: h0(:, :)
        h0 = quadratic_gap(grid, self%rx, self%ry)
    end subroutine quadratic_evaluate

    subroutine punch_rough_evaluate(self, grid, h0)
        class(fc_punch_rough_surface), intent(in) :: self
        type(fc_grid), intent(in) :: grid
        real(dp), intent(out) :: h0(:, :)
        call punch_rough_gap(grid, self%diameter, self%rough, h0)
    end subroutine punch_rough_evaluate

    subroutine wavy_evaluate(self, grid, h0)
        class(fc_wavy_surface), intent(in) :: self
        type(fc_grid), intent(in) :: grid
        real(dp), intent(out) :: h0(:, :)
        h0 = wavy_gap(grid, self%amplitude, self%wavelength_x, self%wavelength_y)
    end subroutine wavy_evaluate

end module fc_geometry_surfaces
