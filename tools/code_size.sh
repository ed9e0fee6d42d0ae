#!/usr/bin/env bash
# The longest functions and source files of the product (algo/, io/, hal/, firmware/, host_sim/;
# tests are not counted), for issue 33's limits: a function's lines from its signature to its
# closing brace (universal-ctags' line and end fields), a file's lines.
# Usage: tools/code_size.sh [ROOT] [N]      prints the N longest of each (default 10)
#        tools/code_size.sh --check [ROOT]   prints every function over 60 lines and every file over
#                                            500, and exits 1 when there is one
set -euo pipefail
check=0
if [ "${1:-}" = --check ]; then check=1; shift; fi
root=${1:-.}
count=${2:-10}
max_function=60
max_file=500
cd "$root"
command -v ctags >/dev/null || { echo "code_size: ctags not found: run tools/deps.sh native" >&2; exit 2; }
folders=(algo io hal firmware host_sim)

function_lengths() {
  ctags -R --languages=C++ --kinds-C++=f --fields=+ne -x --_xformat='%{end} %{line} %F %N' "${folders[@]}" |
    awk '$1 != "-" { print $1 - $2 + 1, $3 ":" $2, $4 }' | sort -rn
}
file_lengths() {
  find "${folders[@]}" \( -name '*.cpp' -o -name '*.hpp' \) -exec wc -l {} + | grep -v ' total$' | sort -rn
}

if [ "$check" = 1 ]; then
  long_functions=$(function_lengths | awk -v max="$max_function" '$1 > max')
  long_files=$(file_lengths | awk -v max="$max_file" '$1 > max')
  [ -n "$long_functions" ] && printf 'functions over %d lines:\n%s\n' "$max_function" "$long_functions"
  [ -n "$long_files" ] && printf 'files over %d lines:\n%s\n' "$max_file" "$long_files"
  [ -z "$long_functions$long_files" ]
  exit
fi
echo "longest functions (lines, file:line, name):"
function_lengths | sed -n "1,${count}p"
echo "longest files (lines, file):"
file_lengths | sed -n "1,${count}p"
