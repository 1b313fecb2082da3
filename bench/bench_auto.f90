!> fastcontact-bench-auto: what the automatic layer (accuracy target, automatic area, model reduction) saves, and what it costs.
!!
!! For each model reduction the reduced and the full model are solved on the same scene; the
!! program prints the answers, their relative difference and the wall-clock cost ratio
!! (full / reduced).  For the accuracy target it prints the grids visited, the estimate, the
!! true error and the cost against solving the final grid alone and against a fixed fine grid.
!! The replay (section 7) runs the estimator on one reference sequence per scene from every
!! given grid and 21 targets, and counts bound failures and over-refinement.
!! Output: a table on stdout and CSV (`--csv FILE`, default build/bench_auto.csv);
!! `--replay-only` runs only the replay.
!! Timings are wall-clock seconds of one run (set-up included); repeat for variance.
program bench_auto
    use, intrinsic :: iso_fortran_env, only: int64, error_unit
    use fc_kinds, only: dp, msg_len
    use fc_namelist, only: fc_case_chunk, read_case_file
    use fc_input, only: fc_case_input, apply_case
    use fc_input_validate, only: validate_case
    use fc_input_scene, only: build_case
    use fc_scene, only: fc_case
    use fc_contact, only: fc_contact_operators
    use fc_hertz, only: fc_hertz_solution, hertz_from_approach, hertz_from_force
    use fc_auto, only: fc_auto_outcome, fc_level, solve_case_auto, plane_strain_hertz, level_estimate, &
        certify_coarsest, target_quantities, estimate_safety, estimate_safety_h2
    implicit none
    character(len=*), parameter :: nl = new_line('a')
    character(len=*), parameter :: hertz_scene = &
        '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
        "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"//nl//'&normal approach = 0.1091 /'//nl
    character(len=*), parameter :: cattaneo_scene = &
        "&case problem = 'normal+tangential' /"//nl// &
        '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
        '&grid nx = 128, ny = 128, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /'//nl// &
        "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl//'&normal approach = 0.02 /'//nl
    type(fc_auto_outcome) :: red, full, seq
    ! estimator variants replayed in section 7: [two-grid factor, safety, safety in the O(h²) band]
    integer, parameter :: nvar = 5
    real(dp), parameter :: variants(3, nvar) = reshape([estimate_safety, estimate_safety, estimate_safety_h2, &
        2.0_dp, 2.0_dp, 1.25_dp, &
        2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp/3, 2.0_dp, 2.0_dp, 1.0_dp/3, 1.0_dp, 1.0_dp], [3, nvar])
    character(len=*), parameter :: variant_names(nvar) = [character(len=40) :: &
        'package: 2|d|; s = 2, 1.5 for r in [3,6]', 'band factor 1.25', 's = 2 everywhere', &
        'previous: two-grid 2|d|/3; s = 2', 'pure Richardson: |d|/3; s = 1']
    integer :: totals(6, nvar), nwork(nvar), cert_totals(3)  ! certified grid: bound failures, minimal, attainable
    real(dp) :: worst_margin(nvar), work(4000, nvar)
    character(len=:), allocatable :: scene
    real(dp) :: tr, tf, b, p0
    type(fc_hertz_solution) :: hz
    integer :: csv, i
    logical :: replay_only = .false.
    character(len=256) :: csv_path, arg
    csv_path = 'build/bench_auto.csv'
    i = 1
    do while (i <= command_argument_count())
        call get_command_argument(i, arg)
        if (arg == '--csv' .and. i < command_argument_count()) then
            call get_command_argument(i + 1, csv_path); i = i + 1
        else if (arg == '--replay-only') then
            replay_only = .true.
        else
            write (error_unit, '(a)') 'fastcontact-bench-auto: unknown argument "'//trim(arg)//'"'
            write (error_unit, '(a)') 'usage: fastcontact-bench-auto [--csv FILE] [--replay-only]'
            stop 2
        end if
        i = i + 1
    end do
    open (newunit=csv, file=trim(csv_path), status='replace', action='write')
    write (csv, '(a)') 'section,variant,model,grid,quantity,value,reference,rel_diff,seconds,cost_ratio'
    hz = hertz_from_approach(1/600.0_dp, 1/326.0_dp, 82000.0_dp/0.72_dp, 0.1091_dp)
    if (.not. replay_only) call reductions_and_sweep()
    call replay_all()
    close (csv)
    write (*, '(a)') 'CSV: '//trim(csv_path)

