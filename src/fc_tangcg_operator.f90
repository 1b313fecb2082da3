!> The tangential influence operator of one grid and material: the blocks A^xx, A^xy = A^yx,
!! A^yy and, for dissimilar bodies (K ≠ 0), the coupling blocks A^xz, A^yz, A^zx, A^zy
!! (signs in doc/conventions.md), with the combined 2×2 product used by the tangential
!! solvers ([[fc_tangcg]]) and the coupling displacements used by the Panagiotopoulos
!! iteration ([[fc_contact]]).  Storage and lifetime: doc/operators.md.
module fc_tangcg_operator
    use fc_kinds
    use fc_geometry, only: fc_grid
    use fc_influence
    use, intrinsic :: iso_c_binding, only: c_loc, c_associated
    use fc_tangprec, only: fc_block_inverse, build_block_inverse
    implicit none
    private

    !> Tangential influence blocks on one grid (and the coupling blocks when K ≠ 0).  All
    !! blocks share a_xx's FFT plans and buffers (one set per grid); even blocks store real
    !! symbols, the odd coupling blocks their imaginary parts.  Plans are released by
    !! `destroy` or when the operator is dropped; a copy is independent of the original.
    type, public :: fc_tangential_operator
        type(fc_grid) :: grid
        type(fc_material) :: material
        type(fc_bttb) :: a_xx, a_xy, a_yy   !! tangential blocks (A^yx = A^xy)
        type(fc_bttb) :: a_xz, a_yz         !! u_t from pn (built only when K ≠ 0)
        type(fc_bttb) :: a_zx, a_zy         !! u_z from p_t (built only when K ≠ 0)
        complex(dp), allocatable :: spec_x(:, :), spec_y(:, :), work(:, :), work2(:, :)
        type(fc_block_inverse) :: prec      !! TangCG's FFT preconditioner (fc_tangprec)
        !> The preconditioner's Strang circulant on the grid (blocks M^xx, M^xy, M^yy, periodic,
        !! sharing one plan set; made on first use by [[apply_block_inverse]])
        type(fc_bttb) :: c_xx, c_xy, c_yy
        complex(dp), allocatable :: cspec_x(:, :), cspec_y(:, :), cwork(:, :), cwork2(:, :)
        integer :: nproducts = 0            !! combined 2×2 block products
        real(dp) :: setup_seconds = 0
        !> the blocks of the periodic half-space on the grid itself, preconditioned by their
        !! exact inverse in c_xx, c_xy, c_yy (fc_periodic); `prec` is then not built
        logical :: periodic = .false.
        !> periodic cell: compliance β [mm per N/mm²] given to the uniform traction mode, which
        !! the periodic blocks (mean removed) do not displace: A_β p = A p + β·mean(p) per
        !! component, its inverse's uniform mode 1/β.  Set only while a prescribed force is
        !! solved on a cell in contact everywhere ([[fc_tangcg_force]]), where it makes the
        !! shift–force map regular; 0 otherwise (the physical operator)
        real(dp) :: mean_compliance = 0
    contains
        procedure :: apply => tangential_apply
        procedure :: destroy => tangential_destroy
        procedure :: coupled => tangential_coupled
        procedure :: matches => tangential_matches
        procedure, private :: tangential_assign
        generic :: assignment(=) => tangential_assign
    end type fc_tangential_operator

    public :: build_tangential_operator, coupling_displacements, apply_block_inverse, prepare_block_inverse_circulant

