!> The batch driver `fastcontact CASES.nml [--out DIR]` (doc/user_guide.md) as a library routine,
!! so that tests can run it in-process.
!!
!! Every case in the file is solved in order.  Per good case DIR/<name>.json (summary) and,
!! unless `&output table = .false.`, DIR/<name>.csv (element table) are written, plus a
!! readable report on `report_unit`.  A case with bad input gets a message on `error_unit`
!! naming group, key and value, no outputs (stale files of that name are removed), and the
!! driver continues with the next case.
!!
!! Problems: 'normal' ([[solve_normal]], or FMG with `&solver normal = 'fmg'`) and
!! 'normal+tangential' / 'tangential' (the same: [[solve_contact]], normal then
!! tangential, Panagiotopoulos rounds when K ≠ 0; FMG only when K = 0), through [[fc_auto]].
!! 'strip_mp1' … 'strip_mp3': the 2D no-slip model problems of thesis §3.2.5 solved by
!! [[fc_mg2d]] (`&solver strip`), see [[solve_strip_case]] ([[fc_driver_strip]]).
!! The normal and tangential operators are kept across cases and rebuilt only when the grid
!! or the material changes.
!!
!! Exit code: 0 all cases converged; 1 a case had an input error (or the command line /
!! case file was bad); 2 no input error but a solver did not converge or diverged.
!!
!! `--resume` and `--part K/N` ([[fc_driver_resume]]) skip the cases an earlier run finished
!! with the same input, or keep one of N round-robin parts of the file.
!!
!! Size (~880 lines): the case loop with its three outcomes (error, sweep or sequence,
!! single solve), its `--check` pass (each case's grid and memory, nothing solved), the
!! `--case`, `--part` and `--resume` selection and the summary it fills; what the MPI
!! package's drivers share with it (exit codes, command line, case errors, output files,
!! Hertz reference) lives in [[fc_driver_common]], the strip cases and the sequence tables
!! in [[fc_driver_strip]] and [[fc_sequence_csv]].
module fc_driver
    use, intrinsic :: iso_fortran_env, only: output_unit, int64, error_unit_default => error_unit
    use fc_kinds, only: dp, msg_len, FC_CONVERGED, FC_DIVERGED, FC_ERR_IO, FC_ERR_VALUE, status_name
    use fc_geometry, only: fc_grid
    use fc_influence, only: fc_material
    use fc_contact, only: fc_contact_operators, FC_PROBLEM_ROLLING
    use fc_sequence_csv, only: write_sequence_csv, sweep_header, steps_header
    use fc_driver_strip, only: solve_strip_case, strip_memory_need, check_strip_memory
    use fc_namelist, only: fc_case_chunk, read_case_file
    use fc_input, only: fc_case_input, apply_case, strip_model_index, grid_is_auto
    use fc_input_validate, only: validate_case
    use fc_input_scene, only: build_case, case_notes
    use fc_scene, only: fc_case, case_memory, case_fits_memory, check_case_ic_header
    use fc_strings, only: fmt_int, fmt_real
    use fc_errors, only: FC_ERR_FRICTION_BOUND, FC_ERR_NO_CONTACT, FC_ERR_GEOMETRY, FC_ERR_IO, FC_ERR_ALLOC, FC_ERR_AREA, &
        FC_ERR_GRID, FC_ERR_IC_FILE, FC_ERR_MODEL_RANGE, FC_ERR_FFT_WISDOM
    use fc_output, only: fc_case_summary, write_case_json, write_case_csv, write_case_npy, write_case_report
    use fc_auto, only: fc_auto_outcome, solve_case_auto, case_grid
    use fc_threads, only: set_thread_count
    use fc_memory, only: available_memory, memory_fits, format_bytes, memory_env
    use fc_version, only: fc_build_info
    use fc_driver_common
    use fc_driver_resume, only: case_fingerprints, with_files, case_files, previous_outcome, fingerprint_len
    implicit none
    private

    ! re-exported: the drivers' shared pieces, for callers that know them from here
    public :: EXIT_OK, EXIT_INPUT_ERROR, EXIT_NOT_CONVERGED
    public :: run_driver, driver_usage, make_directory, remove_file, parse_driver_arguments, write_case_error
    public :: case_output_dir, remove_case_outputs, hertz_reference

