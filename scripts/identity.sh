#!/usr/bin/env bash
# Fingerprints of ten runs, for checking that a change leaves trajectories and
# analyses bit-identical (issue 52's rule): per-channel message hashes of each
# log (examples/message_hashes.rs), a hash of `carom analyze --json` of each, and
# the final-state hash of `examples/profile 10000 0.5 3e5` (carom-engine).
#   bash scripts/identity.sh OUT_DIR      # then: diff OLD/identity.txt NEW/identity.txt
set -euo pipefail
out=${1:?usage: identity.sh OUT_DIR}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
out=$(cd "$out" && pwd)
cd "$root"
cargo build --release -q --bin carom --example message_hashes
cargo build --release -q -p carom-engine --example profile
bin=$root/target/release/carom
d=$root/data
runs=(
  "default|"
  "walled-mixture|$d/binary-mixture.json --set box.boundary=\"walls\" --set species.0.count=300 --set species.1.count=200 --set box.packing_fraction=0.35 --set placement=\"random\" --set seed=5 --set stop.duration=20"
  "channel|$d/channel.json --set stop.duration=20"
  "granular-cooling|$d/granular-cooling.json --set stop.duration=20"
  "binary-mixture|$d/binary-mixture.json --set stop.duration=10"
  "com-restitution|$d/granular-cooling.json --set collision.model=\"centre-of-mass\" --set stop.duration=20"
  "gravity|$d/atmosphere.json --set stop.duration=20"
  "thermostat|$d/thermostatted-fluid.json --set stop.duration=20"
  "compression|$d/compression-crystal.json --set compression.target_packing_fraction=0.32 --set stop.duration=40"
  "floor|$d/vibrated-bed.json --set stop.duration=20"
)
: >"$out/identity.txt"
for r in "${runs[@]}"; do
  name=${r%%|*}
  args=${r#*|}
  eval "\"$bin\" run $args --out \"$out/$name.mcap\" --force -q"
  {
    echo "== $name"
    "$root/target/release/examples/message_hashes" "$out/$name.mcap"
    # Run where the log is: the report names the file as given.
    (cd "$out" && "$bin" analyze "$name.mcap" --json -q >"$name.json")
    echo "analyze $(sha256sum <"$out/$name.json" | cut -c1-16)"
  } >>"$out/identity.txt"
done
echo "== profile" >>"$out/identity.txt"
"$root/target/release/examples/profile" 10000 0.5 3e5 2>&1 | grep -i hash >>"$out/identity.txt"
cat "$out/identity.txt"
