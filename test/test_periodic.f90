!> Suite `periodic`: the tangential problem on the periodic half-space (a rough-surface cell
!! repeated in x and y) — its kernels, its exact block inverse, the discrete
!! Ciavarella–Jäger identity, translation invariance across the cell's edges, and the
!! driver's and flat API's checks.  (The periodic normal problem is tested in `parallel`.)
module test_periodic
    use fc_kinds, only: dp, FC_CONVERGED, FC_ERR_UNSUPPORTED
    use fc_geometry, only: fc_grid, make_grid, wavy_gap, quadratic_gap
    use fc_influence, only: fc_material, combine_material, element_coefficient, IC_ZZ, IC_XX, IC_YY, IC_XY, IC_XZ, &
        IC_ZX, IC_YZ, IC_ZY
    use fc_periodic, only: periodic_wrapped_kernel, build_periodic_tangential_operator
    use fc_tangcg_operator, only: fc_tangential_operator, apply_block_inverse
    use fc_tangcg_types, only: EL_ADHESION
    use fc_contact, only: fc_contact_operators, fc_contact_loading, fc_contact_settings, fc_contact_result, solve_contact, &
        FC_PROBLEM_NORMAL, FC_PROBLEM_TANGENTIAL
    use fc_test_driver, only: fresh_dir, run_namelist
    use test_driver, only: json_num
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_null_char
    use fc_legacy, only: fc_init, fc_finalize, fc_set_material, fc_set_grid, fc_set_gap_array, fc_set_normal_force, &
        fc_set_friction, fc_set_forces, fc_set_rolling, fc_set_periodic, fc_calculate, fc_get_forces, fc_get_tractions, &
        fc_get_error_message, FCL_OK
    use fc_testing
    implicit none
    private
    public :: collect_periodic

