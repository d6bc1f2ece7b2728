#!/usr/bin/env bash
# The one place where granflow's dependencies are named. All are Debian 12 packages.
# Installs only what is missing; safe to call at every run.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git   # toolchain
  petsc-dev                              # PETSc 3.18 with OpenMPI and hypre: grids, KSP, options
  libopenblas0-serial                    # optimised BLAS for PETSc's vector kernels (petsc-dev
                                         # alone brings the reference BLAS: case A's viscous
                                         # solves 23 % slower); serial, one thread per MPI rank
  openmpi-bin                            # mpirun
  libtomlplusplus-dev                    # TOML case files
  libcli11-dev                           # command-line parser
  libgtest-dev                           # unit tests (GoogleTest)
  python3 python3-numpy python3-matplotlib  # figures and report scripts
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "granflow: installing missing Debian packages: ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
