"""The values the flight-dynamics model takes and gives (hil/HIL_INTERFACES.md section 1)."""
from dataclasses import dataclass
from typing import Tuple

TURBULENCE_LEVELS = ("none", "light", "moderate")


@dataclass(frozen=True)
class Surfaces:
    """Servo commands or positions in the signs of msg/pwm.msg: elevator trailing edge down +
    (pitches nose down), aileron + rolls right, rudder trailing edge left + (yaws left);
    throttle 0..1."""
    elevator_deg: float
    aileron_deg: float
    rudder_deg: float
    throttle: float


@dataclass(frozen=True)
class Wind:
    """Mean wind blowing from mean_from_deg (true, meteorological) at mean_mps, with seeded
    turbulence on top."""
    mean_from_deg: float = 0.0
    mean_mps: float = 0.0
    turbulence: str = "none"

    def __post_init__(self):
        if self.turbulence not in TURBULENCE_LEVELS:
            raise ValueError(f"turbulence must be one of {TURBULENCE_LEVELS}, not {self.turbulence!r}")
        if not self.mean_mps >= 0.0:
            raise ValueError(f"mean wind speed must be >= 0, not {self.mean_mps}")


@dataclass(frozen=True)
class Truth:
    """The simulator's state at one instant. Body axes FRD, earth NED, SI units and degrees."""
    t_s: float
    lat_deg: float
    lon_deg: float
    alt_msl_m: float
    height_agl_m: float
    ground_msl_m: float
    vn_mps: float
    ve_mps: float
    vd_mps: float
    roll_deg: float
    pitch_deg: float
    heading_deg: float
    p_rad_s: float
    q_rad_s: float
    r_rad_s: float
    accel_body_mps2: Tuple[float, float, float]   # specific force (what an accelerometer reads)
    airspeed_true_mps: float
    airspeed_cal_mps: float
    alpha_deg: float
    beta_deg: float
    servo: Surfaces                               # at the surfaces, after the servo model
    on_ground: bool
    mag_body_gauss: Tuple[float, float, float]
    pressure_pa: float
    temperature_c: float
    crashed: bool = False                         # the flight ended on the ground (FdmCrash)
    air_density_kg_m3: float = 1.225              # where the aircraft is (JSBSim's atmosphere)
