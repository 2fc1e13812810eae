# Sourced by ci/build and ci/sanitize: the build system both CI configurations are made with.
# ISG_GENERATOR is Ninja where it is installed (ci/install-deps installs it), else Unix Makefiles.
if [[ -z ${ISG_GENERATOR:-} ]]; then
  if command -v ninja >/dev/null; then ISG_GENERATOR=Ninja; else ISG_GENERATOR="Unix Makefiles"; fi
fi

# isg_use_generator DIR GENERATOR [KEEP...]: empties DIR (but the entries named KEEP) when it was
# configured with another generator, saying so, so that it is configured again with GENERATOR.
isg_use_generator() {
  local dir=$1 generator=$2
  shift 2
  [[ -f $dir/CMakeCache.txt ]] || return 0
  local made_with
  made_with=$(sed -n 's/^CMAKE_GENERATOR:INTERNAL=//p' "$dir/CMakeCache.txt")
  [[ $made_with == "$generator" ]] && return 0
  echo "ci: $dir was made with \"$made_with\"; making it again with \"$generator\"" >&2
  local keep=() entry
  for entry in "$@"; do keep+=(! -name "$entry"); done
  find "$dir" -mindepth 1 -maxdepth 1 "${keep[@]}" -exec rm -rf {} +
}
