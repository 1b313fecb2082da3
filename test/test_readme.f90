!> The README's library example, compiled against the `fastcontact` facade and run.
!!
!! `readme_example` holds the statements of the README's `program hertz_demo` verbatim
!! (declarations and body); `readme_in_sync` reads README.md and fails when a statement of
!! the README's example is missing from this file, so the two cannot drift apart.
module test_readme
    use fc_testing, only: error_type, unittest_type, new_unittest, check, file_text => file_lines
    implicit none
    private
    public :: collect_readme

    character(len=*), parameter :: this_file = 'test/test_readme.f90'

contains

    subroutine collect_readme(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)
        tests = [new_unittest('library_example_runs', library_example_runs), &
                 new_unittest('readme_in_sync', readme_in_sync)]
    end subroutine collect_readme

    !> Hertz Test I at 128² with the README's code: Fn within 0.1 % of the analytic 82004 N
    !! (the discretisation error at 128² is 1e-4, doc/bench_normal.csv), converged, and the
    !! iteration count the README advertises (7–11; bound 17).
    subroutine library_example_runs(error)
        type(error_type), allocatable, intent(out) :: error
        real(kind(1.0d0)) :: fn
        integer :: ncon, iterations, status
        call readme_example(fn, ncon, iterations, status)
        call check(error, fn, 82004.0d0, 'README example: Fn against Hertz', rel=1.0d-3)
        call check(error, status == 0, 'README example: status not converged')
        call check(error, iterations >= 5 .and. iterations <= 17, 'README example: iterations outside 5-17')
        call check(error, ncon > 1000 .and. ncon < 128*128/2, 'README example: implausible contact element count')
    end subroutine library_example_runs

    !> The README's program as a subroutine: same statements, results handed back.
    subroutine readme_example(fn, ncon, iterations, status)
    use fastcontact
    implicit none
    real(dp), intent(out) :: fn
    integer, intent(out) :: ncon, iterations, status
    type(fc_problem) :: prob
    type(fc_contact_result) :: res
    integer :: stat
    character(len=msg_len) :: errmsg
    call set_material(prob, 82000.0_dp, 82000.0_dp, 0.28_dp, 0.28_dp, stat, errmsg)
    call make_grid(prob%grid, 128, 128, -10.0_dp, 10.0_dp, -6.0_dp, 6.0_dp, stat, errmsg)
    prob%h0 = quadratic_gap(prob%grid, 300.0_dp, 163.0_dp)   ! Hertz Test I: rx = 300, ry = 163 mm
    prob%load%normal%approach = 0.1091_dp                     ! prescribed approach [mm]
    prob%settings%normal%solver = 'bccg'                      ! or 'norm', 'fmg'
    call solve(prob, res, stat, errmsg)
    if (stat /= 0) error stop trim(errmsg)
    print '(a,f0.1,a,i0,a,i0,2a)', 'Fn = ', res%normal%fn, ' N, contact elements: ', res%normal%ncon, &
        ', iterations: ', res%normal%iterations, ', status: ', status_name(res%status)
        fn = res%normal%fn; ncon = res%normal%ncon; iterations = res%normal%iterations; status = res%status
    call prob%destroy()                                       ! release the FFT plans
    end subroutine readme_example

    !> Every statement line of the README's ```fortran block (other than program/end
    !! program) appears verbatim in this file.
    subroutine readme_in_sync(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: src
        character(len=512) :: line
        integer :: u, ios, nlines
        logical :: in_block
        src = file_text(this_file)
        call check(error, len(src) > 0, 'cannot read '//this_file)
        open (newunit=u, file='README.md', status='old', action='read', iostat=ios)
        call check(error, ios == 0, 'cannot open README.md')
        if (allocated(error)) return
        in_block = .false.; nlines = 0
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (line(1:10) == '```fortran') then
                in_block = .true.; cycle
            end if
            if (.not. in_block) cycle
            if (line(1:3) == '```') exit
            if (index(line, 'program hertz_demo') > 0 .or. len_trim(line) == 0) cycle
            nlines = nlines + 1
            call check(error, index(src, trim(line)) > 0, 'README example line not in '//this_file//': '//trim(line))
        end do
        close (u)
        call check(error, nlines >= 10, 'README.md: the library example (```fortran block) was not found')
    end subroutine readme_in_sync

end module test_readme
