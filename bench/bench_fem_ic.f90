!> Benchmark of numerical influence coefficients (thesis ch. 5), results in doc/numerical_ic.md.
!!
!!   fastcontact-bench-fem-ic coef STRETCH [CSV]   §5.3: |A0 − F0|/|A0| (eq. 5.12) of A^zz against
!!        L/h_c for Mesh1/Mesh2, linear/quadratic (10×10 grid on [−4,4]², G = 82000, ν = 0.28),
!!        with CalculiX CPU time and degrees of freedom (normal load case only).
!!   fastcontact-bench-fem-ic contact N MESH F[:F_FAR] L_OVER_HC [CSV]   §5.4: the sphere
!!        (G = 200, ν = 0.42, R = 50, approach 0.02, [−1.2,1.2]², N×N grid): errors in Fz,
!!        pmax and contact area against Hertz and in Fx (w_x = 0.00817, μ = 0.4) against
!!        3.2216 N, with the half-space kernels and with FE coefficients of both bodies.
!! Rows are appended to CSV (default doc/bench_fem_ic_coef.csv, doc/bench_fem_ic_contact.csv).
program bench_fem_ic
    use fc_kinds, only: dp, msg_len, pi
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_fem_mesh, only: fc_fem_params
    use fc_fem_ic, only: compute_fem_ic, fc_fem_info
    use fc_icfile
    use fc_contact
    implicit none
    character(len=256) :: mode, arg, csv
    integer :: n
    real(dp) :: stretch
    mode = ''
    if (command_argument_count() >= 1) call get_command_argument(1, mode)
    select case (trim(mode))
    case ('coef')
        if (command_argument_count() < 2) call usage()
        call get_command_argument(2, arg); read (arg, *) stretch
        csv = 'doc/bench_fem_ic_coef.csv'
        if (command_argument_count() >= 3) call get_command_argument(3, csv)
        call bench_coef(stretch, csv)
    case ('contact')
        if (command_argument_count() < 5) call usage()
        call get_command_argument(2, arg); read (arg, *) n
        csv = 'doc/bench_fem_ic_contact.csv'
        if (command_argument_count() >= 6) call get_command_argument(6, csv)
        call bench_contact(n, csv)
    case default
        call usage()
    end select
