!> Multigrid with the FFT smoother for the 2D no-slip strip problems (thesis ch. 3).
!!
!! A cylinder on a plane in plane strain is modelled on an n×1 grid of the strip
!! [−4,4]×[−50,50] mm (thesis §3.2.4): A = A^xx is a dense SPD Toeplitz matrix and the
!! no-slip problem is A p = u (eq. 3.9).  Three model problems (§3.2.5, §3.5):
!!
!! * MP1: steel (G = 82000, ν = 0.28), constant rigid shift 0.0008 mm;
!! * MP2: rubber (G = 0.3, ν = 0.49), rigid shift δt·w = −x;
!! * MP3: as MP1 on the two strips [−4,−2] ∪ [0,4] of the potential area (A_r is A with
!!   the rows and columns outside the strips removed; products by FFT on the whole strip
!!   with masking, thesis [100]).
!!
!! Smoothers (Richardson p ← p + S (u − A p)):
!!
!! * 'fft'     — S = M, the Toeplitz matrix whose coefficients approximate one interior
!!               column of A⁻¹ (§3.3.1: pointwise inverse of the FFT of A's coefficients on
!!               the (2n−1)-circulant).  Multigrid diverges from 32×1 on (Table 3.1).
!! * 'fft-sd'  — S = P M with two-subdomain deflation P = I − MA·Z E⁻¹ Zᵀ, E = Zᵀ M A Z
!!               (§3.4.1, eqs. 3.14–3.17).
!! * 'fft-rsm' — S = M̄ = M_r − diag(sum(M_r) − γ), γ = min row sum of M on the potential
!!               area (row-sum modification, eqs. 3.18–3.19, and its MP3 form 3.21).
!!
!! Multigrid (§3.3.3): coarsening by pairs of cells, restriction by averaging (3.12), copy
!! interpolation (3.13), each level's own coefficients, coarsest level (2×1) solved
!! directly (LAPACK); on MP3 a coarse cell belongs to the strips when either child does.
!! FFT+RSM is also available as a one-grid solver (§3.5.3).
!!
!! Stopping: ‖u − A p‖_rms/‖u‖_rms ≤ tol (1e−8 in the thesis) from a random initial guess;
!! convergence factor q = (‖d_k‖/‖d_0‖)^(1/k).  Work units: one product with A or M on
!! the finest grid = 1, halved per coarser level; the defect after a cycle is reused by
!! the next one, so a V(1,1)-cycle costs 5 products on the finest grid, V(1,0)/V(0,1) 3
!! (as counted in the thesis, §3.5.2).
!!
!! The products, coefficients and the Toeplitz inverse are [[fc_mg2d_ops]]'s: per level one
!! in-place FFT plan pair shared by A and M, all levels transforming in one buffer, made
!! with the hierarchy together with the work arrays, so that the cycles allocate nothing
!! (doc/multigrid.md, "Performance at 2^20").
!! Size: ~710 lines; the solvers and the two spectral analyses share the private level
!! type and cycle routines, so they stay in one module.
module fc_mg2d
    use fc_kinds
    use fc_geometry, only: fc_grid, make_grid
    use fc_influence
    use fc_mg2d_ops, only: strip_fft, strip_kernel, strip_toeplitz_inverse, strip_toeplitz_inverse_even, &
        strip_workspace, strip_workspace_need
    use fc_lapack, only: solve_spd, eigenvalues_general
    use fc_threads, only: omp_min_elements
    implicit none
    private

    !> A 2D strip problem A_r p = u on an n×1 grid.
    type, public :: fc_strip_problem
        type(fc_grid) :: grid                 !! n×1 grid of the potential contact strip
        type(fc_material) :: material         !! combined constants
        integer :: block = IC_XX              !! influence block (A^xx: tangential no-slip)
        real(dp), allocatable :: rhs(:)       !! u = −δt·w [mm]
        logical, allocatable :: contact(:)    !! elements of the contact strips (MP3); all true else
    end type fc_strip_problem

    !> Settings of the strip solvers.
    type, public :: fc_mg2d_settings
        character(len=8) :: smoother = 'fft-rsm'  !! 'fft', 'fft-sd' or 'fft-rsm'
        integer :: nu1 = 1                        !! pre-smoothing steps of V(nu1,nu2)
        integer :: nu2 = 1                        !! post-smoothing steps
        real(dp) :: tol = 1.0e-8_dp               !! ‖d‖_rms/‖u‖_rms
        integer :: maxit = 100                    !! cycles (MG) or iterations (one-grid solver)
        integer :: coarsest = 2                   !! coarsest grid size (cells)
        integer :: seed = 12345                   !! random initial guess p ∈ [0,1) (thesis §3.5)
        logical :: random_start = .true.          !! .false.: start from p = 0
    end type fc_mg2d_settings

    !> Result of a strip solve.
    type, public :: fc_mg2d_result
        real(dp), allocatable :: p(:)        !! traction per element [N/mm²]
        integer :: status = FC_ERROR         !! FC_CONVERGED, FC_NOT_CONVERGED, FC_DIVERGED
        integer :: iterations = 0            !! cycles / iterations
        real(dp) :: residual = huge(1.0_dp)  !! final ‖d‖_rms/‖u‖_rms
        real(dp) :: factor = 0               !! convergence factor q
        real(dp) :: work_units = 0           !! products in finest-grid units
        integer :: levels = 0                !! grid levels used
        real(dp) :: cpu_seconds = 0          !! solve time including set-up
        character(len=msg_len) :: message = ''
        real(dp), allocatable :: history(:)  !! relative defect before each cycle (0…k)
    end type fc_mg2d_result

    !> One level of the strip hierarchy, with its plans and work arrays (made once per
    !! solve; the cycles allocate nothing).
    type :: strip_level
        integer :: n = 0
        type(fc_grid) :: grid
        type(strip_fft) :: fft                 !! plans and buffer shared by A and M
        real(dp), allocatable :: ka(:)         !! A's coefficients a(0:n−1)
        real(dp), allocatable :: sa(:), sm(:)  !! symbols of A and M (0:n)
        real(dp) :: gamma = 0                  !! min row sum of M (eq. 3.19)
        logical, allocatable :: con(:)         !! contact strips on this level
        logical :: all_con = .true.            !! every element in contact (MP1, MP2)
        real(dp), allocatable :: shift(:)      !! RSM: sum(M_r) − γ on con
        real(dp), allocatable :: w(:, :)       !! SD: Ā Z (n×2)
        real(dp), allocatable :: z(:, :)       !! SD: Z (n×2)
        real(dp) :: einv(2, 2) = 0             !! SD: E⁻¹
        real(dp) :: cost = 1                   !! n_level/n_finest
        real(dp), allocatable :: r(:), x(:), d(:), t(:)   !! right-hand side, iterate, defect, scratch
        integer, allocatable :: idx(:)         !! coarsest level: elements in contact
        real(dp), allocatable :: ac(:, :), acw(:, :), bc(:, :)  !! coarsest level: A_r, its copy, rhs
    end type strip_level

    type :: strip_hierarchy
        type(strip_level), allocatable :: lev(:)   !! 1 = coarsest
        type(strip_workspace) :: ws                !! FFT buffer shared by the levels
        integer :: nlev = 0
        real(dp) :: work = 0
    end type strip_hierarchy

    public :: strip_model_problem, solve_strip_mg, solve_strip_fft_rsm, mg2d_spectral_radius, strip_level_sizes
    public :: strip_toeplitz_inverse, strip_smoother_radius  ! strip_toeplitz_inverse from fc_mg2d_ops