contains

    !> Usage text of the driver.
    function driver_usage() result(text)
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line('a')
        text = 'usage: fastcontact CASES.nml [--out DIR] [--case NAME[,NAME...]] [--part K/N] [--resume]'//nl// &
            '       fastcontact CASES.nml --check [--case NAME]   (check cases, estimate their memory; solve nothing)'//nl// &
            '       fastcontact --help | --version'//nl//nl// &
            'Solves every case of the namelist file CASES.nml in order: groups &case, &material,'//nl// &
            '&grid, &geometry, &normal, &tangential, &solver, &output; a later case repeats only'//nl// &
            'what changes.  &case problem = normal, normal+tangential, tangential, rolling (steady'//nl// &
            'creep forces; sweeps write DIR/<name>_creep.csv), transient_rolling, hertz, strip_mp1..3.'//nl// &
            '--case solves only the cases of those names (the others are read for what they pass on);'//nl// &
            '--part K/N only cases K, K+N, K+2N, ... (N processes, e.g. a job array, share the file);'//nl// &
            '--resume skips the cases an earlier run finished with the same input (their JSON says so).'//nl// &
            'Writes DIR/<name>.json (summary) and DIR/<name>.csv (one row per element) per case'//nl// &
            "(DIR: --out, else &output dir, else 'out').  Threads: &solver threads or"//nl// &
            'OMP_NUM_THREADS.  See doc/user_guide.md and doc/namelist.md.'//nl//nl// &
            'Exit status: 0 all cases converged, 1 input error in some case, 2 some solver did not converge.'
    end function driver_usage

    !> Usage text of the MPI batch driver, which runs [[run_driver]] on each rank.
    function batch_usage() result(text)
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line('a')
        text = 'usage: mpirun -np P fastcontact-mpi CASES.nml [--out DIR] [--resume]'//nl// &
            '       mpirun -np P fastcontact-mpi CASES.nml --check'//nl// &
            '       mpirun -np P fastcontact-mpi CASES.nml --distributed [--out DIR] [--check] [--resume]'//nl//nl// &
            'Solves the cases of CASES.nml as fastcontact does, spread over the P ranks (each case'//nl// &
            'by one rank, dynamic load balance), with the same outputs, report and exit status.'//nl// &
            '--resume skips the cases an earlier run finished with the same input.  --distributed'//nl// &
            'solves every case by all ranks together (normal problems on very large grids).'//nl// &
            'See doc/parallel.md.'
    end function batch_usage

    !> Run the driver on the command-line arguments `args` (without the program name).
    !! With `only_case` = k (the MPI batch driver): cases before k are read and checked only,
    !! for what case k inherits; cases k … `last_case` (default k) are solved and written, their
    !! statuses (0 converged, 1 input error, 2 solver failure) returned in `statuses`; no
    !! closing summary line.
    subroutine run_driver(args, exit_code, report_unit, error_unit, only_case, last_case, statuses, operators, &
                          memory_share)
        character(len=*), intent(in) :: args(:)
        integer, intent(out) :: exit_code
        integer, intent(in), optional :: report_unit   !! report (default: stdout)
        integer, intent(in), optional :: error_unit    !! error messages (default: stderr)
        integer, intent(in), optional :: only_case     !! first case to solve (1-based)
        integer, intent(in), optional :: last_case     !! last case to solve (with only_case)
        !> per solved case (with only_case); + `STATUS_SKIPPED` ([[fc_driver_common]]) for a case `--resume` skipped
        integer, allocatable, intent(out), optional :: statuses(:)
        !> operators kept by the caller across calls (the MPI batch: one set per rank); a call
        !! reuses them while grid and material match, exactly as consecutive cases of one file do
        type(fc_contact_operators), intent(inout), optional :: operators
        !> processes sharing this machine's available memory (the MPI batch: the ranks on the
        !! node); the memory check gives each its share (default 1)
        integer, intent(in), optional :: memory_share
        integer :: rep, err, k, stat, ncase_err, ncase_fail, share
        character(len=:), allocatable :: case_file, out_dir, action, errtext
        type(fc_case_chunk), allocatable :: cases(:)
        type(fc_case_input) :: state, saved_state
        integer, allocatable :: used_case(:)
        character(len=64), allocatable :: used(:)
        character(len=64) :: name
        character(len=msg_len) :: errmsg
        type(fc_contact_operators) :: ops
        integer :: case_status, nused_before, nskipped, part(2)
        character(len=case_name_len), allocatable :: selected(:), case_names(:)
        character(len=fingerprint_len), allocatable :: fingerprints(:)
        logical, allocatable :: files_fed(:)
        logical :: resume, skipped
        rep = output_unit; err = error_unit_default
        if (present(report_unit)) rep = report_unit
        if (present(error_unit)) err = error_unit
        share = 1
        if (present(memory_share)) share = max(1, memory_share)
        exit_code = EXIT_OK
        ! ---- command line
        part = 0
        if (present(only_case)) then
            ! the MPI batch: its ranks share the cases; --resume skips those done before
            call parse_driver_arguments(args, 'fastcontact-mpi', batch_usage(), case_file, out_dir, action, errtext, &
                                        resume=resume)
        else
            call parse_driver_arguments(args, 'fastcontact', driver_usage(), case_file, out_dir, action, errtext, selected, &
                                        resume, part)
        end if
        select case (action)
        case ('help')
            if (present(only_case)) then
                write (rep, '(a)') batch_usage()
            else
                write (rep, '(a)') driver_usage()
            end if
            return
        case ('version')
            write (rep, '(a)') fc_build_info(); return
        case ('error')
            write (err, '(a)') errtext
            exit_code = EXIT_INPUT_ERROR; return
        end select
        ! ---- read and split the file
        call read_case_file(case_file, cases, stat, errmsg)
        if (stat /= 0) then
            write (err, '(a)') 'fastcontact: '//trim(case_file)//': '//trim(errmsg)
            exit_code = EXIT_INPUT_ERROR; return
        end if
        allocate (used(0), used_case(0))
        ncase_err = 0; ncase_fail = 0; nskipped = 0
        fingerprints = case_fingerprints(cases)
        allocate (files_fed(size(cases)), source=.false.)
        if (allocated(selected)) then
            call check_selection(stat)
            if (stat /= 0) then
                exit_code = EXIT_INPUT_ERROR; return
            end if
        end if
        if (present(statuses) .and. present(only_case)) then
            allocate (statuses(max(0, min(last_solved(), size(cases)) - only_case + 1)))
            statuses = -1
        end if
        if (action == 'check') then
            call check_cases()
            return
        end if
        do k = 1, size(cases)
            if (present(only_case)) then
                if (k > last_solved()) exit
                if (k < only_case) then
                    call inherit_case(k); cycle
                end if
            end if
            if (.not. is_selected(k)) then
                call inherit_case(k); cycle
            end if
            skipped = .false.
            if (resume) skipped = done_before(k, case_status)
            if (skipped) then
                nskipped = nskipped + 1
                call inherit_case(k)
            else
                call run_one_case(k, case_status)
            end if
            if (present(statuses) .and. present(only_case)) &
                statuses(k - only_case + 1) = case_status + merge(STATUS_SKIPPED, 0, skipped)
            select case (case_status)
            case (0)
            case (1); ncase_err = ncase_err + 1
            case default; ncase_fail = ncase_fail + 1
            end select
        end do
        call ops%destroy()
        if (.not. present(only_case)) write (rep, '(a,i0,a,i0,a,i0,a,i0,a)') 'fastcontact: ', &
            nsolved(), ' case(s)'//selection_note()//': ', nsolved() - ncase_err - ncase_fail, ' converged, ', &
            ncase_fail, ' not converged, ', ncase_err, ' with input errors'//skipped_note()
        if (ncase_err > 0) then
            exit_code = EXIT_INPUT_ERROR
        else if (ncase_fail > 0) then
            exit_code = EXIT_NOT_CONVERGED
        end if
    contains

        !> `--check`: every case read, inherited and checked as for a run, and its estimated
        !! peak memory printed against the memory the process may use; nothing is solved or
        !! written.  Exit status 1 when a case has an input error or would not fit.
        subroutine check_cases()
            integer :: nfit, nbig, nerr, status
            nfit = 0; nbig = 0; nerr = 0
            do k = 1, size(cases)
                if (.not. is_selected(k)) then
                    call inherit_case(k); cycle
                end if
                call check_one_case(k, status)
                select case (status)
                case (0); nfit = nfit + 1
                case (1); nerr = nerr + 1
                case default; nbig = nbig + 1
                end select
            end do
            write (rep, '(a,i0,a,i0,a,i0,a,i0,a)') 'fastcontact --check: ', nsolved(), ' case(s)'//selection_note()//': ', nfit, &
                ' to solve, ', nbig, ' too large for the memory, ', nerr, ' with input errors'
            if (nerr + nbig > 0) exit_code = EXIT_INPUT_ERROR
        end subroutine check_cases

        !> Case k of `--check`: status 0 fits (or has no grid to estimate), 1 input error, 2 too
        !! large.
        subroutine check_one_case(k, status)
            integer, intent(in) :: k
            integer, intent(out) :: status
            type(fc_case) :: kase
            integer(int64) :: avail, need
            character(len=:), allocatable :: source, kind, line
            real(dp) :: bpe
            integer :: threads, gnx, gny
            type(fc_auto_outcome) :: no_outcome
            status = 1
            saved_state = state
            call apply_case(cases(k), k, state, name, stat, errmsg)
            if (stat == 0 .and. any(used == state%name)) then
                errmsg = "&case name = '"//trim(state%name)//"': already used in this file (outputs would be overwritten)"
                stat = FC_ERR_VALUE
            end if
            if (stat == 0) call validate_case(state, stat, errmsg)
            if (stat == 0) call available_memory(avail, source, stat, errmsg)
            if (stat /= 0) then
                call write_case_error(rep, err, 'fastcontact', k, cases(k)%line, name, errmsg)
                state = saved_state; return
            end if
            used = [character(len=64) :: used, name]
            used_case = [used_case, k]
            status = 0
            line = ' case '//trim(state%name)//': '
            if (strip_model_index(state) > 0) then
                need = strip_memory_need(state)
                line = line//"strip model problem (solver '"//trim(state%strip)//"'), "//fmt_int(state%nx)//' x 1: about '// &
                    format_bytes(need)
                call against_memory(need, line, status)
            else if (state%problem == 'hertz') then
                line = line//'analytic Hertz solution: no grid'
            else
                kase = build_case(state)
                call check_case_ic_header(kase, stat, errmsg)
                ! the first grid the case is solved on: an automatic area sized, a line
                ! contact as its n x 1 strip
                if (stat == 0) call case_grid(kase, gnx, gny, stat, errmsg)
                if (stat /= 0) then
                    call library_context(stat, errmsg, state, no_outcome)
                    call write_case_error(rep, err, 'fastcontact', k, cases(k)%line, name, errmsg)
                    status = 1; return
                end if
                if (gnx == 0) then
                    write (rep, '(a)') line//'analytic answer (FASTSIM or Hertz): no grid'
                    return
                end if
                call case_memory(kase, gnx, gny, need, kind, bpe, threads)
                line = line//kind//', '//fmt_int(gnx)//' x '//fmt_int(gny)
                if (grid_is_auto(state)) then
                    line = line//' (automatic area)'
                else if (gnx /= kase%nx .or. gny /= kase%ny) then
                    line = line//' (the line contact as a strip)'
                end if
                line = line//', '//fmt_int(threads)//' thread(s): about '//format_bytes(need)
                call against_memory(need, line, status)
                if (kase%target > 0) line = line//'; the accuracy target refines further, as memory allows'
            end if
            write (rep, '(a)') line
        end subroutine check_one_case

        !> `--check`: the estimate `need` [bytes] against the memory available (a run adds what
        !! its process holds then; this pass holds nothing yet), appended to `line`; status 2
        !! when it does not fit.
        subroutine against_memory(need, line, status)
            integer(int64), intent(in) :: need
            character(len=:), allocatable, intent(inout) :: line
            integer, intent(inout) :: status
            integer(int64) :: limit
            logical :: fits
            character(len=:), allocatable :: source
            call memory_fits(need, share, 0_int64, .false., fits, limit, source, stat, errmsg)
            if (limit < 0) then
                line = line//' (the available memory is unknown)'
            else
                line = line//' of '//format_bytes(limit)//' available ('//source//')'
                if (.not. fits) then
                    line = line//': TOO LARGE'; status = 2
                end if
            end if
        end subroutine against_memory

        !> Solve case k; case_status 0 converged, 1 input error, 2 solver failure.
        subroutine run_one_case(k, case_status)
            integer, intent(in) :: k
            integer, intent(out) :: case_status
            character(len=:), allocatable :: dir
            type(fc_material) :: mat
            type(fc_case_summary) :: s
            integer(int64) :: t0, t1, t2, rate
            integer :: j, final_status
            logical :: tang
            type(fc_case) :: kase
            call system_clock(t0, rate)
            case_status = 1
            nused_before = size(used)
            saved_state = state
            call apply_case(cases(k), k, state, name, stat, errmsg)
            dir = output_dir()
            if (stat /= 0) then
                call case_error(); return
            end if
            do j = 1, size(used)
                if (used(j) == state%name) then
                    write (errmsg, '(a,i0,a)') "&case name = '"//trim(state%name)//"': already used by case ", &
                        used_case(j), ' in this file (outputs would be overwritten)'
                    call case_error(clean=.false.); return
                end if
            end do
            used = [character(len=64) :: used, name]
            used_case = [used_case, k]
            call validate_case(state, stat, errmsg)
            if (stat /= 0) then
                call case_error(); return
            end if
            ! the case's values are valid: rejected later (its output directory, a coefficient
            ! file, the memory, a load that only the solve finds impossible) it still passes
            ! them on, as when it is only read for what it passes on (--case) and in the MPI batch
            saved_state = state
            if (index(dir, "'") > 0) then
                errmsg = "&output dir = '"//dir//"': quotes are not allowed in the directory name"
                call case_error(clean=.false.); return
            end if
            call make_directory(dir, stat)
            if (stat /= 0) then
                errmsg = "&output dir = '"//dir//"': cannot create the directory"
                call case_error(clean=.false.); return
            end if
            ! ---- strip model problems: their own solvers and outputs
            kase = build_case(state)
            if (strip_model_index(state) > 0) then
                call check_strip_memory(state, share, stat, errmsg)
                if (stat /= 0) then
                    call case_error(); return
                end if
                call run_strip_case(dir, kase, t0, rate, case_status)
                return
            end if
            ! ---- memory: a given grid beyond what this process may use is an input error now,
            !      not a process killed by the operating system while it builds the operators
            kase%memory_share = share
            if (.not. grid_is_auto(state)) then
                ! a coefficient file for other cells, or too short a reach, before its load
                call check_case_ic_header(kase, stat, errmsg)
                if (stat /= 0) then
                    call library_context(stat, errmsg, state, s%outcome)
                    call case_error(); return
                end if
                call check_case_memory(kase, stat, errmsg)
                if (stat /= 0) then
                    call case_error(); return
                end if
            end if
            ! ---- solve: model choice, potential area, accuracy target (fc_auto); operators reused;
            !      the outcome goes straight into the summary
            call system_clock(t1)
            if (present(operators)) then
                call solve_and_count(operators, kase, s)
            else
                call solve_and_count(ops, kase, s)
            end if
            call system_clock(t2)
            if (stat /= 0) then
                call library_context(stat, errmsg, state, s%outcome)
                call case_error(); return
            end if
            tang = s%outcome%tangential
            mat = s%outcome%material
            ! ---- summary
            s%name = state%name; s%title = state%title; s%problem = state%problem; s%geometry = state%kind
            s%input_fingerprint = case_fingerprint(k, state)
            s%force_prescribed = state%force_prescribed
            s%tol = kase%settings%normal%tol
            if (s%outcome%tol > 0) s%tol = s%outcome%tol
            s%notes = state%notes//case_notes(state)
            if (s%outcome%analytic) then
                call analytic_summary(s, state)
                final_status = FC_CONVERGED
                call remove_file(dir//'/'//trim(state%name)//'.csv')
                call system_clock(t2)
                s%cpu_seconds = real(t2 - t0, dp)/rate
                call write_case_json(dir//'/'//trim(state%name)//'.json', s, stat, errmsg)
                if (stat /= 0) then
                    call case_error(); return
                end if
                call write_case_report(rep, s, reshape([0.0_dp], [0, 0]))
                case_status = 0
                return
            end if
            associate (res => s%outcome%result%normal, grid => s%outcome%grid)
                s%setup_seconds = s%outcome%result%setup_seconds_normal
                s%setup_seconds_tangential = s%outcome%result%setup_seconds_tangential
                s%status = status_name(res%status); s%message = res%message
                s%solver = kase%settings%normal%solver; s%solver_normal = kase%settings%normal%solver
                s%fft_preconditioner = kase%settings%normal%prec_form
                s%status_normal = status_name(res%status)
                s%fn = res%fn; s%approach = res%approach; s%pmax = res%pmax
                s%ncon = res%ncon; s%nadh = res%ncon; s%nslip = 0
                s%iterations = res%iterations; s%outer_iterations = res%outer_iterations; s%matvecs = res%matvecs
                s%iterations_normal = res%iterations; s%outer_iterations_normal = res%outer_iterations
                if (kase%settings%normal%solver == 'fmg') then
                    s%work_units = s%outcome%result%work_units
                    s%convergence_factor = s%outcome%result%convergence_factor
                    s%cycle = state%cycle
                end if
                s%matvecs_normal = res%matvecs; s%residual_normal = res%residual
                s%residual = res%residual
                s%cpu_seconds_normal = s%setup_seconds + res%cpu_seconds
                if (size(s%outcome%levels) > 1) s%cpu_seconds_normal = real(t2 - t1, dp)/rate
                final_status = res%status
                if (tang) call tangential_summary(s, state, kase, final_status)
            end associate
            if (mat%k /= 0 .and. .not. tang) s%notes = s%notes//'K = '//fmt_real(mat%k)// &
                ' /= 0: the normal problem is solved without the tangential coupling. '
            call hertz_reference(s, state, mat)
            ! ---- outputs
            if (state%table) then
                stat = 0
                associate (res => s%outcome%result%normal, tres => s%outcome%result%tangential)
                    if (state%table_format /= 'npy' .and. tang) then
                        call write_case_csv(dir//'/'//trim(state%name)//'.csv', s%outcome%grid, res%pn, res%gap, stat, &
                            errmsg, tres%state, tres%px, tres%py, tres%sx, tres%sy)
                    else if (state%table_format /= 'npy') then
                        call write_case_csv(dir//'/'//trim(state%name)//'.csv', s%outcome%grid, res%pn, res%gap, stat, &
                            errmsg)
                    end if
                    if (stat == 0 .and. state%table_format /= 'csv' .and. tang) then
                        call write_case_npy(dir//'/'//trim(state%name)//'.npy', s%outcome%grid, res%pn, res%gap, stat, &
                            errmsg, tres%state, tres%px, tres%py, tres%sx, tres%sy)
                    else if (stat == 0 .and. state%table_format /= 'csv') then
                        call write_case_npy(dir//'/'//trim(state%name)//'.npy', s%outcome%grid, res%pn, res%gap, stat, &
                            errmsg)
                    end if
                end associate
                if (stat /= 0) then
                    call case_error(); return
                end if
            else
                call remove_file(dir//'/'//trim(state%name)//'.csv')
            end if
            if (allocated(s%outcome%sequence)) then
                ! rolling: creep-force curve or transient steps, one row each
                if (state%problem == 'transient_rolling') then
                    call write_sequence_csv(dir//'/'//trim(state%name)//'_steps.csv', steps_header, s%outcome%sequence, &
                                            stat, errmsg)
                else
                    call write_sequence_csv(dir//'/'//trim(state%name)//'_creep.csv', sweep_header, s%outcome%sequence, &
                                            stat, errmsg)
                end if
                if (stat /= 0) then
                    call case_error(); return
                end if
            end if
            call system_clock(t2)
            s%cpu_seconds = real(t2 - t0, dp)/rate
            call write_case_json(dir//'/'//trim(state%name)//'.json', s, stat, errmsg)
            if (stat /= 0) then
                call remove_file(dir//'/'//trim(state%name)//'.csv')
                call case_error(); return
            end if
            if (tang) then
                call write_case_report(rep, s, s%outcome%result%normal%pn, s%outcome%result%tangential%state)
            else
                call write_case_report(rep, s, s%outcome%result%normal%pn)
            end if
            if (final_status == FC_CONVERGED) then
                case_status = 0
            else
                case_status = 2
                write (err, '(a,i0,a)') 'fastcontact: case ', k, " '"//trim(state%name)//"': solver "// &
                    trim(status_name(final_status))//': '//trim(s%message)
            end if

        end subroutine run_one_case

        !> Solve `kase` on `o` into `s`, noting whether the case built the operators or
        !! reused those of an earlier case.
        subroutine solve_and_count(o, kase, s)
            type(fc_contact_operators), intent(inout) :: o
            type(fc_case), intent(in) :: kase
            type(fc_case_summary), intent(inout) :: s
            integer :: bn, bt
            bn = o%builds_normal; bt = o%builds_tangential
            call solve_case_auto(kase, o, s%outcome, stat, errmsg)
            s%operator_built = o%builds_normal > bn
            s%operator_built_tangential = o%builds_tangential > bt
        end subroutine solve_and_count

        !> Solve a strip model problem case and write its outputs (sets case_status).
        subroutine run_strip_case(dir, kase, t0, rate, case_status)
            character(len=*), intent(in) :: dir
            type(fc_case), intent(in) :: kase
            integer(int64), intent(in) :: t0, rate
            integer, intent(out) :: case_status
            type(fc_case_summary) :: s
            integer(int64) :: t2
            integer :: final_status
            type(fc_grid) :: sgrid
            real(dp), allocatable :: px(:, :), zero(:, :)
            integer, allocatable :: el(:, :)
            case_status = 1
            call set_thread_count(kase%threads)    ! before the strip levels' FFT plans are made
            call solve_strip_case(state, kase, s, sgrid, px, el, final_status, stat, errmsg)
            if (stat /= 0) then
                call case_error(); return
            end if
            allocate (zero(sgrid%nx, 1))
            zero = 0
            if (state%table .and. final_status /= FC_DIVERGED) then
                stat = 0
                if (state%table_format /= 'npy') call write_case_csv(dir//'/'//trim(state%name)//'.csv', sgrid, zero, &
                    zero, stat, errmsg, el, px, zero, zero, zero)
                if (stat == 0 .and. state%table_format /= 'csv') call write_case_npy(dir//'/'//trim(state%name)// &
                    '.npy', sgrid, zero, zero, stat, errmsg, el, px, zero, zero, zero)
                if (stat /= 0) then
                    call case_error(); return
                end if
            else
                call remove_file(dir//'/'//trim(state%name)//'.csv')
            end if
            call system_clock(t2)
            s%cpu_seconds = real(t2 - t0, dp)/rate
            s%input_fingerprint = case_fingerprint(k, state)
            call write_case_json(dir//'/'//trim(state%name)//'.json', s, stat, errmsg)
            if (stat /= 0) then
                call remove_file(dir//'/'//trim(state%name)//'.csv')
                call case_error(); return
            end if
            call write_case_report(rep, s, zero, el)
            if (final_status == FC_CONVERGED) then
                case_status = 0
            else
                case_status = 2
                write (err, '(a,i0,a)') 'fastcontact: case ', k, " '"//trim(state%name)//"': solver "// &
                    trim(status_name(final_status))//': '//trim(s%message)
            end if
        end subroutine run_strip_case

        !> Last case to solve with `only_case`.
        integer function last_solved()
            last_solved = only_case
            if (present(last_case)) last_solved = max(only_case, last_case)
        end function last_solved

        !> `--case`: every name given must name a case of the file (checked before anything is
        !! solved); stat ≠ 0 with the message written otherwise.
        subroutine check_selection(stat)
            integer, intent(out) :: stat
            integer :: j
            character(len=:), allocatable :: known
            stat = 0
            allocate (case_names(size(cases)))
            do j = 1, size(cases)
                case_names(j) = chunk_case_name(j)
            end do
            do j = 1, size(selected)
                if (any(case_names == selected(j))) cycle
                known = ''
                do k = 1, min(size(cases), 20)
                    known = known//merge(', ', '  ', k > 1)//trim(case_names(k))
                end do
                if (size(cases) > 20) known = known//', …'
                write (err, '(a)') "fastcontact: --case '"//trim(selected(j))//"': no case of that name in "// &
                    case_file//' (its cases: '//known(3:)//')'
                stat = FC_ERR_VALUE; return
            end do
        end subroutine check_selection

        !> The name case k gets (`&case name`, else case<k>); names are not inherited, so the
        !! case's own groups decide it.
        function chunk_case_name(k) result(nm)
            integer, intent(in) :: k
            character(len=case_name_len) :: nm
            type(fc_case_input) :: scratch
            call apply_case(cases(k), k, scratch, nm, stat, errmsg)
        end function chunk_case_name

        !> Whether case k is to be solved: every case without `--case`.
        logical function is_selected(k)
            integer, intent(in) :: k
            is_selected = .true.
            if (allocated(selected)) is_selected = any(selected == case_names(k))
            if (part(2) > 0) is_selected = is_selected .and. mod(k - 1, part(2)) == part(1) - 1
        end function is_selected

        !> Cases solved (or checked) in this run.
        integer function nsolved()
            integer :: j
            nsolved = size(cases)
            if (allocated(selected) .or. part(2) > 0) nsolved = count([(is_selected(j), j = 1, size(cases))])
        end function nsolved

        !> Prefix of the closing summary line when `--case` chose the cases.
        function selection_note() result(note)
            character(len=:), allocatable :: note
            note = ''
            if (allocated(selected)) note = ' chosen by --case'
            if (part(2) > 0) note = note//' of part '//fmt_int(part(1))//'/'//fmt_int(part(2))
        end function selection_note

        !> End of the closing summary line with `--resume`: how many were done before.
        function skipped_note() result(note)
            character(len=:), allocatable :: note
            note = ''
            if (resume) note = ' ('//fmt_int(nskipped)//' of them done in an earlier run: skipped)'
        end function skipped_note

        !> Case k's input fingerprint with the contents of the files it reads (`st`: its
        !! values applied), hashed once per case.
        function case_fingerprint(k, st) result(fp)
            integer, intent(in) :: k
            type(fc_case_input), intent(in) :: st
            character(len=fingerprint_len) :: fp
            if (.not. files_fed(k)) then
                fingerprints(k) = with_files(fingerprints(k), case_files(st))
                files_fed(k) = .true.
            end if
            fp = fingerprints(k)
        end function case_fingerprint

        !> `--resume`: case k was finished by an earlier run with the same inputs (its JSON has
        !! its input fingerprint and a final status, [[previous_outcome]]); `case_status` from
        !! that status, and the report says so.
        logical function done_before(k, case_status) result(done)
            integer, intent(in) :: k
            integer, intent(out) :: case_status
            type(fc_case_input) :: scratch
            character(len=case_name_len) :: nm
            character(len=:), allocatable :: what
            integer :: st
            character(len=msg_len) :: msg
            done = .false.; case_status = 0
            scratch = state
            call apply_case(cases(k), k, scratch, nm, st, msg)
            if (st /= 0) return
            if (any(used == scratch%name)) return
            done = previous_outcome(case_output_dir(scratch, out_dir)//'/'//trim(scratch%name)//'.json', &
                                    case_fingerprint(k, scratch), case_status, what)
            if (done) write (rep, '(a)') ' case '//trim(scratch%name)//': done in an earlier run with the same input ('// &
                what//'), skipped (--resume)'//new_line('a')
        end function done_before

        !> Apply and check case k without solving or writing: the state later cases inherit
        !! (as `run_one_case` leaves it, except after an error found only while solving).
        subroutine inherit_case(k)
            integer, intent(in) :: k
            saved_state = state
            call apply_case(cases(k), k, state, name, stat, errmsg)
            if (stat /= 0 .or. any(used == state%name)) then
                state = saved_state; return
            end if
            used = [character(len=64) :: used, name]
            used_case = [used_case, k]
            call validate_case(state, stat, errmsg)
            if (stat /= 0) state = saved_state
        end subroutine inherit_case

        !> Report an input error of the current case and remove stale outputs.
        subroutine case_error(clean)
            logical, intent(in), optional :: clean
            logical :: do_clean
            do_clean = .true.
            if (present(clean)) do_clean = clean
            call write_case_error(rep, err, 'fastcontact', k, cases(k)%line, name, errmsg)
            ! never remove the outputs of an earlier case of the same name
            if (do_clean .and. .not. any(used(1:nused_before) == name)) call remove_case_outputs(output_dir(), name)
            ! the next case inherits from the last case without input errors
            state = saved_state
        end subroutine case_error

        function output_dir() result(d)
            character(len=:), allocatable :: d
            d = case_output_dir(state, out_dir)
        end function output_dir
    end subroutine run_driver

    !> stat = FC_ERR_ALLOC with a message naming `&grid nx, ny` when the estimated peak memory
    !! of `kase` exceeds the memory this process may use ([[case_fits_memory]]: its share of
    !! the available memory, plus what it holds already); nothing is checked when the
    !! available memory is unknown.  stat = FC_ERR_VALUE for an invalid
    !! `FASTCONTACT_AVAILABLE_MEMORY`.
    subroutine check_case_memory(kase, stat, errmsg)
        type(fc_case), intent(in) :: kase
        integer, intent(out) :: stat
        character(len=msg_len), intent(out) :: errmsg
        character(len=:), allocatable :: what
        logical :: fits
        integer :: gnx, gny
        ! the grid the case is solved on (a line contact as its strip); a case the planning
        ! refuses is reported by the solve
        call case_grid(kase, gnx, gny, stat, errmsg)
        if (stat /= 0 .or. gnx == 0) then
            stat = 0; errmsg = ''; return
        end if
        call case_fits_memory(kase, gnx, gny, fits, what, stat, errmsg)
        if (stat /= 0 .or. fits) return
        stat = FC_ERR_ALLOC
        if (len_trim(kase%ic_file) > 0) then
            ! the coefficient sets count too: name the file and how far it reaches
            errmsg = "&material ic_file = '"//trim(kase%ic_file)//"' (offsets to "//fmt_int(kase%ic_header%mx)//' x '// &
                fmt_int(kase%ic_header%my)//'), &grid nx = '//fmt_int(kase%nx)//', ny = '//fmt_int(kase%ny)//': '// &
                what//'; use a smaller grid, a file that reaches no farther than the grid needs (nx-1, ny-1), or '// &
                'more memory, or set '//memory_env//' to override'
        else
            errmsg = '&grid nx = '//fmt_int(kase%nx)//', ny = '//fmt_int(kase%ny)//': '//what// &
                '; use a smaller grid or more memory, or set '//memory_env//' to override'
        end if
    end subroutine check_case_memory

    !> Summary of an analytic (problem = 'hertz') case: no grid, Hertz values as results.
    subroutine analytic_summary(s, state)
        type(fc_case_summary), intent(inout) :: s
        type(fc_case_input), intent(in) :: state
        s%status = 'converged'; s%message = 'analytic Hertz solution'
        s%solver = 'hertz'; s%solver_normal = 'hertz'; s%status_normal = 'converged'
        s%has_hertz = .true.; s%hertz = s%outcome%hertz
        s%fn = s%outcome%hertz%fn; s%approach = s%outcome%hertz%approach; s%pmax = s%outcome%hertz%p0
        s%residual = 0
        if (s%outcome%model == 'fastsim') then
            s%message = "elliptic Hertz and FASTSIM (Kalker's simplified theory)"
            s%solver = 'hertz+fastsim'; s%tangential = .true.; s%tangential_run = .true.
            s%solver_tangential = 'fastsim'; s%status_tangential = 'converged'
            s%fx = s%outcome%fx; s%fy = s%outcome%fy; s%mz = s%outcome%mz; s%mu = state%mu
            s%xi = state%xi; s%eta = state%eta; s%phi = state%phi
            ! steady rolling dissipates the creepages' work (doc/rolling.md, "Frictional dissipation")
            s%dissipation = -(s%fx*s%xi + s%fy*s%eta + s%mz*s%phi)
        end if
        if (s%outcome%has_cattaneo) then
            s%fx = s%outcome%fx; s%fy = s%outcome%fy
            s%mu = state%mu
            s%dissipation = s%outcome%cattaneo%dissipation
            ! the shift opposes the force (tractions act on body 1 and oppose its slip)
            s%xi = -s%outcome%cattaneo%shift*s%outcome%fx/max(hypot(s%outcome%fx, s%outcome%fy), tiny(1.0_dp))
            s%eta = -s%outcome%cattaneo%shift*s%outcome%fy/max(hypot(s%outcome%fx, s%outcome%fy), tiny(1.0_dp))
        end if
    end subroutine analytic_summary

    !> Tangential part of the summary; status = worst of both stages.  When the normal
    !! stage failed the tangential stage was not run: zero tractions, states from the
    !! pressure (adhesion where pn > 0), status of the normal stage.
    subroutine tangential_summary(s, state, kase, final_status)
        type(fc_case_summary), intent(inout) :: s
        type(fc_case_input), intent(in) :: state
        type(fc_case), intent(in) :: kase
        integer, intent(inout) :: final_status
        associate (res => s%outcome%result%normal, tres => s%outcome%result%tangential)
            s%tangential = .true.
            s%solver_tangential = kase%settings%tangential%solver
            if (kase%problem == FC_PROBLEM_ROLLING) s%solver_tangential = kase%settings%rolling%solver
            s%solver = trim(kase%settings%normal%solver)//'+'//trim(s%solver_tangential)
            s%mu = state%mu; s%tforce_prescribed = state%tforce_prescribed
            s%fx_prescribed = state%fx; s%fy_prescribed = state%fy
            s%panagiotopoulos_rounds = s%outcome%result%rounds
            s%cpu_seconds_normal = s%setup_seconds + res%cpu_seconds
            s%tangential_run = s%outcome%result%tangential_run
            if (.not. s%tangential_run) then
                ! (the orchestrator's result has zero tractions and adhesion where pn > 0)
                s%status_tangential = 'not_run'
                s%message = trim(res%message)//' (tangential stage not run)'
                s%xi = state%xi; s%eta = state%eta; s%phi = state%phi
                s%cpu_seconds_tangential = s%setup_seconds_tangential
                return
            end if
            s%status_tangential = status_name(tres%status)
            s%fx = tres%fx; s%fy = tres%fy; s%mz = tres%mz; s%dissipation = tres%dissipation
            s%xi = tres%xi; s%eta = tres%eta; s%phi = tres%phi
            s%nadh = tres%nadh; s%nslip = tres%nslip
            s%iterations_tangential = tres%iterations; s%outer_iterations_tangential = tres%outer_iterations
            s%matvecs_tangential = tres%matvecs; s%residual_tangential = tres%residual
            s%iterations = res%iterations + tres%iterations
            s%outer_iterations = res%outer_iterations + tres%outer_iterations
            s%matvecs = res%matvecs + tres%matvecs
            s%residual = max(res%residual, tres%residual)
            s%cpu_seconds_tangential = s%setup_seconds_tangential + tres%cpu_seconds
            final_status = max(res%status, tres%status)
            s%status = status_name(final_status)
            if (tres%status /= FC_CONVERGED) then
                if (res%status == FC_CONVERGED) then
                    s%message = 'tangential: '//trim(tres%message)
                else
                    s%message = 'normal: '//trim(res%message)//'; tangential: '//trim(tres%message)
                end if
            end if
        end associate
    end subroutine tangential_summary

    !> Name the namelist group, keys and values of a library error that the input checks
    !! cannot foresee (it depends on the grid or the solution), chosen by the error code.
    subroutine library_context(stat, errmsg, state, auto)
        integer, intent(in) :: stat
        character(len=*), intent(inout) :: errmsg
        type(fc_case_input), intent(in) :: state
        type(fc_auto_outcome), intent(in) :: auto   !! (grid of the failed solve)
        select case (stat)
        case (FC_ERR_FRICTION_BOUND)
            errmsg = '&tangential fx = '//fmt_real(state%fx)//', fy = '//fmt_real(state%fy)//', mu = '// &
                fmt_real(state%mu)//': '//trim(errmsg)//' for &normal approach = '//fmt_real(state%approach)
        case (FC_ERR_NO_CONTACT)
            errmsg = '&normal '//trim(errmsg)
        case (FC_ERR_GEOMETRY, FC_ERR_IO)
            errmsg = '&geometry '//trim(errmsg)
        case (FC_ERR_ALLOC)
            if (grid_is_auto(state)) then
                errmsg = '&grid auto = .true., n_across = '//fmt_int(state%n_across)//', margin = '// &
                    fmt_real(state%margin)//': '//trim(errmsg)//'; use fewer elements across the contact (n_across), '// &
                    'or set '//memory_env//' to override'
            else
                errmsg = '&grid '//trim(errmsg)
            end if
        case (FC_ERR_IC_FILE)
            if (len_trim(state%ic_file2) > 0) then
                errmsg = "&material ic_file = '"//trim(state%ic_file)//"', ic_file2 = '"//trim(state%ic_file2)// &
                    "': "//trim(errmsg)
            else
                errmsg = "&material ic_file = '"//trim(state%ic_file)//"': "//trim(errmsg)
            end if
        case (FC_ERR_FFT_WISDOM)
            errmsg = "&solver fft_wisdom = '"//trim(state%fft_wisdom)//"': "//trim(errmsg)
        case (FC_ERR_MODEL_RANGE)
            errmsg = "&solver model = '"//trim(state%model)//"' with &geometry rx = "//fmt_real(state%rx)//', ry = '// &
                fmt_real(state%ry)//': '//trim(errmsg)
        case (FC_ERR_GRID)
            errmsg = '&grid nx = '//fmt_int(auto%grid%nx)//', ny = '//fmt_int(auto%grid%ny)// &
                " with &solver normal = '"//trim(state%normal_solver)//"': "//trim(errmsg)//"; or use normal = 'bccg'"
        case (FC_ERR_AREA)
            ! a potential contact area the library rejects: name what it was made from
            if (grid_is_auto(state) .or. state%problem == 'hertz') then
                errmsg = '&grid (automatic, sized from &normal '//trim(merge('fn      ', 'approach', &
                    state%force_prescribed))//' = '//fmt_real(merge(state%fn, state%approach, state%force_prescribed))// &
                    ', &geometry rx = '//fmt_real(state%rx)//', ry = '//fmt_real(state%ry)//'): '//trim(errmsg)
            else
                errmsg = '&grid nx = '//fmt_int(state%nx)//', ny = '//fmt_int(state%ny)//': '//trim(errmsg)
            end if
        end select
    end subroutine library_context

end module fc_driver
