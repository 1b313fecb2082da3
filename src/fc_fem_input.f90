!> Input of `fastcontact-ic MODEL.nml`: the driver's `&material` (the body's g1, nu1) and
!! `&grid` groups plus `&fem` (the FE model, every key defaulted).  Groups are read with
!! namelist READs; an unknown key or group is an error that names it.
module fc_fem_input
    use fc_kinds, only: dp, msg_len, FC_ERR_VALUE, FC_ERR_IO
    use fc_fem_mesh, only: fc_fem_params
    use fc_strings, only: lower
    implicit none
    private

    !> Everything MODEL.nml defines.
    type, public :: fc_fem_model
        real(dp) :: g1 = 0, nu1 = 0.28_dp          !! the body [N/mm², –]
        real(dp) :: g2 = 0, nu2 = 0.28_dp          !! body 2 for the CONTACT (combined) output; g2 = 0: same as body 1
        integer :: nx = 0, ny = 0                  !! contact grid
        real(dp) :: xmin = 0, xmax = 0, ymin = 0, ymax = 0
        type(fc_fem_params) :: fem
    end type fc_fem_model

    public :: read_fem_model

contains

    !> Read MODEL.nml.  Missing `&material` or `&grid` is an error; `&fem` is optional.
    subroutine read_fem_model(path, m, stat, errmsg)
        character(len=*), intent(in) :: path
        type(fc_fem_model), intent(out) :: m
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u, ios
        character(len=msg_len) :: iomsg
        real(dp) :: g1, nu1, g2, nu2, xmin, xmax, ymin, ymax
        integer :: nx, ny
        character(len=256) :: ic_file
        character(len=8) :: mesh, integration
        integer :: order, threads
        character(len=16) :: load
        real(dp) :: l_over_hc, cube_over_hc, hc_over_hs, stretch, stretch_far
        character(len=24) :: solver
        character(len=256) :: ccx, workdir
        logical :: keep_work
        namelist /material/ g1, nu1, g2, nu2, ic_file
        namelist /grid/ nx, ny, xmin, xmax, ymin, ymax
        namelist /fem/ mesh, order, load, l_over_hc, cube_over_hc, hc_over_hs, stretch, stretch_far, solver, threads, ccx, &
            workdir, keep_work, integration
        stat = FC_ERR_IO
        open (newunit=u, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            errmsg = 'cannot open '//trim(path)//': '//trim(iomsg); return
        end if
        g1 = m%g1; nu1 = m%nu1; g2 = m%g2; nu2 = m%nu2; ic_file = ''
        read (u, nml=material, iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            errmsg = trim(path)//': &material: '//trim(iomsg); close (u); return
        end if
        m%g1 = g1; m%nu1 = nu1; m%g2 = g2; m%nu2 = nu2
        rewind (u)
        nx = 0; ny = 0; xmin = 0; xmax = 0; ymin = 0; ymax = 0
        read (u, nml=grid, iostat=ios, iomsg=iomsg)
        if (ios /= 0) then
            errmsg = trim(path)//': &grid: '//trim(iomsg); close (u); return
        end if
        m%nx = nx; m%ny = ny; m%xmin = xmin; m%xmax = xmax; m%ymin = ymin; m%ymax = ymax
        rewind (u)
        mesh = m%fem%mesh; order = m%fem%order; load = m%fem%load; l_over_hc = m%fem%l_over_hc
        cube_over_hc = m%fem%cube_over_hc; hc_over_hs = m%fem%hc_over_hs; stretch = m%fem%stretch
        stretch_far = m%fem%stretch_far
        solver = m%fem%solver; threads = m%fem%threads; ccx = m%fem%ccx; workdir = m%fem%workdir
        keep_work = m%fem%keep_work; integration = m%fem%integration
        read (u, nml=fem, iostat=ios, iomsg=iomsg)
        if (ios > 0) then
            errmsg = trim(path)//': &fem: '//trim(iomsg); close (u); return
        end if
        close (u)
        m%fem%mesh = lower(mesh); m%fem%order = order; m%fem%load = lower(load); m%fem%l_over_hc = l_over_hc
        m%fem%cube_over_hc = cube_over_hc; m%fem%hc_over_hs = hc_over_hs; m%fem%stretch = stretch
        m%fem%stretch_far = stretch_far
        m%fem%solver = lower(solver); m%fem%threads = threads; m%fem%ccx = ccx; m%fem%workdir = workdir
        m%fem%keep_work = keep_work; m%fem%integration = lower(integration)
        if (.not. (m%g1 > 0)) then
            write (errmsg, '(a,es12.4,a)') 'material: g1 = ', m%g1, ' must be > 0 (the body computed)'; return
        end if
        if (m%nx < 1 .or. m%ny < 1 .or. m%nx > 4096 .or. m%ny > 4096) then
            write (errmsg, '(a,i0,a,i0,a)') 'grid: nx = ', m%nx, ', ny = ', m%ny, ' must lie in [1, 4096]'; return
        end if
        if (.not. (m%xmax > m%xmin .and. m%ymax > m%ymin)) then
            write (errmsg, '(a,4es12.4)') 'grid: need xmax > xmin and ymax > ymin, got ', m%xmin, m%xmax, m%ymin, m%ymax
            return
        end if
        stat = 0; errmsg = ''
    end subroutine read_fem_model


end module fc_fem_input
