/* Creep forces of a rolling wheel per time step through the flat API (doc/rolling.md):
 * the Cattaneo-size sphere (R = 50 mm, G = 200 N/mm², nu = 0.42, Fn = 9.1954 N, mu = 0.4)
 * rolls in +x with a longitudinal creepage that grows step by step, a small lateral
 * creepage and spin.  One handle: the operators are built once and every step starts from
 * the previous solution.  Prints creepage, Fx/(mu Fn), Fy/(mu Fn), Mz, slip elements and
 * iterations per step.
 *
 * Build and run (see doc/legacy_api.md; .ci/run runs it):
 *   scripts/build_shared.sh --examples && build/rolling_api
 * or, against an existing build/libfastcontact.so:
 *   gcc -Iinclude example/rolling_api.c -Lbuild -lfastcontact -Wl,-rpath,$PWD/build -o rolling_api && ./rolling_api
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
    const int nx = 60, ny = 50, nsteps = 10;
    const double l = 1.2857, g = 200.0, nu = 0.42, r = 50.0, fn = 9.1954, mu = 0.4;
    const double eta = 2.0e-4, phi = 1.0e-3;
    int h, ierr, k;
    fc_init(&h, &ierr); check(h, ierr, "fc_init");
    fc_set_material(&h, &g, &g, &nu, &nu, &ierr); check(h, ierr, "fc_set_material");
    fc_set_grid(&h, &nx, &ny, &(double){-l}, &l, &(double){-l}, &l, &ierr); check(h, ierr, "fc_set_grid");
    fc_set_gap_quadratic(&h, &r, &r, &ierr); check(h, ierr, "fc_set_gap_quadratic");
    fc_set_normal_force(&h, &fn, &ierr); check(h, ierr, "fc_set_normal_force");
    fc_set_friction(&h, &mu, &ierr); check(h, ierr, "fc_set_friction");
    printf("%5s %10s %10s %10s %12s %12s %6s %6s\n", "step", "xi", "Fx/muFn", "Fy/muFn", "Mz", "Tgamma", "nslip",
           "iters");
    for (k = 1; k <= nsteps; ++k) {
        double xi = 5.0e-4 * k, fnr, fx, fy, mz, tgamma;
        int ncon, nadh, nslip, itn, itt;
        fc_set_rolling(&h, &xi, &eta, &phi, &ierr); check(h, ierr, "fc_set_rolling");
        fc_calculate(&h, &ierr); check(h, ierr, "fc_calculate");
        fc_get_forces(&h, &fnr, &fx, &fy, &mz, &ierr); check(h, ierr, "fc_get_forces");
        fc_get_dissipation(&h, &tgamma, &ierr); check(h, ierr, "fc_get_dissipation");
        fc_get_contact_stats(&h, &ncon, &nadh, &nslip, &ierr); check(h, ierr, "fc_get_contact_stats");
        fc_get_iterations(&h, &itn, &itt, &ierr); check(h, ierr, "fc_get_iterations");
        printf("%5d %10.3e %10.5f %10.5f %12.5e %12.5e %6d %6d\n", k, xi, fx / (mu * fnr), fy / (mu * fnr), mz, tgamma,
               nslip, itt);
    }
    fc_finalize(&h, &ierr);
    return 0;
}
