!> The influence coefficients a case uses: read one file (fastcontact or CONTACT format),
!! combine a body's coefficients with body 2 (a second file or the analytic half-space),
!! check them against the body's material — one call for the driver and the flat API.
module fc_icfile_load
    use fc_kinds, only: dp, msg_len, FC_ERR_VALUE, FC_ERR_IO
    use fc_icfile
    use fc_icfile_contact, only: read_contact_file
    implicit none
    private

    public :: load_influence_source, read_any_ic_file, ic_source_header

contains

    !> Read `path` in either format (fastcontact files start with `format = fastcontact-ic`).
    subroutine read_any_ic_file(path, set, stat, errmsg, header_only)
        character(len=*), intent(in) :: path
        type(fc_ic_set), intent(inout) :: set
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        logical, intent(in), optional :: header_only   !! the header only: offsets, cell size, content
        logical :: exists
        inquire (file=path, exist=exists)
        if (.not. exists) then
            stat = FC_ERR_IO; errmsg = "influence-coefficient file '"//trim(path)//"' does not exist"; return
        end if
        if (is_fastcontact_ic_file(path)) then
            call read_ic_file(path, set, stat, errmsg, header_only)
        else
            call read_contact_file(path, set, stat, errmsg, header_only)
        end if
    end subroutine read_any_ic_file

    !> Combined coefficients for a contact of body 1 (`path`) with body 2: `path2` when given,
    !! else the elastic half-space (g2, nu2) (g2 ≥ 1e29: rigid).  A file of content 'body'
    !! must have been computed for (g1, nu1); a 'combined' file (CONTACT's format, or ours)
    !! already holds both bodies, and `path2` must then be empty.
    subroutine load_influence_source(path, path2, g1, nu1, g2, nu2, set, stat, errmsg)
        character(len=*), intent(in) :: path, path2
        real(dp), intent(in) :: g1, nu1, g2, nu2
        type(fc_ic_set), intent(inout) :: set
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_ic_set) :: b1, b2
        call read_any_ic_file(path, b1, stat, errmsg)
        if (stat /= 0) return
        if (b1%content == 'combined') then
            if (len_trim(path2) > 0) then
                stat = FC_ERR_VALUE
                errmsg = "'"//trim(path)//"' holds combined coefficients of both bodies; ic_file2 = '"//trim(path2)// &
                    "' must not be given"
                return
            end if
            call move_ic_set(b1, set)
            return
        end if
        call check_material(b1, path, g1, nu1, 'g1', 'nu1', stat, errmsg)
        if (stat /= 0) return
        if (len_trim(path2) > 0) then
            call read_any_ic_file(path2, b2, stat, errmsg)
            if (stat /= 0) return
            if (b2%content /= 'body') then
                stat = FC_ERR_VALUE; errmsg = "ic_file2 = '"//trim(path2)//"' must hold one body's coefficients (content body)"
                return
            end if
            call check_material(b2, path2, g2, nu2, 'g2', 'nu2', stat, errmsg)
            if (stat /= 0) return
        else
            call analytic_body_set(g2, nu2, b1%dx, b1%dy, b1%mx, b1%my, b2, stat, errmsg)
            if (stat /= 0) return
        end if
        ! combined into body 1's set, which then moves to `set`: at most two sets in memory
        call combine_ic_sets_in_place(b1, b2, stat, errmsg)
        if (stat /= 0) return
        deallocate (b2%a)
        call move_ic_set(b1, set)
        call validate_ic_set(set, 'combined coefficients of '//trim(path), stat, errmsg)
    end subroutine load_influence_source

    !> The headers of the coefficient files of a contact (`path`, and `path2` when given):
    !! body 1's cell size and content, and the largest offsets (mx, my) of the two, what
    !! [[load_influence_source]] will hold (its peak: body 1's set and body 2's, each of 72 B
    !! per offset pair, doc/reliability.md, "Memory"); no coefficients.  stat ≠ 0 when a
    !! header cannot be read (the load reports it in full).
    subroutine ic_source_header(path, path2, header, stat, errmsg)
        character(len=*), intent(in) :: path, path2
        type(fc_ic_set), intent(out) :: header
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_ic_set) :: h2
        call read_any_ic_file(path, header, stat, errmsg, header_only=.true.)
        if (stat /= 0 .or. len_trim(path2) == 0) return
        call read_any_ic_file(path2, h2, stat, errmsg, header_only=.true.)
        if (stat /= 0) return
        header%mx = max(header%mx, h2%mx); header%my = max(header%my, h2%my)
    end subroutine ic_source_header

    subroutine check_material(b, path, g, nu, gkey, nukey, stat, errmsg)
        type(fc_ic_set), intent(in) :: b
        character(len=*), intent(in) :: path, gkey, nukey
        real(dp), intent(in) :: g, nu
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (abs(b%g - g) > 1.0e-9_dp*abs(g) .or. abs(b%nu - nu) > 1.0e-9_dp) then
            stat = FC_ERR_VALUE
            write (errmsg, '(5a,es12.5,3a,g0.6,a,es12.5,a,g0.6)') "'", trim(path), "' was computed for another body: ", &
                gkey, ' = ', g, ', ', nukey, ' = ', nu, ' but the file has g = ', b%g, ', nu = ', b%nu
        end if
    end subroutine check_material

end module fc_icfile_load
