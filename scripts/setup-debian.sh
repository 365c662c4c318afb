#!/usr/bin/env bash
# Installs what cellctl needs to build and test on Debian 12, from Debian's packages only.
# Safe to run again: when everything is there it installs nothing and says so.
# --fuzz adds clang with libFuzzer for the fuzz preset (fuzz/README.md); the build, the demo and the
# test suite do not need it.
set -euo pipefail

packages=(
  build-essential g++ cmake ninja-build pkg-config git
  libeigen3-dev libyaml-cpp-dev libspdlog-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  socat python3 librsvg2-bin
  libmosquitto-dev mosquitto libcpp-httplib-dev
  chromium chromium-driver python3-selenium
)
if [ "${1:-}" = "--fuzz" ]; then packages+=(clang libclang-rt-14-dev); fi

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
