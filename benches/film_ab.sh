#!/usr/bin/env bash
# Interleaved A/B of two `pathtrace` binaries on the Cornell box: the cost of the exact
# fixed-point film (docs/distributed.md). Usage: benches/film_ab.sh OLD NEW [RUNS]
# Prints each run's samples/s and the medians; runs alternate so machine load hits both alike.
set -euo pipefail
old=$1 new=$2 runs=${3:-5}
args=(render cornell-box --size 256x256 --spp 256 --threads 2 -o /tmp/film_ab.pfm --stats-json /tmp/film_ab.json -q)
declare -a a b
for i in $(seq "$runs"); do
    for which in old new; do
        bin=${!which}
        "$bin" "${args[@]}"
        rate=$(python3 -c 'import json;print(json.load(open("/tmp/film_ab.json"))["samples_per_second"])')
        echo "run $i $which $rate samples/s"
        if [ "$which" = old ]; then a+=("$rate"); else b+=("$rate"); fi
    done
done
python3 - "${a[*]}" "${b[*]}" <<'PY'
import statistics, sys
old = [float(x) for x in sys.argv[1].split()]
new = [float(x) for x in sys.argv[2].split()]
mo, mn = statistics.median(old), statistics.median(new)
print(f"median old {mo/1e6:.3f} M samples/s, new {mn/1e6:.3f} M samples/s, new/old {mn/mo:.3f}")
PY
rm -f /tmp/film_ab.pfm /tmp/film_ab.json