contains

    !> Sections 1–6: each model reduction against the full model; the accuracy target on
    !! Hertz Test I; the target sweep of four scenes.
    subroutine reductions_and_sweep()
        write (*, '(a)') 'fastcontact-bench-auto: reduced vs full model (cost ratio = full seconds / reduced seconds)'

        ! ---- 1. problem = 'hertz' vs the full model to 1e-3 (auto area)
        call solve_text("&case problem = 'hertz' /"//nl//hertz_scene, red, tr)
        call solve_text(hertz_scene//'&solver target = 1.0e-3 /'//nl, full, tf)
        call row('hertz_analytic', 'analytic', red, 'fn', red%hertz%fn, full%result%normal%fn, tr, tf)
        call row('hertz_analytic', 'full_target_1e-3', full, 'fn', full%result%normal%fn, red%hertz%fn, tf, tf)
        call row('hertz_analytic', 'full_target_1e-3', full, 'pmax', full%result%normal%pmax, red%hertz%p0, tf, tf)

        ! ---- 2. line contact: cylinder as a strip vs a 3D grid of the same cylinder
        call solve_text('&material g1 = 82000.0, g2 = 82000.0 /'//nl// &
            "&geometry kind = 'cylinder', rx = 100.0, length = 20.0 /"//nl//'&normal fn = 2.0e4 /'//nl, red, tr)
        call solve_text('&material g1 = 82000.0, g2 = 82000.0 /'//nl// &
            "&geometry kind = 'cylinder', rx = 100.0, length = 20.0 /"//nl//'&normal fn = 2.0e4 /'//nl// &
            "&solver model = 'full' /"//nl, full, tf)
        call plane_strain_hertz(100.0_dp, 1000.0_dp, 82000.0_dp/0.72_dp, b, p0)
        call row('line_contact', 'strip2d', red, 'pmax', red%result%normal%pmax, p0, tr, tf)
        call row('line_contact', 'full_3d_finite_cylinder', full, 'pmax_centre_line', &
            maxval(full%result%normal%pn(:, (full%grid%ny + 1)/2)), p0, tf, tf)
        call row('line_contact', 'full_3d_finite_cylinder', full, 'pmax_ends', full%result%normal%pmax, p0, tf, tf)

        ! ---- 3. no tangential loading (zero shifts, K = 0): normal only vs normal + tangential
        call solve_text(cattaneo_scene//'&tangential mu = 0.4, xi = 0.0, eta = 0.0, phi = 0.0 /'//nl, red, tr)
        call solve_text(cattaneo_scene//'&tangential mu = 0.4, xi = 0.0, eta = 0.0, phi = 0.0 /'//nl// &
            "&solver model = 'full' /"//nl, full, tf)
        call row('no_tangential_loading', 'normal_only', red, 'fn', red%result%normal%fn, full%result%normal%fn, tr, tf)
        call row('no_tangential_loading', 'full', full, 'fx', full%result%tangential%fx, 0.0_dp, tf, tf)

        ! ---- 4. K = 0: decoupled (one normal + one tangential solve) vs the coupled pipeline
        call solve_text(cattaneo_scene//'&tangential mu = 0.4, xi = -0.0081724 /'//nl, red, tr)
        call solve_text(cattaneo_scene//'&tangential mu = 0.4, xi = -0.0081724 /'//nl//"&solver model = 'full' /"//nl, &
            full, tf)
        call row('k0_decoupled', 'decoupled', red, 'fx', red%result%tangential%fx, full%result%tangential%fx, tr, tf)

        ! ---- 5. accuracy target vs the final grid alone and a fixed 256² grid
        call solve_text(hertz_scene//'&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl// &
            '&solver target = 5.0e-4 /'//nl, red, tr)
        do i = 1, size(red%levels)
            write (*, '(a,i5,a,es12.4,a,es12.4,a,f8.4,a)') '    target 5e-4: grid ', red%levels(i)%nx, '^2  estimate ', &
                red%levels(i)%estimate, '  true error ', abs(red%levels(i)%fn - hz%fn)/hz%fn, '  ', red%levels(i)%seconds, ' s'
            write (csv, '(a,i0,a,es14.6,a,es14.6,a,es12.4,a,es12.4,a)') 'target_levels,level,full,', red%levels(i)%nx, &
                ',fn,', red%levels(i)%fn, ',', hz%fn, ',', abs(red%levels(i)%fn - hz%fn)/hz%fn, ',', red%levels(i)%seconds, ','
        end do
        call solve_text(hertz_scene//'&grid nx = 64, ny = 64, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl, &
            full, tf)
        call row('accuracy_target', 'target_5e-4_all_grids', red, 'fn', red%result%normal%fn, hz%fn, tr, tf)
        call row('accuracy_target', 'final_grid_alone', full, 'fn', full%result%normal%fn, hz%fn, tf, tf)
        call solve_text(hertz_scene//'&grid nx = 256, ny = 256, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'// &
            nl, full, tf)
        call row('accuracy_target', 'fixed_256', full, 'fn', full%result%normal%fn, hz%fn, tf, tr)

        ! ---- 6. target sweep: the grid the algorithm chooses for each target (one full run per
        ! target: the solver tolerance, hence the noise floor of the estimate, follows the target)
        ! against the truth from one reference sequence refined to the finest grid.
        write (*, '(a)') '  target sweep (chosen grid vs the coarsest grid whose TRUE error meets T):'
        scene = hertz_scene//'&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl
        call solve_text(scene//'&solver target = 1.0e-9, max_levels = 6 /'//nl, seq, tr)
        call sweep('hertz_16', scene, seq, hz%fn, 0.0_dp, .false.)
        call solve_text(hertz_scene//'&solver target = 1.0e-9, max_levels = 6 /'//nl, seq, tr)
        call sweep('hertz_auto_area', hertz_scene, seq, hz%fn, 0.0_dp, .false.)
        scene = "&case problem = 'normal+tangential' /"//nl// &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /'//nl// &
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl//'&normal approach = 0.02 /'//nl// &
            '&tangential mu = 0.4, xi = -0.0081724 /'//nl
        call solve_text(scene//'&solver target = 1.0e-9, max_levels = 6 /'//nl, seq, tr)
        ! Fn: analytic Hertz; Fx: the 512² value (its own error is ~3e-6, Richardson on 256²/512²)
        call sweep('cattaneo_16', scene, seq, hertz_fn_cattaneo(), seq%levels(size(seq%levels))%fx, .true.)
        scene = '&material g1 = 1.0e30, g2 = 40000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -6.0, xmax = 6.0, ymin = -5.0, ymax = 5.0 /'//nl// &
            "&geometry kind = 'punch_rough', diameter = 8.97 /"//nl//'&normal approach = 0.01 /'//nl
        call solve_text(scene//'&solver target = 1.0e-9, max_levels = 7 /'//nl, seq, tr)
        ! reference: the 1024² value
        call sweep('rough_punch_16', scene, seq, seq%levels(size(seq%levels))%fn, 0.0_dp, .false.)

    end subroutine reductions_and_sweep

    !> Section 7: the estimator replayed from every given grid of 15 scenes.
    subroutine replay_all()
        integer :: v
        ! ---- 7. replay of the estimator from every given grid: one reference sequence per scene,
        ! the estimator (fc_auto's level_estimate) replayed on it for each given grid (probe one
        ! level below) and 21 targets 1e-2 ... 1e-4; true errors against analytic Hertz where it
        ! applies, else against the Richardson value of the two finest grids (then not replayed).
        write (*, '(a)') '  replay from every given grid (21 targets 1e-2 ... 1e-4 each):'
        totals = 0; worst_margin = 0; nwork = 0; cert_totals = 0
        scene = hertz_scene//'&grid nx = 16, ny = 16, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'//nl
        call replay('hertz_16', scene, hz%fn, 0.0_dp)
        call replay('hertz_12', hertz_scene//'&grid nx = 12, ny = 12, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /'// &
            nl, hz%fn, 0.0_dp)
        call replay('hertz_20x12', hertz_scene//'&grid nx = 20, ny = 12, xmin = -10.0, xmax = 10.0, ymin = -6.0, '// &
            'ymax = 6.0 /'//nl, hz%fn, 0.0_dp)
        call replay('hertz_auto_area', hertz_scene, hz%fn, 0.0_dp)
        call replay('hertz_auto_fn', hertz_scene//'&normal fn = 82004.0 /'//nl, &
            hertz_approach(1/600.0_dp, 1/326.0_dp, 82000.0_dp/0.72_dp, 82004.0_dp), 0.0_dp)
        call replay('ellipse_rx400_ry20', '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            "&geometry kind = 'quadratic', rx = 400.0, ry = 20.0 /"//nl//'&normal fn = 1.0e4 /'//nl, &
            hertz_approach(1/800.0_dp, 1/40.0_dp, 82000.0_dp/0.72_dp, 1.0e4_dp), 0.0_dp)
        call replay('ellipse_rx100_ry33', '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -4.0, xmax = 4.0, ymin = -2.5, ymax = 2.5 /'//nl// &
            "&geometry kind = 'quadratic', rx = 100.0, ry = 33.0 /"//nl//'&normal approach = 0.05 /'//nl, &
            hertz_force(1/200.0_dp, 1/66.0_dp, 82000.0_dp/0.72_dp, 0.05_dp), 0.0_dp)
        scene = '&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /'//nl// &
            "&geometry kind = 'quadratic', rx = 20.0, ry = 20.0 /"//nl//'&normal fn = 500.0 /'//nl
        call replay('sphere_auto_area', scene, hertz_approach(1/40.0_dp, 1/40.0_dp, 82000.0_dp/0.72_dp, 500.0_dp), &
            0.0_dp)
        call replay('sphere_wide_area', scene//'&grid nx = 16, ny = 16, xmin = -1.0, xmax = 1.0, ymin = -1.0, ymax = 1.0 /'// &
            nl, hertz_approach(1/40.0_dp, 1/40.0_dp, 82000.0_dp/0.72_dp, 500.0_dp), 0.0_dp)
        scene = "&case problem = 'normal+tangential' /"//nl// &
            '&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /'//nl// &
            '&grid nx = 16, ny = 16, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /'//nl// &
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"//nl//'&normal approach = 0.02 /'//nl
        call replay('cattaneo_16', scene//'&tangential mu = 0.4, xi = -0.0081724 /'//nl, hertz_fn_cattaneo(), 0.0_dp)
        call replay('cattaneo_12', scene//'&grid nx = 12, ny = 12 /'//nl//'&tangential mu = 0.4, xi = -0.0081724 /'//nl, &
            hertz_fn_cattaneo(), 0.0_dp)
        call replay('cattaneo_small_shift', scene//'&tangential mu = 0.4, xi = -0.003 /'//nl, hertz_fn_cattaneo(), 0.0_dp)
        call replay('cattaneo_spin', scene//'&tangential mu = 0.4, xi = -0.002, eta = 0.001, phi = 0.002 /'//nl, &
            hertz_fn_cattaneo(), 0.0_dp)
        call replay('cattaneo_forces', scene//'&normal fn = 9.1954 /'//nl//'&tangential mu = 0.4, fx = 1.28736 /'//nl, &
            0.0_dp, 0.0_dp)
        call replay('rigid_on_elastic', scene//'&material g1 = 1.0e30, g2 = 200.0, nu1 = 0.28, nu2 = 0.3 /'//nl// &
            '&tangential mu = 0.3, xi = -0.004 /'//nl, 0.0_dp, 0.0_dp)
        write (*, '(a)') '  all scenes, per estimator variant (minimal: one level coarser misses T, counted where the '// &
            'probe misses T):'
        write (*, '(4x,a,i0,a,i0,a,i0,a,f5.1,a)') 'package, coarsest grid certified by the finest: bound failures ', &
            cert_totals(1), ', minimal ', cert_totals(2), ' of ', cert_totals(3), ' (', &
            100.0_dp*cert_totals(2)/max(cert_totals(3), 1), ' %)'
        write (csv, '(a,3(i0,a))') 'replay,all:certified coarsest grid,bound_fail|minimal_attainable|attainable,', &
            cert_totals(1), '|', cert_totals(2), '|', cert_totals(3), ',,,,,'
        do v = 1, nvar
            write (*, '(4x,a40,a,i0,a,i0,a,i0,a,i0,a,f5.1,a,f5.2,a,f6.2,a,f6.2)') variant_names(v), ': met ', totals(1, v), &
                ', bound failures ', totals(2, v), ', not met ', totals(4, v), ', minimal ', totals(6, v), ' (', &
                100.0_dp*totals(6, v)/max(totals(5, v), 1), ' %), worst true/est ', worst_margin(v), &
                ', work/cheapest median ', percentile(work(1:nwork(v), v), 0.5_dp), ', 90 % ', &
                percentile(work(1:nwork(v), v), 0.9_dp)
            write (csv, '(a,6(i0,a),es12.4,a,es12.4,a,es12.4)') 'replay,all:'//trim(variant_names(v))// &
                ',met|bound_fail|minimal|not_met|attainable|minimal_attainable,', totals(1, v), '|', totals(2, v), '|', &
                totals(3, v), '|', totals(4, v), '|', totals(5, v), '|', totals(6, v), ',worst_true_over_estimate,', &
                worst_margin(v), ',', percentile(work(1:nwork(v), v), 0.5_dp), ',', percentile(work(1:nwork(v), v), 0.9_dp)
        end do
    end subroutine replay_all

    !> Target sweep: for each target solve `scene` with it and compare the chosen grid with
    !! the reference sequence `seq` (the true error of each of its grids against `ref_fn` and,
    !! with `with_fx`, `ref_fx`).  "minimal": the grid one level coarser than the chosen one
    !! misses the target (the issue's criterion); "oracle": the coarsest grid of `seq` that
    !! meets it.  Cost ratio: seconds of all grids visited / seconds of the oracle grid alone.
    subroutine sweep(scene_name, scene_text, seq, ref_fn, ref_fx, with_fx)
        character(len=*), intent(in) :: scene_name, scene_text
        type(fc_auto_outcome), intent(in) :: seq
        real(dp), intent(in) :: ref_fn, ref_fx
        logical, intent(in) :: with_fx
        real(dp), parameter :: targets(7) = [1.0e-2_dp, 5.0e-3_dp, 2.0e-3_dp, 1.0e-3_dp, 5.0e-4_dp, 2.0e-4_dp, 1.0e-4_dp]
        type(fc_auto_outcome) :: out, alone
        character(len=400) :: gbuf
        real(dp), allocatable :: true_seq(:)
        real(dp) :: true_err, coarser_err, secs, ratio
        integer :: k, t, n, oracle, kc
        logical :: minimal, bound
        character(len=8) :: cgrid, ogrid
        character(len=16) :: tbuf
        n = size(seq%levels)
        allocate (true_seq(n))
        do k = 1, n
            true_seq(k) = rel_err(seq%levels(k)%fn, seq%levels(k)%fx, ref_fn, ref_fx, with_fx)
        end do
        do t = 1, size(targets)
            write (tbuf, '(es10.3)') targets(t)
            call solve_text(scene_text//'&solver target = '//trim(adjustl(tbuf))//' /'//nl, out, secs)
            oracle = 0
            do k = 1, n
                if (true_seq(k) <= targets(t)) then
                    oracle = k; exit
                end if
            end do
            ogrid = 'none'
            if (oracle > 0) write (ogrid, '(i0)') seq%levels(oracle)%nx
            if (.not. out%target_met) then
                write (*, '(4x,a16,a,es8.1,a,es9.2,a,i0,a,a)') scene_name, ' T ', targets(t), '  NOT MET: estimate ', &
                    out%estimate, ' after ', size(out%levels), ' grids; oracle ', trim(ogrid)
                write (csv, '(a,es9.2,a,es12.4,a,es12.4)') 'target_sweep,'//scene_name//',T=', targets(t), &
                    ',chosen=none|oracle='//trim(ogrid)//',estimate,', out%estimate, ',,,', secs
                cycle
            end if
            write (cgrid, '(i0)') out%grid%nx
            true_err = rel_err(out%result%normal%fn, out%result%tangential%fx, ref_fn, ref_fx, with_fx)
            ! the reference sequence holds the same grids (same start, refined by two)
            kc = 0
            do k = 1, n
                if (seq%levels(k)%nx == out%grid%nx) kc = k - 1
            end do
            coarser_err = huge(1.0_dp)
            if (kc >= 1) coarser_err = true_seq(kc)
            minimal = coarser_err > targets(t)
            bound = true_err <= out%estimate
            ! the coarsest sufficient grid solved alone, same area and solver tolerance
            ratio = -1
            if (oracle > 0) then
                write (gbuf, '(a,i0,a,i0,4(a,es22.14),a,es10.3,a)') '&grid auto = .false., nx = ', &
                    seq%levels(oracle)%nx, ', ny = ', seq%levels(oracle)%ny, ', xmin = ', out%grid%xmin, &
                    ', xmax = ', out%grid%xmax, ', ymin = ', out%grid%ymin, ', ymax = ', out%grid%ymax, &
                    ' /'//nl//'&solver tol = ', out%tol, ' /'
                call solve_text(scene_text//trim(gbuf)//nl, alone, secs)
                ratio = out%total_seconds/max(alone%total_seconds, 1.0e-6_dp)
            end if
            write (*, '(4x,a16,a,es8.1,a,a5,a,es9.2,a,es9.2,a,l1,a,l1,a,a5,a,f6.1)') scene_name, ' T ', targets(t), &
                '  chosen ', cgrid, '  est ', out%estimate, '  true ', true_err, '  bound ', bound, '  minimal ', &
                minimal, '  oracle ', ogrid, '  cost/oracle ', ratio
            write (csv, '(a,es9.2,a,es12.4,a,es12.4,a,es12.4,a,es12.4,a,es12.4)') 'target_sweep,'//scene_name//',T=', &
                targets(t), ',chosen='//trim(cgrid)//'|oracle='//trim(ogrid)//',estimate,', out%estimate, ',', true_err, &
                ',', coarser_err, ',', out%total_seconds, ',', ratio
            ! the coarsest grid certified by the finest (JSON accuracy.coarsest_sufficient)
            if (out%sufficient < 1) cycle
            kc = 0
            do k = 1, n
                if (seq%levels(k)%nx == out%levels(out%sufficient)%nx) kc = k
            end do
            if (kc < 1) cycle
            coarser_err = -1      ! −1: no grid below the certified one was visited
            if (kc >= 2) coarser_err = true_seq(kc - 1)
            write (cgrid, '(i0)') out%levels(out%sufficient)%nx
            write (*, '(4x,a16,a,es8.1,a,a5,a,es9.2,a,es9.2,a,es9.2,a)') scene_name, ' T ', targets(t), '  certified ', &
                cgrid, '  bound ', out%sufficient_bound, '  true ', true_seq(kc), '  one level below ', coarser_err, &
                trim(merge(' misses', ' meets ', coarser_err > targets(t) .or. coarser_err < 0))
            write (csv, '(a,es9.2,a,es12.4,a,es12.4,a,es12.4)') 'target_sweep_certified,'//scene_name//',T=', &
                targets(t), ',certified='//trim(cgrid)//',bound,', out%sufficient_bound, ',', true_seq(kc), ',', coarser_err
        end do
    end subroutine sweep

    !> Replay the estimator on the reference sequence of scene `text` from every given grid:
    !! for each grid k ≥ 2 of the sequence as the given grid (probe k − 1) and each target,
    !! the grid the algorithm would stop at (default `max_levels` 5, noise 10·min(tol, T/100))
    !! is compared with the true errors: `truth_q1` of fn (approach prescribed) or of the
    !! approach (fn prescribed), `truth_q2` of the tangential quantity; 0 = the Richardson value
    !! of the two finest grids (observed ratio), which are then not replayed.  For each
    !! estimator variant adds to `totals` (met, bound failures, one level coarser misses, not
    !! met, probe misses T, of those one level coarser misses), `worst_margin` and `work`
    !! (elements of all grids visited / elements of the coarsest sufficient grid, when the
    !! probe is not sufficient itself); prints the scene's line for the package's variant.
    subroutine replay(name, text, truth_q1, truth_q2)
        character(len=*), intent(in) :: name, text
        real(dp), intent(in) :: truth_q1, truth_q2
        type(fc_auto_outcome) :: ref
        type(fc_case) :: s
        type(fc_level), allocatable :: lv(:)
        real(dp), allocatable :: q(:, :), true_err(:)
        real(dp) :: secs, truth(2), scale(2), tgt, noise, est, ratio, margin
        integer :: n, nq, nuse, k, start, it, chosen, oracle, cnt(6), j, v, jc
        real(dp) :: cbound
        logical :: tang, mono, extrapolated
        character(len=64) :: qname
        call solve_text(text//'&solver target = 1.0e-9, max_levels = 6 /'//nl, ref, secs, s)
        n = 0
        do k = 1, size(ref%levels)
            if (ref%levels(k)%status /= 'converged') exit
            n = k
        end do
        lv = ref%levels(1:n)
        tang = ref%tangential
        ! the estimator's own quantities (relative to the finest level; the tangential one
        ! already relative to its scale): fn or approach, then the tangential quantity
        call target_quantities(lv, s, tang, q, qname)
        nq = size(q, 2)
        allocate (true_err(n))
        truth = [truth_q1/abs(merge(lv(n)%approach, lv(n)%fn, s%normal%force_prescribed)), truth_q2]
        extrapolated = .false.
        do j = 1, nq
            if (truth(j) == 0) then
                truth(j) = richardson_limit(q(:, j)); extrapolated = .true.
            end if
        end do
        scale = [abs(truth(1)), 1.0_dp]
        nuse = merge(n - 1, n, extrapolated)
        do k = 1, nuse
            true_err(k) = maxval(abs(q(k, :) - truth(1:nq))/scale(1:nq))
        end do
        do v = 1, nvar
            cnt = 0; margin = 0
            do start = 1, nuse - 1
                do it = 0, 20
                    tgt = 10.0_dp**(-2 - it/10.0_dp)
                    noise = 10*min(s%settings%normal%tol, tgt/100)
                    chosen = 0
                    do k = start + 1, min(nuse, start + 5)
                        call level_estimate(lv(start:k), s, tang, noise, est, ratio, mono, qname, variants(:, v))
                        if (est <= tgt) then
                            chosen = k; exit
                        end if
                    end do
                    if (chosen == 0) then
                        cnt(4) = cnt(4) + 1; cycle
                    end if
                    cnt(1) = cnt(1) + 1
                    if (true_err(chosen) > est) cnt(2) = cnt(2) + 1
                    if (true_err(chosen - 1) > tgt) cnt(3) = cnt(3) + 1
                    ! attainable: the probe misses the target, so a minimal choice exists above it
                    if (true_err(start) > tgt) then
                        cnt(5) = cnt(5) + 1
                        if (true_err(chosen - 1) > tgt) cnt(6) = cnt(6) + 1
                    end if
                    margin = max(margin, true_err(chosen)/est)
                    if (v == 1) then
                        ! the coarsest grid certified by the finest (reported as coarsest_sufficient)
                        call certify_coarsest(lv(start:chosen), s, tang, est, tgt, jc, cbound)
                        jc = start - 1 + jc
                        if (true_err(jc) > cbound) cert_totals(1) = cert_totals(1) + 1
                        if (true_err(start) > tgt) then
                            cert_totals(3) = cert_totals(3) + 1
                            if (jc > start) then
                                if (true_err(jc - 1) > tgt) cert_totals(2) = cert_totals(2) + 1
                            end if
                        end if
                    end if
                    oracle = 0
                    do k = start, nuse
                        if (true_err(k) <= tgt) then
                            oracle = k; exit
                        end if
                    end do
                    if (oracle > start .and. nwork(v) < size(work, 1)) then
                        nwork(v) = nwork(v) + 1
                        work(nwork(v), v) = sum(real(lv(start:chosen)%nx, dp)*lv(start:chosen)%ny)/ &
                            (real(lv(oracle)%nx, dp)*lv(oracle)%ny)
                    end if
                end do
            end do
            totals(:, v) = totals(:, v) + cnt
            worst_margin(v) = max(worst_margin(v), margin)
            if (v > 1) cycle
            write (*, '(4x,a20,a,i0,a,i0,a,i3,a,i3,a,i3,a,i3,a,i3,a,i3,a,f5.2)') name, ' grids ', lv(1)%nx, '..', &
                lv(nuse)%nx, ': met ', cnt(1), '  bound failures ', cnt(2), '  not met ', cnt(4), '  coarser misses ', &
                cnt(3), '; probe misses T: ', cnt(5), ', of which minimal ', cnt(6), '  worst true/est ', margin
            write (csv, '(a,6(i0,a),es12.4)') 'replay,'//name//',met|bound_fail|minimal|not_met|attainable|'// &
                'minimal_attainable,', cnt(1), '|', cnt(2), '|', cnt(3), '|', cnt(4), '|', cnt(5), '|', cnt(6), &
                ',worst_true_over_estimate,', margin
        end do
    end subroutine replay

    !> Limit of a sequence on grids refined by two: Richardson with the observed ratio of its
    !! last two differences (4 if that ratio is below 1.5).
    pure real(dp) function richardson_limit(v) result(lim)
        real(dp), intent(in) :: v(:)
        real(dp) :: d, r
        integer :: n
        n = size(v)
        d = v(n) - v(n - 1)
        r = 4
        if (d /= 0) r = (v(n - 1) - v(n - 2))/d
        if (r < 1.5_dp) r = 4
        lim = v(n) + d/(r - 1)
    end function richardson_limit

    !> The `p`-quantile of `x` (0 ≤ p ≤ 1, nearest rank; 0 for an empty array).
    real(dp) function percentile(x, p) result(m)
        real(dp), intent(in) :: x(:), p
        real(dp), allocatable :: y(:)
        real(dp) :: t
        integer :: i, j
        m = 0
        if (size(x) == 0) return
        y = x
        do i = 2, size(y)
            t = y(i); j = i - 1
            do while (j >= 1)
                if (y(j) <= t) exit
                y(j + 1) = y(j); j = j - 1
            end do
            y(j + 1) = t
        end do
        m = y(max(1, min(size(y), ceiling(p*size(y)))))
    end function percentile

    !> Relative error of Fn (and of Fx with `with_fx`) against the references.
    pure real(dp) function rel_err(fn, fx, ref_fn, ref_fx, with_fx) result(e)
        real(dp), intent(in) :: fn, fx, ref_fn, ref_fx
        logical, intent(in) :: with_fx
        e = abs(fn - ref_fn)/abs(ref_fn)
        if (with_fx) e = max(e, abs(fx - ref_fx)/abs(ref_fx))
    end function rel_err

    !> Analytic Hertz approach [mm] for curvatures A, B [1/mm], E* [N/mm²] and force fn [N].
    real(dp) function hertz_approach(a, b, estar, fn) result(approach)
        real(dp), intent(in) :: a, b, estar, fn
        type(fc_hertz_solution) :: h
        h = hertz_from_force(a, b, estar, fn)
        approach = h%approach
    end function hertz_approach

    !> Analytic Hertz force [N] for curvatures A, B [1/mm], E* [N/mm²] and approach [mm].
    real(dp) function hertz_force(a, b, estar, approach) result(fn)
        real(dp), intent(in) :: a, b, estar, approach
        type(fc_hertz_solution) :: h
        h = hertz_from_approach(a, b, estar, approach)
        fn = h%fn
    end function hertz_force

    !> Hertz Fn of the Cattaneo sphere (R = 50, G = 200, nu = 0.42 both bodies, approach 0.02).
    real(dp) function hertz_fn_cattaneo() result(fn)
        type(fc_hertz_solution) :: h
        h = hertz_from_approach(1/100.0_dp, 1/100.0_dp, 200.0_dp/(1 - 0.42_dp), 0.02_dp)
        fn = h%fn
    end function hertz_fn_cattaneo

    !> One row: `value` vs `reference`, cost `seconds`, cost ratio `other/seconds`.
    subroutine row(section, variant, out, quantity, value, reference, seconds, other)
        character(len=*), intent(in) :: section, variant, quantity
        type(fc_auto_outcome), intent(in) :: out
        real(dp), intent(in) :: value, reference, seconds, other
        real(dp) :: rel
        character(len=24) :: grid
        rel = abs(value - reference)/max(abs(reference), tiny(1.0_dp))
        if (abs(reference) == 0) rel = abs(value)
        write (grid, '(i0,a,i0)') out%grid%nx, 'x', out%grid%ny
        if (out%analytic) grid = 'none'
        write (*, '(2x,a22,1x,a26,1x,a14,1x,a10,1x,a16,es13.5,a,es10.3,a,f9.4,a,f9.1)') section, variant, out%model, grid, &
            quantity, value, '  rel.diff ', rel, '  s ', seconds, '  ratio ', other/max(seconds, 1.0e-6_dp)
        write (csv, '(a,es23.15,a,es23.15,a,es12.4,a,es12.4,a,es12.4)') trim(section)//','//trim(variant)//','// &
            trim(out%model)//','//trim(grid)//','//trim(quantity)//',', value, ',', reference, ',', rel, ',', seconds, &
            ',', other/max(seconds, 1.0e-6_dp)
    end subroutine row

    !> Read namelist text as the driver does and solve it; wall-clock seconds.
    subroutine solve_text(text, out, seconds, state_out)
        character(len=*), intent(in) :: text
        type(fc_auto_outcome), intent(out) :: out
        real(dp), intent(out) :: seconds
        type(fc_case), intent(out), optional :: state_out  !! the validated case, before solving
        type(fc_case_chunk), allocatable :: cases(:)
        type(fc_case_input) :: state
        type(fc_case) :: kase
        type(fc_contact_operators) :: ops
        character(len=64) :: name
        character(len=msg_len) :: msg
        integer :: u, stat, k
        integer(int64) :: t0, t1, rate
        character(len=*), parameter :: path = 'build/bench_auto_case.nml'
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') text
        close (u)
        call read_case_file(path, cases, stat, msg)
        do k = 1, size(cases)
            if (stat == 0) call apply_case(cases(k), k, state, name, stat, msg)
        end do
        if (stat == 0) call validate_case(state, stat, msg)
        if (stat == 0) kase = build_case(state)
        if (present(state_out)) state_out = kase
        call system_clock(t0, rate)
        if (stat == 0) call solve_case_auto(kase, ops, out, stat, msg)
        call system_clock(t1)
        seconds = real(t1 - t0, dp)/rate
        if (stat /= 0) write (*, '(a)') 'bench-auto: case failed: '//trim(msg)
        call ops%destroy()
    end subroutine solve_text

end program bench_auto
