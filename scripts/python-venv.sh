#!/usr/bin/env bash
# The Python package's virtual environment .venv-py (README, "Python"): Debian's python3 (/usr/bin/python3, with the
# python3-dev headers from scripts/install-deps.sh), numpy, matplotlib, pytest from PyPI, and topple itself built by
# scikit-build-core from this checkout. Idempotent: the package is rebuilt incrementally in build/python (pyproject's
# build-dir), without build isolation so that the same scikit-build-core and nanobind (installed here) are used every
# time. Quiet unless something fails.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-py
python=/usr/bin/python3
[[ -x $python ]] || python=python3
if [[ ! -x $venv/bin/python ]]; then
  "$python" -m venv "$venv"
fi
pip=($venv/bin/python -m pip -q --disable-pip-version-check)
if ! $venv/bin/python -c "import numpy, matplotlib, pytest, scikit_build_core, nanobind" 2>/dev/null; then
  "${pip[@]}" install "numpy>=2" matplotlib pytest "scikit-build-core>=0.10" "nanobind>=2.0"
fi
# The distribution was named "topple" before it became topple-quake (pyproject.toml; "topple" on PyPI is another
# project): remove the old one first, or both would own the files of the package.
if $venv/bin/python -m pip show topple >/dev/null 2>&1; then
  "${pip[@]}" uninstall -y topple
fi
# CMAKE_BUILD_PARALLEL_LEVEL: the extension build uses every core (TOPPLE_JOBS when set).
# scripts/test.sh sets TOPPLE_PYTHON_CCACHE=1 (and ccache's settings): the library's objects then come from the
# release build's cache entries. Those match only for the same command line, compiler name included (ccache hashes
# it): scikit-build-core would otherwise set CXX to Python's sysconfig compiler (x86_64-linux-gnu-g++), where the
# release preset finds c++; both are Debian's GCC. CXX and the launcher are read on build/python's first configure
# only: a build/python made before this reuses nothing until it is removed.
if [[ ${TOPPLE_PYTHON_CCACHE:-0} == 1 ]]; then
  export CMAKE_CXX_COMPILER_LAUNCHER=ccache CXX="${CXX:-c++}"
fi
CMAKE_BUILD_PARALLEL_LEVEL="${TOPPLE_JOBS:-$(nproc)}" "${pip[@]}" install --no-build-isolation --no-deps ./
$venv/bin/python -c "import topple; topple.GroundMotion([0.0, 0.1], 0.01)"
