!> Influence coefficients of the elastic half-space (thesis §2.2.4–2.2.5, Kalker).
!!
!! Piecewise-constant tractions on the cell-centred elements of a [[fc_grid]] give
!! displacement differences u = A p.  Each block A^ab is block Toeplitz with Toeplitz
!! blocks (BTTB): its entries depend only on the offset (ix−jx, iy−jy).  This module
!! computes the coefficients (closed-form double differences of antiderivatives) and
!! builds the fast operators of [[fc_toeplitz]] from them; it re-exports [[fc_bttb]].
!!
!! Sign convention (fixed here, used by every module; see doc/conventions.md):
!! u = u(body 1) − u(body 2) at the field element I due to tractions p on body 1 at source
!! element J, with (u,v) = (x_I − x_J, y_I − y_J), and
!!   A^xz(u,v) = −K/(πG)·u/ρ²,  A^zx = −A^xz,  A^yz(u,v) = −K/(πG)·v/ρ²,  A^zy = −A^yz.
!! A^xy = A^yx is even in (u,v), so the tangential block matrix [A^xx A^xy; A^xy A^yy]
!! is symmetric.
module fc_influence
    use fc_kinds, only: dp, pi, msg_len, FC_ERR_VALUE
    use fc_limits, only: real_in_range, min_modulus
    use fc_geometry_grid, only: fc_grid
    use fc_toeplitz
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

    !> A set of tabulated influence coefficients (FE, files): for every offset (ix, iy) with
    !! |ix| ≤ mx, |iy| ≤ my the 3×3 coefficients a(ix, iy, i, j), displacement component i
    !! (1 = x, 2 = y, 3 = z) at a cell centre due to a unit traction component j on a cell of
    !! size dx×dy centred at offset (−ix·dx, −iy·dy) from it [mm per N/mm²]; files, validation
    !! and the combination of two bodies: [[fc_icfile]].
    !> One block's coefficients (an element of a list of kernels).
    type :: kernel_slot
        real(dp), allocatable :: c(:, :)
    end type kernel_slot

    type, public :: fc_ic_set
        integer :: mx = 0, my = 0                    !! largest offsets stored
        real(dp) :: dx = 0, dy = 0                   !! cell size [mm]
        character(len=16) :: content = 'body'        !! 'body' or 'combined'
        character(len=16) :: source = ''             !! 'fem', 'analytic', 'contact', ...
        real(dp) :: g = 0, nu = 0                    !! material of the body (content 'body') [N/mm², –]
        character(len=16) :: load = 'constant'       !! traction shape of the source cell
        character(len=512) :: model = ''            !! model description (FE parameters, ...)
        character(len=16) :: hash = ''               !! cache key of the model parameters
        real(dp), allocatable :: a(:, :, :, :)       !! a(−mx:mx, −my:my, 3, 3) [mm/(N/mm²)]
    end type fc_ic_set

    real(dp), parameter :: rigid_modulus = 1.0e29_dp  !! moduli at or above this are rigid (1/G = 0)

    public :: combine_material, element_coefficient, ic_kernel, build_bttb, rigid_modulus, build_inverse_toeplitz
    public :: ic_kernel_extended, ic_kernels_uncoupled
    public :: ic_set_allocate, ic_block_index, ic_set_kernel, same_cell_size, check_ic_set_grid
    ! the fast operators built from the coefficients (fc_toeplitz)
    public :: fc_bttb, build_bttb_from_kernel, build_bttb_taking_kernel, inverse_toeplitz_from_kernel, fft_symbol_of_kernel
    public :: copy_bttb
    public :: spectrum_pair_product, block_symbol_product_in_place, block_product, SYMBOL_GENERAL, SYMBOL_EVEN, SYMBOL_ODD
    public :: strang_circulant, strang_circulant_of_symbol

