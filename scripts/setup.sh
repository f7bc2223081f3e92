#!/usr/bin/env bash
# Install igacontact's build and script dependencies from Debian's packages.
# Idempotent: when everything is present it only checks and returns (about a second).
# Runs apt-get as root, through sudo otherwise.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas0-pthread libyaml-cpp-dev libhdf5-dev hdf5-tools
  libcli11-dev libfmt-dev libtinyxml2-dev libgtest-dev libgmock-dev libbenchmark-dev
  python3-numpy python3-h5py python3-matplotlib python3-yaml
  # The PETSc/MPI backend (solver.backend: petsc, mpirun): PETSc with MUMPS, hypre and
  # SuperLU_dist, Open MPI, and the MPI build of HDF5 that PETSc links (one HDF5 per process).
  petsc-dev openmpi-bin libhdf5-openmpi-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then sudo_cmd=(); else sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq >&2 || true
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
