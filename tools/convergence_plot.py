#!/usr/bin/env python3
"""Error against time of the estimators, through the Python module (docs/python.md).

Renders a converged reference with sppm (or reads one: --reference ref.pfm|.exr), then steps a
photon.Renderer with each estimator and, at checkpoints that grow by about sqrt(2) in frames,
measures the relative RMSE of its image against the reference, sqrt(sum |a - ref|^2) /
sqrt(sum |ref|^2) over RGB (core/image/image.h's relativeRmse), and plots it log-log against the
wall-clock seconds spent in step() (the readback and the error are not counted; the renderer's
set-up, BVH and buffers, neither). One line per estimator, saved as PNG. The idea is
photon-converge's (apps/photon_converge.cpp, tools/plot_converge.py: checkpoints, one reference,
another seed for it), here with wall-clock time on any backend and nothing but the module.

The reference has its own seed, so that sppm is not measured against its own first frames; its
noise is a floor under every line (at the default 90 s, about half the error sppm reaches in 15 s).
The denoiser is off for both: the estimators' raw error.

    PYTHONPATH=build/release/python python3 tools/convergence_plot.py -o docs/convergence_python.png

Defaults: the Cornell box, CPU, 320x240, the module's photons a frame, 15 s an estimator after a
90 s reference: about 3 minutes on 2 cores. Needs NumPy and matplotlib (Debian: python3-numpy,
python3-matplotlib).
"""
import argparse
import os
import sys
import time

import numpy as np

# The module: PHOTON_PYTHON_DIR, else PYTHONPATH or an installed one, else the README's build.
if "PHOTON_PYTHON_DIR" in os.environ:
    sys.path.insert(0, os.environ["PHOTON_PYTHON_DIR"])
sys.path.append("build/release/python")
import photon  # noqa: E402


def relative_rmse(image, reference):
    a = np.asarray(image, dtype=np.float64)
    r = np.asarray(reference, dtype=np.float64)
    return float(np.sqrt(np.sum((a - r) ** 2)) / np.sqrt(np.sum(r**2)))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene", nargs="?", default="scenes/cornell.json", help="scene or model file")
    p.add_argument("-o", "--output", default="convergence.png", help="the plot (PNG)")
    p.add_argument("--backend", default="cpu", help="auto|cpu|cuda|vulkan (default cpu)")
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--photons", type=int, help="photon paths a frame (default: the module's choice for the backend)")
    p.add_argument("--estimators", default="sppm,progressive,knn,radius,cell", help="comma-separated")
    p.add_argument("--seconds", type=float, default=15.0, help="wall-clock seconds of step() for each estimator")
    p.add_argument("--seed", type=int, default=1, help="the estimators' seed (the reference's: seed + 1000)")
    p.add_argument("--reference", help="a converged image (.pfm or .exr) of the same scene and size")
    p.add_argument("--reference-seconds", type=float, default=90.0, help="how long to render the reference (sppm)")
    p.add_argument("--save-reference", help="write the rendered reference here (.pfm or .exr) for another run")
    p.add_argument("--json", help="also write the measurements as JSON")
    args = p.parse_args()

    settings = dict(backend=args.backend, width=args.width, height=args.height, denoise=False)
    if args.photons:
        settings["photons"] = args.photons
    # Every estimator, the scene and the settings are checked before the reference's minutes:
    # a renderer of each is made (and dropped) now, a bad one refused in one line, exit 2.
    try:
        for estimator in args.estimators.split(","):
            photon.Renderer(args.scene, estimator=estimator, seed=args.seed, **settings)
    except ValueError as error:
        print(f"convergence_plot.py: {error}", file=sys.stderr)
        sys.exit(2)
    if args.reference:
        reference = photon.read_image(args.reference)
        reference_text = "reference " + os.path.basename(args.reference)
    else:
        last = [0.0]

        def progress(frames, seconds):
            if seconds - last[0] >= 10.0:
                last[0] = seconds
                print(f"  reference: {frames} frames, {seconds:.0f} s", flush=True)

        print(f"reference: sppm for {args.reference_seconds:g} s", flush=True)
        reference = photon.render(args.scene, estimator="sppm", time=args.reference_seconds, seed=args.seed + 1000,
                                  progress=progress, **settings)
        reference_text = f"reference sppm {args.reference_seconds:g} s, seed {args.seed + 1000}"
        if args.save_reference:
            photon.write_image(args.save_reference, reference)
    if reference.shape != (args.height, args.width, 3):
        sys.exit(f"{args.reference}: {reference.shape[1]}x{reference.shape[0]}, not the {args.width}x{args.height} asked for")

    curves = {}
    device = photons = None
    for estimator in args.estimators.split(","):
        renderer = photon.Renderer(args.scene, estimator=estimator, seed=args.seed, **settings)
        frames, spent, rows = 0, 0.0, []
        target = 1
        while spent < args.seconds:
            start = time.perf_counter()
            frames = renderer.step(target - frames)
            spent += time.perf_counter() - start
            rows.append((spent, frames, relative_rmse(renderer.image(), reference)))
            target = max(frames + 1, round(frames * 2**0.5))
        stats = renderer.stats()
        device, photons = stats["device"], stats["photons"]["global"]["emitted_paths"]
        curves[estimator] = rows
        print(f"{estimator:12s} {frames:5d} frames {spent:6.2f} s  relative RMSE {rows[0][2]:.4f} -> {rows[-1][2]:.4f}",
              flush=True)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for estimator, rows in curves.items():
        ax.loglog([r[0] for r in rows], [r[2] for r in rows], marker=".", label=estimator)
    ax.set_xlabel("seconds (wall clock, Renderer.step)")
    ax.set_ylabel("relative RMSE against the reference")
    ax.set_title(f"{os.path.basename(args.scene)} {args.width}x{args.height}, {args.backend} ({device}),\n"
                 f"{photons} photon paths a frame, no denoiser; {reference_text}", fontsize=8)
    plain = matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}")
    ax.yaxis.set_major_formatter(plain)
    ax.yaxis.set_minor_formatter(plain)
    ax.xaxis.set_major_formatter(plain)
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=80)
    print("wrote", args.output)
    if args.json:
        import json

        with open(args.json, "w") as f:
            json.dump({"scene": args.scene, "device": device, "photons_per_frame": photons, "reference": reference_text,
                       "estimators": {e: [dict(seconds=s, frames=n, rmse=r) for s, n, r in rows]
                                      for e, rows in curves.items()}}, f, indent=1)


if __name__ == "__main__":
    main()
