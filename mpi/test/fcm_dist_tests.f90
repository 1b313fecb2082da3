!> Tests of the distributed driver (`fastcontact-mpi --distributed`): a namelist of normal
!! cases solved by all ranks together gives the serial driver's answers (force, approach,
!! contact count, pressure table) and its table layout; unsupported cases are input errors
!! naming the group, key and value, and the cases after them still run.
module fcm_dist_tests
    use mpi
    use fc_kinds, only: dp
    use fc_driver, only: run_driver
    use fcm_dist_driver, only: run_dist_driver
    use fc_strings, only: fmt_int
    use fcm_test_support, only: run_mpi_test, slurp_file, set_env, unset_env, rank0_failed
    use, intrinsic :: iso_c_binding, only: c_null_char
    use fcm_fftw_mpi, only: c_ptr, c_int, c_size_t, c_associated, c_f_pointer, fftw_forget_wisdom, &
        fftw_import_wisdom_from_filename, fftw_plan_dft_r2c_1d, fftw_destroy_plan, fftw_alloc_real, fftw_alloc_complex, &
        fftw_free, FFTW_MEASURE, FFTW_WISDOM_ONLY
    implicit none
    private
    public :: dist_driver_tests

    character(len=*), parameter :: dir = 'build/test-mpi-dist'
    character(len=8), parameter :: names(3) = [character(len=8) :: 'dh_a', 'dh_f', 'dw_p']

