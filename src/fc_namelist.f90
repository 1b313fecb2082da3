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
    use fc_limits, only: max_line_length, max_file_chars, max_cases
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
        integer :: unit, ios, lineno, n, pos, fsize
        character(len=max_line_length + 1) :: buf
        character(len=256) :: iomsg
        logical :: in_quote
        character :: quote
        stat = 0; errmsg = ''
        open (newunit=unit, file=filename, status='old', action='read', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            stat = FC_ERR_IO; errmsg = "cannot open case file '"//trim(filename)//"': "//trim(iomsg); return
        end if
        inquire (unit=unit, size=fsize)
        if (fsize > max_file_chars) then
            close (unit)
            stat = FC_ERR_VALUE
            write (errmsg, '(a,i0,a,i0,a)') "case file '"//trim(filename)//"': ", fsize, ' bytes exceed the limit ', &
                max_file_chars, ' bytes'
            return
        end if
        ! every line contributes at most its length + 1 (a blank for the newline): the text
        ! and its line map are allocated once (no quadratic growth on long files)
        fsize = max(fsize, 0) + 1
        allocate (character(len=fsize) :: text)
        allocate (lines(fsize))
        pos = 0; lineno = 0; in_quote = .false.; quote = ' '
        do
            read (unit, '(a)', advance='no', size=n, iostat=ios) buf
            if (ios == 0) then
                ! the buffer filled before the end of the line
                close (unit)
                stat = FC_ERR_VALUE
                write (errmsg, '(a,i0,a,i0,a)') "case file '"//trim(filename)//"': line ", lineno + 1, &
                    ' is longer than the limit of ', max_line_length, ' characters'
                return
            end if
            if (is_iostat_end(ios) .and. n == 0) exit
            if (.not. (is_iostat_eor(ios) .or. is_iostat_end(ios))) then
                close (unit)
                stat = FC_ERR_IO
                write (errmsg, '(a,i0)') "cannot read case file '"//trim(filename)//"' at line ", lineno + 1
                return
            end if
            lineno = lineno + 1
            call strip_comment(buf(1:n), in_quote, quote)
            n = len_trim(buf(1:n))
            if (pos + n + 1 > len(text)) exit     ! cannot happen: fsize bounds the text
            text(pos + 1:pos + n + 1) = buf(1:n)//' '
            lines(pos + 1:pos + n + 1) = lineno
            pos = pos + n + 1
            if (is_iostat_end(ios)) exit
        end do
        close (unit)
        text = text(1:pos)
        lines = lines(1:max(pos, 1))
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
        integer :: i, n, start, gstart, k, ncase, j, ngroups
        integer, allocatable :: starts(:)
        logical :: in_quote
        character :: quote, c
        stat = 0; errmsg = ''
        allocate (groups(16))
        ngroups = 0; ncase = 0
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
            if (g%name == 'case') then
                ncase = ncase + 1
                if (ncase > max_cases) then
                    stat = FC_ERR_VALUE
                    write (errmsg, '(a,i0,a,i0,a)') 'the case file has more than ', max_cases, &
                        ' &case groups (limit; the excess one starts at line ', g%line, '): split it into several files'
                    return
                end if
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
            if (ngroups == size(groups)) call grow(groups)   ! doubling: linear in the file size
            ngroups = ngroups + 1
            call move_alloc(g%items, groups(ngroups)%items)
            groups(ngroups)%name = g%name; groups(ngroups)%line = g%line
            call move_alloc(g%text, groups(ngroups)%text)
            if (text(j:j) == '/') then
                i = j + 1
            else
                i = j + 4
            end if
        end do
        ! cases: one per &case; groups before the first &case belong to the first case
        groups = groups(1:ngroups)
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
    contains
        subroutine grow(a)
            type(fc_nml_group), allocatable, intent(inout) :: a(:)
            type(fc_nml_group), allocatable :: b(:)
            integer :: m
            allocate (b(2*size(a)))
            do m = 1, size(a)
                call move_alloc(a(m)%items, b(m)%items)
                call move_alloc(a(m)%text, b(m)%text)
                b(m)%name = a(m)%name; b(m)%line = a(m)%line
            end do
            call move_alloc(b, a)
        end subroutine grow
    end subroutine split_cases

    pure integer function count_char(text, c)
        character(len=*), intent(in) :: text
        character, intent(in) :: c
        integer :: i
        count_char = 0
        do i = 1, len(text)
            if (text(i:i) == c) count_char = count_char + 1
        end do
    end function count_char

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
        ! at most one item per '=': allocated once (no growth per item)
        allocate (kpos(count_char(body, '=')), epos(count_char(body, '=')))
        nitem = 0
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
            nitem = nitem + 1
            kpos(nitem) = kstart
            epos(nitem) = i
        end do
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
