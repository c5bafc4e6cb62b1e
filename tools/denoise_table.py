#!/usr/bin/env python3
"""The denoiser's table (issue 37): error against time, raw and denoised, from photon-converge's
JSON (one file per scene, made with --set denoise=on and --times), as Markdown; and, with
--picture, a side-by-side picture of one checkpoint's raw and denoised images beside the reference.

Usage:
  tools/denoise_table.py converge-cornell.json converge-caustic.json ...
  tools/denoise_table.py --picture out.png ref.pfm raw.pfm denoised.pfm [x0 y0 x1 y1]
Columns: stage time (the denoised image's includes the denoise stage), relative RMSE of the whole
image, away from the focus (outside the reference's brightest 0.5%), at the reference's edges,
SSIM of the sRGB display images, and the focus's energy relative to the reference's.
"""
import json
import sys


def table(files):
    print("| scene | frames | ms | whole raw → denoised | away from focus | edges | SSIM | focus energy |")
    print("|---|---:|---:|---|---|---|---|---|")
    for path in files:
        data = json.load(open(path))
        name = data["scene"].split(":")[0]
        for estimator, rows in data["estimators"].items():
            for r in rows:
                d = r.get("denoised")
                if d is None:
                    continue
                print(f"| {name} | {r['frames']} | {r['ms']:.0f} (+{r['denoise_ms']:.1f}) "
                      f"| {100 * r['rmse']:.2f}% → **{100 * d['rmse']:.2f}%** "
                      f"| {100 * r['rmse_away_from_focus']:.2f}% → **{100 * d['rmse_away_from_focus']:.2f}%** "
                      f"| {100 * r['rmse_edges']:.2f}% → {100 * d['rmse_edges']:.2f}% "
                      f"| {r['ssim']:.3f} → **{d['ssim']:.3f}** "
                      f"| {r['focus_energy_ratio']:.3f} → {d['focus_energy_ratio']:.3f} |")


def read_pfm(path):
    import numpy as np
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            raise SystemExit(f"{path}: not an RGB PFM")
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        pixels = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4").reshape(h, w, 3)
    return pixels[::-1]


def picture(out, paths, crop):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    images = []
    for p in paths:
        x = np.clip(read_pfm(p), 0.0, 1.0)
        srgb = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
        if crop:
            x0, y0, x1, y1 = crop
            srgb = srgb[y0:y1, x0:x1]
        images.append(srgb)
    gap = np.ones((images[0].shape[0], 4, 3))
    row = images[0]
    for image in images[1:]:
        row = np.concatenate([row, gap, image], axis=1)
    plt.imsave(out, np.clip(row, 0, 1))


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--picture":
        out, paths = sys.argv[2], sys.argv[3:6]
        crop = [int(v) for v in sys.argv[6:10]] if len(sys.argv) >= 10 else None
        picture(out, paths, crop)
        return
    table(sys.argv[1:])


if __name__ == "__main__":
    main()
