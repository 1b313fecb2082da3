!> Distributed normal contact: BCCG over MPI ranks, each rank holding a slab of rows
!! (layout of [[fcm_bttb]]), the products with A^zz and with its Toeplitz preconditioner
!! computed by FFTW-MPI.
!!
!! The iteration is the serial `bccg` of [[fc_norm]] step for step (same elastic cold start, free set, restart
!! rule, Polonsky–Keer force constraint, stagnation and divergence checks, residual
!! ‖g‖/‖h_F‖, messages), with every inner product, count and norm reduced over the ranks
!! (one MPI_Allreduce per group of scalars).  Two deliberate differences, both exact in
!! exact arithmetic: clipped pressures are always corrected by one more FFT product (the
!! serial code updates few of them column by column from the full kernel, which no rank
!! stores), and the coarse deflation option is not offered (off by default in serial
!! too; asking for it is an error).  Results therefore equal the serial solver's to
!! round-off (test `dist_bccg_equals_serial_*`).
!!
!! Preconditioner: the serial construction on the doubled grid (A's coefficients for offsets
!! up to n, symbol inverted pointwise with the floor 1e−8·max, inverse truncated to offsets
!! < n, re-embedded) done with distributed cosine transforms of the quadrant, since every
!! kernel involved is even.  The periodic cell uses the kernel of [[fc_periodic]] (no
!! padding, exact inverse on mean-free vectors).
module fcm_norm
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use, intrinsic :: iso_fortran_env, only: int64
    use mpi
    use fc_kinds, only: dp, msg_len, FC_CONVERGED, FC_NOT_CONVERGED, FC_DIVERGED, FC_ERROR, check_iteration_settings, &
        FC_ERR_NOT_READY, FC_ERR_SHAPE, FC_ERR_VALUE, FC_ERR_UNSUPPORTED, FC_ERR_NO_CONTACT
    use fc_geometry, only: fc_grid, h_no_contact
    use fc_influence, only: fc_material, element_coefficient, IC_ZZ
    use fc_norm, only: fc_normal_settings, fc_normal_result
    use fc_periodic, only: periodic_kernel_block, check_periodic_grid, periodic_images_default
    use fcm_bttb
    implicit none
    private

    !> A^zz and its preconditioner, distributed.  Do not copy a built operator.
    type, public :: fcm_normal_operator
        type(fcm_layout) :: lay
        type(fc_grid) :: grid
        type(fc_material) :: material
        logical :: periodic = .false.
        real(dp), allocatable :: sym_a(:, :)   !! symbol of A (spectral layout, scaled)
        real(dp), allocatable :: sym_m(:, :)   !! symbol of the preconditioner
        integer :: napply_a = 0, napply_m = 0
        real(dp) :: setup_seconds = 0
    end type fcm_normal_operator

    !> peak memory of a distributed BCCG solve per rank (measured, doc/parallel.md section 6):
    !! `dist_base_bytes` + bytes per grid element and rank
    integer(int64), parameter, public :: dist_base_bytes = 16000000_int64
    real(dp), parameter, public :: dist_bytes_per_element = 133            !! doubled-grid (Toeplitz) products
    real(dp), parameter, public :: dist_bytes_per_element_periodic = 103   !! periodic cell (circulant on the grid)

    public :: build_dist_normal_operator, solve_dist_normal, gather_rows, scatter_rows, dist_memory_per_rank

