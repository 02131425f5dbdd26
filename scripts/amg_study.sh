#!/usr/bin/env bash
# The tet4 algebraic-multigrid study (bench/amg_study.py): installs numpy,
# scipy and pyamg from PyPI into build/amg-venv (once), then runs the study
# on build/snh-gpu-bench with the arguments given (e.g. --res 14,22).
# Results: bench-results/amg_study.{md,json}.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=build/amg-venv
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import numpy, scipy, pyamg' 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet numpy scipy pyamg
fi
[ -x build/snh-gpu-bench ] || { echo "amg_study.sh: build/snh-gpu-bench missing (run scripts/setup.sh)" >&2; exit 1; }
# One BLAS thread: timings on a shared machine, and the same for every method.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$PWD/build/pocl-cache}
exec "$venv/bin/python" bench/amg_study.py "$@"
