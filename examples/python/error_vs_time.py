#!/usr/bin/env python3
"""Error against render time for path, photonmap, sppm and vcm on a bench scene (docs/python.md).

Renders the scene with each integrator at several time budgets, measures relMSE against the
reference image with phos.diff, and plots the curves on log-log axes. The defaults take about
40 s on two cores: cornell-glass-mirror at 128 x 128 against ../shared/bench/ref's 256 x 256
reference averaged down 2 x 2 (without the shared references, a 12 s vcm render stands in).

    python3 examples/python/error_vs_time.py [--scene S] [--reference R] [--size N] [-o figure.png]
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
SHARED_REF = os.path.normpath(os.path.join(REPO, "..", "shared", "bench", "ref", "cornell-glass-mirror.pfm"))


def downsample(image, size):
    """Box-averages an H x W x 3 image to size x size (H and W multiples of size)."""
    h, w, _ = image.shape
    return image.reshape(size, h // size, size, w // size, 3).mean(axis=(1, 3))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default=os.path.join(REPO, "scenes", "cornell-glass-mirror.pbrt"))
    ap.add_argument("--reference", default=SHARED_REF, help="converged image (any size that is a multiple)")
    ap.add_argument("--size", type=int, default=128, help="image side in pixels")
    ap.add_argument("--budgets", default="0.5,1,2,4", help="seconds per render, comma-separated")
    ap.add_argument("-o", "--output", default="error_vs_time.png")
    args = ap.parse_args()

    scene = phos.load(args.scene, width=args.size, height=args.size, quiet=True)
    if os.path.exists(args.reference):
        reference = downsample(phos.read(args.reference), args.size)
        ref_label = os.path.basename(args.reference)
    else:
        print("no reference at %s: rendering one with vcm for 12 s" % args.reference)
        reference = phos.render(scene, integrator="vcm", time=12, seed=99).image
        ref_label = "vcm, 12 s"

    budgets = [float(b) for b in args.budgets.split(",")]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for integrator in ("path", "photonmap", "sppm", "vcm"):
        times, errors = [], []
        for seconds in budgets:
            r = phos.render(scene, integrator=integrator, time=seconds, seed=1)
            d = phos.diff(r.image, reference)
            times.append(r.time)
            errors.append(d.relmse)
            print("%-9s %5.2f s  relMSE %.5f  mean ratio %.4f" % (integrator, r.time, d.relmse, d.mean_ratio))
        ax.loglog(times, errors, "o-", label=integrator)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relMSE")
    ax.set_title("%s, %d x %d (reference: %s)" % (os.path.basename(args.scene), args.size, args.size, ref_label),
                 fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
