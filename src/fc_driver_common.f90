!> What the serial driver ([[fc_driver]]) and the MPI package's drivers share: their exit
!! codes, their command line, the report of a case's input error, the output files of a
!! case (its directory, stale outputs removed, `mkdir -p`) and the analytic Hertz values
!! printed beside a quadratic case.
module fc_driver_common
    use fc_kinds, only: dp
    use fc_errors, only: FC_ERR_IO
    use fc_hertz, only: hertz_from_approach, hertz_from_force
    use fc_influence, only: fc_material
    use fc_input, only: fc_case_input
    use fc_output, only: fc_case_summary
    use fc_driver_resume, only: parse_part
    implicit none
    private

    integer, parameter, public :: EXIT_OK = 0           !! all cases converged
    integer, parameter, public :: EXIT_INPUT_ERROR = 1  !! bad command line, file or case input
    integer, parameter, public :: EXIT_NOT_CONVERGED = 2 !! a solver did not converge / diverged
    !> added to a case status (0, 2) in `run_driver`'s `statuses` when `--resume` skipped the
    !! case (done in an earlier run)
    integer, parameter, public :: STATUS_SKIPPED = 10
    integer, parameter, public :: case_name_len = 64       !! length of `&case name` (output file stem)
    integer, parameter, public :: max_selected_cases = 10000 !! names given with `--case`, at most

    public :: make_directory, remove_file, parse_driver_arguments, write_case_error
    public :: case_output_dir, remove_case_outputs, hertz_reference

