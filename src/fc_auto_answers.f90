!> Answers of the automatic layer without a grid solve (model reduction, `&solver model`):
!! the analytic elliptic Hertz solution with Cattaneo–Mindlin for `problem = 'hertz'`, and
!! Kalker's simplified theory (FASTSIM) on the Hertz ellipse for steady rolling, asked for
!! (`model = 'fastsim'`) or chosen by [[fc_auto]] when its error bound meets the target.
module fc_auto_answers
    use fc_kinds, only: dp
    use fc_hertz, only: hertz_from_approach, hertz_from_force, cattaneo_mindlin
    use fc_fastsim, only: fastsim, fc_fastsim_result
    use fc_errors, only: FC_ERR_NO_CONTACT, FC_ERR_FRICTION_BOUND, FC_ERR_MODEL_RANGE
    use fc_strings, only: fmt_real, append_line
    use fc_scene, only: fc_case
    use fc_case_result, only: fc_auto_outcome
    implicit none
    private

    public :: analytic_answer, fastsim_answer

contains

    !> problem = 'hertz': elliptic Hertz for the approach or force, and Cattaneo–Mindlin for a
    !! circular contact with a prescribed tangential force.
    subroutine analytic_answer(s, out, stat, errmsg)
        type(fc_case), intent(in) :: s
        type(fc_auto_outcome), intent(inout) :: out
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        real(dp) :: estar, q
        stat = 0; errmsg = ''
        out%analytic = .true.
        out%model = 'hertz_analytic'
        estar = out%material%g/(1 - out%material%nu)
        if (s%normal%force_prescribed) then
            out%hertz = hertz_from_force(0.5_dp/s%rx, 0.5_dp/s%ry, estar, s%normal%fn)
        else
            out%hertz = hertz_from_approach(0.5_dp/s%rx, 0.5_dp/s%ry, estar, s%normal%approach)
            if (.not. (out%hertz%fn > 0)) then
                stat = FC_ERR_NO_CONTACT
                errmsg = 'approach = '//fmt_real(s%normal%approach)//': must be > 0 for the analytic Hertz solution (no contact)'
                return
            end if
        end if
        call append_line(out%reductions, "problem = 'hertz': analytic elliptic Hertz solution, no grid")
        if (out%material%k /= 0) call append_line(out%warnings, 'K = '//fmt_real(out%material%k)//' /= 0: the analytic '// &
            'Hertz solution neglects the normal-tangential coupling of dissimilar materials')
        if (s%tangential%mu > 0 .and. s%tangential_given) then
            q = hypot(s%tangential%fx, s%tangential%fy)
            if (.not. s%tangential%force_prescribed) then
                call append_line(out%warnings, "problem = 'hertz' with prescribed shifts: Cattaneo-Mindlin needs the "// &
                    'tangential force (fx, fy); tangential part not computed')
            else if (abs(s%rx - s%ry) > 1.0e-12_dp*s%rx) then
                call append_line(out%warnings, "problem = 'hertz': Cattaneo-Mindlin needs a circular contact (rx = ry); "// &
                    'tangential part not computed')
            else if (.not. (q < s%tangential%mu*out%hertz%fn)) then
                stat = FC_ERR_FRICTION_BOUND
                errmsg = '|(fx, fy)| = '//fmt_real(q)//' must be < mu*fn = '//fmt_real(s%tangential%mu*out%hertz%fn)
                return
            else
                out%cattaneo = cattaneo_mindlin(out%hertz%a, out%hertz%p0, out%hertz%fn, s%tangential%mu, q, out%material%g, &
                    out%material%nu)
                out%has_cattaneo = .true.
                out%fx = s%tangential%fx; out%fy = s%tangential%fy
                call append_line(out%reductions, 'circular contact with a tangential force: analytic Cattaneo-Mindlin')
            end if
        end if
        out%estimate = 0
    end subroutine analytic_answer

    !> model = 'fastsim': elliptic Hertz for the normal problem and Kalker's simplified theory
    !! (FASTSIM, 200 × 200 strips) for the creep forces of steady rolling.
    subroutine fastsim_answer(s, out, stat, errmsg)
        type(fc_case), intent(in) :: s
        type(fc_auto_outcome), intent(inout) :: out
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_fastsim_result) :: fr
        real(dp) :: estar
        stat = 0; errmsg = ''
        out%analytic = .true.
        out%model = 'fastsim'
        estar = out%material%g/(1 - out%material%nu)
        if (s%normal%force_prescribed) then
            out%hertz = hertz_from_force(0.5_dp/s%rx, 0.5_dp/s%ry, estar, s%normal%fn)
        else
            out%hertz = hertz_from_approach(0.5_dp/s%rx, 0.5_dp/s%ry, estar, s%normal%approach)
        end if
        if (.not. (out%hertz%fn > 0)) then
            stat = FC_ERR_NO_CONTACT
            errmsg = 'approach = '//fmt_real(s%normal%approach)//': must be > 0 (no contact)'; return
        end if
        call fastsim(out%hertz%a, out%hertz%b, out%hertz%fn, s%tangential%mu, out%material%g, out%material%nu, &
                     s%tangential%xi, s%tangential%eta, s%tangential%phi, 200, 200, fr, stat, errmsg)
        if (stat /= 0) then
            stat = FC_ERR_MODEL_RANGE; return
        end if
        out%fx = fr%fx; out%fy = fr%fy; out%mz = fr%mz
        call append_line(out%reductions, "model = 'fastsim': elliptic Hertz and Kalker's simplified theory (FASTSIM), no grid")
        if (out%material%k /= 0) call append_line(out%warnings, 'K = '//fmt_real(out%material%k)//' /= 0: FASTSIM and the '// &
            'analytic Hertz solution neglect the normal-tangential coupling')
        out%estimate = 0
    end subroutine fastsim_answer

end module fc_auto_answers
