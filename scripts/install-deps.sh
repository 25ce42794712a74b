#!/usr/bin/env bash
# Installs the Debian packages gacompare needs, only those missing. Safe to re-run.
# Uses sudo when not root. Debian 12 (bookworm) package names.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git
  binutils                 # objdump: scripts/count-flops.py (build-essential pulls it in; named for the reader)
  ccache                   # reuses objects across checkouts; the build works without it
  libeigen3-dev            # Eigen 3.4: traditional backend
  libbullet-dev            # Bullet, double precision build (pkg-config bullet-float64)
  libfcl-dev libccd-dev    # FCL 0.7 + libccd: collision referee
  libgtest-dev libgmock-dev
  libbenchmark-dev         # Google Benchmark
  nlohmann-json3-dev       # scene files, results.json
  libcli11-dev             # command line
  libssl-dev               # SHA-256 of scene files (libcrypto)
  libqhull-dev libtinyobjloader-dev  # convex hulls (Qhull, reentrant C API), OBJ meshes
  libgoogle-perftools-dev  # tcmalloc: the executables' allocator (CMakeLists.txt says why)
  libboost-dev             # Boost.Odeint: the peer our solvers are checked and timed against
  python3                  # scripts/results.py and the tools it runs (docs/results/)
  gnuplot-nox              # plots: work-precision diagrams, report figures
  clang libclang-rt-dev    # the libFuzzer targets (scripts/fuzz.sh): clang with its fuzzer and sanitizer runtimes
  chromium                 # the harness test renders report.html headless
  libjs-three              # three.js (non-module build), inlined into replay.html
  slurmctld slurmd slurm-client munge  # the Slurm test: sweeps as a job array on a single-node Slurm it starts
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present" >&2
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
