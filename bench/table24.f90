!> fastcontact-table24: the discrete error of thesis Table 2.4 (Hertz Test I, §2.5.1).
!!
!! For each grid n×n, 8² … 256², the normal problem with prescribed approach 0.1091 is solved
!! to tol 1e−10 by BCCG (the discrete solution p_h), and p_h is compared with the analytic
!! Hertz pressure p at the element centres.  The RMS difference is printed over three sets:
!!
!!   contact  the contact elements, p_h > 0 (the norm of the thesis' Table 2.4)
!!   union    elements in the numerical or the analytic contact area
!!   all      every element of the potential contact area (doc/benchmarks.md `error`)
!!
!! next to the thesis' values.  Usage: fastcontact-table24 (no arguments; about a second in
!! release).  The output is the table of doc/multigrid.md, "Table 2.4".
program fastcontact_table24
    use fc_kinds, only: dp, msg_len, status_name, FC_CONVERGED
    use fc_geometry, only: fc_grid, make_grid, quadratic_gap
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, &
        solve_normal
    use fc_hertz, only: fc_hertz_solution, hertz_from_approach
    implicit none

    ! Hertz Test I (thesis §2.5.1)
    real(dp), parameter :: rx = 300, ry = 163, approach = 0.1091_dp
    real(dp), parameter :: xmin = -10, xmax = 10, ymin = -6, ymax = 6
    integer, parameter :: sizes(6) = [8, 16, 32, 64, 128, 256]
    real(dp), parameter :: thesis(6) = [45.29_dp, 27.69_dp, 16.59_dp, 6.77_dp, 3.70_dp, 1.97_dp]

    type(fc_material) :: mat
    type(fc_hertz_solution) :: hz
    type(fc_grid) :: grid
    type(fc_normal_operator) :: nop
    type(fc_normal_settings) :: set
    type(fc_normal_result) :: res
    real(dp), allocatable :: h0(:, :), pa(:, :), d2(:, :)
    character(len=msg_len) :: msg
    integer :: k, n, i, j, stat
    logical, allocatable :: num_c(:, :), ana_c(:, :)

    mat%g1 = 82000; mat%g2 = 82000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
    call combine_material(mat, stat, msg)
    hz = hertz_from_approach(0.5_dp/rx, 0.5_dp/ry, mat%g/(1 - mat%nu), approach)
    set%solver = 'bccg'; set%tol = 1.0e-10_dp
    write (*, '(a)') 'Table 2.4, Hertz Test I: RMS of p_h - p_Hertz [N/mm^2] (BCCG, tol 1e-10)'
    write (*, '(a8,a8,3a12,a10,a8,a8)') 'grid', 'h', 'contact', 'union', 'all', 'thesis', 'ncon', 'status'
    do k = 1, size(sizes)
        n = sizes(k)
        call make_grid(grid, n, n, xmin, xmax, ymin, ymax, stat, msg)
        if (stat /= 0) error stop trim(msg)
        h0 = quadratic_gap(grid, rx, ry)
        call build_normal_operator(nop, mat, grid)
        call solve_normal(nop, h0, set, res, stat, msg, approach=approach)
        if (stat /= 0) error stop trim(msg)
        allocate (pa(n, n))
        do j = 1, n
            do i = 1, n
                pa(i, j) = hz%pressure(grid%x(i), grid%y(j))
            end do
        end do
        d2 = (res%pn - pa)**2
        num_c = res%pn > 0
        ana_c = pa > 0
        write (*, '(i4,"^2",2x,f8.4,3f12.2,f10.2,i8,2x,a)') n, max(grid%dx, grid%dy), rms(d2, num_c), &
            rms(d2, num_c .or. ana_c), sqrt(sum(d2)/size(d2)), thesis(k), res%ncon, &
            trim(status_name(res%status))
        if (res%status /= FC_CONVERGED) write (*, '(a)') '  '//trim(res%message)
        deallocate (pa)
        call nop%destroy()
    end do

contains

    pure real(dp) function rms(sq, mask)
        real(dp), intent(in) :: sq(:, :)
        logical, intent(in) :: mask(:, :)
        rms = sqrt(sum(sq, mask=mask)/max(1, count(mask)))
    end function rms

end program fastcontact_table24
