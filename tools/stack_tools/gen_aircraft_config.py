"""Turn aircraft/<name>/limits.yaml into the HA core's const HaAircraftConfig initializer.

The HA core must hold no per-aircraft literal, and arduino-cli cannot run generators, so this
script writes a C header (a checked-in copy for the Due, a fresh one in the build dir for host
builds; a test keeps them identical). It builds the safety regions S_x and S_u from the limits,
converts times to integer microseconds and refuses a configuration that makes no sense.

usage: python3 -m stack_tools.gen_aircraft_config <limits.yaml> <out.h>     (out '-' writes to stdout)
       python3 -m stack_tools.gen_aircraft_config --types <out.h>   (the struct: ha_config_schema.py)
"""
import math
import os
import struct
import sys

from stack_tools import gen_limits_ranges  # the one table of ranges every component checks with
from stack_tools import check_config  # aircraft/schema/limits.schema.json: no unknown, missing or mistyped key
from stack_tools.generated_file import run_generator
from stack_tools.paths import ROOT

# The struct the values fill, its vectors' order and its array sizes: one table (HaAircraftConfig).
from stack_tools.ha_config_schema import (MAX_RESTARTS_CAP, SELF_TEST_STEPS, SU_MAX_ROWS, SU_MAX_TERMS,
                                          SX_MAX_ROWS, SX_MAX_TERMS, U_NAMES, X_NAMES, check_values,
                                          render_types)


class ConfigError(Exception):
    pass


STANDARD_GRAVITY_FTPS2 = 32.174  # physics, not aircraft data
FLT_MAX = 3.4028234663852886e38  # the core holds every value as an IEEE-754 single
FLT_MIN_NORMAL = 1.1754943508222875e-38
US_MAX = 2 ** 32 - 1  # times are uint32_t microseconds


def fits_f32(key, value, what="value"):
    """A value the core's float can hold: neither overflowing to inf nor vanishing to 0 (or a
    denormal, which the Due's soft float handles slowly and EVA flags)."""
    if abs(value) > FLT_MAX:
        raise ConfigError("%s: %s %g does not fit a 32-bit float (overflows to inf)"
                          % (key, what, value))
    if value != 0.0 and abs(value) < FLT_MIN_NORMAL:
        raise ConfigError("%s: %s %g vanishes as a 32-bit float (below %g)"
                          % (key, what, value, FLT_MIN_NORMAL))
    return value


