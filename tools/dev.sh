#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine (run as root, or with sudo):
#   tools/dev.sh render   install what is missing, build (Release), render scenes/default.toml
#                         to out/default.png
#   tools/dev.sh test     install what is missing, build, run the whole test suite (ctest),
#                         then the unit tests again under AddressSanitizer + UBSan
#   tools/dev.sh bench    install, build, run the benchmarks (Google Benchmark)
# Both are idempotent: packages are installed only when missing, builds are incremental.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-}
case "$mode" in render|test|bench|build) ;; *)
  echo "usage: tools/dev.sh render|test|bench|build" >&2; exit 2 ;;
esac

packages=(cmake make g++ pkg-config
          libgeographiclib-dev libgdal-dev libopenimageio-dev libtomlplusplus-dev
          libcli11-dev libfmt-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev povray chromium fonts-dejavu-core)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

jobs=$(nproc)
build() {  # build DIR [cmake args...]
  local dir=$1; shift
  [ -f "$dir/CMakeCache.txt" ] || cmake -S . -B "$dir" "$@" >/dev/null
  cmake --build "$dir" -j "$jobs"
}

case "$mode" in
  build) build build -DCMAKE_BUILD_TYPE=Release ;;
  render)
    build build -DCMAKE_BUILD_TYPE=Release
    ./build/relief render scenes/default.toml
    ;;
  test)
    build build -DCMAKE_BUILD_TYPE=Release
    (cd build && ctest --output-on-failure -j "$jobs")
    echo "== unit tests under AddressSanitizer + UBSan"
    build build-asan -DCMAKE_BUILD_TYPE=Debug -DRELIEF_SANITIZE=ON -DRELIEF_BUILD_BENCH=OFF
    (cd build-asan && ctest --output-on-failure -j "$jobs" -L "unit|cli")
    ;;
  bench)
    build build -DCMAKE_BUILD_TYPE=Release
    ./build/bench/relief_bench --benchmark_counters_tabular=true
    ;;
esac
