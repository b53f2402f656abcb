"""libcosim (the OSP co-simulation engine, C++ FMI importer) loads every shipped FMU and steps it
for 20 communication steps; every output stays finite."""
import math

from fmpy import read_model_description
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave


def test_libcosim_loads_and_steps(fmu):
    md = read_model_description(fmu)
    step_ns = int(round(float(md.defaultExperiment.stepSize) * 1e9))
    ex = CosimExecution.from_step_size(step_size=step_ns)
    slave = CosimLocalSlave(fmu_path=fmu, instance_name="triad")
    idx = ex.add_local_slave(local_slave=slave)
    assert idx >= 0
    obs = CosimObserver.create_last_value()
    ex.add_observer(observer=obs)
    assert ex.step(step_count=20)
    assert ex.status().current_time == 20 * step_ns
    outs = [v.valueReference for v in md.modelVariables if v.causality == "output"]
    values = obs.last_real_values(slave_index=idx, variable_references=outs)
    assert len(values) == len(outs)
    assert all(math.isfinite(x) for x in values)