def need(section, key, low=None, high=None):
    if key not in section:
        raise ConfigError("missing key: %s" % key)
    value = section[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ConfigError("%s must be a number" % key)
    value = float(value)
    if not math.isfinite(value):
        raise ConfigError("%s must be finite" % key)
    fits_f32(key, value)
    if low is not None and value < low:
        raise ConfigError("%s = %g is below %g" % (key, value, low))
    if high is not None and value > high:
        raise ConfigError("%s = %g is above %g" % (key, value, high))
    return value


RANGES = gen_limits_ranges.ranges()


def ranged(doc, path):
    """A key of aircraft/limits_ranges.yaml, checked against the range every component uses."""
    section, key = path.split("/")
    low, high = RANGES[path]
    return need(doc[section], key, low, high)


def positive(section, key):
    value = need(section, key)
    if value <= 0.0:
        raise ConfigError("%s must be > 0" % key)
    return value


def whole(section, key, low, high):
    """A count or a pulse width: the core holds it as an integer, so a fraction is refused, not
    truncated."""
    value = need(section, key, low, high)
    if not value.is_integer():
        raise ConfigError("%s = %g must be a whole number (the core would truncate it to %d)"
                          % (key, value, int(value)))
    return int(value)


def us(seconds, key):
    """Seconds to the core's integer microseconds: refused if it rounds to no time at all or
    does not fit the 32-bit clock."""
    value = int(round(seconds * 1e6))
    if value <= 0:
        raise ConfigError("%s = %g s rounds to 0 us" % (key, seconds))
    if value > US_MAX:
        raise ConfigError("%s = %g s does not fit a 32-bit microsecond clock" % (key, seconds))
    return value


def symmetric_rows(dim, index, limit, key):
    """Rows +v/limit <= 1 and -v/limit <= 1 of a symmetric box constraint."""
    up = [0.0] * dim
    down = [0.0] * dim
    up[index] = fits_f32(key, 1.0 / limit, "region row 1/limit =")
    down[index] = -up[index]
    return [up, down]


FT_PER_M = 1.0 / 0.3048
# What the airframe's stall speed in limits.yaml may differ from the one airframe.yaml implies:
# the rounding of a figure quoted in ft/s, not a second opinion.
STALL_SPEED_AGREEMENT = 0.02


def airframe_path(limits_path, aircraft):
    """airframe.yaml beside limits.yaml, else the aircraft's own in aircraft/<name>/."""
    beside = os.path.join(os.path.dirname(os.path.abspath(limits_path)), "airframe.yaml")
    if os.path.exists(beside):
        return beside
    return os.path.join(ROOT, "aircraft", str(aircraft), "airframe.yaml")


def airframe_stall(airframe):
    """The 1 g stall speed (ft/s, at max take-off mass, the airframe's density) and the stall
    angle of attack (deg: lift linear in alpha up to cl_max) of airframe.yaml."""
    try:
        aero = airframe["aero"]
        mass = float(airframe["mass_kg"])
        g = float(airframe["gravity_m_s2"])
        rho = float(airframe["air_density_kg_m3"])
        area = float(airframe["geometry"]["wing_area_m2"])
        cl_max, cl0 = float(aero["cl_max"]), float(aero["cl0"])
        cl_alpha = float(aero["cl_alpha_per_rad"])
    except (KeyError, TypeError, ValueError) as err:
        raise ConfigError("airframe.yaml: cannot read the stall from it (%s)" % err)
    if min(mass, g, rho, area, cl_max, cl_alpha) <= 0.0 or cl_max <= cl0:
        raise ConfigError("airframe.yaml: mass, gravity, density, wing area, cl_max and cl_alpha "
                          "must be > 0 and cl_max above cl0")
    stall_ftps = math.sqrt(2.0 * mass * g / (rho * area * cl_max)) * FT_PER_M
    alpha_deg = math.degrees((cl_max - cl0) / cl_alpha)
    return stall_ftps, alpha_deg


def trim_alpha_deg(airframe, nose_up_deg):
    """The angle of attack airframe.yaml's pitching moment trims at with this much nose-up
    elevator (trailing edge up; msg/pwm.msg's elevator is its negative), pitch rate zero:
    cm0 + cm_alpha alpha + cm_elevator (-nose_up) = 0."""
    try:
        aero = airframe["aero"]
        cm0, cm_alpha = float(aero["cm0"]), float(aero["cm_alpha_per_rad"])
        cm_de = float(aero["cm_elevator_per_rad"])
    except (KeyError, TypeError, ValueError) as err:
        raise ConfigError("airframe.yaml: cannot read the pitching moment from it (%s)" % err)
    if cm_alpha >= 0.0 or cm_de >= 0.0:
        raise ConfigError("airframe.yaml: cm_alpha_per_rad and cm_elevator_per_rad must be < 0 "
                          "(a statically stable airframe, trailing edge down pitching down)")
    return math.degrees(-(cm0 - cm_de * math.radians(nose_up_deg)) / cm_alpha)


# What limits.yaml's elevator trim may differ from the airframe's: a figure rounded to a tenth,
# not another trim.
ELEVATOR_TRIM_AGREEMENT_DEG = 0.3


def level_trim_elevator_deg(airframe, airspeed_ftps):
    """The elevator (deg, trailing edge down positive) with which airframe.yaml flies level at
    this airspeed, pitch rate zero: its lift equal to its weight, its pitching moment zero."""
    try:
        aero = airframe["aero"]
        v_m_s = airspeed_ftps / FT_PER_M
        qbar_s = 0.5 * float(airframe["air_density_kg_m3"]) * v_m_s * v_m_s \
            * float(airframe["geometry"]["wing_area_m2"])
        cl_needed = float(airframe["mass_kg"]) * float(airframe["gravity_m_s2"]) / qbar_s
        cl_a, cl_de = float(aero["cl_alpha_per_rad"]), float(aero["cl_elevator_per_rad"])
        cm_a, cm_de = float(aero["cm_alpha_per_rad"]), float(aero["cm_elevator_per_rad"])
        lift, moment = cl_needed - float(aero["cl0"]), -float(aero["cm0"])
    except (KeyError, TypeError, ValueError, ZeroDivisionError) as err:
        raise ConfigError("airframe.yaml: cannot trim it (%s)" % err)
    det = cl_a * cm_de - cl_de * cm_a
    if det == 0.0:
        raise ConfigError("airframe.yaml: its lift and pitching moment cannot be trimmed together")
    return math.degrees((cl_a * moment - cm_a * lift) / det)


def check_trim_against_airframe(c, airframe):
    """The safety controller flies about limits.yaml's elevator trim (a blind HA holds it): it
    must be the one airframe.yaml trims level at the throttle loop's target speed."""
    if -c["sc_elevator_trim_deg"] >= c["sc_elevator_pull_max_deg"]:
        raise ConfigError("elevator_trim_deg = %g is at or past the HA's own elevator stop "
                          "(elevator_pull_max_deg %g nose up): it could not fly its own trim"
                          % (c["sc_elevator_trim_deg"], c["sc_elevator_pull_max_deg"]))
    trim_deg = level_trim_elevator_deg(airframe, c["sc_target_ftps"])
    if abs(c["sc_elevator_trim_deg"] - trim_deg) > ELEVATOR_TRIM_AGREEMENT_DEG:
        raise ConfigError("elevator_trim_deg = %g contradicts airframe.yaml, which trims level at "
                          "the %.1f ft/s target with %.2f deg (more than %g deg apart)"
                          % (c["sc_elevator_trim_deg"], c["sc_target_ftps"], trim_deg,
                             ELEVATOR_TRIM_AGREEMENT_DEG))


def check_against_airframe(c, airframe):
    """One source for the stall: limits.yaml's stall speed and stall alpha must be airframe.yaml's.
    The HA judges the stall by both (ha_checks.c), so an alpha limit past the wing's stall or a
    stall speed below the wing's would let a stalled aircraft pass."""
    stall_ftps, alpha_deg = airframe_stall(airframe)
    if abs(c["stall_speed_ftps"] - stall_ftps) > STALL_SPEED_AGREEMENT * stall_ftps:
        raise ConfigError("stall_speed_ftps = %g contradicts airframe.yaml, whose mass, wing area "
                          "and cl_max stall at %.1f ft/s (more than %g%% apart)"
                          % (c["stall_speed_ftps"], stall_ftps, 100 * STALL_SPEED_AGREEMENT))
    if c["stall_alpha_deg"] > alpha_deg:
        raise ConfigError("stall_alpha_deg = %g is beyond airframe.yaml's stall angle of attack "
                          "%.2f deg ((cl_max - cl0) / cl_alpha): a stalled wing would pass"
                          % (c["stall_alpha_deg"], alpha_deg))
    # The elevator stops (ha_checks.c: the HP's pull; ha_safety_ctrl.c: the HA's own).
    own = trim_alpha_deg(airframe, c["sc_elevator_pull_max_deg"])
    if own >= c["stall_alpha_deg"]:
        raise ConfigError("elevator_pull_max_deg = %g trims the wing at %.2f deg, at or past "
                          "stall_alpha_deg %g: the HA's own elevator would hold a stall"
                          % (c["sc_elevator_pull_max_deg"], own, c["stall_alpha_deg"]))
    hp = trim_alpha_deg(airframe, c["elevator_pull_limit_deg"])
    if hp < alpha_deg:
        raise ConfigError("elevator_pull_limit_deg = %g trims the wing at %.2f deg, below its "
                          "%.2f deg stall: a healthy HP flying near the stall would be taken out"
                          % (c["elevator_pull_limit_deg"], hp, alpha_deg))


def _surfaces_state_sensors(c, doc, airframe):
    """The surfaces' and the state's limits, the sensors' bounds; the roll and pitch limits and
    the rate limits (roll; pitch and yaw)."""
    act, st, sen, sc = doc["actuators"], doc["state"], doc["sensors"], doc["safety_controller"]
    c["elevator_limit_deg"] = ranged(doc, "actuators/elevator_limit_deg")
    c["aileron_limit_deg"] = ranged(doc, "actuators/aileron_limit_deg")
    c["rudder_limit_deg"] = ranged(doc, "actuators/rudder_limit_deg")
    c["throttle_min"] = ranged(doc, "actuators/throttle_min")
    c["throttle_max"] = ranged(doc, "actuators/throttle_max")
    if c["throttle_max"] <= c["throttle_min"]:
        raise ConfigError("throttle_max must exceed throttle_min")
    c["surface_rate_limit_deg_per_s"] = positive(act, "surface_rate_limit_deg_per_s")
    c["throttle_rate_limit_per_s"] = positive(act, "throttle_rate_limit_per_s")
    c["surface_release_rate_deg_per_s"] = need(act, "surface_release_rate_deg_per_s",
                                               c["surface_rate_limit_deg_per_s"], 600.0)

    c["elevator_pull_limit_deg"] = ranged(doc, "actuators/elevator_pull_limit_deg")
    if c["elevator_pull_limit_deg"] > c["elevator_limit_deg"]:
        raise ConfigError("elevator_pull_limit_deg = %g is past elevator_limit_deg %g"
                          % (c["elevator_pull_limit_deg"], c["elevator_limit_deg"]))
    c["sc_elevator_pull_max_deg"] = need(sc, "elevator_pull_max_deg", 0.0,
                                         c["elevator_pull_limit_deg"])
    c["alpha_limit_deg"] = ranged(doc, "state/alpha_limit_deg")
    c["stall_alpha_deg"] = ranged(doc, "state/stall_alpha_deg")
    if c["stall_alpha_deg"] > c["alpha_limit_deg"]:
        raise ConfigError("stall_alpha_deg = %g is beyond alpha_limit_deg %g: the HP's estimate "
                          "would be refused before the wing could stall"
                          % (c["stall_alpha_deg"], c["alpha_limit_deg"]))
    c["beta_limit_deg"] = ranged(doc, "state/beta_limit_deg")
    roll = ranged(doc, "state/roll_limit_deg")
    pitch = ranged(doc, "state/pitch_limit_deg")
    rate = (positive(st, "roll_rate_limit_deg_per_s"), positive(st, "body_rate_limit_deg_per_s"))
    c["stall_speed_ftps"] = ranged(doc, "state/stall_speed_ftps")
    c["ceiling_agl_ft"] = ranged(doc, "state/ceiling_agl_ft")
    c["airborne_agl_ft"] = ranged(doc, "state/airborne_agl_ft")
    if c["airborne_agl_ft"] > c["ceiling_agl_ft"]:
        raise ConfigError("airborne_agl_ft = %g is above ceiling_agl_ft %g"
                          % (c["airborne_agl_ft"], c["ceiling_agl_ft"]))
    c["landed_confirm_us"] = us(positive(st, "landed_confirm_s"), "landed_confirm_s")
    c["inner_region_fraction"] = need(st, "inner_region_fraction", 0.05, 0.99)
    # The HA switches on an inset of S_x and of the ceiling (limits.yaml says why): strictly
    # outside the hand-back region, so the two cannot chatter, and at most S_x itself.
    c["switch_region_fraction"] = need(st, "switch_region_fraction", c["inner_region_fraction"], 1.0)
    if c["switch_region_fraction"] <= c["inner_region_fraction"]:
        raise ConfigError("switch_region_fraction must exceed inner_region_fraction: the HA would "
                          "switch inside the region it hands back in")
    c["ceiling_switch_agl_ft"] = c["ceiling_agl_ft"] * c["switch_region_fraction"]
    c["max_airspeed_ftps"] = need(sen, "max_airspeed_ftps", c["stall_speed_ftps"])
    # Below stall speed: a stronger tailwind would excuse a pitot reading zero at cruise.
    c["max_wind_ftps"] = need(sen, "max_wind_ftps", 1.0, c["stall_speed_ftps"])
    c["state_timeout_us"] = us(positive(sen, "state_timeout_s"), "state_timeout_s")
    c["airspeed_timeout_us"] = us(positive(sen, "airspeed_timeout_s"), "airspeed_timeout_s")
    if airframe is not None:
        check_against_airframe(c, airframe)
    return roll, pitch, rate


def _regions(c, roll, pitch, rate):
    """S_x and S_u as region rows, within the core's table sizes."""
    # S_x (x - x0) <= 1: symmetric boxes on the angles and rates, and the ceiling on altitude
    # (the HA needs no lower altitude bound here: the stall and airborne checks cover it).
    limits = [("alpha_limit_deg", c["alpha_limit_deg"]), ("beta_limit_deg", c["beta_limit_deg"]),
              ("roll_limit_deg", roll), ("pitch_limit_deg", pitch),
              ("roll_rate_limit_deg_per_s", rate[0])] + [("body_rate_limit_deg_per_s", rate[1])] * 2
    sx = []
    for i, (key, lim) in enumerate(limits):
        sx += symmetric_rows(len(X_NAMES), i, lim, key)
    alt = [0.0] * len(X_NAMES)
    alt[X_NAMES.index("alt_agl_ft")] = fits_f32("ceiling_agl_ft", 1.0 / c["ceiling_agl_ft"],
                                                 "region row 1/limit =")
    sx.append(alt)
    c["sx"] = sx
    c["x0"] = [0.0] * len(X_NAMES)

    # S_u (u - u0) <= 1: surfaces symmetric about neutral, throttle centred on its range.
    su = []
    for i, key in enumerate(["elevator_limit_deg", "aileron_limit_deg", "rudder_limit_deg"]):
        su += symmetric_rows(len(U_NAMES), i, c[key], key)
    half = (c["throttle_max"] - c["throttle_min"]) / 2.0
    su += symmetric_rows(len(U_NAMES), 3, half, "throttle_max")
    c["su"] = su
    c["u0"] = [0.0, 0.0, 0.0, (c["throttle_max"] + c["throttle_min"]) / 2.0]
    if len(sx) > SX_MAX_ROWS or len(su) > SU_MAX_ROWS:
        raise ConfigError("too many region rows for HA_SX_MAX_ROWS/HA_SU_MAX_ROWS")
    if len(nonzero_terms(sx)[1]) > SX_MAX_TERMS or len(nonzero_terms(su)[1]) > SU_MAX_TERMS:
        raise ConfigError("too many nonzero region coefficients for HA_SX_MAX_TERMS/HA_SU_MAX_TERMS")


def _decision(c, dec):
    """The decision's period, timeouts and restart cap, each consistent with the others."""
    rate_hz = ranged({"decision": dec}, "decision/rate_hz")
    c["period_us"] = us(1.0 / rate_hz, "rate_hz")
    c["late_periods_tolerated"] = whole(dec, "late_periods_tolerated", 0.0, 100.0)
    c["no_command_timeout_us"] = us(positive(dec, "no_command_timeout_s"),
                                    "no_command_timeout_s")
    c["stable_window_us"] = us(positive(dec, "stable_window_s"), "stable_window_s")
    c["max_restarts"] = whole(dec, "max_restarts", 1.0, MAX_RESTARTS_CAP)
    c["restart_window_us"] = us(positive(dec, "restart_window_s"), "restart_window_s")
    c["hp_reset_pulse_us"] = us(positive(dec, "hp_reset_pulse_s"), "hp_reset_pulse_s")
    c["hp_boot_timeout_us"] = us(positive(dec, "hp_boot_timeout_s"), "hp_boot_timeout_s")
    if c["hp_boot_timeout_us"] <= c["no_command_timeout_us"]:
        raise ConfigError("hp_boot_timeout_s must exceed no_command_timeout_s")
    # An HP that never comes back is reset every pulse + boot timeout; the K-th reset must fall
    # inside the window for the cap to be reached and the HA to latch.
    if c["max_restarts"] * (c["hp_reset_pulse_us"] + c["hp_boot_timeout_us"]) >= \
            c["restart_window_us"]:
        raise ConfigError("max_restarts x (hp_reset_pulse_s + hp_boot_timeout_s) must be shorter "
                          "than restart_window_s, or a dead HP is reset forever and never latched")
    # Nothing the core times can be shorter than the period it is checked in.
    for key in ("no_command_timeout_us", "state_timeout_us", "airspeed_timeout_us",
                "stable_window_us", "hp_reset_pulse_us", "landed_confirm_us"):
        if c[key] < c["period_us"]:
            raise ConfigError("%s_s (%d us) is shorter than one period (%d us at rate_hz)"
                              % (key[:-3], c[key], c["period_us"]))
    # Tolerated late periods must run out before the no-command timeout, or the tolerance is
    # a fiction: the HP would be declared dead while still "late".
    if c["late_periods_tolerated"] * c["period_us"] >= c["no_command_timeout_us"]:
        raise ConfigError("late_periods_tolerated x period (%d us) must be shorter than "
                          "no_command_timeout_s (%d us)"
                          % (c["late_periods_tolerated"] * c["period_us"],
                             c["no_command_timeout_us"]))
    # The microsecond clock wraps after 2^32 us; longer windows could not be measured.
    for key in ("stable_window_us", "restart_window_us", "no_command_timeout_us",
                "hp_boot_timeout_us"):
        if c[key] >= 2 ** 31:
            raise ConfigError("%s too long for a 32-bit microsecond clock" % key)


def _pulses(c, rc, servo):
    """The RC and servo pulse ranges, the PIC threshold and the sticks' slopes."""
    for prefix, sec in (("rc", rc), ("servo", servo)):
        lo = whole(sec, "pulse_min_us", 500.0, 2500.0)
        hi = whole(sec, "pulse_max_us", 500.0, 2500.0)
        if hi <= lo:
            raise ConfigError("%s pulse_max_us must exceed pulse_min_us" % prefix)
        c[prefix + "_pulse_min_us"] = lo
        c[prefix + "_pulse_max_us"] = hi
    c["pic_threshold_us"] = whole(rc, "pic_threshold_us", c["rc_pulse_min_us"],
                                  c["rc_pulse_max_us"])
    # Stick slopes: [min, max] us onto [-limit, +limit] (throttle onto [min, max]), derived here
    # so the HA divides nothing per period.
    rc_span_us = float(c["rc_pulse_max_us"] - c["rc_pulse_min_us"])
    for surface in ("elevator", "aileron", "rudder"):
        c["rc_%s_deg_per_us" % surface] = 2.0 * c["%s_limit_deg" % surface] / rc_span_us
    c["rc_throttle_per_us"] = (c["throttle_max"] - c["throttle_min"]) / rc_span_us


def _safety_controller_loops(c, sc, roll, pitch):
    """The safety controller's circle, gains, band and pitch limits."""
    c["sc_bank_limit_deg"] = need(sc, "bank_limit_deg", 1.0, roll * c["inner_region_fraction"])
    c["sc_circle_radius_ft"] = positive(sc, "circle_radius_ft")
    direction = need(sc, "circle_direction")
    if direction not in (1.0, -1.0):
        raise ConfigError("circle_direction must be 1 or -1")
    c["sc_circle_direction"] = direction
    for key in ("radial_gain_deg_per_ft", "heading_to_bank_gain", "roll_kp", "pitch_kp",
                "alt_to_pitch_gain_deg_per_ft", "speed_to_pitch_gain_deg_per_ftps",
                "throttle_kp_per_ftps"):
        c["sc_" + key] = positive(sc, key)
    c["sc_radial_correction_max_deg"] = need(sc, "radial_correction_max_deg", 0.0, 90.0)
    for key in ("roll_ki", "roll_kd", "pitch_ki", "pitch_kd", "yaw_damper_gain",
                "throttle_ki_per_ft"):
        c["sc_" + key] = need(sc, key, 0.0)
    c["sc_alt_min_ft"] = need(sc, "alt_min_ft", c["airborne_agl_ft"], c["ceiling_agl_ft"])
    c["sc_alt_max_ft"] = need(sc, "alt_max_ft", c["sc_alt_min_ft"], c["ceiling_agl_ft"])
    if c["sc_alt_max_ft"] <= c["sc_alt_min_ft"]:
        raise ConfigError("alt_max_ft must lie above alt_min_ft: pitch and power's throttle "
                          "is full at the band's floor and the trim at its middle")
    if c["sc_alt_max_ft"] >= c["ceiling_agl_ft"] * c["inner_region_fraction"]:
        raise ConfigError("safety controller band must lie inside the inner region")
    c["sc_pitch_cmd_limit_deg"] = need(sc, "pitch_cmd_limit_deg", 1.0,
                                       pitch * c["inner_region_fraction"])
    c["sc_stall_margin"] = need(sc, "stall_margin", 1.05, 3.0)
    c["sc_pitch_error_max_deg"] = need(sc, "pitch_error_max_deg", 1.0, 45.0)
    # Pitch and power (ha_safety_ctrl.c): without a speed the nose goes no higher than this.
    c["sc_power_pitch_deg"] = need(sc, "power_pitch_deg", -c["sc_pitch_cmd_limit_deg"],
                                   c["sc_pitch_cmd_limit_deg"])
    # The pitch loop's lift guard (ha_safety_ctrl.c): past lift_margin of the wing's maximum lift
    # coefficient, n > margin (IAS / V_stall)^2, the nose is pushed down lift_push_deg_per_g.
    c["sc_lift_margin_per_ias_sq"] = (need(sc, "lift_margin", 0.3, 0.9)
                                      / c["stall_speed_ftps"] ** 2)
    c["sc_lift_push_deg_per_g"] = need(sc, "lift_push_deg_per_g", 0.0, 100.0)


def _safety_controller_speeds(c, sc, st):
    """The speeds the safety controller flies, hands back and switches at, and what derives from them."""
    # The throttle loop's target must lie above the pitch loop's floor, or the aircraft could
    # never climb at it (the nose may rise only with speed above stall x stall_margin).
    c["sc_cruise_margin"] = need(sc, "cruise_margin", c["sc_stall_margin"], 3.0)
    if c["sc_cruise_margin"] <= c["sc_stall_margin"]:
        raise ConfigError("cruise_margin must exceed stall_margin: at the throttle loop's target "
                          "speed the pitch loop could not raise the nose")
    if c["stall_speed_ftps"] * c["sc_cruise_margin"] >= c["max_airspeed_ftps"]:
        raise ConfigError("cruise_margin: target airspeed above max_airspeed_ftps")
    target_ftps = c["stall_speed_ftps"] * c["sc_cruise_margin"]
    handback = need(st, "handback_stall_multiple", 1.0, c["sc_cruise_margin"])
    if handback <= 1.0 or handback >= c["sc_cruise_margin"]:
        raise ConfigError("handback_stall_multiple must lie strictly between 1 and cruise_margin: "
                          "above stall for margin, below the speed the HA itself flies at")
    c["handback_airspeed_ftps"] = c["stall_speed_ftps"] * handback
    stall_switch = need(st, "stall_switch_multiple", 1.0, handback)
    if stall_switch >= handback:
        raise ConfigError("stall_switch_multiple must lie below handback_stall_multiple: the HA "
                          "would hand back at a speed it switches at")
    c["stall_switch_airspeed_ftps"] = c["stall_speed_ftps"] * stall_switch
    # A held pitot reading must not hide the aircraft decelerating through the stall inset: at
    # 1 g it takes (switch speed - stall speed) / g to lose it.
    inset_s = (c["stall_switch_airspeed_ftps"] - c["stall_speed_ftps"]) / STANDARD_GRAVITY_FTPS2
    if c["airspeed_timeout_us"] > inset_s * 1e6:
        raise ConfigError("airspeed_timeout_s = %g s is longer than the %.3f s a 1 g deceleration "
                          "takes from the stall switch speed to stall: a held reading would hide "
                          "the stall" % (c["airspeed_timeout_us"] * 1e-6, inset_s))
    # Steady coordinated turn: tan(bank) = V^2 / (g R). Derived here once, not per period.
    c["sc_circle_bank_ff_deg"] = math.degrees(
        math.atan(target_ftps * target_ftps / (STANDARD_GRAVITY_FTPS2 * c["sc_circle_radius_ft"])))
    if c["sc_circle_bank_ff_deg"] >= c["sc_bank_limit_deg"]:
        raise ConfigError("circle_radius_ft too small: its turn needs more bank than bank_limit_deg")
    c["sc_throttle_trim"] = need(sc, "throttle_trim", c["throttle_min"], c["throttle_max"])
    c["sc_elevator_trim_deg"] = need(sc, "elevator_trim_deg", -c["elevator_limit_deg"],
                                     c["elevator_limit_deg"])
    # Pitch and power's throttle: the trim at the band's middle, full at its floor.
    c["sc_power_throttle_per_ft"] = ((c["throttle_max"] - c["sc_throttle_trim"])
                                     / (0.5 * (c["sc_alt_max_ft"] - c["sc_alt_min_ft"])))
    c["sc_integrator_authority"] = need(sc, "integrator_authority", 0.0, 1.0)
    c["sc_blind_fade_per_s"] = 1.0 / positive(sc, "blind_fade_s")
    derive_safety_ctrl(c)


def _self_test(c, selft):
    """The pre-flight self-test's step and its limits."""
    step_s = positive(selft, "step_s")
    c["self_test_throttle_max"] = need(selft, "throttle_max", c["throttle_min"],
                                       c["throttle_max"])
    slowest = max(2.0 * max(c["elevator_limit_deg"], c["aileron_limit_deg"],
                            c["rudder_limit_deg"]) / c["surface_rate_limit_deg_per_s"],
                  (c["self_test_throttle_max"] - c["throttle_min"])
                  / c["throttle_rate_limit_per_s"])
    if step_s <= slowest:
        raise ConfigError("self_test step_s must exceed %.3f s (slew limit to limit)" % slowest)
    c["self_test_step_us"] = us(step_s, "step_s")
    # The sequence as the targets the core flies, a row per step in HA_U_* order: each surface to
    # + and - its limit and back, then the throttle to half and all of its test maximum and back.
    half = 0.5 * (c["self_test_throttle_max"] - c["throttle_min"])
    c["self_test_u"] = [[d * c[key] if j == i else 0.0 for j in range(3)] + [c["throttle_min"]]
                        for i, key in enumerate(("elevator_limit_deg", "aileron_limit_deg",
                                                 "rudder_limit_deg"))
                        for d in (1.0, -1.0, 0.0)]
    c["self_test_u"] += [[0.0, 0.0, 0.0, c["throttle_min"] + k * half] for k in (1, 2, 0)]
    assert len(c["self_test_u"]) == SELF_TEST_STEPS
    c["self_test_max_tilt_deg"] = need(selft, "max_tilt_deg", 0.0, 45.0)
    c["self_test_max_rate_deg_s"] = need(selft, "max_rate_deg_s", 0.0, 30.0)
    c["self_test_max_groundspeed_ftps"] = need(selft, "max_groundspeed_ftps", 0.0,
                                               c["stall_speed_ftps"])


def build(doc, airframe=None):
    """The HA's configuration from limits.yaml (and the airframe, when given, to check the limits
    against): every value ranged and consistent with the others, in the order the sections
    depend on each other; ConfigError names the first that is not."""
    # Keys first: a misspelt key would otherwise leave the one it meant missing, or ignored.
    try:
        check_config.validate(doc, "limits", "limits.yaml")
    except check_config.ConfigError as err:
        raise ConfigError(str(err)) from None
    sc = doc["safety_controller"]
    c = {}
    c["aircraft"] = str(doc["aircraft"])
    roll, pitch, rate = _surfaces_state_sensors(c, doc, airframe)
    _regions(c, roll, pitch, rate)
    _decision(c, doc["decision"])
    _pulses(c, doc["rc"], doc["servo"])
    _safety_controller_loops(c, sc, roll, pitch)
    _safety_controller_speeds(c, sc, doc["state"])
    _self_test(c, doc["self_test"])
    build_airdata(c, doc)
    if airframe is not None:
        check_trim_against_airframe(c, airframe)
    for key, value in c.items():
        if isinstance(value, float):
            fits_f32(key, value, "derived value")
    return c


def f32_round(value):
    """value as the binary32 the C code holds it in."""
    return struct.unpack("<f", struct.pack("<f", value))[0]


def derive_safety_ctrl(c):
    """What ha_safety_ctrl.c computed from the configuration every period, now once: each value
    rounded after every operation as C's float arithmetic does, so the step's results are
    unchanged to the bit (on the Due each operation was a soft-float call of ~50 instructions)."""
    r = f32_round
    auth = r(c["sc_integrator_authority"])
    half = r(0.5 * r(r(c["throttle_max"]) - r(c["throttle_min"])))
    mid = r(r(c["throttle_min"]) + half)
    c["sc_target_ftps"] = r(r(c["stall_speed_ftps"]) * r(c["sc_cruise_margin"]))
    c["sc_speed_floor_ftps"] = r(r(c["stall_speed_ftps"]) * r(c["sc_stall_margin"]))
    c["sc_alt_mid_ft"] = r(0.5 * r(r(c["sc_alt_min_ft"]) + r(c["sc_alt_max_ft"])))
    c["sc_throttle_half"] = half
    c["sc_throttle_mid"] = mid
    c["sc_throttle_trim_offset"] = r(r(c["sc_throttle_trim"]) - mid)
    c["sc_power_throttle_max"] = r(r(c["throttle_max"]) - r(c["sc_throttle_trim"]))
    c["sc_aileron_integ_limit"] = r(auth * r(c["aileron_limit_deg"]))
    c["sc_elevator_integ_limit"] = r(auth * r(c["elevator_limit_deg"]))
    c["sc_throttle_integ_limit"] = r(auth * half)
    c["sc_blind_fade_auth_per_s"] = r(r(c["sc_blind_fade_per_s"]) * auth)


def build_airdata(c, doc):
    """The HA's airspeed picture (ha_airdata.c) and the bounds on the sensors' timeouts."""
    sen = doc["sensors"]
    c["stall_switch_airspeed_sq"] = c["stall_switch_airspeed_ftps"] ** 2
    c["handback_airspeed_sq"] = c["handback_airspeed_ftps"] ** 2
    # The circle's guidance in vectors, no atan2f/sqrtf per period (ha_safety_ctrl.c).
    radius = c["sc_circle_radius_ft"]
    if c["sc_radial_correction_max_deg"] >= 85.0:
        raise ConfigError("radial_correction_max_deg must be below 85: the course would turn "
                          "straight at home")
    c["sc_radial_tan_per_ft2"] = math.radians(c["sc_radial_gain_deg_per_ft"]) / (2.0 * radius)
    c["sc_radial_tan_max"] = math.tan(math.radians(c["sc_radial_correction_max_deg"]))
    c["sc_circle_radius_sq_ft2"] = radius * radius
    # Above the gusts and sideslip of ordinary flight, below the wind bound (past it the known
    # wind would excuse more than an unknown one).
    c["airspeed_tolerance_ftps"] = need(sen, "airspeed_tolerance_ftps", 1.0, c["max_wind_ftps"])
    c["max_wind_sq"] = c["max_wind_ftps"] ** 2
    tau_s = need(sen, "wind_time_constant_s", 1.0, 600.0)
    c["wind_per_period"] = c["period_us"] * 1e-6 / tau_s
    c["wind_known_us"] = us(3.0 * tau_s, "wind_time_constant_s")
    c["wind_forget_us"] = us(tau_s, "wind_time_constant_s")
    # Long enough that a live sensor's noise cannot repeat a reading (100 reads at 100 Hz), short
    # enough that the HA has the servos before an HP flying on a stuck reading slows to the stall.
    c["pitot_stuck_us"] = us(need(sen, "pitot_stuck_s", 10.0 * c["period_us"] * 1e-6, 5.0),
                             "pitot_stuck_s")
    # A sensor trusted past what the rules can wait for is a dead sensor believed: every timeout
    # must run out before the HP could prove a stable window on the stale value, and before a
    # landing could be confirmed on it; and within the wrapping 32-bit clock.
    for key in ("state_timeout_us", "airspeed_timeout_us"):
        for bound in ("stable_window_us", "landed_confirm_us"):
            if c[key] >= c[bound]:
                raise ConfigError("%s_s = %g s must be shorter than %s_s (%g s): a dead sensor "
                                  "would be trusted for as long as that rule waits"
                                  % (key[:-3], c[key] * 1e-6, bound[:-3], c[bound] * 1e-6))
    for key in ("state_timeout_us", "airspeed_timeout_us", "landed_confirm_us", "wind_known_us",
                "wind_forget_us", "pitot_stuck_us",
                "hp_reset_pulse_us", "self_test_step_us"):
        if c[key] >= 2 ** 31:
            raise ConfigError("%s_s too long for a 32-bit microsecond clock" % key[:-3])


def f32(value):
    text = "%.9g" % value
    if "." not in text and "e" not in text and "n" not in text:
        text += ".0"
    return text + "f"


def row(values):
    return "{" + ", ".join(f32(v) for v in values) + "}"


def nonzero_terms(rows):
    """A dense matrix as the core holds it: each row's end in the term list, and the nonzero
    terms (column, coefficient) row by row."""
    ends, terms = [], []
    for r in rows:
        terms += [(j, v) for j, v in enumerate(r) if v != 0.0]
        ends.append(len(terms))
    return ends, terms


def render_region(name, rows):
    ends, terms = nonzero_terms(rows)
    return (["    .%s_rows = %du, \\" % (name, len(rows)),
             "    .%s_row_end = {%s}, \\" % (name, ", ".join("%du" % e for e in ends)),
             "    .%s = { \\" % name]
            + ["      {%du, %s}, \\" % (j, f32(v)) for j, v in terms] + ["    }, \\"])


def render(c, source):
    try:
        check_values(c)
    except ValueError as err:
        raise ConfigError(str(err)) from err
    floats = [k for k in c if isinstance(c[k], float)]
    ints = [k for k in c if isinstance(c[k], int)]
    lines = [
        "/* Generated by tools/stack_tools/gen_aircraft_config.py from %s." % source,
        " * Do not edit: change the YAML and rebuild (CMake regenerates it; the checked-in copy",
        " * must match). */",
        "#ifndef HA_GENERATED_AIRCRAFT_CONFIG_H",
        "#define HA_GENERATED_AIRCRAFT_CONFIG_H",
        "",
        "/* S_x rows over (%s);" % ", ".join(X_NAMES),
        " * S_u rows over (%s). */" % ", ".join(U_NAMES),
        "#define HA_AIRCRAFT_CONFIG_INITIALIZER \\",
        "  { \\",
        "    .aircraft = \"%s\", \\" % c["aircraft"],
    ]
    lines += render_region("sx", c["sx"]) + ["    .x0 = %s, \\" % row(c["x0"])]
    lines += render_region("su", c["su"]) + ["    .u0 = %s, \\" % row(c["u0"])]
    lines += ["    .self_test_u = { \\"] + ["      %s, \\" % row(r) for r in c["self_test_u"]] + ["    }, \\"]
    for key in floats:
        lines.append("    .%s = %s, \\" % (key, f32(c[key])))
    for key in ints:
        lines.append("    .%s = %du, \\" % (key, c[key]))
    lines += ["  }", "", "#endif /* HA_GENERATED_AIRCRAFT_CONFIG_H */", ""]
    return "\n".join(lines)


def generate(limits_path):
    """The header for limits_path; an error names the file (check_config's do already)."""
    try:
        doc = check_config.load(limits_path, "limits")
        # Name the source by aircraft, not by absolute path, so every checkout generates the same
        # bytes.
        source = "aircraft/%s/limits.yaml" % doc["aircraft"]
        path = airframe_path(limits_path, doc["aircraft"])
        if not os.path.exists(path):
            raise ConfigError("no airframe.yaml for aircraft %s (looked for %s): the stall speed "
                              "and alpha limit cannot be checked" % (doc["aircraft"], path))
        airframe = check_config.load(path, "airframe")
        return render(build(doc, airframe), source)
    except (ConfigError, KeyError, TypeError) as err:
        raise ConfigError("%s: %s" % (limits_path, err)) from err


def write_header(path, text):
    """'-' is stdout; a file is written whole each time, so its date follows its inputs'."""
    if path == "-":
        sys.stdout.write(text)
    else:
        with open(path, "w") as f:
            f.write(text)


def main(argv):
    if len(argv) == 3 and argv[1] == "--types":
        write_header(argv[2], render_types())
        return 0
    return run_generator(argv, __doc__, "gen_aircraft_config", generate,
                         (ConfigError, check_config.ConfigError), write_header)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
