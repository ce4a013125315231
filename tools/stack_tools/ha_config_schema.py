"""The HA core's configuration type, HaAircraftConfig, in one table: the generator writes the C
header from it (arduino_ha/src/generated/ha_config.h, checked in because arduino-cli cannot run
the generator; test_generated_config keeps it identical) and refuses an initializer whose values
are not exactly its fields. So a limit has one name in one place: a field here with no value
would otherwise compile as a silent 0 in the core.

usage: python3 tools/gen_aircraft_config.py --types OUT_H
"""
import textwrap

# Order of the state and actuator vectors of S_x and S_u: HA_X_* and HA_U_* are written from it.
X_NAMES = ["alpha_deg", "beta_deg", "roll_deg", "pitch_deg", "p_deg_s", "q_deg_s", "r_deg_s",
           "alt_agl_ft"]
U_NAMES = ["elevator_deg", "aileron_deg", "rudder_deg", "throttle"]
SX_MAX_ROWS = 20
SU_MAX_ROWS = 10
# Nonzero coefficients a region may hold (a box has one a row; the thesis's polytope more).
SX_MAX_TERMS = 64
SU_MAX_TERMS = 24
MAX_RESTARTS_CAP = 16  # the restart history is a fixed array
SELF_TEST_STEPS = 12  # the pre-flight self-test's sequence: 3 surfaces x 3, the throttle x 3