contains

    subroutine collect_periodic(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('tangential_kernels', test_kernels), &
            new_unittest('tangential_exact_block_inverse', test_block_inverse), &
            new_unittest('tangential_ciavarella_jaeger', test_ciavarella_jaeger), &
            new_unittest('tangential_full_contact', test_full_contact), &
            new_unittest('tangential_full_contact_near_capacity', test_near_capacity), &
            new_unittest('tangential_full_contact_anisotropic', test_full_contact_anisotropic), &
            new_unittest('tangential_translation_invariance', test_translation), &
            new_unittest('tangential_far_images', test_far_images), &
            new_unittest('coupling_kernels', test_coupling_kernels), &
            new_unittest('dissimilar_far_images', test_far_images_dissimilar), &
            new_unittest('dissimilar_pressure_slips_everything', test_dissimilar_dead_zone), &
            new_unittest('driver_periodic_tangential', test_driver), &
            new_unittest('tiny_prescribed_forces', test_tiny_forces), &
            new_unittest('api_periodic_tangential', test_api) ]
    end subroutine collect_periodic

    subroutine material(mat, nu)
        type(fc_material), intent(out) :: mat
        real(dp), intent(in) :: nu
        integer :: stat
        character(len=200) :: m
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = nu; mat%nu2 = nu
        call combine_material(mat, stat, m)
    end subroutine material

    !> A periodic wavy cell n × n on [0, 1]² — h0 = A(1 − cos 2πx cos 2πy/ℓy) shifted, A = 1 µm,
    !! ℓy = `wavelength_y` (0: flat in y) — of identical bodies with ν = 0, on operators of
    !! the periodic half-space.
    subroutine wavy_cell(n, wavelength_y, mat, grid, h0, ops)
        integer, intent(in) :: n
        real(dp), intent(in) :: wavelength_y
        type(fc_material), intent(out) :: mat
        type(fc_grid), intent(out) :: grid
        real(dp), allocatable, intent(out) :: h0(:, :)
        type(fc_contact_operators), intent(inout) :: ops
        integer :: stat
        character(len=256) :: em
        call material(mat, 0.0_dp)
        call make_grid(grid, n, n, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, stat, em)
        h0 = wavy_gap(grid, 0.001_dp, 1.0_dp, wavelength_y)
        ops%periodic = .true.
    end subroutine wavy_cell

    !> A normal + tangential loading: the normal force `fn` and the tangential force
    !! (`fx`, `fy`) [N] prescribed, friction `mu`.
    pure function force_load(fn, mu, fx, fy) result(load)
        real(dp), intent(in) :: fn, mu, fx, fy
        type(fc_contact_loading) :: load
        load%problem = FC_PROBLEM_TANGENTIAL
        load%normal%force_prescribed = .true.; load%normal%fn = fn
        load%tangential%mu = mu; load%tangential%force_prescribed = .true.
        load%tangential%fx = fx; load%tangential%fy = fy
    end function force_load

    !> The normal solutions of the cell under the forces `p` and `pstar` [N].
    subroutine normal_pair(ops, grid, mat, h0, set, p, pstar, rp, rs)
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_grid), intent(in) :: grid
        type(fc_material), intent(in) :: mat
        real(dp), intent(in) :: h0(:, :), p, pstar
        type(fc_contact_settings), intent(in) :: set
        type(fc_contact_result), intent(out) :: rp, rs
        type(fc_contact_loading) :: load
        integer :: stat
        character(len=256) :: em
        load%problem = FC_PROBLEM_NORMAL
        load%normal%force_prescribed = .true.; load%normal%fn = p
        call solve_contact(ops, grid, mat, h0, load, set, rp, stat, em)
        load%normal%fn = pstar
        call solve_contact(ops, grid, mat, h0, load, set, rs, stat, em)
    end subroutine normal_pair

    !> The periodic kernels of a 16×12 cell: A^xx, A^yy even in x and y, A^xy odd in both
    !! (so every kernel point-symmetric and its symbol real); A^xy near the origin of a
    !! 48×48 cell within 1e−3 of the half-space's (its images' odd parts cancel there to
    !! order (r/L)³), with its sign on the 16×12 cell; the sums
    !! with 2 image rings within 2e−4 of those with 20 (the far images' smeared tail); with
    !! ν = 0, A^xx equal to A^zz and A^xy zero.
    subroutine test_kernels(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        real(dp), allocatable :: wxx(:, :), wyy(:, :), wxy(:, :), w20(:, :), wzz(:, :)
        real(dp) :: d, near
        integer :: stat, i, j, nx, ny
        character(len=256) :: em
        nx = 16; ny = 12
        call material(mat, 0.3_dp)
        call make_grid(grid, nx, ny, 0.0_dp, 1.6_dp, 0.0_dp, 1.0_dp, stat, em)
        call periodic_wrapped_kernel(mat, grid, 2, IC_XX, wxx)
        call periodic_wrapped_kernel(mat, grid, 2, IC_YY, wyy)
        call periodic_wrapped_kernel(mat, grid, 2, IC_XY, wxy)
        d = 0
        do j = 0, ny - 1
            do i = 0, nx - 1
                d = max(d, abs(wxx(i, j) - wxx(modulo(-i, nx), j)), abs(wxx(i, j) - wxx(i, modulo(-j, ny))), &
                    abs(wyy(i, j) - wyy(modulo(-i, nx), j)), abs(wxy(i, j) + wxy(modulo(-i, nx), j)), &
                    abs(wxy(i, j) + wxy(i, modulo(-j, ny))))
            end do
        end do
        call check(error, d, 0.0_dp, 'A^xx, A^yy even, A^xy odd in x and in y', abs=0.0_dp)
        block
            type(fc_grid) :: big
            real(dp), allocatable :: bxy(:, :)
            call make_grid(big, 48, 48, 0.0_dp, 4.8_dp, 0.0_dp, 4.8_dp, stat, em)
            call periodic_wrapped_kernel(mat, big, 2, IC_XY, bxy)
            near = 0
            do j = 1, 2
                do i = 1, 2
                    near = max(near, abs(bxy(i, j) - element_coefficient(IC_XY, mat, i*big%dx, j*big%dy, big%dx, big%dy)))
                end do
            end do
            call check(error, near, 0.0_dp, 'A^xy near the origin as on the half-space (48 x 48 cell)', &
                abs=1e-3_dp*maxval(abs(bxy)))
        end block
        call check(error, wxy(1, 1)*element_coefficient(IC_XY, mat, grid%dx, grid%dy, grid%dx, grid%dy) > 0, &
            'A^xy has the half-space sign')
        call periodic_wrapped_kernel(mat, grid, 20, IC_XX, w20)
        call check(error, maxval(abs(w20 - wxx)), 0.0_dp, 'A^xx: 2 image rings as 20', abs=2e-4_dp*maxval(abs(wxx)))
        call periodic_wrapped_kernel(mat, grid, 20, IC_XY, w20)
        call check(error, maxval(abs(w20 - wxy)), 0.0_dp, 'A^xy: 2 image rings as 20', abs=2e-4_dp*maxval(abs(wxy)))
        call material(mat, 0.0_dp)
        call periodic_wrapped_kernel(mat, grid, 2, IC_XX, wxx)
        call periodic_wrapped_kernel(mat, grid, 2, IC_ZZ, wzz)
        call periodic_wrapped_kernel(mat, grid, 2, IC_XY, wxy)
        call check(error, maxval(abs(wxx - wzz)) == 0 .and. maxval(abs(wxy)) == 0, 'nu = 0: A^xx = A^zz, A^xy = 0')
    end subroutine test_kernels

    !> The preconditioner of the periodic tangential operator is A's exact inverse on
    !! mean-free tractions: M·A·v = v for v of zero mean in x and in y (to rounding), on
    !! either form asked for; products against the direct circular sums, for dissimilar
    !! bodies the coupling blocks' too.
    subroutine test_block_inverse(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_tangential_operator) :: top
        real(dp) :: vx(16, 12), vy(16, 12), ux(16, 12), uy(16, 12), zx(16, 12), zy(16, 12), dx(16, 12)
        integer :: stat, i, j
        character(len=256) :: em
        call material(mat, 0.3_dp)
        call make_grid(grid, 16, 12, 0.0_dp, 1.6_dp, 0.0_dp, 1.0_dp, stat, em)
        call build_periodic_tangential_operator(top, mat, grid, stat, em)
        call check(error, stat == 0 .and. top%periodic, 'built: '//trim(em))
        if (allocated(error)) return
        do j = 1, 12
            do i = 1, 16
                vx(i, j) = modulo(0.37_dp*i + 0.61_dp*j*j, 1.0_dp)
                vy(i, j) = modulo(0.73_dp*i*i + 0.19_dp*j, 1.0_dp)
            end do
        end do
        vx = vx - sum(vx)/size(vx); vy = vy - sum(vy)/size(vy)
        call top%apply(vx, vy, ux, uy)
        call top%a_xx%apply_direct(vx, dx)
        call top%a_xy%apply_direct(vy, zx)
        call check(error, maxval(abs(dx + zx - ux)), 0.0_dp, 'A v against the direct circular sums', &
            abs=1e-12_dp*maxval(abs(ux)))
        call apply_block_inverse(top, ux, uy, zx, zy, circulant=.false.)
        call check(error, max(maxval(abs(zx - vx)), maxval(abs(zy - vy))), 0.0_dp, 'M A v = v (toeplitz form asked)', &
            abs=1e-10_dp*maxval(abs(vx)))
        call apply_block_inverse(top, ux, uy, zx, zy, circulant=.true.)
        call check(error, max(maxval(abs(zx - vx)), maxval(abs(zy - vy))), 0.0_dp, 'M A v = v (circulant form)', &
            abs=1e-10_dp*maxval(abs(vx)))
        ! dissimilar bodies: the coupling blocks too, their products (imaginary symbols) against
        ! the direct circular sums
        call dissimilar(mat)
        call build_periodic_tangential_operator(top, mat, grid, stat, em)
        call check(error, stat == 0 .and. top%coupled(), 'dissimilar bodies: coupling blocks built: '//trim(em))
        if (allocated(error)) return
        call top%a_xz%apply(vx, ux)
        call top%a_xz%apply_direct(vx, dx)
        call check(error, maxval(abs(dx - ux)), 0.0_dp, 'A^xz v against the direct circular sums', &
            abs=1e-12_dp*maxval(abs(ux)))
        call top%a_zy%apply(vy, uy)
        call top%a_zy%apply_direct(vy, dx)
        call check(error, maxval(abs(dx - uy)), 0.0_dp, 'A^zy v against the direct circular sums', &
            abs=1e-12_dp*maxval(abs(uy)))
    end subroutine test_block_inverse

    !> With ν = 0 the tangential kernel A^xx equals A^zz and A^xy vanishes, so the solution of
    !! the periodic problem under a tangential force Q < μP is, element by element,
    !! q = μ(p(P) − p(P*)) with P* = P − Q/μ, and the adhesion area is the contact area at P*
    !! (Ciavarella; Jäger): exact for the discrete problems too.  A 2D wavy cell in partial
    !! contact, 32², tolerances 1e−10: tractions to 1e−7 of μ·pmax (measured 3e−11).
    subroutine test_ciavarella_jaeger(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: rt, rs
        real(dp), allocatable :: h0(:, :)
        real(dp), parameter :: mu = 0.3_dp, p = 0.05_dp, q = 0.01_dp
        integer :: stat
        character(len=256) :: em
        call wavy_cell(32, 1.0_dp, mat, grid, h0, ops)
        set%normal%tol = 1e-10_dp; set%tangential%tol = 1e-10_dp
        load = force_load(p, mu, q, 0.0_dp)
        call solve_contact(ops, grid, mat, h0, load, set, rt, stat, em)
        call check(error, stat == 0 .and. rt%status == FC_CONVERGED, 'tangential solve: '//trim(em))
        if (allocated(error)) return
        load%problem = FC_PROBLEM_NORMAL; load%normal%fn = p - q/mu
        call solve_contact(ops, grid, mat, h0, load, set, rs, stat, em)
        call check(error, stat == 0 .and. rs%status == FC_CONVERGED, 'normal solve at P*: '//trim(em))
        if (allocated(error)) return
        call check(error, count(rt%tangential%state == EL_ADHESION) > 0 .and. &
            count(rt%tangential%state == EL_ADHESION) < count(rt%normal%pn > 0), 'partial slip')
        call check(error, maxval(abs(rt%tangential%px - mu*(rt%normal%pn - rs%normal%pn))), 0.0_dp, &
            'q = mu (p(P) - p(P*))', abs=1e-7_dp*mu*rt%normal%pmax)
        call check(error, maxval(abs(rt%tangential%py)), 0.0_dp, 'no lateral traction', abs=1e-12_dp*mu*rt%normal%pmax)
        call check(error, all((rt%tangential%state == EL_ADHESION) .eqv. (rs%normal%pn > 0)), &
            'adhesion area = contact area at P*')
    end subroutine test_ciavarella_jaeger

    !> A cell in contact everywhere (ν = 0, wavy cell 32² at P = 5 N, 3.5× the load of full
    !! contact): uniform tractions displace nothing there, so
    !! (a) a force the whole cell carries in adhesion, Q = 0.1 N, gives q = Q/(cell area)
    !!     everywhere in adhesion at zero shift;
    !! (b) Q = 1.44 N (P* = P − Q/μ = 0.2 N, in partial contact) gives the Ciavarella–Jäger
    !!     tractions μ(p(P) − p(P*)), adhesion on the contact at P*, and the shift
    !!     −μ(δ(P) − δ(P*)) (approaches relative to the cell's mean displacement);
    !! (c) that shift prescribed gives the same tractions and Q.
    !! Tolerances 1e−7 of μ·pmax (measured 1e−10).
    subroutine test_full_contact(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: ra, rb, rc, rp, rs
        real(dp), allocatable :: h0(:, :), ref(:, :)
        real(dp), parameter :: mu = 0.3_dp, p = 5.0_dp
        real(dp) :: w
        integer :: stat
        character(len=256) :: em
        call wavy_cell(32, 1.0_dp, mat, grid, h0, ops)
        set%normal%tol = 1e-10_dp; set%tangential%tol = 1e-10_dp
        call normal_pair(ops, grid, mat, h0, set, p, p - 1.44_dp/mu, rp, rs)
        load%normal%force_prescribed = .true.
        call check(error, all(rp%normal%pn > 0) .and. count(rs%normal%pn > 0) < size(h0), &
            'full contact at P, partial at P*')
        if (allocated(error)) return
        ref = mu*(rp%normal%pn - rs%normal%pn)
        w = -mu*(rp%normal%approach - rs%normal%approach)
        load%problem = FC_PROBLEM_TANGENTIAL; load%normal%fn = p
        load%tangential%mu = mu; load%tangential%force_prescribed = .true.; load%tangential%fx = 0.1_dp
        call solve_contact(ops, grid, mat, h0, load, set, ra, stat, em)
        call check(error, stat == 0 .and. ra%status == FC_CONVERGED, '(a) solved: '//trim(em)//' '//trim(ra%tangential%message))
        if (allocated(error)) return
        call check(error, all(ra%tangential%state == EL_ADHESION) .and. ra%tangential%xi == 0, &
            '(a) adhesion everywhere at zero shift')
        call check(error, maxval(abs(ra%tangential%px - 0.1_dp)), 0.0_dp, '(a) q = Q / cell area', &
            abs=1e-7_dp*mu*rp%normal%pmax)
        load%tangential%fx = 1.44_dp
        call solve_contact(ops, grid, mat, h0, load, set, rb, stat, em)
        call check(error, stat == 0 .and. rb%status == FC_CONVERGED, '(b) solved: '//trim(em)//' '//trim(rb%tangential%message))
        if (allocated(error)) return
        call check(error, maxval(abs(rb%tangential%px - ref)), 0.0_dp, '(b) q = mu (p(P) - p(P*))', &
            abs=1e-7_dp*mu*rp%normal%pmax)
        call check(error, all((rb%tangential%state == EL_ADHESION) .eqv. (rs%normal%pn > 0)), &
            '(b) adhesion area = contact area at P*')
        call check(error, rb%tangential%xi, w, '(b) shift', rel=1e-6_dp)
        load%tangential%force_prescribed = .false.; load%tangential%xi = w
        call solve_contact(ops, grid, mat, h0, load, set, rc, stat, em)
        call check(error, stat == 0 .and. rc%status == FC_CONVERGED, '(c) solved: '//trim(em))
        if (allocated(error)) return
        call check(error, maxval(abs(rc%tangential%px - ref)), 0.0_dp, '(c) shift prescribed: the same tractions', &
            abs=1e-7_dp*mu*rp%normal%pmax)
        call check(error, rc%tangential%fx, 1.44_dp, '(c) the same force', rel=1e-6_dp)
    end subroutine test_full_contact

    !> A cell in contact everywhere under a force beyond what adhesion everywhere carries, with
    !! anisotropic kernels: a 2D wavy cell 24² (G = 320, ν = 0.416, P = 6 N), a force of 0.6 μP
    !! at an angle; about 99 % of the cell sticks.  The loop on the shift alone stopped short
    !! (122 steps, 33 600 TangCG iterations, 0.2 N off); with the uniform mode given Mindlin's
    !! compliance it converges in a few steps.  Checked: converged, the force within tol·μP,
    !! and the physical shift it reports (~1e−9 mm), prescribed as a shift, gives the same
    !! tractions and force within 1 % (measured 1e−3 of μ·pmax, 2.4e−3 of |F|: with the cell
    !! in contact everywhere the physical shift–force map is nearly singular, which is why
    !! the loop runs on the other one; the shift before conversion, F/k ≈ 2e−3 mm, would slip
    !! the whole cell).
    subroutine test_full_contact_anisotropic(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: r, rs
        real(dp), allocatable :: h0(:, :)
        real(dp), parameter :: mu = 0.5_dp, p = 6.0_dp, qx = -1.70033_dp, qy = 0.590649_dp
        integer :: stat
        character(len=256) :: em
        mat%g1 = 320; mat%g2 = 320; mat%nu1 = 0.416_dp; mat%nu2 = 0.416_dp
        call combine_material(mat, stat, em)
        call make_grid(grid, 24, 24, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, stat, em)
        h0 = wavy_gap(grid, 0.001_dp, 1.0_dp, 1.0_dp)
        ops%periodic = .true.
        load = force_load(p, mu, qx, qy)
        call solve_contact(ops, grid, mat, h0, load, set, r, stat, em)
        call check(error, stat == 0 .and. all(r%normal%pn > 0), 'full contact: '//trim(em))
        call check(error, r%tangential%nslip > 0 .and. r%tangential%nadh > 0, 'partial slip')
        call check(error, r%status == FC_CONVERGED, 'converged: '//trim(r%tangential%message))
        if (allocated(error)) return
        call check(error, hypot(r%tangential%fx - qx, r%tangential%fy - qy), 0.0_dp, 'force', &
            abs=set%tangential%tol*mu*p)
        load%tangential%force_prescribed = .false.
        load%tangential%xi = r%tangential%xi; load%tangential%eta = r%tangential%eta
        call solve_contact(ops, grid, mat, h0, load, set, rs, stat, em)
        call check(error, stat == 0 .and. rs%status == FC_CONVERGED, 'the shift prescribed: '//trim(em))
        if (allocated(error)) return
        call check(error, max(maxval(abs(rs%tangential%px - r%tangential%px)), maxval(abs(rs%tangential%py - &
            r%tangential%py))), 0.0_dp, 'the shift prescribed: the same tractions', abs=1e-2_dp*mu*r%normal%pmax)
        call check(error, hypot(rs%tangential%fx - qx, rs%tangential%fy - qy), 0.0_dp, 'the shift prescribed: the force', &
            abs=1e-2_dp*hypot(qx, qy))
        write (*, '(a,i0,a,2es10.2)') '    tangential_full_contact_anisotropic: ', r%tangential%iterations, &
            ' TangCG iterations; shift problem: |dq|/(mu pmax), |dF|/|F| = ', max(maxval(abs(rs%tangential%px - &
            r%tangential%px)), maxval(abs(rs%tangential%py - r%tangential%py)))/(mu*r%normal%pmax), &
            hypot(rs%tangential%fx - qx, rs%tangential%fy - qy)/hypot(qx, qy)
    end subroutine test_full_contact_anisotropic

    !> A cell in contact everywhere loaded close to what it carries: ν = 0, a 1D wavy cell 16²
    !! at P = 6 N (p̄ = 9.5 p*), a force of 0.9 μP at an angle (P* = P − |Q|/μ = 0.6 N, just
    !! below full contact).  The force hardly depends on the shift's size there (the shift is
    !! ~5e−7 mm); at tolerance 1e−8 the Broyden loop on that shift stops 2e−4 N short, on the
    !! operator whose uniform mode has Mindlin's compliance it converges.  ν = 0 makes the kernels isotropic, so
    !! the answer is the Ciavarella–Jäger one along the force: q = μ(p(P) − p(P*))·Q/|Q| (to
    !! 1e−6 of μ·pmax).
    subroutine test_near_capacity(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: rt, rp, rs
        real(dp), allocatable :: h0(:, :), ref(:, :)
        real(dp), parameter :: mu = 0.5_dp, p = 6.0_dp, qx = 1.85492_dp, qy = -1.96196_dp
        real(dp) :: q
        integer :: stat
        character(len=256) :: em
        call wavy_cell(16, 0.0_dp, mat, grid, h0, ops)
        set%normal%tol = 1e-10_dp; set%tangential%tol = 1e-8_dp
        q = hypot(qx, qy)
        call normal_pair(ops, grid, mat, h0, set, p, p - q/mu, rp, rs)
        load%normal%force_prescribed = .true.
        call check(error, all(rp%normal%pn > 0) .and. count(rs%normal%pn > 0) < size(h0), &
            'full contact at P, partial at P*')
        if (allocated(error)) return
        ref = mu*(rp%normal%pn - rs%normal%pn)
        load%problem = FC_PROBLEM_TANGENTIAL; load%normal%fn = p
        load%tangential%mu = mu; load%tangential%force_prescribed = .true.
        load%tangential%fx = qx; load%tangential%fy = qy
        call solve_contact(ops, grid, mat, h0, load, set, rt, stat, em)
        call check(error, stat == 0 .and. rt%status == FC_CONVERGED, 'solved: '//trim(em)//' '//trim(rt%tangential%message))
        if (allocated(error)) return
        call check(error, hypot(rt%tangential%fx - qx, rt%tangential%fy - qy), 0.0_dp, 'force', abs=1e-8_dp*mu*p)
        call check(error, max(maxval(abs(rt%tangential%px - ref*qx/q)), maxval(abs(rt%tangential%py - ref*qy/q))), &
            0.0_dp, 'q = mu (p(P) - p(P*)) along Q', abs=1e-6_dp*mu*rp%normal%pmax)
    end subroutine test_near_capacity

    !> A cell is a cell wherever it starts: the same rough cell shifted by (5, −3) elements
    !! gives the shifted tractions (ν = 0.3, a force with both components, so every block
    !! acts across the cell's edges).  Solved after a half-space case of the same grid and
    !! material on the same operators, which must not be reused for the periodic cell.
    subroutine test_translation(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: r0, r1, rh
        real(dp), allocatable :: h0(:, :)
        real(dp) :: pm
        integer :: stat, i, j
        character(len=256) :: em
        call material(mat, 0.3_dp)
        call make_grid(grid, 24, 20, 0.0_dp, 1.2_dp, 0.0_dp, 1.0_dp, stat, em)
        allocate (h0(24, 20))
        do j = 1, 20
            do i = 1, 24
                h0(i, j) = 1e-3_dp*(1 - cos(2*acos(-1.0_dp)*grid%x(i)/1.2_dp)*cos(2*acos(-1.0_dp)*grid%y(j))) &
                    + 2e-4_dp*sin(4*acos(-1.0_dp)*(grid%x(i)/1.2_dp + 2*grid%y(j)))
            end do
        end do
        set%normal%tol = 1e-10_dp; set%tangential%tol = 1e-10_dp
        load = force_load(0.05_dp, 0.3_dp, 0.006_dp, -0.004_dp)
        ! a half-space case first (same grid and material): its operators must not serve the cell
        call solve_contact(ops, grid, mat, quadratic_gap(grid, 50.0_dp, 50.0_dp) - 5e-3_dp, load, set, rh, stat, em)
        ops%periodic = .true.
        call solve_contact(ops, grid, mat, h0, load, set, r0, stat, em)
        call check(error, stat == 0 .and. r0%status == FC_CONVERGED, 'cell: '//trim(em))
        call solve_contact(ops, grid, mat, cshift(cshift(h0, 5, 1), -3, 2), load, set, r1, stat, em)
        call check(error, stat == 0 .and. r1%status == FC_CONVERGED, 'shifted cell: '//trim(em))
        if (allocated(error)) return
        call check(error, ops%builds_tangential == 2, 'the periodic cell gets its own tangential operator')
        pm = 0.3_dp*r0%normal%pmax
        call check(error, count(r0%tangential%state == EL_ADHESION) > 0 .and. r0%tangential%nslip > 0, 'partial slip')
        call check(error, max(maxval(abs(r1%tangential%px - cshift(cshift(r0%tangential%px, 5, 1), -3, 2))), &
            maxval(abs(r1%tangential%py - cshift(cshift(r0%tangential%py, 5, 1), -3, 2)))), 0.0_dp, &
            'shifted tractions', abs=1e-7_dp*pm)
        call check(error, maxval(abs(r0%tangential%py)) > 0.05_dp*pm, 'lateral tractions present')
    end subroutine test_translation

    !> A small circular contact in a cell eight times its diameter hardly feels its images:
    !! the periodic tractions under a tangential force (ν = 0.3) are those of the half-space
    !! on the same grid within 3 % of μ·pmax (the images' pressure and traction fields are
    !! of order (a/L)³ near the contact; measured below 1 %), with the same slip area.
    subroutine test_far_images(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops, opsp
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: rh, rp
        real(dp), allocatable :: h0(:, :)
        real(dp) :: pm
        integer :: stat
        character(len=256) :: em
        call material(mat, 0.3_dp)
        call make_grid(grid, 64, 64, -4.0_dp, 4.0_dp, -4.0_dp, 4.0_dp, stat, em)
        h0 = quadratic_gap(grid, 50.0_dp, 50.0_dp)
        load = force_load(9.1954_dp, 0.4_dp, 2.0_dp, 1.0_dp)
        call solve_contact(ops, grid, mat, h0, load, set, rh, stat, em)
        opsp%periodic = .true.
        call solve_contact(opsp, grid, mat, h0, load, set, rp, stat, em)
        call check(error, stat == 0 .and. rh%status == FC_CONVERGED .and. rp%status == FC_CONVERGED, 'solved: '//trim(em))
        if (allocated(error)) return
        pm = 0.4_dp*rh%normal%pmax
        call check(error, max(maxval(abs(rp%tangential%px - rh%tangential%px)), &
            maxval(abs(rp%tangential%py - rh%tangential%py))), 0.0_dp, 'tractions as on the half-space', abs=0.03_dp*pm)
        call check(error, real(abs(rp%tangential%nslip - rh%tangential%nslip), dp), 0.0_dp, 'slip area', &
            abs=0.05_dp*rh%tangential%nslip)
    end subroutine test_far_images

    !> A dissimilar pair: steel-like body 1 (G = 800, ν = 0.28) on a soft body 2 (G = 200,
    !! ν = 0.42), K ≈ −0.07.
    subroutine dissimilar(mat)
        type(fc_material), intent(out) :: mat
        integer :: stat
        character(len=200) :: m
        mat%g1 = 800; mat%g2 = 200; mat%nu1 = 0.28_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, m)
    end subroutine dissimilar

    !> The periodic coupling blocks of a 16×12 cell (K ≠ 0): A^xz, A^zx odd in x and even in
    !! y, A^yz, A^zy odd in y and even in x, A^zx = −A^xz and A^zy = −A^yz exactly; the sums
    !! with 2 image rings within 5e−4 of those with 20 (measured 3.1e−4 and 1.7e−4: an odd
    !! 1/r kernel's images converge more slowly than the even blocks').  Near the origin of a 48×48 cell
    !! they are the half-space's coefficients plus a uniform strain: the images' load is
    !! balanced by a uniform counter-load (the cell carries its mean pressure), whose
    !! tangential displacement grows linearly, (K/G)·x·dx·dy/(Lx·Ly) for A^xz (y for
    !! A^yz); an odd kernel's singular part keeps it, where an even one's is a constant.
    !! Checked to 5e−5 of the maximum (measured 1.0e−5; 2.8e−3 without the strain term).
    subroutine test_coupling_kernels(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid, big
        real(dp), allocatable :: wxz(:, :), wzx(:, :), wyz(:, :), wzy(:, :), w20(:, :), bxz(:, :), byz(:, :)
        real(dp) :: d, near, slope, off
        integer :: stat, i, j, nx, ny
        character(len=256) :: em
        nx = 16; ny = 12
        call dissimilar(mat)
        call check(error, abs(mat%k) > 0.01_dp, 'the pair is dissimilar')
        call make_grid(grid, nx, ny, 0.0_dp, 1.6_dp, 0.0_dp, 1.0_dp, stat, em)
        call periodic_wrapped_kernel(mat, grid, 2, IC_XZ, wxz)
        call periodic_wrapped_kernel(mat, grid, 2, IC_ZX, wzx)
        call periodic_wrapped_kernel(mat, grid, 2, IC_YZ, wyz)
        call periodic_wrapped_kernel(mat, grid, 2, IC_ZY, wzy)
        d = 0
        do j = 0, ny - 1
            do i = 0, nx - 1
                d = max(d, abs(wxz(i, j) + wxz(modulo(-i, nx), j)), abs(wxz(i, j) - wxz(i, modulo(-j, ny))), &
                    abs(wyz(i, j) - wyz(modulo(-i, nx), j)), abs(wyz(i, j) + wyz(i, modulo(-j, ny))))
            end do
        end do
        call check(error, d, 0.0_dp, 'A^xz odd in x, even in y; A^yz even in x, odd in y', abs=0.0_dp)
        call check(error, maxval(abs(wzx + wxz)) == 0 .and. maxval(abs(wzy + wyz)) == 0, 'A^zx = -A^xz, A^zy = -A^yz')
        call check(error, maxval(abs(wxz)) > 0 .and. maxval(abs(wyz)) > 0, 'coupling blocks not zero')
        call make_grid(big, 48, 48, 0.0_dp, 4.8_dp, 0.0_dp, 4.8_dp, stat, em)
        call periodic_wrapped_kernel(mat, big, 2, IC_XZ, bxz)
        call periodic_wrapped_kernel(mat, big, 2, IC_YZ, byz)
        ! the images' uniform counter-load strains the cell: slope K/G·dx·dy/(Lx·Ly)
        slope = mat%k/mat%g*big%dx*big%dy/(48*big%dx*48*big%dy)
        near = 0; off = 0
        do j = 0, 2
            do i = 0, 2
                near = max(near, abs(bxz(i, j) - element_coefficient(IC_XZ, mat, i*big%dx, j*big%dy, big%dx, big%dy) &
                    - slope*i*big%dx), abs(byz(i, j) - element_coefficient(IC_YZ, mat, i*big%dx, j*big%dy, big%dx, big%dy) &
                    - slope*j*big%dy))
                off = max(off, abs(bxz(i, j) - element_coefficient(IC_XZ, mat, i*big%dx, j*big%dy, big%dx, big%dy)))
            end do
        end do
        call check(error, near, 0.0_dp, 'A^xz, A^yz near the origin: half-space + uniform strain (48 x 48 cell)', &
            abs=5e-5_dp*maxval(abs(bxz)))
        call check(error, off > 1e-3_dp*maxval(abs(bxz)), 'the uniform strain is resolved')
        call periodic_wrapped_kernel(mat, grid, 20, IC_XZ, w20)
        call check(error, maxval(abs(w20 - wxz)), 0.0_dp, 'A^xz: 2 image rings as 20', abs=5e-4_dp*maxval(abs(wxz)))
        d = maxval(abs(w20 - wxz))/maxval(abs(wxz))
        call periodic_wrapped_kernel(mat, grid, 20, IC_YZ, w20)
        call check(error, maxval(abs(w20 - wyz)), 0.0_dp, 'A^yz: 2 image rings as 20', abs=5e-4_dp*maxval(abs(wyz)))
        write (*, '(a,4es10.2)') '    coupling_kernels: near-origin (with, without strain), 20-ring A^xz, A^yz / max = ', &
            near/maxval(abs(bxz)), off/maxval(abs(bxz)), d, maxval(abs(w20 - wyz))/maxval(abs(wyz))
    end subroutine test_coupling_kernels

    !> Dissimilar bodies on a periodic cell (Panagiotopoulos rounds on the periodic coupling
    !! blocks): a small circular contact in a cell eight times its diameter under a
    !! tangential force gives the half-space's pressures (within 1 % of pmax) and tractions
    !! (within 3 % of μ·pmax), as in `tangential_far_images`; the coupling moves the
    !! half-space's pressures by more than that (so a periodic solve without its coupling
    !! blocks fails here).
    subroutine test_far_images_dissimilar(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat, mat0
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops, opsp, ops0
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: rh, rp, r0
        real(dp), allocatable :: h0(:, :)
        real(dp) :: pm, dp_coupling, dp_images, dt_images
        integer :: stat
        character(len=256) :: em
        call dissimilar(mat)
        mat0 = mat; mat0%k = 0
        call make_grid(grid, 64, 64, -4.0_dp, 4.0_dp, -4.0_dp, 4.0_dp, stat, em)
        h0 = quadratic_gap(grid, 50.0_dp, 50.0_dp)
        load = force_load(9.1954_dp, 0.4_dp, 2.0_dp, 1.0_dp)
        set%normal%tol = 1e-8_dp; set%tangential%tol = 1e-8_dp
        call solve_contact(ops, grid, mat, h0, load, set, rh, stat, em)
        call solve_contact(ops0, grid, mat0, h0, load, set, r0, stat, em)
        opsp%periodic = .true.
        call solve_contact(opsp, grid, mat, h0, load, set, rp, stat, em)
        call check(error, stat == 0 .and. rh%status == FC_CONVERGED .and. rp%status == FC_CONVERGED .and. &
            r0%status == FC_CONVERGED, 'solved: '//trim(em))
        if (allocated(error)) return
        call check(error, rp%rounds > 1 .and. rh%rounds > 1, 'Panagiotopoulos rounds on both')
        pm = rh%normal%pmax
        dp_coupling = maxval(abs(rh%normal%pn - r0%normal%pn))
        dp_images = maxval(abs(rp%normal%pn - rh%normal%pn))
        dt_images = max(maxval(abs(rp%tangential%px - rh%tangential%px)), maxval(abs(rp%tangential%py - rh%tangential%py)))
        call check(error, dp_coupling > 0.01_dp*pm, 'the coupling moves the pressures by more than 1 % of pmax')
        call check(error, dp_images, 0.0_dp, 'pressures as on the half-space', abs=0.01_dp*pm)
        call check(error, dt_images, 0.0_dp, 'tractions as on the half-space', abs=0.03_dp*0.4_dp*pm)
        write (*, '(a,3es10.2)') '    dissimilar_far_images: |dp| coupling, |dp| images / pmax, |dq| / mu pmax = ', &
            dp_coupling/pm, dp_images/pm, dt_images/(0.4_dp*pm)
    end subroutine test_far_images_dissimilar

    !> Dissimilar bodies whose pressure alone slips every element: strips two elements wide
    !! (a 1D wavy cell 24 × 4 with two waves, P = 0.02 N, G = 200 / 800, ν = 0 / 0.28, K =
    !! 0.36, μ = 0.2).  The coupling pushes a strip's two sides apart, so at zero shift both
    !! slip (in opposite directions) and the force is nil, and it stays nil for shifts up to
    !! ~2e−6 mm; beyond, one side sticks and the force rises steeply.  Under a force of 5 %
    !! of μP the force loop's first probes used to shrink the shift towards zero (a shift that
    !! slips everything was taken to be too large) and the loop stopped in the dead zone,
    !! not converged.  Checked: at zero shift every element slips with |F| < 1e−6 μP (the
    !! premise); the force loop converges to the force within tol·μP with one side of each
    !! strip sticking; the shift it reports, prescribed, gives its tractions within 1 % of
    !! μ·pmax.
    subroutine test_dissimilar_dead_zone(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: r, r0, rs
        real(dp), allocatable :: h0(:, :)
        real(dp), parameter :: mu = 0.2_dp, p = 0.02_dp, qx = -1.82371e-4_dp, qy = -8.21036e-5_dp
        integer :: stat
        character(len=256) :: em
        mat%g1 = 200; mat%g2 = 800; mat%nu1 = 0; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, em)
        call make_grid(grid, 24, 4, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, stat, em)
        h0 = wavy_gap(grid, 0.001_dp, 0.5_dp, 0.0_dp)
        ops%periodic = .true.
        load = force_load(p, mu, 0.0_dp, 0.0_dp)
        load%tangential%force_prescribed = .false.
        call solve_contact(ops, grid, mat, h0, load, set, r0, stat, em)
        call check(error, stat == 0 .and. r0%status == FC_CONVERGED, 'zero shift: '//trim(em))
        if (allocated(error)) return
        call check(error, r0%tangential%nadh == 0 .and. r0%tangential%nslip == 2*2*4 .and. &
            hypot(r0%tangential%fx, r0%tangential%fy) < 1e-6_dp*mu*p, &
            'zero shift: two strips of 2 x 4 elements, all slipping, no force')
        load = force_load(p, mu, qx, qy)
        call solve_contact(ops, grid, mat, h0, load, set, r, stat, em)
        call check(error, stat == 0 .and. r%status == FC_CONVERGED, 'the force prescribed: converged: '// &
            trim(em)//trim(r%tangential%message))
        if (allocated(error)) return
        call check(error, hypot(r%tangential%fx - qx, r%tangential%fy - qy), 0.0_dp, 'the force', &
            abs=set%tangential%tol*mu*p)
        call check(error, r%tangential%nadh == 2*4 .and. r%tangential%nslip == 2*4, 'one side of each strip sticks')
        load%tangential%force_prescribed = .false.
        load%tangential%xi = r%tangential%xi; load%tangential%eta = r%tangential%eta
        call solve_contact(ops, grid, mat, h0, load, set, rs, stat, em)
        call check(error, stat == 0 .and. rs%status == FC_CONVERGED, 'the shift prescribed: '//trim(em))
        if (allocated(error)) return
        call check(error, max(maxval(abs(rs%tangential%px - r%tangential%px)), maxval(abs(rs%tangential%py - &
            r%tangential%py))), 0.0_dp, 'the shift prescribed: the same tractions', abs=1e-2_dp*mu*r%normal%pmax)
        write (*, '(a,i0,a,i0,a,es10.3,a)') '    dissimilar_pressure_slips_everything: ', r%tangential%iterations, &
            ' TangCG iterations, ', r%tangential%outer_iterations, ' force-loop steps, shift ', r%tangential%xi, ' mm'
    end subroutine test_dissimilar_dead_zone

    !> The driver solves a periodic 'normal+tangential' case (shifts and forces, also for
    !! dissimilar bodies) and refuses rolling, spin and ConvexGS on a periodic cell, naming
    !! the keys.
    subroutine test_driver(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, errors, base
        integer :: code
        base = "&case name = 'cell', problem = 'normal+tangential' /"//new_line('a')// &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.3, nu2 = 0.3 /'//new_line('a')// &
            '&grid nx = 32, ny = 32, xmin = 0.0, xmax = 1.0, ymin = 0.0, ymax = 1.0, periodic = .true. /'//new_line('a')// &
            "&geometry kind = 'wavy', amplitude = 0.001, wavelength_x = 1.0, wavelength_y = 1.0 /"//new_line('a')// &
            '&normal fn = 0.05 /'//new_line('a')//'&tangential mu = 0.3, fx = 0.01, fy = 0.0 /'//new_line('a')
        dir = fresh_dir('periodic')
        call run_namelist(dir, base//"&case name = 'cell_shift' /"//new_line('a')// &
            '&tangential mu = 0.3, xi = -1.0e-4, eta = 0.0 /'//new_line('a'), code, errors)
        call check(error, code == 0, 'periodic tangential cases solved: '//errors)
        call run_namelist(dir, base//"&case name = 'r', problem = 'rolling' /"//new_line('a'), code, errors)
        call check(error, code == 1 .and. index(errors, 'periodic') > 0 .and. index(errors, "'rolling'") > 0, &
            'rolling refused: '//errors)
        call run_namelist(dir, base//"&solver tangential = 'convexgs' /"//new_line('a'), code, errors)
        call check(error, code == 1 .and. index(errors, "'convexgs'") > 0, 'ConvexGS refused: '//errors)
        call run_namelist(dir, base//'&tangential phi = 0.01 /'//new_line('a'), code, errors)
        call check(error, code == 1 .and. index(errors, '&tangential phi') > 0 .and. index(errors, 'spin') > 0, &
            'spin refused: '//errors)
        call run_namelist(dir, base//'&material g1 = 800.0, nu1 = 0.28 /'//new_line('a'), code, errors)
        call check(error, code == 0, 'dissimilar bodies solved: '//errors)
        call execute_command_line("rm -rf '"//dir//"'")
    end subroutine test_driver

    !> Prescribed forces far below the force loop's tolerance (1e−20 N down to the smallest
    !! subnormal) on a rough cell of identical and of dissimilar bodies: every case converges
    !! with |F − F_prescribed| ≤ tol·μFn.  The driver fuzz found these: for dissimilar bodies
    !! the cell carries a force at zero shift (the pressure's coupling), so the probes' secant
    !! through the origin exceeded Mindlin's stiffness by up to 1e300 — the loop then stalled
    !! (1e−20 N: not converged, force error 0.69 N) or its Jacobian's determinant overflowed;
    !! and for 1e−300 N gfortran's norm2 of the probe's shift was 0.  The overflow and the
    !! division by zero stop the sanitizer build (FPE traps), where CI runs this suite too.
    subroutine test_tiny_forces(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, errors, text, json
        character(len=*), parameter :: mats(2) = [character(len=48) :: &
            'g2 = 82000.0, nu1 = 0.28, nu2 = 0.28', 'g2 = 26000.0, nu1 = 0.28, nu2 = 0.33']
        character(len=*), parameter :: forces(3) = [character(len=8) :: '1.0e-20', '1.0e-300', '4.9e-324']
        integer :: code, i, j
        dir = fresh_dir('periodic')
        do i = 1, size(mats)
            do j = 1, size(forces)
                text = "&case name = 'tiny', problem = 'normal+tangential' /"//new_line('a')// &
                    '&material g1 = 82000.0, '//trim(mats(i))//' /'//new_line('a')// &
                    '&grid nx = 16, ny = 16, xmin = 0.0, xmax = 1.0, ymin = 0.0, ymax = 1.0, periodic = .true. /'// &
                    new_line('a')//"&geometry kind = 'punch_rough', diameter = 2.0, sigma = 1.0e-3, gamma = 0.9, "// &
                    'm_modes = 24, n_modes = 24 /'//new_line('a')//'&normal fn = 200.0 /'//new_line('a')// &
                    '&tangential mu = 0.3, fx = '//trim(forces(j))//', fy = 0.0 /'//new_line('a')
                call run_namelist(dir, text, code, errors)
                json = file_lines(dir//'/tiny.json')
                call check(error, code == 0 .and. index(json, '"status": "converged"') > 0, &
                    trim(mats(i))//', fx = '//trim(forces(j))//': converged: '//errors)
                if (allocated(error)) return
                call check(error, abs(json_num(json, 'fx')) <= 1.0e-5_dp*0.3_dp*200.0_dp, &
                    trim(mats(i))//', fx = '//trim(forces(j))//': |Fx - Fx prescribed| <= tol*mu*Fn')
                if (allocated(error)) return
            end do
        end do
        call execute_command_line("rm -rf '"//dir//"'")
    end subroutine test_tiny_forces

    !> The flat API solves the periodic tangential problem as the library does (the same
    !! tractions to 1e−12 of μ·pmax) and refuses steady rolling on a periodic cell with a
    !! message that says so.
    subroutine test_api(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_operators) :: ops
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: r
        integer(c_int) :: h, ierr, ierr2
        real(c_double) :: fn, fx, fy, mz, pn(32*32), px(32*32), py(32*32)
        real(dp), allocatable :: h0(:, :)
        character(kind=c_char, len=512) :: buf
        integer :: stat
        character(len=256) :: em
        call material(mat, 0.3_dp)
        call make_grid(grid, 32, 32, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, stat, em)
        h0 = wavy_gap(grid, 0.001_dp, 1.0_dp, 1.0_dp)
        call fc_init(h, ierr)
        call fc_set_material(h, 200.0_c_double, 200.0_c_double, 0.3_c_double, 0.3_c_double, ierr)
        call fc_set_grid(h, 32_c_int, 32_c_int, 0.0_c_double, 1.0_c_double, 0.0_c_double, 1.0_c_double, ierr)
        call fc_set_gap_array(h, 1024_c_int, reshape(h0, [1024]), ierr)
        call fc_set_periodic(h, 1_c_int, ierr)
        call fc_set_normal_force(h, 0.05_c_double, ierr)
        call fc_set_friction(h, 0.3_c_double, ierr)
        call fc_set_forces(h, 0.01_c_double, -0.004_c_double, 0.0_c_double, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_OK, 'periodic tangential calculation')
        if (allocated(error)) return
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call fc_get_tractions(h, 1024_c_int, pn, px, py, ierr)
        ops%periodic = .true.
        load = force_load(0.05_dp, 0.3_dp, 0.01_dp, -0.004_dp)
        call solve_contact(ops, grid, mat, h0, load, set, r, stat, em)
        call check(error, stat == 0 .and. r%status == FC_CONVERGED, 'library solve: '//trim(em))
        if (allocated(error)) return
        call check(error, real(fx, dp), 0.01_dp, 'Fx', rel=1e-4_dp)
        call check(error, real(fy, dp), -0.004_dp, 'Fy', rel=1e-4_dp)
        call check(error, max(maxval(abs(px - reshape(r%tangential%px, [1024]))), &
            maxval(abs(py - reshape(r%tangential%py, [1024])))), 0.0_dp, 'tractions as the library''s', &
            abs=1e-12_dp*0.3_dp*r%normal%pmax)
        call fc_set_rolling(h, 0.001_c_double, 0.0_c_double, 0.0_c_double, ierr)
        call fc_calculate(h, ierr)
        call fc_get_error_message(h, buf, int(len(buf), c_int), ierr2)
        call check(error, ierr /= FCL_OK .and. index(buf, 'periodic') > 0 .and. index(buf, 'rolling') > 0, &
            'steady rolling on a periodic cell refused: '//buf(1:max(1, index(buf, c_null_char) - 1)))
        call fc_finalize(h, ierr)
    end subroutine test_api

end module test_periodic
