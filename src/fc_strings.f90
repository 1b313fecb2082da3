!> Text helpers shared by the input, output, driver and flat-API layers: numbers for
!! messages, case conversion.
module fc_strings
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
    use fc_kinds, only: dp
    implicit none
    private

    public :: fmt_int, fmt_real, fmt_g6, lower, upper, shorten, append_line

contains

    !> An integer without blanks.
    pure function fmt_int(i) result(s)
        integer, intent(in) :: i
        character(len=:), allocatable :: s
        character(len=20) :: buf
        write (buf, '(i0)') i
        s = trim(buf)
    end function fmt_int

    !> Short text of a real for messages: fixed notation without trailing zeros for
    !! 1e−3 ≤ |x| < 1e7 (and 0), else 9 significant digits in exponent form; NaN, ±Inf.
    function fmt_real(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=40) :: buf
        if (ieee_is_nan(x)) then
            s = 'NaN'; return
        end if
        if (.not. ieee_is_finite(x)) then
            s = merge('+Inf', '-Inf', x > 0); return
        end if
        if (x == 0 .or. (abs(x) >= 1.0e-3_dp .and. abs(x) < 1.0e7_dp)) then
            write (buf, '(f0.8)') x
            buf = adjustl(buf)
            s = trim(buf)
            do while (len(s) > 1 .and. s(len(s):len(s)) == '0')
                s = s(1:len(s) - 1)
            end do
            if (s(len(s):len(s)) == '.') s = s//'0'
            if (s(1:1) == '.') s = '0'//s
            if (len(s) >= 2) then
                if (s(1:2) == '-.') s = '-0'//s(2:)
            end if
        else
            if (abs(x) >= 1.0e100_dp .or. abs(x) < 1.0e-99_dp) then
                write (buf, '(es16.8e3)') x     ! three exponent digits keep the 'E'
            else
                write (buf, '(es15.8)') x
            end if
            s = trim(adjustl(buf))
        end if
    end function fmt_real

    !> A real with 6 significant digits (g0.6), as the flat API's messages write it.
    function fmt_g6(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        write (buf, '(g0.6)') x
        s = trim(adjustl(buf))
    end function fmt_g6

    !> ASCII lower case.
    pure function lower(s) result(t)
        character(len=*), intent(in) :: s
        character(len=len(s)) :: t
        integer :: i
        t = s
        do i = 1, len(s)
            if (s(i:i) >= 'A' .and. s(i:i) <= 'Z') t(i:i) = achar(iachar(s(i:i)) + 32)
        end do
    end function lower

    !> ASCII upper case.
    pure function upper(s) result(t)
        character(len=*), intent(in) :: s
        character(len=len(s)) :: t
        integer :: i
        t = s
        do i = 1, len(s)
            if (s(i:i) >= 'a' .and. s(i:i) <= 'z') t(i:i) = achar(iachar(s(i:i)) - 32)
        end do
    end function upper

    !> `s` trimmed, cut to 60 characters with '...' when longer.
    pure function shorten(s) result(t)
        character(len=*), intent(in) :: s
        character(len=:), allocatable :: t
        if (len_trim(s) > 60) then
            t = s(1:57)//'...'
        else
            t = trim(s)
        end if
    end function shorten

    !> Append `text` as a new line to the list `list` (cut to the list's length).
    pure subroutine append_line(list, text)
        character(len=*), allocatable, intent(inout) :: list(:)
        character(len=*), intent(in) :: text
        character(len=len(list)), allocatable :: tmp(:)
        allocate (tmp(size(list) + 1))
        tmp(1:size(list)) = list
        tmp(size(list) + 1) = text
        call move_alloc(tmp, list)
    end subroutine append_line

end module fc_strings
