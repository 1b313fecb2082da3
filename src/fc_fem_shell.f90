!> Mesh1 of thesis §5.3.1 (`&fem mesh = 'hex'`): hexahedra in nested boxes.
!!
!! The thesis covers the load by a uniform cube of m³ cells, lets the element size grow by f
!! leaving the loaded area and divides "edges that do not contain the small cube uniformly
!! into m intervals": every box around the cube keeps m cells per edge.  (A tensor product of
!! graded axes, `mesh = 'tensor'`, continues the fine cube cells as thin slabs along every
!! axis out to L instead: (cells per axis)³ elements, stretched by up to f^n.)  Here the uniform cube [−l_x,0]×[−l_y,0]×[−l_z,0]
!! (m cells per edge, h_s = l/m) is wrapped in layers: the outer surface of the cube (its three
!! faces x = −l_x, y = −l_y, z = −l_z, m×m cells each) is scaled about the origin by σ_1 < σ_2
!! < … and every face cell between two scales is one hexahedron.  Layer k is f times thicker
!! than layer k−1 (f_far beyond the grid's extent), the last ends at L.  Every layer keeps
!! 3m² elements, each about σ·l/m wide and (f−1)·σ·l thick: the element size grows in
!! proportion to the distance from the load, so the total is m³ + 3m²·(layers), e.g. 2 900
!! C3D20 for the thesis' f = 1.2, m = 4 and L/h_s = 2.6·10⁵.  The elements are frustums
!! with straight edges (mid-edge nodes at the edge midpoints), so on the top surface the
!! map of a face is exactly (ξ, η) ↦ (scale, tangential fraction), which [[shell_surface_value]]
!! inverts in closed form.
!!
!! Nodes: cube lattice (I, J, K) ∈ [0, 2m]³ at position −(l_x I, l_y J, l_z K)/(2m); layer
!! half-level q = 1 … 2·nl holds the surface lattice points (max(I, J, K) = 2m) scaled by
!! σ(q) (odd q: the radial mid-edge nodes).  Quadratic: serendipity nodes (at most one odd
!! lattice index); linear: even indices only.
module fc_fem_shell
    use fc_kinds, only: dp, i8, FC_ERR_VALUE, FC_ERR_IO
    use fc_fem_mesh, only: fc_fem_params, face_shape, face_lattice, top_face_forces, write_deck_physics, close_deck, hex_type, &
        fem_domain, max_cells_axis, max_nodes
    implicit none
    private

    !> The nested-box mesh.
    type, public :: fc_fem_shell_t
        integer :: m = 0                            !! cube cells per edge
        integer :: nl = 0                           !! layers around the cube
        integer :: order = 2
        real(dp) :: lx = 0, ly = 0, lz = 0          !! cube edges [mm]
        real(dp), allocatable :: sigma(:)           !! (0:2nl) scale of half-level q (σ(0) = 1: the cube)
        integer, allocatable :: idc(:, :, :)        !! (0:2m)³ cube node numbers (0: no node)
        integer, allocatable :: ids(:, :, :, :)     !! (0:2m, 0:2m, 0:2m, 1:2nl) layer node numbers
        integer :: nnodes = 0, nelems = 0
        real(dp) :: domain = 0                      !! L [mm]
    end type fc_fem_shell_t

    public :: build_shell_mesh, write_shell_deck, shell_surface_value, shell_top_nodes, box_levels

contains

    !> Build the mesh for cells dx×dy with the parameters `p` (validated; cube_over_hc·hc_over_hs
    !! cells per cube edge, stretch inside the grid's extent, stretch_far beyond).
    subroutine build_shell_mesh(p, nx, ny, dx, dy, mesh, stat, errmsg)
        type(fc_fem_params), intent(in) :: p
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: dx, dy
        type(fc_fem_shell_t), intent(out) :: mesh
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: lmax, smax, near
        integer :: n, m, i, j, k, q, nn
        integer(i8) :: count
        stat = FC_ERR_VALUE
        m = nint(p%cube_over_hc*p%hc_over_hs)
        mesh%m = m; mesh%order = p%order
        mesh%lx = m*dx/p%hc_over_hs; mesh%ly = m*dy/p%hc_over_hs; mesh%lz = m*min(dx, dy)/p%hc_over_hs
        mesh%domain = fem_domain(p, dx, dy)
        lmax = max(mesh%lx, mesh%ly)
        smax = mesh%domain/lmax
        near = max((nx + 1)*dx, (ny + 1)*dy)/lmax
        call box_levels(p, m, smax, near, mesh%sigma, n, stat, errmsg); if (stat /= 0) return
        mesh%nl = n
        stat = FC_ERR_VALUE
        ! count before allocating: (2m+1)³ lattice in the cube, 3(2m)²+3(2m)+1 surface points per level
        count = int(2*m + 1, i8)**3 + int(2*n, i8)*(3_i8*(2*m)**2 + 3_i8*(2*m) + 1)
        if (count > 4*max_nodes) then
            write (errmsg, '(a,i0,a)') 'fem: the shell mesh would have more than ', 4*max_nodes, &
                ' lattice points; raise stretch or lower hc_over_hs or cube_over_hc'
            return
        end if
        allocate (mesh%idc(0:2*m, 0:2*m, 0:2*m), source=0)
        allocate (mesh%ids(0:2*m, 0:2*m, 0:2*m, 1:2*n), source=0)
        nn = 0
        do k = 0, 2*m
            do j = 0, 2*m
                do i = 0, 2*m
                    if (.not. exists(i, j, k, .false.)) cycle
                    nn = nn + 1; mesh%idc(i, j, k) = nn
                end do
            end do
        end do
        do q = 1, 2*n
            do k = 0, 2*m
                do j = 0, 2*m
                    do i = 0, 2*m
                        if (max(i, j, k) /= 2*m) cycle
                        if (.not. exists(i, j, k, mod(q, 2) == 1)) cycle
                        nn = nn + 1; mesh%ids(i, j, k, q) = nn
                    end do
                end do
            end do
        end do
        mesh%nnodes = nn
        if (nn > max_nodes) then
            write (errmsg, '(a,i0,a,i0,a)') 'fem: the model has ', nn, ' nodes, more than ', max_nodes, &
                '; raise stretch or lower l_over_hc, cube_over_hc or hc_over_hs'
            return
        end if
        mesh%nelems = m**3 + 3*m*m*n
        stat = 0; errmsg = ''
    contains
        logical function exists(i, j, k, radial_mid)
            integer, intent(in) :: i, j, k
            logical, intent(in) :: radial_mid
            integer :: nodd
            nodd = mod(i, 2) + mod(j, 2) + mod(k, 2)
            if (p%order == 1) then
                exists = nodd == 0 .and. .not. radial_mid
            else if (radial_mid) then
                exists = nodd == 0
            else
                exists = nodd <= 1
            end if
        end function exists
    end subroutine build_shell_mesh

    !> Scales σ(0:2n) of the half-levels of n nested boxes around a cube of m cells per edge
    !! (σ(0) = 1 the cube, σ(2n) = smax; odd q: the radial mid-points): layer k is h_s·f^k
    !! thick (in cube units 1/m), f = stretch inside `near`, stretch_far beyond; the last layer
    !! is merged with its neighbour if it is less than half as thick.
    subroutine box_levels(p, m, smax, near, sigma, n, stat, errmsg)
        type(fc_fem_params), intent(in) :: p
        integer, intent(in) :: m
        real(dp), intent(in) :: smax, near
        real(dp), allocatable, intent(out) :: sigma(:)
        integer, intent(out) :: n, stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: tmp(0:max_cells_axis + 1), h
        integer :: k
        stat = FC_ERR_VALUE
        tmp(0) = 1; n = 0; h = 1.0_dp/m
        do while (tmp(n) < smax)
            if (tmp(n) < near) then
                h = h*p%stretch
            else
                h = h*p%stretch_far
            end if
            if (n >= max_cells_axis) then
                write (errmsg, '(a,i0,a)') 'fem: the mesh needs more than ', max_cells_axis, &
                    ' layers; raise stretch or lower l_over_hc or hc_over_hs'
                return
            end if
            n = n + 1
            tmp(n) = tmp(n - 1) + h
        end do
        tmp(n) = smax
        if (n > 1) then
            if (tmp(n) - tmp(n - 1) < 0.5_dp*(tmp(n - 1) - tmp(n - 2))) then
                n = n - 1; tmp(n) = smax
            end if
        end if
        allocate (sigma(0:2*n))
        do k = 0, n
            sigma(2*k) = tmp(k)
            if (k > 0) sigma(2*k - 1) = (tmp(k - 1) + tmp(k))/2
        end do
        stat = 0; errmsg = ''
    end subroutine box_levels

    !> Node number at half-level q (0: the cube) and lattice (i, j, k).
    pure integer function node_id(mesh, q, i, j, k) result(id)
        type(fc_fem_shell_t), intent(in) :: mesh
        integer, intent(in) :: q, i, j, k
        if (q == 0) then
            id = mesh%idc(i, j, k)
        else
            id = mesh%ids(i, j, k, q)
        end if
    end function node_id

    !> Position of the node at half-level q and lattice (i, j, k) [mm].
    pure function node_xyz(mesh, q, i, j, k) result(x)
        type(fc_fem_shell_t), intent(in) :: mesh
        integer, intent(in) :: q, i, j, k
        real(dp) :: x(3)
        x = -mesh%sigma(q)*[mesh%lx*i, mesh%ly*j, mesh%lz*k]/(2*mesh%m)
    end function node_xyz

    !> Half-level q and lattice l of local node (r, s, t) ∈ [0,2]³ of a hexahedron: lay = 0 the
    !! cube cell with lattice origin o; lay ≥ 1 the cell of face fc (1: x = −σl_x, 2: y, 3: z)
    !! with tangential lattice origin o(1:2) between the scales of layer lay (r radial).
    pure subroutine local_node(mesh, lay, o, fc, r, s, t, q, l)
        type(fc_fem_shell_t), intent(in) :: mesh
        integer, intent(in) :: lay, o(3), fc, r, s, t
        integer, intent(out) :: q, l(3)
        if (lay == 0) then
            q = 0; l = o + [r, s, t]
        else
            q = 2*(lay - 1) + r
            select case (fc)
            case (1); l = [2*mesh%m, o(1) + s, o(2) + t]
            case (2); l = [o(1) + s, 2*mesh%m, o(2) + t]
            case default; l = [o(1) + s, o(2) + t, 2*mesh%m]
            end select
        end if
    end subroutine local_node

    !> Node numbers nd(r, s, t) of one hexahedron (see [[local_node]]), local axes 2 and 3
    !! swapped when needed so that (r, s, t) is right-handed (positive Jacobian).
    pure subroutine hexa_nodes(mesh, lay, o, fc, nd)
        type(fc_fem_shell_t), intent(in) :: mesh
        integer, intent(in) :: lay, o(3), fc
        integer, intent(out) :: nd(0:2, 0:2, 0:2)
        integer :: r, s, t, q, l(3), tmp(0:2, 0:2, 0:2)
        real(dp) :: p0(3), e1(3), e2(3), e3(3), vol
        do t = 0, 2
            do s = 0, 2
                do r = 0, 2
                    call local_node(mesh, lay, o, fc, r, s, t, q, l)
                    nd(r, s, t) = node_id(mesh, q, l(1), l(2), l(3))
                end do
            end do
        end do
        call local_node(mesh, lay, o, fc, 0, 0, 0, q, l); p0 = node_xyz(mesh, q, l(1), l(2), l(3))
        call local_node(mesh, lay, o, fc, 2, 0, 0, q, l); e1 = node_xyz(mesh, q, l(1), l(2), l(3)) - p0
        call local_node(mesh, lay, o, fc, 0, 2, 0, q, l); e2 = node_xyz(mesh, q, l(1), l(2), l(3)) - p0
        call local_node(mesh, lay, o, fc, 0, 0, 2, q, l); e3 = node_xyz(mesh, q, l(1), l(2), l(3)) - p0
        vol = dot_product([e1(2)*e2(3) - e1(3)*e2(2), e1(3)*e2(1) - e1(1)*e2(3), e1(1)*e2(2) - e1(2)*e2(1)], e3)
        if (vol < 0) then
            tmp = nd
            do t = 0, 2
                do s = 0, 2
                    nd(:, s, t) = tmp(:, t, s)
                end do
            end do
        end if
    end subroutine hexa_nodes

    !> Node numbers of the top surface (NTOP), in any order.
    function shell_top_nodes(mesh) result(ids)
        type(fc_fem_shell_t), intent(in) :: mesh
        integer, allocatable :: ids(:)
        ids = [pack(mesh%idc(:, :, 0), mesh%idc(:, :, 0) > 0), pack(mesh%ids(:, :, 0, :), mesh%ids(:, :, 0, :) > 0)]
    end function shell_top_nodes

    !> Write the CalculiX deck of the nested-box mesh for load direction `dir`.
    subroutine write_shell_deck(path, p, mesh, dir, g, nu, dx, dy, stat, errmsg)
        character(len=*), intent(in) :: path
        type(fc_fem_params), intent(in) :: p
        type(fc_fem_shell_t), intent(in) :: mesh
        integer, intent(in) :: dir
        real(dp), intent(in) :: g, nu, dx, dy
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u, ios, i, j, k, q, m, ne, face, a, b, lay
        real(dp), allocatable :: f(:, :), vals(:), axis(:)
        integer, allocatable :: ids(:), lat(:, :)
        character(len=256) :: iomsg
        m = mesh%m
        open (newunit=u, file=path, status='replace', action='write', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = 'fem: cannot write the CalculiX deck '//trim(path)//': '//trim(iomsg); return
        end if
        write (u, '(a)') '** fastcontact influence-coefficient model (nested boxes), generated'
        write (u, '(a,i0,a,i0,a,es12.5)') '** cube ', m, '^3 cells, ', mesh%nl, ' layers, L = ', mesh%domain
        write (u, '(a)') '*NODE, NSET=NALL'
        do q = 0, 2*mesh%nl
            do k = 0, 2*m
                do j = 0, 2*m
                    do i = 0, 2*m
                        if (node_id(mesh, q, i, j, k) == 0) cycle
                        write (u, '(i0,3(",",es19.12))') node_id(mesh, q, i, j, k), node_xyz(mesh, q, i, j, k)
                    end do
                end do
            end do
        end do
        write (u, '(a)') '*ELEMENT, TYPE='//hex_type(p)//', ELSET=EALL'
        ne = 0
        do k = 0, m - 1
            do j = 0, m - 1
                do i = 0, m - 1
                    call hexa(0, [2*i, 2*j, 2*k], 0)
                end do
            end do
        end do
        do lay = 1, mesh%nl
            do face = 1, 3
                do b = 0, m - 1
                    do a = 0, m - 1
                        call hexa(lay, [2*a, 2*b, 0], face)
                    end do
                end do
            end do
        end do
        ! node sets: symmetry planes, top surface, the clamped outer boundary
        call write_set('NXZERO', pack_nodes(1)); call write_set('NYZERO', pack_nodes(2))
        call write_set('NTOP', shell_top_nodes(mesh))
        call write_set('NOUTER', pack(mesh%ids(:, :, :, 2*mesh%nl), mesh%ids(:, :, :, 2*mesh%nl) > 0))
        ! the load lies in the cube: its top faces form a tensor grid
        allocate (axis(0:m))
        axis = [(-mesh%lx*(m - i)/m, i = 0, m)]
        call top_face_forces(p%load, mesh%order, axis, [(-mesh%ly*(m - i)/m, i = 0, m)], dx, dy, f, stat, errmsg)
        if (stat == 0) then
            ! force lattice (0:2m, increasing to 0) → cube lattice (index 2m at −l, 0 at 0)
            allocate (lat(0:2*m, 0:2*m))
            do j = 0, 2*m
                do i = 0, 2*m
                    lat(i, j) = mesh%idc(2*m - i, 2*m - j, 0)
                end do
            end do
            ids = pack(lat, f /= 0); vals = pack(f, f /= 0)
            call write_deck_physics(u, p, dir, g, nu, ['NOUTER'], ids, vals)
        end if
        call close_deck(u, path, stat, errmsg)
    contains

        !> Nodes on the plane lattice index 0 of axis `axis_` (x = 0 or y = 0).
        function pack_nodes(axis_) result(list)
            integer, intent(in) :: axis_
            integer, allocatable :: list(:)
            if (axis_ == 1) then
                list = [pack(mesh%idc(0, :, :), mesh%idc(0, :, :) > 0), pack(mesh%ids(0, :, :, :), mesh%ids(0, :, :, :) > 0)]
            else
                list = [pack(mesh%idc(:, 0, :), mesh%idc(:, 0, :) > 0), pack(mesh%ids(:, 0, :, :), mesh%ids(:, 0, :, :) > 0)]
            end if
        end function pack_nodes

        subroutine write_set(name, list)
            character(len=*), intent(in) :: name
            integer, intent(in) :: list(:)
            integer :: r
            write (u, '(a)') '*NSET, NSET='//name
            do r = 1, size(list), 16
                write (u, '(i0,15(",",i0:))') list(r:min(r + 15, size(list)))
            end do
        end subroutine write_set

        subroutine hexa(lay, o, fc)
            integer, intent(in) :: lay, o(3), fc
            integer :: nd(0:2, 0:2, 0:2)
            call hexa_nodes(mesh, lay, o, fc, nd)
            ne = ne + 1
            if (mesh%order == 1) then
                write (u, '(i0,8(",",i0))') ne, nd(0, 0, 0), nd(2, 0, 0), nd(2, 2, 0), nd(0, 2, 0), &
                    nd(0, 0, 2), nd(2, 0, 2), nd(2, 2, 2), nd(0, 2, 2)
            else
                write (u, '(i0,15(",",i0),",")') ne, nd(0, 0, 0), nd(2, 0, 0), nd(2, 2, 0), nd(0, 2, 0), &
                    nd(0, 0, 2), nd(2, 0, 2), nd(2, 2, 2), nd(0, 2, 2), &
                    nd(1, 0, 0), nd(2, 1, 0), nd(1, 2, 0), nd(0, 1, 0), nd(1, 0, 2), nd(2, 1, 2), nd(1, 2, 2)
                write (u, '(i0,4(",",i0))') nd(0, 1, 2), nd(0, 0, 1), nd(2, 0, 1), nd(2, 2, 1), nd(0, 2, 1)
            end if
        end subroutine hexa
    end subroutine write_shell_deck

    !> Interpolate nodal values u(node, comp) of the top surface at (x, y) ≤ 0 with the shape
    !! functions of the face containing the point (inverse map in closed form); with `c`
    !! present, w·u with w = sqrt(x² + y² + c²) is interpolated and divided by w.
    function shell_surface_value(mesh, u, x, y, c) result(v)
        type(fc_fem_shell_t), intent(in) :: mesh
        real(dp), intent(in) :: u(:, :), x, y
        real(dp), intent(in), optional :: c
        real(dp) :: v(3), xx, yy, s, t, xi, eta, nsh(8), w, pxy(3)
        integer :: ci, cj, a, li, lj, nn, lay, q, lo, hi, mid, l(3), m, id
        m = mesh%m
        xx = -x/mesh%lx; yy = -y/mesh%ly          ! cube units, cube = [0, 1]²
        nn = 8; if (mesh%order == 1) nn = 4
        v = 0
        s = max(xx, yy)
        if (s <= 1) then
            ci = min(int(xx*m), m - 1); cj = min(int(yy*m), m - 1)
            xi = 2*(xx*m - ci) - 1; eta = 2*(yy*m - cj) - 1
            call face_shape(mesh%order, xi, eta, nsh)
            do a = 1, nn
                call face_lattice(ci, cj, a, li, lj)
                call add(0, [li, lj, 0])
            end do
        else
            lo = 0; hi = mesh%nl                 ! layer with σ(2lo) ≤ s ≤ σ(2hi)
            do while (hi - lo > 1)
                mid = (lo + hi)/2
                if (mesh%sigma(2*mid) <= s) then
                    lo = mid
                else
                    hi = mid
                end if
            end do
            lay = min(lo + 1, mesh%nl)
            xi = 2*(s - mesh%sigma(2*lay - 2))/(mesh%sigma(2*lay) - mesh%sigma(2*lay - 2)) - 1
            t = min(xx, yy)/s*m
            cj = min(int(t), m - 1)
            eta = 2*(t - cj) - 1
            call face_shape(mesh%order, xi, eta, nsh)
            do a = 1, nn
                call face_lattice(0, cj, a, li, lj)   ! li: radial 0..2, lj: tangential lattice
                q = 2*(lay - 1) + li
                if (xx >= yy) then
                    l = [2*m, lj, 0]
                else
                    l = [lj, 2*m, 0]
                end if
                call add(q, l)
            end do
        end if
        if (present(c)) v = v/sqrt(x**2 + y**2 + c**2)
    contains
        subroutine add(q_, l_)
            integer, intent(in) :: q_, l_(3)
            id = node_id(mesh, q_, l_(1), l_(2), l_(3))
            w = 1
            if (present(c)) then
                pxy = node_xyz(mesh, q_, l_(1), l_(2), l_(3))
                w = sqrt(pxy(1)**2 + pxy(2)**2 + c**2)
            end if
            v = v + nsh(a)*w*u(id, :)
        end subroutine add
    end function shell_surface_value

end module fc_fem_shell
