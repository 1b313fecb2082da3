!> Suite `operators`: LAPACK error reporting (fc_lapack) and the lifetime of the FFT
!! operators (fc_influence, fc_norm, fc_tangcg): copies, destruction, shared transforms.
module test_operators
    use fc_kinds, only: dp
    use fc_lapack, only: solve_spd, eigenvalues_general
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence
    use fc_norm, only: fc_normal_operator, build_normal_operator
    use fc_tangcg, only: fc_tangential_operator, build_tangential_operator, coupling_displacements
    use fc_tangcg_operator, only: apply_block_inverse
    use fc_fftw, only: circulant_size, friendly_size
    use fc_kinds, only: pi
    use fc_testing
    implicit none
    private
    public :: collect_operators

contains

    subroutine collect_operators(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('lapack_spd_solve', test_spd_solve), &
            new_unittest('lapack_not_spd_reported', test_not_spd), &
            new_unittest('lapack_eigenvalues', test_eigenvalues), &
            new_unittest('copy_survives_original', test_copy_survives_original), &
            new_unittest('blocks_share_one_plan_set', test_shared_plans), &
            new_unittest('operator_takes_coefficients', test_taking_kernel), &
            new_unittest('real_symbols_even_odd', test_real_symbols), &
            new_unittest('kernel_exact_reflections', test_kernel_reflections), &
            new_unittest('strang_circulant_wraps_kernel', test_strang_circulant), &
            new_unittest('strang_circulant_of_symbol', test_strang_of_symbol), &
            new_unittest('circulant_sizes_fftw_friendly', test_circulant_sizes), &
            new_unittest('products_on_slow_fft_sizes', test_products_slow_sizes), &
            new_unittest('toeplitz_inverse_defined_on_doubled_grid', test_inverse_doubled_grid), &
            new_unittest('block_inverse_defined_on_doubled_grid', test_block_inverse_doubled_grid), &
            new_unittest('final_binding_releases_plans', test_final_binding), &
            new_unittest('large_products_chunked_y_passes', test_chunked_y) ]
    end subroutine collect_operators

    !> A 3×3 SPD system with a known solution.
    subroutine test_spd_solve(error)
        type(error_type), allocatable, intent(out) :: error
        real(dp) :: a(3, 3), b(3, 1), x(3)
        integer :: stat
        character(len=200) :: msg
        a = reshape([4.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 3.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 2.0_dp], [3, 3])
        x = [1.0_dp, -2.0_dp, 3.0_dp]
        b(:, 1) = matmul(a, x)
        call solve_spd(a, b, stat, msg)
        call check(error, stat == 0, 'solve_spd stat = 0: '//trim(msg))
        call check(error, maxval(abs(b(:, 1) - x)), 0.0_dp, 'solution', abs=1e-14_dp)
    end subroutine test_spd_solve

    !> An indefinite matrix: dposv's info > 0 comes back as stat ≠ 0 naming the minor.
    subroutine test_not_spd(error)
        type(error_type), allocatable, intent(out) :: error
        real(dp) :: a(2, 2), b(2, 1)
        integer :: stat
        character(len=200) :: msg
        a = reshape([1.0_dp, 2.0_dp, 2.0_dp, 1.0_dp], [2, 2])   ! eigenvalues 3 and −1
        b = 1
        call solve_spd(a, b, stat, msg)
        call check(error, stat /= 0, 'indefinite matrix must fail')
        call check(error, index(msg, 'not positive definite') > 0 .and. index(msg, 'order 2') > 0, &
            'message names the failing minor: '//trim(msg))
        a = 1; b = 1
        call solve_spd(a(:, 1:1), b, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'do not match') > 0, 'shape mismatch: '//trim(msg))
    end subroutine test_not_spd

    !> Eigenvalues of a rotation-scaling matrix: 2 ± 3i, and a diagonal entry 5.
    subroutine test_eigenvalues(error)
        type(error_type), allocatable, intent(out) :: error
        real(dp) :: a(3, 3)
        real(dp), allocatable :: wr(:), wi(:)
        integer :: stat
        character(len=200) :: msg
        a = reshape([2.0_dp, -3.0_dp, 0.0_dp, 3.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 5.0_dp], [3, 3])
        call eigenvalues_general(a, wr, wi, stat, msg)
        call check(error, stat == 0, 'dgeev stat = 0: '//trim(msg))
        call check(error, maxval(wr), 5.0_dp, 'largest real part', abs=1e-13_dp)
        call check(error, maxval(wi), 3.0_dp, 'largest imaginary part', abs=1e-13_dp)
        call check(error, minval(wi), -3.0_dp, 'smallest imaginary part', abs=1e-13_dp)
    end subroutine test_eigenvalues

    subroutine dissimilar(mat)
        type(fc_material), intent(out) :: mat
        integer :: stat
        character(len=200) :: msg
        mat%g1 = 200; mat%g2 = 1000; mat%nu1 = 0.42_dp; mat%nu2 = 0.3_dp   ! K ≠ 0: coupling blocks
        call combine_material(mat, stat, msg)
    end subroutine dissimilar

    !> The dissimilar material (K ≠ 0), an nx×ny grid on [−1, 1]×[−1, 0.5] and a smooth
    !! field on it, for the product checks.
    subroutine grid_and_field(nx, ny, mat, grid, x)
        integer, intent(in) :: nx, ny
        type(fc_material), intent(out) :: mat
        type(fc_grid), intent(out) :: grid
        real(dp), allocatable, intent(out) :: x(:, :)
        integer :: stat, i, j
        character(len=200) :: msg
        call dissimilar(mat)
        call make_grid(grid, nx, ny, -1.0_dp, 1.0_dp, -1.0_dp, 0.5_dp, stat, msg)
        allocate (x(nx, ny))
        do j = 1, ny
            do i = 1, nx
                x(i, j) = sin(0.7_dp*i) + cos(1.3_dp*j) + 0.1_dp*i*j
            end do
        end do
    end subroutine grid_and_field

    !> Copy the normal and the tangential operator, destroy the originals, use the copies:
    !! FFT products of the copies equal the direct sums (own plans, valid buffers).
    subroutine test_copy_survives_original(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop, ncopy
        type(fc_tangential_operator) :: top, tcopy
        type(fc_bttb) :: blk
        real(dp), allocatable :: x(:, :), y(:, :), yf(:, :), yd(:, :), ux(:, :), uy(:, :), uz(:, :), t(:, :)
        integer :: stat
        character(len=200) :: msg
        call dissimilar(mat)
        call make_grid(grid, 12, 9, -1.0_dp, 1.0_dp, -0.8_dp, 0.7_dp, stat, msg)
        allocate (x(12, 9), y(12, 9), yf(12, 9), yd(12, 9), ux(12, 9), uy(12, 9), uz(12, 9), t(12, 9))
        call random_number(x); call random_number(y)
        call build_normal_operator(nop, mat, grid)
        call build_tangential_operator(top, mat, grid)
        ncopy = nop
        tcopy = top
        call check(error, .not. ncopy%a_zz%shares_plans(nop%a_zz), 'the copy has its own plans')
        call nop%destroy(); call top%destroy()
        call ncopy%a_zz%apply(x, yf); call ncopy%a_zz%apply_direct(x, yd)
        call check(error, rel_diff(pack(yf, .true.), pack(yd, .true.)), 0.0_dp, 'copied A^zz', abs=1e-12_dp)
        ! the operator's preconditioner keeps no coefficients: the oracle is one built with them
        call build_inverse_toeplitz(IC_ZZ, mat, grid, blk)
        call ncopy%precond%apply(x, yf); call blk%apply_direct(x, yd)
        call check(error, rel_diff(pack(yf, .true.), pack(yd, .true.)), 0.0_dp, 'copied preconditioner', abs=1e-12_dp)
        call check(error, .not. allocated(ncopy%precond%kernel), 'preconditioner coefficients not kept')
        call tcopy%apply(x, y, ux, uy)
        call tcopy%a_xx%apply_direct(x, yd); call tcopy%a_xy%apply_direct(y, t)
        call check(error, rel_diff(pack(ux, .true.), pack(yd + t, .true.)), 0.0_dp, 'copied tangential ux', abs=1e-12_dp)
        call tcopy%a_xy%apply_direct(x, yd); call tcopy%a_yy%apply_direct(y, t)
        call check(error, rel_diff(pack(uy, .true.), pack(yd + t, .true.)), 0.0_dp, 'copied tangential uy', abs=1e-12_dp)
        call coupling_displacements(tcopy, x, x, y, ux, uy, uz)
        call tcopy%a_xz%apply_direct(x, yd)
        call check(error, rel_diff(pack(ux, .true.), pack(yd, .true.)), 0.0_dp, 'copied coupling A^xz', abs=1e-12_dp)
        ! self-assignment keeps the operator
        blk = ncopy%a_zz
        blk = blk
        call blk%apply(x, yf); call ncopy%a_zz%apply_direct(x, yd)
        call check(error, rel_diff(pack(yf, .true.), pack(yd, .true.)), 0.0_dp, 'after a = a', abs=1e-12_dp)
        call ncopy%destroy(); call tcopy%destroy()
    end subroutine test_copy_survives_original

    !> One plan set per grid: A^zz and its preconditioner, and all seven tangential blocks.
    subroutine test_shared_plans(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_tangential_operator) :: top
        integer :: stat
        character(len=200) :: msg
        call dissimilar(mat)
        call make_grid(grid, 10, 8, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, stat, msg)
        call build_normal_operator(nop, mat, grid)
        call check(error, nop%precond%shares_plans(nop%a_zz), 'preconditioner shares A^zz plans')
        call build_tangential_operator(top, mat, grid)
        call check(error, top%a_xy%shares_plans(top%a_xx) .and. top%a_yy%shares_plans(top%a_xx) .and. &
            top%a_xz%shares_plans(top%a_xx) .and. top%a_yz%shares_plans(top%a_xx) .and. &
            top%a_zx%shares_plans(top%a_xx) .and. top%a_zy%shares_plans(top%a_xx), 'seven blocks, one plan set')
        call check(error, top%a_xx%fft%refs == 7, 'plan set used by 7 blocks')
        call top%a_xx%destroy()   ! the others keep the set alive
        call check(error, top%a_xy%fft%refs == 6, 'set survives its first owner')
        call nop%destroy(); call top%destroy()
    end subroutine test_shared_plans

    !> An operator built by taking the caller's coefficients for offsets −n…n (no copy)
    !! equals one built from a copy of the offsets −(n−1)…n−1: the same symbol bit for bit,
    !! the same coefficients, products equal to the direct sums; the caller's array is gone.
    subroutine test_taking_kernel(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: copied, taken
        real(dp), allocatable :: kext(:, :), x(:, :), yf(:, :), yd(:, :)
        integer :: stat, b, nx, ny
        character(len=200) :: msg, label
        call dissimilar(mat)
        nx = 9; ny = 7
        call make_grid(grid, nx, ny, -1.0_dp, 1.0_dp, -1.0_dp, 0.5_dp, stat, msg)
        allocate (x(nx, ny), yf(nx, ny), yd(nx, ny))
        call random_number(x)
        do b = IC_ZZ, IC_XZ
            write (label, '(a,i0)') 'block ', b
            call ic_kernel_extended(b, mat, grid, nx, ny, kext)
            call build_bttb_from_kernel(copied, kext(-(nx - 1):nx - 1, -(ny - 1):ny - 1), nx, ny)
            call build_bttb_taking_kernel(taken, kext, nx, ny, plans_from=copied)
            call check(error, .not. allocated(kext), trim(label)//': the caller''s array is taken')
            call check(error, all(lbound(taken%kernel) == [-nx, -ny]), trim(label)//': kept with its own bounds')
            call check(error, all(taken%kernel(-(nx - 1):nx - 1, -(ny - 1):ny - 1) == copied%kernel), &
                trim(label)//': the same coefficients')
            call check(error, taken%parity == copied%parity .and. all(taken%rsymbol == copied%rsymbol), &
                trim(label)//': the same symbol')
            call taken%apply(x, yf); call taken%apply_direct(x, yd)
            call check(error, maxval(abs(yf - yd)) <= 1e-12_dp*maxval(abs(yd)), trim(label)//': product = direct sums')
            call taken%destroy(); call copied%destroy()
        end do
    end subroutine test_taking_kernel

    !> Even blocks store a real symbol, odd (coupling) blocks their imaginary part; the
    !! products still match the direct sums (checked for all blocks in suite influence).
    subroutine test_real_symbols(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op
        complex(dp), allocatable :: sym(:, :)
        integer :: stat, b
        character(len=200) :: msg, label
        call dissimilar(mat)
        call make_grid(grid, 9, 7, -1.0_dp, 1.0_dp, -1.0_dp, 0.5_dp, stat, msg)
        do b = IC_ZZ, IC_ZY
            call build_bttb(op, b, mat, grid)
            write (label, '(a,i0)') 'block ', b
            call check(error, allocated(op%rsymbol) .and. .not. allocated(op%csymbol), trim(label)//' real storage')
            if (b <= IC_XY) then
                call check(error, op%parity == SYMBOL_EVEN, trim(label)//' even')
            else
                call check(error, op%parity == SYMBOL_ODD, trim(label)//' odd')
            end if
            call check(error, size(op%rsymbol) == (op%mx/2 + 1)*op%my, trim(label)//' half spectrum')
        end do
        call build_inverse_toeplitz(IC_ZZ, mat, grid, op)
        call check(error, op%parity == SYMBOL_EVEN, 'Toeplitz inverse even')
        call fft_symbol_of_kernel(op, sym)
        call check(error, maxval(abs(aimag(sym))) == 0, 'inverse symbol real')
        call op%destroy()
    end subroutine test_real_symbols

    !> Strang's circulant on even and odd grid sizes (8×7): the wrapped coefficients are the
    !! kernel's for |offset| < n/2 and the mean of ±n/2 on the shared slot; an even block stays
    !! even (real symbol), A^xy (odd in x and in y) stays even, A^xz (odd in x only) odd with the
    !! Nyquist column zero; the FFT product equals the direct periodic sum.
    subroutine test_strang_circulant(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: circ
        real(dp), allocatable :: k(:, :), x(:, :), y(:, :), yd(:, :)
        integer, parameter :: blocks(3) = [IC_ZZ, IC_XY, IC_XZ], parity(3) = [SYMBOL_EVEN, SYMBOL_EVEN, SYMBOL_ODD]
        integer :: b, nx, ny
        character(len=200) :: label
        nx = 8; ny = 7
        call grid_and_field(nx, ny, mat, grid, x)
        allocate (y(nx, ny), yd(nx, ny))
        do b = 1, 3
            write (label, '(a,i0)') 'block ', blocks(b)
            call ic_kernel(blocks(b), mat, grid, k)
            call strang_circulant(k, nx, ny, circ)
            call check(error, circ%periodic .and. circ%parity == parity(b), trim(label)//' periodic, parity kept')
            call check(error, circ%kernel(1, 2), k(1, 2), trim(label)//' slot (1, 2) = offset (1, 2)', rel=1e-15_dp)
            call check(error, circ%kernel(6, 5), k(-2, -2), trim(label)//' slot (6, 5) = offset (-2, -2)', rel=1e-15_dp)
            call check(error, circ%kernel(4, 3), 0.5_dp*(k(4, 3) + k(-4, 3)), trim(label)//' Nyquist slot: mean of +-n/2', &
                abs=1e-15_dp*maxval(abs(k)))
            call circ%apply(x, y)
            call circ%apply_direct(x, yd)
            call check(error, maxval(abs(y - yd)) <= 1e-13_dp*maxval(abs(yd)), trim(label)//' FFT product = direct sum')
            if (allocated(error)) return
        end do
        call check(error, all(circ%kernel(4, :) == 0), 'odd block: Nyquist column zero')
    end subroutine test_strang_circulant

    !> Strang's circulant made from an operator's symbol on the doubled grid equals the one
    !! made from its coefficients (A^zz and its Toeplitz inverse, 9×8: odd and even n), to
    !! rounding, and is exactly even.
    subroutine test_strang_of_symbol(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op, prec, c1, c2
        integer :: stat, i, j, nx, ny
        character(len=200) :: msg
        logical :: even
        call dissimilar(mat)
        nx = 9; ny = 8
        call make_grid(grid, nx, ny, -1.0_dp, 1.0_dp, -1.0_dp, 0.5_dp, stat, msg)
        call build_bttb(op, IC_ZZ, mat, grid)
        call strang_circulant_of_symbol(op, op%rsymbol, c1)
        call strang_circulant(op%kernel, nx, ny, c2)
        call check(error, maxval(abs(c1%kernel - c2%kernel)) <= 1e-14_dp*maxval(abs(c2%kernel)), 'A^zz: both routes agree')
        call build_inverse_toeplitz(IC_ZZ, mat, grid, prec, plans_from=op)
        call strang_circulant_of_symbol(op, prec%rsymbol, c1)
        call strang_circulant(prec%kernel, nx, ny, c2)
        call check(error, maxval(abs(c1%kernel - c2%kernel)) <= 1e-13_dp*maxval(abs(c2%kernel)), 'M: both routes agree')
        even = .true.
        do j = 0, ny - 1
            do i = 0, nx - 1
                even = even .and. c1%kernel(i, j) == c1%kernel(modulo(-i, nx), modulo(-j, ny))
            end do
        end do
        call check(error, even .and. c1%parity == SYMBOL_EVEN, 'exactly even')
    end subroutine test_strang_of_symbol

    !> The circulant sizes of the products: 2n when FFTW transforms it fast (2^a 3^b 5^c 7^d
    !! 11^e 13^f, e + f ≤ 1), else the next such even size; the Strang circulants' period:
    !! n or the next such size.  Checked against a plain factorisation for n = 1…700.
    subroutine test_circulant_sizes(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, m
        logical :: ok
        call check(error, circulant_size(240) == 480 .and. circulant_size(200) == 400, '240, 200: doubled')
        call check(error, circulant_size(241) == 486 .and. circulant_size(199) == 400, '241 -> 486, 199 -> 400')
        call check(error, circulant_size(1) == 1 .and. circulant_size(13) == 26 .and. circulant_size(17) == 36, &
            '1 -> 1, 13 -> 26, 17 -> 36')
        call check(error, friendly_size(241) == 243 .and. friendly_size(240) == 240 .and. friendly_size(17) == 18, &
            'friendly 241 -> 243, 240, 17 -> 18')
        if (allocated(error)) return
        ok = .true.
        do n = 2, 700
            m = circulant_size(n)
            ok = ok .and. mod(m, 2) == 0 .and. m >= 2*n .and. good(m)
            do m = 2*n, circulant_size(n) - 2, 2
                ok = ok .and. .not. good(m)
            end do
            ok = ok .and. friendly_size(n) >= n .and. good(friendly_size(n))
            do m = n, friendly_size(n) - 1
                ok = ok .and. .not. good(m)
            end do
        end do
        call check(error, ok, 'n = 2..700: smallest good size at or above the bound')
    contains
        logical function good(m)
            integer, intent(in) :: m
            integer :: r, p, e11, e13
            integer, parameter :: primes(4) = [2, 3, 5, 7]
            r = m
            do p = 1, 4
                do while (mod(r, primes(p)) == 0)
                    r = r/primes(p)
                end do
            end do
            e11 = 0; e13 = 0
            do while (mod(r, 11) == 0)
                r = r/11; e11 = e11 + 1
            end do
            do while (mod(r, 13) == 0)
                r = r/13; e13 = e13 + 1
            end do
            good = r == 1 .and. e11 + e13 <= 1
        end function good
    end subroutine test_circulant_sizes

    !> On a 17×19 grid (2n = 34 = 2·17, 38 = 2·19: slow transforms) the products run on a
    !! 36×40 circulant and still equal the direct sums (even, odd-in-both and odd-in-x
    !! blocks, and the normal Toeplitz inverse); the Strang circulants get an 18×20 period,
    !! hold the kernel's coefficients and their product equals the direct periodic sum.
    subroutine test_products_slow_sizes(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op, prec, circ
        real(dp), allocatable :: x(:, :), y(:, :), yd(:, :), k(:, :)
        integer, parameter :: blocks(3) = [IC_ZZ, IC_XY, IC_XZ]
        integer :: b, nx, ny
        character(len=200) :: label
        nx = 17; ny = 19
        call grid_and_field(nx, ny, mat, grid, x)
        allocate (y(nx, ny), yd(nx, ny))
        do b = 1, 3
            write (label, '(a,i0)') 'block ', blocks(b)
            call build_bttb(op, blocks(b), mat, grid)
            call check(error, op%mx == 36 .and. op%my == 40, trim(label)//': circulant 36 x 40')
            call op%apply(x, y)
            call op%apply_direct(x, yd)
            call check(error, maxval(abs(y - yd)) <= 1e-13_dp*maxval(abs(yd)), trim(label)//': FFT product = direct sum')
            call ic_kernel(blocks(b), mat, grid, k)
            call strang_circulant(k, nx, ny, circ)
            call check(error, circ%mx == 18 .and. circ%my == 20 .and. circ%nx == nx .and. circ%ny == ny, &
                trim(label)//': Strang period 18 x 20 on the 17 x 19 grid')
            call check(error, circ%kernel(8, 3), k(8, 3), trim(label)//': slot (8, 3) = offset (8, 3)', rel=1e-15_dp)
            call check(error, circ%kernel(12, 15), k(-6, -5), trim(label)//': slot (12, 15) = offset (-6, -5)', rel=1e-15_dp)
            call circ%apply(x, y)
            call circ%apply_direct(x, yd)
            call check(error, maxval(abs(y - yd)) <= 1e-13_dp*maxval(abs(yd)), trim(label)//': circulant product = direct sum')
            if (allocated(error)) return
        end do
        call build_inverse_toeplitz(IC_ZZ, mat, grid, prec)
        call prec%apply(x, y)
        call prec%apply_direct(x, yd)
        call check(error, maxval(abs(y - yd)) <= 1e-13_dp*maxval(abs(yd)), 'Toeplitz inverse: FFT product = direct sum')
    end subroutine test_products_slow_sizes

    !> BCCG's preconditioner on a grid whose doubled size FFTW transforms slowly (17×19) is
    !! still the one of the 2nx×2ny circulant (thesis §3.3.1): its coefficients equal those
    !! computed here by direct (O(N²)) discrete Fourier sums of that circulant, although its
    !! products run on 36×40.
    subroutine test_inverse_doubled_grid(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: prec
        real(dp), allocatable :: kext(:, :), c(:, :), lam(:, :), m(:, :)
        integer :: stat, nx, ny
        character(len=200) :: msg
        call dissimilar(mat)
        nx = 17; ny = 19
        call make_grid(grid, nx, ny, -1.0_dp, 1.0_dp, -1.0_dp, 0.5_dp, stat, msg)
        call build_inverse_toeplitz(IC_ZZ, mat, grid, prec)
        call check(error, prec%mx == 36 .and. prec%my == 40, 'products on 36 x 40')
        call ic_kernel_extended(IC_ZZ, mat, grid, nx, ny, kext)
        call doubled_circulant(kext, nx, ny, .false., c)
        lam = direct_even_symbol(c)
        lam = 1/max(lam, 1.0e-8_dp*maxval(lam))
        m = central_coefficients(lam, nx, ny)
        call check(error, maxval(abs(prec%kernel - m)) <= 1e-12_dp*maxval(abs(m)), &
            'coefficients = the 34 x 38 circulant inverse''s (direct sums)')
    end subroutine test_inverse_doubled_grid

    !> TangCG's block preconditioner is the block Toeplitz operator of the central
    !! coefficients of the inverse of the 2nx×2ny block circulant (the definition in
    !! fc_tangprec): equal to that operator computed here by direct Fourier sums, the 2×2
    !! inversion per frequency and a direct product.  On 16×12 its symbols are made on the
    !! blocks' own plans (products on the 32×24 circulant); on 17×19 the products run on a
    !! 36×40 circulant, and the 34×38 symbols are made on plans of their own and moved there.
    subroutine test_block_inverse_doubled_grid(error)
        type(error_type), allocatable, intent(out) :: error
        call block_inverse_case(error, 16, 12, shared=.true.)
        if (allocated(error)) return
        call block_inverse_case(error, 17, 19, shared=.false.)
    end subroutine test_block_inverse_doubled_grid

    subroutine block_inverse_case(error, nx, ny, shared)
        type(error_type), allocatable, intent(inout) :: error
        integer, intent(in) :: nx, ny
        logical, intent(in) :: shared   !! whether the products' circulant is the doubled grid
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_tangential_operator) :: top
        real(dp), allocatable :: kxx(:, :), kxy(:, :), kyy(:, :), c(:, :), a(:, :), b(:, :), d(:, :), det(:, :)
        real(dp), allocatable :: mxx(:, :), mxy(:, :), myy(:, :), dx(:, :), dy(:, :), zx(:, :), zy(:, :), rx(:, :), ry(:, :)
        real(dp) :: lmax, lmin
        integer :: stat, i, j, k, l
        character(len=200) :: msg, label
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.3_dp; mat%nu2 = 0.3_dp
        call combine_material(mat, stat, msg)
        write (label, '(i0,a,i0)') nx, ' x ', ny
        call make_grid(grid, nx, ny, -1.0_dp, 1.0_dp, -1.0_dp, 0.5_dp, stat, msg)
        call build_tangential_operator(top, mat, grid)
        call check(error, (top%a_xx%mx == 2*nx .and. top%a_xx%my == 2*ny) .eqv. shared, &
            trim(label)//': products on the doubled grid or not, as intended')
        call ic_kernel_extended(IC_XX, mat, grid, nx, ny, kxx)
        call ic_kernel_extended(IC_XY, mat, grid, nx, ny, kxy)
        call ic_kernel_extended(IC_YY, mat, grid, nx, ny, kyy)
        call doubled_circulant(kxx, nx, ny, .false., c); a = direct_even_symbol(c)
        call doubled_circulant(kxy, nx, ny, .true., c); b = direct_even_symbol(c)
        call doubled_circulant(kyy, nx, ny, .false., c); d = direct_even_symbol(c)
        det = a*d - b*b
        lmax = maxval(0.5_dp*(a + d) + sqrt(0.25_dp*(a - d)**2 + b**2))
        lmin = minval(0.5_dp*(a + d) - sqrt(0.25_dp*(a - d)**2 + b**2))
        call check(error, lmin > 1.0e-8_dp*lmax, trim(label)//': no symbol eigenvalue floored (plain 2x2 inverses)')
        if (allocated(error)) return
        mxx = central_coefficients(d/det, nx, ny)
        mxy = central_coefficients(-b/det, nx, ny)
        myy = central_coefficients(a/det, nx, ny)
        allocate (dx(nx, ny), dy(nx, ny), zx(nx, ny), zy(nx, ny), rx(nx, ny), ry(nx, ny))
        do j = 1, ny
            do i = 1, nx
                dx(i, j) = sin(0.7_dp*i) + cos(1.3_dp*j); dy(i, j) = cos(0.4_dp*i*j) - 0.05_dp*j
            end do
        end do
        rx = 0; ry = 0
        do j = 1, ny
            do i = 1, nx
                do l = 1, ny
                    do k = 1, nx
                        ! the coefficient arrays are 1-based here: offset d at d + n
                        rx(i, j) = rx(i, j) + mxx(i - k + nx, j - l + ny)*dx(k, l) + mxy(i - k + nx, j - l + ny)*dy(k, l)
                        ry(i, j) = ry(i, j) + mxy(i - k + nx, j - l + ny)*dx(k, l) + myy(i - k + nx, j - l + ny)*dy(k, l)
                    end do
                end do
            end do
        end do
        call apply_block_inverse(top, dx, dy, zx, zy, circulant=.false.)
        call check(error, maxval(abs(zx - rx)) + maxval(abs(zy - ry)) <= 1e-12_dp*(maxval(abs(rx)) + maxval(abs(ry))), &
            trim(label)//': M (dx, dy) = the doubled block circulant inverse''s Toeplitz part (direct sums)')
    end subroutine block_inverse_case

    !> c(0:2nx−1, 0:2ny−1) ← the circulant of k(−n…n) on the doubled grid: the slot of offset
    !! ±n holds k(n) (even kernels) or 0 (`odd`, odd in x and in y).
    subroutine doubled_circulant(k, nx, ny, odd, c)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: k(-nx:, -ny:)
        logical, intent(in) :: odd
        real(dp), allocatable, intent(out) :: c(:, :)
        integer :: i, j, di, dj
        allocate (c(0:2*nx - 1, 0:2*ny - 1))
        do j = 0, 2*ny - 1
            dj = j; if (j > ny) dj = j - 2*ny
            do i = 0, 2*nx - 1
                di = i; if (i > nx) di = i - 2*nx
                c(i, j) = k(di, dj)
                if (odd .and. (i == nx .or. j == ny)) c(i, j) = 0
            end do
        end do
    end subroutine doubled_circulant

    !> Real symbol of an even circulant by the direct sums λ(p, q) = Σ c(i, j) cos 2π(pi/mx + qj/my).
    function direct_even_symbol(c) result(lam)
        real(dp), intent(in) :: c(0:, 0:)
        real(dp), allocatable :: lam(:, :)
        integer :: p, q, i, j, mx, my
        mx = size(c, 1); my = size(c, 2)
        allocate (lam(0:mx - 1, 0:my - 1), source=0.0_dp)
        do q = 0, my - 1
            do p = 0, mx - 1
                do j = 0, my - 1
                    do i = 0, mx - 1
                        lam(p, q) = lam(p, q) + c(i, j)*cos(2*pi*(real(mod(p*i, mx), dp)/mx + real(mod(q*j, my), dp)/my))
                    end do
                end do
            end do
        end do
    end function direct_even_symbol

    !> Coefficients at the offsets |di| < nx, |dj| < ny of the even circulant with real symbol
    !! lam(0:mx−1, 0:my−1): (1/(mx·my)) Σ lam(p, q) cos 2π(p·di/mx + q·dj/my).
    function central_coefficients(lam, nx, ny) result(m)
        real(dp), intent(in) :: lam(0:, 0:)
        integer, intent(in) :: nx, ny
        real(dp), allocatable :: m(:, :)
        integer :: p, q, di, dj, mx, my
        mx = size(lam, 1); my = size(lam, 2)
        allocate (m(-(nx - 1):nx - 1, -(ny - 1):ny - 1), source=0.0_dp)
        do dj = -(ny - 1), ny - 1
            do di = -(nx - 1), nx - 1
                do q = 0, my - 1
                    do p = 0, mx - 1
                        m(di, dj) = m(di, dj) + lam(p, q)*cos(2*pi*(real(modulo(p*di, mx), dp)/mx + &
                            real(modulo(q*dj, my), dp)/my))
                    end do
                end do
            end do
        end do
        m = m/real(mx*my, dp)
    end function central_coefficients

    !> On the thesis' Cattaneo grid (240×200, where rounding in the double differences of
    !! large antiderivative values used to leave A^xy a complex symbol) every block has its
    !! reflections exactly: A(−i, j) = ±A(i, j), A(i, −j) = ±A(i, j) with the signs of the
    !! kernel (ZZ, XX, YY even in both; XY odd in both; XZ, ZX odd in x, even in y; YZ, ZY the
    !! reverse), and A^xy is stored as a real (even) symbol.
    subroutine test_kernel_reflections(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: op
        real(dp), allocatable :: k(:, :)
        real(dp), parameter :: ex(IC_ZZ:IC_ZY) = [1, 1, 1, -1, -1, -1, 1, 1], &
            ey(IC_ZZ:IC_ZY) = [1, 1, 1, -1, 1, 1, -1, -1]
        integer :: stat, b, n
        character(len=200) :: msg, label
        call dissimilar(mat)
        call make_grid(grid, 240, 200, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, msg)
        do b = IC_ZZ, IC_ZY
            call ic_kernel(b, mat, grid, k)
            n = 239
            write (label, '(a,i0)') 'block ', b
            call check(error, all(k(-n:n, :) == ex(b)*k(n:-n:-1, :)), trim(label)//' reflection in x exact')
            call check(error, all(k(:, -199:199) == ey(b)*k(:, 199:-199:-1)), trim(label)//' reflection in y exact')
            if (allocated(error)) return
        end do
        call build_bttb(op, IC_XY, mat, grid)
        call check(error, op%parity == SYMBOL_EVEN .and. allocated(op%rsymbol), 'A^xy stored as a real symbol')
        call op%destroy()
    end subroutine test_kernel_reflections

    !> A block that goes out of scope releases its share of the plan set (final binding).
    subroutine test_final_binding(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_bttb) :: owner
        type(fc_bttb), allocatable :: extra(:)
        integer :: stat
        character(len=200) :: msg
        call dissimilar(mat)
        call make_grid(grid, 8, 6, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, stat, msg)
        call build_bttb(owner, IC_ZZ, mat, grid)
        call scoped_user(owner)
        call check(error, owner%fft%refs == 1, 'block dropped at the end of its scope released the plans')
        allocate (extra(3))
        call build_bttb(extra(1), IC_XX, mat, grid, plans_from=owner)
        call build_bttb(extra(2), IC_YY, mat, grid, plans_from=owner)
        call check(error, owner%fft%refs == 3, 'two more users')
        deallocate (extra)
        call check(error, owner%fft%refs == 1, 'deallocated blocks released the plans')
        call owner%destroy()
    contains
        subroutine scoped_user(o)
            type(fc_bttb), intent(in) :: o
            type(fc_bttb) :: local
            call build_bttb(local, IC_XY, mat, grid, plans_from=o)
            call check(error, o%fft%refs == 2, 'local block shares the plans')
        end subroutine scoped_user
    end subroutine test_final_binding

    !> On a 1024² grid (a doubled spectrum of 1025 × 2048 values) the products run their y
    !! passes on contiguous column chunks (A^zz and BCCG's Toeplitz inverse).  The product
    !! with A^zz, whose symbol the chunked passes made as well, equals the direct sums over
    !! the stored coefficients for a load on seven elements spread over the grid (edges and
    !! corners included), to 1e−12 of the largest value.  A 64² operator keeps the strided
    !! passes.
    subroutine test_chunked_y(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop, small
        real(dp), allocatable :: x(:, :), y(:, :), yd(:, :)
        integer, parameter :: n = 1024
        integer :: stat, k, i, j
        integer, parameter :: px(7) = [1, n, 1, n, 517, 3, 1000], py(7) = [1, 1, n, n, 300, 1020, 12]
        character(len=256) :: msg
        mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, msg)
        call make_grid(grid, 64, 64, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, stat, msg)
        call build_normal_operator(small, mat, grid)
        call check(error, .not. small%a_zz%chunked_y(), '64 x 64: strided y passes expected')
        call make_grid(grid, n, n, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, stat, msg)
        call build_normal_operator(nop, mat, grid)
        call check(error, nop%a_zz%chunked_y() .and. nop%precond%chunked_y(), '1024 x 1024: chunked y passes expected')
        if (allocated(error)) return
        allocate (x(n, n), y(n, n), yd(n, n))
        x = 0
        do k = 1, size(px)
            x(px(k), py(k)) = 1 + 0.1_dp*k
        end do
        call nop%a_zz%apply(x, y)
        yd = 0
        do k = 1, size(px)
            do j = 1, n
                do i = 1, n
                    yd(i, j) = yd(i, j) + x(px(k), py(k))*nop%a_zz%kernel(i - px(k), j - py(k))
                end do
            end do
        end do
        call check(error, maxval(abs(y - yd)), 0.0_dp, 'A x, chunked passes vs direct sums', abs=1e-12_dp*maxval(abs(yd)))
    end subroutine test_chunked_y

end module test_operators
