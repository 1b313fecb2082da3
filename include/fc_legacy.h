/* fastcontact — flat, handle-based API (src/fc_legacy.f90, doc/legacy_api.md).
 *
 * Every argument is passed by reference (pointers), arrays have explicit sizes, arrays are
 * stored x fastest: element (ix, iy) is at index ix + iy*nx (0-based).  Every routine ends
 * with an error code: 0 ok, 1 invalid handle, 2 wrong call order / missing data, 3 invalid
 * value, 4 not converged, 5 diverged, 6 array too small, 7 internal error;
 * fc_get_error_message() explains the last failure.
 *
 * Link: -Lbuild -lfastcontact (built by scripts/build_shared.sh).
 */
#ifndef FC_LEGACY_H
#define FC_LEGACY_H

#ifdef __cplusplus
extern "C" {
#endif

enum { FCL_OK = 0, FCL_INVALID_HANDLE = 1, FCL_ORDER = 2, FCL_INVALID_VALUE = 3,
       FCL_NOT_CONVERGED = 4, FCL_DIVERGED = 5, FCL_ARRAY_SIZE = 6, FCL_INTERNAL = 7,
       FCL_MEMORY = 8 };
enum { FCL_FROM_REST = 0, FCL_CONTINUE = 1, FCL_ROLLING = 2 };
enum { FCL_EXTERIOR = 0, FCL_ADHESION = 1, FCL_SLIP = 2 };

void fc_init(int *handle, int *ierr);
void fc_finalize(int *handle, int *ierr);
void fc_get_nhandles(int *nhandles, int *ierr);
void fc_get_version(int *major, int *minor, int *patch, int *ierr);

void fc_set_material(const int *h, const double *g1, const double *g2, const double *nu1, const double *nu2,
                     int *ierr);
void fc_set_grid(const int *h, const int *nx, const int *ny, const double *xmin, const double *xmax,
                 const double *ymin, const double *ymax, int *ierr);
void fc_set_gap_array(const int *h, const int *n, const double *h0, int *ierr);
void fc_set_gap_quadratic(const int *h, const double *rx, const double *ry, int *ierr);
void fc_set_normal_approach(const int *h, const double *approach, int *ierr);
void fc_set_normal_force(const int *h, const double *fn, int *ierr);
void fc_set_friction(const int *h, const double *mu, int *ierr);
void fc_set_shifts(const int *h, const double *xi, const double *eta, const double *phi, int *ierr);
void fc_set_forces(const int *h, const double *fx, const double *fy, const double *phi, int *ierr);
/* precondition: 0 off, 1 on (FFT preconditioners as circulants on the grid, default), 2 on (Toeplitz form) */
void fc_set_solver(const int *h, const int *normal_solver, const int *tangential_solver, const double *tol,
                   const int *maxit, const int *inner_k, const int *precondition, int *ierr);
void fc_set_transient(const int *h, const int *mode, int *ierr);
void fc_set_rolling_step(const int *h, const double *dq, int *ierr);
/* influence coefficients from files (doc/numerical_ic.md): body 1's or combined, body 2's ("": half-space) */
void fc_set_influence_file(const int *h, const char *path, const char *path2, int *ierr);
void fc_set_reuse(const int *h, const int *reuse_operators, const int *warm_start, int *ierr);
/* FFT planning effort: 0 FFTW_ESTIMATE (default), 1 FFTW_MEASURE once per grid (doc/legacy_api.md) */
void fc_set_fft_effort(const int *h, const int *effort, int *ierr);
void fc_set_fft_wisdom(const int *h, const char *path, int *ierr);
/* steady-state rolling in +x: creepages xi, eta [-], spin phi [1/mm] (doc/rolling.md) */
void fc_set_rolling(const int *h, const double *xi, const double *eta, const double *phi, int *ierr);
void fc_set_rolling_forces(const int *h, const double *fx, const double *fy, const double *phi, int *ierr);
void fc_set_rolling_options(const int *h, const int *solver, const double *mu_kinetic, int *ierr);
/* periodic half-space: 0 or 1 (even nx, ny; normal force; friction, no spin or rolling; doc/parallel.md) */
void fc_set_periodic(const int *h, const int *periodic, int *ierr);
/* threads of this handle's solves: 0 (OMP_NUM_THREADS if set, else 1) ... 1024 */
void fc_set_threads(const int *h, const int *nthreads, int *ierr);

void fc_calculate(const int *h, int *ierr);

void fc_get_forces(const int *h, double *fn, double *fx, double *fy, double *mz, int *ierr);
/* frictional dissipation -sum(px*sx + py*sy)*dx*dy: N mm over the shift or transient step,
   N (per mm rolled) in steady rolling; 0 without a tangential problem */
void fc_get_dissipation(const int *h, double *dissipation, int *ierr);
void fc_get_approach(const int *h, double *approach, int *ierr);
void fc_get_pmax(const int *h, double *pmax, int *ierr);
void fc_get_shifts(const int *h, double *xi, double *eta, double *phi, int *ierr);
void fc_get_contact_stats(const int *h, int *ncon, int *nadh, int *nslip, int *ierr);
/* 1 when the last calculation's contact reaches the first or last row or column of the grid
   (the potential contact area clips it: enlarge it), else 0 */
void fc_get_edge_contact(const int *h, int *touches, int *ierr);
void fc_get_tractions(const int *h, const int *n, double *pn, double *px, double *py, int *ierr);
void fc_get_slip(const int *h, const int *n, double *sx, double *sy, int *ierr);
void fc_get_gap(const int *h, const int *n, double *gap, int *ierr);
void fc_get_status_array(const int *h, const int *n, int *status, int *ierr);
void fc_get_iterations(const int *h, int *it_normal, int *it_tangential, int *ierr);
void fc_get_rebuilds(const int *h, int *n_normal, int *n_tangential, int *n_calculations, int *ierr);
void fc_get_grid_size(const int *h, int *nx, int *ny, int *ierr);
void fc_get_error_message(const int *h, char *buffer, const int *buflen, int *ierr);

#ifdef __cplusplus
}
#endif
#endif
