"""The records behind BENCHMARKS.md's work-precision table (wp_table.py) and plots (wp_plot.py):
the accuracy.json of one `bash bench/peers/run.sh` (its results folder)."""
import json
import os

MODELS = ['double_pendulum', 'heavy_top', 'free_body_dzhanibekov', 'free_body_torque',
          'chain100', 'ur5_pd']
DEFAULT = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'results', 'session22b')


class Records:
    """`fixed`: the fixed-step rows of every engine; `adaptive`: triad's error-controlled rows
    (EMa2-/EMa4-<rtol>)."""

    def __init__(self, folder=DEFAULT):
        with open(os.path.join(folder, 'accuracy.json')) as f:
            acc = json.load(f)
        self.adaptive = [r for r in acc if r['method'].startswith('EMa')]
        self.fixed = [r for r in acc if not r['method'].startswith('EMa')]
