#!/usr/bin/env python3
"""Plot the points of one frame of a granmpm run coloured by pressure.

    plot_frame.py RUNDIR OUT.png [--frame N|last] [--z-range ZMIN:ZMAX]

Reads RUNDIR/run.h5 (docs/output.md) with h5py: the frame's x, y and p
datasets and the mesh's extent. A plane run is drawn as it is; a 3D run
as seen along z (all points, the nearest in front) or, with --z-range,
the points of that slab. Each point is a square of its own size. Prints
one line: frame, time, number of points drawn and their pressure range.
Needs python3-h5py, python3-numpy and python3-matplotlib (Debian 12).
"""
import argparse
import os

import h5py
import matplotlib
matplotlib.use("Agg")  # draw to a file, no display needed
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.axes_grid1 import make_axes_locatable


ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("run", help="run directory (holds run.h5)")
ap.add_argument("png", help="image to write")
ap.add_argument("--frame", default="last", help="frame number or 'last' (default)")
ap.add_argument("--z-range", help="3D: only the points with ZMIN <= z <= ZMAX")
args = ap.parse_args()

with h5py.File(args.run + "/run.h5", "r") as f:
    names = sorted(f["frames"])                     # "000000", "000001", ...
    name = names[-1] if args.frame == "last" else "%06d" % int(args.frame)
    if name not in names:
        ap.error("%s has frames 0 ... %d, not %s" % (args.run, len(names) - 1, args.frame))
    g = f["frames"][name]
    t = float(g.attrs["time"])
    dim = int(g.attrs.get("dimension", 2))          # only 3D frames carry it
    x, y, p = g["x"][:], g["y"][:], g["p"][:]
    vol = g["volume"][:]                            # m^2 per unit thickness, 3D m^3
    punit = g["p"].attrs["unit"].decode()           # strings are read as bytes
    z = g["z"][:] if dim == 3 else None
    mesh = f["mesh"]
    xlim = mesh["node_x"][[0, -1]]
    ylim = mesh["node_y"][[0, -1]]

side = np.sqrt(vol) if dim == 2 else np.cbrt(vol)   # a point's edge length, m
if z is not None:
    if args.z_range:
        z0, z1 = map(float, args.z_range.split(":"))
        keep = (z >= z0) & (z <= z1)
    else:
        keep = np.ones(len(z), bool)
    order = np.argsort(z[keep])                     # draw the nearest (largest z) last
    x, y, p, side = (a[keep][order] for a in (x, y, p, side))

w, h = xlim[1] - xlim[0], ylim[1] - ylim[0]
inch = min(7 / w, 5 / h)                            # the mesh at most 7 x 5 inches
fig, ax = plt.subplots(figsize=(w * inch + 2.2, h * inch + 1.2), dpi=120)
ax.set_xlim(*xlim)
ax.set_ylim(*ylim)
ax.set_aspect("equal")
cax = make_axes_locatable(ax).append_axes("right", size=0.15, pad=0.1)
ax.apply_aspect()                                   # fix the box to size the markers
pt_per_m = ax.get_window_extent().width / w * 72 / fig.dpi
sc = ax.scatter(x, y, c=p, s=(side * pt_per_m) ** 2, marker="s", linewidths=0,
                cmap="viridis")
fig.colorbar(sc, cax=cax, label="pressure p (%s)" % punit)
ax.set_xlabel("x (m)")
ax.set_ylabel("y (m)")
title = "%s: frame %d, t = %.4g s" % (os.path.basename(os.path.abspath(args.run)), int(name), t)
if z is not None and args.z_range:
    title += ", %g <= z <= %g m" % (z0, z1)
ax.set_title(title)
fig.savefig(args.png, bbox_inches="tight")

if len(p):
    print("frame %d t %.17g s: %d points, p %.17g to %.17g %s"
          % (int(name), t, len(p), p.min(), p.max(), punit))
else:
    print("frame %d t %.17g s: 0 points" % (int(name), t))
