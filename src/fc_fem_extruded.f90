!> Mesh2 of thesis §5.3.1 as the thesis describes it (`&fem mesh = 'prism'`): prisms whose
!! triangular faces lie in the cross-sections x = const, extruded along x.
!!
!! The cross-section (y, z) is the front surface of Mesh1 (nested squares: the square
!! [−l_y,0]×[−l_z,0] of m×m cells, then layers of 2m cells growing by f, see [[fc_fem_shell]]),
!! every quadrilateral split along its diagonal into two triangles; along x the graded axis
!! of the tensor meshes (m uniform cells over [−l_x, 0], then growing by f to −L).  The top
!! surface is then a tensor grid (x graded, y the cross-section's top edge): strips of width
!! h_s along x next to the axis, stretched as L grows, as in the thesis.
!!
!! Nodes: x lattice i ∈ [0, 2n_x] (even: cell boundaries); cross-section lattice (J, K) at
!! half-level q (0: the square, all (J, K) ∈ [0, 2m]²; q ≥ 1: max(J, K) = 2m).  Odd q with an
!! odd tangential index is the mid-point of a layer quadrilateral's diagonal (the edge shared
!! by its two triangles), placed at the straight diagonal's mid-point.
module fc_fem_extruded
    use fc_kinds, only: dp, i8, FC_ERR_VALUE, FC_ERR_IO
    use fc_fem_mesh, only: fc_fem_params, fc_fem_mesh_t, top_face_forces, write_deck_physics, close_deck, fem_domain, &
        graded_axis, max_nodes, lattice_coord
    use fc_fem_shell, only: box_levels
    implicit none
    private

    !> The extruded prism mesh.
    type, public :: fc_fem_extruded_t
        integer :: m = 0, nl = 0, nxc = 0, order = 2
        real(dp) :: ly = 0, lz = 0, domain = 0
        real(dp), allocatable :: xs(:)                 !! x cell boundaries (0:nxc), increasing to 0
        real(dp), allocatable :: sigma(:)              !! (0:2nl) scales of the cross-section's half-levels
        integer, allocatable :: id(:, :, :, :)         !! (0:2nxc, 0:2m, 0:2m, 0:2nl) node numbers (0: none)
        integer :: nnodes = 0, nelems = 0
    end type fc_fem_extruded_t

    public :: build_extruded_mesh, write_extruded_deck, extruded_top

