#!/usr/bin/env bash
# issue 35: where a step of the 10 000-cube pile goes in the atlas's timed window (its last third), head_atlas:
# per-kernel times and grids (ncu over ~15 steps near step 2 300 of 2 400), at the defaults and at 10 iterations
set -uo pipefail
cd "$(dirname "$0")"; B=$PWD/bin; mkdir -p $B
[ -x $B/head_atlas ] || { gunzip -c head_atlas.gz > $B/head_atlas; chmod +x $B/head_atlas; }
O=$OUT/p2; mkdir -p $O
A=$B/head_atlas
for b in default it10; do
timeout 280 ncu --cache-control none --clock-control none --metrics gpu__time_duration.sum,launch__registers_per_thread,launch__grid_size,launch__occupancy_limit_registers,launch__waves_per_multiprocessor --launch-skip 50000 --launch-count 330 --csv $A --scene cubes --n 10000 --methods apgd --budgets $b --steps 2400 --phases > $O/ncu_cubes_$b.csv 2> $O/ncu_cubes_$b.err; echo "ncu cubes $b rc=$? ($SECONDS s)"
done
# the narrow phase's pass: its local memory (box_face_contact's clip polygons, 1 KB of stack) and divergence
timeout 200 ncu --cache-control none --clock-control none --kernel-name regex:CountPairPoints --launch-skip 2300 --launch-count 5 \
  --metrics gpu__time_duration.sum,launch__registers_per_thread,launch__grid_size,l1tex__t_bytes_pipe_lsu_mem_local_op_ld.sum,l1tex__t_bytes_pipe_lsu_mem_local_op_st.sum,l1tex__t_bytes_pipe_lsu_mem_global_op_ld.sum,lts__t_bytes.sum,dram__bytes.sum,smsp__thread_inst_executed_per_inst_executed.ratio,sm__warps_active.avg.pct_of_peak_sustained_active \
  --csv $A --scene cubes --n 10000 --methods apgd --budgets default --steps 2400 > $O/ncu_pairpoints.csv 2> $O/ncu_pairpoints.err; echo "ncu CountPairPoints rc=$? ($SECONDS s)"
grep -E '"(gpu__time|l1tex|lts__t_bytes|dram__bytes|smsp__thread|sm__warps)' $O/ncu_pairpoints.csv | awk -F'","' '{print $(NF-2), $NF}' | sort | uniq -c | head -40
python3 - "$O" <<'PY'
import csv, sys, collections, glob, os
for f in sorted(glob.glob(os.path.join(sys.argv[1], 'ncu_cubes_[di]*.csv'))):
    rows = [r for r in csv.reader(l for l in open(f) if l.startswith('"'))]
    if not rows: print(f, 'empty'); continue
    h = rows[0]; k = h.index('Kernel Name'); m = h.index('Metric Name'); v = h.index('Metric Value'); g = h.index('Grid Size')
    t = collections.defaultdict(float); n = collections.Counter(); extra = {}
    for r in rows[1:]:
        key = r[k][:90]
        if r[m] == 'gpu__time_duration.sum': t[key] += float(r[v].replace(',', '')); n[key] += 1
        else: extra.setdefault(key, {})[r[m].split('__')[1]] = r[v]; extra[key]['grid'] = r[g]
    steps = max(n.values())
    print(os.path.basename(f), 'total us', round(sum(t.values()) / 1000, 1), 'launches', sum(n.values()))
    for name, ns in sorted(t.items(), key=lambda x: -x[1])[:16]: print(f'  {ns/1000:9.1f} us {n[name]:4d}x  {extra.get(name)}  {name}')
PY
cd $OUT && tar czf p2.tgz p2 && rm -rf p2
