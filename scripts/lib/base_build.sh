# Sourced by scripts that compare the working tree with an older revision.
# Needs die (prints its message and exits 2).

# use_scratch_env: Mesa's shader cache, and an XDG runtime folder when the
# session has none, inside $work, so that runs neither read nor fill the
# user's own caches. Needs $work.
use_scratch_env() {
  export MESA_SHADER_CACHE_DIR=$work/mesa_shader_cache
  if [[ -z ${XDG_RUNTIME_DIR:-} ]]; then
    [[ -d $work/xdg_runtime ]] || mkdir -m 700 "$work/xdg_runtime"
    export XDG_RUNTIME_DIR=$work/xdg_runtime
  fi
}

# run_logged LOG CMD...: runs a build step quietly into LOG; on failure shows
# its tail and stops.
run_logged() {
  local log=$1; shift
  if ! "$@" > "$log" 2>&1; then
    tail -n 40 "$log" >&2
    die "failed: $* (log: $log)"
  fi
}

# build_base_spectrace SHA: builds that revision's spectrace in a detached git
# worktree at $work/src (reused, moved to SHA; it is scratch, so local edits
# there are dropped) into $work/build, with build/'s build type and compiler,
# tests off; sets base_bin. Needs $work and $jobs.
build_base_spectrace() {
  local base_sha=$1 src=$work/src
  git worktree prune
  if [[ -d $src ]] && git worktree list --porcelain | grep -qxF "worktree $src"; then
    run_logged "$work/logs/base-checkout.log" git -C "$src" checkout -q --force --detach "$base_sha"
    git -C "$src" clean -q -f -d
  else
    rm -rf "$src"
    run_logged "$work/logs/base-checkout.log" git worktree add -q --detach "$src" "$base_sha"
  fi
  cache_value() { sed -n "s/^$1:[A-Z]*=//p" build/CMakeCache.txt | head -n 1; }
  local args=(-DCMAKE_BUILD_TYPE="$(cache_value CMAKE_BUILD_TYPE)" -DBUILD_TESTING=OFF)
  [[ -n $(cache_value CMAKE_CXX_COMPILER) ]] && args+=(-DCMAKE_CXX_COMPILER="$(cache_value CMAKE_CXX_COMPILER)")
  [[ -n $(cache_value CMAKE_CXX_FLAGS) ]] && args+=(-DCMAKE_CXX_FLAGS="$(cache_value CMAKE_CXX_FLAGS)")
  [[ -n $(cache_value SPECTRACE_SANITIZE) ]] && args+=(-DSPECTRACE_SANITIZE="$(cache_value SPECTRACE_SANITIZE)")
  run_logged "$work/logs/base-configure.log" cmake -S "$src" -B "$work/build" "${args[@]}"
  run_logged "$work/logs/base-build.log" cmake --build "$work/build" -j "$jobs" --target spectrace
  base_bin=$work/build/spectrace
  if [[ ! -x $base_bin ]]; then  # older layouts
    base_bin=$(find "$work/build" -name spectrace -type f -perm -u+x -print -quit)
    [[ -n $base_bin ]] || die "no spectrace binary under $work/build"
  fi
}
