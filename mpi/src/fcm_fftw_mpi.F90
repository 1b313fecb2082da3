!> FFTW's MPI interface (distributed transposes and cosine transforms) for the MPI package.
!!
!! The header is pulled in with the preprocessor; it also declares FFTW's serial interface,
!! so modules of this package take every FFTW name from here, never from [[fc_fftw]].
module fcm_fftw_mpi
    use, intrinsic :: iso_c_binding
    implicit none
    private

#include "fftw3-mpi.f03"

    public :: c_ptr, c_null_ptr, c_associated, c_int, c_intptr_t, c_size_t, c_f_pointer
    public :: fftw_mpi_init, fftw_mpi_cleanup, fftw_mpi_local_size_many_transposed, fftw_mpi_local_size_2d_transposed
    public :: fftw_mpi_plan_many_transpose, fftw_mpi_plan_r2r_2d
    public :: fftw_plan_dft_r2c_1d, fftw_plan_dft_c2r_1d, fftw_plan_dft_1d
    public :: fftw_execute_dft_r2c, fftw_execute_dft_c2r, fftw_execute_dft, fftw_execute_r2r
    public :: fftw_mpi_execute_r2r, fftw_destroy_plan, fftw_alloc_real, fftw_alloc_complex, fftw_free
    public :: FFTW_ESTIMATE, FFTW_MEASURE, FFTW_FORWARD, FFTW_BACKWARD, FFTW_REDFT00
    public :: fftw_mpi_gather_wisdom, fftw_mpi_broadcast_wisdom, FFTW_WISDOM_ONLY, fftw_forget_wisdom
    public :: fftw_import_wisdom_from_filename
    public :: FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_TRANSPOSED_IN, FFTW_MPI_TRANSPOSED_OUT

end module fcm_fftw_mpi
