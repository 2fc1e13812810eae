#!/usr/bin/env bash
# The localizers' libraries link no codec (docs/architecture.md): the link lines of the tests of
# slam, slam/sgraph, slam/isgraph and slam/baselines — each an executable built from its module's
# library and what that library links, nothing more — name none of the file formats' compression,
# container or message libraries, which formats/ alone links. A robot running the localizer
# carries none of them. PCL, which the plane extraction and NDT use, loads VTK's CMake
# configuration, whose link interface names LZ4: what a link line of PCL's alone holds (PROBE_TXT,
# pcl_link_probe's) is PCL's, reported and not counted.
#   localizers_link_no_codec.sh PROBE LINK...   check these link lines (each a link.txt file or
#                                               ninja:BUILD_DIR:TARGET, common/tests/link_line.sh)
#   localizers_link_no_codec.sh --self-test             check that a codec on a link line is caught
set -euo pipefail
# The libraries of formats/: LZF (PCD), bz2 and lz4 (ROS 1 bags' chunks), zstd and zlib (MCAP),
# SQLite (rosbag2), and the ROS 1 message serialisation (roscpp_serialization, rostime, cpp_common).
codecs='(^|[/ ])(lib)?(lzf|bz2|lz4|zstd|z|sqlite3|jpeg|roscpp_serialization|rostime|cpp_common)(\.so|\.a|[ .]|$)|(^| )-l(lzf|bz2|lz4|zstd|z|sqlite3|jpeg|roscpp_serialization|rostime|cpp_common)( |$)'

codecsOf() { tr ' ' '\n' <"$1" | grep -E "$codecs" | sort -u || true; }

check() {  # link line file [probe file] → 0 when clean, 1 (naming the codecs) when not
  local found pcls=""
  found=$(codecsOf "$1")
  if [[ -n ${2:-} ]]; then
    pcls=$(comm -12 <(echo "$found") <(codecsOf "$2") | grep . || true)
    found=$(comm -23 <(echo "$found") <(codecsOf "$2") | grep . || true)
  fi
  [[ -n $pcls ]] && echo "note: $1: PCL's own link interface brings $(echo $pcls)"
  if [[ -n $found ]]; then
    echo "FAIL: $1 links a codec:"
    echo "$found" | sed 's/^/  /'
    return 1
  fi
}

if [[ ${1:-} == --self-test ]]; then
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  echo "/usr/bin/c++ -O3 a.o -o t libisg_slam.a /usr/lib/x86_64-linux-gnu/libceres.a -lpthread" \
    >"$scratch/clean.txt"
  check "$scratch/clean.txt" >/dev/null || { echo "FAIL: a clean link line was refused"; exit 1; }
  # A codec that PCL's own link line holds is PCL's; one it does not hold is ours.
  echo "/usr/bin/c++ p.o -o p /usr/lib/libpcl_common.so /usr/lib/liblz4.so" >"$scratch/probe.txt"
  echo "/usr/bin/c++ a.o -o t libisg_sgraph.a /usr/lib/libpcl_common.so /usr/lib/liblz4.so" \
    >"$scratch/pcl.txt"
  check "$scratch/pcl.txt" "$scratch/probe.txt" >/dev/null ||
    { echo "FAIL: PCL's own LZ4 was counted as ours"; exit 1; }
  echo "/usr/bin/c++ a.o -o t libisg_sgraph.a /usr/lib/liblz4.so /usr/lib/libzstd.so" \
    >"$scratch/ours.txt"
  if check "$scratch/ours.txt" "$scratch/probe.txt" >/dev/null; then
    echo "FAIL: zstd beside PCL's LZ4 was not caught"; exit 1
  fi
  for codec in /usr/lib/x86_64-linux-gnu/libzstd.so /usr/lib/x86_64-linux-gnu/liblzf.so.1.5 \
               -lsqlite3 /usr/lib/x86_64-linux-gnu/libz.so /usr/lib/libroscpp_serialization.so; do
    echo "/usr/bin/c++ a.o -o t libisg_slam.a $codec -lpthread" >"$scratch/bad.txt"
    if check "$scratch/bad.txt" >/dev/null; then
      echo "FAIL: $codec on a link line was not caught"; exit 1
    fi
  done
  echo "ok: the check catches a codec on a link line and passes a clean one"
  exit 0
fi

source "$(dirname "$0")/../../common/tests/link_line.sh"
lines=$(mktemp -d)
trap 'rm -rf "$lines"' EXIT
linkLineTo "$1" "$lines/probe.txt" || { echo "FAIL: no link line $1"; exit 1; }
shift
status=0
for spec in "$@"; do
  link_line=$lines/$(basename "${spec//[:\/]/_}")
  linkLineTo "$spec" "$link_line" || { echo "FAIL: no link line $spec"; exit 1; }
  check "$link_line" "$lines/probe.txt" || status=1
done
[[ $status == 0 ]] && echo "ok: $# localizer link lines name no codec of ours"
exit $status
