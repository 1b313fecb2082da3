!> Analytic Hertz solution for elliptic contact (thesis §2.5.1; Johnson 1985 §3.5, §4.2).
!!
!! Undeformed distance h = A x² + B y² − δ with A = 1/(2Rx), B = 1/(2Ry), and the
!! combined material of doc/conventions.md, whose point kernel (1−ν)/(πG)/ρ equals 1/(πE*) with
!! E* = G/(1−ν).  Pressure p = p0·sqrt(1 − (x/a)² − (y/b)²) on the contact ellipse.
module fc_hertz
    use fc_kinds, only: dp, pi
    implicit none
    private

    !> Solution of an elliptic Hertz problem.
    type, public :: fc_hertz_solution
        real(dp) :: a = 0        !! semi-axis along x [mm]
        real(dp) :: b = 0        !! semi-axis along y [mm]
        real(dp) :: p0 = 0       !! maximum pressure [N/mm²]
        real(dp) :: fn = 0       !! total normal force [N]
        real(dp) :: approach = 0 !! approach δ [mm]
    contains
        procedure :: pressure => hertz_pressure
    end type fc_hertz_solution

    !> Cattaneo–Mindlin solution of a circular Hertz contact under a tangential force
    !! Q < μP applied monotonically from zero (Johnson 1985 §7.1).
    type, public :: fc_cattaneo_solution
        real(dp) :: a = 0        !! contact radius [mm]
        real(dp) :: c = 0        !! stick radius c = a(1 − Q/μP)^{1/3} [mm]
        real(dp) :: p0 = 0       !! maximum pressure [N/mm²]
        real(dp) :: mu = 0       !! coefficient of friction
        real(dp) :: shift = 0    !! rigid tangential shift of body 1 relative to body 2 [mm] (magnitude)
        !> work of friction while Q grows from 0 [N·mm]: (6/5)·μP·δμ·[1 − (1 − x)^{5/3} −
        !! (5x/6)(1 + (1 − x)^{2/3})], x = Q/μP, δμ the shift at x = 1 (Mindlin–Deresiewicz)
        real(dp) :: dissipation = 0
    contains
        procedure :: traction => cattaneo_traction
    end type fc_cattaneo_solution

    public :: elliptic_ke, hertz_from_approach, hertz_from_force, cattaneo_mindlin

