!> Research diagnostics of the multigrid smoothers (thesis §2.4.4, Fig. 2.6): the
!! spectrum of the smoother's iteration matrix on a small grid, by dense LAPACK.
module fc_fmg_diagnostics
    use fc_kinds
    use fc_geometry, only: fc_grid
    use fc_lapack, only: eigenvalues_general
    use fc_influence, only: fc_material, ic_kernel, IC_ZZ
    implicit none
    private

    public :: smoother_eigenvalues

contains

    !> Eigenvalues (wr + i·wi) of the iteration matrix I − W⁻¹A of an undamped or damped
    !! 'jacobi' (W = D/ω) or 'gs' (W = D/ω + L) smoother for A^zz on the whole of a small
    !! grid (dense, LAPACK dgeev; n ≤ 2048).  Thesis Fig. 2.6: Jacobi has one eigenvalue far
    !! below −1, GS has all |λ| < 1.
    subroutine smoother_eigenvalues(mat, grid, smoother, omega, wr, wi, stat, errmsg)
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        character(len=*), intent(in) :: smoother
        real(dp), intent(in) :: omega
        real(dp), allocatable, intent(out) :: wr(:), wi(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), allocatable :: kernel(:, :), a(:, :), w(:, :), r(:, :)
        integer :: n, i, j
        stat = 0; errmsg = ''
        n = grid%n()
        if (n > 2048) then
            stat = FC_ERR_UNSUPPORTED
            write (errmsg, '(a,i0,a)') 'smoother_eigenvalues: n = ', n, ' > 2048 (dense analysis)'; return
        end if
        call ic_kernel(IC_ZZ, mat, grid, kernel)
        allocate (a(n, n), w(n, n), r(n, n))
        do j = 1, n
            do i = 1, n
                a(i, j) = kernel(mod(i - 1, grid%nx) - mod(j - 1, grid%nx), (i - 1)/grid%nx - (j - 1)/grid%nx)
            end do
        end do
        w = 0
        select case (smoother)
        case ('jacobi')
            do i = 1, n
                w(i, i) = a(i, i)/omega
            end do
        case ('gs')
            do j = 1, n
                do i = j + 1, n
                    w(i, j) = a(i, j)
                end do
                w(j, j) = a(j, j)/omega
            end do
        case default
            stat = FC_ERR_VALUE; errmsg = "smoother_eigenvalues: smoother '"//trim(smoother)//"' is not 'jacobi' or 'gs'"; return
        end select
        ! R = I − W⁻¹A: solve W X = A (W lower triangular), R = I − X
        r = a
        call solve_lower(w, r)
        r = -r
        do i = 1, n
            r(i, i) = r(i, i) + 1
        end do
        call eigenvalues_general(r, wr, wi, stat, errmsg)
        if (stat /= 0) errmsg = 'smoother_eigenvalues: '//trim(errmsg)
    contains
        subroutine solve_lower(lw, x)
            real(dp), intent(in) :: lw(:, :)
            real(dp), intent(inout) :: x(:, :)
            integer :: ii
            do ii = 1, size(x, 1)
                if (ii > 1) x(ii, :) = x(ii, :) - matmul(lw(ii, 1:ii - 1), x(1:ii - 1, :))
                x(ii, :) = x(ii, :)/lw(ii, ii)
            end do
        end subroutine solve_lower
    end subroutine smoother_eigenvalues

end module fc_fmg_diagnostics
