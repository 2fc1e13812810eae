#!/usr/bin/env bash
# The replay path links no MuJoCo: run_tests (built from isg_run alone) names no mujoco library on
# its link line, and ldd finds none in the executable.
set -euo pipefail
executable=$1
source "$(dirname "$0")/../../common/tests/link_line.sh"
link_line=$(mktemp)
trap 'rm -f "$link_line"' EXIT
# $2: a link.txt file or ninja:BUILD_DIR:TARGET (common/tests/link_line.sh)
linkLineTo "$2" "$link_line" || { echo "FAIL: no link line $2"; exit 1; }
if grep -qi mujoco "$link_line"; then
  echo "FAIL: $2 names MuJoCo:"; grep -oi '[^ ]*mujoco[^ ]*' "$link_line"; exit 1
fi
if ldd "$executable" | grep -i mujoco; then
  echo "FAIL: $executable loads MuJoCo"; exit 1
fi
echo "ok: $executable links no MuJoCo ($(ldd "$executable" | wc -l) shared libraries)"
