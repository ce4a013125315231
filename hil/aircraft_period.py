"""The HA's period of an aircraft: limits.yaml's decision.rate_hz, from which the HA's compiled-in
configuration is generated. The HiL runs the HA at it unless a run asks for another rate (a
benchmark at 20 Hz), and the boards' images run nothing else."""
import os

import yaml


def decision_rate_hz(aircraft_dir):
    """The rate [Hz] the aircraft's HA decides at."""
    with open(os.path.join(aircraft_dir, "limits.yaml")) as f:
        return float(yaml.safe_load(f)["decision"]["rate_hz"])
