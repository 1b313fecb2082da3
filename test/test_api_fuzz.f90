!> Seeded random call sequences through the flat bind(C) API ([[fc_legacy]]).
!!
!! Several handles at once, every routine, values drawn from a vocabulary of good and bad
!! numbers (NaN, ±Inf, 0, negative, huge, denormal, sizes over the limits), small grids so
!! that a calculation takes milliseconds.  After every call: `ierr` is one of the documented
!! codes 0–7, a failing call leaves a non-empty message, a successful or not-converged
!! calculation gives finite forces and tractions with pn ≥ 0, the documented order errors
!! hold, and the number of live handles matches the handles the test holds.  Under
!! scripts/sanitize.sh (address/undefined sanitizers, bounds checks, FPE traps) the same
!! sequence also checks memory safety and that no validation computes with NaN/Inf.
!!
!! Deterministic: the seed is fixed (environment FC_API_FUZZ_SEED overrides it, and
!! FC_API_FUZZ_CALLS the number of calls); a failure message gives seed and call number.
module test_api_fuzz
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, ieee_negative_inf, &
        ieee_is_finite
    use fc_kinds, only: dp, i8
    use fc_testing, only: error_type, unittest_type, new_unittest, check
    use fc_legacy
    implicit none
    private
    public :: collect_api_fuzz

    integer, parameter :: nh = 3              !! handles held at once
    integer(i8) :: rng_state = 0
    real(dp) :: recorded(8)                 !! arguments drawn for the current call (failure trace)
    integer :: nrec = 0
    character(len=200) :: trace(0:47, nh) = ''  !! the last calls per handle slot: op, ierr, arguments
    integer :: ntrace(nh) = 0