# (C type, field, what it is); ("", "", text) says what the fields after it are. Times are integer microseconds (the generator converts), so the core never
# converts a float to an integer time.
FIELDS = [
    ('const char *', 'aircraft', ''),

    ('', '',
     'Safety regions: row i holds when sum_j S[i][j] * (v[j] - v0[j]) <= 1, S by rows of '
     "nonzero terms: row i's are sx[sx_row_end[i - 1] .. sx_row_end[i] - 1] (from sx[0] for "
     'row 0).'),
    ('uint32_t', 'sx_rows', ''),
    ('uint8_t', 'sx_row_end[HA_SX_MAX_ROWS]', ''),
    ('HaRegionTerm', 'sx[HA_SX_MAX_TERMS]', ''),
    ('float', 'x0[HA_X_DIM]', ''),
    ('uint32_t', 'su_rows', ''),
    ('uint8_t', 'su_row_end[HA_SU_MAX_ROWS]', ''),
    ('HaRegionTerm', 'su[HA_SU_MAX_TERMS]', ''),
    ('float', 'u0[HA_U_DIM]', ''),
    ('float', 'inner_region_fraction', 'switch back only while max(S_x (x - x0)) <= this'),
    ('', '',
     '... and, airborne, only above this airspeed (stall x handback_stall_multiple, derived by '
     'the generator): airspeed hovering at stall cannot cycle the HP and the HA.'),
    ('float', 'handback_airspeed_ftps', ''),
    ('', '',
     'Switching happens on an inset, not on the edges (derived by the generator): above '
     'max(S_x (x - x0)) = switch_region_fraction, above ceiling_switch_agl_ft, and, airborne, '
     "at or below stall_switch_airspeed_ftps. The HA's sensors err and lag and its controller "
     'needs room to turn the aircraft round inside S_x.'),
    ('float', 'switch_region_fraction', ''),
    ('float', 'ceiling_switch_agl_ft', ''),
    ('float', 'stall_switch_airspeed_ftps', ''),

    ('', '', 'Actuators (the box S_u is built from; the final saturation uses it directly).'),
    ('float', 'elevator_limit_deg', ''),
    ('float', 'aileron_limit_deg', ''),
    ('float', 'rudder_limit_deg', ''),
    ('float', 'throttle_min', ''),
    ('float', 'throttle_max', ''),
    ('float', 'surface_rate_limit_deg_per_s', ''),
    ('float', 'surface_release_rate_deg_per_s', 'a pull eased towards neutral (ha_surfaces.c)'),
    ('', '',
     'Airborne, an HP elevator more nose-up than this (trailing edge up, elevator_deg below '
     'its negative) trims the wing far past its stall: unsafe output (ha_checks.c).'),
    ('float', 'elevator_pull_limit_deg', ''),
    ('float', 'throttle_rate_limit_per_s', ''),

    ('', '', 'State checks.'),
    ('float', 'alpha_limit_deg', "the HP's estimate past this: a diverged estimator"),
    ('float', 'stall_alpha_deg',
     "the wing's stall angle of attack (airframe.yaml): the HA's own sign"),
    ('float', 'beta_limit_deg', ''),
    ('float', 'stall_speed_ftps', ''),
    ('float', 'ceiling_agl_ft', ''),
    ('float', 'airborne_agl_ft', 'one signal of flight among several (ha_core.c: airborne latch)'),
    ('uint32_t', 'landed_confirm_us', 'a landing evident this long clears the airborne latch'),
    ('float', 'max_airspeed_ftps', 'a reading above this is a broken sensor, not a fast aircraft'),
    ('', '', "A reading more than this below the INS's groundspeed is a lying pitot, not a stall."),
    ('float', 'max_wind_ftps', ''),
    ('uint32_t', 'state_timeout_us', 'attitude/position older than this is not trusted'),
    ('', '',
     'A failed pitot read holds the last good one this long: a glitch is not a dead sensor.'),
    ('uint32_t', 'airspeed_timeout_us', ''),

    ('', '', 'Decision logic.'),
    ('uint32_t', 'period_us', ''),
    ('uint32_t', 'late_periods_tolerated', ''),
    ('uint32_t', 'no_command_timeout_us', ''),
    ('uint32_t', 'stable_window_us', ''),
    ('uint32_t', 'max_restarts', ''),
    ('uint32_t', 'restart_window_us', ''),
    ('uint32_t', 'hp_reset_pulse_us', ''),
    ('', '',
     "From releasing the reset line to the HP's first valid command; past it the HP is reset "
     'again (counting towards max_restarts), and at the cap the HA latches.'),
    ('uint32_t', 'hp_boot_timeout_us', ''),

    ('', '',
     'RC receiver and servo pulse calibration: [min, max] maps linearly onto [-limit, +limit] '
     '(throttle onto [throttle_min, throttle_max]).'),
    ('uint32_t', 'rc_pulse_min_us', ''),
    ('uint32_t', 'rc_pulse_max_us', ''),
    ('uint32_t', 'pic_threshold_us', 'PIC channel pulse >= this: pilot in command'),
    ('uint32_t', 'servo_pulse_min_us', ''),
    ('uint32_t', 'servo_pulse_max_us', ''),
    ('', '',
     "The same mapping's slopes per microsecond above rc_pulse_min_us, derived by the "
     'generator: a division per channel costs ~150 soft-float instructions on the Due.'),
    ('float', 'rc_elevator_deg_per_us', ''),
    ('float', 'rc_aileron_deg_per_us', ''),
    ('float', 'rc_rudder_deg_per_us', ''),
    ('float', 'rc_throttle_per_us', ''),

    ('', '', 'Safety controller (cascaded PID).'),
    ('float', 'sc_bank_limit_deg', ''),
    ('float', 'sc_circle_radius_ft', ''),
    ('float', 'sc_circle_direction',
     '+1 clockwise seen from above (right turns), -1 counter-clockwise'),
    ('', '',
     'Bank of a steady turn of sc_circle_radius_ft at the target airspeed, derived by the '
     'generator: an atanf per period costs ~1,500 soft-float instructions on the Due.'),
    ('float', 'sc_circle_bank_ff_deg', ''),
    ('float', 'sc_radial_gain_deg_per_ft', ''),
    ('float', 'sc_radial_correction_max_deg', ''),
    ('float', 'sc_heading_to_bank_gain', ''),
    ('float', 'sc_roll_kp', 'aileron deg per deg'),
    ('float', 'sc_roll_ki', 'aileron deg per deg*s'),
    ('float', 'sc_roll_kd', 'aileron deg per deg/s'),
    ('float', 'sc_pitch_kp', ''),
    ('float', 'sc_pitch_ki', ''),
    ('float', 'sc_pitch_kd', ''),
    ('float', 'sc_yaw_damper_gain', 'rudder deg per deg/s of R'),
    ('float', 'sc_alt_min_ft', ''),
    ('float', 'sc_alt_max_ft', ''),
    ('float', 'sc_alt_to_pitch_gain_deg_per_ft', ''),
    ('float', 'sc_pitch_cmd_limit_deg', ''),
    ('float', 'sc_pitch_error_max_deg', "the pitch loop's error is clamped to +/- this"),
    ('', '',
     "The HA's own elevator stop, nose-up degrees: it trims the wing below its stall "
     '(generator).'),
    ('float', 'sc_elevator_pull_max_deg', ''),
    ('', '',
     'Pitch and power without a speed: the nose no higher than this, the throttle trim plus '
     "this per ft below the band's middle (derived: full at the band's floor)."),
    ('float', 'sc_power_pitch_deg', ''),
    ('float', 'sc_power_throttle_per_ft', ''),
    ('', '',
     'Slow beats low: below stall_speed_ftps * sc_stall_margin the pitch loop lowers the nose '
     'at every altitude; above it the nose may rise sc_speed_to_pitch_gain per ft/s of excess.'),
    ('float', 'sc_stall_margin', ''),
    ('', '',
     "The pitch loop's lift guard: a load factor past lift_margin (IAS / V_stall)^2 (derived: "
     'the margin / V_stall^2) pushes the nose down sc_lift_push_deg_per_g per g.'),
    ('float', 'sc_lift_margin_per_ias_sq', ''),
    ('float', 'sc_lift_push_deg_per_g', ''),
    ('float', 'sc_speed_to_pitch_gain_deg_per_ftps', ''),
    ('float', 'sc_cruise_margin', "the throttle loop's target airspeed = stall_speed_ftps * this"),
    ('float', 'sc_throttle_trim', ''),
    ('float', 'sc_elevator_trim_deg', "airframe.yaml's level trim at sc_target_ftps (generator)"),
    ('float', 'sc_throttle_kp_per_ftps', ''),
    ('float', 'sc_throttle_ki_per_ft', ''),
    ('float', 'sc_integrator_authority',
     'integrator range as a fraction of the actuator half range'),
    ('', '',
     'Without its own attitude the HA cannot close a loop: the integrators (what is left of '
     "the HP's last surfaces) fade to zero, the trims, at this fraction of their authority per "
     'second, derived by the generator as 1 / blind_fade_s.'),
    ('float', 'sc_blind_fade_per_s', ''),

    ('', '', 'Pre-flight surface self-test.'),
    ('uint32_t', 'self_test_step_us', ''),
    ('float', 'self_test_throttle_max', ''),
    ('float', 'self_test_u[HA_SELF_TEST_STEPS][HA_U_DIM]',
     'The sequence, a step a row of targets in HA_U_* order (derived): each surface to + and - its '
     'limit and back, then the throttle to half and all of self_test_throttle_max and back.'),
    ('', '',
     'Parked, for the self-test: roll and pitch within, body rates within, ground speed below.'),
    ('float', 'self_test_max_tilt_deg', ''),
    ('float', 'self_test_max_rate_deg_s', ''),
    ('float', 'self_test_max_groundspeed_ftps', ''),

    ('', '',
     "Air data (ha_airdata.c): the HA's own airspeed picture. The stall check compares "
     'squares: IAS^2 cos(bank) against this, the stall switch speed squared (derived).'),
    ('float', 'stall_switch_airspeed_sq', ''),
    ('float', 'handback_airspeed_sq', 'handback_airspeed_ftps^2 (derived)'),
    ('', '',
     "Once the wind is known, the pitot's true airspeed may differ this much from the INS's "
     'velocity less the wind (gusts, sideslip, what the estimate is still off); before, by up '
     'to max_wind_ftps from the speed over the ground.'),
    ('float', 'airspeed_tolerance_ftps', ''),
    ('float', 'max_wind_sq', "max_wind_ftps^2 (derived): the wind estimate's bound"),
    ('', '',
     'The wind estimate follows at 1 / wind_time_constant_s: this fraction per period '
     '(derived).'),
    ('float', 'wind_per_period', ''),
    ('', '',
     'Learnt from a believed pitot this long the wind is known (derived: 3 x '
     'wind_time_constant_s, 5% of the first error left); the pitot doubted wind_forget_us (1 '
     'x), it is unknown again.'),
    ('uint32_t', 'wind_known_us', ''),
    ('uint32_t', 'wind_forget_us', ''),
    ('', '', 'The same nonzero pitot reading this long is a stuck sensor (ha_airdata.c).'),
    ('uint32_t', 'pitot_stuck_us', ''),
    ('', '',
     "The safety controller's circle in vectors (ha_safety_ctrl.c), derived: tan(correction) = "
     'this x (d^2 - R^2) (radial_gain_deg_per_ft in rad / 2R: the same near the circle), '
     'bounded by tan(radial_correction_max_deg); R^2.'),
    ('float', 'sc_radial_tan_per_ft2', ''),
    ('float', 'sc_radial_tan_max', ''),
    ('float', 'sc_circle_radius_sq_ft2', ''),
    ('', '',
     'Derived by the generator, once instead of every period (ha_safety_ctrl.c): the throttle '
     "loop's target (stall x cruise margin), the slowest speed the nose may rise at (stall x "
     "stall margin), the band's middle, the throttle's half range and middle, the trim and the "
     "power's room to full about them, the integrators' limits (authority x range) and fade "
     'per second.'),
    ('float', 'sc_target_ftps', ''),
    ('float', 'sc_speed_floor_ftps', ''),
    ('float', 'sc_alt_mid_ft', ''),
    ('float', 'sc_throttle_half', ''),
    ('float', 'sc_throttle_mid', ''),
    ('float', 'sc_throttle_trim_offset', ''),
    ('float', 'sc_power_throttle_max', ''),
    ('float', 'sc_aileron_integ_limit', ''),
    ('float', 'sc_elevator_integ_limit', ''),
    ('float', 'sc_throttle_integ_limit', ''),
    ('float', 'sc_blind_fade_auth_per_s', ''),
]

