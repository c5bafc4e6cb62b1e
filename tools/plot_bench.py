#!/usr/bin/python3
"""Charts from photon-bench JSON (photon-bench --json FILE).

  tools/plot_bench.py series.json stages.json --out docs/

writes docs/cpu_vs_gpu.png (the seed's chart: frame time over resolution, one line per backend,
from the first file) and docs/stages.png (per-stage times of each row of the second file, stacked).
"""
import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = ["#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#b07aa1"]


def rows_of(paths):
    rows = []
    for path in paths.split(","):
        with open(path) as f:
            rows += json.load(f)["rows"]
    return rows


def stage_names(paths):
    """The stages in the order a frame runs them, as photon-bench lists them (its "stages"; files
    from before that list give only the keys of stages_ms)."""
    with open(paths.split(",")[0]) as f:
        j = json.load(f)
    return j.get("stages") or list(j["rows"][0]["stages_ms"])


def cpu_vs_gpu(rows, out):
    fig, ax = plt.subplots(figsize=(7, 4.2), dpi=110)
    labelled = False
    for backend, device in sorted({(r["backend"], r["device"]) for r in rows}):
        pts = sorted((r["width"] * r["height"], r["frame_ms"], f'{r["width"]}x{r["height"]}')
                     for r in rows if r["backend"] == backend and r["device"] == device)
        photons = pts and next(r["photons"] for r in rows if r["backend"] == backend and r["device"] == device)
        ax.plot([p[0] / 1e6 for p in pts], [p[1] for p in pts], marker="o",
                label=f"{backend}: {device}, {photons / 1e6:g}M photons")
        if not labelled:
            for p in pts:
                ax.annotate(p[2], (p[0] / 1e6, p[1]), textcoords="offset points", xytext=(4, 4), fontsize=7)
            labelled = True
    ax.set_xlabel("megapixels")
    ax.set_ylabel("frame time (ms, log scale)")
    ax.set_yscale("log")
    photons = sorted({r["photons"] / 1e6 for r in rows})
    ax.set_title(f'{rows[0]["scene"]}: one frame, ' + " / ".join(f"{p:g}M" for p in photons) + " photons (see legend)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "cpu_vs_gpu.png"))


def stages(rows, names, out):
    fig, ax = plt.subplots(figsize=(7, 1.4 + 0.45 * len(rows)), dpi=110)
    labels = [f'{r["backend"]} {r["width"]}x{r["height"]} {r["variant"]}'.strip() for r in rows]
    left = [0.0] * len(rows)
    for stage, colour in zip(names, COLOURS * (1 + len(names) // len(COLOURS))):
        values = [r["stages_ms"][stage] for r in rows]
        ax.barh(labels, values, left=left, color=colour, label=stage)
        left = [a + b for a, b in zip(left, values)]
    for y, total in enumerate(left):
        ax.text(total, y, f" {total:.2f} ms", va="center", fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("milliseconds per frame (median)")
    devices = " / ".join(sorted({r["device"] for r in rows}))
    ax.set_title(f'{rows[0]["scene"]}, {rows[0]["photons"] / 1e6:g}M photons per frame, {devices}', fontsize=9)
    ax.legend(fontsize=7, ncol=5, loc="upper center", bbox_to_anchor=(0.5, -0.12 - 0.6 / len(rows)))
    ax.set_xlim(0, max(left) * 1.25)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "stages.png"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("series", help="photon-bench JSON over resolutions and backends (comma-separated files)")
    parser.add_argument("stages", help="photon-bench JSON whose rows to break down by stage (comma-separated files)")
    parser.add_argument("--out", default="docs")
    args = parser.parse_args()
    cpu_vs_gpu(rows_of(args.series), args.out)
    stages(rows_of(args.stages), stage_names(args.stages), args.out)


if __name__ == "__main__":
    main()
