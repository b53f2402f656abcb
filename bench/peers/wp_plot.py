#!/usr/bin/env python3
"""Work-precision plots (BENCHMARKS.md, section "Work–precision") from the peers harness records.

Draws, from the records of a results folder (its accuracy.json: wp_records.py, as for
wp_table.py):

  wp_<model>.png  per model: largest joint error over the run (x, log) against cost in µs per
                  simulated second = us_per_step / h (y, log); one line per (engine, method)
                  through its fixed-step runs (status ok, finite error), sorted by h; triad's fixed
                  rows (EM2, EM4, EM4s5) and its error-controlled sweeps (EMa2, EMa4, one point per
                  rtol, labelled with the rtol at the decades) drawn thick, the peers thin; dashed
                  verticals at err = 1e-4 and 1e-6 (the thresholds of the table).
  tolerance.png   achieved error against rtol for EMa4 (solid) and EMa2 (dashed) of every model,
                  with err = rtol and the band rtol/10 ... 10 rtol.

  python bench/peers/wp_plot.py [RESULTS_DIR] [OUT_DIR]
      defaults: bench/peers/results/session22b (the run in BENCHMARKS.md) and bench/peers/plots
Needs numpy and matplotlib (e.g. target/venv-peers/bin/python). The PNGs carry no timestamp or
version metadata, so the same records give the same files.
"""
import math
import os
import sys

import numpy as np
import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from wp_records import DEFAULT, MODELS, Records  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = sys.argv[1] if len(sys.argv) > 1 else DEFAULT
OUT = sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, 'plots')

THRESHOLDS = (1e-4, 1e-6)

# triad: thick, saturated; fixed rows warm, error-controlled sweeps blue
TRIAD_STYLE = {
    'EM2': dict(color='#ff7f0e', marker='o', ls='-'),
    'EM4': dict(color='#d62728', marker='s', ls='-'),
    'EM4s5': dict(color='#7a0019', marker='D', ls='-'),
    'EMa2': dict(color='#17becf', marker='v', ls='--'),
    'EMa4': dict(color='#1f3fbf', marker='^', ls='-'),
}
TRIAD_ORDER = ['EM2', 'EM4', 'EM4s5', 'EMa2', 'EMa4']
# peers: one colour per engine, marker/line style per method
PEER_COLOR = {'mujoco': '#2ca02c', 'pinocchio': '#9467bd', 'exudyn': '#8c564b',
              'pybullet': '#e377c2', 'triad-fmu': '#9a9a9a'}
PEER_MARKERS = ['o', 's', '^', 'v', 'x', '+', '*']
PEER_LS = ['-', '--', ':', '-.']
SAVE = dict(dpi=90, metadata={'Software': None})


def cost(r):
    return r['us_per_step'] / r['h']


def usable(r):
    err = r.get('err')
    return (r.get('status') == 'ok' and err is not None and math.isfinite(err) and err > 0
            and r.get('us_per_step') is not None and r.get('h'))


def rtol_of(method):
    return float(method.split('-', 1)[1])


def sweep_name(method):
    return method.split('-', 1)[0]


def series(model, fixed, adaptive):
    """{(engine, method): [records]} for one model; triad's sweeps keyed ('triad', 'EMa2'|'EMa4').

    Fixed-step lines are sorted by h, the sweeps by decreasing rtol."""
    out = {}
    for r in fixed:
        if r['model'] == model and usable(r):
            out.setdefault((r['engine'], r['method']), []).append(r)
    for k in out:
        out[k].sort(key=lambda r: r['h'])
    for r in adaptive:
        if r['model'] == model and r['engine'] == 'triad' and usable(r):
            out.setdefault(('triad', sweep_name(r['method'])), []).append(r)
    for m in ('EMa2', 'EMa4'):
        if ('triad', m) in out:
            out[('triad', m)].sort(key=lambda r: -rtol_of(r['method']))
    return out


