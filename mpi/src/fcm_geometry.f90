!> Undeformed distance of one rank's rows (rows jfirst…jlast of the grid), generated
!! where it is used: no rank ever holds the whole grid.  Every value equals the one the
!! serial routine of [[fc_geometry]] gives for the same grid, bit for bit (same formulas,
!! same order of operations; the rough surface shares [[rough_heights_rows]]).
module fcm_geometry
    use fc_kinds, only: dp, pi
    use fc_geometry, only: fc_grid, fc_rough_params, rough_heights_rows, h_no_contact
    implicit none
    private
    public :: quadratic_gap_rows, wavy_gap_rows, punch_rough_gap_rows

contains

    !> Rows of [[quadratic_gap]] (profile centred at the origin) [mm].
    pure subroutine quadratic_gap_rows(grid, rx, ry, jfirst, jlast, h0)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: rx, ry
        integer, intent(in) :: jfirst, jlast
        real(dp), intent(out) :: h0(grid%nx, jfirst:jlast)
        real(dp) :: ax, ay, cx, cy
        integer :: i, j
        ax = 0; ay = 0
        if (rx > 0) ax = 0.5_dp/rx
        if (ry > 0) ay = 0.5_dp/ry
        do j = jfirst, jlast
            cy = grid%y(j) - 0
            do i = 1, grid%nx
                cx = grid%x(i) - 0
                h0(i, j) = ax*cx**2 + ay*cy**2
            end do
        end do
    end subroutine quadratic_gap_rows

    !> Rows of [[wavy_gap]] [mm].
    pure subroutine wavy_gap_rows(grid, amplitude, wavelength_x, wavelength_y, jfirst, jlast, h0)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: amplitude, wavelength_x, wavelength_y
        integer, intent(in) :: jfirst, jlast
        real(dp), intent(out) :: h0(grid%nx, jfirst:jlast)
        real(dp) :: fx, fy
        integer :: i, j
        do j = jfirst, jlast
            fy = 1
            if (wavelength_y > 0) fy = cos(2*pi*grid%y(j)/wavelength_y)
            do i = 1, grid%nx
                fx = 1
                if (wavelength_x > 0) fx = cos(2*pi*grid%x(i)/wavelength_x)
                h0(i, j) = amplitude*(1 - fx*fy)
            end do
        end do
    end subroutine wavy_gap_rows

    !> Rows of [[punch_rough_gap]]: −z inside the punch of diameter D, h_no_contact outside.
    subroutine punch_rough_gap_rows(grid, diameter, par, jfirst, jlast, h0)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: diameter
        type(fc_rough_params), intent(in) :: par
        integer, intent(in) :: jfirst, jlast
        real(dp), intent(out) :: h0(grid%nx, jfirst:jlast)
        real(dp), allocatable :: z(:, :)
        integer :: i, j
        allocate (z(grid%nx, jfirst:jlast))
        call rough_heights_rows(grid, par, jfirst, jlast, z)
        do j = jfirst, jlast
            do i = 1, grid%nx
                if (grid%x(i)**2 + grid%y(j)**2 <= 0.25_dp*diameter**2) then
                    h0(i, j) = -z(i, j)
                else
                    h0(i, j) = h_no_contact
                end if
            end do
        end do
    end subroutine punch_rough_gap_rows

end module fcm_geometry
