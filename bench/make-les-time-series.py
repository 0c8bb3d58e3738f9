#!/usr/bin/env python3
"""A DALES-like field dump of STEPS time steps for the time-stepping bench (docs/performance.md,
"Stepping through time"): `ql` in kg/kg on (time, zt, yt, xt), N x N columns of 25 m and N
levels of 10 m (default N = 256, 20 steps: 256^3 floats, 64 MiB a step, 1.3 GB in all), a field of
cumulus whose bubbles rise and grow from step to step, so that every step differs everywhere
the cloud is. Written with netCDF4 (python3-netcdf4), uncompressed, as LES models write them.

Usage: make-les-time-series.py OUT.nc [N] [STEPS] [LEVELS]
(LEVELS defaults to N; 1024 1 256 makes the 1 GiB field of docs/performance.md, "A field of
1 GiB")"""
import sys

import netCDF4
import numpy as np

path = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 256
steps = int(sys.argv[3]) if len(sys.argv) > 3 else 20
levels = int(sys.argv[4]) if len(sys.argv) > 4 else n
rng = np.random.default_rng(34)
bubbles = [(rng.uniform(0.1, 0.9) * n * 25.0, rng.uniform(0.1, 0.9) * n * 25.0,
            rng.uniform(0.3, 0.6) * levels * 10.0, rng.uniform(0.04, 0.1) * n * 25.0)
           for _ in range(24)]

with netCDF4.Dataset(path, "w", format="NETCDF3_64BIT_OFFSET") as out:
    out.createDimension("time", None)
    out.createDimension("zt", levels)
    out.createDimension("yt", n)
    out.createDimension("xt", n)
    time = out.createVariable("time", "f8", ("time",))
    time.units = "s"
    axes = {}
    for name, size, step in (("zt", levels, 10.0), ("yt", n, 25.0), ("xt", n, 25.0)):
        axis = out.createVariable(name, "f4", (name,))
        axis.units = "m"
        axis[:] = (np.arange(size) + 0.5) * step
        axes[name] = axis[:].astype(np.float32)
    ql = out.createVariable("ql", "f4", ("time", "zt", "yt", "xt"))
    ql.units = "kg/kg"
    ql.long_name = "Liquid water specific humidity"
    z = axes["zt"][:, None, None]
    y = axes["yt"][None, :, None]
    x = axes["xt"][None, None, :]
    for t in range(steps):
        time[t] = 60.0 * t
        # A slab of levels at a time: the memory stays a few slabs, whatever the field's size.
        for k in range(0, levels, 16):
            zk = z[k:k + 16]
            slab = np.zeros((zk.shape[0], n, n), np.float32)
            for cx, cy, cz, radius in bubbles:
                r = radius * (1.0 + 0.03 * t)
                d = np.sqrt((x - cx) ** 2 + (y - cy) ** 2 + ((zk - cz - 8.0 * t) * 1.5) ** 2)
                np.maximum(slab, 1e-3 * np.clip(1.0 - d / r, 0.0, None), out=slab)
            ql[t, k:k + 16] = slab
