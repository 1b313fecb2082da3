!> Distributed driver `fastcontact-mpi CASES.nml --distributed [--out DIR]`: every case of
!! the file is solved by all ranks together, for grids too large for one machine's memory.
!!
!! The cases are read, inherited and checked exactly as by the serial driver ([[run_driver]]:
!! [[apply_case]], [[validate_case]], [[build_case]]).  Each rank then holds a slab of rows of
!! the grid (the layout of [[fcm_bttb]]): it generates the undeformed distance of its rows
!! itself ([[fcm_geometry]]), and the normal problem is solved by the distributed BCCG
!! ([[solve_dist_normal]]).  No rank ever holds a whole-grid array.
!!
!! Outputs, in the serial driver's formats: `DIR/<name>.json` (rank 0; the serial keys, with
!! `"model": "distributed"` and the rank count in the notes), the element table
!! `DIR/<name>.csv` and/or `.npy` (`&output table_format`; written by the ranks in turn, each
!! appending its rows: byte for byte the table a single process would write of the same
!! pressures), and the case report without the contact map (rank 0).  The exit status
!! follows the serial rules.
!!
!! What a distributed case may ask for: `problem = 'normal'`, `&solver normal = 'bccg'`
!! (without deflation), a given grid of up to 32768² elements (the serial driver's limit is
!! 4096²) (no automatic area, no accuracy target), the half-space
!! (no influence-coefficient files), geometries generated row by row (`quadratic`,
!! `cylinder`, `punch_rough`, `wavy`), periodic or not, prescribed approach or force.
!! Anything else is an input error naming the group, key and value.  Model
!! reductions are not applied: the case is solved on its grid as given.  The distributed
!! BCCG applies its FFT preconditioner in the Toeplitz form (`fft_preconditioner =
!! 'toeplitz'`), whatever the key says; the answers agree within `tol`.  With `&solver
!! fft_wisdom = 'FILE'` the product's plans are measured (FFTW_MEASURE: 1D transforms and
!! the transposes, 0.83–0.92 of the estimated plans' solve time at 1024²–2048² on 2 ranks),
!! from the file's wisdom where it has them: rank 0 reads the file and broadcasts it, and
!! after the build the ranks' wisdom is gathered and written back.
!!
!! The operator is kept while grid, material and periodicity stay the same, as the serial
!! driver keeps its operators across consecutive cases.
module fcm_dist_driver
    use mpi
    use, intrinsic :: iso_fortran_env, only: output_unit, int64, error_unit_default => error_unit
    use fc_kinds, only: dp, msg_len, FC_CONVERGED, status_name
    use fc_strings, only: fmt_int, fmt_real
    use fc_geometry, only: fc_grid, make_grid, h_no_contact
    use fc_influence, only: fc_material, combine_material
    use fc_namelist, only: fc_case_chunk, read_case_file
    use fc_input, only: fc_case_input, apply_case, grid_is_auto, max_dist_grid_elements
    use fc_input_validate, only: validate_case
    use fc_input_scene, only: build_case, case_notes
    use fc_scene, only: fc_case
    use fc_output, only: fc_case_summary, write_case_json, write_case_report
    use fc_table_io, only: write_element_table_csv, write_element_table_npy
    use fc_driver_common, only: EXIT_OK, EXIT_INPUT_ERROR, EXIT_NOT_CONVERGED, make_directory, remove_file, &
        parse_driver_arguments, write_case_error, case_output_dir, remove_case_outputs, hertz_reference
    use fc_version, only: fc_build_info
    use fc_driver_resume, only: case_fingerprints, with_files, case_files, previous_outcome, fingerprint_len
    use fc_strings, only: fmt_int
    use fc_threads, only: set_thread_count
    use fcm_norm, only: fcm_normal_operator, build_dist_normal_operator, solve_dist_normal, dist_memory_per_rank
    use fc_memory, only: available_memory, process_resident_bytes, format_bytes, memory_env
    use fc_errors, only: FC_ERR_ALLOC, FC_ERR_FFT_WISDOM, FC_ERR_NO_CONTACT, FC_ERR_VALUE, FC_ERR_UNSUPPORTED
    use fc_fft_effort, only: read_wisdom, write_wisdom, wisdom_temp_name
    use fcm_fftw_mpi, only: fftw_mpi_broadcast_wisdom, fftw_mpi_gather_wisdom
    use fcm_geometry, only: quadratic_gap_rows, wavy_gap_rows, punch_rough_gap_rows
    use fc_norm, only: fc_normal_result
    implicit none
    private

    public :: run_dist_driver, dist_case_unsupported

