# Sourced by the bench scripts (not run on its own).
# build_host BUILD_DIR TARGET: builds TARGET in the host build tree BUILD_DIR,
# configuring the host-release preset first when no tree is configured there;
# progress and the build's output go to stderr, so a script's stdout stays its table.
build_host() {
  echo "building $2 in $1..." >&2
  [ -f "$1/CMakeCache.txt" ] || cmake --preset host-release >&2
  cmake --build "$1" --target "$2" >&2
}
