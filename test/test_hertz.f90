!> Suite `hertz`: analytic elliptic Hertz solution and rough-surface generation.
module test_hertz
    use fc_kinds, only: dp, pi
    use fc_hertz
    use fc_geometry
    use fc_testing
    implicit none
    private
    public :: collect_hertz

contains

    subroutine collect_hertz(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('elliptic_integrals', test_elliptic), &
            new_unittest('test_I_reference_numbers', test_reference), &
            new_unittest('cattaneo_sphere_numbers', test_sphere), &
            new_unittest('force_approach_roundtrip', test_roundtrip), &
            new_unittest('thin_ellipse_finite', test_thin_ellipse), &
            new_unittest('rough_surface_sigma_and_seed', test_rough), &
            new_unittest('grid_centres_and_profiles', test_grid), &
            new_unittest('table_and_wavy_geometry', test_table) ]
    end subroutine collect_hertz

    !> K(m), E(m) against tabulated values (Abramowitz & Stegun 17.3, 15 digits).
    subroutine test_elliptic(error)
        type(error_type), allocatable, intent(out) :: error
        real(dp) :: k, e
        call elliptic_ke(0.0_dp, k, e)
        call check(error, k, pi/2, 'K(0)', rel=1e-15_dp)
        call check(error, e, pi/2, 'E(0)', rel=1e-15_dp)
        call elliptic_ke(0.5_dp, k, e)
        call check(error, k, 1.854074677301372_dp, 'K(0.5)', rel=1e-14_dp)
        call check(error, e, 1.350643881047675_dp, 'E(0.5)', rel=1e-14_dp)
        call elliptic_ke(0.99_dp, k, e)
        call check(error, k, 3.695637362989875_dp, 'K(0.99)', rel=1e-13_dp)
        call check(error, e, 1.015993545025224_dp, 'E(0.99)', rel=1e-13_dp)
    end subroutine test_elliptic

    !> Test I (thesis §2.5.1): a = 6.0020, b = 3.9992, p0 = 1631.2, F = 82004 (rounded as given).
    subroutine test_reference(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_hertz_solution) :: s
        s = hertz_from_approach(1/600.0_dp, 1/326.0_dp, 82000/0.72_dp, 0.1091_dp)
        call check(error, s%a, 6.0020_dp, 'a', abs=0.5e-4_dp)
        call check(error, s%b, 3.9992_dp, 'b', abs=0.5e-4_dp)
        call check(error, s%p0, 1631.2_dp, 'p0', abs=0.05_dp)
        call check(error, s%fn, 82004.0_dp, 'F', abs=0.5_dp)
        call check(error, s%pressure(0.0_dp, 0.0_dp), s%p0, 'p(0,0) = p0', rel=1e-15_dp)
        call check(error, s%pressure(6.1_dp, 0.0_dp), 0.0_dp, 'p outside ellipse', abs=0.0_dp)
    end subroutine test_reference

    !> Cattaneo sphere (thesis §4.4): R = 50, G = 200, ν = 0.42, Fn = 9.1954 → a = 1, δ = 0.02, p0 = 4.3905.
    subroutine test_sphere(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_hertz_solution) :: s
        s = hertz_from_force(0.01_dp, 0.01_dp, 200/0.58_dp, 9.1954_dp)
        call check(error, s%a, 1.0_dp, 'a', abs=1e-4_dp)
        call check(error, s%b, 1.0_dp, 'b', abs=1e-4_dp)
        call check(error, s%approach, 0.02_dp, 'delta', abs=1e-6_dp)
        call check(error, s%p0, 4.3905_dp, 'p0', abs=1e-4_dp)
    end subroutine test_sphere

    !> Prescribed force and prescribed approach are inverse to each other; axes swap
    !! when Ry > Rx.
    subroutine test_roundtrip(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_hertz_solution) :: s1, s2, s3
        s1 = hertz_from_approach(1/600.0_dp, 1/326.0_dp, 1.0e5_dp, 0.05_dp)
        s2 = hertz_from_force(1/600.0_dp, 1/326.0_dp, 1.0e5_dp, s1%fn)
        call check(error, s2%approach, 0.05_dp, 'approach round trip', rel=1e-12_dp)
        s3 = hertz_from_approach(1/326.0_dp, 1/600.0_dp, 1.0e5_dp, 0.05_dp)
        call check(error, s3%a, s1%b, 'swapped axes a', rel=1e-12_dp)
        call check(error, s3%b, s1%a, 'swapped axes b', rel=1e-12_dp)
        call check(error, s3%fn, s1%fn, 'swapped axes F', rel=1e-12_dp)
    end subroutine test_roundtrip

    !> Eq. (2.16) sets R(0,0) = σ²; sampled on a grid finer than the highest mode
    !! (nx > 2M, ny > 2N) the discrete mean is 0 and the discrete variance is exactly σ².
    !! The same seed gives the same surface; another seed another one.
    !> Curvature ratios up to 1e14 (the driver's radius limits) give a finite ellipse whose
    !! force and approach round-trip; beyond, the ellipse is clipped, still finite (no 1/(1−e²)
    !! with e² = 1).
    subroutine test_thin_ellipse(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_hertz_solution) :: s, t
        real(dp), parameter :: ratios(3) = [1.0e8_dp, 1.0e14_dp, 1.0e30_dp]
        real(dp) :: ratio
        character(len=12) :: r
        integer :: k
        do k = 1, 3
            ratio = ratios(k)
            write (r, '(es12.3)') ratio
            s = hertz_from_approach(0.5_dp, 0.5_dp/ratio, 1000.0_dp, 1.0e-3_dp)
            call check(error, s%a > 0 .and. s%b > s%a .and. s%b < huge(1.0_dp) .and. s%p0 > 0 .and. &
                s%p0 < huge(1.0_dp) .and. s%fn > 0 .and. s%fn < huge(1.0_dp), 'ellipse not finite at ratio '//r)
            if (allocated(error)) return
            if (ratio > 1.0e15_dp) cycle
            t = hertz_from_force(0.5_dp, 0.5_dp/ratio, 1000.0_dp, s%fn)
            call check(error, abs(t%approach - 1.0e-3_dp) < 1.0e-9_dp, 'force/approach round trip at ratio '//r)
            if (allocated(error)) return
        end do
    end subroutine test_thin_ellipse

    subroutine test_rough(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        type(fc_rough_params) :: par
        real(dp) :: z(64, 64), z2(64, 64)
        integer :: stat
        character(len=200) :: msg
        call make_grid(grid, 64, 64, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, stat, msg)
        call rough_heights(grid, par, z)
        call check(error, sum(z)/size(z), 0.0_dp, 'mean height', abs=1e-14_dp)
        call check(error, sqrt(sum(z**2)/size(z)), par%sigma, 'sampled sigma', rel=1e-12_dp)
        call rough_heights(grid, par, z2)
        call check(error, all(z == z2), 'same seed reproduces the surface')
        par%seed = 7
        call rough_heights(grid, par, z2)
        call check(error, maxval(abs(z - z2)) > 0.01_dp, 'another seed gives another surface')
        ! the most negative seed: |seed| is taken in 64 bits (in 32 bits it overflowed, which
        ! the sanitizer run reports as undefined behaviour)
        par%seed = -huge(1) - 1
        call rough_heights(grid, par, z)
        call check(error, sqrt(sum(z**2)/size(z)), par%sigma, 'seed = -2^31: sampled sigma', rel=1e-12_dp)
        call check(error, maxval(abs(z - z2)) > 0.01_dp, 'seed = -2^31 gives another surface than seed 7')
    end subroutine test_rough

    !> Element centres at xmin + (i−½)dx (doc/conventions.md) and the quadratic profile.
    subroutine test_grid(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        real(dp), allocatable :: h(:, :)
        integer :: stat
        character(len=200) :: msg
        call make_grid(grid, 4, 2, -2.0_dp, 2.0_dp, 0.0_dp, 1.0_dp, stat, msg)
        call check(error, grid%x(1), -1.5_dp, 'x(1)', abs=1e-15_dp)
        call check(error, grid%y(2), 0.75_dp, 'y(2)', abs=1e-15_dp)
        h = quadratic_gap(grid, 2.0_dp, 0.0_dp)
        call check(error, h(1, 1), 1.5_dp**2/4, 'h = x²/(2 rx), flat in y', rel=1e-15_dp)
        call make_grid(grid, 0, 2, -2.0_dp, 2.0_dp, 0.0_dp, 1.0_dp, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'nx') > 0, 'nx = 0 rejected: '//trim(msg))
        call make_grid(grid, 2, 2, 2.0_dp, 2.0_dp, 0.0_dp, 1.0_dp, stat, msg)
        call check(error, stat /= 0, 'empty extent rejected')
    end subroutine test_grid

    !> Table geometry: nx·ny values, x fastest, comments skipped; a short or malformed
    !! file is an error naming the file.  Wavy profile: h = A(1 − cos cos).
    subroutine test_table(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        real(dp) :: h(3, 2)
        real(dp), allocatable :: w(:, :)
        integer :: stat, unit
        character(len=200) :: msg
        character(len=*), parameter :: fname = 'build/test_table_geometry.txt'
        call make_grid(grid, 3, 2, 0.0_dp, 3.0_dp, 0.0_dp, 2.0_dp, stat, msg)
        open (newunit=unit, file=fname, status='replace', action='write')
        write (unit, '(a)') '# undeformed distance, x fastest', '0.1 0.2 0.3', '', '0.4, 0.5', '0.6'
        close (unit)
        call read_gap_table(fname, grid, h, stat, msg)
        call check(error, stat == 0, 'table read: '//trim(msg))
        call check(error, h(3, 1), 0.3_dp, 'h(3,1)', abs=1e-15_dp)
        call check(error, h(1, 2), 0.4_dp, 'h(1,2)', abs=1e-15_dp)
        open (newunit=unit, file=fname, status='replace', action='write')
        write (unit, '(a)') '0.1 0.2 0.3 0.4 0.5'
        close (unit)
        call read_gap_table(fname, grid, h, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'expected nx*ny = 6') > 0, 'short table rejected: '//trim(msg))
        open (newunit=unit, file=fname, status='replace', action='write')
        write (unit, '(a)') '0.1 0.2 abc 0.4 0.5 0.6'
        close (unit)
        call read_gap_table(fname, grid, h, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'line 1') > 0, 'malformed table rejected: '//trim(msg))
        open (newunit=unit, file=fname, status='old')
        close (unit, status='delete')
        call read_gap_table('build/no_such_file.txt', grid, h, stat, msg)
        call check(error, stat /= 0 .and. index(msg, 'no_such_file') > 0, 'missing file rejected')
        w = wavy_gap(grid, 0.01_dp, 2.0_dp, 0.0_dp)
        call check(error, w(1, 1), 0.01_dp*(1 - cos(pi*0.5_dp)), 'wavy h(1,1)', abs=1e-15_dp)
    end subroutine test_table

end module test_hertz
