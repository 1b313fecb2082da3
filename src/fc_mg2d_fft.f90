!> FFT products of the 2D strip problems (thesis ch. 3): products with n×n symmetric
!! Toeplitz matrices on the 2n-circulant, for the strip multigrid's levels ([[fc_mg2d_ops]]
!! builds the matrices, [[fc_mg2d]] runs the cycles).
!!
!! [[strip_fft]] holds, per level, one in-place complex plan pair that transforms the
!! 2n-point real sequences of the 2n-circulant as n-point complex ones (even and odd entries
!! as real and imaginary parts, the half spectrum recovered with n/2 twiddles of our own),
!! made once and shared by both matrices of a level (A and M), whose symbols are real (even
!! circulants) and stored as n+1 real numbers; the levels of a hierarchy run their
!! transforms in one shared FFTW-aligned buffer ([[strip_workspace]]).  Why complex plans
!! of n points rather than FFTW's real plans of 2n: a product takes the same time either
!! way, but FFTW_ESTIMATE plans the real pair of 2n points 8–40 times slower (2^21 points:
!! 39 ms against 2.7 ms; 114 ms against 14 ms for the 20 levels of a 2^20 hierarchy),
!! which was a tenth of a 2^20 solve.  On levels of 2^18 and 2^20 cells and more the
!! n-point transform is a radix-2 or radix-4 step of our own and two or four FFTW
!! transforms of n/2 or n/4 points, which stay in cache and skip the zero-padded half
!! (a 2^20-cell product 29–31 → 12.9 ms; doc/multigrid.md, "Planning the products").
module fc_mg2d_fft
    use fc_kinds, only: dp, pi
    use fc_fftw
    use fc_threads, only: fftw_threads_for_size, omp_min_elements
    use fc_fft_effort, only: strip_product_radix, strip_product_plans
    implicit none
    private

    !> Buffer and in-place FFT plans for products with n×n symmetric Toeplitz matrices
    !! (circulant of size 2n): the 2n-point real sequence x is transformed as the n-point
    !! complex sequence z_k = x_2k + i·x_2k+1 (0-based), whose spectrum gives x's half
    !! spectrum X_0…X_n through the twiddles `tw`.  The buffer is allocated by FFTW for SIMD
    !! alignment, hence a pointer; plans and buffer are released by the final binding.
    type, public :: strip_fft
        integer :: n = 0                          !! matrix size
        integer :: m = 0                          !! circulant size 2n
        real(dp), pointer, contiguous :: buf(:) => null()   !! 2n reals: the real sequence
        complex(dp), pointer, contiguous :: cbuf(:) => null()  !! the same storage as n complex
        complex(dp), allocatable :: tw(:)         !! tw(k) = exp(−2πik/(2n)), k = 0…n/2
        !> the n-point transforms as `radix` transforms of n/radix points after a radix-2 or
        !! radix-4 step of our own (1: FFTW's n-point plan; large levels, fc_fft_effort's
        !! `strip_product_radix`)
        integer :: radix = 1
        type(c_ptr) :: raw = c_null_ptr           !! FFTW allocation behind buf
        !> forward and backward, in place: `radix` transforms of n/radix points
        type(c_ptr) :: pf = c_null_ptr, pb = c_null_ptr
    contains
        procedure :: init => strip_fft_init
        procedure :: symbol => strip_fft_symbol
        procedure :: product => strip_fft_product
        procedure :: destroy => strip_fft_destroy
        final :: strip_fft_final
    end type strip_fft

    !> One FFTW-aligned real buffer shared by the levels of a strip hierarchy, which use it
    !! one after the other (their products, symbols and Toeplitz inverses).  One buffer of the
    !! largest level's size instead of one per level and per inverse: the set-up at 2^20 cells
    !! touched about 90 000 fresh pages, which cost a tenth of the solve (doc/multigrid.md,
    !! "Performance at 2^20").  Freed by the final binding.
    type, public :: strip_workspace
        real(dp), pointer, contiguous :: buf(:) => null()   !! the buffer (FFTW alignment)
        type(c_ptr) :: raw = c_null_ptr                     !! FFTW allocation behind buf
    contains
        procedure :: reserve => strip_workspace_reserve
        procedure :: release => strip_workspace_release
        final :: strip_workspace_final
    end type strip_workspace