contains

    !> Build the tangential blocks (and coupling blocks if K ≠ 0) for `grid`.
    subroutine build_tangential_operator(top, material, grid, ic, kxx_in, kxy_in, kyy_in, plans_from)
        type(fc_tangential_operator), intent(inout) :: top
        type(fc_material), intent(in) :: material
        type(fc_grid), intent(in) :: grid
        type(fc_ic_set), intent(in), optional :: ic   !! coefficients instead of the half-space ones
        !> the half-space A^xx, A^xy, A^yy for offsets −nx…nx, −ny…ny computed by the caller
        !! ([[ic_kernels_uncoupled]]); taken (deallocated).  All three or none.
        real(dp), allocatable, intent(inout), optional :: kxx_in(:, :), kxy_in(:, :), kyy_in(:, :)
        !> an operator of the same grid whose FFT plans and buffers the blocks share (the
        !! normal one: one set per grid); not one whose products may run at the same time
        type(fc_bttb), intent(in), optional :: plans_from
        integer(i8) :: t0, t1, rate   ! 64-bit: a µs clock (default integers tick in ms)
        call system_clock(t0, rate)
        call top%destroy()
        top%grid = grid
        top%material = material
        ! one coefficient evaluation per block serves A (offsets < n) and TangCG's
        ! preconditioner (offsets ≤ n)
        block
            real(dp), allocatable :: kxx(:, :), kxy(:, :), kyy(:, :)
            if (present(kxx_in) .and. present(kxy_in) .and. present(kyy_in)) then
                call move_alloc(kxx_in, kxx); call move_alloc(kxy_in, kxy); call move_alloc(kyy_in, kyy)
            else if (present(ic)) then
                call ic_block(IC_XX, kxx); call ic_block(IC_XY, kxy); call ic_block(IC_YY, kyy)
            else
                call ic_kernels_uncoupled(material, grid, grid%nx, grid%ny, kxx=kxx, kxy=kxy, kyy=kyy)
            end if
            ! the blocks take the coefficients (no copies); the preconditioner reads them
            ! there and transforms on the blocks' plans
            call build_bttb_taking_kernel(top%a_xx, kxx, grid%nx, grid%ny, plans_from)
            call build_bttb_taking_kernel(top%a_xy, kxy, grid%nx, grid%ny, top%a_xx)
            call build_bttb_taking_kernel(top%a_yy, kyy, grid%nx, grid%ny, top%a_xx)
            call build_block_inverse(top%prec, top%a_xx%kernel, top%a_xy%kernel, top%a_yy%kernel, grid%nx, grid%ny, &
                plans_from=top%a_xx)
        end block
        if (material%k /= 0) then
            call build_block(top%a_xz, IC_XZ, top%a_xx)
            call build_block(top%a_yz, IC_YZ, top%a_xx)
            call build_block(top%a_zx, IC_ZX, top%a_xx)
            call build_block(top%a_zy, IC_ZY, top%a_xx)
        end if
        allocate (top%spec_x(top%a_xx%mx/2 + 1, top%a_xx%my))
        allocate (top%spec_y, top%work, top%work2, mold=top%spec_x)
        top%nproducts = 0
        call system_clock(t1)
        top%setup_seconds = real(t1 - t0, dp)/rate
    contains
        !> One block from the half-space formulas or from `ic`, sharing the plans of `plans_from`.
        subroutine build_block(op, block, plans_from)
            type(fc_bttb), intent(inout) :: op
            integer, intent(in) :: block
            type(fc_bttb), intent(in), optional :: plans_from
            real(dp), allocatable :: k(:, :)
            integer :: stat
            character(len=msg_len) :: msg
            if (present(ic)) then
                call ic_set_kernel(ic, block, grid, k, stat, msg)
                call build_bttb_from_kernel(op, k(-(grid%nx - 1):grid%nx - 1, -(grid%ny - 1):grid%ny - 1), grid%nx, grid%ny, &
                    plans_from)
            else
                call build_bttb(op, block, material, grid, plans_from=plans_from)
            end if
        end subroutine build_block
        !> Coefficients of one block for offsets −n…n from `ic`.
        subroutine ic_block(block, k)
            integer, intent(in) :: block
            real(dp), allocatable, intent(out) :: k(:, :)
            integer :: stat
            character(len=msg_len) :: msg
            call ic_set_kernel(ic, block, grid, k, stat, msg)
        end subroutine ic_block
    end subroutine build_tangential_operator

    subroutine tangential_destroy(self)
        class(fc_tangential_operator), intent(inout) :: self
        call self%a_xx%destroy(); call self%a_xy%destroy(); call self%a_yy%destroy()
        call self%a_xz%destroy(); call self%a_yz%destroy()
        call self%a_zx%destroy(); call self%a_zy%destroy()
        if (allocated(self%spec_x)) deallocate (self%spec_x, self%spec_y, self%work, self%work2)
        self%prec = fc_block_inverse()
        call self%c_xx%destroy(); call self%c_xy%destroy(); call self%c_yy%destroy()
        if (allocated(self%cspec_x)) deallocate (self%cspec_x, self%cspec_y, self%cwork, self%cwork2)
        self%periodic = .false.
    end subroutine tangential_destroy

    !> Whether the built blocks serve `grid` and `material`: same element count and size
    !! (relative 1e−12) and the same G, ν and K (K decides the coupling blocks).
    pure logical function tangential_matches(self, grid, material) result(ok)
        class(fc_tangential_operator), intent(in) :: self
        type(fc_grid), intent(in) :: grid
        type(fc_material), intent(in) :: material
        ok = self%a_xx%built() .and. self%grid%nx == grid%nx .and. self%grid%ny == grid%ny .and. &
            abs(self%grid%dx - grid%dx) <= 1e-12_dp*grid%dx .and. abs(self%grid%dy - grid%dy) <= 1e-12_dp*grid%dy &
            .and. self%material%g == material%g .and. self%material%nu == material%nu .and. self%material%k == material%k
    end function tangential_matches
    !> `lhs = rhs`: deep copy; the copy's blocks share their own new plan set.
    !! (Explicit rather than component-wise: gfortran 12 finalizes a shallow temporary in
    !! the intrinsic assignment of a type with finalizable components.)
    subroutine tangential_assign(lhs, rhs)
        class(fc_tangential_operator), intent(inout) :: lhs
        type(fc_tangential_operator), intent(in) :: rhs
        if (same_object(lhs, rhs)) return
        call lhs%destroy()
        lhs%grid = rhs%grid
        lhs%material = rhs%material
        lhs%nproducts = rhs%nproducts
        lhs%setup_seconds = rhs%setup_seconds
        lhs%periodic = rhs%periodic
        lhs%mean_compliance = rhs%mean_compliance
        call copy_bttb(lhs%a_xx, rhs%a_xx)
        call copy_bttb(lhs%a_xy, rhs%a_xy, plans_from=lhs%a_xx)
        call copy_bttb(lhs%a_yy, rhs%a_yy, plans_from=lhs%a_xx)
        call copy_bttb(lhs%a_xz, rhs%a_xz, plans_from=lhs%a_xx)
        call copy_bttb(lhs%a_yz, rhs%a_yz, plans_from=lhs%a_xx)
        call copy_bttb(lhs%a_zx, rhs%a_zx, plans_from=lhs%a_xx)
        call copy_bttb(lhs%a_zy, rhs%a_zy, plans_from=lhs%a_xx)
        if (allocated(rhs%spec_x)) allocate (lhs%spec_x, lhs%spec_y, lhs%work, lhs%work2, mold=rhs%spec_x)
        lhs%prec = rhs%prec
        call copy_bttb(lhs%c_xx, rhs%c_xx)
        call copy_bttb(lhs%c_xy, rhs%c_xy, plans_from=lhs%c_xx)
        call copy_bttb(lhs%c_yy, rhs%c_yy, plans_from=lhs%c_xx)
        if (allocated(rhs%cspec_x)) allocate (lhs%cspec_x, lhs%cspec_y, lhs%cwork, lhs%cwork2, mold=rhs%cspec_x)
    contains
        logical function same_object(a, b)
            class(fc_tangential_operator), intent(in), target :: a
            type(fc_tangential_operator), intent(in), target :: b
            same_object = c_associated(c_loc(a%setup_seconds), c_loc(b%setup_seconds))
        end function same_object
    end subroutine tangential_assign

    !> (zx, zy) = M (dx, dy), M the FFT block preconditioner of [[fc_tangprec]] (TangCG's, and
    !! the steady rolling solver's): with `circulant`, M's Strang circulant on the grid
    !! (periodic transforms of nx×ny points; made on first use), else M itself on the doubled
    !! grid.  Two forward and two inverse transforms either way.  A periodic operator has
    !! one form only, the exact inverse on the grid.
    subroutine apply_block_inverse(top, dx, dy, zx, zy, circulant)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: dx(:, :), dy(:, :)
        real(dp), intent(out) :: zx(:, :), zy(:, :)
        logical, intent(in) :: circulant
        if (circulant .or. top%periodic) then
            call prepare_block_inverse_circulant(top)
            call block_product(top%c_xx, top%c_xy, top%c_yy, top%cspec_x, top%cspec_y, top%cwork, top%cwork2, &
                               dx, dy, zx, zy)
            ! the inverse of A_β: uniform mode 1/β (the circulant's zero-frequency block is
            ! diagonal, so the means are replaced component by component)
            if (top%mean_compliance > 0) then
                zx = zx - sum(zx)/size(zx) + sum(dx)/(size(dx)*top%mean_compliance)
                zy = zy - sum(zy)/size(zy) + sum(dy)/(size(dy)*top%mean_compliance)
            end if
            return
        end if
        call top%a_xx%forward(dx, top%spec_x)
        call top%a_xx%forward(dy, top%spec_y)
        call block_symbol_product_in_place(top%spec_x, top%spec_y, top%prec%mxx, top%prec%mxy, top%prec%myy, &
            conjugate=.false.)
        call top%a_xx%backward(top%spec_x, zx)
        call top%a_xx%backward(top%spec_y, zy)
    end subroutine apply_block_inverse

    !> Make the Strang circulants of the block inverse's blocks (from their symbols on the
    !! doubled grid) unless they exist: on the first circulant application, or ahead of the
    !! solve (the orchestrator does it inside the operator build, where it overlaps the
    !! normal build on a second thread).
    subroutine prepare_block_inverse_circulant(top)
        type(fc_tangential_operator), intent(inout) :: top
        if (top%c_xx%built()) return
        call strang_circulant_of_symbol(top%a_xx, top%prec%mxx, top%c_xx, keep_kernel=.false.)
        call strang_circulant_of_symbol(top%a_xx, top%prec%mxy, top%c_xy, plans_from=top%c_xx, keep_kernel=.false.)
        call strang_circulant_of_symbol(top%a_xx, top%prec%myy, top%c_yy, plans_from=top%c_xx, keep_kernel=.false.)
        if (allocated(top%cspec_x)) deallocate (top%cspec_x, top%cspec_y, top%cwork, top%cwork2)
        allocate (top%cspec_x(top%c_xx%mx/2 + 1, top%c_xx%my))   ! the circulants' period (strang_period)
        allocate (top%cspec_y, top%cwork, top%cwork2, mold=top%cspec_x)
    end subroutine prepare_block_inverse_circulant

    !> True when the normal and tangential problems are coupled (K ≠ 0).
    pure logical function tangential_coupled(self)
        class(fc_tangential_operator), intent(in) :: self
        tangential_coupled = self%a_xz%built()
    end function tangential_coupled

    !> (ux, uy) = [A^xx A^xy; A^xy A^yy]·(px, py): two forward and two inverse FFTs (plus
    !! β·mean(p) with a `mean_compliance` β).
    subroutine tangential_apply(self, px, py, ux, uy)
        class(fc_tangential_operator), intent(inout) :: self
        real(dp), intent(in) :: px(:, :), py(:, :)
        real(dp), intent(out) :: ux(:, :), uy(:, :)
        call block_product(self%a_xx, self%a_xy, self%a_yy, self%spec_x, self%spec_y, self%work, self%work2, &
                           px, py, ux, uy)
        if (self%mean_compliance > 0) then
            ux = ux + self%mean_compliance*sum(px)/size(px)
            uy = uy + self%mean_compliance*sum(py)/size(py)
        end if
        self%nproducts = self%nproducts + 1
    end subroutine tangential_apply

    !> Coupling displacements for K ≠ 0: tangential (A^xz pn, A^yz pn) and normal
    !! A^zx px + A^zy py.  Zero when the bodies are quasi-identical.
    subroutine coupling_displacements(top, pn, px, py, ux_from_pn, uy_from_pn, uz_from_pt)
        type(fc_tangential_operator), intent(inout) :: top
        real(dp), intent(in) :: pn(:, :), px(:, :), py(:, :)
        real(dp), intent(out) :: ux_from_pn(:, :), uy_from_pn(:, :), uz_from_pt(:, :)
        real(dp), allocatable :: tmp(:, :)
        if (.not. top%coupled()) then
            ux_from_pn = 0; uy_from_pn = 0; uz_from_pt = 0
            return
        end if
        allocate (tmp, mold=pn)
        call top%a_xz%apply(pn, ux_from_pn)
        call top%a_yz%apply(pn, uy_from_pn)
        call top%a_zx%apply(px, uz_from_pt)
        call top%a_zy%apply(py, tmp)
        uz_from_pt = uz_from_pt + tmp
    end subroutine coupling_displacements

end module fc_tangcg_operator
