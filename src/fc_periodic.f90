!> Periodic half-space for the normal and the tangential problem: a rough-surface cell
!! (representative volume element) repeated in x and y with periods Lx = nx·dx, Ly = ny·dy.
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
!! and the distributed one of the MPI package (cosine transforms of the quadrant).  The
!! tangential blocks A^xx, A^yy (even) and A^xy (odd in x and in y) are summed the same way
!! ([[periodic_wrapped_kernel]]), so their symbols are real too.  For dissimilar bodies
!! (K ≠ 0) the coupling blocks A^xz, A^zx (odd in x, even in y) and A^yz, A^zy (odd in y,
!! even in x) are summed the same way; their symbols are imaginary.  Near the origin they
!! are the half-space's coefficients plus a uniform strain, (K/G)·x·dx·dy/(Lx·Ly) for A^xz:
!! the cell carries its mean pressure, so the images' load is balanced by a uniform
!! counter-load, whose tangential displacement grows linearly.
!!
!! Operators.  The periodic product is a circular convolution: the serial operator is the
!! circulant of w on the grid itself ([[build_bttb_periodic]]: nx×ny transforms, a quarter
!! of the doubled grid's work and memory; [[fc_norm]]'s column updates of clipped elements
!! take the offsets modulo the grid).  The preconditioner is the exact inverse of the
!! circulant on mean-free vectors: symbol 1/ŵ (zero mode 0, values floored at 1e−8 of the
!! largest as in [[inverse_toeplitz_from_kernel]]), on the same plans; for the tangential
!! operator the inverse of the 2×2 block symbol ([[build_periodic_tangential_operator]]).
module fc_periodic
    use fc_kinds, only: dp, i8, msg_len, FC_ERR_VALUE, FC_ERR_AREA, FC_ERR_UNSUPPORTED
    use fc_geometry, only: fc_grid
    use fc_influence, only: fc_material, element_coefficient, IC_ZZ, IC_XX, IC_YY, IC_XY, IC_XZ, IC_ZX, IC_YZ, IC_ZY
    use fc_norm, only: fc_normal_operator
    use fc_toeplitz, only: fc_bttb, build_bttb_periodic, kernel_of_real_symbol
    use fc_tangcg_operator, only: fc_tangential_operator
    use fc_fftw
    implicit none
    private

    integer, parameter, public :: periodic_images_default = 2  !! image rings summed exactly
    integer, parameter, public :: periodic_images_max = 50     !! bound on `images` (cost ∝ (2m+1)²)

    public :: periodic_kernel_block, build_periodic_normal_operator, check_periodic_grid
    public :: periodic_wrapped_kernel, build_periodic_tangential_operator, check_periodic_problem

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

    !> Whether the periodic half-space takes this problem: the normal one by BCCG or NORM (not
    !! FMG); a tangential one by TangCG (dissimilar bodies, K ≠ 0, by Panagiotopoulos rounds
    !! on the coupling blocks), without spin (a rotation of the whole surface is not
    !! periodic) and without rolling.  stat = FC_ERR_UNSUPPORTED with the reason otherwise.
    subroutine check_periodic_problem(fmg, tangential, rolling, phi, tangential_solver, stat, errmsg)
        logical, intent(in) :: fmg, tangential, rolling   !! FMG asked; a tangential stage; rolling
        real(dp), intent(in) :: phi                       !! spin [rad]
        character(len=*), intent(in) :: tangential_solver
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = FC_ERR_UNSUPPORTED
        if (fmg) then
            errmsg = "the periodic half-space is solved by 'bccg' or 'norm', not FMG"
        else if (rolling) then
            errmsg = 'the periodic half-space has no rolling (steady or transient); shifts and prescribed '// &
                'tangential forces only'
        else if (tangential .and. phi /= 0) then
            errmsg = 'the periodic half-space takes no spin (a rotation of the whole surface is not periodic): phi = 0'
        else if (tangential .and. tangential_solver /= 'tangcg') then
            errmsg = "the periodic half-space's tangential problem is solved by 'tangcg' only"
        else
            stat = 0; errmsg = ''
        end if
    end subroutine check_periodic_problem

    !> Periodic kernel w(i, j) (mean not removed) for 0-based offsets i0 ≤ i ≤ i1, j0 ≤ j ≤ j1,
    !! each within [0, n/2] [mm per N/mm²], of influence block `block` (default A^zz; the
    !! tangential blocks A^xx, A^xy, A^yy are summed the same way: the far images' uniform
    !! load displaces every point alike but for the box's own term).  Rows are independent:
    !! a distributed run computes its own rows, threads share the rows of one call.
    subroutine periodic_kernel_block(mat, grid, images, i0, i1, j0, j1, w, block)
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: images, i0, i1, j0, j1
        real(dp), intent(out) :: w(i0:, j0:)
        integer, intent(in), optional :: block   !! IC_ZZ (default) or another block of fc_influence
        real(dp) :: lx, ly, bx, by, dens, acc, r
        integer :: i, j, s, t, mxi, myi, blk
        blk = IC_ZZ
        if (present(block)) blk = block
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
                        acc = acc + element_coefficient(blk, mat, i*grid%dx + s*lx, j*grid%dy + t*ly, grid%dx, grid%dy)
                    end do
                end do
                w(i, j) = acc - dens*element_coefficient(blk, mat, i*grid%dx, j*grid%dy, bx, by)
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
        real(dp), allocatable :: w(:, :), rb(:, :)
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
        call periodic_wrapped_kernel(material, grid, nim, IC_ZZ, w)
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

    !> The periodic kernel of `block` on the whole cell, w(0:nx−1, 0:ny−1) with offsets
    !! taken in (−n/2, n/2]: the quadrant 0 ≤ i ≤ nx/2, 0 ≤ j ≤ ny/2 summed
    !! ([[periodic_kernel_block]]) and mirrored — A^zz, A^xx, A^yy are even in x and in y,
    !! A^xy odd in both, the coupling blocks A^xz, A^zx odd in x and A^yz, A^zy odd in y
    !! (zero on the lines i = 0, nx/2, resp. j = 0, ny/2, where an odd periodic function
    !! vanishes) — so that w is exactly point-symmetric (A^zz, A^xx, A^yy, A^xy: real
    !! symbol) or point-antisymmetric (the coupling blocks: imaginary symbol).  The mean of
    !! the even blocks is removed (displacements of a periodic cell are defined up to a
    !! constant; an odd block's is zero already).
    subroutine periodic_wrapped_kernel(mat, grid, images, block, w)
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: images, block
        real(dp), allocatable, intent(out) :: w(:, :)
        real(dp), allocatable :: q(:, :)
        real(dp) :: sx, sy
        integer :: nx, ny, i, j
        logical :: odd_x, odd_y
        nx = grid%nx; ny = grid%ny
        odd_x = block == IC_XY .or. block == IC_XZ .or. block == IC_ZX
        odd_y = block == IC_XY .or. block == IC_YZ .or. block == IC_ZY
        allocate (q(0:nx/2, 0:ny/2), w(0:nx - 1, 0:ny - 1))
        call periodic_kernel_block(mat, grid, images, 0, nx/2, 0, ny/2, q, block)
        if (odd_x) then
            q(0, :) = 0; q(nx/2, :) = 0
        end if
        if (odd_y) then
            q(:, 0) = 0; q(:, ny/2) = 0
        end if
        do j = 0, ny - 1
            sy = 1
            if (odd_y .and. j > ny/2) sy = -1
            do i = 0, nx - 1
                sx = 1
                if (odd_x .and. i > nx/2) sx = -1
                w(i, j) = sx*sy*q(min(i, nx - i), min(j, ny - j))
            end do
        end do
        if (.not. (odd_x .or. odd_y)) w = w - sum(w)/size(w)
    end subroutine periodic_wrapped_kernel

    !> Build the tangential blocks A^xx, A^xy, A^yy of the periodic half-space into `top` (the
    !! operator type of [[fc_tangcg_operator]]: TangCG then solves the periodic cell) and, as
    !! its FFT preconditioner, the exact inverse of the 2×2 block circulant on mean-free
    !! vectors (per frequency the inverse of the real symmetric 2×2 symbol, frequencies whose
    !! determinant is below 1e−12 of the largest 0; the zero mode, A's null direction, the
    !! largest of the inverse's values), applied by
    !! [[apply_block_inverse]] in either form.  For dissimilar bodies (K ≠ 0) also the
    !! coupling blocks A^xz, A^yz, A^zx, A^zy, which the orchestrator's Panagiotopoulos
    !! rounds use as on the half-space.  Rigid shifts are relative to the cell's mean
    !! displacement.
    subroutine build_periodic_tangential_operator(top, material, grid, stat, errmsg, images, plans_from)
        type(fc_tangential_operator), intent(inout) :: top
        type(fc_material), intent(in) :: material
        type(fc_grid), intent(in) :: grid
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer, intent(in), optional :: images   !! image rings (default [[fc_periodic:periodic_images_default]])
        !> a periodic operator of the same cell whose FFT plans the blocks share (the normal one)
        type(fc_bttb), intent(in), optional :: plans_from
        real(dp), allocatable :: w(:, :), mxx(:, :), mxy(:, :), myy(:, :)
        real(dp) :: det, dmax, a, b, c, scale
        integer :: nx, ny, nim, i, j
        integer(i8) :: t0, t1, rate
        call system_clock(t0, rate)
        nim = periodic_images_default
        if (present(images)) nim = images
        call check_periodic_grid(grid, nim, stat, errmsg)
        if (stat /= 0) return
        nx = grid%nx; ny = grid%ny
        call top%destroy()
        top%grid = grid
        top%material = material
        call periodic_wrapped_kernel(material, grid, nim, IC_XX, w)
        call build_bttb_periodic(top%a_xx, w, plans_from)
        call periodic_wrapped_kernel(material, grid, nim, IC_XY, w)
        call build_bttb_periodic(top%a_xy, w, top%a_xx)
        call periodic_wrapped_kernel(material, grid, nim, IC_YY, w)
        call build_bttb_periodic(top%a_yy, w, top%a_xx)
        if (material%k /= 0) then
            call periodic_wrapped_kernel(material, grid, nim, IC_XZ, w)
            call build_bttb_periodic(top%a_xz, w, top%a_xx)
            call periodic_wrapped_kernel(material, grid, nim, IC_YZ, w)
            call build_bttb_periodic(top%a_yz, w, top%a_xx)
            call periodic_wrapped_kernel(material, grid, nim, IC_ZX, w)
            call build_bttb_periodic(top%a_zx, w, top%a_xx)
            call periodic_wrapped_kernel(material, grid, nim, IC_ZY, w)
            call build_bttb_periodic(top%a_zy, w, top%a_xx)
        end if
        ! the exact block inverse: the three symbols are real (point-symmetric kernels).
        ! Stored symbols are scaled by 1/N (N = nx·ny: the unnormalised transforms), so A's
        ! eigenvalues are N·s and M's stored symbol is their inverse over N: s⁻¹/N²
        scale = 1/(real(nx, dp)*real(ny, dp))**2
        associate (sxx => top%a_xx%rsymbol, sxy => top%a_xy%rsymbol, syy => top%a_yy%rsymbol)
            allocate (mxx, mxy, myy, mold=sxx)
            dmax = maxval(sxx*syy - sxy**2)
            do j = 1, size(sxx, 2)
                do i = 1, size(sxx, 1)
                    a = sxx(i, j); b = sxy(i, j); c = syy(i, j)
                    det = a*c - b*b
                    if ((i == 1 .and. j == 1) .or. det <= 1.0e-12_dp*dmax) then
                        mxx(i, j) = 0; mxy(i, j) = 0; myy(i, j) = 0
                    else
                        mxx(i, j) = scale*c/det; mxy(i, j) = -scale*b/det; myy(i, j) = scale*a/det
                    end if
                end do
            end do
        end associate
        ! uniform tractions (A's null direction on the whole cell) get the weight of A's
        ! softest other mode, so that TangCG can move along them when every element of the
        ! cell is in adhesion (its step then goes to the first traction bound)
        mxx(1, 1) = max(maxval(mxx), maxval(myy)); myy(1, 1) = mxx(1, 1)
        call periodic_from_symbol(mxx, top%c_xx, top%a_xx)
        call periodic_from_symbol(mxy, top%c_xy, top%a_xx)
        call periodic_from_symbol(myy, top%c_yy, top%a_xx)
        allocate (top%spec_x(top%a_xx%mx/2 + 1, top%a_xx%my))
        allocate (top%spec_y, top%work, top%work2, top%cspec_x, top%cspec_y, top%cwork, top%cwork2, mold=top%spec_x)
        top%periodic = .true.
        top%nproducts = 0
        call system_clock(t1)
        top%setup_seconds = real(t1 - t0, dp)/rate
    contains
        !> A periodic operator on the cell whose (normalised) real symbol is `sym`, on the
        !! plans of `plans_from`.
        subroutine periodic_from_symbol(sym, op, plans_from)
            real(dp), intent(in) :: sym(:, :)
            type(fc_bttb), intent(inout) :: op
            type(fc_bttb), intent(inout) :: plans_from
            real(dp), allocatable :: kern(:, :)
            allocate (kern(0:nx - 1, 0:ny - 1))
            call kernel_of_real_symbol(plans_from, sym, kern)
            call build_bttb_periodic(op, kern, plans_from, keep_kernel=.false.)
        end subroutine periodic_from_symbol
    end subroutine build_periodic_tangential_operator


end module fc_periodic
