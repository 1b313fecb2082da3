!> Suite `mg2d`: multigrid with the FFT smoother on the 2D no-slip strip problems MP1–MP3
!! against thesis ch. 3 (Tables 3.1–3.5, 3.7–3.9, Figs. 3.4, 3.11).
module test_mg2d
    use fc_kinds
    use fc_influence
    use fc_mg2d
    use fc_geometry, only: make_grid
    use fc_mg2d_ops, only: strip_fft, strip_kernel, strip_toeplitz_inverse_even, strip_workspace, strip_workspace_need
    use fc_testing
    implicit none
    private
    public :: collect_mg2d, toeplitz_test_data

    integer, parameter :: nus(2, 3) = reshape([1, 1, 1, 0, 0, 1], [2, 3])

contains

    subroutine collect_mg2d(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('toeplitz_inverse_approximates_interior', test_toeplitz_inverse), &
            new_unittest('strip_kernel_and_product_vs_direct', test_strip_ops), &
            new_unittest('strip_kernel_blocks_vs_ic_kernel', test_strip_kernel_blocks), &
            new_unittest('toeplitz_inverse_even_in_workspace', test_toeplitz_inverse_even), &
            new_unittest('plain_fft_spectral_radius_table31', test_table31), &
            new_unittest('plain_fft_divergence_reported', test_fft_diverges), &
            new_unittest('smoother_radius_fft_vs_rsm', test_smoother_radius), &
            new_unittest('mg_fft_rsm_mp1_mp2_tables34_35', test_rsm_mp12), &
            new_unittest('mg_fft_rsm_mp3_table38', test_rsm_mp3), &
            new_unittest('fft_rsm_solver_tables37_39', test_rsm_solver), &
            new_unittest('mg_fft_sd_tables32_33', test_sd), &
            new_unittest('solution_satisfies_system', test_solution), &
            new_unittest('errors_reported', test_errors) ]
    end subroutine collect_mg2d

    character(len=56) function label(what, mp, n, nu1, nu2)
        character(len=*), intent(in) :: what
        integer, intent(in) :: mp, n, nu1, nu2
        write (label, '(a,a,i0,1x,i0,a,i0,a,i0,a)') what, ' MP', mp, n, ' V(', nu1, ',', nu2, ')'
    end function label

    !> Coefficients a(0:n−1) of a symmetric, diagonally dominant Toeplitz matrix and a vector
    !! x(1:n) for the product tests (here and in the parallel suite).
    pure subroutine toeplitz_test_data(a, x)
        real(dp), intent(out) :: a(0:), x(:)
        integer :: i, n
        n = size(x)
        do i = 0, size(a) - 1
            a(i) = 1/(1 + 0.3_dp*i) + merge(2.0_dp, 0.0_dp, i == 0)
        end do
        do i = 1, n
            x(i) = sin(0.37_dp*i) + 0.1_dp*i/n
        end do
    end subroutine toeplitz_test_data

    !> The strip operators of the fast path: coefficients by symmetry equal ic_kernel's to
    !! 1e−13 of the largest (same antiderivatives, other rounding) for A^xx, A^zz and A^yy on
    !! MP1 and MP2 grids; the in-place FFT product equals the direct O(n²) Toeplitz sum to
    !! 1e−13 relative (FFT rounding at n = 64 … 256), also for non-powers of two (96, odd
    !! 97) and the smallest sizes (1, 2, 3, 4, 5, 8, 16), in each transform layout.
    subroutine test_strip_ops(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(strip_fft) :: f
        real(dp), allocatable :: kern(:, :), a(:), sym(:), x(:), y(:), yd(:)
        integer :: mp, n, b, i, j, k, stat, radix
        character(len=32) :: what
        integer, parameter :: blocks(3) = [IC_XX, IC_ZZ, IC_YY]
        ! the half-spectrum pairs (k, n − k) of the product: n even (a middle pair), n odd,
        ! and the smallest sizes
        integer, parameter :: sizes(11) = [1, 2, 3, 4, 5, 8, 16, 64, 96, 97, 256]
        character(len=256) :: msg
        do mp = 1, 2
            do b = 1, 3
                call strip_model_problem(mp, 128, prob, stat, msg)
                call check(error, stat == 0, msg)
                call ic_kernel(blocks(b), prob%material, prob%grid, kern)
                allocate (a(0:127))
                call strip_kernel(blocks(b), prob%material, prob%grid, a)
                call check(error, maxval(abs(a - kern(0:127, 0)))/maxval(abs(kern)) < 1e-13_dp, &
                    trim(label('strip kernel = ic_kernel', mp, 128, b, 0)))
                call check(error, maxval(abs(kern(-127:-1, 0) - kern(127:1:-1, 0)))/maxval(abs(kern)) < 1e-13_dp, &
                    'A is symmetric')
                deallocate (a)
            end do
        end do
        do k = 1, size(sizes)
            n = sizes(k)
            allocate (a(0:n - 1), sym(0:n), x(n), y(n), yd(n))
            call toeplitz_test_data(a, x)
            do i = 1, n
                yd(i) = 0
                do j = 1, n
                    yd(i) = yd(i) + a(abs(i - j))*x(j)
                end do
            end do
            ! the n-point layout and the radix-2 and radix-4 ones (n/2- and n/4-point
            ! transforms, used from 2^18 and 2^20 cells) on the sizes divisible by 4 and 8
            do radix = 1, 4
                if (radix == 3 .or. mod(n, 2*radix) /= 0) cycle
                call f%init(n, radix=radix)
                write (what, '(a,i0,a,i0)') 'n = ', n, ', radix ', radix
                call check(error, f%radix == radix, 'layout not taken: '//trim(what))
                call f%symbol(a, sym)
                call f%product(sym, x, y)
                call check(error, maxval(abs(y - yd))/maxval(abs(yd)) < 1e-13_dp, 'FFT product = direct, '//trim(what))
                call f%destroy()
            end do
            deallocate (a, sym, x, y, yd)
        end do
    end subroutine test_strip_ops

    !> strip_kernel evaluates its antiderivatives in blocks of 4096 offsets, each block
    !! starting afresh: on 3·4096 + 5 cells (four blocks, the last partial) it equals
    !! ic_kernel to 1e−13 of the largest coefficient, as on one block above.
    subroutine test_strip_kernel_blocks(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        real(dp), allocatable :: kern(:, :), a(:)
        integer :: b, stat, n
        integer, parameter :: blocks(3) = [IC_XX, IC_ZZ, IC_YY]
        character(len=256) :: msg
        n = 3*4096 + 5
        call strip_model_problem(1, 128, prob, stat, msg)           ! MP1's material
        call make_grid(prob%grid, n, 1, -4.0_dp, 4.0_dp, -50.0_dp, 50.0_dp, stat, msg)
        call check(error, stat == 0, msg)
        allocate (a(0:n - 1))
        do b = 1, 3
            call ic_kernel(blocks(b), prob%material, prob%grid, kern)
            call strip_kernel(blocks(b), prob%material, prob%grid, a)
            call check(error, maxval(abs(a - kern(0:n - 1, 0)))/maxval(abs(kern)) < 1e-13_dp, &
                'strip kernel = ic_kernel over four blocks of offsets')
        end do
    end subroutine test_strip_kernel_blocks

    !> The even form of the Toeplitz inverse, computed in a shared workspace from a(0:n−1),
    !! equals the even part of strip_toeplitz_inverse exactly, on the real-transform path
    !! (n = 16: 31 points) and the complex one (n = 4096: 8191 is prime), also when the
    !! workspace is larger than needed and holds other data.
    subroutine test_toeplitz_inverse_even(error)
        type(error_type), allocatable, intent(out) :: error
        type(strip_workspace) :: ws
        real(dp), allocatable :: a(:), m(:), me(:)
        integer :: n, d, k
        integer, parameter :: sizes(2) = [16, 4096]
        call ws%reserve(strip_workspace_need(sizes))
        do k = 1, 2
            n = sizes(k)
            allocate (a(-(n - 1):n - 1), m(-(n - 1):n - 1), me(0:n - 1))
            do d = 0, n - 1
                a(d) = 1/(0.5_dp + d) + merge(1.0_dp, 0.0_dp, d == 0)
                a(-d) = a(d)
            end do
            call strip_toeplitz_inverse(n, a, m)
            ws%buf = 7
            call strip_toeplitz_inverse_even(n, a(0:n - 1), me, ws)
            call check(error, me(0) == m(0) .and. all(me(1:n - 1) == (m(1:n - 1) + m(-1:-(n - 1):-1))/2), &
                'even inverse in the workspace = even part of M, n = '//merge('  16', '4096', n == 16))
            deallocate (a, m, me)
        end do
    end subroutine test_toeplitz_inverse_even

    !> §3.3.1: M's coefficients approximate an interior column of A⁻¹ (16×1 MP1): the centre
    !! column of M equals that of the dense inverse to 5 % (relative, 2-norm); near the
    !! boundary the true inverse differs more (the boundary effect the RSM corrects); M has
    !! a positive peak and negative coefficients for offsets 1…n/2 (the last few, |d| ≈ n,
    !! carry the circulant's wrap-around and may be positive).
    subroutine test_toeplitz_inverse(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        real(dp), allocatable :: kern(:, :), m(:), a(:, :), ainv(:, :)
        integer :: stat, n, i, j
        character(len=200) :: msg
        real(dp) :: err_c, err_b, mincol(16), bcol(16)
        n = 16
        call strip_model_problem(1, n, prob, stat, msg)
        call ic_kernel(IC_XX, prob%material, prob%grid, kern)
        allocate (m(-(n - 1):n - 1), a(n, n))
        call strip_toeplitz_inverse(n, kern(:, 0), m)
        do j = 1, n
            do i = 1, n
                a(i, j) = kern(i - j, 0)
            end do
        end do
        ainv = invert(a)
        do i = 1, n
            mincol(i) = m(i - n/2); bcol(i) = m(i - 1)
        end do
        err_c = norm2(mincol - ainv(:, n/2))/norm2(ainv(:, n/2))
        err_b = norm2(bcol - ainv(:, 1))/norm2(ainv(:, 1))
        call check(error, err_c < 0.05_dp, 'centre column of M ≈ centre column of inv(A)')
        call check(error, err_b > err_c, 'boundary column approximated worse than the centre column')
        call check(error, m(0) > 0 .and. all(m(1:n/2) < 0), 'M pattern: positive peak, negative neighbours (Fig. 3.2)')
    contains
        function invert(b) result(x)
            real(dp), intent(in) :: b(:, :)
            real(dp) :: x(size(b, 1), size(b, 2)), w(size(b, 1), 2*size(b, 1)), f
            integer :: r, q, nn
            nn = size(b, 1)
            w = 0; w(:, 1:nn) = b
            do r = 1, nn
                w(r, nn + r) = 1
            end do
            do r = 1, nn            ! Gauss–Jordan without pivoting (SPD)
                w(r, :) = w(r, :)/w(r, r)
                do q = 1, nn
                    if (q == r) cycle
                    f = w(q, r); w(q, :) = w(q, :) - f*w(r, :)
                end do
            end do
            x = w(:, nn + 1:)
        end function invert
    end subroutine test_toeplitz_inverse

    !> Table 3.1: spectral radius of MG with the plain FFT smoother, MP1.
    !! Thesis 8…256: V(1,1) 1.80, 17.4, 249, 5.06e3, 1.41e5, 5.20e6; V(1,0) 0.22, 0.71, 2.60,
    !! 11.8, 61.9, 375.  We check 8…128 within 10 %, V(0,1) = V(1,0) (symmetry), and ρ > 1
    !! from 32×1 on for every cycle.
    subroutine test_table31(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        real(dp) :: rho, rho10
        real(dp), parameter :: v11(5) = [1.80_dp, 17.4_dp, 249.0_dp, 5.06e3_dp, 1.41e5_dp]
        real(dp), parameter :: v10(5) = [0.22_dp, 0.71_dp, 2.60_dp, 11.8_dp, 61.9_dp]
        integer :: stat, k, n
        character(len=200) :: msg
        set%smoother = 'fft'
        do k = 1, 5
            n = 2**(k + 2)
            call strip_model_problem(1, n, prob, stat, msg)
            set%nu1 = 1; set%nu2 = 1
            call mg2d_spectral_radius(prob, set, rho, stat, msg)
            call check(error, stat == 0, 'spectral radius: '//trim(msg))
            call check(error, rho, v11(k), trim(label('rho', 1, n, 1, 1)), rel=0.1_dp)
            set%nu1 = 1; set%nu2 = 0
            call mg2d_spectral_radius(prob, set, rho10, stat, msg)
            call check(error, rho10, v10(k), trim(label('rho', 1, n, 1, 0)), rel=0.1_dp)
            set%nu1 = 0; set%nu2 = 1
            call mg2d_spectral_radius(prob, set, rho, stat, msg)
            call check(error, rho, rho10, 'rho V(0,1) = rho V(1,0)', rel=1e-6_dp)
            if (n >= 32) call check(error, rho10 > 1, trim(label('divergent', 1, n, 1, 0)))
        end do
    end subroutine test_table31

    !> The plain FFT smoother in MG diverges on MP1 from 32×1 on: the solver reports
    !! FC_DIVERGED with a message and hands back no iterate (p = 0), never "converged".
    subroutine test_fft_diverges(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        integer :: stat, c
        character(len=200) :: msg
        call strip_model_problem(1, 1024, prob, stat, msg)
        set%smoother = 'fft'
        do c = 1, 3
            set%nu1 = nus(1, c); set%nu2 = nus(2, c)
            call solve_strip_mg(prob, set, res, stat, msg)
            call check(error, stat == 0, 'runs: '//trim(msg))
            call check(error, res%status == FC_DIVERGED, trim(label('plain FFT diverged', 1, 1024, nus(1, c), nus(2, c))))
            call check(error, index(res%message, 'diverged') > 0, 'message: '//trim(res%message))
            call check(error, all(res%p == 0), 'no diverged iterate returned')
        end do
    end subroutine test_fft_diverges

    !> Figs. 3.4 / 3.11 (32×1 MP1): the FFT smoother's iteration matrix I − MA has spectral
    !! radius > 1 (two problematic eigenvalues); with the row-sum modification I − M̄A all
    !! eigenvalues lie below 1.
    subroutine test_smoother_radius(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        real(dp) :: rho_f, rho_r
        integer :: stat
        character(len=200) :: msg
        call strip_model_problem(1, 32, prob, stat, msg)
        call strip_smoother_radius(prob, 'fft', rho_f, stat, msg)
        call check(error, stat == 0, msg)
        call strip_smoother_radius(prob, 'fft-rsm', rho_r, stat, msg)
        call check(error, stat == 0, msg)
        call check(error, rho_f > 1, 'FFT smoother: spectral radius > 1')
        call check(error, rho_r < 1, 'FFT+RSM smoother: spectral radius < 1')
    end subroutine test_smoother_radius

    !> Tables 3.4 (MP1) and 3.5 (MP2), MG with FFT+RSM, tol 1e−8 from a random start.
    !! The thesis tabulates 2^16 … 2^20 only.  On its first two columns (MP1 2^16: 3 (0.002),
    !! 6 (0.039), 5 (0.023); 2^17: 3 (0.002), 5 (0.024), 5 (0.018); MP2 2^16: 4 (0.004),
    !! 7 (0.049), 7 (0.043); 2^17: 4 (0.004), 7 (0.044), 6 (0.029)) we require the cycles within
    !! ±1 and the convergence factors within ±0.005 (we measure them equal to 3 digits).
    !! Below the table (2^14) the cycles must stay within ±1 of the 2^16 column; at 2^10 and
    !! 2^12 the counts must not increase with n (the thesis' counts fall slowly with n, and ours
    !! continue that trend: MP1 V(1,0) 8, 7, 7 at 2^10, 2^12, 2^14 before the thesis' 6 at 2^16).
    subroutine test_rsm_mp12(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: its1(3, 2) = reshape([3, 6, 5, 3, 5, 5], [3, 2])
        real(dp), parameter :: q1(3, 2) = reshape([0.002_dp, 0.039_dp, 0.023_dp, 0.002_dp, 0.024_dp, 0.018_dp], [3, 2])
        integer, parameter :: its2(3, 2) = reshape([4, 7, 7, 4, 7, 6], [3, 2])
        real(dp), parameter :: q2(3, 2) = reshape([0.004_dp, 0.049_dp, 0.043_dp, 0.004_dp, 0.044_dp, 0.029_dp], [3, 2])
        call rsm_table(error, 1, its1, q1)
        call rsm_table(error, 2, its2, q2)
    end subroutine test_rsm_mp12

    !> Table 3.8 (MP3, two contact strips, eq. 3.21): 2^16 column 4 (0.005), 6 (0.041),
    !! 6 (0.035); 2^17 column 3 (0.002), 6 (0.037), 5 (0.022); same bands as for MP1/MP2.
    subroutine test_rsm_mp3(error)
        type(error_type), allocatable, intent(out) :: error
        call rsm_table(error, 3, reshape([4, 6, 6, 3, 6, 5], [3, 2]), &
            reshape([0.005_dp, 0.041_dp, 0.035_dp, 0.002_dp, 0.037_dp, 0.022_dp], [3, 2]))
    end subroutine test_rsm_mp3

    !> Runs V(1,1), V(1,0), V(0,1) on 2^10, 2^12, 2^14, 2^16, 2^17; `its(:, 1)`, `q(:, 1)` are
    !! the thesis' 2^16 column, `its(:, 2)`, `q(:, 2)` its 2^17 column.
    subroutine rsm_table(error, mp, its, q)
        type(error_type), allocatable, intent(inout) :: error
        integer, intent(in) :: mp, its(3, 2)
        real(dp), intent(in) :: q(3, 2)
        integer, parameter :: powers(5) = [10, 12, 14, 16, 17]
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        integer :: stat, k, c, n, col, previous(3)
        character(len=200) :: msg
        previous = huge(1)
        do k = 1, size(powers)
            n = 2**powers(k)
            call strip_model_problem(mp, n, prob, stat, msg)
            do c = 1, 3
                set%nu1 = nus(1, c); set%nu2 = nus(2, c)
                call solve_strip_mg(prob, set, res, stat, msg)
                call check(error, stat == 0 .and. res%status == FC_CONVERGED, trim(label('converged', mp, n, nus(1, c), &
                    nus(2, c)))//' '//trim(res%message))
                call check(error, res%residual <= set%tol, 'residual <= tol')
                select case (powers(k))
                case (16, 17)
                    col = powers(k) - 15
                    call check(error, abs(res%iterations - its(c, col)) <= 1, trim(label('cycles ±1', mp, n, nus(1, c), &
                        nus(2, c))))
                    call check(error, res%factor, q(c, col), trim(label('factor', mp, n, nus(1, c), nus(2, c))), abs=0.005_dp)
                case (14)
                    call check(error, abs(res%iterations - its(c, 1)) <= 1, trim(label('cycles ±1 of 2^16', mp, n, &
                        nus(1, c), nus(2, c))))
                case default
                    call check(error, res%iterations <= previous(c), trim(label('cycles non-increasing', mp, n, &
                        nus(1, c), nus(2, c))))
                end select
                previous(c) = res%iterations
            end do
        end do
    end subroutine rsm_table

    !> Tables 3.7 / 3.9: FFT+RSM as a one-grid solver, 2^16: MP1 28 (0.511), MP2 34 (0.537),
    !! MP3 36 (0.598).  Band: ±2 iterations, factor ±0.03; at 2^12 within ±3 (stable in n).
    subroutine test_rsm_solver(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        integer, parameter :: its(3) = [28, 34, 36]
        real(dp), parameter :: q(3) = [0.511_dp, 0.537_dp, 0.598_dp]
        integer :: stat, mp, k, n
        character(len=200) :: msg
        do mp = 1, 3
            do k = 12, 16, 4
                n = 2**k
                call strip_model_problem(mp, n, prob, stat, msg)
                call solve_strip_fft_rsm(prob, set, res, stat, msg)
                call check(error, res%status == FC_CONVERGED, trim(label('FFT+RSM solver', mp, n, 0, 0))//' converged')
                if (k == 16) then
                    call check(error, abs(res%iterations - its(mp)) <= 2, trim(label('solver its ±2', mp, n, 0, 0)))
                    call check(error, res%factor, q(mp), trim(label('solver factor', mp, n, 0, 0)), abs=0.03_dp)
                else
                    call check(error, abs(res%iterations - its(mp)) <= 3, trim(label('solver its ±3', mp, n, 0, 0)))
                end if
                call check(error, res%levels == 1, 'one grid')
            end do
        end do
    end subroutine test_rsm_solver

    !> Tables 3.2 / 3.3, MG with FFT+SD at 2^14 (thesis 2^16: MP1 V(1,0) 6, V(0,1) 5; MP2 11,
    !! 10): within ±2.  The thesis notes V(1,1) with SD does not converge: ours must not be
    !! returned as converged within 30 cycles.
    subroutine test_sd(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        integer, parameter :: its(2, 2) = reshape([6, 5, 11, 10], [2, 2])
        integer :: stat, mp, c, n
        character(len=200) :: msg
        n = 2**14
        set%smoother = 'fft-sd'
        do mp = 1, 2
            call strip_model_problem(mp, n, prob, stat, msg)
            do c = 2, 3
                set%nu1 = nus(1, c); set%nu2 = nus(2, c)
                call solve_strip_mg(prob, set, res, stat, msg)
                call check(error, res%status == FC_CONVERGED, trim(label('SD converged', mp, n, nus(1, c), nus(2, c))))
                call check(error, abs(res%iterations - its(c - 1, mp)) <= 2, trim(label('SD cycles', mp, n, nus(1, c), &
                    nus(2, c))))
            end do
            set%nu1 = 1; set%nu2 = 1; set%maxit = 30
            call solve_strip_mg(prob, set, res, stat, msg)
            call check(error, res%status /= FC_CONVERGED, trim(label('SD V(1,1) fails', mp, n, 1, 1))//': '//trim(res%message))
            set%maxit = 100
        end do
    end subroutine test_sd

    !> The converged tractions satisfy A_r p = u independently of the solver's own defect:
    !! recompute with the direct O(n²) product (MP3, 1024×1), zero off the strips, and MG and
    !! the one-grid solver agree to 1e−6 (relative).
    subroutine test_solution(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: r1, r2
        type(fc_bttb) :: op
        real(dp), allocatable :: u(:, :)
        integer :: stat, n
        character(len=200) :: msg
        n = 1024
        call strip_model_problem(3, n, prob, stat, msg)
        call solve_strip_mg(prob, set, r1, stat, msg)
        call solve_strip_fft_rsm(prob, set, r2, stat, msg)
        call check(error, r1%status == FC_CONVERGED .and. r2%status == FC_CONVERGED, 'both converged')
        call build_bttb(op, IC_XX, prob%material, prob%grid)
        allocate (u(n, 1))
        call op%apply_direct(reshape(r1%p, [n, 1]), u)
        call check(error, norm2(pack(u(:, 1) - prob%rhs, prob%contact))/norm2(prob%rhs), 0.0_dp, 'A_r p = u (direct)', &
            abs=2e-8_dp)
        call check(error, all(pack(r1%p, .not. prob%contact) == 0), 'p = 0 off the strips')
        call check(error, rel_diff(r1%p, r2%p), 0.0_dp, 'MG = one-grid solver', abs=1e-6_dp)
        call op%destroy()
    end subroutine test_solution

    !> Invalid input: stat ≠ 0 with a message.
    subroutine test_errors(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        integer :: stat
        character(len=200) :: msg
        call strip_model_problem(4, 64, prob, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'model problem') > 0, 'MP4: '//trim(msg))
        call strip_model_problem(1, 100, prob, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'power of 2') > 0, 'n = 100: '//trim(msg))
        call strip_model_problem(1, -huge(1) - 1, prob, stat, msg)   ! no overflow in the power-of-2 test
        call check(error, stat /= 0 .and. index(msg, 'power of 2') > 0, 'n = -2^31: '//trim(msg))
        call strip_model_problem(1, 64, prob, stat, msg)
        set%smoother = 'jacobi'
        call solve_strip_mg(prob, set, res, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'jacobi') > 0, 'smoother: '//trim(msg))
        set%smoother = 'fft-rsm'; set%nu1 = 0; set%nu2 = 0
        call solve_strip_mg(prob, set, res, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'cycle') > 0, 'V(0,0): '//trim(msg))
        set%nu1 = 1; set%nu2 = 1
        call strip_model_problem(1, 64, prob, stat, msg)
        deallocate (prob%rhs, prob%contact)
        prob%grid%nx = 5001; prob%grid%dx = 8.0_dp/5001
        allocate (prob%rhs(5001), prob%contact(5001))
        prob%rhs = 1; prob%contact = .true.
        call solve_strip_mg(prob, set, res, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'coarsens') > 0, 'n = 5001 refused: '//trim(msg))
        prob%contact = .false.
        call solve_strip_mg(prob, set, res, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'contact') > 0, 'no contact: '//trim(msg))
    end subroutine test_errors

end module test_mg2d
