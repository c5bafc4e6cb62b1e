#!/usr/bin/env python3
"""Plots error against GPU time from photon-converge's JSON (one file per scene).

Usage: tools/plot_converge.py out.png converge-smallpt.json converge-caustic.json ...
Each scene gets two panels: the whole image's relative RMSE, and the caustic window's peak
against the reference's (1 is converged), both over the summed stage time, log-scaled.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    out, files = sys.argv[1], sys.argv[2:]
    fig, axes = plt.subplots(2, len(files), figsize=(4.2 * len(files), 6.4), squeeze=False)
    for column, path in enumerate(files):
        data = json.load(open(path))
        for estimator, rows in data["estimators"].items():
            ms = [r["ms"] for r in rows]
            axes[0][column].loglog(ms, [r["rmse"] for r in rows], marker=".", label=estimator)
            axes[1][column].semilogx(ms, [r["peak_ratio"] for r in rows], marker=".", label=estimator)
        title = data["scene"].split(":")[0]
        axes[0][column].set_title(f"{title}\n{data['device']}, {data['photons_per_frame'] // 1000}k photons a frame",
                                  fontsize=9)
        axes[0][column].set_ylabel("relative RMSE, whole image")
        axes[1][column].set_ylabel("caustic window: peak / reference")
        axes[1][column].axhline(1.0, color="grey", linewidth=0.5)
        for row in axes:
            row[column].set_xlabel("GPU time, ms (sum of the stages)")
            row[column].grid(True, which="both", linewidth=0.3)
        axes[0][column].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
