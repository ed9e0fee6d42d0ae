#!/usr/bin/env bash
# Checks the dependency direction of the source tree by its #include lines:
#   algo/     -> the C++ standard library, Eigen and algo/ only (no OS, device or file headers)
#   hal/      -> algo/, hal/ and system libraries
#   firmware/ -> algo/, hal/, firmware/
#   host_sim/ -> algo/, host_sim/, and hal/ but not its real-device backends (hal/linux/)
# Prints every offending line and exits 1 when there is one.
set -u
root=${1:-.}
cd "$root" || exit 2
status=0

offend() {
  echo "layering: $1"
  status=1
}

while IFS= read -r hit; do
  header=$(sed -E 's/^[^:]+:[0-9]+:\s*#\s*include\s*[<"]([^>"]+)[>"].*/\1/' <<<"$hit")
  case "$hit" in
    algo/*)
      case "$header" in
        algo/*|Eigen/*) ;;
        */*|*.h) offend "$hit (algo/ may include only the standard library, Eigen and algo/)" ;;
      esac ;;
    hal/*)
      case "$header" in firmware/*|host_sim/*|tests/*) offend "$hit (hal/ may not include $header)" ;; esac ;;
    firmware/*)
      case "$header" in host_sim/*|tests/*) offend "$hit (firmware/ may not include $header)" ;; esac ;;
    host_sim/*)
      case "$header" in firmware/*|tests/*|hal/linux/*) offend "$hit (host_sim/ may not include $header)" ;; esac ;;
  esac
done < <(grep -rnE '^\s*#\s*include' algo hal firmware host_sim --include='*.hpp' --include='*.cpp' --include='*.h')

[ "$status" = 0 ] && echo "layering: every #include follows the dependency direction"
exit "$status"
