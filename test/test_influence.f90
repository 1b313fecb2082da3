!> Suite `influence`: influence coefficients and BTTB products (doc/conventions.md).
module test_influence
    use fc_kinds, only: dp, pi
    use fc_geometry, only: fc_grid, make_grid
    use fc_influence
    use fc_periodic, only: periodic_wrapped_kernel
    use fc_toeplitz, only: build_bttb_periodic
    use fc_lapack, only: dpotrf, dsyev
    use fc_testing
    implicit none
    private
    public :: collect_influence

contains

    subroutine collect_influence(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('material_combination', test_material), &
            new_unittest('fft_equals_direct_all_blocks', test_fft_vs_direct), &
            new_unittest('fft_equals_direct_periodic', test_periodic_vs_direct), &
            new_unittest('azz_symmetric_positive_definite', test_azz_spd), &
            new_unittest('closed_form_vs_quadrature', test_quadrature), &
            new_unittest('periodic_sinusoid_response', test_periodic_sinusoid), &
            new_unittest('preconditioner_approximates_inverse', test_preconditioner), &
            new_unittest('uncoupled_kernels_share_one_term', test_uncoupled_kernels) ]
    end subroutine collect_influence

    subroutine steel(mat, g1, g2, nu1, nu2)
        type(fc_material), intent(out) :: mat
        real(dp), intent(in) :: g1, g2, nu1, nu2
        integer :: stat
        character(len=200) :: msg
        mat%g1 = g1; mat%g2 = g2; mat%nu1 = nu1; mat%nu2 = nu2
        call combine_material(mat, stat, msg)
    end subroutine steel

    !> Kalker's combination (doc/conventions.md): identical bodies, rigid body, dissimilar K sign.
    subroutine test_material(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: m
        integer :: stat
        character(len=200) :: msg
        call steel(m, 82000.0_dp, 82000.0_dp, 0.28_dp, 0.28_dp)
        call check(error, m%g, 82000.0_dp, 'identical bodies: G', rel=1e-14_dp)
        call check(error, m%nu, 0.28_dp, 'identical bodies: nu', rel=1e-14_dp)
        call check(error, m%k, 0.0_dp, 'identical bodies: K', abs=1e-14_dp)
        call steel(m, 1.0e30_dp, 40000.0_dp, 0.28_dp, 0.28_dp)
        call check(error, m%g, 80000.0_dp, 'rigid body 1: G = 2 G2', rel=1e-14_dp)
        call check(error, m%nu, 0.28_dp, 'rigid body 1: nu = nu2', rel=1e-14_dp)
        ! K = (G/4)[(1−2ν1)/G1 − (1−2ν2)/G2] = −(80000/4)(0.44/40000) = −0.22
        call check(error, m%k, -0.22_dp, 'rigid body 1: K', rel=1e-12_dp)
        m%g1 = -1; m%g2 = 1; m%nu1 = 0.3_dp; m%nu2 = 0.3_dp
        call combine_material(m, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'g1') > 0, 'G1 <= 0 must be rejected naming g1: '//trim(msg))
        m%g1 = 1; m%nu2 = 0.5_dp
        call combine_material(m, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'nu2') > 0, 'nu2 = 0.5 must be rejected naming nu2: '//trim(msg))
    end subroutine test_material

    !> FFT product equals the direct O(n²) product to 1e−12 (relative) for every block on
    !! non-square grids, including strips (n×1, 1×n).
    subroutine test_fft_vs_direct(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: shapes(2, 5) = reshape([7, 5, 12, 9, 16, 1, 1, 11, 20, 13], [2, 5])
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op
        real(dp), allocatable :: x(:, :), yf(:, :), yd(:, :)
        integer :: s, b, stat
        character(len=200) :: msg, label
        call steel(mat, 200.0_dp, 1000.0_dp, 0.42_dp, 0.3_dp)   ! dissimilar: K ≠ 0
        do s = 1, size(shapes, 2)
            call make_grid(grid, shapes(1, s), shapes(2, s), -1.3_dp, 1.1_dp, -0.7_dp, 0.9_dp, stat, msg)
            allocate (x(grid%nx, grid%ny), yf(grid%nx, grid%ny), yd(grid%nx, grid%ny))
            call random_number(x)
            x = x - 0.3_dp
            do b = IC_ZZ, IC_ZY
                call build_bttb(op, b, mat, grid)
                call op%apply(x, yf)
                call op%apply_direct(x, yd)
                write (label, '(a,i0,a,i0,a,i0)') 'block ', b, ' grid ', grid%nx, 'x', grid%ny
                call check(error, rel_diff(pack(yf, .true.), pack(yd, .true.)), 0.0_dp, trim(label), abs=1e-12_dp)
            end do
            call op%destroy()
            deallocate (x, yf, yd)
        end do
    end subroutine test_fft_vs_direct

    !> Periodic variant (the periodic half-space's kernels of fc_periodic): FFT product
    !! equals the direct periodic (circular) sum.
    subroutine test_periodic_vs_direct(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op
        real(dp) :: x(10, 6), yf(10, 6), yd(10, 6)
        real(dp), allocatable :: w(:, :)
        integer :: stat, b
        character(len=200) :: msg
        call steel(mat, 200.0_dp, 200.0_dp, 0.3_dp, 0.3_dp)
        call make_grid(grid, 10, 6, 0.0_dp, 2.0_dp, 0.0_dp, 1.5_dp, stat, msg)
        call random_number(x)
        do b = IC_ZZ, IC_XY
            call periodic_wrapped_kernel(mat, grid, 2, b, w)
            call build_bttb_periodic(op, w)
            call op%apply(x, yf)
            call op%apply_direct(x, yd)
            call check(error, rel_diff(pack(yf, .true.), pack(yd, .true.)), 0.0_dp, 'periodic block', abs=1e-12_dp)
        end do
        call op%destroy()
    end subroutine test_periodic_vs_direct

    !> A^zz is symmetric and positive definite (Cholesky by LAPACK dpotrf succeeds and the
    !! smallest eigenvalue from dsyev is positive) on small grids.
    subroutine test_azz_spd(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op
        real(dp), allocatable :: a(:, :), chol(:, :), w(:), work(:), e(:, :), col(:, :)
        integer :: stat, n, j, info, g
        integer, parameter :: dims(2, 3) = reshape([6, 5, 9, 4, 16, 1], [2, 3])
        character(len=200) :: msg
        call steel(mat, 82000.0_dp, 82000.0_dp, 0.28_dp, 0.28_dp)
        do g = 1, 3
            call make_grid(grid, dims(1, g), dims(2, g), -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
            n = grid%n()
            allocate (a(n, n), e(grid%nx, grid%ny), col(grid%nx, grid%ny))
            call build_bttb(op, IC_ZZ, mat, grid)
            do j = 1, n
                e = 0
                e(mod(j - 1, grid%nx) + 1, (j - 1)/grid%nx + 1) = 1
                call op%apply_direct(e, col)
                a(:, j) = pack(col, .true.)
            end do
            call check(error, maxval(abs(a - transpose(a))) <= 1e-15_dp*maxval(abs(a)), 'A^zz symmetric')
            chol = a
            call dpotrf('L', n, chol, n, info)
            call check(error, info == 0, 'Cholesky of A^zz succeeds')
            allocate (w(n), work(3*n))
            call dsyev('N', 'L', n, a, n, w, work, 3*n, info)
            call check(error, info == 0 .and. w(1) > 0, 'smallest eigenvalue of A^zz positive')
            deallocate (a, w, work, e, col)
        end do
        call op%destroy()
    end subroutine test_azz_spd

    !> Closed-form element coefficients agree with an independent quadrature of the point
    !! kernel.  For kernels homogeneous of degree −1, the integral over a triangle with a
    !! vertex at the singular point reduces to cross(P1, P2−P1)·∫₀¹ f(P1 + t(P2−P1)) dt, so
    !! the rectangle integral is a sum of four smooth line integrals (composite Gauss).
    !! Tolerance 1e−9 relative (quadrature error of the composite rule).
    subroutine test_quadrature(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        real(dp), parameter :: dx = 0.4_dp, dy = 0.25_dp
        real(dp), parameter :: offsets(2, 7) = reshape([0.0_dp, 0.0_dp, 0.4_dp, 0.0_dp, 0.0_dp, 0.25_dp, &
            0.4_dp, -0.25_dp, 1.2_dp, 0.75_dp, -2.0_dp, 0.5_dp, 4.4_dp, -3.25_dp], [2, 7])
        real(dp) :: closed, quad, c
        integer :: b, k
        character(len=120) :: label
        call steel(mat, 300.0_dp, 100.0_dp, 0.25_dp, 0.4_dp)
        c = 1/(pi*mat%g)
        do k = 1, size(offsets, 2)
            do b = IC_ZZ, IC_ZY
                closed = element_coefficient(b, mat, offsets(1, k), offsets(2, k), dx, dy)
                select case (b)
                case (IC_ZZ); quad = c*(1 - mat%nu)*rect(1)
                case (IC_XX); quad = c*((1 - mat%nu)*rect(1) + mat%nu*rect(2))
                case (IC_YY); quad = c*((1 - mat%nu)*rect(1) + mat%nu*rect(3))
                case (IC_XY); quad = c*mat%nu*rect(4)
                case (IC_XZ); quad = -c*mat%k*rect(5)
                case (IC_ZX); quad = c*mat%k*rect(5)
                case (IC_YZ); quad = -c*mat%k*rect(6)
                case default; quad = c*mat%k*rect(6)
                end select
                write (label, '(a,i0,a,2f7.3)') 'block ', b, ' offset ', offsets(:, k)
                call check(error, closed, quad, trim(label), rel=1e-9_dp, abs=1e-14_dp)
            end do
        end do
    contains
        !> ∫∫ kernel(u,v) over the source element seen from offset (X,Y).
        real(dp) function rect(kind)
            integer, intent(in) :: kind
            real(dp) :: px(5), py(5)
            integer :: e
            px = offsets(1, k) + [dx, -dx, -dx, dx, dx]/2
            py = offsets(2, k) + [dy, dy, -dy, -dy, dy]/2
            rect = 0
            do e = 1, 4
                rect = rect + edge(kind, px(e), py(e), px(e + 1), py(e + 1))
            end do
        end function rect
        real(dp) function edge(kind, x1, y1, x2, y2)
            integer, intent(in) :: kind
            real(dp), intent(in) :: x1, y1, x2, y2
            real(dp), parameter :: gx(8) = [-0.9602898564975363_dp, -0.7966664774136267_dp, -0.5255324099163290_dp, &
                -0.1834346424956498_dp, 0.1834346424956498_dp, 0.5255324099163290_dp, 0.7966664774136267_dp, &
                0.9602898564975363_dp]
            real(dp), parameter :: gw(8) = [0.1012285362903763_dp, 0.2223810344533745_dp, 0.3137066458778873_dp, &
                0.3626837833783620_dp, 0.3626837833783620_dp, 0.3137066458778873_dp, 0.2223810344533745_dp, &
                0.1012285362903763_dp]
            integer, parameter :: npanel = 400
            real(dp) :: cr, s, t, u, v, r, a0
            integer :: ip, ig
            cr = x1*(y2 - y1) - y1*(x2 - x1)
            edge = 0
            if (abs(cr) < 1e-14_dp) return
            s = 0
            do ip = 1, npanel
                a0 = real(ip - 1, dp)/npanel
                do ig = 1, 8
                    t = a0 + (gx(ig) + 1)/(2*npanel)
                    u = x1 + t*(x2 - x1); v = y1 + t*(y2 - y1)
                    r = hypot(u, v)
                    select case (kind)
                    case (1); s = s + gw(ig)*1/r
                    case (2); s = s + gw(ig)*u**2/r**3
                    case (3); s = s + gw(ig)*v**2/r**3
                    case (4); s = s + gw(ig)*u*v/r**3
                    case (5); s = s + gw(ig)*u/r**2
                    case default; s = s + gw(ig)*v/r**2
                    end select
                end do
            end do
            edge = cr*s/(2*npanel)
        end function edge
    end subroutine test_quadrature

    !> Periodic A^zz (fc_periodic's kernel: 2 image rings and the far images' tail): a
    !! sinusoidal pressure p = cos(2πx/L) on a long periodic strip of the surface gives the
    !! plane-strain response u = 2(1−ν)/G · L/(2π) · p (Johnson §13.2, with the combined G of
    !! doc/conventions.md).  Piecewise-constant elements make this approximate: tolerance
    !! 0.5 % at 64 elements per wavelength (measured 1.0e−3; the plain lattice sum over 40
    !! image rings without the tail, which this library had before, was within 2 %).
    subroutine test_periodic_sinusoid(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op
        real(dp) :: p(64, 4), u(64, 4), expected
        real(dp), allocatable :: w(:, :)
        integer :: stat, i
        character(len=200) :: msg
        call steel(mat, 1000.0_dp, 1000.0_dp, 0.3_dp, 0.3_dp)
        call make_grid(grid, 64, 4, 0.0_dp, 1.0_dp, 0.0_dp, 0.0625_dp, stat, msg)
        do i = 1, 64
            p(i, :) = cos(2*pi*grid%x(i))
        end do
        call periodic_wrapped_kernel(mat, grid, 2, IC_ZZ, w)
        call build_bttb_periodic(op, w)
        call op%apply(p, u)
        expected = 2*(1 - mat%nu)/mat%g/(2*pi)
        write (*, '(a,2es10.2)') '    periodic_sinusoid_response: amplitude, shape errors ', &
            u(1, 1)/p(1, 1)/expected - 1, rel_diff(pack(u, .true.), pack(expected*p, .true.))
        call check(error, u(1, 1)/p(1, 1), expected, 'periodic response amplitude', rel=0.005_dp)
        call check(error, rel_diff(pack(u, .true.), pack(expected*p, .true.)), 0.0_dp, 'periodic response shape', &
            abs=0.005_dp)
        call op%destroy()
    end subroutine test_periodic_sinusoid

    !> The Toeplitz preconditioner M ≈ (A^zz)⁻¹ (thesis §3.3.1): M·A·x ≈ x on the central
    !! half of the grid for a smooth x supported well inside it (relative 10 %).  Near the
    !! edges M·A·x is far off (measured ~100 %): A·x is truncated at the grid edge and M,
    !! an infinite-domain inverse, reacts strongly to that jump — the edge overshoot that
    !! BCCG's masking to the free set deals with.
    subroutine test_preconditioner(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op, prec
        real(dp) :: x(48, 40), ax(48, 40), max_(48, 40), r2, minsym
        integer :: stat, i, j
        character(len=200) :: msg
        call steel(mat, 82000.0_dp, 82000.0_dp, 0.28_dp, 0.28_dp)
        call make_grid(grid, 48, 40, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
        do j = 1, 40
            do i = 1, 48
                r2 = (grid%x(i)/5)**2 + (grid%y(j)/3)**2
                x(i, j) = exp(-4*r2)
            end do
        end do
        call build_bttb(op, IC_ZZ, mat, grid)
        call build_inverse_toeplitz(IC_ZZ, mat, grid, prec, minsym)
        call check(error, minsym > 0, 'doubled-grid circulant of A^zz is positive definite')
        call op%apply(x, ax)
        call prec%apply(ax, max_)
        call check(error, rel_diff(pack(max_(13:36, 11:30), .true.), pack(x(13:36, 11:30), .true.)), 0.0_dp, &
            'M A x ≈ x in the interior', abs=0.1_dp)
        call op%destroy(); call prec%destroy()
    end subroutine test_preconditioner

    !> ic_kernels_uncoupled (the 1/ρ term evaluated once for A^zz, A^xx, A^yy): every
    !! coefficient equals the element-by-element formula (to 1e−13 of the largest: the two
    !! differ only in rounding) and the block-by-block evaluation exactly; asking for a subset
    !! returns the same numbers, each block in its own argument.
    subroutine test_uncoupled_kernels(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: mx = 9, my = 6
        integer, parameter :: blocks(4) = [IC_ZZ, IC_XX, IC_XY, IC_YY]
        type(fc_material) :: mat
        type(fc_grid) :: grid
        real(dp), allocatable :: kzz(:, :), kxx(:, :), kxy(:, :), kyy(:, :), one(:, :), sep(:, :), sxy(:, :), syy(:, :)
        real(dp) :: worst, kmax
        integer :: b, i, j, stat
        character(len=200) :: msg
        call steel(mat, 200.0_dp, 1000.0_dp, 0.42_dp, 0.3_dp)
        call make_grid(grid, 7, 5, -1.3_dp, 1.1_dp, -0.7_dp, 0.9_dp, stat, msg)
        call ic_kernels_uncoupled(mat, grid, mx, my, kzz, kxx, kxy, kyy)
        do b = 1, 4
            select case (blocks(b))
            case (IC_ZZ); one = kzz
            case (IC_XX); one = kxx
            case (IC_XY); one = kxy
            case default; one = kyy
            end select
            call check(error, all(lbound(one) == [-mx, -my]) .and. all(ubound(one) == [mx, my]), 'bounds')
            if (allocated(error)) return
            kmax = maxval(abs(one)); worst = 0
            do j = -my, my
                do i = -mx, mx
                    worst = max(worst, abs(one(i, j) - element_coefficient(blocks(b), mat, i*grid%dx, j*grid%dy, &
                        grid%dx, grid%dy)))
                end do
            end do
            write (msg, '(a,i0)') 'element-by-element formula, block ', blocks(b)
            call check(error, worst/kmax, 0.0_dp, trim(msg), abs=1e-13_dp)
            call ic_kernel_extended(blocks(b), mat, grid, mx, my, sep)
            write (msg, '(a,i0)') 'block by block, bit for bit, block ', blocks(b)
            call check(error, all(sep == one), trim(msg))
            if (allocated(error)) return
        end do
        call ic_kernels_uncoupled(mat, grid, mx, my, kxy=sxy, kyy=syy)
        call check(error, all(sxy == kxy) .and. all(syy == kyy), 'subset (A^xy, A^yy): the same numbers in place')
        call check(error, any(kxx /= kyy) .and. any(kxx /= kzz), 'A^xx, A^yy, A^zz are different blocks')
    end subroutine test_uncoupled_kernels

end module test_influence
