!> CONTACT's influence-coefficient file (its C = 9 option): read and write, so that
!! coefficients can be exchanged with CONTACT (doc/ic_file_format.md).
!!
!! Layout as implemented here (our reading of CONTACT's user guide; `%` starts a comment):
!!
!!     nmatrix  iaconvex        1 (one matrix for all positions), 1 or 2 (convex body)
!!     lquasid  xyzorder        0 (general: 9 columns), 312 (component order n, x, y)
!!     lsymmx   lsymmy          1 (only ix >= 0 stored, mirrored), 0 (all iy stored)
!!     mx  my  dx  dy           grid size (offsets 0..mx-1 and -(my-1)..my-1), cell size [mm]
!!   then for each iy = -(my-1) … my-1 two header lines (comments; any line that does not
!!   start with a number is skipped) and mx rows
!!     ixofs  xrel  Czz Czx Czy  Cxz Cxx Cxy  Cyz Cyx Cyy
!!   with xrel = ixofs·dx and C_ab the displacement difference in direction a due to a unit
!!   traction in direction b (combined coefficients of both bodies, mm per N/mm²).
!!   Offsets −ix follow by mirroring in x: Czx, Cxz, Cxy, Cyx change sign, the others not.
!!
!! Assumptions: the normal direction n is our z with our sign convention (a pressure pushes
!! the surfaces apart, A^zz > 0); the lateral coordinate is our y; nmatrix = 1 only (one
!! matrix, translation invariant: the only case a BTTB operator represents).
module fc_icfile_contact
    use fc_kinds, only: dp, i8, msg_len, FC_ERR_VALUE, FC_ERR_IO
    use fc_icfile, only: fc_ic_set, ic_set_allocate, validate_ic_set, ic_max_offset, rename_file, temp_name, &
        end_of_header
    implicit none
    private

    public :: write_contact_file, read_contact_file

contains

    !> Write a combined set in CONTACT's format (offsets 0..set%mx in x, ±set%my in y),
    !! atomically.  The set must be mirror-symmetric in x as the format stores ix ≥ 0 only.
    subroutine write_contact_file(path, set, stat, errmsg)
        character(len=*), intent(in) :: path
        type(fc_ic_set), intent(in) :: set
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u, ios, ix, iy, i, j
        real(dp) :: s, scale
        character(len=:), allocatable :: tmp
        character(len=msg_len) :: iomsg
        stat = FC_ERR_VALUE
        if (set%content /= 'combined') then
            errmsg = "CONTACT influence-coefficient files hold combined coefficients; got content '"// &
                trim(set%content)//"'"
            return
        end if
        do j = 1, 3
            do i = 1, 3
                s = mirror_sign(i, j)
                scale = max(maxval(abs(set%a(:, :, i, j))), tiny(1.0_dp))
                if (maxval(abs(set%a(:, :, i, j) - s*set%a(set%mx:-set%mx:-1, :, i, j))) > 1.0e-12_dp*scale) then
                    errmsg = 'CONTACT format needs coefficients mirror-symmetric in x; this set is not'; return
                end if
            end do
        end do
        tmp = temp_name(path)
        open (newunit=u, file=tmp, status='replace', action='write', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = 'cannot write '//tmp//': '//trim(iomsg); return
        end if
        write (u, '(a)') '   1    1    % nmatrix, iaconvex: one matrix for all positions; convex body 1'
        write (u, '(a)') '   0  312    % lquasid, xyzorder: general (9 columns), order n, x, y'
        write (u, '(a)') '   1    0    % lsymmx, lsymmy: ix >= 0 stored (mirrored in x), all iy stored'
        write (u, '(i0,1x,i0,2(1x,es25.17e3),a)') set%mx + 1, set%my + 1, set%dx, set%dy, '  % mx, my, dx, dy'
        do iy = -set%my, set%my
            write (u, '(a,i0,a,es14.6,a)') '% offset iy = ', iy, ' (y = ', iy*set%dy, ')'
            write (u, '(a)') '% ix  x  Czz Czx Czy  Cxz Cxx Cxy  Cyz Cyx Cyy (written by fastcontact)'
            do ix = 0, set%mx
                write (u, '(i0,1x,es25.17e3,9(1x,es25.17e3))', iostat=ios, iomsg=iomsg) ix, ix*set%dx, &
                    set%a(ix, iy, 3, 3), set%a(ix, iy, 3, 1), set%a(ix, iy, 3, 2), &
                    set%a(ix, iy, 1, 3), set%a(ix, iy, 1, 1), set%a(ix, iy, 1, 2), &
                    set%a(ix, iy, 2, 3), set%a(ix, iy, 2, 1), set%a(ix, iy, 2, 2)
                if (ios /= 0) exit
            end do
            if (ios /= 0) exit
        end do
        if (ios == 0) close (u, iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            close (u, status='delete', iostat=ix)
            stat = FC_ERR_IO; errmsg = 'cannot write '//tmp//': '//trim(iomsg); return
        end if
        call rename_file(tmp, path, stat, errmsg)
    end subroutine write_contact_file

    !> Sign of component (i, j) under x → −x (x is component 1).
    pure real(dp) function mirror_sign(i, j) result(s)
        integer, intent(in) :: i, j
        s = 1
        if ((i == 1) .neqv. (j == 1)) s = -1
    end function mirror_sign

    !> Read CONTACT's format into a combined set (offsets ±(mx−1), ±(my−1)) and validate it.
    subroutine read_contact_file(path, set, stat, errmsg, header_only)
        character(len=*), intent(in) :: path
        type(fc_ic_set), intent(inout) :: set
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        !> read and check the header only (offsets, cell size; no coefficients)
        logical, intent(in), optional :: header_only
        logical :: done
        integer :: u, ios, line, nmatrix, iaconvex, lquasid, xyzorder, lsymmx, lsymmy, mx, my, ix, iy, jx
        real(dp) :: dx, dy, v(10)
        character(len=4096) :: buf
        character(len=msg_len) :: iomsg
        stat = FC_ERR_IO
        open (newunit=u, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            errmsg = 'cannot open influence-coefficient file '//trim(path)//': '//trim(iomsg); return
        end if
        line = 0
        ! every read failure leaves the block to the one message below
        parse: block
            call next_data(ios); if (ios /= 0) exit parse
            read (buf, *, iostat=ios) nmatrix, iaconvex; if (ios /= 0) exit parse
            call next_data(ios); if (ios /= 0) exit parse
            read (buf, *, iostat=ios) lquasid, xyzorder; if (ios /= 0) exit parse
            call next_data(ios); if (ios /= 0) exit parse
            read (buf, *, iostat=ios) lsymmx, lsymmy; if (ios /= 0) exit parse
            call next_data(ios); if (ios /= 0) exit parse
            read (buf, *, iostat=ios) mx, my, dx, dy; if (ios /= 0) exit parse
            if (nmatrix /= 1) then
                write (errmsg, '(2a,i0,a)') trim(path), ': nmatrix = ', nmatrix, &
                    ' is not supported (only 1: coefficients independent of position)'
                close (u); return
            end if
            if (iaconvex /= 1 .and. iaconvex /= 2) then
                write (errmsg, '(2a,i0,a)') trim(path), ': iaconvex = ', iaconvex, ' must be 1 or 2'; close (u); return
            end if
            if (lquasid /= 0 .or. xyzorder /= 312) then
                write (errmsg, '(2a,i0,a,i0,a)') trim(path), ': lquasid = ', lquasid, ', xyzorder = ', xyzorder, &
                    ' not supported (need 0 and 312: nine columns in order n, x, y)'
                close (u); return
            end if
            if (lsymmx /= 1 .or. lsymmy /= 0) then
                write (errmsg, '(2a,i0,a,i0,a)') trim(path), ': lsymmx = ', lsymmx, ', lsymmy = ', lsymmy, &
                    ' not supported (need 1 and 0)'
                close (u); return
            end if
            if (mx < 1 .or. my < 1 .or. mx > ic_max_offset + 1 .or. my > ic_max_offset + 1) then
                write (errmsg, '(2a,i0,a,i0,a,i0,a)') trim(path), ': mx = ', mx, ', my = ', my, ' must lie in [1, ', &
                    ic_max_offset + 1, ']'
                close (u); return
            end if
            if (.not. (dx > 0 .and. dy > 0)) then
                write (errmsg, '(2a,2es12.4,a)') trim(path), ': dx, dy = ', dx, dy, ' must be > 0'; close (u); return
            end if
            set%content = 'combined'; set%source = 'contact'; set%load = 'constant'
            set%model = 'CONTACT influence-coefficient file '//trim(path); set%hash = ''; set%g = 0; set%nu = 0
            call end_of_header(u, path, int(mx, i8)*(2_i8*my - 1), mx - 1, my - 1, dx, dy, set, header_only, done, stat, &
                errmsg)
            if (done) return
            call ic_set_allocate(set, mx - 1, my - 1, dx, dy)
            do iy = -(my - 1), my - 1
                do ix = 0, mx - 1
                    call next_data(ios); if (ios /= 0) exit parse
                    read (buf, *, iostat=ios) jx, v
                    if (ios /= 0) exit parse
                    if (jx /= ix) then
                        write (errmsg, '(2a,i0,a,i0,a,i0,a,i0)') trim(path), ': line ', line, ': ixofs = ', jx, &
                            ' where ', ix, ' was expected (offset iy = ', iy
                        errmsg = trim(errmsg)//')'
                        close (u); return
                    end if
                    call store(ix, iy, 1.0_dp)
                    if (ix > 0) call store(-ix, iy, -1.0_dp)
                end do
            end do
            close (u)
            call validate_ic_set(set, path, stat, errmsg)
            return
        end block parse
        write (errmsg, '(2a,i0,a)') trim(path), ': line ', line, ': cannot read the expected numbers'
        close (u)
    contains
        subroutine next_data(ios)
            integer, intent(out) :: ios
            integer :: p
            character(len=1) :: first
            do
                read (u, '(a)', iostat=ios) buf
                if (ios /= 0) return
                line = line + 1
                p = index(buf, '%')
                if (p > 0) buf(p:) = ' '
                ! a line not starting with a number is a comment too (block headers)
                if (len_trim(buf) > 0) then
                    first = adjustl(buf)
                    if (index('0123456789+-.', first) == 0) cycle
                    return
                end if
            end do
        end subroutine next_data
        subroutine store(jx, iy, s)
            integer, intent(in) :: jx, iy
            real(dp), intent(in) :: s
            ! columns after ixofs: xrel, then zz zx zy xz xx xy yz yx yy
            set%a(jx, iy, 3, 3) = v(2); set%a(jx, iy, 3, 1) = s*v(3); set%a(jx, iy, 3, 2) = v(4)
            set%a(jx, iy, 1, 3) = s*v(5); set%a(jx, iy, 1, 1) = v(6); set%a(jx, iy, 1, 2) = s*v(7)
            set%a(jx, iy, 2, 3) = v(8); set%a(jx, iy, 2, 1) = s*v(9); set%a(jx, iy, 2, 2) = v(10)
        end subroutine store
    end subroutine read_contact_file

end module fc_icfile_contact
