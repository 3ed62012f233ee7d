#!/usr/bin/env python3
"""A sweep of SPPM's radius-reduction parameter alpha on the caustic-point scene (docs/python.md).

For each alpha, renders with a growing number of iterations and plots relMSE against iterations:
small alpha shrinks the radii fast (less bias, more noise), large alpha slowly. About 30 s on two
cores at the defaults: 128 x 128 against ../shared/bench/ref's 256 x 256 reference averaged down
2 x 2 (without the shared references, a 15 s sppm render stands in).

    python3 examples/python/sppm_alpha_sweep.py [--scene S] [--reference R] [-o figure.png]
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import phos  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
SHARED_REF = os.path.normpath(os.path.join(REPO, "..", "shared", "bench", "ref", "caustic-point.pfm"))


def downsample(image, size):
    h, w, _ = image.shape
    return image.reshape(size, h // size, size, w // size, 3).mean(axis=(1, 3))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default=os.path.join(REPO, "scenes", "caustic-point.scn"))
    ap.add_argument("--reference", default=SHARED_REF)
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--alphas", default="0.3,0.5,0.7,0.9")
    ap.add_argument("--iterations", default="4,16,64,256")
    ap.add_argument("-o", "--output", default="sppm_alpha_sweep.png")
    args = ap.parse_args()

    scene = phos.load(args.scene, width=args.size, height=args.size, quiet=True)
    if os.path.exists(args.reference):
        reference = downsample(phos.read(args.reference), args.size)
    else:
        print("no reference at %s: rendering one with sppm for 15 s" % args.reference)
        reference = phos.render(scene, integrator="sppm", time=15, seed=99).image

    counts = [int(i) for i in args.iterations.split(",")]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for alpha in (float(a) for a in args.alphas.split(",")):
        errors = []
        for n in counts:
            r = phos.render(scene, integrator="sppm", iterations=n, alpha=alpha, photons_per_iter=50000, seed=1)
            d = phos.diff(r.image, reference)
            errors.append(d.relmse)
            print("alpha %.2f  %3d iterations  %5.2f s  relMSE %.5f  mean ratio %.4f"
                  % (alpha, n, r.time, d.relmse, d.mean_ratio))
        ax.loglog(counts, errors, "o-", label="alpha %.2f" % alpha)
    ax.set_xlabel("iterations (50 000 photons each)")
    ax.set_ylabel("relMSE")
    ax.set_title("sppm on %s, %d x %d" % (os.path.basename(args.scene), args.size, args.size), fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
