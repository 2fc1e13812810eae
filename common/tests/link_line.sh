# Sourced by the tests that read a link line (slam/tests/localizers_link_no_codec.sh,
# run/tests/replay_links_no_mujoco.sh). A link line is named either by a file, where Make keeps it
# (CMakeFiles/TARGET.dir/link.txt), or as ninja:BUILD_DIR:TARGET, where Ninja keeps it in
# build.ninja: the last command of the target's, cut before the steps that follow the link.
# CMake passes whichever its generator made (isg_link_line in the top CMakeLists.txt).

# linkLineTo SPEC FILE: writes the link line SPEC names to FILE; 1 when there is none.
linkLineTo() {
  local spec=$1 file=$2
  if [[ $spec == ninja:* ]]; then
    local dir target
    IFS=: read -r _ dir target <<<"$spec"
    ninja -C "$dir" -t commands "$target" 2>/dev/null | tail -n 1 | sed 's/ && cd .*//' >"$file"
    grep -q -- " -o " "$file"
  else
    [[ -f $spec ]] && cp "$spec" "$file"
  fi
}
