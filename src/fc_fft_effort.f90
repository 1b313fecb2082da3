!> FFTW planning effort for repeated solves on one grid (flat API `fc_set_fft_effort`,
!! driver `&solver fft_wisdom`).
!!
!! The operators of [[fc_toeplitz]] plan with FFTW_ESTIMATE: no measurement, instant.
!! FFTW_MEASURE finds faster plans by timing candidates, at a planning cost that only
!! repeated calls repay.  FFTW keeps what it measured as process-wide "wisdom", which any
!! later plan of the same shape — including FFTW_ESTIMATE plans — uses.  [[prime_fft_plans]]
!! therefore measures, once per grid shape, the plans the product of an nx×ny operator
!! uses (the same shapes, strides and buffer kinds as [[fc_toeplitz]]); the operators built
!! afterwards get the measured plans without any change to how they are built.  Planning
!! overwrites the buffers, which are scratch arrays here.  [[use_fft_wisdom]] keeps the
!! wisdom in a file, so that only the first process on a grid pays for the measurement.
!! The file is written to a temporary name beside it and renamed over it (C's `rename`,
!! atomic on POSIX file systems): processes sharing one file, such as the ranks of an MPI
!! batch, read either the old file or the new one, never one half written (before, two
!! ranks on a shared file failed cases as "not wisdom" in 4 of 5 batches, doc/parallel.md).
!!
!! The strip solver's products (fc_mg2d_fft: in-place complex transforms of n points per
!! level) are measured the same way by [[prime_strip_plans]], and [[use_fft_wisdom]] keeps
!! them when it is given the levels' sizes.
!!
!! Measured break-even and per-call gains: doc/legacy_api.md ("FFT planning effort"),
!! doc/benchmarks.md (wisdom files), doc/multigrid.md (strips at 2^20).
module fc_fft_effort
    use fc_kinds, only: dp, FC_ERR_FFT_WISDOM
    use fc_fftw
    use fc_threads, only: fftw_threads_for_size
    use, intrinsic :: iso_c_binding, only: c_char
    implicit none
    private

    interface
        !> C's rename(3): atomic replacement of `to` on POSIX file systems; 0 on success.
        integer(c_int) function c_rename(from, to) bind(C, name='rename')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: from(*), to(*)
        end function c_rename
        !> POSIX getpid(2): makes the temporary name of a process's write unique.
        integer(c_int) function c_getpid() bind(C, name='getpid')
            import :: c_int
        end function c_getpid
    end interface

    public :: prime_fft_plans, fft_plans_in_wisdom, use_fft_wisdom, read_wisdom, write_wisdom, wisdom_temp_name
    public :: prime_strip_plans, strip_plans_in_wisdom, strip_product_radix, strip_product_plans

