#!/usr/bin/env bash
# Time per Newton iteration of one scene under two builds, alternated A B A B so that
# a drift of the machine's load shows as a drift, not as a difference between the builds.
#   bash bench/cost_abab.sh OLD/.venv/bin/hypercontact NEW/.venv/bin/hypercontact [scene] [--set ...]
# Prints, per run, the load average at its start, the Newton iterations N (curves.csv) and
# every phase of summary.json's time_split divided by N (output excluded). Reports; asserts nothing.
set -euo pipefail
A=$1; B=$2; shift 2
scene=${1:-punch}; shift || true
sets=("$@"); [ ${#sets[@]} -eq 0 ] && sets=(--set mesh.n=32 --set mesh.m=8)
out=$(mktemp -d /tmp/cost_abab.XXXX)
for i in 1 2; do
  for label in before after; do
    exe=$A; [ $label = after ] && exe=$B
    load=$(cut -d' ' -f1 /proc/loadavg)
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 "$exe" run "$scene" --out "$out/$label$i" \
      --set output.xdmf=false "${sets[@]}" > "$out/$label$i.log" 2>&1
    /usr/bin/python3 - "$out/$label$i" "$label $i" "$load" <<'PY'
import csv, json, sys
run, name, load = sys.argv[1:]
split = json.load(open(f"{run}/summary.json"))["time_split"]
n = sum(int(r["newton_iterations"]) for r in csv.DictReader(open(f"{run}/curves.csv")))
per = {k: round(v / n, 4) for k, v in split.items() if k != "output"}
work = sum(v for k, v in per.items() if k in ("linear solve", "volume assembly", "contact", "contact search"))
print(f"{name}: load {load}, N {n}, s/it (contact + volume + linear) {work:.3f}, {per}")
PY
  done
done
