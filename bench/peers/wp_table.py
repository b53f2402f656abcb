#!/usr/bin/env python3
"""Work-precision table (BENCHMARKS.md): cheapest run reaching err <= 1e-4 and 1e-6 per model, triad
(fixed and error-controlled rows) against the cheapest peer; cost = us per simulated second.
  python bench/peers/wp_table.py [RESULTS_DIR]   (default: bench/peers/results/session20; a
  RESULTS_DIR holding one accuracy.json, the records of one `bash bench/peers/run.sh`, takes
  every row from it)"""
import sys, os
HERE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), 'results', 'session20')
import json
if os.path.exists(HERE + '/accuracy.json'):
    # one run of bench/peers/run.sh: every record in one file
    acc=json.load(open(HERE + '/accuracy.json'))
    ad=[r for r in acc if r['method'].startswith('EMa')]
    part=prev=[r for r in acc if not r['method'].startswith('EMa')]
    ONE_RUN=True
else:
    ad=json.load(open(HERE + '/adaptive.json'))
    part=json.load(open(HERE + '/fixed_dp_dzhanibekov.json'))
    prev=json.load(open(HERE + '/fixed_peers_fine.json'))
    ONE_RUN=False
def cost(r): return r['us_per_step']/r['h']
rows=[]
for model in ['double_pendulum','heavy_top','free_body_dzhanibekov','free_body_torque','chain100','ur5_pd']:
    # A: the run that covered these two models (fixed rows of triad and the peers); B: the rest
    same = model in ('double_pendulum', 'free_body_dzhanibekov')
    src = part if same else prev
    for thr in (1e-4,1e-6):
        def best(rs):
            ok=[r for r in rs if r.get('status')=='ok' and r.get('err') is not None and r['err']<=thr and 'us_per_step' in r]
            return min(ok,key=cost) if ok else None
        peers=[r for r in src if r['model']==model and not r['engine'].startswith('triad')]
        tri=[r for r in ad if r['model']==model]+[r for r in src if r['model']==model and r['engine']=='triad']
        bp=best(peers); bt=best(tri)
        f=lambda r: f"{cost(r):.3g} ({r['engine']} {r['method']} h={r['h']:g}, err {r['err']:.1e})" if r else '-'
        ratio = cost(bt)/cost(bp) if bp and bt else float('nan')
        rows.append((model,thr,f(bt),f(bp),ratio,'one run' if ONE_RUN else 'A' if same else 'B'))
ok2=sum(1 for r in rows if r[4]<=2); ok1=sum(1 for r in rows if r[4]<1)
for r in rows: print(f"| {r[0]} | {r[1]:g} | {r[2]} | {r[3]} | {r[4]:.2f} | {r[5]} |")
print(f"\nwithin 2x of the cheapest peer: {ok2} of {len(rows)}; cheaper: {ok1}")
