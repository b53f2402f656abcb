"""The records behind BENCHMARKS.md's work-precision table (wp_table.py) and plots (wp_plot.py).

A results folder holds either one accuracy.json (the records of one `bash bench/peers/run.sh`:
every row from it) or the split records of results/session20: fixed-step rows of every engine
for double_pendulum and free_body_dzhanibekov from fixed_dp_dzhanibekov.json, for the other
models from fixed_peers_fine.json, and triad's error-controlled rows (EMa2-/EMa4-<rtol>) from
adaptive.json."""
import json
import os

MODELS = ['double_pendulum', 'heavy_top', 'free_body_dzhanibekov', 'free_body_torque',
          'chain100', 'ur5_pd']
# the models whose fixed rows come from fixed_dp_dzhanibekov.json in the split layout
SAME_RUN = ('double_pendulum', 'free_body_dzhanibekov')
DEFAULT = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'results', 'session22b')


class Records:
    """`fixed(model)`: the fixed-step rows that apply to `model`; `adaptive`: triad's
    error-controlled rows; `one_run`: whether every row comes from one harness run."""

    def __init__(self, folder=DEFAULT):
        def load(name):
            with open(os.path.join(folder, name)) as f:
                return json.load(f)
        self.one_run = os.path.exists(os.path.join(folder, 'accuracy.json'))
        if self.one_run:
            acc = load('accuracy.json')
            self.adaptive = [r for r in acc if r['method'].startswith('EMa')]
            self._same = self._rest = [r for r in acc if not r['method'].startswith('EMa')]
        else:
            self.adaptive = load('adaptive.json')
            self._same = load('fixed_dp_dzhanibekov.json')
            self._rest = load('fixed_peers_fine.json')

    def fixed(self, model):
        return self._same if model in SAME_RUN else self._rest

    def run_label(self, model):
        """'one run', or in the split layout 'A' (fixed rows from the run that covered the
        SAME_RUN models) / 'B' (the rest)."""
        return 'one run' if self.one_run else 'A' if model in SAME_RUN else 'B'
