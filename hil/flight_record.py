"""What a HiL flight leaves behind for its judges, by name: the simulator writes it, the verdicts
(hil.verdicts) and the fault classes' own checks read it.

- `FlightRecord`: the whole flight as the verdicts judge it (hil.verdicts.summarize): its
  periods, the scenario it flew (plan, home, fault, world), what the ground station was shown,
  and what it cost. The simulator hands it over when the flight ends (Simulation.flight_record);
  a verdict reads nothing else, so it can be judged, and tested, without a simulator.

- `Period`: one HA period on the simulator's time axis, the truth and the HA's reply of it. In
  lockstep there is one per step; real time keeps one per simulator step too.
- `HaPeriod`: one period as the HA itself counted it (lockstep: the same periods; real time: the
  HA's own ticks from its replies, which the simulator sees up to a step late).

Who flew when is computed once, by report_core.switches.stretches over any controller series:
the verdicts' `who_flew` from the periods and the flight report's runs from the bag's
DecisionStatus both call it."""
from dataclasses import dataclass, field
from typing import NamedTuple, Optional


class Period(NamedTuple):
    t_us: int  # simulated time of the period
    truth: object  # drone_ros/HilTruth as published on /hil/truth (feet, degrees)
    reply: object  # hil.ha_channel's reply: controller, reasons, applied surfaces, counters
    cmd_seq: object  # the HP command's sequence number the HA took, or None
    airspeed_cal_ftps: float  # calibrated airspeed of the truth (what a pitot would read)

    @property
    def t_s(self):
        return self.t_us * 1e-6


class HaPeriod(NamedTuple):
    t_s: float
    commands_received: int  # the HA link's count of HP commands delivered so far
    controller: int  # msg/DecisionStatus.msg CONTROLLER_*
    reasons_at_switch: int


@dataclass
class World:
    """The air a flight flew in."""
    field_elevation_ft: float
    temperature_c: float
    start_density_kg_m3: Optional[float]  # at the airborne start; None if it never came
    wind: object  # the scenario's (hil.fdm.Wind: mean_from_deg, mean_mps, turbulence)
    wind_at_end: object  # a fault may have changed it in flight
    design_wind: object = None  # hil.design_wind.DesignWind of the aircraft, if it has one


@dataclass
class FlightRecord:
    aircraft: str
    seed: int
    mode: str  # "lockstep" or "realtime"
    rate_hz: float
    period_us: int
    controller_dt_s: float
    periods: list  # Period, one per simulator step
    ha_periods: list  # HaPeriod, on the periods' time axis
    ground_s: float  # parked until then; the airborne start
    regions: object  # hil.verdicts.Regions: S_x, S_u and the limits they come from
    stall_alphas_deg: tuple  # the airframe's (positive, negative) stall angles of attack
    plan: object  # hil.mission's plan flown (home, items)
    home: tuple  # (lat, lon, alt m): where the aircraft stood parked
    reach_ft: float  # the controller's "waypoint reached" distance
    fault: object = None  # the hil.faults class that was injected, which judges its own effect
    crashed_at: Optional[float] = None  # when an HP crash or hang was injected
    events: list = field(default_factory=list)
    waypoint_log: list = field(default_factory=list)  # (t_s, the guidance's waypoint index)
    world: Optional[World] = None
    gs_positions: Optional[list] = None  # hil.gs_monitor.Position; None: nobody watched
    gs_home: object = None  # the HOME_POSITION the ground station was shown
    wall_s: float = 0.0
    cpu_s: float = 0.0  # the simulator's own
    step_totals: dict = field(default_factory=dict)  # wall s per phase of a step, summed
    latency: Optional[dict] = None  # sensor to servo in real time
