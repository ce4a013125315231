"""airframe.yaml's rigid body, aerodynamics and propulsion, read once: the gain design's
nonlinear model (drone_ros/gnc/design) and the simulator's JSBSim model (hil/fdm) are built on
these same numbers. SI units in the names."""


class AirframeBody:
    """data: a checked airframe.yaml (stack_tools.check_config.load)."""

    def __init__(self, data):
        self.mass_kg = float(data["mass_kg"])
        inertia = data["inertia_kg_m2"]
        self.ixx, self.iyy, self.izz = (float(inertia[k]) for k in ("ixx", "iyy", "izz"))
        self.ixz = float(inertia.get("ixz", 0.0))
        geo = data["geometry"]
        self.wing_area_m2 = float(geo["wing_area_m2"])
        self.span_m = float(geo["wing_span_m"])
        self.chord_m = float(geo["mean_chord_m"])
        self.aero = {k: float(v) for k, v in data["aero"].items()}
        # The design model's constant atmosphere; the simulation itself uses ISA and WGS84.
        self.design_air_density_kg_m3 = float(data["air_density_kg_m3"])
        self.design_gravity_m_s2 = float(data["gravity_m_s2"])
        prop = data["propulsion"]
        self.max_thrust_n = float(prop["max_thrust_n"])
        self.zero_thrust_speed_mps = float(prop["zero_thrust_speed_m_s"])