contains

    !> Combine two bodies into G, ν, K (doc/conventions.md).  A modulus ≥ 1e29 is a rigid body.
    subroutine combine_material(mat, stat, errmsg)
        type(fc_material), intent(inout) :: mat
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: c1, c2
        stat = 0; errmsg = ''
        ! range tests that never compare a NaN (quiet under floating-point traps)
        if (.not. real_in_range(mat%g1, min_modulus, huge(1.0_dp))) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a,es8.1,a)') 'material: g1 = ', mat%g1, ' must be > 0 (finite, >= ', &
                min_modulus, ')'
            return
        end if
        if (.not. real_in_range(mat%g2, min_modulus, huge(1.0_dp))) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a,es8.1,a)') 'material: g2 = ', mat%g2, ' must be > 0 (finite, >= ', &
                min_modulus, ')'
            return
        end if
        if (.not. (real_in_range(mat%nu1, 0.0_dp, 0.5_dp) .and. mat%nu1 /= 0.5_dp)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.6,a)') 'material: nu1 = ', mat%nu1, ' must lie in [0, 0.5)'
            return
        end if
        if (.not. (real_in_range(mat%nu2, 0.0_dp, 0.5_dp) .and. mat%nu2 /= 0.5_dp)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.6,a)') 'material: nu2 = ', mat%nu2, ' must lie in [0, 0.5)'
            return
        end if
        c1 = 1/mat%g1; if (mat%g1 >= rigid_modulus) c1 = 0
        c2 = 1/mat%g2; if (mat%g2 >= rigid_modulus) c2 = 0
        if (c1 + c2 <= 0) then
            stat = FC_ERR_VALUE; errmsg = 'material: both bodies are rigid (g1 and g2 >= 1e29)'
            return
        end if
        mat%g = 2/(c1 + c2)
        mat%nu = mat%g*(mat%nu1*c1 + mat%nu2*c2)/2
        mat%k = mat%g/4*((1 - 2*mat%nu1)*c1 - (1 - 2*mat%nu2)*c2)
    end subroutine combine_material

    ! ---- antiderivatives F with ∂²F/∂u∂v = kernel (doc/conventions.md) ---------------------------

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
    !! offset (X,Y) = (x_I − x_J, y_I − y_J) [mm per N/mm²] (double difference, doc/conventions.md).
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
    !! evaluated once per element corner of one quadrant, mirrored to the others and
    !! double-differenced (sixteen times fewer special-function calls than element by element).
    subroutine ic_kernel_extended(block, mat, grid, mx, my, kernel)
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: mx, my
        real(dp), allocatable, intent(out) :: kernel(:, :)
        type(kernel_slot) :: k(1)
        call half_space_kernels(mat, grid, mx, my, [block], k)
        call move_alloc(k(1)%c, kernel)
    end subroutine ic_kernel_extended

    !> The uncoupled blocks' coefficients (A^zz, A^xx, A^xy, A^yy: those present) for offsets
    !! −mx…mx, −my…my at once.  A^zz, A^xx and A^yy share the 1/ρ term (A^xx and A^yy add
    !! one ν term each), which is evaluated once: all four take four antiderivatives instead
    !! of six, the three tangential ones three instead of five.  Each result equals
    !! [[ic_kernel_extended]]'s bit for bit (the same terms added in the same order).
    subroutine ic_kernels_uncoupled(mat, grid, mx, my, kzz, kxx, kxy, kyy)
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: mx, my
        real(dp), allocatable, intent(out), optional :: kzz(:, :), kxx(:, :), kxy(:, :), kyy(:, :)
        type(kernel_slot) :: k(4)
        integer :: blocks(4), n
        n = 0
        if (present(kzz)) call want(IC_ZZ)
        if (present(kxx)) call want(IC_XX)
        if (present(kxy)) call want(IC_XY)
        if (present(kyy)) call want(IC_YY)
        call half_space_kernels(mat, grid, mx, my, blocks(:n), k)
        n = 0
        if (present(kzz)) call take(kzz)
        if (present(kxx)) call take(kxx)
        if (present(kxy)) call take(kxy)
        if (present(kyy)) call take(kyy)
    contains
        subroutine want(block)
            integer, intent(in) :: block
            n = n + 1
            blocks(n) = block
        end subroutine want
        subroutine take(kernel)   ! the next result, in the order asked for
            real(dp), allocatable, intent(inout) :: kernel(:, :)
            n = n + 1
            call move_alloc(k(n)%c, kernel)
        end subroutine take
    end subroutine ic_kernels_uncoupled

    !> The coefficients of `blocks` (IC_*, each at most once) for offsets −mx…mx, −my…my into
    !! k(1:size(blocks)).  The 1/ρ term of A^zz, A^xx, A^yy is evaluated once for all of them.
    !! (`add_primitive` stays internal, on this routine's work arrays: as a module procedure
    !! on dummy arrays gfortran vectorised its uv/ρ³ loop differently — libmvec's hypot or
    !! not — and A^xy changed in the last bits.)
    subroutine half_space_kernels(mat, grid, mx, my, blocks, k)
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: mx, my
        integer, intent(in) :: blocks(:)
        type(kernel_slot), intent(inout) :: k(:)
        real(dp), allocatable :: fc(:, :), cx(:), cy(:), base(:, :)
        real(dp) :: c
        integer :: i, j, b
        allocate (cx(-mx:mx + 1), cy(-my:my + 1), fc(-mx:mx + 1, -my:my + 1))
        do i = -mx, mx + 1
            cx(i) = (i - 0.5_dp)*grid%dx
        end do
        do j = -my, my + 1
            cy(j) = (j - 0.5_dp)*grid%dy
        end do
        c = 1/(pi*mat%g)
        ! the 1/ρ term shared by A^zz, A^xx, A^yy (computed as A^zz is: 0 + the term)
        if (any(blocks == IC_ZZ .or. blocks == IC_XX .or. blocks == IC_YY)) then
            allocate (base(-mx:mx, -my:my))
            base = 0
            call add_primitive(1, c*(1 - mat%nu), base)
        end if
        do b = 1, size(blocks)
            select case (blocks(b))
            case (IC_ZZ, IC_XX, IC_YY)
                ! the last block that needs the shared term takes it instead of a copy
                if (any(blocks(b + 1:) == IC_ZZ .or. blocks(b + 1:) == IC_XX .or. blocks(b + 1:) == IC_YY)) then
                    k(b)%c = base
                else
                    call move_alloc(base, k(b)%c)
                end if
            case default
                allocate (k(b)%c(-mx:mx, -my:my))
                k(b)%c = 0
            end select
            select case (blocks(b))
            case (IC_XX)
                call add_primitive(2, c*mat%nu, k(b)%c)
            case (IC_YY)
                call add_primitive(3, c*mat%nu, k(b)%c)
            case (IC_XY)
                call add_primitive(4, c*mat%nu, k(b)%c)
            case (IC_XZ)
                call add_primitive(5, -c*mat%k, k(b)%c)
            case (IC_ZX)
                call add_primitive(5, c*mat%k, k(b)%c)
            case (IC_YZ)
                call add_primitive(6, -c*mat%k, k(b)%c)
            case (IC_ZY)
                call add_primitive(6, c*mat%k, k(b)%c)
            end select
        end do
    contains
        !> kernel += factor × the double difference of antiderivative `which` (1: 1/ρ,
        !! 2: u²/ρ³, 3: v²/ρ³, 4: uv/ρ³, 5: u/ρ², 6: v/ρ²) over the elements.
        subroutine add_primitive(which, factor, kernel)
            integer, intent(in) :: which
            real(dp), intent(in) :: factor
            real(dp), intent(inout) :: kernel(-mx:, -my:)
            integer :: ii, jj, im, jm
            real(dp) :: su, sv, s, d
            if (factor == 0) return
            ! The corners are symmetric (cx(1−i) = −cx(i), likewise cy) and every antiderivative
            ! is even or odd in each argument, so it is evaluated on the quadrant i, j ≥ 1 only
            ! and mirrored (exactly: asinh, atan are odd, hypot and log even) — a quarter of
            ! the special-function calls.  Rows are independent: shared among threads.
            su = -1; sv = -1                       ! parity in u (= x) and in v (= y)
            select case (which)
            case (4); su = 1; sv = 1               ! −ρ
            case (5); su = 1                       ! v·ln ρ + u·atan(v/u): even in u, odd in v
            case (6); sv = 1                       ! roles of u and v swapped
            end select
            !$omp parallel do default(shared) private(jj) schedule(static)
            do jj = 1, my + 1
                select case (which)
                case (1); fc(1:, jj) = f_inv_rho(cx(1:), cy(jj))
                case (2); fc(1:, jj) = f_uu_rho3(cx(1:), cy(jj))
                case (3); fc(1:, jj) = f_vv_rho3(cx(1:), cy(jj))
                case (4); fc(1:, jj) = f_uv_rho3(cx(1:), cy(jj))
                case (5); fc(1:, jj) = f_u_rho2(cx(1:), cy(jj))
                case default; fc(1:, jj) = f_u_rho2(cy(jj), cx(1:))
                end select
            end do
            !$omp end parallel do
            ! the other three quadrants, read from the first one only
            !$omp parallel do default(shared) private(ii, jj, im, jm, s) schedule(static)
            do jj = -my, my + 1
                jm = jj; s = 1
                if (jj <= 0) then
                    jm = 1 - jj; s = sv
                end if
                if (jj <= 0) fc(1:, jj) = s*fc(1:, jm)
                do ii = -mx, 0
                    im = 1 - ii
                    fc(ii, jj) = (su*s)*fc(im, jm)
                end do
            end do
            !$omp end parallel do
            ! The double difference inherits the reflections: A(−i, j) = −su·A(i, j) and
            ! A(i, −j) = −sv·A(i, j).  Computed for i, j ≥ 0 and mirrored, the coefficients
            ! keep these symmetries exactly, so an even block (A^xy as well as A^zz, A^xx,
            ! A^yy) gets a real symbol and an odd one an imaginary symbol ([[fc_toeplitz]]).
            !$omp parallel do default(shared) private(ii, jj, d) schedule(static)
            do jj = 0, my
                do ii = 0, mx
                    d = factor*(fc(ii + 1, jj + 1) - fc(ii + 1, jj) - fc(ii, jj + 1) + fc(ii, jj))
                    ! odd in x (y): exactly zero on the axis, not the rounding of a − b − a + b
                    if ((ii == 0 .and. su > 0) .or. (jj == 0 .and. sv > 0)) d = 0
                    kernel(ii, jj) = kernel(ii, jj) + d
                    if (ii > 0) kernel(-ii, jj) = kernel(-ii, jj) + (-su)*d
                    if (jj > 0) kernel(ii, -jj) = kernel(ii, -jj) + (-sv)*d
                    if (ii > 0 .and. jj > 0) kernel(-ii, -jj) = kernel(-ii, -jj) + (su*sv)*d
                end do
            end do
            !$omp end parallel do
        end subroutine add_primitive
    end subroutine half_space_kernels

    !> Build the BTTB operator of one influence block on `grid` (the half-space; the periodic
    !! half-space's kernels, lattice sums with the far images' tail, are [[fc_periodic]]'s).
    !! With `plans_from` (a built operator on the same grid) the FFT plans and buffers are
    !! shared with it.
    subroutine build_bttb(op, block, mat, grid, plans_from)
        type(fc_bttb), intent(inout) :: op
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        type(fc_bttb), intent(in), optional :: plans_from
        real(dp), allocatable :: kernel(:, :)
        call ic_kernel(block, mat, grid, kernel)
        call build_bttb_from_kernel(op, kernel, grid%nx, grid%ny, plans_from)
    end subroutine build_bttb

    !> Toeplitz approximation M ≈ A⁻¹ of one (symmetric) influence block (thesis §3.3.1,
    !! extended to 2D; see [[inverse_toeplitz_from_kernel]]).  With `plans_from` the FFT
    !! plans and buffers are shared with that operator (same grid).
    subroutine build_inverse_toeplitz(block, mat, grid, prec, min_symbol, plans_from)
        integer, intent(in) :: block
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        type(fc_bttb), intent(inout) :: prec
        real(dp), intent(out), optional :: min_symbol  !! smallest symbol value / largest (diagnostic)
        type(fc_bttb), intent(in), optional :: plans_from
        real(dp), allocatable :: kext(:, :)
        call ic_kernel_extended(block, mat, grid, grid%nx, grid%ny, kext)
        call inverse_toeplitz_from_kernel(kext, grid%nx, grid%ny, prec, min_symbol, plans_from)
    end subroutine build_inverse_toeplitz

    ! ------------------------------------------------- tabulated coefficients ----

    !> Allocate a zeroed set.
    subroutine ic_set_allocate(set, mx, my, dx, dy)
        type(fc_ic_set), intent(inout) :: set
        integer, intent(in) :: mx, my
        real(dp), intent(in) :: dx, dy
        if (allocated(set%a)) deallocate (set%a)
        set%mx = mx; set%my = my; set%dx = dx; set%dy = dy
        allocate (set%a(-mx:mx, -my:my, 3, 3), source=0.0_dp)
    end subroutine ic_set_allocate

    !> Component indices (i, j) of a library block IC_ZZ, IC_XX, ... (displacement i due to load j).
    pure subroutine ic_block_index(block, i, j)
        integer, intent(in) :: block
        integer, intent(out) :: i, j
        select case (block)
        case (IC_ZZ); i = 3; j = 3
        case (IC_XX); i = 1; j = 1
        case (IC_YY); i = 2; j = 2
        case (IC_XY); i = 1; j = 2
        case (IC_XZ); i = 1; j = 3
        case (IC_ZX); i = 3; j = 1
        case (IC_YZ); i = 2; j = 3
        case (IC_ZY); i = 3; j = 2
        case default; i = 0; j = 0
        end select
    end subroutine ic_block_index

    !> Whether two cell sizes agree to 1e-9 (relative).
    pure logical function same_cell_size(a, b)
        real(dp), intent(in) :: a, b
        same_cell_size = abs(a - b) <= 1.0e-9_dp*max(abs(a), abs(b))
    end function same_cell_size

    !> Whether a set (its header is enough: cell size and offsets) serves `grid`: the same
    !! cells (relative 1e−9) and offsets reaching at least nx−1, ny−1.  stat = FC_ERR_VALUE
    !! with the sizes in `errmsg` when not.
    subroutine check_ic_set_grid(set, grid, stat, errmsg)
        type(fc_ic_set), intent(in) :: set
        type(fc_grid), intent(in) :: grid
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = FC_ERR_VALUE
        if (.not. same_cell_size(set%dx, grid%dx) .or. .not. same_cell_size(set%dy, grid%dy)) then
            write (errmsg, '(a,2es14.6,a,2es14.6,a)') 'influence coefficients are for cells dx, dy = ', set%dx, set%dy, &
                ' mm, the grid has ', grid%dx, grid%dy, ' mm'
            return
        end if
        if (set%mx < grid%nx - 1 .or. set%my < grid%ny - 1) then
            write (errmsg, '(a,i0,a,i0,a,i0,a,i0,a)') 'influence coefficients reach offsets ', set%mx, ' x ', set%my, &
                ', the grid of ', grid%nx, ' x ', grid%ny, ' cells needs at least nx-1, ny-1'
            return
        end if
        stat = 0; errmsg = ''
    end subroutine check_ic_set_grid

    !> Kernel of one library block for a grid of nx×ny cells: kernel(−nx:nx, −ny:ny) (the
    !! offsets ±nx, ±ny serve only the preconditioner's wrap-around slot; when the set stops
    !! at nx−1 they repeat the last stored coefficient).
    subroutine ic_set_kernel(set, block, grid, kernel, stat, errmsg)
        type(fc_ic_set), intent(in) :: set
        integer, intent(in) :: block
        type(fc_grid), intent(in) :: grid
        real(dp), allocatable, intent(out) :: kernel(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: i, j, ix, iy, ci, cj
        call check_ic_set_grid(set, grid, stat, errmsg)
        if (stat /= 0) return
        call ic_block_index(block, i, j)
        allocate (kernel(-grid%nx:grid%nx, -grid%ny:grid%ny))
        do iy = -grid%ny, grid%ny
            cj = max(-set%my, min(set%my, iy))
            do ix = -grid%nx, grid%nx
                ci = max(-set%mx, min(set%mx, ix))
                kernel(ix, iy) = set%a(ci, cj, i, j)
            end do
        end do
        stat = 0; errmsg = ''
    end subroutine ic_set_kernel

end module fc_influence
