!> Threaded reductions over grid arrays, shared by the iterative solvers (BCCG, TangCG).
!!
!! Each is one OpenMP `parallel do` over the columns with a reduction, taken only for
!! arrays with more than [[fc_threads:omp_min_elements]] elements.  Serial (one thread, or a small
!! array) the sum runs in element order, exactly like the intrinsic `sum(a*b)`; with T threads
!! each thread sums a contiguous block of columns and the T partial sums are added, which
!! changes the result by rounding only (relative O(n·eps) at worst, in practice ~√n·eps).
module fc_vector_ops
    use fc_kinds, only: dp
    use fc_threads, only: omp_min_elements
    implicit none
    private

    public :: vdot, vsum

contains

    !> Σ a·b over all elements (the intrinsic `sum(a*b)`).
    function vdot(a, b) result(s)
        real(dp), intent(in), contiguous :: a(:, :), b(:, :)
        real(dp) :: s
        integer :: i, j
        s = 0
        !$omp parallel do default(shared) private(i) reduction(+:s) schedule(static) if(size(a) > omp_min_elements)
        do j = 1, size(a, 2)
            do i = 1, size(a, 1)
                s = s + a(i, j)*b(i, j)
            end do
        end do
        !$omp end parallel do
    end function vdot

    !> Σ a over all elements (the intrinsic `sum(a)`).
    function vsum(a) result(s)
        real(dp), intent(in), contiguous :: a(:, :)
        real(dp) :: s
        integer :: i, j
        s = 0
        !$omp parallel do default(shared) private(i) reduction(+:s) schedule(static) if(size(a) > omp_min_elements)
        do j = 1, size(a, 2)
            do i = 1, size(a, 1)
                s = s + a(i, j)
            end do
        end do
        !$omp end parallel do
    end function vsum

end module fc_vector_ops
