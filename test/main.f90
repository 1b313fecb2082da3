!> Test runner: `fpm test` runs every suite; `fpm test -- SUITE [TEST]` runs one.
!! Ends with the line `N passed, N failed` and a non-zero exit status on any failure.
program tester
    use fc_testing, only: run_suite, unittest_type
    use test_contact, only: collect_contact
    use test_influence, only: collect_influence
    use test_hertz, only: collect_hertz
    use test_normal, only: collect_normal
    use test_tangential, only: collect_tangential
    use test_driver, only: collect_driver
    use test_fmg, only: collect_fmg
    use test_mg2d, only: collect_mg2d
    use test_auto, only: collect_auto
    use test_stability, only: collect_stability
    use test_legacy, only: collect_legacy
    use test_table_io, only: collect_table_io
    use test_rolling, only: collect_rolling
    use test_operators, only: collect_operators
    use test_fem_ic, only: collect_fem_ic
    use test_parallel, only: collect_parallel
    use test_periodic, only: collect_periodic
    use test_api_fuzz, only: collect_api_fuzz
    use test_reliability, only: collect_reliability
    use test_readme, only: collect_readme
    use test_summary, only: collect_summary
    use test_batch, only: collect_batch
    implicit none
    character(len=64) :: suite, only
    integer :: npass, nfail
    type(unittest_type), allocatable :: tests(:)
    suite = ''; only = ''
    if (command_argument_count() >= 1) call get_command_argument(1, suite)
    if (command_argument_count() >= 2) call get_command_argument(2, only)
    npass = 0; nfail = 0
    if (want('influence')) then
        call collect_influence(tests); call run_suite('influence', tests, only, npass, nfail)
    end if
    if (want('hertz')) then
        call collect_hertz(tests); call run_suite('hertz', tests, only, npass, nfail)
    end if
    if (want('normal')) then
        call collect_normal(tests); call run_suite('normal', tests, only, npass, nfail)
    end if
    if (want('tangential')) then
        call collect_tangential(tests); call run_suite('tangential', tests, only, npass, nfail)
    end if
    if (want('driver')) then
        call collect_driver(tests); call run_suite('driver', tests, only, npass, nfail)
    end if
    if (want('fmg')) then
        call collect_fmg(tests); call run_suite('fmg', tests, only, npass, nfail)
    end if
    if (want('mg2d')) then
        call collect_mg2d(tests); call run_suite('mg2d', tests, only, npass, nfail)
    end if
    if (want('legacy')) then
        call collect_legacy(tests); call run_suite('legacy', tests, only, npass, nfail)
    end if
    if (want('api_fuzz')) then
        call collect_api_fuzz(tests); call run_suite('api_fuzz', tests, only, npass, nfail)
    end if
    if (want('periodic')) then
        call collect_periodic(tests); call run_suite('periodic', tests, only, npass, nfail)
    end if
    if (want('reliability')) then
        call collect_reliability(tests); call run_suite('reliability', tests, only, npass, nfail)
    end if
    if (want('summary')) then
        call collect_summary(tests); call run_suite('summary', tests, only, npass, nfail)
    end if
    if (want('batch')) then
        call collect_batch(tests); call run_suite('batch', tests, only, npass, nfail)
    end if
    if (want('readme')) then
        call collect_readme(tests); call run_suite('readme', tests, only, npass, nfail)
    end if
    if (want('stability')) then
        call collect_stability(tests); call run_suite('stability', tests, only, npass, nfail)
    end if
    if (want('contact')) then
        call collect_contact(tests); call run_suite('contact', tests, only, npass, nfail)
    end if
    if (want('auto')) then
        call collect_auto(tests); call run_suite('auto', tests, only, npass, nfail)
    end if
    if (want('table_io')) then
        call collect_table_io(tests); call run_suite('table_io', tests, only, npass, nfail)
    end if
    if (want('rolling')) then
        call collect_rolling(tests); call run_suite('rolling', tests, only, npass, nfail)
    end if
    if (want('operators')) then
        call collect_operators(tests); call run_suite('operators', tests, only, npass, nfail)
    end if
    if (want('fem_ic')) then
        call collect_fem_ic(tests); call run_suite('fem_ic', tests, only, npass, nfail)
    end if
    if (want('parallel')) then
        call collect_parallel(tests); call run_suite('parallel', tests, only, npass, nfail)
    end if
    write (*, '(i0,a,i0,a)') npass, ' passed, ', nfail, ' failed'
    if (nfail > 0 .or. npass == 0) stop 1   ! non-zero exit status (no backtrace, unlike error stop)
contains
    logical function want(name)
        character(len=*), intent(in) :: name
        want = len_trim(suite) == 0 .or. trim(suite) == name
    end function want
end program tester
