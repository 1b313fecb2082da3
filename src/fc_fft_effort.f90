!> FFTW planning effort for repeated solves on one grid (flat API, `fc_set_fft_effort`).
!!
!! The operators of [[fc_toeplitz]] plan with FFTW_ESTIMATE: no measurement, instant.
!! FFTW_MEASURE finds faster plans by timing candidates, at a planning cost that only
!! repeated calls repay.  FFTW keeps what it measured as process-wide "wisdom", which any
!! later plan of the same shape — including FFTW_ESTIMATE plans — uses.  [[prime_fft_plans]]
!! therefore measures, once per grid shape, the plans the product of an nx×ny operator
!! uses (the same shapes, strides and buffer kinds as [[fc_toeplitz]]); the operators built
!! afterwards get the measured plans without any change to how they are built.  Planning
!! overwrites the buffers, which are scratch arrays here.
!!
!! Measured break-even and per-call gains: doc/legacy_api.md ("FFT planning effort").
module fc_fft_effort
    use fc_kinds, only: dp
    use fc_fftw
    implicit none
    private

    public :: prime_fft_plans

contains

    !> Measure (FFTW_MEASURE) the FFT plans of products on an nx×ny grid (circulant
    !! 2nx×2ny, or nx×ny when `periodic`) so that later FFTW_ESTIMATE plans of these
    !! shapes reuse the measured ones.  Cost: tens of ms at 60×50, about a second at
    !! 240×200 (doc/legacy_api.md).
    subroutine prime_fft_plans(nx, ny, periodic)
        integer, intent(in) :: nx, ny
        logical, intent(in), optional :: periodic
        real(dp), allocatable :: rbuf(:, :)
        complex(dp), allocatable :: cbuf(:, :)
        type(c_ptr) :: p(6)
        integer :: mx, my, mxh, k
        logical :: per
        per = .false.
        if (present(periodic)) per = periodic
        if (per) then
            mx = nx; my = ny
        else
            mx = 2*nx; if (nx == 1) mx = 1
            my = 2*ny; if (ny == 1) my = 1
        end if
        mxh = mx/2 + 1
        allocate (rbuf(mx, my), cbuf(mxh, my))
        p = c_null_ptr
        !$omp critical (fc_fftw_planner)
        p(1) = fftw_plan_dft_r2c_2d(int(my, c_int), int(mx, c_int), rbuf, cbuf, FFTW_MEASURE)
        p(2) = fftw_plan_dft_c2r_2d(int(my, c_int), int(mx, c_int), cbuf, rbuf, FFTW_MEASURE)
        if (my > ny) then
            ! the padding-aware passes of fc_toeplitz: r2c along x on the ny data columns,
            ! c2c along y; the inverse in the opposite order
            p(3) = fftw_plan_many_dft_r2c(1_c_int, [int(mx, c_int)], int(ny, c_int), rbuf, [int(mx, c_int)], &
                1_c_int, int(mx, c_int), cbuf, [int(mxh, c_int)], 1_c_int, int(mxh, c_int), FFTW_MEASURE)
            p(4) = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), cbuf, [int(my, c_int)], &
                int(mxh, c_int), 1_c_int, cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, FFTW_FORWARD, FFTW_MEASURE)
            p(5) = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), cbuf, [int(my, c_int)], &
                int(mxh, c_int), 1_c_int, cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, FFTW_BACKWARD, FFTW_MEASURE)
            p(6) = fftw_plan_many_dft_c2r(1_c_int, [int(mx, c_int)], int(ny, c_int), cbuf, [int(mxh, c_int)], &
                1_c_int, int(mxh, c_int), rbuf, [int(mx, c_int)], 1_c_int, int(mx, c_int), FFTW_MEASURE)
        end if
        do k = 1, size(p)
            if (c_associated(p(k))) call fftw_destroy_plan(p(k))
        end do
        !$omp end critical (fc_fftw_planner)
    end subroutine prime_fft_plans

end module fc_fft_effort