contains

    subroutine collect_api_fuzz(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [new_unittest('random_call_sequences', random_call_sequences), &
                 new_unittest('documented_order_and_values', documented_order_and_values)]
    end subroutine collect_api_fuzz

    ! ---- small deterministic generator (MINSTD) --------------------------------------------

    !> Uniform integer in [lo, hi] from a MINSTD generator (Park–Miller, no integer overflow:
    !! 48271·(2³¹ − 1) < 2⁶³).
    integer function rand_int(lo, hi)
        integer, intent(in) :: lo, hi
        rng_state = modulo(48271_i8*rng_state, 2147483647_i8)
        rand_int = lo + int(modulo(rng_state, int(hi, i8) - int(lo, i8) + 1_i8))
    end function rand_int

    real(dp) function rand_unit()
        rand_unit = real(rand_int(0, 1000000), dp)/1.0e6_dp
    end function rand_unit

    !> A real: mostly a plausible value `typical` scaled, sometimes a hostile one.
    real(dp) function any_real(typical)
        real(dp), intent(in) :: typical
        real(dp) :: x
        select case (rand_int(1, 20))
        case (1); x = ieee_value(x, ieee_quiet_nan)
        case (2); x = ieee_value(x, ieee_positive_inf)
        case (3); x = ieee_value(x, ieee_negative_inf)
        case (4); x = 0
        case (5); x = -typical
        case (6); x = huge(1.0_dp)
        case (7); x = -huge(1.0_dp)
        case (8); x = tiny(1.0_dp)*0.5_dp     ! denormal
        case (9); x = 1.0e30_dp
        case default; x = typical*(0.5_dp + rand_unit())
        end select
        any_real = x
    end function any_real

    real(dp) function rec_real(typical)
        real(dp), intent(in) :: typical
        rec_real = any_real(typical)
        nrec = min(nrec + 1, size(recorded)); recorded(nrec) = rec_real
    end function rec_real

    integer function rec_int(typical)
        integer, intent(in) :: typical
        rec_int = any_int(typical)
        nrec = min(nrec + 1, size(recorded)); recorded(nrec) = rec_int
    end function rec_int

    integer function any_int(typical)
        integer, intent(in) :: typical
        select case (rand_int(1, 14))
        case (1); any_int = 0
        case (2); any_int = -1
        case (3); any_int = huge(0)
        case (4); any_int = -huge(0) - 1
        case (5); any_int = 4097
        case (6); any_int = 1000001
        case default; any_int = max(1, typical/2 + rand_int(0, max(1, typical)))
        end select
    end function any_int

    ! ---- the random sequence ----------------------------------------------------------------

    subroutine random_call_sequences(error)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: h(nh), ierr, nlive, nx, ny, k1, k2, k3
        integer :: call_no, ncalls, i, op, seed, n, ios, counts(0:7), last_calc(nh)
        real(c_double) :: fn, fx, fy, mz, a(4)
        real(c_double), allocatable :: pn(:), px(:), py(:), h0(:)
        integer(c_int), allocatable :: st(:)
        character(kind=c_char) :: buf(256)
        character(len=32) :: env
        character(len=200) :: where
        seed = 20151123; ncalls = 20000
        call get_environment_variable('FC_API_FUZZ_SEED', env, status=ios)
        if (ios == 0) read (env, *, iostat=ios) seed
        call get_environment_variable('FC_API_FUZZ_CALLS', env, status=ios)
        if (ios == 0) read (env, *, iostat=ios) ncalls
        rng_state = modulo(int(seed, i8)*7919_i8, 2147483646_i8) + 1_i8
        h = 0; counts = 0; last_calc = -1
        do i = 1, nh
            call fc_init(h(i), ierr)
        end do
        do call_no = 1, ncalls
            i = rand_int(1, nh)
            op = rand_int(1, 24)
            write (where, '(a,i0,a,i0,a,i0,a,i0)') 'seed ', seed, ', call ', call_no, ', op ', op, ', handle ', h(i)
            nrec = 0; ierr = FCL_OK
            select case (op)
            case (1)
                call fc_set_material(h(i), rec_real(82000.0_dp), rec_real(82000.0_dp), rec_real(0.28_dp), &
                    rec_real(0.28_dp), ierr)
            case (2)
                nx = merge(rec_int(8), rand_int(1, 12), rand_int(1, 4) == 1)
                ny = merge(rec_int(8), rand_int(1, 12), rand_int(1, 4) == 1)
                if (int(nx, i8)*int(ny, i8) > 40000_i8 .and. nx <= 4096 .and. ny <= 4096) nx = 3  ! keep it cheap
                call fc_set_grid(h(i), nx, ny, -rec_real(10.0_dp), rec_real(10.0_dp), -rec_real(6.0_dp), &
                    rec_real(6.0_dp), ierr)
            case (3, 4)
                call fc_set_gap_quadratic(h(i), rec_real(300.0_dp), rec_real(163.0_dp), ierr)
            case (5)
                call fc_get_grid_size(h(i), nx, ny, ierr)
                n = 1
                if (ierr == 0) n = max(1, int(nx)*int(ny))
                if (n > 40000) n = 1
                allocate (h0(n))
                h0 = [(rec_real(0.01_dp), k1 = 1, n)]     ! no arithmetic on hostile values here
                call fc_set_gap_array(h(i), int(n, c_int) + merge(0, 1, rand_int(1, 6) > 1), h0, ierr)
                deallocate (h0)
            case (6)
                call fc_set_normal_approach(h(i), rec_real(0.1_dp), ierr)
            case (7)
                call fc_set_normal_force(h(i), rec_real(80000.0_dp), ierr)
            case (8)
                call fc_set_friction(h(i), rec_real(0.3_dp), ierr)
            case (9)
                call fc_set_shifts(h(i), rec_real(1.0e-3_dp), rec_real(1.0e-4_dp), rec_real(1.0e-5_dp), ierr)
            case (10)
                call fc_set_forces(h(i), rec_real(1000.0_dp), rec_real(100.0_dp), rec_real(1.0e-5_dp), ierr)
            case (11)
                call fc_set_solver(h(i), rand_int(-1, 3), rand_int(-1, 3), rec_real(1.0e-5_dp), rec_int(50), &
                    rec_int(3), rand_int(-1, 2), ierr)
            case (12)
                call fc_set_transient(h(i), rand_int(-1, 3), ierr)
            case (13)
                call fc_set_rolling_step(h(i), rec_real(0.1_dp), ierr)
            case (14)
                call fc_set_reuse(h(i), rand_int(-1, 2), rand_int(-1, 2), ierr)
            case (15, 16, 17, 18)
                call fc_calculate(h(i), ierr)
                last_calc(i) = ierr
                call check(error, ierr >= 0 .and. ierr <= 7, trim(where)//': fc_calculate ierr out of range')
                if (ierr == FCL_OK .or. ierr == FCL_NOT_CONVERGED) call check_result(h(i), where, error)
            case (19)
                call fc_get_forces(h(i), fn, fx, fy, mz, ierr)
                ! a diverged calculation (5) may leave non-finite values; anything else may not
                if (ierr == 0 .and. last_calc(i) /= FCL_DIVERGED .and. .not. all(ieee_is_finite([fn, fx, fy, mz]))) then
                    write (where, '(a,4(1x,g0.4))') trim(where)//': fc_get_forces returned a non-finite force:', &
                        fn, fx, fy, mz
                    call check(error, .false., trim(where))
                end if
            case (20)
                call fc_get_grid_size(h(i), nx, ny, ierr)
                n = max(0, int(nx)*int(ny)) - rand_int(0, 1)
                if (ierr /= 0 .or. n > 40000) n = rand_int(0, 3)
                allocate (pn(max(n, 1)), px(max(n, 1)), py(max(n, 1)), st(max(n, 1)))
                call fc_get_tractions(h(i), int(n, c_int), pn, px, py, ierr)
                call fc_get_status_array(h(i), int(n, c_int), st, k1)
                call fc_get_slip(h(i), int(n, c_int), px, py, k1)
                call fc_get_gap(h(i), int(n, c_int), pn, k1)
                deallocate (pn, px, py, st)
            case (21)
                call fc_get_approach(h(i), a(1), ierr)
                call fc_get_pmax(h(i), a(2), k1)
                call fc_get_shifts(h(i), a(1), a(2), a(3), k1)
                call fc_get_contact_stats(h(i), k1, k2, k3, ierr)
                call fc_get_iterations(h(i), k1, k2, ierr)
                call fc_get_rebuilds(h(i), k1, k2, k3, ierr)
            case (22)
                ! an invalid handle: 0, negative, finalised, never issued
                k2 = rand_int(1, 4)
                k1 = 0
                if (k2 == 2) k1 = -1
                if (k2 == 3) k1 = 9999
                if (k2 == 4) k1 = -huge(0_c_int) - 1_c_int
                call fc_calculate(k1, ierr)
                call check(error, ierr == FCL_INVALID_HANDLE, trim(where)//': invalid handle not reported')
            case (23)
                call fc_get_error_message(h(i), buf, int(rand_int(0, 256), c_int), ierr)
            case (24)
                if (rand_int(1, 3) == 1) then
                    call fc_finalize(h(i), ierr)
                    call check(error, ierr == FCL_OK .and. h(i) == 0, trim(where)//': fc_finalize failed')
                    ntrace(i) = 0; last_calc(i) = -1
                    call fc_init(h(i), ierr)
                end if
            end select
            ntrace(i) = ntrace(i) + 1
            write (trace(modulo(ntrace(i), 48), i), '(i0,a,i0,a,i0,a,8(g0.5,1x))') call_no, ': op ', op, &
                ' -> ierr ', ierr, ' args ', recorded(1:nrec)
            call check(error, ierr >= 0 .and. ierr <= 7, trim(where)//': ierr out of the documented range 0..7')
            if (ierr >= 0 .and. ierr <= 7) counts(ierr) = counts(ierr) + 1
            if (ierr /= FCL_OK .and. ierr /= FCL_INVALID_HANDLE .and. op /= 23) then
                call fc_get_error_message(h(i), buf, 256_c_int, k1)
                call check(error, k1 == FCL_OK .and. buf(1) /= char(0) .and. buf(1) /= ' ', &
                    trim(where)//': a failing call left no message')
            end if
            call fc_get_nhandles(nlive, k1)
            call check(error, nlive == nh, trim(where)//': live handles differ from those held')
            if (allocated(error)) then
                ! the calls leading to the failure, oldest first
                do k1 = ntrace(i) - 47, ntrace(i)
                    if (k1 >= 1) error%message = error%message//new_line('a')//'      '// &
                        trim(trace(modulo(k1, 48), i))
                end do
                exit
            end if
        end do
        do i = 1, nh
            call fc_finalize(h(i), ierr)
        end do
        call fc_get_nhandles(nlive, ierr)
        call check(error, nlive == 0, 'handles left after finalising all')
        ! the sequence must reach the solver and its error paths, not only the setters
        call check(error, counts(0) > 100 .and. counts(3) > 100 .and. counts(2) > 10, &
            'the random sequence exercised too few outcomes')
    end subroutine random_call_sequences

    !> A calculation that returned 0 or 4 must leave finite, sign-correct results.
    subroutine check_result(h, where, error)
        integer(c_int), intent(in) :: h
        character(len=*), intent(in) :: where
        type(error_type), allocatable, intent(inout) :: error
        integer(c_int) :: nx, ny, ierr
        real(c_double) :: fn, fx, fy, mz
        real(c_double), allocatable :: pn(:), px(:), py(:)
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call check(error, ierr == FCL_OK, trim(where)//': no forces after a calculation')
        call check(error, all(ieee_is_finite([fn, fx, fy, mz])), trim(where)//': non-finite forces after a calculation')
        call fc_get_grid_size(h, nx, ny, ierr)
        allocate (pn(nx*ny), px(nx*ny), py(nx*ny))
        call fc_get_tractions(h, nx*ny, pn, px, py, ierr)
        call check(error, ierr == FCL_OK, trim(where)//': no tractions after a calculation')
        if (ierr == FCL_OK) then
            call check(error, all(ieee_is_finite(pn)) .and. all(ieee_is_finite(px)) .and. all(ieee_is_finite(py)), &
                trim(where)//': non-finite tractions')
            call check(error, all(pn >= 0), trim(where)//': negative pressure')
        end if
    end subroutine check_result

    !> The documented codes for call-order mistakes and special values (doc/legacy_api.md).
    subroutine documented_order_and_values(error)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: h, ierr
        real(c_double) :: h0(16), inf
        real(c_double) :: fn, fx, fy, mz
        inf = ieee_value(inf, ieee_positive_inf)
        call fc_init(h, ierr)
        ! gap before grid: FCL_ORDER (array and quadratic alike)
        h0 = 0
        call fc_set_gap_array(h, 16_c_int, h0, ierr)
        call check(error, ierr == FCL_ORDER, 'fc_set_gap_array before fc_set_grid must return 2')
        call fc_set_gap_quadratic(h, 300.0_dp, 163.0_dp, ierr)
        call check(error, ierr == FCL_ORDER, 'fc_set_gap_quadratic before fc_set_grid must return 2')
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_ORDER, 'fc_calculate without data must return 2')
        call fc_get_forces(h, fn, fx, fy, mz, ierr)
        call check(error, ierr == FCL_ORDER, 'a getter before the first calculation must return 2')
        call fc_set_material(h, 82000.0_dp, 82000.0_dp, 0.28_dp, 0.28_dp, ierr)
        call fc_set_grid(h, 4, 4, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, ierr)
        call check(error, ierr == FCL_OK, 'fc_set_grid 4x4')
        ! a radius <= 0 means flat in that direction (documented), also both
        call fc_set_gap_quadratic(h, -300.0_dp, 163.0_dp, ierr)
        call check(error, ierr == FCL_OK, 'fc_set_gap_quadratic: a negative radius is flat (documented), not an error')
        call fc_set_gap_quadratic(h, -1.0_dp, -1.0_dp, ierr)
        call check(error, ierr == FCL_OK, 'fc_set_gap_quadratic: both radii <= 0 is a flat surface, not an error')
        call fc_set_gap_quadratic(h, inf, 163.0_dp, ierr)
        call check(error, ierr == FCL_INVALID_VALUE, 'fc_set_gap_quadratic: an infinite radius must return 3')
        ! -Inf and NaN gap entries are invalid; +Inf (like >= 1e20) excludes an element
        h0 = 0.01_dp
        h0(5) = -inf
        call fc_set_gap_array(h, 16_c_int, h0, ierr)
        call check(error, ierr == FCL_INVALID_VALUE, 'fc_set_gap_array: a -Inf entry must return 3')
        h0(5) = inf
        call fc_set_gap_array(h, 16_c_int, h0, ierr)
        call check(error, ierr == FCL_OK, 'fc_set_gap_array: a +Inf entry excludes the element')
        ! iteration limits: maxit = 0 and above the library limit rejected at the call
        call fc_set_solver(h, 0_c_int, 0_c_int, 1.0e-5_dp, 0_c_int, 3_c_int, 1_c_int, ierr)
        call check(error, ierr == FCL_INVALID_VALUE, 'fc_set_solver: maxit = 0 must return 3')
        call fc_set_solver(h, 0_c_int, 0_c_int, 1.0e-5_dp, huge(0_c_int), 3_c_int, 1_c_int, ierr)
        call check(error, ierr == FCL_INVALID_VALUE, 'fc_set_solver: maxit = 2147483647 must return 3')
        call fc_finalize(h, ierr)
    end subroutine documented_order_and_values

end module test_api_fuzz
