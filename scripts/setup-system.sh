#!/usr/bin/env bash
# System packages artiplan needs beyond Python: Java (ENHSP) and Mesa (headless MuJoCo rendering).
# Installs only what is missing, and only when it can (root + apt-get); otherwise says what to install.
set -u
need=()
command -v java >/dev/null 2>&1 || need+=(default-jre-headless)
ldconfig -p 2>/dev/null | grep -q 'libEGL.so' || need+=(libegl1 libegl-mesa0 libgl1-mesa-dri)
ldconfig -p 2>/dev/null | grep -q 'libOSMesa.so' || need+=(libosmesa6)
[ ${#need[@]} -eq 0 ] && exit 0
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "artiplan setup: installing system packages: ${need[*]}"
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}") >/dev/null 2>&1 \
    || echo "artiplan setup: warning: could not install ${need[*]} (rendering or ENHSP may be unavailable)"
else
  echo "artiplan setup: please install: ${need[*]} (rendering or ENHSP may be unavailable)"
fi
exit 0
