#!/usr/bin/env python3
"""Work-precision table (BENCHMARKS.md): cheapest run reaching err <= 1e-4 and 1e-6 per model, triad
(fixed and error-controlled rows) against the cheapest peer; cost = us per simulated second.
  python bench/peers/wp_table.py [RESULTS_DIR]   (default: bench/peers/results/session22b, the
  run in BENCHMARKS.md)"""
import sys

from wp_records import MODELS, Records

recs = Records(*sys.argv[1:2])


def cost(r):
    return r['us_per_step'] / r['h']


rows = []
for model in MODELS:
    src = recs.fixed
    for thr in (1e-4, 1e-6):
        def best(rs):
            ok = [r for r in rs if r.get('status') == 'ok' and r.get('err') is not None and r['err'] <= thr and 'us_per_step' in r]
            return min(ok, key=cost) if ok else None
        peers = [r for r in src if r['model'] == model and not r['engine'].startswith('triad')]
        tri = [r for r in recs.adaptive if r['model'] == model] + [r for r in src if r['model'] == model and r['engine'] == 'triad']
        bp = best(peers)
        bt = best(tri)
        f = lambda r: f"{cost(r):.3g} ({r['engine']} {r['method']} h={r['h']:g}, err {r['err']:.1e})" if r else '-'
        ratio = cost(bt) / cost(bp) if bp and bt else float('nan')
        rows.append((model, thr, f(bt), f(bp), ratio))
ok2 = sum(1 for r in rows if r[4] <= 2)
ok1 = sum(1 for r in rows if r[4] < 1)
for r in rows:
    print(f"| {r[0]} | {r[1]:g} | {r[2]} | {r[3]} | {r[4]:.2f} |")
print(f"\nwithin 2x of the cheapest peer: {ok2} of {len(rows)}; cheaper: {ok1}")
