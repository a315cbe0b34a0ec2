#!/usr/bin/env python3
"""Gmsh 2D reference for benches/surface_mesh.rs: the same wavy horizon patch (3700 x 3700 m,
z = -1200 + 80 sin(x/900) cos(y/1100)) as an OCC B-spline surface, meshed with Gmsh's default
Frontal-Delaunay (algorithm 6), single thread, uniform size; prints triangles, seconds, c/c*."""
import math, sys, time
import numpy as np
import gmsh

def run(size):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    n = 40
    tags = []
    for j in range(n):
        for i in range(n):
            x = 3700.0 * i / (n - 1)
            y = 3700.0 * j / (n - 1)
            z = -1200 + 80 * math.sin(x / 900) * math.cos(y / 1100)
            tags.append(gmsh.model.occ.addPoint(x, y, z))
    gmsh.model.occ.addBSplineSurface(tags, n)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMin", size)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    t0 = time.perf_counter()
    gmsh.model.mesh.generate(2)
    dt = time.perf_counter() - t0
    ntags, coords, _ = gmsh.model.mesh.getNodes()
    pos = {int(t): coords[3 * k:3 * k + 3] for k, t in enumerate(ntags)}
    et, _, en = gmsh.model.mesh.getElements(2)
    tris = np.array([pos[int(t)] for t in en[0]]).reshape(-1, 3, 3)
    gmsh.finalize()
    a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    s = ((b - a) ** 2).sum(1) + ((c - a) ** 2).sum(1) + ((c - b) ** 2).sum(1)
    q = s / (4 * math.sqrt(3) * area)
    print(f"| gmsh wavy {size} m | {len(q)} | {q.mean():.4f} | {q.std():.4f} | {q.max():.3f} | "
          f"{100 * (q > 1.15).mean():.2f} | {100 * (q > 1.5).mean():.2f} | {dt:.3f} s | {len(q) / dt:.0f} tri/s |")

for size in [float(s) for s in (sys.argv[1:] or ["200", "100", "50", "25"])]:
    run(size)
