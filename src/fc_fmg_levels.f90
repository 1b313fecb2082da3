!> Multigrid grid hierarchy for the normal contact LCP: levels, their operators, and the
!! inter-grid transfers (thesis §2.4.2).
!!
!! * levels: the target grid coarsened by factors of two (both directions, keeping the
!!   cells' aspect ratio, or one direction for a strip) down to `coarsest` cells; each
!!   level has its own influence coefficients (same material, doubled element size) and
!!   its own undeformed distance h0, from an [[fc_surface]] or averaged over 2×2 cells;
!! * restriction: four-point average of the defect; a coarse cell is in contact when any
!!   of its four fine cells is (restriction of the active set);
!! * interpolation: copy (piecewise constant) of the coarse correction, and bilinear
!!   interpolation of the deformation for the nested iteration (thesis §2.4.3).
module fc_fmg_levels
    use fc_kinds
    use fc_errors, only: FC_ERR_GRID
    use fc_geometry, only: fc_grid, make_grid, h_no_contact
    use fc_geometry_grid, only: fc_surface
    use fc_fmg_types, only: fc_fmg_settings
    use fc_influence
    implicit none
    private

    ! the settings type lives in [[fc_fmg_types]] (below the orchestrator's types)
    public :: fc_fmg_settings

    !> One grid level: grid, influence operator, undeformed distance.
    type, public :: fmg_level
        type(fc_grid) :: grid
        type(fc_bttb) :: op                 !! A on this level (FFT products, kernel rows for GS)
        type(fc_bttb) :: prec               !! M ≈ A⁻¹ (only for the 'fft-rsm' smoother)
        real(dp) :: gamma = 0               !! RSM level γ = min row sum of M (eq. 3.19)
        real(dp), allocatable :: h0(:, :)   !! undeformed distance without approach
        logical, allocatable :: allowed(:, :)
        real(dp) :: cost = 1                !! n_level / n_target
        integer :: fx = 1, fy = 1           !! coarsening factors towards the next coarser level
        !> the smoothers' work arrays (made at first use): Gauss–Seidel's partial sums in plane 1;
        !! the FFT smoothers' products in planes 1 and 2
        real(dp), allocatable :: work(:, :, :)
    end type fmg_level

    !> Grid hierarchy with its operators; build once, solve for many approaches.
    type, public :: fc_fmg_hierarchy
        integer :: nlev = 0
        type(fmg_level), allocatable :: lev(:)   !! 1 = coarsest, nlev = target
        type(fc_material) :: material
        logical :: has_prec = .false.
        real(dp) :: work = 0                      !! running work-unit counter
        real(dp) :: checks = 0                    !! running count of uncounted products
    contains
        procedure :: destroy => hierarchy_destroy
    end type fc_fmg_hierarchy

    integer, parameter, public :: max_coarsest_cells = 4096   !! dense LAPACK solve on the coarsest grid

    public :: build_fmg_hierarchy, build_preconditioners, fmg_cycle_from_name
    public :: restrict_defect, interp_copy, interp_bilinear

contains

    !> Parse a cycle name 'V(1,1)', 'V(1,0)', 'V(0,1)' (any ν1, ν2 ≥ 0, not both 0) into ν1, ν2.
    subroutine fmg_cycle_from_name(name, nu1, nu2, stat, errmsg)
        character(len=*), intent(in) :: name
        integer, intent(out) :: nu1, nu2
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: i1, i2, ic, ios
        character(len=:), allocatable :: s
        stat = 0; errmsg = ''; nu1 = 1; nu2 = 1
        s = trim(adjustl(name))
        i1 = index(s, '('); ic = index(s, ','); i2 = index(s, ')')
        ios = 1
        if (len(s) > 0 .and. i1 == 2 .and. ic > i1 .and. i2 == len(s) .and. i2 > ic) then
            if (s(1:1) == 'V' .or. s(1:1) == 'v') then
                read (s(i1 + 1:ic - 1), *, iostat=ios) nu1
                if (ios == 0) read (s(ic + 1:i2 - 1), *, iostat=ios) nu2
            end if
        end if
        if (ios /= 0 .or. nu1 < 0 .or. nu2 < 0 .or. (nu1 == 0 .and. nu2 == 0)) then   ! no nu1 + nu2: it can overflow
            stat = FC_ERR_VALUE; errmsg = "solver: cycle = '"//trim(name)//"' is not 'V(n1,n2)' with n1, n2 >= 0, n1 + n2 > 0"
            nu1 = 1; nu2 = 1
        end if
    end subroutine fmg_cycle_from_name

    ! ---- hierarchy -----------------------------------------------------------------------

    !> Build the grid hierarchy for `grid` (target) and material `mat` (combined constants
    !! set).  h0 on the coarse levels comes from `surface` when given, else from averaging
    !! the target `h0` over 2×2 cells (cells outside every child stay out of contact).
    subroutine build_fmg_hierarchy(hier, mat, grid, h0, settings, stat, errmsg, surface)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: h0(:, :)
        type(fc_fmg_settings), intent(in) :: settings
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        class(fc_surface), intent(in), optional :: surface
        integer :: nlev, nx, ny, l, fx, fy
        integer :: sx(64), sy(64), fxs(64), fys(64)
        stat = 0; errmsg = ''
        call hier%destroy()
        if (size(h0, 1) /= grid%nx .or. size(h0, 2) /= grid%ny) then
            stat = FC_ERR_SHAPE; write (errmsg, '(a,2(i0,1x),a,2(i0,1x))') 'fmg: h0 has shape ', shape(h0), &
                'but the grid is ', grid%nx, grid%ny
            return
        end if
        if (.not. (mat%g > 0)) then
            stat = FC_ERR_NOT_READY; errmsg = 'fmg: material not combined (call combine_material first)'; return
        end if
        if (settings%coarsest < 1) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a)') 'solver: coarsest = ', settings%coarsest, ' must be >= 1'; return
        end if
        ! level sizes, finest first
        nlev = 1; nx = grid%nx; ny = grid%ny
        sx(1) = nx; sy(1) = ny; fxs(1) = 1; fys(1) = 1
        do
            fx = 1; fy = 1
            if (mod(nx, 2) == 0 .and. nx/2 >= settings%coarsest) fx = 2
            if (mod(ny, 2) == 0 .and. ny/2 >= settings%coarsest) fy = 2
            if (fx*fy == 1 .or. nlev == 64) exit
            ! keep the cells' aspect ratio: coarsen both directions or stop (unless ny = 1 / nx = 1)
            if (fx /= fy .and. .not. (nx == 1 .or. ny == 1)) exit
            fxs(nlev) = fx; fys(nlev) = fy
            nx = nx/fx; ny = ny/fy
            nlev = nlev + 1
            sx(nlev) = nx; sy(nlev) = ny; fxs(nlev) = 1; fys(nlev) = 1
        end do
        if (nx*ny > max_coarsest_cells) then
            stat = FC_ERR_GRID
            write (errmsg, '(a,i0,a,i0,a,i0,a,i0,a,i0,a)') 'grid ', grid%nx, 'x', grid%ny, ' coarsens only to ', &
                nx, 'x', ny, ' (more than ', max_coarsest_cells, ' cells for the direct coarsest solve); '// &
                'use nx, ny with more factors of 2'
            return
        end if
        hier%nlev = nlev
        hier%material = mat
        allocate (hier%lev(nlev))
        do l = 1, nlev   ! l = 1 coarsest ↔ index nlev+1−l in the finest-first lists
            associate (lv => hier%lev(l), k => nlev + 1 - l)
                call make_grid(lv%grid, sx(k), sy(k), grid%xmin, grid%xmax, grid%ymin, grid%ymax, stat, errmsg)
                if (stat /= 0) return
                lv%fx = 1; lv%fy = 1
                if (l > 1) then
                    lv%fx = fxs(k); lv%fy = fys(k)
                end if
                lv%cost = real(sx(k), dp)*sy(k)/(real(grid%nx, dp)*grid%ny)
                call build_bttb(lv%op, IC_ZZ, mat, lv%grid)
                allocate (lv%h0(sx(k), sy(k)), lv%allowed(sx(k), sy(k)))
            end associate
        end do
        hier%lev(nlev)%h0 = h0
        do l = nlev - 1, 1, -1
            if (present(surface)) then
                call surface%evaluate(hier%lev(l)%grid, hier%lev(l)%h0)
            else
                call restrict_h0(hier%lev(l + 1)%h0, hier%lev(l + 1)%fx, hier%lev(l + 1)%fy, hier%lev(l)%h0)
            end if
        end do
        do l = 1, nlev
            hier%lev(l)%allowed = hier%lev(l)%h0 < 0.5_dp*h_no_contact
        end do
        if (settings%smoother == 'fft-rsm') call build_preconditioners(hier)
    end subroutine build_fmg_hierarchy

    !> M ≈ A⁻¹ on every level (thesis §3.3.1 in 2D) and γ = min row sum of M (eq. 3.19).
    subroutine build_preconditioners(hier)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        integer :: l
        real(dp), allocatable :: ones(:, :), rs(:, :)
        do l = 1, hier%nlev
            associate (lv => hier%lev(l))
                call build_inverse_toeplitz(IC_ZZ, hier%material, lv%grid, lv%prec, plans_from=lv%op)
                allocate (ones(lv%grid%nx, lv%grid%ny), rs(lv%grid%nx, lv%grid%ny))
                ones = 1
                call lv%prec%apply(ones, rs)
                lv%gamma = minval(rs)
                deallocate (ones, rs)
            end associate
        end do
        hier%has_prec = .true.
    end subroutine build_preconditioners

    !> Coarse h0: average over the allowed children; no contact if none is allowed.
    subroutine restrict_h0(hf, fx, fy, hc)
        real(dp), intent(in) :: hf(:, :)
        integer, intent(in) :: fx, fy
        real(dp), intent(out) :: hc(:, :)
        integer :: i, j, a, b, cnt
        real(dp) :: s
        do j = 1, size(hc, 2)
            do i = 1, size(hc, 1)
                s = 0; cnt = 0
                do b = 1, fy
                    do a = 1, fx
                        if (hf(fx*(i - 1) + a, fy*(j - 1) + b) < 0.5_dp*h_no_contact) then
                            s = s + hf(fx*(i - 1) + a, fy*(j - 1) + b); cnt = cnt + 1
                        end if
                    end do
                end do
                if (cnt > 0) then
                    hc(i, j) = s/cnt
                else
                    hc(i, j) = h_no_contact
                end if
            end do
        end do
    end subroutine restrict_h0

    subroutine hierarchy_destroy(self)
        class(fc_fmg_hierarchy), intent(inout) :: self
        integer :: l
        if (allocated(self%lev)) then
            do l = 1, size(self%lev)
                call self%lev(l)%op%destroy()
                call self%lev(l)%prec%destroy()
            end do
            deallocate (self%lev)
        end if
        self%nlev = 0
        self%has_prec = .false.
    end subroutine hierarchy_destroy

    !> Four-point (fx·fy-point) average of the defect; a coarse cell is in contact if any
    !! child is (thesis §2.4.2).
    subroutine restrict_defect(d, fx, fy, con, dc, conc)
        real(dp), intent(in) :: d(:, :)
        integer, intent(in) :: fx, fy
        logical, intent(in) :: con(:, :)
        real(dp), intent(out) :: dc(:, :)
        logical, intent(out) :: conc(:, :)
        integer :: i, j
        do j = 1, size(dc, 2)
            do i = 1, size(dc, 1)
                dc(i, j) = sum(d(fx*(i - 1) + 1:fx*i, fy*(j - 1) + 1:fy*j))/(fx*fy)
                conc(i, j) = any(con(fx*(i - 1) + 1:fx*i, fy*(j - 1) + 1:fy*j))
            end do
        end do
        where (.not. conc) dc = 0
    end subroutine restrict_defect

    !> Copy (piecewise-constant) interpolation from the coarse to the fine grid.
    subroutine interp_copy(vc, fx, fy, v)
        real(dp), intent(in) :: vc(:, :)
        integer, intent(in) :: fx, fy
        real(dp), intent(out) :: v(:, :)
        integer :: i, j
        do j = 1, size(v, 2)
            do i = 1, size(v, 1)
                v(i, j) = vc((i - 1)/fx + 1, (j - 1)/fy + 1)
            end do
        end do
    end subroutine interp_copy

    !> Bilinear interpolation of cell-centred values (linear extrapolation at the edges).
    subroutine interp_bilinear(uc, fx, fy, u)
        real(dp), intent(in) :: uc(:, :)
        integer, intent(in) :: fx, fy
        real(dp), intent(out) :: u(:, :)
        real(dp), allocatable :: tmp(:, :)
        integer :: i, j, i0, j0, nc
        real(dp) :: t, w
        allocate (tmp(size(u, 1), size(uc, 2)))
        nc = size(uc, 1)
        do i = 1, size(u, 1)
            if (nc == 1 .or. fx == 1) then
                tmp(i, :) = uc(min((i - 1)/fx + 1, nc), :)
                cycle
            end if
            t = (i - 0.5_dp)/fx + 0.5_dp            ! fine centre in coarse index units
            i0 = min(max(floor(t), 1), nc - 1)
            w = t - i0
            tmp(i, :) = (1 - w)*uc(i0, :) + w*uc(i0 + 1, :)
        end do
        nc = size(uc, 2)
        do j = 1, size(u, 2)
            if (nc == 1 .or. fy == 1) then
                u(:, j) = tmp(:, min((j - 1)/fy + 1, nc))
                cycle
            end if
            t = (j - 0.5_dp)/fy + 0.5_dp
            j0 = min(max(floor(t), 1), nc - 1)
            w = t - j0
            u(:, j) = (1 - w)*tmp(:, j0) + w*tmp(:, j0 + 1)
        end do
    end subroutine interp_bilinear

end module fc_fmg_levels