contains

    !> Build the distributed operator for `grid` on `comm` (collective).  Every rank passes
    !! the same material and grid.
    subroutine build_dist_normal_operator(dop, material, grid, comm, stat, errmsg, periodic, images, measure)
        type(fcm_normal_operator), intent(inout) :: dop
        type(fc_material), intent(in) :: material
        type(fc_grid), intent(in) :: grid
        integer, intent(in) :: comm
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        logical, intent(in), optional :: periodic
        integer, intent(in), optional :: images
        !> measured plans for the products (FFTW_MEASURE, from the wisdom the ranks hold)
        logical, intent(in), optional :: measure
        real(dp), allocatable :: q(:, :), s(:, :)
        real(dp) :: smax, scale, t0
        integer :: nx, ny, i, j, jj, nim, ierr
        logical :: per
        t0 = mpi_wtime()
        per = .false.
        if (present(periodic)) per = periodic
        nim = periodic_images_default
        if (present(images)) nim = images
        nx = grid%nx; ny = grid%ny
        if (per) then
            call check_periodic_grid(grid, nim, stat, errmsg)
            if (stat /= 0) return
        end if
        if (allocated(dop%sym_a)) deallocate (dop%sym_a)
        if (allocated(dop%sym_m)) deallocate (dop%sym_m)
        call layout_init(dop%lay, comm, nx, ny, per, stat, errmsg, measure)
        if (stat /= 0) return
        dop%grid = grid; dop%material = material; dop%periodic = per
        associate (lay => dop%lay)
            allocate (q(0:lay%nxh - 1, lay%nql), s(0:lay%nsy - 1, lay%nkl))
            allocate (dop%sym_a(0:lay%nsy - 1, lay%nkl), dop%sym_m(0:lay%nsy - 1, lay%nkl))
            scale = 1/(real(lay%mx, dp)*real(lay%my, dp))
            if (per) then
                if (lay%nql > 0) call periodic_kernel_block(material, grid, nim, 0, nx/2, lay%q0, lay%q0 + lay%nql - 1, q)
                call cosine_transform(lay, q, s)
                if (lay%nkl > 0 .and. lay%k0 == 0) s(0, 1) = 0    ! mean removed: displacements up to a constant
                dop%sym_a = s*scale
                smax = global_max(maxval(s))
                dop%sym_m = 1/max(s, 1.0e-8_dp*smax)*scale
                if (lay%nkl > 0 .and. lay%k0 == 0) dop%sym_m(0, 1) = 0
            else
                ! A's coefficients for offsets 0 … n (the wrap-around slot n serves the preconditioner)
                !$omp parallel do default(shared) private(i, jj)
                do j = 1, lay%nql
                    jj = lay%q0 + j - 1
                    do i = 0, nx
                        q(i, j) = element_coefficient(IC_ZZ, material, i*grid%dx, jj*grid%dy, grid%dx, grid%dy)
                    end do
                end do
                !$omp end parallel do
                ! preconditioner: invert the symbol of the full circulant, keep offsets < n
                call cosine_transform(lay, q, s)
                smax = global_max(maxval(s))
                s = 1/max(s, 1.0e-8_dp*smax)*scale
                call cosine_transform_back(lay, s, q)
                call clear_wrap_slots(q)
                call cosine_transform(lay, q, dop%sym_m)
                dop%sym_m = dop%sym_m*scale
                ! A itself: the Toeplitz embedding has zeros in the wrap-around slots
                !$omp parallel do default(shared) private(i, jj)
                do j = 1, lay%nql
                    jj = lay%q0 + j - 1
                    do i = 0, nx
                        q(i, j) = element_coefficient(IC_ZZ, material, i*grid%dx, jj*grid%dy, grid%dx, grid%dy)
                    end do
                end do
                !$omp end parallel do
                call clear_wrap_slots(q)
                call cosine_transform(lay, q, dop%sym_a)
                dop%sym_a = dop%sym_a*scale
            end if
        end associate
        dop%napply_a = 0; dop%napply_m = 0
        call mpi_barrier(comm, ierr)
        dop%setup_seconds = mpi_wtime() - t0
    contains
        subroutine clear_wrap_slots(qq)
            real(dp), intent(inout) :: qq(0:, :)
            integer :: jq
            qq(nx, :) = 0
            do jq = 1, dop%lay%nql
                if (dop%lay%q0 + jq - 1 == ny) qq(:, jq) = 0
            end do
        end subroutine clear_wrap_slots
        real(dp) function global_max(v)
            real(dp), intent(in) :: v
            call mpi_allreduce(v, global_max, 1, MPI_DOUBLE_PRECISION, MPI_MAX, comm, ierr)
        end function global_max
    end subroutine build_dist_normal_operator

    !> Solve the normal problem on the distributed grid: h0 holds this rank's rows
    !! (nx, nyl) of the undeformed distance; exactly one of `approach`, `fn`.  res%pn and
    !! res%gap hold this rank's rows; fn, approach, pmax, ncon, residual, status are global.
    !! Collective.  Only settings%solver = 'bccg' (with or without preconditioner).
    subroutine solve_dist_normal(dop, h0, settings, res, stat, errmsg, approach, fn, p_start)
        type(fcm_normal_operator), intent(inout) :: dop
        real(dp), intent(in) :: h0(:, :)
        type(fc_normal_settings), intent(in) :: settings
        type(fc_normal_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: approach, fn
        real(dp), intent(in), optional :: p_start(:, :)
        integer :: nx, nyl, ierr
        logical :: force_mode, any_contact
        real(dp) :: delta, fnv, t0
        stat = 0; errmsg = ''
        nx = dop%grid%nx; nyl = dop%lay%nyl
        if (.not. allocated(dop%sym_a)) then
            stat = FC_ERR_NOT_READY; errmsg = 'solve_dist_normal: operator not built'; return
        end if
        if (size(h0, 1) /= nx .or. size(h0, 2) /= nyl) then
            stat = FC_ERR_SHAPE; write (errmsg, '(a,2(i0,1x),a,2(i0,1x))') 'solve_dist_normal: h0 has shape ', shape(h0), &
                'but this rank holds ', nx, nyl
            return
        end if
        if (present(approach) .eqv. present(fn)) then
            stat = FC_ERR_VALUE; errmsg = 'solve_dist_normal: give exactly one of approach and fn'; return
        end if
        if (trim(settings%solver) /= 'bccg') then
            stat = FC_ERR_UNSUPPORTED
            errmsg = "normal = '"//trim(settings%solver)//"': the distributed solver is 'bccg'"; return
        end if
        if (settings%deflation) then
            stat = FC_ERR_UNSUPPORTED; errmsg = 'deflation = .true. is not available in the distributed solver'; return
        end if
        force_mode = present(fn)
        fnv = 0; delta = 0
        if (force_mode) then
            fnv = fn
            if (.not. (fn > 0)) then
                stat = FC_ERR_VALUE; write (errmsg, '(a,es12.4,a)') 'fn = ', fn, ' must be > 0'; return
            end if
        else
            delta = approach
            any_contact = any(h0 - delta <= 0 .and. h0 < 0.5_dp*h_no_contact)
            call mpi_allreduce(MPI_IN_PLACE, any_contact, 1, MPI_LOGICAL, MPI_LOR, dop%lay%comm, ierr)
            if (.not. any_contact) then
                stat = FC_ERR_NO_CONTACT; write (errmsg, '(a,es12.4,a)') 'approach = ', approach, &
                    ' gives no contact (h0 − approach > 0 everywhere)'
                return
            end if
        end if
        call check_iteration_settings(settings%tol, settings%maxit, stat, errmsg)
        if (stat /= 0) return
        allocate (res%pn(nx, nyl), res%gap(nx, nyl))
        res%pn = 0
        if (present(p_start)) then
            if (all(shape(p_start) == [nx, nyl])) res%pn = max(0.0_dp, p_start)
            where (.not. h0 < 0.5_dp*h_no_contact) res%pn = 0
        end if
        dop%napply_a = 0; dop%napply_m = 0
        t0 = mpi_wtime()
        call run_dist_bccg(dop, h0, settings, force_mode, delta, fnv, res)
        res%cpu_seconds = mpi_wtime() - t0
        res%matvecs = dop%napply_a
        res%precond_applications = dop%napply_m
        res%fn = gsum(sum(res%pn))*dop%grid%area()
        res%pmax = gmax(max(0.0_dp, maxval(res%pn)))
        res%ncon = gcount(count(res%pn > 0))
        res%touches_boundary = on_edge()
        if (res%touches_boundary .and. res%status == FC_CONVERGED .and. .not. dop%periodic) &
            res%message = 'converged; contact reaches the edge of the potential contact area (enlarge it)'
    contains
        real(dp) function gsum(v)
            real(dp), intent(in) :: v
            call mpi_allreduce(v, gsum, 1, MPI_DOUBLE_PRECISION, MPI_SUM, dop%lay%comm, ierr)
        end function gsum
        real(dp) function gmax(v)
            real(dp), intent(in) :: v
            call mpi_allreduce(v, gmax, 1, MPI_DOUBLE_PRECISION, MPI_MAX, dop%lay%comm, ierr)
        end function gmax
        integer function gcount(v)
            integer, intent(in) :: v
            call mpi_allreduce(v, gcount, 1, MPI_INTEGER, MPI_SUM, dop%lay%comm, ierr)
        end function gcount
        logical function on_edge()
            logical :: e
            e = .false.
            if (nyl > 0) then
                e = any(res%pn(1, :) > 0) .or. any(res%pn(nx, :) > 0)
                if (dop%lay%y0 == 0) e = e .or. any(res%pn(:, 1) > 0)
                if (dop%lay%y0 + nyl == dop%grid%ny) e = e .or. any(res%pn(:, nyl) > 0)
            end if
            call mpi_allreduce(e, on_edge, 1, MPI_LOGICAL, MPI_LOR, dop%lay%comm, ierr)
        end function on_edge
    end subroutine solve_dist_normal

    !> The BCCG iteration of [[fc_norm]] on the local rows (see the module header).
    subroutine run_dist_bccg(dop, h0, settings, force_mode, delta_in, fn, res)
        type(fcm_normal_operator), intent(inout) :: dop
        real(dp), intent(in) :: h0(:, :)
        type(fc_normal_settings), intent(in) :: settings
        logical, intent(in) :: force_mode
        real(dp), intent(in) :: delta_in, fn
        type(fc_normal_result), intent(inout) :: res
        real(dp), allocatable, dimension(:, :) :: p, u, g, z, d, q
        logical, allocatable, dimension(:, :) :: free, free_old, allowed
        real(dp) :: delta, area, alpha, beta, gz, gz_old, dq, hnorm, rnorm, best, dden, scale, r(4)
        integer :: it, since_best, nfree, nclip, nx, nyl, comm
        logical :: restart, have_u
        real(dp), allocatable :: hist(:)
        nx = size(h0, 1); nyl = size(h0, 2); comm = dop%lay%comm
        have_u = .false.
        allocate (p(nx, nyl), u(nx, nyl), g(nx, nyl), z(nx, nyl), d(nx, nyl), q(nx, nyl))
        allocate (free(nx, nyl), free_old(nx, nyl), allowed(nx, nyl))
        area = dop%grid%area()
        allowed = h0 < 0.5_dp*h_no_contact
        p = res%pn
        delta = delta_in
        if (gsum1(sum(p)) <= 0 .and. settings%precondition .and. settings%elastic_start) call elastic_start()
        if (force_mode) then
            if (gsum1(sum(p)) <= 0) then
                where (allowed) p = 1
            end if
            p = p*fn/(area*gsum1(sum(p)))
        end if
        if (.not. have_u) call apply_a(p, u)
        allocate (hist(settings%maxit))
        free_old = .false.
        d = 0; gz_old = 1; best = huge(1.0_dp); since_best = 0
        res%status = FC_NOT_CONVERGED
        res%outer_iterations = 0
        do it = 1, settings%maxit
            ! g = h0 + u − δ (u = A p), δ the mean gap over the contact set in force mode
            g = h0 + u
            if (force_mode) then
                r(1:2) = [sum(g, mask=p > 0), real(count(p > 0), dp)]
                call allreduce_sum(r(1:2))
                if (r(2) > 0) delta = r(1)/r(2)
            end if
            g = g - delta
            free = allowed .and. (p > 0 .or. g < 0)
            where (.not. free) g = 0
            r(1:3) = [real(count(free), dp), sum((h0 - delta)**2, mask=free), sum(g**2)]
            call allreduce_sum(r(1:3))
            nfree = nint(r(1)); hnorm = sqrt(r(2)); rnorm = sqrt(r(3))
            if (nfree == 0 .or. hnorm <= 0) then
                res%message = 'no element in contact'
                res%status = FC_NOT_CONVERGED
                exit
            end if
            res%residual = rnorm/hnorm
            hist(it) = res%residual
            res%iterations = it - 1
            if (ieee_is_nan(res%residual) .or. res%residual > 1.0e8_dp) then
                res%status = FC_DIVERGED
                res%message = 'BCCG diverged (residual not finite or > 1e8)'
                exit
            end if
            if (res%residual <= settings%tol) then
                res%status = FC_CONVERGED
                res%message = 'converged'
                exit
            end if
            if (res%residual < 0.999_dp*best) then
                best = res%residual; since_best = 0
            else
                since_best = since_best + 1
                if (since_best > 100) then
                    res%message = 'BCCG stagnated: no residual decrease in 100 iterations'
                    exit
                end if
            end if
            if (it == settings%maxit) then
                write (res%message, '(a,i0,a)') 'BCCG not converged in maxit = ', settings%maxit, ' iterations'
                exit
            end if
            r(1) = merge(1.0_dp, 0.0_dp, any(free .neqv. free_old))
            call allreduce_sum(r(1:1))
            restart = r(1) > 0
            if (restart) res%outer_iterations = res%outer_iterations + 1
            if (force_mode) call project_mean(g, free)
            if (settings%precondition) then
                call apply_m(g, z)
                where (.not. free) z = 0
            else
                z = g
            end if
            if (force_mode) call project_mean(z, free)
            gz = gsum1(sum(g*z))
            if (restart .or. it == 1) then
                d = -z
            else
                beta = max(0.0_dp, gz/gz_old)
                d = -z + beta*d
                where (.not. free) d = 0
            end if
            free_old = free
            gz_old = gz
            call apply_a(d, q)
            r(1:2) = [sum(d*q), sum(g*d)]
            call allreduce_sum(r(1:2))
            dq = r(1); dden = r(2)
            if (.not. (dq > 0)) then
                res%status = FC_DIVERGED
                res%message = 'BCCG: search direction with non-positive curvature'
                exit
            end if
            alpha = -dden/dq
            p = p + alpha*d
            u = u + alpha*q
            r(1) = count(p < 0)
            call allreduce_sum(r(1:1))
            nclip = nint(r(1))
            if (nclip > 0) then
                p = max(p, 0.0_dp)
                call apply_a(p, u)
                if (force_mode) then
                    r(1) = gsum1(sum(p))
                    if (r(1) > 0) then
                        scale = fn/(area*r(1))
                        p = scale*p; u = scale*u
                    end if
                end if
            end if
        end do
        res%approach = delta
        res%pn = p
        res%gap = h0 - delta + u
        where (.not. allowed) res%gap = h_no_contact
        allocate (res%history(max(0, min(it, settings%maxit))), source=hist(1:max(0, min(it, settings%maxit))))
    contains
        subroutine apply_a(x, y)
            real(dp), intent(in) :: x(:, :)
            real(dp), intent(out) :: y(:, :)
            call dop%lay%apply(dop%sym_a, x, y)
            dop%napply_a = dop%napply_a + 1
        end subroutine apply_a
        subroutine apply_m(x, y)
            real(dp), intent(in) :: x(:, :)
            real(dp), intent(out) :: y(:, :)
            call dop%lay%apply(dop%sym_m, x, y)
            dop%napply_m = dop%napply_m + 1
        end subroutine apply_m
        subroutine allreduce_sum(v)
            real(dp), intent(inout) :: v(:)
            integer :: ierr
            call mpi_allreduce(MPI_IN_PLACE, v, size(v), MPI_DOUBLE_PRECISION, MPI_SUM, comm, ierr)
        end subroutine allreduce_sum
        real(dp) function gsum1(v)
            real(dp), intent(in) :: v
            real(dp) :: w(1)
            w(1) = v
            call allreduce_sum(w)
            gsum1 = w(1)
        end function gsum1
        !> The serial solver's cold start (fc_norm): p = max(0, −M (h0 − δ)) on the
        !! penetration set; with a prescribed force δ bracketed and refined by the Illinois
        !! variant of regula falsi to about 1 % of the force.  Same steps, global reductions.
        subroutine elastic_start()
            real(dp) :: lo, hi, mid, hmin, hmax, f, flo, fhi, w(1)
            integer :: k, ierr
            if (.not. force_mode) then
                call approach_start()
                return
            end if
            w(1) = minval(h0, mask=allowed)
            call mpi_allreduce(MPI_IN_PLACE, w, 1, MPI_DOUBLE_PRECISION, MPI_MIN, comm, ierr)
            hmin = w(1)
            w(1) = maxval(h0, mask=allowed)
            call mpi_allreduce(MPI_IN_PLACE, w, 1, MPI_DOUBLE_PRECISION, MPI_MAX, comm, ierr)
            hmax = w(1)
            lo = hmin; flo = 0
            hi = hmin + 0.25_dp*(hmax - hmin)
            call estimate(hi, fhi)
            do k = 1, 20
                if (fhi >= fn) exit
                lo = hi; flo = fhi
                hi = hmin + 2*(hi - hmin)
                call estimate(hi, fhi)
            end do
            do k = 1, 4
                if (.not. (fhi > flo)) exit
                mid = lo + (fn - flo)*(hi - lo)/(fhi - flo)
                call estimate(mid, f)
                if (abs(f - fn) <= 0.01_dp*fn) return
                if (f > fn) then
                    hi = mid; fhi = f; flo = 0.5_dp*flo
                else
                    lo = mid; flo = f; fhi = 0.5_dp*fhi
                end if
            end do
        end subroutine elastic_start
        !> The serial solver's prescribed-approach start (fc_norm): energy-scaled estimates
        !! at levels f = 1, 3/4, 1/2 of the penetration and the parabola's vertex, the lowest
        !! energy kept (in d, q with u = A p).  Same steps, global reductions.
        subroutine approach_start()
            real(dp) :: hmin, fr(4), jv(4), jbest, den, f0, w(1)
            integer :: k, ierr
            w(1) = minval(h0, mask=allowed)
            call mpi_allreduce(MPI_IN_PLACE, w, 1, MPI_DOUBLE_PRECISION, MPI_MIN, comm, ierr)
            hmin = w(1)
            fr(1:3) = [1.0_dp, 0.75_dp, 0.5_dp]
            jbest = 0
            do k = 1, 4
                if (k == 4) then
                    den = jv(1) - 2*jv(2) + jv(3)
                    if (.not. (den > 0)) exit
                    fr(4) = fr(2) + 0.25_dp*(jv(3) - jv(1))/(2*den)
                    fr(4) = min(1.0_dp, max(0.25_dp, fr(4)))
                    if (minval(abs(fr(1:3) - fr(4))) < 0.05_dp) exit
                end if
                call scaled_estimate(hmin + fr(k)*(delta - hmin), jv(k))
                if (jv(k) < jbest) then
                    jbest = jv(k); d = p; q = u
                end if
            end do
            if (jbest < 0) then
                p = d; u = q; have_u = .true.
            else
                call estimate(delta, f0)
            end if
        end subroutine approach_start
        subroutine scaled_estimate(t, jv)
            real(dp), intent(in) :: t
            real(dp), intent(out) :: jv
            real(dp) :: force, pau, pg, c
            jv = 0
            call estimate(t, force)
            if (.not. force > 0) return
            call apply_a(p, u)
            pau = gsum1(sum(p*u))
            pg = gsum1(sum(p*(h0 - delta), mask=allowed))
            if (.not. (pau > 0 .and. pg < 0)) return
            c = -pg/pau
            p = c*p; u = c*u
            jv = -0.5_dp*pg**2/pau
        end subroutine scaled_estimate
        subroutine estimate(dlt, force)
            real(dp), intent(in) :: dlt
            real(dp), intent(out) :: force
            where (allowed .and. h0 - dlt < 0)
                g = h0 - dlt
            elsewhere
                g = 0
            end where
            call apply_m(-g, z)
            where (allowed .and. h0 - dlt < 0)
                p = max(z, 0.0_dp)
            elsewhere
                p = 0
            end where
            force = gsum1(sum(p))*area
        end subroutine estimate
        !> Subtract the global mean over the free set (projection onto Σ_F x = 0).
        subroutine project_mean(x, fr)
            real(dp), intent(inout) :: x(:, :)
            logical, intent(in) :: fr(:, :)
            real(dp) :: w(2)
            w = [sum(x, mask=fr), real(count(fr), dp)]
            call allreduce_sum(w)
            if (w(2) > 0) then
                where (fr)
                    x = x - w(1)/w(2)
                elsewhere
                    x = 0
                end where
            end if
        end subroutine project_mean
    end subroutine run_dist_bccg

    !> Gather the row slabs a(nx, nyl) of every rank into full(nx, ny) on `root`.
    subroutine gather_rows(dop, a, full, root)
        type(fcm_normal_operator), intent(in) :: dop
        real(dp), intent(in) :: a(:, :)
        real(dp), allocatable, intent(out) :: full(:, :)
        integer, intent(in) :: root
        integer, allocatable :: counts(:), displs(:)
        integer :: ierr, nloc, r
        nloc = size(a)
        allocate (counts(dop%lay%nprocs), displs(dop%lay%nprocs))
        call mpi_gather(nloc, 1, MPI_INTEGER, counts, 1, MPI_INTEGER, root, dop%lay%comm, ierr)
        displs(1) = 0
        do r = 2, dop%lay%nprocs
            displs(r) = displs(r - 1) + counts(r - 1)
        end do
        if (dop%lay%rank == root) then
            allocate (full(dop%grid%nx, dop%grid%ny))
        else
            allocate (full(1, 1))
        end if
        call mpi_gatherv(a, nloc, MPI_DOUBLE_PRECISION, full, counts, displs, MPI_DOUBLE_PRECISION, root, &
            dop%lay%comm, ierr)
    end subroutine gather_rows

    !> This rank's rows of a full array given on every rank.
    pure function scatter_rows(dop, full) result(a)
        type(fcm_normal_operator), intent(in) :: dop
        real(dp), intent(in) :: full(:, :)
        real(dp) :: a(size(full, 1), dop%lay%nyl)
        a = full(:, dop%lay%y0 + 1:dop%lay%y0 + dop%lay%nyl)
    end function scatter_rows

    !> Estimated peak memory of one rank [bytes] for an nx × ny grid over `nprocs` ranks: the
    !! model M = 16 MB + 133 B × n/P (103 B for a periodic cell) of doc/parallel.md, with the
    !! largest slab (rows are split as evenly as FFTW-MPI splits them, at most one row more).
    pure function dist_memory_per_rank(nx, ny, nprocs, periodic) result(b)
        integer, intent(in) :: nx, ny, nprocs
        logical, intent(in) :: periodic
        integer(int64) :: b
        real(dp) :: bpe
        bpe = merge(dist_bytes_per_element_periodic, dist_bytes_per_element, periodic)
        b = dist_base_bytes + int(bpe*real(nx, dp)*real((ny + max(1, nprocs) - 1)/max(1, nprocs), dp), int64)
    end function dist_memory_per_rank

end module fcm_norm
