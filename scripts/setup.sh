#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine for pcl_crf: installs the Debian packages it
# needs, builds it in ./build, then either runs the main demo (--demo, the
# default) or the whole test suite (--test).
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:---demo}
case "$mode" in
  --demo|--test) ;;
  *) echo "usage: $0 [--demo|--test]" >&2; exit 2 ;;
esac

packages=(build-essential cmake libpcl-dev liblbfgs-dev libgtest-dev libbenchmark-dev zlib1g-dev
          xvfb xauth librosbag-dev libsensor-msgs-dev libgeometry-msgs-dev locales python3)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
sudo_cmd=""
[ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}"
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTS=ON -DBUILD_APPS=ON -DBUILD_BENCHMARKS=ON
cmake --build build -j "$jobs"

if [ "$mode" = "--test" ]; then
  # The GermanLocale tests read and write files in a program whose locale writes 0,25.
  if ! locale -a 2>/dev/null | grep -qix 'de_DE\.utf-\?8'; then
    echo "== generating the de_DE.UTF-8 locale for the tests"
    $sudo_cmd localedef -i de_DE -f UTF-8 de_DE.UTF-8 || echo "(not generated: the GermanLocale tests will skip)"
  fi
  cd build && ctest --output-on-failure -j "$jobs"
else
  bash scripts/demo.sh
fi
