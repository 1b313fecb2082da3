!> Experiment for thesis Table 2.8: NORM (active set + CG) with few CG steps per active-set
!! iteration on rough punch case 3 (δ = 0.25).  Not part of the solver: it re-implements the
!! active-set loop of fc_norm::run_norm (approach mode only) with switches for the readings
!! of thesis §2.3/§2.4.1 that differ from ours, and also runs the library's solve_normal.
!!
!! Usage: fastcontact-norm-table28 N SEED VARIANT [INNER_MAXIT] [MAXIT] [VERBOSE] [APPROACH] [K] [FACTOR]
!!   VARIANT  lib: fc_norm solve_normal (solver 'norm')
!!            libf: the same with the force prescribed (the force of the BCCG solution)
!!            a:   ours (warm-started CG, drop negatives and add penetrations in one step)
!!            b:   add penetrating elements only in an iteration that dropped no element
!!            c:   CG restarted from p = 0 in every active-set iteration
!!            d:   dropped elements keep their negative pressure (p not projected)
!!            e:   like a, but add elements with e <= 0 (thesis step 4.b) instead of e < 0
!!            f:   CG not restarted across active-set iterations: the search direction and
!!                 ‖r‖² of the previous iteration are kept (direction masked to the new set)
!!            g:   like a, but u = A p recomputed after the negative pressures are zeroed,
!!                 before the penetration test (step 4.b with the updated pressures)
!!   SEED 2015 is the default surface of fc_rough_params; APPROACH defaults to 0.25 (case 3).
!!   K, FACTOR: window and factor of the candidate stagnation rule (default 20, 0.9).
!! Prints one summary line 'RESULT ...' and, with VERBOSE = 1, the history per iteration:
!! residual, contact elements, added, dropped, and the first iteration j < k − 1 with the same
!! active set when it differs from that of k − 1 (0: none).
program norm_table28
    use fc_kinds
    use fc_geometry, only: fc_grid, make_grid, punch_rough_gap, fc_rough_params, h_no_contact
    use fc_influence, only: fc_material, combine_material, fc_bttb
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, &
        solve_normal
    implicit none
    real(dp) :: approach, fn
    integer :: n, seed, inner_max, maxit, verbose, st, nit, stat_v
    character(len=16) :: variant
    character(len=64) :: arg
    type(fc_material) :: mat
    type(fc_grid) :: grid
    type(fc_rough_params) :: par
    type(fc_normal_operator) :: nop
    type(fc_normal_settings) :: set
    type(fc_normal_result) :: res
    real(dp), allocatable :: h0(:, :), hist(:), pfin(:, :)
    integer, allocatable :: ncon_h(:), nadd_h(:), ndrop_h(:), rep_h(:)
    character(len=msg_len) :: msg
    integer :: k, t0, t1, rate, fire
    integer :: stag_window       !! K of the candidate stagnation rule
    real(dp) :: stag_factor      !! required improvement over K iterations

    n = int_arg(1, 128); seed = int_arg(2, 2015)
    call get_command_argument(3, arg); variant = 'lib'
    if (len_trim(arg) > 0) variant = trim(arg)
    inner_max = int_arg(4, 4); maxit = int_arg(5, 200); verbose = int_arg(6, 0)
    approach = 0.25_dp
    call get_command_argument(7, arg)
    if (len_trim(arg) > 0) read (arg, *) approach
    stag_window = int_arg(8, 20)
    stag_factor = 0.9_dp
    call get_command_argument(9, arg)
    if (len_trim(arg) > 0) read (arg, *) stag_factor

    mat%g1 = 1.0e30_dp; mat%g2 = 40000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
    call combine_material(mat, st, msg)
    call make_grid(grid, n, n, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, st, msg)
    allocate (h0(n, n))
    par%seed = seed
    call punch_rough_gap(grid, 8.97_dp, par, h0)
    call build_normal_operator(nop, mat, grid)
    call system_clock(t0, rate)
    if (variant == 'lib' .or. variant == 'libf') then
        set%solver = 'norm'; set%inner_maxit = inner_max; set%tol = 1.0e-6_dp; set%maxit = maxit
        if (variant == 'libf') then
            ! prescribed force: the force of the BCCG solution for this approach
            set%solver = 'bccg'; set%tol = 1.0e-9_dp
            call solve_normal(nop, h0, set, res, st, msg, approach=approach)
            set%solver = 'norm'; set%tol = 1.0e-6_dp
            fn = res%fn
            call solve_normal(nop, h0, set, res, st, msg, fn=fn)
        else
            call solve_normal(nop, h0, set, res, st, msg, approach=approach)
        end if
        call system_clock(t1)
        write (*, '(a,i5,i6,1x,a4,i3,i5,1x,a,i4,i8,es11.3,f8.2,1x,a)') 'RESULT ', n, seed, variant, inner_max, &
            maxit, status_name(res%status), res%outer_iterations, res%ncon, res%residual, &
            real(t1 - t0, dp)/rate, trim(res%message)
        if (verbose == 1) then
            do k = 1, size(res%history)
                write (*, '(a,i5,es12.4)') 'HIST ', k, res%history(k)
            end do
        end if
    else
        allocate (hist(maxit), ncon_h(maxit), nadd_h(maxit), ndrop_h(maxit), rep_h(maxit))
        call norm_variant(nop%a_zz, h0, approach, trim(variant), inner_max, 1.0e-6_dp, maxit, stat_v, nit, &
            hist, ncon_h, nadd_h, ndrop_h, rep_h, pfin)
        call system_clock(t1)
        fire = stagnation_fire()
        write (*, '(a,i5,i6,1x,a4,i3,i5,1x,a,i4,i8,es11.3,f8.2,1x,a,i0,a,i0)') 'RESULT ', n, seed, variant, inner_max, &
            maxit, status_name(stat_v), nit, count(pfin > 0), hist(nit), real(t1 - t0, dp)/rate, &
            'first return to an earlier active set at iteration ', first_repeat(), &
            '; stagnation rule would fire at iteration ', fire
        if (verbose == 1) then
            write (*, '(a)') 'HIST   it    residual   ncon  added dropped same_set_as'
            do k = 1, nit
                write (*, '(a,i5,es12.4,3i7,i6)') 'HIST ', k, hist(k), ncon_h(k), nadd_h(k), ndrop_h(k), rep_h(k)
            end do
        end if
    end if
    call nop%destroy()

