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
    public :: FFTW_ESTIMATE, FFTW_MEASURE, FFTW_UNALIGNED, FFTW_DESTROY_INPUT, FFTW_FORWARD, FFTW_BACKWARD

end module fc_fftw
