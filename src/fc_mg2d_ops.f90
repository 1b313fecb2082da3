!> Operators of the 2D strip problems (thesis ch. 3) other than the FFT products
!! ([[fc_mg2d_fft]]): the strip's influence coefficients and the Toeplitz inverse M ≈ A⁻¹
!! on the thesis' (2n − 1)-circulant, computed in the hierarchy's shared buffer.
!!
!! The coefficients of A^xx (and A^zz, A^yy) on an n×1 grid are double differences of
!! antiderivatives that are odd in both u and v; with the element corners placed
!! symmetrically about 0 only the corners u > 0, v > 0 are evaluated (n special-function
!! calls per antiderivative instead of 4n + 4).
module fc_mg2d_ops
    use fc_kinds, only: dp, pi
    use fc_geometry, only: fc_grid
    use fc_influence, only: fc_material, ic_kernel, IC_ZZ, IC_XX, IC_YY
    use fc_fftw
    use fc_threads, only: fftw_threads_for_size, omp_min_elements
    use fc_mg2d_fft, only: strip_fft, strip_workspace
    implicit none
    private

    public :: strip_fft, strip_workspace   ! re-exported: the products' types ([[fc_mg2d_fft]])
    public :: strip_kernel, strip_toeplitz_inverse, strip_toeplitz_inverse_even, strip_workspace_need

