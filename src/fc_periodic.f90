!> Periodic half-space for the normal problem: a rough-surface cell (representative volume
!! element) repeated in x and y with periods Lx = nx·dx, Ly = ny·dy.
!!
!! Kernel.  The displacement at offset (i·dx, j·dy) due to unit pressure on one element and
!! all its periodic images is the lattice sum of the element coefficient A^zz over the
!! (2m+1)² nearest images (m = `images`) plus the far images smeared into a uniform load of
!! density dx·dy/(Lx·Ly) outside the box B of the summed cells:
!!
!!   w(x) = Σ_{|s|,|t| ≤ m} A(x + s·Lx, y + t·Ly) − dx·dy/(Lx·Ly) · A_B(x, y) + const,
!!
!! A_B the displacement under unit pressure on B (the element formula with size
!! (2m+1)Lx × (2m+1)Ly).  The constant (the divergent potential of the whole plane) is
!! fixed by removing the mean of w: displacements of a periodic cell are defined up to a
!! constant, so the cell is loaded by its mean pressure (prescribed force).  Without the
!! tail the truncated lattice sum converges like 1/m (measured: 2 % error of the
!! sinusoid response with m = 40); with it the remaining error is smooth and of higher
!! order, and m = 2 (the default) reproduces the wavy surface's full-contact pressure to
!! the discretisation error (test `periodic_wavy_full_contact`).
!!
!! The window of images is centred on the offset taken in (−n/2, n/2], so w is exactly even
!! in x and in y: only the quadrant 0 ≤ i ≤ nx/2, 0 ≤ j ≤ ny/2 is computed (nx, ny even),
!! and its Fourier symbol is real — the same values serve the serial operator built here
!! and the distributed one of the MPI package (cosine transforms of the quadrant).
!!
!! Operators.  The periodic product is a circular convolution: the serial operator is the
!! circulant of w on the grid itself ([[build_bttb_periodic]]: nx×ny transforms, a quarter
!! of the doubled grid's work and memory; [[fc_norm]]'s column updates of clipped elements
!! take the offsets modulo the grid).  The preconditioner is the exact inverse of the
!! circulant on mean-free vectors: symbol 1/ŵ (zero mode 0, values floored at 1e−8 of the
!! largest as in [[inverse_toeplitz_from_kernel]]), on the same plans.
module fc_periodic
    use fc_kinds, only: dp, i8, msg_len, FC_ERR_VALUE, FC_ERR_AREA
    use fc_geometry, only: fc_grid
    use fc_influence, only: fc_material, element_coefficient, IC_ZZ
    use fc_toeplitz, only: build_bttb_periodic
    use fc_norm, only: fc_normal_operator
    use fc_fftw
    implicit none
    private

    integer, parameter, public :: periodic_images_default = 2  !! image rings summed exactly
    integer, parameter, public :: periodic_images_max = 50     !! bound on `images` (cost ∝ (2m+1)²)

    public :: periodic_kernel_block, build_periodic_normal_operator, check_periodic_grid

