#!/usr/bin/env bash
# The replay path links no MuJoCo: run_tests (built from isg_run alone) names no mujoco library on
# its link line, and ldd finds none in the executable.
set -euo pipefail
executable=$1
link_line=$2
if grep -qi mujoco "$link_line"; then
  echo "FAIL: $link_line names MuJoCo:"; grep -oi '[^ ]*mujoco[^ ]*' "$link_line"; exit 1
fi
if ldd "$executable" | grep -i mujoco; then
  echo "FAIL: $executable loads MuJoCo"; exit 1
fi
echo "ok: $executable links no MuJoCo ($(ldd "$executable" | wc -l) shared libraries)"
