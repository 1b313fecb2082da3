!> FASTSIM, Kalker's simplified theory of steady rolling (Kalker 1982, "A fast algorithm for
!! the simplified theory of rolling contact", Veh. Syst. Dyn. 11) — the cheap model railway
!! codes use when the full theory is too slow.
!!
!! The surface displacement is taken proportional to the local traction, u = L·p, with one
!! flexibility per direction chosen so that the simplified theory reproduces Kalker's
!! linear-theory creep coefficients (module [[fc_rolling_ref]]):
!!   L1 = 8a/(3·G·C11),  L2 = 8a/(3·G·C22),  L3 = π·a·√(a/b)/(4·G·C23).
!! With the parabolic traction bound g = μ·(2Fn/(πab))·(1 − x²/a² − y²/b²) on the contact
!! ellipse, the steady slip s = w − ∂u/∂x is integrated strip by strip from the leading
!! edge x = +a(y) (conventions of the full solver: body 1 rolls in +x, forces on body 1,
!! w = [ξ − φ·y, η + φ·x]):  p(x − δx) = p(x) − δx·[ξ/L1 − φ·y/L3, η/L2 + φ·x/L3], clipped
!! to |p| ≤ g.  Cost O(nx·ny), no linear system.
module fc_fastsim
    use fc_kinds, only: dp, pi, FC_ERR_VALUE
    use fc_rolling_ref, only: kalker_coefficients
    use fc_geometry_grid, only: fc_grid
    implicit none
    private

    !> Creep forces of FASTSIM.
    type, public :: fc_fastsim_result
        real(dp) :: fx = 0, fy = 0   !! creep forces on body 1 [N]
        real(dp) :: mz = 0           !! spin moment Σ (x·py − y·px)·δA [N·mm]
        real(dp) :: c11 = 0, c22 = 0, c23 = 0   !! Kalker coefficients used
        integer :: nslip = 0, ncon = 0           !! elements at the traction bound, elements in all
    end type fc_fastsim_result

    public :: fastsim, fastsim_error_bound, fastsim_on_grid

    !> Measured error of FASTSIM against the full theory: the largest |F_fastsim − F_full|/(μFn)
    !! over the normalised creepage 0.1 … 3 (fastcontact-bench-rolling --fastsim, ν = 0.25,
    !! doc/rolling.md), rows a/b = 0.2, 0.5, 1, 2, 5, columns ξ, η, φ.
    real(dp), parameter :: ratio_nodes(5) = [0.2_dp, 0.5_dp, 1.0_dp, 2.0_dp, 5.0_dp]
    real(dp), parameter :: measured_error(5, 3) = reshape([ &
        0.056_dp, 0.039_dp, 0.030_dp, 0.026_dp, 0.022_dp, &
        0.053_dp, 0.035_dp, 0.026_dp, 0.023_dp, 0.021_dp, &
        0.014_dp, 0.046_dp, 0.073_dp, 0.090_dp, 0.082_dp], [5, 3])

