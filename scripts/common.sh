# Shared by scripts/explore, scripts/test and scripts/bench: install what the
# project needs on Debian 12 (idempotent, quiet when already there) and build
# into build/ (catkin devel space in build/devel). Source it, do not run it.

NBV_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
NBV_BUILD="$NBV_ROOT/build"
# The python3 first on PATH may be a pyenv shim without catkin's modules.
export PATH="/usr/bin:/bin:$PATH"
export PYTHON_EXECUTABLE=/usr/bin/python3

nbv_log() { printf '[surface_nbv] %s\n' "$*" >&2; }

# nbv_install_deps [LIST]: the packages of scripts/debian-packages.txt, or of LIST.
nbv_install_deps() {
  local wanted missing=()
  wanted=$(grep -vE '^\s*(#|$)' "${1:-$NBV_ROOT/scripts/debian-packages.txt}")
  for pkg in $wanted; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' || missing+=("$pkg")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  nbv_log "installing ${#missing[@]} Debian package(s): ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { nbv_log "need root (or sudo) to install: ${missing[*]}"; return 1; }
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq >/dev/null || { nbv_log "apt-get update failed"; return 1; }
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/tmp/surface_nbv_apt.log 2>&1 || {
    tail -20 /tmp/surface_nbv_apt.log >&2
    nbv_log "apt-get install failed (log: /tmp/surface_nbv_apt.log)"
    return 1
  }
}

# nbv_build [make targets...]: configure (Release, tests enabled) and build.
nbv_build() {
  cmake -S "$NBV_ROOT" -B "$NBV_BUILD" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release \
    -DCATKIN_ENABLE_TESTING=ON >"$NBV_BUILD.cmake.log" 2>&1 || {
    tail -40 "$NBV_BUILD.cmake.log" >&2
    nbv_log "cmake configure failed (log: $NBV_BUILD.cmake.log)"
    return 1
  }
  local jobs
  jobs=$(nproc 2>/dev/null || echo 2)
  nbv_log "building ${*:-all} with $jobs jobs"
  # make's own status, whatever the filter does (grep exits 1 when it prints nothing).
  local status_file="$NBV_BUILD.make.status"
  { make -C "$NBV_BUILD" -j"$jobs" --no-print-directory "$@" 2>&1; echo "$?" >"$status_file"; } |
    grep -vE '^\[ *[0-9]+%\]|^(Scanning|Consolidate|Built target)' || true
  [ "$(cat "$status_file" 2>/dev/null)" = "0" ] || { nbv_log "build failed"; return 1; }
}
