#!/usr/bin/env python3
"""The suite's mesh-1m grid (benches/peers/suite_mitsuba.py, `mesh_1m_scene`) with rays like its
bounce rays, written in the export format of `pathtrace bench bvh --export` for
benches/peers/embree_quality.c:

    python3 benches/peers/grid_export.py OUT [--rays N] [--seed S]

Each ray starts on a random triangle of the grid (uniform in the triangle, lifted 10⁻⁴ along
the upward face normal) and leaves in a cosine-distributed direction about that normal, as a
diffuse bounce does. The distances column (our hits) is left at zero: only Embree reads it here.
"""

import argparse
import os
import struct
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def grid_triangles(folder):
    """The (T, 3, 3) corners of the grid PLY the suite writes (binary: float xyz, uchar+3 int)."""
    import types
    # suite_mitsuba imports its renderer helpers at module level; the grid writer needs none.
    sys.modules.setdefault("equal_quality", types.SimpleNamespace(rel_mse=None, run_pathtrace=None, timed_render=None))
    sys.modules.setdefault("scene_means", types.SimpleNamespace(inline_includes=None))
    import suite_mitsuba
    xml = suite_mitsuba.mesh_1m_scene(folder)
    raw = open(os.path.join(os.path.dirname(xml), "grid.ply"), "rb").read()
    end = raw.index(b"end_header\n") + len(b"end_header\n")
    header = raw[:end].decode()
    nv = int(header.split("element vertex ")[1].split()[0])
    nf = int(header.split("element face ")[1].split()[0])
    verts = np.frombuffer(raw, dtype="<f4", count=nv * 3, offset=end).reshape(-1, 3)
    faces = np.frombuffer(raw, dtype=np.dtype([("n", "u1"), ("i", "<i4", 3)]), count=nf, offset=end + nv * 12)
    return verts[faces["i"]]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("--rays", type=int, default=1_000_000)
    p.add_argument("--seed", type=int, default=1)
    a = p.parse_args()
    repo = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    tri = grid_triangles(os.path.join(repo, "target", "bench-scenes")).astype(np.float64)
    rng = np.random.default_rng(a.seed)
    pick = rng.integers(0, len(tri), a.rays)
    t = tri[pick]
    u, v = rng.random(a.rays), rng.random(a.rays)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    point = t[:, 0] + u[:, None] * (t[:, 1] - t[:, 0]) + v[:, None] * (t[:, 2] - t[:, 0])
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    n[n[:, 1] < 0] *= -1
    # Cosine-distributed directions about n (Malley's method on a frame around n).
    r1, r2 = rng.random(a.rays), rng.random(a.rays)
    phi, s = 2 * np.pi * r1, np.sqrt(r2)
    local = np.stack([s * np.cos(phi), s * np.sin(phi), np.sqrt(1 - r2)], axis=1)
    helper = np.where(np.abs(n[:, :1]) > 0.9, [[0.0, 1.0, 0.0]], [[1.0, 0.0, 0.0]])
    b1 = np.cross(n, helper)
    b1 /= np.linalg.norm(b1, axis=1)[:, None]
    b2 = np.cross(n, b1)
    d = local[:, :1] * b1 + local[:, 1:2] * b2 + local[:, 2:] * n
    origin = point + 1e-4 * n
    with open(a.out, "wb") as fh:
        fh.write(b"PTBVHEX1" + struct.pack("<QQ", len(tri), a.rays))
        fh.write(tri.astype("<f4").tobytes())
        fh.write(np.concatenate([origin, d], axis=1).astype("<f4").tobytes())
        fh.write(np.zeros(a.rays, dtype="<f4").tobytes())


if __name__ == "__main__":
    main()
