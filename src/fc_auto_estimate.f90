!> The error estimate of the accuracy target of [[fc_auto]]: the target quantities of the
!! grids visited, the Richardson-type estimate of the finest grid's relative error and the
!! coarsest grid certified to meet the target (the rule and its calibration are stated in
!! [[fc_auto]]'s header and doc/benchmarks.md).  Public so that fastcontact-bench-auto can
!! replay the estimator on reference sequences.
module fc_auto_estimate
    use fc_kinds, only: dp
    use fc_scene, only: fc_case
    use fc_case_result, only: fc_level
    implicit none
    private

    real(dp), parameter, public :: estimate_safety = 2.0_dp  !! safety factor of the Richardson estimate
    !> Safety factor when the observed ratio r = d_{k−1}/d_k lies in [`h2_ratio_low`,
    !! `h2_ratio_high`], i.e. the sequence is in the O(h²) regime (r = 4 ± 50 %)
    real(dp), parameter, public :: estimate_safety_h2 = 1.5_dp
    real(dp), parameter, public :: h2_ratio_low = 3.0_dp, h2_ratio_high = 6.0_dp

    public :: richardson_estimate, level_estimate, certify_coarsest, target_quantities

contains

    !> Estimate of the last level's relative error over the target quantities (the largest
    !! over fn or approach, the tangential quantity and, with `target_pmax`, pmax).  Public so
    !! that fastcontact-bench-auto can replay it on reference sequences from every given grid.
    subroutine level_estimate(levels, s, tang, noise, est, ratio, monotone, qname, factors)
        type(fc_level), intent(in) :: levels(:)
        type(fc_case), intent(in) :: s
        logical, intent(in) :: tang
        real(dp), intent(in) :: noise
        real(dp), intent(out) :: est, ratio
        logical, intent(out) :: monotone
        character(len=*), intent(out) :: qname
        real(dp), intent(in), optional :: factors(3)  !! see [[richardson_estimate]]
        real(dp), allocatable :: q(:, :)
        real(dp) :: e, r
        logical :: mono
        integer :: k
        call target_quantities(levels, s, tang, q, qname)
        est = 0; ratio = 0; monotone = .true.
        do k = 1, size(q, 2)
            call richardson_estimate(q(:, k), noise, e, r, mono, factors)
            if (e > est) then
                est = e; ratio = r
            end if
            monotone = monotone .and. mono
        end do
    end subroutine level_estimate

    !> The target quantities of each level, relative to the last level: fn (approach
    !! prescribed) or the approach (fn prescribed); the tangential quantity (signed projection
    !! on the last level's direction of (xi, eta) when forces are prescribed, of (Fx, Fy)
    !! relative to max(|Ft|, 0.1·mu·Fn) when shifts are); pmax with `target_pmax`.
    subroutine target_quantities(levels, s, tang, q, qname)
        type(fc_level), intent(in) :: levels(:)
        type(fc_case), intent(in) :: s
        logical, intent(in) :: tang
        real(dp), allocatable, intent(out) :: q(:, :)
        character(len=*), intent(out) :: qname
        real(dp) :: scale, norm_t
        integer :: n
        n = size(levels)
        allocate (q(n, 0))
        if (s%normal%force_prescribed) then
            q = reshape([q, levels%approach/abs(levels(n)%approach)], [n, size(q, 2) + 1]); qname = 'approach'
        else
            q = reshape([q, levels%fn/abs(levels(n)%fn)], [n, size(q, 2) + 1]); qname = 'fn'
        end if
        if (tang) then
            if (s%tangential%force_prescribed) then
                scale = max(hypot(levels(n)%xi, levels(n)%eta), tiny(1.0_dp))
                q = reshape([q, (levels%xi*levels(n)%xi + levels%eta*levels(n)%eta)/scale**2], [n, size(q, 2) + 1])
                qname = trim(qname)//' xi_eta'
            else
                norm_t = max(hypot(levels(n)%fx, levels(n)%fy), tiny(1.0_dp))
                scale = max(norm_t, 0.1_dp*s%tangential%mu*levels(n)%fn, tiny(1.0_dp))
                q = reshape([q, (levels%fx*levels(n)%fx + levels%fy*levels(n)%fy)/(norm_t*scale)], [n, size(q, 2) + 1])
                qname = trim(qname)//' fx_fy'
            end if
        end if
        if (s%target_pmax) then
            q = reshape([q, levels%pmax/abs(levels(n)%pmax)], [n, size(q, 2) + 1]); qname = trim(qname)//' pmax'
        end if
    end subroutine target_quantities

    !> The coarsest of `levels` certified to meet `target`, once the finest (last) level has
    !! the error estimate `est`: level j's error is at most max_q |q_j − q_n| + est (triangle
    !! inequality through the finest grid), so this holds whenever the estimate does.  The
    !! solve cannot stop there (seeing grid n is what certifies it), but the grid is the answer
    !! to "which grid does this scene need" for later solves of the same scene.
    subroutine certify_coarsest(levels, s, tang, est, target, j, bound)
        type(fc_level), intent(in) :: levels(:)
        type(fc_case), intent(in) :: s
        logical, intent(in) :: tang
        real(dp), intent(in) :: est, target
        integer, intent(out) :: j                     !! level index (0: none, est > target)
        real(dp), intent(out) :: bound                !! certified relative error bound of level j
        real(dp), allocatable :: q(:, :)
        character(len=64) :: qname
        integer :: n
        n = size(levels)
        j = 0; bound = -1
        if (n == 0 .or. est > target) return
        call target_quantities(levels, s, tang, q, qname)
        do j = 1, n
            bound = maxval(abs(q(j, :) - q(n, :))) + est
            if (bound <= target) return
        end do
        j = n; bound = est
    end subroutine certify_coarsest

    !> Relative error estimate of the last of the values `q` (already divided by the last
    !! value's magnitude, or distances to the last value) on grids refined by two; see the
    !! module header.  `ratio`: observed d_{k−1}/d_k (0 with two grids); `monotone`: false
    !! when the differences change sign or grow.
    !! `factors` = [two-grid factor f2 (est_2 = f2·|d_2|), safety s, safety in the O(h²) band]
    !! replaces the package's [`estimate_safety`, `estimate_safety`, `estimate_safety_h2`];
    !! only fastcontact-bench-auto sets it, to measure the alternatives on the same data.
    pure subroutine richardson_estimate(q, noise, est, ratio, monotone, factors)
        real(dp), intent(in) :: q(:)
        real(dp), intent(in) :: noise
        real(dp), intent(out) :: est, ratio
        logical, intent(out) :: monotone
        real(dp), intent(in), optional :: factors(3)
        real(dp) :: d, dprev, f(3)
        integer :: n
        f = [estimate_safety, estimate_safety, estimate_safety_h2]
        if (present(factors)) f = factors
        n = size(q)
        est = -1; ratio = 0; monotone = .true.
        if (n < 2) return
        d = q(n) - q(n - 1)
        if (n == 2) then
            ! no rate is known yet: assume only that the error at least halves per level (the
            ! slowest ratio measured); 2|d|/3 from the O(h²) rate failed whenever the two grids
            ! happened to err alike (Cattaneo from 32² to 64²: true error 1.4× 2|d|/3)
            est = f(1)*abs(d)
            return
        end if
        dprev = q(n - 1) - q(n - 2)
        if (abs(d) <= noise .and. abs(dprev) <= noise) then
            est = noise; ratio = 0; return
        end if
        if (abs(d) <= noise) then
            ratio = abs(dprev)/max(abs(d), tiny(1.0_dp))
            est = f(2)*max(noise, abs(dprev)/12); return
        end if
        ratio = dprev/d
        if (ratio <= 1) then
            monotone = .false.
            est = max(abs(d), abs(dprev))
        else
            est = max(abs(d)/(min(ratio, 4.0_dp) - 1), abs(dprev)/12)
            if (ratio >= h2_ratio_low .and. ratio <= h2_ratio_high) then
                est = f(3)*est
            else
                est = f(2)*est
            end if
        end if
    end subroutine richardson_estimate

end module fc_auto_estimate
