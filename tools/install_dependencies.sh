#!/usr/bin/env bash
# Installs everything voxremesh needs to build and test, from Debian's packages. Idempotent: it
# installs only what is missing. Runs apt-get as root, through sudo when not root.
set -euo pipefail

packages=(
  g++ cmake make ccache
  libopenvdb-dev libboost-iostreams-dev libtbb-dev libopenmesh-dev libgtest-dev zlib1g-dev
  libblosc-dev  # the .vdb layout check decompresses blosc blocks (src/volume/vdb_tree_layout.cpp)
  libopenvdb-tools python3-openvdb
  calculix-ccx  # tests/calculix_modes_test.cpp runs ccx on the original and remeshed decks
  clang libclang-rt-dev  # the sanitizer and fuzzing build (tools/ci_sanitizers.sh)
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_dependencies: all ${#packages[@]} packages present"
  exit 0
fi

as_root=()
if [ "$(id -u)" -ne 0 ]; then as_root=(sudo); fi
echo "install_dependencies: installing ${missing[*]}"
"${as_root[@]}" apt-get update -q
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
