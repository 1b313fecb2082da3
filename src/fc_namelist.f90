!> Pre-parser of namelist case files: comments removed, the file split into groups
!! `&name ... /` and the groups into cases at each `&case`; each group's `key = value` items
!! are listed (keys lower case, subscripts removed) so that unknown groups and keys can be
!! reported by name before a namelist READ of the group's text.
!!
!! A case starts at each `&case` group; the groups up to the next `&case` belong to it
!! (groups before the first `&case` belong to the first case; a file without `&case` is
!! one case).  Text in quotes is kept; `!` starts a comment outside quotes.
module fc_namelist
    use fc_errors, only: FC_ERR_VALUE, FC_ERR_IO
    use fc_strings, only: lower, shorten
    implicit none
    private

    integer, parameter, public :: key_len = 32    !! longest key name kept
    integer, parameter, public :: val_len = 512   !! longest value text kept

    !> One `key = value` of a group as written in the file.
    type, public :: fc_nml_item
        character(len=key_len) :: key = ''     !! lower-case key (subscripts removed)
        character(len=val_len) :: value = ''   !! value text, trimmed
    end type fc_nml_item

    !> One namelist group as written in the file (comments removed, lines joined).
    type, public :: fc_nml_group
        character(len=key_len) :: name = ''          !! lower-case group name
        integer :: line = 0                          !! line of the `&name`
        character(len=:), allocatable :: text        !! `&name ... /` ready for a namelist READ
        type(fc_nml_item), allocatable :: items(:)   !! keys in order of appearance
    end type fc_nml_group

    !> The groups of one case.
    type, public :: fc_case_chunk
        integer :: line = 0                          !! line of its `&case` (or first group)
        type(fc_nml_group), allocatable :: groups(:)
    end type fc_case_chunk

    public :: read_case_file, split_cases, is_ident_char

