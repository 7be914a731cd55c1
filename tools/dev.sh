#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine (run as root, or with sudo):
#   tools/dev.sh render   install what is missing, build (Release), render scenes/default.toml
#                         to out/default.png
#   tools/dev.sh test     install what is missing, build, run the whole test suite (ctest),
#                         then, built with clang under AddressSanitizer + UBSan, the unit and
#                         command-line tests again and the readers under libFuzzer
#   tools/dev.sh bench    install, build, run the benchmarks (Google Benchmark)
#   tools/dev.sh build    install, build (Release)
#   tools/dev.sh check    the quick loop: build (Release), the unit and command-line tests but the
#                         longest (label slow): a few minutes after a change to one file
# Each is idempotent and recovers from an interrupted or failed earlier run: packages are
# installed only when missing (a half-installed one is finished first), builds are incremental,
# and a build folder whose configure step never completed is configured again.
# tools/fresh-machine-check.sh proves these commands in a minimal Debian 12 root.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-}
case "$mode" in render|test|bench|build|check) ;; *)
  echo "usage: tools/dev.sh render|test|bench|build|check" >&2; exit 2 ;;
esac

# openimageio-tools: Debian 12's OpenImageIO CMake config names its command-line tools
# (/usr/bin/iconvert, ...) as imported targets, so find_package fails without them.
# locales: the definitions the tests build a decimal-comma locale from.
# clang, libfuzzer-14-dev, libclang-rt-14-dev (the sanitizers' and libFuzzer's runtimes): the
# sanitizer build and its fuzz targets; libomp-14-dev: OpenMP for clang (g++ has its own).
# bubblewrap: POV-Ray's sandbox. libpng-dev: PNGs outside the image commands; libssl-dev: SHA-1.
# libcairo2-dev, libpango1.0-dev: the still's overlays (text through fontconfig: fonts-dejavu-core).
# libnova-dev: the sun's position from a date ([lighting] datetime).
# libeigen3-dev, libsuitesparse-dev: the sparse matrices and the Cholesky (CHOLMOD) that fit a net
# to scattered samples (net.gridding = "fit").
# slurm-wlm, munge: the tests' private Slurm cluster (tests/slurm/cluster.sh; relief --executor slurm).
# gdal-bin: gdal_translate and gdalwarp, which the tests cut DEM tiles with and the benchmarks make
# rasters of every size with (relief itself links libgdal).
# ffmpeg: relief animate encodes its frames to MP4, WebM or GIF with it.
# libassimp-dev, libtinygltf-dev: relief export's STL, OBJ and PLY, and its glTF; assimp-utils and
# admesh: the tests read the glTF back with Assimp and check the STL is a closed solid.
# libcpp-httplib-dev: relief preview's server. nodejs, npm: the build installs the preview page's
# packages (web/package-lock.json: three.js, esbuild, playwright-core) with npm ci and bundles the
# page; a Node.js of another source with its own npm (NodeSource's) is used as it is. curl, iproute2
# (ss): the preview's test asks its server and reads where it listens.
# poppler-utils: pdftotext, pdffonts, pdfimages, pdfinfo, which the tests read PDF stills back with.
# ccache: a compiler cache outside the clone, so that a second build on this machine (a clean clone
# of CI's included) compiles only what changed.
packages=(cmake make g++ pkg-config
          libgeographiclib-dev libgdal-dev libopenimageio-dev openimageio-tools libtomlplusplus-dev
          libcli11-dev libfmt-dev nlohmann-json3-dev libnanoflann-dev libeigen3-dev libsuitesparse-dev libpng-dev libssl-dev libcairo2-dev libpango1.0-dev libnova-dev libgtest-dev libbenchmark-dev
          libassimp-dev libtinygltf-dev assimp-utils admesh libcpp-httplib-dev curl iproute2
          povray bubblewrap chromium fonts-dejavu-core locales clang libfuzzer-14-dev libclang-rt-14-dev libomp-14-dev
          slurm-wlm munge gdal-bin ffmpeg poppler-utils ccache)
command -v npm >/dev/null || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  # An interrupted earlier install leaves packages unpacked but not configured: finish them.
  $sudo dpkg --configure -a
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq -f --no-install-recommends
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

jobs=$(nproc)
# The compiler cache lives outside the clone (ccache's own ~/.cache/ccache unless CCACHE_DIR says),
# and paths under the clone are hashed relative to it (CCACHE_BASEDIR; the unity builds' sources
# too), so a clone elsewhere on the machine finds what this one compiled.
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-10G}"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
build() {  # build DIR [cmake args...]; TARGETS="a b" builds only those
  local dir=$1; shift
  # CMake writes CMakeCache.txt before it checks anything, and the build system (Makefile) only
  # when configuring succeeded; without a Makefile the folder is half-configured: start afresh.
  if [ ! -f "$dir/Makefile" ]; then
    rm -rf "$dir"
    cmake -S . -B "$dir" "${launcher[@]}" "$@" >/dev/null
  elif [ ${#launcher[@]} -gt 0 ] && ! grep -q '^CMAKE_CXX_COMPILER_LAUNCHER:.*ccache' "$dir/CMakeCache.txt"; then
    cmake -S . -B "$dir" "${launcher[@]}" >/dev/null  # a folder configured before the cache was
  fi
  local targets=()
  for t in ${TARGETS:-}; do targets+=(--target "$t"); done
  cmake --build "$dir" -j "$jobs" "${targets[@]}"
}

case "$mode" in
  build) build build -DCMAKE_BUILD_TYPE=Release ;;
  check)
    build build -DCMAKE_BUILD_TYPE=Release
    (cd build && ctest --output-on-failure --timeout 900 -j "$jobs" -L "unit|cli" -LE slow)
    ;;
  render)
    build build -DCMAKE_BUILD_TYPE=Release
    ./build/relief render scenes/default.toml
    ;;
  test)
    # --timeout: a test that hangs fails by itself (named) instead of stalling the whole run.
    timeout=900
    build build -DCMAKE_BUILD_TYPE=Release
    (cd build && ctest --output-on-failure --timeout "$timeout" -j "$jobs")
    # One clang build under AddressSanitizer + UBSan serves both the second run of the unit and
    # command-line tests and the readers' libFuzzer targets, where a third build of everything
    # (g++'s sanitizer build, -DRELIEF_SANITIZE=ON, still there to be made by hand) took 5 minutes.
    echo "== under AddressSanitizer + UBSan (clang): the unit and command-line tests, and each reader under libFuzzer for ${RELIEF_FUZZ_SECONDS:-30} s"
    build build-sanitize -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRELIEF_FUZZ=ON \
      -DRELIEF_BUILD_BENCH=OFF -DRELIEF_FUZZ_SECONDS="${RELIEF_FUZZ_SECONDS:-30}"
    (cd build-sanitize && ctest --output-on-failure --timeout "$timeout" -j "$jobs" -L "unit|cli|fuzz")
    ;;
  bench)
    build build -DCMAKE_BUILD_TYPE=Release
    ./build/bench/relief_bench --benchmark_counters_tabular=true
    ;;
esac
