!> Analytic and published references for rolling contact: Carter's 2D solution and
!! Kalker's linear-theory creep coefficients.
!!
!! Conventions as the package's rolling solver: body 1 rolls in +x (leading edge at +a),
!! forces on body 1, a positive creepage gives a negative force; G, ν the combined
!! material (identical bodies: those of each body).
!!
!! * Carter (1926), line contact of half-width a with pressure p0·√(1 − x²/a²) and
!!   coefficient μ: traction −μ·p0·√(1 − x²/a²) plus, on the stick zone of half-width c at
!!   the leading edge (centre d = a − c), +μ·p0·(c/a)·√(1 − (x − d)²/c²); the creepage
!!   ξ = 2(1−ν)·μ·p0·(1 − c/a)/G follows from the 2D tangential compliance
!!   u'(x) = −2(1−ν)/(πG)·PV∫ q(t)/(x − t) dt of the displacement difference, and the
!!   force per unit length is Fx = −μ·(π a p0/2)·(1 − c²/a²) (Johnson 1985 §8.2).
!! * Kalker's creep coefficients (Kalker 1967; tabulated in Kalker 1990, "Three-dimensional
!!   elastic bodies in rolling contact", Table E3, and Johnson 1985 Table 8.1): small
!!   creepage, full adhesion, elliptic contact with semi-axes a (rolling direction) and b:
!!   Fx = −G·a·b·C11·ξ,  Fy = −G·a·b·C22·η − G·(ab)^{3/2}·C23·φ.
!!   Tabulated for ν = 0, 0.25, 0.5 and a/b = 0.1 … 1 and b/a = 0.9 … 0.1; interpolated
!!   quadratically in ν and linearly in the ratio between the nodes.
module fc_rolling_ref
    use fc_kinds, only: dp, pi, FC_ERR_VALUE
    implicit none
    private

    public :: carter_stick_ratio, carter_traction, carter_force_ratio, carter_creepage
    public :: kalker_coefficients

    !> a/b nodes of the table: a/b = 0.1 … 1.0, then b/a = 0.9 … 0.1 (a/b = 1.11 … 10).
    real(dp), parameter :: ratio_node(19) = [0.1_dp, 0.2_dp, 0.3_dp, 0.4_dp, 0.5_dp, 0.6_dp, 0.7_dp, 0.8_dp, &
        0.9_dp, 1.0_dp, 1/0.9_dp, 1/0.8_dp, 1/0.7_dp, 1/0.6_dp, 1/0.5_dp, 1/0.4_dp, 1/0.3_dp, 1/0.2_dp, 1/0.1_dp]
    real(dp), parameter :: nu_node(3) = [0.0_dp, 0.25_dp, 0.5_dp]
    !> C11(ν, ratio), rows ν = 0, 0.25, 0.5.
    real(dp), parameter :: c11_table(19, 3) = reshape([ &
        2.51_dp, 2.59_dp, 2.68_dp, 2.78_dp, 2.88_dp, 2.98_dp, 3.09_dp, 3.19_dp, 3.29_dp, 3.40_dp, &
        3.51_dp, 3.65_dp, 3.82_dp, 4.06_dp, 4.37_dp, 4.84_dp, 5.57_dp, 6.96_dp, 10.7_dp, &
        3.31_dp, 3.37_dp, 3.44_dp, 3.53_dp, 3.62_dp, 3.72_dp, 3.81_dp, 3.91_dp, 4.01_dp, 4.12_dp, &
        4.22_dp, 4.36_dp, 4.54_dp, 4.78_dp, 5.10_dp, 5.57_dp, 6.34_dp, 7.78_dp, 11.7_dp, &
        4.85_dp, 4.81_dp, 4.80_dp, 4.82_dp, 4.83_dp, 4.91_dp, 4.97_dp, 5.05_dp, 5.12_dp, 5.20_dp, &
        5.30_dp, 5.42_dp, 5.58_dp, 5.80_dp, 6.11_dp, 6.57_dp, 7.34_dp, 8.82_dp, 12.9_dp], [19, 3])
    !> C22(ν, ratio).
    real(dp), parameter :: c22_table(19, 3) = reshape([ &
        2.51_dp, 2.59_dp, 2.68_dp, 2.78_dp, 2.88_dp, 2.98_dp, 3.09_dp, 3.19_dp, 3.29_dp, 3.40_dp, &
        3.51_dp, 3.65_dp, 3.82_dp, 4.06_dp, 4.37_dp, 4.84_dp, 5.57_dp, 6.96_dp, 10.7_dp, &
        2.52_dp, 2.63_dp, 2.75_dp, 2.88_dp, 3.01_dp, 3.14_dp, 3.28_dp, 3.41_dp, 3.54_dp, 3.67_dp, &
        3.81_dp, 3.99_dp, 4.21_dp, 4.50_dp, 4.90_dp, 5.48_dp, 6.40_dp, 8.14_dp, 12.8_dp, &
        2.53_dp, 2.66_dp, 2.81_dp, 2.98_dp, 3.14_dp, 3.31_dp, 3.48_dp, 3.65_dp, 3.82_dp, 3.98_dp, &
        4.16_dp, 4.39_dp, 4.67_dp, 5.04_dp, 5.56_dp, 6.31_dp, 7.51_dp, 9.79_dp, 16.0_dp], [19, 3])
    !> C23(ν, ratio).
    real(dp), parameter :: c23_table(19, 3) = reshape([ &
        0.334_dp, 0.483_dp, 0.607_dp, 0.720_dp, 0.827_dp, 0.930_dp, 1.03_dp, 1.13_dp, 1.23_dp, 1.33_dp, &
        1.44_dp, 1.58_dp, 1.76_dp, 2.01_dp, 2.35_dp, 2.88_dp, 3.79_dp, 5.72_dp, 12.2_dp, &
        0.473_dp, 0.603_dp, 0.715_dp, 0.823_dp, 0.929_dp, 1.03_dp, 1.14_dp, 1.25_dp, 1.36_dp, 1.47_dp, &
        1.59_dp, 1.75_dp, 1.95_dp, 2.23_dp, 2.62_dp, 3.24_dp, 4.32_dp, 6.63_dp, 14.6_dp, &
        0.731_dp, 0.809_dp, 0.889_dp, 0.977_dp, 1.07_dp, 1.18_dp, 1.29_dp, 1.40_dp, 1.51_dp, 1.63_dp, &
        1.77_dp, 1.94_dp, 2.18_dp, 2.50_dp, 2.96_dp, 3.70_dp, 5.01_dp, 7.89_dp, 18.0_dp], [19, 3])