contains

    !> Measure (FFTW_MEASURE) the FFT plans of products on an nx×ny grid (circulant
    !! 2nx×2ny or fc_fftw's circulant_size, nx×ny when `periodic`) so that later FFTW_ESTIMATE plans of these
    !! shapes reuse the measured ones.  Cost: tens of ms at 60×50, about a second at
    !! 240×200 (doc/legacy_api.md).
    subroutine prime_fft_plans(nx, ny, periodic)
        integer, intent(in) :: nx, ny
        logical, intent(in), optional :: periodic
        logical :: all_made
        all_made = product_plans(nx, ny, FFTW_MEASURE, periodic)
    end subroutine prime_fft_plans

    !> Whether FFTW's wisdom already holds measured plans for the products on an nx×ny grid
    !! (planning with FFTW_WISDOM_ONLY succeeds for every one of them).
    logical function fft_plans_in_wisdom(nx, ny, periodic) result(known)
        integer, intent(in) :: nx, ny
        logical, intent(in), optional :: periodic
        known = product_plans(nx, ny, ior(FFTW_MEASURE, FFTW_WISDOM_ONLY), periodic)
    end function fft_plans_in_wisdom

    !> Measure (FFTW_MEASURE) the plans of the strip solver's products on levels of n cells
    !! for every n in `sizes` (in-place real transforms of 2n points, planned with the
    !! thread count fc_mg2d_ops uses for that size), so that the levels built afterwards get
    !! them.  Cost: about 30 s for the levels of n = 2^20 on the 2-core test machine (the
    !! finest level's 2^21-point pair alone about 5 s), once.
    subroutine prime_strip_plans(sizes)
        integer, intent(in) :: sizes(:)
        logical :: all_made
        all_made = strip_plans(sizes, FFTW_MEASURE)
    end subroutine prime_strip_plans

    !> Whether FFTW's wisdom already holds measured plans for the strip levels `sizes`.
    logical function strip_plans_in_wisdom(sizes) result(known)
        integer, intent(in) :: sizes(:)
        known = strip_plans(sizes, ior(FFTW_MEASURE, FFTW_WISDOM_ONLY))
    end function strip_plans_in_wisdom

    !> Wisdom file `path` for an nx×ny grid, or for the levels `strip_sizes` of a strip
    !! hierarchy when they are given: read it when it exists, measure the plans when neither
    !! the process nor the file has them, and write the file unless it already held them.
    !! `new_plans`: the process did not have the plans before this call (operators built
    !! earlier on estimated plans should be rebuilt).  stat = FC_ERR_FFT_WISDOM when the
    !! file exists but is not FFTW wisdom, or cannot be written.
    subroutine use_fft_wisdom(path, nx, ny, periodic, new_plans, stat, errmsg, strip_sizes)
        character(len=*), intent(in) :: path
        integer, intent(in) :: nx, ny
        logical, intent(in) :: periodic
        logical, intent(out) :: new_plans
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer, intent(in), optional :: strip_sizes(:)  !! level sizes of a strip hierarchy
        logical :: exists, had, have
        integer :: u, ios
        character(len=:), allocatable :: tmp
        stat = 0; errmsg = ''
        had = known()
        new_plans = .not. had
        tmp = wisdom_temp_name(path)
        inquire (file=path, exist=exists)
        if (.not. exists) then
            ! can the file be written?  Asked before the measurement, which takes seconds, and
            ! of the temporary name: another process may create `path` meanwhile
            open (newunit=u, file=tmp, status='replace', action='write', iostat=ios)
            if (ios /= 0) then
                stat = FC_ERR_FFT_WISDOM
                errmsg = 'cannot create the wisdom file (does its directory exist?)'
                return
            end if
            close (u, status='delete')
        else if (.not. read_wisdom(path)) then
            stat = FC_ERR_FFT_WISDOM
            errmsg = 'the file exists but FFTW cannot read it as wisdom (delete it to measure again)'
            return
        end if
        have = known()
        ! the plans came from the file alone: it is complete, leave it as it is
        if (exists .and. .not. had .and. have) return
        if (.not. have) then
            if (present(strip_sizes)) then
                call prime_strip_plans(strip_sizes)
            else
                call prime_fft_plans(nx, ny, periodic)
            end if
        end if
        select case (write_wisdom(tmp, path))
        case (1)
            stat = FC_ERR_FFT_WISDOM
            errmsg = 'cannot write the wisdom file (does its directory exist?)'
        case (2)
            stat = FC_ERR_FFT_WISDOM
            errmsg = 'cannot replace the wisdom file by the new one'
        end select
        if (stat /= 0) then        ! no temporary file left behind
            open (newunit=u, file=tmp, status='old', iostat=ios)
            if (ios == 0) close (u, status='delete')
        end if
    contains
        logical function known()
            if (present(strip_sizes)) then
                known = strip_plans_in_wisdom(strip_sizes)
            else
                known = fft_plans_in_wisdom(nx, ny, periodic)
            end if
        end function known
    end subroutine use_fft_wisdom

    !> The temporary name a process writes wisdom to before renaming it to `path`
    !! (`path.tmpPID`: processes sharing the file never write the same temporary).
    function wisdom_temp_name(path) result(tmp)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: tmp
        character(len=12) :: pid
        write (pid, '(i0)') c_getpid()
        tmp = trim(path)//'.tmp'//trim(pid)
    end function wisdom_temp_name

    !> Read FFTW's wisdom from `path`, merged with what the process has; .false. when FFTW
    !! reports a failure.
    logical function read_wisdom(path) result(ok)
        character(len=*), intent(in) :: path
        integer(c_int) :: done
        !$omp critical (fc_fftw_planner)
        done = fftw_import_wisdom_from_filename(trim(path)//c_null_char)
        !$omp end critical (fc_fftw_planner)
        ok = done /= 0
    end function read_wisdom

    !> Write the process's wisdom to `tmp`, then rename it over `path`, both inside the
    !! planner's critical section (threads of one process share the temporary name).
    !! 0: done; 1: `tmp` could not be written; 2: the rename failed (`tmp` is left for the
    !! caller to remove).
    integer function write_wisdom(tmp, path) result(code)
        character(len=*), intent(in) :: tmp, path
        !$omp critical (fc_fftw_planner)
        if (fftw_export_wisdom_to_filename(tmp//c_null_char) == 0) then
            code = 1
        else if (c_rename(tmp//c_null_char, trim(path)//c_null_char) /= 0) then
            code = 2
        else
            code = 0
        end if
        !$omp end critical (fc_fftw_planner)
    end function write_wisdom

    !> Plan (with `flags`) and destroy the transforms of the products on an nx×ny grid;
    !! .true. when every plan was made (with FFTW_WISDOM_ONLY: all were in the wisdom).
    logical function product_plans(nx, ny, flags, periodic) result(all_made)
        integer, intent(in) :: nx, ny
        integer(c_int), intent(in) :: flags
        logical, intent(in), optional :: periodic
        real(dp), allocatable :: rbuf(:, :)
        complex(dp), allocatable :: cbuf(:, :)
        type(c_ptr) :: p(4)
        integer :: mx, my, mxh, k
        logical :: per
        per = .false.
        if (present(periodic)) per = periodic
        if (per) then
            mx = nx; my = ny
        else
            mx = circulant_size(nx); my = circulant_size(ny)
        end if
        mxh = mx/2 + 1
        allocate (rbuf(mx, my), cbuf(mxh, my))
        !$omp critical (fc_fftw_planner)
        ! the passes of fc_toeplitz's products: r2c along x on the ny data columns, c2c along
        ! y; the inverse in the opposite order
        p(1) = fftw_plan_many_dft_r2c(1_c_int, [int(mx, c_int)], int(ny, c_int), rbuf, [int(mx, c_int)], &
            1_c_int, int(mx, c_int), cbuf, [int(mxh, c_int)], 1_c_int, int(mxh, c_int), flags)
        p(2) = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), cbuf, [int(my, c_int)], &
            int(mxh, c_int), 1_c_int, cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, FFTW_FORWARD, flags)
        p(3) = fftw_plan_many_dft(1_c_int, [int(my, c_int)], int(mxh, c_int), cbuf, [int(my, c_int)], &
            int(mxh, c_int), 1_c_int, cbuf, [int(my, c_int)], int(mxh, c_int), 1_c_int, FFTW_BACKWARD, flags)
        p(4) = fftw_plan_many_dft_c2r(1_c_int, [int(mx, c_int)], int(ny, c_int), cbuf, [int(mxh, c_int)], &
            1_c_int, int(mxh, c_int), rbuf, [int(mx, c_int)], 1_c_int, int(mx, c_int), flags)
        all_made = .true.
        do k = 1, size(p)
            all_made = all_made .and. c_associated(p(k))
            if (c_associated(p(k))) call fftw_destroy_plan(p(k))
        end do
        !$omp end critical (fc_fftw_planner)
    end function product_plans

    !> How the strip products of an n-cell level (fc_mg2d_fft's `strip_fft`) run their
    !! n-point complex transforms: 1, as one n-point transform; 2 or 4, as that many
    !! transforms of n/2 or n/4 points after a radix-2 or radix-4 step of their own, which
    !! also skips the zero-padded half.  Chosen where the smaller transforms run faster than
    !! FFTW_ESTIMATE's n-point plan (one thread, one product with its copies, C program
    !! against the same FFTW, doc/multigrid.md): 2^20 cells 29–31 (1), 19–22 (2), 12.9 ms (4);
    !! 2^19 8.1–8.4, 4.9–5.4, 4.8–4.9 ms; 2^18 2.2–2.4, 1.9–2.0, 2.1 ms; 2^17 0.91, 0.95 ms;
    !! 2^16 0.42, 0.79 ms.  Here, so that the measured plans of [[prime_strip_plans]] are
    !! those the products make.
    pure integer function strip_product_radix(n) result(radix)
        integer, intent(in) :: n
        radix = 1
        if (n >= 262144 .and. mod(n, 4) == 0) radix = 2
        if (n >= 1048576 .and. mod(n, 8) == 0) radix = 4
    end function strip_product_radix

    !> The forward and backward in-place plans (with `flags`) of a strip product on n cells
    !! in the layout `radix` on `cbuf` (n complex): one n-point transform (radix 1), or
    !! `radix` transforms of n/radix points.  Call inside the critical section
    !! `fc_fftw_planner`, with the planner's thread count set.
    subroutine strip_product_plans(n, radix, cbuf, flags, pf, pb)
        integer, intent(in) :: n, radix
        complex(dp), intent(inout), contiguous :: cbuf(:)   !! passed to FFTW as is (no copy)
        integer(c_int), intent(in) :: flags
        type(c_ptr), intent(out) :: pf, pb
        integer(c_int) :: l, r
        if (radix > 1) then
            r = int(radix, c_int); l = int(n/radix, c_int)
            pf = fftw_plan_many_dft(1_c_int, [l], r, cbuf, [l], 1_c_int, l, cbuf, [l], 1_c_int, l, FFTW_FORWARD, flags)
            pb = fftw_plan_many_dft(1_c_int, [l], r, cbuf, [l], 1_c_int, l, cbuf, [l], 1_c_int, l, FFTW_BACKWARD, flags)
        else
            pf = fftw_plan_dft_1d(int(n, c_int), cbuf, cbuf, FFTW_FORWARD, flags)
            pb = fftw_plan_dft_1d(int(n, c_int), cbuf, cbuf, FFTW_BACKWARD, flags)
        end if
    end subroutine strip_product_plans

    !> Plan (with `flags`) and destroy the strip levels' product transforms: as
    !! fc_mg2d_fft's `strip_fft`, an FFTW-aligned buffer of 2n reals, forward and backward
    !! complex transforms of n points in place, or r times n/r points where
    !! [[strip_product_radix]] is r > 1; .true. when every plan was made.
    logical function strip_plans(sizes, flags) result(all_made)
        integer, intent(in) :: sizes(:)
        integer(c_int), intent(in) :: flags
        complex(dp), pointer, contiguous :: cbuf(:)
        type(c_ptr) :: raw, pf, pb
        integer :: l, n, saved
        all_made = .true.
        do l = 1, size(sizes)
            n = sizes(l)
            if (strip_product_radix(n) > 1) cycle   ! measured plans run slower there (doc/multigrid.md)
            raw = fftw_alloc_real(int(2*n, c_size_t))
            call c_f_pointer(raw, cbuf, [n])
            saved = 1
            !$omp critical (fc_fftw_planner)
            call fftw_threads_for_size(2*n, saved)
            call strip_product_plans(n, strip_product_radix(n), cbuf, flags, pf, pb)
            call fftw_threads_for_size(-1, saved)
            all_made = all_made .and. c_associated(pf) .and. c_associated(pb)
            if (c_associated(pf)) call fftw_destroy_plan(pf)
            if (c_associated(pb)) call fftw_destroy_plan(pb)
            !$omp end critical (fc_fftw_planner)
            call fftw_free(raw)
        end do
    end function strip_plans

end module fc_fft_effort
