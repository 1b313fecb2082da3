!> Input limits shared by the batch driver and the flat API (doc/reliability.md).
!!
!! Every number a user gives is checked against a finite range before it is used: a value
!! outside the range is not a contact problem this package can solve in double precision
!! (it would overflow, underflow to a meaningless result, or cost hours), so it is
!! rejected with a message naming the value and the limit.  NaN and ±Inf are tested with
!! `ieee_is_finite` before any comparison, so validation never raises a floating-point
!! exception (the sanitizer run traps on invalid operations).
!!
!! Units: mm, N, N/mm², rad (as everywhere in the package).
module fc_limits
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fc_kinds, only: dp, i8
    implicit none
    private

    real(dp), parameter, public :: max_length = 1.0e6_dp         !! |coordinate|, |approach|, |shift|, |gap| [mm]
    real(dp), parameter, public :: min_radius = 1.0e-6_dp        !! smallest radius of curvature > 0 [mm]
    !> smallest cylinder length and wavelength > 0 [mm]: the grid's smallest element size
    !! (fc_geometry's min_element_size); below it, lengths near the smallest double overflowed
    !! the line load Fn/length and the phase 2πx/λ
    real(dp), parameter, public :: min_length = 1.0e-9_dp
    real(dp), parameter, public :: max_radius = 1.0e8_dp         !! largest radius of curvature [mm] (0: flat);
        !! with min_radius it bounds the curvature ratio to 1e14, the thinnest Hertz ellipse
        !! (1 − e² ≥ 4.4e-16) that double precision resolves
    real(dp), parameter, public :: min_modulus = 1.0e-6_dp       !! smallest shear modulus [N/mm²]
    real(dp), parameter, public :: max_force = 1.0e15_dp         !! |Fn|, |Fx|, |Fy| [N]
    real(dp), parameter, public :: min_force = 1.0e-12_dp        !! smallest prescribed Fn [N]
    real(dp), parameter, public :: max_friction = 100.0_dp       !! coefficient of friction μ
    real(dp), parameter, public :: min_friction = 1.0e-12_dp     !! smallest μ > 0 (0 is frictionless; below: denormal bounds)
    real(dp), parameter, public :: max_spin = 1.0e3_dp           !! |φ| [rad/mm]
    real(dp), parameter, public :: max_creepage = 1.0e3_dp       !! |ξ|, |η| of steady or transient rolling [-]
    !> smallest kinetic coefficient of friction of steady rolling when the static one is > 0
    !! (slip without friction has no traction direction); as the smallest positive μ accepted
    real(dp), parameter, public :: min_mu_kinetic = 1.0e-12_dp
    integer, parameter, public :: max_cases = 10000              !! cases in one namelist file
    integer(i8), parameter, public :: max_grid_elements = 4096_i8*4096_i8  !! nx·ny of a serial grid (given or automatic)
    integer, parameter, public :: max_modes = 4096               !! m_modes, n_modes of a rough surface
    integer, parameter, public :: max_mode_pairs = 65536         !! m_modes·n_modes (mode tables: 24 bytes each)
    integer(i8), parameter, public :: max_mode_work = 2_i8**32   !! m_modes·n_modes·(nx + ny) (rough-surface cost)
    integer, parameter, public :: max_smoothing = 100            !! ν1, ν2 of a multigrid cycle
    integer, parameter, public :: max_line_length = 4000         !! characters per line of a case file
    integer, parameter, public :: max_file_chars = 16*1024*1024  !! characters of a case file

    public :: real_in_range, fmt_limit

contains

    !> True when x is finite and lo ≤ x ≤ hi (no comparison is made with a NaN or Inf).
    elemental logical function real_in_range(x, lo, hi)
        real(dp), intent(in) :: x, lo, hi
        real_in_range = .false.
        if (.not. ieee_is_finite(x)) return
        real_in_range = x >= lo .and. x <= hi
    end function real_in_range

    !> Short text of a limit for messages ('1e+06').
    function fmt_limit(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=16) :: buf
        write (buf, '(es9.1e2)') x
        s = trim(adjustl(buf))
    end function fmt_limit

end module fc_limits
