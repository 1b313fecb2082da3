!> The automatic potential contact area of a scene (`&grid auto`): its size from the Hertz
!! estimate (elliptic Hertz for quadratic profiles, plane-strain Hertz per unit length for
!! line contacts) plus a margin, and the check that the computed contact stays inside it.
!! Used by the automatic layer ([[fc_auto]]), which enlarges a clipped area and solves again.
module fc_auto_area
    use fc_kinds, only: dp, pi
    use fc_influence, only: fc_material
    use fc_hertz, only: fc_hertz_solution, hertz_from_approach, hertz_from_force
    use fc_errors, only: FC_ERR_VALUE, FC_ERR_NO_CONTACT
    use fc_strings, only: fmt_real
    use fc_scene, only: fc_case
    implicit none
    private

    public :: auto_area, line_indentation, plane_strain_hertz, contact_touches_boundary, even_up

contains

    !> Whether any element in contact lies in the first or last column (and, unless `line`,
    !! the first or last row) of the grid.
    pure logical function contact_touches_boundary(pn, line) result(touches)
        real(dp), intent(in) :: pn(:, :)
        logical, intent(in) :: line   !! line contact: the y edges are the ends of the body
        integer :: nx, ny
        nx = size(pn, 1); ny = size(pn, 2)
        touches = any(pn(1, :) > 0) .or. any(pn(nx, :) > 0)
        if (.not. line .and. ny > 1) touches = touches .or. any(pn(:, 1) > 0) .or. any(pn(:, ny) > 0)
    end function contact_touches_boundary

    !> Plane-strain Hertz for a cylinder of radius r [mm] under force per length pl [N/mm],
    !! estar = G/(1−ν): half-width b = sqrt(4 r P'/(π E*)) and p0 = 2P'/(π b).
    pure subroutine plane_strain_hertz(r, pl, estar, b, p0)
        real(dp), intent(in) :: r, pl, estar
        real(dp), intent(out) :: b, p0
        b = sqrt(4*r*pl/(pi*estar))
        p0 = 2*pl/(pi*max(b, tiny(1.0_dp)))
    end subroutine plane_strain_hertz

    !> Size the potential contact area of `s` from the Hertz estimate (sets nx, ny, xmin …
    !! ymax).  Quadratic: elliptic Hertz semi-axes a, b; line contacts: plane-strain half
    !! width (force per length) or the geometric overlap √(2 R δ) (approach).  Each half-axis
    !! gets (1 + margin); n_across elements span the contact's diameter in x (and in y for
    !! elliptic contacts).
    subroutine auto_area(s, mat, stat, errmsg)
        type(fc_case), intent(inout) :: s
        type(fc_material), intent(in) :: mat
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_hertz_solution) :: hz
        real(dp) :: estar, ha, hb, p0, len_y
        integer :: nacross
        stat = 0; errmsg = ''
        estar = mat%g/(1 - mat%nu)
        nacross = s%n_across
        if (nacross == 0) nacross = merge(8, 32, s%target > 0)
        select case (s%kind)
        case ('quadratic')
            if (s%normal%force_prescribed) then
                hz = hertz_from_force(0.5_dp/s%rx, 0.5_dp/s%ry, estar, s%normal%fn)
            else
                hz = hertz_from_approach(0.5_dp/s%rx, 0.5_dp/s%ry, estar, s%normal%approach)
            end if
            if (.not. (hz%a > 0 .and. hz%b > 0)) then
                stat = FC_ERR_NO_CONTACT
                errmsg = 'approach = '//fmt_real(s%normal%approach)//': no contact, the automatic area cannot be sized'
                return
            end if
            ha = (1 + s%margin)*hz%a; hb = (1 + s%margin)*hz%b
            s%nx = even_up((1 + s%margin)*nacross)
            s%ny = even_up((1 + s%margin)*nacross)
            s%xmin = -ha; s%xmax = ha; s%ymin = -hb; s%ymax = hb
        case ('cylinder', 'strip2d')
            len_y = s%ymax - s%ymin
            if (s%kind == 'cylinder') len_y = s%length
            if (s%normal%force_prescribed) then
                call plane_strain_hertz(s%rx, s%normal%fn/len_y, estar, ha, p0)
            else
                if (.not. (s%normal%approach > 0)) then
                    stat = FC_ERR_NO_CONTACT
                    errmsg = 'approach = '//fmt_real(s%normal%approach)//': no contact, the automatic area cannot be sized'
                    return
                end if
                ha = sqrt(2*s%rx*s%normal%approach)
            end if
            ha = (1 + s%margin)*ha
            s%nx = even_up((1 + s%margin)*nacross)
            s%xmin = -ha; s%xmax = ha
            if (s%kind == 'cylinder') then
                s%ymin = -0.5_dp*len_y; s%ymax = 0.5_dp*len_y
            end if
            if (s%ny == -1) then
                s%ny = min(512, max(2, even_up(len_y/((s%xmax - s%xmin)/s%nx))))
            else
                s%ny = 1
            end if
        case default
            stat = FC_ERR_VALUE
            errmsg = "kind = '"//trim(s%kind)//"': the automatic area needs kind = 'quadratic', 'cylinder' or 'strip2d'"
        end select
    end subroutine auto_area

    !> Indentation scale of a line contact: the approach, or b²/(2R) from plane-strain Hertz.
    real(dp) function line_indentation(s, mat) result(d)
        type(fc_case), intent(in) :: s
        type(fc_material), intent(in) :: mat
        real(dp) :: b, p0
        if (.not. s%normal%force_prescribed) then
            d = abs(s%normal%approach)
        else
            call plane_strain_hertz(s%rx, s%normal%fn/(s%ymax - s%ymin), mat%g/(1 - mat%nu), b, p0)
            d = b**2/(2*s%rx)
        end if
    end function line_indentation

    !> Smallest even integer ≥ x (at least 2).
    pure integer function even_up(x)
        real(dp), intent(in) :: x
        even_up = max(2, 2*ceiling(0.5_dp*x - 1.0e-9_dp))
    end function even_up

end module fc_auto_area
