#!/usr/bin/env python3
"""The photon maps of a scene as scatter plots (docs/python.md).

Traces the photon maps as `phos render --integrator photonmap` would, and draws each map's photons
seen from the front (x, y) and from above (x, z), coloured by their power; a few seconds.

    python3 examples/python/photon_scatter.py [--scene S] [--photons N] [-o figure.png]
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import phos  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default=os.path.join(REPO, "scenes", "cornell-glass-mirror.pbrt"))
    ap.add_argument("--global-photons", type=int, default=30000)
    ap.add_argument("--caustic-photons", type=int, default=30000)
    ap.add_argument("-o", "--output", default="photon_scatter.png")
    args = ap.parse_args()

    scene = phos.load(args.scene, quiet=True)
    p = phos.photons(scene, global_=args.global_photons, caustic=args.caustic_photons)
    present = [m for m in np.unique(p.map)]
    fig, axes = plt.subplots(len(present), 2, figsize=(9, 4.2 * len(present)), squeeze=False)
    for row, m in enumerate(present):
        sel = p.map == m
        pos, power = p.position[sel], p.power[sel]
        colour = power / np.maximum(np.percentile(power.max(axis=1), 99), 1e-12)
        colour = np.clip(colour / np.maximum(colour.max(axis=1, keepdims=True), 1), 0, 1)
        for col, (a, b, names) in enumerate(((0, 1, "x y"), (0, 2, "x z"))):
            ax = axes[row][col]
            ax.set_facecolor("black")
            ax.scatter(pos[:, a], pos[:, b], s=0.8, c=colour, linewidths=0)
            ax.set_aspect("equal")
            ax.set_xlabel(names.split()[0])
            ax.set_ylabel(names.split()[1])
            ax.set_title("%s map: %d photons (%s)" % (p.map_names[m], sel.sum(), names), fontsize=9)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print("wrote", args.output, "(%d photons)" % len(p.position))


if __name__ == "__main__":
    main()
