#!/usr/bin/env bash
# Measures `beam-impact report` on hostile logs (issue 9): wall time and peak memory (max RSS,
# /usr/bin/time -v) per file and exit codes, over
#   - the committed corpus tests/corpus/logs/*,
#   - N seeded mutations of a real log (default 1000),
#   - a rollback-heavy log (320 000 step messages, half after a rollback) beside a linear log of
#     the same number of step messages.
# Times are measured here, never asserted in tests. Usage, from the repository root:
#   tests/corpus/measure-report.sh [N]     (writes its files under target/hostile-logs/)
set -euo pipefail
N=${1:-1000}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT=$ROOT/target/hostile-logs
BIN=$ROOT/target/release/beam-impact
rm -rf "$OUT" && mkdir -p "$OUT/mutations" "$OUT/big"
cd "$ROOT"
cargo build --release --quiet
# The mutations and the big logs come from the same builders as the tests.
BEAM_IMPACT_HOSTILE_OUT=$OUT BEAM_IMPACT_FUZZ_ITERATIONS=$N \
    cargo test --release --quiet --test integration -- --ignored --exact hostile_logs::write_measurement_logs >/dev/null

measure() { # file label -> "label seconds maxrss_kb exit"
    local file=$1 label=$2 code=0
    /usr/bin/time -f "%e %M" -o "$OUT/time.txt" "$BIN" report "$file" --out "$OUT/figures" \
        >"$OUT/stdout.txt" 2>"$OUT/stderr.txt" || code=$?
    rm -rf "$OUT/figures"
    local t
    t=$(tail -1 "$OUT/time.txt")
    if [ "$code" -ne 0 ] && [ "$code" -ne 2 ]; then
        echo "FAIL $label exit $code: $(head -c 300 "$OUT/stderr.txt")" >&2
    fi
    echo "$label $t $code"
}

summarize() { # lines "label seconds rss code" on stdin
    awk '{ n++; if ($2 > t) { t = $2; tl = $1 } if ($3 > m) { m = $3; ml = $1 } c[$4]++ }
         END { printf "  %d files: slowest %.2f s (%s), largest max RSS %.1f MB (%s); exit codes:", n, t, tl, m / 1024, ml;
               for (k in c) printf " %s x%d", k, c[k]; printf "\n" }'
}

echo "corpus (tests/corpus/logs), per file: seconds, max RSS kB, exit code"
for f in tests/corpus/logs/*.mcap; do measure "$f" "$(basename "$f")"; done | tee "$OUT/corpus.txt" | column -t
summarize <"$OUT/corpus.txt"

echo "mutations of a real log ($N)"
for f in "$OUT"/mutations/*.mcap; do measure "$f" "$(basename "$f")"; done >"$OUT/mutations.txt"
summarize <"$OUT/mutations.txt"

echo "320 000 step messages: linear vs half after a rollback (seconds, max RSS kB, exit code; file size)"
for f in "$OUT"/big/*.mcap; do
    echo "$(measure "$f" "$(basename "$f")") $(stat -c %s "$f") bytes"
done | column -t
