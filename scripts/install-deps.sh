#!/usr/bin/env bash
# Installs the Debian 12 packages RigidFlex needs to build and test. Idempotent: packages
# already present are left alone. Runs apt-get as root (directly or via sudo); otherwise
# prints the one command to run.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libeigen3-dev      # small dense linear algebra in kernels
  libmuparser-dev    # *PARAMETER_EXPRESSION and function expressions
  libcli11-dev       # command line
  libfmt-dev         # formatting of messages and output files
  libhdf5-dev        # restart dumps and the mode database (HDF5 C API)
  libspectra-dev     # Lanczos eigensolver (eigen analysis)
  libsuitesparse-dev # CHOLMOD sparse Cholesky (eigen analysis)
  libgtest-dev       # unit and verification tests
  libbenchmark-dev   # kernel benchmarks
  python3            # result read-back tests (tests/python: standard library only)
  python3-matplotlib # scripts/rigidflex-plot.py (PNG plots of a run; its test skips without it)
  python3-paraview   # pvpython: the last frame as a PNG, ParaView's LS-DYNA reader on our d3plot
  xvfb xauth         # xvfb-run: an X display for pvpython on a headless machine
  clang              # libFuzzer targets and the sanitizer stage of scripts/test.sh
  libclang-rt-dev    # clang's sanitizer and libFuzzer runtimes (not pulled in without recommends)
  libomp-dev         # OpenMP runtime for clang builds (LLVM's libomp)
  libopenmpi-dev openmpi-bin # distributed runs (src/parallel, docs/parallel.md)
  libmetis-dev       # element partitioning for distributed runs (METIS 5)
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  SUDO="sudo"
else
  echo "install-deps: not root; run this as root:" >&2
  echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
