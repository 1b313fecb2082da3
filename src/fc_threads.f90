!> The OpenMP thread count and FFTW's threaded planner.
!!
!! The count is a positive `threads` when one is given (`&solver threads`, the flat API,
!! [[set_thread_count]]), else `OMP_NUM_THREADS` when it is set, else 1 ([[fc_default_threads]]):
!! without either a run is serial, as before threads existed (OpenMP's own default, one
!! thread per core, would also apply to machines shared with other jobs).
!! FFTW plans made after [[set_thread_count]] split each transform over that many threads
!! (FFTW's threaded library, `fftw3_omp`); plans made before keep their count, so the
!! driver sets the count before it builds the operators of a case.  Every plan creation and
!! destruction in the package, and the thread count of the planner, run inside the one named
!! critical section `fc_fftw_planner` (FFTW's planner is not re-entrant; its own
!! `fftw_make_planner_thread_safe` is also called, but four flat-API handles planning at once
!! still corrupted the heap without the section), so handles may be built from different
!! threads.  Built without OpenMP, every routine here reports one
!! thread and does nothing else.
!!
!! What runs in parallel: FFT products (FFTW), the influence-coefficient loops, the
!! periodic kernel, the rows and columns of the distributed products, and above
!! [[fc_threads:omp_min_elements]] the element loops and vector operations of BCCG and TangCG
!! (doc/parallel.md).
module fc_threads
    use, intrinsic :: iso_c_binding, only: c_int
    !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads, omp_get_num_procs
    implicit none
    private

    !> Bound on a requested count (the driver's `&solver threads` and the flat API's
    !! fc_set_threads check requests against it and name it in their messages)
    integer, parameter, public :: max_threads_allowed = 1024
    !> Grids smaller than this (nx·ny) keep single-threaded FFT plans when the caller gives
    !! the grid size (doubled-grid transforms below 2·32768 points gain nothing from a second
    !! thread).  On an idle 2-core machine, 2 threads with threaded FFTs from this size run
    !! Cattaneo 240×200 1.41× faster than one thread (1.0× with FFTs threaded only from 512²);
    !! on a machine loaded beyond its cores they lose (doc/parallel.md §5.3).
    integer, parameter, public :: fftw_thread_min_elements = 32768
    !> Grid cells (nx·ny) from which a 2×2 block product (tangential operator, TangCG's block
    !! inverse) runs its x and y components side by side, one thread each, with two
    !! threads or more (fc_toeplitz's `block_product`): products 1.2–1.3× faster than one
    !! thread at 40×40 … 80×64, 1.6–1.9× from 120×100; below, 30×25, 1.1× (doc/parallel.md §5.3)
    integer, parameter, public :: lanes_min_elements = 1024
    !> Element loops and vector operations of the solvers (BCCG, TangCG, the FFT products'
    !! spectral multiplications and copies) run on several threads only for arrays with more
    !! elements than this; below it a parallel region costs more than the loop (measured with
    !! bench/bench_omp_loops.f90, doc/parallel.md §5.3).  Below the threshold, and with one
    !! thread, the loops run in element order, exactly as the serial code.
    integer, parameter, public :: omp_min_elements = 32768

    interface
        integer(c_int) function fftw_init_threads() bind(C, name='fftw_init_threads')
            import :: c_int
        end function fftw_init_threads
        subroutine fftw_plan_with_nthreads(n) bind(C, name='fftw_plan_with_nthreads')
            import :: c_int
            integer(c_int), value :: n
        end subroutine fftw_plan_with_nthreads
        subroutine fftw_make_planner_thread_safe() bind(C, name='fftw_make_planner_thread_safe')
        end subroutine fftw_make_planner_thread_safe
        integer(c_int) function fftw_planner_nthreads() bind(C, name='fftw_planner_nthreads')
            import :: c_int
        end function fftw_planner_nthreads
    end interface

    logical, save :: fftw_threads_ready = .false.   ! set once, before any threaded plan

    public :: set_thread_count, fc_thread_count, fc_openmp_enabled, fc_default_threads
    public :: fftw_threads_for_size, fftw_planner_threads

contains

    !> True when the library was compiled with OpenMP.
    pure logical function fc_openmp_enabled()
        fc_openmp_enabled = .false.
        !$ fc_openmp_enabled = .true.
    end function fc_openmp_enabled

    !> Threads used from now on (OpenMP regions and FFTW plans made after the call).
    integer function fc_thread_count()
        fc_thread_count = 1
        !$ fc_thread_count = omp_get_max_threads()
    end function fc_thread_count

    !> Threads when none is requested: OMP_NUM_THREADS if set to a count in 1 … 1024 (the
    !! first entry of a list), else 1.
    integer function fc_default_threads() result(n)
        character(len=64) :: v
        integer :: length, st, ios, k
        n = 1
        call get_environment_variable('OMP_NUM_THREADS', v, length, st)
        if (st /= 0 .or. length == 0) return
        k = scan(v, ',')
        if (k > 0) v = v(1:k - 1)
        read (v, *, iostat=ios) k
        if (ios == 0 .and. k >= 1 .and. k <= max_threads_allowed) n = k
    end function fc_default_threads

    !> Use `n` threads (n ≤ 0: [[fc_default_threads]]) for OpenMP regions and for FFTW plans
    !! made from now on.  With `elements` (the grid size nx·ny), FFT plans stay on one thread
    !! below [[fc_threads:fftw_thread_min_elements]], where a second FFTW thread costs more than it saves
    !! (doc/parallel.md §5.3).  Call it outside parallel regions.
    subroutine set_thread_count(n, elements)
        integer, intent(in) :: n
        integer, intent(in), optional :: elements
        integer(c_int) :: ok
        integer :: m, nfft
        m = n
        if (m <= 0) m = fc_default_threads()
        !$ call omp_set_num_threads(min(m, max_threads_allowed))
        !$omp critical (fc_threads_init)
        !$ if (.not. fftw_threads_ready) then
        !$     ok = fftw_init_threads()
        !$     call fftw_make_planner_thread_safe()
        !$     fftw_threads_ready = ok /= 0
        !$ end if
        !$omp end critical (fc_threads_init)
        !$ nfft = omp_get_max_threads()
        !$ if (present(elements)) then
        !$     if (elements < fftw_thread_min_elements) nfft = 1
        !$ end if
        !$omp critical (fc_fftw_planner)
        !$ if (fftw_threads_ready) call fftw_plan_with_nthreads(int(nfft, c_int))
        !$omp end critical (fc_fftw_planner)
        ok = 0
    end subroutine set_thread_count


    !> For one plan of a transform with `points` real points: plans made until the next call
    !! use one thread when `points` < 2·[[fc_threads:fftw_thread_min_elements]] (a second thread costs
    !! more than it saves there), else the count of the last [[set_thread_count]]; returns
    !! the planner's previous count in `saved`, to restore with
    !! `call fftw_threads_for_size(-1, saved)`.  Call inside the critical section
    !! `fc_fftw_planner`; without OpenMP it does nothing.
    subroutine fftw_threads_for_size(points, saved)
        integer, intent(in) :: points     !! transform size; < 0: restore `saved`
        integer, intent(inout) :: saved   !! the planner's count before the call
        !$ if (.not. fftw_threads_ready) return
        !$ if (points < 0) then
        !$     call fftw_plan_with_nthreads(int(max(saved, 1), c_int))
        !$ else
        !$     saved = int(fftw_planner_nthreads())
        !$     if (points < 2*fftw_thread_min_elements) call fftw_plan_with_nthreads(1_c_int)
        !$ end if
    end subroutine fftw_threads_for_size

    !> Threads of the FFTW plans made now (1 without OpenMP or before threads are set up).
    !! Call inside the critical section `fc_fftw_planner`.
    integer function fftw_planner_threads() result(n)
        n = 1
        !$ if (fftw_threads_ready) n = max(1, int(fftw_planner_nthreads()))
    end function fftw_planner_threads
end module fc_threads