contains

    subroutine dist_driver_tests(only, npass, nfail)
        character(len=*), intent(in) :: only
        integer, intent(inout) :: npass, nfail
        call run_mpi_test('dist_driver_equals_serial_driver', only, test_equal, npass, nfail)
        call run_mpi_test('dist_driver_rejects_unsupported', only, test_unsupported, npass, nfail)
        call run_mpi_test('dist_driver_memory_check', only, test_memory, npass, nfail)
        call run_mpi_test('dist_driver_fft_wisdom', only, test_wisdom, npass, nfail)
        call run_mpi_test('dist_driver_resume', only, test_resume, npass, nfail)
    end subroutine dist_driver_tests

    !> `--resume` on the distributed driver: a second run of two cases skips both (report and
    !! closing line say so, the JSON is not rewritten); after one JSON is deleted, only that
    !! case is solved again, to the same force.
    subroutine test_resume(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: rank, ierr, code, u, k
        character(len=4096), allocatable :: args(:)
        character(len=:), allocatable :: rep, before_a, before_b
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        if (rank == 0) then
            call execute_command_line('rm -rf '//dir//'/res && mkdir -p '//dir//'/res')
            open (newunit=u, file=dir//'/res.nml', status='replace', action='write')
            write (u, '(a)') "&case name = 'ra' /"
            write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
            write (u, '(a)') "&grid nx = 32, ny = 24, xmin = -1.2, xmax = 1.2, ymin = -1.0, ymax = 1.0 /"
            write (u, '(a)') "&geometry kind = 'quadratic', rx = 40.0, ry = 30.0 /"
            write (u, '(a)') "&normal approach = 0.004 /"
            write (u, '(a)') "&case name = 'rb' /"
            write (u, '(a)') "&normal fn = 300.0 /"
            close (u)
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        args = [character(len=4096) :: dir//'/res.nml', '--out', dir//'/res/out', '--resume']
        do k = 1, 3
            if (k == 3 .and. rank == 0) call execute_command_line('rm -f '//dir//'/res/out/rb.json')
            call mpi_barrier(MPI_COMM_WORLD, ierr)
            call run_dist(args, 'res'//fmt_int(k), code)
            if (code /= 0) then
                msg = 'run '//fmt_int(k)//': exit status '//fmt_int(code); return
            end if
            if (rank == 0) then
                rep = slurp_file(dir//'/res'//fmt_int(k)//'.rep'//rank_suffix(0))
                select case (k)
                case (1)
                    before_a = slurp_file(dir//'/res/out/ra.json'); before_b = slurp_file(dir//'/res/out/rb.json')
                    if (index(rep, '(0 of them done in an earlier run: skipped)') == 0) msg = 'run 1: '//rep
                case (2)
                    if (index(rep, 'case ra: done in an earlier run with the same input (converged), skipped') == 0 &
                        .or. index(rep, '(2 of them done in an earlier run: skipped)') == 0) msg = 'run 2: '//rep
                    if (slurp_file(dir//'/res/out/ra.json') /= before_a) msg = 'run 2 rewrote ra.json'
                case (3)
                    if (index(rep, '(1 of them done in an earlier run: skipped)') == 0 .or. index(rep, 'case rb: done') > 0) &
                        msg = 'run 3 (rb.json deleted): '//rep
                    if (.not. allocated(msg)) then
                        if (.not. close_to(json_num(slurp_file(dir//'/res/out/rb.json'), 'fn'), json_num(before_b, 'fn'), &
                                           1.0e-14_dp)) msg = 'run 3: rb solved again to another force'
                    end if
                end select
            end if
            if (rank0_failed(msg)) return
        end do
    end subroutine test_resume

    !> `&solver fft_wisdom`: the first case measures its plans and writes the file (rank 0,
    !! the wisdom of both ranks gathered), a second case of the same grid reuses nothing
    !! built on estimated plans and gives the same force as the estimated case to 1e−9; a
    !! second run reads the file; a file that is not wisdom is an input error naming the key.
    subroutine test_wisdom(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: rank, ierr, code, urep, uerr, u, k
        character(len=4096), allocatable :: args(:)
        character(len=:), allocatable :: e, w1, w2, j
        real(dp) :: f(3)
        type(c_ptr) :: pr, pc, plan
        real(dp), pointer :: rb(:)
        complex(dp), pointer :: cb(:)
        logical :: there
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        if (rank == 0) then
            call execute_command_line('rm -rf '//dir//'/wis && mkdir -p '//dir//'/wis')
            open (newunit=u, file=dir//'/wis.nml', status='replace', action='write')
            write (u, '(a)') "&case name = 'est' /"
            write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
            write (u, '(a)') "&grid nx = 48, ny = 40, xmin = -1.2, xmax = 1.2, ymin = -1.0, ymax = 1.0 /"
            write (u, '(a)') "&geometry kind = 'quadratic', rx = 40.0, ry = 30.0 /"
            write (u, '(a)') "&normal approach = 0.004 /"
            write (u, '(a)') "&solver tol = 1e-12 /"
            write (u, '(a)') "&case name = 'mea' /"
            write (u, '(a)') "&solver tol = 1e-12, fft_wisdom = '"//dir//"/wis/w.wis' /"
            close (u)
            open (newunit=u, file=dir//'/wis/bad.wis', status='replace', action='write')
            write (u, '(a)') 'not wisdom'
            close (u)
            open (newunit=u, file=dir//'/wisbad.nml', status='replace', action='write')
            write (u, '(a)') "&case name = 'bad' /"
            write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
            write (u, '(a)') "&grid nx = 48, ny = 40, xmin = -1.2, xmax = 1.2, ymin = -1.0, ymax = 1.0 /"
            write (u, '(a)') "&geometry kind = 'quadratic', rx = 40.0, ry = 30.0 /"
            write (u, '(a)') "&normal approach = 0.004 /"
            write (u, '(a)') "&solver fft_wisdom = '"//dir//"/wis/bad.wis' /"
            close (u)
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        do k = 1, 2      ! the second run reads the file the first wrote
            args = [character(len=4096) :: dir//'/wis.nml', '--out', dir//'/wis/out'//fmt_int(k)]
            call run_dist(args, 'wis', code)
            if (code /= 0) then
                msg = 'run '//fmt_int(k)//': exit status '//fmt_int(code)//' (expected 0)'; return
            end if
            if (rank == 0) then
                r0_1: block
                    w1 = slurp_file(dir//'/wis/w.wis')
                    ! measured plans leave entries, the transposes' among them (estimated ones none)
                    if (index(w1, '(fftw-3') == 0 .or. index(w1, '(fftw_mpi_transpose') == 0) then
                        msg = 'run '//fmt_int(k)//': no measured transposes in w.wis: '//w1(1:min(200, len(w1))); exit r0_1
                    end if
                    if (k == 1) w2 = w1
                    j = slurp_file(dir//'/wis/out'//fmt_int(k)//'/mea.json')
                    if (index(j, '"status": "converged"') == 0 .or. index(j, 'not used') > 0) then
                        msg = 'run '//fmt_int(k)//': measured case: '//j(1:min(400, len(j))); exit r0_1
                    end if
                    f(k) = json_num(j, 'fn')
                    if (k == 1) f(3) = json_num(slurp_file(dir//'/wis/out1/est.json'), 'fn')
                    if (.not. close_to(f(k), f(3), 1.0e-9_dp)) then
                        msg = 'run '//fmt_int(k)//': fn with measured plans differs from the estimated one'; exit r0_1
                    end if
                end block r0_1
            end if
            if (rank0_failed(msg)) return
        end do
        if (rank == 0) then
            r0_2: block
                if (len(w1) < len(w2)) then
                    msg = 'the second run lost wisdom of the first'; exit r0_2
                end if
                ! the file holds *measured* plans: the x transform of the doubled grid (96 points)
                ! plans from it alone with FFTW_MEASURE (estimated plans would not satisfy that)
                call fftw_forget_wisdom()
                if (fftw_import_wisdom_from_filename(dir//'/wis/w.wis'//c_null_char) == 0) then
                    msg = 'w.wis cannot be read back'; exit r0_2
                end if
                pr = fftw_alloc_real(96_c_size_t); pc = fftw_alloc_complex(49_c_size_t)
                call c_f_pointer(pr, rb, [96]); call c_f_pointer(pc, cb, [49])
                plan = fftw_plan_dft_r2c_1d(96_c_int, rb, cb, ior(FFTW_MEASURE, FFTW_WISDOM_ONLY))
                there = c_associated(plan)
                if (there) call fftw_destroy_plan(plan)
                call fftw_free(pr); call fftw_free(pc)
                if (.not. there) then
                    msg = 'w.wis has no measured plan of the x transform'; exit r0_2
                end if
            end block r0_2
        end if
        if (rank0_failed(msg)) return
        args = [character(len=4096) :: dir//'/wisbad.nml', '--out', dir//'/wis/bad']
        call run_dist(args, 'wisbad', code)
        if (code /= 1) then
            msg = 'not wisdom: exit status '//fmt_int(code)//' (expected 1)'; return
        end if
        if (rank == 0) then
            r0_3: block
                e = slurp_file(dir//'/wisbad.err0')
                if (index(e, "&solver fft_wisdom = '"//dir//"/wis/bad.wis': the file exists but FFTW cannot read it") == 0) then
                    msg = 'no error naming the wisdom file in: '//e; exit r0_3
                end if
            end block r0_3
        end if
        if (rank0_failed(msg)) return
    end subroutine test_wisdom


    !> A case whose operator needs more memory per rank than the node's available memory
    !! (here given by FASTCONTACT_AVAILABLE_MEMORY) shared by its ranks is an input error on
    !! every rank, naming &grid nx, ny, the ranks and the sizes, with no outputs; with
    !! enough memory the same case is solved.
    subroutine test_memory(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: rank, nprocs, ierr, code, urep, uerr, u
        character(len=4096), allocatable :: args(:)
        character(len=:), allocatable :: e, want
        logical :: there
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        call mpi_comm_size(MPI_COMM_WORLD, nprocs, ierr)
        if (rank == 0) then
            call execute_command_line('rm -rf '//dir//'/mem && mkdir -p '//dir//'/mem')
            open (newunit=u, file=dir//'/mem.nml', status='replace', action='write')
            write (u, '(a)') "&case name = 'mem' /"
            write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
            write (u, '(a)') "&grid nx = 24, ny = 20, xmin = -1.2, xmax = 1.2, ymin = -1.0, ymax = 1.0 /"
            write (u, '(a)') "&geometry kind = 'quadratic', rx = 40.0, ry = 30.0 /"
            write (u, '(a)') "&normal approach = 0.004 /"
            close (u)
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        args = [character(len=4096) :: dir//'/mem.nml', '--out', dir//'/mem']
        ! 16 MB + 133 B × 24 × ⌈20/P⌉ per rank against at most 10 MB
        call set_env('FASTCONTACT_AVAILABLE_MEMORY', '10M')
        call run_dist(args, 'mem', code)
        if (code /= 1) then
            msg = 'too little memory: exit status '//fmt_int(code)//' (expected 1: input error)'; return
        end if
        if (rank == 0) then
            r0_4: block
                e = slurp_file(dir//'/mem.err0')
                want = '&grid nx = 24, ny = 20: the distributed solve needs about 16 MB per rank on '//fmt_int(nprocs)//' ranks'
                if (index(e, want) == 0 .or. index(e, 'FASTCONTACT_AVAILABLE_MEMORY of a node shared by') == 0) then
                    msg = 'no error naming the grid and the sizes in: '//e; exit r0_4
                end if
                inquire (file=dir//'/mem/mem.json', exist=there)
                if (there) then
                    msg = 'a summary was written for a case refused for memory'; exit r0_4
                end if
            end block r0_4
        end if
        if (rank0_failed(msg)) return
        ! --check: the estimate per rank, nothing solved
        call set_env('FASTCONTACT_AVAILABLE_MEMORY', '100G')
        args = [character(len=4096) :: dir//'/mem.nml', '--out', dir//'/mem', '--check']
        call run_dist(args, 'mem3', code)
        if (code /= 0) then
            msg = '--check: exit status '//fmt_int(code)//' (expected 0)'; return
        end if
        if (rank == 0) then
            r0_5: block
                e = slurp_file(dir//'/mem3.rep0')
                if (index(e, ' case mem: 24 x 20 on '//fmt_int(nprocs)//' ranks: about 16 MB per rank of ') == 0 .or. &
                    index(e, 'fastcontact-mpi --distributed --check: 1 case(s) on '//fmt_int(nprocs)//' ranks: 1 to solve') == 0) &
                    then
                    msg = '--check report: '//e; exit r0_5
                end if
                inquire (file=dir//'/mem/mem.json', exist=there)
                if (there) then
                    msg = '--check wrote a summary'; exit r0_5
                end if
            end block r0_5
        end if
        if (rank0_failed(msg)) return
        args = [character(len=4096) :: dir//'/mem.nml', '--out', dir//'/mem']
        call run_dist(args, 'mem2', code)
        call unset_env('FASTCONTACT_AVAILABLE_MEMORY')
        if (code /= 0) msg = 'enough memory: exit status '//fmt_int(code)//' (expected 0)'
    end subroutine test_memory

    !> Three cases (Hertz with prescribed approach, then force — inherited grid and
    !! material, the operator reused —, a periodic wavy cell with prescribed force), tol
    !! 1e−10 so that the serial and the distributed solve are the same solution to round-off
    !! whatever their paths: force and approach to 1e−9, the same contact count, every
    !! element's pressure to 1e−8·pmax and its gap to 1e−8 of the largest gap (the `.npy`
    !! table of the second case too: same header, records and pressures), and the
    !! table's coordinates, indices and status letters identical text; whether the contact
    !! touches the edge as the serial driver says (never for the periodic cell).  The summary
    !! says where it was solved.
    subroutine test_equal(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: rank, ierr, code_s, code_d, urep, uerr, k
        character(len=4096), allocatable :: args(:)
        character(len=:), allocatable :: js, jd
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        if (rank == 0) then
            call execute_command_line('mkdir -p '//dir//'/serial '//dir//'/dist')
            call write_cases(dir//'/cases.nml')
            open (newunit=urep, file=dir//'/serial.rep', status='replace')
            open (newunit=uerr, file=dir//'/serial.err', status='replace')
            args = [character(len=4096) :: dir//'/cases.nml', '--out', dir//'/serial']
            call run_driver(args, code_s, urep, uerr)
            close (urep); close (uerr)
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        open (newunit=urep, file=dir//'/dist.rep'//rank_suffix(rank), status='replace')
        open (newunit=uerr, file=dir//'/dist.err'//rank_suffix(rank), status='replace')
        args = [character(len=4096) :: dir//'/cases.nml', '--out', dir//'/dist']
        call run_dist_driver(args, MPI_COMM_WORLD, code_d, urep, uerr)
        close (urep); close (uerr)
        if (rank /= 0) return
        if (code_s /= 0 .or. code_d /= 0) then
            msg = 'exit codes serial '//fmt_int(code_s)//', distributed '//fmt_int(code_d)//': '// &
                slurp_file(dir//'/dist.err0')//slurp_file(dir//'/serial.err'); return
        end if
        do k = 1, size(names)
            js = slurp_file(dir//'/serial/'//trim(names(k))//'.json')
            jd = slurp_file(dir//'/dist/'//trim(names(k))//'.json')
            if (.not. close_to(json_num(jd, 'fn'), json_num(js, 'fn'), 1e-9_dp) .or. &
                .not. close_to(json_num(jd, 'approach'), json_num(js, 'approach'), 1e-9_dp) .or. &
                json_num(jd, 'ncon') /= json_num(js, 'ncon') .or. json_num(jd, 'ncon') < 1) then
                msg = trim(names(k))//': fn, approach or ncon differ from the serial driver'; return
            end if
            if ((index(jd, '"touches_boundary": true') > 0) .neqv. (index(js, '"touches_boundary": true') > 0)) then
                msg = trim(names(k))//'.json: touches_boundary differs from the serial driver'; return
            end if
            if (index(jd, '"model": "distributed"') == 0 .or. index(jd, 'distributed over ') == 0 .or. &
                index(jd, '"status": "converged"') == 0) then
                msg = trim(names(k))//'.json: model, notes or status not as expected'; return
            end if
            call compare_tables(dir//'/serial/'//trim(names(k))//'.csv', dir//'/dist/'//trim(names(k))//'.csv', msg)
            if (allocated(msg)) then
                msg = trim(names(k))//'.csv: '//msg; return
            end if
        end do
        call compare_npy(slurp_file(dir//'/serial/dh_f.npy'), slurp_file(dir//'/dist/dh_f.npy'), msg)
        if (allocated(msg)) then
            msg = 'dh_f.npy: '//msg; return
        end if
        jd = slurp_file(dir//'/dist/dh_f.json')
        if (index(jd, '"operator_built": false') == 0) msg = 'dh_f: the operator of dh_a (same grid) was not reused'
    end subroutine test_equal

    !> Unsupported cases are input errors (exit status 1) naming group, key and value, as is
    !! an approach that brings no element into contact (the solver's message in the
    !! driver's form); the cases after them still run, and a bad command line is rejected.
    subroutine test_unsupported(msg)
        character(len=:), allocatable, intent(out) :: msg
        integer :: rank, ierr, code, urep, uerr, u
        character(len=4096), allocatable :: args(:)
        character(len=:), allocatable :: e
        character(len=*), parameter :: expect(5) = [character(len=40) :: "&case problem = 'normal+tangential'", &
            "&solver normal = 'norm'", "&geometry kind = 'table'", "'no_contact' (line 16): &normal approach =", &
            "&grid: the automatic potential contact"]
        integer :: k
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        if (rank == 0) then
            call execute_command_line('mkdir -p '//dir//'/bad')
            open (newunit=u, file=dir//'/h0.txt', status='replace', action='write')   ! a valid 24 x 20 table
            write (u, '(24(es12.4))') (0.01_dp*k, k=1, 480)
            close (u)
            open (newunit=u, file=dir//'/bad.nml', status='replace', action='write')
            write (u, '(a)') "&case name = 'ok1' /"
            write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
            write (u, '(a)') "&grid nx = 24, ny = 20, xmin = -1.2, xmax = 1.2, ymin = -1.0, ymax = 1.0 /"
            write (u, '(a)') "&geometry kind = 'quadratic', rx = 40.0, ry = 30.0 /"
            write (u, '(a)') "&normal approach = 0.004 /"
            write (u, '(a)') "&case name = 'tang', problem = 'normal+tangential' /"
            write (u, '(a)') "&tangential mu = 0.3, xi = 2.0e-4 /"
            write (u, '(a)') "&case name = 'norm_solver' /"
            write (u, '(a)') "&solver normal = 'norm' /"
            write (u, '(a)') "&case name = 'table_geo' /"
            write (u, '(a)') "&geometry kind = 'table', file = '"//dir//"/h0.txt' /"
            write (u, '(a)') "&case name = 'npy' /"
            write (u, '(a)') "&output table_format = 'csv' /"
            write (u, '(a)') "&case name = 'auto_area' /"
            write (u, '(a)') "&grid auto = .true. /"
            write (u, '(a)') "&case name = 'no_contact' /"
            write (u, '(a)') "&normal approach = -0.01 /"
            write (u, '(a)') "&case name = 'ok2' /"
            write (u, '(a)') "&normal approach = 0.005 /"
            close (u)
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
        open (newunit=urep, file=dir//'/bad.rep'//rank_suffix(rank), status='replace')
        open (newunit=uerr, file=dir//'/bad.err'//rank_suffix(rank), status='replace')
        args = [character(len=4096) :: dir//'/bad.nml', '--out', dir//'/bad']
        call run_dist_driver(args, MPI_COMM_WORLD, code, urep, uerr)
        close (urep); close (uerr)
        if (code /= 1) then
            msg = 'exit status '//fmt_int(code)//' (expected 1: input errors)'; return
        end if
        if (rank == 0) then
            e = slurp_file(dir//'/bad.err0')
            do k = 1, size(expect)
                if (index(e, trim(expect(k))) == 0) then
                    msg = 'no error naming '//trim(expect(k))//' in: '//e; return
                end if
            end do
            if (index(e, "'ok1'") > 0 .or. index(e, "'ok2'") > 0) then
                msg = 'a supported case reported an error: '//e; return
            end if
            if (index(slurp_file(dir//'/bad/ok2.json'), '"status": "converged"') == 0) then
                msg = 'the case after the errors was not solved'; return
            end if
        end if
        args = [character(len=4096) :: dir//'/bad.nml', '--bogus']
        open (newunit=uerr, file=dir//'/bad2.err'//rank_suffix(rank), status='replace')
        call run_dist_driver(args, MPI_COMM_WORLD, code, urep, uerr)
        close (uerr)
        if (code /= 1) msg = 'unknown argument: exit status '//fmt_int(code)//' (expected 1)'
    end subroutine test_unsupported

    subroutine write_cases(path)
        character(len=*), intent(in) :: path
        integer :: u
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') "&case name = 'dh_a', title = 'Hertz, approach' /"
        write (u, '(a)') "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
        write (u, '(a)') "&grid nx = 40, ny = 35, xmin = -2.0, xmax = 2.0, ymin = -1.6, ymax = 1.6 /"
        write (u, '(a)') "&geometry kind = 'quadratic', rx = 30.0, ry = 20.0 /"
        write (u, '(a)') "&normal approach = 0.03 /"
        write (u, '(a)') "&solver tol = 1.0e-10 /"
        write (u, '(a)') "&case name = 'dh_f', title = 'Hertz, force' /"
        write (u, '(a)') "&normal fn = 600.0 /"
        write (u, '(a)') "&output table_format = 'both' /"
        write (u, '(a)') "&case name = 'dw_p', title = 'periodic wavy cell, force' /"
        write (u, '(a)') "&grid periodic = .true., nx = 32, ny = 32, xmin = -1.0, xmax = 1.0, ymin = -1.0, ymax = 1.0 /"
        write (u, '(a)') "&geometry kind = 'wavy', amplitude = 2.0e-3, wavelength_x = 2.0, wavelength_y = 2.0 /"
        write (u, '(a)') "&normal fn = 200.0 /"
        close (u)
    end subroutine write_cases

    !> The two element tables: same header and rows; ix, iy, x, y and status as the same
    !! text, pn to 1e−8 of its largest value, gap to 1e−8 of the largest |gap|.
    subroutine compare_tables(pa, pb, msg)
        character(len=*), intent(in) :: pa, pb
        character(len=:), allocatable, intent(inout) :: msg
        integer :: ua, ub, ios_a, ios_b, n
        character(len=512) :: la, lb
        real(dp), allocatable :: va(:, :), vb(:, :)
        real(dp) :: pscale, gscale
        open (newunit=ua, file=pa, status='old', action='read', iostat=ios_a)
        open (newunit=ub, file=pb, status='old', action='read', iostat=ios_b)
        if (ios_a /= 0 .or. ios_b /= 0) then
            msg = 'a table is missing'; return
        end if
        read (ua, '(a)') la; read (ub, '(a)') lb
        if (la /= lb) then
            msg = 'headers differ'; return
        end if
        allocate (va(2, 0), vb(2, 0))
        n = 0
        do
            read (ua, '(a)', iostat=ios_a) la
            read (ub, '(a)', iostat=ios_b) lb
            if (ios_a /= 0 .or. ios_b /= 0) exit
            n = n + 1
            if (field_prefix(la) /= field_prefix(lb)) then
                msg = 'row '//fmt_int(n)//' differs in ix, iy, x, y or status: '//trim(la)//' | '//trim(lb); return
            end if
            va = reshape([va, pn_gap(la)], [2, n]); vb = reshape([vb, pn_gap(lb)], [2, n])
        end do
        close (ua); close (ub)
        if (ios_a == 0 .or. ios_b == 0) then
            msg = 'row counts differ'; return
        end if
        if (n == 0) then
            msg = 'empty table'; return
        end if
        pscale = maxval(abs(va(1, :))); gscale = maxval(abs(va(2, :)))
        if (maxval(abs(va(1, :) - vb(1, :))) > 1e-8_dp*pscale .or. maxval(abs(va(2, :) - vb(2, :))) > 1e-8_dp*gscale) &
            msg = 'pressures or gaps differ beyond 1e-8'
    end subroutine compare_tables

    !> Two `.npy` element tables: the same size and header, every record's ix, iy, x, y and
    !! status bytes identical, pn to 1e−8 of its largest value.
    subroutine compare_npy(a, b, msg)
        character(len=*), intent(in) :: a, b
        character(len=:), allocatable, intent(inout) :: msg
        integer, parameter :: rec = 73
        integer :: h, n, k, p
        real(dp), allocatable :: pa(:), pb(:)
        if (len(a) /= len(b) .or. len(a) < 12) then
            msg = 'sizes differ ('//fmt_int(len(a))//' and '//fmt_int(len(b))//' bytes)'; return
        end if
        h = 10 + iachar(a(9:9)) + 256*iachar(a(10:10))
        if (a(1:h) /= b(1:h)) then
            msg = 'headers differ'; return
        end if
        n = (len(a) - h)/rec
        if (n < 1 .or. h + n*rec /= len(a)) then
            msg = 'not a whole number of records'; return
        end if
        allocate (pa(n), pb(n))
        do k = 1, n
            p = h + (k - 1)*rec
            if (a(p + 1:p + 25) /= b(p + 1:p + 25)) then
                msg = 'record '//fmt_int(k)//': ix, iy, x, y or status differ'; return
            end if
            pa(k) = transfer(a(p + 26:p + 33), 1.0_dp); pb(k) = transfer(b(p + 26:p + 33), 1.0_dp)
        end do
        if (maxval(abs(pa - pb)) > 1e-8_dp*maxval(abs(pa))) msg = 'pressures differ beyond 1e-8'
    end subroutine compare_npy

    !> ix,iy,x,y,status of a table row (the text up to the 5th comma).
    function field_prefix(line) result(p)
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: p
        integer :: i, c
        c = 0
        do i = 1, len_trim(line)
            if (line(i:i) == ',') c = c + 1
            if (c == 5) exit
        end do
        p = line(1:i)
    end function field_prefix

    !> pn (6th field) and gap (11th) of a table row.
    function pn_gap(line) result(v)
        character(len=*), intent(in) :: line
        real(dp) :: v(2)
        character(len=len(line)) :: t
        real(dp) :: f(9)
        integer :: i1, i2, c
        t = line
        c = index(t, ',E,') + index(t, ',A,') + index(t, ',S,')
        t(c + 1:c + 1) = '0'
        read (t, *) i1, i2, f(1), f(2), f(3), f(4), f(5), f(6), f(7), f(8), f(9)
        v = [f(4), f(9)]
    end function pn_gap

    !> The number after `"key": ` in a JSON text (huge when absent).
    real(dp) function json_num(text, key) result(v)
        character(len=*), intent(in) :: text, key
        integer :: i, j, ios
        v = huge(1.0_dp)
        i = index(text, '"'//key//'": ')
        if (i == 0) return
        i = i + len(key) + 4
        j = scan(text(i:), ','//new_line('a'))
        if (j == 0) return
        read (text(i:i + j - 2), *, iostat=ios) v
        if (ios /= 0) v = huge(1.0_dp)
    end function json_num

    logical function close_to(a, b, rel)
        real(dp), intent(in) :: a, b, rel
        close_to = abs(a - b) <= rel*max(abs(a), abs(b)) .and. abs(b) < huge(1.0_dp)
    end function close_to

    function rank_suffix(rank) result(s)
        integer, intent(in) :: rank
        character(len=:), allocatable :: s
        s = fmt_int(rank)
    end function rank_suffix

    !> The distributed driver on `args` (collective), its report and errors in
    !! dir/TAG.rep<rank> and dir/TAG.err<rank>.
    subroutine run_dist(args, tag, code)
        character(len=*), intent(in) :: args(:), tag
        integer, intent(out) :: code
        integer :: rank, ierr, urep, uerr
        call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
        open (newunit=urep, file=dir//'/'//tag//'.rep'//rank_suffix(rank), status='replace')
        open (newunit=uerr, file=dir//'/'//tag//'.err'//rank_suffix(rank), status='replace')
        call run_dist_driver(args, MPI_COMM_WORLD, code, urep, uerr)
        close (urep); close (uerr)
    end subroutine run_dist

end module fcm_dist_tests
