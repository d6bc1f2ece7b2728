# Sourced by the validation scripts (interface_compare.sh, channel.sh): one run of a case, the way
# they all make it. Needs root (the repository) and gf (the granflow binary) set by the caller.
#
#   run_case OUT CASE RANKS [granflow options...]
#
# With LIST set, prints the command; a run whose summary.json says "completed" is skipped unless
# FORCE is set; otherwise runs `nice [mpirun -n RANKS] $gf run $root/CASE --out OUT --overwrite
# OPTIONS --set output.progress_interval=60` into OUT.log and prints its exit code and wall time.
run_case() {
  local out="$1" case="$2" ranks="$3"
  shift 3
  local cmd="granflow run $case --out ${out#"$root"/} $*"
  local launch=(nice "$gf")
  if [[ "$ranks" -gt 1 ]]; then
    cmd="mpirun -n $ranks $cmd"
    launch=(nice mpirun -n "$ranks" "$gf")
  fi
  if [[ -n "${LIST:-}" ]]; then echo "$cmd"; return 0; fi
  if [[ -z "${FORCE:-}" ]] && grep -qs '"status": "completed"' "$out/summary.json"; then
    echo "skip $out (completed)"; return 0
  fi
  echo "run  $cmd"
  local start=$SECONDS rc=0
  "${launch[@]}" run "$root/$case" --out "$out" --overwrite "$@" \
    --set output.progress_interval=60 > "$out.log" 2>&1 || rc=$?
  echo "     exit $rc, $((SECONDS - start)) s"
}

# Every run of the caller's RUNS array ("name|case|options[|ranks]", ranks 1 if empty), those
# named in ONLY if it is set, once per value of KEY, into $out_root/<name>_<value>:
#
#   run_variants KEY "VALUE..."
run_variants() {
  local key="$1" values="$2" r name case opts ranks v
  for r in "${RUNS[@]}"; do
    IFS='|' read -r name case opts ranks <<<"$r"
    ranks="${ranks:-1}"
    if [[ -n "${ONLY:-}" && " $ONLY " != *" $name "* ]]; then continue; fi
    for v in $values; do
      # shellcheck disable=SC2086
      run_case "$out_root/${name}_$v" "$case" "$ranks" $opts --set "$key=$v"
    done
  done
}
