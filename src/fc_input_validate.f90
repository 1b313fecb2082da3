!> Checks of a case record ([[fc_case_input]]), one validator per namelist group; the
!! first failing check gives stat = FC_ERR_VALUE and a message naming group, key, value and
!! the limit.  Validation never changes the record: values implied by others (a cylinder's
!! y extent, a strip's single row) are derived by [[effective_record]], which the scene
!! builder uses as well.
!!
!! Size (~630 lines): one validator per group, each with the messages that name its keys,
!! values and limits; most lines are those messages.
module fc_input_validate
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fc_kinds, only: dp, i8, msg_len, max_iterations
    use fc_errors, only: FC_OK, FC_ERR_VALUE
    use fc_strings, only: fmt_int, fmt_real
    use fc_influence, only: fc_material, combine_material, rigid_modulus
    use fc_fmg_levels, only: fmg_cycle_from_name
    use fc_input, only: fc_case_input, is_given, grid_is_auto, is_tangential, strip_model_index, max_grid_elements
    use fc_limits
    use fc_threads, only: max_threads_allowed
    implicit none
    private

    character(len=4), parameter :: area_keys(6) = ['nx  ', 'ny  ', 'xmin', 'xmax', 'ymin', 'ymax']

    public :: validate_case, effective_record

contains

    !> The record with the values other keys imply: a cylinder spans its length in y (one
    !! row unless ny was given); a strip has one row; an automatic strip area gets the
    !! placeholder y extent [−50, 50] mm until it is sized.
    pure function effective_record(s) result(t)
        type(fc_case_input), intent(in) :: s
        type(fc_case_input) :: t
        t = s
        if (strip_model_index(s) > 0) then
            t%ny = 1
            return
        end if
        if (s%kind == 'cylinder') then
            t%ymin = -0.5_dp*s%length; t%ymax = 0.5_dp*s%length
            if (.not. is_given(s, 'grid', 'ny')) t%ny = 1
        end if
        if (s%kind == 'strip2d') then
            if (grid_is_auto(s) .or. s%problem == 'hertz') then
                if (.not. is_given(s, 'grid', 'ymin')) then
                    t%ymin = -50; t%ymax = 50
                end if
            else if (.not. is_given(s, 'grid', 'ny')) then
                t%ny = 1
            end if
        end if
    end function effective_record

    !> Check the values of a case, group by group; the message names group, key and value.
    subroutine validate_case(s_in, stat, errmsg, grid_limit)
        type(fc_case_input), intent(in) :: s_in
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        !> largest nx·ny accepted (default `max_grid_elements`; the distributed driver's is
        !! `max_dist_grid_elements`)
        integer(i8), intent(in), optional :: grid_limit
        type(fc_case_input) :: s
        integer(i8) :: limit
        stat = FC_OK; errmsg = ''
        limit = max_grid_elements
        if (present(grid_limit)) limit = grid_limit
        s = effective_record(s_in)
        call validate_case_group(s, errmsg)
        if (len_trim(errmsg) == 0) then
            if (strip_model_index(s) > 0) then
                call validate_strip(s, errmsg)
            else
                call validate_material(s, errmsg)
                if (len_trim(errmsg) == 0) call validate_geometry(s, errmsg)
                if (len_trim(errmsg) == 0) call validate_grid(s, limit, errmsg)
                if (len_trim(errmsg) == 0) call validate_normal(s, errmsg)
                if (len_trim(errmsg) == 0) call validate_tangential(s, errmsg)
                if (len_trim(errmsg) == 0) call validate_solver(s, errmsg)
                if (len_trim(errmsg) == 0) call validate_rolling(s, errmsg)
                if (len_trim(errmsg) == 0 .and. s%periodic) call validate_periodic(s, errmsg)
                if (len_trim(errmsg) == 0) call validate_output(s, errmsg)
            end if
        end if
        if (len_trim(errmsg) > 0) stat = FC_ERR_VALUE
    end subroutine validate_case

    !> &case: name usable as a file stem, known problem.
    subroutine validate_case_group(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (len_trim(s%name) == 0 .or. verify(trim(s%name), &
            'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.+') /= 0 .or. s%name(1:1) == '.') then
            errmsg = "&case name = '"//trim(s%name)//"': use letters, digits, '_', '-', '.', '+' only (file name)"
            return
        end if
        select case (s%problem)
        case ('normal', 'tangential', 'normal+tangential', 'hertz', 'strip_mp1', 'strip_mp2', 'strip_mp3', 'rolling', &
              'transient_rolling')
        case default
            errmsg = "&case problem = '"//trim(s%problem)//"': unknown problem; use 'normal', 'normal+tangential', "// &
                "'tangential', 'rolling', 'transient_rolling', 'hertz' or 'strip_mp1', 'strip_mp2', 'strip_mp3'"
        end select
    end subroutine validate_case_group

    !> &material: both moduli given and > 0, not both rigid, 0 ≤ ν < 0.5.
    subroutine validate_material(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (.not. is_given(s, 'material', 'g1')) then
            errmsg = '&material g1: missing required value (shear modulus of body 1; >= 1e29 for rigid)'
        else if (.not. is_given(s, 'material', 'g2')) then
            errmsg = '&material g2: missing required value (shear modulus of body 2; >= 1e29 for rigid)'
        else if (.not. real_in_range(s%g1, min_modulus, huge(1.0_dp))) then
            errmsg = '&material g1 = '//fmt_real(s%g1)//': must be > 0 (finite, >= '//fmt_limit(min_modulus)//')'
        else if (.not. real_in_range(s%g2, min_modulus, huge(1.0_dp))) then
            errmsg = '&material g2 = '//fmt_real(s%g2)//': must be > 0 (finite, >= '//fmt_limit(min_modulus)//')'
        else if (.not. (real_in_range(s%nu1, 0.0_dp, 0.5_dp) .and. s%nu1 /= 0.5_dp)) then
            errmsg = '&material nu1 = '//fmt_real(s%nu1)//': must lie in [0, 0.5)'
        else if (.not. (real_in_range(s%nu2, 0.0_dp, 0.5_dp) .and. s%nu2 /= 0.5_dp)) then
            errmsg = '&material nu2 = '//fmt_real(s%nu2)//': must lie in [0, 0.5)'
        else if (s%g1 >= rigid_modulus .and. s%g2 >= rigid_modulus) then
            errmsg = '&material g1 = '//fmt_real(s%g1)//', g2 = '//fmt_real(s%g2)//': both bodies rigid'
        else if (len_trim(s%ic_file) == 0 .and. len_trim(s%ic_file2) > 0) then
            errmsg = "&material ic_file2 = '"//trim(s%ic_file2)//"': needs ic_file (body 1) too"
        end if
    end subroutine validate_material

    !> &geometry: a known kind with its parameters (the analytic Hertz answer needs an
    !! elliptic quadratic profile).
    subroutine validate_geometry(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (.not. is_given(s, 'geometry', 'kind')) then
            errmsg = "&geometry kind: missing required value ('quadratic', 'cylinder', 'punch_rough', 'wavy', "// &
                "'strip2d', 'table')"
            return
        end if
        select case (s%kind)
        case ('quadratic', 'cylinder', 'punch_rough', 'wavy', 'strip2d', 'table')
        case default
            errmsg = "&geometry kind = '"//trim(s%kind)//"': unknown; use 'quadratic', 'cylinder', 'punch_rough', "// &
                "'wavy', 'strip2d' or 'table'"
            return
        end select
        ! every real of the group finite and bounded before any comparison below
        if (.not. all(real_in_range([s%rx, s%ry, s%diameter, s%rough%sigma, s%rough%gamma, s%amplitude, &
            s%wavelength_x, s%wavelength_y, s%length], -huge(1.0_dp), huge(1.0_dp)))) then
            errmsg = '&geometry rx = '//fmt_real(s%rx)//', ry = '//fmt_real(s%ry)//', diameter = '// &
                fmt_real(s%diameter)//', sigma = '//fmt_real(s%rough%sigma)//', gamma = '//fmt_real(s%rough%gamma)// &
                ', amplitude = '//fmt_real(s%amplitude)//', wavelength_x = '//fmt_real(s%wavelength_x)// &
                ', wavelength_y = '//fmt_real(s%wavelength_y)//', length = '//fmt_real(s%length)// &
                ': not all finite numbers'
            return
        end if
        if (s%problem == 'hertz') then
            if (s%kind /= 'quadratic' .or. .not. (s%rx > 0 .and. s%ry > 0)) then
                errmsg = "&case problem = 'hertz': needs &geometry kind = 'quadratic' with rx > 0 and ry > 0 (got kind = '"// &
                    trim(s%kind)//"', rx = "//fmt_real(s%rx)//', ry = '//fmt_real(s%ry)//')'
                return
            end if
        end if
        if (s%kind == 'cylinder' .and. .not. (s%length >= min_length .and. s%length <= 2*max_length)) then
            errmsg = '&geometry length = '//fmt_real(s%length)//": must be > 0 for kind = 'cylinder' "// &
                '(cylinder length along y [mm], at least '//fmt_limit(min_length)//', at most '// &
                fmt_limit(2*max_length)//')'
            return
        end if
        select case (s%kind)
        case ('quadratic', 'strip2d', 'cylinder')
            if (.not. is_given(s, 'geometry', 'rx')) then
                errmsg = "&geometry rx: missing required value for kind = '"//trim(s%kind)//"'"
            else if (.not. (s%rx >= min_radius .and. s%rx <= max_radius)) then
                errmsg = '&geometry rx = '//fmt_real(s%rx)//': must be > 0 (at least '//fmt_limit(min_radius)// &
                    ' mm, at most '//fmt_limit(max_radius)//' mm)'
            else if (s%kind == 'quadratic') then
                if (.not. is_given(s, 'geometry', 'ry')) then
                    errmsg = "&geometry ry: missing required value for kind = 'quadratic' (0: flat in y)"
                else if (.not. (s%ry == 0 .or. (s%ry >= min_radius .and. s%ry <= max_radius))) then
                    errmsg = '&geometry ry = '//fmt_real(s%ry)//': must be >= 0 (0: flat in y; else at least '// &
                        fmt_limit(min_radius)//' mm, at most '//fmt_limit(max_radius)//' mm)'
                end if
            end if
        case ('punch_rough')
            if (.not. is_given(s, 'geometry', 'diameter')) then
                errmsg = "&geometry diameter: missing required value for kind = 'punch_rough'"
            else if (.not. (s%diameter > 0 .and. s%diameter <= 2*max_length)) then
                errmsg = '&geometry diameter = '//fmt_real(s%diameter)//': must be > 0 (at most '// &
                    fmt_limit(2*max_length)//' mm)'
            else if (.not. (s%rough%sigma >= 0 .and. s%rough%sigma <= max_length)) then
                errmsg = '&geometry sigma = '//fmt_real(s%rough%sigma)//': must be >= 0 (at most '// &
                    fmt_limit(max_length)//' mm)'
            else if (.not. (s%rough%gamma > 0 .and. s%rough%gamma <= 1)) then
                errmsg = '&geometry gamma = '//fmt_real(s%rough%gamma)//': must lie in (0, 1]'
            else if (s%rough%m_modes < 1 .or. s%rough%m_modes > max_modes) then
                errmsg = '&geometry m_modes = '//fmt_int(s%rough%m_modes)//': must lie in [1, '//fmt_int(max_modes)//']'
            else if (s%rough%n_modes < 1 .or. s%rough%n_modes > max_modes) then
                errmsg = '&geometry n_modes = '//fmt_int(s%rough%n_modes)//': must lie in [1, '//fmt_int(max_modes)//']'
            else if (int(s%rough%m_modes, i8)*s%rough%n_modes > max_mode_pairs) then
                errmsg = '&geometry m_modes = '//fmt_int(s%rough%m_modes)//', n_modes = '//fmt_int(s%rough%n_modes)// &
                    ': m_modes*n_modes must be <= '//fmt_int(max_mode_pairs)
            else if (int(s%rough%m_modes, i8)*s%rough%n_modes*(int(s%nx, i8) + s%ny) > max_mode_work) then
                errmsg = '&geometry m_modes = '//fmt_int(s%rough%m_modes)//', n_modes = '//fmt_int(s%rough%n_modes)// &
                    ' on the &grid nx = '//fmt_int(s%nx)//', ny = '//fmt_int(s%ny)// &
                    ': too costly (m_modes*n_modes*(nx + ny) must be <= 2^32)'
            end if
        case ('wavy')
            if (.not. is_given(s, 'geometry', 'amplitude')) then
                errmsg = "&geometry amplitude: missing required value for kind = 'wavy'"
            else if (.not. (s%amplitude > 0 .and. s%amplitude <= max_length)) then
                errmsg = '&geometry amplitude = '//fmt_real(s%amplitude)//': must be > 0 (at most '// &
                    fmt_limit(max_length)//' mm)'
            else if (.not. ((s%wavelength_x == 0 .or. s%wavelength_x >= min_length) .and. &
                            (s%wavelength_y == 0 .or. s%wavelength_y >= min_length))) then
                errmsg = '&geometry wavelength_x = '//fmt_real(s%wavelength_x)//', wavelength_y = '// &
                    fmt_real(s%wavelength_y)//': must be 0 (flat) or at least '//fmt_limit(min_length)//' mm'
            end if
        case ('table')
            if (len_trim(s%file) == 0) then
                errmsg = "&geometry file: missing required value for kind = 'table'"
            else if (.not. file_exists(s%file)) then
                errmsg = "&geometry file = '"//trim(s%file)//"': file not found"
            end if
        end select
    end subroutine validate_geometry

    !> &grid: the automatic-area and accuracy-target keys; for a fixed area all of nx … ymax
    !! given, nx, ny ≥ 1, non-empty, at most `limit` elements (4096² unless distributed).
    subroutine validate_grid(s, limit, errmsg)
        type(fc_case_input), intent(in) :: s
        integer(i8), intent(in) :: limit   !! largest nx·ny
        character(len=*), intent(out) :: errmsg
        integer :: i
        logical :: auto
        errmsg = ''
        auto = grid_is_auto(s) .or. s%problem == 'hertz'
        if (.not. real_in_range(s%margin, 0.0_dp, 10.0_dp)) then
            errmsg = '&grid margin = '//fmt_real(s%margin)//': must lie in [0, 10] (fraction added around the '// &
                'Hertz estimate)'
            return
        end if
        if (s%n_across < 0 .or. s%n_across > 4096) then
            errmsg = '&grid n_across = '//fmt_int(s%n_across)//': must lie in [0, 4096] (0: default)'; return
        end if
        if (.not. real_in_range(s%target, 0.0_dp, nearest(1.0_dp, -1.0_dp))) then
            errmsg = '&solver target = '//fmt_real(s%target)//': must lie in [0, 1) (relative error; 0: off)'; return
        end if
        ! the solver tolerance becomes 0.01·target: below 1e-10 it would reach rounding (or underflow)
        if (s%target > 0 .and. s%target < 1.0e-10_dp) then
            errmsg = '&solver target = '//fmt_real(s%target)//': must be 0 (off) or >= 1e-10 (relative error)'; return
        end if
        if (s%max_levels < 2 .or. s%max_levels > 12) then
            errmsg = '&solver max_levels = '//fmt_int(s%max_levels)//': must lie in [2, 12]'; return
        end if
        select case (s%model)
        case ('auto', 'full')
        case ('fastsim')
            if (s%problem /= 'rolling' .or. s%kind /= 'quadratic' .or. .not. (s%rx > 0 .and. s%ry > 0) .or. &
                s%tforce_prescribed .or. len_trim(s%sweep) > 0) then
                errmsg = "&solver model = 'fastsim': needs problem = 'rolling' with &geometry kind = 'quadratic', "// &
                    'rx > 0, ry > 0, creepages xi, eta, phi (no fx, fy) and no sweep'
                return
            end if
        case default
            errmsg = "&solver model = '"//trim(s%model)//"': use 'auto' (reduce the model where possible), 'full' "// &
                "or 'fastsim' (steady rolling: Kalker's simplified theory)"
            return
        end select
        if (auto) then
            if (.not. any(s%kind == [character(len=16) :: 'quadratic', 'cylinder', 'strip2d']) .and. &
                s%problem /= 'hertz') then
                errmsg = "&grid auto = .true.: the automatic potential contact area needs a Hertzian geometry "// &
                    "(kind = 'quadratic', 'cylinder' or 'strip2d'); give nx, ny, xmin, xmax, ymin, ymax for kind = '"// &
                    trim(s%kind)//"'"
            else if (s%problem /= 'hertz' .and. s%model == 'auto' .and. s%kind == 'quadratic' .and. s%ry == 0) then
                ! a line contact becomes a strip, whose length an automatic area cannot know
                errmsg = "&geometry ry = 0 (line contact) with an automatic grid: the length is unknown; use "// &
                    "kind = 'cylinder' with length, or give &grid ymin, ymax"
            end if
            return
        end if
        if (s%kind == 'strip2d' .and. s%ny /= 1) then
            errmsg = '&grid ny = '//fmt_int(s%ny)//": must be 1 for &geometry kind = 'strip2d'"; return
        end if
        do i = 1, 6
            associate (key => area_keys(i))
                if (.not. is_given(s, 'grid', trim(key)) .and. .not. (key == 'ny' .and. s%kind == 'strip2d') &
                    .and. .not. (s%kind == 'cylinder' .and. key /= 'nx' .and. key /= 'xmin' .and. key /= 'xmax')) then
                    errmsg = '&grid '//trim(key)//': missing required value'; return
                end if
            end associate
        end do
        do i = 1, 4
            associate (x => [s%xmin, s%xmax, s%ymin, s%ymax])
                if (.not. real_in_range(x(i), -max_length, max_length)) then
                    errmsg = '&grid '//trim(area_keys(i + 2))//' = '//fmt_real(x(i))//': must be a finite number with |'// &
                        trim(area_keys(i + 2))//'| <= '//fmt_limit(max_length)//' mm'
                    return
                end if
            end associate
        end do
        if (s%nx < 1) then
            errmsg = '&grid nx = '//fmt_int(s%nx)//': must be >= 1'
        else if (s%ny < 1) then
            errmsg = '&grid ny = '//fmt_int(s%ny)//': must be >= 1'
        else if (.not. (s%xmax > s%xmin)) then
            errmsg = '&grid xmax = '//fmt_real(s%xmax)//': must be > xmin = '//fmt_real(s%xmin)//' (empty grid)'
        else if (.not. (s%ymax > s%ymin)) then
            errmsg = '&grid ymax = '//fmt_real(s%ymax)//': must be > ymin = '//fmt_real(s%ymin)//' (empty grid)'
        else if (int(s%nx, i8)*int(s%ny, i8) > limit) then
            errmsg = '&grid nx = '//fmt_int(s%nx)//', ny = '//fmt_int(s%ny)//': oversized grid (nx*ny > '// &
                fmt_int(nint(sqrt(real(limit, dp))))//'*'//fmt_int(nint(sqrt(real(limit, dp))))//')'
        end if
    end subroutine validate_grid

    !> &normal: approach (finite) or fn (> 0) given.
    subroutine validate_normal(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (.not. (is_given(s, 'normal', 'approach') .or. is_given(s, 'normal', 'fn'))) then
            errmsg = '&normal approach, fn: missing required value (give approach or fn)'
        else if (s%force_prescribed) then
            if (.not. real_in_range(s%fn, min_force, max_force)) errmsg = '&normal fn = '//fmt_real(s%fn)// &
                ': must be > 0 (in ['//fmt_limit(min_force)//', '//fmt_limit(max_force)//'] N)'
        else if (.not. real_in_range(s%approach, -max_length, max_length)) then
            errmsg = '&normal approach = '//fmt_real(s%approach)//': not a finite number with |approach| <= '// &
                fmt_limit(max_length)//' mm'
        end if
    end subroutine validate_normal

    !> &tangential: values checked whenever given; mu required for tangential problems,
    !! > 0 with prescribed forces, and |(fx, fy)| < mu·fn when fn is prescribed too.
    subroutine validate_tangential(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (.not. (real_in_range(s%mu, min_friction, max_friction) .or. s%mu == 0)) then
            errmsg = '&tangential mu = '//fmt_real(s%mu)//': must be >= 0 (coefficient of friction: 0, or in ['// &
                fmt_limit(min_friction)//', '//fmt_limit(max_friction)//'])'
            return
        end if
        if (.not. (all(real_in_range([s%xi, s%eta], -max_length, max_length)) .and. &
            real_in_range(s%phi, -max_spin, max_spin) .and. all(real_in_range([s%fx, s%fy], -max_force, max_force)))) then
            errmsg = '&tangential xi = '//fmt_real(s%xi)//', eta = '//fmt_real(s%eta)//', phi = '//fmt_real(s%phi)// &
                ', fx = '//fmt_real(s%fx)//', fy = '//fmt_real(s%fy)//': not finite numbers within the limits |xi|, '// &
                '|eta| <= '//fmt_limit(max_length)//' mm, |phi| <= '//fmt_limit(max_spin)//', |fx|, |fy| <= '// &
                fmt_limit(max_force)//' N'
            return
        end if
        if (.not. is_tangential(s)) return
        if (.not. is_given(s, 'tangential', 'mu')) then
            errmsg = "&tangential mu: missing required value for problem = '"//trim(s%problem)// &
                "' (coefficient of friction, >= 0)"
        else if (s%tforce_prescribed) then
            if (.not. (s%mu > 0)) then
                errmsg = '&tangential mu = '//fmt_real(s%mu)//': must be > 0 when the forces fx, fy are prescribed'
            else if (s%force_prescribed .and. .not. (hypot(s%fx, s%fy) < s%mu*s%fn)) then
                errmsg = '&tangential fx = '//fmt_real(s%fx)//', fy = '//fmt_real(s%fy)//': |(fx, fy)| = '// &
                    fmt_real(hypot(s%fx, s%fy))//' must be < mu*fn = '//fmt_real(s%mu*s%fn)// &
                    ' (mu = '//fmt_real(s%mu)//', &normal fn = '//fmt_real(s%fn)//'; full slip has no unique shift)'
            end if
        end if
    end subroutine validate_tangential

    !> &solver: known solvers, iteration keys, multigrid keys; FMG has no coupling rounds
    !! (dissimilar materials need BCCG).
    subroutine validate_solver(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        type(fc_material) :: m
        integer :: stat
        character(len=msg_len) :: msg
        errmsg = ''
        select case (s%normal_solver)
        case ('bccg', 'norm', 'fmg')
        case default
            errmsg = "&solver normal = '"//trim(s%normal_solver)//"': unknown solver; use 'bccg', 'norm' or 'fmg'"; return
        end select
        call validate_iteration_keys(s, errmsg)
        if (len_trim(errmsg) > 0) return
        if (s%inner_maxit < 0 .or. s%inner_maxit > max_iterations) then
            errmsg = '&solver inner_maxit = '//fmt_int(s%inner_maxit)//': must lie in [0, '//fmt_int(max_iterations)// &
                '] (0: no limit)'; return
        end if
        call validate_multigrid(s, errmsg)
        if (len_trim(errmsg) > 0) return
        select case (s%tangential)
        case ('tangcg', 'convexgs')
        case default
            errmsg = "&solver tangential = '"//trim(s%tangential)//"': unknown solver; use 'tangcg' or 'convexgs'"; return
        end select
        select case (s%fft_preconditioner)
        case ('circulant', 'toeplitz')
        case default
            errmsg = "&solver fft_preconditioner = '"//trim(s%fft_preconditioner)//"': use 'circulant' (the default) "// &
                "or 'toeplitz'"; return
        end select
        if (s%inner_k < 1 .or. s%inner_k > max_iterations) then
            errmsg = '&solver inner_k = '//fmt_int(s%inner_k)//': must lie in [1, '//fmt_int(max_iterations)// &
                '] (TangCG iterations between subdivision checks)'
            return
        end if
        if (s%threads < 0 .or. s%threads > max_threads_allowed) then
            errmsg = '&solver threads = '//fmt_int(s%threads)//': must lie in [0, '//fmt_int(max_threads_allowed)// &
                '] (0: OMP_NUM_THREADS, else 1)'
            return
        end if
        ! (with mu = 0 and model = 'auto' the tangential stage is dropped: no coupling)
        if (s%normal_solver == 'fmg' .and. is_tangential(s) .and. .not. (s%model == 'auto' .and. s%mu == 0)) then
            m%g1 = s%g1; m%g2 = s%g2; m%nu1 = s%nu1; m%nu2 = s%nu2
            call combine_material(m, stat, msg)
            if (stat == 0 .and. m%k /= 0) errmsg = "&solver normal = 'fmg': not available for dissimilar materials "// &
                '(K = '//fmt_real(m%k)//" /= 0): the Panagiotopoulos loop alternates normal and tangential solves; "// &
                "use normal = 'bccg'"
        end if
    end subroutine validate_solver

    !> &output: a directory.
    subroutine validate_output(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (len_trim(s%dir) == 0) errmsg = "&output dir = '': must not be empty"
        if (len_trim(errmsg) == 0 .and. all(s%table_format /= [character(len=8) :: 'csv', 'npy', 'both'])) &
            errmsg = "&output table_format = '"//trim(s%table_format)//"': must be 'csv', 'npy' or 'both'"
    end subroutine validate_output

    !> Rolling keys (&tangential mu_kinetic, dq, nsteps, sweep*, &solver rolling): values
    !! checked whenever given; sweeps only for 'rolling', dq/nsteps for 'transient_rolling'.
    subroutine validate_rolling(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        logical :: steady, transient
        real(dp), parameter :: max_element_steps = 1.0e7_dp   !! nsteps·nx·ny of a transient run
        real(dp), parameter :: max_sweep = 999999.9999_dp     !! |sweep_from|, |sweep_to| < 1e6
        real(dp) :: steps
        errmsg = ''
        steady = s%problem == 'rolling'
        transient = s%problem == 'transient_rolling'
        if ((steady .or. transient) .and. .not. all(real_in_range([s%xi, s%eta], -max_creepage, max_creepage))) then
            errmsg = '&tangential xi = '//fmt_real(s%xi)//', eta = '//fmt_real(s%eta)//': rolling creepages (ratios '// &
                'of slip to rolling speed) must satisfy |xi|, |eta| <= '//fmt_limit(max_creepage)
            return
        end if
        select case (s%rolling)
        case ('gmres', 'march', 'steadygs')
        case default
            errmsg = "&solver rolling = '"//trim(s%rolling)//"': unknown solver; use 'gmres', 'march' or 'steadygs'"
            return
        end select
        select case (s%rolling_start)
        case ('fastsim', 'adhesion')
        case default
            errmsg = "&solver rolling_start = '"//trim(s%rolling_start)//"': unknown start; use 'fastsim' (the default) "// &
                "or 'adhesion'"
            return
        end select
        if (is_given(s, 'tangential', 'mu_kinetic')) then
            if (.not. real_in_range(s%mu_kinetic, 0.0_dp, s%mu)) then
                errmsg = '&tangential mu_kinetic = '//fmt_real(s%mu_kinetic)//': must be in [0, mu = '//fmt_real(s%mu)// &
                    '] (kinetic friction in slip)'
                return
            end if
            if (s%mu > 0 .and. s%mu_kinetic < min_mu_kinetic) then
                errmsg = '&tangential mu_kinetic = '//fmt_real(s%mu_kinetic)//': with mu = '//fmt_real(s%mu)// &
                    ' > 0 must be >= '//fmt_real(min_mu_kinetic)//' (slip without friction has no direction; '// &
                    'mu = 0 for frictionless contact)'
                return
            end if
        end if
        if (is_given(s, 'tangential', 'dq')) then
            if (.not. real_in_range(s%dq, tiny(1.0_dp), huge(1.0_dp))) then
                errmsg = '&tangential dq = '//fmt_real(s%dq)//': must be > 0 (travelled distance per step, mm)'; return
            end if
        end if
        if (s%nsteps < 0 .or. s%nsteps > 100000) then
            errmsg = '&tangential nsteps = '//fmt_int(s%nsteps)//': must be in [0, 100000] (0: automatic)'; return
        end if
        ! cost bound: element solves of a transient run on a fixed grid (automatic steps: the
        ! area length travelled four times at dq = dx, i.e. 4·nx steps)
        if (transient .and. .not. grid_is_auto(s)) then
            if (s%nsteps > 0) then
                steps = s%nsteps
            else if (s%dq > 0) then
                steps = 4*(s%xmax - s%xmin)/s%dq
            else
                steps = 4*real(s%nx, dp)
            end if
            if (steps*real(s%nx, dp)*real(s%ny, dp) > max_element_steps) then
                errmsg = '&tangential nsteps = '//fmt_int(s%nsteps)//' with &grid nx = '//fmt_int(s%nx)//', ny = '// &
                    fmt_int(s%ny)//': steps x elements must be <= 1e7 (a run of minutes); fewer steps (nsteps, '// &
                    'or a larger dq) or a coarser grid'
                return
            end if
        end if
        if (transient .and. s%tforce_prescribed) then
            errmsg = "&tangential fx, fy: problem = 'transient_rolling' takes creepages xi, eta, phi"; return
        end if
        if (transient .and. s%mu_kinetic >= 0 .and. s%mu_kinetic /= s%mu) then
            errmsg = '&tangential mu_kinetic = '//fmt_real(s%mu_kinetic)//": problem = 'transient_rolling' has "// &
                'one coefficient of friction (mu)'
            return
        end if
        if (len_trim(s%sweep) == 0) return
        select case (s%sweep)
        case ('xi', 'eta', 'phi', 'fx', 'fy')
        case default
            errmsg = "&tangential sweep = '"//trim(s%sweep)//"': use 'xi', 'eta', 'phi', 'fx' or 'fy' (or '' for none)"
            return
        end select
        if (.not. steady) then
            errmsg = "&tangential sweep = '"//trim(s%sweep)//"': only for problem = 'rolling'"; return
        end if
        if (s%target > 0) then
            errmsg = '&solver target = '//fmt_real(s%target)//": not available for a creep-force sweep (give a "// &
                'fixed grid)'
            return
        end if
        if (.not. (is_given(s, 'tangential', 'sweep_from') .and. is_given(s, 'tangential', 'sweep_to'))) then
            errmsg = "&tangential sweep = '"//trim(s%sweep)//"': sweep_from and sweep_to are required"; return
        end if
        if (.not. all(real_in_range([s%sweep_from, s%sweep_to], -max_sweep, max_sweep))) then
            errmsg = '&tangential sweep_from = '//fmt_real(s%sweep_from)//', sweep_to = '//fmt_real(s%sweep_to)// &
                ': must be finite, |value| < 1e6'
            return
        end if
        if (s%sweep_n < 2 .or. s%sweep_n > 1000) then
            errmsg = '&tangential sweep_n = '//fmt_int(s%sweep_n)//': must be in [2, 1000]'; return
        end if
        if ((s%sweep == 'fx' .or. s%sweep == 'fy') .and. .not. s%tforce_prescribed) then
            errmsg = "&tangential sweep = '"//trim(s%sweep)//"': needs prescribed forces (give fx or fy)"; return
        end if
        if ((s%sweep == 'xi' .or. s%sweep == 'eta') .and. s%tforce_prescribed) then
            errmsg = "&tangential sweep = '"//trim(s%sweep)//"': needs creepages (give xi or eta, not fx, fy)"; return
        end if
        if ((s%sweep == 'xi' .or. s%sweep == 'eta') .and. &
            .not. all(real_in_range([s%sweep_from, s%sweep_to], -max_creepage, max_creepage))) then
            errmsg = '&tangential sweep_from = '//fmt_real(s%sweep_from)//', sweep_to = '//fmt_real(s%sweep_to)// &
                ": sweep = '"//trim(s%sweep)//"' runs over a creepage: |value| <= "//fmt_limit(max_creepage)
            return
        end if
    end subroutine validate_rolling

    !> &solver tol > 0 and maxit >= 1 (shared by every problem kind).
    subroutine validate_iteration_keys(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (.not. real_in_range(s%tol, tiny(1.0_dp), huge(1.0_dp))) then
            errmsg = '&solver tol = '//fmt_real(s%tol)//': must be > 0'
        else if (s%maxit < 1 .or. s%maxit > max_iterations) then
            errmsg = '&solver maxit = '//fmt_int(s%maxit)//': must lie in [1, '//fmt_int(max_iterations)//']'
        end if
    end subroutine validate_iteration_keys

    !> The multigrid keys of &solver (cycle, omega, beta, smoother, strip), checked whenever given.
    subroutine validate_multigrid(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        integer :: stat, nu1, nu2
        character(len=msg_len) :: msg
        errmsg = ''
        call fmg_cycle_from_name(s%cycle, nu1, nu2, stat, msg)
        if (stat /= 0) then
            errmsg = "&solver cycle = '"//trim(s%cycle)//"': not 'V(n1,n2)' with n1, n2 >= 0 and n1 + n2 > 0 "// &
                "(e.g. 'V(1,1)', 'V(1,0)', 'V(0,1)')"
        else if (nu1 > max_smoothing .or. nu2 > max_smoothing) then
            errmsg = "&solver cycle = '"//trim(s%cycle)//"': smoothing steps n1, n2 must be <= "//fmt_int(max_smoothing)
        else if (.not. real_in_range(s%omega, tiny(1.0_dp), nearest(2.0_dp, -1.0_dp))) then
            errmsg = '&solver omega = '//fmt_real(s%omega)//': must lie in (0, 2) (damping of the FMG smoother)'
        else if (.not. real_in_range(s%beta, 0.0_dp, huge(1.0_dp))) then
            errmsg = '&solver beta = '//fmt_real(s%beta)//': must be >= 0 (FMG initial contact area e <= beta*max(u))'
        else if (.not. any(s%smoother == [character(len=8) :: 'gs', 'jacobi', 'fft-rsm'])) then
            errmsg = "&solver smoother = '"//trim(s%smoother)//"': unknown FMG smoother; use 'gs', 'jacobi' or 'fft-rsm'"
        else if (.not. any(s%strip == [character(len=16) :: 'mg-fft-rsm', 'mg-fft-sd', 'fft-rsm'])) then
            errmsg = "&solver strip = '"//trim(s%strip)//"': unknown strip solver; use 'mg-fft-rsm', 'mg-fft-sd' "// &
                "or 'fft-rsm'"
        end if
    end subroutine validate_multigrid

    !> A strip model problem case (problem = 'strip_mp1' … 'strip_mp3'): kind = 'strip2d',
    !! nx a power of 2 ≥ 4, ny = 1, the solver keys.  Material, potential area and loading
    !! come from the model problem (thesis §3.2.5).
    subroutine validate_strip(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (.not. is_given(s, 'geometry', 'kind')) then
            errmsg = "&geometry kind: missing required value for problem = '"//trim(s%problem)//"' (use 'strip2d')"
        else if (s%kind /= 'strip2d') then
            errmsg = "&geometry kind = '"//trim(s%kind)//"': problem = '"//trim(s%problem)//"' needs kind = 'strip2d'"
        else if (.not. is_given(s, 'grid', 'nx')) then
            errmsg = "&grid nx: missing required value for problem = '"//trim(s%problem)//"' (a power of 2, >= 4)"
        ! in 64 bits: Fortran's .or. need not short-circuit, and nx − 1 overflows for nx = −2^31
        else if (s%nx < 4 .or. iand(int(s%nx, i8), int(s%nx, i8) - 1) /= 0 .or. int(s%nx, i8) > max_grid_elements) then
            errmsg = '&grid nx = '//fmt_int(s%nx)//": must be a power of 2 in [4, 4096^2] for problem = '"// &
                trim(s%problem)//"'"
        else if (is_given(s, 'grid', 'ny') .and. s%ny /= 1) then
            errmsg = '&grid ny = '//fmt_int(s%ny)//": must be 1 for &geometry kind = 'strip2d'"
        end if
        if (len_trim(errmsg) > 0) return
        call validate_iteration_keys(s, errmsg)
        if (len_trim(errmsg) > 0) return
        call validate_multigrid(s, errmsg)
        if (len_trim(errmsg) > 0) return
        call validate_output(s, errmsg)
    end subroutine validate_strip

    logical function file_exists(path)
        character(len=*), intent(in) :: path
        inquire (file=trim(path), exist=file_exists)
    end function file_exists

    !> `&grid periodic = .true.`: the grid is one cell of a surface repeated in x and y
    !! (periodic half-space): an explicit grid of even nx, ny, the mean pressure prescribed
    !! through fn, BCCG or NORM; a tangential problem (shifts or forces, not rolling) by
    !! TangCG.
    subroutine validate_periodic(s, errmsg)
        type(fc_case_input), intent(in) :: s
        character(len=*), intent(out) :: errmsg
        errmsg = ''
        if (grid_is_auto(s)) then
            errmsg = '&grid periodic = .true. with an automatic grid: give the cell (nx, ny, xmin, xmax, ymin, ymax)'
        else if (s%nx < 2 .or. s%ny < 2 .or. modulo(s%nx, 2) /= 0 .or. modulo(s%ny, 2) /= 0) then
            errmsg = '&grid periodic = .true., nx = '//fmt_int(s%nx)//', ny = '//fmt_int(s%ny)// &
                ': the periodic cell needs even nx and ny >= 2'
        else if (s%problem == 'hertz' .or. s%problem == 'rolling' .or. s%problem == 'transient_rolling') then
            errmsg = "&grid periodic = .true. with problem = '"//trim(s%problem)// &
                "': the periodic half-space takes problem = 'normal', 'normal+tangential' or 'tangential'"
        else if (is_tangential(s) .and. s%phi /= 0) then
            errmsg = '&grid periodic = .true. with &tangential phi = '//fmt_real(s%phi)// &
                ': a periodic cell takes no spin (a rotation of the whole surface is not periodic); phi = 0'
        else if (is_tangential(s) .and. s%tangential /= 'tangcg') then
            errmsg = "&grid periodic = .true. with &solver tangential = '"//trim(s%tangential)// &
                "': the periodic tangential problem is solved by 'tangcg'"
        else if (.not. s%force_prescribed) then
            errmsg = '&grid periodic = .true. with &normal approach: prescribe fn (mean pressure x cell area); '// &
                'the displacements of a periodic cell are defined up to a constant'
        else if (s%normal_solver == 'fmg') then
            errmsg = "&grid periodic = .true. with &solver normal = 'fmg': use 'bccg' or 'norm'"
        else if (len_trim(s%ic_file) > 0) then
            errmsg = '&grid periodic = .true. with &material ic_file: the periodic half-space has its own '// &
                'influence coefficients'
        else if (s%kind == 'strip2d' .or. s%kind == 'cylinder') then
            errmsg = "&grid periodic = .true. with &geometry kind = '"//trim(s%kind)//"': use a 3D surface "// &
                "(quadratic, wavy, punch_rough, table)"
        end if
    end subroutine validate_periodic

end module fc_input_validate