contains

    !> FASTSIM on the ellipse with semi-axes a (rolling direction), b [mm], normal force
    !! fn [N], friction mu, combined shear modulus g [N/mm²] and ratio nu, creepages xi, eta
    !! [-] and spin phi [1/mm]; nx × ny elements (strips along y, nx along each strip).
    !! stat ≠ 0 for invalid input (message in errmsg): a, b, fn, g > 0, mu ≥ 0,
    !! 0.1 ≤ a/b ≤ 10 (the range of the creep-coefficient table), 2 ≤ nx, ny ≤ 10000.
    subroutine fastsim(a, b, fn, mu, g, nu, xi, eta, phi, nx, ny, res, stat, errmsg)
        real(dp), intent(in) :: a, b, fn, mu, g, nu, xi, eta, phi
        integer, intent(in) :: nx, ny
        type(fc_fastsim_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: l1, l2, l3, p0, dy, y, ay, dx, x, px, py, gb, t, area
        integer :: i, j
        stat = FC_ERR_VALUE; errmsg = ''
        if (.not. (a > 0 .and. b > 0 .and. fn > 0 .and. g > 0 .and. mu >= 0)) then
            write (errmsg, '(a,5(g0.6,a))') 'fastsim: a = ', a, ', b = ', b, ', fn = ', fn, ', g = ', g, &
                ', mu = ', mu, ': a, b, fn, g must be > 0 and mu >= 0'
            return
        end if
        if (nx < 2 .or. ny < 2 .or. nx > 10000 .or. ny > 10000) then
            write (errmsg, '(a,i0,a,i0,a)') 'fastsim: nx = ', nx, ', ny = ', ny, ' must lie in [2, 10000]'; return
        end if
        call kalker_coefficients(nu, a/b, res%c11, res%c22, res%c23, stat)
        if (stat /= 0) then
            write (errmsg, '(a,g0.6,a,g0.6,a)') 'fastsim: a/b = ', a/b, ', nu = ', nu, &
                ': outside the creep-coefficient table (0.1 <= a/b <= 10, 0 <= nu <= 0.5)'
            return
        end if
        l1 = 8*a/(3*g*res%c11)
        l2 = 8*a/(3*g*res%c22)
        l3 = pi*a*sqrt(a/b)/(4*g*res%c23)
        p0 = 2*fn/(pi*a*b)                 ! peak of the parabolic traction bound / mu
        dy = 2*b/ny
        res%fx = 0; res%fy = 0; res%mz = 0; res%nslip = 0; res%ncon = 0
        do j = 1, ny
            y = -b + (j - 0.5_dp)*dy
            ay = a*sqrt(max(0.0_dp, 1 - (y/b)**2))
            dx = 2*ay/nx
            area = dx*dy
            px = 0; py = 0
            do i = 1, nx
                x = ay - (i - 0.5_dp)*dx      ! from the leading edge backwards
                px = px - dx*(xi/l1 - phi*y/l3)
                py = py - dx*(eta/l2 + phi*x/l3)
                gb = mu*p0*max(0.0_dp, 1 - (x/a)**2 - (y/b)**2)
                t = hypot(px, py)
                if (t > gb) then
                    if (t > 0) then
                        px = px*gb/t; py = py*gb/t
                    end if
                    res%nslip = res%nslip + 1
                end if
                res%ncon = res%ncon + 1
                res%fx = res%fx + px*area
                res%fy = res%fy + py*area
                res%mz = res%mz + (x*py - y*px)*area
            end do
        end do
        stat = 0
    end subroutine fastsim

    !> FASTSIM's tractions on a solver grid, as the cold start of the full theory's steady
    !! rolling solver ([[fc_rolling]]): each grid row is integrated from its leading element
    !! (largest x) backwards over its run of contact elements, with the element's own traction
    !! bound (`bound`, e.g. μk·pn [N/mm²]) in place of the parabolic one, so that any pressure
    !! (not only Hertzian) gets a start whose slip area lies at the trailing side as in the
    !! full theory.  The flexibilities are those of [[fastsim]] for the ellipse that spans the
    !! contact elements' extent (a/b clipped to the coefficient table, 0.1 … 10) and the
    !! combined shear modulus g [N/mm²] and ratio nu.  Tractions on body 1 [N/mm²], zero outside
    !! `contact`; px = py = 0 everywhere when no element is in contact.
    pure subroutine fastsim_on_grid(grid, contact, bound, g, nu, xi, eta, phi, px, py)
        type(fc_grid), intent(in) :: grid
        logical, intent(in) :: contact(:, :)
        real(dp), intent(in) :: bound(:, :), g, nu, xi, eta, phi
        real(dp), intent(out) :: px(:, :), py(:, :)
        real(dp) :: a, b, x0, x1, y0, y1, c11, c22, c23, l1, l2, l3, qx, qy, x, y, t
        integer :: i, j, st
        px = 0; py = 0
        if (.not. any(contact) .or. .not. g > 0) return
        x0 = huge(1.0_dp); x1 = -x0; y0 = x0; y1 = -x0
        do j = 1, size(contact, 2)
            if (.not. any(contact(:, j))) cycle
            y0 = min(y0, grid%y(j)); y1 = max(y1, grid%y(j))
            do i = 1, size(contact, 1)
                if (contact(i, j)) then
                    x0 = min(x0, grid%x(i)); x1 = max(x1, grid%x(i))
                end if
            end do
        end do
        a = (x1 - x0 + grid%dx)/2; b = (y1 - y0 + grid%dy)/2
        call kalker_coefficients(min(0.5_dp, max(0.0_dp, nu)), max(0.1_dp, min(10.0_dp, a/b)), c11, c22, c23, st)
        if (st /= 0) return
        l1 = 8*a/(3*g*c11); l2 = 8*a/(3*g*c22); l3 = pi*a*sqrt(a/b)/(4*g*c23)
        do j = 1, size(contact, 2)
            y = grid%y(j); qx = 0; qy = 0
            do i = size(contact, 1), 1, -1
                if (.not. contact(i, j)) then
                    qx = 0; qy = 0; cycle        ! a new run starts at its own leading edge
                end if
                x = grid%x(i)
                qx = qx - grid%dx*(xi/l1 - phi*y/l3)
                qy = qy - grid%dx*(eta/l2 + phi*x/l3)
                t = hypot(qx, qy)
                if (t > bound(i, j)) then
                    if (t > 0) then
                        qx = qx*bound(i, j)/t; qy = qy*bound(i, j)/t
                    end if
                end if
                px(i, j) = qx; py(i, j) = qy
            end do
        end do
    end subroutine fastsim_on_grid

    !> Error bound of FASTSIM's creep force as a fraction of μFn for semi-axis ratio a/b and
    !! the creepages given: 1.5 × the largest measured error of the directions with a nonzero
    !! creepage at the two table ratios around a/b; huge outside 0.2 ≤ a/b ≤ 5 (not measured).
    pure real(dp) function fastsim_error_bound(a_over_b, xi, eta, phi) result(e)
        real(dp), intent(in) :: a_over_b, xi, eta, phi
        logical :: used(3)
        integer :: k, lo
        e = huge(1.0_dp)
        if (.not. (a_over_b >= ratio_nodes(1) .and. a_over_b <= ratio_nodes(5))) return
        used = [xi /= 0, eta /= 0, phi /= 0]
        lo = 1
        do k = 1, 4
            if (a_over_b >= ratio_nodes(k)) lo = k
        end do
        e = 0
        do k = 1, 3
            if (used(k)) e = max(e, measured_error(lo, k), measured_error(min(lo + 1, 5), k))
        end do
        e = 1.5_dp*e
    end function fastsim_error_bound

end module fc_fastsim
