!> FFT-based preconditioner for the tangential 2×2 block operator (TangCG's adhesion part).
!!
!! The construction of thesis §3.3.1, as used for the normal problem's BCCG preconditioner,
!! applied to the block operator [A^xx A^xy; A^xy A^yy]: the coefficients of the three
!! blocks for offsets −n…n fill 2nx×2ny circulants (the wrap-around slot holds the true
!! coefficient at offset n for the even blocks A^xx, A^yy and zero for the odd block A^xy,
!! which keeps every circulant symmetric); at each frequency the real symmetric 2×2 symbol
!! matrix is inverted.  Applied to data on the nx×ny grid (zero-padded to the doubled grid)
!! and restricted back, this is a product with the block Toeplitz matrix formed by the
!! central coefficients of the inverse circulant: a principal block of a symmetric positive
!! definite matrix, hence SPD.  Symbol eigenvalues are floored at 1e−8 of the largest.
!! When the products run on a larger circulant (fc_fftw's circulant_size, where FFTW
!! transforms 2n slowly) that block Toeplitz matrix is moved there: same operator.
module fc_tangprec
    use fc_kinds, only: dp
    use fc_fftw
    use fc_threads, only: omp_min_elements
    use fc_toeplitz, only: fc_bttb, even_circulant_symbol
    implicit none
    private

    !> Symbols of M ≈ [A^xx A^xy; A^xy A^yy]⁻¹ on the products' circulant (fc_fftw's
    !! circulant_size: the doubled grid unless FFTW transforms it slowly), scaled like
    !! fc_bttb's symbols (including 1/(mx·my)), so that they multiply the spectra of `forward`.
    type, public :: fc_block_inverse
        integer :: nx = 0, ny = 0
        real(dp), allocatable :: mxx(:, :), mxy(:, :), myy(:, :)   !! real: the circulants are even
    contains
        procedure :: built => block_inverse_built
    end type fc_block_inverse

    public :: build_block_inverse

