#!/usr/bin/env bash
# Installs what topple needs from Debian's packages (idempotent; run as root or with sudo).
#
#   scripts/install-deps.sh --run     build and run the `topple` command (the main job, scripts/demo.sh): compiler,
#                                     CMake, the libraries it links, gnuplot for its figures and reports, GMT with its
#                                     coastlines and borders and ghostscript for the regional report's map
#   scripts/install-deps.sh --python  --run plus Python's headers and venv, for the Python package (python-venv.sh)
#   scripts/install-deps.sh --test    everything: --python plus the test and benchmark libraries, MPI, clang (fuzzing)
#                                     and chromium (the report is opened in a headless browser); scripts/test.sh
#   scripts/install-deps.sh           the same as --test (what it did before the modes existed)
#
# MPI is optional for running (`topple sweep` splits its chunks across ranks only when built with it): --run leaves
# it out, --test installs it. GMT is optional too: without it the regional report is written with a note where the map
# would be. Python tools used only by tests and benchmarks live in virtual environments
# (scripts/python-venv.sh, scripts/test-venv.sh).
set -euo pipefail

mode="${1:---test}"
run_packages=(
  build-essential cmake ninja-build pkg-config
  libcli11-dev libfmt-dev nlohmann-json3-dev libtomlplusplus-dev libboost-dev
  libtbb-dev libfftw3-dev libxxhash-dev
  libgeographiclib-dev  # geodesic distances (WGS84, Karney 2013) for the regional fit
  libcgal-dev  # meshes (topple body): reading OBJ/OFF/STL/PLY in double precision; convex hull, self-intersection
  gnuplot-nox  # figures: --plot, the inversion report
  gmt gmt-gshhg gmt-dcw ghostscript  # the regional report's map: GMT, its coastlines and borders (GSHHG), its
                                     # country polygons (DCW, for coast -E when restyling), ghostscript for the PNG
)
python_packages=(python3 python3-venv python3-dev)
test_packages=(
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  libopenmpi-dev openmpi-bin
  clang     # the fuzz preset (libFuzzer)
  libsiconos-kernel-dev libsiconos-mechanics-dev libsiconos-numerics-dev  # test_siconos_reference: the 3-D check
  chromium  # the inversion report is opened in a real headless browser
  ccache    # scripts/test.sh: the Python package's build reuses the release build's objects of the library
)
case "$mode" in
  --run) packages=("${run_packages[@]}") ;;
  --python) packages=("${run_packages[@]}" "${python_packages[@]}") ;;
  --test) packages=("${run_packages[@]}" "${python_packages[@]}" "${test_packages[@]}") ;;
  -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
  *) echo "install-deps: unknown mode '$mode' (use --run, --python or --test)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  sudo=""
  [[ $(id -u) -eq 0 ]] || sudo="sudo"
  echo "install-deps ($mode): installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install-deps ($mode): all Debian packages present"
fi
