!> Numerical influence coefficients by the finite element method with CalculiX (thesis ch. 5).
!!
!! [[compute_fem_ic]] builds the model of [[fc_fem_mesh]] for the cells of a contact grid,
!! runs `ccx` once per load direction (normal, x; y too unless the mesh is symmetric under
!! x ↔ y), reads the top-surface displacements from the `.dat` file, evaluates them at the
!! contact-cell centres with the element's face shape functions, and fills a set of
!! content 'body' ([[fc_icfile]]) for every offset |ix| ≤ nx, |iy| ≤ ny (the preconditioner
!! of BCCG needs the offsets ±n).  The quarter model gives the offsets with ix, iy ≤ 0; the
!! others follow from the symmetries of the load cases (Table 5.1):
!!   normal load:  u_z even in x and y, u_x odd in x, u_y odd in y;
!!   x load:       u_x even, u_y odd in x and y, u_z odd in x;   (y load: x ↔ y).
!! Signs map the FE frame (body in z ≤ 0) to the library's: A^zz = −u_z (pressure pushes
!! into the body), A^xz = u_x, A^zx = −u_z; the pair A^xy, A^yx is averaged (they differ by
!! the FE's reciprocity error, reported in [[fc_fem_info]]).
module fc_fem_ic
    use, intrinsic :: iso_c_binding, only: c_int, c_long
    use fc_kinds, only: dp, msg_len, FC_ERR_VALUE, FC_ERR_IO
    use fc_fem_mesh
    use fc_fem_shell
    use fc_fem_extruded
    use fc_icfile, only: fc_ic_set, ic_set_allocate, hash_text
    implicit none
    private

    !> Cost and diagnostics of one FE computation.
    type, public :: fc_fem_info
        integer :: nodes = 0, elements = 0, dofs = 0   !! model size (per run)
        integer :: runs = 0                            !! CalculiX runs (load cases)
        real(dp) :: ccx_cpu = 0                        !! CalculiX CPU time, user + system, all runs [s]
        real(dp) :: ccx_wall = 0                       !! CalculiX wall time, all runs [s]
        real(dp) :: domain = 0                         !! L [mm]
        real(dp) :: reciprocity = 0                    !! max |A^xy − A^yx| / max |A^xy| before averaging
        character(len=512) :: workdir = ''             !! work directory used
    end type fc_fem_info

    !> Top-surface nodal displacements of the FE runs: u(lattice i, lattice j, component) of the
    !! tensor meshes, u(node, 1, component) of the nested-box mesh (`shell`).
    type, public :: fc_fem_top
        logical :: shell = .false.
        type(fc_fem_mesh_t) :: mesh
        type(fc_fem_shell_t) :: sh
        real(dp), allocatable :: uz(:, :, :), ux(:, :, :), uy(:, :, :)  !! uy only when the mesh is not x ↔ y symmetric
    end type fc_fem_top

    public :: compute_fem_ic, fem_model_hash, fem_model_text, surface_value, top_to_set

contains

    !> Canonical text of everything that determines the coefficients (cache key source).
    function fem_model_text(p, g, nu, nx, ny, dx, dy) result(text)
        type(fc_fem_params), intent(in) :: p
        real(dp), intent(in) :: g, nu, dx, dy
        integer, intent(in) :: nx, ny
        character(len=512) :: text
        write (text, '(a,i0,4a,4(a,es24.16e3),a,2(a,es24.16e3),2(a,i0),2(a,es24.16e3))') 'fem-model-2 mesh=', &
            p%order, '/'//trim(p%mesh)//'/'//trim(p%integration), ' load=', trim(p%load), ' solver='//trim(p%solver), &
            ' L/hc=', p%l_over_hc, ' l/hc=', p%cube_over_hc, ' hc/hs=', p%hc_over_hs, ' f=', p%stretch, &
            ' ffar='//trim(real_text(p%stretch_far))//' |', &
            ' g=', g, ' nu=', nu, ' nx=', nx, ' ny=', ny, ' dx=', dx, ' dy=', dy
    end function fem_model_text

    function real_text(x) result(t)
        real(dp), intent(in) :: x
        character(len=32) :: t
        write (t, '(es24.16e3)') x
        t = adjustl(t)
    end function real_text

    !> Cache key of a model (parameters after [[fem_defaults]]).
    function fem_model_hash(p, g, nu, nx, ny, dx, dy) result(h)
        type(fc_fem_params), intent(in) :: p
        real(dp), intent(in) :: g, nu, dx, dy
        integer, intent(in) :: nx, ny
        character(len=16) :: h
        h = hash_text(trim(fem_model_text(p, g, nu, nx, ny, dx, dy)))
    end function fem_model_hash

    !> Compute one body's influence coefficients (G = g [N/mm²], ν = nu) for a grid of nx×ny
    !! cells of size dx×dy [mm] with the FE model `p` (automatic values filled in here).
    subroutine compute_fem_ic(p, g, nu, nx, ny, dx, dy, set, info, stat, errmsg, top_out)
        type(fc_fem_params), intent(inout) :: p
        real(dp), intent(in) :: g, nu, dx, dy
        integer, intent(in) :: nx, ny
        type(fc_ic_set), intent(inout) :: set
        type(fc_fem_info), intent(out) :: info
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_fem_top), intent(out), optional :: top_out
        type(fc_fem_top) :: top
        type(fc_fem_mesh_t) :: mesh
        type(fc_fem_extruded_t) :: ext
        real(dp), allocatable :: uz(:, :, :), ux(:, :, :), uy(:, :, :)
        character(len=:), allocatable :: dir
        logical :: made_dir, need_y
        real(dp) :: scale
        stat = FC_ERR_VALUE
        if (.not. (g > 0 .and. g < 1.0e29_dp)) then
            write (errmsg, '(a,es12.4,a)') 'material: g1 = ', g, ' must be > 0 and < 1e29 (an elastic body)'; return
        end if
        if (.not. (nu >= 0 .and. nu < 0.5_dp)) then
            write (errmsg, '(a,g0.6,a)') 'material: nu1 = ', nu, ' must lie in [0, 0.5)'; return
        end if
        if (nx < 1 .or. ny < 1 .or. nx > 4096 .or. ny > 4096 .or. .not. (dx > 0 .and. dy > 0)) then
            write (errmsg, '(a,i0,a,i0,a,2es12.4,a)') 'grid: nx = ', nx, ', ny = ', ny, ', dx, dy = ', dx, dy, &
                ' must satisfy 1 <= n <= 4096 and dx, dy > 0'
            return
        end if
        call fem_defaults(p, nx, ny, dx, dy)
        call fem_validate(p, nx, ny, dx, dy, stat, errmsg); if (stat /= 0) return
        top%shell = p%mesh == 'hex'
        if (top%shell) then
            call build_shell_mesh(p, nx, ny, dx, dy, top%sh, stat, errmsg); if (stat /= 0) return
            info%nodes = top%sh%nnodes; info%elements = top%sh%nelems; info%domain = top%sh%domain
        else if (p%mesh == 'prism') then
            call build_extruded_mesh(p, nx, ny, dx, dy, ext, stat, errmsg); if (stat /= 0) return
            call extruded_top(ext, mesh)
            info%nodes = ext%nnodes; info%elements = ext%nelems; info%domain = ext%domain
        else
            call build_fem_mesh(p, nx, ny, dx, dy, mesh, stat, errmsg); if (stat /= 0) return
            info%nodes = mesh%nnodes; info%elements = mesh%nelems; info%domain = mesh%domain
        end if
        info%dofs = 3*info%nodes
        call make_workdir(p, fem_model_hash(p, g, nu, nx, ny, dx, dy), dir, made_dir, stat, errmsg)
        if (stat /= 0) return
        info%workdir = dir
        need_y = p%mesh == 'prism' .or. p%mesh == 'tprism' .or. abs(dx - dy) > 1.0e-12_dp*max(dx, dy)
        call run_case(FEM_LOAD_Z, 'job_z', uz); if (stat /= 0) return
        if (p%normal_only) then
            allocate (ux, uy, mold=uz); ux = 0; uy = 0
        else
            call run_case(FEM_LOAD_X, 'job_x', ux); if (stat /= 0) return
            if (need_y) then
                call run_case(FEM_LOAD_Y, 'job_y', uy); if (stat /= 0) return
            end if
        end if
        if (.not. top%shell) top%mesh = mesh
        call move_alloc(uz, top%uz); call move_alloc(ux, top%ux)
        if (need_y) call move_alloc(uy, top%uy)
        call top_to_set(top, nx, ny, dx, dy, .false., set)
        scale = max(maxval(abs(set%a(:, :, 1, 2))), tiny(1.0_dp))
        info%reciprocity = maxval(abs(set%a(:, :, 1, 2) - set%a(:, :, 2, 1)))/scale
        set%a(:, :, 1, 2) = (set%a(:, :, 1, 2) + set%a(:, :, 2, 1))/2
        set%a(:, :, 2, 1) = set%a(:, :, 1, 2)
        set%content = 'body'; set%source = 'fem'; set%g = g; set%nu = nu; set%load = p%load
        set%hash = fem_model_hash(p, g, nu, nx, ny, dx, dy)
        write (set%model, '(3a,i0,a,es12.5,5(a,g0.6),a,i0,a,i0,a,f0.2,a)') 'CalculiX ', trim(p%mesh)//' '//trim(p%integration), &
            ' order ', p%order, &
            ' L = ', info%domain, ' mm (L/hc = ', p%l_over_hc, ', l/hc = ', p%cube_over_hc, ', hc/hs = ', p%hc_over_hs, &
            ', f = ', p%stretch, ', f_far = ', p%stretch_far, '), ', info%elements, ' elements, ', info%dofs, &
            ' dofs, ccx cpu ', info%ccx_cpu, ' s'
        if (made_dir .and. .not. p%keep_work) call remove_dir(dir)
        if (present(top_out)) call move_alloc_top(top, top_out)
        stat = 0; errmsg = ''
    contains

        subroutine run_case(load_dir, job, u)
            integer, intent(in) :: load_dir
            character(len=*), intent(in) :: job
            real(dp), allocatable, intent(out) :: u(:, :, :)
            real(dp) :: cpu, wall
            real(dp), allocatable :: v(:, :)
            if (top%shell) then
                call write_shell_deck(dir//'/'//job//'.inp', p, top%sh, load_dir, g, nu, dx, dy, stat, errmsg)
            else if (p%mesh == 'prism') then
                call write_extruded_deck(dir//'/'//job//'.inp', p, ext, load_dir, g, nu, dx, dy, stat, errmsg)
            else
                call write_fem_deck(dir//'/'//job//'.inp', p, mesh, load_dir, g, nu, dx, dy, stat, errmsg)
            end if
            if (stat /= 0) return
            call run_ccx(p, dir, job, cpu, wall, stat, errmsg)
            info%ccx_cpu = info%ccx_cpu + cpu; info%ccx_wall = info%ccx_wall + wall
            info%runs = info%runs + 1
            if (stat /= 0) return
            if (top%shell) then
                call read_node_displacements(dir//'/'//job//'.dat', shell_top_nodes(top%sh), top%sh%nnodes, v, stat, errmsg)
                if (stat /= 0) return
                allocate (u(size(v, 1), 1, 3)); u(:, 1, :) = v
            else
                call read_top_displacements(dir//'/'//job//'.dat', mesh, u, stat, errmsg)
            end if
        end subroutine run_case

    end subroutine compute_fem_ic

    subroutine move_alloc_top(a, b)
        type(fc_fem_top), intent(inout) :: a
        type(fc_fem_top), intent(out) :: b
        b%shell = a%shell; b%mesh = a%mesh; b%sh = a%sh
        if (allocated(a%uz)) call move_alloc(a%uz, b%uz)
        if (allocated(a%ux)) call move_alloc(a%ux, b%ux)
        if (allocated(a%uy)) call move_alloc(a%uy, b%uy)
    end subroutine move_alloc_top

    !> Fill the coefficient blocks of `set` (offsets |ix| ≤ nx, |iy| ≤ ny) from the top-surface
    !! nodal displacements of the normal and x (and y) load runs, by the symmetries of the
    !! load cases; `weighted` selects the 1/ρ-weighted interpolation of [[surface_value]].
    !! A^xy and A^yx are left as computed (the caller averages them).
    subroutine top_to_set(top, nx, ny, dx, dy, weighted, set)
        type(fc_fem_top), intent(in) :: top
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: dx, dy
        logical, intent(in) :: weighted
        type(fc_ic_set), intent(inout) :: set
        integer :: ix, iy
        real(dp) :: sx, sy, f(3), c
        c = max(dx, dy)
        call ic_set_allocate(set, nx, ny, dx, dy)
        do iy = -ny, ny
            sy = 1; if (iy > 0) sy = -1
            do ix = -nx, nx
                sx = 1; if (ix > 0) sx = -1
                f = field(top%uz, abs(ix), abs(iy))
                set%a(ix, iy, 3, 3) = -f(3)
                set%a(ix, iy, 1, 3) = sx*f(1)
                set%a(ix, iy, 2, 3) = sy*f(2)
                f = field(top%ux, abs(ix), abs(iy))
                set%a(ix, iy, 1, 1) = f(1)
                set%a(ix, iy, 2, 1) = sx*sy*f(2)
                set%a(ix, iy, 3, 1) = -sx*f(3)
                if (allocated(top%uy)) then
                    f = field(top%uy, abs(ix), abs(iy))
                else   ! mirror x ↔ y of the x-load field
                    f = field(top%ux, abs(iy), abs(ix))
                    f = [f(2), f(1), f(3)]
                end if
                set%a(ix, iy, 2, 2) = f(2)
                set%a(ix, iy, 1, 2) = sx*sy*f(1)
                set%a(ix, iy, 3, 2) = -sy*f(3)
            end do
        end do
    contains
        !> FE displacement at the model point (−i·dx, −j·dy) of the top surface.
        function field(u, i, j) result(v)
            real(dp), intent(in) :: u(0:, 0:, :)
            integer, intent(in) :: i, j
            real(dp) :: v(3)
            if (top%shell .and. weighted) then
                v = shell_surface_value(top%sh, u(:, 0, :), -i*dx, -j*dy, c)
            else if (top%shell) then
                v = shell_surface_value(top%sh, u(:, 0, :), -i*dx, -j*dy)
            else if (weighted) then
                v = surface_value(top%mesh, u, -i*dx, -j*dy, c)
            else
                v = surface_value(top%mesh, u, -i*dx, -j*dy)
            end if
        end function field
    end subroutine top_to_set

    !> Interpolate top-surface nodal values u(lattice i, lattice j, comp) at (x, y) with the
    !! shape functions of the face containing the point.  With `c` present the product
    !! w·u, w = sqrt(x² + y² + c²), is interpolated and divided by w at the point: every
    !! surface displacement of a load near the origin decays as 1/ρ, and w·u is smooth even
    !! across elements that span their distance from the load.
    function surface_value(mesh, u, x, y, c) result(v)
        type(fc_fem_mesh_t), intent(in) :: mesh
        real(dp), intent(in) :: u(0:, 0:, :)
        real(dp), intent(in) :: x, y
        real(dp), intent(in), optional :: c
        real(dp) :: v(3), nsh(8), xi, eta, w
        integer :: ci, cj, a, li, lj, nn
        ci = locate(mesh%xs, x); cj = locate(mesh%ys, y)
        xi = 2*(x - mesh%xs(ci))/(mesh%xs(ci + 1) - mesh%xs(ci)) - 1
        eta = 2*(y - mesh%ys(cj))/(mesh%ys(cj + 1) - mesh%ys(cj)) - 1
        call face_shape(mesh%order, xi, eta, nsh)
        nn = 8; if (mesh%order == 1) nn = 4
        v = 0
        do a = 1, nn
            call face_lattice(ci, cj, a, li, lj)
            w = 1
            if (present(c)) w = sqrt(lattice_coord(mesh%xs, li)**2 + lattice_coord(mesh%ys, lj)**2 + c**2)
            v = v + nsh(a)*w*u(li, lj, :)
        end do
        if (present(c)) v = v/sqrt(x**2 + y**2 + c**2)
    end function surface_value

    !> Cell c with a(c) ≤ x ≤ a(c+1) (bisection; clamped to the axis).
    pure integer function locate(a, x) result(c)
        real(dp), intent(in) :: a(0:)
        real(dp), intent(in) :: x
        integer :: lo, hi, mid
        lo = 0; hi = ubound(a, 1)
        do while (hi - lo > 1)
            mid = (lo + hi)/2
            if (a(mid) <= x) then
                lo = mid
            else
                hi = mid
            end if
        end do
        c = lo
    end function locate

    !> Create the work directory: `p%workdir` if given, else a fresh one under $TMPDIR or /tmp.
    subroutine make_workdir(p, key, dir, made, stat, errmsg)
        type(fc_fem_params), intent(in) :: p
        character(len=*), intent(in) :: key
        character(len=:), allocatable, intent(out) :: dir
        logical, intent(out) :: made
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=512) :: base
        character(len=24) :: pid
        integer :: n, es, cs
        interface
            integer(c_int) function c_getpid() bind(c, name='getpid')
                import :: c_int
            end function c_getpid
        end interface
        made = .false.
        if (len_trim(p%workdir) > 0) then
            dir = trim(p%workdir)
        else
            call get_environment_variable('TMPDIR', base, n)
            if (n == 0 .or. n > len(base)) base = '/tmp'
            write (pid, '(i0)') c_getpid()
            dir = trim(base)//'/fastcontact-ic-'//trim(pid)//'-'//key(1:8)
            made = .true.
        end if
        if (index(dir, "'") > 0) then
            stat = FC_ERR_VALUE; errmsg = "fem: workdir = '"//dir//"' must not contain a quote"; return
        end if
        call execute_command_line("mkdir -p '"//dir//"'", exitstat=es, cmdstat=cs)
        if (cs /= 0 .or. es /= 0) then
            stat = FC_ERR_IO; errmsg = "fem: cannot create the work directory '"//dir//"'"; return
        end if
        stat = 0; errmsg = ''
    end subroutine make_workdir

    subroutine remove_dir(dir)
        character(len=*), intent(in) :: dir
        integer :: es, cs
        call execute_command_line("rm -rf '"//dir//"'", exitstat=es, cmdstat=cs)
    end subroutine remove_dir

    !> Run `ccx -i job` in `dir`; CPU time of the child (getrusage) and wall time returned.
    subroutine run_ccx(p, dir, job, cpu, wall, stat, errmsg)
        type(fc_fem_params), intent(in) :: p
        character(len=*), intent(in) :: dir, job
        real(dp), intent(out) :: cpu, wall
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=:), allocatable :: cmd, logf
        character(len=16) :: nt
        integer :: es, cs, u, ios
        integer(8) :: t0, t1, rate
        real(dp) :: c0, c1
        logical :: exists
        character(len=512) :: line
        write (nt, '(i0)') p%threads
        logf = dir//'/'//job//'.log'
        cmd = "cd '"//dir//"' && OMP_NUM_THREADS="//trim(nt)//" CCX_NPROC_EQUATION_SOLVER="//trim(nt)// &
            " "//trim(p%ccx)//" -i "//job//" > "//job//".log 2>&1"
        c0 = children_cpu()
        call system_clock(t0, rate)
        call execute_command_line(cmd, exitstat=es, cmdstat=cs)
        call system_clock(t1)
        cpu = children_cpu() - c0
        wall = real(t1 - t0, dp)/rate
        stat = FC_ERR_IO
        if (cs /= 0 .or. es == 127 .or. es == 126) then
            errmsg = "fem: CalculiX command '"//trim(p%ccx)//"' not found or not executable "// &
                '(install calculix-ccx or set &fem ccx); command `'//cmd//'`, log '//logf
            return
        end if
        ! CalculiX reports input errors in its log, sometimes with exit status 0
        open (newunit=u, file=logf, status='old', action='read', iostat=ios)
        if (ios == 0) then
            do
                read (u, '(a)', iostat=ios) line
                if (ios /= 0) exit
                if (index(line, '*ERROR') > 0) then
                    close (u)
                    errmsg = 'fem: CalculiX reported "'//trim(adjustl(line))//'"; command `'//cmd//'`, log '//logf
                    return
                end if
            end do
            close (u)
        end if
        if (es /= 0) then
            write (errmsg, '(a,i0,4a)') 'fem: CalculiX failed with exit status ', es, '; command `', cmd, '`, log ', logf
            return
        end if
        inquire (file=dir//'/'//job//'.dat', exist=exists)
        if (.not. exists) then
            errmsg = 'fem: CalculiX wrote no '//dir//'/'//job//'.dat; command `'//cmd//'`, log '//logf; return
        end if
        stat = 0; errmsg = ''
    end subroutine run_ccx

    !> CPU time (user + system) of terminated children of this process [s].
    real(dp) function children_cpu() result(t)
        type, bind(c) :: timeval
            integer(c_long) :: sec, usec
        end type timeval
        type, bind(c) :: rusage
            type(timeval) :: utime, stime
            integer(c_long) :: rest(14)
        end type rusage
        interface
            integer(c_int) function c_getrusage(who, r) bind(c, name='getrusage')
                import :: c_int, rusage
                integer(c_int), value :: who
                type(rusage), intent(out) :: r
            end function c_getrusage
        end interface
        type(rusage) :: r
        integer(c_int), parameter :: rusage_children = -1
        t = 0
        if (c_getrusage(rusage_children, r) /= 0) return
        t = real(r%utime%sec + r%stime%sec, dp) + real(r%utime%usec + r%stime%usec, dp)*1.0e-6_dp
    end function children_cpu

    !> Read the displacements of node set NTOP from a CalculiX .dat file into
    !! u(lattice i, lattice j, component) of the top surface of a tensor mesh.
    subroutine read_top_displacements(path, mesh, u, stat, errmsg)
        character(len=*), intent(in) :: path
        type(fc_fem_mesh_t), intent(in) :: mesh
        real(dp), allocatable, intent(out) :: u(:, :, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), allocatable :: v(:, :)
        integer :: i, j, kt
        kt = 2*mesh%nzc
        call read_node_displacements(path, pack(mesh%id(:, :, kt), mesh%id(:, :, kt) > 0), mesh%nnodes, v, stat, errmsg)
        if (stat /= 0) return
        allocate (u(0:2*mesh%nxc, 0:2*mesh%nyc, 3), source=0.0_dp)
        do j = 0, 2*mesh%nyc
            do i = 0, 2*mesh%nxc
                if (mesh%id(i, j, kt) > 0) u(i, j, :) = v(mesh%id(i, j, kt), :)
            end do
        end do
    end subroutine read_top_displacements

    !> Read the displacements of the nodes `want` from a CalculiX .dat file into u(node, component)
    !! (nodes 1 … nnodes; every wanted node must be present).
    subroutine read_node_displacements(path, want, nnodes, u, stat, errmsg)
        character(len=*), intent(in) :: path
        integer, intent(in) :: want(:), nnodes
        real(dp), allocatable, intent(out) :: u(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        logical, allocatable :: wanted(:), seen(:)
        integer :: un, ios, nid, count
        real(dp) :: v(3)
        character(len=512) :: line
        logical :: in_block
        allocate (u(nnodes, 3), source=0.0_dp)
        allocate (wanted(nnodes), seen(nnodes), source=.false.)
        wanted(want) = .true.
        stat = FC_ERR_IO
        open (newunit=un, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) then
            errmsg = 'fem: cannot open the CalculiX results '//path; return
        end if
        in_block = .false.; count = 0
        do
            read (un, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (index(line, 'displacements') > 0) then
                in_block = .true.; cycle
            end if
            if (.not. in_block .or. len_trim(line) == 0) cycle
            read (line, *, iostat=ios) nid, v
            if (ios /= 0) then
                in_block = .false.; cycle
            end if
            if (nid < 1 .or. nid > nnodes) cycle
            if (.not. wanted(nid)) cycle
            u(nid, :) = v
            if (.not. seen(nid)) count = count + 1
            seen(nid) = .true.
        end do
        close (un)
        if (count /= size(want)) then
            write (errmsg, '(3a,i0,a,i0)') 'fem: ', path, ' holds displacements of ', count, &
                ' top-surface nodes, expected ', size(want)
            return
        end if
        stat = 0; errmsg = ''
    end subroutine read_node_displacements

end module fc_fem_ic
