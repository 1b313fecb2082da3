#!/usr/bin/env python3
"""Multibody-style loop through the flat API from Python (ctypes, standard library only).

A sphere (R = 50 mm) is pressed on a plane, shifted tangentially, then unloaded while the
shift is held (the Cattaneo reference case of doc/conventions.md: G = 200 N/mm², nu = 0.42,
mu = 0.4).  Transient mode 1: the shifts are the increments of each step.  Prints the same table as
example/legacy_sphere.f90 and example/legacy_sphere.c, then reads the traction and status
arrays of the last step.

    scripts/build_shared.sh && python3 example/legacy_sphere.py [path/to/libfastcontact.so]
"""
import ctypes as ct
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
LIB = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "build", "libfastcontact.so")
fc = ct.CDLL(LIB)

I, D = ct.c_int, ct.c_double


class FastContactError(RuntimeError):
    pass


def call(name, *args):
    """Call fc_<name>(args..., ierr); plain ints/floats are passed by reference."""
    ierr = I(0)
    refs = []
    for a in args:
        if isinstance(a, int):
            a = I(a)
        elif isinstance(a, float):
            a = D(a)
        refs.append(a if isinstance(a, ct.Array) else ct.byref(a))
    getattr(fc, "fc_" + name)(*refs, ct.byref(ierr))
    if ierr.value != 0 and name != "get_error_message":
        buf = ct.create_string_buffer(256)
        getattr(fc, "fc_get_error_message")(ct.byref(handle), buf, ct.byref(I(256)), ct.byref(I(0)))
        raise FastContactError(f"fc_{name}: ierr = {ierr.value}: {buf.value.decode()}")


nx, ny, nsteps, l, fmax = 40, 40, 12, 1.2857, 9.1954
fn_frac = [0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0, 1.0, 0.8125, 0.625, 0.4375, 0.25]
dxi = [0.0] * 4 + [-0.0015] * 4 + [0.0] * 4
phase = ["load"] * 4 + ["shift"] * 4 + ["unload"] * 4

handle = I(0)
call("init", handle)
call("set_material", handle, 200.0, 200.0, 0.42, 0.42)
call("set_grid", handle, nx, ny, -l, l, -l, l)
call("set_gap_quadratic", handle, 50.0, 50.0)
call("set_friction", handle, 0.4)
call("set_solver", handle, 1, 1, 1e-8, 1000, 3, 1)
call("set_transient", handle, 1)

print("step phase        Fn [N]    Fx [N]    shift [mm]  ncon  nadh nslip")
shift = 0.0
fn, fx, fy, mz, xi, eta, phi = (D() for _ in range(7))
ncon, nadh, nslip = I(), I(), I()
for k in range(nsteps):
    call("set_normal_force", handle, fn_frac[k] * fmax)
    call("set_shifts", handle, dxi[k], 0.0, 0.0)
    call("calculate", handle)
    call("get_forces", handle, fn, fx, fy, mz)
    call("get_shifts", handle, xi, eta, phi)
    call("get_contact_stats", handle, ncon, nadh, nslip)
    shift += xi.value
    print(f"{k + 1:4d} {phase[k]:<6s}{fn.value:12.4f}{fx.value:10.5f}{shift:14.6f}"
          f"{ncon.value:6d}{nadh.value:6d}{nslip.value:6d}")

# arrays of the last step: x runs fastest, element (ix, iy) at ix + iy*nx
n = nx * ny
pn, px, py = (D * n)(), (D * n)(), (D * n)()
status = (I * n)()
call("get_tractions", handle, n, pn, px, py)
call("get_status_array", handle, n, status)
area = (2 * l / nx) * (2 * l / ny)
print(f"check: sum(pn)*dx*dy = {sum(pn) * area:.4f} N, slip elements = {sum(1 for s in status if s == 2)}")
call("finalize", handle)
