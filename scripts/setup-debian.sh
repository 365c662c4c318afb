#!/usr/bin/env bash
# Installs what cellctl needs on Debian 12, from Debian's packages only.
# Safe to run again: when everything is there it installs nothing and says so.
#   scripts/setup-debian.sh          the build, the test suite and the benchmarks (what CI runs)
#   scripts/setup-debian.sh --demo   only what building cellctl needs (the README's demo command):
#                                    no test frameworks, no mosquitto broker, no chromium
#   scripts/setup-debian.sh --fuzz   all of the first, plus clang with libFuzzer for the fuzz preset
#                                    (fuzz/README.md)
set -euo pipefail

# cellctl itself: compilers, CMake, and the libraries it links (OpenSSL for the records' SHA-256,
# libmosquitto for the plant link, cpp-httplib for the web page).
build=(
  build-essential g++ cmake ninja-build pkg-config git
  libeigen3-dev libyaml-cpp-dev libspdlog-dev libfmt-dev libcli11-dev nlohmann-json3-dev libssl-dev
  libmosquitto-dev libcpp-httplib-dev
)
# The test suite and the benchmarks: the frameworks, and the real programs the tests drive (a
# broker, a browser, an SVG renderer, socat; openssl makes the broker's test certificates; prometheus
# scrapes the many-cells test's cells; systemd's systemd-analyze verifies the packaged unit).
tests=(
  libgtest-dev libgmock-dev libbenchmark-dev
  socat python3 librsvg2-bin
  mosquitto openssl chromium chromium-driver python3-selenium prometheus systemd
)
case "${1:-}" in
  "") packages=("${build[@]}" "${tests[@]}") ;;
  --demo) packages=("${build[@]}") ;;
  --fuzz) packages=("${build[@]}" "${tests[@]}" clang libclang-rt-14-dev) ;;
  *)
    echo "usage: scripts/setup-debian.sh [--demo | --fuzz]" >&2
    exit 2
    ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: run as root or install sudo (missing: ${missing[*]})" >&2; exit 1; }
  sudo="sudo"
fi
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