contains

    !> Whether `grid` can carry the periodic half-space: nx and ny even and ≥ 2.
    subroutine check_periodic_grid(grid, images, stat, errmsg)
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: images
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (grid%nx < 2 .or. grid%ny < 2 .or. modulo(grid%nx, 2) /= 0 .or. modulo(grid%ny, 2) /= 0) then
            stat = FC_ERR_AREA
            write (errmsg, '(a,i0,a,i0,a)') 'grid: periodic = .true. needs even nx and ny >= 2, got nx = ', &
                grid%nx, ', ny = ', grid%ny, ' (the cell is repeated in x and y)'
        else if (images < 0 .or. images > periodic_images_max) then
            stat = FC_ERR_AREA
            write (errmsg, '(a,i0,a,i0,a)') 'grid: periodic images = ', images, ' must lie in [0, ', &
                periodic_images_max, ']'
        end if
    end subroutine check_periodic_grid

    !> Periodic kernel w(i, j) (mean not removed) for 0-based offsets i0 ≤ i ≤ i1, j0 ≤ j ≤ j1,
    !! each within [0, n/2] [mm per N/mm²].  Rows are independent: a distributed run computes
    !! its own rows, threads share the rows of one call.
    subroutine periodic_kernel_block(mat, grid, images, i0, i1, j0, j1, w)
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: images, i0, i1, j0, j1
        real(dp), intent(out) :: w(i0:, j0:)
        real(dp) :: lx, ly, bx, by, dens, acc, r
        integer :: i, j, s, t, mxi, myi
        lx = grid%nx*grid%dx; ly = grid%ny*grid%dy
        ! a square box of summed cells (half-width r) also for elongated cells
        r = (images + 0.5_dp)*max(lx, ly)
        mxi = max(images, ceiling(r/lx - 0.5_dp)); myi = max(images, ceiling(r/ly - 0.5_dp))
        bx = (2*mxi + 1)*lx; by = (2*myi + 1)*ly
        dens = grid%dx*grid%dy/(lx*ly)
        !$omp parallel do default(shared) private(i, s, t, acc) schedule(dynamic, 4)
        do j = j0, j1
            do i = i0, i1
                acc = 0
                do t = -myi, myi
                    do s = -mxi, mxi
                        acc = acc + element_coefficient(IC_ZZ, mat, i*grid%dx + s*lx, j*grid%dy + t*ly, grid%dx, grid%dy)
                    end do
                end do
                w(i, j) = acc - dens*element_coefficient(IC_ZZ, mat, i*grid%dx, j*grid%dy, bx, by)
            end do
        end do
        !$omp end parallel do
    end subroutine periodic_kernel_block

    !> Build A^zz of the periodic half-space and its preconditioner into `nop` (the operator
    !! type of [[fc_norm]]: [[solve_normal]] then solves the periodic cell; prescribe the
    !! force — the approach is relative to the mean displacement, which is set to zero).
    subroutine build_periodic_normal_operator(nop, material, grid, stat, errmsg, images)
        type(fc_normal_operator), intent(inout) :: nop
        type(fc_material), intent(in) :: material
        type(fc_grid), intent(in) :: grid
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer, intent(in), optional :: images   !! image rings (default [[fc_periodic:periodic_images_default]])
        real(dp), allocatable :: q(:, :), w(:, :), rb(:, :)
        complex(dp), allocatable :: cb(:, :)
        type(c_ptr) :: plan_f, plan_b
        real(dp) :: smax, s
        integer :: nx, ny, nim, i, j
        integer(i8) :: t0, t1, rate   ! 64-bit: a µs clock (default integers tick in ms)
        call system_clock(t0, rate)
        nim = periodic_images_default
        if (present(images)) nim = images
        call check_periodic_grid(grid, nim, stat, errmsg)
        if (stat /= 0) return
        nx = grid%nx; ny = grid%ny
        call nop%destroy()
        nop%grid = grid
        nop%material = material
        allocate (q(0:nx/2, 0:ny/2), w(0:nx - 1, 0:ny - 1))
        call periodic_kernel_block(material, grid, nim, 0, nx/2, 0, ny/2, q)
        do j = 0, ny - 1
            do i = 0, nx - 1
                w(i, j) = q(min(i, nx - i), min(j, ny - j))
            end do
        end do
        w = w - sum(w)/size(w)
        call build_bttb_periodic(nop%a_zz, w)
        ! exact inverse on mean-free vectors: symbol 1/ŵ, zero mode dropped
        allocate (rb(nx, ny), cb(nx/2 + 1, ny))
        !$omp critical (fc_fftw_planner)
        plan_f = fftw_plan_dft_r2c_2d(int(ny, c_int), int(nx, c_int), rb, cb, FFTW_ESTIMATE)
        plan_b = fftw_plan_dft_c2r_2d(int(ny, c_int), int(nx, c_int), cb, rb, FFTW_ESTIMATE)
        !$omp end critical (fc_fftw_planner)
        rb = w
        call fftw_execute_dft_r2c(plan_f, rb, cb)
        smax = maxval(real(cb, dp))
        do j = 1, ny
            do i = 1, nx/2 + 1
                s = 0
                if (i > 1 .or. j > 1) s = 1/(max(real(cb(i, j), dp), 1.0e-8_dp*smax)*real(nx, dp)*real(ny, dp))
                cb(i, j) = cmplx(s, 0.0_dp, dp)
            end do
        end do
        call fftw_execute_dft_c2r(plan_b, cb, rb)
        !$omp critical (fc_fftw_planner)
        call fftw_destroy_plan(plan_f); call fftw_destroy_plan(plan_b)
        !$omp end critical (fc_fftw_planner)
        w = rb
        call build_bttb_periodic(nop%precond, w, plans_from=nop%a_zz, keep_kernel=.false.)
        call system_clock(t1)
        nop%setup_seconds = real(t1 - t0, dp)/rate
    end subroutine build_periodic_normal_operator


end module fc_periodic
