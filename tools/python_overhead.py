# The Python module's overhead over photon-render for the same frames (docs/python.md). Run from the
# repository root after the README's build: python3 tools/python_overhead.py
import subprocess, sys, time
sys.path.insert(0, "build/release/python")
import photon
args = dict(backend="cpu", width=640, height=480, photons=100000, frames=10, deterministic=True, seed=1)
cli = ["build/release/bin/photon-render", "scenes/cornell.json", "-q", "-o", "/tmp/o.pfm"] + sum([["--" + k.replace("_", "-")] if v is True else ["--" + k.replace("_", "-"), str(v)] for k, v in args.items()], [])
py, sh = [], []
for rep in range(3):
    t = time.perf_counter(); subprocess.run(cli, check=True); sh.append(time.perf_counter() - t)
    t = time.perf_counter(); photon.render("scenes/cornell.json", **args); py.append(time.perf_counter() - t)
print("photon-render s:", " ".join("%.3f" % x for x in sh))
print("photon.render s:", " ".join("%.3f" % x for x in py))
print("median ratio: %.4f" % (sorted(py)[1] / sorted(sh)[1]))
