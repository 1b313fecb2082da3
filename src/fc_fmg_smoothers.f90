!> Smoothers of the multigrid normal solver and the exact solve on the coarsest grid
!! (thesis §2.4.2, §2.4.4).
!!
!! * damped Gauss–Seidel (ω = 0.8 by default) acting on the contact set only
!!   (lexicographic order).  A is dense, so a sweep costs O(n_C·n) — O(n²) — as in the
!!   thesis; the rows are read from the BTTB kernel, never from a stored dense matrix;
!!   threads share each grid row's sums over the other rows (same result bit for bit);
!! * damped Jacobi, available only to demonstrate its failure (thesis Fig. 2.6);
!! * 'fft-rsm', the O(n log n) smoother beyond the thesis (its outlook §6.3): Richardson
!!   with the Toeplitz approximation M ≈ A⁻¹ (§3.3.1 in 2D) reduced to C and row-sum
!!   modified as in eq. (3.21);
!! * the coarsest grid (4×4 by default) is solved exactly with LAPACK (dposv) on the
!!   contact subset.
!!
!! Work units: a GS sweep counts as one product on its level (the thesis' convention), a
!! Jacobi sweep as one FFT product, an FFT+RSM sweep as two (A and M) plus one per cycle
!! and level for the row sums M·1_C.
module fc_fmg_smoothers
    use fc_kinds
    use fc_lapack, only: solve_spd
    use fc_threads, only: omp_min_elements, fc_thread_count
    use fc_fmg_levels, only: fc_fmg_settings, fc_fmg_hierarchy, fmg_level
    implicit none
    private

    public :: smooth, direct_solve

contains

    !> One smoothing sweep on level l.  A GS sweep counts as one product on that level (the
    !! thesis' convention), a Jacobi sweep as one FFT product, an FFT+RSM sweep as two (A and M).
    subroutine smooth(hier, l, settings, con, rhs, p, rs)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        integer, intent(in) :: l
        type(fc_fmg_settings), intent(in) :: settings
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(inout) :: p(:, :)
        real(dp), allocatable, intent(inout) :: rs(:, :)
        associate (lv => hier%lev(l))
            if (.not. allocated(lv%work)) allocate (lv%work(size(p, 1), size(p, 2), 2))
            select case (settings%smoother)
            case ('jacobi')
                call jacobi_sweep(lv, con, rhs, p, settings%omega)
                hier%work = hier%work + lv%cost
            case ('fft-rsm')
                if (.not. allocated(rs)) then
                    call rsm_rowsums(lv, con, rs)
                    hier%work = hier%work + lv%cost
                end if
                call fft_rsm_sweep(lv, con, rhs, p, rs, settings%rsm_floor)
                hier%work = hier%work + 2*lv%cost
            case default
                call gs_sweep(lv%op%kernel, con, rhs, p, settings%omega, lv%work(:, :, 1))
                hier%work = hier%work + lv%cost
            end select
        end associate
    end subroutine smooth

    !> Damped Gauss–Seidel on the contact set, lexicographic order (thesis §2.4.2).
    !! Row I of A is the kernel shifted to I; the sum runs over the bounding box of the
    !! contact set only (p = 0 elsewhere).  kernel(a,b) = kernel(−a,b) = kernel(a,−b).
    !! While row j is updated the other rows of p do not change, so their parts of row j's
    !! sums are computed first, each grid row by one thread, into `part`; the sequential
    !! sweep along row j adds them in row order with the row's own part: the same sums in
    !! the same order as element by element, whatever the thread count (bit for bit).
    subroutine gs_sweep(kernel, con, rhs, p, omega, part)
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: kernel(-(size(con, 1) - 1):, -(size(con, 2) - 1):)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(inout) :: p(:, :)
        real(dp), intent(in) :: omega
        real(dp), intent(inout) :: part(:, :)   !! work array, the grid's shape
        integer :: nx, ny, i, j, l, lo(size(con, 2)), hi(size(con, 2)), jlo, jhi
        real(dp) :: s, diag
        logical :: par
        nx = size(con, 1); ny = size(con, 2)
        jlo = ny + 1; jhi = 0
        do l = 1, ny
            lo(l) = nx + 1; hi(l) = 0
            do i = 1, nx
                if (con(i, l)) then
                    lo(l) = min(lo(l), i); hi(l) = i
                end if
            end do
            if (hi(l) > 0) then
                jlo = min(jlo, l); jhi = l
            end if
        end do
        diag = kernel(0, 0)
        par = fc_thread_count() > 1
        do j = jlo, jhi
            if (hi(j) < lo(j)) cycle
            ! one thread calls the loop outside a parallel region (no region per row)
            if (par .and. int(hi(j) - lo(j) + 1, i8)*nx*(jhi - jlo + 1) > omp_min_elements) then
                !$omp parallel default(shared)
                call other_rows()
                !$omp end parallel
            else
                call other_rows()
            end if
            do i = lo(j), hi(j)
                if (.not. con(i, j)) cycle
                s = 0
                do l = jlo, jhi
                    if (hi(l) < lo(l)) cycle
                    if (l == j) then
                        s = s + dot_product(kernel(lo(j) - i:hi(j) - i, 0), p(lo(j):hi(j), j))
                    else
                        s = s + part(i, l)
                    end if
                end do
                p(i, j) = p(i, j) + omega*(rhs(i, j) - s)/diag
            end do
        end do
    contains
        !> The parts of row j's sums from the other rows, the rows shared among the threads of
        !! an enclosing parallel region.
        subroutine other_rows()
            integer :: i, l
            !$omp do schedule(static)
            do l = jlo, jhi
                if (l == j .or. hi(l) < lo(l)) cycle
                do i = lo(j), hi(j)
                    if (con(i, j)) part(i, l) = dot_product(kernel(lo(l) - i:hi(l) - i, l - j), p(lo(l):hi(l), l))
                end do
            end do
            !$omp end do
        end subroutine other_rows
    end subroutine gs_sweep

    !> Damped Jacobi on the contact set (an FFT product per sweep).
    subroutine jacobi_sweep(lv, con, rhs, p, omega)
        type(fmg_level), intent(inout) :: lv
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(inout) :: p(:, :)
        real(dp), intent(in) :: omega
        real(dp) :: diag
        integer :: i, j
        associate (u => lv%work(:, :, 1))
            call lv%op%apply(p, u)
            diag = lv%op%kernel(0, 0)
            !$omp parallel do default(shared) private(i) schedule(static) if(size(p) > omp_min_elements)
            do j = 1, size(p, 2)
                do i = 1, size(p, 1)
                    if (con(i, j)) p(i, j) = p(i, j) + omega*(rhs(i, j) - u(i, j))/diag
                end do
            end do
            !$omp end parallel do
        end associate
    end subroutine jacobi_sweep

    !> FFT smoother with row-sum modification on the contact set (thesis eqs. 3.10, 3.21),
    !! undamped: p_C ← p_C + M̄ (rhs − A p)_C,  M̄ = M_CC − diag(sum(M_CC) − γ),
    !! γ = min row sum of M.  Beyond the thesis, M̄'s diagonal is floored at θ/A_ii: on the
    !! isolated contact spots of rough surfaces the row-sum shift removes almost all of the
    !! diagonal and the smoother stalls (measured: no convergence in 100 cycles at 128²
    !! with θ = 0).  `rs` holds sum(M_CC) = M·1_C (computed once per cycle and level).
    subroutine fft_rsm_sweep(lv, con, rhs, p, rs, theta)
        type(fmg_level), intent(inout) :: lv
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :), rs(:, :), theta
        real(dp), intent(inout) :: p(:, :)
        real(dp) :: mdiag
        integer :: i, j
        logical :: par
        par = size(p) > omp_min_elements
        associate (u => lv%work(:, :, 1), d => lv%work(:, :, 2))
            call lv%op%apply(p, u)
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, size(p, 2)
                do i = 1, size(p, 1)
                    if (con(i, j)) then
                        d(i, j) = rhs(i, j) - u(i, j)
                    else
                        d(i, j) = 0
                    end if
                end do
            end do
            !$omp end parallel do
            call lv%prec%apply(d, u)
            ! diagonal of M̄ = M_CC − diag(sum(M_CC) − γ), floored at θ/A_ii: on isolated
            ! contact elements (rough surfaces) the row-sum shift leaves almost no diagonal
            mdiag = lv%prec%kernel(0, 0) - theta/lv%op%kernel(0, 0)
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, size(p, 2)
                do i = 1, size(p, 1)
                    if (con(i, j)) p(i, j) = p(i, j) + u(i, j) - min(rs(i, j) - lv%gamma, mdiag)*d(i, j)
                end do
            end do
            !$omp end parallel do
        end associate
    end subroutine fft_rsm_sweep

    !> Row sums of M over the contact set, M·1_C (one product).
    subroutine rsm_rowsums(lv, con, rs)
        type(fmg_level), intent(inout) :: lv
        logical, intent(in) :: con(:, :)
        real(dp), allocatable, intent(out) :: rs(:, :)
        real(dp), allocatable :: one(:, :)
        allocate (rs(size(con, 1), size(con, 2)), one(size(con, 1), size(con, 2)))
        one = merge(1.0_dp, 0.0_dp, con)
        call lv%prec%apply(one, rs)
    end subroutine rsm_rowsums

    !> Exact solve of A_CC p_C = rhs_C on the coarsest level (LAPACK dposv).  A_CC is
    !! symmetric positive definite; a Cholesky failure (stat ≠ 0) leaves p = 0.
    subroutine direct_solve(lv, con, rhs, p, stat, errmsg)
        type(fmg_level), intent(in) :: lv
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(out) :: p(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer, allocatable :: ix(:), iy(:)
        real(dp), allocatable :: a(:, :), b(:, :)
        integer :: n, i, j, k
        stat = 0; errmsg = ''
        n = count(con)
        p = 0
        if (n == 0) return
        allocate (ix(n), iy(n), a(n, n), b(n, 1))
        k = 0
        do j = 1, size(con, 2)
            do i = 1, size(con, 1)
                if (con(i, j)) then
                    k = k + 1; ix(k) = i; iy(k) = j; b(k, 1) = rhs(i, j)
                end if
            end do
        end do
        do j = 1, n
            do i = 1, n
                a(i, j) = lv%op%kernel(ix(i) - ix(j), iy(i) - iy(j))
            end do
        end do
        call solve_spd(a, b, stat, errmsg)
        if (stat /= 0) then
            write (errmsg, '(a,i0,a,i0,a)') 'fmg coarsest-grid solve on ', size(con, 1), 'x', size(con, 2), ': ' &
                //trim(errmsg)
            return
        end if
        do k = 1, n
            p(ix(k), iy(k)) = b(k, 1)
        end do
    end subroutine direct_solve

end module fc_fmg_smoothers
