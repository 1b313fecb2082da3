!> Influence coefficients of the elastic half-space and fast BTTB products (SPEC §2).
!!
!! Piecewise-constant tractions on the cell-centred elements of a [[fc_grid]] give
!! displacement differences u = A p.  Each block A^ab is block Toeplitz with Toeplitz
!! blocks (BTTB): its entries depend only on the offset (ix−jx, iy−jy).  Products are
!! computed as circulant convolutions on a doubled grid with FFTW (plans and kernel
!! transforms built once, one forward and one inverse real FFT per product); the direct
!! O(n²) product is kept as the test oracle (thesis §2.2.4, §3.3.1).
!!
!! Sign convention (fixed here, used by every module): u = u(body 1) − u(body 2) at the
!! field element I due to tractions p on body 1 at source element J, with
!! (u,v) = (x_I − x_J, y_I − y_J), and
!!   A^xz(u,v) = −K/(πG)·u/ρ²,  A^zx = −A^xz,  A^yz(u,v) = −K/(πG)·v/ρ²,  A^zy = −A^yz.
!! A^xy = A^yx is even in (u,v), so the tangential block matrix [A^xx A^xy; A^xy A^yy]
!! is symmetric.
module fc_influence
    use fc_kinds, only: dp, pi, msg_len
    use fc_limits, only: real_in_range, min_modulus
    use fc_geometry, only: fc_grid
    use fc_fftw
    implicit none
    private

    !> Elastic constants of the two bodies and their combination (Kalker).
    type, public :: fc_material
        real(dp) :: g1 = 0, g2 = 0     !! shear moduli of body 1 and 2 [N/mm²]; ≥ 1e29 means rigid
        real(dp) :: nu1 = 0, nu2 = 0   !! Poisson ratios, 0 ≤ ν < 0.5
        real(dp) :: g = 0              !! combined modulus, 2/G = 1/G1 + 1/G2
        real(dp) :: nu = 0             !! combined ratio, ν/G = (ν1/G1 + ν2/G2)/2
        real(dp) :: k = 0              !! difference parameter K = (G/4)[(1−2ν1)/G1 − (1−2ν2)/G2]
    end type fc_material

    !> Influence blocks available in [[fc_bttb]] constructors.
    integer, parameter, public :: IC_ZZ = 1, IC_XX = 2, IC_YY = 3, IC_XY = 4, IC_XZ = 5, IC_ZX = 6, &
        IC_YZ = 7, IC_ZY = 8

    !> BTTB operator: y = A x for one influence block on one grid.
    !! Holds FFTW plans on its own buffers; do not copy a built operator (use it in place).
    type, public :: fc_bttb
        integer :: nx = 0, ny = 0          !! grid size
        integer :: mx = 0, my = 0          !! circulant (embedding) size
        logical :: periodic = .false.      !! periodic convolution on the grid itself
        real(dp), allocatable :: kernel(:, :)    !! coefficients A(dix, diy), dix ∈ [−(nx−1), nx−1] [mm/(N/mm²)]
        complex(dp), allocatable :: symbol(:, :) !! r2c transform of the circulant, scaled by 1/(mx·my)
        real(dp), allocatable :: rbuf(:, :)
        complex(dp), allocatable :: cbuf(:, :)
        type(c_ptr) :: plan_fwd = c_null_ptr, plan_bwd = c_null_ptr
        ! Products skip the zero padding: r2c along x on the ny data columns only, then c2c
        ! along y; inverse in the opposite order, c2r only for the ny columns kept.
        type(c_ptr) :: plan_x_fwd = c_null_ptr, plan_y_fwd = c_null_ptr
        type(c_ptr) :: plan_y_bwd = c_null_ptr, plan_x_bwd = c_null_ptr
        logical :: split = .false.         !! use the padding-aware passes
        integer :: nproducts = 0           !! number of products applied (work counter)
    contains
        procedure :: apply => bttb_apply
        procedure :: apply_direct => bttb_apply_direct
        procedure :: forward => bttb_forward
        procedure :: backward => bttb_backward
        procedure :: destroy => bttb_destroy
        procedure :: built => bttb_built
    end type fc_bttb

    real(dp), parameter :: rigid_modulus = 1.0e29_dp  !! moduli at or above this are rigid (1/G = 0)

    public :: combine_material, element_coefficient, ic_kernel, build_bttb, build_bttb_from_kernel
    public :: fft_symbol_of_kernel, rigid_modulus, build_inverse_toeplitz, ic_kernel_extended
    public :: inverse_toeplitz_from_kernel

