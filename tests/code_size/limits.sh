#!/usr/bin/env bash
# tools/code_size.sh --check notices a function over 60 lines and a file over 500, and passes a
# function of 60 lines in a file of 500: one tree per case.
set -u
check=$1
status=0
# A tree whose algo/code.cpp holds a function of $1 lines, padded with comment lines to $2 lines.
make_tree() {
  local function_lines=$1 file_lines=$2 tree
  tree=$(mktemp -d)
  mkdir -p "$tree/algo" "$tree/io" "$tree/hal" "$tree/firmware" "$tree/host_sim"
  {
    echo "int f() {"
    for ((i = 0; i < function_lines - 2; ++i)); do echo "  int a$i = 0;"; done
    echo "}"
    for ((i = function_lines; i < file_lines; ++i)); do echo "// $i"; done
  } > "$tree/algo/code.cpp"
  echo "$tree"
}
expect() {
  local wanted=$1 function_lines=$2 file_lines=$3 tree result
  tree=$(make_tree "$function_lines" "$file_lines")
  if "$check" --check "$tree" >/dev/null; then result=pass; else result=fail; fi
  [ "$result" = "$wanted" ] || { echo "code_size: a $function_lines-line function in a $file_lines-line file: $result, wanted $wanted"; status=1; }
  rm -rf "$tree"
}
expect pass 60 500
expect fail 61 100
expect fail 10 501
[ "$status" = 0 ] && echo "code_size: the limits hold at 60 and 500 lines"
exit "$status"
