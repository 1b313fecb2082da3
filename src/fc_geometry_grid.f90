!> The grid type of the potential contact area (doc/conventions.md): nx×ny cell-centred
!! elements on [xmin,xmax]×[ymin,ymax]; element (i,j) has its centre at
!! (xmin+(i-½)dx, ymin+(j-½)dy), and the abstract [[fc_surface]], an undeformed distance
!! evaluated on any grid.  A module of its own, below the influence coefficients and the
!! solvers that need only the types; [[fc_geometry]] builds grids ([[make_grid]]) and
!! undeformed distances and re-exports the grid type, [[fc_geometry_surfaces]] the surfaces.
module fc_geometry_grid
    use fc_kinds, only: dp
    implicit none
    private

    !> Grid of the potential contact area (units: mm).
    type, public :: fc_grid
        integer :: nx = 0            !! elements in x
        integer :: ny = 0            !! elements in y
        real(dp) :: xmin = 0, xmax = 0, ymin = 0, ymax = 0  !! outer edges [mm]
        real(dp) :: dx = 0, dy = 0   !! element size [mm]
    contains
        procedure :: x => grid_x
        procedure :: y => grid_y
        procedure :: n => grid_n
        procedure :: area => grid_area
    end type fc_grid

    !> Undeformed distance that keeps an element out of contact (outside a punch).
    real(dp), parameter, public :: h_no_contact = 1.0e20_dp

    !> Undeformed distance h0 (without approach) as a formula that can be evaluated on
    !! any grid; FMG evaluates it on every level.  Extend it for your own geometry
    !! ([[fc_geometry_surfaces]] has the package's).
    type, abstract, public :: fc_surface
    contains
        procedure(surface_evaluate), deferred :: evaluate
    end type fc_surface

    abstract interface
        !> h0 [mm] at the element centres of `grid`; `h_no_contact` where no contact can occur.
        subroutine surface_evaluate(self, grid, h0)
            import :: fc_surface, fc_grid, dp
            class(fc_surface), intent(in) :: self
            type(fc_grid), intent(in) :: grid
            real(dp), intent(out) :: h0(:, :)
        end subroutine surface_evaluate
    end interface

contains

    !> x coordinate of the centre of column i [mm].
    elemental real(dp) function grid_x(self, i)
        class(fc_grid), intent(in) :: self
        integer, intent(in) :: i
        grid_x = self%xmin + (i - 0.5_dp)*self%dx
    end function grid_x

    !> y coordinate of the centre of row j [mm].
    elemental real(dp) function grid_y(self, j)
        class(fc_grid), intent(in) :: self
        integer, intent(in) :: j
        grid_y = self%ymin + (j - 0.5_dp)*self%dy
    end function grid_y

    !> Number of elements.
    pure integer function grid_n(self)
        class(fc_grid), intent(in) :: self
        grid_n = self%nx*self%ny
    end function grid_n

    !> Element area dx·dy [mm²].
    pure real(dp) function grid_area(self)
        class(fc_grid), intent(in) :: self
        grid_area = self%dx*self%dy
    end function grid_area

end module fc_geometry_grid
