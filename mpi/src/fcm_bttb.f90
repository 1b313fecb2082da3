!> Distributed products with the influence matrix of an even kernel (A^zz, its Toeplitz
!! preconditioner, the periodic kernel) over the ranks of an MPI communicator.
!!
!! Layout (slab decomposition).  The nx×ny grid is split into blocks of rows: rank r holds
!! rows y0+1 … y0+nyl of every vector (x runs fastest, as in the serial code).  A product
!! y = C x with the circulant C of size mx×my (mx = 2nx, my = 2ny: the doubled grid of the
!! Toeplitz embedding; mx = nx, my = ny for the periodic cell) is computed as
!!
!!   1. per local row: real FFT of length mx (the row zero-padded from nx), nxh = mx/2+1 bins;
!!   2. FFTW-MPI transpose (all-to-all): rank r now holds spectral columns k0+1 … k0+nkl,
!!      each with all ny data rows;
!!   3. per local column: complex FFT of length my (zero-padded from ny), multiplication by
!!      the symbol, inverse FFT, the first ny entries kept;
!!   4. transpose back, inverse real FFT per row, the first nx entries kept.
!!
!! The padding never travels over the network and no rank stores a doubled-grid array:
!! per rank about 2·nx·ny/P complex numbers of buffers.  Rows (1., 4.) and columns (3.)
!! are independent and shared among OpenMP threads.
!!
!! Symbols.  The kernels are even in x and y, so the symbol of the circulant is real and
!! equals the 2D cosine transform (REDFT00) of the kernel's quadrant 0 ≤ i < nxh,
!! 0 ≤ j < nsy (nsy = my/2+1): the quadrant is distributed by rows, transformed by
!! FFTW-MPI with transposed output, and lands in exactly the spectral columns this rank
!! owns in step 3.  sym(ky, kx) is stored for ky ∈ [0, my/2] (ky and my−ky share a value).
module fcm_bttb
    use mpi
    use fc_kinds, only: dp, FC_ERR_GRID, FC_ERR_INTERNAL
    use fcm_fftw_mpi
    implicit none
    private

    !> Distribution, buffers and plans of the distributed products on one grid.
    !! Owns FFTW plans and buffers: do not copy an initialised layout.
    type, public :: fcm_layout
        integer :: comm = MPI_COMM_NULL
        integer :: nprocs = 1, rank = 0
        integer :: nx = 0, ny = 0          !! grid size
        integer :: mx = 0, my = 0          !! circulant size
        logical :: periodic = .false.      !! circulant on the grid itself (no padding)
        integer :: nxh = 0                 !! spectral columns mx/2+1
        integer :: nsy = 0                 !! symbol rows my/2+1
        integer :: nyl = 0, y0 = 0         !! local grid rows y0+1 … y0+nyl
        integer :: nkl = 0, k0 = 0         !! local spectral columns k0+1 … k0+nkl
        integer :: nql = 0, q0 = 0         !! local quadrant rows q0 … q0+nql−1 (symbol set-up)
        integer :: nproducts = 0           !! products applied (work counter)
        type(c_ptr) :: p1 = c_null_ptr, p2 = c_null_ptr
        complex(dp), pointer, contiguous :: c1(:, :) => null()  !! row spectra (nxh, nyl)
        complex(dp), pointer, contiguous :: t(:, :) => null()   !! transposed (ny, nkl)
        real(dp), pointer, contiguous :: r1(:) => null(), r2(:) => null()
        type(c_ptr) :: plan_t_fwd = c_null_ptr, plan_t_bwd = c_null_ptr
        type(c_ptr) :: plan_xf = c_null_ptr, plan_xb = c_null_ptr, plan_yf = c_null_ptr, plan_yb = c_null_ptr
    contains
        procedure :: apply => layout_apply
        procedure :: destroy => layout_destroy
        final :: layout_final
    end type fcm_layout

    public :: layout_init, cosine_transform, cosine_transform_back