def wp_plot(model, fixed, adaptive):
    data = series(model, fixed, adaptive)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    handles = []
    # peers first (underneath), engine by engine
    peers = sorted(k for k in data if k[0] != 'triad')
    per_engine = {}
    for eng, meth in peers:
        i = per_engine.setdefault(eng, [])
        i.append(meth)
        n = len(i) - 1
        rs = data[(eng, meth)]
        label = f'{eng} {meth}' + (' (fmpy)' if eng == 'triad-fmu' else '')
        h, = ax.plot([r['err'] for r in rs], [cost(r) for r in rs],
                     color=PEER_COLOR.get(eng, '#555555'),
                     marker=PEER_MARKERS[n % len(PEER_MARKERS)],
                     ls=PEER_LS[n % len(PEER_LS)], lw=0.9, ms=3.5, alpha=0.8, mfc='none', zorder=2,
                     label=label)
        handles.append(h)
    triad_handles = []
    for meth in TRIAD_ORDER:
        rs = data.get(('triad', meth))
        if not rs:
            continue
        st = TRIAD_STYLE[meth]
        sweep = meth.startswith('EMa')
        label = f'triad {meth}' + (' (rtol)' if sweep else '')
        h, = ax.plot([r['err'] for r in rs], [cost(r) for r in rs], color=st['color'],
                     marker=st['marker'], ls=st['ls'], lw=2.4, ms=5.5, zorder=5, label=label)
        triad_handles.append(h)
        if sweep:
            dy = 5 if meth == 'EMa4' else -9
            placed = []  # (log err, log cost, stack) of labelled points: stack coincident labels
            for r in rs:
                # labels at the decades only (the sweep also has 2 and 5 between them)
                decade = math.log10(rtol_of(r['method']))
                if abs(decade - round(decade)) > 1e-9:
                    continue
                lx, ly = math.log10(r['err']), math.log10(cost(r))
                stack = sum(1 for px, py in placed
                            if abs(px - lx) < 0.15 and abs(py - ly) < 0.15)
                placed.append((lx, ly))
                # a label that would land on an earlier one goes to the other side of the point
                off = (3, dy) if stack % 2 == 0 else (-3, -4 - dy)
                ax.annotate(r['method'].split('-', 1)[1], (r['err'], cost(r)), xytext=off,
                            ha='left' if stack % 2 == 0 else 'right',
                            textcoords='offset points', fontsize=6,
                            color=st['color'], zorder=6,
                            bbox=dict(boxstyle='square,pad=0.05', fc='white', ec='none', alpha=0.7))
    for thr in THRESHOLDS:
        ax.axvline(thr, color='k', ls='--', lw=0.8, alpha=0.6, zorder=1)
        ax.annotate(f'{thr:.0e}', (thr, 1), xycoords=('data', 'axes fraction'), xytext=(2, -9),
                    textcoords='offset points', fontsize=7, color='k', alpha=0.7)
    ax.set_xscale('log')
    ax.set_yscale('log')
    ax.set_xlabel('largest joint error over the run')
    ax.set_ylabel('cost [µs per simulated second]')
    ax.set_title(model)
    ax.grid(True, which='major', lw=0.4, alpha=0.4)
    ax.legend(handles=triad_handles + handles, loc='upper left', bbox_to_anchor=(1.01, 1.0),
              fontsize=6.5, frameon=False, handlelength=2.6, borderaxespad=0.0)
    fig.tight_layout()
    path = os.path.join(OUT, f'wp_{model}.png')
    fig.savefig(path, **SAVE)
    plt.close(fig)
    return path


def tolerance_plot(adaptive):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    colors = plt.get_cmap('tab10').colors
    all_rtol = []
    for i, model in enumerate(MODELS):
        for meth, ls, mk in (('EMa4', '-', 'o'), ('EMa2', '--', 's')):
            rs = sorted((r for r in adaptive if r['model'] == model and r['engine'] == 'triad'
                         and sweep_name(r['method']) == meth and usable(r)),
                        key=lambda r: rtol_of(r['method']))
            if not rs:
                continue
            x = [rtol_of(r['method']) for r in rs]
            all_rtol += x
            ax.plot(x, [r['err'] for r in rs], color=colors[i], ls=ls, marker=mk, ms=4,
                    lw=1.6 if meth == 'EMa4' else 1.1, mfc='none' if meth == 'EMa2' else colors[i])
    lo, hi = min(all_rtol) / 2, max(all_rtol) * 2
    t = np.geomspace(lo, hi, 50)
    ax.fill_between(t, t / 10, t * 10, color='0.85', zorder=0, lw=0)
    ax.plot(t, t, color='k', lw=1.0, zorder=1)
    ax.set_xscale('log')
    ax.set_yscale('log')
    ax.set_xlim(lo, hi)
    ax.set_xlabel('rtol')
    ax.set_ylabel('achieved largest joint error')
    ax.set_title('tolerance proportionality (triad, error-controlled)')
    ax.grid(True, which='major', lw=0.4, alpha=0.4)
    handles = [Line2D([], [], color=colors[i], lw=1.6, label=m) for i, m in enumerate(MODELS)]
    handles += [Line2D([], [], color='k', ls='-', marker='o', ms=4, lw=1.6, label='EMa4 (order 4)'),
                Line2D([], [], color='k', ls='--', marker='s', mfc='none', ms=4, lw=1.1,
                       label='EMa2 (order 2)'),
                Line2D([], [], color='k', lw=1.0, label='err = rtol'),
                Patch(color='0.85', label='rtol/10 … 10·rtol')]
    ax.legend(handles=handles, loc='upper left', bbox_to_anchor=(1.01, 1.0), fontsize=7,
              frameon=False, borderaxespad=0.0)
    fig.tight_layout()
    path = os.path.join(OUT, 'tolerance.png')
    fig.savefig(path, **SAVE)
    plt.close(fig)
    return path


def main():
    os.makedirs(OUT, exist_ok=True)
    recs = Records(RESULTS)
    for model in MODELS:
        print(wp_plot(model, recs.fixed, recs.adaptive))
    print(tolerance_plot(recs.adaptive))


if __name__ == '__main__':
    main()
