!> Benchmark of numerical influence coefficients (thesis ch. 5), results in doc/numerical_ic.md.
!!
!!   fastcontact-bench-fem-ic coef MESH STRETCH [CSV]   §5.3: |A0 − F0|/|A0| (eq. 5.12) of A^zz
!!        against L/h_c for one mesh (hex, tensor, prism), quadratic (reduced and full
!!        integration for hexahedra) and linear elements (10×10 grid on [−4,4]², G = 82000,
!!        ν = 0.28), with CalculiX CPU time and degrees of freedom (normal load case only).
!!   fastcontact-bench-fem-ic contact N MESH F[:F_FAR] L_OVER_HC [CSV [INTEGRATION]]   §5.4: the
!!        sphere (G = 200, ν = 0.42, R = 50, approach 0.02, [−1.2,1.2]², N×N grid): errors in
!!        Fz, pmax and contact area against Hertz and in Fx (w_x = 0.00817, μ = 0.4) against
!!        3.2216 N, with the half-space kernels and with FE coefficients of both bodies.
!!        F = 0 or L_OVER_HC = 0: the automatic value.
!!   fastcontact-bench-fem-ic decompose N MESH F[:F_FAR] L_OVER_HC [HC_OVER_HS [CUBE_OVER_HC]]
!!        where the error comes from (stdout only): FE/analytic − 1 at the top-surface nodes
!!        and cell centres, and contact errors with FE coefficients up to an offset radius and
!!        analytic ones beyond; FEM_INTEGRATION=full|reduced in the environment.
!! Rows are appended to CSV (default doc/bench_fem_ic_coef.csv, doc/bench_fem_ic_contact.csv).
program bench_fem_ic
    use fc_kinds, only: dp, msg_len, pi
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_fem_mesh, only: fc_fem_params
    use fc_fem_ic, only: compute_fem_ic, fc_fem_info, fc_fem_top, top_to_set
    use fc_fem_mesh, only: lattice_coord
    use fc_fem_shell, only: shell_surface_value
    use fc_influence, only: element_coefficient, IC_ZZ, IC_XX, IC_YY
    use fc_icfile
    use fc_contact
    implicit none
    character(len=256) :: mode, arg, csv
    integer :: n
    real(dp) :: stretch
    real(dp) :: cell_h = 0   !! contact cell size of the decompose mode [mm]
    mode = ''
    if (command_argument_count() >= 1) call get_command_argument(1, mode)
    select case (trim(mode))
    case ('coef')
        if (command_argument_count() < 3) call usage()
        call get_command_argument(3, arg); read (arg, *) stretch
        csv = 'doc/bench_fem_ic_coef.csv'
        if (command_argument_count() >= 4) call get_command_argument(4, csv)
        call get_command_argument(2, arg)
        call bench_coef(trim(arg), stretch, csv)
    case ('contact')
        if (command_argument_count() < 5) call usage()
        call get_command_argument(2, arg); read (arg, *) n
        csv = 'doc/bench_fem_ic_contact.csv'
        if (command_argument_count() >= 6) call get_command_argument(6, csv)
        call bench_contact(n, csv)
    case ('decompose')
        if (command_argument_count() < 5) call usage()
        call get_command_argument(2, arg); read (arg, *) n
        call bench_decompose(n)
    case default
        call usage()
    end select
