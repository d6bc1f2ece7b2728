#!/usr/bin/env bash
# The physics the paper names as missing (issue 21), on the paper's two cases: case A
# (cases/ar07_rough*.toml) and case B (cases/ar2_smooth*.toml, in a 2 m long channel so that the
# front does not reach the far wall) at n = 64 and 128, each without (`none`: the paper's 2D
# model, the case file as it is), with the friction of the channel's side walls (`side`:
# cases/*_channel.toml, W = 0.1 m, without its gate), with the gate alone (`gate`: the same file
# without its side walls) and with both (`both`: cases/*_channel.toml as it is). One run after the
# other on one rank (nice), into
# runs/channel/<name>_<variant>/; then scripts/validation/channel.py writes
# docs/channel_compare.md from whatever runs exist.
#
#   scripts/validation/channel.sh                        # the runs below, in order
#   ONLY="a_n64 b_n64" VARIANTS=side scripts/validation/channel.sh
#   LIST=1 scripts/validation/channel.sh                 # the runs and their commands
#   SET=fine scripts/validation/channel.sh               # the finest grids (below)
#
# SET=fine: case A at n = 256 (on 2 ranks) and case B at n = 128, `none` and `both`, into runs/channel_fine/,
# written by channel.py to docs/channel_compare_fine.md (its figures channel_front_fine_*.png).
#
# A run whose summary.json says "completed" is skipped unless FORCE=1. GRANFLOW=path chooses
# the binary (default build/granflow), OUT_ROOT the output root (default runs/channel).
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
gf="${GRANFLOW:-$root/build/granflow}"
set_name="${SET:-main}"
case "$set_name" in
  main) out_root="${OUT_ROOT:-$root/runs/channel}"; doc="$root/docs/channel_compare.md"
        variants="${VARIANTS:-none side gate both}" ;;
  fine) out_root="${OUT_ROOT:-$root/runs/channel_fine}"; doc="$root/docs/channel_compare_fine.md"
        variants="${VARIANTS:-none both}" ;;
  *) echo "channel.sh: SET = '$set_name' is not allowed (main or fine)" >&2; exit 2 ;;
esac
opts0="--set output.vtk_interval=0"
# name | case file stem | options | ranks
RUNS=(
  "a_n64|cases/ar07_rough|--set grid.n=64 $opts0"
  "b_n64|cases/ar2_smooth|--set grid.n=64 --set domain.Lx=2.0 $opts0"
  "a_n128|cases/ar07_rough|--set grid.n=128 $opts0"
  "b_n128|cases/ar2_smooth|--set grid.n=128 --set domain.Lx=2.0 $opts0"
)
if [[ "$set_name" == fine ]]; then
  RUNS=(
    "b_n128|cases/ar2_smooth|--set grid.n=128 --set domain.Lx=2.0 $opts0"
    "a_n256|cases/ar07_rough|--set grid.n=256 $opts0|2"
  )
fi
# variant | case file suffix | options
VARS=(
  "none||"
  "side|_channel|--set boundary.gate.x=0"
  "gate|_channel|--set boundary.side_walls.width=0 --set boundary.side_walls.friction_angle=0"
  "both|_channel|"
)
[[ -n "${LIST:-}" || -x "$gf" ]] || "$root/scripts/build.sh" || exit 1
mkdir -p "$out_root"
# shellcheck source=run_lib.sh
source "$root/scripts/validation/run_lib.sh"
for r in "${RUNS[@]}"; do
  IFS='|' read -r name stem opts ranks <<<"$r"
  ranks="${ranks:-1}"
  if [[ -n "${ONLY:-}" && " $ONLY " != *" $name "* ]]; then continue; fi
  for v in "${VARS[@]}"; do
    IFS='|' read -r var suffix vopts <<<"$v"
    [[ " $variants " == *" $var "* ]] || continue
    case="$stem$suffix.toml"
    # shellcheck disable=SC2086
    run_case "$out_root/${name}_$var" "$case" "$ranks" $opts $vopts
  done
done
[[ -n "${LIST:-}" ]] || /usr/bin/python3 "$root/scripts/validation/channel.py" \
  "$out_root" "$doc"
