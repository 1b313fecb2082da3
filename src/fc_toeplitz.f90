!> Block Toeplitz matrices with Toeplitz blocks (BTTB) and their fast products by FFT.
!!
!! An [[fc_bttb]] is y = A x on an nx×ny grid where A's entries depend only on the offset
!! (ix−jx, iy−jy): the coefficients `kernel(dix, diy)`.  Products are circulant
!! convolutions on a doubled grid (mx = 2nx, my = 2ny, or the next size FFTW transforms
!! fast: fc_fftw's circulant_size; the grid itself when periodic),
!! one forward and one inverse real FFT per product (thesis §2.2.4, §3.3.1); the direct
!! O(n²) sum is kept as the test oracle.  This module knows nothing of elasticity: the
!! coefficients come from [[fc_influence]].
!!
!! Storage and lifetime:
!! * the symbol (the transform of the circulant) is stored as real numbers when the
!!   circulant is even, c(−i,−j) = c(i,j) (symbol real: A^zz, A^xx, A^yy, A^xy and the
!!   Toeplitz inverses), or odd, c(−i,−j) = −c(i,j) (symbol imaginary: the coupling blocks
!!   A^xz, A^zx, A^yz, A^zy); only other kernels keep a complex symbol;
!! * FFTW plans and the work buffers live in a reference-counted plan set.  Blocks of one
!!   operator on one grid share ONE set (`plans_from` on the build routines), and so do
!!   the normal and the tangential operator when they are built one after the other; the
!!   set is freed with the last block using it, by [[fc_bttb]]'s `destroy` or its final
!!   binding;
!! * copies are deep: assigning an [[fc_bttb]] gives the copy its own plans and buffers
!!   (defined assignment), so a copy stays valid after the original is destroyed and two
!!   copies never write into each other's buffers.  A copied operator made of several
!!   blocks therefore owns one plan set per block; build in place to share.
!! Blocks sharing a plan set must not be applied concurrently (one set of buffers).  Plans
!! are made and destroyed inside the critical section `fc_fftw_planner` (see fc_threads).
!!
!! Size (~1300 lines): construction (Strang circulants and the even circulants' symbols of
!! TangCG's block inverse included, which use the plan set's buffers), lifetime, the
!! products, the large grids' chunked y passes and the block products' lanes (which add a
!! second plan set and buffer to it) share the plan set and its buffers; splitting them would
!! make the plan set public, and a module of its own below this one would add a layer to
!! the module graph (doc/architecture.md).
module fc_toeplitz
    use fc_kinds, only: dp, i8
    use, intrinsic :: iso_c_binding, only: c_loc
    use fc_fftw
    use fc_threads, only: omp_min_elements, fftw_threads_for_size, lanes_min_elements, fftw_planner_threads
    !$ use omp_lib, only: omp_get_max_threads, omp_in_parallel, omp_get_thread_num, omp_get_num_threads
    implicit none
    private

    !> How the symbol is stored.
    integer, parameter, public :: SYMBOL_GENERAL = 0  !! complex symbol
    integer, parameter, public :: SYMBOL_EVEN = 1     !! real symbol (even circulant)
    integer, parameter, public :: SYMBOL_ODD = 2      !! imaginary symbol, its imaginary part stored

    !> FFTW plans and work buffers for products of one size (nx×ny grid in an mx×my
    !! circulant), shared by reference count among the blocks of an operator.
    type :: fc_fft_plans
        integer :: nx = 0, ny = 0, mx = 0, my = 0
        real(dp), allocatable :: rbuf(:, :)
        complex(dp), allocatable :: cbuf(:, :)
        ! Every 2D transform is two passes of 1D transforms.  Products skip the zero padding:
        ! r2c along x on the ny data columns only, then c2c along y; inverse in the opposite
        ! order, c2r only for the ny columns kept.  Transforms of a whole mx×my array (the
        ! builds) take the x passes over all my columns (`plan_xf_*`, made when my > ny).
        ! No 2D plans: one construction for products and builds (doc/operators.md, "Plans").
        type(c_ptr) :: plan_x_fwd = c_null_ptr, plan_y_fwd = c_null_ptr
        type(c_ptr) :: plan_y_bwd = c_null_ptr, plan_x_bwd = c_null_ptr
        type(c_ptr) :: plan_xf_fwd = c_null_ptr, plan_xf_bwd = c_null_ptr
        !> Large spectra (mxh·my ≥ [[fc_toeplitz:transposed_y_min]]) take the y passes on column chunks
        !! of `tw` columns copied into contiguous buffers (`tbuf`, one per thread), where the
        !! strided plans run out of cache; `tw` = 0: the strided plans.
        integer :: tw = 0
        integer :: tthreads = 1                        !! threads (buffers) of the chunked passes
        type(c_ptr) :: plan_yt_fwd = c_null_ptr, plan_yt_bwd = c_null_ptr
        complex(dp), allocatable :: tbuf(:, :, :)     !! (my, tw, tthreads)
        integer :: refs = 0                !! blocks using this set
        integer :: planner_threads = 1     !! threads of these plans
        !> lanes of [[block_product]]: its two components run side by side, one thread each,
        !! executing the same single-threaded plans (FFTW's new-array execution) on two real
        !! buffers.  The plans are this set's own when they are single-threaded, else `serial`;
        !! made on first use with two threads or more (lanes_state = LANES_ON).
        type(fc_fft_plans), pointer :: serial => null()
        real(dp), allocatable :: rbuf2(:, :)
        integer :: lanes_state = 0
    end type fc_fft_plans
    integer, parameter :: LANES_NONE = 0, LANES_ON = 1
    !> Spectra of at least this many complex values (mxh·my: 33 MB, a 1024² grid's doubled
    !! spectrum) take the chunked y passes: measured 0.55–0.66 of the strided passes' time at
    !! 1024² and 0.57–0.63 at 2048², no gain at 512² (a spectrum of 17 MB that the caches
    !! hold) and below (doc/operators.md, "Plans").
    integer, parameter :: transposed_y_min = 2**21
    integer, parameter :: transposed_y_width = 16   !! columns per chunk (my·16 values)

    !> BTTB operator: y = A x for one influence block (or preconditioner) on one grid.
    type, public :: fc_bttb
        integer :: nx = 0, ny = 0          !! grid size
        integer :: mx = 0, my = 0          !! circulant (embedding) size
        logical :: periodic = .false.      !! periodic convolution on the grid itself
        !> coefficients A(dix, diy), dix ∈ [−(nx−1), nx−1] at least [mm/(N/mm²)] (an operator
        !! built by [[build_bttb_taking_kernel]] keeps the caller's array, which may reach
        !! ±nx); not kept by the preconditioners the solvers build with keep_kernel = .false.
        real(dp), allocatable :: kernel(:, :)
        integer :: parity = SYMBOL_GENERAL       !! SYMBOL_EVEN, SYMBOL_ODD or SYMBOL_GENERAL
        real(dp), allocatable :: rsymbol(:, :)   !! even: symbol; odd: its imaginary part (scaled by 1/(mx·my))
        complex(dp), allocatable :: csymbol(:, :) !! general kernels: r2c transform of the circulant / (mx·my)
        type(fc_fft_plans), pointer :: fft => null()  !! plans and buffers (possibly shared)
        integer :: nproducts = 0           !! number of products applied (work counter)
    contains
        procedure :: apply => bttb_apply
        procedure :: apply_direct => bttb_apply_direct
        procedure :: forward => bttb_forward
        procedure :: backward => bttb_backward
        procedure :: multiply => bttb_multiply
        procedure :: destroy => bttb_destroy
        procedure :: built => bttb_built
        procedure :: shares_plans => bttb_shares_plans
        procedure :: lanes_on => bttb_lanes_on
        procedure :: storage_bytes => bttb_storage_bytes
        procedure :: chunked_y => bttb_chunked_y
        procedure, private :: bttb_assign
        generic :: assignment(=) => bttb_assign
        final :: bttb_final
    end type fc_bttb

    public :: build_bttb_from_kernel, build_bttb_taking_kernel, build_bttb_periodic, inverse_toeplitz_from_kernel
    public :: kernel_of_real_symbol
    public :: fft_symbol_of_kernel, even_circulant_symbol
    public :: strang_circulant, strang_circulant_of_symbol
    public :: copy_bttb, spectrum_pair_product, block_symbol_product_in_place, block_product

contains

    ! ---- construction -----------------------------------------------------------------------

    !> Build a (non-periodic) BTTB operator from explicit coefficients
    !! kernel(−(nx−1):nx−1, −(ny−1):ny−1); used for influence blocks and preconditioners.
    !! With `plans_from` (a built operator of the same grid) the FFT plans and buffers are
    !! shared with it instead of created.
    subroutine build_bttb_from_kernel(op, kernel, nx, ny, plans_from)
        type(fc_bttb), intent(inout) :: op
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: kernel(-(nx - 1):, -(ny - 1):)
        type(fc_bttb), intent(in), optional :: plans_from
        integer :: mx, my
        mx = circulant_size(nx); my = circulant_size(ny)
        call setup_plans(op, nx, ny, mx, my, plans_from)
        call load_kernel(op, kernel)
        call finish_symbol(op)
    end subroutine build_bttb_from_kernel

    !> As [[build_bttb_from_kernel]], taking the caller's coefficients instead of copying
    !! them: `kernel` (offsets −(nx−1)…nx−1 at least, with its own bounds, e.g. the
    !! −nx…nx of [[ic_kernels_uncoupled]] that the preconditioners need too) becomes the
    !! operator's `kernel` and is deallocated on return.
    subroutine build_bttb_taking_kernel(op, kernel, nx, ny, plans_from)
        type(fc_bttb), intent(inout) :: op
        integer, intent(in) :: nx, ny
        real(dp), allocatable, intent(inout) :: kernel(:, :)
        type(fc_bttb), intent(in), optional :: plans_from
        call setup_plans(op, nx, ny, circulant_size(nx), circulant_size(ny), plans_from)
        call place_kernel(op, kernel)
        call move_alloc(kernel, op%kernel)
        call finish_symbol(op)
    end subroutine build_bttb_taking_kernel

    !> Build a periodic operator on the grid itself from the wrapped coefficients
    !! kernel(0:nx−1, 0:ny−1) (offsets taken modulo the grid).  With `grid` = [gx, gy] smaller
    !! than the kernel's period, the operator acts on a gx×gy grid as the circulant of that
    !! period restricted to it (data zero-padded to the period, the result read on the grid):
    !! the preconditioners' Strang circulants on a grid whose size FFTW transforms slowly.
    subroutine build_bttb_periodic(op, kernel, plans_from, keep_kernel, grid)
        type(fc_bttb), intent(inout) :: op
        real(dp), intent(in) :: kernel(0:, 0:)
        type(fc_bttb), intent(in), optional :: plans_from
        logical, intent(in), optional :: keep_kernel   !! see [[drop_kernel]] (default .true.)
        integer, intent(in), optional :: grid(2)
        integer :: nx, ny, gx, gy
        nx = size(kernel, 1); ny = size(kernel, 2)
        gx = nx; gy = ny
        if (present(grid)) then
            gx = grid(1); gy = grid(2)
        end if
        call setup_plans(op, gx, gy, nx, ny, plans_from)
        op%periodic = .true.
        allocate (op%kernel(0:nx - 1, 0:ny - 1), source=kernel)
        op%fft%rbuf = kernel
        call finish_symbol(op)
        call drop_kernel(op, keep_kernel)
    end subroutine build_bttb_periodic

    !> With `keep_kernel = .false.`, release the coefficients of an operator whose symbol is
    !! real (even): only the oracle [[bttb_apply_direct]] reads them, and for the
    !! preconditioners on large grids they are the largest array of all (the Toeplitz
    !! inverse's (2nx−1)·(2ny−1) values: 33 MB at 1024²).  Kept otherwise.
    subroutine drop_kernel(op, keep_kernel)
        type(fc_bttb), intent(inout) :: op
        logical, intent(in), optional :: keep_kernel
        if (.not. present(keep_kernel)) return
        if (.not. keep_kernel .and. op%parity == SYMBOL_EVEN .and. allocated(op%kernel)) deallocate (op%kernel)
    end subroutine drop_kernel

    !> Toeplitz approximation M ≈ A⁻¹ from A's coefficients kext(−nx:nx, −ny:ny) (thesis
    !! §3.3.1, extended to 2D).  The coefficients for offsets −nx+1…nx (and likewise in y)
    !! fill a 2nx×2ny circulant — the wrap-around slot holds the true coefficient at offset
    !! nx, which keeps the circulant positive definite — whose symbol is inverted
    !! pointwise; the central (2nx−1)×(2ny−1) coefficients of the inverse form M's kernel.
    !! M on the grid is a principal block of that positive definite circulant, hence
    !! symmetric positive definite; symbol values are floored at 1e−8 of the maximum.  M's
    !! products run on circulant_size like A's (2n or the next size FFTW transforms fast).
    !! (The 1D strip solver keeps the thesis' (2n−1)-circulant, [[strip_toeplitz_inverse]].)
    subroutine inverse_toeplitz_from_kernel(kext, nx, ny, prec, min_symbol, plans_from, keep_kernel)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: kext(-nx:nx, -ny:ny)
        type(fc_bttb), intent(inout) :: prec
        real(dp), intent(out), optional :: min_symbol  !! smallest symbol value / largest (diagnostic)
        logical, intent(in), optional :: keep_kernel   !! see [[drop_kernel]] (default .true.)
        type(fc_bttb), intent(in), optional :: plans_from
        real(dp), allocatable :: mker(:, :)
        real(dp) :: smax
        integer :: mx, my, j, jw
        type(fc_fft_plans), pointer :: w2n
        logical :: own
        mx = 2*nx; if (nx == 1) mx = 1
        my = 2*ny; if (ny == 1) my = 1
        call setup_plans(prec, nx, ny, circulant_size(nx), circulant_size(ny), plans_from)
        ! M is defined on the 2nx×2ny circulant; the products run on circulant_size, which is
        ! the same size unless FFTW transforms 2n slowly: then a set of plans of its own
        call doubled_circulant_plans(nx, ny, prec%fft, w2n, own)
        call fill_doubled_circulant(w2n, kext, nx, ny, odd_odd=.false.)
        associate (w => w2n)
            call full_forward(w)
            smax = maxval(real(w%cbuf, dp))
            if (present(min_symbol)) min_symbol = minval(real(w%cbuf, dp))/smax
            w%cbuf = 1/cmplx(max(real(w%cbuf, dp), 1.0e-8_dp*smax), 0.0_dp, dp)/real(mx*my, dp)
            call full_backward(w)
            allocate (mker(-(nx - 1):nx - 1, -(ny - 1):ny - 1))
            do j = -(ny - 1), ny - 1
                jw = j + 1; if (j < 0) jw = j + my + 1      ! modulo(j, my) + 1
                mker(0:nx - 1, j) = w%rbuf(1:nx, jw)
                mker(-(nx - 1):-1, j) = w%rbuf(mx - nx + 2:mx, jw)
            end do
        end associate
        call release_doubled_circulant_plans(w2n, own)
        call load_kernel(prec, mker)
        call finish_symbol(prec)
        call drop_kernel(prec, keep_kernel)
    end subroutine inverse_toeplitz_from_kernel

    !> Strang's circulant of a Toeplitz operator: the periodic operator on the nx×ny grid
    !! itself whose coefficients are those of `kernel` for the offsets −n/2…n/2, wrapped (the
    !! offsets ±n/2 of an even n share one slot and get the mean of the two, so that even and
    !! odd kernels stay even and odd).  A product with it costs about a quarter of one on the
    !! doubled grid.  For the FFT preconditioners M ≈ A⁻¹, whose coefficients decay much
    !! faster than A's, it preconditions nearly as well as M itself (doc/solvers.md,
    !! "Preconditioner form").  `kernel` must cover the offsets ±⌊n/2⌋.
    subroutine strang_circulant(kernel, nx, ny, circ, plans_from, keep_kernel)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: kernel(-(nx - 1):, -(ny - 1):)
        type(fc_bttb), intent(inout) :: circ
        type(fc_bttb), intent(in), optional :: plans_from   !! a periodic operator of this grid
        logical, intent(in), optional :: keep_kernel        !! see [[drop_kernel]] (default .true.)
        real(dp), allocatable :: wrapped(:, :)
        integer :: px, py
        call strang_period(nx, ny, px, py)
        allocate (wrapped(0:px - 1, 0:py - 1))
        call wrap_strang(kernel(-(px/2):px/2, -(py/2):py/2), px, py, wrapped)
        call build_bttb_periodic(circ, wrapped, plans_from, keep_kernel, grid=[nx, ny])
    end subroutine strang_circulant

    !> The coefficients kern(0:mx−1, 0:my−1) of the periodic operator on `op`'s period whose
    !! symbol, scaled as `op`'s (1/(mx·my) included), is the real `rsymbol`: one inverse
    !! transform on `op`'s plans and buffers (which must not be in use), the two rounded
    !! values of each pair ±offset averaged, so that the result is exactly point-symmetric
    !! (its symbol real again).  Used for exact inverses of periodic operators.
    subroutine kernel_of_real_symbol(op, rsymbol, kern)
        type(fc_bttb), intent(inout) :: op
        real(dp), intent(in) :: rsymbol(:, :)
        real(dp), intent(out) :: kern(0:, 0:)
        integer :: i, j
        associate (w => op%fft)
            w%cbuf = cmplx(rsymbol, 0.0_dp, dp)
            call full_backward(w)
            do j = 0, op%my - 1
                do i = 0, op%mx - 1
                    kern(i, j) = 0.5_dp*(w%rbuf(i + 1, j + 1) + w%rbuf(modulo(-i, op%mx) + 1, modulo(-j, op%my) + 1))
                end do
            end do
        end associate
    end subroutine kernel_of_real_symbol

    !> Period of the Strang circulants on an nx×ny grid: the grid itself, or in a direction
    !! whose size FFTW transforms slowly (a large prime factor) the next size it transforms
    !! fast (fc_fftw's friendly_size), as long as the coefficients reach half of it.
    pure subroutine strang_period(nx, ny, px, py)
        integer, intent(in) :: nx, ny
        integer, intent(out) :: px, py
        px = friendly_size(nx); if (px > 2*nx - 2) px = nx
        py = friendly_size(ny); if (py > 2*ny - 2) py = ny
    end subroutine strang_period

    !> Strang's circulant ([[strang_circulant]]) of the operator whose symbol on `op`'s doubled
    !! grid, scaled as `op`'s (1/(mx·my) included), is the real `rsymbol` — an even circulant
    !! known by its symbol only, such as TangCG's block preconditioner.  The coefficients come
    !! from one inverse transform on `op`'s plans and buffers (which must not be in use); the
    !! two rounded values of each pair ±offset are averaged, so the result is exactly even.
    subroutine strang_circulant_of_symbol(op, rsymbol, circ, plans_from, keep_kernel)
        type(fc_bttb), intent(inout) :: op
        real(dp), intent(in) :: rsymbol(:, :)
        type(fc_bttb), intent(inout) :: circ
        type(fc_bttb), intent(in), optional :: plans_from   !! a periodic operator of this grid
        logical, intent(in), optional :: keep_kernel        !! see [[drop_kernel]] (default .true.)
        real(dp), allocatable :: k(:, :), wrapped(:, :)
        integer :: nx, ny, hx, hy, i, j, px, py
        nx = op%nx; ny = op%ny
        call strang_period(nx, ny, px, py)
        hx = px/2; hy = py/2
        allocate (k(-hx:hx, -hy:hy), wrapped(0:px - 1, 0:py - 1))
        associate (w => op%fft)
            w%cbuf = cmplx(rsymbol, 0.0_dp, dp)
            call full_backward(w)
            do j = -hy, hy
                do i = -hx, hx
                    k(i, j) = 0.5_dp*(w%rbuf(at(i, op%mx), at(j, op%my)) + w%rbuf(at(-i, op%mx), at(-j, op%my)))
                end do
            end do
        end associate
        call wrap_strang(k, px, py, wrapped)
        call build_bttb_periodic(circ, wrapped, plans_from, keep_kernel, grid=[nx, ny])
    contains
        !> Index of offset k in a period m (offset k sits at modulo(k, m) + 1).
        pure integer function at(k, m)
            integer, intent(in) :: k, m
            at = k + 1
            if (k < 0) at = k + m + 1
        end function at
    end subroutine strang_circulant_of_symbol

    !> w(i, j), slots 0…n−1 of the period, ← k at the offset of each slot in (−n/2, n/2]; the
    !! slot n/2 of an even n takes the mean of the offsets ±n/2 (of four at a corner).
    pure subroutine wrap_strang(k, nx, ny, w)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: k(-(nx/2):, -(ny/2):)
        real(dp), intent(out) :: w(0:, 0:)
        integer :: i, j, hx, hy
        logical :: evx, evy
        hx = nx/2; hy = ny/2
        evx = mod(nx, 2) == 0; evy = mod(ny, 2) == 0
        do j = 0, ny - 1
            do i = 0, nx - 1
                w(i, j) = k(off(i, nx), off(j, ny))
            end do
        end do
        if (evx) then
            do j = 0, ny - 1
                w(hx, j) = 0.5_dp*(k(hx, off(j, ny)) + k(-hx, off(j, ny)))
            end do
        end if
        if (evy) then
            do i = 0, nx - 1
                w(i, hy) = 0.5_dp*(k(off(i, nx), hy) + k(off(i, nx), -hy))
            end do
        end if
        if (evx .and. evy) w(hx, hy) = 0.25_dp*(k(hx, hy) + k(-hx, hy) + k(hx, -hy) + k(-hx, -hy))
    contains
        pure integer function off(s, n)
            integer, intent(in) :: s, n
            off = s
            if (2*s > n) off = s - n
        end function off
    end subroutine wrap_strang


    !> Release `op` and give it plans: shared with `plans_from` when that operator is built
    !! for the same sizes, else a new set.
    subroutine setup_plans(op, nx, ny, mx, my, plans_from)
        type(fc_bttb), intent(inout) :: op
        integer, intent(in) :: nx, ny, mx, my
        type(fc_bttb), intent(in), optional :: plans_from
        call op%destroy()
        op%nx = nx; op%ny = ny; op%mx = mx; op%my = my
        op%periodic = .false.
        if (present(plans_from)) then
            if (associated(plans_from%fft)) then
                if (plans_from%fft%nx == nx .and. plans_from%fft%ny == ny .and. plans_from%fft%mx == mx &
                    .and. plans_from%fft%my == my) then
                    op%fft => plans_from%fft
                    op%fft%refs = op%fft%refs + 1
                    return
                end if
            end if
        end if
        allocate (op%fft)
        !$omp critical (fc_fftw_planner)
        call plans_create(op%fft, nx, ny, mx, my)
        !$omp end critical (fc_fftw_planner)
    end subroutine setup_plans

    !> Create FFTW plans (FFTW_ESTIMATE: no measurement, deterministic) on new buffers: the
    !! passes of the products and, unless `products_only`, of whole-array transforms.
    subroutine plans_create(w, nx, ny, mx, my, products_only)
        type(fc_fft_plans), intent(inout) :: w
        integer, intent(in) :: nx, ny, mx, my
        logical, intent(in), optional :: products_only   !! only the plans of products (lanes)
        integer :: mxh
        logical :: whole
        w%nx = nx; w%ny = ny; w%mx = mx; w%my = my
        w%planner_threads = fftw_planner_threads()
        whole = my > ny
        if (present(products_only)) whole = whole .and. .not. products_only
        mxh = mx/2 + 1
        allocate (w%rbuf(mx, my), w%cbuf(mxh, my))
        ! FFTW's row-major dimensions are the reverse of Fortran's: x is the contiguous one.
        w%plan_x_fwd = x_pass_r2c(ny)
        w%plan_y_fwd = y_pass(FFTW_FORWARD)
        w%plan_y_bwd = y_pass(FFTW_BACKWARD)
        w%plan_x_bwd = x_pass_c2r(ny)
        if (whole) then
            w%plan_xf_fwd = x_pass_r2c(my)
            w%plan_xf_bwd = x_pass_c2r(my)
        end if
        if (int(mxh, i8)*my >= transposed_y_min .and. my > 1) call chunk_plans()
        w%refs = 1
    contains
        type(c_ptr) function x_pass_r2c(columns) result(plan)
            integer, intent(in) :: columns
            plan = fftw_plan_many_dft_r2c(1_c_int, [int(mx, c_int)], int(columns, c_int), w%rbuf, [int(mx, c_int)], &
                1_c_int, int(mx, c_int), w%cbuf, [int(mxh, c_int)], 1_c_int, int(mxh, c_int), FFTW_ESTIMATE)
        end function x_pass_r2c
        type(c_ptr) function x_pass_c2r(columns) result(plan)
            integer, intent(in) :: columns
            plan = fftw_plan_many_dft_c2r(1_c_int, [int(mx, c_int)], int(columns, c_int), w%cbuf, [int(mxh, c_int)], &
                1_c_int, int(mxh, c_int), w%rbuf, [int(mx, c_int)], 1_c_int, int(mx, c_int), FFTW_ESTIMATE)
        end function x_pass_c2r
        type(c_ptr) function y_pass(sign) result(plan)
            integer(c_int), intent(in) :: sign
            plan = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), w%cbuf, [int(my, c_int)], &
                int(mxh, c_int), 1_c_int, w%cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, sign, FFTW_ESTIMATE)
        end function y_pass
        !> Single-threaded plans of `tw` contiguous columns (the chunks run on threads of
        !! their own) and one buffer per thread.
        subroutine chunk_plans()
            integer :: saved
            w%tw = transposed_y_width
            w%tthreads = 1
            !$ w%tthreads = max(1, omp_get_max_threads())
            allocate (w%tbuf(my, w%tw, w%tthreads))
            saved = 0
            call fftw_threads_for_size(1, saved)
            w%plan_yt_fwd = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(w%tw, c_int), w%tbuf, [int(my, c_int)], &
                1_c_int, int(my, c_int), w%tbuf, [int(my, c_int)], 1_c_int, int(my, c_int), FFTW_FORWARD, FFTW_ESTIMATE)
            w%plan_yt_bwd = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(w%tw, c_int), w%tbuf, [int(my, c_int)], &
                1_c_int, int(my, c_int), w%tbuf, [int(my, c_int)], 1_c_int, int(my, c_int), FFTW_BACKWARD, FFTW_ESTIMATE)
            call fftw_threads_for_size(-1, saved)
        end subroutine chunk_plans
    end subroutine plans_create

    !> The y pass of a product or transform, in place on the spectrum c (mxh × my): complex
    !! transforms of length my along y, forward or backward, reading rows 1…rows_in of c (the
    !! rows beyond taken as zero) and writing rows 1…rows_out.  Small spectra run the
    !! strided plan over all rows (the caller has zeroed rows beyond rows_in); large ones
    !! ([[fc_toeplitz:transposed_y_min]]) copy chunks of `tw` columns transposed into contiguous
    !! buffers, transform them there and copy back the rows needed.
    !! With `slot`, the chunks run one after the other on the calling thread through buffer
    !! `slot` (the lanes of [[block_product]], one slot each).
    subroutine y_pass(w, c, forward, rows_in, rows_out, slot)
        type(fc_fft_plans), intent(inout) :: w
        complex(dp), intent(inout), contiguous :: c(:, :)
        logical, intent(in) :: forward
        integer, intent(in) :: rows_in, rows_out
        integer, intent(in), optional :: slot
        integer :: k, nb, tid
        type(c_ptr) :: plan
        if (w%tw == 0) then
            if (forward) then
                call fftw_execute_dft(w%plan_y_fwd, c, c)
            else
                call fftw_execute_dft(w%plan_y_bwd, c, c)
            end if
            return
        end if
        plan = w%plan_yt_fwd
        if (.not. forward) plan = w%plan_yt_bwd
        nb = (size(c, 1) + w%tw - 1)/w%tw
        if (present(slot)) then
            do k = 1, nb
                call y_chunk(plan, c, w%tbuf(:, :, min(slot, w%tthreads)), (k - 1)*w%tw + 1, min(size(c, 1), k*w%tw), &
                    rows_in, rows_out)
            end do
            return
        end if
        !$omp parallel do default(shared) private(tid) schedule(static) num_threads(w%tthreads)
        do k = 1, nb
            tid = 1
            !$ tid = omp_get_thread_num() + 1
            call y_chunk(plan, c, w%tbuf(:, :, tid), (k - 1)*w%tw + 1, min(size(c, 1), k*w%tw), rows_in, rows_out)
        end do
        !$omp end parallel do
    end subroutine y_pass

    !> One chunk of [[y_pass]]: columns ib…ie of c through the buffer b (my × tw).
    subroutine y_chunk(plan, c, b, ib, ie, rows_in, rows_out)
        type(c_ptr), intent(in) :: plan
        complex(dp), intent(inout) :: c(:, :)
        complex(dp), intent(inout), contiguous :: b(:, :)
        integer, intent(in) :: ib, ie, rows_in, rows_out
        integer :: i, j
        do j = 1, rows_in
            do i = ib, ie
                b(j, i - ib + 1) = c(i, j)
            end do
        end do
        b(rows_in + 1:, 1:ie - ib + 1) = 0
        if (ie - ib + 1 < size(b, 2)) b(:, ie - ib + 2:) = 0   ! the last chunk's unused columns
        call fftw_execute_dft(plan, b, b)
        do j = 1, rows_out
            do i = ib, ie
                c(i, j) = b(j, i - ib + 1)
            end do
        end do
    end subroutine y_chunk

    !> cbuf ← the 2D FFT of the whole real buffer (rbuf is kept).
    subroutine full_forward(w)
        type(fc_fft_plans), intent(inout) :: w
        if (c_associated(w%plan_xf_fwd)) then
            call fftw_execute_dft_r2c(w%plan_xf_fwd, w%rbuf, w%cbuf)
        else
            call fftw_execute_dft_r2c(w%plan_x_fwd, w%rbuf, w%cbuf)
        end if
        call y_pass(w, w%cbuf, .true., w%my, w%my)
    end subroutine full_forward

    !> rbuf ← the unnormalised 2D inverse FFT of cbuf (cbuf is destroyed).
    subroutine full_backward(w)
        type(fc_fft_plans), intent(inout) :: w
        call y_pass(w, w%cbuf, .false., w%my, w%my)
        if (c_associated(w%plan_xf_bwd)) then
            call fftw_execute_dft_c2r(w%plan_xf_bwd, w%cbuf, w%rbuf)
        else
            call fftw_execute_dft_c2r(w%plan_x_bwd, w%cbuf, w%rbuf)
        end if
    end subroutine full_backward

    !> Destroy the plans and free the buffers.
    recursive subroutine plans_free(w)
        type(fc_fft_plans), intent(inout) :: w
        if (c_associated(w%plan_xf_fwd)) call fftw_destroy_plan(w%plan_xf_fwd)
        if (c_associated(w%plan_xf_bwd)) call fftw_destroy_plan(w%plan_xf_bwd)
        if (c_associated(w%plan_x_fwd)) call fftw_destroy_plan(w%plan_x_fwd)
        if (c_associated(w%plan_y_fwd)) call fftw_destroy_plan(w%plan_y_fwd)
        if (c_associated(w%plan_y_bwd)) call fftw_destroy_plan(w%plan_y_bwd)
        if (c_associated(w%plan_x_bwd)) call fftw_destroy_plan(w%plan_x_bwd)
        if (c_associated(w%plan_yt_fwd)) call fftw_destroy_plan(w%plan_yt_fwd)
        if (c_associated(w%plan_yt_bwd)) call fftw_destroy_plan(w%plan_yt_bwd)
        w%plan_yt_fwd = c_null_ptr; w%plan_yt_bwd = c_null_ptr; w%tw = 0
        if (allocated(w%tbuf)) deallocate (w%tbuf)
        w%plan_xf_fwd = c_null_ptr; w%plan_xf_bwd = c_null_ptr
        w%plan_x_fwd = c_null_ptr; w%plan_y_fwd = c_null_ptr
        w%plan_y_bwd = c_null_ptr; w%plan_x_bwd = c_null_ptr
        if (allocated(w%rbuf)) deallocate (w%rbuf)
        if (allocated(w%cbuf)) deallocate (w%cbuf)
        if (associated(w%serial)) then
            call plans_free(w%serial)
            deallocate (w%serial)
        end if
        if (allocated(w%rbuf2)) deallocate (w%rbuf2)
        w%lanes_state = LANES_NONE
        w%refs = 0
    end subroutine plans_free

    !> Store the coefficients and place them in the circulant (the plan set's real buffer).
    subroutine load_kernel(op, kernel)
        type(fc_bttb), intent(inout) :: op
        real(dp), intent(in) :: kernel(-(op%nx - 1):, -(op%ny - 1):)
        allocate (op%kernel(-(op%nx - 1):op%nx - 1, -(op%ny - 1):op%ny - 1), source=kernel)
        call place_kernel(op, op%kernel)
    end subroutine load_kernel

    !> Place the coefficients for offsets −(n−1)…n−1 of `kernel` (indexed by offset; its
    !! bounds may be wider) in the circulant, the plan set's real buffer.
    subroutine place_kernel(op, kernel)
        type(fc_bttb), intent(inout) :: op
        real(dp), allocatable, intent(in) :: kernel(:, :)   ! allocatable: keeps the bounds
        integer :: j, jw
        op%fft%rbuf = 0
        associate (nx => op%nx, mx => op%mx, rbuf => op%fft%rbuf)
            do j = -(op%ny - 1), op%ny - 1
                jw = j + 1; if (j < 0) jw = j + op%my + 1   ! offset k sits at modulo(k, m) + 1
                rbuf(1:nx, jw) = kernel(0:nx - 1, j)
                rbuf(mx - nx + 2:mx, jw) = kernel(-(nx - 1):-1, j)
            end do
        end associate
    end subroutine place_kernel

    !> Transform the circulant in the real buffer into the scaled symbol, stored as real
    !! numbers when the circulant is even or odd.
    subroutine finish_symbol(op)
        type(fc_bttb), intent(inout) :: op
        real(dp) :: scale
        op%parity = circulant_parity(op%fft%rbuf)
        call full_forward(op%fft)
        scale = real(op%mx*op%my, dp)
        select case (op%parity)
        case (SYMBOL_EVEN)
            allocate (op%rsymbol, source=real(op%fft%cbuf, dp)/scale)
        case (SYMBOL_ODD)
            allocate (op%rsymbol, source=aimag(op%fft%cbuf)/scale)
        case default
            allocate (op%csymbol, source=op%fft%cbuf/scale)
        end select
        op%nproducts = 0
    end subroutine finish_symbol

    !> SYMBOL_EVEN when c(−i,−j) = c(i,j) (indices modulo the circulant), SYMBOL_ODD when
    !! c(−i,−j) = −c(i,j), both to 1e−13 of max|c| (rounding of the coefficient sums);
    !! else SYMBOL_GENERAL.  The symbol of an even (odd) real circulant is real (imaginary).
    pure integer function circulant_parity(c) result(parity)
        real(dp), intent(in) :: c(:, :)
        integer :: mx, my, i, j, jr
        real(dp) :: tol
        logical :: even, odd
        mx = size(c, 1); my = size(c, 2)
        tol = 1.0e-13_dp*maxval(abs(c))
        even = .true.; odd = .true.
        ! the partner of index k is modulo(1 − k, m) + 1: 1 for k = 1, else m + 2 − k.  Each
        ! pair of columns (j, jr) once, element i against mx + 2 − i; stop as soon as
        ! neither symmetry holds (each test a plain comparison, so the loops vectorise)
        do j = 1, my/2 + 1
            jr = 1
            if (j > 1) jr = my + 2 - j
            if (even) even = abs(c(1, j) - c(1, jr)) <= tol
            if (odd) odd = abs(c(1, j) + c(1, jr)) <= tol
            if (even) then
                do i = 2, mx
                    if (abs(c(i, j) - c(mx + 2 - i, jr)) > tol) then
                        even = .false.; exit
                    end if
                end do
            end if
            if (odd) then
                do i = 2, mx
                    if (abs(c(i, j) + c(mx + 2 - i, jr)) > tol) then
                        odd = .false.; exit
                    end if
                end do
            end if
            if (.not. (even .or. odd)) exit
        end do
        if (even) then
            parity = SYMBOL_EVEN
        else if (odd) then
            parity = SYMBOL_ODD
        else
            parity = SYMBOL_GENERAL
        end if
    end function circulant_parity

    !> Symbol (unscaled r2c transform of the circulant) as complex numbers; used by
    !! preconditioner construction (thesis §3.3.1).
    subroutine fft_symbol_of_kernel(op, symbol)
        type(fc_bttb), intent(in) :: op
        complex(dp), allocatable, intent(out) :: symbol(:, :)
        real(dp) :: scale
        scale = real(op%mx*op%my, dp)
        select case (op%parity)
        case (SYMBOL_EVEN)
            allocate (symbol, source=cmplx(op%rsymbol*scale, 0.0_dp, dp))
        case (SYMBOL_ODD)
            allocate (symbol, source=cmplx(0.0_dp, op%rsymbol*scale, dp))
        case default
            allocate (symbol, source=op%csymbol*scale)
        end select
    end subroutine fft_symbol_of_kernel

    !> Symbol (unscaled transform) of the 2nx×2ny circulant (nx = 1: 1 in x; likewise in y)
    !! of the coefficients kext(−nx:nx, −ny:ny) of a kernel even in x and y, or odd in both
    !! (`odd_odd`): the circulant is even and its symbol real.  The wrap-around slot
    !! (offset ±n) holds the coefficient at offset n (even) or 0 (odd in both), which keeps
    !! the circulant symmetric: the construction of TangCG's block preconditioner
    !! (fc_tangprec).  The transforms run on the plans and buffers of `plans_from` when they
    !! are made for that circulant (the usual case, fc_fftw's circulant_size = 2n), else on
    !! a set of their own.
    subroutine even_circulant_symbol(kext, nx, ny, odd_odd, symbol, plans_from)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: kext(-nx:nx, -ny:ny)
        logical, intent(in) :: odd_odd
        real(dp), intent(out) :: symbol(:, :)   !! (mx/2 + 1, my)
        type(fc_bttb), intent(in), optional :: plans_from
        type(fc_fft_plans), pointer :: cand, w
        logical :: own
        cand => null()
        if (present(plans_from)) cand => plans_from%fft
        call doubled_circulant_plans(nx, ny, cand, w, own)
        call fill_doubled_circulant(w, kext, nx, ny, odd_odd)
        call full_forward(w)
        symbol = real(w%cbuf, dp)
        call release_doubled_circulant_plans(w, own)
    end subroutine even_circulant_symbol

    !> The plan set for whole-array transforms of the 2nx×2ny circulant (1 in a direction of
    !! one element): `cand` when it is made for that size, else a new set (`own`).
    subroutine doubled_circulant_plans(nx, ny, cand, w, own)
        integer, intent(in) :: nx, ny
        type(fc_fft_plans), pointer, intent(in) :: cand
        type(fc_fft_plans), pointer, intent(out) :: w
        logical, intent(out) :: own
        integer :: mx, my
        mx = 2*nx; if (nx == 1) mx = 1
        my = 2*ny; if (ny == 1) my = 1
        own = .true.
        if (associated(cand)) own = .not. (cand%nx == nx .and. cand%ny == ny .and. cand%mx == mx .and. cand%my == my)
        if (own) then
            allocate (w)
            !$omp critical (fc_fftw_planner)
            call plans_create(w, nx, ny, mx, my)
            !$omp end critical (fc_fftw_planner)
        else
            w => cand
        end if
    end subroutine doubled_circulant_plans

    !> Free a set [[doubled_circulant_plans]] made (`own`); a borrowed one stays.
    subroutine release_doubled_circulant_plans(w, own)
        type(fc_fft_plans), pointer, intent(inout) :: w
        logical, intent(in) :: own
        if (.not. own) return
        !$omp critical (fc_fftw_planner)
        call plans_free(w)
        !$omp end critical (fc_fftw_planner)
        deallocate (w)
    end subroutine release_doubled_circulant_plans

    !> w's real buffer ← the 2nx×2ny circulant of kext(−n…n): offset d at modulo(d, m) + 1,
    !! the wrap-around slot (offset ±n) holding kext(n), or 0 with `odd_odd`.
    subroutine fill_doubled_circulant(w, kext, nx, ny, odd_odd)
        type(fc_fft_plans), intent(inout) :: w
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: kext(-nx:nx, -ny:ny)
        logical, intent(in) :: odd_odd
        integer :: mx, my, i, j, di, dj
        mx = w%mx; my = w%my
        do j = 0, my - 1
            dj = j; if (j > my/2) dj = j - my
            do i = 0, mx - 1
                di = i; if (i > mx/2) di = i - mx
                if (odd_odd .and. ((mx > 1 .and. i == mx/2) .or. (my > 1 .and. j == my/2))) then
                    w%rbuf(i + 1, j + 1) = 0
                else
                    w%rbuf(i + 1, j + 1) = kext(di, dj)
                end if
            end do
        end do
    end subroutine fill_doubled_circulant

    ! ---- copies and lifetime ----------------------------------------------------------------

    !> Deep copy: `dst` gets the coefficients and symbol of `src` and its own plans and
    !! buffers, or shares those of `plans_from` (a built operator of the same sizes).
    subroutine copy_bttb(dst, src, plans_from)
        type(fc_bttb), intent(inout) :: dst
        type(fc_bttb), intent(in) :: src
        type(fc_bttb), intent(in), optional :: plans_from
        if (.not. associated(src%fft)) then
            call dst%destroy()
        else
            call setup_plans(dst, src%nx, src%ny, src%mx, src%my, plans_from)
        end if
        dst%nx = src%nx; dst%ny = src%ny; dst%mx = src%mx; dst%my = src%my
        dst%periodic = src%periodic
        dst%parity = src%parity
        dst%nproducts = src%nproducts
        if (allocated(src%kernel)) allocate (dst%kernel, source=src%kernel)
        if (allocated(src%rsymbol)) allocate (dst%rsymbol, source=src%rsymbol)
        if (allocated(src%csymbol)) allocate (dst%csymbol, source=src%csymbol)
    end subroutine copy_bttb

    !> `lhs = rhs`: deep copy with the copy's own plans and buffers.
    subroutine bttb_assign(lhs, rhs)
        class(fc_bttb), intent(inout) :: lhs
        type(fc_bttb), intent(in) :: rhs
        if (same_storage(lhs, rhs)) return   ! `a = a` (destroying lhs first would destroy rhs)
        select type (lhs)
        type is (fc_bttb)
            call copy_bttb(lhs, rhs)
        end select
    end subroutine bttb_assign

    !> True when a and b are the same object (their coefficient arrays coincide).
    logical function same_storage(a, b)
        class(fc_bttb), intent(in), target :: a
        type(fc_bttb), intent(in), target :: b
        same_storage = .false.
        if (allocated(a%kernel) .and. allocated(b%kernel)) then
            same_storage = c_associated(c_loc(a%kernel), c_loc(b%kernel))
        else if (allocated(a%rsymbol) .and. allocated(b%rsymbol)) then
            same_storage = c_associated(c_loc(a%rsymbol), c_loc(b%rsymbol))
        else if (allocated(a%csymbol) .and. allocated(b%csymbol)) then
            same_storage = c_associated(c_loc(a%csymbol), c_loc(b%csymbol))
        end if
    end function same_storage

    !> Release plans (when no other block uses them) and buffers.
    subroutine bttb_destroy(self)
        class(fc_bttb), intent(inout) :: self
        if (associated(self%fft)) then
            self%fft%refs = self%fft%refs - 1
            if (self%fft%refs <= 0) then
                !$omp critical (fc_fftw_planner)
                call plans_free(self%fft)
                !$omp end critical (fc_fftw_planner)
                deallocate (self%fft)
            end if
            nullify (self%fft)
        end if
        if (allocated(self%kernel)) deallocate (self%kernel)
        if (allocated(self%rsymbol)) deallocate (self%rsymbol)
        if (allocated(self%csymbol)) deallocate (self%csymbol)
        self%nx = 0; self%ny = 0; self%mx = 0; self%my = 0
        self%parity = SYMBOL_GENERAL
    end subroutine bttb_destroy

    !> Final binding: an operator that goes out of scope or is deallocated releases its
    !! plans and buffers.
    impure elemental subroutine bttb_final(self)
        type(fc_bttb), intent(inout) :: self
        call bttb_destroy(self)
    end subroutine bttb_final

    !> True once the operator has been built.
    pure logical function bttb_built(self)
        class(fc_bttb), intent(in) :: self
        bttb_built = allocated(self%rsymbol) .or. allocated(self%csymbol)
    end function bttb_built

    !> True when `self` and `other` use the same plan set.
    logical function bttb_shares_plans(self, other)
        class(fc_bttb), intent(in) :: self
        type(fc_bttb), intent(in) :: other
        bttb_shares_plans = .false.
        if (associated(self%fft) .and. associated(other%fft)) bttb_shares_plans = associated(self%fft, other%fft)
    end function bttb_shares_plans

    !> Bytes held by this operator's coefficients and symbol, plus its plan set's buffers
    !! divided among the blocks sharing it.
    real(dp) function bttb_storage_bytes(self) result(bytes)
        class(fc_bttb), intent(in) :: self
        bytes = 0
        if (allocated(self%kernel)) bytes = bytes + 8.0_dp*size(self%kernel)
        if (allocated(self%rsymbol)) bytes = bytes + 8.0_dp*size(self%rsymbol)
        if (allocated(self%csymbol)) bytes = bytes + 16.0_dp*size(self%csymbol)
        if (associated(self%fft)) then
            if (self%fft%refs > 0) bytes = bytes + (8.0_dp*size(self%fft%rbuf) + 16.0_dp*size(self%fft%cbuf))/self%fft%refs
        end if
    end function bttb_storage_bytes

    ! ---- products ---------------------------------------------------------------------------

    !> y = A x by FFT (O(n log n)).  x, y are nx×ny arrays.
    subroutine bttb_apply(self, x, y)
        class(fc_bttb), intent(inout) :: self
        real(dp), intent(in) :: x(:, :)
        real(dp), intent(out) :: y(:, :)
        call transform_forward(self%fft, x)
        call multiply_in_place(self, self%fft%cbuf, conjugate=.true.)
        call transform_backward_from(self%fft, self%fft%cbuf, y, conjugated=.true.)
        self%nproducts = self%nproducts + 1
    end subroutine bttb_apply

    !> Spectrum of x (zero-padded to the circulant size): the first half of a product,
    !! so that several blocks can share one forward transform.
    !! The transform writes into `spectrum` directly when FFTW may use it in place of the
    !! plan set's buffer (same shape and alignment, [[fftw_compatible]]), else through the
    !! buffer and a copy; both give the same numbers.
    subroutine bttb_forward(self, x, spectrum)
        class(fc_bttb), intent(inout) :: self
        real(dp), intent(in) :: x(:, :)
        complex(dp), intent(out), contiguous, target :: spectrum(:, :)
        if (fftw_compatible(spectrum, self%fft%cbuf)) then
            call transform_forward_to(self%fft, x, spectrum)
        else
            call transform_forward(self%fft, x)
            call copy_spectrum(self%fft%cbuf, spectrum)
        end if
    end subroutine bttb_forward

    !> y = IFFT(spectrum) restricted to the grid (spectrum already multiplied by symbols).
    !! `spectrum` is scratch: the transform may run in it and destroy it (as [[bttb_forward]]).
    !! With `conjugated`, `spectrum` holds the conjugate of that spectrum (as
    !! [[spectrum_pair_product]] makes it on request): the cheaper inverse of
    !! [[transform_backward_from]].
    subroutine bttb_backward(self, spectrum, y, conjugated)
        class(fc_bttb), intent(inout) :: self
        complex(dp), intent(inout), contiguous, target :: spectrum(:, :)
        real(dp), intent(out) :: y(:, :)
        logical, intent(in), optional :: conjugated
        logical :: conj_in
        conj_in = .false.
        if (present(conjugated)) conj_in = conjugated
        if (fftw_compatible(spectrum, self%fft%cbuf)) then
            call transform_backward_from(self%fft, spectrum, y, conj_in)
        else
            call copy_spectrum(spectrum, self%fft%cbuf)
            call transform_backward_from(self%fft, self%fft%cbuf, y, conj_in)
        end if
        self%nproducts = self%nproducts + 1
    end subroutine bttb_backward

    !> Whether the block products on this operator's plan set run their two components side
    !! by side ([[block_product]]; set by the first such product).
    logical function bttb_lanes_on(self)
        class(fc_bttb), intent(in) :: self
        bttb_lanes_on = .false.
        if (associated(self%fft)) bttb_lanes_on = self%fft%lanes_state == LANES_ON
    end function bttb_lanes_on

    !> Whether FFTW may execute the plans made on `buf` on `a` instead: same shape and the
    !! same alignment as FFTW counts it (`fftw_alignment_of`: the address modulo the SIMD
    !! alignment of the library's build).
    logical function fftw_compatible(a, buf)
        complex(dp), intent(in), contiguous, target :: a(:, :)
        complex(dp), intent(in), contiguous, target :: buf(:, :)
        fftw_compatible = all(shape(a) == shape(buf))
        if (fftw_compatible) fftw_compatible = fc_fftw_alignment_of(c_loc(a)) == fc_fftw_alignment_of(c_loc(buf))
    end function fftw_compatible

    !> out = spectrum · symbol (`add`: out = out + spectrum · symbol).
    subroutine bttb_multiply(self, spectrum, out, add)
        class(fc_bttb), intent(in) :: self
        complex(dp), intent(in) :: spectrum(:, :)
        complex(dp), intent(inout) :: out(:, :)
        logical, intent(in), optional :: add
        logical :: acc
        integer :: i, j
        acc = .false.
        if (present(add)) acc = add
        ! column loops, threaded above omp_min_elements (the spectra have ~2·nx·ny entries)
        !$omp parallel do default(shared) private(i) schedule(static) if(size(out) > omp_min_elements)
        do j = 1, size(out, 2)
            select case (self%parity)
            case (SYMBOL_EVEN)
                if (acc) then
                    out(:, j) = out(:, j) + spectrum(:, j)*self%rsymbol(:, j)
                else
                    out(:, j) = spectrum(:, j)*self%rsymbol(:, j)
                end if
            case (SYMBOL_ODD)    ! (a + ib)·(i s) = −b s + i a s
                if (acc) then
                    do i = 1, size(out, 1)
                        out(i, j) = out(i, j) + cmplx(-aimag(spectrum(i, j))*self%rsymbol(i, j), &
                            real(spectrum(i, j), dp)*self%rsymbol(i, j), dp)
                    end do
                else
                    do i = 1, size(out, 1)
                        out(i, j) = cmplx(-aimag(spectrum(i, j))*self%rsymbol(i, j), &
                            real(spectrum(i, j), dp)*self%rsymbol(i, j), dp)
                    end do
                end if
            case default
                if (acc) then
                    out(:, j) = out(:, j) + spectrum(:, j)*self%csymbol(:, j)
                else
                    out(:, j) = spectrum(:, j)*self%csymbol(:, j)
                end if
            end select
        end do
        !$omp end parallel do
    end subroutine bttb_multiply

    !> c ← c · symbol.
    !! With `conjugate`, c = conj(c · symbol), for the mirrored inverse ([[transform_backward_from]]).
    subroutine multiply_in_place(self, c, conjugate)
        type(fc_bttb), intent(in) :: self
        complex(dp), intent(inout) :: c(:, :)
        logical, intent(in) :: conjugate
        integer :: i, j
        real(dp) :: sgn
        sgn = merge(-1.0_dp, 1.0_dp, conjugate)   ! sign of the imaginary part
        !$omp parallel do default(shared) private(i) schedule(static) if(size(c) > omp_min_elements)
        do j = 1, size(c, 2)
            select case (self%parity)
            case (SYMBOL_EVEN)
                if (conjugate) then
                    c(:, j) = conjg(c(:, j))*self%rsymbol(:, j)
                else
                    c(:, j) = c(:, j)*self%rsymbol(:, j)
                end if
            case (SYMBOL_ODD)
                do i = 1, size(c, 1)
                    c(i, j) = cmplx(-aimag(c(i, j))*self%rsymbol(i, j), sgn*real(c(i, j), dp)*self%rsymbol(i, j), dp)
                end do
            case default
                if (conjugate) then
                    c(:, j) = conjg(c(:, j)*self%csymbol(:, j))
                else
                    c(:, j) = c(:, j)*self%csymbol(:, j)
                end if
            end select
        end do
        !$omp end parallel do
    end subroutine multiply_in_place

    !> out = sa·A + sb·B for two blocks of one grid (one pass when both symbols are real);
    !! with `conjugate`, its conjugate (for [[bttb_backward]]'s `conjugated`).
    subroutine spectrum_pair_product(a, sa, b, sb, out, conjugate)
        type(fc_bttb), intent(in) :: a, b
        complex(dp), intent(in) :: sa(:, :), sb(:, :)
        complex(dp), intent(out) :: out(:, :)
        logical, intent(in), optional :: conjugate
        integer :: j
        logical :: conj_out, par
        conj_out = .false.
        if (present(conjugate)) conj_out = conjugate
        par = size(out) > omp_min_elements
        if (a%parity == SYMBOL_EVEN .and. b%parity == SYMBOL_EVEN) then
            if (conj_out) then
                !$omp parallel do default(shared) schedule(static) if(par)
                do j = 1, size(out, 2)
                    out(:, j) = conjg(sa(:, j))*a%rsymbol(:, j) + conjg(sb(:, j))*b%rsymbol(:, j)
                end do
                !$omp end parallel do
            else
                !$omp parallel do default(shared) schedule(static) if(par)
                do j = 1, size(out, 2)
                    out(:, j) = sa(:, j)*a%rsymbol(:, j) + sb(:, j)*b%rsymbol(:, j)
                end do
                !$omp end parallel do
            end if
        else
            call a%multiply(sa, out)
            call b%multiply(sb, out, add=.true.)
            if (conj_out) then
                !$omp parallel do default(shared) schedule(static) if(par)
                do j = 1, size(out, 2)
                    out(:, j) = conjg(out(:, j))
                end do
                !$omp end parallel do
            end if
        end if
    end subroutine spectrum_pair_product

    !> (sx, sy) ← [sxx sxy; sxy syy]·(sx, sy) frequency by frequency for a symmetric 2×2
    !! block of real symbols; with `conjugate`, the conjugates (for [[bttb_backward]]'s
    !! `conjugated`).  The two [[spectrum_pair_product]]s of a block product in one pass
    !! and without a third spectrum (the same operations, the same numbers).
    subroutine block_symbol_product_in_place(sx, sy, sxx, sxy, syy, conjugate)
        complex(dp), intent(inout) :: sx(:, :), sy(:, :)
        real(dp), intent(in) :: sxx(:, :), sxy(:, :), syy(:, :)
        logical, intent(in) :: conjugate
        complex(dp) :: a, b
        integer :: i, j
        logical :: par
        par = size(sx) > omp_min_elements
        if (conjugate) then
            !$omp parallel do default(shared) private(i, a, b) schedule(static) if(par)
            do j = 1, size(sx, 2)
                do i = 1, size(sx, 1)
                    a = conjg(sx(i, j)); b = conjg(sy(i, j))
                    sx(i, j) = a*sxx(i, j) + b*sxy(i, j)
                    sy(i, j) = a*sxy(i, j) + b*syy(i, j)
                end do
            end do
            !$omp end parallel do
        else
            !$omp parallel do default(shared) private(i, a, b) schedule(static) if(par)
            do j = 1, size(sx, 2)
                do i = 1, size(sx, 1)
                    a = sx(i, j); b = sy(i, j)
                    sx(i, j) = a*sxx(i, j) + b*sxy(i, j)
                    sy(i, j) = a*sxy(i, j) + b*syy(i, j)
                end do
            end do
            !$omp end parallel do
        end if
    end subroutine block_symbol_product_in_place

    !> (zx, zy) = [bxx bxy; bxy byy]·(dx, dy) for three blocks on bxx's plan set: two forward
    !! transforms into `sx`, `sy`, two symbol pairs into `w`, `w2`, two inverse transforms.
    !! With two or more OpenMP threads (outside a parallel region) and a grid of at least
    !! [[fc_threads:lanes_min_elements]] cells, the x and y components run side by side, each on one
    !! thread with single-threaded plans (the plan set's lanes): two transforms in parallel
    !! scale better than one threaded transform after the other, and on grids below
    !! [[fc_threads:fftw_thread_min_elements]], whose transforms are not threaded at all, they are the
    !! only parallelism of the product (doc/parallel.md §5.3).  `w2` is used only there,
    !! `w` only there or when a symbol is not real (else the symbols multiply the spectra
    !! in place, [[block_symbol_product_in_place]]).
    subroutine block_product(bxx, bxy, byy, sx, sy, w, w2, dx, dy, zx, zy)
        type(fc_bttb), intent(inout) :: bxx
        type(fc_bttb), intent(in) :: bxy, byy
        complex(dp), intent(inout), contiguous, target :: sx(:, :), sy(:, :), w(:, :), w2(:, :)
        real(dp), intent(in) :: dx(:, :), dy(:, :)
        real(dp), intent(out) :: zx(:, :), zy(:, :)
        integer :: tid, nt
        type(fc_fft_plans), pointer :: p
        if (use_lanes(bxx%fft, sx, sy, w, w2)) then
            p => bxx%fft
            if (associated(p%serial)) p => p%serial
            tid = 0; nt = 1
            !$omp parallel num_threads(2) default(shared) firstprivate(tid, nt)
            !$ tid = omp_get_thread_num()
            !$ nt = omp_get_num_threads()   ! 1 if the runtime grants one thread: both on it
            if (tid == 0) call lane_forward(p, p%rbuf, dx, sx, 1)
            if (tid == 1 .or. nt == 1) call lane_forward(p, bxx%fft%rbuf2, dy, sy, 2)
            !$omp barrier
            if (tid == 0) then
                call spectrum_pair_product(bxx, sx, bxy, sy, w, conjugate=.true.)
                call lane_backward(p, p%rbuf, w, zx, 1)
            end if
            if (tid == 1 .or. nt == 1) then
                call spectrum_pair_product(bxy, sx, byy, sy, w2, conjugate=.true.)
                call lane_backward(p, bxx%fft%rbuf2, w2, zy, 2)
            end if
            !$omp end parallel
            bxx%nproducts = bxx%nproducts + 2
        else if (bxx%parity == SYMBOL_EVEN .and. bxy%parity == SYMBOL_EVEN .and. byy%parity == SYMBOL_EVEN) then
            call bxx%forward(dx, sx)
            call bxx%forward(dy, sy)
            call block_symbol_product_in_place(sx, sy, bxx%rsymbol, bxy%rsymbol, byy%rsymbol, conjugate=.true.)
            call bxx%backward(sx, zx, conjugated=.true.)
            call bxx%backward(sy, zy, conjugated=.true.)
        else
            call bxx%forward(dx, sx)
            call bxx%forward(dy, sy)
            call spectrum_pair_product(bxx, sx, bxy, sy, w, conjugate=.true.)
            call bxx%backward(w, zx, conjugated=.true.)
            call spectrum_pair_product(bxy, sx, byy, sy, w, conjugate=.true.)
            call bxx%backward(w, zy, conjugated=.true.)
        end if
    end subroutine block_product

    !> Whether [[block_product]] runs its components side by side on `w`'s lanes (two
    !! threads or more, outside a parallel region, at least [[fc_threads:lanes_min_elements]] cells,
    !! spectra FFTW may use in place of the plans' buffer); makes the lanes on first use
    !! (inside the planner's critical section).
    logical function use_lanes(w, s1, s2, s3, s4)
        type(fc_fft_plans), intent(inout), target :: w
        complex(dp), intent(in), contiguous, target :: s1(:, :), s2(:, :), s3(:, :), s4(:, :)
        integer :: saved
        type(fc_fft_plans), pointer :: q
        use_lanes = .false.
        !$ use_lanes = omp_get_max_threads() >= 2 .and. .not. omp_in_parallel()
        if (.not. use_lanes) return
        use_lanes = w%nx*w%ny >= lanes_min_elements
        if (.not. use_lanes) return
        if (w%lanes_state == LANES_NONE) then
            !$omp critical (fc_fftw_planner)
            if (w%planner_threads > 1) then
                allocate (w%serial)
                saved = 0
                call fftw_threads_for_size(0, saved)       ! single-threaded plans
                call plans_create(w%serial, w%nx, w%ny, w%mx, w%my, products_only=.true.)
                call fftw_threads_for_size(-1, saved)
            end if
            !$omp end critical (fc_fftw_planner)
            allocate (w%rbuf2, mold=w%rbuf)
            w%lanes_state = LANES_ON
        end if
        use_lanes = w%lanes_state == LANES_ON
        if (.not. use_lanes) return
        q => w
        if (associated(w%serial)) q => w%serial
        use_lanes = fc_fftw_alignment_of(c_loc(w%rbuf2)) == fc_fftw_alignment_of(c_loc(q%rbuf)) .and. &
            fftw_compatible(s1, q%cbuf) .and. fftw_compatible(s2, q%cbuf) .and. &
            fftw_compatible(s3, q%cbuf) .and. fftw_compatible(s4, q%cbuf)
        ! chunked y passes need a buffer per lane (plans made on one thread have one)
        if (q%tw > 0) use_lanes = use_lanes .and. q%tthreads >= 2
    end function use_lanes

    !> s ← FFT of x zero-padded to mx×my by the single-threaded plans of `p` on the real
    !! buffer `rb` (p%rbuf or a buffer of the same alignment); nested loops stay serial.
    subroutine lane_forward(p, rb, x, s, slot)
        type(fc_fft_plans), intent(inout) :: p
        real(dp), intent(inout), contiguous :: rb(:, :)
        real(dp), intent(in) :: x(:, :)
        complex(dp), intent(inout), contiguous :: s(:, :)
        integer, intent(in) :: slot   !! the lane's chunk buffer (large grids)
        integer :: j
        do j = 1, p%ny
            rb(1:p%nx, j) = x(:, j)
            if (p%mx > p%nx) rb(p%nx + 1:, j) = 0
        end do
        call fftw_execute_dft_r2c(p%plan_x_fwd, rb, s)
        if (p%tw == 0) then
            do j = p%ny + 1, p%my
                s(:, j) = 0
            end do
        end if
        call y_pass(p, s, .true., p%ny, p%my, slot)
    end subroutine lane_forward

    !> y ← inverse FFT of s restricted to the grid, by the plans of `p` on the real buffer
    !! `rb` (as [[lane_forward]]), s holding the conjugate of the spectrum: the mirrored
    !! inverse of [[transform_backward_from]]; s is destroyed.
    subroutine lane_backward(p, rb, s, y, slot)
        type(fc_fft_plans), intent(inout) :: p
        real(dp), intent(inout), contiguous :: rb(:, :)
        complex(dp), intent(inout), contiguous :: s(:, :)
        real(dp), intent(out) :: y(:, :)
        integer, intent(in) :: slot   !! the lane's chunk buffer (large grids)
        integer :: i, j, mx
        mx = p%mx
        call y_pass(p, s, .true., p%my, p%ny, slot)
        call fftw_execute_dft_c2r(p%plan_x_bwd, s, rb)
        do j = 1, p%ny
            y(1, j) = rb(1, j)
            do i = 2, p%nx
                y(i, j) = rb(mx - i + 2, j)
            end do
        end do
    end subroutine lane_backward

    !> cbuf ← FFT of x zero-padded to mx×my.
    subroutine transform_forward(w, x)
        type(fc_fft_plans), intent(inout) :: w
        real(dp), intent(in) :: x(:, :)
        call transform_forward_to(w, x, w%cbuf)
    end subroutine transform_forward

    !> c ← FFT of x zero-padded to mx×my; c is the plan set's cbuf or an array FFTW may use in
    !! its place ([[fftw_compatible]]); w's cbuf is not referenced otherwise.
    subroutine transform_forward_to(w, x, c)
        type(fc_fft_plans), intent(inout) :: w
        real(dp), intent(in) :: x(:, :)
        complex(dp), intent(inout), contiguous :: c(:, :)
        integer :: nx, ny, j
        logical :: par
        nx = w%nx; ny = w%ny
        par = size(w%rbuf) > omp_min_elements
        ! x into the real buffer with its zero padding in x (the x passes never read columns
        ! beyond ny; the padding columns of the spectrum are zeroed after them)
        !$omp parallel do default(shared) schedule(static) if(par)
        do j = 1, ny
            w%rbuf(1:nx, j) = x(:, j)
            if (w%mx > nx) w%rbuf(nx + 1:, j) = 0
        end do
        !$omp end parallel do
        call fftw_execute_dft_r2c(w%plan_x_fwd, w%rbuf, c)
        if (w%tw == 0) then
            !$omp parallel do default(shared) schedule(static) if(par)
            do j = ny + 1, w%my
                c(:, j) = 0
            end do
            !$omp end parallel do
        end if
        call y_pass(w, c, .true., ny, w%my)
    end subroutine transform_forward_to

    !> y ← inverse FFT of c (the plan set's cbuf or an array FFTW may use in its place),
    !! restricted to the grid; c is destroyed.  With `conjugated`, c holds the conjugate of the
    !! spectrum: the y pass then runs as the forward plan (forward of conj(c) = conj of the
    !! inverse of c), and the real x pass of that conjugate gives the result mirrored in x,
    !! r(−x mod mx), read back in mirrored order.  The products make their spectra
    !! conjugated in the symbol multiplication (no extra pass) and take this way because
    !! FFTW_ESTIMATE plans the inverse y pass of small grids with a buffered solver that
    !! allocates a buffer for every column at every execution; the forward pass is never
    !! slower (doc/operators.md, "Plans").
    subroutine transform_backward_from(w, c, y, conjugated)
        type(fc_fft_plans), intent(inout) :: w
        complex(dp), intent(inout), contiguous :: c(:, :)
        real(dp), intent(out) :: y(:, :)
        logical, intent(in) :: conjugated
        integer :: i, j, mx
        logical :: par
        mx = w%mx
        par = size(w%rbuf) > omp_min_elements
        if (conjugated) then
            call y_pass(w, c, .true., w%my, w%ny)
            call fftw_execute_dft_c2r(w%plan_x_bwd, c, w%rbuf)
            !$omp parallel do default(shared) private(i) schedule(static) if(par)
            do j = 1, w%ny
                y(1, j) = w%rbuf(1, j)
                do i = 2, w%nx
                    y(i, j) = w%rbuf(mx - i + 2, j)
                end do
            end do
            !$omp end parallel do
        else
            call y_pass(w, c, .false., w%my, w%ny)
            call fftw_execute_dft_c2r(w%plan_x_bwd, c, w%rbuf)
            !$omp parallel do default(shared) schedule(static) if(par)
            do j = 1, w%ny
                y(:, j) = w%rbuf(1:w%nx, j)
            end do
            !$omp end parallel do
        end if
    end subroutine transform_backward_from

    !> b ← a for two spectra of the same shape (threaded column copy).
    subroutine copy_spectrum(a, b)
        complex(dp), intent(in) :: a(:, :)
        complex(dp), intent(out) :: b(:, :)
        integer :: j
        !$omp parallel do default(shared) schedule(static) if(size(a) > omp_min_elements)
        do j = 1, size(a, 2)
            b(:, j) = a(:, j)
        end do
        !$omp end parallel do
    end subroutine copy_spectrum

    !> Whether the products' y passes run on contiguous column chunks (large spectra).
    logical function bttb_chunked_y(self)
        class(fc_bttb), intent(in) :: self
        bttb_chunked_y = .false.
        if (associated(self%fft)) bttb_chunked_y = self%fft%tw > 0
    end function bttb_chunked_y

    !> y = A x by the direct O(n²) sum over the stored coefficients: the test oracle.
    subroutine bttb_apply_direct(self, x, y)
        class(fc_bttb), intent(in) :: self
        real(dp), intent(in) :: x(:, :)
        real(dp), intent(out) :: y(:, :)
        integer :: i, j, k, l, di, dj
        real(dp) :: s
        if (.not. allocated(self%kernel)) error stop 'fc_bttb%apply_direct: the coefficients were not kept (keep_kernel)'
        do j = 1, self%ny
            do i = 1, self%nx
                s = 0
                do l = 1, self%ny
                    dj = j - l
                    if (self%periodic) dj = modulo(dj, self%my)
                    do k = 1, self%nx
                        di = i - k
                        if (self%periodic) di = modulo(di, self%mx)
                        s = s + self%kernel(di, dj)*x(k, l)
                    end do
                end do
                y(i, j) = s
            end do
        end do
    end subroutine bttb_apply_direct

end module fc_toeplitz