contains

    subroutine usage()
        write (*, '(a)') 'usage: fastcontact-bench-fem-ic coef MESH STRETCH [CSV]'
        write (*, '(a)') '       | contact N MESH STRETCH L_OVER_HC [CSV [INTEGRATION]]'
        write (*, '(a)') '       | decompose N MESH STRETCH L_OVER_HC [HC_OVER_HS [CUBE_OVER_HC]]'
        stop 2
    end subroutine usage

    !> §5.3: eq. 5.12 error of A^zz at the origin (normal load only) for one mesh.
    subroutine bench_coef(mesh, f, csv)
        character(len=*), intent(in) :: mesh
        real(dp), intent(in) :: f
        character(len=*), intent(in) :: csv
        type(fc_fem_params) :: p
        type(fc_ic_set) :: set, ana
        type(fc_fem_info) :: info
        integer :: stat, u, k, v, nk
        character(len=msg_len) :: msg
        real(dp), parameter :: ratios(6) = [80.0_dp, 320.0_dp, 1280.0_dp, 5120.0_dp, 20480.0_dp, 81920.0_dp]
        integer, parameter :: orders(3) = [2, 2, 1]
        character(len=8), parameter :: integ(3) = ['reduced', 'full   ', 'full   ']
        real(dp) :: h, err
        logical :: exists
        h = 0.8_dp
        nk = 3; if (mesh == 'hex') nk = 6
        call analytic_body_set(82000.0_dp, 0.28_dp, h, h, 10, 10, ana, stat, msg)
        inquire (file=csv, exist=exists)
        open (newunit=u, file=csv, position='append', action='write')
        if (.not. exists) write (u, '(a)') &
            'mesh,order,integration,l_over_hc,stretch,hc_over_hs,elements,dofs,ccx_cpu_s,ccx_wall_s,err_origin'
        do v = 1, 3
            if (mesh == 'prism' .and. v == 1) cycle
            do k = 1, nk
                if (orders(v) == 1 .and. k > 2) cycle
                p = fc_fem_params()
                p%mesh = mesh; p%order = orders(v); p%integration = integ(v); p%l_over_hc = ratios(k)
                p%stretch = f
                p%normal_only = .true.
                call compute_fem_ic(p, 82000.0_dp, 0.28_dp, 10, 10, h, h, set, info, stat, msg)
                if (stat /= 0) then
                    write (*, '(2a)') 'error: ', trim(msg); cycle
                end if
                err = abs(set%a(0, 0, 3, 3) - ana%a(0, 0, 3, 3))/ana%a(0, 0, 3, 3)
                write (u, '(a,",",i0,",",a,",",f0.0,",",f0.2,",",f0.0,2(",",i0),2(",",f0.2),",",es10.3)') trim(p%mesh), &
                    p%order, trim(p%integration), p%l_over_hc, p%stretch, p%hc_over_hs, info%elements, info%dofs, &
                    info%ccx_cpu, info%ccx_wall, err
                flush (u)
                write (*, '(a,1x,i0,1x,a,a,f0.0,a,i0,a,f0.1,a,es10.3)') trim(p%mesh), p%order, trim(p%integration), &
                    ' L/hc=', p%l_over_hc, ' dofs=', info%dofs, ' cpu=', info%ccx_cpu, ' err=', err
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
        if (command_argument_count() >= 7) then
            call get_command_argument(7, arg); p%integration = trim(arg)
        end if
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
        if (.not. exists) write (u, '(a)') 'grid,mesh,order,integration,l_over_hc,L_mm,stretch,hc_over_hs,elements,'// &
            'dofs,ccx_cpu_s,'// &
            'solve_s,fz_err,pmax_err,area_err,fx_err,fz_err_halfspace,pmax_err_halfspace,area_err_halfspace,fx_err_halfspace'
        write (u, '(i0,",",a,",",i0,",",a,",",f0.0,",",f0.2,",",a,",",f0.0,2(",",i0),",",f0.2,",",f0.4,8(",",es10.3))') &
            n, trim(p%mesh), p%order, trim(p%integration), p%l_over_hc, info%domain, trim(stretch_text(p)), p%hc_over_hs, &
            info%elements, info%dofs, &
            info%ccx_cpu, tf, errs(rf, h), errs(ra, h)
        close (u)
        write (*, '(a,i0,1x,a,a,f0.0,a,i0,a,f0.1,a,4es10.2,a,4es10.2)') 'grid ', n, trim(p%mesh), ' L/hc=', p%l_over_hc, &
            ' dofs=', info%dofs, ' ccx cpu=', info%ccx_cpu, ' FE errs (Fz pmax area Fx):', errs(rf, h), '  half-space:', errs(ra, h)
    end subroutine bench_contact

    !> Where the error of the §5.4 forces comes from, on an n×n grid: FE/analytic − 1 of
    !! A^zz and A^xx at the top-surface nodes along the x axis (FE error without any
    !! interpolation) and at the cell centres along the axis and the diagonal (plain and
    !! 1/ρ-weighted interpolation), then the contact errors with hybrid kernels (FE up to
    !! an offset radius K, analytic beyond) that locate the offsets responsible.
    subroutine bench_decompose(n)
        integer, intent(in) :: n
        type(fc_fem_params) :: p
        type(fc_ic_set) :: plain, wtd, ana, hyb, ic
        type(fc_fem_info) :: info
        type(fc_fem_top) :: top
        type(fc_material) :: mat, body
        type(fc_contact_operators) :: ops
        type(fc_contact_result) :: r
        integer :: stat, i, jt, k, ix, iy, kk
        character(len=msg_len) :: msg
        character(len=256) :: arg
        real(dp) :: h, x, an, t
        integer, parameter :: radii(6) = [0, 2, 8, 32, 64, 100000]
        real(dp) :: v(3), w(3)
        p = fc_fem_params()
        call get_command_argument(3, arg); p%mesh = trim(arg)
        call get_command_argument(4, arg)
        if (index(arg, ':') > 0) then
            read (arg(:index(arg, ':') - 1), *) p%stretch; read (arg(index(arg, ':') + 1:), *) p%stretch_far
        else
            read (arg, *) p%stretch
        end if
        call get_command_argument(5, arg); read (arg, *) p%l_over_hc
        if (command_argument_count() >= 6) then
            call get_command_argument(6, arg); read (arg, *) p%hc_over_hs
        end if
        if (command_argument_count() >= 7) then
            call get_command_argument(7, arg); read (arg, *) p%cube_over_hc
        end if
        call get_environment_variable('FEM_INTEGRATION', arg)
        p%integration = trim(arg)
        h = 2.4_dp/n; cell_h = h
        call compute_fem_ic(p, 200.0_dp, 0.42_dp, n, n, h, h, plain, info, stat, msg, top)
        if (stat /= 0) then
            write (*, '(2a)') 'error: ', trim(msg); stop 1
        end if
        write (*, '(a,i0,a,i0,a,f0.1,a,f0.1)') 'model: elements ', info%elements, ' dofs ', info%dofs, ' ccx cpu ', &
            info%ccx_cpu, ' s, L = ', info%domain
        write (*, '(a,es10.3)') 'reciprocity |Axy-Ayx|/max: ', info%reciprocity
        call analytic_body_set(200.0_dp, 0.42_dp, h, h, n, n, ana, stat, msg)
        body%g1 = 200; body%nu1 = 0.42_dp; body%g2 = 1.0e30_dp; body%nu2 = 0
        call combine_material(body, stat, msg)
        write (*, '(a)') '# nodes along the x axis (y = 0): x/h, zz FE/an-1, xx FE/an-1'
        if (top%shell) then
            do i = 0, 2*top%sh%m + 2*top%sh%nl
                if (i <= 2*top%sh%m) then
                    x = -top%sh%lx*i/(2*top%sh%m)
                else
                    x = -top%sh%lx*top%sh%sigma(i - 2*top%sh%m)
                end if
                if (-x > (n + 1)*h) exit
                v = shell_surface_value(top%sh, top%uz(:, 1, :), x, 0.0_dp)
                w = shell_surface_value(top%sh, top%ux(:, 1, :), x, 0.0_dp)
                call node_line(x, v(3), w(1))
            end do
        else
            jt = 2*top%mesh%nyc
            do i = 2*top%mesh%nxc, 0, -1
                x = lattice_coord(top%mesh%xs, i)
                if (-x > (n + 1)*h) exit
                call node_line(x, top%uz(i, jt, 3), top%ux(i, jt, 1))
            end do
        end if
        call top_to_set(top, n, n, h, h, .true., wtd)
        wtd%a(:, :, 1, 2) = (wtd%a(:, :, 1, 2) + wtd%a(:, :, 2, 1))/2; wtd%a(:, :, 2, 1) = wtd%a(:, :, 1, 2)
        wtd%content = 'body'
        write (*, '(a)') '# cell centres [%]: k, zz axis plain/weighted, zz diag plain/weighted, xx axis plain/weighted'
        do k = 0, n
            if (k > 8 .and. mod(k, max(1, n/20)) /= 0 .and. k /= n) cycle
            write (*, '(i5,6f9.4)') k, pc(plain, ana, k, 0, 3, 3), pc(wtd, ana, k, 0, 3, 3), pc(plain, ana, k, k, 3, 3), &
                pc(wtd, ana, k, k, 3, 3), pc(plain, ana, k, 0, 1, 1), pc(wtd, ana, k, 0, 1, 1)
        end do
        mat%g1 = 200; mat%nu1 = 0.42_dp; mat%g2 = 200; mat%nu2 = 0.42_dp
        call combine_material(mat, stat, msg)
        write (*, '(a)') '# contact errors [%] (Fz pmax area Fx): kernel'
        call ops_from(ana, ops); call sphere(ops, mat, n, r, t); call show(r, h, 'analytic')
        call ops_from(plain, ops); call sphere(ops, mat, n, r, t); call show(r, h, 'FE plain')
        call ops_from(wtd, ops); call sphere(ops, mat, n, r, t); call show(r, h, 'FE weighted')
        do kk = 1, size(radii)
            hyb = ana
            do iy = -n, n
                do ix = -n, n
                    if (max(abs(ix), abs(iy)) <= radii(kk)) hyb%a(ix, iy, :, :) = wtd%a(ix, iy, :, :)
                end do
            end do
            call ops_from(hyb, ops); call sphere(ops, mat, n, r, t)
            write (arg, '(a,i0,a)') 'FE weighted for |k|<=', radii(kk), ', analytic beyond'
            call show(r, h, trim(arg))
        end do
        hyb = ana; hyb%a = ana%a*(wtd%a(0, 0, 3, 3)/ana%a(0, 0, 3, 3))
        call ops_from(hyb, ops); call sphere(ops, mat, n, r, t); call show(r, h, 'analytic scaled by FE A(0)/an A(0)')
    end subroutine bench_decompose

    subroutine node_line(x, uz, ux)
        real(dp), intent(in) :: x, uz, ux
        type(fc_material) :: body
        integer :: stat
        character(len=msg_len) :: msg
        real(dp) :: h
        body%g1 = 200; body%nu1 = 0.42_dp; body%g2 = 1.0e30_dp; body%nu2 = 0
        call combine_material(body, stat, msg)
        h = cell_h
        write (*, '(f9.3,2f10.5)') -x/h, 100*(-uz/element_coefficient(IC_ZZ, body, x, 0.0_dp, h, h) - 1), &
            100*(ux/element_coefficient(IC_XX, body, x, 0.0_dp, h, h) - 1)
    end subroutine node_line

    real(dp) function pc(s, ana, i, j, a, b)
        type(fc_ic_set), intent(in) :: s, ana
        integer, intent(in) :: i, j, a, b
        pc = 100*(s%a(i, j, a, b)/ana%a(i, j, a, b) - 1)
    end function pc

    subroutine ops_from(s, ops)
        type(fc_ic_set), intent(in) :: s
        type(fc_contact_operators), intent(out) :: ops
        type(fc_ic_set) :: ic
        integer :: stat
        character(len=msg_len) :: msg
        call combine_ic_sets(s, s, ic, stat, msg)
        if (stat == 0) call set_influence_coefficients(ops, ic, stat, msg)
        if (stat /= 0) then
            write (*, '(2a)') 'error: ', trim(msg); stop 1
        end if
    end subroutine ops_from

    subroutine show(r, h, label)
        type(fc_contact_result), intent(in) :: r
        real(dp), intent(in) :: h
        character(len=*), intent(in) :: label
        write (*, '(4f9.4,2x,a)') 100*errs(r, h), label
    end subroutine show

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