contains

    subroutine usage()
        write (*, '(a)') 'usage: fastcontact-bench-fem-ic coef STRETCH [CSV] | contact N MESH STRETCH L_OVER_HC [CSV]'
        stop 2
    end subroutine usage

    !> §5.3: eq. 5.12 error of A^zz at the origin (normal load only).
    subroutine bench_coef(f, csv)
        real(dp), intent(in) :: f
        character(len=*), intent(in) :: csv
        type(fc_fem_params) :: p
        type(fc_ic_set) :: set, ana
        type(fc_fem_info) :: info
        integer :: stat, u, k, order, im
        character(len=msg_len) :: msg
        character(len=8), parameter :: meshes(2) = ['hex  ', 'prism']
        real(dp), parameter :: ratios(3) = [80.0_dp, 320.0_dp, 1280.0_dp]
        real(dp) :: h, err
        logical :: exists
        h = 0.8_dp
        call analytic_body_set(82000.0_dp, 0.28_dp, h, h, 10, 10, ana, stat, msg)
        inquire (file=csv, exist=exists)
        open (newunit=u, file=csv, position='append', action='write')
        if (.not. exists) write (u, '(a)') 'mesh,order,l_over_hc,stretch,hc_over_hs,elements,dofs,ccx_cpu_s,ccx_wall_s,err_origin'
        do im = 1, 2
            do order = 2, 1, -1
                do k = 1, 3
                    if (order == 1 .and. k == 3) cycle
                    p = fc_fem_params()
                    p%mesh = meshes(im); p%order = order; p%l_over_hc = ratios(k)
                    p%stretch = f
                    p%normal_only = .true.
                    call compute_fem_ic(p, 82000.0_dp, 0.28_dp, 10, 10, h, h, set, info, stat, msg)
                    if (stat /= 0) then
                        write (*, '(2a)') 'error: ', trim(msg); cycle
                    end if
                    err = abs(set%a(0, 0, 3, 3) - ana%a(0, 0, 3, 3))/ana%a(0, 0, 3, 3)
                    write (u, '(a,",",i0,",",f0.0,",",f0.2,",",f0.0,2(",",i0),2(",",f0.2),",",es10.3)') trim(p%mesh), &
                        p%order, p%l_over_hc, p%stretch, p%hc_over_hs, info%elements, info%dofs, info%ccx_cpu, &
                        info%ccx_wall, err
                    flush (u)
                    write (*, '(a,1x,i0,a,f0.0,a,i0,a,f0.1,a,es10.3)') trim(p%mesh), p%order, ' L/hc=', p%l_over_hc, &
                        ' dofs=', info%dofs, ' cpu=', info%ccx_cpu, ' err=', err
                end do
            end do
        end do
        close (u)
    end subroutine bench_coef

    !> §5.4 normal and tangential problem on an n×n grid.
    subroutine bench_contact(n, csv)
        integer, intent(in) :: n
        character(len=*), intent(in) :: csv
        type(fc_fem_params) :: p
        type(fc_ic_set) :: set, ic
        type(fc_fem_info) :: info
        type(fc_material) :: mat
        type(fc_contact_operators) :: ops_a, ops_f
        type(fc_contact_result) :: ra, rf
        integer :: stat, u
        character(len=msg_len) :: msg
        character(len=256) :: arg
        real(dp) :: h, ta, tf
        logical :: exists
        p = fc_fem_params()
        call get_command_argument(3, arg); p%mesh = trim(arg)
        call get_command_argument(4, arg)   ! f, or f:f_far
        if (index(arg, ':') > 0) then
            read (arg(:index(arg, ':') - 1), *) p%stretch; read (arg(index(arg, ':') + 1:), *) p%stretch_far
        else
            read (arg, *) p%stretch
        end if
        call get_command_argument(5, arg); read (arg, *) p%l_over_hc
        h = 2.4_dp/n
        call compute_fem_ic(p, 200.0_dp, 0.42_dp, n, n, h, h, set, info, stat, msg)
        if (stat /= 0) then
            write (*, '(2a)') 'error: ', trim(msg); stop 1
        end if
        mat%g1 = 200; mat%nu1 = 0.42_dp; mat%g2 = 200; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, msg)
        call combine_ic_sets(set, set, ic, stat, msg)
        call set_influence_coefficients(ops_f, ic, stat, msg)
        call sphere(ops_a, mat, n, ra, ta)
        call sphere(ops_f, mat, n, rf, tf)
        inquire (file=csv, exist=exists)
        open (newunit=u, file=csv, position='append', action='write')
        if (.not. exists) write (u, '(a)') 'grid,mesh,order,l_over_hc,L_mm,stretch,hc_over_hs,elements,dofs,ccx_cpu_s,'// &
            'solve_s,fz_err,pmax_err,area_err,fx_err,fz_err_halfspace,pmax_err_halfspace,area_err_halfspace,fx_err_halfspace'
        write (u, '(i0,",",a,",",i0,",",f0.0,",",f0.2,",",a,",",f0.0,2(",",i0),",",f0.2,",",f0.4,8(",",es10.3))') &
            n, trim(p%mesh), p%order, p%l_over_hc, info%domain, trim(stretch_text(p)), p%hc_over_hs, info%elements, info%dofs, &
            info%ccx_cpu, tf, errs(rf, h), errs(ra, h)
        close (u)
        write (*, '(a,i0,1x,a,a,f0.0,a,i0,a,f0.1,a,4es10.2,a,4es10.2)') 'grid ', n, trim(p%mesh), ' L/hc=', p%l_over_hc, &
            ' dofs=', info%dofs, ' ccx cpu=', info%ccx_cpu, ' FE errs (Fz pmax area Fx):', errs(rf, h), '  half-space:', errs(ra, h)
    end subroutine bench_contact

    !> The §5.4 sphere on an n×n grid through [[solve_contact]]; CPU seconds of the solve.
    subroutine sphere(ops, mat, n, res, seconds)
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_material), intent(in) :: mat
        integer, intent(in) :: n
        type(fc_contact_result), intent(out) :: res
        real(dp), intent(out) :: seconds
        type(fc_grid) :: grid
        type(fc_contact_loading) :: load
        type(fc_contact_settings) :: settings
        real(dp), allocatable :: h0(:, :)
        real(dp) :: c0, c1
        integer :: stat
        character(len=msg_len) :: msg
        call make_grid(grid, n, n, -1.2_dp, 1.2_dp, -1.2_dp, 1.2_dp, stat, msg)
        h0 = quadratic_gap(grid, 50.0_dp, 50.0_dp)
        load%problem = FC_PROBLEM_TANGENTIAL
        load%normal%approach = 0.02_dp
        load%tangential%mu = 0.4_dp; load%tangential%xi = -0.00817_dp
        settings%normal%solver = 'bccg'; settings%normal%tol = 1e-8_dp
        settings%tangential%tol = 1e-8_dp
        call cpu_time(c0)
        call solve_contact(ops, grid, mat, h0, load, settings, res, stat, msg)
        call cpu_time(c1)
        seconds = c1 - c0
        if (stat /= 0) then
            write (*, '(2a)') 'error: ', trim(msg); stop 1
        end if
    end subroutine sphere

    !> f, or f:f_far when the far-field factor differs.
    function stretch_text(p) result(t)
        type(fc_fem_params), intent(in) :: p
        character(len=24) :: t
        if (p%stretch_far /= p%stretch) then
            write (t, '(f0.2,":",f0.2)') p%stretch, p%stretch_far
        else
            write (t, '(f0.2)') p%stretch
        end if
    end function stretch_text

    !> Relative errors of Fz, pmax, contact area (Hertz) and Fx (3.2216 N, thesis §5.4.2).
    function errs(r, h) result(e)
        type(fc_contact_result), intent(in) :: r
        real(dp), intent(in) :: h
        real(dp) :: e(4)
        e(1) = r%normal%fn/9.1954_dp - 1
        e(2) = r%normal%pmax/4.3905_dp - 1
        e(3) = count(r%normal%pn > 0)*h*h/pi - 1
        e(4) = r%tangential%fx/3.2216_dp - 1
    end function errs

end program bench_fem_ic
