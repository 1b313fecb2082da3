!> Full multigrid (FMG) for the normal contact LCP (thesis ch. 2, §2.4; SPEC §3).
!!
!! The LCP e = h + A p ≥ 0, p ≥ 0, e·p = 0 is solved by an *MG + active set* iteration:
!! each active-set iteration applies ONE multigrid V-cycle to A_CC p_C = −h_C on the
!! current contact set C, then updates C (drop p < 0, add e ≤ 0; thesis §2.4.1).
!!
!! Multigrid components (thesis §2.4.2):
!!
!! * smoother: damped Gauss–Seidel (ω = 0.8 by default) acting on the contact set only
!!   (lexicographic order).  A is dense, so a sweep costs O(n_C·n) — O(n²) — as in the
!!   thesis; the rows are read from the BTTB kernel, never from a stored dense matrix.
!!   Damped Jacobi is available only to demonstrate its failure (thesis Fig. 2.6), and
!!   'fft-rsm' is the O(n log n) smoother beyond the thesis (its outlook §6.3): Richardson
!!   with the Toeplitz approximation M ≈ A⁻¹ (§3.3.1 in 2D) reduced to C and row-sum
!!   modified as in eq. (3.21).
!! * restriction: four-point average of the defect; a coarse cell is in contact when any
!!   of its four fine cells is (restriction of the active set);
!! * interpolation: copy (piecewise constant) of the coarse correction, zero outside C;
!! * coarse operators: each level's own influence coefficients (same material, doubled
!!   element size); coarsest grid (4×4 by default) solved exactly with LAPACK (dposv) on
!!   the contact subset;
!! * all exterior quantities (pressure, defect, correction) are zero.
!!
!! FMG (nested iteration, §2.4.3): the coarsest LCP is solved exactly; going up one level
!! the pressure is copied, the deformation u = A p is interpolated bilinearly, and the
!! initial contact set is {e = h + u ≤ β·max(u)} (eq. 2.17, β = 0.003).  Intermediate
!! levels iterate until the contact set stops changing; the target level until it stops
!! changing AND the stopping rule (2.18) ‖d‖_rms/‖h‖_rms ≤ tol holds, with d the defect
!! −h − A p and h taken over the contact set.
!!
!! FMG needs h on every level.  Pass an [[fc_surface]] (a formula evaluated on each grid,
!! as the thesis does for the rough surface, Fig. 2.11) or let the solver average the
!! target-grid h0 over 2×2 cells.
!!
!! Work units (thesis §2.5.1): one product with A on the target grid = 1; a smoothing
!! sweep or a defect on a level with n_l cells costs n_l/n_target; the coarsest exact solve
!! is free.  As in the thesis, the product u = A p used by the active-set update (done by
!! FFT) is not counted; it is reported separately in [[fc_fmg_stats]].  Non-GS smoothers
!! are counted by their FFT products: Jacobi 1 per sweep, FFT+RSM 2 per sweep (A and M)
!! plus 1 per cycle and level for the row sums M·1_C.
module fc_fmg
    use fc_kinds
    use fc_errors, only: FC_ERR_GRID
    use fc_geometry, only: fc_grid, make_grid, h_no_contact, quadratic_gap, punch_rough_gap, wavy_gap, &
        fc_rough_params
    use fc_influence
    use fc_norm, only: fc_normal_result
    implicit none
    private

    !> Undeformed distance h0 (without approach) as a formula that can be evaluated on
    !! any grid; FMG evaluates it on every level.  Extend it for your own geometry.
    type, abstract, public :: fc_surface
    contains
        procedure(surface_evaluate), deferred :: evaluate
    end type fc_surface

    abstract interface
        !> h0 [mm] at the element centres of `grid`; `h_no_contact` where no contact can occur.
        subroutine surface_evaluate(self, grid, h0)
            import :: fc_surface, fc_grid, dp
            class(fc_surface), intent(in) :: self
            type(fc_grid), intent(in) :: grid
            real(dp), intent(out) :: h0(:, :)
        end subroutine surface_evaluate
    end interface

    !> Quadratic (Hertzian) profile h0 = x²/(2 rx) + y²/(2 ry), thesis §2.5.1.
    type, extends(fc_surface), public :: fc_quadratic_surface
        real(dp) :: rx = 0, ry = 0   !! relative radii of curvature [mm] (0: flat)
    contains
        procedure :: evaluate => quadratic_evaluate
    end type fc_quadratic_surface

    !> Rigid flat punch on a random rough surface, thesis §2.5.2 (eqs. 2.13–2.16).
    type, extends(fc_surface), public :: fc_punch_rough_surface
        real(dp) :: diameter = 8.97_dp        !! punch diameter [mm]
        type(fc_rough_params) :: rough        !! σ, γ, M, N, seed
    contains
        procedure :: evaluate => punch_rough_evaluate
    end type fc_punch_rough_surface

    !> Wavy surface A·(1 − cos(2πx/λx)·cos(2πy/λy)).
    type, extends(fc_surface), public :: fc_wavy_surface
        real(dp) :: amplitude = 0, wavelength_x = 0, wavelength_y = 0  !! [mm]
    contains
        procedure :: evaluate => wavy_evaluate
    end type fc_wavy_surface

    !> Settings of the FMG / MG + active-set solver.
    type, public :: fc_fmg_settings
        integer :: nu1 = 1                 !! pre-smoothing sweeps (V(nu1,nu2))
        integer :: nu2 = 1                 !! post-smoothing sweeps
        real(dp) :: omega = 0.8_dp         !! damping of the smoother (thesis Table 2.1)
        real(dp) :: beta = 0.003_dp        !! initial-area parameter of eq. (2.17)
        real(dp) :: tol = 1.0e-6_dp        !! stopping rule (2.18) on the target grid
        integer :: maxit = 100             !! active-set iterations (cycles) on the target grid
        integer :: maxit_level = 50        !! active-set iterations on intermediate grids
        integer :: coarsest = 4            !! stop coarsening below this many cells per direction
        logical :: nested = .true.         !! .true.: FMG; .false.: MG + active set from {h ≤ 0}
        character(len=8) :: smoother = 'gs'  !! 'gs' (thesis), 'jacobi' (fails), 'fft-rsm' (§6.3)
        logical :: keep_history = .false.  !! store the pressure after every target-grid cycle
        real(dp) :: rsm_floor = 0.8_dp     !! 'fft-rsm': diagonal of M̄ floored at rsm_floor/A_ii (0: thesis RSM)
    end type fc_fmg_settings

    !> Diagnostics of one FMG solve.
    type, public :: fc_fmg_stats
        integer :: levels = 0                         !! number of grid levels
        integer, allocatable :: nx(:), ny(:)          !! level sizes, 1 = coarsest
        integer, allocatable :: level_iterations(:)   !! active-set iterations per level
        real(dp) :: work_units = 0                    !! thesis work units (see module header)
        real(dp) :: check_products = 0                !! uncounted A·p for the active-set update, in target units
        real(dp), allocatable :: residual(:)          !! (2.18) after each target-grid cycle
        logical, allocatable :: area_changed(:)       !! contact set modified after that cycle ("(C)")
        real(dp), allocatable :: p_history(:, :, :)   !! pressures: initial (0) and after each cycle
        integer :: ncon_initial = 0                   !! elements in the initial target contact set
        real(dp) :: convergence_factor = 0            !! (2.18) residual: (r_m/r_1)^(1/(m−1)) on the target grid
    end type fc_fmg_stats

    !> One grid level: grid, influence operator, undeformed distance.
    type :: fmg_level
        type(fc_grid) :: grid
        type(fc_bttb) :: op                 !! A on this level (FFT products, kernel rows for GS)
        type(fc_bttb) :: prec               !! M ≈ A⁻¹ (only for the 'fft-rsm' smoother)
        real(dp) :: gamma = 0               !! RSM level γ = min row sum of M (eq. 3.19)
        real(dp), allocatable :: h0(:, :)   !! undeformed distance without approach
        logical, allocatable :: allowed(:, :)
        real(dp) :: cost = 1                !! n_level / n_target
        integer :: fx = 1, fy = 1           !! coarsening factors towards the next coarser level
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

    interface
        subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: dp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: info
        end subroutine dposv
        subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
            import :: dp
            character(len=1), intent(in) :: jobvl, jobvr
            integer, intent(in) :: n, lda, ldvl, ldvr, lwork
            real(dp), intent(inout) :: a(lda, *)
            real(dp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
            integer, intent(out) :: info
        end subroutine dgeev
    end interface

    integer, parameter :: max_coarsest_cells = 4096   !! dense LAPACK solve on the coarsest grid

    public :: solve_normal_fmg, build_fmg_hierarchy, fmg_solve_lcp, mg_solve_fixed
    public :: fmg_cycle_from_name, smoother_eigenvalues

contains

    ! ---- surfaces ------------------------------------------------------------------------

    subroutine quadratic_evaluate(self, grid, h0)
        class(fc_quadratic_surface), intent(in) :: self
        type(fc_grid), intent(in) :: grid
        real(dp), intent(out) :: h0(:, :)
        h0 = quadratic_gap(grid, self%rx, self%ry)
    end subroutine quadratic_evaluate

    subroutine punch_rough_evaluate(self, grid, h0)
        class(fc_punch_rough_surface), intent(in) :: self
        type(fc_grid), intent(in) :: grid
        real(dp), intent(out) :: h0(:, :)
        call punch_rough_gap(grid, self%diameter, self%rough, h0)
    end subroutine punch_rough_evaluate

    subroutine wavy_evaluate(self, grid, h0)
        class(fc_wavy_surface), intent(in) :: self
        type(fc_grid), intent(in) :: grid
        real(dp), intent(out) :: h0(:, :)
        h0 = wavy_gap(grid, self%amplitude, self%wavelength_x, self%wavelength_y)
    end subroutine wavy_evaluate

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
            stat = 1; errmsg = "solver: cycle = '"//trim(name)//"' is not 'V(n1,n2)' with n1, n2 >= 0, n1 + n2 > 0"
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
            stat = 1; write (errmsg, '(a,2(i0,1x),a,2(i0,1x))') 'fmg: h0 has shape ', shape(h0), &
                'but the grid is ', grid%nx, grid%ny
            return
        end if
        if (.not. (mat%g > 0)) then
            stat = 1; errmsg = 'fmg: material not combined (call combine_material first)'; return
        end if
        if (settings%coarsest < 1) then
            stat = 1; write (errmsg, '(a,i0,a)') 'solver: coarsest = ', settings%coarsest, ' must be >= 1'; return
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
                call build_inverse_toeplitz(IC_ZZ, hier%material, lv%grid, lv%prec)
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

    ! ---- public drivers ------------------------------------------------------------------

    !> Solve the normal contact problem by FMG (or MG + active set when
    !! `settings%nested = .false.`) with prescribed approach δ [mm] (or total force fn [N],
    !! by a secant iteration on δ around FMG).  Results in the [[fc_normal_result]] of
    !! fc_norm: `iterations` = active-set iterations (V-cycles) on the target grid,
    !! `outer_iterations` = the same (force mode: FMG solves), `matvecs` = work units rounded,
    !! `residual` = (2.18).  h0 is the target-grid distance without approach; `surface`
    !! (optional) gives h0 on the coarse levels.
    subroutine solve_normal_fmg(mat, grid, h0, settings, res, stat, errmsg, approach, fn, surface, stats)
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: h0(:, :)
        type(fc_fmg_settings), intent(in) :: settings
        type(fc_normal_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: approach, fn
        class(fc_surface), intent(in), optional :: surface
        type(fc_fmg_stats), intent(out), optional :: stats
        type(fc_fmg_hierarchy) :: hier
        type(fc_fmg_stats) :: st
        call build_fmg_hierarchy(hier, mat, grid, h0, settings, stat, errmsg, surface)
        if (stat /= 0) return
        call fmg_solve_lcp(hier, settings, res, st, stat, errmsg, approach, fn)
        if (present(stats)) stats = st
        call hier%destroy()
    end subroutine solve_normal_fmg

    !> Solve the LCP on a built hierarchy (reusable for several approaches).
    subroutine fmg_solve_lcp(hier, settings, res, stats, stat, errmsg, approach, fn)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        type(fc_fmg_settings), intent(in) :: settings
        type(fc_normal_result), intent(out) :: res
        type(fc_fmg_stats), intent(out) :: stats
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: approach, fn
        integer :: t0, t1, rate
        stat = 0; errmsg = ''
        call check_settings(hier, settings, stat, errmsg)
        if (stat /= 0) return
        if (present(approach) .eqv. present(fn)) then
            stat = 1; errmsg = 'fmg: give exactly one of approach and fn'; return
        end if
        call system_clock(t0, rate)
        if (present(approach)) then
            call fmg_approach(hier, settings, approach, res, stats, stat, errmsg)
        else
            call fmg_force(hier, settings, fn, res, stats, stat, errmsg)
        end if
        call system_clock(t1)
        res%cpu_seconds = real(t1 - t0, dp)/rate
    end subroutine fmg_solve_lcp

    subroutine check_settings(hier, settings, stat, errmsg)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        type(fc_fmg_settings), intent(in) :: settings
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (hier%nlev < 1) then
            stat = 1; errmsg = 'fmg: hierarchy not built'; return
        end if
        if (settings%nu1 < 0 .or. settings%nu2 < 0 .or. settings%nu1 + settings%nu2 == 0) then
            stat = 1; write (errmsg, '(a,i0,a,i0,a)') 'solver: cycle V(', settings%nu1, ',', settings%nu2, &
                ') needs nu1, nu2 >= 0 and nu1 + nu2 > 0'
            return
        end if
        if (.not. (settings%omega > 0 .and. settings%omega < 2)) then
            stat = 1; write (errmsg, '(a,g0.4,a)') 'solver: omega = ', settings%omega, ' must lie in (0, 2)'; return
        end if
        if (.not. (settings%beta >= 0)) then
            stat = 1; write (errmsg, '(a,g0.4,a)') 'solver: beta = ', settings%beta, ' must be >= 0'; return
        end if
        if (.not. (settings%tol > 0)) then
            stat = 1; write (errmsg, '(a,es12.4,a)') 'solver: tol = ', settings%tol, ' must be > 0'; return
        end if
        if (settings%maxit < 1 .or. settings%maxit_level < 1) then
            stat = 1; write (errmsg, '(a,i0,a,i0,a)') 'solver: maxit = ', settings%maxit, ', maxit_level = ', &
                settings%maxit_level, ' must be >= 1'
            return
        end if
        select case (settings%smoother)
        case ('gs', 'jacobi')
        case ('fft-rsm')
            if (.not. hier%has_prec) call build_preconditioners(hier)
        case default
            stat = 1; errmsg = "solver: smoother = '"//trim(settings%smoother)//"' is not one of 'gs', 'jacobi', 'fft-rsm'"
        end select
    end subroutine check_settings

    !> FMG / MG + active set with prescribed approach.
    subroutine fmg_approach(hier, settings, delta, res, stats, stat, errmsg)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        type(fc_fmg_settings), intent(in) :: settings
        real(dp), intent(in) :: delta
        type(fc_normal_result), intent(out) :: res
        type(fc_fmg_stats), intent(out) :: stats
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), allocatable :: p(:, :), u(:, :), pc(:, :), uc(:, :), h(:, :)
        logical, allocatable :: con(:, :)
        integer :: l, nlev, nit, status
        real(dp) :: resid, umax
        character(len=msg_len) :: msg
        stat = 0; errmsg = ''
        nlev = hier%nlev
        associate (top => hier%lev(nlev))
            if (.not. any(top%allowed .and. top%h0 - delta <= 0)) then
                stat = 1; write (errmsg, '(a,es12.4,a)') 'normal: approach = ', delta, &
                    ' gives no contact (h0 − approach > 0 everywhere)'
                return
            end if
        end associate
        hier%work = 0; hier%checks = 0
        stats%levels = nlev
        allocate (stats%nx(nlev), stats%ny(nlev), stats%level_iterations(nlev))
        stats%level_iterations = 0
        do l = 1, nlev
            stats%nx(l) = hier%lev(l)%grid%nx; stats%ny(l) = hier%lev(l)%grid%ny
        end do
        if (settings%nested) then
            ! coarsest level: exact LCP (active set + direct solves)
            l = 1
            allocate (p(hier%lev(1)%grid%nx, hier%lev(1)%grid%ny))
            h = hier%lev(1)%h0 - delta
            con = hier%lev(1)%allowed .and. h <= 0
            p = 0
            call active_set(hier, 1, settings, delta, con, p, .false., 100, nit, status, resid, msg)
            stats%level_iterations(1) = nit
            do l = 2, nlev
                ! nested iteration: copy p, bilinear u, initial area e ≤ β max(u) (eq. 2.17)
                call move_alloc(p, pc)
                allocate (uc(size(pc, 1), size(pc, 2)))
                call hier%lev(l - 1)%op%apply(pc, uc)
                hier%checks = hier%checks + hier%lev(l - 1)%cost
                allocate (p(hier%lev(l)%grid%nx, hier%lev(l)%grid%ny), u(hier%lev(l)%grid%nx, hier%lev(l)%grid%ny))
                call interp_copy(pc, hier%lev(l)%fx, hier%lev(l)%fy, p)
                call interp_bilinear(uc, hier%lev(l)%fx, hier%lev(l)%fy, u)
                h = hier%lev(l)%h0 - delta
                umax = maxval(u)
                con = hier%lev(l)%allowed .and. (h + u <= settings%beta*umax)
                where (.not. con) p = 0
                deallocate (pc, uc, u)
                if (l < nlev) then
                    call active_set(hier, l, settings, delta, con, p, .false., settings%maxit_level, nit, status, &
                        resid, msg)
                    stats%level_iterations(l) = nit
                end if
            end do
            if (nlev == 1) then
                ! single level: the exact solve above is the answer
                call finish(status, resid, msg, nit)
                return
            end if
        else
            allocate (p(hier%lev(nlev)%grid%nx, hier%lev(nlev)%grid%ny))
            h = hier%lev(nlev)%h0 - delta
            con = hier%lev(nlev)%allowed .and. h <= 0
            p = 0
        end if
        stats%ncon_initial = count(con)
        call active_set(hier, nlev, settings, delta, con, p, .true., settings%maxit, nit, status, resid, msg, stats)
        stats%level_iterations(nlev) = nit
        call finish(status, resid, msg, nit)
    contains
        subroutine finish(status, resid, msg, nit)
            integer, intent(in) :: status, nit
            real(dp), intent(in) :: resid
            character(len=*), intent(in) :: msg
            associate (top => hier%lev(nlev))
                allocate (res%pn(top%grid%nx, top%grid%ny), res%gap(top%grid%nx, top%grid%ny))
                res%pn = max(p, 0.0_dp)
                call top%op%apply(res%pn, res%gap)
                res%gap = res%gap + top%h0 - delta
                where (.not. top%allowed) res%gap = h_no_contact
                res%approach = delta
                res%fn = sum(res%pn)*top%grid%area()
                res%pmax = maxval(res%pn)
                res%ncon = count(res%pn > 0)
                res%status = status
                res%iterations = nit
                res%outer_iterations = nit
                res%residual = resid
                res%message = msg
                stats%work_units = hier%work
                stats%check_products = hier%checks
                res%matvecs = nint(hier%work)
                if (allocated(stats%residual)) then
                    allocate (res%history(size(stats%residual)), source=stats%residual)
                end if
            end associate
        end subroutine finish
    end subroutine fmg_approach

    !> Prescribed total force: secant iteration on δ around FMG (F(δ) is increasing), the
    !! second guess from Hertz scaling.  Every FMG solve starts afresh; `iterations` and the
    !! work units add up over the solves, `outer_iterations` counts the solves.
    subroutine fmg_force(hier, settings, fn, res, stats, stat, errmsg)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        type(fc_fmg_settings), intent(in) :: settings
        real(dp), intent(in) :: fn
        type(fc_normal_result), intent(out) :: res
        type(fc_fmg_stats), intent(out) :: stats
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: d0, d1, f0, f1, d2, work, hmin, scale
        integer :: it, nsolve, iters
        stat = 0; errmsg = ''
        if (.not. (fn > 0)) then
            stat = 1; write (errmsg, '(a,es12.4,a)') 'normal: fn = ', fn, ' must be > 0'; return
        end if
        associate (top => hier%lev(hier%nlev))
            hmin = minval(top%h0, mask=top%allowed)
            scale = max(maxval(top%h0, mask=top%allowed) - hmin, 1.0e-6_dp)
        end associate
        work = 0; nsolve = 0; iters = 0
        ! first guess: 1 % of the profile range past first touch; second: Hertz scaling
        ! (δ − h_min) ∝ F^(2/3); then secant steps
        d0 = hmin + 0.01_dp*scale
        call one(d0, f0); if (stat /= 0) return
        if (f0 > 0) then
            d1 = hmin + (d0 - hmin)*(fn/f0)**(2.0_dp/3.0_dp)
        else
            d1 = hmin + 0.05_dp*scale
        end if
        call one(d1, f1); if (stat /= 0) return
        do it = 1, 60
            if (abs(f1 - fn) <= 0.1_dp*settings%tol*fn .or. res%status /= FC_CONVERGED) exit
            if (f1 /= f0) then
                d2 = d1 + (fn - f1)*(d1 - d0)/(f1 - f0)
            else
                d2 = d1 + scale
            end if
            ! keep the iterate in contact and the steps bounded
            d2 = max(d2, hmin + 1.0e-3_dp*(d1 - hmin))
            d0 = d1; f0 = f1; d1 = d2
            call one(d1, f1); if (stat /= 0) return
        end do
        res%outer_iterations = nsolve
        res%iterations = iters
        stats%work_units = work
        res%matvecs = nint(work)
        if (res%status == FC_CONVERGED .and. abs(f1 - fn) > 10*settings%tol*fn) then
            res%status = FC_NOT_CONVERGED
            write (res%message, '(a,es10.3,a,es10.3)') 'fmg force loop: force ', f1, ' differs from fn = ', fn
        end if
    contains
        subroutine one(d, f)
            real(dp), intent(in) :: d
            real(dp), intent(out) :: f
            call fmg_approach(hier, settings, d, res, stats, stat, errmsg)
            if (stat /= 0) then
                errmsg = 'fmg force loop: '//trim(errmsg); return
            end if
            nsolve = nsolve + 1
            iters = iters + res%iterations
            work = work + stats%work_units
            f = res%fn
        end subroutine one
    end subroutine fmg_force

    ! ---- MG + active set on one level ------------------------------------------------------

    !> MG + active-set iterations on level l (thesis §2.4.1).  With `to_tol`, stop when the
    !! contact set is unchanged and (2.18) holds; else as soon as the set is unchanged.
    !! The coarsest level (l = 1) uses exact solves instead of V-cycles.
    subroutine active_set(hier, l, settings, delta, con, p, to_tol, maxit, nit, status, resid, msg, stats)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        integer, intent(in) :: l, maxit
        type(fc_fmg_settings), intent(in) :: settings
        real(dp), intent(in) :: delta
        logical, intent(inout) :: con(:, :)
        real(dp), intent(inout) :: p(:, :)
        logical, intent(in) :: to_tol
        integer, intent(out) :: nit, status
        real(dp), intent(out) :: resid
        character(len=*), intent(out) :: msg
        type(fc_fmg_stats), intent(inout), optional :: stats
        real(dp), allocatable, dimension(:, :) :: h, u, rhs
        logical, allocatable :: con_new(:, :)
        real(dp) :: hn, r0
        logical :: changed
        integer :: k, kk
        real(dp), allocatable :: rhist(:), phist(:, :, :)
        logical, allocatable :: chist(:)
        allocate (h(size(p, 1), size(p, 2)), u(size(p, 1), size(p, 2)), rhs(size(p, 1), size(p, 2)))
        allocate (con_new(size(p, 1), size(p, 2)))
        associate (lv => hier%lev(l))
            h = lv%h0 - delta
            allocate (rhist(maxit), chist(maxit))
            if (present(stats) .and. settings%keep_history) then
                allocate (phist(size(p, 1), size(p, 2), 0:maxit))
                phist(:, :, 0) = p
            end if
            status = FC_NOT_CONVERGED; resid = huge(1.0_dp); nit = 0; r0 = -1
            write (msg, '(a,i0,a,i0,a,i0,a)') 'not converged in maxit = ', maxit, ' active-set iterations on ', &
                lv%grid%nx, 'x', lv%grid%ny
            do k = 1, maxit
                nit = k
                where (.not. con) p = 0
                if (.not. any(con)) then
                    u = 0
                else
                    where (con)
                        rhs = -h
                    elsewhere
                        rhs = 0
                    end where
                    call vcycle(hier, l, settings, con, rhs, p)
                    call lv%op%apply(p, u)
                    hier%checks = hier%checks + lv%cost
                end if
                ! defect of the linear system on the current set, relative to h (eq. 2.18)
                hn = sqrt(sum(h**2, mask=con))
                if (hn > 0) then
                    resid = sqrt(sum((h + u)**2, mask=con))/hn
                else
                    resid = 0
                end if
                if (r0 < 0 .and. any(con)) r0 = resid
                rhist(k) = resid
                ! (4.a) drop negative pressures (p_I = 0) → intermediate sets C̄, Ē;
                ! (4.b) add every element of Ē that penetrates, e = h + A p ≤ 0, with the
                ! deformation of the pressures AFTER 4.a.  Testing e with the u of step 3
                ! (which still contains the dropped tensile pressures) lowers e just outside
                ! the set: elements dropped one step are re-admitted the next, and MG +
                ! active set from C⁰ needed 14 (128²) / 28 (256²) V(1,1) iterations instead
                ! of the thesis' 10 / 12 (Table 2.2).  The extra product is uncounted
                ! (like the one of step 3) and skipped when nothing was dropped.
                con_new = con
                where (con .and. p < 0)
                    con_new = .false.
                    p = 0
                end where
                if (any(con .neqv. con_new)) then
                    call lv%op%apply(p, u)
                    hier%checks = hier%checks + lv%cost
                end if
                where (.not. con_new .and. lv%allowed .and. h + u <= 0) con_new = .true.
                changed = any(con_new .neqv. con)
                con = con_new
                chist(k) = changed
                if (allocated(phist)) phist(:, :, k) = p
                if (resid /= resid .or. resid > 1.0e6_dp*max(r0, 1.0e-300_dp) .or. resid > 1.0e8_dp) then
                    status = FC_DIVERGED
                    write (msg, '(a,es9.2,a,i0,a,i0,a,i0)') 'diverged: defect ', resid, ' after ', k, &
                        ' cycles on ', lv%grid%nx, 'x', lv%grid%ny
                    exit
                end if
                if (.not. changed .and. (.not. to_tol .or. resid <= settings%tol)) then
                    status = FC_CONVERGED; msg = 'converged'
                    exit
                end if
            end do
            if (present(stats) .and. to_tol) then
                kk = nit
                allocate (stats%residual(kk), source=rhist(1:kk))
                allocate (stats%area_changed(kk), source=chist(1:kk))
                if (allocated(phist)) allocate (stats%p_history(size(p, 1), size(p, 2), 0:kk), source=phist(:, :, 0:kk))
                if (kk > 0 .and. r0 > 0 .and. resid > 0) stats%convergence_factor = (resid/r0)**(1.0_dp/max(1, kk - 1))
            end if
        end associate
    end subroutine active_set

    !> Solve A_CC p_C = −h_C on a FIXED contact set `con` of the target level by V-cycles
    !! from p (the thesis' "C⁰ system", Table 2.1).  Returns cycles, the average defect
    !! reduction factor q = (‖d_m‖/‖d_0‖)^(1/m) and a status (diverged if ‖d‖ grows 1e6×).
    subroutine mg_solve_fixed(hier, settings, delta, con, p, cycles, factor, status, work_units)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        type(fc_fmg_settings), intent(in) :: settings
        real(dp), intent(in) :: delta
        logical, intent(in) :: con(:, :)
        real(dp), intent(inout) :: p(:, :)
        integer, intent(out) :: cycles, status
        real(dp), intent(out) :: factor
        real(dp), intent(out), optional :: work_units
        real(dp), allocatable :: h(:, :), rhs(:, :), u(:, :)
        real(dp) :: d0, d, hn
        integer :: k, stat
        character(len=msg_len) :: msg
        status = FC_NOT_CONVERGED; cycles = 0; factor = 0
        call check_settings(hier, settings, stat, msg)
        if (stat /= 0) then
            status = FC_ERROR; return
        end if
        allocate (h(size(p, 1), size(p, 2)), rhs(size(p, 1), size(p, 2)), u(size(p, 1), size(p, 2)))
        associate (lv => hier%lev(hier%nlev))
            h = lv%h0 - delta
            where (con)
                rhs = -h
            elsewhere
                rhs = 0
            end where
            where (.not. con) p = 0
            hier%work = 0
            hn = sqrt(sum(h**2, mask=con))
            call lv%op%apply(p, u)
            d0 = sqrt(sum((rhs + (-u))**2, mask=con))
            d = d0
            do k = 1, settings%maxit
                if (d <= settings%tol*hn) then
                    status = FC_CONVERGED; exit
                end if
                call vcycle(hier, hier%nlev, settings, con, rhs, p)
                call lv%op%apply(p, u)
                d = sqrt(sum((rhs - u)**2, mask=con))
                cycles = k
                if (d /= d .or. d > 1.0e6_dp*d0) then
                    status = FC_DIVERGED; exit
                end if
            end do
            if (status == FC_NOT_CONVERGED .and. d <= settings%tol*hn) status = FC_CONVERGED
            if (cycles > 0 .and. d0 > 0) factor = (d/d0)**(1.0_dp/cycles)
            if (present(work_units)) work_units = hier%work
        end associate
    end subroutine mg_solve_fixed

    ! ---- V-cycle ---------------------------------------------------------------------------

    !> One V(ν1,ν2)-cycle for A_CC p_C = rhs_C on level l (p = 0 outside `con`).
    recursive subroutine vcycle(hier, l, settings, con, rhs, p)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        integer, intent(in) :: l
        type(fc_fmg_settings), intent(in) :: settings
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(inout) :: p(:, :)
        real(dp), allocatable :: d(:, :), dc(:, :), vc(:, :), v(:, :), rs(:, :)
        logical, allocatable :: conc(:, :)
        integer :: k, ncx, ncy
        if (.not. any(con)) then
            p = 0; return
        end if
        if (l == 1) then
            call direct_solve(hier%lev(1), con, rhs, p)
            return
        end if
        associate (lv => hier%lev(l), lc => hier%lev(l - 1))
            do k = 1, settings%nu1
                call smooth(hier, l, settings, con, rhs, p, rs)
            end do
            allocate (d(size(p, 1), size(p, 2)))
            call lv%op%apply(p, d)
            hier%work = hier%work + lv%cost
            where (con)
                d = rhs - d
            elsewhere
                d = 0
            end where
            ncx = lc%grid%nx; ncy = lc%grid%ny
            allocate (dc(ncx, ncy), conc(ncx, ncy), vc(ncx, ncy), v(size(p, 1), size(p, 2)))
            call restrict_defect(d, lv%fx, lv%fy, con, dc, conc)
            vc = 0
            call vcycle(hier, l - 1, settings, conc, dc, vc)
            call interp_copy(vc, lv%fx, lv%fy, v)
            where (con) p = p + v
            do k = 1, settings%nu2
                call smooth(hier, l, settings, con, rhs, p, rs)
            end do
        end associate
    end subroutine vcycle

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

    ! ---- smoothers -------------------------------------------------------------------------

    !> One smoothing sweep on level l.  A GS sweep counts as one product on that level (the
    !! thesis' convention), a Jacobi sweep as one FFT product, an FFT+RSM sweep as two (A and M).
    subroutine smooth(hier, l, settings, con, rhs, p, rs)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        integer, intent(in) :: l
        type(fc_fmg_settings), intent(in) :: settings
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(inout) :: p(:, :)
        real(dp), allocatable, intent(inout) :: rs(:, :)
        select case (settings%smoother)
        case ('jacobi')
            call jacobi_sweep(hier%lev(l), con, rhs, p, settings%omega)
            hier%work = hier%work + hier%lev(l)%cost
        case ('fft-rsm')
            if (.not. allocated(rs)) then
                call rsm_rowsums(hier%lev(l), con, rs)
                hier%work = hier%work + hier%lev(l)%cost
            end if
            call fft_rsm_sweep(hier%lev(l), con, rhs, p, rs, settings%rsm_floor)
            hier%work = hier%work + 2*hier%lev(l)%cost
        case default
            call gs_sweep(hier%lev(l)%op%kernel, con, rhs, p, settings%omega)
            hier%work = hier%work + hier%lev(l)%cost
        end select
    end subroutine smooth

    !> Damped Gauss–Seidel on the contact set, lexicographic order (thesis §2.4.2).
    !! Row I of A is the kernel shifted to I; the sum runs over the bounding box of the
    !! contact set only (p = 0 elsewhere).  kernel(a,b) = kernel(−a,b) = kernel(a,−b).
    subroutine gs_sweep(kernel, con, rhs, p, omega)
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: kernel(-(size(con, 1) - 1):, -(size(con, 2) - 1):)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(inout) :: p(:, :)
        real(dp), intent(in) :: omega
        integer :: nx, ny, i, j, l, lo(size(con, 2)), hi(size(con, 2)), jlo, jhi
        real(dp) :: s, diag
        nx = size(con, 1); ny = size(con, 2)
        jlo = ny + 1; jhi = 0
        do l = 1, ny
            lo(l) = nx + 1; hi(l) = 0
            do i = 1, nx
                if (con(i, l)) then
                    lo(l) = min(lo(l), i); hi(l) = i
                end if
            end do
            if (hi(l) > 0) then
                jlo = min(jlo, l); jhi = l
            end if
        end do
        diag = kernel(0, 0)
        do j = 1, ny
            do i = 1, nx
                if (.not. con(i, j)) cycle
                s = 0
                do l = jlo, jhi
                    if (hi(l) < lo(l)) cycle
                    s = s + dot_product(kernel(lo(l) - i:hi(l) - i, l - j), p(lo(l):hi(l), l))
                end do
                p(i, j) = p(i, j) + omega*(rhs(i, j) - s)/diag
            end do
        end do
    end subroutine gs_sweep

    !> Damped Jacobi on the contact set (an FFT product per sweep).
    subroutine jacobi_sweep(lv, con, rhs, p, omega)
        type(fmg_level), intent(inout) :: lv
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(inout) :: p(:, :)
        real(dp), intent(in) :: omega
        real(dp), allocatable :: u(:, :)
        allocate (u(size(p, 1), size(p, 2)))
        call lv%op%apply(p, u)
        where (con) p = p + omega*(rhs - u)/lv%op%kernel(0, 0)
    end subroutine jacobi_sweep

    !> FFT smoother with row-sum modification on the contact set (thesis eqs. 3.10, 3.21),
    !! undamped: p_C ← p_C + M̄ (rhs − A p)_C,  M̄ = M_CC − diag(sum(M_CC) − γ),
    !! γ = min row sum of M.  Beyond the thesis, M̄'s diagonal is floored at θ/A_ii: on the
    !! isolated contact spots of rough surfaces the row-sum shift removes almost all of the
    !! diagonal and the smoother stalls (measured: no convergence in 100 cycles at 128²
    !! with θ = 0).  `rs` holds sum(M_CC) = M·1_C (computed once per cycle and level).
    subroutine fft_rsm_sweep(lv, con, rhs, p, rs, theta)
        type(fmg_level), intent(inout) :: lv
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :), rs(:, :), theta
        real(dp), intent(inout) :: p(:, :)
        real(dp), allocatable :: u(:, :), d(:, :)
        allocate (u(size(p, 1), size(p, 2)), d(size(p, 1), size(p, 2)))
        call lv%op%apply(p, u)
        where (con)
            d = rhs - u
        elsewhere
            d = 0
        end where
        call lv%prec%apply(d, u)
        ! diagonal of M̄ = M_CC − diag(sum(M_CC) − γ), floored at θ/A_ii: on isolated
        ! contact elements (rough surfaces) the row-sum shift leaves almost no diagonal
        where (con) p = p + u - min(rs - lv%gamma, lv%prec%kernel(0, 0) - theta/lv%op%kernel(0, 0))*d
    end subroutine fft_rsm_sweep

    !> Row sums of M over the contact set, M·1_C (one product).
    subroutine rsm_rowsums(lv, con, rs)
        type(fmg_level), intent(inout) :: lv
        logical, intent(in) :: con(:, :)
        real(dp), allocatable, intent(out) :: rs(:, :)
        real(dp), allocatable :: one(:, :)
        allocate (rs(size(con, 1), size(con, 2)), one(size(con, 1), size(con, 2)))
        one = merge(1.0_dp, 0.0_dp, con)
        call lv%prec%apply(one, rs)
    end subroutine rsm_rowsums

    !> Exact solve of A_CC p_C = rhs_C on the coarsest level (LAPACK dposv).
    subroutine direct_solve(lv, con, rhs, p)
        type(fmg_level), intent(in) :: lv
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(out) :: p(:, :)
        integer, allocatable :: ix(:), iy(:)
        real(dp), allocatable :: a(:, :), b(:, :)
        integer :: n, i, j, k, info
        n = count(con)
        p = 0
        if (n == 0) return
        allocate (ix(n), iy(n), a(n, n), b(n, 1))
        k = 0
        do j = 1, size(con, 2)
            do i = 1, size(con, 1)
                if (con(i, j)) then
                    k = k + 1; ix(k) = i; iy(k) = j; b(k, 1) = rhs(i, j)
                end if
            end do
        end do
        do j = 1, n
            do i = 1, n
                a(i, j) = lv%op%kernel(ix(i) - ix(j), iy(i) - iy(j))
            end do
        end do
        call dposv('U', n, 1, a, n, b, n, info)
        if (info /= 0) return     ! A is SPD; a failure leaves the correction zero
        do k = 1, n
            p(ix(k), iy(k)) = b(k, 1)
        end do
    end subroutine direct_solve

    ! ---- smoother analysis (thesis §2.4.4) --------------------------------------------------

    !> Eigenvalues (wr + i·wi) of the iteration matrix I − W⁻¹A of an undamped or damped
    !! 'jacobi' (W = D/ω) or 'gs' (W = D/ω + L) smoother for A^zz on the whole of a small
    !! grid (dense, LAPACK dgeev; n ≤ 2048).  Thesis Fig. 2.6: Jacobi has one eigenvalue far
    !! below −1, GS has all |λ| < 1.
    subroutine smoother_eigenvalues(mat, grid, smoother, omega, wr, wi, stat, errmsg)
        type(fc_material), intent(in) :: mat
        type(fc_grid), intent(in) :: grid
        character(len=*), intent(in) :: smoother
        real(dp), intent(in) :: omega
        real(dp), allocatable, intent(out) :: wr(:), wi(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), allocatable :: kernel(:, :), a(:, :), w(:, :), r(:, :), vl(:, :), vr(:, :), work(:)
        integer :: n, i, j, info
        stat = 0; errmsg = ''
        n = grid%n()
        if (n > 2048) then
            stat = 1; write (errmsg, '(a,i0,a)') 'smoother_eigenvalues: n = ', n, ' > 2048 (dense analysis)'; return
        end if
        call ic_kernel(IC_ZZ, mat, grid, kernel)
        allocate (a(n, n), w(n, n), r(n, n))
        do j = 1, n
            do i = 1, n
                a(i, j) = kernel(mod(i - 1, grid%nx) - mod(j - 1, grid%nx), (i - 1)/grid%nx - (j - 1)/grid%nx)
            end do
        end do
        w = 0
        select case (smoother)
        case ('jacobi')
            do i = 1, n
                w(i, i) = a(i, i)/omega
            end do
        case ('gs')
            do j = 1, n
                do i = j + 1, n
                    w(i, j) = a(i, j)
                end do
                w(j, j) = a(j, j)/omega
            end do
        case default
            stat = 1; errmsg = "smoother_eigenvalues: smoother '"//trim(smoother)//"' is not 'jacobi' or 'gs'"; return
        end select
        ! R = I − W⁻¹A: solve W X = A (W lower triangular), R = I − X
        r = a
        call solve_lower(w, r)
        r = -r
        do i = 1, n
            r(i, i) = r(i, i) + 1
        end do
        allocate (wr(n), wi(n), vl(1, 1), vr(1, 1), work(8*n))
        call dgeev('N', 'N', n, r, n, wr, wi, vl, 1, vr, 1, work, size(work), info)
        if (info /= 0) then
            stat = 1; write (errmsg, '(a,i0)') 'smoother_eigenvalues: dgeev info = ', info
        end if
    contains
        subroutine solve_lower(lw, x)
            real(dp), intent(in) :: lw(:, :)
            real(dp), intent(inout) :: x(:, :)
            integer :: ii
            do ii = 1, size(x, 1)
                if (ii > 1) x(ii, :) = x(ii, :) - matmul(lw(ii, 1:ii - 1), x(1:ii - 1, :))
                x(ii, :) = x(ii, :)/lw(ii, ii)
            end do
        end subroutine solve_lower
    end subroutine smoother_eigenvalues

end module fc_fmg
