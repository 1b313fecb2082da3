!> fastcontact-bench-suite: accuracy against cost of every solver on the reference cases of
!! doc/conventions.md "Reference cases" over a range of grids.  Writes ONE CSV, one row per (case, solver, grid):
!!
!!   case,solver,options,nx,ny,unknowns,error,error_vs,fn_error_rel,area_error_rel,ncon,
!!   iterations,matvecs,work_units,residual,status,setup_seconds,solve_seconds,total_seconds,
!!   setup_cpu_seconds,solve_cpu_seconds,total_cpu_seconds,peak_rss_mb
!!
!! `options` is quoted (it may hold commas, e.g. V(1,1)).
!!
!! Cases and references (`error_vs` names the reference of each row):
!!
!! * `hertz_test1` (thesis §2.5.1): `error` = RMS over all elements of p − p_Hertz [N/mm²]
!!   (analytic elliptic Hertz at the element centres), `hertz_analytic`.
!! * `rough_case1..3` (thesis §2.5.2, δ = −0.11, 0.01, 0.25): `error` = ‖p − R p_ref‖₂/‖R p_ref‖₂
!!   where p_ref is BCCG (tol 1e−10) on the finest grid and R averages it over the fine cells of
!!   each coarse cell (grids are nested); `fn_error_rel` and `area_error_rel` compare total force
!!   and contact area with the reference directly.  `bccg_<n>x<n>_blockavg`.
!! * `cattaneo_case1..7` (thesis Table 4.1): `error` = ‖p_t − R p_t,ref‖₂/‖R p_t,ref‖₂ over both
!!   traction components, p_t,ref from TangCG(3) (tol 1e−9) on the finest grid, the normal
!!   pressure from BCCG (Fn = 9.1954, tol 1e−10) on each grid.  `tangcg_<nx>x<ny>_blockavg`.
!! * `cattaneo_mindlin` (thesis §5.4.2: Fx = 0.875 μ Fn prescribed): `error` = RMS over all
!!   elements of |p_t| − the Cattaneo–Mindlin traction [N/mm²], `cattaneo_mindlin_analytic`.
!! * `mp1` (thesis §3.2.5; when fc_mg2d is present): `error` = relative block-averaged
!!   difference to the finest-grid MG FFT+RSM solution, `mg_fftrsm_<n>_blockavg`.
!!
!! Cost columns: `iterations` and `matvecs` as the solver reports them (products with A);
!! `work_units` is each solver's own work measure: BCCG/NORM FFT-pair products including the
!! preconditioner, FMG and MG the thesis work units (one fine-grid product = 1), TangCG the
!! combined 2×2 block products, ConvexGS its sweeps.  `setup_seconds` is the operator set-up
!! (influence coefficients, FFT symbols, preconditioner, FMG hierarchy), `solve_seconds` the
!! solve, `total_seconds` = both: wall clock of this program around the library calls
!! (system_clock, 64-bit counter); the `*_cpu_seconds` columns are the same intervals in process
!! CPU time (cpu_time), robust when other jobs share the cores (the charts use them).  Tangential rows add the normal solve of the same grid to
!! `setup_seconds`; MP1 rows have the MG set-up inside `solve_seconds` (one library call).  `peak_rss_mb` is VmHWM from /proc/self/status
!! after the run, reset before the run by writing 5 to /proc/self/clear_refs (Linux ≥ 4.0) to
!! the resident size at that moment — which includes memory the allocator kept from earlier
!! runs (and the references), so it is an upper bound for the run, informative at large grids;
!! where the reset is refused it is the process high-water mark so far.  −1: not measurable.
!!
!! Usage: fastcontact-bench-suite [--quick] [--only CASE] [--out FILE]
!!   --quick   small grids only (CI sanity, a few seconds in release)
!!   --only C  run only the case family C: hertz, rough, cattaneo, mindlin, mp1
!!   --out F   CSV file (default doc/bench_suite.csv)
!!
!! Size (~780 lines): one program for the one CSV; each case family's references and rows
!! are one internal procedure.
program fastcontact_bench_suite
    use, intrinsic :: iso_fortran_env, only: int64
    use fc_kinds, only: dp, pi, status_name, FC_CONVERGED
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap, punch_rough_gap, fc_rough_params, h_no_contact
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result
    use fc_norm, only: build_normal_operator, solve_normal
    use fc_tangcg, only: fc_tangential_operator, fc_tangential_settings, fc_tangential_result
    use fc_tangcg, only: fc_tangential_loading
    use fc_tangcg, only: build_tangential_operator, solve_tangential
    use fc_tangcg_force, only: solve_tangential_loading
    use fc_fmg, only: fc_fmg_settings, fc_fmg_stats, fc_fmg_hierarchy, fc_quadratic_surface
    use fc_fmg, only: fc_punch_rough_surface, build_fmg_hierarchy, fmg_solve_lcp
    use fc_mg2d, only: fc_strip_problem, fc_mg2d_settings, fc_mg2d_result
    use fc_mg2d, only: strip_model_problem, solve_strip_mg, solve_strip_fft_rsm
    use fc_hertz, only: fc_hertz_solution, hertz_from_approach, fc_cattaneo_solution, cattaneo_mindlin
    implicit none

    !> One run's row of the CSV.
    type :: row_type
        character(len=24) :: case_name = ''
        character(len=16) :: solver = ''
        character(len=40) :: options = ''
        integer :: nx = 0, ny = 0
        integer(int64) :: unknowns = 0
        real(dp) :: error = -1
        character(len=40) :: error_vs = ''
        real(dp) :: fn_error = 0, area_error = 0
        integer :: ncon = 0, iterations = 0, matvecs = 0
        real(dp) :: work = 0, residual = 0
        integer :: status = 3
        real(dp) :: setup = 0, solve = 0
        real(dp) :: setup_extra = 0              !! added to the set-up (tangential: the normal solve)
        integer(int64) :: t_mark = 0             !! clock count when the solve started
        real(dp) :: cpu0 = 0, cpu_mark = 0       !! process CPU time at the start / when the solve started
        real(dp) :: setup_extra_cpu = 0          !! CPU part of setup_extra
        real(dp) :: setup_cpu = 0, solve_cpu = 0 !! process CPU seconds (cpu_time)
        real(dp) :: peak_mb = -1
    end type row_type

    ! normal solver tolerance for every benchmark row (each solver's own residual)
    real(dp), parameter :: tol_normal = 1.0e-6_dp
    real(dp), parameter :: tol_tangential = 1.0e-5_dp

    ! state shared by the case families
    type(fc_material) :: hmat, rmat, cmat          !! Hertz, rough punch, Cattaneo materials
    type(fc_hertz_solution) :: hz                  !! analytic Hertz Test I
    type(fc_rough_params) :: par                   !! rough surface (thesis §2.5.2, seed 2015)
    real(dp), allocatable :: pref(:, :, :)         !! rough references, one per case
    real(dp) :: fref(3), aref(3)                   !! reference forces and contact areas
    real(dp), allocatable :: pxr(:, :, :), pyr(:, :, :)  !! Cattaneo reference tractions
    real(dp), parameter :: xi(7) = [0.0_dp, 1.5e-5_dp, 0.0_dp, 0.0021_dp, 0.0037_dp, 0.0_dp, 0.0044_dp]
    real(dp), parameter :: eta(7) = [0.0_dp, 0.0_dp, 0.0015_dp, 0.0010_dp, 0.0048_dp, 0.005_dp, 0.0_dp]
    real(dp), parameter :: phi(7) = [5e-7_dp, 1e-5_dp, 0.0012_dp, 0.003_dp, 0.004_dp, 0.009_dp, 0.08_dp]
    real(dp), parameter :: rough_approach(3) = [-0.11_dp, 0.01_dp, 0.25_dp]
    character(len=40) :: rough_vs, catt_vs
    integer :: convexgs_max

    character(len=512) :: out_file, arg, only
    logical :: quick
    integer :: unit, iarg, ios, nrows, nbad

    out_file = 'doc/bench_suite.csv'
    quick = .false.; only = ''
    iarg = 1
    do while (iarg <= command_argument_count())
        call get_command_argument(iarg, arg)
        select case (trim(arg))
        case ('--quick')
            quick = .true.
        case ('--out')
            iarg = iarg + 1
            call get_command_argument(iarg, out_file)
        case ('--only')
            iarg = iarg + 1
            call get_command_argument(iarg, only)
        case ('-h', '--help')
            call usage('')
        case default
            call usage('unknown argument "'//trim(arg)//'"')
        end select
        iarg = iarg + 1
    end do

    open (newunit=unit, file=trim(out_file), status='replace', action='write', iostat=ios)
    if (ios /= 0) then
        write (*, '(a)') 'fastcontact-bench-suite: cannot open '//trim(out_file)
        error stop 2
    end if
    write (unit, '(a)') 'case,solver,options,nx,ny,unknowns,error,error_vs,fn_error_rel,area_error_rel,ncon,' // &
        'iterations,matvecs,work_units,residual,status,setup_seconds,solve_seconds,total_seconds,' // &
        'setup_cpu_seconds,solve_cpu_seconds,total_cpu_seconds,peak_rss_mb'
    write (*, '(a)') 'fastcontact-bench-suite'//merge(' --quick', '        ', quick)//' -> '//trim(out_file)
    write (*, '(a18,1x,a10,1x,a16,1x,a9,1x,a11,1x,a6,1x,a8,1x,a13,1x,a8,1x,a8,1x,a7)') 'case', 'solver', 'options', &
        'grid', 'error', 'iter', 'work', 'status', 'setup_s', 'solve_s', 'peak_MB'
    nrows = 0; nbad = 0

    if (wanted('hertz')) call hertz_family()
    if (wanted('rough')) call rough_family()
    if (wanted('cattaneo')) call cattaneo_family()
    if (wanted('mindlin')) call mindlin_family()
    if (wanted('mp1')) call mp1_family()
    close (unit)
    write (*, '(/,i0,a,i0,a)') nrows, ' rows written, ', nbad, ' not converged (see the status column)'

contains

    logical function wanted(family)
        character(len=*), intent(in) :: family
        wanted = len_trim(only) == 0 .or. trim(only) == family
    end function wanted

    ! ---- Hertz Test I ----------------------------------------------------------------------

    subroutine hertz_family()
        integer, allocatable :: sizes(:)
        integer :: k, n
        hmat = material(82000.0_dp, 82000.0_dp, 0.28_dp)
        hz = hertz_from_approach(0.5_dp/300, 0.5_dp/163, hmat%g/(1 - hmat%nu), 0.1091_dp)
        if (quick) then
            sizes = [32, 64]
        else
            sizes = [32, 64, 128, 256, 512, 1024]
        end if
        do k = 1, size(sizes)
            n = sizes(k)
            call hertz_normal_run('bccg', n)
            if (n <= 512) call hertz_normal_run('norm', n)
            if (n <= 128) call hertz_fmg_run('gs', n)
            call hertz_fmg_run('fft-rsm', n)
        end do
    end subroutine hertz_family

        subroutine hertz_normal_run(solver, n)
            character(len=*), intent(in) :: solver
            integer, intent(in) :: n
            type(fc_grid) :: grid
            type(fc_normal_operator) :: nop
            type(fc_normal_settings) :: set
            type(fc_normal_result) :: res
            type(row_type) :: row
            integer(int64) :: t0
            integer :: st
            character(len=256) :: msg
            call start(row, t0)
            call make_grid(grid, n, n, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, st, msg)
            call build_normal_operator(nop, hmat, grid)
            set%solver = solver; set%tol = tol_normal
            call mark(row)
            call solve_normal(nop, quadratic_gap(grid, 300.0_dp, 163.0_dp), set, res, st, msg, approach=0.1091_dp)
            call check_stat(st, msg)
            row%solver = solver; row%options = 'tol=1e-6'
            if (solver == 'bccg') row%options = 'precondition;tol=1e-6'
            call normal_row(row, grid, res, real(res%matvecs + res%precond_applications, dp))
            call hertz_error(grid, res, row)
            call finish(row, t0)
            call nop%destroy()
        end subroutine hertz_normal_run

        subroutine hertz_fmg_run(smoother, n)
            character(len=*), intent(in) :: smoother
            integer, intent(in) :: n
            type(fc_grid) :: grid
            type(fc_fmg_settings) :: set
            type(fc_fmg_hierarchy) :: hier
            type(fc_fmg_stats) :: stats
            type(fc_quadratic_surface) :: surf
            type(fc_normal_result) :: res
            type(row_type) :: row
            real(dp), allocatable :: h0(:, :)
            integer(int64) :: t0
            integer :: st
            character(len=256) :: msg
            call start(row, t0)
            call make_grid(grid, n, n, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, st, msg)
            surf%rx = 300; surf%ry = 163
            h0 = quadratic_gap(grid, 300.0_dp, 163.0_dp)
            set%smoother = smoother; set%tol = tol_normal
            call build_fmg_hierarchy(hier, hmat, grid, h0, set, st, msg, surface=surf)
            call check_stat(st, msg)
            call mark(row)
            call fmg_solve_lcp(hier, set, res, stats, st, msg, approach=0.1091_dp)
            call check_stat(st, msg)
            row%solver = 'fmg'; row%options = 'V(1,1);smoother='//trim(smoother)//';tol=1e-6'
            call normal_row(row, grid, res, stats%work_units)
            call hertz_error(grid, res, row)
            call finish(row, t0)
            call hier%destroy()
        end subroutine hertz_fmg_run

        subroutine hertz_error(grid, res, row)
            type(fc_grid), intent(in) :: grid
            type(fc_normal_result), intent(in) :: res
            type(row_type), intent(inout) :: row
            integer :: i, j
            real(dp) :: s
            s = 0
            do j = 1, grid%ny
                do i = 1, grid%nx
                    s = s + (res%pn(i, j) - hz%pressure(grid%x(i), grid%y(j)))**2
                end do
            end do
            row%case_name = 'hertz_test1'
            row%error = sqrt(s/(real(grid%nx, dp)*grid%ny))
            row%error_vs = 'hertz_analytic'
            row%fn_error = (res%fn - hz%fn)/hz%fn
            row%area_error = (res%ncon*grid%area() - pi*hz%a*hz%b)/(pi*hz%a*hz%b)
        end subroutine hertz_error

    ! ---- rough punch ----------------------------------------------------------------------

    subroutine rough_family()
        integer, allocatable :: sizes(:)
        integer :: nref, k, c, n, st
        character(len=256) :: msg
        rmat = material(1.0e30_dp, 40000.0_dp, 0.28_dp)
        if (quick) then
            sizes = [32, 64]; nref = 128
        else
            sizes = [64, 128, 256, 512]; nref = 1024
        end if
        write (rough_vs, '(a,i0,a,i0,a)') 'bccg_', nref, 'x', nref, '_blockavg'
        ! reference: BCCG, tol 1e-10, on the finest grid
        block
            type(fc_grid) :: grid
            type(fc_normal_operator) :: nop
            type(fc_normal_settings) :: set
            type(fc_normal_result) :: res
            real(dp), allocatable :: h0(:, :)
            call make_grid(grid, nref, nref, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, st, msg)
            allocate (h0(nref, nref), pref(nref, nref, 3))
            call punch_rough_gap(grid, 8.97_dp, par, h0)
            call build_normal_operator(nop, rmat, grid)
            set%tol = 1.0e-10_dp
            do c = 1, 3
                call solve_normal(nop, h0, set, res, st, msg, approach=rough_approach(c))
                call check_stat(st, msg)
                if (res%status /= FC_CONVERGED) write (*, '(a)') 'rough reference: '//trim(res%message)
                pref(:, :, c) = res%pn
                fref(c) = res%fn
                aref(c) = res%ncon*grid%area()
                write (*, '(a,i0,a,i0,a,f6.2,a,i0,a)') 'rough reference case ', c, ' on ', nref, '^2: ', &
                    100.0_dp*res%ncon/count(h0 < 0.5_dp*h_no_contact), ' % of the punch in contact, ', &
                    res%iterations, ' BCCG iterations'
            end do
            call nop%destroy()
        end block
        do k = 1, size(sizes)
            n = sizes(k)
            call rough_grid_runs(n)
        end do
    end subroutine rough_family

        subroutine rough_grid_runs(n)
            integer, intent(in) :: n
            integer :: c, st
            character(len=256) :: msg
            type(fc_grid) :: grid
            type(fc_normal_operator) :: nop
            type(fc_normal_settings) :: set
            type(fc_normal_result) :: res
            type(fc_fmg_settings) :: fset
            type(fc_fmg_hierarchy) :: hier
            type(fc_fmg_stats) :: stats
            type(fc_punch_rough_surface) :: surf
            type(row_type) :: row
            real(dp), allocatable :: h0(:, :)
            integer(int64) :: t0
            integer :: isol, ism
            character(len=8), parameter :: smoothers(2) = ['gs     ', 'fft-rsm']
            call make_grid(grid, n, n, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, st, msg)
            allocate (h0(n, n))
            call punch_rough_gap(grid, 8.97_dp, par, h0)
            do isol = 1, 2
                if (isol == 2 .and. n > 512) cycle
                do c = 1, 3
                    call start(row, t0)
                    ! the operator is rebuilt per run so that set-up and peak memory are per run
                    call build_normal_operator(nop, rmat, grid)
                    set%solver = merge('bccg', 'norm', isol == 1); set%tol = tol_normal
                    call mark(row)
                    call solve_normal(nop, h0, set, res, st, msg, approach=rough_approach(c))
                    call check_stat(st, msg)
                    row%solver = set%solver; row%options = 'tol=1e-6'
                    if (isol == 1) row%options = 'precondition;tol=1e-6'
                    call normal_row(row, grid, res, real(res%matvecs + res%precond_applications, dp))
                    call rough_error(c, grid, res, row)
                    call finish(row, t0)
                    call nop%destroy()
                end do
            end do
            do ism = 1, 2
                if (ism == 1 .and. n > 128) cycle
                do c = 1, 3
                    call start(row, t0)
                    fset%smoother = smoothers(ism); fset%tol = tol_normal
                    surf%diameter = 8.97_dp; surf%rough = par
                    call build_fmg_hierarchy(hier, rmat, grid, h0, fset, st, msg, surface=surf)
                    call check_stat(st, msg)
                    call mark(row)
                    call fmg_solve_lcp(hier, fset, res, stats, st, msg, approach=rough_approach(c))
                    call check_stat(st, msg)
                    row%solver = 'fmg'; row%options = 'V(1,1);smoother='//trim(smoothers(ism))//';tol=1e-6'
                    call normal_row(row, grid, res, stats%work_units)
                    call rough_error(c, grid, res, row)
                    call finish(row, t0)
                    call hier%destroy()
                end do
            end do
        end subroutine rough_grid_runs

        subroutine rough_error(c, grid, res, row)
            integer, intent(in) :: c
            type(fc_grid), intent(in) :: grid
            type(fc_normal_result), intent(in) :: res
            type(row_type), intent(inout) :: row
            write (row%case_name, '(a,i0)') 'rough_case', c
            row%error = block_error(res%pn, pref(:, :, c))
            row%error_vs = rough_vs
            row%fn_error = (res%fn - fref(c))/fref(c)
            row%area_error = (res%ncon*grid%area() - aref(c))/aref(c)
        end subroutine rough_error

    ! ---- Cattaneo cases 1–7 (thesis Table 4.1) --------------------------------------------

    subroutine cattaneo_family()
        integer, allocatable :: gx(:), gy(:)
        integer :: nrefx, nrefy, k, c, st
        character(len=256) :: msg
        cmat = material(200.0_dp, 200.0_dp, 0.42_dp)
        if (quick) then
            gx = [30, 60]; gy = [25, 50]; nrefx = 120; nrefy = 100; convexgs_max = 60
        else
            gx = [30, 60, 120, 240]; gy = [25, 50, 100, 200]; nrefx = 480; nrefy = 400; convexgs_max = 120
        end if
        write (catt_vs, '(a,i0,a,i0,a)') 'tangcg_', nrefx, 'x', nrefy, '_blockavg'
        allocate (pxr(nrefx, nrefy, 7), pyr(nrefx, nrefy, 7))
        block
            type(fc_grid) :: grid
            type(fc_normal_result) :: nr
            type(fc_tangential_operator) :: top
            type(fc_tangential_settings) :: ts
            type(fc_tangential_result) :: tr
            real(dp) :: dummy, dummy2
            call cattaneo_normal(nrefx, nrefy, grid, nr, dummy, dummy2)
            call build_tangential_operator(top, cmat, grid)
            ts%tol = 1.0e-9_dp; ts%maxit = 20000
            do c = 1, 7
                call solve_tangential(top, nr%pn, 0.4_dp, ts, tr, st, msg, xi(c), eta(c), phi(c))
                call check_stat(st, msg)
                if (tr%status /= FC_CONVERGED) write (*, '(a)') 'cattaneo reference: '//trim(tr%message)
                pxr(:, :, c) = tr%px; pyr(:, :, c) = tr%py
            end do
            write (*, '(a,i0,a,i0,a)') 'cattaneo reference: TangCG(3) tol 1e-9 on ', nrefx, 'x', nrefy, ' done'
            call top%destroy()
        end block
        do k = 1, size(gx)
            call cattaneo_grid_runs(gx(k), gy(k))
        end do
    end subroutine cattaneo_family

        subroutine cattaneo_grid_runs(nx, ny)
            integer, intent(in) :: nx, ny
            integer :: c, st
            character(len=256) :: msg
            type(fc_grid) :: grid
            type(fc_normal_result) :: nr
            type(fc_tangential_operator) :: top
            type(fc_tangential_settings) :: ts
            type(fc_tangential_result) :: tr
            type(row_type) :: row
            real(dp) :: normal_seconds, normal_cpu
            integer(int64) :: t0
            integer :: s
            character(len=8), parameter :: label(3) = ['tangcg  ', 'tangcg  ', 'convexgs']
            logical, parameter :: pre(3) = [.true., .false., .true.]
            call cattaneo_normal(nx, ny, grid, nr, normal_seconds, normal_cpu)
            do c = 1, 7
                do s = 1, 3
                    if (s == 3 .and. nx > convexgs_max) cycle
                    call start(row, t0)
                    call build_tangential_operator(top, cmat, grid)
                    ts = fc_tangential_settings()
                    ts%solver = label(s); ts%precondition = pre(s); ts%tol = tol_tangential
                    call mark(row)
                    call solve_tangential(top, nr%pn, 0.4_dp, ts, tr, st, msg, xi(c), eta(c), phi(c))
                    call check_stat(st, msg)
                    write (row%case_name, '(a,i0)') 'cattaneo_case', c
                    row%solver = label(s)
                    if (s == 3) then
                        row%options = 'tol=1e-5'
                        row%work = tr%iterations
                    else
                        row%options = 'K=3;'//merge('precondition   ', 'no_precondition', pre(s))//';tol=1e-5'
                        row%work = tr%matvecs
                    end if
                    row%nx = nx; row%ny = ny; row%unknowns = 2_int64*nx*ny
                    row%error = traction_error(tr%px, tr%py, pxr(:, :, c), pyr(:, :, c))
                    row%error_vs = catt_vs
                    row%fn_error = 0; row%area_error = 0
                    row%ncon = tr%ncon; row%iterations = tr%iterations; row%matvecs = tr%matvecs
                    row%residual = tr%residual; row%status = tr%status
                    row%setup_extra = normal_seconds; row%setup_extra_cpu = normal_cpu
                    call finish(row, t0)
                    call top%destroy()
                end do
            end do
        end subroutine cattaneo_grid_runs

        real(dp) function traction_error(px, py, qx, qy) result(e)
            real(dp), intent(in) :: px(:, :), py(:, :), qx(:, :), qy(:, :)
            real(dp), allocatable :: rx(:, :), ry(:, :)
            allocate (rx(size(px, 1), size(px, 2)), ry(size(px, 1), size(px, 2)))
            call block_average(qx, rx)
            call block_average(qy, ry)
            e = sqrt(sum((px - rx)**2 + (py - ry)**2)/max(sum(rx**2 + ry**2), tiny(1.0_dp)))
        end function traction_error

    !> Normal problem of the Cattaneo cases: sphere R = 50 on a plane, Fn = 9.1954, BCCG.
    subroutine cattaneo_normal(nx, ny, grid, nr, seconds, cpu_seconds)
        integer, intent(in) :: nx, ny
        type(fc_grid), intent(out) :: grid
        type(fc_normal_result), intent(out) :: nr
        real(dp), intent(out) :: seconds, cpu_seconds
        real(dp) :: c0
        type(fc_material) :: mat
        type(fc_normal_operator) :: nop
        type(fc_normal_settings) :: ns
        integer(int64) :: t0
        integer :: st
        character(len=256) :: msg
        call cpu_time(c0)
        call system_clock(t0)
        mat = material(200.0_dp, 200.0_dp, 0.42_dp)
        call make_grid(grid, nx, ny, -1.2857_dp, 1.2857_dp, -1.2857_dp, 1.2857_dp, st, msg)
        call build_normal_operator(nop, mat, grid)
        ns%tol = 1.0e-10_dp
        call solve_normal(nop, quadratic_gap(grid, 50.0_dp, 50.0_dp), ns, nr, st, msg, fn=9.1954_dp)
        call check_stat(st, msg)
        call nop%destroy()
        seconds = elapsed(t0)
        call cpu_time(cpu_seconds)
        cpu_seconds = cpu_seconds - c0
    end subroutine cattaneo_normal

    ! ---- Cattaneo–Mindlin: prescribed Fx = 0.875 μ Fn --------------------------------------

    subroutine mindlin_family()
        integer, allocatable :: gx(:), gy(:)
        integer :: k, s, st, i, j
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_normal_result) :: nr
        type(fc_tangential_operator) :: top
        type(fc_tangential_settings) :: ts
        type(fc_tangential_result) :: tr
        type(fc_tangential_loading) :: load
        type(fc_cattaneo_solution) :: cm
        type(row_type) :: row
        real(dp) :: normal_seconds, normal_cpu, sq
        integer(int64) :: t0
        character(len=256) :: msg
        character(len=8), parameter :: label(3) = ['tangcg  ', 'tangcg  ', 'convexgs']
        logical, parameter :: pre(3) = [.true., .false., .true.]
        mat = material(200.0_dp, 200.0_dp, 0.42_dp)
        ! a = 1, p0 = 4.3905 (doc/conventions.md); Fn = 9.1954, μ = 0.4, Q = 0.875 μ Fn: stick radius 0.5
        cm = cattaneo_mindlin(1.0_dp, 4.3905_dp, 9.1954_dp, 0.4_dp, 0.875_dp*0.4_dp*9.1954_dp, mat%g, mat%nu)
        if (quick) then
            gx = [30, 60]; gy = [25, 50]
        else
            gx = [30, 60, 120, 240]; gy = [25, 50, 100, 200]
        end if
        load%mu = 0.4_dp; load%force_prescribed = .true.
        load%fx = 0.875_dp*0.4_dp*9.1954_dp; load%fy = 0
        do k = 1, size(gx)
            call cattaneo_normal(gx(k), gy(k), grid, nr, normal_seconds, normal_cpu)
            do s = 1, 3
                if (s == 3 .and. gx(k) > 60) cycle
                call start(row, t0)
                call build_tangential_operator(top, mat, grid)
                ts = fc_tangential_settings()
                ts%solver = label(s); ts%precondition = pre(s); ts%tol = tol_tangential
                call mark(row)
                call solve_tangential_loading(top, nr%pn, load, ts, tr, st, msg)
                call check_stat(st, msg)
                row%case_name = 'cattaneo_mindlin'
                row%solver = label(s)
                if (s == 3) then
                    row%options = 'force;tol=1e-5'
                    row%work = tr%iterations
                else
                    row%options = 'K=3;'//merge('precondition   ', 'no_precondition', pre(s))//';force;tol=1e-5'
                    row%work = tr%matvecs
                end if
                row%nx = gx(k); row%ny = gy(k); row%unknowns = 2_int64*gx(k)*gy(k)
                sq = 0
                do j = 1, grid%ny
                    do i = 1, grid%nx
                        sq = sq + (hypot(tr%px(i, j), tr%py(i, j)) - cm%traction(hypot(grid%x(i), grid%y(j))))**2
                    end do
                end do
                row%error = sqrt(sq/(real(grid%nx, dp)*grid%ny))
                row%error_vs = 'cattaneo_mindlin_analytic'
                ! fn_error_rel: rigid shift against Mindlin's; area_error_rel: stick area against π c²
                row%fn_error = (abs(tr%xi) - cm%shift)/cm%shift
                row%area_error = (tr%nadh*grid%area() - pi*cm%c**2)/(pi*cm%c**2)
                row%ncon = tr%ncon; row%iterations = tr%iterations; row%matvecs = tr%matvecs
                row%residual = tr%residual; row%status = tr%status
                row%setup_extra = normal_seconds; row%setup_extra_cpu = normal_cpu
                call finish(row, t0)
                call top%destroy()
            end do
        end do
    end subroutine mindlin_family

    ! ---- MP1: 2D strip, constant shift (thesis §3.2.5, §3.5) ------------------------------

    subroutine mp1_family()
        integer, allocatable :: expo(:)
        integer :: eref, k, s, st, n
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        type(row_type) :: row
        real(dp), allocatable :: pref(:)
        integer(int64) :: t0
        character(len=256) :: msg
        character(len=40) :: vs
        character(len=12), parameter :: label(3) = ['mg          ', 'mg          ', 'fft-rsm-1g  ']
        character(len=8), parameter :: smoother(3) = ['fft-rsm ', 'fft-sd  ', 'fft-rsm ']
        if (quick) then
            expo = [8, 9, 10]; eref = 12
        else
            expo = [10, 12, 14, 16, 18]; eref = 20
        end if
        write (vs, '(a,i0,a)') 'mg_fftrsm_', 2**eref, '_blockavg'
        call strip_model_problem(1, 2**eref, prob, st, msg)
        call check_stat(st, msg)
        set%tol = 1.0e-10_dp; set%maxit = 200
        call solve_strip_mg(prob, set, res, st, msg)
        call check_stat(st, msg)
        if (res%status /= FC_CONVERGED) write (*, '(a)') 'mp1 reference: '//trim(res%message)
        pref = res%p
        do k = 1, size(expo)
            n = 2**expo(k)
            call strip_model_problem(1, n, prob, st, msg)
            call check_stat(st, msg)
            do s = 1, 3
                call start(row, t0)
                set = fc_mg2d_settings()
                set%smoother = smoother(s); set%tol = 1.0e-8_dp; set%maxit = 200
                ! FFT+SD converges with V(1,0) (thesis Tables 3.2/3.3), not with V(1,1)
                if (s == 2) set%nu2 = 0
                call mark(row)
                if (s == 3) then
                    call solve_strip_fft_rsm(prob, set, res, st, msg)
                else
                    call solve_strip_mg(prob, set, res, st, msg)
                end if
                call check_stat(st, msg)
                row%case_name = 'mp1'
                row%solver = label(s)
                row%options = 'smoother='//trim(smoother(s))//';tol=1e-8'
                if (s == 1) row%options = 'V(1,1);'//row%options
                if (s == 2) row%options = 'V(1,0);'//row%options
                row%nx = n; row%ny = 1; row%unknowns = n
                row%error = block_error(reshape(res%p, [n, 1]), reshape(pref, [size(pref), 1]))
                row%error_vs = vs
                row%fn_error = (sum(res%p)/n - sum(pref)/size(pref))/(sum(pref)/size(pref))
                row%area_error = 0
                row%ncon = n; row%iterations = res%iterations; row%matvecs = 0
                row%work = res%work_units; row%residual = res%residual; row%status = res%status
                call finish(row, t0)
            end do
        end do
    end subroutine mp1_family

    ! ---- helpers --------------------------------------------------------------------------

    !> Combined material of two bodies with moduli g1, g2 and the same Poisson ratio.
    function material(g1, g2, nu) result(mat)
        real(dp), intent(in) :: g1, g2, nu
        type(fc_material) :: mat
        integer :: st
        character(len=256) :: msg
        mat%g1 = g1; mat%g2 = g2; mat%nu1 = nu; mat%nu2 = nu
        call combine_material(mat, st, msg)
        call check_stat(st, msg)
    end function material

    !> Common columns of a normal-solver row.
    subroutine normal_row(row, grid, res, work)
        type(row_type), intent(inout) :: row
        type(fc_grid), intent(in) :: grid
        type(fc_normal_result), intent(in) :: res
        real(dp), intent(in) :: work
        row%nx = grid%nx; row%ny = grid%ny; row%unknowns = int(grid%nx, int64)*grid%ny
        row%ncon = res%ncon; row%iterations = res%iterations; row%matvecs = res%matvecs
        row%work = work; row%residual = res%residual; row%status = res%status
    end subroutine normal_row

    !> Average `fine` over the fine cells of each coarse cell (nested grids, integer ratio).
    subroutine block_average(fine, coarse)
        real(dp), intent(in) :: fine(:, :)
        real(dp), intent(out) :: coarse(:, :)
        integer :: fx, fy, i, j
        fx = size(fine, 1)/size(coarse, 1); fy = size(fine, 2)/size(coarse, 2)
        if (fx*size(coarse, 1) /= size(fine, 1) .or. fy*size(coarse, 2) /= size(fine, 2)) &
            error stop 'fastcontact-bench-suite: reference grid is not a refinement of the run grid'
        do j = 1, size(coarse, 2)
            do i = 1, size(coarse, 1)
                coarse(i, j) = sum(fine(fx*(i - 1) + 1:fx*i, fy*(j - 1) + 1:fy*j))/(fx*fy)
            end do
        end do
    end subroutine block_average

    !> ‖p − R p_ref‖₂/‖R p_ref‖₂ with R the block average onto p's grid.
    real(dp) function block_error(p, pref) result(e)
        real(dp), intent(in) :: p(:, :), pref(:, :)
        real(dp), allocatable :: r(:, :)
        allocate (r(size(p, 1), size(p, 2)))
        call block_average(pref, r)
        e = sqrt(sum((p - r)**2)/max(sum(r**2), tiny(1.0_dp)))
    end function block_error

    !> Start a run: reset the peak-RSS counter and the clock.
    subroutine start(row, t0)
        type(row_type), intent(out) :: row
        integer(int64), intent(out) :: t0
        integer :: u, ios
        open (newunit=u, file='/proc/self/clear_refs', action='write', status='old', iostat=ios)
        if (ios == 0) then
            write (u, '(a)', iostat=ios) '5'
            close (u)
        end if
        call cpu_time(row%cpu0)
        call system_clock(t0)
    end subroutine start

    !> The solve starts now (wall clock and process CPU time).
    subroutine mark(row)
        type(row_type), intent(inout) :: row
        call cpu_time(row%cpu_mark)
        call system_clock(row%t_mark)
    end subroutine mark

    real(dp) function elapsed(t0)
        integer(int64), intent(in) :: t0
        integer(int64) :: t1, rate
        call system_clock(t1, rate)
        elapsed = real(t1 - t0, dp)/real(rate, dp)
    end function elapsed

    !> VmHWM of this process in MB (−1 when /proc is unavailable).
    real(dp) function peak_rss_mb() result(mb)
        integer :: u, ios, kb
        character(len=256) :: line
        mb = -1
        open (newunit=u, file='/proc/self/status', action='read', status='old', iostat=ios)
        if (ios /= 0) return
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (line(1:6) == 'VmHWM:') then
                read (line(7:), *, iostat=ios) kb
                if (ios == 0) mb = kb/1024.0_dp
                exit
            end if
        end do
        close (u)
    end function peak_rss_mb

    !> Complete a row (set-up = start → solve start, solve = solve start → now, peak memory),
    !! write it to the CSV and the terminal.
    subroutine finish(row, t0)
        type(row_type), intent(inout) :: row
        integer(int64), intent(in) :: t0
        character(len=24) :: gname
        integer(int64) :: t1, rate
        real(dp) :: cpu1
        call system_clock(t1, rate)
        call cpu_time(cpu1)
        row%solve_cpu = cpu1 - row%cpu_mark
        row%setup_cpu = row%setup_extra_cpu + row%cpu_mark - row%cpu0
        row%solve = real(t1 - row%t_mark, dp)/real(rate, dp)
        row%setup = row%setup_extra + real(row%t_mark - t0, dp)/real(rate, dp)
        row%peak_mb = peak_rss_mb()
        write (unit, '(a,",",a,",",a,2(",",i0),",",i0,",",a,",",a,2(",",a),3(",",i0),",",a,",",a,",",a,6(",",a),",",a)') &
            trim(row%case_name), trim(row%solver), '"'//trim(row%options)//'"', row%nx, row%ny, row%unknowns, &
            num(row%error, '(es13.6)'), trim(row%error_vs), num(row%fn_error, '(es11.4)'), &
            num(row%area_error, '(es11.4)'), row%ncon, row%iterations, row%matvecs, num(row%work, '(f0.2)'), &
            num(row%residual, '(es10.3)'), status_name(row%status), num(row%setup, '(f0.5)'), &
            num(row%solve, '(f0.5)'), num(row%setup + row%solve, '(f0.5)'), &
            num(row%setup_cpu, '(f0.5)'), num(row%solve_cpu, '(f0.5)'), num(row%setup_cpu + row%solve_cpu, '(f0.5)'), &
            num(row%peak_mb, '(f0.1)')
        flush (unit)
        nrows = nrows + 1
        if (row%status /= FC_CONVERGED) nbad = nbad + 1
        write (gname, '(i0,"x",i0)') row%nx, row%ny
        write (*, '(a18,1x,a10,1x,a16,1x,a9,1x,es11.4,1x,i6,1x,f8.1,1x,a13,1x,f8.3,1x,f8.3,1x,f7.1)') &
            row%case_name, row%solver, row%options(1:16), gname, row%error, row%iterations, row%work, &
            status_name(row%status), row%setup, row%solve, row%peak_mb
    end subroutine finish

    subroutine check_stat(st, msg)
        integer, intent(in) :: st
        character(len=*), intent(in) :: msg
        if (st /= 0) then
            write (*, '(a)') 'fastcontact-bench-suite: '//trim(msg)
            error stop 1
        end if
    end subroutine check_stat

    !> A real formatted with `fmt`, without blanks and with a leading zero (".5" → "0.5").
    function num(x, fmt) result(str)
        real(dp), intent(in) :: x
        character(len=*), intent(in) :: fmt
        character(len=:), allocatable :: str
        character(len=40) :: buf
        write (buf, fmt) x
        str = trim(adjustl(buf))
        if (str(1:1) == '.') str = '0'//str
        if (len(str) > 1) then
            if (str(1:2) == '-.') str = '-0'//str(2:)
        end if
    end function num

    subroutine usage(problem)
        character(len=*), intent(in) :: problem
        if (len(problem) > 0) write (*, '(a)') 'fastcontact-bench-suite: '//problem
        write (*, '(a)') 'usage: fastcontact-bench-suite [--quick] [--only hertz|rough|cattaneo|mindlin|mp1] [--out FILE]'
        if (len(problem) > 0) error stop 2
        stop
    end subroutine usage

end program fastcontact_bench_suite
