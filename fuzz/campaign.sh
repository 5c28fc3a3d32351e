#!/usr/bin/env bash
# A fuzzing campaign: each target for CPU_SECONDS of CPU time (default 630,
# a little over 10 CPU-minutes), one after the other, from the committed
# seed corpus, with debug assertions (cargo-fuzz `-a`), and a table of
# what each run did. CPU time, not wall time: on a busy machine a
# wall-clock limit (`-max_total_time`) fuzzes less than it says.
#
#   fuzz/campaign.sh [CPU_SECONDS] [TARGET...]
#
# Needs a nightly toolchain and cargo-fuzz, as fuzz/smoke.sh. Builds into
# FUZZ_TARGET_DIR (default fuzz/target). New inputs go to a scratch
# folder; a crash leaves its reproducer in fuzz/artifacts/<target>/ and
# is counted in the table. Logs: LOGS (default a temporary folder).
set -euo pipefail
cd "$(dirname "$0")"
cpu_seconds="${1:-630}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(gltf_load scene_toml texture_decode merl_parse environment_map meshopt_buffer ktx2_texture webp_texture draco_mesh)
target_dir="${FUZZ_TARGET_DIR:-$PWD/target}"
logs="${LOGS:-$(mktemp -d)}"
mkdir -p "$logs"
cargo +nightly fuzz build -a --target-dir "$target_dir" >&2
bin_dir="$target_dir/x86_64-unknown-linux-gnu/release"
ticks=$(getconf CLK_TCK)
echo "| target | CPU s | executions | exec/s | corpus | crashes |"
echo "|---|---|---|---|---|---|"
for target in "${targets[@]}"; do
    scratch="$(mktemp -d)"
    dict=()
    [ "$target" = gltf_load ] && dict=(-dict=gltf.dict)
    [ "$target" = scene_toml ] && dict=(-dict=scene.dict)
    mkdir -p "artifacts/$target"
    before=$(ls "artifacts/$target" | grep -cE '^(crash|oom|timeout|leak)-' || true)
    log="$logs/$target.log"
    seeds="corpus/$target"
    if [ "$target" = draco_mesh ]; then
        # Without the seed that stops every debug-assertion run in
        # draco-oxide-decoder (fuzz/smoke.sh says why); the fuzzer may
        # still find that overflow, and the table then counts it.
        seeds="$(mktemp -d)"
        cp "corpus/$target"/* "$seeds"/
        rm -f "$seeds/found-dequantize-shift-overflow.draco"
    fi
    "$bin_dir/$target" "$scratch" "$seeds" "${dict[@]}" -timeout=10 \
        -rss_limit_mb=4096 -print_final_stats=1 -artifact_prefix="artifacts/$target/" \
        >"$log" 2>&1 &
    pid=$!
    cpu=0
    while kill -0 "$pid" 2>/dev/null; do
        sleep 5
        stat=$(cat "/proc/$pid/stat" 2>/dev/null) || break
        # Fields 14 and 15 after the command name: user and system ticks.
        read -r -a f <<<"${stat##*) }"
        cpu=$(((f[11] + f[12]) / ticks))
        if [ "$cpu" -ge "$cpu_seconds" ]; then
            kill -INT "$pid"
            break
        fi
    done
    wait "$pid" || true
    execs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -oE '[0-9]+$' || echo "?")
    rate=$(grep -oE 'stat::average_exec_per_sec: *[0-9]+' "$log" | grep -oE '[0-9]+$' || echo "?")
    corpus=$(ls "$scratch" | wc -l)
    after=$(ls "artifacts/$target" | grep -cE '^(crash|oom|timeout|leak)-' || true)
    crashes=$((after - before))
    echo "| $target | $cpu | $execs | $rate | $corpus new | $crashes |"
    rm -rf "$scratch"
    [ "$seeds" = "corpus/$target" ] || rm -rf "$seeds"
done
