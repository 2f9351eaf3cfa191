#!/usr/bin/env bash
# A virtual environment used only by tests that compare against peer implementations (pyrotd, eqsig), from PyPI.
# Idempotent and quiet: does nothing when .venv-test already holds the packages. Tests that need it skip when it is
# absent (GTEST_SKIP), so a machine without network still passes the rest of the suite; a failed install removes
# the half-made environment rather than leave one that would make those tests fail.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-test
if [[ -x $venv/bin/python ]] && $venv/bin/python -c "import numpy, pyrotd, eqsig, pytest" 2>/dev/null; then
  exit 0
fi
[[ -x $venv/bin/python ]] || python3 -m venv "$venv"
# pyrotd imports pkg_resources: setuptools is listed for Pythons whose venvs no longer include it.
if ! $venv/bin/pip install -q --disable-pip-version-check numpy scipy pyrotd eqsig pytest setuptools; then
  rm -rf "$venv"
  echo "test-venv: could not install the peer packages; tests comparing against pyrotd/eqsig will be skipped" >&2
  exit 1
fi
