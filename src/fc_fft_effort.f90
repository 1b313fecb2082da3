!> FFTW planning effort for repeated solves on one grid (flat API `fc_set_fft_effort`,
!! driver `&solver fft_wisdom`).
!!
!! The operators of [[fc_toeplitz]] plan with FFTW_ESTIMATE: no measurement, instant.
!! FFTW_MEASURE finds faster plans by timing candidates, at a planning cost that only
!! repeated calls repay.  FFTW keeps what it measured as process-wide "wisdom", which any
!! later plan of the same shape — including FFTW_ESTIMATE plans — uses.  [[prime_fft_plans]]
!! therefore measures, once per grid shape, the plans the product of an nx×ny operator
!! uses (the same shapes, strides and buffer kinds as [[fc_toeplitz]]); the operators built
!! afterwards get the measured plans without any change to how they are built.  Planning
!! overwrites the buffers, which are scratch arrays here.  [[use_fft_wisdom]] keeps the
!! wisdom in a file, so that only the first process on a grid pays for the measurement.
!!
!! Measured break-even and per-call gains: doc/legacy_api.md ("FFT planning effort"),
!! doc/benchmarks.md (wisdom files).
module fc_fft_effort
    use fc_kinds, only: dp, FC_ERR_FFT_WISDOM
    use fc_fftw
    implicit none
    private

    public :: prime_fft_plans, fft_plans_in_wisdom, use_fft_wisdom

contains

    !> Measure (FFTW_MEASURE) the FFT plans of products on an nx×ny grid (circulant
    !! 2nx×2ny or fc_fftw's circulant_size, nx×ny when `periodic`) so that later FFTW_ESTIMATE plans of these
    !! shapes reuse the measured ones.  Cost: tens of ms at 60×50, about a second at
    !! 240×200 (doc/legacy_api.md).
    subroutine prime_fft_plans(nx, ny, periodic)
        integer, intent(in) :: nx, ny
        logical, intent(in), optional :: periodic
        logical :: all_made
        all_made = product_plans(nx, ny, FFTW_MEASURE, periodic)
    end subroutine prime_fft_plans

    !> Whether FFTW's wisdom already holds measured plans for the products on an nx×ny grid
    !! (planning with FFTW_WISDOM_ONLY succeeds for every one of them).
    logical function fft_plans_in_wisdom(nx, ny, periodic) result(known)
        integer, intent(in) :: nx, ny
        logical, intent(in), optional :: periodic
        known = product_plans(nx, ny, ior(FFTW_MEASURE, FFTW_WISDOM_ONLY), periodic)
    end function fft_plans_in_wisdom

    !> Wisdom file `path` for an nx×ny grid: read it when it exists, measure the grid's plans
    !! when neither the process nor the file has them, and write the file unless it already
    !! held them.  `new_plans`: the process did not have the grid's plans before this call
    !! (operators built earlier on estimated plans should be rebuilt).  stat =
    !! FC_ERR_FFT_WISDOM when the file exists but is not FFTW wisdom, or cannot be written.
    subroutine use_fft_wisdom(path, nx, ny, periodic, new_plans, stat, errmsg)
        character(len=*), intent(in) :: path
        integer, intent(in) :: nx, ny
        logical, intent(in) :: periodic
        logical, intent(out) :: new_plans
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        logical :: exists, had, have
        integer :: u, ios
        stat = 0; errmsg = ''
        had = fft_plans_in_wisdom(nx, ny, periodic)
        new_plans = .not. had
        inquire (file=path, exist=exists)
        if (.not. exists) then
            ! can the file be written?  Asked before the measurement, which takes seconds
            open (newunit=u, file=path, status='new', action='write', iostat=ios)
            if (ios /= 0) then
                stat = FC_ERR_FFT_WISDOM
                errmsg = 'cannot create the wisdom file (does its directory exist?)'
                return
            end if
            close (u, status='delete')
        else if (.not. wisdom_file(path, read=.true.)) then
            stat = FC_ERR_FFT_WISDOM
            errmsg = 'the file exists but FFTW cannot read it as wisdom (delete it to measure again)'
            return
        end if
        have = fft_plans_in_wisdom(nx, ny, periodic)
        ! the plans came from the file alone: it is complete, leave it as it is
        if (exists .and. .not. had .and. have) return
        if (.not. have) call prime_fft_plans(nx, ny, periodic)
        if (.not. wisdom_file(path, read=.false.)) then
            stat = FC_ERR_FFT_WISDOM
            errmsg = 'cannot write the wisdom file (does its directory exist?)'
        end if
    end subroutine use_fft_wisdom

    !> Read FFTW's wisdom from `path` (merged with what the process has) or write it there;
    !! .false. when FFTW reports a failure.
    logical function wisdom_file(path, read) result(ok)
        character(len=*), intent(in) :: path
        logical, intent(in) :: read
        integer(c_int) :: done
        !$omp critical (fc_fftw_planner)
        if (read) then
            done = fftw_import_wisdom_from_filename(trim(path)//c_null_char)
        else
            done = fftw_export_wisdom_to_filename(trim(path)//c_null_char)
        end if
        !$omp end critical (fc_fftw_planner)
        ok = done /= 0
    end function wisdom_file

    !> Plan (with `flags`) and destroy the transforms of the products on an nx×ny grid;
    !! .true. when every plan was made (with FFTW_WISDOM_ONLY: all were in the wisdom).
    logical function product_plans(nx, ny, flags, periodic) result(all_made)
        integer, intent(in) :: nx, ny
        integer(c_int), intent(in) :: flags
        logical, intent(in), optional :: periodic
        real(dp), allocatable :: rbuf(:, :)
        complex(dp), allocatable :: cbuf(:, :)
        type(c_ptr) :: p(4)
        integer :: mx, my, mxh, k
        logical :: per
        per = .false.
        if (present(periodic)) per = periodic
        if (per) then
            mx = nx; my = ny
        else
            mx = circulant_size(nx); my = circulant_size(ny)
        end if
        mxh = mx/2 + 1
        allocate (rbuf(mx, my), cbuf(mxh, my))
        !$omp critical (fc_fftw_planner)
        ! the passes of fc_toeplitz's products: r2c along x on the ny data columns, c2c along
        ! y; the inverse in the opposite order
        p(1) = fftw_plan_many_dft_r2c(1_c_int, [int(mx, c_int)], int(ny, c_int), rbuf, [int(mx, c_int)], &
            1_c_int, int(mx, c_int), cbuf, [int(mxh, c_int)], 1_c_int, int(mxh, c_int), flags)
        p(2) = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), cbuf, [int(my, c_int)], &
            int(mxh, c_int), 1_c_int, cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, FFTW_FORWARD, flags)
        p(3) = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), cbuf, [int(my, c_int)], &
            int(mxh, c_int), 1_c_int, cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, FFTW_BACKWARD, flags)
        p(4) = fftw_plan_many_dft_c2r(1_c_int, [int(mx, c_int)], int(ny, c_int), cbuf, [int(mxh, c_int)], &
            1_c_int, int(mxh, c_int), rbuf, [int(mx, c_int)], 1_c_int, int(mx, c_int), flags)
        all_made = .true.
        do k = 1, size(p)
            all_made = all_made .and. c_associated(p(k))
            if (c_associated(p(k))) call fftw_destroy_plan(p(k))
        end do
        !$omp end critical (fc_fftw_planner)
    end function product_plans

end module fc_fft_effort
