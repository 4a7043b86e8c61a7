#!/usr/bin/env bash
# Installs insitu's build and test dependencies from Debian 12 packages. Idempotent; run as root.
# The last line is the studio's browser test (tests/studio/browser_test.py): headless chromium
# driven by selenium.
set -euo pipefail
packages=(
  cmake g++ make pkg-config
  libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libopencv-dev libceres-dev
  libtinyobjloader-dev libtinygltf-dev libdraco-dev libmeshoptimizer-dev libtbb-dev libeigen3-dev libcpp-httplib-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev libexiv2-dev libzstd-dev libgtest-dev libbenchmark-dev zlib1g-dev
  pybind11-dev python3-dev python3-numpy python3-openimageio
  chromium chromium-driver python3-selenium
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
