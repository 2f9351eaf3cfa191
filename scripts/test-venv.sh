#!/usr/bin/env bash
# A virtual environment used only by tests that compare against peer implementations (pyrotd, eqsig), from PyPI.
# Idempotent and quiet: does nothing when .venv-test already holds the packages. Tests that need it skip when it is
# absent (GTEST_SKIP), so a machine without network still passes the rest of the suite.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-test
if [[ -x $venv/bin/python ]] && $venv/bin/python -c "import numpy, pyrotd, eqsig, pytest" 2>/dev/null; then
  exit 0
fi
[[ -x $venv/bin/python ]] || python3 -m venv "$venv"
$venv/bin/pip install -q --disable-pip-version-check numpy scipy pyrotd eqsig pytest
