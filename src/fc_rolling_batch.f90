!> Rolling sequences of the batch driver: creep-force curves (steady rolling swept over one
!! loading value, each point warm-started from the previous one) and transient rolling
!! (steps of travelled distance dq carrying u', p' from step to step), both through the
!! orchestrator [[solve_contact]].  One table row per point or step.
module fc_rolling_batch
    use fc_kinds, only: dp, i8, FC_CONVERGED, status_name
    use fc_geometry, only: fc_grid
    use fc_influence, only: fc_material
    use fc_contact, only: fc_contact_operators, fc_contact_loading, fc_contact_settings, fc_contact_result, &
        fc_contact_state, solve_contact, FC_PROBLEM_ROLLING, FC_PROBLEM_TANGENTIAL, FC_TRANSIENT_ROLLING
    use fc_scene, only: fc_case
    implicit none
    private

    !> Columns of a creep-force curve (`sweep`) and of a transient run (`steps`).
    character(len=*), parameter, public :: sweep_header = &
        'value,xi,eta,phi,fx,fy,mz,fx_mufn,fy_mufn,nadh,nslip,iterations,seconds,status'
    character(len=*), parameter, public :: steps_header = &
        'step,distance,fx,fy,mz,fx_mufn,fy_mufn,nadh,nslip,iterations,seconds,status'

    public :: is_rolling_sequence, rolling_sequence, write_sequence_csv

contains

    !> Whether the case is a sequence (creep-force sweep or transient rolling).
    pure logical function is_rolling_sequence(s)
        type(fc_case), intent(in) :: s
        is_rolling_sequence = s%rolling%transient .or. (s%problem == FC_PROBLEM_ROLLING .and. len_trim(s%rolling%sweep) > 0)
    end function is_rolling_sequence

    !> Run the sequence of case `s` with the loading and settings prepared for one solve
    !! (`load%problem` = FC_PROBLEM_ROLLING for a sweep; the transient run sets its own
    !! shifts creepage·dq).  `res`: the last point or step; `rows`: one row per point/step
    !! (last column: the status code; written as its name).  The sequence
    !! stops at the first point or step that does not converge.
    subroutine rolling_sequence(s, ops, grid, mat, h0, load_in, settings, res, rows, stat, errmsg)
        type(fc_case), intent(in) :: s
        type(fc_contact_operators), intent(inout) :: ops
        type(fc_grid), intent(in) :: grid
        type(fc_material), intent(in) :: mat
        real(dp), intent(in) :: h0(:, :)
        type(fc_contact_loading), intent(in) :: load_in
        type(fc_contact_settings), intent(in) :: settings
        type(fc_contact_result), intent(out) :: res
        real(dp), allocatable, intent(out) :: rows(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        type(fc_contact_loading) :: load
        type(fc_contact_state) :: state
        real(dp) :: dq, value, mufn, secs
        integer :: k, n
        integer(i8) :: t0, t1, rate
        stat = 0; errmsg = ''
        load = load_in
        state%warm_start = .true.
        if (s%rolling%transient) then
            dq = s%rolling%dq
            if (dq == 0) dq = grid%dx
            n = s%rolling%nsteps
            if (n == 0) n = max(1, ceiling(4*(grid%xmax - grid%xmin)/dq))
            load%problem = FC_PROBLEM_TANGENTIAL
            load%transient = FC_TRANSIENT_ROLLING
            load%dq = dq
            load%tangential%force_prescribed = .false.
            load%tangential%xi = s%tangential%xi*dq; load%tangential%eta = s%tangential%eta*dq
            load%tangential%phi = s%tangential%phi*dq
            allocate (rows(n, 12))
        else
            n = s%rolling%sweep_n
            allocate (rows(n, 14))
        end if
        rows = 0
        do k = 1, n
            if (.not. s%rolling%transient) then
                value = s%rolling%sweep_from + (s%rolling%sweep_to - s%rolling%sweep_from)*(k - 1)/real(n - 1, dp)
                select case (s%rolling%sweep)
                case ('xi'); load%tangential%xi = value
                case ('eta'); load%tangential%eta = value
                case ('phi'); load%tangential%phi = value
                case ('fx'); load%tangential%fx = value
                case ('fy'); load%tangential%fy = value
                end select
            end if
            call system_clock(t0, rate)
            call solve_contact(ops, grid, mat, h0, load, settings, res, stat, errmsg, state=state)
            call system_clock(t1)
            if (stat /= 0) then
                rows = rows(1:k - 1, :)
                return
            end if
            secs = real(t1 - t0, dp)/rate
            mufn = load%tangential%mu*res%normal%fn
            if (.not. mufn > 0) mufn = 1
            associate (t => res%tangential)
                if (s%rolling%transient) then
                    rows(k, :) = [real(k, dp), k*dq, t%fx, t%fy, t%mz, t%fx/mufn, t%fy/mufn, real(t%nadh, dp), &
                                  real(t%nslip, dp), real(t%iterations, dp), secs, real(res%status, dp)]
                else
                    rows(k, :) = [value, t%xi, t%eta, t%phi, t%fx, t%fy, t%mz, t%fx/mufn, t%fy/mufn, real(t%nadh, dp), &
                                  real(t%nslip, dp), real(t%iterations, dp), secs, real(res%status, dp)]
                end if
            end associate
            if (res%status /= FC_CONVERGED) then
                rows = rows(1:k, :)
                exit
            end if
        end do
        if (s%rolling%transient) then
            ! report the creepages (the steps used creepage·dq as shifts)
            res%tangential%xi = s%tangential%xi; res%tangential%eta = s%tangential%eta
            res%tangential%phi = s%tangential%phi
        end if
    end subroutine rolling_sequence

    !> Write the rows of a sequence as CSV with `header`.
    subroutine write_sequence_csv(path, header, rows, stat, errmsg)
        character(len=*), intent(in) :: path, header
        real(dp), intent(in) :: rows(:, :)
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u, k, j, n
        character(len=256) :: iomsg
        character(len=32) :: cell
        character(len=:), allocatable :: line
        stat = 0; errmsg = ''
        open (newunit=u, file=path, status='replace', action='write', iostat=stat, iomsg=iomsg)
        if (stat /= 0) then
            errmsg = "cannot write '"//trim(path)//"': "//trim(iomsg); return
        end if
        write (u, '(a)') header
        n = size(rows, 2)
        do k = 1, size(rows, 1)
            line = ''
            do j = 1, n
                if (j == n) then
                    cell = status_name(nint(rows(k, j)))
                else if ((j >= n - 4 .and. j <= n - 2) .or. (j == 1 .and. header(1:4) == 'step')) then
                    write (cell, '(i0)') nint(rows(k, j))
                else
                    write (cell, '(es15.7)') rows(k, j)
                end if
                line = line//trim(adjustl(cell))
                if (j < n) line = line//','
            end do
            write (u, '(a)') line
        end do
        close (u)
    end subroutine write_sequence_csv

end module fc_rolling_batch