contains

    !> Plans, twiddles and buffer for n×n products; the plans are made before anything is
    !! stored.  With `ws` the products run in the workspace's buffer (at least 2n reals, see
    !! [[strip_workspace_need]]), which must outlive these plans' use; else in a buffer of
    !! their own.
    subroutine strip_fft_init(self, n, ws, radix)
        class(strip_fft), intent(inout) :: self
        integer, intent(in) :: n
        type(strip_workspace), intent(in), optional, target :: ws
        !> 1, 2 or 4 whatever n (n divisible by 2·radix, else 1); default fc_fft_effort's
        !! `strip_product_radix` (tests run every layout on small n)
        integer, intent(in), optional :: radix
        integer :: saved
        saved = 1
        call self%destroy()
        self%n = n; self%m = 2*n
        if (present(ws)) then
            if (.not. associated(ws%buf)) error stop 'strip_fft_init: workspace not reserved'
            if (size(ws%buf) < self%m) error stop 'strip_fft_init: workspace smaller than 2n'
            call c_f_pointer(ws%raw, self%buf, [self%m])
            call c_f_pointer(ws%raw, self%cbuf, [n])
        else
            self%raw = fftw_alloc_real(int(self%m, c_size_t))
            call c_f_pointer(self%raw, self%buf, [self%m])
            call c_f_pointer(self%raw, self%cbuf, [n])
        end if
        self%radix = strip_product_radix(n)
        if (present(radix)) then
            self%radix = 1
            if ((radix == 2 .or. radix == 4) .and. mod(n, 2*radix) == 0) self%radix = radix
        end if
        !$omp critical (fc_fftw_planner)
        call fftw_threads_for_size(self%m, saved)
        call strip_product_plans(n, self%radix, self%cbuf, FFTW_ESTIMATE, self%pf, self%pb)
        call fftw_threads_for_size(-1, saved)
        !$omp end critical (fc_fftw_planner)
        allocate (self%tw(0:n/2))
        call half_twiddles(self%m, self%tw)
        self%buf = 0
    end subroutine strip_fft_init

    !> tw(k) = exp(−2πik/m), k = 0…m/4 (m = 2n): directly up to m/8, above by the symmetry
    !! exp(−2πi(m/4 − k)/m) = −i·conj(tw(k)) when m/4 is an integer.
    subroutine half_twiddles(m, tw)
        integer, intent(in) :: m
        complex(dp), intent(out) :: tw(0:)
        integer :: k, h, q
        real(dp) :: a
        h = ubound(tw, 1)                  ! n/2
        q = h
        if (mod(m, 4) == 0) q = h/2        ! m/4 = n/2 is an integer: the rest by symmetry
        !$omp parallel do default(shared) private(a) schedule(static) if(h > omp_min_elements)
        do k = 0, q
            a = -2*pi*real(k, dp)/real(m, dp)
            tw(k) = cmplx(cos(a), sin(a), dp)
        end do
        !$omp end parallel do
        if (q < h) then
            !$omp parallel do default(shared) schedule(static) if(h > omp_min_elements)
            do k = q + 1, h
                tw(k) = cmplx(-aimag(tw(h - k)), -real(tw(h - k), dp), dp)
            end do
            !$omp end parallel do
        end if
    end subroutine half_twiddles

    !> Symbol sym(0:n) of the symmetric Toeplitz matrix with coefficients c(0:n−1)
    !! (c(−d) = c(d)) on the 2n-circulant, scaled by 1/(2n) for [[strip_fft_product]].
    subroutine strip_fft_symbol(self, c, sym)
        class(strip_fft), intent(inout) :: self
        real(dp), intent(in) :: c(0:)
        real(dp), intent(out) :: sym(0:)
        integer :: n, d, k
        complex(dp) :: z0, z1, z2, z3, zk, zj, e, o, lo, hi
        complex(dp), parameter :: iu = (0.0_dp, 1.0_dp)
        integer :: q
        logical :: par
        n = self%n
        par = n > omp_min_elements
        !$omp parallel do default(shared) schedule(static) if(par)
        do d = 0, n - 1
            self%buf(d + 1) = c(d)
            if (d > 0) self%buf(self%m - d + 1) = c(d)
        end do
        !$omp end parallel do
        self%buf(n + 1) = 0
        select case (self%radix)
        case (2)
            ! radix-2 decimation in frequency: Z_2m from z_j + z_{j+n/2}, Z_2m+1 from
            ! (z_j − z_{j+n/2})·w^2j, each an n/2-point transform
            !$omp parallel do default(shared) private(lo, hi) schedule(static) if(par)
            do d = 0, n/2 - 1
                lo = self%cbuf(d + 1); hi = self%cbuf(d + n/2 + 1)
                self%cbuf(d + 1) = lo + hi
                self%cbuf(d + n/2 + 1) = (lo - hi)*wpow(self%tw, n, 2*d)
            end do
            !$omp end parallel do
        case (4)
            ! radix 4: Z_4m+r from (Σ_s (−i)^rs·z_{j+sq})·w^2rj, q = n/4, each a q-point transform
            q = n/4
            !$omp parallel do default(shared) private(z0, z1, z2, z3) schedule(static) if(par)
            do d = 0, q - 1
                z0 = self%cbuf(d + 1); z1 = self%cbuf(d + q + 1); z2 = self%cbuf(d + 2*q + 1); z3 = self%cbuf(d + 3*q + 1)
                self%cbuf(d + 1) = z0 + z1 + z2 + z3
                self%cbuf(d + q + 1) = (z0 - iu*z1 - z2 + iu*z3)*wpow(self%tw, n, 2*d)
                self%cbuf(d + 2*q + 1) = (z0 - z1 + z2 - z3)*wpow(self%tw, n, 4*d)
                self%cbuf(d + 3*q + 1) = (z0 + iu*z1 - z2 - iu*z3)*wpow(self%tw, n, 6*d)
            end do
            !$omp end parallel do
        end select
        call fftw_execute_dft(self%pf, self%cbuf, self%cbuf)
        z0 = self%cbuf(1)
        sym(0) = (real(z0, dp) + aimag(z0))/self%m
        sym(n) = (real(z0, dp) - aimag(z0))/self%m
        ! X_k = E_k + w^k·O_k and X_{n−k} = conj(E_k − w^k·O_k), E_k = (Z_k + conj Z_{n−k})/2,
        ! O_k = (Z_k − conj Z_{n−k})/(2i); the symbol is real (even circulant)
        !$omp parallel do default(shared) private(zk, zj, e, o) schedule(static) if(par)
        do k = 1, n/2
            zk = self%cbuf(spectrum_index(self%radix, n, k)); zj = self%cbuf(spectrum_index(self%radix, n, n - k))
            e = (zk + conjg(zj))/2
            o = (zk - conjg(zj))*cmplx(0.0_dp, -0.5_dp, dp)
            sym(k) = real(e + self%tw(k)*o, dp)/self%m
            sym(n - k) = real(e - self%tw(k)*o, dp)/self%m
        end do
        !$omp end parallel do
    end subroutine strip_fft_symbol

    !> y = T x for the symmetric Toeplitz matrix of symbol `sym` (from [[strip_fft_symbol]]):
    !! the first n entries of the 2n-circulant product with [x, 0].  The spectrum is taken
    !! apart into x's half spectrum, multiplied by the symbol and put together for the
    !! backward transform in one pass over the pairs (k, n − k).
    subroutine strip_fft_product(self, sym, x, y)
        class(strip_fft), intent(inout) :: self
        real(dp), intent(in) :: sym(0:)
        real(dp), intent(in) :: x(:)
        real(dp), intent(out) :: y(:)
        integer :: n, k, j, h, q
        real(dp) :: y0, yn, wr, wi, ar, ai, br, bi
        logical :: par
        n = self%n
        par = n > omp_min_elements     ! element loops threaded on large levels (elementwise: same results)
        if (self%radix == 4) then
            call product_radix4(self, sym, x, y)
            return
        end if
        if (self%radix == 2) then
            ! [x, 0] as z_j = x_2j + i·x_2j+1, j < n/2, and zeros: the radix-2 step gives
            ! A = z and B = z·w^2j, whose n/2-point transforms are Z_2m and Z_2m+1
            h = n/2; q = n/4
            ! w^2j = tw(2j) for j ≤ n/4, −i·tw(2j − n/2) above ([[wpow]]): two loops
            !$omp parallel do default(shared) private(wr, wi, ar, ai) schedule(static) if(par)
            do j = 0, q
                wr = real(self%tw(2*j), dp); wi = aimag(self%tw(2*j))
                ar = x(2*j + 1); ai = x(2*j + 2)
                self%buf(2*j + 1) = ar; self%buf(2*j + 2) = ai
                self%buf(n + 2*j + 1) = ar*wr - ai*wi; self%buf(n + 2*j + 2) = ar*wi + ai*wr
            end do
            !$omp end parallel do
            !$omp parallel do default(shared) private(wr, wi, ar, ai) schedule(static) if(par)
            do j = q + 1, h - 1
                wr = aimag(self%tw(2*j - h)); wi = -real(self%tw(2*j - h), dp)
                ar = x(2*j + 1); ai = x(2*j + 2)
                self%buf(2*j + 1) = ar; self%buf(2*j + 2) = ai
                self%buf(n + 2*j + 1) = ar*wr - ai*wi; self%buf(n + 2*j + 2) = ar*wi + ai*wr
            end do
            !$omp end parallel do
            call fftw_execute_dft(self%pf, self%cbuf, self%cbuf)
            ! Z_0 = A_0 (with Z_n), the middle Z_{n/2} = A_{n/4}; pairs (k, n − k) of even k in
            ! A (A_m, A_{n/2−m}), of odd k in B (B_m, B_{n/2−1−m})
            y0 = sym(0)*(self%buf(1) + self%buf(2))
            yn = sym(n)*(self%buf(1) - self%buf(2))
            self%buf(1) = y0 + yn; self%buf(2) = y0 - yn
            self%buf(2*q + 1) = 2*sym(h)*self%buf(2*q + 1); self%buf(2*q + 2) = 2*sym(h)*self%buf(2*q + 2)
            !$omp parallel do default(shared) private(j) schedule(static) if(par)
            do k = 1, q - 1
                j = h - k
                call pair_update(self%buf(2*k + 1), self%buf(2*k + 2), self%buf(2*j + 1), self%buf(2*j + 2), &
                    self%tw(2*k), sym(2*k), sym(n - 2*k))
            end do
            !$omp end parallel do
            !$omp parallel do default(shared) private(j) schedule(static) if(par)
            do k = 0, q - 1
                j = h - 1 - k
                call pair_update(self%buf(n + 2*k + 1), self%buf(n + 2*k + 2), self%buf(n + 2*j + 1), &
                    self%buf(n + 2*j + 2), self%tw(2*k + 1), sym(2*k + 1), sym(n - 2*k - 1))
            end do
            !$omp end parallel do
            call fftw_execute_dft(self%pb, self%cbuf, self%cbuf)
            ! z'_j = a'_j + conj(w^2j)·b'_j = y_2j + i·y_2j+1 for j < n/2
            !$omp parallel do default(shared) private(wr, wi, br, bi) schedule(static) if(par)
            do j = 0, q
                wr = real(self%tw(2*j), dp); wi = aimag(self%tw(2*j))
                br = self%buf(n + 2*j + 1); bi = self%buf(n + 2*j + 2)
                y(2*j + 1) = self%buf(2*j + 1) + (br*wr + bi*wi)
                y(2*j + 2) = self%buf(2*j + 2) + (bi*wr - br*wi)
            end do
            !$omp end parallel do
            !$omp parallel do default(shared) private(wr, wi, br, bi) schedule(static) if(par)
            do j = q + 1, h - 1
                wr = aimag(self%tw(2*j - h)); wi = -real(self%tw(2*j - h), dp)
                br = self%buf(n + 2*j + 1); bi = self%buf(n + 2*j + 2)
                y(2*j + 1) = self%buf(2*j + 1) + (br*wr + bi*wi)
                y(2*j + 2) = self%buf(2*j + 2) + (bi*wr - br*wi)
            end do
            !$omp end parallel do
            return
        end if
        !$omp parallel do default(shared) schedule(static) if(par)
        do k = 1, n
            self%buf(k) = x(k); self%buf(n + k) = 0
        end do
        !$omp end parallel do
        call fftw_execute_dft(self%pf, self%cbuf, self%cbuf)
        ! Y = sym·X on the half spectrum, then Z'_k = (Y_k + Y_{k+n}) + i·(Y_k − Y_{k+n})·conj(w^k)
        ! with Y_{k+n} = conj(Y_{n−k}): the backward transform of Z' is y_2k + i·y_2k+1.
        ! For a pair k < j = n − k, with E = (Z_k + conj Z_j)/2, O = (Z_k − conj Z_j)/(2i),
        ! T = w^k·O, U = (s_k + s_j)·E + (s_k − s_j)·T, V = (s_k − s_j)·E + (s_k + s_j)·T:
        ! Z'_k = U + i·V·conj(w^k), Z'_j = conj(U) + i·conj(V)·w^k (written out in reals)
        y0 = sym(0)*(self%buf(1) + self%buf(2))
        yn = sym(n)*(self%buf(1) - self%buf(2))
        self%buf(1) = y0 + yn; self%buf(2) = y0 - yn
        !$omp parallel do default(shared) private(j) schedule(static) if(par)
        do k = 1, (n - 1)/2
            j = n - k
            call pair_update(self%buf(2*k + 1), self%buf(2*k + 2), self%buf(2*j + 1), self%buf(2*j + 2), &
                self%tw(k), sym(k), sym(j))
        end do
        !$omp end parallel do
        if (mod(n, 2) == 0 .and. n > 1) then        ! the middle, k = j = n/2: Z' = 2·s·Z
            self%buf(n + 1) = 2*sym(n/2)*self%buf(n + 1); self%buf(n + 2) = 2*sym(n/2)*self%buf(n + 2)
        end if
        call fftw_execute_dft(self%pb, self%cbuf, self%cbuf)
        !$omp parallel do default(shared) schedule(static) if(par)
        do k = 1, n
            y(k) = self%buf(k)
        end do
        !$omp end parallel do
    end subroutine strip_fft_product

    !> [[strip_fft_product]] after a radix-4 step: [x, 0] as z_j = x_2j + i·x_2j+1 (j < n/2,
    !! zeros above), u = z_j and v = z_{j+q} (q = n/4, j < q); A_r = (u + (−i)^r·v)·w^2rj,
    !! whose q-point transforms are Z_{4m+r}.  The pairs (k, n − k): k = 4m in A_0
    !! (A_0(m), A_0(q−m); Z_0 and the middle Z_{n/2} = A_0(q/2) alone), k = 4m + 2 in A_2
    !! (A_2(m), A_2(q−1−m)), k = 4m + 1 in A_1 with n − k in A_3 (A_1(m), A_3(q−1−m)).
    !! Backward: b_r = conj(w^2rj)·a_r, z'_j = b_0 + b_1 + b_2 + b_3 and
    !! z'_{j+q} = b_0 + i·b_1 − b_2 − i·b_3, the output y_2j + i·y_2j+1 for j < n/2.
    subroutine product_radix4(self, sym, x, y)
        type(strip_fft), intent(inout) :: self
        real(dp), intent(in) :: sym(0:)
        real(dp), intent(in) :: x(:)
        real(dp), intent(out) :: y(:)
        integer :: n, q, j, k, l, kh
        real(dp) :: y0, yn, ur, ui, vr, vi
        complex(dp) :: s1, s2, s3, b0, b1, b2, b3, w2, w4, t
        logical :: par
        n = self%n; q = n/4
        par = n > omp_min_elements
        ! w^2j = tw(2j) (2j < n/2); w^4j and w^6j as its square and cube (a few roundings
        ! of 1e−16, no branches in the loop)
        !$omp parallel do default(shared) private(ur, ui, vr, vi, s1, s2, s3, w2, w4) schedule(static) if(par)
        do j = 0, q - 1
            ur = x(2*j + 1); ui = x(2*j + 2); vr = x(2*(j + q) + 1); vi = x(2*(j + q) + 2)
            self%buf(2*j + 1) = ur + vr; self%buf(2*j + 2) = ui + vi
            w2 = self%tw(2*j); w4 = w2*w2
            s1 = cmplx(ur + vi, ui - vr, dp)*w2
            s2 = cmplx(ur - vr, ui - vi, dp)*w4
            s3 = cmplx(ur - vi, ui + vr, dp)*(w4*w2)
            self%buf(2*(q + j) + 1) = real(s1, dp); self%buf(2*(q + j) + 2) = aimag(s1)
            self%buf(2*(2*q + j) + 1) = real(s2, dp); self%buf(2*(2*q + j) + 2) = aimag(s2)
            self%buf(2*(3*q + j) + 1) = real(s3, dp); self%buf(2*(3*q + j) + 2) = aimag(s3)
        end do
        !$omp end parallel do
        call fftw_execute_dft(self%pf, self%cbuf, self%cbuf)
        y0 = sym(0)*(self%buf(1) + self%buf(2))
        yn = sym(n)*(self%buf(1) - self%buf(2))
        self%buf(1) = y0 + yn; self%buf(2) = y0 - yn
        self%buf(q + 1) = 2*sym(n/2)*self%buf(q + 1); self%buf(q + 2) = 2*sym(n/2)*self%buf(q + 2)  ! A_0(q/2)
        !$omp parallel do default(shared) private(l) schedule(static) if(par)
        do k = 1, q/2 - 1                                   ! A_0: k = 4m
            l = q - k
            call pair_update(self%buf(2*k + 1), self%buf(2*k + 2), self%buf(2*l + 1), self%buf(2*l + 2), &
                self%tw(4*k), sym(4*k), sym(n - 4*k))
        end do
        !$omp end parallel do
        !$omp parallel do default(shared) private(l) schedule(static) if(par)
        do k = 0, q/2 - 1                                   ! A_2: k = 4m + 2
            l = q - 1 - k
            call pair_update(self%buf(2*(2*q + k) + 1), self%buf(2*(2*q + k) + 2), self%buf(2*(2*q + l) + 1), &
                self%buf(2*(2*q + l) + 2), self%tw(4*k + 2), sym(4*k + 2), sym(n - 4*k - 2))
        end do
        !$omp end parallel do
        ! A_1 with A_3: k = 4m + 1, w^k = tw(k) up to n/2, −i·tw(k − n/2) above: two loops
        kh = (n/2 - 1)/4
        !$omp parallel do default(shared) private(l) schedule(static) if(par)
        do k = 0, kh
            l = q - 1 - k
            call pair_update(self%buf(2*(q + k) + 1), self%buf(2*(q + k) + 2), self%buf(2*(3*q + l) + 1), &
                self%buf(2*(3*q + l) + 2), self%tw(4*k + 1), sym(4*k + 1), sym(n - 4*k - 1))
        end do
        !$omp end parallel do
        !$omp parallel do default(shared) private(l, t) schedule(static) if(par)
        do k = kh + 1, q - 1
            l = q - 1 - k
            t = self%tw(4*k + 1 - n/2)
            call pair_update(self%buf(2*(q + k) + 1), self%buf(2*(q + k) + 2), self%buf(2*(3*q + l) + 1), &
                self%buf(2*(3*q + l) + 2), cmplx(aimag(t), -real(t, dp), dp), sym(4*k + 1), sym(n - 4*k - 1))
        end do
        !$omp end parallel do
        call fftw_execute_dft(self%pb, self%cbuf, self%cbuf)
        !$omp parallel do default(shared) private(b0, b1, b2, b3, w2, w4) schedule(static) if(par)
        do j = 0, q - 1
            w2 = conjg(self%tw(2*j)); w4 = w2*w2
            b0 = self%cbuf(j + 1)
            b1 = self%cbuf(q + j + 1)*w2
            b2 = self%cbuf(2*q + j + 1)*w4
            b3 = self%cbuf(3*q + j + 1)*(w4*w2)
            y(2*j + 1) = real(b0, dp) + real(b1, dp) + real(b2, dp) + real(b3, dp)
            y(2*j + 2) = aimag(b0) + aimag(b1) + aimag(b2) + aimag(b3)
            y(2*(j + q) + 1) = real(b0, dp) - aimag(b1) - real(b2, dp) + aimag(b3)
            y(2*(j + q) + 2) = aimag(b0) + real(b1, dp) - aimag(b2) - real(b3, dp)
        end do
        !$omp end parallel do
    end subroutine product_radix4

    !> One pair (k, j = n − k) of the product's half-spectrum pass, in place: (ar, ai) = Z_k,
    !! (br, bi) = Z_j on entry, Z'_k and Z'_j on exit; t = w^k, sk, sj the symbol at k and j.
    !! With E = (Z_k + conj Z_j)/2, O = (Z_k − conj Z_j)/(2i), T = t·O,
    !! U = (sk + sj)·E + (sk − sj)·T, V = (sk − sj)·E + (sk + sj)·T:
    !! Z'_k = U + i·V·conj(t), Z'_j = conj(U) + i·conj(V)·t (written out in reals).
    pure subroutine pair_update(ar, ai, br, bi, t, sk, sj)
        real(dp), intent(inout) :: ar, ai, br, bi
        complex(dp), intent(in) :: t
        real(dp), intent(in) :: sk, sj
        real(dp) :: er, ei, or, oi, tr, ti, cr, ci, sp, sd, ur, ui, vr, vi, pa, pb
        er = 0.5_dp*(ar + br); ei = 0.5_dp*(ai - bi)
        or = 0.5_dp*(ai + bi); oi = 0.5_dp*(br - ar)
        tr = real(t, dp); ti = aimag(t)
        cr = tr*or - ti*oi; ci = tr*oi + ti*or
        sp = sk + sj; sd = sk - sj
        ur = sp*er + sd*cr; ui = sp*ei + sd*ci
        vr = sd*er + sp*cr; vi = sd*ei + sp*ci
        pa = vi*tr - vr*ti; pb = vr*tr + vi*ti
        ar = ur - pa; ai = ui + pb
        br = ur + pa; bi = pb - ui
    end subroutine pair_update

    !> w^k = exp(−2πik/(2n)) for 0 ≤ k < 2n from tw(0:n/2) = w^0…w^{n/2}, by
    !! w^{n/2} = −i, w^n = −1, w^{3n/2} = i.
    pure complex(dp) function wpow(tw, n, k)
        complex(dp), intent(in) :: tw(0:)
        integer, intent(in) :: n, k
        integer :: h
        h = n/2
        if (k <= h) then
            wpow = tw(k)
        else if (k <= n) then
            wpow = cmplx(aimag(tw(k - h)), -real(tw(k - h), dp), dp)      ! −i·tw
        else if (k <= 3*h) then
            wpow = -tw(k - n)
        else
            wpow = cmplx(-aimag(tw(k - 3*h)), real(tw(k - 3*h), dp), dp)  ! i·tw
        end if
    end function wpow

    !> Position in cbuf of the spectrum's Z_k, 0 ≤ k < n: k + 1, or after a radix-r step
    !! Z_{rm+s} at s·n/r + m + 1.
    pure integer function spectrum_index(radix, n, k) result(p)
        integer, intent(in) :: radix, n, k
        p = mod(k, radix)*(n/radix) + k/radix + 1
    end function spectrum_index

    subroutine strip_fft_destroy(self)
        class(strip_fft), intent(inout) :: self
        !$omp critical (fc_fftw_planner)
        if (c_associated(self%pf)) call fftw_destroy_plan(self%pf)
        if (c_associated(self%pb)) call fftw_destroy_plan(self%pb)
        !$omp end critical (fc_fftw_planner)
        if (c_associated(self%raw)) call fftw_free(self%raw)
        if (allocated(self%tw)) deallocate (self%tw)
        self%pf = c_null_ptr; self%pb = c_null_ptr; self%raw = c_null_ptr; self%radix = 1
        self%buf => null(); self%cbuf => null()
        self%n = 0; self%m = 0
    end subroutine strip_fft_destroy

    impure elemental subroutine strip_fft_final(self)
        type(strip_fft), intent(inout) :: self
        call self%destroy()
    end subroutine strip_fft_final

    !> A buffer of at least `nreal` reals (kept if already large enough).
    subroutine strip_workspace_reserve(self, nreal)
        class(strip_workspace), intent(inout) :: self
        integer, intent(in) :: nreal
        if (associated(self%buf)) then
            if (size(self%buf) >= nreal) return
        end if
        call self%release()
        self%raw = fftw_alloc_real(int(nreal, c_size_t))
        call c_f_pointer(self%raw, self%buf, [nreal])
    end subroutine strip_workspace_reserve

    subroutine strip_workspace_release(self)
        class(strip_workspace), intent(inout) :: self
        if (c_associated(self%raw)) call fftw_free(self%raw)
        self%raw = c_null_ptr
        self%buf => null()
    end subroutine strip_workspace_release

    impure elemental subroutine strip_workspace_final(self)
        type(strip_workspace), intent(inout) :: self
        call self%release()
    end subroutine strip_workspace_final

end module fc_mg2d_fft
