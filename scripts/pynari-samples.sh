#!/usr/bin/env bash
# Runs pynari's own samples (samples/*.py of a pynari checkout) unchanged on this build's pynari module:
# each writes its image with -o, which must not be blank. Usage: scripts/pynari-samples.sh PYNARI_DIR [BUILD]
# The samples import matplotlib.pyplot and use it only without -o; where python3-matplotlib is absent, a
# stand-in that imports PIL.Image (as matplotlib does, and as the samples rely on) takes its place.
set -euo pipefail
src=$(cd "$1/samples" && pwd)
build=$(cd "${2:-build}" && pwd)
python=${PYTHON:-/usr/bin/python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$src"/. "$work/"  # the samples read their data files from the working folder
if ! "$python" -c "import matplotlib.pyplot" 2>/dev/null; then
  mkdir -p "$work/stand-in/matplotlib"
  : > "$work/stand-in/matplotlib/__init__.py"
  printf 'import PIL.Image\n' > "$work/stand-in/matplotlib/pyplot.py"
fi
export PYTHONPATH="$build/python:$work/stand-in${PYTHONPATH:+:$PYTHONPATH}"
export ANARI_LIBRARY=${ANARI_LIBRARY:-ripple}  # sample06 names a library itself, barney_mpi unless set
cd "$work"
failed=0
for sample in *.py; do
  name=${sample%.py}
  start=$(date +%s)
  if "$python" "$sample" -o "$name.png" > "$name.log" 2>&1 && [ -f "$name.png" ] &&
     "$python" -c "import sys, numpy as np, PIL.Image as I; a = np.asarray(I.open(sys.argv[1])).astype(float); sys.exit(0 if a.std() > 1 else 1)" "$name.png"; then
    echo "ok      $name ($(( $(date +%s) - start )) s)"
  elif [ "$name" = sample-getInfo ] && grep -q "renderer understands" "$name.log"; then
    echo "ok      $name (prints device information; no image)"
  else
    echo "FAILED  $name: $(grep -E 'Error|error|blank' "$name.log" | tail -n 1 | cut -c1-240)"
    failed=1
  fi
done
exit $failed
