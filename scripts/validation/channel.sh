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
# SET=fine: case A at n = 256 (on 2 ranks) and case B at n = 128, `none` and `both`, and case B at
# the paper's grid 768 x 256 (n = 256 in the case file's 1.38 m domain: with the side walls or the
# gate its front stops short of 1.1 m; `none` is not run there, its front reaches the far wall:
# docs/VALIDATION.md has it; `VARIANTS="side gate"` adds the side walls alone and the gate alone
# at n = 256: `both` took 9127 s (1, 2, then 1 rank, beside another run), `side` ran 8927 s to
# t = 1.05 s of 1.36 s on one core), and case B's 2D model at 768 x 256 in the 2 m channel
# (`b_n256_2m`, 1113 x 256 cells: the reference for those effects at that grid; 4627 s on one
# core), and case B with the gate alone at 768 x 256 cells' size in a domain a quarter taller
# (`b_n256_tall`, 768 x 320 cells, Ly = 0.575 m, on 2 ranks: the air returning over the plate
# in the case file's domain held `gate` near dt = 5e-5 s, 1670 steps to t = 0.21 s; SET=lid
# shows that the taller domain moves the figures by at most 1.5 %), into runs/channel_fine/,
# written by channel.py to
# docs/channel_compare_fine.md (its figures channel_front_fine_*.png).
#
# SET=lid: the domain's lid above the gate. The plate's top (boundary.gate.height) is 2 cm below
# the lid in both channel cases, and while the plate is in, the air that the collapse drives to
# the back of the column returns through that gap: at 10-13 m/s in case B. The real channel
# is open above. `gate` and `both` at n = 64 and `both` at n = 128, each in the case file's
# domain and in one 25 % taller (the same cells, one quarter more rows; the plate as before),
# into runs/channel_lid/, written by channel.py to docs/channel_compare_lid.md (docs/CHANNEL.md
# says what it shows).
#
# A run whose summary.json says "completed" is skipped unless FORCE=1. GRANFLOW=path chooses
# the binary (default build/granflow), OUT_ROOT the output root (default runs/channel), RANKS the
# rank count of every run (default: the run's own, 1 unless its entry says otherwise).
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
  lid) out_root="${OUT_ROOT:-$root/runs/channel_lid}"; doc="$root/docs/channel_compare_lid.md"
        variants="${VARIANTS:-gate both}" ;;
  *) echo "channel.sh: SET = '$set_name' is not allowed (main, fine or lid)" >&2; exit 2 ;;
esac
opts0="--set output.vtk_interval=0"
# name | case file stem | options | ranks | variants (default: all of VARIANTS)
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
    "b_n256|cases/ar2_smooth|--set grid.n=256 $opts0|1|side gate both"
    "b_n256_2m|cases/ar2_smooth|--set grid.n=256 --set domain.Lx=2.0 $opts0|1|none"
    "b_n256_tall|cases/ar2_smooth|--set grid.n=320 --set domain.Ly=0.575 $opts0|2|gate"
  )
fi
if [[ "$set_name" == lid ]]; then
  RUNS=(
    "a_n64|cases/ar07_rough|--set grid.n=64 $opts0"
    "a_n64_tall|cases/ar07_rough|--set grid.n=80 --set domain.Ly=0.25 $opts0"
    "b_n64|cases/ar2_smooth|--set grid.n=64 --set domain.Lx=2.0 $opts0"
    "b_n64_tall|cases/ar2_smooth|--set grid.n=80 --set domain.Ly=0.575 --set domain.Lx=2.0 $opts0"
    "a_n128|cases/ar07_rough|--set grid.n=128 $opts0|1|both"
    "a_n128_tall|cases/ar07_rough|--set grid.n=160 --set domain.Ly=0.25 $opts0|1|both"
    "b_n128|cases/ar2_smooth|--set grid.n=128 --set domain.Lx=2.0 $opts0|1|both"
    "b_n128_tall|cases/ar2_smooth|--set grid.n=160 --set domain.Ly=0.575 --set domain.Lx=2.0 $opts0|1|both"
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
  IFS='|' read -r name stem opts ranks rvars <<<"$r"
  ranks="${RANKS:-${ranks:-1}}"
  rvars="${rvars:-$variants}"
  if [[ -n "${ONLY:-}" && " $ONLY " != *" $name "* ]]; then continue; fi
  for v in "${VARS[@]}"; do
    IFS='|' read -r var suffix vopts <<<"$v"
    [[ " $variants " == *" $var "* && " $rvars " == *" $var "* ]] || continue
    case="$stem$suffix.toml"
    # shellcheck disable=SC2086
    run_case "$out_root/${name}_$var" "$case" "$ranks" $opts $vopts
  done
done
[[ -n "${LIST:-}" ]] || /usr/bin/python3 "$root/scripts/validation/channel.py" \
  "$out_root" "$doc"