contains

    !> Read `filename` and split it into cases.  stat ≠ 0 for an unreadable file or a
    !! syntax error (unterminated group, text that is not `key = value`).
    subroutine read_case_file(filename, cases, stat, errmsg)
        character(len=*), intent(in) :: filename
        type(fc_case_chunk), allocatable, intent(out) :: cases(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=:), allocatable :: text
        integer, allocatable :: lines(:)
        integer :: unit, ios, lineno, n
        character(len=4096) :: buf
        character(len=256) :: iomsg
        logical :: in_quote
        character :: quote
        stat = 0; errmsg = ''
        open (newunit=unit, file=filename, status='old', action='read', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = "cannot open case file '"//trim(filename)//"': "//trim(iomsg); return
        end if
        text = ''
        allocate (lines(0))
        lineno = 0; in_quote = .false.; quote = ' '
        do
            read (unit, '(a)', iostat=ios) buf
            if (ios /= 0) exit
            lineno = lineno + 1
            call strip_comment(buf, in_quote, quote)
            n = len_trim(buf)
            text = text//buf(1:n)//' '
            lines = [lines, spread(lineno, 1, n + 1)]
        end do
        close (unit)
        call split_cases(text, lines, cases, stat, errmsg)
    end subroutine read_case_file

    !> Blank the part of `line` after a `!` that is outside quotes; quote state carries over.
    subroutine strip_comment(line, in_quote, quote)
        character(len=*), intent(inout) :: line
        logical, intent(inout) :: in_quote
        character, intent(inout) :: quote
        integer :: i
        do i = 1, len_trim(line)
            if (line(i:i) == char(9)) line(i:i) = ' '
            if (in_quote) then
                if (line(i:i) == quote) in_quote = .false.
            else if (line(i:i) == '"' .or. line(i:i) == "'") then
                in_quote = .true.; quote = line(i:i)
            else if (line(i:i) == '!') then
                line(i:) = ''
                return
            end if
        end do
    end subroutine strip_comment

    !> Split comment-free `text` (one string, `lines(k)` = file line of character k) into
    !! groups, and the groups into cases at each `&case`.
    subroutine split_cases(text, lines, cases, stat, errmsg)
        character(len=*), intent(in) :: text
        integer, intent(in) :: lines(:)
        type(fc_case_chunk), allocatable, intent(out) :: cases(:)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_nml_group), allocatable :: groups(:)
        type(fc_nml_group) :: g
        integer :: i, n, start, gstart, k, ncase, j
        integer, allocatable :: starts(:)
        logical :: in_quote
        character :: quote, c
        stat = 0; errmsg = ''
        allocate (groups(0))
        n = len(text)
        i = 1
        do while (i <= n)
            c = text(i:i)
            if (c == ' ' .or. c == ',') then
                i = i + 1; cycle
            end if
            if (c /= '&' .and. c /= '$') then
                ! gfortran skips text between groups; we do the same but only up to a '&'
                i = i + 1; cycle
            end if
            gstart = i
            start = i + 1
            k = start
            do while (k <= n)
                if (.not. is_ident_char(text(k:k))) exit
                k = k + 1
            end do
            if (allocated(g%items)) deallocate (g%items)
            g%name = lower(text(start:k - 1))
            g%line = lines(min(gstart, size(lines)))
            if (len_trim(g%name) == 0) then
                stat = FC_ERR_VALUE; write (errmsg, '(a,i0)') "'&' not followed by a group name at line ", g%line; return
            end if
            if (g%name == 'end') then
                i = k; cycle
            end if
            ! find the closing '/' (or '&end' / '$end') outside quotes
            in_quote = .false.; quote = ' '
            j = k
            do while (j <= n)
                c = text(j:j)
                if (in_quote) then
                    if (c == quote) in_quote = .false.
                else if (c == '"' .or. c == "'") then
                    in_quote = .true.; quote = c
                else if (c == '/') then
                    exit
                else if (c == '&' .or. c == '$') then
                    if (lower(text(j + 1:min(n, j + 3))) == 'end') exit
                    stat = FC_ERR_VALUE
                    write (errmsg, '(a,i0,a,i0)') 'group &'//trim(g%name)//' (line ', g%line, &
                        ") is not terminated by '/' before the next group at line ", lines(j)
                    return
                end if
                j = j + 1
            end do
            if (j > n) then
                stat = FC_ERR_VALUE
                write (errmsg, '(a,i0,a)') 'group &'//trim(g%name)//' (line ', g%line, ") is not terminated by '/'"
                return
            end if
            g%text = '&'//trim(g%name)//' '//text(k:j - 1)//' /'
            call parse_items(g, text(k:j - 1), stat, errmsg)
            if (stat /= 0) return
            groups = [groups, g]
            if (text(j:j) == '/') then
                i = j + 1
            else
                i = j + 4
            end if
        end do
        ! cases: one per &case; groups before the first &case belong to the first case
        if (size(groups) == 0) then
            stat = FC_ERR_VALUE; errmsg = 'no namelist groups found in the case file'; return
        end if
        ncase = max(1, count(groups%name == 'case'))
        allocate (cases(ncase), starts(ncase + 1))
        k = 0
        do i = 1, size(groups)
            if (groups(i)%name == 'case') then
                k = k + 1; starts(k) = i
            end if
        end do
        starts(1) = 1
        starts(ncase + 1) = size(groups) + 1
        do k = 1, ncase
            cases(k)%groups = groups(starts(k):starts(k + 1) - 1)
            cases(k)%line = groups(starts(k))%line
        end do
    end subroutine split_cases

    !> Find the `key = value` items in the body of a group.
    subroutine parse_items(g, body, stat, errmsg)
        type(fc_nml_group), intent(inout) :: g
        character(len=*), intent(in) :: body
        integer, intent(inout) :: stat
        character(len=*), intent(inout) :: errmsg
        integer :: i, n, k, kstart, depth, nitem
        integer, allocatable :: kpos(:), epos(:)
        logical :: in_quote
        character :: quote, c
        n = len(body)
        allocate (kpos(0), epos(0))
        in_quote = .false.; quote = ' '
        do i = 1, n
            c = body(i:i)
            if (in_quote) then
                if (c == quote) in_quote = .false.
                cycle
            end if
            if (c == '"' .or. c == "'") then
                in_quote = .true.; quote = c; cycle
            end if
            if (c /= '=') cycle
            ! walk back: blanks, optional (subscript), identifier
            k = i - 1
            do while (k >= 1)
                if (body(k:k) /= ' ') exit
                k = k - 1
            end do
            if (k >= 1) then
                if (body(k:k) == ')') then
                    depth = 0
                    do while (k >= 1)
                        if (body(k:k) == ')') depth = depth + 1
                        if (body(k:k) == '(') depth = depth - 1
                        k = k - 1
                        if (depth == 0) exit
                    end do
                    do while (k >= 1)
                        if (body(k:k) /= ' ') exit
                        k = k - 1
                    end do
                end if
            end if
            kstart = k
            do while (kstart >= 1)
                if (.not. (is_ident_char(body(kstart:kstart)) .or. body(kstart:kstart) == '%')) exit
                kstart = kstart - 1
            end do
            kstart = kstart + 1
            if (kstart > k) then
                stat = FC_ERR_VALUE
                write (errmsg, '(a,i0,a)') 'group &'//trim(g%name)//' (line ', g%line, &
                    "): '=' without a key name in '"//trim(shorten(body))//"'"
                return
            end if
            kpos = [kpos, kstart]
            epos = [epos, i]
        end do
        nitem = size(kpos)
        allocate (g%items(nitem))
        if (nitem == 0) then
            if (len_trim(body) > 0) then
                stat = FC_ERR_VALUE
                write (errmsg, '(a,i0,a)') 'group &'//trim(g%name)//' (line ', g%line, &
                    "): expected 'key = value', got '"//trim(shorten(adjustl(body)))//"'"
            end if
            return
        end if
        if (len_trim(body(1:kpos(1) - 1)) > 0) then
            stat = FC_ERR_VALUE
            write (errmsg, '(a,i0,a)') 'group &'//trim(g%name)//' (line ', g%line, &
                "): expected 'key = value', got '"//trim(shorten(adjustl(body(1:kpos(1) - 1))))//"'"
            return
        end if
        do k = 1, nitem
            g%items(k)%key = key_of(body(kpos(k):epos(k) - 1))
            if (k < nitem) then
                g%items(k)%value = trim_value(body(epos(k) + 1:kpos(k + 1) - 1))
            else
                g%items(k)%value = trim_value(body(epos(k) + 1:))
            end if
        end do
    contains
        function key_of(s) result(key)
            character(len=*), intent(in) :: s
            character(len=key_len) :: key
            integer :: p
            p = index(s, '(')
            if (p > 0) then
                key = lower(adjustl(s(1:p - 1)))
            else
                key = lower(adjustl(s))
            end if
        end function key_of
        function trim_value(s) result(v)
            character(len=*), intent(in) :: s
            character(len=val_len) :: v
            integer :: m
            v = adjustl(s)
            m = len_trim(v)
            do while (m > 0)
                if (v(m:m) /= ',' .and. v(m:m) /= ' ') exit
                v(m:m) = ' '
                m = m - 1
            end do
        end function trim_value
    end subroutine parse_items


    pure logical function is_ident_char(c)
        character, intent(in) :: c
        is_ident_char = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. (c >= '0' .and. c <= '9') &
            .or. c == '_'
    end function is_ident_char
end module fc_namelist
