#!/usr/bin/env python3
"""Write each fault block of the L1/L2/L3 peer model as a closed boundary (.off) plus its embedded
dangling-fault triangles (.embedded.off), from the surface meshes that bench_peers.py keeps in
its work directory (_work/surf_<level>.npz: points P, per-region faces F_<region> and embedded
faces E_<region>). The tet meshers then run on exactly the triangles Gmsh made.

usage: peer_regions.py <bench_peers output dir> <out dir>
"""
import os
import sys

import numpy as np


def write_off(path, points, faces):
    used, inv = np.unique(faces.ravel(), return_inverse=True)
    local = inv.reshape(-1, 3)
    with open(path, "w") as fh:
        fh.write("OFF\n%d %d 0\n" % (len(used), len(local)))
        for p in points[used]:
            fh.write("%.17g %.17g %.17g\n" % tuple(p))
        for f in local:
            fh.write("3 %d %d %d\n" % tuple(f))


def main():
    src, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    for level in ("L1", "L2", "L3"):
        path = os.path.join(src, "_work", "surf_%s.npz" % level)
        if not os.path.exists(path):
            print("no %s: skipped" % path)
            continue
        z = np.load(path)
        for key in z.files:
            if not key.startswith("F_") or key == "F_all":
                continue
            region = key[2:]
            for tag, faces in (("", z["F_" + region]), (".embedded", z["E_" + region])):
                if len(faces):
                    write_off(os.path.join(out, "%s_%s%s.off" % (level, region, tag)), z["P"], faces)


if __name__ == "__main__":
    main()
