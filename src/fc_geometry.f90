!> Potential contact grid and undeformed distance (thesis §2.2.4–2.2.5; doc/conventions.md).
!!
!! The potential contact area is the rectangle [xmin,xmax]×[ymin,ymax] divided into
!! nx×ny cell-centred elements; element (i,j) has its centre at
!! (xmin+(i-½)dx, ymin+(j-½)dy).  The undeformed distance `h0` returned here does not
!! contain the approach: the solvers use h = h0 − δ.
module fc_geometry
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fc_kinds, only: dp, i8, pi, msg_len, FC_ERR_VALUE, FC_ERR_IO, FC_ERR_AREA
    use fc_table_io, only: read_real_table
    use fc_limits, only: max_length, min_length
    use fc_geometry_grid, only: fc_grid, h_no_contact
    implicit none
    private

    public :: fc_grid, h_no_contact   ! (from [[fc_geometry_grid]])

    !> Smallest element size [mm]: below it the influence coefficients lose every digit.
    real(dp), parameter, public :: min_element_size = min_length

    !> Parameters of the random rough surface, thesis eqs. (2.13)–(2.16).
    type, public :: fc_rough_params
        real(dp) :: sigma = 0.1_dp    !! target standard deviation of heights [mm]
        real(dp) :: gamma = 0.8_dp    !! amplitude decay factor, 0 < gamma ≤ 1
        integer :: m_modes = 12       !! number of modes in x (M)
        integer :: n_modes = 10       !! number of modes in y (N)
        integer :: seed = 2015        !! seed of the portable generator
    end type fc_rough_params

    public :: make_grid, quadratic_gap, rough_heights, rough_heights_rows, punch_rough_gap, wavy_gap, read_gap_table

    integer(i8), parameter :: rng_a = 48271_i8, rng_m = 2147483647_i8

