#!/usr/bin/env bash
# Runs the `intersect` bench of a base commit and of the working tree
# alternately and prints the medians (issue 19: "against commit cc923c0, run
# alternately").
#
# Usage: scripts/compare_with_base.sh [BASE]      (BASE defaults to cc923c0)
#
# Environment (all optional):
#   ROUNDS         runs of each side, alternating base, head, base, ... (3)
#   CRITERION_ARGS extra arguments for each run (e.g. "--measurement-time 2
#                  --warm-up-time 0.5" for more, shorter rounds)
#   FILTER         criterion filter (a regex on the bench id); by default the
#                  single-ray ids that exist at cc923c0 and here, and the batch
#                  groups (they exist only here)
#   BASE_WORKTREE  where the base commit is checked out (a git worktree; made
#                  if missing; default: a new temporary directory)
#   CALLGRIND_RAYS N: if set and valgrind is installed, instructions per ray
#                  of `ray_profile glass` and `ray_profile vase` on both sides,
#                  from N and 2N rays (100000 is the usual N)
#
# Both sides build in this checkout's target directory (dependencies are built
# once); the binaries are copied out right after each build, because the two
# revolve builds may share artifact names. Needs git, cargo and python3.
set -euo pipefail

BASE=${1:-cc923c0}
ROUNDS=${ROUNDS:-3}
FILTER=${FILTER:-'^intersect_(wine_glass|vase)/exact/random$|^intersect_triangle/moller_trumbore/random$|^intersect_batch_'}
ROOT=$(git rev-parse --show-toplevel)
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$ROOT/target}
OUT=$(mktemp -d)
BASE_WORKTREE=${BASE_WORKTREE:-$OUT/base-worktree}
if [ ! -e "$BASE_WORKTREE" ]; then
    git -C "$ROOT" worktree add --detach "$BASE_WORKTREE" "$BASE" >&2
fi
echo "base $(git -C "$BASE_WORKTREE" rev-parse --short HEAD) in $BASE_WORKTREE;" \
    "head $(git -C "$ROOT" rev-parse --short HEAD) (plus uncommitted changes) in $ROOT;" \
    "results in $OUT" >&2

# The executable cargo reports for a build (the last one listed).
executable() {
    grep -o '"executable":"[^"]*"' | tail -n 1 | sed 's/"executable":"\(.*\)"/\1/'
}

# build SIDE DIR: the bench (and ray_profile) of the checkout DIR, copied to
# $OUT/SIDE-*.
build() {
    local side=$1 dir=$2
    # The benches are the package revolve-benches since issue 25; before,
    # they were the root package's.
    local package=()
    if [ -e "$dir/benches/Cargo.toml" ]; then package=(-p revolve-benches); fi
    (cd "$dir" && nice -n 10 cargo bench "${package[@]}" --bench intersect --no-run --message-format=json) \
        | executable | xargs -I{} cp {} "$OUT/$side-intersect"
    if [ -n "${CALLGRIND_RAYS:-}" ]; then
        (cd "$dir" && nice -n 10 cargo build --release --example ray_profile --message-format=json) \
            | executable | xargs -I{} cp {} "$OUT/$side-ray_profile"
    fi
}
build base "$BASE_WORKTREE"
build head "$ROOT"

for round in $(seq 1 "$ROUNDS"); do
    for side in base head; do
        echo "round $round: $side" >&2
        CRITERION_HOME="$OUT/criterion-$side-$round" \
            "$OUT/$side-intersect" --bench "$FILTER" ${CRITERION_ARGS:-} > "$OUT/$side-$round.log" 2>&1
    done
done

python3 - "$OUT" "$ROUNDS" <<'PY'
import json, os, re, statistics, sys

out, rounds = sys.argv[1], int(sys.argv[2])

def medians(side):
    """Bench id -> the per-run medians (ns per iteration) of every round."""
    runs = {}
    for r in range(1, rounds + 1):
        home = os.path.join(out, f"criterion-{side}-{r}")
        for dirpath, _, files in os.walk(home):
            if os.path.basename(dirpath) == "new" and "estimates.json" in files:
                bench = os.path.relpath(os.path.dirname(dirpath), home)
                with open(os.path.join(dirpath, "estimates.json")) as f:
                    runs.setdefault(bench, []).append(json.load(f)["median"]["point_estimate"])
    return runs

base, head = medians("base"), medians("head")
unit = "intersect_triangle/moller_trumbore/random"


def cell(runs, pick):
    return f"{pick(runs):9.1f}" if runs else f"{'-':>9}"


def ratio(a, b, pick):
    return f"{pick(a) / pick(b):7.3f}" if a and b else f"{'-':>7}"


print(f"ns per ray: the median and the best of {rounds} alternating runs per side "
      "(each run's figure is the median of its samples); ratios of medians and of bests")
print(f"{'bench':44} {'base med':>9} {'head med':>9} {'base best':>9} {'head best':>9}"
      f" {'h/b med':>7} {'h/b best':>7} {'h/MT med':>8}")
for bench in sorted(set(base) | set(head)):
    b, h = base.get(bench), head.get(bench)
    # A head-only batch id is compared with the base's single-ray time on
    # the same shape (issue 19's "today's single-ray time").
    m = re.match(r"intersect_batch_(\w+)/", bench)
    ref = f"intersect_{m.group(1)}/exact/random" if m else bench
    rb = base.get(ref)
    med, best = statistics.median, min
    cols = [cell(b, med), cell(h, med), cell(b, best), cell(h, best),
            ratio(h, rb, med), ratio(h, rb, best), ratio(h, head.get(unit), med)]
    note = f"  (base: {ref})" if ref != bench else ""
    print(f"{bench:44} {' '.join(cols)}{note}")
PY

if [ -n "${CALLGRIND_RAYS:-}" ] && command -v valgrind > /dev/null; then
    # Per ray without the set-up: the difference between N and 2N rays,
    # divided by N (as docs/performance.md measures).
    n=$CALLGRIND_RAYS
    echo "instructions per ray (callgrind Ir of ray_profile SHAPE 2N minus SHAPE N, over N = $n):"
    for shape in glass vase; do
        for side in base head; do
            irs=()
            for rays in "$n" $((2 * n)); do
                log="$OUT/callgrind-$side-$shape-$rays.log"
                (cd "$OUT" && valgrind --tool=callgrind --callgrind-out-file="$OUT/callgrind-$side-$shape-$rays" \
                    "$OUT/$side-ray_profile" "$shape" "$rays" > /dev/null 2> "$log")
                irs+=("$(grep -o 'Collected : [0-9]*' "$log" | grep -o '[0-9]*$')")
            done
            echo "  $shape $side: $(((irs[1] - irs[0]) / n)) per ray (${irs[0]} with set-up for N)"
        done
    done
fi