contains

    !> Complete elliptic integrals K(m) and E(m) of parameter m = k² ∈ [0,1), by the
    !! arithmetic–geometric mean (accurate to round-off).
    pure subroutine elliptic_ke(m, kk, ee)
        real(dp), intent(in) :: m
        real(dp), intent(out) :: kk, ee
        real(dp) :: a, b, c, an, s, pow2
        integer :: it
        a = 1; b = sqrt(1 - m); c = sqrt(m)
        s = 0.5_dp*c**2; pow2 = 0.5_dp
        do it = 1, 60
            an = 0.5_dp*(a + b)
            c = 0.5_dp*(a - b)
            b = sqrt(a*b)
            a = an
            pow2 = 2*pow2
            s = s + pow2*c**2
            if (abs(c) <= epsilon(1.0_dp)*a) exit
        end do
        kk = pi/(2*a)
        ee = kk*(1 - s)
    end subroutine elliptic_ke

    !> Hertz solution for curvatures A = 1/(2Rx), B = 1/(2Ry) [1/mm], effective
    !! modulus estar = G/(1−ν) [N/mm²] and approach δ [mm].
    pure function hertz_from_approach(curv_a, curv_b, estar, approach) result(sol)
        real(dp), intent(in) :: curv_a, curv_b, estar, approach
        type(fc_hertz_solution) :: sol
        real(dp) :: amin, amax, ratio, e2, kk, ee, lo, hi, f, amaj, bmin
        integer :: it
        amin = min(curv_a, curv_b); amax = max(curv_a, curv_b)
        sol%approach = approach
        if (approach <= 0 .or. amin <= 0) return
        ratio = amax/amin
        ! N/M = [(a/b)² E − K]/(K − E) increases monotonically with e² from 1 (circle).
        ! e² stays below 1 − 2ε: beyond a curvature ratio of ~1.2e14 the ellipse is clipped
        ! there (semi-axis ratio ~2e-8) instead of dividing by 1 − e² = 0.
        lo = 0; hi = 1 - 2*epsilon(1.0_dp)
        do it = 1, 200
            e2 = 0.5_dp*(lo + hi)
            f = ratio_of(e2)
            if (f > ratio) then
                hi = e2
            else
                lo = e2
            end if
            if (hi - lo < 1.0e-16_dp) exit
        end do
        e2 = 0.5_dp*(lo + hi)
        if (e2 < 1.0e-12_dp) then      ! circular limit: a² = R δ
            amaj = sqrt(approach/(2*amin)); bmin = amaj
            sol%p0 = 2*estar*amaj*2*amin/pi
        else
            call elliptic_ke(e2, kk, ee)
            amaj = sqrt(approach*(kk - ee)/(amin*kk*e2))
            bmin = amaj*sqrt(1 - e2)
            sol%p0 = approach*estar/(bmin*kk)
        end if
        if (curv_a <= curv_b) then
            sol%a = amaj; sol%b = bmin
        else
            sol%a = bmin; sol%b = amaj
        end if
        sol%fn = 2*pi*sol%a*sol%b*sol%p0/3
    contains
        pure real(dp) function ratio_of(ecc2)
            real(dp), intent(in) :: ecc2
            real(dp) :: k1, e1
            if (ecc2 < 1.0e-12_dp) then
                ratio_of = 1; return
            end if
            if (ecc2 >= 1) then
                ratio_of = huge(1.0_dp); return
            end if
            call elliptic_ke(ecc2, k1, e1)
            ratio_of = (e1/(1 - ecc2) - k1)/(k1 - e1)
        end function ratio_of
    end function hertz_from_approach

    !> Hertz solution for a prescribed total force fn [N] (F ∝ δ^{3/2}).
    pure function hertz_from_force(curv_a, curv_b, estar, fn) result(sol)
        real(dp), intent(in) :: curv_a, curv_b, estar, fn
        type(fc_hertz_solution) :: sol
        type(fc_hertz_solution) :: unit
        if (fn <= 0) return
        unit = hertz_from_approach(curv_a, curv_b, estar, 1.0_dp)
        sol = hertz_from_approach(curv_a, curv_b, estar, (fn/unit%fn)**(2.0_dp/3.0_dp))
    end function hertz_from_force

    !> Analytic pressure at (x,y) [N/mm²].
    elemental real(dp) function hertz_pressure(self, x, y) result(p)
        class(fc_hertz_solution), intent(in) :: self
        real(dp), intent(in) :: x, y
        real(dp) :: s
        p = 0
        if (self%a <= 0 .or. self%b <= 0) return
        s = 1 - (x/self%a)**2 - (y/self%b)**2
        if (s > 0) p = self%p0*sqrt(s)
    end function hertz_pressure

    !> Cattaneo–Mindlin for a circular contact of radius a with maximum pressure p0, total
    !! force P, friction μ and tangential force Q (0 ≤ Q < μP); combined G, ν (doc/conventions.md).
    !! Shift δ = 3μP(2−ν)/(8Ga)·[1 − (1 − Q/μP)^{2/3}] (two bodies, Johnson eq. 7.40).
    !! Dissipation: the work of friction over the slip annulus while Q grows monotonically
    !! from 0, ∫ μp·|s| dA (the slip of a point only grows, along Q), in closed form; exact
    !! for ν = 0, Mindlin's approximation otherwise (doc/rolling.md, "Frictional
    !! dissipation").
    pure function cattaneo_mindlin(a, p0, fn, mu, q, g, nu) result(sol)
        real(dp), intent(in) :: a, p0, fn, mu, q, g, nu
        type(fc_cattaneo_solution) :: sol
        real(dp) :: ratio, full_shift
        sol%a = a; sol%p0 = p0; sol%mu = mu
        ratio = min(max(q/(mu*fn), 0.0_dp), 1.0_dp)
        sol%c = a*(1 - ratio)**(1.0_dp/3.0_dp)
        full_shift = 3*mu*fn*(2 - nu)/(8*g*a)
        sol%shift = full_shift*(1 - (1 - ratio)**(2.0_dp/3.0_dp))
        sol%dissipation = 1.2_dp*mu*fn*full_shift*(1 - (1 - ratio)**(5.0_dp/3.0_dp) - &
                          (5*ratio/6)*(1 + (1 - ratio)**(2.0_dp/3.0_dp)))
    end function cattaneo_mindlin

    !> Magnitude of the tangential traction at radius r [N/mm²]:
    !! μp0/a·[√(a²−r²) − √(c²−r²)] (second term only inside the stick circle).
    elemental real(dp) function cattaneo_traction(self, r) result(t)
        class(fc_cattaneo_solution), intent(in) :: self
        real(dp), intent(in) :: r
        t = 0
        if (r < self%a) t = sqrt(self%a**2 - r**2)
        if (r < self%c) t = t - sqrt(self%c**2 - r**2)
        t = self%mu*self%p0/self%a*t
    end function cattaneo_traction

end module fc_hertz
