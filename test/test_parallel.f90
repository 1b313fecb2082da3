!> Suite `parallel`: threads (results independent of the thread count), the periodic
!! half-space (Johnson's wavy surface in full contact, circulant structure, grid checks) and
!! the row-slab generation of rough surfaces used by distributed runs.  The distributed
!! solver itself is tested in mpi/test (run under mpirun).
!!
!! Size (~830 lines, 18 tests): one file per suite; each thread test solves the same
!! problem on one and on two threads, so its set-up is written out twice in one place.
module test_parallel
    use fc_kinds, only: dp, pi, FC_CONVERGED
    use fc_geometry, only: fc_grid, make_grid, fc_rough_params, quadratic_gap, wavy_gap, rough_heights, &
        rough_heights_rows
    use fc_influence, only: fc_material, combine_material
    use fc_fmg, only: fc_fmg_settings, solve_normal_fmg
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_periodic, only: build_periodic_normal_operator
    use fc_threads, only: set_thread_count, fc_thread_count, fc_openmp_enabled, omp_min_elements, &
        lanes_min_elements
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_settings, fc_tangential_result, build_tangential_operator, &
        solve_tangential
    use fc_tangcg_operator, only: apply_block_inverse
    use fc_rolling, only: fc_rolling_settings, fc_rolling_loading, solve_rolling
    use fc_driver, only: run_driver
    use fc_mg2d, only: fc_strip_problem, fc_mg2d_settings, fc_mg2d_result, strip_model_problem, solve_strip_mg
    use fc_mg2d_ops, only: strip_fft
    use test_mg2d, only: toeplitz_test_data
    use fc_contact, only: fc_contact_operators, fc_contact_loading, fc_contact_settings, fc_contact_result, solve_contact, &
        FC_PROBLEM_TANGENTIAL
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_null_char
    use fc_legacy, only: fc_init, fc_finalize, fc_set_material, fc_set_grid, fc_set_gap_quadratic, fc_set_gap_array, &
        fc_set_normal_force, fc_calculate, fc_get_pmax, fc_set_periodic, fc_set_threads, fc_get_error_message, FCL_OK, &
        FCL_ORDER, FCL_INVALID_VALUE
    use fc_testing
    implicit none
    private
    public :: collect_parallel

contains

    subroutine collect_parallel(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest('threads_same_result', test_threads_same), &
            new_unittest('threads_same_result_cattaneo', test_threads_same_cattaneo), &
            new_unittest('threads_convexgs_bitwise', test_threads_convexgs), &
            new_unittest('threads_fmg_gauss_seidel_bitwise', test_threads_fmg_gs), &
            new_unittest('threads_block_product_side_by_side', test_lanes), &
            new_unittest('threads_lanes_chunked_y_passes', test_lanes_chunked), &
            new_unittest('threads_same_result_rolling', test_threads_rolling), &
            new_unittest('threads_concurrent_operator_builds', test_threads_orchestrator), &
            new_unittest('threads_same_result_strip_mg', test_threads_strip), &
            new_unittest('threads_count_bounds', test_thread_bounds), &
            new_unittest('periodic_wavy_full_contact', test_wavy), &
            new_unittest('periodic_operator_is_circulant', test_circulant), &
            new_unittest('periodic_grid_checks', test_periodic_checks), &
            new_unittest('rough_rows_equal_whole_surface', test_rough_rows), &
            new_unittest('driver_periodic_wavy_partial_contact', test_driver_wavy), &
            new_unittest('driver_periodic_input_errors', test_driver_periodic_errors), &
            new_unittest('driver_threads_key', test_driver_threads), &
            new_unittest('api_handles_from_threads', test_api_threads), &
            new_unittest('api_periodic_wavy', test_api_periodic) ]
    end subroutine collect_parallel

    subroutine steel(mat)
        type(fc_material), intent(out) :: mat
        integer :: stat
        character(len=200) :: m
        mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
        call combine_material(mat, stat, m)
    end subroutine steel

    !> Hertz 64×48, force prescribed, solved with 1 and with 2 threads (threaded FFTW plans
    !! and OpenMP loops): the same iterations and pressures to 1e−12 of pmax (sums in a
    !! different order change the last bits only).
    subroutine test_threads_same(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: r1, r2
        integer :: stat, nt0
        character(len=256) :: em
        nt0 = fc_thread_count()
        call steel(mat)
        call make_grid(grid, 64, 48, -2.0_dp, 2.0_dp, -1.5_dp, 1.5_dp, stat, em)
        call set_thread_count(1)
        call build_normal_operator(nop, mat, grid)
        call solve_normal(nop, quadratic_gap(grid, 30.0_dp, 20.0_dp), set, r1, stat, em, fn=400.0_dp)
        call set_thread_count(2)
        call build_normal_operator(nop, mat, grid)
        call solve_normal(nop, quadratic_gap(grid, 30.0_dp, 20.0_dp), set, r2, stat, em, fn=400.0_dp)
        call set_thread_count(nt0)
        call check(error, r1%status == FC_CONVERGED .and. r2%status == FC_CONVERGED, 'both runs converge')
        call check(error, r1%iterations == r2%iterations, 'same iteration count')
        call check(error, maxval(abs(r1%pn - r2%pn)), 0.0_dp, '1 vs 2 threads: pressure', abs=1e-12_dp*r1%pmax)
        call check(error, r2%fn, r1%fn, '1 vs 2 threads: force', rel=1e-13_dp)
        if (fc_openmp_enabled()) then
            call set_thread_count(2)
            call check(error, fc_thread_count() == 2, 'set_thread_count(2) gives 2 threads')
            call set_thread_count(nt0)
        end if
    end subroutine test_threads_same

    !> The Cattaneo material (G = 200, ν = 0.42) and the 192×176 grid over the Table 4.1 area,
    !! checked to lie above omp_min_elements (where the solvers' loops run threaded).
    subroutine cattaneo_192(mat, grid, error)
        type(fc_material), intent(out) :: mat
        type(fc_grid), intent(out) :: grid
        type(error_type), allocatable, intent(inout) :: error
        integer :: stat
        character(len=256) :: em
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, em)
        call make_grid(grid, 192, 176, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, em)
        call check(error, grid%nx*grid%ny > omp_min_elements, 'grid above the threshold of the threaded loops')
    end subroutine cattaneo_192

    !> The Cattaneo sphere of thesis Table 4.1 case 4 (R = 50, G = 200, ν = 0.42, Fn = 9.1954,
    !! μ = 0.4) on 192×176 — above omp_min_elements, so that BCCG's and TangCG's element
    !! loops, reductions and spectral products run on 2 threads (FFTW plans too) — solved
    !! with 1 and with 2 threads.  Two threads add the partial sums of the inner products in
    !! another order: each product differs by rounding (relative ~1e−16·√n), and CG carries
    !! such perturbations to the iterates amplified at most by the iteration's condition
    !! (here ≲ 1e3).  Same iteration counts and slip/adhesion split; pressures and
    !! tractions to 1e−10 of their maxima (measured: ≲ 1e−13).
    subroutine test_threads_same_cattaneo(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: n1, n2
        type(fc_tangential_operator) :: top
        type(fc_tangential_settings) :: ts
        type(fc_tangential_result) :: t1, t2
        integer :: stat, nt0, nt
        character(len=256) :: em
        real(dp) :: tmax
        nt0 = fc_thread_count()
        call cattaneo_192(mat, grid, error)
        if (allocated(error)) return
        do nt = 1, 2
            call set_thread_count(nt)
            call build_normal_operator(nop, mat, grid)
            call build_tangential_operator(top, mat, grid)
            if (nt == 1) then
                call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), set, n1, stat, em, fn=9.1954_dp)
                call solve_tangential(top, n1%pn, 0.4_dp, ts, t1, stat, em, 0.0021_dp, 0.0010_dp, 0.003_dp)
            else
                call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), set, n2, stat, em, fn=9.1954_dp)
                ! the same pressure for both tangential solves: only TangCG's threads differ
                call solve_tangential(top, n1%pn, 0.4_dp, ts, t2, stat, em, 0.0021_dp, 0.0010_dp, 0.003_dp)
            end if
        end do
        call set_thread_count(nt0)
        call check(error, n1%status == FC_CONVERGED .and. n2%status == FC_CONVERGED, 'BCCG converges with 1 and 2 threads')
        call check(error, n1%iterations == n2%iterations, 'BCCG: same iteration count')
        call check(error, maxval(abs(n1%pn - n2%pn)), 0.0_dp, 'BCCG 1 vs 2 threads: pressure', abs=1e-10_dp*n1%pmax)
        call check(error, t1%status == FC_CONVERGED .and. t2%status == FC_CONVERGED, 'TangCG converges with 1 and 2 threads')
        call check(error, t1%iterations == t2%iterations, 'TangCG: same iteration count')
        call check(error, t1%nslip == t2%nslip .and. t1%nadh == t2%nadh, 'TangCG: same slip and adhesion areas')
        tmax = 0.4_dp*n1%pmax
        call check(error, max(maxval(abs(t1%px - t2%px)), maxval(abs(t1%py - t2%py))), 0.0_dp, &
            'TangCG 1 vs 2 threads: tractions', abs=1e-10_dp*tmax)
        write (*, '(a,2es10.2)') '    threads_same_result_cattaneo: max |dp|/pmax, max |dpt|/(mu pmax) = ', &
            maxval(abs(n1%pn - n2%pn))/n1%pmax, max(maxval(abs(t1%px - t2%px)), maxval(abs(t1%py - t2%py)))/tmax
    end subroutine test_threads_same_cattaneo

    !> ConvexGS (thesis §4.2.4) on Table 4.1 case 4 at 60×50 with 1 and with 2 threads: its
    !! column updates of the rows other than the element's own run one row per thread after
    !! each grid row, adding the same terms in the same order as one thread, so the sweeps,
    !! the tractions and the subdivision are the same bit for bit (a race or a changed order
    !! of the sums shows as a difference).  Checked to be above the loop's threshold.
    subroutine test_threads_convexgs(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: nres
        type(fc_tangential_operator) :: top
        type(fc_tangential_settings) :: ts
        type(fc_tangential_result) :: t(2)
        integer :: stat, nt0, nt
        character(len=256) :: em
        nt0 = fc_thread_count()
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, em)
        call make_grid(grid, 60, 50, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, em)
        call set_thread_count(1)
        call build_normal_operator(nop, mat, grid)
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), set, nres, stat, em, fn=9.1954_dp)
        call build_tangential_operator(top, mat, grid)
        ts%solver = 'convexgs'
        do nt = 1, 2
            call set_thread_count(nt)
            call solve_tangential(top, nres%pn, 0.4_dp, ts, t(nt), stat, em, 0.0021_dp, 0.0010_dp, 0.003_dp)
        end do
        call set_thread_count(nt0)
        ! the widest contact row's changes (one per element at the first sweep) reach the loop's threshold
        call check(error, int(maxval(count(nres%pn > 0, dim=1)))*grid%nx*grid%ny > omp_min_elements, &
            'column updates above the threshold of the threaded loop')
        call check(error, t(1)%status == FC_CONVERGED .and. t(2)%status == FC_CONVERGED, 'ConvexGS converges on 1 and 2 threads')
        call check(error, t(1)%iterations == t(2)%iterations, 'ConvexGS: same sweeps')
        call check(error, all(t(1)%px == t(2)%px) .and. all(t(1)%py == t(2)%py), 'ConvexGS: tractions equal bit for bit')
        call check(error, all(t(1)%state == t(2)%state), 'ConvexGS: same subdivision')
        call check(error, t(1)%nslip > 0 .and. t(1)%nadh > 0, 'case 4 has slip and adhesion')
    end subroutine test_threads_convexgs

    !> FMG with the Gauss–Seidel smoother (thesis §2.4) on Hertz Test I at 64² with 1 and
    !! with 2 threads: the other rows' parts of a row's sums are computed one row per thread
    !! before the row's sequential sweep adds them in order, so the cycles and pressures are
    !! the same bit for bit.
    subroutine test_threads_fmg_gs(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_fmg_settings) :: set
        type(fc_normal_result) :: r(2)
        integer :: stat(2), nt0, nt
        character(len=256) :: em
        nt0 = fc_thread_count()
        call steel(mat)
        call make_grid(grid, 64, 64, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat(1), em)
        set%tol = 1e-8_dp
        do nt = 1, 2
            call set_thread_count(nt)
            call solve_normal_fmg(mat, grid, quadratic_gap(grid, 300.0_dp, 163.0_dp), set, r(nt), stat(nt), em, &
                approach=0.1091_dp)
        end do
        call set_thread_count(nt0)
        call check(error, all(stat == 0) .and. r(1)%status == FC_CONVERGED .and. r(2)%status == FC_CONVERGED, &
            'FMG converges on 1 and 2 threads: '//trim(em))
        ! the contact (about 38 × 42 elements) times the row length is above the loop's threshold
        call check(error, int(count(r(1)%pn > 0))*grid%nx > omp_min_elements, 'smoother above the threshold')
        call check(error, r(1)%iterations == r(2)%iterations, 'FMG: same iterations')
        call check(error, all(r(1)%pn == r(2)%pn), 'FMG: pressures equal bit for bit')
    end subroutine test_threads_fmg_gs

    !> The 2×2 block products with two threads run their x and y components side by side
    !! (fc_toeplitz's `block_product` on the plan set's lanes) from lanes_min_elements cells.
    !! On 40×36 (above that, below the threaded-FFT size, so the lanes are the only
    !! parallelism): the tangential product equals the direct O(n²) sums of the blocks to
    !! 1e−12 of max|u| (rounding of the FFTs), and the product and TangCG's block inverse
    !! (circulant and Toeplitz forms) equal the one-thread results to 1e−14 (the same
    !! single-threaded transforms).  The same on 41×37, whose circulants are not the doubled
    !! grid nor its Strang circulants the grid itself (doc/operators.md, circulant sizes).
    subroutine test_lanes(error)
        type(error_type), allocatable, intent(out) :: error
        call lanes_on_grid(40, 36, error)
        if (allocated(error)) return
        ! 41×37: doubled sizes 82 = 2·41, 74 = 2·37 are slow for FFTW, so the products run on
        ! 84×78 and the Strang circulants on a 42×39 period (fc_fftw's circulant_size, friendly_size)
        call lanes_on_grid(41, 37, error)
    end subroutine test_lanes

    !> On a 1024² grid with two threads the block products run on the lanes and take the
    !! chunked y passes, one buffer per lane; the product equals the direct sums over the
    !! blocks' coefficients for loads on five elements (edges and corners) to 1e−12.
    subroutine test_lanes_chunked(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_tangential_operator) :: top
        integer, parameter :: n = 1024
        integer, parameter :: ix(5) = [1, n, 1, 600, 77], iy(5) = [1, 1, n, 511, 1000]
        real(dp), allocatable :: px(:, :), py(:, :), ux(:, :), uy(:, :), dx(:, :), dy(:, :)
        integer :: stat, nt0, k, i, j
        character(len=256) :: em
        if (.not. fc_openmp_enabled()) return
        nt0 = fc_thread_count()
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, em)
        call make_grid(grid, n, n, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, stat, em)
        call set_thread_count(2, n*n)
        call build_tangential_operator(top, mat, grid)
        allocate (px(n, n), py(n, n), ux(n, n), uy(n, n), dx(n, n), dy(n, n))
        px = 0; py = 0
        do k = 1, size(ix)
            px(ix(k), iy(k)) = 1 + 0.1_dp*k; py(ix(k), iy(k)) = 0.5_dp - 0.2_dp*k
        end do
        call top%apply(px, py, ux, uy)
        call set_thread_count(nt0)
        call check(error, top%a_xx%lanes_on() .and. top%a_xx%chunked_y(), 'lanes with chunked y passes expected')
        if (allocated(error)) return
        dx = 0; dy = 0
        do k = 1, size(ix)
            do j = 1, n
                do i = 1, n
                    associate (a => px(ix(k), iy(k)), b => py(ix(k), iy(k)), di => i - ix(k), dj => j - iy(k))
                        dx(i, j) = dx(i, j) + a*top%a_xx%kernel(di, dj) + b*top%a_xy%kernel(di, dj)
                        dy(i, j) = dy(i, j) + a*top%a_xy%kernel(di, dj) + b*top%a_yy%kernel(di, dj)
                    end associate
                end do
            end do
        end do
        call check(error, maxval(abs(ux - dx)), 0.0_dp, 'x, lanes vs direct sums', abs=1e-12_dp*maxval(abs(dx)))
        call check(error, maxval(abs(uy - dy)), 0.0_dp, 'y, lanes vs direct sums', abs=1e-12_dp*maxval(abs(dy)))
    end subroutine test_lanes_chunked

    subroutine lanes_on_grid(nx, ny, error)
        integer, intent(in) :: nx, ny
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_tangential_operator) :: top
        real(dp), allocatable :: px(:, :), py(:, :), ux(:, :, :), uy(:, :, :), zx(:, :, :), zy(:, :, :), dx(:, :), dy(:, :)
        real(dp), allocatable :: tx(:, :, :), ty(:, :, :)
        integer :: stat, nt0, nt
        character(len=256) :: em
        character(len=16) :: g
        write (g, '(i0,a,i0,a)') nx, 'x', ny, ': '
        nt0 = fc_thread_count()
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, em)
        call make_grid(grid, nx, ny, -1.0_dp, 1.0_dp, -0.9_dp, 0.9_dp, stat, em)
        call check(error, grid%nx*grid%ny >= lanes_min_elements, trim(g)//'grid at or above lanes_min_elements')
        if (allocated(error)) return
        allocate (px(nx, ny), py(nx, ny), dx(nx, ny), dy(nx, ny), ux(nx, ny, 2), uy(nx, ny, 2), zx(nx, ny, 2), zy(nx, ny, 2))
        allocate (tx(nx, ny, 2), ty(nx, ny, 2))
        call random_number(px); call random_number(py)
        px = px - 0.5_dp; py = 2*py - 0.3_dp
        do nt = 1, 2
            call set_thread_count(nt, grid%nx*grid%ny)
            call build_tangential_operator(top, mat, grid)
            call top%apply(px, py, ux(:, :, nt), uy(:, :, nt))
            call apply_block_inverse(top, px, py, zx(:, :, nt), zy(:, :, nt), .true.)
            call apply_block_inverse(top, px, py, tx(:, :, nt), ty(:, :, nt), .false.)
            if (nt == 2 .and. fc_openmp_enabled()) then
                call check(error, top%a_xx%lanes_on(), trim(g)//'two threads: the block products run on the lanes')
            end if
            if (nt == 2) then
                call top%a_xx%apply_direct(px, dx); call top%a_xy%apply_direct(py, dy); dx = dx + dy
                call check(error, maxval(abs(ux(:, :, 2) - dx)), 0.0_dp, trim(g)//'side by side: x vs direct sums', &
                    abs=1e-12_dp*maxval(abs(dx)))
                call top%a_xy%apply_direct(px, dx); call top%a_yy%apply_direct(py, dy); dy = dx + dy
                call check(error, maxval(abs(uy(:, :, 2) - dy)), 0.0_dp, trim(g)//'side by side: y vs direct sums', &
                    abs=1e-12_dp*maxval(abs(dy)))
            end if
        end do
        call set_thread_count(nt0)
        call check(error, max(maxval(abs(ux(:, :, 1) - ux(:, :, 2))), maxval(abs(uy(:, :, 1) - uy(:, :, 2)))), 0.0_dp, &
            trim(g)//'product, 1 vs 2 threads', abs=1e-14_dp*maxval(abs(ux(:, :, 1))))
        call check(error, max(maxval(abs(zx(:, :, 1) - zx(:, :, 2))), maxval(abs(zy(:, :, 1) - zy(:, :, 2)))), 0.0_dp, &
            trim(g)//'circulant block inverse, 1 vs 2 threads', abs=1e-14_dp*maxval(abs(zx(:, :, 1))))
        call check(error, max(maxval(abs(tx(:, :, 1) - tx(:, :, 2))), maxval(abs(ty(:, :, 1) - ty(:, :, 2)))), 0.0_dp, &
            trim(g)//'Toeplitz block inverse, 1 vs 2 threads', abs=1e-14_dp*maxval(abs(tx(:, :, 1))))
    end subroutine lanes_on_grid

    !> Newton–GMRES steady rolling (Table 4.1 case 4's numbers as creepages) on 192×176,
    !! above omp_min_elements, so that its element loops, Gram–Schmidt dot products and
    !! updates and its block products run on two threads, against one thread: the same
    !! Krylov iterations and slip area, forces to 1e−8·μFn (two threads add the dot
    !! products' partial sums in another order: rounding only; measured ≲ 1e−12).
    subroutine test_threads_rolling(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: nr
        type(fc_tangential_operator) :: top
        type(fc_rolling_settings) :: rs
        type(fc_rolling_loading) :: rl
        type(fc_tangential_result) :: r(2)
        integer :: stat, nt0, nt
        character(len=256) :: em
        real(dp) :: ftol
        nt0 = fc_thread_count()
        call cattaneo_192(mat, grid, error)
        if (allocated(error)) return
        call set_thread_count(1)
        call build_normal_operator(nop, mat, grid)
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), set, nr, stat, em, fn=9.1954_dp)
        rl%mu = 0.4_dp; rl%xi = 0.0021_dp; rl%eta = 0.0010_dp; rl%phi = 0.003_dp
        do nt = 1, 2
            call set_thread_count(nt)
            call build_tangential_operator(top, mat, grid)
            call solve_rolling(top, nr%pn, rl, rs, r(nt), stat, em)
        end do
        call set_thread_count(nt0)
        ftol = 0.4_dp*nr%fn
        call check(error, r(1)%status == FC_CONVERGED .and. r(2)%status == FC_CONVERGED, 'converges with 1 and 2 threads')
        call check(error, r(1)%iterations == r(2)%iterations, 'same Krylov iterations')
        call check(error, r(1)%nslip == r(2)%nslip, 'same slip area')
        call check(error, max(abs(r(1)%fx - r(2)%fx), abs(r(1)%fy - r(2)%fy)), 0.0_dp, '1 vs 2 threads: forces', &
                   abs=1e-8_dp*ftol)
        write (*, '(a,es10.2)') '    threads_same_result_rolling: max |dF|/(mu Fn) = ', &
            max(abs(r(1)%fx - r(2)%fx), abs(r(1)%fy - r(2)%fy))/ftol
        call nop%destroy(); call top%destroy()
    end subroutine test_threads_rolling

    !> The orchestrator with two threads builds the normal and the tangential operators side
    !! by side ([[ensure_operators]]): the same Cattaneo problem as above through
    !! `solve_contact` with fresh operators on 1 and 2 threads gives each operator built once
    !! and the same solution (iterations, areas; pressures and tractions to 1e−10 of their
    !! maxima, as above: only the solvers' threaded sums differ).
    subroutine test_threads_orchestrator(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: set
        type(fc_contact_result) :: r(2)
        integer :: stat, nt0, nt
        character(len=256) :: em
        real(dp), allocatable :: h0(:, :)
        if (.not. fc_openmp_enabled()) then
            write (*, '(a)') '    threads_concurrent_operator_builds: built without OpenMP, nothing to compare'
            return
        end if
        nt0 = fc_thread_count()
        mat%g1 = 200; mat%g2 = 200; mat%nu1 = 0.42_dp; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, em)
        call make_grid(grid, 192, 176, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, stat, em)
        h0 = quadratic_gap(grid, 50.0_dp, 50.0_dp)
        load%problem = FC_PROBLEM_TANGENTIAL
        load%normal%force_prescribed = .true.; load%normal%fn = 9.1954_dp
        load%tangential%mu = 0.4_dp
        load%tangential%xi = 0.0021_dp; load%tangential%eta = 0.0010_dp; load%tangential%phi = 0.003_dp
        do nt = 1, 2
            block
                type(fc_contact_operators) :: ops
                call set_thread_count(nt)
                call solve_contact(ops, grid, mat, h0, load, set, r(nt), stat, em)
                call check(error, stat == 0, 'solve_contact: '//trim(em))
                if (allocated(error)) exit
                call check(error, ops%builds_normal == 1 .and. ops%builds_tangential == 1, &
                    'each operator built once')
                call ops%destroy()
            end block
            if (allocated(error)) exit
        end do
        call set_thread_count(nt0)
        if (allocated(error)) return
        call check(error, all([r(1)%status, r(2)%status] == FC_CONVERGED), 'converged with 1 and 2 threads')
        call check(error, r(1)%normal%iterations == r(2)%normal%iterations .and. &
            r(1)%tangential%iterations == r(2)%tangential%iterations, 'same iteration counts')
        call check(error, r(1)%tangential%nslip == r(2)%tangential%nslip, 'same slip area')
        call check(error, maxval(abs(r(1)%normal%pn - r(2)%normal%pn)), 0.0_dp, 'pressure', abs=1e-10_dp*r(1)%normal%pmax)
        call check(error, max(maxval(abs(r(1)%tangential%px - r(2)%tangential%px)), &
            maxval(abs(r(1)%tangential%py - r(2)%tangential%py))), 0.0_dp, 'tractions', abs=1e-10_dp*0.4_dp*r(1)%normal%pmax)
    end subroutine test_threads_orchestrator

    !> The strip multigrid (thesis ch. 3) on MP1 with 2^16 cells, V(1,1): its FFTs (131072
    !! points, threaded plans), the levels' element loops and the set-up loops run on 2
    !! threads above 32768 cells.  Same cycle count and the same tractions to 1e−12 of their
    !! maximum as one thread (measured: equal; the loops are elementwise, the threaded
    !! transforms may round differently); the same for the products in the radix-2 and
    !! radix-4 layouts of the large levels, run on 2^16 cells.
    subroutine test_threads_strip(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: r(2)
        integer :: stat, nt0, nt
        character(len=256) :: em
        if (.not. fc_openmp_enabled()) return
        nt0 = fc_thread_count()
        do nt = 1, 2
            call set_thread_count(nt)
            call strip_model_problem(1, 2**16, prob, stat, em)
            call check(error, stat == 0, em)
            if (allocated(error)) exit
            call solve_strip_mg(prob, set, r(nt), stat, em)
            call check(error, stat == 0 .and. r(nt)%status == FC_CONVERGED, 'strip MG converged: '//trim(em))
            if (allocated(error)) exit
        end do
        call set_thread_count(nt0)
        if (allocated(error)) return
        call check(error, r(1)%iterations == r(2)%iterations, 'same cycle count')
        call check(error, maxval(abs(r(1)%p - r(2)%p)), 0.0_dp, 'tractions 1 vs 2 threads', abs=1e-12_dp*maxval(abs(r(1)%p)))
        write (*, '(a,es10.2)') '    threads_same_result_strip_mg: max |dp|/max |p| = ', &
            maxval(abs(r(1)%p - r(2)%p))/maxval(abs(r(1)%p))
        ! the radix-2 and radix-4 products (used from 2^18 and 2^20 cells) on 2^16 cells,
        ! where their loops run on both threads: the same products as on one thread
        block
            integer, parameter :: n = 2**16
            type(strip_fft) :: f
            real(dp) :: a(0:n - 1), sym(0:n), x(n), y(n, 2)
            integer :: radix
            call toeplitz_test_data(a, x)
            do radix = 2, 4, 2
                do nt = 1, 2
                    call set_thread_count(nt)
                    call f%init(n, radix=radix)
                    call f%symbol(a, sym)
                    call f%product(sym, x, y(:, nt))
                    call f%destroy()
                end do
                call set_thread_count(nt0)
                call check(error, maxval(abs(y(:, 1) - y(:, 2))), 0.0_dp, 'radix-2/4 product 1 vs 2 threads', &
                    abs=1e-12_dp*maxval(abs(y(:, 1))))
            end do
        end block
    end subroutine test_threads_strip

    !> Requested thread counts are bounded where users give them: fc_set_threads refuses
    !! −1 and 5000 naming the value and the limit (max_threads_allowed = 1024) and accepts 0
    !! (OMP_NUM_THREADS) and 1024; the driver's &solver threads = 5000 is refused naming group,
    !! key, value and limit.
    subroutine test_thread_bounds(error)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: h, ierr
        integer :: code
        character(len=400) :: buf
        character(len=:), allocatable :: err
        call fc_init(h, ierr)
        call fc_set_threads(h, -1_c_int, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(api_message(h), 'nthreads = -1') > 0, &
                   'fc_set_threads(-1) refused naming the value: '//api_message(h))
        if (allocated(error)) return
        call fc_set_threads(h, 5000_c_int, ierr)
        call check(error, ierr == FCL_INVALID_VALUE .and. index(api_message(h), '5000') > 0 .and. &
                   index(api_message(h), '1024') > 0, 'fc_set_threads(5000) refused naming the limit: '//api_message(h))
        if (allocated(error)) return
        call fc_set_threads(h, 0_c_int, ierr)
        call check(error, ierr == FCL_OK, 'fc_set_threads(0) accepted')
        call fc_set_threads(h, 1024_c_int, ierr)
        call check(error, ierr == FCL_OK, 'fc_set_threads(1024) accepted')
        call fc_finalize(h, ierr)
        if (allocated(error)) return
        call drive("&case name = 'tb' / &material g1 = 82000.0, g2 = 82000.0 / &grid nx = 16, ny = 16, "// &
                   "xmin = -2.0, xmax = 2.0, ymin = -1.5, ymax = 1.5 / &geometry kind = 'quadratic', rx = 30.0, "// &
                   "ry = 20.0 / &normal fn = 400.0 / &solver threads = 5000 /", code, err)
        call check(error, code == 1 .and. index(err, '&solver threads = 5000') > 0 .and. index(err, '1024') > 0, &
                   'driver: threads = 5000 refused naming key and limit: '//err)
    contains
        function api_message(hh) result(msg)
            integer(c_int), intent(in) :: hh
            character(len=:), allocatable :: msg
            integer(c_int) :: e
            integer :: k
            call fc_get_error_message(hh, buf, int(len(buf), c_int), e)
            k = index(buf, c_null_char)
            msg = buf(1:max(0, k - 1))
        end function api_message
    end subroutine test_thread_bounds

    !> Wavy surface h0 = A(1 − cos 2πx/λ) on a periodic cell of one wavelength under mean
    !! pressure p̄ = 1.5 p*, p* = π E* A/λ (E* = G/(1−ν) with Kalker's combined constants):
    !! full contact, p = p̄ + p* cos 2πx/λ (Johnson, Contact Mechanics §13.2).  64 elements
    !! per wavelength: the piecewise-constant elements change the amplitude by about
    !! (π/64)²/6 ≈ 0.04 %, the image sum (2 rings + continuum tail) by < 0.1 %; tolerance 0.5 %
    !! of p*.  Below p̄ = p* the contact must open.
    subroutine test_wavy(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: set
        type(fc_normal_result) :: res
        real(dp), allocatable :: h0(:, :), pex(:, :)
        real(dp) :: lam, amp, pstar, pbar
        integer :: stat, i
        character(len=256) :: em
        call steel(mat)
        lam = 2.0_dp; amp = 2e-4_dp
        call make_grid(grid, 64, 4, 0.0_dp, lam, 0.0_dp, 4*lam/64, stat, em)
        h0 = wavy_gap(grid, amp, lam, 0.0_dp)
        pstar = pi*mat%g/(1 - mat%nu)*amp/lam
        pbar = 1.5_dp*pstar
        call build_periodic_normal_operator(nop, mat, grid, stat, em)
        call check(error, stat == 0, 'build: '//trim(em))
        if (allocated(error)) return
        set%tol = 1e-10_dp
        call solve_normal(nop, h0, set, res, stat, em, fn=pbar*lam*grid%ymax)
        call check(error, stat == 0 .and. res%status == FC_CONVERGED, 'solve: '//trim(em)//' '//trim(res%message))
        if (allocated(error)) return
        allocate (pex(64, 4))
        do i = 1, 64
            pex(i, :) = pbar + pstar*cos(2*pi*grid%x(i)/lam)
        end do
        call check(error, res%ncon == 64*4, 'full contact at 1.5 p*')
        call check(error, maxval(abs(res%pn - pex)), 0.0_dp, 'pressure vs Johnson (units of p*)', abs=0.005_dp*pstar)
        call solve_normal(nop, h0, set, res, stat, em, fn=0.9_dp*pstar*lam*grid%ymax)
        call check(error, res%ncon < 64*4, 'partial contact at 0.9 p*')
    end subroutine test_wavy

    !> A cyclic shift of the load shifts the periodic response by the same amount, and the
    !! response to a uniform load is zero (displacements up to a constant, mean removed).
    !! The operator is the circulant on the grid itself (transforms of nx×ny points, not of
    !! the doubled grid), and its FFT product equals the direct circular sums (1e−12).
    subroutine test_circulant(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        real(dp) :: x(16, 12), y(16, 12), ys(16, 12)
        integer :: stat, i, j
        character(len=256) :: em
        call steel(mat)
        call make_grid(grid, 16, 12, 0.0_dp, 1.6_dp, 0.0_dp, 1.0_dp, stat, em)
        call build_periodic_normal_operator(nop, mat, grid, stat, em)
        do j = 1, 12
            do i = 1, 16
                x(i, j) = modulo(0.37_dp*i + 0.61_dp*j*j, 1.0_dp)
            end do
        end do
        call check(error, nop%a_zz%mx == 16 .and. nop%a_zz%my == 12 .and. nop%precond%mx == 16 .and. &
            nop%precond%my == 12, 'periodic operators on the grid itself (16 x 12)')
        call nop%a_zz%apply(x, y)
        call nop%a_zz%apply_direct(x, ys)
        call check(error, maxval(abs(ys - y)), 0.0_dp, 'FFT product vs direct circular sums', abs=1e-12_dp*maxval(abs(y)))
        call nop%a_zz%apply(cshift(cshift(x, 5, 1), -3, 2), ys)
        call check(error, maxval(abs(ys - cshift(cshift(y, 5, 1), -3, 2))), 0.0_dp, 'shifted response', &
            abs=1e-12_dp*maxval(abs(y)))
        x = 1
        call nop%a_zz%apply(x, y)
        call check(error, maxval(abs(y)), 0.0_dp, 'uniform load: zero response', abs=1e-12_dp*maxval(abs(ys)))
    end subroutine test_circulant

    subroutine test_periodic_checks(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_operator) :: nop
        integer :: stat
        character(len=256) :: em
        call steel(mat)
        call make_grid(grid, 15, 12, 0.0_dp, 1.6_dp, 0.0_dp, 1.0_dp, stat, em)
        call build_periodic_normal_operator(nop, mat, grid, stat, em)
        call check(error, stat /= 0 .and. index(em, 'nx = 15') > 0, 'odd nx rejected naming it: '//trim(em))
        call make_grid(grid, 16, 12, 0.0_dp, 1.6_dp, 0.0_dp, 1.0_dp, stat, em)
        call build_periodic_normal_operator(nop, mat, grid, stat, em, images=51)
        call check(error, stat /= 0 .and. index(em, 'images = 51') > 0, 'images above the bound rejected: '//trim(em))
    end subroutine test_periodic_checks

    !> Slabs of rows of the rough surface equal the whole-grid surface bit for bit.
    subroutine test_rough_rows(error)
        type(error_type), allocatable, intent(out) :: error
        type(fc_grid) :: grid
        type(fc_rough_params) :: par
        real(dp) :: z(30, 22), za(30, 1:9), zb(30, 10:22)
        integer :: stat
        character(len=256) :: em
        call make_grid(grid, 30, 22, -1.0_dp, 1.3_dp, -0.8_dp, 0.9_dp, stat, em)
        par%seed = 123
        call rough_heights(grid, par, z)
        call rough_heights_rows(grid, par, 1, 9, za)
        call rough_heights_rows(grid, par, 10, 22, zb)
        call check(error, all(za == z(:, 1:9)) .and. all(zb == z(:, 10:22)), 'slabs equal the whole surface')
    end subroutine test_rough_rows

    !> Write `text` to build/test_parallel.nml and run the driver on it (report discarded);
    !! errors go to build/test_parallel.err, returned in `errtext`.
    subroutine drive(text, code, errtext)
        character(len=*), intent(in) :: text
        integer, intent(out) :: code
        character(len=:), allocatable, intent(out) :: errtext
        character(len=64) :: args(3)
        character(len=512) :: line
        integer :: u, ur, ue, ios
        open (newunit=u, file='build/test_parallel.nml', status='replace', action='write')
        write (u, '(a)') text
        close (u)
        args(1) = 'build/test_parallel.nml'; args(2) = '--out'; args(3) = 'build/test_parallel_out'
        open (newunit=ur, status='scratch')
        open (newunit=ue, file='build/test_parallel.err', status='replace')
        call run_driver(args, code, ur, ue)
        close (ur)
        rewind (ue)
        errtext = ''
        do
            read (ue, '(a)', iostat=ios) line
            if (ios /= 0) exit
            errtext = errtext//trim(line)//' '
        end do
        close (ue)
    end subroutine drive

    !> Value of a numeric JSON key of build/test_parallel_out/NAME.json (huge if absent).
    real(dp) function json_value(name, key) result(v)
        character(len=*), intent(in) :: name, key
        character(len=4096) :: line
        integer :: u, ios, k
        v = huge(1.0_dp)
        open (newunit=u, file='build/test_parallel_out/'//name//'.json', status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            k = index(line, '"'//key//'": ')
            if (k == 1 + verify(line, ' ') - 1 .and. k > 0) then
                read (line(k + len(key) + 4:), *, iostat=ios) v
                exit
            end if
        end do
        close (u)
    end function json_value

    !> The driver with `&grid periodic = .true.` on the wavy surface below full contact:
    !! Johnson's partial-contact solution (§13.2) has sin²(πa/λ) = p̄/p* and
    !! pmax = 2·sqrt(p̄·p*).  64 elements per wavelength: pmax within 1 %, contact width
    !! 2a within one element per side.
    subroutine test_driver_wavy(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: err
        real(dp) :: pstar, pbar, a, lam, pmax, ncon
        integer :: code
        lam = 2.0_dp
        pstar = pi*82000.0_dp/(1 - 0.28_dp)*2.0e-4_dp/lam
        pbar = 4.0_dp/(lam*0.125_dp)
        call drive("&case name = 'wavy_cell' / &material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 / "// &
            "&grid nx = 64, ny = 4, xmin = 0.0, xmax = 2.0, ymin = 0.0, ymax = 0.125, periodic = .true. / "// &
            "&geometry kind = 'wavy', amplitude = 2.0e-4, wavelength_x = 2.0 / &normal fn = 4.0 / "// &
            "&solver tol = 1.0e-10 /", code, err)
        call check(error, code == 0, 'driver exit status 0: '//err)
        if (allocated(error)) return
        pmax = json_value('wavy_cell', 'pmax')
        ncon = json_value('wavy_cell', 'ncon')
        a = lam/pi*asin(sqrt(pbar/pstar))
        call check(error, pmax, 2*sqrt(pbar*pstar), 'pmax vs Johnson 2 sqrt(pbar p*)', rel=0.01_dp)
        call check(error, abs(ncon/4 - 2*a/(lam/64)) <= 2, 'contact width 2a within one element per side')
    end subroutine test_driver_wavy

    subroutine test_driver_periodic_errors(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: err
        character(len=*), parameter :: base = "&case name = 'cell' / &material g1 = 82000.0, g2 = 82000.0 / "// &
            "&geometry kind = 'wavy', amplitude = 2.0e-4, wavelength_x = 2.0 / "
        integer :: code
        call drive(base//"&grid nx = 64, ny = 4, xmin = 0.0, xmax = 2.0, ymin = 0.0, ymax = 0.125, periodic = .true. /"// &
            " &normal approach = 1.0e-4 /", code, err)
        call check(error, code == 1 .and. index(err, 'periodic') > 0 .and. index(err, 'fn') > 0, &
            'periodic with approach rejected: '//err)
        call drive(base//"&grid nx = 63, ny = 4, xmin = 0.0, xmax = 2.0, ymin = 0.0, ymax = 0.125, periodic = .true. /"// &
            " &normal fn = 4.0 /", code, err)
        call check(error, code == 1 .and. index(err, 'nx = 63') > 0, 'odd nx rejected naming it: '//err)
        call drive(base//"&grid nx = 64, ny = 4, xmin = 0.0, xmax = 2.0, ymin = 0.0, ymax = 0.125, periodic = .true. /"// &
            " &normal fn = 4.0 / &case problem = 'rolling' / &tangential mu = 0.3, xi = 1.0e-4 /", code, err)
        call check(error, code == 1 .and. index(err, "problem = 'rolling'") > 0 .and. index(err, 'periodic') > 0, &
            'periodic rolling rejected: '//err)
    end subroutine test_driver_periodic_errors

    !> &solver threads: bounds checked; 2 threads give the 1-thread result to round-off.
    subroutine test_driver_threads(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: err
        character(len=*), parameter :: base = "&case name = 'hz' / &material g1 = 82000.0, g2 = 82000.0 / "// &
            "&grid nx = 48, ny = 40, xmin = -2.0, xmax = 2.0, ymin = -1.5, ymax = 1.5 / "// &
            "&geometry kind = 'quadratic', rx = 30.0, ry = 20.0 / &normal fn = 400.0 / "
        integer :: code
        real(dp) :: p1, p2
        call drive(base//"&solver threads = -1 /", code, err)
        call check(error, code == 1 .and. index(err, 'threads = -1') > 0, 'threads = -1 rejected: '//err)
        call drive(base//"&solver threads = 1 /", code, err)
        p1 = json_value('hz', 'pmax')
        call drive(base//"&solver threads = 2 /", code, err)
        p2 = json_value('hz', 'pmax')
        call set_thread_count(0)
        call check(error, code == 0, 'threads = 2 runs: '//err)
        call check(error, p2, p1, 'pmax with 2 threads', rel=1e-12_dp)
    end subroutine test_driver_threads

    !> Four handles calculated at the same time from four OpenMP threads (creation, solve
    !! and release in the threads) give the pressures of the same handles calculated one
    !! after the other.
    subroutine test_api_threads(error)
        type(error_type), allocatable, intent(out) :: error
        real(c_double) :: pseq(4), ppar(4)
        integer :: k, ok_count
        ok_count = 0
        do k = 1, 4
            call one_handle(k, pseq(k))
        end do
        !$omp parallel do num_threads(4) default(shared) reduction(+:ok_count)
        do k = 1, 4
            call one_handle(k, ppar(k))
            if (ppar(k) > 0) ok_count = ok_count + 1
        end do
        !$omp end parallel do
        call check(error, ok_count == 4, 'every concurrent calculation succeeded')
        call check(error, maxval(abs(ppar - pseq)), 0.0_dp, 'concurrent = sequential pmax', abs=1e-12_dp*maxval(pseq))
    contains
        subroutine one_handle(k, pmax)
            integer, intent(in) :: k
            real(c_double), intent(out) :: pmax
            integer(c_int) :: h, ierr
            pmax = -1
            call fc_init(h, ierr)
            if (ierr /= FCL_OK) return
            call fc_set_material(h, 82000.0_c_double, 82000.0_c_double, 0.28_c_double, 0.28_c_double, ierr)
            call fc_set_grid(h, 40_c_int + 8*k, 36_c_int, -2.0_c_double, 2.0_c_double, -1.5_c_double, 1.5_c_double, ierr)
            call fc_set_gap_quadratic(h, 30.0_c_double, 20.0_c_double, ierr)
            call fc_set_normal_force(h, 100.0_c_double*k, ierr)
            call fc_set_threads(h, 1_c_int, ierr)
            call fc_calculate(h, ierr)
            if (ierr == FCL_OK) call fc_get_pmax(h, pmax, ierr)
            call fc_finalize(h, ierr)
        end subroutine one_handle
    end subroutine test_api_threads

    !> The flat API's periodic cell: Johnson's partial contact pmax = 2 sqrt(p̄ p*) as in the
    !! driver test; without a force it is refused; a bad flag is refused.
    subroutine test_api_periodic(error)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: h, ierr
        real(c_double) :: pmax, h0(64*4)
        real(dp) :: pstar, pbar, lam
        integer :: i
        lam = 2.0_dp
        pstar = pi*82000.0_dp/(1 - 0.28_dp)*2.0e-4_dp/lam
        pbar = 4.0_dp/(lam*0.125_dp)
        do i = 1, 64
            h0(i:256:64) = 2.0e-4_dp*(1 - cos(2*pi*(i - 0.5_dp)*lam/64/lam))
        end do
        call fc_init(h, ierr)
        call fc_set_material(h, 82000.0_c_double, 82000.0_c_double, 0.28_c_double, 0.28_c_double, ierr)
        call fc_set_grid(h, 64_c_int, 4_c_int, 0.0_c_double, 2.0_c_double, 0.0_c_double, 0.125_c_double, ierr)
        call fc_set_gap_array(h, 256_c_int, h0, ierr)
        call fc_set_periodic(h, 2_c_int, ierr)
        call check(error, ierr == FCL_INVALID_VALUE, 'periodic = 2 refused')
        call fc_set_periodic(h, 1_c_int, ierr)
        call fc_set_normal_force(h, 4.0_c_double, ierr)
        call fc_calculate(h, ierr)
        call check(error, ierr == FCL_OK, 'periodic calculation')
        call fc_get_pmax(h, pmax, ierr)
        call check(error, real(pmax, dp), 2*sqrt(pbar*pstar), 'API periodic pmax vs Johnson', rel=0.01_dp)
        call fc_finalize(h, ierr)
    end subroutine test_api_periodic

end module test_parallel