# Written from the limits' regions and the self-test's sequence, not scalars of their own.
TABLE_FIELDS = ("aircraft", "sx_rows", "sx_row_end", "sx", "x0", "su_rows", "su_row_end", "su",
                 "u0", "self_test_u")
C_TYPES = {"float": float, "uint32_t": int}


def scalar_fields():
    """{name: Python type} of the fields the generator fills from a value of its own."""
    return {name: C_TYPES[ctype] for row in FIELDS if row[0]
            for ctype, name in [row[:2]] if name.split("[")[0] not in TABLE_FIELDS}


def check_values(c):
    """Raises ValueError unless c's scalar values are exactly the struct's scalar fields, each of
    its C type."""
    want = scalar_fields()
    have = {k: type(v) for k, v in c.items() if k not in TABLE_FIELDS}
    missing = sorted(set(want) - set(have))
    extra = sorted(set(have) - set(want))
    wrong = sorted(k for k in set(want) & set(have) if want[k] is not have[k])
    if missing or extra or wrong:
        raise ValueError("the configuration's values and HaAircraftConfig's fields differ "
                         "(tools/stack_tools/ha_config_schema.py): no value for %s; no field for %s; "
                         "wrong type for %s" % (missing or "-", extra or "-", wrong or "-"))


def comment(text, indent, width=100):
    lines = textwrap.wrap(text, width - len(indent) - 3, break_on_hyphens=False)
    out = ["%s/* %s" % (indent, lines[0])] + ["%s * %s" % (indent, l) for l in lines[1:]]
    out[-1] += " */"
    return out


