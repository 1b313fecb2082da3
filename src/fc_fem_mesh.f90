!> Finite element model of thesis §5.2–5.3 for numerical influence coefficients: the
!! `&fem` parameters, their defaults and limits, the parts of a CalculiX deck common to every
!! mesh (boundary conditions of thesis Table 5.1, equivalent nodal forces of a unit load on
!! the quarter of the source element, the step), and the graded tensor-product meshes of the
!! quarter block [−L,0]³ (`tensor`: hexahedra, `tprism`: prisms).  Mesh1 (nested boxes) is
!! [[fc_fem_shell]], Mesh2 (extruded prisms) [[fc_fem_extruded]].
!!
!! Size (~640 lines): the `&fem` record with its validation and the deck parts every mesh
!! writes are one concern for the three mesh writers; the tensor meshes are its smallest user.
!!
!! Tensor meshes (per axis, coordinates increasing from −L to 0): a uniform "cube" region
!! [−l, 0] with m = l/h_s cells of size h_s = h_c/(h_c/h_s), then cells growing by the
!! stretching factor f up to −L (the last cell absorbs the remainder); `tensor` uses these
!! nodes as a tensor product of hexahedra (C3D20(R), or C3D8 when linear); `tprism` splits
!! every hexahedron into two wedges whose triangular faces lie in the planes x = const,
!! C3D15 or C3D6.  Nodes live on a lattice with two points per cell and
!! axis (corners at even, mid-edge nodes at odd lattice indices).
!!
!! Loads (thesis Table 5.1, Remark 5.1): a unit traction on the top face z = 0, either
!! piecewise constant on [−dx/2,0]×[−dy/2,0] or the bilinear tent (1−|x|/dx)(1−|y|/dy) on
!! [−dx,0]×[−dy,0]; normal loads push into the body (force along −z), tangential loads act
!! along +x or +y.  Symmetry planes x = 0 and y = 0 carry the Dirichlet conditions of
!! Table 5.1 for the load direction; the faces x = −L, y = −L, z = −L are clamped.
module fc_fem_mesh
    use fc_kinds, only: dp, i8, msg_len, FC_ERR_VALUE, FC_ERR_IO, FC_ERR_INTERNAL
    implicit none
    private

    integer, parameter, public :: FEM_LOAD_Z = 3, FEM_LOAD_X = 1, FEM_LOAD_Y = 2  !! load directions

    !> Parameters of the FE model (`&fem` group); 0 means "automatic" where stated.
    type, public :: fc_fem_params
        character(len=8) :: mesh = 'hex'          !! 'hex' (Mesh1, nested boxes), 'prism' (Mesh2, extruded), 'tensor' or 'tprism' (tensor products)
        integer :: order = 2                      !! element order: 2 quadratic (default), 1 linear
        character(len=16) :: load = 'constant'    !! 'constant' (piecewise constant) or 'bilinear' (tent)
        real(dp) :: l_over_hc = 0                 !! domain size L/h_c (0: automatic, see doc/numerical_ic.md)
        real(dp) :: cube_over_hc = 1              !! uniform cube size l/h_c (Table 5.3: 1 … 1.25)
        real(dp) :: hc_over_hs = 4                !! cube refinement h_c/h_s (Table 5.3: ≥ 4)
        real(dp) :: stretch = 0                   !! growth factor f outside the cube (0: 1.2 hex, 1.5 prism)
        real(dp) :: stretch_far = 0               !! growth factor beyond the grid's extent (0: stretch)
        character(len=24) :: solver = 'spooles'   !! CalculiX solver: spooles, iterative cholesky, iterative scaling
        integer :: threads = 1                    !! threads given to CalculiX
        character(len=256) :: ccx = 'ccx'         !! CalculiX command
        character(len=256) :: workdir = ''        !! work directory ('' : a fresh one under $TMPDIR or /tmp)
        logical :: keep_work = .false.            !! keep the work directory after success
        character(len=8) :: integration = ''      !! 'full' or 'reduced' (C3D20R; quadratic hexahedra only); '': automatic
        logical :: normal_only = .false.          !! run the normal load case only (A^zz, A^xz, A^yz; benchmarks)
    end type fc_fem_params

    !> The generated mesh: axes and lattice node numbering.
    type, public :: fc_fem_mesh_t
        real(dp), allocatable :: xs(:), ys(:), zs(:)  !! cell boundaries per axis (0:n), increasing to 0
        integer :: nxc = 0, nyc = 0, nzc = 0          !! cells per axis
        integer, allocatable :: id(:, :, :)           !! node number at lattice point (0:2n) or 0
        integer :: nnodes = 0, nelems = 0
        logical :: prism = .false.
        integer :: order = 2
        real(dp) :: domain = 0                        !! L [mm]
    end type fc_fem_mesh_t

    integer, parameter :: max_cells_axis = 400        !! cells per axis accepted
    integer(i8), parameter :: max_nodes = 500000_i8   !! nodes accepted (1.5 M unknowns: SPOOLES needs ~20 GB beyond)
    integer(i8), parameter :: auto_nodes = 30000_i8   !! node budget of the automatic stretch

    public :: fem_defaults, fem_validate, build_fem_mesh, write_fem_deck, fem_domain, lattice_coord
    public :: face_shape, face_lattice, top_face_forces, write_deck_physics, close_deck, hex_type, graded_axis
    public :: max_cells_axis, max_nodes

