#!/usr/bin/env bash
# Installs the Debian packages the stack needs (only those missing) and makes
# sure LCM's UDP multicast can reach loopback. Idempotent; run as root (or
# with sudo available). Extra package names may be passed as arguments.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  liblcm-dev liblcm-bin liblcm-java libglib2.0-dev libjchart2d-java default-jdk-headless
  libeigen3-dev libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
  libyaml-cpp-dev libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev zlib1g-dev iproute2
  supervisor
  "$@"
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# LCM publishes to 239.255.76.67 by default; a host with no route for it
# (no network, no default route) cannot send. Route multicast to loopback then.
if ! ip route get 239.255.76.67 >/dev/null 2>&1; then
  echo "setup: no route for multicast; adding 224.0.0.0/4 on lo"
  "${sudo_cmd[@]}" ip link set lo multicast on
  "${sudo_cmd[@]}" ip route add 224.0.0.0/4 dev lo
fi

# The kernel's default UDP receive buffer (212992 bytes) is what LCM warns
# about: a process busy for a few milliseconds then loses datagrams (the
# demo's lcm-logger lost scans with it). Raise it where this host lets us.
want=2097152
for key in net.core.rmem_max net.core.rmem_default; do
  current=$(sysctl -n "$key" 2>/dev/null || echo "$want")
  if [ "$current" -lt "$want" ]; then
    if "${sudo_cmd[@]}" sysctl -q -w "$key=$want" >/dev/null 2>&1; then
      echo "setup: raised $key from $current to $want bytes (LCM's UDP receive buffer)"
    else
      echo "setup: $key is $current bytes and cannot be raised here; LCM may lose messages under load"
    fi
  fi
done
