#!/usr/bin/env bash
# Runs each cargo-fuzz target for SECONDS (default 600) one after another, at low priority,
# on the binaries `cargo fuzz build --sanitizer none` built (stable Rust), growing corpus/<target>/
# and writing any crash to artifacts/<target>/. libFuzzer's final statistics go to
# logs/<target>.log. Usage, from fuzz/:  ./campaign.sh [SECONDS] [TARGET...]
# KEEP_GOING=1 runs libFuzzer in fork mode past crashes (each one still lands in artifacts/).
set -uo pipefail
cd "$(dirname "$0")"
SECONDS_PER_TARGET=${1:-600}
shift || true
TARGETS=${*:-log_file log_chunk state state_payload scenario resource_scenario}
BIN=target/x86_64-unknown-linux-gnu/release
mkdir -p logs
for t in $TARGETS; do
    mkdir -p "corpus/$t" "artifacts/$t"
    echo "$(date -u +%FT%TZ) $t: $SECONDS_PER_TARGET s"
    extra=()
    [ -n "${KEEP_GOING:-}" ] && extra=(-fork=1 -ignore_crashes=1)
    nice -n 10 "$BIN/$t" "${extra[@]}" "corpus/$t" -max_total_time="$SECONDS_PER_TARGET" -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="artifacts/$t/" >"logs/$t.log" 2>&1
    echo "$(date -u +%FT%TZ) $t: exit $?; $(grep -E 'stat::number_of_executed_units|stat::peak_rss_mb' "logs/$t.log" | tr '\n' ' ')"
done