contains

    !> Fill the automatic values of `p` for a grid of nx×ny cells of size dx×dy.
    !! Mesh1 (`hex`, nested boxes): the thesis' f = 1.2 and L = 4·10⁴ × the grid extent (the
    !! clamped faces lower the coefficients near the load by ≈ 1.9 ρ/L, see
    !! doc/numerical_ic.md), at most 10⁷ h_c.  The tensor-product meshes (`tensor`, `prism`):
    !! the thesis' f (1.2, 1.5) when that model has at most `auto_nodes` nodes, else the first
    !! of 1.5, 2, 2.5, 3 that fits (a one-to-two minute CalculiX run on one core).  Reduced
    !! integration for quadratic hexahedra.  Values given explicitly are kept.
    subroutine fem_defaults(p, nx, ny, dx, dy)
        type(fc_fem_params), intent(inout) :: p
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: dx, dy
        real(dp), parameter :: candidates(4) = [1.5_dp, 2.0_dp, 2.5_dp, 3.0_dp]
        integer :: k
        if (p%l_over_hc == 0) then
            select case (p%mesh)
            case ('prism', 'tprism'); p%l_over_hc = max(80.0_dp, 50.0_dp*max(nx, ny))
            case ('tensor'); p%l_over_hc = max(80.0_dp, 400.0_dp*max(nx, ny))
            case default; p%l_over_hc = min(1.0e7_dp, max(80.0_dp, 4.0e4_dp*max(nx, ny)))
            end select
        end if
        if (p%stretch == 0) then
            p%stretch = 1.2_dp
            if (p%mesh == 'prism' .or. p%mesh == 'tprism') p%stretch = 1.5_dp
            do k = 1, size(candidates)
                if (p%mesh == 'hex' .or. p%mesh == 'prism') exit   ! nested boxes/squares: the thesis' f is cheap
                if (model_nodes(p, nx, ny, dx, dy) <= auto_nodes) exit
                if (candidates(k) > p%stretch) p%stretch = candidates(k)
            end do
        end if
        if (p%stretch_far == 0) p%stretch_far = p%stretch
        if (len_trim(p%integration) == 0) then
            p%integration = 'full'
            if ((p%mesh == 'hex' .or. p%mesh == 'tensor') .and. p%order == 2) p%integration = 'reduced'
        end if
    end subroutine fem_defaults

    !> Nodes of the model `p` would build (0 when the axes cannot be built).
    integer(i8) function model_nodes(p, nx, ny, dx, dy) result(count)
        type(fc_fem_params), intent(in) :: p
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: dx, dy
        type(fc_fem_params) :: q
        real(dp), allocatable :: xs(:), ys(:), zs(:)
        integer :: stat, m, ncx, ncy, ncz
        real(dp) :: l, near
        character(len=msg_len) :: msg
        q = p
        if (q%stretch_far == 0) q%stretch_far = q%stretch
        count = huge(1_i8)
        if (q%hc_over_hs < 1 .or. q%stretch < 1.01_dp .or. q%stretch_far < 1.01_dp) return
        l = fem_domain(q, dx, dy)
        near = max((nx + 1)*dx, (ny + 1)*dy)
        m = nint(q%cube_over_hc*q%hc_over_hs)
        call graded_axis(l, dx/q%hc_over_hs, m, q%stretch, near, q%stretch_far, xs, stat, msg); if (stat /= 0) return
        call graded_axis(l, dy/q%hc_over_hs, m, q%stretch, near, q%stretch_far, ys, stat, msg); if (stat /= 0) return
        call graded_axis(l, min(dx, dy)/q%hc_over_hs, m, q%stretch, near, q%stretch_far, zs, stat, msg)
        if (stat /= 0) return
        ncx = ubound(xs, 1); ncy = ubound(ys, 1); ncz = ubound(zs, 1)
        count = int(ncx + 1, i8)*(ncy + 1)*(ncz + 1)
        if (q%order == 2) then
            count = count + int(ncx, i8)*(ncy + 1)*(ncz + 1) + int(ncx + 1, i8)*ncy*(ncz + 1) + &
                int(ncx + 1, i8)*(ncy + 1)*ncz
            if (q%mesh == 'tprism') count = count + int(ncx + 1, i8)*ncy*ncz
        end if
    end function model_nodes

    !> Domain size L [mm] of the model for cells dx×dy.
    pure real(dp) function fem_domain(p, dx, dy) result(l)
        type(fc_fem_params), intent(in) :: p
        real(dp), intent(in) :: dx, dy
        l = p%l_over_hc*max(dx, dy)
    end function fem_domain

    !> Check the parameters (after [[fem_defaults]]) for a grid nx×ny of cells dx×dy; the
    !! message names the `&fem` key, its value and the limit.
    subroutine fem_validate(p, nx, ny, dx, dy, stat, errmsg)
        type(fc_fem_params), intent(in) :: p
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: dx, dy
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: m, l
        stat = FC_ERR_VALUE
        if (p%mesh /= 'hex' .and. p%mesh /= 'prism' .and. p%mesh /= 'tensor' .and. p%mesh /= 'tprism') then
            errmsg = "fem: mesh = '"//trim(p%mesh)//"' must be 'hex', 'prism', 'tensor' or 'tprism'"; return
        end if
        if (p%integration /= 'full' .and. p%integration /= 'reduced') then
            errmsg = "fem: integration = '"//trim(p%integration)//"' must be 'full' or 'reduced'"; return
        end if
        if (p%integration == 'reduced' .and. (p%mesh == 'prism' .or. p%mesh == 'tprism' .or. p%order /= 2)) then
            errmsg = "fem: integration = 'reduced' needs quadratic hexahedra (mesh = 'hex' or 'tensor', order = 2)"; return
        end if
        if (p%order /= 1 .and. p%order /= 2) then
            write (errmsg, '(a,i0,a)') 'fem: order = ', p%order, ' must be 1 (linear) or 2 (quadratic)'; return
        end if
        if (p%load /= 'constant' .and. p%load /= 'bilinear') then
            errmsg = "fem: load = '"//trim(p%load)//"' must be 'constant' or 'bilinear'"; return
        end if
        if (.not. (p%hc_over_hs >= 1 .and. p%hc_over_hs <= 64) .or. abs(p%hc_over_hs - nint(p%hc_over_hs)) > 1e-9_dp) then
            write (errmsg, '(a,g0.6,a)') 'fem: hc_over_hs = ', p%hc_over_hs, ' must be an integer in [1, 64]'; return
        end if
        if (p%load == 'constant' .and. mod(nint(p%hc_over_hs), 2) /= 0) then
            write (errmsg, '(a,g0.6,a)') 'fem: hc_over_hs = ', p%hc_over_hs, &
                " must be even for load = 'constant' (the load edge at h_c/2 must be a mesh line)"; return
        end if
        m = p%cube_over_hc*p%hc_over_hs
        if (.not. (p%cube_over_hc >= 0.5_dp .and. p%cube_over_hc <= 16) .or. abs(m - nint(m)) > 1e-9_dp) then
            write (errmsg, '(a,g0.6,a)') 'fem: cube_over_hc = ', p%cube_over_hc, &
                ' must lie in [0.5, 16] with cube_over_hc*hc_over_hs an integer'; return
        end if
        if (p%load == 'bilinear' .and. p%cube_over_hc < 1) then
            write (errmsg, '(a,g0.6,a)') 'fem: cube_over_hc = ', p%cube_over_hc, &
                " must be >= 1 for load = 'bilinear' (the tent spans one cell)"; return
        end if
        if (.not. (p%stretch >= 1.01_dp .and. p%stretch <= 4)) then
            write (errmsg, '(a,g0.6,a)') 'fem: stretch = ', p%stretch, ' must lie in [1.01, 4]'; return
        end if
        if (.not. (p%stretch_far >= 1.01_dp .and. p%stretch_far <= 4)) then
            write (errmsg, '(a,g0.6,a)') 'fem: stretch_far = ', p%stretch_far, ' must lie in [1.01, 4]'; return
        end if
        l = fem_domain(p, dx, dy)
        if (.not. (l >= 2*max((nx + 1)*dx, (ny + 1)*dy)) .or. .not. (p%l_over_hc <= 1.0e7_dp)) then
            write (errmsg, '(a,g0.6,a,es10.3,a,es10.3,a)') 'fem: l_over_hc = ', p%l_over_hc, ' gives L = ', l, &
                ' mm; need L >= 2*(n+1)*h = ', 2*max((nx + 1)*dx, (ny + 1)*dy), ' mm (and l_over_hc <= 1e7)'; return
        end if
        if (p%threads < 1 .or. p%threads > 64) then
            write (errmsg, '(a,i0,a)') 'fem: threads = ', p%threads, ' must lie in [1, 64]'; return
        end if
        select case (p%solver)
        case ('spooles', 'iterative cholesky', 'iterative scaling', 'pardiso', 'pastix')
        case default
            errmsg = "fem: solver = '"//trim(p%solver)// &
                "' must be 'spooles', 'iterative cholesky', 'iterative scaling', 'pardiso' or 'pastix'"; return
        end select
        if (len_trim(p%ccx) == 0) then
            errmsg = "fem: ccx = '' must name the CalculiX command"; return
        end if
        stat = 0; errmsg = ''
    end subroutine fem_validate

    !> Cell boundaries of one axis from −L to 0: m uniform cells of size hs in [−m·hs, 0],
    !! then growing by f up to `near`, by f_far beyond; the last cell ends at −L (merged with
    !! its neighbour if < half size).
    subroutine graded_axis(l, hs, m, f, near, f_far, xs, stat, errmsg)
        real(dp), intent(in) :: l, hs, f, near, f_far
        integer, intent(in) :: m
        real(dp), allocatable, intent(out) :: xs(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: tmp(0:max_cells_axis + 1), pos, h
        integer :: n, i
        stat = 0; errmsg = ''
        tmp(0) = 0
        do i = 1, m
            tmp(i) = i*hs
        end do
        n = m; pos = m*hs; h = hs
        do while (pos < l)
            if (pos < near) then
                h = h*f
            else
                h = h*f_far
            end if
            if (n >= max_cells_axis) then
                stat = FC_ERR_VALUE
                write (errmsg, '(a,i0,a)') 'fem: the mesh needs more than ', max_cells_axis, &
                    ' cells per axis; raise stretch or lower l_over_hc or hc_over_hs'
                return
            end if
            n = n + 1
            pos = pos + h
            tmp(n) = pos
        end do
        tmp(n) = l
        if (n > m + 1) then
            if (tmp(n) - tmp(n - 1) < 0.5_dp*(tmp(n - 1) - tmp(n - 2))) then
                n = n - 1; tmp(n) = l
            end if
        end if
        allocate (xs(0:n))
        do i = 0, n
            xs(i) = -tmp(n - i)
        end do
        xs(n) = 0
    end subroutine graded_axis

    !> Build the mesh for cells dx×dy (parameters validated).
    subroutine build_fem_mesh(p, nx, ny, dx, dy, mesh, stat, errmsg)
        type(fc_fem_params), intent(in) :: p
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: dx, dy
        type(fc_fem_mesh_t), intent(out) :: mesh
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: m, i, j, k, nodd, n
        integer(i8) :: count
        real(dp) :: l, near
        l = fem_domain(p, dx, dy)
        mesh%domain = l
        near = max((nx + 1)*dx, (ny + 1)*dy)   ! the coefficients are sampled up to here
        m = nint(p%cube_over_hc*p%hc_over_hs)
        call graded_axis(l, dx/p%hc_over_hs, m, p%stretch, near, p%stretch_far, mesh%xs, stat, errmsg)
        if (stat /= 0) return
        call graded_axis(l, dy/p%hc_over_hs, m, p%stretch, near, p%stretch_far, mesh%ys, stat, errmsg)
        if (stat /= 0) return
        call graded_axis(l, min(dx, dy)/p%hc_over_hs, m, p%stretch, near, p%stretch_far, mesh%zs, stat, errmsg)
        if (stat /= 0) return
        mesh%nxc = ubound(mesh%xs, 1); mesh%nyc = ubound(mesh%ys, 1); mesh%nzc = ubound(mesh%zs, 1)
        mesh%prism = p%mesh == 'tprism'
        mesh%order = p%order
        ! count first so that an oversized model is refused before allocating it
        count = int(mesh%nxc + 1, i8)*(mesh%nyc + 1)*(mesh%nzc + 1)
        if (p%order == 2) then
            count = count + 3_i8*mesh%nxc*(mesh%nyc + 1)*(mesh%nzc + 1)
            if (mesh%prism) count = count + int(mesh%nxc + 1, i8)*mesh%nyc*mesh%nzc
        end if
        if (count > max_nodes) then
            stat = FC_ERR_VALUE
            write (errmsg, '(a,i0,a,i0,a)') 'fem: the model has ', count, ' nodes, more than ', max_nodes, &
                '; raise stretch or lower l_over_hc, cube_over_hc or hc_over_hs'
            return
        end if
        allocate (mesh%id(0:2*mesh%nxc, 0:2*mesh%nyc, 0:2*mesh%nzc), source=0)
        n = 0
        do k = 0, 2*mesh%nzc
            do j = 0, 2*mesh%nyc
                do i = 0, 2*mesh%nxc
                    nodd = mod(i, 2) + mod(j, 2) + mod(k, 2)
                    if (p%order == 1) then
                        if (nodd /= 0) cycle
                    else if (nodd > 1) then
                        ! wedges need the mid-points of the y–z diagonals (x even, y and z odd)
                        if (.not. (mesh%prism .and. mod(i, 2) == 0 .and. nodd == 2)) cycle
                    end if
                    n = n + 1
                    mesh%id(i, j, k) = n
                end do
            end do
        end do
        mesh%nnodes = n
        mesh%nelems = mesh%nxc*mesh%nyc*mesh%nzc
        if (mesh%prism) mesh%nelems = 2*mesh%nelems
    end subroutine build_fem_mesh

    !> Coordinate of lattice index `i` on axis `a` (cell boundaries at even indices).
    pure real(dp) function lattice_coord(a, i) result(x)
        real(dp), intent(in) :: a(0:)
        integer, intent(in) :: i
        if (mod(i, 2) == 0) then
            x = a(i/2)
        else
            x = (a(i/2) + a(i/2 + 1))/2
        end if
    end function lattice_coord

    !> Write the CalculiX deck for one load direction to `path`.
    !! g [N/mm²], nu: the body's shear modulus and Poisson ratio; dx, dy: contact cells [mm].
    subroutine write_fem_deck(path, p, mesh, dir, g, nu, dx, dy, stat, errmsg)
        character(len=*), intent(in) :: path
        type(fc_fem_params), intent(in) :: p
        type(fc_fem_mesh_t), intent(in) :: mesh
        integer, intent(in) :: dir
        real(dp), intent(in) :: g, nu, dx, dy
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u, ios, i, j, k, ne
        integer :: c(0:1, 0:1, 0:1)
        character(len=msg_len) :: iomsg
        real(dp), allocatable :: f(:, :), vals(:)
        integer, allocatable :: ids(:)
        open (newunit=u, file=path, status='replace', action='write', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = 'fem: cannot write the CalculiX deck '//trim(path)//': '//trim(iomsg); return
        end if
        write (u, '(a)') '** fastcontact influence-coefficient model (thesis ch. 5), generated'
        write (u, '(a,i0,a,i0,a,i0,a,es12.5)') '** cells ', mesh%nxc, ' x ', mesh%nyc, ' x ', mesh%nzc, ', L = ', mesh%domain
        write (u, '(a)') '*NODE, NSET=NALL'
        do k = 0, 2*mesh%nzc
            do j = 0, 2*mesh%nyc
                do i = 0, 2*mesh%nxc
                    if (mesh%id(i, j, k) == 0) cycle
                    write (u, '(i0,3(",",es19.12))') mesh%id(i, j, k), lattice_coord(mesh%xs, i), &
                        lattice_coord(mesh%ys, j), lattice_coord(mesh%zs, k)
                end do
            end do
        end do
        ! elements
        if (mesh%prism) then
            if (mesh%order == 2) then
                write (u, '(a)') '*ELEMENT, TYPE=C3D15, ELSET=EALL'
            else
                write (u, '(a)') '*ELEMENT, TYPE=C3D6, ELSET=EALL'
            end if
        else
            write (u, '(a)') '*ELEMENT, TYPE='//hex_type(p)//', ELSET=EALL'
        end if
        ne = 0
        do k = 0, mesh%nzc - 1
            do j = 0, mesh%nyc - 1
                do i = 0, mesh%nxc - 1
                    call element_lines(i, j, k)
                end do
            end do
        end do
        ! node sets of the boundary faces and of the top surface (output)
        call write_face_set('NXMIN', 1, 0); call write_face_set('NXZERO', 1, 2*mesh%nxc)
        call write_face_set('NYMIN', 2, 0); call write_face_set('NYZERO', 2, 2*mesh%nyc)
        call write_face_set('NZMIN', 3, 0); call write_face_set('NTOP', 3, 2*mesh%nzc)
        call top_face_forces(p%load, mesh%order, mesh%xs, mesh%ys, dx, dy, f, stat, errmsg)
        if (stat == 0) then
            ids = pack(mesh%id(:, :, 2*mesh%nzc), f /= 0); vals = pack(f, f /= 0)
            call write_deck_physics(u, p, dir, g, nu, ['NXMIN', 'NYMIN', 'NZMIN'], ids, vals)
        end if
        call close_deck(u, path, stat, errmsg)
    contains

        subroutine element_lines(i, j, k)
            integer, intent(in) :: i, j, k
            integer :: a, b, d
            do d = 0, 1
                do b = 0, 1
                    do a = 0, 1
                        c(a, b, d) = mesh%id(2*(i + a), 2*(j + b), 2*(k + d))
                    end do
                end do
            end do
            if (.not. mesh%prism) then
                ne = ne + 1
                if (mesh%order == 1) then
                    write (u, '(i0,8(",",i0))') ne, c(0, 0, 0), c(1, 0, 0), c(1, 1, 0), c(0, 1, 0), &
                        c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)
                else
                    ! corners, mid-edges of the bottom and top faces, then the vertical edges
                    write (u, '(i0,15(",",i0),",")') ne, c(0, 0, 0), c(1, 0, 0), c(1, 1, 0), c(0, 1, 0), &
                        c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1), &
                        mid(2*i + 1, 2*j, 2*k), mid(2*i + 2, 2*j + 1, 2*k), mid(2*i + 1, 2*j + 2, 2*k), &
                        mid(2*i, 2*j + 1, 2*k), mid(2*i + 1, 2*j, 2*k + 2), mid(2*i + 2, 2*j + 1, 2*k + 2), &
                        mid(2*i + 1, 2*j + 2, 2*k + 2)
                    write (u, '(i0,4(",",i0))') mid(2*i, 2*j + 1, 2*k + 2), &
                        mid(2*i, 2*j, 2*k + 1), mid(2*i + 2, 2*j, 2*k + 1), mid(2*i + 2, 2*j + 2, 2*k + 1), &
                        mid(2*i, 2*j + 2, 2*k + 1)
                end if
            else
                ! two wedges per cell; triangles in the y–z plane (counter-clockwise in (y, z)),
                ! extruded along x: T1 = (j,k),(j+1,k),(j+1,k+1); T2 = (j,k),(j+1,k+1),(j,k+1)
                call wedge(i, [2*j, 2*j + 2, 2*j + 2], [2*k, 2*k, 2*k + 2])
                call wedge(i, [2*j, 2*j + 2, 2*j], [2*k, 2*k + 2, 2*k + 2])
            end if
        end subroutine element_lines

        subroutine wedge(i, jy, kz)
            integer, intent(in) :: i, jy(3), kz(3)
            integer :: t0(3), t1(3), m0(3), m1(3), mv(3), q, r
            do q = 1, 3
                r = mod(q, 3) + 1
                t0(q) = mesh%id(2*i, jy(q), kz(q))
                t1(q) = mesh%id(2*i + 2, jy(q), kz(q))
                m0(q) = mid(2*i, (jy(q) + jy(r))/2, (kz(q) + kz(r))/2)
                m1(q) = mid(2*i + 2, (jy(q) + jy(r))/2, (kz(q) + kz(r))/2)
                mv(q) = mid(2*i + 1, jy(q), kz(q))
            end do
            ne = ne + 1
            if (mesh%order == 1) then
                write (u, '(i0,6(",",i0))') ne, t0, t1
            else
                write (u, '(i0,15(",",i0))') ne, t0, t1, m0, m1, mv
            end if
        end subroutine wedge

        integer function mid(a, b, d)
            integer, intent(in) :: a, b, d
            mid = mesh%id(a, b, d)
        end function mid

        !> Node set of the lattice plane index `val` of axis `axis`.
        subroutine write_face_set(name, axis, val)
            character(len=*), intent(in) :: name
            integer, intent(in) :: axis, val
            integer, allocatable :: ids(:)
            integer :: q
            select case (axis)
            case (1); ids = pack(mesh%id(val, :, :), mesh%id(val, :, :) > 0)
            case (2); ids = pack(mesh%id(:, val, :), mesh%id(:, val, :) > 0)
            case default; ids = pack(mesh%id(:, :, val), mesh%id(:, :, val) > 0)
            end select
            write (u, '(a)') '*NSET, NSET='//name
            do q = 1, size(ids), 16
                write (u, '(i0,15(",",i0:))') ids(q:min(q + 15, size(ids)))
            end do
        end subroutine write_face_set

    end subroutine write_fem_deck

    !> CalculiX type of the hexahedra of `p`: C3D20 / C3D20R (reduced integration) or C3D8.
    function hex_type(p) result(t)
        type(fc_fem_params), intent(in) :: p
        character(len=:), allocatable :: t
        if (p%order == 1) then
            t = 'C3D8'
        else if (p%integration == 'reduced') then
            t = 'C3D20R'
        else
            t = 'C3D20'
        end if
    end function hex_type

    !> Equivalent nodal forces f(lattice i, lattice j) of the unit traction (constant on
    !! [−dx/2,0]×[−dy/2,0] or the tent on [−dx,0]×[−dy,0]) on a tensor grid of top faces with
    !! cell boundaries xs, ys (increasing to 0); 4×4 Gauss points per face.
    subroutine top_face_forces(load, order, xs, ys, dx, dy, f, stat, errmsg)
        character(len=*), intent(in) :: load
        integer, intent(in) :: order
        real(dp), intent(in) :: xs(0:), ys(0:), dx, dy
        real(dp), allocatable, intent(out) :: f(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: gp(4), gw(4), xa, xb, ya, yb, xi, eta, x, y, w, t, nsh(8), ext_x, ext_y
        integer :: ii, jj, q1, q2, a, nn, li, lj, nxc, nyc
        gp = [-0.861136311594053_dp, -0.339981043584856_dp, 0.339981043584856_dp, 0.861136311594053_dp]
        gw = [0.347854845137454_dp, 0.652145154862546_dp, 0.652145154862546_dp, 0.347854845137454_dp]
        stat = 0; errmsg = ''
        nxc = ubound(xs, 1); nyc = ubound(ys, 1)
        allocate (f(0:2*nxc, 0:2*nyc), source=0.0_dp)
        if (load == 'constant') then
            ext_x = dx/2; ext_y = dy/2
        else
            ext_x = dx; ext_y = dy
        end if
        nn = 8; if (order == 1) nn = 4
        do jj = 0, nyc - 1
            ya = ys(jj); yb = ys(jj + 1)
            if (yb <= -ext_y*(1 - 1e-9_dp)) cycle
            if (ya < -ext_y*(1 + 1e-9_dp)) then
                stat = FC_ERR_INTERNAL; errmsg = 'fem: internal error: the load edge in y is not a mesh line'; return
            end if
            do ii = 0, nxc - 1
                xa = xs(ii); xb = xs(ii + 1)
                if (xb <= -ext_x*(1 - 1e-9_dp)) cycle
                if (xa < -ext_x*(1 + 1e-9_dp)) then
                    stat = FC_ERR_INTERNAL; errmsg = 'fem: internal error: the load edge in x is not a mesh line'; return
                end if
                do q2 = 1, 4
                    do q1 = 1, 4
                        xi = gp(q1); eta = gp(q2)
                        x = (xa + xb)/2 + xi*(xb - xa)/2
                        y = (ya + yb)/2 + eta*(yb - ya)/2
                        t = 1
                        if (load /= 'constant') t = (1 - abs(x)/dx)*(1 - abs(y)/dy)
                        w = gw(q1)*gw(q2)*(xb - xa)*(yb - ya)/4*t
                        call face_shape(order, xi, eta, nsh)
                        do a = 1, nn
                            call face_lattice(ii, jj, a, li, lj)
                            f(li, lj) = f(li, lj) + w*nsh(a)
                        end do
                    end do
                end do
            end do
        end do
    end subroutine top_face_forces

    !> The part of a deck common to every mesh: material, the clamped node sets `clamped`,
    !! the symmetry conditions of thesis Table 5.1 on the node sets NXZERO and NYZERO for the
    !! load direction `dir`, the static step with the nodal forces `vals` (unit traction,
    !! before the sign of the direction) on nodes `ids`, and the output of node set NTOP.
    subroutine write_deck_physics(u, p, dir, g, nu, clamped, ids, vals)
        integer, intent(in) :: u, dir
        type(fc_fem_params), intent(in) :: p
        real(dp), intent(in) :: g, nu, vals(:)
        character(len=*), intent(in) :: clamped(:)
        integer, intent(in) :: ids(:)
        integer :: q, dofc
        real(dp) :: sgn
        write (u, '(a)') '*MATERIAL, NAME=BODY'
        write (u, '(a)') '*ELASTIC'
        write (u, '(es19.12,",",es19.12)') 2*g*(1 + nu), nu
        write (u, '(a)') '*SOLID SECTION, ELSET=EALL, MATERIAL=BODY'
        write (u, '(a)') '*BOUNDARY'
        do q = 1, size(clamped)
            write (u, '(a)') trim(clamped(q))//',1,3,0.'
        end do
        select case (dir)
        case (FEM_LOAD_Z)   ! symmetric about x = 0 and y = 0
            write (u, '(a)') 'NXZERO,1,1,0.'
            write (u, '(a)') 'NYZERO,2,2,0.'
        case (FEM_LOAD_X)   ! antisymmetric about x = 0, symmetric about y = 0
            write (u, '(a)') 'NXZERO,2,3,0.'
            write (u, '(a)') 'NYZERO,2,2,0.'
        case (FEM_LOAD_Y)   ! symmetric about x = 0, antisymmetric about y = 0
            write (u, '(a)') 'NXZERO,1,1,0.'
            write (u, '(a)') 'NYZERO,1,1,0.'
            write (u, '(a)') 'NYZERO,3,3,0.'
        end select
        write (u, '(a)') '*STEP'
        select case (p%solver)
        case ('spooles'); write (u, '(a)') '*STATIC, SOLVER=SPOOLES'
        case ('iterative cholesky'); write (u, '(a)') '*STATIC, SOLVER=ITERATIVE CHOLESKY'
        case ('iterative scaling'); write (u, '(a)') '*STATIC, SOLVER=ITERATIVE SCALING'
        case ('pardiso'); write (u, '(a)') '*STATIC, SOLVER=PARDISO'
        case ('pastix'); write (u, '(a)') '*STATIC, SOLVER=PASTIX'
        end select
        select case (dir)
        case (FEM_LOAD_Z); dofc = 3; sgn = -1   ! pressure pushes into the body
        case (FEM_LOAD_X); dofc = 1; sgn = 1
        case default; dofc = 2; sgn = 1
        end select
        write (u, '(a)') '*CLOAD'
        do q = 1, size(ids)
            write (u, '(i0,",",i0,",",es19.12)') ids(q), dofc, sgn*vals(q)
        end do
        write (u, '(a)') '*NODE PRINT, NSET=NTOP'
        write (u, '(a)') 'U'
        write (u, '(a)') '*END STEP'
    end subroutine write_deck_physics

    !> Lattice indices of local node `a` of top face (ii, jj): corners (−,−), (+,−), (+,+),
    !! (−,+), then mid-sides bottom, right, top, left (the order of [[face_shape]]).
    pure subroutine face_lattice(ii, jj, a, li, lj)
        integer, intent(in) :: ii, jj, a
        integer, intent(out) :: li, lj
        integer, parameter :: ox(8) = [0, 2, 2, 0, 1, 2, 1, 0], oy(8) = [0, 0, 2, 2, 0, 1, 2, 1]
        li = 2*ii + ox(a); lj = 2*jj + oy(a)
    end subroutine face_lattice

    !> Shape functions of a quadrilateral face at (ξ, η) ∈ [−1,1]²: 8-node serendipity
    !! (order 2) or bilinear (order 1), node order as in [[face_lattice]].
    pure subroutine face_shape(order, xi, eta, n)
        integer, intent(in) :: order
        real(dp), intent(in) :: xi, eta
        real(dp), intent(out) :: n(8)
        real(dp), parameter :: sx(4) = [-1, 1, 1, -1], sy(4) = [-1, -1, 1, 1]
        integer :: a
        n = 0
        if (order == 1) then
            do a = 1, 4
                n(a) = (1 + sx(a)*xi)*(1 + sy(a)*eta)/4
            end do
        else
            do a = 1, 4
                n(a) = (1 + sx(a)*xi)*(1 + sy(a)*eta)*(sx(a)*xi + sy(a)*eta - 1)/4
            end do
            n(5) = (1 - xi**2)*(1 - eta)/2
            n(6) = (1 + xi)*(1 - eta**2)/2
            n(7) = (1 - xi**2)*(1 + eta)/2
            n(8) = (1 - xi)*(1 - eta**2)/2
        end if
    end subroutine face_shape


    !> Finish a CalculiX deck written on unit `u`: deleted when `stat` ≠ 0 (no half-written
    !! deck survives an error), else closed with its I/O status checked.
    subroutine close_deck(u, path, stat, errmsg)
        integer, intent(in) :: u
        character(len=*), intent(in) :: path
        integer, intent(inout) :: stat
        character(len=*), intent(inout) :: errmsg
        integer :: ios
        character(len=msg_len) :: iomsg
        if (stat /= 0) then
            close (u, status='delete'); return
        end if
        close (u, iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = 'fem: cannot write the CalculiX deck '//trim(path)//': '//trim(iomsg); return
        end if
        stat = 0; errmsg = ''
    end subroutine close_deck

end module fc_fem_mesh
