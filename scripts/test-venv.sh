#!/usr/bin/env bash
# A virtual environment used only by tests that compare against peer implementations (pyrotd, eqsig), from PyPI.
# Idempotent and quiet: does nothing when .venv-test already holds the packages. Tests that need it skip when it is
# absent (GTEST_SKIP), so a machine without network still passes the rest of the suite; a failed install removes
# the half-made environment rather than leave one that would make those tests fail.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-test
# OpenQuake's hazardlib (BSSA14's peer, tests/inversion/test_prior.cpp) only with TOPPLE_TEST_HAZARDLIB=1: the test
# command compares against hazardlib's table (tests/peer/bssa14_hazardlib.json, written by tests/peer/peer_bssa14.py
# --table with the version it names) and leaves the comparison run live to this (it skips without hazardlib). The
# engine's full requirements need GDAL's development files, so the engine is installed without them and with only what
# `import openquake.hazardlib.gsim` needs (about 2 of the 2.7 minutes of this script from nothing on the CI machine,
# most of it numba); where that fails, the live BSSA14 peer test skips and the rest of the environment stays.
hazardlib() {
  [[ ${TOPPLE_TEST_HAZARDLIB:-0} == 1 ]] || return 0
  $venv/bin/python -c "import openquake.hazardlib.gsim.boore_2014" 2>/dev/null && return 0
  $venv/bin/pip install -q --disable-pip-version-check --no-deps openquake.engine &&
    $venv/bin/pip install -q --disable-pip-version-check pandas toml shapely pyproj h5py psutil requests decorator \
      numba h3 alpha_shapes pyzmq fiona 2>/dev/null &&
    $venv/bin/python -c "import openquake.hazardlib.gsim.boore_2014" 2>/dev/null ||
    echo "test-venv: OpenQuake's hazardlib did not install; the BSSA14 peer test will be skipped" >&2
  return 0
}
if [[ -x $venv/bin/python ]] && $venv/bin/python -c "import numpy, pyrotd, eqsig, pytest" 2>/dev/null; then
  hazardlib
  exit 0
fi
[[ -x $venv/bin/python ]] || python3 -m venv "$venv"
# pyrotd imports pkg_resources: setuptools is listed for Pythons whose venvs no longer include it.
if ! $venv/bin/pip install -q --disable-pip-version-check numpy scipy pyrotd eqsig pytest setuptools; then
  rm -rf "$venv"
  echo "test-venv: could not install the peer packages; tests comparing against pyrotd/eqsig will be skipped" >&2
  exit 1
fi
hazardlib
