!> Full multigrid (FMG) for the normal contact LCP (thesis ch. 2, §2.4).
!!
!! The LCP e = h + A p ≥ 0, p ≥ 0, e·p = 0 is solved by an *MG + active set* iteration:
!! each active-set iteration applies ONE multigrid V-cycle to A_CC p_C = −h_C on the
!! current contact set C, then updates C (drop p < 0, add e ≤ 0; thesis §2.4.1).
!! The grid hierarchy and transfers are in [[fc_fmg_levels]], the smoothers and the
!! coarsest exact solve in [[fc_fmg_smoothers]]; all exterior quantities (pressure,
!! defect, correction) are zero.
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
    use fc_geometry, only: fc_grid, h_no_contact
    use fc_geometry_surfaces, only: fc_surface, fc_quadratic_surface, fc_punch_rough_surface, fc_wavy_surface
    use fc_influence
    use fc_norm, only: fc_normal_result
    use fc_fmg_levels, only: fc_fmg_settings, fc_fmg_hierarchy, build_fmg_hierarchy, &
        build_preconditioners, fmg_cycle_from_name, restrict_defect, interp_copy, interp_bilinear
    use fc_fmg_smoothers, only: smooth, direct_solve
    implicit none
    private

    ! the surfaces, the settings and the hierarchy are part of this solver's interface
    public :: fc_surface, fc_quadratic_surface, fc_punch_rough_surface, fc_wavy_surface
    public :: fc_fmg_settings, fc_fmg_hierarchy, build_fmg_hierarchy, fmg_cycle_from_name

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

    public :: solve_normal_fmg, fmg_solve_lcp, mg_solve_fixed

contains

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
        integer(i8) :: t0, t1, rate   ! 64-bit: a µs clock (default integers tick in ms)
        stat = 0; errmsg = ''
        call check_settings(hier, settings, stat, errmsg)
        if (stat /= 0) return
        if (present(approach) .eqv. present(fn)) then
            stat = FC_ERR_VALUE; errmsg = 'fmg: give exactly one of approach and fn'; return
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
            stat = FC_ERR_NOT_READY; errmsg = 'fmg: hierarchy not built'; return
        end if
        if (settings%nu1 < 0 .or. settings%nu2 < 0 .or. settings%nu1 + settings%nu2 == 0) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a,i0,a)') 'solver: cycle V(', settings%nu1, ',', settings%nu2, &
                ') needs nu1, nu2 >= 0 and nu1 + nu2 > 0'
            return
        end if
        if (.not. (settings%omega > 0 .and. settings%omega < 2)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.4,a)') 'solver: omega = ', settings%omega, ' must lie in (0, 2)'; return
        end if
        if (.not. (settings%beta >= 0)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,g0.4,a)') 'solver: beta = ', settings%beta, ' must be >= 0'; return
        end if
        if (.not. (settings%tol > 0)) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a)') 'solver: tol = ', settings%tol, ' must be > 0'; return
        end if
        if (settings%maxit < 1 .or. settings%maxit_level < 1) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a,i0,a)') 'solver: maxit = ', settings%maxit, ', maxit_level = ', &
                settings%maxit_level, ' must be >= 1'
            return
        end if
        select case (settings%smoother)
        case ('gs', 'jacobi')
        case ('fft-rsm')
            if (.not. hier%has_prec) call build_preconditioners(hier)
        case default
            stat = FC_ERR_VALUE
            errmsg = "solver: smoother = '"//trim(settings%smoother)//"' is not one of 'gs', 'jacobi', 'fft-rsm'"
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
                stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a)') 'normal: approach = ', delta, &
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
            if (status == FC_ERROR) then
                call fail_on_level(); return
            end if
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
                    if (status == FC_ERROR) then
                        call fail_on_level(); return
                    end if
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
        !> A coarse level failed (LAPACK): report it with zero pressure on the target grid.
        subroutine fail_on_level()
            deallocate (p)
            allocate (p(hier%lev(nlev)%grid%nx, hier%lev(nlev)%grid%ny))
            p = 0
            call finish(status, resid, msg, nit)
        end subroutine fail_on_level

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
            stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a)') 'normal: fn = ', fn, ' must be > 0'; return
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
        integer :: vstat
        character(len=msg_len) :: vmsg
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
                    call vcycle(hier, l, settings, con, rhs, p, vstat, vmsg)
                    if (vstat /= 0) then
                        status = FC_ERROR; msg = vmsg
                        exit
                    end if
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
                call vcycle(hier, hier%nlev, settings, con, rhs, p, stat, msg)
                if (stat /= 0) then
                    status = FC_ERROR; exit
                end if
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
    !! stat ≠ 0 (with errmsg) when the coarsest-grid Cholesky solve fails.
    recursive subroutine vcycle(hier, l, settings, con, rhs, p, stat, errmsg)
        type(fc_fmg_hierarchy), intent(inout) :: hier
        integer, intent(in) :: l
        type(fc_fmg_settings), intent(in) :: settings
        logical, intent(in) :: con(:, :)
        real(dp), intent(in) :: rhs(:, :)
        real(dp), intent(inout) :: p(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), allocatable :: d(:, :), dc(:, :), vc(:, :), v(:, :), rs(:, :)
        logical, allocatable :: conc(:, :)
        integer :: k, ncx, ncy
        stat = 0; errmsg = ''
        if (.not. any(con)) then
            p = 0; return
        end if
        if (l == 1) then
            call direct_solve(hier%lev(1), con, rhs, p, stat, errmsg)
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
            call vcycle(hier, l - 1, settings, conc, dc, vc, stat, errmsg)
            if (stat /= 0) return
            call interp_copy(vc, lv%fx, lv%fy, v)
            where (con) p = p + v
            do k = 1, settings%nu2
                call smooth(hier, l, settings, con, rhs, p, rs)
            end do
        end associate
    end subroutine vcycle

end module fc_fmg
