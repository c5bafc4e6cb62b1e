#!/usr/bin/env python3
"""Box-filters a PFM image by an integer factor: a converged render at W × H, averaged over
factor × factor blocks, is the converged render at W/factor × H/factor (each pixel's jittered rays
cover its footprint evenly), so one long GPU render gives the tests small references.

Usage: tools/box_downsample.py in.pfm factor out.pfm
"""
import struct
import sys


def main():
    src, factor, dst = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    with open(src, "rb") as f:
        if f.readline().strip() != b"PF":
            raise SystemExit(f"{src}: not an RGB PFM")
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = f.read()
    if w % factor or h % factor:
        raise SystemExit(f"{src}: {w}x{h} is not a multiple of {factor}")
    fmt = "<" if scale < 0 else ">"
    values = struct.unpack(f"{fmt}{w * h * 3}f", data[: w * h * 12])
    ow, oh = w // factor, h // factor
    out = []
    for y in range(oh):  # PFM rows run bottom to top in both files alike
        for x in range(ow):
            for c in range(3):
                s = 0.0
                for dy in range(factor):
                    row = (y * factor + dy) * w
                    for dx in range(factor):
                        s += values[(row + x * factor + dx) * 3 + c]
                out.append(s / (factor * factor))
    with open(dst, "wb") as f:
        f.write(f"PF\n{ow} {oh}\n-1.0\n".encode())
        f.write(struct.pack(f"<{len(out)}f", *out))


if __name__ == "__main__":
    main()
