# SPDX-License-Identifier: Apache-2.0
# Functions that scripts/*.sh source (this file is not run on its own): installing the Debian
# packages a script needs, and running MeshLab with a private home.

# install_missing_packages WHO PACKAGE...: apt-get installs those of the packages that are not
# installed yet (as root); apt is not touched at all when none is missing. WHO starts every
# message. Returns 1 when packages are missing and this is not root.
install_missing_packages() {
  local who=$1 p missing=()
  shift
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -gt 0 ] || return 0
  if [ "$(id -u)" != 0 ]; then
    echo "$who: error: missing packages ${missing[*]}; run as root or apt-get install them" >&2
    return 1
  fi
  echo "$who: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# use_private_meshlab_home DIR: HOME and the XDG folders in DIR (created when missing), so that
# MeshLab, Qt and Mesa write nothing into the real home; exported for the rest of the script.
use_private_meshlab_home() {
  local home=$1
  local settings="$home/.config/VCG/MeshLab_64bit_fp.conf"
  mkdir -p "$home/.config/VCG" "$home/.cache" "$home/run"
  chmod 700 "$home/run"
  # Without a GPU memory budget MeshLab logs "no additional memory available" per layer.
  [ -f "$settings" ] || cat > "$settings" <<'INI'
[General]
MeshLab%3A%3ASystem%3A%3AmaxGPUMemDedicatedToGeometry="<!DOCTYPE MeshLabSettings>\n<Param value=\"350\" type=\"RichInt\" name=\"MeshLab::System::maxGPUMemDedicatedToGeometry\"/>\n"
INI
  export HOME="$home" XDG_CONFIG_HOME="$home/.config" XDG_CACHE_HOME="$home/.cache" \
         XDG_RUNTIME_DIR="$home/run" MESA_SHADER_CACHE_DISABLE=true
}
