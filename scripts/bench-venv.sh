#!/usr/bin/env bash
# A virtual environment used only by benchmarks that compare against peer programs (pySLAMMER), from PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x .venv-bench/bin/python ]] || python3 -m venv .venv-bench
.venv-bench/bin/pip install -q --disable-pip-version-check numpy pyslammer
