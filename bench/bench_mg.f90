!> fastcontact-bench-mg: cost of the multigrid solvers (thesis ch. 2 and 3) against BCCG and
!! NORM.  One CSV row per run:
!!
!!   case,solver,cycle,nx,ny,unknowns,iterations,work_units,products,error_vs_hertz,
!!   residual,status,seconds,factor
!!
!! cycle           quoted (it contains a comma): "V(1,1)", "V(1,0)", "V(0,1)"; "" when not MG
!! case            hertz (Test I, §2.5.1), rough1..rough3 (punch cases, §2.5.2), mp1..mp3 (§3.5)
!! solver          fmg-gs (FMG, damped GS, thesis §2.4), fmg-fft-rsm (FMG with the FFT+RSM
!!                 smoother, beyond the thesis; V(1,1) and V(2,2)), bccg, norm (fc_norm), mg-fft-rsm (MG with the
!!                 FFT+RSM smoother, §3.4.2), fft-rsm (one-grid FFT+RSM solver, §3.5.3)
!! iterations      FMG: active-set iterations (V-cycles) on the target grid; MG: V-cycles;
!!                 BCCG: CG iterations; NORM: active-set iterations
!! work_units      thesis convention (one product with A on the target grid = 1; see fc_fmg,
!!                 fc_mg2d); BCCG and NORM: products with A (NORM's = CG iterations + checks)
!! products        every FFT product done, in target-grid units: FMG adds the uncounted
!!                 active-set checks, BCCG adds its preconditioner products
!! error_vs_hertz  RMS of p − p_Hertz over all elements [N/mm²] (Hertz only, else empty)
!! residual        the solver's final relative residual (its own definition)
!! seconds         wall clock of the whole call, set-up (influence coefficients, FFT plans,
!!                 preconditioners, hierarchy) included
!! factor          average defect reduction per cycle (MG, FMG target grid), else empty
!!
!! Usage: fastcontact-bench-mg [--quick] [--nmax N] [--large N] [--kmax K] [--out FILE]
!!   --quick    small sizes only (32²…64², strips up to 2^12): a smoke test
!!   --nmax N   largest grid for FMG-GS and NORM (default 256; GS is O(n²) per sweep)
!!   --large N  largest grid for FMG-FFT+RSM vs BCCG (default 1024)
!!   --kmax K   largest strip 2^K (default 20)
!!   --out F    CSV file (default doc/bench_mg.csv)
program fastcontact_bench_mg
    use fc_kinds, only: dp, status_name
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap, h_no_contact
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, solve_normal
    use fc_fmg, only: fc_fmg_settings, fc_fmg_stats, fc_quadratic_surface, fc_punch_rough_surface, solve_normal_fmg
    use fc_hertz, only: fc_hertz_solution, hertz_from_approach
    use fc_mg2d, only: fc_strip_problem, fc_mg2d_settings, fc_mg2d_result, strip_model_problem
    use fc_mg2d, only: solve_strip_mg, solve_strip_fft_rsm
    implicit none

    real(dp), parameter :: hertz_approach = 0.1091_dp
    real(dp), parameter :: rough_approach(3) = [-0.11_dp, 0.01_dp, 0.25_dp]
    real(dp), parameter :: tol = 1.0e-6_dp
    integer, parameter :: nus(2, 4) = reshape([1, 1, 1, 0, 0, 1, 2, 2], [2, 4])
    character(len=*), parameter :: fmt_row = &
        '(a,",",a,",""",a,""",",i0,",",i0,",",i0,",",i0,",",f0.1,",",f0.1,",",a,",",es9.3,",",a,",",f0.4,",",a)'
    character(len=512) :: out_file, arg
    character(len=64) :: val
    integer :: nmax, nlarge, kmax, iarg, nargs, ios, unit, n, k, icase, c, mp, nmin_large
    logical :: quick
    character(len=8) :: cname

    out_file = 'doc/bench_mg.csv'
    quick = .false.; nmax = 256; nlarge = 1024; kmax = 20
    nargs = command_argument_count()
    iarg = 1
    do while (iarg <= nargs)
        call get_command_argument(iarg, arg)
        select case (trim(arg))
        case ('--quick')
            quick = .true.; nmax = 64; nlarge = 128; kmax = 12
        case ('--nmax', '--large', '--kmax')
            iarg = iarg + 1
            call get_command_argument(iarg, val)
            read (val, *, iostat=ios) k
            if (ios /= 0 .or. k < 1) call usage(trim(arg)//' needs a positive integer, got "'//trim(val)//'"')
            if (arg == '--nmax') nmax = k
            if (arg == '--large') nlarge = k
            if (arg == '--kmax') kmax = k
        case ('--out')
            iarg = iarg + 1
            if (iarg > nargs) call usage('--out needs a file name')
            call get_command_argument(iarg, out_file)
        case ('-h', '--help')
            call usage('')
        case default
            call usage('unknown argument "'//trim(arg)//'"')
        end select
        iarg = iarg + 1
    end do

    open (newunit=unit, file=trim(out_file), status='replace', action='write', iostat=ios)
    if (ios /= 0) call usage('cannot open "'//trim(out_file)//'" for writing')
    write (unit, '(a)') 'case,solver,cycle,nx,ny,unknowns,iterations,work_units,products,error_vs_hertz,'// &
        'residual,status,seconds,factor'

    ! --- chapter 2: FMG (GS), BCCG, NORM on Hertz and the rough punch, 32² … nmax² --------
    n = 32
    do while (n <= nmax)
        do icase = 0, 3
            do c = 1, 3
                call run_normal(icase, n, 'fmg-gs', c)
            end do
            call run_normal(icase, n, 'bccg', 1)
            call run_normal(icase, n, 'norm', 1)
        end do
        n = 2*n
    end do
    ! --- beyond the thesis: FMG with the FFT+RSM smoother vs BCCG, up to nlarge² ----------
    nmin_large = 64
    n = nmin_large
    do while (n <= nlarge)
        do icase = 0, 3
            call run_normal(icase, n, 'fmg-fft-rsm', 1)
            call run_normal(icase, n, 'fmg-fft-rsm', 4)
            if (n > nmax) call run_normal(icase, n, 'bccg', 1)
        end do
        n = 2*n
    end do
    ! --- chapter 3: MP1–MP3, MG FFT+RSM (three cycles) and the FFT+RSM solver -----------
    do mp = 1, 3
        do k = 10, kmax
            if (k < 16 .and. mod(k, 2) == 1) cycle
            do c = 1, 3
                call run_strip(mp, k, 'mg-fft-rsm', c)
            end do
            call run_strip(mp, k, 'fft-rsm', 1)
        end do
    end do
    close (unit)
    write (*, '(a)') 'wrote '//trim(out_file)

contains

    subroutine usage(msg)
        character(len=*), intent(in) :: msg
        if (len_trim(msg) > 0) write (*, '(a)') 'fastcontact-bench-mg: '//trim(msg)
        write (*, '(a)') 'usage: fastcontact-bench-mg [--quick] [--nmax N] [--large N] [--kmax K] [--out FILE]'
        if (len_trim(msg) > 0) error stop 2
        stop
    end subroutine usage

    character(len=8) function cycle_name(c)
        integer, intent(in) :: c
        write (cycle_name, '(a,i0,a,i0,a)') 'V(', nus(1, c), ',', nus(2, c), ')'
    end function cycle_name

    !> One normal-contact run: icase 0 = Hertz Test I, 1..3 = rough punch cases.
    subroutine run_normal(icase, n, solver, c)
        integer, intent(in) :: icase, n, c
        character(len=*), intent(in) :: solver
        type(fc_material) :: mat
        type(fc_grid) :: grid
        type(fc_quadratic_surface) :: qs
        type(fc_punch_rough_surface) :: rs
        type(fc_fmg_settings) :: fset
        type(fc_fmg_stats) :: st
        type(fc_normal_settings) :: nset
        type(fc_normal_operator) :: nop
        type(fc_normal_result) :: res
        real(dp), allocatable :: h0(:, :)
        real(dp) :: approach, work, products, seconds
        character(len=32) :: err_field, cyc, fac
        character(len=256) :: msg
        integer :: stat, t0, t1, rate
        if (icase == 0) then
            mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
            call make_grid(grid, n, n, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, msg)
            qs%rx = 300; qs%ry = 163
            h0 = quadratic_gap(grid, qs%rx, qs%ry)
            approach = hertz_approach
            cname = 'hertz'
        else
            mat%g1 = 1.0e30_dp; mat%g2 = 40000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
            call make_grid(grid, n, n, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, stat, msg)
            allocate (h0(n, n))
            call rs%evaluate(grid, h0)
            approach = rough_approach(icase)
            write (cname, '(a,i0)') 'rough', icase
        end if
        call combine_material(mat, stat, msg)
        cyc = ''; fac = ''
        call system_clock(t0, rate)
        select case (solver)
        case ('fmg-gs', 'fmg-fft-rsm')
            fset%tol = tol
            fset%nu1 = nus(1, c); fset%nu2 = nus(2, c)
            if (solver == 'fmg-fft-rsm') fset%smoother = 'fft-rsm'
            cyc = cycle_name(c)
            if (icase == 0) then
                call solve_normal_fmg(mat, grid, h0, fset, res, stat, msg, approach=approach, surface=qs, stats=st)
            else
                call solve_normal_fmg(mat, grid, h0, fset, res, stat, msg, approach=approach, surface=rs, stats=st)
            end if
            work = st%work_units
            products = st%work_units + st%check_products
            write (fac, '(f0.4)') st%convergence_factor
        case default
            nset%solver = solver
            nset%tol = tol
            call build_normal_operator(nop, mat, grid)
            call solve_normal(nop, h0, nset, res, stat, msg, approach=approach)
            work = res%matvecs
            products = res%matvecs + res%precond_applications
            call nop%destroy()
        end select
        call system_clock(t1)
        seconds = real(t1 - t0, dp)/rate
        if (stat /= 0) then
            write (*, '(a)') 'run failed: '//trim(cname)//' '//solver//': '//trim(msg)
            return
        end if
        err_field = ''
        if (icase == 0) write (err_field, '(f0.4)') hertz_error(grid, res%pn)
        if (solver == 'norm' .or. solver == 'bccg') then
            ! NORM reports active-set iterations as its iteration count
            if (solver == 'norm') res%iterations = res%outer_iterations
        end if
        write (unit, fmt_row) trim(cname), solver, trim(cyc), n, n, n*n, res%iterations, work, products, &
            trim(err_field), res%residual, status_name(res%status), seconds, trim(fac)
        flush (unit)
        write (*, '(a8,1x,a12,1x,a7,i6,i5,f9.1,f9.1,1x,a10,f10.3)') cname, solver, cyc, n, res%iterations, work, &
            products, status_name(res%status), seconds
    end subroutine run_normal

    real(dp) function hertz_error(grid, p) result(err)
        type(fc_grid), intent(in) :: grid
        real(dp), intent(in) :: p(:, :)
        type(fc_hertz_solution) :: s
        integer :: i, j
        s = hertz_from_approach(1/600.0_dp, 1/326.0_dp, 82000/0.72_dp, hertz_approach)
        err = 0
        do j = 1, grid%ny
            do i = 1, grid%nx
                err = err + (p(i, j) - s%pressure(grid%x(i), grid%y(j)))**2
            end do
        end do
        err = sqrt(err/grid%n())
    end function hertz_error

    !> One strip run (MP1–MP3) on 2^k × 1.
    subroutine run_strip(mp, k, solver, c)
        integer, intent(in) :: mp, k, c
        character(len=*), intent(in) :: solver
        type(fc_strip_problem) :: prob
        type(fc_mg2d_settings) :: set
        type(fc_mg2d_result) :: res
        character(len=256) :: msg
        character(len=8) :: cyc
        character(len=32) :: fac
        integer :: stat, n, t0, t1, rate
        real(dp) :: seconds
        n = 2**k
        write (cname, '(a,i0)') 'mp', mp
        call system_clock(t0, rate)
        call strip_model_problem(mp, n, prob, stat, msg)
        if (solver == 'fft-rsm') then
            cyc = ''
            call solve_strip_fft_rsm(prob, set, res, stat, msg)
        else
            set%nu1 = nus(1, c); set%nu2 = nus(2, c)
            cyc = cycle_name(c)
            call solve_strip_mg(prob, set, res, stat, msg)
        end if
        call system_clock(t1)
        seconds = real(t1 - t0, dp)/rate
        if (stat /= 0) then
            write (*, '(a)') 'run failed: '//trim(cname)//' '//solver//': '//trim(msg)
            return
        end if
        write (fac, '(f0.4)') res%factor
        write (unit, fmt_row) trim(cname), solver, trim(cyc), n, 1, n, res%iterations, res%work_units, res%work_units, &
            '', res%residual, status_name(res%status), seconds, trim(fac)
        flush (unit)
        write (*, '(a8,1x,a12,1x,a7,i8,i5,f9.1,f8.4,1x,a10,f10.3)') cname, solver, cyc, n, res%iterations, &
            res%work_units, res%factor, status_name(res%status), seconds
    end subroutine run_strip

end program fastcontact_bench_mg
