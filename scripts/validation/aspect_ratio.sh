#!/usr/bin/env bash
# Columns of case A's material across aspect ratios (issue 21, "Across aspect ratios"): the
# collapse of a column of width L and height H = a L against the back wall, a = H/L = 0.5, 0.7,
# 1, 2, 4 (L = 0.2 m for a <= 2, L = 0.1 m for a = 4), with cases/ar07_rough.toml's material and
# walls (DP tan 25.5 deg, eta_0 = 0.5 Pa s, rho_s = 1550, bottom Coulomb 25.5 deg, back wall
# 10.5 deg, the default clsvof interface), each variant of VARIANTS (the channel's side walls off,
# then on: cases/ar07_rough_channel.toml's W = 0.1 m, tan 10.5 deg; then the side walls and the
# gate of that case, lifted at 2.333 m/s from x = L) at two grids a factor 2
# apart (16 and 32 cells across L; a <= 1 also at 64, a check of the grid convergence where the
# columns are shortest), one run after the other on one rank (nice), into
# runs/aspect/<a>_c<cells across L>_<variant>/; then scripts/validation/aspect_ratio.py writes
# docs/aspect_ratio.md and docs/figures/aspect_{runout,height}.png from whatever runs exist.
#
#   scripts/validation/aspect_ratio.sh                          # every run below, coarse grids first
#   ONLY="a05 a40_c32_walls" scripts/validation/aspect_ratio.sh # some aspect ratios / runs only
#   GRIDS=16 VARIANT_NAMES=nowalls scripts/validation/aspect_ratio.sh
#   LIST=1 scripts/validation/aspect_ratio.sh                   # the runs and their commands
#
# A run whose summary.json says "completed" and whose command.txt holds the same options is
# skipped unless FORCE=1 (a run made with other options, e.g. an older domain, is run again). GRANFLOW=path chooses
# the binary (default build/granflow), OUT_ROOT the output root (default runs/aspect), GRIDS the
# cells across L for every aspect ratio (default: each one's list below), VARIANT_NAMES a subset
# of the variants' names.
#
# The domain of each a (the same for both grids, so that their cells nest):
#   Lx = max(0.8 m, L (1 + 1.5 f(a))) with f(a) = max(1.2 a, 1.9 a^(2/3), 2 a): the published
#        quasi-2D runout laws (docs/aspect_ratio.md) and 2 a, the envelope of granflow's own
#        coarse-grid runouts (1.8 a to 2.0 a for a = 1, 2, 4: with the laws alone the front of
#        a = 4 came within 4 cells of the far wall), rounded up to a whole coarse cell; 0.8 m
#        (case A's) is the floor because the case file's [[probe]] "bottom" ends at x = 0.8 m
#        and [[probe]] entries cannot be changed by --set;
#   Ly = 1.15 H rounded up to a whole coarse cell (L/16), and at least H + 2 coarse cells
#        (granflow refuses a column closer to the top than eps_cells + 1 = 2 cells: a = 0.7);
#   t_end = 1.3 x 1.06 s x sqrt(H / 0.14 m) (case A, H = 0.14 m, stops by 1.06 s), rounded up
#        to 0.1 s. aspect_ratio.py checks that each run stopped and stayed clear of the far wall.
# One-core wall times (shared 2-core machine) are in docs/aspect_ratio.md.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
gf="${GRANFLOW:-$root/build/granflow}"
out_root="${OUT_ROOT:-$root/runs/aspect}"
all_grids="${GRIDS:-16 32 64}"
case_file="cases/ar07_rough.toml"
# name|a|L (m)|H (m)|Lx (m)|Ly (m)|t_end (s)|cells across L (grids)
ASPECTS=(
  "a05|0.5|0.2|0.1|0.8|0.125|1.2|16 32 64"
  "a07|0.7|0.2|0.14|0.8|0.175|1.4|16 32 64"
  "a10|1|0.2|0.2|0.8|0.2375|1.7|16 32 64"
  "a20|2|0.2|0.4|1.4|0.4625|2.4|16 32"
  "a40|4|0.1|0.4|1.3|0.4625|2.4|16 32"
)
# name|--set options added to the case (one line per variant)
VARIANTS=(
  "nowalls|"
  "walls|--set boundary.side_walls.width=0.1 --set boundary.side_walls.friction_angle=10.5"
  # Side walls and the gate of cases/ar07_rough_channel.toml (2.333 m/s, tan 10.5 deg) at x = L,
  # the plate one coarse cell (L/16) below the domain's top: {L} and {GH} are filled in per a.
  "both|--set boundary.side_walls.width=0.1 --set boundary.side_walls.friction_angle=10.5 --set boundary.gate.x={L} --set boundary.gate.height={GH} --set boundary.gate.speed=2.333 --set boundary.gate.friction_angle=10.5"
)
common="--set output.vtk_interval=0 --set output.progress_interval=60"
[[ -n "${LIST:-}" || -x "$gf" ]] || "$root/scripts/build.sh" || exit 1
mkdir -p "$out_root"
for cells in $all_grids; do
  for r in "${ASPECTS[@]}"; do
    IFS='|' read -r aname a L H Lx Ly tend agrids <<<"$r"
    [[ -n "${GRIDS:-}" || " $agrids " == *" $cells "* ]] || continue
    # grid.n = cells along Ly = Ly / (L / cells); nx = n Lx / Ly follows
    n=$(awk -v Ly="$Ly" -v L="$L" -v c="$cells" 'BEGIN { x = Ly * c / L; n = int(x + 0.5);
        if (n < 1 || (x - n) > 1e-9 || (n - x) > 1e-9) n = -1; print n }')
    if [[ "$n" -lt 1 ]]; then echo "$aname: Ly = $Ly is not a whole number of cells L/$cells" >&2; exit 1; fi
    geom="--set domain.Lx=$Lx --set domain.Ly=$Ly --set grid.n=$n --set initial.x1=$L"
    geom="$geom --set initial.y1=$H --set time.t_end=$tend"
    for v in "${VARIANTS[@]}"; do
      IFS='|' read -r vname vopts <<<"$v"
      gh=$(awk -v Ly="$Ly" -v L="$L" 'BEGIN { printf "%.10g", Ly - L / 16 }')
      vopts="${vopts//\{L\}/$L}"
      vopts="${vopts//\{GH\}/$gh}"
      if [[ -n "${VARIANT_NAMES:-}" && " $VARIANT_NAMES " != *" $vname "* ]]; then continue; fi
      name="${aname}_c${cells}_${vname}"
      if [[ -n "${ONLY:-}" && " $ONLY " != *" $aname "* && " $ONLY " != *" $name "* ]]; then continue; fi
      out="$out_root/$name"
      cmd="granflow run $case_file --out ${out#$root/} $geom $vopts $common"
      if [[ -n "${LIST:-}" ]]; then echo "$cmd"; continue; fi
      if [[ -z "${FORCE:-}" ]] && grep -qs '"status": "completed"' "$out/summary.json" &&
         grep -qsF -- "$(echo $geom $vopts $common)" "$out/command.txt"; then
        echo "skip $out (completed)"; continue
      fi
      echo "run  $cmd"
      start=$SECONDS
      # shellcheck disable=SC2086
      nice "$gf" run "$root/$case_file" --out "$out" --overwrite $geom $vopts $common \
        > "$out.log" 2>&1
      echo "     exit $?, $((SECONDS - start)) s"
    done
  done
done
[[ -n "${LIST:-}" ]] || /usr/bin/python3 "$root/scripts/validation/aspect_ratio.py" \
  "$out_root" "$root/docs/aspect_ratio.md" "$root/docs/figures"
