!> Suite `operators`: LAPACK error reporting (fc_lapack) and the lifetime of the FFT
!! operators (fc_influence, fc_norm, fc_tangcg): copies, destruction, shared transforms.
module test_operators
    use fc_kinds, only: dp
    use fc_lapack, only: solve_spd, eigenvalues_general
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
            new_unittest('lapack_eigenvalues', test_eigenvalues) ]
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

end module test_operators
