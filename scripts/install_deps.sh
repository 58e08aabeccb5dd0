#!/usr/bin/env bash
# Installs the Debian 12 packages granasym needs, when missing.
#
# chromium is the headless browser of the report test
# (tests/study/report_browser_test.sh): about 113 MB to download and 520 MB
# installed with its 23 libraries (GTK 3, codecs) on a machine with the
# build packages; about a minute.
#
# slurm-wlm (slurmctld, slurmd, slurm-client) and munge are for the Slurm
# tests, which start a private single-node cluster (tests/slurm/). Their
# maintainer scripts would start the system daemons; in a container (no init)
# that fails and fails the install, and on a workstation the tests do not want
# them. So they are installed with a policy-rc.d that forbids starting
# services (exit 101, invoke-rc.d's "action not allowed"), unless the machine
# already has one; it is removed again afterwards.
# clang-format (14 on Debian 12) is for the test that keeps the tree
# formatted (scripts/check_format.sh). ccache caches compilations for
# scripts/build.sh (rebuilds after a branch switch or a clean).
# python3-sphinx and python3-myst-parser build the user guide (docs/guide;
# the test Docs.guide_builds and the target `docs`).
# python3-dev and pybind11-dev build the Python module (`import granasym`,
# python/); python3-numpy and python3-pandas are what it returns, and
# python3-pytest runs its tests (tests/python).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config ccache
  libeigen3-dev libceres-dev libgoogle-glog-dev libnlopt-cxx-dev libnlopt-dev libsundials-dev libhdf5-dev
  libcli11-dev libtoml11-dev libfmt-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox
  python3-sphinx python3-myst-parser
  python3-dev pybind11-dev python3-numpy python3-pandas python3-pytest
  clang-format
  chromium
)
daemon_packages=(slurm-wlm munge)
installed() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}
missing=()
for package in "${packages[@]}"; do
  if ! installed "$package"; then missing+=("$package"); fi
done
missing_daemons=()
for package in "${daemon_packages[@]}"; do
  if ! installed "$package"; then missing_daemons+=("$package"); fi
done
all_missing=("${missing[@]}" "${missing_daemons[@]}")
if [ ${#all_missing[@]} -eq 0 ]; then
  exit 0
fi
echo "granasym: installing missing Debian packages: ${all_missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
    echo "error: packages missing (${all_missing[*]}) and not root; run as root or install them" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if [ ${#missing_daemons[@]} -gt 0 ]; then
  policy=/usr/sbin/policy-rc.d
  if [ ! -e "$policy" ]; then
    trap '$sudo rm -f "$policy"' EXIT
    printf '#!/bin/sh\n# granasym install_deps.sh: no services started while installing\nexit 101\n' |
      $sudo tee "$policy" >/dev/null
    $sudo chmod 755 "$policy"
  fi
  $sudo apt-get install -y -qq --no-install-recommends "${missing_daemons[@]}" </dev/null
fi
