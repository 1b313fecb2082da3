!> Experiment for thesis Table 2.8: NORM (active set + CG) with few CG steps per active-set
!! iteration on rough punch case 3 (δ = 0.25).  Every variant is fc_norm's own NORM
!! (solve_normal, solver 'norm', `inner_maxit` CG steps per active-set step); the readings of
!! thesis §2.3/§2.4.1 that differ from ours are the setting `norm_reading` of fc_normal_settings.
!!
!! Usage: fastcontact-norm-table28 N SEED VARIANT [INNER_MAXIT] [MAXIT] [VERBOSE] [APPROACH]
!!   VARIANT  lib, a: ours (warm-started CG, drop negatives and add penetrations in one step)
!!            libf: ours with the force prescribed (the force of the BCCG solution)
!!            b:   add penetrating elements only in an iteration that dropped no element
!!            c:   CG restarted from p = 0 in every active-set iteration
!!            d:   dropped elements keep their negative pressure (p not projected)
!!            e:   add elements with e <= 0 (thesis step 4.b) instead of e < 0
!!            f:   CG not restarted across active-set iterations: the search direction and
!!                 ‖r‖² of the previous iteration are kept (direction masked to the new set)
!!            g:   u = A p recomputed after the negative pressures are zeroed, before the
!!                 penetration test (step 4.b with the updated pressures)
!!   SEED 2015 is the default surface of fc_rough_params; APPROACH defaults to 0.25 (case 3).
!! Prints one summary line 'RESULT ...' and, with VERBOSE = 1, the residual per iteration.
program norm_table28
    use fc_kinds
    use fc_geometry, only: fc_grid, make_grid, punch_rough_gap, fc_rough_params
    use fc_influence, only: fc_material, combine_material
    use fc_norm, only: fc_normal_operator, fc_normal_settings, fc_normal_result, build_normal_operator, &
        solve_normal
    implicit none
    real(dp) :: approach, fn
    integer :: n, seed, inner_max, maxit, verbose, st
    character(len=16) :: variant
    character(len=64) :: arg
    type(fc_material) :: mat
    type(fc_grid) :: grid
    type(fc_rough_params) :: par
    type(fc_normal_operator) :: nop
    type(fc_normal_settings) :: set
    type(fc_normal_result) :: res
    real(dp), allocatable :: h0(:, :)
    character(len=msg_len) :: msg
    integer :: k, t0, t1, rate

    n = int_arg(1, 128); seed = int_arg(2, 2015)
    call get_command_argument(3, arg); variant = 'lib'
    if (len_trim(arg) > 0) variant = trim(arg)
    inner_max = int_arg(4, 4); maxit = int_arg(5, 200); verbose = int_arg(6, 0)
    approach = 0.25_dp
    call get_command_argument(7, arg)
    if (len_trim(arg) > 0) read (arg, *) approach

    mat%g1 = 1.0e30_dp; mat%g2 = 40000; mat%nu1 = 0.28_dp; mat%nu2 = 0.28_dp
    call combine_material(mat, st, msg)
    call make_grid(grid, n, n, -6.0_dp, 6.0_dp, -5.0_dp, 5.0_dp, st, msg)
    allocate (h0(n, n))
    par%seed = seed
    call punch_rough_gap(grid, 8.97_dp, par, h0)
    call build_normal_operator(nop, mat, grid)
    set%solver = 'norm'; set%inner_maxit = inner_max; set%tol = 1.0e-6_dp; set%maxit = maxit
    select case (variant)
    case ('lib', 'a', 'libf')
        set%norm_reading = ''
    case ('b'); set%norm_reading = 'add_if_no_drop'
    case ('c'); set%norm_reading = 'restart'
    case ('d'); set%norm_reading = 'keep_negative'
    case ('e'); set%norm_reading = 'add_on_zero'
    case ('f'); set%norm_reading = 'continue_cg'
    case ('g'); set%norm_reading = 'recompute_u'
    case default
        write (*, '(a)') 'fastcontact-norm-table28: VARIANT must be lib, libf or a-g, got '//trim(variant)
        stop 1
    end select
    call system_clock(t0, rate)
    if (variant == 'libf') then
        ! prescribed force: the force of the BCCG solution for this approach
        set%solver = 'bccg'; set%tol = 1.0e-9_dp
        call solve_normal(nop, h0, set, res, st, msg, approach=approach)
        set%solver = 'norm'; set%tol = 1.0e-6_dp
        fn = res%fn
        call solve_normal(nop, h0, set, res, st, msg, fn=fn)
    else
        call solve_normal(nop, h0, set, res, st, msg, approach=approach)
    end if
    call system_clock(t1)
    if (st /= 0) then
        write (*, '(a)') 'fastcontact-norm-table28: '//trim(msg)
        stop 1
    end if
    write (*, '(a,i5,i6,1x,a4,i3,i5,1x,a,i4,i8,es11.3,f8.2,1x,a)') 'RESULT ', n, seed, variant, inner_max, &
        maxit, status_name(res%status), res%outer_iterations, res%ncon, res%residual, &
        real(t1 - t0, dp)/rate, trim(res%message)
    if (verbose == 1) then
        do k = 1, size(res%history)
            write (*, '(a,i5,es12.4)') 'HIST ', k, res%history(k)
        end do
    end if
    call nop%destroy()

contains

    integer function int_arg(i, default) result(v)
        integer, intent(in) :: i, default
        character(len=64) :: a
        integer :: ios
        call get_command_argument(i, a)
        v = default
        if (len_trim(a) > 0) then
            read (a, *, iostat=ios) v
            if (ios /= 0) v = default
        end if
    end function int_arg

end program norm_table28
