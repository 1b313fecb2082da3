!> Shared pieces of the steady rolling solvers (module [[fc_rolling]]): the settings, loading
!! and case types (re-exported from [[fc_rolling_types]]), the convective difference of the steady slip, the rigid creepage, the
!! traction-change criterion (thesis eq. 4.49), the diagonal of the steady operator and the
!! final status of a solve.
module fc_rolling_base
    use fc_kinds
    use fc_rolling_types, only: fc_rolling_settings, fc_rolling_loading, fc_rolling_case
    use fc_geometry, only: fc_grid
    use fc_tangcg_operator, only: fc_tangential_operator
    use fc_tangcg_types, only: fc_tangential_result, EL_ADHESION, EL_SLIP
    use fc_threads, only: omp_min_elements
    !$ use omp_lib, only: omp_get_max_threads, omp_in_parallel
    implicit none
    private

    ! the value types live in [[fc_rolling_types]] (below the orchestrator's types)
    public :: fc_rolling_settings, fc_rolling_loading, fc_rolling_case

    public :: convective_difference, rigid_creepage, steady_diagonal, rolling_summary, steady_dissipation
    public :: dot, pdot, paxpy, pdivide

    !> A reference solver of steady rolling ('march', 'steadygs'): the tractions res%px, res%py
    !! (the start on entry) for the rigid slip plus offset (wx, wy), the pressure pn with its
    !! static and kinetic traction bounds gs, gk [N/mm²] and μs (the march's one coefficient).
    !! [[fc_rolling]] takes it as an argument, so that the fast solver does not depend on the
    !! references; [[fc_rolling_refsolvers]] has the package's ([[reference_solver]]), which
    !! the orchestrator passes.
    abstract interface
        subroutine rolling_reference_solver(top, pn, mu, gs, gk, wx, wy, settings, res, stat, errmsg)
            import :: dp, fc_tangential_operator, fc_rolling_settings, fc_tangential_result
            type(fc_tangential_operator), intent(inout) :: top
            real(dp), intent(in) :: pn(:, :), mu, gs(:, :), gk(:, :), wx(:, :), wy(:, :)
            type(fc_rolling_settings), intent(in) :: settings
            type(fc_tangential_result), intent(inout) :: res
            integer, intent(out) :: stat
            character(len=*), intent(out) :: errmsg
        end subroutine rolling_reference_solver
    end interface
    public :: rolling_reference_solver

contains

    !> d_i = (f_i − f_{i+1})/δx along x with f_{nx+1} = 0: the convective part of the steady
    !! slip (material in front of the grid is undeformed).
    pure subroutine convective_difference(f, dx, d)
        real(dp), intent(in) :: f(:, :)
        real(dp), intent(in) :: dx
        real(dp), intent(out) :: d(:, :)
        integer :: nx
        nx = size(f, 1)
        d(1:nx - 1, :) = (f(1:nx - 1, :) - f(2:nx, :))/dx
        d(nx, :) = f(nx, :)/dx
    end subroutine convective_difference

    !> Rigid creepage w_I = [ξ − φ·y_I, η + φ·x_I].
    pure subroutine rigid_creepage(grid, xi, eta, phi, wx, wy)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: xi, eta, phi
        real(dp), intent(out) :: wx(:, :), wy(:, :)
        integer :: i, j
        do j = 1, grid%ny
            do i = 1, grid%nx
                wx(i, j) = xi - phi*grid%y(j)
                wy(i, j) = eta + phi*grid%x(i)
            end do
        end do
    end subroutine rigid_creepage

    !> Diagonal (dxx, dyy) of the steady operator s ← (A p − (A p)_{+x})/δx:
    !! (A_II − A_{I+x,I})/δx per component (A^xy vanishes on the x axis).
    subroutine steady_diagonal(top, dxx, dyy)
        type(fc_tangential_operator), intent(in) :: top
        real(dp), intent(out) :: dxx, dyy
        dxx = top%a_xx%kernel(0, 0); dyy = top%a_yy%kernel(0, 0)
        if (top%grid%nx > 1) then
            dxx = dxx - top%a_xx%kernel(1, 0); dyy = dyy - top%a_yy%kernel(1, 0)
        end if
        dxx = dxx/top%grid%dx; dyy = dyy/top%grid%dx
    end subroutine steady_diagonal

    !> Forces, moment and element counts.
    subroutine rolling_summary(grid, res)
        type(fc_grid), intent(in) :: grid
        type(fc_tangential_result), intent(inout) :: res
        integer :: i, j
        res%fx = sum(res%px)*grid%area()
        res%fy = sum(res%py)*grid%area()
        res%mz = 0
        do j = 1, grid%ny
            do i = 1, grid%nx
                res%mz = res%mz + (grid%x(i)*res%py(i, j) - grid%y(j)*res%px(i, j))
            end do
        end do
        res%mz = res%mz*grid%area()
        res%nadh = count(res%state == EL_ADHESION)
        res%nslip = count(res%state == EL_SLIP)
        res%ncon = res%nadh + res%nslip
    end subroutine rolling_summary

    !> Frictional dissipation of a steady rolling solution per mm rolled [N] (the wear number
    !! Tγ): −Σ p·ŝ·δx·δy with the slip velocity ŝ = w + (u_{I−x} − u_{I+x})/(2δx), u = A·p +
    !! offset (`res%ux`, `res%uy` hold A·p), by the central difference where the solver's
    !! slip (`res%sx`, `res%sy`) has the upwind one.  The upwind slip's sum is O(h) smaller:
    !! the first-order difference dissipates −Σ p·(u_I − u_{I+x})/δx ≥ 0 of its own where
    !! the continuum's ∫ p·∂(A p)/∂x vanishes (A symmetric and translation invariant), so the
    !! central one converges to the same limit as O(h²) (doc/rolling.md, "Frictional
    !! dissipation").  At the trailing column the difference is one-sided; ahead of the grid
    !! the material is undeformed (u = 0), as in the solver.
    pure real(dp) function steady_dissipation(grid, res, offset_x, offset_y) result(d)
        type(fc_grid), intent(in) :: grid
        type(fc_tangential_result), intent(in) :: res
        real(dp), intent(in) :: offset_x(:, :), offset_y(:, :)  !! known displacements, e.g. A^xz·pn [mm]
        real(dp) :: cx, cy, wx, wy, behind_x, behind_y, ahead_x, ahead_y, scale
        integer :: i, j, nx
        d = 0
        if (.not. (allocated(res%ux) .and. allocated(res%uy) .and. allocated(res%px) .and. allocated(res%py))) return
        nx = grid%nx
        do j = 1, grid%ny
            do i = 1, nx
                if (res%px(i, j) == 0 .and. res%py(i, j) == 0) cycle
                ahead_x = 0; ahead_y = 0
                if (i < nx) then
                    ahead_x = res%ux(i + 1, j) + offset_x(i + 1, j); ahead_y = res%uy(i + 1, j) + offset_y(i + 1, j)
                end if
                if (i > 1) then
                    behind_x = res%ux(i - 1, j) + offset_x(i - 1, j); behind_y = res%uy(i - 1, j) + offset_y(i - 1, j)
                    scale = 2*grid%dx
                else
                    behind_x = res%ux(i, j) + offset_x(i, j); behind_y = res%uy(i, j) + offset_y(i, j)
                    scale = grid%dx
                end if
                cx = (behind_x - ahead_x)/scale; cy = (behind_y - ahead_y)/scale
                wx = res%xi - res%phi*grid%y(j); wy = res%eta + res%phi*grid%x(i)
                d = d - (res%px(i, j)*(wx + cx) + res%py(i, j)*(wy + cy))
            end do
        end do
        d = d*grid%area()
    end function steady_dissipation

    !> Dot product of two contiguous vectors with four partial sums: the Krylov solver's
    !! Gram–Schmidt is dominated by its dot products, and a single running sum serialises
    !! on the addition latency.
    pure real(dp) function dot(a, b, n)
        integer, intent(in) :: n
        real(dp), intent(in) :: a(n), b(n)
        real(dp) :: s1, s2, s3, s4
        integer :: i, m
        s1 = 0; s2 = 0; s3 = 0; s4 = 0
        m = n - mod(n, 4)
        do i = 1, m, 4
            s1 = s1 + a(i)*b(i)
            s2 = s2 + a(i + 1)*b(i + 1)
            s3 = s3 + a(i + 2)*b(i + 2)
            s4 = s4 + a(i + 3)*b(i + 3)
        end do
        do i = m + 1, n
            s1 = s1 + a(i)*b(i)
        end do
        dot = (s1 + s2) + (s3 + s4)
    end function dot


    !> Threads for a vector operation of n elements: 1 below [[fc_threads:omp_min_elements]], inside a
    !! parallel region or with one thread (then the serial code runs unchanged).
    integer function vector_threads(n) result(nt)
        integer, intent(in) :: n
        nt = 1
        !$ if (n > omp_min_elements .and. .not. omp_in_parallel()) nt = min(omp_get_max_threads(), 64)
    end function vector_threads

    !> [[dot]] with threads: each thread takes one contiguous block (four partial sums
    !! each), the block sums are added in block order, so the result depends on the thread
    !! count by rounding only; one thread gives [[dot]] exactly.
    real(dp) function pdot(a, b, n) result(s)
        integer, intent(in) :: n
        real(dp), intent(in) :: a(n), b(n)
        real(dp) :: part(64)
        integer :: nt, t, lo, hi
        nt = vector_threads(n)
        if (nt == 1) then
            s = dot(a, b, n); return
        end if
        !$omp parallel do num_threads(nt) default(shared) private(lo, hi) schedule(static, 1)
        do t = 1, nt
            lo = int((int(t - 1, i8)*n)/nt) + 1; hi = int((int(t, i8)*n)/nt)
            part(t) = dot(a(lo:hi), b(lo:hi), hi - lo + 1)
        end do
        !$omp end parallel do
        s = sum(part(1:nt))
    end function pdot

    !> y ← y + α·x over n elements, threaded above [[fc_threads:omp_min_elements]].
    subroutine paxpy(alpha, x, y, n)
        integer, intent(in) :: n
        real(dp), intent(in) :: alpha, x(n)
        real(dp), intent(inout) :: y(n)
        integer :: i
        !$omp parallel do default(shared) schedule(static) if(vector_threads(n) > 1)
        do i = 1, n
            y(i) = y(i) + alpha*x(i)
        end do
        !$omp end parallel do
    end subroutine paxpy

    !> y ← y/d over n elements, threaded above [[fc_threads:omp_min_elements]].
    subroutine pdivide(y, d, n)
        integer, intent(in) :: n
        real(dp), intent(in) :: d
        real(dp), intent(inout) :: y(n)
        integer :: i
        !$omp parallel do default(shared) schedule(static) if(vector_threads(n) > 1)
        do i = 1, n
            y(i) = y(i)/d
        end do
        !$omp end parallel do
    end subroutine pdivide

end module fc_rolling_base
