"""Small helpers shared by the FMU tests: drive an FMU step by step with fmpy's FMU2Slave."""
import shutil

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


class Driver:
    """One instantiated, initialised FMU; `vr[name]` maps variable names to value references."""

    def __init__(self, fmu_path, name="inst", unzip=None, start=0.0, initialise=True):
        self.md = read_model_description(fmu_path)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.own_unzip = unzip is None
        self.unzip = unzip or extract(fmu_path)
        self.fmu = FMU2Slave(guid=self.md.guid, unzipDirectory=self.unzip,
                             modelIdentifier=self.md.coSimulation.modelIdentifier, instanceName=name)
        self.fmu.instantiate()
        self.t = start
        if initialise:
            self.fmu.setupExperiment(startTime=start)
            self.fmu.enterInitializationMode()
            self.fmu.exitInitializationMode()

    def names(self, causality):
        return [v.name for v in self.md.modelVariables if v.causality == causality and v.type == "Real"]

    def get(self, names):
        return self.fmu.getReal([self.vr[n] for n in names])

    def set(self, names, values):
        self.fmu.setReal([self.vr[n] for n in names], list(values))

    def step(self, h):
        self.fmu.doStep(currentCommunicationPoint=self.t, communicationStepSize=h)
        self.t += h

    def close(self):
        self.fmu.freeInstance()
        if self.own_unzip:
            shutil.rmtree(self.unzip, ignore_errors=True)
