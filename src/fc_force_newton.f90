!> Outer loop for prescribed tangential forces (Fx, Fy): find the shift or creepages
!! x = (ξ, η) at which the inner solver's forces equal the prescribed ones.  A Broyden
!! iteration on the 2×2 Jacobian dF/dx, safeguarded by step halving; the inner tolerance
!! follows the force error (inner solves far from the answer need less accuracy).  Used by
!! the shift problem (fc_tangcg) and steady rolling (fc_rolling).
!!
!! Reverse communication, so that the caller keeps its own solver, results and warm starts:
!!
!!     call nw%start(x0, jac0, tol, hypot(fx, fy), flimit)
!!     do
!!         solve at nw%x_trial with tolerance nw%tol_inner, forces F → r = F − (fx, fy)
!!         call nw%update(r, accepted, done, iterations, matvecs, cpu_seconds)
!!         if (accepted) keep this solve as the current result
!!         if (done) exit
!!     end do
!!     nw%converged, nw%outer, nw%r and the inner solves' totals
!!
!! Force tolerance tol·flimit [N]; at most 60 outer steps of at most 31 trial points each
!! (plus two for a difference Jacobian, below).
!!
!! Near saturation (|F| → μ·Fn) the forces hardly change with the size of x but strongly with
!! its direction; a Broyden update across a step there can turn the Jacobian so far that the
!! next direction points away from the answer and the step is halved to nothing (random
!! creep-force sweeps at 0.95·μFn with spin, doc/rolling.md).  So when a direction's full
!! step and two halvings are all rejected, the Jacobian is measured again at the current
!! iterate by differences (two more solves, x + h·e1 and x + h·e2, h = 2 % of |x| or of the
!! creepage scale flimit/|J0|), once per iterate, and the direction taken anew.
module fc_force_newton
    use fc_kinds, only: dp
    implicit none
    private

    integer, parameter :: max_outer = 60, max_halvings = 30

    !> State of one force loop (units of x: those of the caller's shift or creepages).
    type, public :: fc_force_newton_t
        real(dp) :: x_trial(2) = 0      !! point the caller must evaluate next
        real(dp) :: tol_inner = 0       !! tolerance for that inner solve
        real(dp) :: r(2) = 0            !! force residual F − F_prescribed at the current iterate [N]
        integer :: outer = 0            !! outer (Broyden) steps taken
        logical :: converged = .false.  !! |r| ≤ tol·flimit with the inner solve at tol
        integer :: iterations = 0       !! inner-solver iterations summed over every trial point
        integer :: matvecs = 0          !! inner-solver products summed over every trial point
        real(dp) :: cpu_seconds = 0     !! inner-solver CPU seconds summed over every trial point
        real(dp), private :: x(2) = 0, dx(2) = 0, jac(2, 2) = 0, step = 1
        real(dp), private :: tol = 0, flimit = 1, ftol = 0
        integer, private :: halvings = 0
        logical, private :: first = .true.
        logical, private :: reeval = .false.   !! the trial re-solves the current iterate more tightly
        integer, private :: fd_stage = 0       !! 1, 2: the trial is x + h·e1, x + h·e2 (difference Jacobian)
        logical, private :: refreshed = .false.  !! the Jacobian was measured at the current iterate
        real(dp), private :: fd_h = 0, fd_r1(2) = 0, xscale = 0
    contains
        procedure :: start => newton_start
        procedure :: update => newton_update
    end type fc_force_newton_t

contains

    !> Begin at x0 with the Jacobian guess jac0 [N per unit of x]; tol is the final relative
    !! tolerance, fref = |(Fx, Fy)| and flimit = μ·Fn [N].
    subroutine newton_start(self, x0, jac0, tol, fref, flimit)
        class(fc_force_newton_t), intent(inout) :: self
        real(dp), intent(in) :: x0(2), jac0(2, 2), tol, fref, flimit
        self%x = x0; self%x_trial = x0; self%jac = jac0
        self%tol = tol; self%flimit = flimit; self%ftol = tol*flimit
        self%tol_inner = max(tol, min(1.0e-3_dp, 0.1_dp*fref/flimit))
        self%outer = 0; self%halvings = 0; self%step = 1
        self%converged = .false.; self%first = .true.; self%reeval = .false.
        self%fd_stage = 0; self%refreshed = .false.
        ! creepage (or shift) at which the initial Jacobian reaches the friction bound
        self%xscale = flimit/max(maxval(abs(jac0)), tiny(1.0_dp))
        self%r = 0
        self%iterations = 0; self%matvecs = 0; self%cpu_seconds = 0
    end subroutine newton_start

    !> Take the residual of the solve at x_trial and that solve's cost.  `accepted`: that
    !! solve is the new current iterate; `done`: stop (converged, singular Jacobian, or 60
    !! outer steps).
    subroutine newton_update(self, r_trial, accepted, done, iterations, matvecs, cpu_seconds)
        class(fc_force_newton_t), intent(inout) :: self
        real(dp), intent(in) :: r_trial(2)
        logical, intent(out) :: accepted, done
        integer, intent(in), optional :: iterations, matvecs
        real(dp), intent(in), optional :: cpu_seconds
        real(dp) :: dr(2), dx(2)
        done = .false.
        if (present(iterations)) self%iterations = self%iterations + iterations
        if (present(matvecs)) self%matvecs = self%matvecs + matvecs
        if (present(cpu_seconds)) self%cpu_seconds = self%cpu_seconds + cpu_seconds
        if (self%first) then
            self%first = .false.
            self%r = r_trial; accepted = .true.
            self%outer = 1
            call next_direction(self, done)
            return
        end if
        if (self%fd_stage == 1) then
            ! the difference Jacobian: first column taken, the second trial next
            accepted = .false.
            self%fd_r1 = r_trial
            self%x_trial = self%x + [0.0_dp, self%fd_h]
            self%fd_stage = 2
            return
        else if (self%fd_stage == 2) then
            accepted = .false.
            self%jac(:, 1) = (self%fd_r1 - self%r)/self%fd_h
            self%jac(:, 2) = (r_trial - self%r)/self%fd_h
            self%fd_stage = 0
            call next_direction(self, done)
            return
        end if
        if (norm_2(r_trial) < norm_2(self%r) .or. self%halvings == max_halvings .or. self%reeval) then
            self%reeval = .false.
            ! Broyden update of the Jacobian with the step actually taken
            accepted = .true.
            dr = r_trial - self%r
            dx = self%x_trial - self%x
            if (dot_product(dx, dx) > 0) self%jac = self%jac + &
                spread(dr - matmul(self%jac, dx), 2, 2)*spread(dx, 1, 2)/dot_product(dx, dx)
            self%x = self%x_trial; self%r = r_trial
            self%refreshed = .false.
            self%outer = self%outer + 1
            if (self%outer > max_outer) then
                done = .true.; return
            end if
            call next_direction(self, done)
        else
            accepted = .false.
            self%halvings = self%halvings + 1
            if (self%halvings == 3 .and. .not. self%refreshed) then
                ! three trials of this direction rejected: measure the Jacobian here instead
                self%refreshed = .true.
                self%fd_h = 0.02_dp*max(norm_2(self%x), self%xscale)
                self%x_trial = self%x + [self%fd_h, 0.0_dp]
                self%fd_stage = 1
                return
            end if
            self%step = self%step/2
            self%x_trial = self%x + self%step*self%dx
        end if
    end subroutine newton_update

    !> At the current iterate: stop if converged, else the Newton direction of the current
    !! Jacobian and its first trial point (full step).
    subroutine next_direction(self, done)
        type(fc_force_newton_t), intent(inout) :: self
        logical, intent(out) :: done
        real(dp) :: det
        done = .false.
        if (norm_2(self%r) <= self%ftol .and. self%tol_inner <= self%tol) then
            self%converged = .true.; done = .true.; return
        end if
        if (norm_2(self%r) <= self%ftol) then
            ! the force tolerance met by a loosely solved iterate: solve the same point to the
            ! final tolerance before stepping on (else trials at that accuracy, whose residual
            ! includes the loose solve's force error, were all rejected and the step halved to
            ! nothing: doc/rolling.md); no step, so no Broyden update either
            self%tol_inner = self%tol
            self%x_trial = self%x; self%step = 1; self%halvings = 0
            self%reeval = .true.
            return
        end if
        self%tol_inner = max(self%tol, min(self%tol_inner, 0.01_dp*norm_2(self%r)/self%flimit))
        det = self%jac(1, 1)*self%jac(2, 2) - self%jac(1, 2)*self%jac(2, 1)
        if (det == 0) then
            done = .true.; return
        end if
        self%dx = -[self%jac(2, 2)*self%r(1) - self%jac(1, 2)*self%r(2), &
                    -self%jac(2, 1)*self%r(1) + self%jac(1, 1)*self%r(2)]/det
        self%step = 1; self%halvings = 0
        self%x_trial = self%x + self%dx
    end subroutine next_direction

    !> |v| of a 2-vector without underflow or overflow of the squares (gfortran's norm2
    !! squares unscaled: a residual of 1e−200 N had the norm 0).
    pure real(dp) function norm_2(v)
        real(dp), intent(in) :: v(2)
        norm_2 = hypot(v(1), v(2))
    end function norm_2

end module fc_force_newton