contains

    !> Half-width ratio c/a of Carter's stick zone for creepage ξ (0 in full slip).
    pure real(dp) function carter_stick_ratio(xi, p0, mu, g, nu) result(ca)
        real(dp), intent(in) :: xi   !! creepage [-]
        real(dp), intent(in) :: p0   !! maximum pressure [N/mm²]
        real(dp), intent(in) :: mu, g, nu   !! friction, combined shear modulus [N/mm²], ratio
        real(dp) :: xs
        xs = 2*(1 - nu)*mu*p0/g          ! creepage of incipient full slip
        ca = max(0.0_dp, 1 - abs(xi)/xs)
    end function carter_stick_ratio

    !> Creepage ξ ≥ 0 that gives the stick ratio c/a (inverse of [[carter_stick_ratio]]).
    pure real(dp) function carter_creepage(ca, p0, mu, g, nu) result(xi)
        real(dp), intent(in) :: ca, p0, mu, g, nu
        xi = 2*(1 - nu)*mu*p0*(1 - ca)/g
    end function carter_creepage

    !> Carter's tangential traction q(x) [N/mm²] on body 1 for creepage ξ (sign: opposite ξ).
    elemental real(dp) function carter_traction(x, a, p0, mu, g, nu, xi) result(q)
        real(dp), intent(in) :: x        !! position [mm], leading edge at +a
        real(dp), intent(in) :: a, p0, mu, g, nu, xi
        real(dp) :: c, d
        q = 0
        if (abs(x) >= a) return
        q = -mu*p0*sqrt(1 - (x/a)**2)
        c = a*carter_stick_ratio(xi, p0, mu, g, nu)
        d = a - c
        if (c > 0 .and. abs(x - d) < c) q = q + mu*p0*(c/a)*sqrt(1 - ((x - d)/c)**2)
        q = sign(1.0_dp, xi)*q
        if (xi == 0) q = 0
    end function carter_traction

    !> Carter's creep-force law Fx/(μ·Fn) = −sign(ξ)·(1 − (c/a)²).
    pure real(dp) function carter_force_ratio(xi, p0, mu, g, nu) result(f)
        real(dp), intent(in) :: xi, p0, mu, g, nu
        f = -sign(1.0_dp, xi)*(1 - carter_stick_ratio(xi, p0, mu, g, nu)**2)
        if (xi == 0) f = 0
    end function carter_force_ratio

    !> Kalker's creep coefficients C11, C22, C23 for Poisson's ratio ν ∈ [0, 0.5] and
    !! semi-axis ratio a/b ∈ [0.1, 10] (a along the rolling direction).  stat = FC_ERR_VALUE outside.
    pure subroutine kalker_coefficients(nu, a_over_b, c11, c22, c23, stat)
        real(dp), intent(in) :: nu, a_over_b
        real(dp), intent(out) :: c11, c22, c23
        integer, intent(out) :: stat
        real(dp) :: wnu(3), t
        integer :: k, lo
        c11 = 0; c22 = 0; c23 = 0
        stat = FC_ERR_VALUE
        if (.not. (nu >= 0 .and. nu <= 0.5_dp)) return
        if (.not. (a_over_b >= ratio_node(1)*(1 - 1e-12_dp) .and. a_over_b <= ratio_node(19)*(1 + 1e-12_dp))) return
        stat = 0
        ! quadratic Lagrange weights in ν
        wnu(1) = (nu - nu_node(2))*(nu - nu_node(3))/((nu_node(1) - nu_node(2))*(nu_node(1) - nu_node(3)))
        wnu(2) = (nu - nu_node(1))*(nu - nu_node(3))/((nu_node(2) - nu_node(1))*(nu_node(2) - nu_node(3)))
        wnu(3) = (nu - nu_node(1))*(nu - nu_node(2))/((nu_node(3) - nu_node(1))*(nu_node(3) - nu_node(2)))
        lo = 1
        do k = 1, 18
            if (a_over_b >= ratio_node(k)) lo = k
        end do
        lo = min(lo, 18)
        t = (min(a_over_b, ratio_node(19)) - ratio_node(lo))/(ratio_node(lo + 1) - ratio_node(lo))
        t = max(0.0_dp, min(1.0_dp, t))
        c11 = sum(wnu*((1 - t)*c11_table(lo, :) + t*c11_table(lo + 1, :)))
        c22 = sum(wnu*((1 - t)*c22_table(lo, :) + t*c22_table(lo + 1, :)))
        c23 = sum(wnu*((1 - t)*c23_table(lo, :) + t*c23_table(lo + 1, :)))
    end subroutine kalker_coefficients

end module fc_rolling_ref