contains

    !> Build the mesh for cells dx×dy with the parameters `p` (validated).
    subroutine build_extruded_mesh(p, nx, ny, dx, dy, mesh, stat, errmsg)
        type(fc_fem_params), intent(in) :: p
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: dx, dy
        type(fc_fem_extruded_t), intent(out) :: mesh
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: m, i, j, k, q, nn
        integer(i8) :: count
        real(dp) :: near
        m = nint(p%cube_over_hc*p%hc_over_hs)
        mesh%m = m; mesh%order = p%order
        mesh%ly = m*dy/p%hc_over_hs; mesh%lz = m*min(dx, dy)/p%hc_over_hs
        mesh%domain = fem_domain(p, dx, dy)
        near = max((nx + 1)*dx, (ny + 1)*dy)
        call graded_axis(mesh%domain, dx/p%hc_over_hs, m, p%stretch, near, p%stretch_far, mesh%xs, stat, errmsg)
        if (stat /= 0) return
        mesh%nxc = ubound(mesh%xs, 1)
        call box_levels(p, m, mesh%domain/mesh%ly, near/mesh%ly, mesh%sigma, mesh%nl, stat, errmsg)
        if (stat /= 0) return
        stat = FC_ERR_VALUE
        count = int(2*mesh%nxc + 1, i8)*((2*m + 1)**2 + int(2*mesh%nl, i8)*(4*m + 1))
        if (count > 4*max_nodes) then
            write (errmsg, '(a,i0,a)') 'fem: the prism mesh would have more than ', 4*max_nodes, &
                ' lattice points; raise stretch or lower l_over_hc, cube_over_hc or hc_over_hs'
            return
        end if
        allocate (mesh%id(0:2*mesh%nxc, 0:2*m, 0:2*m, 0:2*mesh%nl), source=0)
        nn = 0
        do q = 0, 2*mesh%nl
            do k = 0, 2*m
                do j = 0, 2*m
                    if (q > 0 .and. max(j, k) /= 2*m) cycle
                    do i = 0, 2*mesh%nxc
                        if (.not. exists(i, j, k, q)) cycle
                        nn = nn + 1; mesh%id(i, j, k, q) = nn
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
        mesh%nelems = 2*mesh%nxc*(m*m + 2*m*mesh%nl)
        stat = 0; errmsg = ''
    contains
        !> Node at x lattice i of cross-section point (j, k, q)?  Corners: even x and cross-section
        !! corners; quadratic: also the edge mid-points of the triangles (even x) and the mid-points
        !! along x of the cross-section corners (odd x).
        logical function exists(i, j, k, q)
            integer, intent(in) :: i, j, k, q
            logical :: corner2d, mid2d
            corner2d = mod(j, 2) == 0 .and. mod(k, 2) == 0 .and. mod(q, 2) == 0
            if (q == 0) then
                mid2d = .not. corner2d            ! edge mid-points and the cells' diagonal mid-points
            else if (mod(q, 2) == 0) then
                mid2d = mod(j, 2) + mod(k, 2) == 1   ! tangential edge mid-points
            else
                mid2d = .true.                    ! radial mid-points (even tangential) and diagonal mid-points (odd)
            end if
            if (p%order == 1) then
                exists = corner2d .and. mod(i, 2) == 0
            else if (mod(i, 2) == 0) then
                exists = corner2d .or. mid2d
            else
                exists = corner2d
            end if
        end function exists
    end subroutine build_extruded_mesh

    !> Cross-section position (y, z) of point (j, k) at half-level q [mm].
    pure function yz(mesh, j, k, q) result(p)
        type(fc_fem_extruded_t), intent(in) :: mesh
        integer, intent(in) :: j, k, q
        real(dp) :: p(2)
        integer :: t
        if (mod(q, 2) == 1 .and. (mod(j, 2) == 1 .or. mod(k, 2) == 1)) then
            ! diagonal mid-point of the layer quadrilateral: (inner corner at t−1 + outer corner at t+1)/2
            if (j == 2*mesh%m) then
                t = k
                p = (unit(j, t - 1, mesh%sigma(q - 1)) + unit(j, t + 1, mesh%sigma(q + 1)))/2
            else
                t = j
                p = (unit(t - 1, k, mesh%sigma(q - 1)) + unit(t + 1, k, mesh%sigma(q + 1)))/2
            end if
        else
            p = unit(j, k, mesh%sigma(q))
        end if
    contains
        pure function unit(a, b, s) result(r)
            integer, intent(in) :: a, b
            real(dp), intent(in) :: s
            real(dp) :: r(2)
            r = -s*[mesh%ly*a, mesh%lz*b]/(2*mesh%m)
        end function unit
    end function yz

    !> The top surface (z = 0) as a tensor mesh for [[fc_fem_ic]]'s reader and sampler: x axis
    !! `xs`, y axis the cross-section's top edge, node numbers in id(:, :, 0) (nzc = 0).
    subroutine extruded_top(mesh, top)
        type(fc_fem_extruded_t), intent(in) :: mesh
        type(fc_fem_mesh_t), intent(out) :: top
        integer :: j, ny, jl, q, jj
        ny = mesh%m + mesh%nl
        top%xs = mesh%xs
        allocate (top%ys(0:ny), top%zs(0:0))
        top%zs = 0
        do j = 0, ny                              ! cell boundary j (increasing to 0)
            jl = ny - j                           ! distance index from the axis
            if (jl <= mesh%m) then
                top%ys(j) = -mesh%ly*jl/mesh%m
            else
                top%ys(j) = -mesh%ly*mesh%sigma(2*(jl - mesh%m))
            end if
        end do
        top%nxc = mesh%nxc; top%nyc = ny; top%nzc = 0; top%order = mesh%order
        top%nnodes = mesh%nnodes; top%nelems = mesh%nelems; top%domain = mesh%domain
        allocate (top%id(0:2*mesh%nxc, 0:2*ny, 0:0), source=0)
        do jj = 0, 2*ny                           ! lattice along y, increasing to 0
            jl = 2*ny - jj
            if (jl <= 2*mesh%m) then
                top%id(:, jj, 0) = mesh%id(:, jl, 0, 0)
            else
                q = jl - 2*mesh%m
                top%id(:, jj, 0) = mesh%id(:, 2*mesh%m, 0, q)
            end if
        end do
    end subroutine extruded_top

    !> Write the CalculiX deck of the extruded prism mesh for load direction `dir`.
    subroutine write_extruded_deck(path, p, mesh, dir, g, nu, dx, dy, stat, errmsg)
        character(len=*), intent(in) :: path
        type(fc_fem_params), intent(in) :: p
        type(fc_fem_extruded_t), intent(in) :: mesh
        integer, intent(in) :: dir
        real(dp), intent(in) :: g, nu, dx, dy
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_fem_mesh_t) :: top
        integer :: u, ios, i, j, k, q, m, ne, lay, a, face
        real(dp), allocatable :: f(:, :), vals(:)
        integer, allocatable :: ids(:)
        character(len=256) :: iomsg
        m = mesh%m
        open (newunit=u, file=path, status='replace', action='write', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = 'fem: cannot write the CalculiX deck '//trim(path)//': '//trim(iomsg); return
        end if
        write (u, '(a)') '** fastcontact influence-coefficient model (Mesh2: extruded prisms), generated'
        write (u, '(a)') '*NODE, NSET=NALL'
        do q = 0, 2*mesh%nl
            do k = 0, 2*m
                do j = 0, 2*m
                    if (q > 0 .and. max(j, k) /= 2*m) cycle
                    do i = 0, 2*mesh%nxc
                        if (mesh%id(i, j, k, q) == 0) cycle
                        write (u, '(i0,3(",",es19.12))') mesh%id(i, j, k, q), lattice_coord(mesh%xs, i), yz(mesh, j, k, q)
                    end do
                end do
            end do
        end do
        if (mesh%order == 2) then
            write (u, '(a)') '*ELEMENT, TYPE=C3D15, ELSET=EALL'
        else
            write (u, '(a)') '*ELEMENT, TYPE=C3D6, ELSET=EALL'
        end if
        ne = 0
        do i = 0, mesh%nxc - 1
            do k = 0, m - 1                          ! the square's cells: local (r, t) = (j, k)
                do j = 0, m - 1
                    call quad(i, 0, 2*j, 2*k, 0)
                end do
            end do
            do lay = 1, mesh%nl
                do face = 1, 2                       ! 1: y = −σl_y (tangential k), 2: z = −σl_z (tangential j)
                    do a = 0, m - 1
                        call quad(i, lay, 2*a, 0, face)
                    end do
                end do
            end do
        end do
        call write_set('NXZERO', pack(mesh%id(2*mesh%nxc, :, :, :), mesh%id(2*mesh%nxc, :, :, :) > 0))
        call write_set('NYZERO', pack(mesh%id(:, 0, :, :), mesh%id(:, 0, :, :) > 0))
        call write_set('NTOP', pack(mesh%id(:, :, 0, :), mesh%id(:, :, 0, :) > 0))
        call write_set('NXMIN', pack(mesh%id(0, :, :, :), mesh%id(0, :, :, :) > 0))
        call write_set('NOUTER', pack(mesh%id(:, :, :, 2*mesh%nl), mesh%id(:, :, :, 2*mesh%nl) > 0))
        call extruded_top(mesh, top)
        call top_face_forces(p%load, mesh%order, top%xs, top%ys, dx, dy, f, stat, errmsg)
        if (stat == 0) then
            ids = pack(top%id(:, :, 0), f /= 0); vals = pack(f, f /= 0)
            call write_deck_physics(u, p, dir, g, nu, ['NXMIN ', 'NOUTER'], ids, vals)
        end if
        call close_deck(u, path, stat, errmsg)
    contains

        subroutine write_set(name, list)
            character(len=*), intent(in) :: name
            integer, intent(in) :: list(:)
            integer :: r
            write (u, '(a)') '*NSET, NSET='//name
            do r = 1, size(list), 16
                write (u, '(i0,15(",",i0:))') list(r:min(r + 15, size(list)))
            end do
        end subroutine write_set

        !> Cross-section point of local (r, t) ∈ [0,2]² of the quadrilateral with origin (o1, o2):
        !! lay = 0 the square (r along j, t along k); lay ≥ 1 a layer cell (r radial).
        subroutine point(lay_, o1, o2, fc, r, t, jj, kk, qq)
            integer, intent(in) :: lay_, o1, o2, fc, r, t
            integer, intent(out) :: jj, kk, qq
            if (lay_ == 0) then
                jj = o1 + r; kk = o2 + t; qq = 0
            else
                qq = 2*(lay_ - 1) + r
                if (fc == 1) then
                    jj = 2*m; kk = o1 + t
                else
                    jj = o1 + t; kk = 2*m
                end if
            end if
        end subroutine point

        !> The two wedges of one cross-section quadrilateral in x cell ix, split along the
        !! diagonal (0,0)–(2,2): T1 = (0,0), (2,0), (2,2); T2 = (0,0), (2,2), (0,2).
        subroutine quad(ix, lay_, o1, o2, fc)
            integer, intent(in) :: ix, lay_, o1, o2, fc
            call wedge(ix, lay_, o1, o2, fc, [0, 2, 2], [0, 0, 2])
            call wedge(ix, lay_, o1, o2, fc, [0, 2, 0], [0, 2, 2])
        end subroutine quad

        subroutine wedge(ix, lay_, o1, o2, fc, rr, tt)
            integer, intent(in) :: ix, lay_, o1, o2, fc, rr(3), tt(3)
            integer :: c(3, 3), mids(3, 3), v, w, jj, kk, qq, perm(3), nd(15), e(3)
            real(dp) :: pa(2), pb(2), pc(2), cr
            ! corners (cross-section) and edge mid-points v → v+1
            do v = 1, 3
                w = mod(v, 3) + 1
                call point(lay_, o1, o2, fc, rr(v), tt(v), jj, kk, qq); c(:, v) = [jj, kk, qq]
                call point(lay_, o1, o2, fc, (rr(v) + rr(w))/2, (tt(v) + tt(w))/2, jj, kk, qq); mids(:, v) = [jj, kk, qq]
            end do
            pa = yz(mesh, c(1, 1), c(2, 1), c(3, 1)); pb = yz(mesh, c(1, 2), c(2, 2), c(3, 2))
            pc = yz(mesh, c(1, 3), c(2, 3), c(3, 3))
            cr = (pb(1) - pa(1))*(pc(2) - pa(2)) - (pb(2) - pa(2))*(pc(1) - pa(1))
            ! counter-clockwise in (y, z): the face normal points along +x, to the second face
            perm = [1, 2, 3]; e = [1, 2, 3]        ! e(v): mid-point of edge perm(v) → perm(v+1)
            if (cr < 0) then
                perm = [1, 3, 2]; e = [3, 2, 1]
            end if
            do v = 1, 3
                nd(v) = mesh%id(2*ix, c(1, perm(v)), c(2, perm(v)), c(3, perm(v)))
                nd(v + 3) = mesh%id(2*ix + 2, c(1, perm(v)), c(2, perm(v)), c(3, perm(v)))
                nd(v + 6) = mesh%id(2*ix, mids(1, e(v)), mids(2, e(v)), mids(3, e(v)))
                nd(v + 9) = mesh%id(2*ix + 2, mids(1, e(v)), mids(2, e(v)), mids(3, e(v)))
                nd(v + 12) = mesh%id(2*ix + 1, c(1, perm(v)), c(2, perm(v)), c(3, perm(v)))
            end do
            ne = ne + 1
            if (mesh%order == 1) then
                write (u, '(i0,6(",",i0))') ne, nd(1:6)
            else
                write (u, '(i0,15(",",i0))') ne, nd
            end if
        end subroutine wedge
    end subroutine write_extruded_deck

end module fc_fem_extruded
