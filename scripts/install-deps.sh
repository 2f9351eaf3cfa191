#!/usr/bin/env bash
# Installs what topple needs to build and test, from Debian's packages (idempotent; run as root or with sudo).
# Python tools used only by tests and benchmarks live in a virtual environment: see scripts/python-venv.sh.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang
  libcli11-dev libfmt-dev nlohmann-json3-dev libtomlplusplus-dev libboost-dev
  libtbb-dev libopenmpi-dev openmpi-bin libfftw3-dev libxxhash-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  gnuplot-nox python3 python3-venv
  chromium  # test only: the inversion report is opened in a real headless browser
  python3-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  sudo=""
  [[ $(id -u) -eq 0 ]] || sudo="sudo"
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install-deps: all Debian packages present"
fi