def render_types():
    out = ["/* Generated by tools/stack_tools/ha_config_schema.py (python3 tools/gen_aircraft_config.py",
           " * --types arduino_ha/src/generated/ha_config.h). Do not edit: change the table and",
           " * regenerate (a test fails until the checked-in copy matches). */",
           "#ifndef HA_CONFIG_H", "#define HA_CONFIG_H", "", "#include <stdint.h>", "",
           "#ifdef __cplusplus", 'extern "C" {', "#endif", ""]
    for prefix, names, what in (("HA_X_", X_NAMES, "State vector x of the safety region S_x "
                                 "(x - x0) <= 1, in this order."),
                                ("HA_U_", U_NAMES, "Actuator vector u of the actuator region S_u "
                                 "(u - u0) <= 1, in this order.")):
        out += comment(what, "") + ["enum {"]
        out += ["  %s%s = %d," % (prefix, n.upper(), i) for i, n in enumerate(names)]
        out += ["  %sDIM = %d" % (prefix, len(names)), "};", ""]
    out += ["#define HA_SX_MAX_ROWS %d" % SX_MAX_ROWS, "#define HA_SU_MAX_ROWS %d" % SU_MAX_ROWS,
            "#define HA_SX_MAX_TERMS %d" % SX_MAX_TERMS, "#define HA_SU_MAX_TERMS %d" % SU_MAX_TERMS,
            "#define HA_MAX_RESTARTS_CAP %d" % MAX_RESTARTS_CAP,
            "#define HA_SELF_TEST_STEPS %d" % SELF_TEST_STEPS, ""]
    out += comment("A nonzero coefficient of a region's row, S[row][col]: only these are stored, "
                   "so that no zero is multiplied or even looked at per period (on the Due the "
                   "scan of the dense 15 x 8 and 8 x 4 matrices cost some 1,300 instructions a "
                   "step).", "")
    out += ["typedef struct {", "  uint8_t col;", "  float coef;", "} HaRegionTerm;", "",
            "typedef struct {"]
    for row in FIELDS:
        if not row[0]:
            out += ([] if out[-1] == "typedef struct {" else [""]) + comment(row[2], "  ")
        else:
            sep = "" if row[0].endswith("*") else " "
            decl = "  %s%s%s;" % (row[0], sep, row[1])
            out += [decl + " /* %s */" % row[2]] if row[2] and len(decl) + len(row[2]) + 7 <= 100 \
                else (comment(row[2], "  ") if row[2] else []) + [decl]
    out += ["} HaAircraftConfig;", "", "#ifdef __cplusplus", "}", "#endif", "",
            "#endif /* HA_CONFIG_H */", ""]
    return "\n".join(out)
