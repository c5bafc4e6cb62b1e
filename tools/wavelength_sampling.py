#!/usr/bin/env python3
"""How close a flat spectrum seen through the frames' wavelength sets comes to white, for densities
paths could draw wavelengths from (core/spectral/spectrum.cpp chose |r|+|g|+|b|): the largest
channel error after 1, 4, 16 and 64 frames, mean over three seeds, with three wavelengths a frame a
third of the cdf apart and the hero stepping by `step` (golden ratio / 3, as frameSpectrum does, or
the golden ratio).  Needs numpy.   python3 tools/wavelength_sampling.py"""
import numpy as np


def lobe(x, mu, below, above):
    s = np.where(x < mu, below, above)
    return np.exp(-0.5 * ((x - mu) / s) ** 2)


def cie1931(l):  # Wyman, Sloan & Shirley 2013, as core/spectral/spectrum.cpp
    x = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) - 0.065 * lobe(l, 501.1, 20.4, 26.2)
    y = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1)
    z = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8)
    return np.stack([x, y, z], -1)


SRGB = np.array([[3.2404542, -1.5371385, -0.4985314], [-0.9692660, 1.8760108, 0.0415560],
                 [0.0556434, -0.2040259, 1.0572252]])
STEP = 0.05
L = np.arange(360, 830, STEP) + STEP / 2
RGB = cie1931(L) @ SRGB.T
RGB /= RGB.sum(0) * STEP  # white-balanced: the flat spectrum is (1, 1, 1)

DENSITIES = {
    "pbrt-v4 SampleVisible (~y)": 1 / np.cosh(0.0072 * (L - 538)) ** 2,
    "x + y + z": cie1931(L).sum(-1),
    "uniform": np.ones_like(L),
    "|r| + |g| + |b| (chosen)": np.abs(RGB).sum(-1),
}

for step_name, step in (("golden ratio / 3", 0.6180339887 / 3), ("golden ratio", 0.6180339887)):
    print(f"hero step {step_name}: largest channel error after 1, 4, 16, 64 frames")
    for name, density in DENSITIES.items():
        pdf = density / (density.sum() * STEP)
        cdf = np.cumsum(pdf) * STEP
        errors = []
        for seed in (0.1, 0.37, 0.77):
            row = []
            for frames in (1, 4, 16, 64):
                total = np.zeros(3)
                for f in range(frames):
                    hero = (seed + f * step) % 1
                    for i in range(3):
                        j = min(np.searchsorted(cdf, (hero + i / 3) % 1), len(L) - 1)
                        total += RGB[j] / pdf[j] / 3
                row.append(np.abs(total / frames - 1).max())
            errors.append(row)
        print(f"  {name:28s}", " ".join(f"{e:.4f}" for e in np.mean(errors, 0)))
