"""The HA's period of an aircraft: limits.yaml's decision.rate_hz, from which the HA's compiled-in
configuration is generated. The HiL runs the HA at it unless a run asks for another rate (a
benchmark at 20 Hz), and the boards' images run nothing else. And the aircraft's cruise, where
the HiL's airborne start puts it."""
import os

import yaml


def design_airspeed_ftps(aircraft_dir):
    """The airspeed [ft/s] the aircraft's gains were designed at (airframe.yaml's design point):
    its cruise, where the HiL's airborne start puts it."""
    with open(os.path.join(aircraft_dir, "airframe.yaml")) as f:
        return float(yaml.safe_load(f)["design_point"]["airspeed_ftps"])


def decision_rate_hz(aircraft_dir):
    """The rate [Hz] the aircraft's HA decides at."""
    with open(os.path.join(aircraft_dir, "limits.yaml")) as f:
        return float(yaml.safe_load(f)["decision"]["rate_hz"])