contains

    !> Set up the layout of an nx×ny grid on `comm` (collective).  stat ≠ 0 when the grid
    !! cannot be distributed (fewer rows than ranks, or a dimension < 2).
    subroutine layout_init(lay, comm, nx, ny, periodic, stat, errmsg, measure)
        type(fcm_layout), intent(inout) :: lay
        integer, intent(in) :: comm, nx, ny
        logical, intent(in) :: periodic
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        !> measure the product's plans (FFTW_MEASURE: the 1D transforms and the transposes,
        !! from the wisdom the ranks hold where it has them) instead of estimating them
        logical, intent(in), optional :: measure
        integer(c_int) :: flags
        integer(c_intptr_t) :: alloc, nyl, y0, nkl, k0, nql, q0, nkl2, k02
        type(c_ptr) :: pr, pc
        real(dp), pointer :: rb(:)
        complex(dp), pointer :: cb(:)
        integer :: ierr
        stat = 0; errmsg = ''
        flags = FFTW_ESTIMATE
        if (present(measure)) then
            if (measure) flags = FFTW_MEASURE
        end if
        call lay%destroy()
        call mpi_comm_size(comm, lay%nprocs, ierr)
        call mpi_comm_rank(comm, lay%rank, ierr)
        if (nx < 2 .or. ny < lay%nprocs .or. ny < 2) then
            stat = FC_ERR_GRID
            write (errmsg, '(a,i0,a,i0,a,i0,a)') 'distributed grid: nx = ', nx, ', ny = ', ny, &
                ' cannot be split over ', lay%nprocs, ' ranks (need nx >= 2 and ny >= max(2, ranks))'
            return
        end if
        lay%comm = comm
        lay%nx = nx; lay%ny = ny; lay%periodic = periodic
        if (periodic) then
            lay%mx = nx; lay%my = ny
        else
            lay%mx = 2*nx; lay%my = 2*ny
        end if
        lay%nxh = lay%mx/2 + 1
        lay%nsy = lay%my/2 + 1
        alloc = fftw_mpi_local_size_many_transposed(2_c_int, [int(ny, c_intptr_t), int(lay%nxh, c_intptr_t)], &
            2_c_intptr_t, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, comm, nyl, y0, nkl, k0)
        lay%nyl = int(nyl); lay%y0 = int(y0); lay%nkl = int(nkl); lay%k0 = int(k0)
        alloc = max(alloc, 2_c_intptr_t)
        lay%p1 = fftw_alloc_real(int(alloc, c_size_t))
        lay%p2 = fftw_alloc_real(int(alloc, c_size_t))
        call c_f_pointer(lay%p1, lay%r1, [alloc])
        call c_f_pointer(lay%p2, lay%r2, [alloc])
        call c_f_pointer(lay%p1, lay%c1, [lay%nxh, lay%nyl])
        call c_f_pointer(lay%p2, lay%t, [ny, lay%nkl])
        lay%plan_t_fwd = fftw_mpi_plan_many_transpose(int(ny, c_intptr_t), int(lay%nxh, c_intptr_t), 2_c_intptr_t, &
            FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, lay%r1, lay%r2, comm, flags)
        lay%plan_t_bwd = fftw_mpi_plan_many_transpose(int(lay%nxh, c_intptr_t), int(ny, c_intptr_t), 2_c_intptr_t, &
            FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, lay%r2, lay%r1, comm, flags)
        ! 1D plans on aligned scratch (fftw_alloc): executed later on other fftw_alloc'd rows
        pr = fftw_alloc_real(int(lay%mx, c_size_t)); pc = fftw_alloc_complex(int(max(lay%nxh, lay%my), c_size_t))
        call c_f_pointer(pr, rb, [lay%mx]); call c_f_pointer(pc, cb, [max(lay%nxh, lay%my)])
        lay%plan_xf = fftw_plan_dft_r2c_1d(int(lay%mx, c_int), rb, cb, flags)
        lay%plan_xb = fftw_plan_dft_c2r_1d(int(lay%mx, c_int), cb, rb, flags)
        lay%plan_yf = fftw_plan_dft_1d(int(lay%my, c_int), cb, cb, FFTW_FORWARD, flags)
        lay%plan_yb = fftw_plan_dft_1d(int(lay%my, c_int), cb, cb, FFTW_BACKWARD, flags)
        call fftw_free(pr); call fftw_free(pc)
        ! quadrant rows for the symbol set-up; its spectral columns must be the ones above
        alloc = fftw_mpi_local_size_2d_transposed(int(lay%nsy, c_intptr_t), int(lay%nxh, c_intptr_t), comm, &
            nql, q0, nkl2, k02)
        lay%nql = int(nql); lay%q0 = int(q0)
        if (nkl2 /= nkl .or. (nkl > 0 .and. k02 /= k0)) then
            stat = FC_ERR_INTERNAL; errmsg = 'distributed grid: FFTW distributions of the transpose and the cosine transform differ'
        end if
    end subroutine layout_init

    !> y = C x for the circulant with real symbol `sym(0:nsy−1, nkl)` (scaled by 1/(mx·my)),
    !! restricted to the grid; x, y are the local rows (nx, nyl).  Collective.
    subroutine layout_apply(self, sym, x, y)
        class(fcm_layout), intent(inout) :: self
        real(dp), intent(in) :: sym(0:, :)
        real(dp), intent(in) :: x(:, :)
        real(dp), intent(out) :: y(:, :)
        type(c_ptr) :: pr, pc
        real(dp), pointer :: rb(:)
        complex(dp), pointer :: cb(:)
        integer :: j, c, k, nx, ny, mx, my
        nx = self%nx; ny = self%ny; mx = self%mx; my = self%my
        !$omp parallel default(shared) private(pr, pc, rb, cb, j)
        pr = fftw_alloc_real(int(mx, c_size_t)); pc = fftw_alloc_complex(int(self%nxh, c_size_t))
        call c_f_pointer(pr, rb, [mx]); call c_f_pointer(pc, cb, [self%nxh])
        !$omp do schedule(static)
        do j = 1, self%nyl
            rb(1:nx) = x(:, j)
            rb(nx + 1:mx) = 0
            call fftw_execute_dft_r2c(self%plan_xf, rb, cb)
            self%c1(:, j) = cb
        end do
        !$omp end do
        call fftw_free(pr); call fftw_free(pc)
        !$omp end parallel
        call fftw_mpi_execute_r2r(self%plan_t_fwd, self%r1, self%r2)
        !$omp parallel default(shared) private(pc, cb, c, k)
        pc = fftw_alloc_complex(int(my, c_size_t))
        call c_f_pointer(pc, cb, [my])
        !$omp do schedule(static)
        do c = 1, self%nkl
            cb(1:ny) = self%t(:, c)
            cb(ny + 1:my) = 0
            call fftw_execute_dft(self%plan_yf, cb, cb)
            do k = 0, my - 1
                cb(k + 1) = cb(k + 1)*sym(min(k, my - k), c)
            end do
            call fftw_execute_dft(self%plan_yb, cb, cb)
            self%t(:, c) = cb(1:ny)
        end do
        !$omp end do
        call fftw_free(pc)
        !$omp end parallel
        call fftw_mpi_execute_r2r(self%plan_t_bwd, self%r2, self%r1)
        !$omp parallel default(shared) private(pr, pc, rb, cb, j)
        pr = fftw_alloc_real(int(mx, c_size_t)); pc = fftw_alloc_complex(int(self%nxh, c_size_t))
        call c_f_pointer(pr, rb, [mx]); call c_f_pointer(pc, cb, [self%nxh])
        !$omp do schedule(static)
        do j = 1, self%nyl
            cb = self%c1(:, j)
            call fftw_execute_dft_c2r(self%plan_xb, cb, rb)
            y(:, j) = rb(1:nx)
        end do
        !$omp end do
        call fftw_free(pr); call fftw_free(pc)
        !$omp end parallel
        self%nproducts = self%nproducts + 1
    end subroutine layout_apply

    !> s = REDFT00 of the quadrant q(0:nxh−1, local quadrant rows) in the spectral layout
    !! s(0:nsy−1, nkl) (unnormalised: the DFT of the even circulant).  Collective; set-up only.
    subroutine cosine_transform(lay, q, s)
        type(fcm_layout), intent(in) :: lay
        real(dp), intent(in) :: q(:, :)
        real(dp), intent(out) :: s(:, :)
        call run_r2r(lay, q, s, .true.)
    end subroutine cosine_transform

    !> Inverse direction of [[cosine_transform]] (spectral layout in, quadrant rows out; the
    !! transform is its own inverse up to the factor (mx·my), which the caller applies).
    subroutine cosine_transform_back(lay, s, q)
        type(fcm_layout), intent(in) :: lay
        real(dp), intent(in) :: s(:, :)
        real(dp), intent(out) :: q(:, :)
        call run_r2r(lay, s, q, .false.)
    end subroutine cosine_transform_back

    subroutine run_r2r(lay, a, b, forward)
        type(fcm_layout), intent(in) :: lay
        real(dp), intent(in) :: a(:, :)
        real(dp), intent(out) :: b(:, :)
        logical, intent(in) :: forward
        integer(c_intptr_t) :: alloc, l0, s0, l1, s1
        type(c_ptr) :: pin, pout, plan
        real(dp), pointer :: rin(:), rout(:)
        integer(c_int) :: flags
        alloc = fftw_mpi_local_size_2d_transposed(int(lay%nsy, c_intptr_t), int(lay%nxh, c_intptr_t), lay%comm, &
            l0, s0, l1, s1)
        alloc = max(alloc, 1_c_intptr_t)
        pin = fftw_alloc_real(int(alloc, c_size_t)); pout = fftw_alloc_real(int(alloc, c_size_t))
        call c_f_pointer(pin, rin, [alloc]); call c_f_pointer(pout, rout, [alloc])
        flags = FFTW_ESTIMATE + FFTW_MPI_TRANSPOSED_OUT
        if (.not. forward) flags = FFTW_ESTIMATE + FFTW_MPI_TRANSPOSED_IN
        plan = fftw_mpi_plan_r2r_2d(int(lay%nsy, c_intptr_t), int(lay%nxh, c_intptr_t), rin, rout, lay%comm, &
            FFTW_REDFT00, FFTW_REDFT00, flags)
        if (size(a) > 0) rin(1:size(a)) = reshape(a, [size(a)])
        call fftw_mpi_execute_r2r(plan, rin, rout)
        if (size(b) > 0) b = reshape(rout(1:size(b)), shape(b))
        call fftw_destroy_plan(plan)
        call fftw_free(pin); call fftw_free(pout)
    end subroutine run_r2r

    !> Release plans and buffers.
    subroutine layout_destroy(self)
        class(fcm_layout), intent(inout) :: self
        if (c_associated(self%plan_t_fwd)) call fftw_destroy_plan(self%plan_t_fwd)
        if (c_associated(self%plan_t_bwd)) call fftw_destroy_plan(self%plan_t_bwd)
        if (c_associated(self%plan_xf)) call fftw_destroy_plan(self%plan_xf)
        if (c_associated(self%plan_xb)) call fftw_destroy_plan(self%plan_xb)
        if (c_associated(self%plan_yf)) call fftw_destroy_plan(self%plan_yf)
        if (c_associated(self%plan_yb)) call fftw_destroy_plan(self%plan_yb)
        self%plan_t_fwd = c_null_ptr; self%plan_t_bwd = c_null_ptr
        self%plan_xf = c_null_ptr; self%plan_xb = c_null_ptr; self%plan_yf = c_null_ptr; self%plan_yb = c_null_ptr
        if (c_associated(self%p1)) call fftw_free(self%p1)
        if (c_associated(self%p2)) call fftw_free(self%p2)
        self%p1 = c_null_ptr; self%p2 = c_null_ptr
        nullify (self%c1, self%t, self%r1, self%r2)
        self%nx = 0; self%ny = 0
    end subroutine layout_destroy

    subroutine layout_final(self)
        type(fcm_layout), intent(inout) :: self
        call self%destroy()
    end subroutine layout_final

end module fcm_bttb