contains

    !> Model problem MP1, MP2 or MP3 (`which` = 1, 2, 3) on an n×1 grid (thesis §3.2.5, §3.5).
    subroutine strip_model_problem(which, n, prob, stat, errmsg)
        integer, intent(in) :: which, n
        type(fc_strip_problem), intent(out) :: prob
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: i
        real(dp) :: x
        stat = 0; errmsg = ''
        if (which < 1 .or. which > 3) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a)') 'strip2d: model problem ', which, ' is not 1, 2 or 3'; return
        end if
        if (n < 4 .or. iand(int(n, i8), int(n, i8) - 1) /= 0) then   ! 64 bits: no overflow at n = −2^31
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a)') 'strip2d: n = ', n, ' must be a power of 2 >= 4'; return
        end if
        call make_grid(prob%grid, n, 1, -4.0_dp, 4.0_dp, -50.0_dp, 50.0_dp, stat, errmsg)
        if (stat /= 0) return
        if (which == 2) then
            prob%material%g1 = 0.3_dp; prob%material%g2 = 0.3_dp
            prob%material%nu1 = 0.49_dp; prob%material%nu2 = 0.49_dp
        else
            prob%material%g1 = 82000; prob%material%g2 = 82000
            prob%material%nu1 = 0.28_dp; prob%material%nu2 = 0.28_dp
        end if
        call combine_material(prob%material, stat, errmsg)
        if (stat /= 0) return
        prob%block = IC_XX
        allocate (prob%rhs(n), prob%contact(n))
        prob%contact = .true.
        do i = 1, n
            x = prob%grid%x(i)
            select case (which)
            case (2)
                prob%rhs(i) = x                       ! u = −δt·w with δt·w = −x
            case default
                prob%rhs(i) = -0.0008_dp              ! u = −δt·w with δt·w = 0.0008 mm
            end select
            if (which == 3) prob%contact(i) = (x > -4 .and. x < -2) .or. (x > 0 .and. x < 4)
        end do
        where (.not. prob%contact) prob%rhs = 0
    end subroutine strip_model_problem

    ! ---- hierarchy -------------------------------------------------------------------------

    subroutine build_hierarchy(prob, settings, nlev_max, hier, stat, errmsg)
        type(fc_strip_problem), intent(in) :: prob
        type(fc_mg2d_settings), intent(in) :: settings
        integer, intent(in) :: nlev_max
        type(strip_hierarchy), intent(inout) :: hier
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: nlev, l, i, nf
        integer, allocatable :: sizes(:)
        stat = 0; errmsg = ''
        nf = prob%grid%nx
        sizes = level_sizes(nf, settings%coarsest, nlev_max)
        nlev = size(sizes)
        if (nlev_max > 1 .and. sizes(1) > 4096) then
            stat = FC_ERR_GRID
            write (errmsg, '(a,i0,a,i0,a)') 'strip2d: n = ', nf, ' coarsens only to ', sizes(1), &
                ' cells (> 4096 for the direct coarsest solve); use n with more factors of 2'
            return
        end if
        hier%nlev = nlev
        allocate (hier%lev(nlev))
        call hier%ws%reserve(strip_workspace_need(sizes))
        do l = nlev, 1, -1
            associate (lv => hier%lev(l))
                lv%n = sizes(l)
                lv%cost = real(sizes(l), dp)/nf
                call make_grid(lv%grid, sizes(l), 1, prob%grid%xmin, prob%grid%xmax, prob%grid%ymin, prob%grid%ymax, &
                    stat, errmsg)
                if (stat /= 0) return
                allocate (lv%con(sizes(l)))
                if (l == nlev) then
                    lv%con = prob%contact
                else
                    do i = 1, sizes(l)
                        lv%con(i) = hier%lev(l + 1)%con(2*i - 1) .or. hier%lev(l + 1)%con(2*i)
                    end do
                end if
                lv%all_con = all(lv%con)
                call build_level(prob, settings, lv, hier%ws)
                if (l == 1 .and. nlev_max > 1) call build_coarsest(lv)
            end associate
        end do
    end subroutine build_hierarchy

    !> Cells of the levels (coarsest first, the finest nf last): halved while even and not
    !! below `coarsest`, at most nlev_max levels.
    pure function level_sizes(nf, coarsest, nlev_max) result(sizes)
        integer, intent(in) :: nf, coarsest, nlev_max
        integer, allocatable :: sizes(:)
        integer :: n, nlev, l
        nlev = 1; n = nf
        do while (mod(n, 2) == 0 .and. n/2 >= max(1, coarsest) .and. nlev < nlev_max)
            n = n/2; nlev = nlev + 1
        end do
        allocate (sizes(nlev))
        sizes(nlev) = nf
        do l = nlev - 1, 1, -1
            sizes(l) = sizes(l + 1)/2
        end do
    end function level_sizes

    !> Cells of the levels that [[solve_strip_mg]] (`multigrid`) or [[solve_strip_fft_rsm]]
    !! builds for `prob`, coarsest first: the sizes whose FFT plans
    !! fc_fft_effort's `use_fft_wisdom(..., strip_sizes=)` measures and keeps.
    pure function strip_level_sizes(prob, settings, multigrid) result(sizes)
        type(fc_strip_problem), intent(in) :: prob
        type(fc_mg2d_settings), intent(in) :: settings
        logical, intent(in) :: multigrid
        integer, allocatable :: sizes(:)
        sizes = level_sizes(prob%grid%nx, settings%coarsest, merge(64, 1, multigrid))
    end function strip_level_sizes

    !> A, M, γ, the RSM shift, the SD matrices and the work arrays of one level.
    !! M's coefficients pass through the level's defect array d, which is free until the
    !! cycles start (no temporaries of the level's size: doc/multigrid.md, "Performance").
    subroutine build_level(prob, settings, lv, ws)
        type(fc_strip_problem), intent(in) :: prob
        type(fc_mg2d_settings), intent(in) :: settings
        type(strip_level), intent(inout) :: lv
        type(strip_workspace), intent(inout) :: ws
        real(dp) :: e(2, 2), det
        integer :: n, j
        n = lv%n
        allocate (lv%ka(0:n - 1), lv%sa(0:n), lv%sm(0:n))
        allocate (lv%r(n), lv%x(n), lv%d(n), lv%t(n), lv%shift(n))
        call lv%fft%init(n, ws)
        call strip_kernel(prob%block, prob%material, lv%grid, lv%ka)
        associate (ms => lv%d)                               ! M's coefficients m(0:n−1)
            call strip_toeplitz_inverse_even(n, lv%ka, ms, ws)  ! even part (M is symmetric)
            call lv%fft%symbol(lv%ka, lv%sa)
            call lv%fft%symbol(ms, lv%sm)
            ! row sums of M by a sliding window over its coefficients (O(n))
            call toeplitz_row_sums(ms, lv%t)
        end associate
        lv%gamma = minval(lv%t)                              ! eq. (3.19), full potential strip
        if (.not. lv%all_con) then
            lv%d = merge(1.0_dp, 0.0_dp, lv%con)
            call lv%fft%product(lv%sm, lv%d, lv%t)
        end if
        where (lv%con)
            lv%shift = lv%t - lv%gamma                       ! eq. (3.21): sum(M_r) − γ
        elsewhere
            lv%shift = 0
        end where
        if (settings%smoother == 'fft-sd') then
            allocate (lv%z(n, 2), lv%w(n, 2))
            lv%z = 0
            lv%z(1:n/2, 1) = 1; lv%z(n/2 + 1:n, 2) = 1
            lv%z(:, 1) = merge(lv%z(:, 1), 0.0_dp, lv%con)
            lv%z(:, 2) = merge(lv%z(:, 2), 0.0_dp, lv%con)
            do j = 1, 2
                call lv%fft%product(lv%sa, lv%z(:, j), lv%t)
                where (.not. lv%con) lv%t = 0
                call lv%fft%product(lv%sm, lv%t, lv%d)
                where (.not. lv%con) lv%d = 0
                lv%w(:, j) = lv%d
            end do
            e = matmul(transpose(lv%z), lv%w)
            det = e(1, 1)*e(2, 2) - e(1, 2)*e(2, 1)
            if (abs(det) > 0) then
                lv%einv = reshape([e(2, 2), -e(2, 1), -e(1, 2), e(1, 1)], [2, 2])/det
            else
                lv%einv = 0
            end if
        end if
        lv%r = 0; lv%x = 0; lv%d = 0; lv%t = 0
    end subroutine build_level

    !> rs(i) = Σ_{j=1..n} m(|i−j|) for the symmetric Toeplitz matrix of coefficients m(0:n−1):
    !! a window sliding by one offset per row, summed with compensation (Kahan) so that
    !! the n updates add no more than a few roundings.
    pure subroutine toeplitz_row_sums(m, rs)
        real(dp), intent(in) :: m(0:)
        real(dp), intent(out) :: rs(:)
        real(dp) :: s, c, y, t
        integer :: n, i
        n = size(rs)
        s = 0; c = 0
        do i = n - 1, 0, -1                ! row 1: offsets 0, −1, …, −(n−1)
            y = m(i) - c; t = s + y; c = (t - s) - y; s = t
        end do
        rs(1) = s
        do i = 2, n                        ! row i gains offset i−1, loses offset −(n−i+1)
            y = m(i - 1) - c; t = s + y; c = (t - s) - y; s = t
            y = -m(n - i + 1) - c; t = s + y; c = (t - s) - y; s = t
            rs(i) = s
        end do
    end subroutine toeplitz_row_sums

    !> Dense A_r on the coarsest level's contact elements (solved directly each cycle).
    subroutine build_coarsest(lv)
        type(strip_level), intent(inout) :: lv
        integer :: nc, i, j
        nc = count(lv%con)
        lv%idx = pack([(i, i=1, lv%n)], lv%con)
        allocate (lv%ac(nc, nc), lv%acw(nc, nc), lv%bc(nc, 1))
        do j = 1, nc
            do i = 1, nc
                lv%ac(i, j) = lv%ka(abs(lv%idx(i) - lv%idx(j)))
            end do
        end do
    end subroutine build_coarsest

    subroutine destroy_hierarchy(hier)
        type(strip_hierarchy), intent(inout) :: hier
        integer :: l
        if (.not. allocated(hier%lev)) return
        do l = 1, size(hier%lev)
            call hier%lev(l)%fft%destroy()
        end do
        deallocate (hier%lev)
        call hier%ws%release()
        hier%nlev = 0
    end subroutine destroy_hierarchy

    ! ---- operators -----------------------------------------------------------------------

    !> d ← r − A_r x on the contact strips of level l (0 elsewhere); one product.
    subroutine defect(hier, l)
        type(strip_hierarchy), intent(inout) :: hier
        integer, intent(in) :: l
        integer :: i
        associate (lv => hier%lev(l))
            call lv%fft%product(lv%sa, lv%x, lv%d)
            hier%work = hier%work + lv%cost
            if (lv%all_con) then
                !$omp parallel do default(shared) schedule(static) if(lv%n > omp_min_elements)
                do i = 1, lv%n
                    lv%d(i) = lv%r(i) - lv%d(i)
                end do
                !$omp end parallel do
            else
                !$omp parallel do default(shared) schedule(static) if(lv%n > omp_min_elements)
                do i = 1, lv%n
                    lv%d(i) = merge(lv%r(i) - lv%d(i), 0.0_dp, lv%con(i))
                end do
                !$omp end parallel do
            end if
        end associate
    end subroutine defect

    !> x ← x + S d on level l for the chosen smoother (one product with M).
    subroutine smooth_step(hier, l, smoother)
        type(strip_hierarchy), intent(inout) :: hier
        integer, intent(in) :: l
        character(len=*), intent(in) :: smoother
        real(dp) :: c(2)
        integer :: i
        associate (lv => hier%lev(l))
            call lv%fft%product(lv%sm, lv%d, lv%t)
            hier%work = hier%work + lv%cost
            select case (smoother)
            case ('fft-rsm')
                !$omp parallel do default(shared) schedule(static) if(lv%n > omp_min_elements)
                do i = 1, lv%n
                    if (lv%con(i)) lv%x(i) = lv%x(i) + (lv%t(i) - lv%shift(i)*lv%d(i))
                end do
                !$omp end parallel do
            case ('fft-sd')
                ! P y = y − Ā Z E⁻¹ Zᵀ y  (eq. 3.14 with precomputed Ā Z)
                where (.not. lv%con) lv%t = 0
                c = matmul(lv%einv, matmul(transpose(lv%z), lv%t))
                lv%t = lv%t - matmul(lv%w, c)
                where (lv%con) lv%x = lv%x + lv%t
            case default
                where (lv%con) lv%x = lv%x + lv%t
            end select
        end associate
    end subroutine smooth_step

    !> Direct solve A_r v = d on the coarsest level (dposv), x ← x + v; v = 0 off the strips.
    subroutine coarse_solve(lv, stat, errmsg)
        type(strip_level), intent(inout) :: lv
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (size(lv%idx) == 0) return
        lv%acw = lv%ac
        lv%bc(:, 1) = lv%d(lv%idx)
        call solve_spd(lv%acw, lv%bc, stat, errmsg)
        if (stat /= 0) then
            errmsg = 'strip2d coarsest-grid solve: '//trim(errmsg); return
        end if
        lv%x(lv%idx) = lv%x(lv%idx) + lv%bc(:, 1)
    end subroutine coarse_solve

    !> One V(ν1,ν2)-cycle for A_r x = r on level l (the level's own arrays).  On entry d is
    !! the defect of x, on exit the defect of the new x (so the caller's stopping test and
    !! the next cycle reuse it).
    recursive subroutine vcycle(hier, l, settings, stat, errmsg)
        type(strip_hierarchy), intent(inout) :: hier
        integer, intent(in) :: l
        type(fc_mg2d_settings), intent(in) :: settings
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: k, i
        stat = 0; errmsg = ''
        if (l == 1) then
            call coarse_solve(hier%lev(1), stat, errmsg)
            if (stat /= 0) return
            hier%lev(1)%d = 0
            return
        end if
        do k = 1, settings%nu1
            call smooth_step(hier, l, settings%smoother)
            call defect(hier, l)
        end do
        associate (fine => hier%lev(l), coarse => hier%lev(l - 1))
            !$omp parallel do default(shared) schedule(static) if(coarse%n > omp_min_elements)
            do i = 1, coarse%n                                      ! eq. (3.12)
                coarse%r(i) = merge(0.5_dp*(fine%d(2*i - 1) + fine%d(2*i)), 0.0_dp, coarse%con(i))
                coarse%x(i) = 0
                coarse%d(i) = coarse%r(i)
            end do
            !$omp end parallel do
        end associate
        call vcycle(hier, l - 1, settings, stat, errmsg)
        if (stat /= 0) return
        associate (fine => hier%lev(l), coarse => hier%lev(l - 1))
            !$omp parallel do default(shared) schedule(static) if(coarse%n > omp_min_elements)
            do i = 1, coarse%n                                      ! eq. (3.13)
                if (fine%con(2*i - 1)) fine%x(2*i - 1) = fine%x(2*i - 1) + coarse%x(i)
                if (fine%con(2*i)) fine%x(2*i) = fine%x(2*i) + coarse%x(i)
            end do
            !$omp end parallel do
        end associate
        call defect(hier, l)
        do k = 1, settings%nu2
            call smooth_step(hier, l, settings%smoother)
            call defect(hier, l)
        end do
    end subroutine vcycle

    ! ---- solvers ---------------------------------------------------------------------------

    subroutine check_input(prob, settings, stat, errmsg)
        type(fc_strip_problem), intent(in) :: prob
        type(fc_mg2d_settings), intent(in) :: settings
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (.not. allocated(prob%rhs) .or. .not. allocated(prob%contact)) then
            stat = FC_ERR_NOT_READY; errmsg = 'strip2d: problem not set (rhs/contact)'; return
        end if
        if (prob%grid%ny /= 1 .or. size(prob%rhs) /= prob%grid%nx .or. size(prob%contact) /= prob%grid%nx) then
            stat = FC_ERR_SHAPE; errmsg = 'strip2d: needs an n×1 grid with rhs and contact of size n'; return
        end if
        if (.not. any(prob%contact)) then
            stat = FC_ERR_NO_CONTACT; errmsg = 'strip2d: no element in contact'; return
        end if
        select case (settings%smoother)
        case ('fft', 'fft-sd', 'fft-rsm')
        case default
            stat = FC_ERR_VALUE
            errmsg = "solver: smoother = '"//trim(settings%smoother)//"' is not one of 'fft', 'fft-sd', 'fft-rsm'"
            return
        end select
        if (settings%nu1 < 0 .or. settings%nu2 < 0 .or. settings%nu1 + settings%nu2 == 0) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a,i0,a)') 'solver: cycle V(', settings%nu1, ',', settings%nu2, &
                ') needs nu1, nu2 >= 0 and nu1 + nu2 > 0'
            return
        end if
        if (.not. (settings%tol > 0) .or. settings%maxit < 1) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,es10.3,a,i0,a)') 'solver: tol = ', settings%tol, ', maxit = ', settings%maxit, &
                ' need tol > 0, maxit >= 1'
            return
        end if
    end subroutine check_input

    !> Initial guess: uniform random numbers in [0,1) from a portable generator (MINSTD),
    !! zero off the strips.
    subroutine initial_guess(settings, con, p)
        type(fc_mg2d_settings), intent(in) :: settings
        logical, intent(in) :: con(:)
        real(dp), intent(out) :: p(:)
        integer(i8) :: state
        integer :: i
        p = 0
        if (.not. settings%random_start) return
        state = max(1_i8, mod(abs(int(settings%seed, i8)), 2147483646_i8) + 1)   ! abs in 64 bits
        do i = 1, size(p, 1)
            state = mod(48271_i8*state, 2147483647_i8)
            p(i) = real(state, dp)/2147483647.0_dp
        end do
        where (.not. con) p = 0
    end subroutine initial_guess

    !> Multigrid with the FFT / FFT+SD / FFT+RSM smoother for A_r p = u (thesis §3.3–3.5).
    !! Divergence (defect grown 1e6× or not finite) is reported as FC_DIVERGED.
    subroutine solve_strip_mg(prob, settings, res, stat, errmsg)
        type(fc_strip_problem), intent(in) :: prob
        type(fc_mg2d_settings), intent(in) :: settings
        type(fc_mg2d_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        call run_solver(prob, settings, .true., res, stat, errmsg)
    end subroutine solve_strip_mg

    !> FFT+RSM as a one-grid Richardson solver p ← p + M̄ (u − A_r p) (thesis §3.5.3).
    subroutine solve_strip_fft_rsm(prob, settings, res, stat, errmsg)
        type(fc_strip_problem), intent(in) :: prob
        type(fc_mg2d_settings), intent(in) :: settings
        type(fc_mg2d_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_mg2d_settings) :: s
        s = settings
        s%smoother = 'fft-rsm'
        call run_solver(prob, s, .false., res, stat, errmsg)
    end subroutine solve_strip_fft_rsm

    subroutine run_solver(prob, settings, multigrid, res, stat, errmsg)
        type(fc_strip_problem), intent(in) :: prob
        type(fc_mg2d_settings), intent(in) :: settings
        logical, intent(in) :: multigrid
        type(fc_mg2d_result), intent(out) :: res
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(strip_hierarchy) :: hier
        real(dp) :: unorm, d0, dn
        integer :: k, n, vstat
        integer(i8) :: t0, t1, rate   ! 64-bit: a µs clock (default integers tick in ms)
        character(len=msg_len) :: vmsg
        call check_input(prob, settings, stat, errmsg)
        if (stat /= 0) return
        call system_clock(t0, rate)
        if (multigrid) then
            call build_hierarchy(prob, settings, 64, hier, stat, errmsg)
        else
            call build_hierarchy(prob, settings, 1, hier, stat, errmsg)
        end if
        if (stat /= 0) return
        n = prob%grid%nx
        res%levels = hier%nlev
        allocate (res%history(0:settings%maxit))
        associate (fine => hier%lev(hier%nlev))
            fine%r = merge(prob%rhs, 0.0_dp, prob%contact)
            unorm = sqrt(sum(fine%r**2))
            if (.not. (unorm > 0)) then
                stat = FC_ERR_VALUE; errmsg = 'strip2d: right-hand side is zero on the contact strips'
                call destroy_hierarchy(hier); return
            end if
            call initial_guess(settings, fine%con, fine%x)
        end associate
        hier%work = 0
        call defect(hier, hier%nlev)
        d0 = sqrt(sum(hier%lev(hier%nlev)%d**2))
        res%history(0) = d0/unorm
        res%status = FC_NOT_CONVERGED
        write (res%message, '(a,i0,a)') 'not converged in maxit = ', settings%maxit, ' iterations'
        dn = d0
        do k = 1, settings%maxit
            if (dn <= settings%tol*unorm) then
                res%status = FC_CONVERGED; res%message = 'converged'; exit
            end if
            if (multigrid) then
                call vcycle(hier, hier%nlev, settings, vstat, vmsg)
                if (vstat /= 0) then
                    res%status = FC_ERROR; res%message = vmsg; exit
                end if
            else
                call smooth_step(hier, 1, 'fft-rsm')
                call defect(hier, 1)
            end if
            dn = sqrt(sum(hier%lev(hier%nlev)%d**2))
            res%iterations = k
            res%history(k) = dn/unorm
            if (dn /= dn .or. dn > 1.0e6_dp*d0) then
                res%status = FC_DIVERGED
                write (res%message, '(a,es9.2,a,i0,a)') 'diverged: defect grew by ', dn/d0, ' in ', k, &
                    ' iterations (smoother '''//trim(settings%smoother)//''')'
                exit
            end if
        end do
        if (res%status == FC_NOT_CONVERGED .and. dn <= settings%tol*unorm) then
            res%status = FC_CONVERGED; res%message = 'converged'
        end if
        res%residual = dn/unorm
        if (res%iterations > 0 .and. d0 > 0 .and. dn > 0) res%factor = (dn/d0)**(1.0_dp/res%iterations)
        call trim_history(res%history, res%iterations)
        res%work_units = hier%work
        if (res%status == FC_DIVERGED .or. res%status == FC_ERROR) then
            allocate (res%p(n)); res%p = 0       ! never hand back a diverged iterate as a result
        else
            call move_alloc(hier%lev(hier%nlev)%x, res%p)
        end if
        call destroy_hierarchy(hier)
        call system_clock(t1)
        res%cpu_seconds = real(t1 - t0, dp)/rate
    end subroutine run_solver

    !> Shrink h(0:) to h(0:k), keeping the lower bound 0.
    subroutine trim_history(h, k)
        real(dp), allocatable, intent(inout) :: h(:)
        integer, intent(in) :: k
        real(dp), allocatable :: tmp(:)
        allocate (tmp(0:k))
        tmp = h(0:k)
        call move_alloc(tmp, h)
    end subroutine trim_history

    ! ---- analysis --------------------------------------------------------------------------

    !> Spectral radius of the multigrid iteration matrix (error propagation of one cycle)
    !! for `prob` and `settings`, built column by column and analysed with LAPACK dgeev
    !! (thesis Table 3.1).  n ≤ 1024.
    subroutine mg2d_spectral_radius(prob, settings, rho, stat, errmsg)
        type(fc_strip_problem), intent(in) :: prob
        type(fc_mg2d_settings), intent(in) :: settings
        real(dp), intent(out) :: rho
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(strip_hierarchy) :: hier
        real(dp), allocatable :: t(:, :)
        integer :: n, j
        rho = -1
        call check_input(prob, settings, stat, errmsg)
        if (stat /= 0) return
        n = prob%grid%nx
        if (n > 1024) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a)') 'mg2d_spectral_radius: n = ', n, ' > 1024'; return
        end if
        call build_hierarchy(prob, settings, 64, hier, stat, errmsg)
        if (stat /= 0) return
        allocate (t(n, n))
        hier%lev(hier%nlev)%r = 0
        do j = 1, n
            associate (fine => hier%lev(hier%nlev))
                fine%x = 0
                if (fine%con(j)) fine%x(j) = 1
            end associate
            call defect(hier, hier%nlev)
            call vcycle(hier, hier%nlev, settings, stat, errmsg)
            if (stat /= 0) then
                call destroy_hierarchy(hier); return
            end if
            t(:, j) = hier%lev(hier%nlev)%x
        end do
        call destroy_hierarchy(hier)
        call radius_of(t, rho, stat, errmsg)
    end subroutine mg2d_spectral_radius

    !> Spectral radius of the one-grid smoother iteration matrix I − S A_r (thesis
    !! Figs. 3.4, 3.7, 3.11).
    subroutine strip_smoother_radius(prob, smoother, rho, stat, errmsg)
        type(fc_strip_problem), intent(in) :: prob
        character(len=*), intent(in) :: smoother
        real(dp), intent(out) :: rho
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(strip_hierarchy) :: hier
        type(fc_mg2d_settings) :: s
        real(dp), allocatable :: t(:, :)
        integer :: n, j
        rho = -1
        s%smoother = smoother
        call check_input(prob, s, stat, errmsg)
        if (stat /= 0) return
        n = prob%grid%nx
        if (n > 1024) then
            stat = FC_ERR_VALUE; write (errmsg, '(a,i0,a)') 'strip_smoother_radius: n = ', n, ' > 1024'; return
        end if
        call build_hierarchy(prob, s, 1, hier, stat, errmsg)
        if (stat /= 0) return
        allocate (t(n, n))
        hier%lev(1)%r = 0
        do j = 1, n
            hier%lev(1)%x = 0
            if (hier%lev(1)%con(j)) hier%lev(1)%x(j) = 1
            call defect(hier, 1)
            call smooth_step(hier, 1, smoother)
            t(:, j) = hier%lev(1)%x
        end do
        call destroy_hierarchy(hier)
        call radius_of(t, rho, stat, errmsg)
    end subroutine strip_smoother_radius

    subroutine radius_of(t, rho, stat, errmsg)
        real(dp), intent(inout) :: t(:, :)
        real(dp), intent(out) :: rho
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp), allocatable :: wr(:), wi(:)
        call eigenvalues_general(t, wr, wi, stat, errmsg)
        if (stat /= 0) then
            rho = -1; return
        end if
        rho = maxval(hypot(wr, wi))
    end subroutine radius_of

end module fc_mg2d