contains

    !> Combine two bodies into G, ν, K (SPEC §2).  A modulus ≥ 1e29 is a rigid body.
    subroutine combine_material(mat, stat, errmsg)
        type(fc_material), intent(inout) :: mat
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: c1, c2
        stat = 0; errmsg = ''
        ! range tests that never compare a NaN (quiet under floating-point traps)
        if (.not. real_in_range(mat%g1, min_modulus, huge(1.0_dp))) then
            stat = 1; write (errmsg, '(a,es12.4,a,es8.1,a)') 'material: g1 = ', mat%g1, ' must be > 0 (finite, >= ', &
                min_modulus, ')'
            return
        end if
        if (.not. real_in_range(mat%g2, min_modulus, huge(1.0_dp))) then
            stat = 1; write (errmsg, '(a,es12.4,a,es8.1,a)') 'material: g2 = ', mat%g2, ' must be > 0 (finite, >= ', &
                min_modulus, ')'
            return
        end if
        if (.not. (real_in_range(mat%nu1, 0.0_dp, 0.5_dp) .and. mat%nu1 /= 0.5_dp)) then
            stat = 1; write (errmsg, '(a,g0.6,a)') 'material: nu1 = ', mat%nu1, ' must lie in [0, 0.5)'
            return
        end if
        if (.not. (real_in_range(mat%nu2, 0.0_dp, 0.5_dp) .and. mat%nu2 /= 0.5_dp)) then
            stat = 1; write (errmsg, '(a,g0.6,a)') 'material: nu2 = ', mat%nu2, ' must lie in [0, 0.5)'
            return
        end if
        c1 = 1/mat%g1; if (mat%g1 >= rigid_modulus) c1 = 0
        c2 = 1/mat%g2; if (mat%g2 >= rigid_modulus) c2 = 0
        if (c1 + c2 <= 0) then
            stat = 1; errmsg = 'material: both bodies are rigid (g1 and g2 >= 1e29)'
            return
        end if
        mat%g = 2/(c1 + c2)
        mat%nu = mat%g*(mat%nu1*c1 + mat%nu2*c2)/2
        mat%k = mat%g/4*((1 - 2*mat%nu1)*c1 - (1 - 2*mat%nu2)*c2)
    end subroutine combine_material

    ! ---- antiderivatives F with ∂²F/∂u∂v = kernel (SPEC §2) ---------------------------

    !> ∫∫ 1/ρ: u·asinh(v/|u|) + v·asinh(u/|v|).
    elemental real(dp) function f_inv_rho(u, v) result(f)
        real(dp), intent(in) :: u, v
        f = 0
        if (u /= 0) f = f + u*asinh(v/abs(u))
        if (v /= 0) f = f + v*asinh(u/abs(v))
    end function f_inv_rho

    !> ∫∫ u²/ρ³: v·asinh(u/|v|).
    elemental real(dp) function f_uu_rho3(u, v) result(f)
        real(dp), intent(in) :: u, v
        f = 0
        if (v /= 0) f = v*asinh(u/abs(v))
    end function f_uu_rho3

    !> ∫∫ v²/ρ³: u·asinh(v/|u|).
    elemental real(dp) function f_vv_rho3(u, v) result(f)
        real(dp), intent(in) :: u, v
        f = 0
        if (u /= 0) f = u*asinh(v/abs(u))
    end function f_vv_rho3

    !> ∫∫ uv/ρ³: −ρ.
    elemental real(dp) function f_uv_rho3(u, v) result(f)
        real(dp), intent(in) :: u, v
        f = -hypot(u, v)
    end function f_uv_rho3

    !> ∫∫ u/ρ²: v·ln ρ + u·atan(v/u).
    elemental real(dp) function f_u_rho2(u, v) result(f)
        real(dp), intent(in) :: u, v
        real(dp) :: rho
        f = 0
        rho = hypot(u, v)
        if (v /= 0) f = f + v*log(rho)
        if (u /= 0) f = f + u*atan(v/u)
    end function f_u_rho2

    !> Influence coefficient of block `block` for a source element of size dx×dy at
    !! offset (X,Y) = (x_I − x_J, y_I − y_J) [mm per N/mm²] (SPEC §2 double difference).
    elemental real(dp) function element_coefficient(block, mat, x, y, dx, dy) result(a)
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        real(dp), intent(in) :: x, y, dx, dy
        real(dp) :: hx, hy, c
        hx = dx/2; hy = dy/2
        c = 1/(pi*mat%g)
        select case (block)
        case (IC_ZZ)
            a = c*(1 - mat%nu)*dd(1)
        case (IC_XX)
            a = c*((1 - mat%nu)*dd(1) + mat%nu*dd(2))
        case (IC_YY)
            a = c*((1 - mat%nu)*dd(1) + mat%nu*dd(3))
        case (IC_XY)
            a = c*mat%nu*dd(4)
        case (IC_XZ)
            a = -c*mat%k*dd(5)
        case (IC_ZX)
            a = c*mat%k*dd(5)
        case (IC_YZ)
            a = -c*mat%k*dd(6)
        case (IC_ZY)
            a = c*mat%k*dd(6)
        case default
            a = 0
        end select
    contains
        pure real(dp) function dd(which)
            integer, intent(in) :: which
            select case (which)
            case (1)
                dd = f_inv_rho(x + hx, y + hy) - f_inv_rho(x + hx, y - hy) - f_inv_rho(x - hx, y + hy) + f_inv_rho(x - hx, y - hy)
            case (2)
                dd = f_uu_rho3(x + hx, y + hy) - f_uu_rho3(x + hx, y - hy) - f_uu_rho3(x - hx, y + hy) + f_uu_rho3(x - hx, y - hy)
            case (3)
                dd = f_vv_rho3(x + hx, y + hy) - f_vv_rho3(x + hx, y - hy) - f_vv_rho3(x - hx, y + hy) + f_vv_rho3(x - hx, y - hy)
            case (4)
                dd = f_uv_rho3(x + hx, y + hy) - f_uv_rho3(x + hx, y - hy) - f_uv_rho3(x - hx, y + hy) + f_uv_rho3(x - hx, y - hy)
            case (5)
                dd = f_u_rho2(x + hx, y + hy) - f_u_rho2(x + hx, y - hy) - f_u_rho2(x - hx, y + hy) + f_u_rho2(x - hx, y - hy)
            case default   ! v/ρ²: the u/ρ² antiderivative with the roles of u and v swapped
                dd = f_u_rho2(y + hy, x + hx) - f_u_rho2(y - hy, x + hx) - f_u_rho2(y + hy, x - hx) + f_u_rho2(y - hy, x - hx)
            end select
        end function dd
    end function element_coefficient

    !> Coefficients of one block for all offsets of `grid`:
    !! kernel(dix, diy) = A(dix·dx, diy·dy), dix ∈ [−(nx−1), nx−1], diy ∈ [−(ny−1), ny−1].
    subroutine ic_kernel(block, mat, grid, kernel)
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        real(dp), allocatable, intent(out) :: kernel(:, :)
        call ic_kernel_extended(block, mat, grid, grid%nx - 1, grid%ny - 1, kernel)
    end subroutine ic_kernel

    !> Coefficients for offsets dix ∈ [−mx, mx], diy ∈ [−my, my].  The antiderivatives are
    !! evaluated once per element corner and double-differenced (four times fewer special
    !! function calls than element by element).
    subroutine ic_kernel_extended(block, mat, grid, mx, my, kernel)
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: mx, my
        real(dp), allocatable, intent(out) :: kernel(:, :)
        real(dp), allocatable :: fc(:, :), cx(:), cy(:)
        real(dp) :: c
        integer :: i, j
        allocate (kernel(-mx:mx, -my:my), cx(-mx:mx + 1), cy(-my:my + 1), fc(-mx:mx + 1, -my:my + 1))
        do i = -mx, mx + 1
            cx(i) = (i - 0.5_dp)*grid%dx
        end do
        do j = -my, my + 1
            cy(j) = (j - 0.5_dp)*grid%dy
        end do
        c = 1/(pi*mat%g)
        kernel = 0
        select case (block)
        case (IC_ZZ)
            call add_primitive(1, c*(1 - mat%nu))
        case (IC_XX)
            call add_primitive(1, c*(1 - mat%nu)); call add_primitive(2, c*mat%nu)
        case (IC_YY)
            call add_primitive(1, c*(1 - mat%nu)); call add_primitive(3, c*mat%nu)
        case (IC_XY)
            call add_primitive(4, c*mat%nu)
        case (IC_XZ)
            call add_primitive(5, -c*mat%k)
        case (IC_ZX)
            call add_primitive(5, c*mat%k)
        case (IC_YZ)
            call add_primitive(6, -c*mat%k)
        case (IC_ZY)
            call add_primitive(6, c*mat%k)
        end select
    contains
        subroutine add_primitive(which, factor)
            integer, intent(in) :: which
            real(dp), intent(in) :: factor
            integer :: ii, jj
            if (factor == 0) return
            do jj = -my, my + 1
                select case (which)
                case (1); fc(:, jj) = f_inv_rho(cx, cy(jj))
                case (2); fc(:, jj) = f_uu_rho3(cx, cy(jj))
                case (3); fc(:, jj) = f_vv_rho3(cx, cy(jj))
                case (4); fc(:, jj) = f_uv_rho3(cx, cy(jj))
                case (5); fc(:, jj) = f_u_rho2(cx, cy(jj))
                case default; fc(:, jj) = f_u_rho2(cy(jj), cx)
                end select
            end do
            do jj = -my, my
                do ii = -mx, mx
                    kernel(ii, jj) = kernel(ii, jj) + factor*(fc(ii + 1, jj + 1) - fc(ii + 1, jj) - fc(ii, jj + 1) + fc(ii, jj))
                end do
            end do
        end subroutine add_primitive
    end subroutine ic_kernel_extended

    !> Build the BTTB operator of one influence block on `grid`.
    !! With `periodic`, the kernel is summed over (2·images+1)² periods and its mean removed:
    !! a periodic RVE whose displacements are defined up to a constant (use prescribed force).
    subroutine build_bttb(op, block, mat, grid, periodic, images)
        type(fc_bttb), intent(inout) :: op
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        logical, intent(in), optional :: periodic
        integer, intent(in), optional :: images   !! periods summed on each side (default 4)
        real(dp), allocatable :: kernel(:, :), wrapped(:, :)
        logical :: per
        integer :: nim, i, j, si, sj
        real(dp) :: lx, ly
        per = .false.
        if (present(periodic)) per = periodic
        if (.not. per) then
            call ic_kernel(block, mat, grid, kernel)
            call build_bttb_from_kernel(op, kernel, grid%nx, grid%ny)
            return
        end if
        nim = 4
        if (present(images)) nim = images
        lx = grid%nx*grid%dx; ly = grid%ny*grid%dy
        allocate (wrapped(0:grid%nx - 1, 0:grid%ny - 1))
        do j = 0, grid%ny - 1
            do i = 0, grid%nx - 1
                wrapped(i, j) = 0
                do sj = -nim, nim
                    do si = -nim, nim
                        wrapped(i, j) = wrapped(i, j) + element_coefficient(block, mat, &
                            i*grid%dx + si*lx, j*grid%dy + sj*ly, grid%dx, grid%dy)
                    end do
                end do
            end do
        end do
        wrapped = wrapped - sum(wrapped)/size(wrapped)
        call setup_buffers(op, grid%nx, grid%ny, grid%nx, grid%ny)
        op%periodic = .true.
        allocate (op%kernel(0:grid%nx - 1, 0:grid%ny - 1), source=wrapped)
        op%rbuf = wrapped
        call finish_symbol(op)
    end subroutine build_bttb

    !> Build a (non-periodic) BTTB operator from explicit coefficients
    !! kernel(−(nx−1):nx−1, −(ny−1):ny−1); used for influence blocks and preconditioners.
    subroutine build_bttb_from_kernel(op, kernel, nx, ny)
        type(fc_bttb), intent(inout) :: op
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: kernel(-(nx - 1):, -(ny - 1):)
        integer :: mx, my, i, j
        mx = 2*nx; if (nx == 1) mx = 1
        my = 2*ny; if (ny == 1) my = 1
        call setup_buffers(op, nx, ny, mx, my)
        allocate (op%kernel(-(nx - 1):nx - 1, -(ny - 1):ny - 1), source=kernel)
        op%rbuf = 0
        do j = -(ny - 1), ny - 1
            do i = -(nx - 1), nx - 1
                op%rbuf(modulo(i, mx) + 1, modulo(j, my) + 1) = kernel(i, j)
            end do
        end do
        call finish_symbol(op)
    end subroutine build_bttb_from_kernel

    subroutine setup_buffers(op, nx, ny, mx, my)
        type(fc_bttb), intent(inout) :: op
        integer, intent(in) :: nx, ny, mx, my
        integer :: mxh
        call op%destroy()
        op%nx = nx; op%ny = ny; op%mx = mx; op%my = my
        op%periodic = .false.
        allocate (op%rbuf(mx, my), op%cbuf(mx/2 + 1, my), op%symbol(mx/2 + 1, my))
        ! FFTW's row-major dimensions are the reverse of Fortran's: (my, mx).
        op%plan_fwd = fftw_plan_dft_r2c_2d(int(my, c_int), int(mx, c_int), op%rbuf, op%cbuf, FFTW_ESTIMATE)
        op%plan_bwd = fftw_plan_dft_c2r_2d(int(my, c_int), int(mx, c_int), op%cbuf, op%rbuf, FFTW_ESTIMATE)
        op%split = my > ny
        if (op%split) then
            mxh = mx/2 + 1
            op%plan_x_fwd = fftw_plan_many_dft_r2c(1_c_int, [int(mx, c_int)], int(ny, c_int), op%rbuf, [int(mx, c_int)], &
                1_c_int, int(mx, c_int), op%cbuf, [int(mxh, c_int)], 1_c_int, int(mxh, c_int), FFTW_ESTIMATE)
            op%plan_y_fwd = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), op%cbuf, [int(my, c_int)], &
                int(mxh, c_int), 1_c_int, op%cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, FFTW_FORWARD, FFTW_ESTIMATE)
            op%plan_y_bwd = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), op%cbuf, [int(my, c_int)], &
                int(mxh, c_int), 1_c_int, op%cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, FFTW_BACKWARD, FFTW_ESTIMATE)
            op%plan_x_bwd = fftw_plan_many_dft_c2r(1_c_int, [int(mx, c_int)], int(ny, c_int), op%cbuf, [int(mxh, c_int)], &
                1_c_int, int(mxh, c_int), op%rbuf, [int(mx, c_int)], 1_c_int, int(mx, c_int), FFTW_ESTIMATE)
        end if
    end subroutine setup_buffers

    !> Transform the circulant in rbuf into the scaled symbol.
    subroutine finish_symbol(op)
        type(fc_bttb), intent(inout) :: op
        call fftw_execute_dft_r2c(op%plan_fwd, op%rbuf, op%cbuf)
        op%symbol = op%cbuf/real(op%mx*op%my, dp)
        op%nproducts = 0
    end subroutine finish_symbol

    !> Symbol (unscaled r2c transform) of a circulant built from a kernel; used by
    !! preconditioner construction (thesis §3.3.1).
    subroutine fft_symbol_of_kernel(op, symbol)
        type(fc_bttb), intent(in) :: op
        complex(dp), allocatable, intent(out) :: symbol(:, :)
        allocate (symbol, source=op%symbol*real(op%mx*op%my, dp))
    end subroutine fft_symbol_of_kernel

    !> Toeplitz approximation M ≈ A⁻¹ of one (symmetric) influence block (thesis §3.3.1,
    !! extended to 2D).  A's coefficients for offsets −nx+1…nx (and likewise in y) fill a
    !! 2nx×2ny circulant — the wrap-around slot holds the true coefficient at offset nx, which
    !! keeps the circulant positive definite — whose symbol is inverted pointwise; the
    !! central (2nx−1)×(2ny−1) coefficients of the inverse form M's kernel.  M on the grid is
    !! a principal block of that positive definite circulant, hence symmetric positive
    !! definite; symbol values are floored at 1e−8 of the maximum as a safeguard.
    subroutine build_inverse_toeplitz(block, mat, grid, prec, min_symbol)
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        type(fc_bttb), intent(inout) :: prec
        real(dp), intent(out), optional :: min_symbol  !! smallest symbol value / largest (diagnostic)
        real(dp), allocatable :: kext(:, :)
        call ic_kernel_extended(block, mat, grid, grid%nx, grid%ny, kext)
        call inverse_toeplitz_from_kernel(kext, grid%nx, grid%ny, prec, min_symbol)
    end subroutine build_inverse_toeplitz

    !> As [[build_inverse_toeplitz]], from coefficients kext(−nx:nx, −ny:ny) already computed.
    subroutine inverse_toeplitz_from_kernel(kext, nx, ny, prec, min_symbol)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: kext(-nx:, -ny:)
        type(fc_bttb), intent(inout) :: prec
        real(dp), intent(out), optional :: min_symbol
        type(fc_bttb) :: work
        real(dp), allocatable :: mker(:, :)
        real(dp) :: smax
        integer :: mx, my, i, j, di, dj
        mx = 2*nx; if (nx == 1) mx = 1
        my = 2*ny; if (ny == 1) my = 1
        call setup_buffers(work, nx, ny, mx, my)
        do j = 0, my - 1
            dj = j; if (j > my/2) dj = j - my
            do i = 0, mx - 1
                di = i; if (i > mx/2) di = i - mx
                work%rbuf(i + 1, j + 1) = kext(di, dj)
            end do
        end do
        call fftw_execute_dft_r2c(work%plan_fwd, work%rbuf, work%cbuf)
        smax = maxval(real(work%cbuf, dp))
        if (present(min_symbol)) min_symbol = minval(real(work%cbuf, dp))/smax
        work%cbuf = 1/cmplx(max(real(work%cbuf, dp), 1.0e-8_dp*smax), 0.0_dp, dp)/real(mx*my, dp)
        call fftw_execute_dft_c2r(work%plan_bwd, work%cbuf, work%rbuf)
        allocate (mker(-(nx - 1):nx - 1, -(ny - 1):ny - 1))
        do j = -(ny - 1), ny - 1
            do i = -(nx - 1), nx - 1
                mker(i, j) = work%rbuf(modulo(i, mx) + 1, modulo(j, my) + 1)
            end do
        end do
        call work%destroy()
        call build_bttb_from_kernel(prec, mker, nx, ny)
    end subroutine inverse_toeplitz_from_kernel

    !> y = A x by FFT (O(n log n)).  x, y are nx×ny arrays.
    subroutine bttb_apply(self, x, y)
        class(fc_bttb), intent(inout) :: self
        real(dp), intent(in) :: x(:, :)
        real(dp), intent(out) :: y(:, :)
        call transform_forward(self, x)
        self%cbuf = self%cbuf*self%symbol
        call transform_backward(self, y)
    end subroutine bttb_apply

    !> Spectrum of x (zero-padded to the circulant size): the first half of a product,
    !! so that several blocks can share one forward transform.
    subroutine bttb_forward(self, x, spectrum)
        class(fc_bttb), intent(inout) :: self
        real(dp), intent(in) :: x(:, :)
        complex(dp), intent(out) :: spectrum(:, :)
        call transform_forward(self, x)
        spectrum = self%cbuf
    end subroutine bttb_forward

    !> y = IFFT(spectrum) restricted to the grid (spectrum already multiplied by symbols).
    subroutine bttb_backward(self, spectrum, y)
        class(fc_bttb), intent(inout) :: self
        complex(dp), intent(in) :: spectrum(:, :)
        real(dp), intent(out) :: y(:, :)
        self%cbuf = spectrum
        call transform_backward(self, y)
    end subroutine bttb_backward

    !> cbuf ← FFT of x zero-padded to mx×my.
    subroutine transform_forward(self, x)
        class(fc_bttb), intent(inout) :: self
        real(dp), intent(in) :: x(:, :)
        integer :: nx, ny
        nx = self%nx; ny = self%ny
        if (self%split) then
            self%rbuf(1:nx, 1:ny) = x
            self%rbuf(nx + 1:, 1:ny) = 0
            call fftw_execute_dft_r2c(self%plan_x_fwd, self%rbuf, self%cbuf)
            self%cbuf(:, ny + 1:) = 0
            call fftw_execute_dft(self%plan_y_fwd, self%cbuf, self%cbuf)
        else
            if (self%mx == nx) then
                self%rbuf = x
            else
                self%rbuf(1:nx, :) = x
                self%rbuf(nx + 1:, :) = 0
            end if
            call fftw_execute_dft_r2c(self%plan_fwd, self%rbuf, self%cbuf)
        end if
    end subroutine transform_forward

    !> y ← inverse FFT of cbuf, restricted to the grid (cbuf is destroyed).
    subroutine transform_backward(self, y)
        class(fc_bttb), intent(inout) :: self
        real(dp), intent(out) :: y(:, :)
        if (self%split) then
            call fftw_execute_dft(self%plan_y_bwd, self%cbuf, self%cbuf)
            call fftw_execute_dft_c2r(self%plan_x_bwd, self%cbuf, self%rbuf)
        else
            call fftw_execute_dft_c2r(self%plan_bwd, self%cbuf, self%rbuf)
        end if
        y = self%rbuf(1:self%nx, 1:self%ny)
        self%nproducts = self%nproducts + 1
    end subroutine transform_backward

    !> y = A x by the direct O(n²) sum over the stored coefficients: the test oracle.
    subroutine bttb_apply_direct(self, x, y)
        class(fc_bttb), intent(in) :: self
        real(dp), intent(in) :: x(:, :)
        real(dp), intent(out) :: y(:, :)
        integer :: i, j, k, l, di, dj
        real(dp) :: s
        do j = 1, self%ny
            do i = 1, self%nx
                s = 0
                do l = 1, self%ny
                    dj = j - l
                    if (self%periodic) dj = modulo(dj, self%ny)
                    do k = 1, self%nx
                        di = i - k
                        if (self%periodic) di = modulo(di, self%nx)
                        s = s + self%kernel(di, dj)*x(k, l)
                    end do
                end do
                y(i, j) = s
            end do
        end do
    end subroutine bttb_apply_direct

    !> Release plans and buffers.
    subroutine bttb_destroy(self)
        class(fc_bttb), intent(inout) :: self
        if (c_associated(self%plan_fwd)) call fftw_destroy_plan(self%plan_fwd)
        if (c_associated(self%plan_bwd)) call fftw_destroy_plan(self%plan_bwd)
        self%plan_fwd = c_null_ptr; self%plan_bwd = c_null_ptr
        if (c_associated(self%plan_x_fwd)) call fftw_destroy_plan(self%plan_x_fwd)
        if (c_associated(self%plan_y_fwd)) call fftw_destroy_plan(self%plan_y_fwd)
        if (c_associated(self%plan_y_bwd)) call fftw_destroy_plan(self%plan_y_bwd)
        if (c_associated(self%plan_x_bwd)) call fftw_destroy_plan(self%plan_x_bwd)
        self%plan_x_fwd = c_null_ptr; self%plan_y_fwd = c_null_ptr
        self%plan_y_bwd = c_null_ptr; self%plan_x_bwd = c_null_ptr
        self%split = .false.
        if (allocated(self%kernel)) deallocate (self%kernel)
        if (allocated(self%symbol)) deallocate (self%symbol)
        if (allocated(self%rbuf)) deallocate (self%rbuf)
        if (allocated(self%cbuf)) deallocate (self%cbuf)
        self%nx = 0; self%ny = 0
    end subroutine bttb_destroy

    !> True once the operator has been built.
    pure logical function bttb_built(self)
        class(fc_bttb), intent(in) :: self
        bttb_built = allocated(self%symbol)
    end function bttb_built

end module fc_influence
