#!/usr/bin/env bash
# Checks the dependency direction of the source tree by its #include lines:
#   algo/     -> the C++ standard library, Eigen and algo/ only (no OS, device or file headers),
#                and inside algo/ each folder only the folders below it (the table below);
#                algo/kernels/ also the compiler's x86 intrinsics (immintrin.h: freestanding,
#                no OS; Eigen's vectorisation includes the same header)
#   io/       -> algo/, io/, hal's device-interface headers (hal/*.hpp) and file libraries
#   hal/      -> the interfaces (hal/*.hpp): algo/ and hal/*.hpp only;
#                the backends (hal/DIR/): algo/, hal/, io/ and system libraries
#   firmware/ -> algo/, io/, hal/, firmware/
#   host_sim/ -> algo/, io/, host_sim/, and hal/ but not its real-device backends (hal/linux/)
# Prints every offending line and exits 1 when there is one.
set -u
root=${1:-.}
cd "$root" || exit 2
status=0

# The algo/ folders each folder may include besides itself (algo/CMakeLists.txt links the same).
# A pose source (markers/NAME) sees the layers below it but no other source.
declare -A algo_allowed=(
  [core]=""
  [frames]="core"
  [geometry]="core"
  [kernels]="core"
  [map]="core geometry"
  [source]="core frames geometry kernels map"
  [markers]="core frames geometry kernels map source"
  [pipeline]="core frames geometry kernels map source markers"
  [calibration]="core frames geometry kernels map source"
  [survey]="core frames geometry kernels map source markers"
)

offend() {
  echo "layering: $1"
  status=1
}

# The folder of an algo/ path that the table speaks of, into $folder: markers/NAME for a
# source, else the first folder below algo/. (No subshells: thousands of includes are checked.)
algo_folder() {
  local path=${1#algo/} rest
  case "$path" in
    markers/*/*) rest=${path#markers/}; folder="markers/${rest%%/*}" ;;
    */*) folder=${path%%/*} ;;
    *) folder="" ;;
  esac
}

check_algo_include() {
  local hit=$1 file=$2 header=$3
  local from to allowed folder
  algo_folder "$file"
  from=$folder
  algo_folder "$header"
  to=$folder
  [ "$from" = "$to" ] && return
  allowed=${algo_allowed[${from%%/*}]-unknown}
  if [ "$allowed" = unknown ]; then
    offend "$hit (algo/${from%%/*}/ is not in the table of tools/check_layering.sh)"
    return
  fi
  for layer in $allowed; do
    [ "${to%%/*}" = "$layer" ] && [ "$layer" != markers -o "${from%%/*}" != markers ] && return
  done
  offend "$hit (algo/$from/ may not include algo/$to/)"
}

include_line='^[^:]+:[0-9]+:[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"]'
while IFS= read -r hit; do
  file=${hit%%:*}
  header=$hit
  [[ $hit =~ $include_line ]] && header=${BASH_REMATCH[1]}
  case "$file" in
    algo/*)
      case "$header" in
        algo/*) check_algo_include "$hit" "$file" "$header" ;;
        Eigen/*) ;;
        immintrin.h) [ "${file#algo/kernels/}" != "$file" ] ||
          offend "$hit (only algo/kernels/ may include the compiler's intrinsics)" ;;
        */*|*.h) offend "$hit (algo/ may include only the standard library, Eigen and algo/)" ;;
      esac ;;
    io/*)
      case "$header" in
        hal/*/*|firmware/*|host_sim/*|tests/*) offend "$hit (io/ may not include $header)" ;;
      esac ;;
    hal/*/*)
      case "$header" in firmware/*|host_sim/*|tests/*) offend "$hit (hal/ may not include $header)" ;; esac ;;
    hal/*)
      case "$header" in
        io/*|hal/*/*|firmware/*|host_sim/*|tests/*) offend "$hit (hal's interfaces may not include $header)" ;;
      esac ;;
    firmware/*)
      case "$header" in host_sim/*|tests/*) offend "$hit (firmware/ may not include $header)" ;; esac ;;
    host_sim/*)
      case "$header" in firmware/*|tests/*|hal/linux/*) offend "$hit (host_sim/ may not include $header)" ;; esac ;;
  esac
done < <(grep -rnE '^\s*#\s*include' algo io hal firmware host_sim --include='*.hpp' --include='*.cpp' --include='*.h')

[ "$status" = 0 ] && echo "layering: every #include follows the dependency direction"
exit "$status"