contains

    !> The output directory of a case: `out_dir` (the command line's --out) when present,
    !! else the case's `&output dir`.
    function case_output_dir(state, out_dir) result(d)
        type(fc_case_input), intent(in) :: state
        character(len=*), intent(in), optional :: out_dir
        character(len=:), allocatable :: d
        if (present(out_dir)) then
            d = out_dir
        else
            d = trim(state%dir)
        end if
    end function case_output_dir

    !> The analytic Hertz solution beside a quadratic case's numbers (both radii given): for
    !! its prescribed force or approach, with the combined material `mat`.
    subroutine hertz_reference(s, state, mat)
        type(fc_case_summary), intent(inout) :: s
        type(fc_case_input), intent(in) :: state
        type(fc_material), intent(in) :: mat
        real(dp) :: ca, cb
        if (.not. (state%kind == 'quadratic' .and. state%rx > 0 .and. state%ry > 0)) return
        ca = 0.5_dp/state%rx; cb = 0.5_dp/state%ry
        s%has_hertz = .true.
        if (state%force_prescribed) then
            s%hertz = hertz_from_force(ca, cb, mat%g/(1 - mat%nu), state%fn)
        else
            s%hertz = hertz_from_approach(ca, cb, mat%g/(1 - mat%nu), state%approach)
        end if
    end subroutine hertz_reference

    !> Remove a case's summary and table from `dir` (stale outputs of a case that failed).
    subroutine remove_case_outputs(dir, name)
        character(len=*), intent(in) :: dir, name
        call remove_file(dir//'/'//trim(name)//'.json')
        call remove_file(dir//'/'//trim(name)//'.csv')
    end subroutine remove_case_outputs

    !> The drivers' command line: `CASES.nml [--out DIR | --out=DIR] | --help | --version`,
    !! and, for a caller that passes `selected`, `--case NAME[,NAME…]` (repeatable).
    !! `action` is 'run' (case_file and, when given, out_dir set), 'help', 'version' or
    !! 'error' (`errtext`: the message lines, prefixed by `prog`, with `usage` where it helps).
    subroutine parse_driver_arguments(args, prog, usage, case_file, out_dir, action, errtext, selected, resume, part)
        character(len=*), intent(in) :: args(:)
        character(len=*), intent(in) :: prog    !! program name for the messages
        character(len=*), intent(in) :: usage   !! usage text
        character(len=:), allocatable, intent(out) :: case_file, out_dir, action, errtext
        !> the case names given with `--case` (allocated only when some were given); without
        !! this argument `--case` is an unexpected argument
        character(len=case_name_len), allocatable, intent(out), optional :: selected(:)
        !> `--resume` given (without this argument it is an unexpected argument)
        logical, intent(out), optional :: resume
        !> `--part K/N` as [K, N] ([0, 0] when not given; without this argument `--part` is
        !! an unexpected argument)
        integer, intent(out), optional :: part(2)
        integer :: i, stat_part
        character(len=:), allocatable :: msg
        action = 'run'; errtext = ''
        if (present(resume)) resume = .false.
        if (present(part)) part = 0
        i = 1
        do while (i <= size(args))
            select case (trim(args(i)))
            case ('-h', '--help')
                action = 'help'; return
            case ('-V', '--version')
                action = 'version'; return
            case ('--check')
                action = 'check'
            case ('--out', '-o')
                if (i == size(args)) then
                    call fail(prog//': --out needs a directory'//new_line('a')//usage); return
                end if
                out_dir = trim(args(i + 1)); i = i + 1
            case default
                if (len_trim(args(i)) > 6) then
                    if (args(i)(1:6) == '--out=') then
                        out_dir = trim(args(i)(7:)); i = i + 1; cycle
                    end if
                end if
                if (present(resume)) then
                    if (trim(args(i)) == '--resume') then
                        resume = .true.; i = i + 1; cycle
                    end if
                end if
                if (present(part)) then
                    if (trim(args(i)) == '--part' .or. index(args(i), '--part=') == 1) then
                        if (trim(args(i)) == '--part') then
                            if (i == size(args)) then
                                call fail(prog//': --part needs K/N'//new_line('a')//usage); return
                            end if
                            i = i + 1
                            call parse_part(trim(args(i)), part(1), part(2), stat_part, msg)
                        else
                            call parse_part(trim(args(i)(8:)), part(1), part(2), stat_part, msg)
                        end if
                        if (stat_part /= 0) then
                            call fail(prog//': '//msg); return
                        end if
                        i = i + 1; cycle
                    end if
                end if
                if (present(selected)) then
                    if (trim(args(i)) == '--case') then
                        if (i == size(args)) then
                            call fail(prog//': --case needs a case name'//new_line('a')//usage); return
                        end if
                        if (.not. add_names(trim(args(i + 1)))) return
                        i = i + 2; cycle
                    else if (len_trim(args(i)) > 7) then
                        if (args(i)(1:7) == '--case=') then
                            if (.not. add_names(trim(args(i)(8:)))) return
                            i = i + 1; cycle
                        end if
                    end if
                end if
                if (args(i)(1:1) == '-' .or. allocated(case_file)) then
                    call fail(prog//": unexpected argument '"//trim(args(i))//"'"//new_line('a')//usage); return
                end if
                case_file = trim(args(i))
            end select
            i = i + 1
        end do
        if (.not. allocated(case_file)) then
            call fail(prog//': no case file given'//new_line('a')//usage); return
        end if
        if (allocated(out_dir)) then
            if (len_trim(out_dir) == 0) call fail(prog//': --out needs a non-empty directory')
        end if
    contains
        subroutine fail(text)
            character(len=*), intent(in) :: text
            action = 'error'; errtext = text
        end subroutine fail

        !> Append the comma-separated names of `list` to `selected`; false (and the error
        !! set) for an empty or over-long name or too many names.
        logical function add_names(list) result(ok)
            character(len=*), intent(in) :: list
            character(len=256) :: buf
            integer :: a, b
            ok = .false.
            if (.not. allocated(selected)) allocate (selected(0))
            a = 1
            do
                b = index(list(a:), ',')
                b = merge(len(list) + 1, a + b - 1, b == 0)
                if (b == a) then
                    call fail(prog//": --case '"//list//"': empty case name"); return
                end if
                if (b - a > case_name_len) then
                    write (buf, '(a,i0,a)') ": --case '"//list(a:min(b - 1, a + 79))//"': a case name has at most ", &
                        case_name_len, ' characters'
                    call fail(prog//trim(buf)); return
                end if
                if (size(selected) >= max_selected_cases) then
                    write (buf, '(a,i0,a)') ': --case: at most ', max_selected_cases, ' case names'
                    call fail(prog//trim(buf)); return
                end if
                selected = [character(len=case_name_len) :: selected, list(a:b - 1)]
                if (b > len(list)) exit
                a = b + 1
            end do
            ok = .true.
        end function add_names
    end subroutine parse_driver_arguments

    !> An input error of case `k` (at `line` of the file): the message on `err` and the
    !! report's error line on `rep`.
    subroutine write_case_error(rep, err, prog, k, line, name, errmsg)
        integer, intent(in) :: rep, err, k, line
        character(len=*), intent(in) :: prog, name, errmsg
        write (err, '(a,i0,a,i0,a)') prog//': case ', k, " '"//trim(name)//"' (line ", line, '): '//trim(errmsg)
        write (rep, '(a)') ' case '//trim(name)//'   *** ERROR *** '//trim(errmsg)
        write (rep, '(a)') ''
    end subroutine write_case_error

    !> mkdir -p DIR by the C library's mkdir (each parent in turn; existing ones are
    !! fine), not by a shell: a child process cost every run about 2 ms.  stat ≠ 0 when DIR
    !! is not a directory afterwards.
    subroutine make_directory(dir, stat)
        use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
        character(len=*), intent(in) :: dir
        integer, intent(out) :: stat
        interface
            integer(c_int) function c_mkdir(path, mode) bind(C, name='mkdir')
                import :: c_int, c_char
                character(kind=c_char), intent(in) :: path(*)
                integer(c_int), value :: mode
            end function c_mkdir
        end interface
        integer(c_int), parameter :: mode = int(o'777', c_int)   ! less the umask, as mkdir(1)
        integer(c_int) :: rc
        integer :: i, n
        logical :: exists
        n = len_trim(dir)
        stat = FC_ERR_IO
        if (n == 0) return
        do i = 2, n
            if (dir(i:i) == '/' .and. dir(i - 1:i - 1) /= '/') rc = c_mkdir(dir(1:i - 1)//c_null_char, mode)
        end do
        rc = c_mkdir(dir(1:n)//c_null_char, mode)
        inquire (file=dir(1:n)//'/.', exist=exists)
        if (exists) stat = 0
    end subroutine make_directory

    !> Delete a file if it exists.
    subroutine remove_file(path)
        character(len=*), intent(in) :: path
        logical :: exists
        integer :: u, ios
        inquire (file=path, exist=exists)
        if (.not. exists) return
        open (newunit=u, file=path, status='old', iostat=ios)
        if (ios == 0) close (u, status='delete', iostat=ios)
    end subroutine remove_file

end module fc_driver_common