contains

    !> Solve every case of the file given in `args` on all ranks of `comm` (collective).
    !! `args` as for the serial driver (CASES.nml, --out DIR, --help); `exit_code` is the same
    !! on every rank.  Report and error messages are written by rank 0 to `report_unit`
    !! (default stdout) and `err_unit` (default stderr).
    subroutine run_dist_driver(args, comm, exit_code, report_unit, err_unit)
        character(len=*), intent(in) :: args(:)
        integer, intent(in) :: comm
        integer, intent(out) :: exit_code
        integer, intent(in), optional :: report_unit, err_unit
        integer :: rep, err, rank, nprocs, ierr, k, stat, ncase_err, ncase_fail, case_status, nskipped
        logical :: resume   !! --resume: skip the cases an earlier run finished with the same input
        character(len=fingerprint_len), allocatable :: fingerprints(:)
        character(len=:), allocatable :: case_file, out_dir, action, errtext
        type(fc_case_chunk), allocatable :: cases(:)
        type(fc_case_input) :: state, saved_state
        character(len=64), allocatable :: used(:)
        character(len=64) :: name
        character(len=msg_len) :: errmsg
        type(fcm_normal_operator) :: dop
        logical :: built
        type(fc_grid) :: built_grid
        type(fc_material) :: built_mat
        logical :: built_periodic, built_measured
        logical :: check_only   !! --check: check every case and estimate its memory per rank; solve nothing
        rep = output_unit; err = error_unit_default
        if (present(report_unit)) rep = report_unit
        if (present(err_unit)) err = err_unit
        call mpi_comm_rank(comm, rank, ierr)
        call mpi_comm_size(comm, nprocs, ierr)
        exit_code = EXIT_OK
        built = .false.; built_periodic = .false.; built_measured = .false.
        ! ---- command line (the same on every rank)
        call parse_driver_arguments(args, 'fastcontact-mpi', dist_usage(), case_file, out_dir, action, errtext, &
                                    resume=resume)
        select case (action)
        case ('help')
            if (rank == 0) write (rep, '(a)') dist_usage()
            return
        case ('version')
            if (rank == 0) write (rep, '(a)') fc_build_info()
            return
        case ('error')
            if (rank == 0) write (err, '(a)') errtext
            exit_code = EXIT_INPUT_ERROR; return
        end select
        check_only = action == 'check'
        call read_case_file(case_file, cases, stat, errmsg)
        if (stat /= 0) then
            if (rank == 0) write (err, '(a)') 'fastcontact-mpi: '//trim(case_file)//': '//trim(errmsg)
            exit_code = EXIT_INPUT_ERROR; return
        end if
        allocate (used(0))
        ncase_err = 0; ncase_fail = 0; nskipped = 0
        fingerprints = case_fingerprints(cases)
        do k = 1, size(cases)
            call run_one(k, case_status)
            select case (case_status)
            case (0)
            case (1); ncase_err = ncase_err + 1
            case default; ncase_fail = ncase_fail + 1
            end select
        end do
        if (rank == 0 .and. check_only) then
            write (rep, '(a,i0,a,i0,a,i0,a,i0,a)') 'fastcontact-mpi --distributed --check: ', size(cases), &
                ' case(s) on ', nprocs, ' ranks: ', size(cases) - ncase_err, ' to solve, ', ncase_err, &
                ' with input errors or too large for the memory'
        else if (rank == 0) then
            write (rep, '(a,i0,a,i0,a,i0,a,i0,a,i0,a)') 'fastcontact-mpi: ', size(cases), &
                ' case(s) on ', nprocs, ' ranks: ', size(cases) - ncase_err - ncase_fail, ' converged, ', ncase_fail, &
                ' not converged, ', ncase_err, ' with input errors'//skipped_note()
        end if
        if (ncase_err > 0) then
            exit_code = EXIT_INPUT_ERROR
        else if (ncase_fail > 0) then
            exit_code = EXIT_NOT_CONVERGED
        end if
    contains

        !> Case k on all ranks; case_status 0 converged, 1 input error, 2 solver failure.
        subroutine run_one(k, case_status)
            integer, intent(in) :: k
            integer, intent(out) :: case_status
            character(len=:), allocatable :: dir
            type(fc_case) :: kase
            type(fc_material) :: mat
            type(fc_grid) :: grid
            type(fc_normal_result) :: res
            type(fc_case_summary) :: s
            real(dp), allocatable :: h0(:, :)
            real(dp) :: t0
            integer :: j0, j1, nyl, nbefore
            logical :: reuse, can_touch, wisdom
            t0 = mpi_wtime()
            case_status = 1
            saved_state = state
            nbefore = size(used)
            call apply_case(cases(k), k, state, name, stat, errmsg)
            dir = output_dir()
            if (stat /= 0) then
                call case_error(nbefore); return
            end if
            if (any(used == state%name)) then
                errmsg = "&case name = '"//trim(state%name)//"': already used in this file (outputs would be overwritten)"
                call case_error(nbefore, clean=.false.); return
            end if
            used = [character(len=64) :: used, name]
            call validate_case(state, stat, errmsg, grid_limit=max_dist_grid_elements)   ! grids beyond one machine
            if (stat /= 0) then
                call case_error(nbefore); return
            end if
            kase = build_case(state)
            errmsg = dist_case_unsupported(state, kase)
            if (len_trim(errmsg) > 0) then
                call case_error(nbefore); return
            end if
            if (resume .and. .not. check_only) then
                if (done_before(k, dir, case_status)) return
            end if
            if (check_only) then
                call check_dist_memory(kase, stat, errmsg, report=.true.)
                if (stat /= 0) then
                    call case_error(nbefore, clean=.false.); return
                end if
                case_status = 0
                return
            end if
            call make_directory(dir, stat)
            if (stat /= 0) then
                errmsg = "&output dir = '"//dir//"': cannot create the directory"
                call case_error(nbefore, clean=.false.); return
            end if
            if (kase%threads > 0) call set_thread_count(kase%threads)
            ! ---- operator: built on all ranks, kept while grid, material and periodicity match
            mat = kase%material
            call combine_material(mat, stat, errmsg)
            if (stat == 0) call make_grid(grid, kase%nx, kase%ny, kase%xmin, kase%xmax, kase%ymin, kase%ymax, stat, errmsg)
            if (stat /= 0) then
                errmsg = '&grid nx = '//fmt_int(kase%nx)//', ny = '//fmt_int(kase%ny)//': '//trim(errmsg)
                call case_error(nbefore); return
            end if
            ! an operator on estimated plans is rebuilt for a case that names a wisdom file
            wisdom = len_trim(kase%fft_wisdom) > 0
            reuse = built .and. (kase%periodic .eqv. built_periodic) .and. same_grid(grid, built_grid) .and. &
                mat%g == built_mat%g .and. mat%nu == built_mat%nu .and. (built_measured .or. .not. wisdom)
            if (.not. reuse) then
                call check_dist_memory(kase, stat, errmsg)
                if (stat /= 0) then
                    call case_error(nbefore); return
                end if
                if (wisdom) call load_dist_wisdom(trim(kase%fft_wisdom), stat, errmsg)
                if (stat /= 0) then
                    errmsg = "&solver fft_wisdom = '"//trim(kase%fft_wisdom)//"': "//trim(errmsg)
                    call case_error(nbefore); return
                end if
                built = .false.
                call build_dist_normal_operator(dop, mat, grid, comm, stat, errmsg, periodic=kase%periodic, &
                                                measure=wisdom)
                if (stat /= 0) then
                    if (kase%periodic) then
                        errmsg = '&grid periodic = .true., nx = '//fmt_int(kase%nx)//', ny = '//fmt_int(kase%ny)//': '// &
                            trim(errmsg)
                    else
                        errmsg = '&grid nx = '//fmt_int(kase%nx)//', ny = '//fmt_int(kase%ny)//': '//trim(errmsg)
                    end if
                    call case_error(nbefore); return
                end if
                if (wisdom) call save_dist_wisdom(trim(kase%fft_wisdom), stat, errmsg)
                if (stat /= 0) then
                    errmsg = "&solver fft_wisdom = '"//trim(kase%fft_wisdom)//"': "//trim(errmsg)
                    call case_error(nbefore); return
                end if
                built = .true.; built_grid = grid; built_mat = mat; built_periodic = kase%periodic
                built_measured = wisdom
            end if
            ! ---- this rank's rows of h0
            nyl = dop%lay%nyl
            j0 = dop%lay%y0 + 1; j1 = dop%lay%y0 + nyl
            allocate (h0(grid%nx, j0:j1))
            select case (kase%kind)
            case ('quadratic')
                call quadratic_gap_rows(grid, kase%rx, kase%ry, j0, j1, h0)
            case ('cylinder')
                call quadratic_gap_rows(grid, kase%rx, 0.0_dp, j0, j1, h0)
            case ('punch_rough')
                call punch_rough_gap_rows(grid, kase%diameter, kase%rough, j0, j1, h0)
            case ('wavy')
                call wavy_gap_rows(grid, kase%amplitude, kase%wavelength_x, kase%wavelength_y, j0, j1, h0)
            end select
            can_touch = any(h0 < 0.5_dp*h_no_contact)
            call mpi_allreduce(MPI_IN_PLACE, can_touch, 1, MPI_LOGICAL, MPI_LOR, comm, ierr)
            if (.not. can_touch) then
                errmsg = "&geometry kind = '"//trim(kase%kind)//"': no element can come into contact "// &
                    '(e.g. punch diameter smaller than an element)'
                call case_error(nbefore); return
            end if
            ! ---- solve
            if (kase%normal%force_prescribed) then
                call solve_dist_normal(dop, h0, kase%settings%normal, res, stat, errmsg, fn=kase%normal%fn)
            else
                call solve_dist_normal(dop, h0, kase%settings%normal, res, stat, errmsg, approach=kase%normal%approach)
            end if
            if (stat /= 0) then
                ! the library names the key and value ('approach = … gives no contact'); the
                ! namelist group follows from the error code
                select case (stat)
                case (FC_ERR_NO_CONTACT, FC_ERR_VALUE); errmsg = '&normal '//trim(errmsg)
                case (FC_ERR_UNSUPPORTED); errmsg = '&solver '//trim(errmsg)
                end select
                call case_error(nbefore); return
            end if
            ! ---- summary (the serial driver's keys)
            s%name = state%name; s%title = state%title; s%problem = state%problem; s%geometry = state%kind
            s%input_fingerprint = with_files(fingerprints(k), case_files(state))
            s%force_prescribed = state%force_prescribed
            s%tol = kase%settings%normal%tol
            s%notes = state%notes//case_notes(state)//'distributed over '//fmt_int(nprocs)//' ranks. '
            if (mat%k /= 0) s%notes = s%notes//'K = '//fmt_real(mat%k)// &
                ' /= 0: the normal problem is solved without the tangential coupling. '
            s%status = status_name(res%status); s%message = res%message
            s%solver = 'bccg'; s%solver_normal = 'bccg'
            s%fft_preconditioner = 'toeplitz'
            s%status_normal = s%status
            s%fn = res%fn; s%approach = res%approach; s%pmax = res%pmax
            s%ncon = res%ncon; s%nadh = res%ncon; s%nslip = 0
            s%iterations = res%iterations; s%outer_iterations = res%outer_iterations; s%matvecs = res%matvecs
            s%iterations_normal = res%iterations; s%outer_iterations_normal = res%outer_iterations
            s%matvecs_normal = res%matvecs
            s%residual = res%residual; s%residual_normal = res%residual
            s%operator_built = .not. reuse
            if (.not. reuse) s%setup_seconds = dop%setup_seconds
            s%cpu_seconds_normal = s%setup_seconds + res%cpu_seconds
            s%outcome%grid = grid; s%outcome%material = mat
            s%outcome%model = 'distributed'
            s%outcome%touches_boundary = res%touches_boundary .and. .not. kase%periodic   ! a cell has no edge
            s%outcome%result%normal%precond_applications = res%precond_applications
            if (allocated(res%history)) s%outcome%result%normal%history = res%history
            call hertz_reference(s, state, mat)
            ! ---- outputs: the table by the ranks in turn, then the summary and report on rank 0
            if (state%table) then
                if (state%table_format /= 'npy') call write_table(dir//'/'//trim(state%name)//'.csv', grid, j0, res, .false.)
                if (stat == 0 .and. state%table_format /= 'csv') &
                    call write_table(dir//'/'//trim(state%name)//'.npy', grid, j0, res, .true.)
                if (stat /= 0) then
                    call case_error(nbefore); return
                end if
            else if (rank == 0) then
                call remove_file(dir//'/'//trim(state%name)//'.csv')
            end if
            s%cpu_seconds = mpi_wtime() - t0
            stat = 0
            if (rank == 0) call write_case_json(dir//'/'//trim(state%name)//'.json', s, stat, errmsg)
            call mpi_bcast(stat, 1, MPI_INTEGER, 0, comm, ierr)
            if (stat /= 0) then
                call mpi_bcast(errmsg, len(errmsg), MPI_CHARACTER, 0, comm, ierr)
                if (rank == 0) call remove_file(dir//'/'//trim(state%name)//'.csv')
                call case_error(nbefore); return
            end if
            if (rank == 0) call write_case_report(rep, s, reshape([0.0_dp], [0, 0]))
            if (res%status == FC_CONVERGED) then
                case_status = 0
            else
                case_status = 2
                if (rank == 0) write (err, '(a,i0,a)') 'fastcontact-mpi: case ', k, " '"//trim(state%name)//"': solver "// &
                    trim(status_name(res%status))//': '//trim(s%message)
            end if
        end subroutine run_one

        !> `--resume`: case k (its values applied to `state`) was finished by an earlier run
        !! with the same input ([[previous_outcome]]); rank 0 reads its JSON and tells the
        !! others.  `case_status` from the status the JSON records; the report says so.
        logical function done_before(k, dir, case_status) result(done)
            integer, intent(in) :: k
            character(len=*), intent(in) :: dir
            integer, intent(inout) :: case_status
            character(len=:), allocatable :: what
            integer :: buf(2)
            buf = 0
            if (rank == 0) then
                if (previous_outcome(dir//'/'//trim(state%name)//'.json', with_files(fingerprints(k), case_files(state)), &
                                     buf(2), what)) then
                    buf(1) = 1
                    write (rep, '(a)') ' case '//trim(state%name)//': done in an earlier run with the same input ('// &
                        what//'), skipped (--resume)'//new_line('a')
                end if
            end if
            call mpi_bcast(buf, 2, MPI_INTEGER, 0, comm, ierr)
            done = buf(1) == 1
            if (done) then
                case_status = buf(2); nskipped = nskipped + 1
            end if
        end function done_before

        !> End of the closing line with `--resume`.
        function skipped_note() result(note)
            character(len=:), allocatable :: note
            note = ''
            if (resume) note = ' ('//fmt_int(nskipped)//' of them done in an earlier run: skipped)'
        end function skipped_note

        !> The element table of this case (CSV, or `.npy` with `npy`), rank after rank (rank 0
        !! with the header), each appending its rows; stat and errmsg the same on every rank
        !! afterwards.
        subroutine write_table(path, grid, j0, res, npy)
            character(len=*), intent(in) :: path
            type(fc_grid), intent(in) :: grid
            integer, intent(in) :: j0
            type(fc_normal_result), intent(in) :: res
            logical, intent(in) :: npy
            integer :: r, ii, jj, st
            character(len=msg_len) :: msg
            st = 0; msg = ''
            do r = 0, nprocs - 1
                if (r == rank) then
                    associate (xs => [(grid%x(ii), ii=1, grid%nx)], ys => [(grid%y(jj), jj=j0, j0 + size(res%pn, 2) - 1)])
                        if (npy) then
                            call write_element_table_npy(path, xs, ys, res%pn, res%gap, st, msg, iy_first=j0, &
                                append=r > 0, ny_total=grid%ny)
                        else
                            call write_element_table_csv(path, xs, ys, res%pn, res%gap, st, msg, iy_first=j0, append=r > 0)
                        end if
                    end associate
                end if
                call mpi_barrier(comm, ierr)
            end do
            call mpi_allreduce(st, stat, 1, MPI_INTEGER, MPI_MAX, comm, ierr)
            errmsg = ''
            if (stat /= 0) errmsg = "&output table = .true.: cannot write the element table '"//path//"'"
        end subroutine write_table

        !> stat /= 0 on every rank, with rank 0's message naming `&grid nx, ny`, when the
        !! operator and vectors of `kase` (`dist_memory_per_rank`) would need more memory per
        !! rank than some rank may use: the available memory of its node (fc_memory) shared by
        !! the ranks on that node, plus what the rank holds already.  Collective.
        subroutine check_dist_memory(kase, stat, errmsg, report)
            type(fc_case), intent(in) :: kase
            integer, intent(out) :: stat
            character(len=msg_len), intent(out) :: errmsg
            logical, intent(in), optional :: report   !! --check: rank 0 prints the estimate of a case that fits
            integer(int64) :: avail, need, budget, held
            character(len=:), allocatable :: source, line
            integer :: nodecomm, pernode, ierr2
            call available_memory(avail, source, stat, errmsg)
            call mpi_allreduce(MPI_IN_PLACE, stat, 1, MPI_INTEGER, MPI_MAX, comm, ierr2)
            if (stat /= 0) then
                if (len_trim(errmsg) == 0) errmsg = memory_env//': not a size in bytes on another rank'
                return
            end if
            call mpi_comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, nodecomm, ierr2)
            call mpi_comm_size(nodecomm, pernode, ierr2)
            call mpi_comm_free(nodecomm, ierr2)
            budget = huge(budget)                  ! unknown: not checked on this rank
            if (avail >= 0) then
                held = 0
                if (source /= memory_env) held = max(0_int64, process_resident_bytes())
                budget = avail/pernode + held
            end if
            call mpi_allreduce(MPI_IN_PLACE, budget, 1, MPI_INTEGER8, MPI_MIN, comm, ierr2)
            need = dist_memory_per_rank(kase%nx, kase%ny, nprocs, kase%periodic)
            if (need <= budget) then
                if (present(report) .and. rank == 0) then
                    line = ' case '//trim(state%name)//': '//fmt_int(kase%nx)//' x '//fmt_int(kase%ny)//' on '// &
                        fmt_int(nprocs)//' ranks: about '//format_bytes(need)//' per rank'
                    if (budget == huge(budget)) then
                        line = line//' (the available memory is unknown)'
                    else
                        line = line//' of '//format_bytes(budget)//' a rank may use ('//source//' of a node shared by '// &
                            fmt_int(pernode)//' ranks)'
                    end if
                    write (rep, '(a)') line
                end if
                return
            end if
            stat = FC_ERR_ALLOC
            errmsg = '&grid nx = '//fmt_int(kase%nx)//', ny = '//fmt_int(kase%ny)//': the distributed solve needs about '// &
                format_bytes(need)//' per rank on '//fmt_int(nprocs)//' ranks, more than the '//format_bytes(budget)// &
                ' a rank may use ('//source//' of a node shared by '//fmt_int(pernode)//' ranks); about '// &
                format_bytes(nprocs*need)//' in all: run on more nodes, or set '//memory_env//' to override'
        end subroutine check_dist_memory

        !> Before a build with measured plans: rank 0 reads the wisdom file `path` (or, when
        !! it does not exist yet, checks that it can be created) and every rank receives its
        !! wisdom.  stat = FC_ERR_FFT_WISDOM on every rank when the file is not FFTW wisdom or
        !! cannot be created.  Collective.
        subroutine load_dist_wisdom(path, stat, errmsg)
            character(len=*), intent(in) :: path
            integer, intent(out) :: stat
            character(len=msg_len), intent(out) :: errmsg
            logical :: exists
            integer :: u, ios, ierr2
            stat = 0; errmsg = ''
            if (rank == 0) then
                inquire (file=path, exist=exists)
                if (exists) then
                    if (.not. read_wisdom(path)) then
                        stat = FC_ERR_FFT_WISDOM
                        errmsg = 'the file exists but FFTW cannot read it as wisdom (delete it to measure again)'
                    end if
                else
                    open (newunit=u, file=wisdom_temp_name(path), status='replace', action='write', iostat=ios)
                    if (ios /= 0) then
                        stat = FC_ERR_FFT_WISDOM
                        errmsg = 'cannot create the wisdom file (does its directory exist?)'
                    else
                        close (u, status='delete')
                    end if
                end if
            end if
            call mpi_bcast(stat, 1, MPI_INTEGER, 0, comm, ierr2)
            call mpi_bcast(errmsg, len(errmsg), MPI_CHARACTER, 0, comm, ierr2)
            if (stat == 0) call fftw_mpi_broadcast_wisdom(comm)
        end subroutine load_dist_wisdom

        !> After a build with measured plans: the wisdom of all ranks is gathered on rank 0
        !! and written to `path` (a temporary file renamed over it).  stat =
        !! FC_ERR_FFT_WISDOM on every rank when it cannot be written.  Collective.
        subroutine save_dist_wisdom(path, stat, errmsg)
            character(len=*), intent(in) :: path
            integer, intent(out) :: stat
            character(len=msg_len), intent(out) :: errmsg
            character(len=:), allocatable :: tmp
            integer :: u, ios, ierr2
            stat = 0; errmsg = ''
            call fftw_mpi_gather_wisdom(comm)
            if (rank == 0) then
                tmp = wisdom_temp_name(path)
                select case (write_wisdom(tmp, path))
                case (1)
                    stat = FC_ERR_FFT_WISDOM; errmsg = 'cannot write the wisdom file (does its directory exist?)'
                case (2)
                    stat = FC_ERR_FFT_WISDOM; errmsg = 'cannot replace the wisdom file by the new one'
                end select
                if (stat /= 0) then
                    open (newunit=u, file=tmp, status='old', iostat=ios)
                    if (ios == 0) close (u, status='delete')
                end if
            end if
            call mpi_bcast(stat, 1, MPI_INTEGER, 0, comm, ierr2)
            call mpi_bcast(errmsg, len(errmsg), MPI_CHARACTER, 0, comm, ierr2)
        end subroutine save_dist_wisdom

        !> Report an input error of case k (rank 0) and remove its stale outputs; the next case
        !! inherits from the last case without input errors.
        subroutine case_error(nbefore, clean)
            integer, intent(in) :: nbefore
            logical, intent(in), optional :: clean
            logical :: do_clean
            do_clean = .true.
            if (present(clean)) do_clean = clean
            if (rank == 0) then
                call write_case_error(rep, err, 'fastcontact-mpi', k, cases(k)%line, name, errmsg)
                if (do_clean .and. .not. any(used(1:nbefore) == name)) call remove_case_outputs(output_dir(), name)
            end if
            state = saved_state
        end subroutine case_error

        function output_dir() result(d)
            character(len=:), allocatable :: d
            d = case_output_dir(state, out_dir)
        end function output_dir
    end subroutine run_dist_driver

    !> Why a checked case cannot be solved distributed ('' when it can), naming the group,
    !! key and value.
    function dist_case_unsupported(state, kase) result(msg)
        type(fc_case_input), intent(in) :: state
        type(fc_case), intent(in) :: kase
        character(len=msg_len) :: msg
        character(len=*), parameter :: tail = ' (distributed solves: normal problems on a given grid)'
        msg = ''
        if (state%problem /= 'normal') then
            msg = "&case problem = '"//trim(state%problem)//"': a distributed solve is a normal problem "// &
                "(problem = 'normal')"
        else if (trim(state%normal_solver) /= 'bccg') then
            msg = "&solver normal = '"//trim(state%normal_solver)//"': the distributed solver is 'bccg'"
        else if (state%deflation) then
            msg = '&solver deflation = .true.: not available in the distributed solver'
        else if (grid_is_auto(state)) then
            msg = '&grid: the automatic potential contact area is not available; give nx, ny, xmin, xmax, ymin, ymax'//tail
        else if (kase%target > 0) then
            msg = '&solver target = '//fmt_real(kase%target)//': accuracy targets are not available'//tail
        else if (len_trim(state%ic_file) > 0 .or. len_trim(state%ic_file2) > 0) then
            msg = "&material ic_file = '"//trim(state%ic_file)//"': influence coefficients from files are not "// &
                'available; distributed solves use the half-space'
        else if (all(trim(state%kind) /= [character(len=16) :: 'quadratic', 'cylinder', 'punch_rough', 'wavy'])) then
            msg = "&geometry kind = '"//trim(state%kind)//"': distributed solves generate the geometry on each rank: "// &
                "kind = 'quadratic', 'cylinder', 'punch_rough' or 'wavy'"
        end if
    end function dist_case_unsupported

    !> Same grid (size and edges) for the operator.
    pure logical function same_grid(a, b)
        type(fc_grid), intent(in) :: a, b
        same_grid = a%nx == b%nx .and. a%ny == b%ny .and. a%xmin == b%xmin .and. a%xmax == b%xmax .and. &
            a%ymin == b%ymin .and. a%ymax == b%ymax
    end function same_grid

    function dist_usage() result(text)
        character(len=:), allocatable :: text
        character(len=1), parameter :: nl = achar(10)
        text = 'usage: mpirun -np P fastcontact-mpi CASES.nml --distributed [--out DIR] [--check] [--resume]'//nl// &
            '  every case solved by all P ranks together (normal problems, BCCG, grids generated'//nl// &
            '  row by row); without --distributed the cases are spread over the ranks.  --check:'//nl// &
            '  check every case and estimate its memory per rank against the nodes; solve nothing.'//nl// &
            '  --resume: skip the cases an earlier run finished with the same input'
    end function dist_usage

end module fcm_dist_driver
