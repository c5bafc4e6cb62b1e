# The Python module's overhead over photon-render for the same frames (docs/python.md). Run from the
# repository root after the README's build:
#   python3 tools/python_overhead.py [BACKEND [WIDTHxHEIGHT [PHOTONS [FRAMES]]]]
# (defaults: cpu 640x480 100000 10); PHOTON_RENDER and PHOTON_PYTHON_DIR point elsewhere.
import os, subprocess, sys, time
sys.path.insert(0, os.environ.get("PHOTON_PYTHON_DIR", "build/release/python"))
import photon
backend, size, photons, frames = (sys.argv[1:] + ["cpu", "640x480", "100000", "10"][len(sys.argv) - 1:])[:4]
width, height = map(int, size.split("x"))
args = dict(backend=backend, width=width, height=height, photons=int(photons), frames=int(frames), deterministic=True, seed=1)
cli = [os.environ.get("PHOTON_RENDER", "build/release/bin/photon-render"), "scenes/cornell.json", "-q", "-o", "/tmp/o.pfm"]
cli += sum([["--" + k.replace("_", "-")] if v is True else ["--" + k.replace("_", "-"), str(v)] for k, v in args.items()], [])
py, sh = [], []
for rep in range(3):
    t = time.perf_counter(); subprocess.run(cli, check=True); sh.append(time.perf_counter() - t)
    t = time.perf_counter(); photon.render("scenes/cornell.json", **args); py.append(time.perf_counter() - t)
print("%s %s, %s photons, %s frames" % (backend, size, photons, frames))
print("photon-render s:", " ".join("%.3f" % x for x in sh))
print("photon.render s:", " ".join("%.3f" % x for x in py))
print("median ratio: %.4f" % (sorted(py)[1] / sorted(sh)[1]))