contains

    integer function int_arg(i, default) result(v)
        integer, intent(in) :: i, default
        character(len=64) :: a
        integer :: ios
        call get_command_argument(i, a)
        v = default
        if (len_trim(a) > 0) then
            read (a, *, iostat=ios) v
            if (ios /= 0) v = default
        end if
    end function int_arg

    !> Candidate rule (evaluated, not used to stop): at iteration k > K the active set changed in
    !! each of the last K iterations and the best residual of those K is not below
    !! stag_factor × the best residual before them.  0: never fires.
    integer function stagnation_fire() result(r)
        integer :: k
        r = 0
        do k = stag_window + 1, nit
            if (all(nadd_h(k - stag_window + 1:k) + ndrop_h(k - stag_window + 1:k) > 0) .and. &
                minval(hist(k - stag_window + 1:k)) > stag_factor*minval(hist(1:k - stag_window))) then
                r = k; return
            end if
        end do
    end function stagnation_fire

    integer function first_repeat() result(r)
        integer :: i
        r = 0
        do i = 1, nit
            if (rep_h(i) > 0) then
                r = i; return
            end if
        end do
    end function first_repeat

    !> Active set + truncated CG with switches (see the program header).  stat: FC_* code.
    !! rep(k): earliest iteration j < k − 1 whose active set (before its CG solve) equals that of k,
    !! when the set of k differs from that of k − 1 (a return to an earlier set: cycling).
    subroutine norm_variant(a, h0, delta, var, inner_max, tol, maxit, stat, nit, hist, ncon_h, nadd_h, ndrop_h, &
            rep, pout)
        type(fc_bttb), intent(inout) :: a
        real(dp), intent(in) :: h0(:, :), delta, tol
        character(len=*), intent(in) :: var
        integer, intent(in) :: inner_max, maxit
        integer, intent(out) :: stat, nit
        real(dp), intent(out) :: hist(:)
        integer, intent(out) :: ncon_h(:), nadd_h(:), ndrop_h(:), rep(:)
        real(dp), allocatable, intent(out) :: pout(:, :)
        real(dp), dimension(size(h0, 1), size(h0, 2)) :: p, u, r, d, q, h
        logical, dimension(size(h0, 1), size(h0, 2)) :: con, con_new, allowed
        logical, allocatable :: sets(:, :, :)
        real(dp) :: alpha, beta, rr, rr_old, dq, hnorm, rnorm, e
        integer :: outer, inner, i, j, nadd, ndrop, kk
        real(dp) :: rr_keep
        allowed = h0 < 0.5_dp*h_no_contact
        h = h0 - delta
        con = allowed .and. h <= 0
        p = 0
        allocate (sets(size(h0, 1), size(h0, 2), maxit))
        stat = FC_NOT_CONVERGED
        nit = 0
        rep = 0
        d = 0; rr_keep = 0
        do outer = 1, maxit
            nit = outer
            sets(:, :, outer) = con
            do kk = 1, outer - 2
                if (all(sets(:, :, outer - 1) .eqv. con)) exit
                if (all(sets(:, :, kk) .eqv. con)) then
                    rep(outer) = kk; exit
                end if
            end do
            ncon_h(outer) = count(con)
            if (var == 'c') p = 0
            call a%apply(p, u)
            r = 0
            where (con) r = -(h + u)
            hnorm = sqrt(sum(h**2, mask=con))
            rr = sum(r*r)
            if (var == 'f' .and. outer > 1) then
                where (.not. con) d = 0
                d = r + (rr/rr_keep)*d
            else
                d = r
            end if
            do inner = 1, inner_max
                if (sqrt(rr) <= 0.1_dp*tol*hnorm) exit
                call a%apply(d, q)
                where (.not. con) q = 0
                dq = sum(d*q)
                if (.not. (dq > 0)) exit
                alpha = rr/dq
                p = p + alpha*d
                r = r - alpha*q
                rr_old = rr
                rr = sum(r*r)
                beta = rr/rr_old
                d = r + beta*d
            end do
            rr_keep = rr
            call a%apply(p, u)
            rnorm = sqrt(sum((h + u)**2, mask=con .and. p >= 0))
            hist(outer) = rnorm/max(hnorm, tiny(1.0_dp))
            if (.not. (hist(outer) <= 1.0e8_dp)) then
                stat = FC_DIVERGED; exit
            end if
            con_new = con
            nadd = 0; ndrop = 0
            do j = 1, size(h0, 2)
                do i = 1, size(h0, 1)
                    if (con(i, j)) then
                        if (p(i, j) < 0) then
                            con_new(i, j) = .false.; ndrop = ndrop + 1
                            if (var /= 'd') p(i, j) = 0
                        end if
                    end if
                end do
            end do
            if (var == 'g' .and. ndrop > 0) call a%apply(p, u)
            if (.not. (var == 'b' .and. ndrop > 0)) then
                do j = 1, size(h0, 2)
                    do i = 1, size(h0, 1)
                        if (.not. con(i, j) .and. allowed(i, j)) then
                            e = h(i, j) + u(i, j)
                            if (e < 0 .or. (var == 'e' .and. e <= 0)) then
                                con_new(i, j) = .true.; nadd = nadd + 1
                            end if
                        end if
                    end do
                end do
            end if
            nadd_h(outer) = nadd; ndrop_h(outer) = ndrop
            con = con_new
            if (nadd + ndrop == 0 .and. hist(outer) <= tol) then
                stat = FC_CONVERGED; exit
            end if
        end do
        pout = max(p, 0.0_dp)
        where (.not. con) pout = 0
    end subroutine norm_variant

end program norm_table28
