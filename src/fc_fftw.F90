!> Thin wrapper around FFTW's Fortran 2003 interface.
!!
!! The header is pulled in with the preprocessor (`#include`), which fpm handles
!! without extra flags; only the handful of routines fastcontact uses are public.
module fc_fftw
    use, intrinsic :: iso_c_binding
    implicit none
    private

#include "fftw3.f03"

    !> FFTW's `fftw_alignment_of` for an address of any type: arrays with equal values may
    !! replace each other in new-array execution of one plan (FFTW manual, "New-array
    !! Execute Functions").
    interface
        integer(c_int) function fc_fftw_alignment_of(p) bind(C, name='fftw_alignment_of')
            import :: c_int, c_ptr
            type(c_ptr), value :: p
        end function fc_fftw_alignment_of
    end interface

    public :: c_ptr, c_null_ptr, c_associated, c_int, fc_fftw_alignment_of
    public :: fftw_plan_dft_r2c_2d, fftw_plan_dft_c2r_2d
    public :: fftw_execute_dft_r2c, fftw_execute_dft_c2r
    public :: fftw_plan_many_dft_r2c, fftw_plan_many_dft_c2r, fftw_plan_many_dft, fftw_execute_dft
    public :: fftw_destroy_plan, fftw_plan_dft_r2c_1d, fftw_plan_dft_c2r_1d, fftw_plan_dft_1d
    public :: fftw_alloc_real, fftw_alloc_complex, fftw_free, c_f_pointer, c_size_t, fftw_forget_wisdom
    public :: fftw_import_wisdom_from_filename, fftw_export_wisdom_to_filename, FFTW_WISDOM_ONLY, c_null_char
    public :: circulant_size, friendly_size
    public :: FFTW_ESTIMATE, FFTW_MEASURE, FFTW_UNALIGNED, FFTW_DESTROY_INPUT, FFTW_FORWARD, FFTW_BACKWARD

contains

    !> Size of the circulant that embeds a Toeplitz product of n points: 2n when FFTW
    !! transforms that size fast, else the next even size of the form 2^a 3^b 5^c 7^d 11^e
    !! 13^f with e + f ≤ 1, the sizes FFTW's manual names as the ones it handles best (any
    !! size ≥ 2n − 1 gives the same product).  On 241×199 the doubled 482×398 (2·241, 2·199)
    !! made TangCG four times slower than on 240×200 (doc/operators.md, "Circulant sizes").
    !! 1 for n = 1 (no transform along that direction).
    pure integer function circulant_size(n) result(m)
        integer, intent(in) :: n
        if (n <= 1) then
            m = 1
            return
        end if
        m = 2*n
        do while (.not. fftw_friendly(m))
            m = m + 2
        end do
    end function circulant_size

    !> n when FFTW transforms n points fast (see [[circulant_size]]), else the next larger
    !! such size: the period of the preconditioners' Strang circulants on an nx×ny grid.
    pure integer function friendly_size(n) result(m)
        integer, intent(in) :: n
        m = max(n, 1)
        do while (.not. fftw_friendly(m))
            m = m + 1
        end do
    end function friendly_size

    !> True when m = 2^a 3^b 5^c 7^d 11^e 13^f with e + f ≤ 1.
    pure logical function fftw_friendly(m) result(ok)
        integer, intent(in) :: m
        integer :: r, k, e
        integer, parameter :: small(4) = [2, 3, 5, 7]
        r = m
        do k = 1, size(small)
            do while (mod(r, small(k)) == 0)
                r = r/small(k)
            end do
        end do
        e = 0
        do while (mod(r, 11) == 0)
            r = r/11; e = e + 1
        end do
        do while (mod(r, 13) == 0)
            r = r/13; e = e + 1
        end do
        ok = r == 1 .and. e <= 1
    end function fftw_friendly

end module fc_fftw
