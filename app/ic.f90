!> `fastcontact-ic MODEL.nml --out FILE [--contact CFILE] [--force] [--compare] [--analytic]`
!!
!! Computes one body's influence coefficients with CalculiX (thesis ch. 5) for the contact
!! grid of MODEL.nml (`&material g1, nu1`, `&grid`, `&fem`) and writes them to FILE in the
!! fastcontact format (doc/ic_file_format.md).  When FILE exists and holds the same model
!! (hash of the parameters in its header) nothing is recomputed.  `--contact CFILE` also
!! writes the combined coefficients in CONTACT's format (body 2: the same body, or the
!! half-space `&material g2, nu2` when g2 is given; g2 >= 1e29: rigid).  `--compare`
!! prints the relative deviation of A^zz at the origin and along the axes from the
!! half-space values (thesis eq. 5.12).  `--analytic` writes the half-space body's own
!! coefficients (G = g1, ν = nu1; no finite elements, no `&fem` needed): a reference file
!! to check a pipeline against, whose solutions equal the half-space's.
program fastcontact_ic
    use fc_kinds, only: dp, msg_len
    use fc_fem_mesh, only: fem_defaults
    use fc_fem_input, only: fc_fem_model, read_fem_model
    use fc_fem_ic, only: compute_fem_ic, fc_fem_info, fem_model_hash
    use fc_icfile
    use fc_icfile_contact, only: write_contact_file
    implicit none
    type(fc_fem_model) :: m
    type(fc_ic_set) :: set, other, comb, ana
    type(fc_fem_info) :: info
    character(len=1024) :: arg, model_path, out_path, contact_path
    character(len=msg_len) :: errmsg
    integer :: i, stat, n
    logical :: force, compare, exists, cached, analytic
    real(dp) :: dx, dy
    model_path = ''; out_path = ''; contact_path = ''; force = .false.; compare = .false.; analytic = .false.
    n = command_argument_count()
    i = 1
    do while (i <= n)
        call get_command_argument(i, arg)
        select case (trim(arg))
        case ('--out', '--contact')
            if (i == n) call fail('option '//trim(arg)//' needs a file name')
            i = i + 1
            if (trim(arg) == '--out') then
                call get_command_argument(i, out_path)
            else
                call get_command_argument(i, contact_path)
            end if
        case ('--force'); force = .true.
        case ('--compare'); compare = .true.
        case ('--analytic'); analytic = .true.
        case ('-h', '--help')
            write (*, '(a)') 'usage: fastcontact-ic MODEL.nml --out FILE [--contact CFILE] [--force] [--compare] [--analytic]'
            stop
        case default
            if (arg(1:1) == '-') call fail('unknown option '//trim(arg))
            if (len_trim(model_path) > 0) call fail('more than one model file given')
            model_path = arg
        end select
        i = i + 1
    end do
    if (len_trim(model_path) == 0 .or. len_trim(out_path) == 0) &
        call fail('usage: fastcontact-ic MODEL.nml --out FILE [--contact CFILE] [--force] [--compare] [--analytic]')
    call read_fem_model(model_path, m, stat, errmsg)
    if (stat /= 0) call fail(errmsg)
    dx = (m%xmax - m%xmin)/m%nx; dy = (m%ymax - m%ymin)/m%ny
    if (analytic) then
        ! the half-space body on the offsets a computed set has (0 … nx, 0 … ny)
        call analytic_body_set(m%g1, m%nu1, dx, dy, m%nx, m%ny, set, stat, errmsg)
        if (stat /= 0) call fail(errmsg)
        call write_ic_file(out_path, set, stat, errmsg)
        if (stat /= 0) call fail(errmsg)
        write (*, '(2a)') 'fastcontact-ic: wrote (analytic half-space body) ', trim(out_path)
    else
        call fem_defaults(m%fem, m%nx, m%ny, dx, dy)
        write (*, '(3a,i0,3a,es10.3,4(a,g0.4))') 'fastcontact-ic: model ', trim(m%fem%mesh), ' order ', m%fem%order, &
            ' ('//trim(m%fem%integration)//' integration), load ', trim(m%fem%load), ', L = ', &
            m%fem%l_over_hc*max(dx, dy), ' mm, L/h_c = ', m%fem%l_over_hc, &
            ', l/h_c = ', m%fem%cube_over_hc, ', h_c/h_s = ', m%fem%hc_over_hs, ', f = ', m%fem%stretch
        call fe_coefficients()
    end if
    if (compare .or. len_trim(contact_path) > 0) then
        call analytic_body_set(m%g1, m%nu1, dx, dy, set%mx, set%my, ana, stat, errmsg)
        if (stat /= 0) call fail(errmsg)
    end if
    if (compare) call print_comparison()
    if (len_trim(contact_path) > 0) then
        if (m%g2 == 0) then
            other = set
        else
            call analytic_body_set(m%g2, m%nu2, dx, dy, set%mx, set%my, other, stat, errmsg)
            if (stat /= 0) call fail(errmsg)
        end if
        call combine_ic_sets(set, other, comb, stat, errmsg)
        if (stat /= 0) call fail(errmsg)
        call write_contact_file(contact_path, comb, stat, errmsg)
        if (stat /= 0) call fail(errmsg)
        write (*, '(2a)') 'fastcontact-ic: wrote (CONTACT format, combined) ', trim(contact_path)
    end if
contains
    subroutine fe_coefficients()
        cached = .false.
        inquire (file=out_path, exist=exists)
        if (exists .and. .not. force) then
            if (is_fastcontact_ic_file(out_path)) then
                call read_ic_file(out_path, set, stat, errmsg)
                cached = stat == 0 .and. set%hash == fem_model_hash(m%fem, m%g1, m%nu1, m%nx, m%ny, dx, dy)
            end if
        end if
        if (cached) then
            write (*, '(3a)') 'fastcontact-ic: ', trim(out_path), ' is up to date (same model hash), not recomputed'
            return
        end if
        call compute_fem_ic(m%fem, m%g1, m%nu1, m%nx, m%ny, dx, dy, set, info, stat, errmsg)
        if (stat /= 0) call fail(errmsg)
        call validate_ic_set(set, 'computed coefficients', stat, errmsg)
        if (stat /= 0) call fail(errmsg)
        call write_ic_file(out_path, set, stat, errmsg)
        if (stat /= 0) call fail(errmsg)
        write (*, '(a,i0,a,i0,a,i0,a,f0.2,a,f0.2,a,es9.2)') 'fastcontact-ic: ', info%elements, ' elements, ', info%dofs, &
            ' dofs, ', info%runs, ' CalculiX runs, cpu ', info%ccx_cpu, ' s, wall ', info%ccx_wall, &
            ' s; xy/yx reciprocity ', info%reciprocity
        write (*, '(2a)') 'fastcontact-ic: wrote ', trim(out_path)
    end subroutine fe_coefficients
    subroutine print_comparison()
        integer :: k
        write (*, '(a)') '  offset    FE A^zz          half-space       rel.dev   | A^xx rel.dev  A^xy rel.dev  A^zx rel.dev'
        do k = 0, min(set%mx, 8)
            write (*, '(i4,a,2es17.9,es11.3,a,3es14.3)') k, ',0 ', set%a(k, 0, 3, 3), ana%a(k, 0, 3, 3), &
                rel(set%a(k, 0, 3, 3), ana%a(k, 0, 3, 3)), ' |', rel(set%a(k, 0, 1, 1), ana%a(k, 0, 1, 1)), &
                rel(set%a(k, min(k, set%my), 1, 2), ana%a(k, min(k, set%my), 1, 2)), rel(set%a(k, 0, 3, 1), ana%a(k, 0, 3, 1))
        end do
        k = set%mx
        write (*, '(i4,a,2es17.9,es11.3)') k, ',0 ', set%a(k, 0, 3, 3), ana%a(k, 0, 3, 3), &
            rel(set%a(k, 0, 3, 3), ana%a(k, 0, 3, 3))
    end subroutine print_comparison
    pure real(dp) function rel(a, b)
        real(dp), intent(in) :: a, b
        rel = 0
        if (b /= 0) rel = (a - b)/abs(b)
    end function rel
    subroutine fail(msg)
        character(len=*), intent(in) :: msg
        write (*, '(2a)') 'fastcontact-ic: error: ', trim(msg)
        stop 2
    end subroutine fail
end program fastcontact_ic