contains

    !> Build a grid, validating sizes and extents (stat = FC_ERR_AREA with a message naming
    !! the value and its limit).
    subroutine make_grid(grid, nx, ny, xmin, xmax, ymin, ymax, stat, errmsg)
        type(fc_grid), intent(out) :: grid
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: xmin, xmax, ymin, ymax
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (nx < 1 .or. ny < 1) then
            stat = FC_ERR_AREA; write (errmsg, '(a,i0,a,i0)') 'grid: nx and ny must be >= 1, got nx = ', nx, ', ny = ', ny
            return
        end if
        ! finite first: no comparison touches a NaN (floating-point traps stay quiet)
        if (.not. all(ieee_is_finite([xmin, xmax, ymin, ymax]))) then
            stat = FC_ERR_AREA; write (errmsg, '(a,4(1x,g0.6))') 'grid: xmin, xmax, ymin, ymax must be finite, got', &
                xmin, xmax, ymin, ymax
            return
        end if
        if (maxval(abs([xmin, xmax, ymin, ymax])) > max_length) then
            stat = FC_ERR_AREA
            write (errmsg, '(a,4(1x,g0.6),a,es8.1,a)') 'grid: xmin, xmax, ymin, ymax =', xmin, xmax, ymin, ymax, &
                ' exceed the limit |x|, |y| <= ', max_length, ' mm'
            return
        end if
        if (.not. (xmax > xmin) .or. .not. (ymax > ymin)) then
            stat = FC_ERR_AREA
            write (errmsg, '(a,4(es12.4))') 'grid: need xmax > xmin and ymax > ymin, got ', xmin, xmax, ymin, ymax
            return
        end if
        if ((xmax - xmin)/nx < min_element_size .or. (ymax - ymin)/ny < min_element_size) then
            stat = FC_ERR_AREA
            write (errmsg, '(a,2(es11.3e3),a,es8.1,a)') 'grid: element size dx, dy =', (xmax - xmin)/nx, &
                (ymax - ymin)/ny, ' below the limit ', min_element_size, ' mm'
            return
        end if
        grid%nx = nx; grid%ny = ny
        grid%xmin = xmin; grid%xmax = xmax; grid%ymin = ymin; grid%ymax = ymax
        grid%dx = (xmax - xmin)/nx
        grid%dy = (ymax - ymin)/ny
    end subroutine make_grid

    !> Quadratic (Hertzian) profile h0 = (x−x0)²/(2 rx) + (y−y0)²/(2 ry) [mm].
    !! A radius of 0 or a huge radius means "flat in that direction" (thesis §2.5.1).
    pure function quadratic_gap(grid, rx, ry, x0, y0) result(h0)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: rx, ry          !! relative radii of curvature [mm]
        real(dp), intent(in), optional :: x0, y0 !! centre of the profile [mm]
        real(dp) :: h0(grid%nx, grid%ny)
        real(dp) :: cx, cy, ax, ay, xc, yc
        integer :: i, j
        xc = 0; yc = 0
        if (present(x0)) xc = x0
        if (present(y0)) yc = y0
        ax = 0; ay = 0
        if (rx > 0) ax = 0.5_dp/rx
        if (ry > 0) ay = 0.5_dp/ry
        do j = 1, grid%ny
            cy = grid%y(j) - yc
            do i = 1, grid%nx
                cx = grid%x(i) - xc
                h0(i, j) = ax*cx**2 + ay*cy**2
            end do
        end do
    end function quadratic_gap

    !> Next uniform number in (0,1) of the portable MINSTD generator (reproducible
    !! on every compiler, unlike `random_number`).
    subroutine next_uniform(state, r)
        integer(i8), intent(inout) :: state
        real(dp), intent(out) :: r
        state = mod(rng_a*state, rng_m)
        r = real(state, dp)/real(rng_m, dp)
    end subroutine next_uniform

    !> Rough surface heights z(x,y), thesis eqs. (2.13)–(2.16), on the whole grid.
    !! The amplitudes are scaled so that R(0,0) = sigma² exactly (eq. 2.16); the
    !! rectangle [0,lx]×[0,ly] of eq. (2.13) is the potential contact area.
    subroutine rough_heights(grid, par, z)
        type(fc_grid), intent(in) :: grid
        type(fc_rough_params), intent(in) :: par
        real(dp), intent(out) :: z(grid%nx, grid%ny)
        call rough_heights_rows(grid, par, 1, grid%ny, z)
    end subroutine rough_heights

    !> Rows jfirst…jlast of [[rough_heights]] (a distributed run generates its own slab;
    !! the values equal the whole-grid ones bit for bit: same modes, same arithmetic).
    subroutine rough_heights_rows(grid, par, jfirst, jlast, z)
        type(fc_grid), intent(in) :: grid
        type(fc_rough_params), intent(in) :: par
        integer, intent(in) :: jfirst, jlast
        real(dp), intent(out) :: z(grid%nx, jfirst:jlast)
        real(dp) :: amp(par%m_modes, par%n_modes), phx(par%m_modes, par%n_modes), phy(par%m_modes, par%n_modes)
        real(dp) :: r, lx, ly, r00, xi, yj
        real(dp), allocatable :: cx(:), cy(:)
        integer(i8) :: state
        integer :: m, n, i, j
        state = max(1_i8, mod(abs(int(par%seed, i8)), rng_m - 1) + 1)   ! abs in 64 bits: seed = -2^31 is valid
        do n = 1, par%n_modes
            do m = 1, par%m_modes
                call next_uniform(state, r); phx(m, n) = 2*pi*r
                call next_uniform(state, r); phy(m, n) = 2*pi*r
                call next_uniform(state, r); amp(m, n) = r*par%gamma**(m + n - 2)
            end do
        end do
        r00 = 0.25_dp*sum(amp**2)                        ! eq. (2.15) with the trial amplitudes
        amp = amp*par%sigma/sqrt(r00)                     ! eq. (2.16)
        lx = grid%xmax - grid%xmin
        ly = grid%ymax - grid%ymin
        allocate (cx(grid%nx), cy(jfirst:jlast))
        z = 0
        do n = 1, par%n_modes
            do m = 1, par%m_modes
                do i = 1, grid%nx
                    xi = grid%x(i) - grid%xmin
                    cx(i) = cos(2*pi*m*xi/lx + phx(m, n))
                end do
                do j = jfirst, jlast
                    yj = grid%y(j) - grid%ymin
                    cy(j) = cos(2*pi*n*yj/ly + phy(m, n))
                end do
                do j = jfirst, jlast
                    z(:, j) = z(:, j) + amp(m, n)*cx*cy(j)
                end do
            end do
        end do
    end subroutine rough_heights_rows

    !> Flat rigid circular punch of diameter `diameter` on a rough surface (thesis §2.5.2):
    !! h0 = −z inside the punch, `h_no_contact` outside (the approach δ is added by the solver).
    subroutine punch_rough_gap(grid, diameter, par, h0)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: diameter   !! punch diameter D [mm]
        type(fc_rough_params), intent(in) :: par
        real(dp), intent(out) :: h0(grid%nx, grid%ny)
        real(dp) :: z(grid%nx, grid%ny)
        integer :: i, j
        call rough_heights(grid, par, z)
        do j = 1, grid%ny
            do i = 1, grid%nx
                if (grid%x(i)**2 + grid%y(j)**2 <= 0.25_dp*diameter**2) then
                    h0(i, j) = -z(i, j)
                else
                    h0(i, j) = h_no_contact
                end if
            end do
        end do
    end subroutine punch_rough_gap

    !> Wavy surface h0 = A·(1 − cos(2πx/λx)·cos(2πy/λy)) (Johnson §13.2); λ ≤ 0 means flat
    !! in that direction.
    pure function wavy_gap(grid, amplitude, wavelength_x, wavelength_y) result(h0)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: amplitude, wavelength_x, wavelength_y  !! [mm]
        real(dp) :: h0(grid%nx, grid%ny)
        real(dp) :: fx, fy
        integer :: i, j
        do j = 1, grid%ny
            fy = 1
            if (wavelength_y > 0) fy = cos(2*pi*grid%y(j)/wavelength_y)
            do i = 1, grid%nx
                fx = 1
                if (wavelength_x > 0) fx = cos(2*pi*grid%x(i)/wavelength_x)
                h0(i, j) = amplitude*(1 - fx*fy)
            end do
        end do
    end function wavy_gap

    !> Read nx·ny undeformed distances [mm] from a text file, x running fastest.
    !! Blank lines and lines starting with '#' or '!' are skipped; several values per
    !! line are allowed.
    subroutine read_gap_table(filename, grid, h0, stat, errmsg)
        character(len=*), intent(in) :: filename
        type(fc_grid), intent(in) :: grid
        real(dp), intent(out) :: h0(grid%nx, grid%ny)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), allocatable :: vals(:)
        allocate (vals(grid%nx*grid%ny))
        call read_real_table(filename, vals, stat, errmsg)
        if (stat /= 0) return
        h0 = reshape(vals, [grid%nx, grid%ny])
    end subroutine read_gap_table

end module fc_geometry