contains

    !> Reals a workspace needs for the products (2n) and the Toeplitz inverses
    !! ([[strip_toeplitz_inverse_even]]) of every level size in `sizes`.
    pure integer function strip_workspace_need(sizes) result(need)
        integer, intent(in) :: sizes(:)
        integer :: l
        need = 0
        do l = 1, size(sizes)
            need = max(need, 2*sizes(l), inverse_buffer_reals(sizes(l)))
        end do
    end function strip_workspace_need

    ! ---- coefficients ------------------------------------------------------------------------

    !> Coefficients a(0:n−1) (a(−d) = a(d)) of influence block `block` on the n×1 `grid`
    !! [mm per N/mm²].  A^zz, A^xx, A^yy use the odd symmetry of their antiderivatives;
    !! other blocks are taken from [[ic_kernel]].
    subroutine strip_kernel(block, mat, grid, a)
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        real(dp), intent(out) :: a(0:)
        real(dp), allocatable :: kern(:, :)
        real(dp) :: c, hy, f1a, f2a, f1b, f2b
        integer :: n, i, i0, b, nb
        integer, parameter :: kernel_block = 4096
        n = grid%nx
        if (grid%ny /= 1 .or. .not. (block == IC_ZZ .or. block == IC_XX .or. block == IC_YY)) then
            call ic_kernel(block, mat, grid, kern)
            a(0:n - 1) = kern(0:n - 1, 0)
            return
        end if
        ! Corners u_i = (i − ½)dx, v = ±dy/2; F(−u, v) = F(u, −v) = −F(u, v), so the double
        ! difference for offset d is 2[F(u_{d+1}, hy) − F(u_d, hy)] with F(u_0) = −F(u_1).
        ! Blocks of offsets, each carrying F from one offset to the next: every F is
        ! evaluated once (plus once per block), and no array of n + 1 values is needed.
        hy = grid%dy/2
        c = 1/(pi*mat%g)
        nb = (n + kernel_block - 1)/kernel_block
        !$omp parallel do default(shared) private(i, i0, f1a, f2a, f1b, f2b) schedule(static) &
        !$omp if(n > omp_min_elements)
        do b = 1, nb
            i0 = (b - 1)*kernel_block
            if (i0 == 0) then
                call antiderivatives(1, f1a, f2a)
                f1a = -f1a; f2a = -f2a
            else
                call antiderivatives(i0, f1a, f2a)
            end if
            do i = i0, min(n, i0 + kernel_block) - 1
                call antiderivatives(i + 1, f1b, f2b)
                a(i) = 2*c*((1 - mat%nu)*(f1b - f1a) + mat%nu*(f2b - f2a))
                f1a = f1b; f2a = f2b
            end do
        end do
        !$omp end parallel do
    contains
        !> F1 = ∫∫ 1/ρ and F2 = ∫∫ u²/ρ³ (A^xx), ∫∫ v²/ρ³ (A^yy) or 0 (A^zz) at corner u_i.
        pure subroutine antiderivatives(i, f1, f2)
            integer, intent(in) :: i
            real(dp), intent(out) :: f1, f2
            real(dp) :: u
            u = (i - 0.5_dp)*grid%dx
            f1 = u*asinh(hy/u) + hy*asinh(u/hy)
            select case (block)
            case (IC_XX); f2 = hy*asinh(u/hy)
            case (IC_YY); f2 = u*asinh(hy/u)
            case default; f2 = 0
            end select
        end subroutine antiderivatives
    end subroutine strip_kernel

    ! ---- Toeplitz inverse ----------------------------------------------------------------------

    !> Coefficients m(−(n−1):n−1) of the Toeplitz M ≈ A⁻¹ (thesis §3.3.1): A's coefficients
    !! a_{−(n−1)…n−1} form a (2n−1)-circulant, its symbol is inverted pointwise and the
    !! inverse circulant's coefficients for offsets |d| ≤ n−1 are M's (equivalently: the
    !! centre column of the inverse of the circulant, "m = IFFT(FFT(u)./FFT(a))").
    !! A is symmetric (a(−d) = a(d)); the circulant is built from a(0:n−1).
    !! The circulant is even, so both transforms are real; 2n−1 is often prime (2^13−1,
    !! 2^17−1, 2^19−1), where FFTW's complex transform plans and runs several times faster
    !! than its real one, so the complex one is used for sizes with a large prime factor.
    !! Not [[inverse_toeplitz_from_kernel]]: that 2D construction embeds A in a 2n-circulant
    !! whose wrap-around slot holds the coefficient at offset n and floors the symbol at 1e−8;
    !! this is the thesis' (2n−1)-circulant, whose smoothing and convergence factors ch. 3
    !! reports.  The two give different M (not a round-off difference), so each keeps its own.
    subroutine strip_toeplitz_inverse(n, a, m, min_symbol)
        integer, intent(in) :: n                         !! grid size
        real(dp), intent(in) :: a(-(n - 1):n - 1)        !! A's coefficients
        real(dp), intent(out) :: m(-(n - 1):n - 1)       !! M's coefficients
        real(dp), intent(out), optional :: min_symbol    !! smallest symbol / largest
        type(strip_workspace) :: ws
        call ws%reserve(inverse_buffer_reals(n))
        call circulant_inverse(n, a(0:n - 1), ws, min_symbol, m_full=m)
        call ws%release()
    end subroutine strip_toeplitz_inverse

    !> The even part (m(d) + m(−d))/2, d = 0…n−1, of [[strip_toeplitz_inverse]]'s M from A's
    !! coefficients a(0:n−1), computed in the buffer of `ws` (at least
    !! [[strip_workspace_need]]([n]) reals): no arrays of 2n − 1 offsets, no buffer of its own.
    subroutine strip_toeplitz_inverse_even(n, a, m, ws, min_symbol)
        integer, intent(in) :: n                         !! grid size
        real(dp), intent(in) :: a(0:)                    !! A's coefficients a(0:n−1)
        real(dp), intent(out) :: m(0:)                   !! M's coefficients m(0:n−1)
        type(strip_workspace), intent(inout) :: ws       !! shared buffer
        real(dp), intent(out), optional :: min_symbol    !! smallest symbol / largest
        if (.not. associated(ws%buf)) error stop 'strip_toeplitz_inverse_even: workspace not reserved'
        if (size(ws%buf) < inverse_buffer_reals(n)) error stop 'strip_toeplitz_inverse_even: workspace too small'
        call circulant_inverse(n, a(0:n - 1), ws, min_symbol, m_even=m(0:n - 1))
    end subroutine strip_toeplitz_inverse_even

    !> Reals the (2n−1)-circulant inverse needs in place: 2n for the real transform, 2(2n−1)
    !! for the complex one.
    pure integer function inverse_buffer_reals(n) result(k)
        integer, intent(in) :: n
        if (largest_prime_factor(2*n - 1) > 2048) then
            k = 2*(2*n - 1)
        else
            k = 2*n
        end if
    end function inverse_buffer_reals

    !> The (2n−1)-circulant of the even coefficients a(0:n−1), inverted in the buffer of `ws`;
    !! returns all offsets (m_full) or the even part (m_even).
    subroutine circulant_inverse(n, a, ws, min_symbol, m_full, m_even)
        integer, intent(in) :: n
        real(dp), intent(in) :: a(0:n - 1)
        type(strip_workspace), intent(in) :: ws
        real(dp), intent(out), optional :: min_symbol
        real(dp), intent(out), optional :: m_full(-(n - 1):n - 1)
        real(dp), intent(out), optional :: m_even(0:n - 1)
        integer :: nn, d
        real(dp), pointer, contiguous :: rbuf(:)
        complex(dp), pointer, contiguous :: cbuf(:)
        type(c_ptr) :: pf, pb
        real(dp) :: smax, smin
        logical :: complex_fft, par
        integer :: saved
        saved = 1
        nn = 2*n - 1
        par = n > omp_min_elements      ! element loops threaded on large levels (same results)
        complex_fft = largest_prime_factor(nn) > 2048
        if (complex_fft) then
            call c_f_pointer(ws%raw, cbuf, [nn])
            !$omp critical (fc_fftw_planner)
            call fftw_threads_for_size(nn, saved)
            pf = fftw_plan_dft_1d(int(nn, c_int), cbuf, cbuf, FFTW_FORWARD, FFTW_ESTIMATE)
            call fftw_threads_for_size(-1, saved)
            !$omp end critical (fc_fftw_planner)
            pb = c_null_ptr
            !$omp parallel do default(shared) schedule(static) if(par)
            do d = 0, n - 1
                cbuf(d + 1) = a(d)
                if (d > 0) cbuf(nn - d + 1) = a(d)
            end do
            !$omp end parallel do
            call fftw_execute_dft(pf, cbuf, cbuf)
            call symbol_range(real(cbuf, dp), smax, smin)
            if (present(min_symbol)) min_symbol = smin/smax
            ! the symbol is real (even circulant); the inverse transform of a real even
            ! sequence is its forward transform divided by the size
            !$omp parallel do default(shared) schedule(static) if(par)
            do d = 1, nn
                cbuf(d) = 1/cmplx(max(real(cbuf(d), dp), 1.0e-12_dp*smax), 0.0_dp, dp)/real(nn, dp)
            end do
            !$omp end parallel do
            call fftw_execute_dft(pf, cbuf, cbuf)
            if (present(m_full)) then
                !$omp parallel do default(shared) schedule(static) if(par)
                do d = -(n - 1), n - 1
                    m_full(d) = real(cbuf(modulo(d, nn) + 1), dp)
                end do
                !$omp end parallel do
            end if
            if (present(m_even)) then
                m_even(0) = real(cbuf(1), dp)
                !$omp parallel do default(shared) schedule(static) if(par)
                do d = 1, n - 1
                    m_even(d) = (real(cbuf(d + 1), dp) + real(cbuf(nn - d + 1), dp))/2
                end do
                !$omp end parallel do
            end if
        else
            ! in place: nn reals padded to nn + 1 = 2(nn/2 + 1)
            call c_f_pointer(ws%raw, rbuf, [nn + 1])
            call c_f_pointer(ws%raw, cbuf, [nn/2 + 1])
            !$omp critical (fc_fftw_planner)
            call fftw_threads_for_size(nn, saved)
            pf = fftw_plan_dft_r2c_1d(int(nn, c_int), rbuf, cbuf, FFTW_ESTIMATE)
            pb = fftw_plan_dft_c2r_1d(int(nn, c_int), cbuf, rbuf, FFTW_ESTIMATE)
            call fftw_threads_for_size(-1, saved)
            !$omp end critical (fc_fftw_planner)
            !$omp parallel do default(shared) schedule(static) if(par)
            do d = 0, n - 1
                rbuf(d + 1) = a(d)
                if (d > 0) rbuf(nn - d + 1) = a(d)
            end do
            !$omp end parallel do
            call fftw_execute_dft_r2c(pf, rbuf, cbuf)
            call symbol_range(real(cbuf, dp), smax, smin)
            if (present(min_symbol)) min_symbol = smin/smax
            !$omp parallel do default(shared) schedule(static) if(par)
            do d = 1, size(cbuf)
                cbuf(d) = 1/cmplx(max(real(cbuf(d), dp), 1.0e-12_dp*smax), 0.0_dp, dp)/real(nn, dp)
            end do
            !$omp end parallel do
            call fftw_execute_dft_c2r(pb, cbuf, rbuf)
            if (present(m_full)) then
                !$omp parallel do default(shared) schedule(static) if(par)
                do d = -(n - 1), n - 1
                    m_full(d) = rbuf(modulo(d, nn) + 1)
                end do
                !$omp end parallel do
            end if
            if (present(m_even)) then
                m_even(0) = rbuf(1)
                !$omp parallel do default(shared) schedule(static) if(par)
                do d = 1, n - 1
                    m_even(d) = (rbuf(d + 1) + rbuf(nn - d + 1))/2
                end do
                !$omp end parallel do
            end if
        end if
        !$omp critical (fc_fftw_planner)
        call fftw_destroy_plan(pf)
        if (c_associated(pb)) call fftw_destroy_plan(pb)
        !$omp end critical (fc_fftw_planner)
    end subroutine circulant_inverse

    !> Largest and smallest entry of s (max and min are exact in any order).
    subroutine symbol_range(s, smax, smin)
        real(dp), intent(in) :: s(:)
        real(dp), intent(out) :: smax, smin
        integer :: k
        smax = -huge(1.0_dp); smin = huge(1.0_dp)
        !$omp parallel do default(shared) reduction(max:smax) reduction(min:smin) schedule(static) &
        !$omp if(size(s) > 2*omp_min_elements)
        do k = 1, size(s)
            smax = max(smax, s(k)); smin = min(smin, s(k))
        end do
        !$omp end parallel do
    end subroutine symbol_range

    !> Largest prime factor of k ≥ 1 (trial division, O(√k)).
    pure integer function largest_prime_factor(k) result(p)
        integer, intent(in) :: k
        integer :: r, f
        r = k; p = 1; f = 2
        do while (f*f <= r)
            if (mod(r, f) == 0) then
                p = f; r = r/f
            else
                f = f + 1
            end if
        end do
        if (r > 1) p = max(p, r)
    end function largest_prime_factor

end module fc_mg2d_ops
