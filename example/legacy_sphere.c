/* Multibody-style loop through the flat API from C: a sphere (R = 50 mm) pressed on a plane,
 * shifted tangentially, then unloaded while the shift is held (the Cattaneo reference case
 * of doc/conventions.md: G = 200 N/mm², nu = 0.42, mu = 0.4).  Transient mode 1: the shifts are the increments of
 * each step, the previous step's (u', p') is the state.  Prints the same table as
 * example/legacy_sphere.f90 and example/legacy_sphere.py.
 *
 * Build and run (see doc/legacy_api.md):
 *   scripts/build_shared.sh --examples && build/legacy_sphere_c
 * or by hand:
 *   gcc -Iinclude example/legacy_sphere.c -Lbuild -lfastcontact -Wl,-rpath,$PWD/build -o legacy_sphere_c
 */
#include <stdio.h>
#include <stdlib.h>
#include "fc_legacy.h"

static void check(int h, int ierr, const char *where)
{
    char msg[256];
    int buflen = (int)sizeof msg, e;
    if (ierr == 0) return;
    fc_get_error_message(&h, msg, &buflen, &e);
    fprintf(stderr, "%s failed (ierr = %d): %s\n", where, ierr, msg);
    exit(1);
}

int main(void)
{
    const int nx = 40, ny = 40, nsteps = 12;
    const double l = 1.2857, fmax = 9.1954;
    const double fn_frac[12] = {0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0, 1.0, 0.8125, 0.625, 0.4375, 0.25};
    const double dxi[12] = {0, 0, 0, 0, -0.0015, -0.0015, -0.0015, -0.0015, 0, 0, 0, 0};
    const char *phase[12] = {"load", "load", "load", "load", "shift", "shift", "shift", "shift",
                             "unload", "unload", "unload", "unload"};
    const double g = 200.0, nu = 0.42, r = 50.0, mu = 0.4, tol = 1e-8, xmin = -l, xmax = l, zero = 0.0;
    const int solver = 1, maxit = 1000, inner_k = 3, precondition = 1, mode = FCL_CONTINUE;
    int h, ierr, k, ncon, nadh, nslip, major, minor, patch;
    double fn, fx, fy, mz, xi, eta, phi, shift = 0.0;

    fc_get_version(&major, &minor, &patch, &ierr);
    printf("fastcontact library %d.%d.%d\n", major, minor, patch);
    fc_init(&h, &ierr);
    fc_set_material(&h, &g, &g, &nu, &nu, &ierr);                 check(h, ierr, "fc_set_material");
    fc_set_grid(&h, &nx, &ny, &xmin, &xmax, &xmin, &xmax, &ierr); check(h, ierr, "fc_set_grid");
    fc_set_gap_quadratic(&h, &r, &r, &ierr);                      check(h, ierr, "fc_set_gap_quadratic");
    fc_set_friction(&h, &mu, &ierr);                              check(h, ierr, "fc_set_friction");
    fc_set_solver(&h, &solver, &solver, &tol, &maxit, &inner_k, &precondition, &ierr);
    check(h, ierr, "fc_set_solver");
    fc_set_transient(&h, &mode, &ierr);                           check(h, ierr, "fc_set_transient");

    printf("step phase        Fn [N]    Fx [N]    shift [mm]  ncon  nadh nslip\n");
    for (k = 0; k < nsteps; k++) {
        double fnk = fn_frac[k] * fmax;
        fc_set_normal_force(&h, &fnk, &ierr);
        fc_set_shifts(&h, &dxi[k], &zero, &zero, &ierr);
        fc_calculate(&h, &ierr);                                  check(h, ierr, "fc_calculate");
        fc_get_forces(&h, &fn, &fx, &fy, &mz, &ierr);
        fc_get_shifts(&h, &xi, &eta, &phi, &ierr);
        fc_get_contact_stats(&h, &ncon, &nadh, &nslip, &ierr);
        shift += xi;
        printf("%4d %-6s%12.4f%10.5f%14.6f%6d%6d%6d\n", k + 1, phase[k], fn, fx, shift, ncon, nadh, nslip);
    }
    fc_finalize(&h, &ierr);
    return 0;
}
