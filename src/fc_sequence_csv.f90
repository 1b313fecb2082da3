!> Tables of the rolling sequences ([[rolling_sequence]] in [[fc_contact]]): one CSV row per
!! point of a creep-force curve (`NAME_creep.csv`) or per step of a transient run
!! (`NAME_steps.csv`); columns in doc/rolling.md.
module fc_sequence_csv
    use fc_kinds, only: dp, status_name
    implicit none
    private

    !> Columns of a creep-force curve (`sweep`) and of a transient run (`steps`).
    character(len=*), parameter, public :: sweep_header = &
        'value,xi,eta,phi,fx,fy,mz,fx_mufn,fy_mufn,dissipation,nadh,nslip,iterations,seconds,status'
    character(len=*), parameter, public :: steps_header = &
        'step,distance,fx,fy,mz,fx_mufn,fy_mufn,dissipation,nadh,nslip,iterations,seconds,status'

    public :: write_sequence_csv

contains

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

end module fc_sequence_csv
