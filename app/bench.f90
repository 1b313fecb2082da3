program hz
use fc_kinds
use fc_geometry
use fc_influence
use fc_norm
use fc_hertz
implicit none
type(fc_grid) :: grid
type(fc_material) :: mat
type(fc_normal_operator) :: nop
type(fc_normal_settings) :: s
type(fc_normal_result) :: r
type(fc_hertz_solution) :: hs
real(dp), allocatable :: h0(:,:), pa(:,:)
integer :: stat, n, i, j, k
character(len=256) :: msg, arg
call get_command_argument(1, arg); read(arg,*) n
mat%g1=82000; mat%g2=82000; mat%nu1=0.28_dp; mat%nu2=0.28_dp
call combine_material(mat, stat, msg)
call make_grid(grid, n, n, -10._dp, 10._dp, -6._dp, 6._dp, stat, msg)
h0 = quadratic_gap(grid, 300._dp, 163._dp)
call build_normal_operator(nop, mat, grid)
print *, 'setup', nop%setup_seconds
hs = hertz_from_approach(1/600._dp, 1/326._dp, mat%g/(1-mat%nu), 0.1091_dp)
allocate(pa(n,n))
do j=1,n; do i=1,n; pa(i,j)=hs%pressure(grid%x(i),grid%y(j)); end do; end do
do k=1,4
  select case(k)
  case(1); s%solver='bccg'; s%precondition=.true.; s%deflation=.true.
  case(2); s%solver='bccg'; s%precondition=.true.; s%deflation=.false.
  case(3); s%solver='bccg'; s%precondition=.false.
  case(4); s%solver='norm'
  end select
  if (k==4 .and. n>256) exit
  call solve_normal(nop, h0, s, r, stat, msg, approach=0.1091_dp)
  print '(a6,l2,l2,a,i5,a,i5,a,i6,a,es10.3,a,f10.4,a,f10.2,a,i6,a,f9.3,a,i0)', s%solver, s%precondition, &
   s%deflation, ' it', r%iterations, ' out', r%outer_iterations, &
   ' mv', r%matvecs, ' res', r%residual, ' t', r%cpu_seconds, ' F', r%fn, ' ncon', r%ncon, &
   ' err', sqrt(sum((r%pn-pa)**2)/n**2), ' st', r%status
  call solve_normal(nop, h0, s, r, stat, msg, fn=82004._dp)
  print '(a6,l2,l2,a,i5,a,i5,a,i6,a,es10.3,a,f10.4,a,f10.2,a,f9.5)', 'F:'//s%solver, s%precondition, &
   s%deflation, ' it', r%iterations, ' out', r%outer_iterations, &
   ' mv', r%matvecs, ' res', r%residual, ' t', r%cpu_seconds, ' F', r%fn, ' delta', r%approach
end do
end program
