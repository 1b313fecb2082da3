!> Lexical check of every `key = value` of a case file before its namelist READ
!! (doc/reliability.md): the value must be one literal of the key's type — a real, an
!! integer within the default integer range, a logical, or a quoted string no longer than
!! the field that holds it.  A bad value is reported as `&group key = value: <why>`, so no
!! read error reaches the user as gfortran's "Bad real number in item 1" or "Bad repeat
!! count", and no name or title is silently cut.
module fc_input_check
    use fc_kinds, only: i8
    use fc_strings, only: fmt_int, lower
    implicit none
    private

    public :: check_value, value_kind

contains

    !> errmsg = '' when `value` is a valid literal for `key` of `group`, else the message.
    subroutine check_value(group, key, value, errmsg)
        character(len=*), intent(in) :: group, key, value
        character(len=*), intent(out) :: errmsg
        character(len=:), allocatable :: v, head
        integer :: maxlen
        errmsg = ''
        v = trim(adjustl(value))
        head = '&'//trim(group)//' '//trim(key)//' = '//shown(v)//': '
        if (len(v) == 0) then
            errmsg = head//'missing value'; return
        end if
        select case (kind_of(key, maxlen))
        case ('real')
            if (.not. is_real(v)) then
                errmsg = head//'not a real number (e.g. 82000.0, 1.5e-3)'
            else if (decimal_magnitude(v) >= 308) then
                ! rejected before the read converts it: the conversion would overflow (a trap
                ! under -ffpe-trap=overflow, +Inf otherwise)
                errmsg = head//'outside the double-precision range (|value| < 1e308)'
            end if
        case ('integer')
            if (.not. is_integer_text(v)) then
                errmsg = head//'not an integer'
            else if (.not. fits_default_integer(v)) then
                errmsg = head//'outside the integer range [-2147483648, 2147483647]'
            end if
        case ('logical')
            if (.not. is_logical(v)) errmsg = head//'not a logical (.true. or .false.)'
        case ('string')
            if (len_trim(value) >= len(value) .and. (v(1:1) == "'" .or. v(1:1) == '"')) then
                ! the pre-parser keeps len(value) characters: the string is longer still
                errmsg = head//'more than '//fmt_int(len(value) - 2)//' characters, the limit is '//fmt_int(maxlen)
            else if (.not. is_quoted(v)) then
                errmsg = head//"not a quoted string (write it in quotes, e.g. 'text')"
            else if (len(v) - 2 > maxlen) then
                errmsg = head//fmt_int(len(v) - 2)//' characters, more than the limit '//fmt_int(maxlen)
            end if
        end select
    end subroutine check_value

    !> Type of the value of `key` ('real', 'integer', 'logical', 'string'; '' unknown).
    function value_kind(key) result(kind)
        character(len=*), intent(in) :: key
        character(len=:), allocatable :: kind
        integer :: maxlen
        kind = kind_of(key, maxlen)
    end function value_kind

    !> Type of a key ('real', 'integer', 'logical', 'string'; '' unknown) and, for strings,
    !! the length of the field that holds it.
    function kind_of(key, maxlen) result(kind)
        character(len=*), intent(in) :: key
        integer, intent(out) :: maxlen
        character(len=:), allocatable :: kind
        maxlen = 0
        select case (lower(trim(key)))
        case ('g1', 'g2', 'nu1', 'nu2', 'xmin', 'xmax', 'ymin', 'ymax', 'margin', 'rx', 'ry', 'diameter', 'sigma', &
              'gamma', 'amplitude', 'wavelength_x', 'wavelength_y', 'length', 'approach', 'fn', 'mu', 'xi', 'eta', &
              'phi', 'fx', 'fy', 'tol', 'omega', 'beta', 'target', 'mu_kinetic', 'dq', 'sweep_from', 'sweep_to')
            kind = 'real'
        case ('nx', 'ny', 'n_across', 'm_modes', 'n_modes', 'seed', 'maxit', 'inner_maxit', 'inner_k', 'max_levels', &
              'threads', 'nsteps', 'sweep_n')
            kind = 'integer'
        case ('auto', 'precondition', 'precondition_tangential', 'deflation', 'target_pmax', 'table', 'periodic')
            kind = 'logical'
        case ('name'); kind = 'string'; maxlen = 64
        case ('title'); kind = 'string'; maxlen = 128
        case ('problem', 'normal', 'tangential'); kind = 'string'; maxlen = 32
        case ('kind', 'cycle', 'strip', 'model'); kind = 'string'; maxlen = 16
        case ('smoother', 'sweep', 'table_format'); kind = 'string'; maxlen = 8
        case ('rolling', 'fft_preconditioner', 'rolling_start'); kind = 'string'; maxlen = 16
        case ('ic_file', 'ic_file2', 'file', 'dir', 'fft_wisdom'); kind = 'string'; maxlen = 256
        case default; kind = ''
        end select
    end function kind_of

    !> A real literal: [sign] digits [. digits] [(e|d) [sign] digits], at least one digit in
    !! the mantissa, or NaN / Inf / Infinity with a sign (the validators reject those by key).
    !> Decimal exponent of the first significant digit of a real literal that [[is_real]]
    !! accepted (e.g. 12.5e3 → 4, 0.05 → −2, 0 → −huge); exponents beyond 9 digits saturate.
    pure integer function decimal_magnitude(v) result(mag)
        character(len=*), intent(in) :: v
        integer :: i, n, nint_digits, lead0, ex, sgn, nd
        logical :: nonzero
        character(len=len(v)) :: w
        w = v
        call lower_in_place(w)
        n = len_trim(w); i = 1
        mag = -huge(1)
        if (w(1:1) == '+' .or. w(1:1) == '-') i = 2
        if (index(w, 'n') > 0) return                      ! nan, inf, infinity: checked by the validators
        nint_digits = 0; lead0 = 0; nonzero = .false.
        do while (i <= n)
            if (.not. is_digit(w(i:i))) exit
            if (w(i:i) /= '0' .or. nonzero) then
                nonzero = .true.; nint_digits = nint_digits + 1
            end if
            i = i + 1
        end do
        if (i <= n) then
            if (w(i:i) == '.') then
                i = i + 1
                do while (i <= n)
                    if (.not. is_digit(w(i:i))) exit
                    if (.not. nonzero) then
                        if (w(i:i) == '0') then
                            lead0 = lead0 + 1
                        else
                            nonzero = .true.
                        end if
                    end if
                    i = i + 1
                end do
            end if
        end if
        if (.not. nonzero) return
        if (nint_digits > 0) then
            mag = nint_digits - 1
        else
            mag = -(lead0 + 1)
        end if
        ex = 0; sgn = 1; nd = 0
        if (i <= n) then
            i = i + 1                                      ! 'e' or 'd'
            if (i <= n) then
                if (w(i:i) == '-') sgn = -1
                if (w(i:i) == '+' .or. w(i:i) == '-') i = i + 1
            end if
            do while (i <= n)
                if (.not. is_digit(w(i:i))) exit
                if (nd < 9) ex = 10*ex + (iachar(w(i:i)) - iachar('0'))
                if (nd >= 9) ex = 999999999
                nd = nd + 1; i = i + 1
            end do
        end if
        mag = mag + sgn*ex
    end function decimal_magnitude

    pure logical function is_real(v)
        character(len=*), intent(in) :: v
        integer :: i, n, nd
        character(len=len(v)) :: w
        is_real = .false.
        w = v
        call lower_in_place(w)
        i = 1; n = len(v)
        if (w(1:1) == '+' .or. w(1:1) == '-') i = 2
        if (i > n) return
        if (w(i:) == 'nan' .or. w(i:) == 'inf' .or. w(i:) == 'infinity') then
            is_real = .true.; return
        end if
        nd = 0
        do while (i <= n)
            if (.not. is_digit(w(i:i))) exit
            i = i + 1; nd = nd + 1
        end do
        if (i <= n) then
            if (w(i:i) == '.') then
                i = i + 1
                do while (i <= n)
                    if (.not. is_digit(w(i:i))) exit
                    i = i + 1; nd = nd + 1
                end do
            end if
        end if
        if (nd == 0) return
        if (i <= n) then
            if (w(i:i) /= 'e' .and. w(i:i) /= 'd') return
            i = i + 1
            if (i <= n) then
                if (w(i:i) == '+' .or. w(i:i) == '-') i = i + 1
            end if
            nd = 0
            do while (i <= n)
                if (.not. is_digit(w(i:i))) exit
                i = i + 1; nd = nd + 1
            end do
            if (nd == 0) return
        end if
        is_real = i > n
    end function is_real

    pure logical function is_integer_text(v)
        character(len=*), intent(in) :: v
        integer :: i
        i = 1
        if (v(1:1) == '+' .or. v(1:1) == '-') i = 2
        is_integer_text = i <= len(v) .and. verify(v(i:), '0123456789') == 0
    end function is_integer_text

    !> The integer literal fits the default (32-bit) integer.
    logical function fits_default_integer(v)
        character(len=*), intent(in) :: v
        integer(i8) :: x
        integer :: ios, i, first
        fits_default_integer = .false.
        i = 1
        if (v(1:1) == '+' .or. v(1:1) == '-') i = 2
        first = verify(v(i:), '0')                 ! first non-zero digit
        if (first == 0) then
            fits_default_integer = .true.; return  ! all zeros
        end if
        if (len(v) - (i + first - 1) + 1 > 10) return
        read (v, *, iostat=ios) x
        if (ios /= 0) return
        fits_default_integer = x >= -huge(0) - 1_i8 .and. x <= huge(0)
    end function fits_default_integer

    !> Namelist logical: optional '.', then t or f, then letters, optional '.' (.true., T, .f.).
    pure logical function is_logical(v)
        character(len=*), intent(in) :: v
        character(len=len(v)) :: w
        integer :: i, j
        w = v
        call lower_in_place(w)
        i = 1; j = len(w)
        if (w(1:1) == '.') i = 2
        if (j > i .and. w(j:j) == '.') j = j - 1
        is_logical = .false.
        if (i > j) return
        if (w(i:i) /= 't' .and. w(i:i) /= 'f') return
        is_logical = verify(w(i:j), 'abcdefghijklmnopqrstuvwxyz') == 0
    end function is_logical

    !> One string in matching quotes with no unescaped quote of the same kind inside
    !! (a doubled quote stands for one).
    pure logical function is_quoted(v)
        character(len=*), intent(in) :: v
        character :: q
        integer :: i, n
        is_quoted = .false.
        n = len(v)
        if (n < 2) return
        q = v(1:1)
        if ((q /= "'" .and. q /= '"') .or. v(n:n) /= q) return
        i = 2
        do while (i <= n - 1)
            if (v(i:i) == q) then
                if (i + 1 <= n - 1 .and. v(i + 1:i + 1) == q) then
                    i = i + 2; cycle
                end if
                return
            end if
            i = i + 1
        end do
        is_quoted = .true.
    end function is_quoted

    pure logical function is_digit(c)
        character, intent(in) :: c
        is_digit = c >= '0' .and. c <= '9'
    end function is_digit

    pure subroutine lower_in_place(w)
        character(len=*), intent(inout) :: w
        integer :: i
        do i = 1, len(w)
            if (w(i:i) >= 'A' .and. w(i:i) <= 'Z') w(i:i) = achar(iachar(w(i:i)) + 32)
        end do
    end subroutine lower_in_place

    !> The value as shown in messages (long values shortened).
    pure function shown(v) result(t)
        character(len=*), intent(in) :: v
        character(len=:), allocatable :: t
        if (len(v) > 60) then
            t = v(1:50)//'... ('//'long)'
        else
            t = v
        end if
    end function shown

end module fc_input_check
