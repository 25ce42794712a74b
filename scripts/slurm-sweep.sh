#!/usr/bin/env bash
# Runs `gacompare sweep` on a Slurm cluster: a job array with one task per
# shard (`--shard i/N`), and `gacompare merge` as a job that starts when every
# shard has ended well (afterok). What the array and the merge run is written
# to DIR-shards/ as two batch scripts first, so a cluster without Slurm can run
# the same commands by hand (--dry-run prints them and submits nothing).
#
#   scripts/slurm-sweep.sh [--shards N] [--sbatch "ARGS"] [--gacompare BIN]
#                          [--wait] [--dry-run] --out DIR SCENE [SWEEP OPTIONS...]
#
#   --shards N      tasks in the array (default 4); unit k runs in task k mod N
#   --sbatch ARGS   passed to both sbatch calls (partition, account, time limit:
#                   "--partition=short --time=01:00:00"), split on spaces
#   --gacompare BIN the binary the jobs run (default: build/release, else
#                   build/ci, under the repository); it must be reachable from
#                   the compute nodes (a shared file system)
#   --wait          return when the merge has ended, with its exit status
#   --dry-run       write the two scripts and print the commands, submit nothing
#   --out DIR       the merged sweep (shards go to DIR-shards/shard-K)
#
# Every argument reaches the batch scripts quoted (printf %q): a scene's path
# or a folder name is data, never shell code.
set -euo pipefail

die() { echo "slurm-sweep: $*" >&2; exit 2; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shards=4
sbatch_args=""
gacompare=""
wait_for_merge=0
dry_run=0
out=""
sweep=()
while [ $# -gt 0 ]; do
  case "$1" in
    --shards) [ $# -ge 2 ] || die "--shards needs a number"; shards=$2; shift 2 ;;
    --sbatch) [ $# -ge 2 ] || die "--sbatch needs its arguments in one string"; sbatch_args=$2; shift 2 ;;
    --gacompare) [ $# -ge 2 ] || die "--gacompare needs a path"; gacompare=$2; shift 2 ;;
    --wait) wait_for_merge=1; shift ;;
    --dry-run) dry_run=1; shift ;;
    --out) [ $# -ge 2 ] || die "--out needs a folder"; out=$2; shift 2 ;;
    --shard|--shard=*) die "the shards are this script's to deal: give --shards N, not --shard" ;;
    *) sweep+=("$1"); shift ;;
  esac
done
[[ "$shards" =~ ^[1-9][0-9]{0,3}$ ]] || die "--shards: expected a whole number from 1 to 9999, got '$shards'"
[ -n "$out" ] || die "--out DIR is required: the merged sweep's folder"
[ ${#sweep[@]} -ge 1 ] || die "a scene file is required (and any gacompare sweep options after it)"
if [ -z "$gacompare" ]; then
  for b in "$root/build/release/compare/gacompare" "$root/build/ci/compare/gacompare"; do
    if [ -x "$b" ]; then gacompare=$b; break; fi
  done
  [ -n "$gacompare" ] || die "no gacompare binary under build/ (bash scripts/build.sh builds it; --gacompare names another)"
fi
[ -x "$gacompare" ] || die "--gacompare: '$gacompare' is not an executable file"
gacompare=$(realpath "$gacompare")
# Absolute paths: the jobs may start in another folder on another node.
out=$(realpath -m "$out")
for i in "${!sweep[@]}"; do
  if [ -e "${sweep[$i]}" ]; then sweep[$i]=$(realpath "${sweep[$i]}"); fi
done
shard_root="$out-shards"
mkdir -p "$shard_root"

quoted() { local q=""; for a in "$@"; do q+=" $(printf '%q' "$a")"; done; echo "${q# }"; }

last=$((shards - 1))
cat > "$shard_root/array.sbatch" <<EOF
#!/usr/bin/env bash
#SBATCH --job-name=gacompare-sweep
#SBATCH --array=0-$last
#SBATCH --ntasks=1
#SBATCH --output=$(printf '%q' "$shard_root")/shard-%a.log
# Shard i of $shards of the sweep; every shard writes its own folder.
set -euo pipefail
i=\${SLURM_ARRAY_TASK_ID:?this script runs as a Slurm array task (or set SLURM_ARRAY_TASK_ID=0..$last by hand)}
exec $(quoted "$gacompare" sweep "${sweep[@]}") --quiet --shard "\$i/$shards" --out $(printf '%q' "$shard_root")/shard-"\$i"
EOF
dirs=()
for ((i = 0; i < shards; ++i)); do dirs+=("$shard_root/shard-$i"); done
cat > "$shard_root/merge.sbatch" <<EOF
#!/usr/bin/env bash
#SBATCH --job-name=gacompare-merge
#SBATCH --ntasks=1
#SBATCH --output=$(printf '%q' "$shard_root")/merge.log
# Joins the $shards shard folders into one sweep (its report included).
set -euo pipefail
exec $(quoted "$gacompare" merge "${dirs[@]}" --out "$out")
EOF
chmod +x "$shard_root/array.sbatch" "$shard_root/merge.sbatch"

read -r -a extra <<< "$sbatch_args"
if [ "$dry_run" = 1 ]; then
  echo "slurm-sweep: wrote $shard_root/array.sbatch and merge.sbatch. On Slurm:" >&2
  echo "  jid=\$(sbatch --parsable ${extra[*]} $(printf '%q' "$shard_root/array.sbatch"))"
  echo "  sbatch --dependency=afterok:\$jid ${extra[*]} $(printf '%q' "$shard_root/merge.sbatch")"
  echo "slurm-sweep: by hand, without Slurm:" >&2
  echo "  for i in \$(seq 0 $last); do SLURM_ARRAY_TASK_ID=\$i bash $(printf '%q' "$shard_root/array.sbatch"); done"
  echo "  bash $(printf '%q' "$shard_root/merge.sbatch")"
  exit 0
fi
command -v sbatch > /dev/null || die "sbatch not found: no Slurm here. --dry-run prints the commands to run the shards by hand"
array=$(sbatch --parsable "${extra[@]}" "$shard_root/array.sbatch") || die "sbatch refused the array job"
array=${array%%;*}
wait_flag=()
if [ "$wait_for_merge" = 1 ]; then wait_flag=(--wait); fi
echo "slurm-sweep: array job $array ($shards shards: $shard_root/shard-K, logs shard-K.log)" >&2
if [ "$wait_for_merge" = 1 ]; then
  echo "slurm-sweep: waiting for the merge into $out" >&2
  sbatch --parsable --dependency=afterok:"$array" --kill-on-invalid-dep=yes "${wait_flag[@]}" "${extra[@]}" \
    "$shard_root/merge.sbatch" || die "the merge did not end well: see $shard_root/merge.log and the shard logs"
else
  merge=$(sbatch --parsable --dependency=afterok:"$array" --kill-on-invalid-dep=yes "${extra[@]}" "$shard_root/merge.sbatch") \
    || die "sbatch refused the merge job"
  echo "slurm-sweep: merge job ${merge%%;*} starts when every shard has ended well; it writes $out" >&2
fi
