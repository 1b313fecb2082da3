!> LAPACK, declared once: the interfaces of the routines fastcontact calls and wrappers
!! that check `info` and report a failure through stat/errmsg (never silently).
!!
!! Only small dense systems go to LAPACK: the coarsest multigrid grid, and the spectra
!! of smoother iteration matrices on small grids (research diagnostics and tests).
module fc_lapack
    use fc_kinds, only: dp
    use fc_errors, only: FC_ERR_SHAPE, FC_ERR_INTERNAL
    implicit none
    private

    interface
        !> Cholesky solve A X = B, A symmetric positive definite.
        subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: dp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: info
        end subroutine dposv
        !> Eigenvalues (and optionally eigenvectors) of a general real matrix.
        subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
            import :: dp
            character(len=1), intent(in) :: jobvl, jobvr
            integer, intent(in) :: n, lda, ldvl, ldvr, lwork
            real(dp), intent(inout) :: a(lda, *)
            real(dp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
            integer, intent(out) :: info
        end subroutine dgeev
        !> Cholesky factorisation of a symmetric positive definite matrix.
        subroutine dpotrf(uplo, n, a, lda, info)
            import :: dp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotrf
        !> Eigenvalues (and optionally eigenvectors) of a symmetric matrix.
        subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
            import :: dp
            character(len=1), intent(in) :: jobz, uplo
            integer, intent(in) :: n, lda, lwork
            real(dp), intent(inout) :: a(lda, *)
            real(dp), intent(out) :: w(*), work(*)
            integer, intent(out) :: info
        end subroutine dsyev
    end interface

    public :: dposv, dgeev, dpotrf, dsyev
    public :: solve_spd, eigenvalues_general

contains

    !> Solve A x = b (one or more right-hand sides, the columns of b) for a symmetric
    !! positive definite A by Cholesky (dposv).  On return `a` holds the factor and `b` the
    !! solution.  stat ≠ 0 when A is not positive definite (to working precision) or an
    !! argument is invalid; `b` is then not a solution.
    subroutine solve_spd(a, b, stat, errmsg)
        real(dp), intent(inout) :: a(:, :)
        real(dp), intent(inout) :: b(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: n, info
        stat = 0; errmsg = ''
        n = size(a, 1)
        if (size(a, 2) /= n .or. size(b, 1) /= n) then
            stat = FC_ERR_SHAPE
            write (errmsg, '(a,i0,a,i0,a,i0,a)') 'solve_spd: matrix ', size(a, 1), 'x', size(a, 2), &
                ' and right-hand side of length ', size(b, 1), ' do not match'
            return
        end if
        if (n == 0) return
        call dposv('U', n, size(b, 2), a, n, b, n, info)
        call check_info('dposv', info, n, stat, errmsg)
    end subroutine solve_spd

    !> Eigenvalues wr + i·wi of a general real n×n matrix (dgeev, no eigenvectors).
    !! `a` is destroyed.
    subroutine eigenvalues_general(a, wr, wi, stat, errmsg)
        real(dp), intent(inout) :: a(:, :)
        real(dp), allocatable, intent(out) :: wr(:), wi(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), allocatable :: work(:)
        real(dp) :: vl(1, 1), vr(1, 1), query(1)
        integer :: n, info
        stat = 0; errmsg = ''
        n = size(a, 1)
        if (size(a, 2) /= n) then
            stat = FC_ERR_SHAPE
            write (errmsg, '(a,i0,a,i0,a)') 'eigenvalues_general: matrix ', size(a, 1), 'x', size(a, 2), ' is not square'
            return
        end if
        allocate (wr(n), wi(n))
        if (n == 0) return
        call dgeev('N', 'N', n, a, n, wr, wi, vl, 1, vr, 1, query, -1, info)
        call check_info('dgeev (workspace query)', info, n, stat, errmsg)
        if (stat /= 0) return
        allocate (work(max(int(query(1)), 4*n)))
        call dgeev('N', 'N', n, a, n, wr, wi, vl, 1, vr, 1, work, size(work), info)
        call check_info('dgeev', info, n, stat, errmsg)
    end subroutine eigenvalues_general

    !> Translate a LAPACK `info` into stat/errmsg.
    subroutine check_info(routine, info, n, stat, errmsg)
        character(len=*), intent(in) :: routine
        integer, intent(in) :: info, n
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (info == 0) return
        stat = FC_ERR_INTERNAL   ! a numerical failure of a routine the caller gave a valid matrix
        if (info < 0) then
            write (errmsg, '(a,i0,a,i0,a)') 'LAPACK '//routine//': argument ', -info, ' is invalid (n = ', n, ')'
        else if (routine == 'dposv') then
            write (errmsg, '(a,i0,a,i0,a,i0,a)') 'LAPACK dposv: the leading minor of order ', info, ' of the ', n, 'x', &
                n, ' matrix is not positive definite'
        else
            write (errmsg, '(a,i0,a,i0,a)') 'LAPACK '//routine//': no convergence, info = ', info, ' (n = ', n, ')'
        end if
    end subroutine check_info

end module fc_lapack