contains

    pure logical function block_inverse_built(self)
        class(fc_block_inverse), intent(in) :: self
        block_inverse_built = allocated(self%mxx)
    end function block_inverse_built

    !> Build the preconditioner from the blocks' coefficients for offsets −n…n (see module
    !! header): k_xx, k_xy, k_yy(−nx:nx, −ny:ny) as [[ic_kernel_extended]] returns them.
    !! With `plans_from` (an operator of the grid) the three symbols are transformed on its
    !! plans and buffers when they are made for the 2nx×2ny circulant.
    subroutine build_block_inverse(prec, kxx, kxy, kyy, nx, ny, plans_from)
        type(fc_block_inverse), intent(inout) :: prec
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: kxx(-nx:nx, -ny:ny), kxy(-nx:nx, -ny:ny), kyy(-nx:nx, -ny:ny)
        type(fc_bttb), intent(in), optional :: plans_from
        real(dp) :: a, b, c, det, tr, disc, l1, l2, lmax, floor_, scale
        integer :: mx, my, i, k
        mx = 2*nx; if (nx == 1) mx = 1
        my = 2*ny; if (ny == 1) my = 1
        prec%nx = nx; prec%ny = ny
        if (allocated(prec%mxx)) deallocate (prec%mxx, prec%mxy, prec%myy)
        allocate (prec%mxx(mx/2 + 1, my), prec%mxy(mx/2 + 1, my), prec%myy(mx/2 + 1, my))
        ! the blocks' symbols (real: even circulants), inverted in place below
        call even_circulant_symbol(kxx, nx, ny, .false., prec%mxx, plans_from)
        call even_circulant_symbol(kxy, nx, ny, .true., prec%mxy, plans_from)
        call even_circulant_symbol(kyy, nx, ny, .false., prec%myy, plans_from)
        ! largest eigenvalue over all frequencies, for the floor
        lmax = 0
        !$omp parallel do default(shared) private(i, a, b, c) reduction(max:lmax) schedule(static) &
        !$omp if(size(prec%mxx) > omp_min_elements)
        do k = 1, my
            do i = 1, mx/2 + 1
                a = prec%mxx(i, k); b = prec%mxy(i, k); c = prec%myy(i, k)
                lmax = max(lmax, 0.5_dp*(a + c) + sqrt(0.25_dp*(a - c)**2 + b**2))
            end do
        end do
        !$omp end parallel do
        floor_ = 1.0e-8_dp*lmax
        scale = 1/real(mx*my, dp)
        !$omp parallel do default(shared) private(i, a, b, c, tr, det, disc, l1, l2) schedule(static) &
        !$omp if(size(prec%mxx) > omp_min_elements)
        do k = 1, my
            do i = 1, mx/2 + 1
                a = prec%mxx(i, k); b = prec%mxy(i, k); c = prec%myy(i, k)
                tr = a + c; det = a*c - b*b
                disc = sqrt(0.25_dp*(a - c)**2 + b**2)
                l1 = 0.5_dp*tr + disc; l2 = 0.5_dp*tr - disc
                if (l2 >= floor_) then
                    prec%mxx(i, k) = c/det*scale
                    prec%myy(i, k) = a/det*scale
                    prec%mxy(i, k) = -b/det*scale
                else
                    ! floor the eigenvalues: M = Σ v vᵀ / max(λ, floor)
                    call floored_inverse(a, b, c, max(l1, floor_), max(l2, floor_), scale, prec%mxx(i, k), &
                        prec%mxy(i, k), prec%myy(i, k))
                end if
            end do
        end do
        !$omp end parallel do
        ! the products run on circulant_size (2n unless FFTW transforms 2n slowly): the same
        ! Toeplitz operator there (its central coefficients), by one more pair of transforms
        if (circulant_size(nx) /= mx .or. circulant_size(ny) /= my) then
            call resize_symbol(prec%mxx); call resize_symbol(prec%mxy); call resize_symbol(prec%myy)
        end if
    contains
        !> sym (real, scaled by 1/(mx·my), on the 2nx×2ny circulant) ← the symbol on the
        !! circulant_size circulant of the block Toeplitz operator it acts as on the grid: the
        !! coefficients for offsets −(n−1)…n−1 of the inverse transform, zero elsewhere.
        subroutine resize_symbol(sym)
            real(dp), allocatable, intent(inout) :: sym(:, :)
            real(dp), allocatable :: r2(:, :), rm(:, :)
            complex(dp), allocatable :: c2(:, :), cm(:, :)
            type(c_ptr) :: pb, pf
            integer :: nxm, nym, jj, j2, jm
            nxm = circulant_size(nx); nym = circulant_size(ny)
            allocate (r2(mx, my), c2(mx/2 + 1, my), rm(nxm, nym), cm(nxm/2 + 1, nym))
            !$omp critical (fc_fftw_planner)
            pb = fftw_plan_dft_c2r_2d(int(my, c_int), int(mx, c_int), c2, r2, FFTW_ESTIMATE)
            pf = fftw_plan_dft_r2c_2d(int(nym, c_int), int(nxm, c_int), rm, cm, FFTW_ESTIMATE)
            !$omp end critical (fc_fftw_planner)
            c2 = cmplx(sym, 0.0_dp, dp)
            call fftw_execute_dft_c2r(pb, c2, r2)       ! the coefficients (sym holds 1/(mx·my))
            rm = 0
            do jj = -(ny - 1), ny - 1
                j2 = jj + 1; if (jj < 0) j2 = jj + my + 1
                jm = jj + 1; if (jj < 0) jm = jj + nym + 1
                rm(1:nx, jm) = r2(1:nx, j2)
                if (nx > 1) rm(nxm - nx + 2:nxm, jm) = r2(mx - nx + 2:mx, j2)
            end do
            call fftw_execute_dft_r2c(pf, rm, cm)
            !$omp critical (fc_fftw_planner)
            call fftw_destroy_plan(pb); call fftw_destroy_plan(pf)
            !$omp end critical (fc_fftw_planner)
            deallocate (sym)
            allocate (sym, source=real(cm, dp)/real(nxm*nym, dp))
        end subroutine resize_symbol
    end subroutine build_block_inverse

    !> Inverse of the symmetric 2×2 matrix [a b; b c] with its eigenvalues replaced by
    !! l1 ≥ l2 > 0, times `scale`.
    pure subroutine floored_inverse(a, b, c, l1, l2, scale, mxx, mxy, myy)
        real(dp), intent(in) :: a, b, c, l1, l2, scale
        real(dp), intent(out) :: mxx, mxy, myy
        real(dp) :: vx, vy, nrm, e1
        ! eigenvector of the larger eigenvalue of [a b; b c]
        e1 = 0.5_dp*(a + c) + sqrt(0.25_dp*(a - c)**2 + b**2)
        if (abs(b) > 0) then
            vx = b; vy = e1 - a
        else if (a >= c) then
            vx = 1; vy = 0
        else
            vx = 0; vy = 1
        end if
        nrm = hypot(vx, vy)
        vx = vx/nrm; vy = vy/nrm
        ! M = v vᵀ/l1 + w wᵀ/l2 with w = (−vy, vx)
        mxx = scale*(vx*vx/l1 + vy*vy/l2)
        myy = scale*(vy*vy/l1 + vx*vx/l2)
        mxy = scale*(vx*vy/l1 - vx*vy/l2)
    end subroutine floored_inverse

end module fc_tangprec
