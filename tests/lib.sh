# Helpers for the tests/*.sh scripts, which source this file: counting failures and checking
# images. A script ends with `exit "$failures"`.

failures=0

# fail <message>: one failed check, reported and counted.
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# finite_pfm <image.pfm>: every value of the PFM image is finite, and there is at least one.
finite_pfm() {
  python3 - "$1" <<'PY'
import array, math, sys
data = open(sys.argv[1], 'rb').read()
header, size, scale, pixels = data.split(b'\n', 3)
values = array.array('f'); values.frombytes(pixels)
sys.exit(0 if values and all(math.isfinite(v) for v in values) else 1)
PY
}
