"""Verdicts of a HiL flight from the simulator's truth: the safety regions S_x and S_u built from
limits.yaml by the same generator the HA's configuration comes from
(tools/stack_tools/gen_aircraft_config.py), and the flight's summary.json."""
import bisect
import math

from drone_ros.msg import DecisionStatus
from report_core.switches import stretches
from stack_common import geo
from stack_common.units import FT_PER_M
from stack_tools import gen_aircraft_config

from hil.flight_record import HaPeriod

# Who drives the servos: msg/DecisionStatus.msg's CONTROLLER_* (the HA core's header is generated
# from the same lines), by value and by name.
CONTROLLERS = {getattr(DecisionStatus, n): n[len("CONTROLLER_"):] for n in dir(DecisionStatus)
               if n.startswith("CONTROLLER_")}
HP, HA_LATCHED = DecisionStatus.CONTROLLER_HP, DecisionStatus.CONTROLLER_HA_LATCHED
# The HA safety controller drives the servos (incl. recovering, latched).
HA_SIDE = (DecisionStatus.CONTROLLER_HA, DecisionStatus.CONTROLLER_RECOVERING, HA_LATCHED)
# A float32 surface value may sit a rounding step past a limit given in decimal.
EPS = 1e-5


class Regions:
    def __init__(self, limits_doc):
        c = gen_aircraft_config.build(limits_doc)
        self.c = c
        self.sx, self.x0 = c["sx"], c["x0"]
        self.su, self.u0 = c["su"], c["u0"]
        self.period_s = 1.0 / float(limits_doc["decision"]["rate_hz"])
        self.stable_window_s = float(limits_doc["decision"]["stable_window_s"])
        self.late_periods_tolerated = int(limits_doc["decision"]["late_periods_tolerated"])
        self.stall_ftps = c["stall_speed_ftps"]
        self.ceiling_ft = c["ceiling_agl_ft"]
        self.airborne_ft = c["airborne_agl_ft"]
        # A flight's verdicts ask each period's rows two or three times (every check that reads
        # them): the summary's largest cost, a tenth of a flight's CPU. Bounded: a Regions may
        # judge many flights.
        self._rows = {}

    @staticmethod
    def _max_row(rows, v, v0):
        # The differences once, not once a row: each row's sum has the same terms in the same
        # order as sum(a * (x - x0)), so the same value to the bit.
        d = [x - x0 for x, x0 in zip(v, v0)]
        return max(sum([a * e for a, e in zip(r, d)]) for r in rows)

    def _max_row_of(self, key, rows, v, v0):
        row = self._rows.get(key)
        if row is None:
            if len(self._rows) >= 100000:
                self._rows.clear()
            row = self._rows[key] = self._max_row(rows, v, v0)
        return row

    def su_max(self, u):
        """max_i (S_u (u - u0))_i for u = (elevator, aileron, rudder, throttle)."""
        u = tuple(u)
        return self._max_row_of(("u",) + u, self.su, u, self.u0)

    def sx_max(self, m):
        x = (m.alpha_deg, m.beta_deg, m.roll_deg, m.pitch_deg, m.p_deg_s, m.q_deg_s, m.r_deg_s,
             m.height_above_home_ft)
        return self._max_row_of(x, self.sx, x, self.x0)


def reason_names(mask):
    """REASON_* names of msg/DecisionStatus.msg set in mask."""
    return [n[len("REASON_"):] for n in dir(DecisionStatus)
            if n.startswith("REASON_") and getattr(DecisionStatus, n) & mask]


def segments(records):
    """Who flew when: one entry per stretch of one controller (report_core.switches.stretches),
    with the HA's reasons at its first period."""
    out = []
    for run in stretches([p.reply.controller for p in records]):
        first = records[run.first]
        reply = first.reply
        name = CONTROLLERS.get(reply.controller, str(reply.controller))
        end = records[run.end] if run.end < len(records) else records[-1]
        out.append({"from_s": round(first.t_s, 3), "to_s": round(end.t_s, 3), "controller": name,
                    "reasons_at_switch": reply.reasons_at_switch,
                    "why": reason_names(reply.reasons_at_switch if reply.controller != HP else 0),
                    "reasons": reply.reasons,
                    "stable_for_s_at_switch": round(reply.stable_for_s, 3)})
    return out


def waypoint_progress(plan, home, records, reach_ft):
    """Closest approach of the true track to each waypoint, and which were reached."""
    wps = [geo.north_east_ft(home, it.lat_deg, it.lon_deg) for it in plan.items]
    best = [float("inf")] * len(wps)
    first = [None] * len(wps)
    for p in records:
        m = p.truth
        if m.on_ground:
            continue
        for i, (n, e) in enumerate(wps):
            d = math.hypot(m.north_ft - n, m.east_ft - e)
            if d < best[i]:
                best[i] = d
            if d <= reach_ft and first[i] is None:
                first[i] = round(p.t_s, 2)
    return [{"waypoint": i + 1, "closest_ft": round(b, 1), "first_reached_s": f}
            for i, (b, f) in enumerate(zip(best, first))]


def nearest_rank(values, q):
    """The q-quantile as a value that occurred (nearest rank)."""
    if not values:
        return None
    v = sorted(values)
    return v[max(0, min(len(v) - 1, int(math.ceil(q * len(v))) - 1))]


def segment_distance_ft(p, a, b):
    """Distance from point p to the segment a-b (north, east in ft)."""
    dn, de = b[0] - a[0], b[1] - a[1]
    L2 = dn * dn + de * de
    u = 0.0 if L2 == 0.0 else max(0.0, min(1.0, ((p[0] - a[0]) * dn + (p[1] - a[1]) * de) / L2))
    return math.hypot(p[0] - (a[0] + u * dn), p[1] - (a[1] + u * de))


def mission_tracking(plan, home, records, progress):
    """Cross-track error: the true track's distance from the mission's path (its legs, waypoint
    to waypoint) over the stretches the HP flew whole, from reaching one waypoint to reaching the
    next with the HP on the servos throughout (a takeover and the HP's return to the track are
    not tracking). The distance is to the nearest of the stretch's leg and its neighbours: the
    guidance turns for the next waypoint once within its reach distance of this one, so it cuts
    each corner on the path, not across it."""
    wps = [geo.north_east_ft(home, it.lat_deg, it.lon_deg) for it in plan.items]
    errors, legs = [], 0
    for i in range(len(wps) - 1):
        t0, t1 = progress[i]["first_reached_s"], progress[i + 1]["first_reached_s"]
        if t0 is None or t1 is None or t1 <= t0:
            continue
        leg = [x for x in records if t0 - 1e-9 <= x.t_s <= t1 + 1e-9]
        if not leg or any(x.reply.controller != HP for x in leg):
            continue
        legs += 1
        near = [(wps[j], wps[j + 1]) for j in range(max(0, i - 1), min(len(wps) - 1, i + 2))]
        errors += [min(segment_distance_ft((x.truth.north_ft, x.truth.east_ft), a, b) for a, b in near) for x in leg]
    return {"legs_flown_by_hp": legs, "legs": len(wps) - 1, "samples": len(errors),
            "max_cross_track_ft": round(max(errors), 2) if errors else None,
            "p95_cross_track_ft": None if not errors else round(nearest_rank(errors, 0.95), 2)}


def ground_station_view(rec, window_s=3.0):
    """The ground station's positions (GLOBAL_POSITION_INT as microhard_gs sent it) held against
    the truth: each one's nearest true position, horizontal and height together, of the
    `window_s` of simulated time before it arrived (the telemetry lags by its own period, in wall
    time), its distance to it and its height above home against that sample's. A position whose
    nearest sample is parked was measured on the ground, however late it came (on a loaded
    machine one sent just before the airborne start arrived after it): it is not one in flight.
    And the ground station's home against the simulator's."""
    if rec.gs_positions is None:
        return None
    recs = rec.periods
    times = [x.t_s for x in recs]
    horiz, vert = [], []
    for pos in rec.gs_positions:
        lo = bisect.bisect_left(times, pos.t_s - window_s)
        hi = bisect.bisect_right(times, pos.t_s + 1e-9)
        if hi - lo < 1:
            continue
        n, e = geo.north_east_ft(rec.home, pos.lat_deg, pos.lon_deg)
        h = pos.relative_alt_m * FT_PER_M
        best = min(recs[lo:hi], key=lambda x: math.hypot(math.hypot(x.truth.north_ft - n, x.truth.east_ft - e),
                                                         x.truth.height_above_home_ft - h))
        if best.truth.on_ground:
            continue
        horiz.append(math.hypot(best.truth.north_ft - n, best.truth.east_ft - e))
        vert.append(abs(best.truth.height_above_home_ft - h))
    home = None
    if rec.gs_home is not None:
        n, e = geo.north_east_ft(rec.home, rec.gs_home.lat_deg, rec.gs_home.lon_deg)
        home = {"horizontal_ft": round(math.hypot(n, e), 3),
                "vertical_ft": round(abs(rec.gs_home.alt_m - rec.home[2]) * FT_PER_M, 3)}
    return {"positions_received": len(rec.gs_positions), "positions_in_flight": len(horiz),
            "window_s": window_s,
            "max_horizontal_error_ft": round(max(horiz), 2) if horiz else None,
            "p95_horizontal_error_ft": None if not horiz else round(nearest_rank(horiz, 0.95), 2),
            "max_height_error_ft": round(max(vert), 2) if vert else None,
            "home_vs_truth": home}


def stall_alphas_deg(af):
    """The airframe's stall angles of attack (airframe.yaml through the FDM's hil.fdm airframe:
    lift reaches cl_max, or cl_min inverted), degrees."""
    return math.degrees(af.alpha_stall_rad), math.degrees(af.alpha_stall_neg_rad)


def stalled(m, alphas):
    """The wing is stalled in this truth sample: its true angle of attack past a stall angle."""
    return not m.on_ground and (m.alpha_deg > alphas[0] or m.alpha_deg < alphas[1])


def launch_stall_periods(recs, alphas):
    """How many periods from the airborne start the wing was already stalled: the simulator
    launches the aircraft at ground_s in whatever the turbulence field holds there, and a gust
    there (HiL campaign: alpha 11.9 deg in the first period, moderate turbulence) is the launch's,
    nobody's doing; it ends with the first period the wing flies."""
    n = 0
    for x in recs:
        if not stalled(x.truth, alphas):
            break
        n += 1
    return n


def longest_stall_s(recs, alphas, period_s):
    """The longest unbroken stretch of periods with the wing stalled while the HA's side flew: a
    gust that spikes alpha for a period or two against a stall flown into and held."""
    best = run = 0
    for x in recs:
        run = run + 1 if x.reply.controller in HA_SIDE and stalled(x.truth, alphas) else 0
        best = max(best, run)
    return best * period_s


def recovery_height_losses(recs, since_s, rebound_ft=2.0):
    """Per takeover (the HP, then the HA's side on the servos, airborne) from since_s on: the height
    lost from the takeover to the recovery, the lowest point before the aircraft climbs again by
    rebound_ft (or the HP has the servos back, or the flight ends: then it never recovered).
    [(takeover time, height lost in ft, recovered)]."""
    out = []
    i, n = 0, len(recs)
    while i < n:
        x = recs[i]
        prev = recs[i - 1].reply.controller if i else None
        if x.t_s < since_s - 1e-9 or prev != HP or x.reply.controller not in HA_SIDE or x.truth.on_ground:
            i += 1
            continue
        h0 = low = x.truth.height_above_home_ft
        recovered = False
        j = i
        while j < n and recs[j].reply.controller in HA_SIDE:
            h = recs[j].truth.height_above_home_ft
            low = min(low, h)
            if h >= low + rebound_ft:
                recovered = True
                break
            j += 1
        # Not sinking at the takeover, or handed back before it sank rebound_ft: recovered at once.
        recovered = recovered or (j < n and recs[j].reply.controller == HP)
        out.append((x.t_s, h0 - low, recovered))
        i = max(j, i + 1)
    return out


def ha_periods(sim):
    """Every period the HA ran, as (t_s, commands its link had delivered, controller, reasons at
    its last switch) on the simulator's time axis. Lockstep: the records, one per step. Real
    time: the HA's own ticks from its replies (sim.ha_periods on time.monotonic(), less
    sim.pace0_mono, the monotonic time of simulated 0), not the simulator's steps, which see a
    tick up to a step later."""
    rt = getattr(sim, "ha_periods", None)
    if rt is None:
        return [HaPeriod(x.t_s, x.reply.commands_received, x.reply.controller, x.reply.reasons_at_switch)
                for x in sim.records]
    if sim.pace0_mono is None:  # stopped before its first step
        return []
    return [HaPeriod(t - sim.pace0_mono, *rest) for t, *rest in rt]


def command_deadline(periods, silent_from_s, late_periods_tolerated):
    """The deadline miss of an HP silent from silent_from_s on, by the HA's rule: a period is late
    when no new command arrived in it (its link's count did not move); the command is missed at
    the end of the (late_periods_tolerated + 1)-th late period in a row, and the takeover is due
    then. The first such period at or after silent_from_s; (first late period's end, deadline
    miss) in the periods' time, or None if the flight ended before. In lockstep a crash at step
    K gives (K, K + tolerated periods); in real time the HP's timer, the kill and the HA's ticks
    are at any phase to each other, so it lies up to two periods later (hil/README.md)."""
    late = 0
    prev = None
    for i, p in enumerate(periods):
        n = p.commands_received
        late = late + 1 if prev is not None and n == prev else 0
        prev = n
        if late > late_periods_tolerated and p.t_s >= silent_from_s - 1e-9:
            return periods[i - late_periods_tolerated].t_s, p.t_s
    return None


def first_takeover_s(periods, from_s):
    """The first period at or after from_s in which the HP did not have the servos."""
    return next((p.t_s for p in periods if p.t_s >= from_s - 1e-9 and p.controller != HP), None)


def crash_takeover(periods, crash_s, regions):
    """The takeover after an HP crash at crash_s, judged on the HA's periods: the deadline miss
    by the HA's rule (command_deadline), the first period the HP no longer had the servos, and
    whether that was within one HA period of the deadline miss."""
    period_s, tolerated = regions.period_s, regions.late_periods_tolerated
    miss = command_deadline(periods, crash_s, tolerated)
    # The flight ended before the deadline: lockstep's rule (the crash's period is the first late).
    first_miss_s, deadline_miss_s = miss or (crash_s, crash_s + tolerated * period_s)
    t_ha = first_takeover_s(periods, crash_s)
    before = next((p.controller for p in reversed(periods) if p.t_s < crash_s - 1e-9), None)
    return {
        "crash_injected_s": round(crash_s, 3),
        # Who had the servos in the HA's last period before the kill, on the HA's own ticks: in real
        # time a simulator step runs after the HA ticks it shows, so who_flew's periods put the
        # takeover up to two periods before the HA made it (the step of 8.00 s showing the
        # takeover of 8.017 s, measured).
        "controller_before_crash": None if before is None else CONTROLLERS.get(before, str(before)),
        "first_missed_period_s": round(first_miss_s, 3),
        "deadline_miss_s": round(deadline_miss_s, 3),
        "takeover_s": None if t_ha is None else round(t_ha, 3),
        "latency_after_crash_s": None if t_ha is None else round(t_ha - crash_s, 3) + 0.0,
        "latency_after_deadline_miss_s": None if t_ha is None else round(t_ha - deadline_miss_s, 3) + 0.0,
        "within_one_period_of_deadline_miss": t_ha is not None and t_ha - deadline_miss_s <= period_s + 1e-9,
        "reasons_at_switch": next((p.reasons_at_switch for p in periods if p.t_s == t_ha), None),
    }


def unsafe(regions, applied):
    """A servo output outside S_u, or not a number at all."""
    return not all(math.isfinite(v) for v in applied) or regions.su_max(applied) > 1.0 + EPS


def outside_s_x(r, recs, at):
    """Periods outside S_x: (under the HA's safety controller, of those inherited from an
    excursion that began while the HP flew, whoever flew from the fault at `at` on), and the
    HA's worst S_x row with its record (None, None: the HA never flew)."""
    outside_ha = inherited = outside_any = 0
    excursion_from_hp = False
    prev_out = False
    max_row = worst = None
    for x in recs:
        row = r.sx_max(x.truth)
        out = row > 1.0
        if out and (at is None or x.t_s >= at - 1e-9):
            outside_any += 1
        if out and not prev_out:
            excursion_from_hp = x.reply.controller == HP
        if x.reply.controller in HA_SIDE:
            if max_row is None or row > max_row:
                max_row, worst = row, x
            if out:
                outside_ha += 1
                inherited += 1 if excursion_from_hp else 0
        prev_out = out
    return outside_ha, inherited, outside_any, max_row, worst


def truth_takeover_due_s(r, recs, at):
    """When the truth itself made a takeover due after the fault at `at`: the first airborne
    period the HP flew outside S_x, above the ceiling, or at or below the stall speed (None)."""
    if at is None:
        return None
    for x in recs:
        t = x.t_s
        m = x.truth
        if t < at - 1e-9 or x.reply.controller != HP or m.on_ground:
            continue
        airborne = m.height_above_home_ft > r.airborne_ft
        if r.sx_max(m) > 1.0 or m.height_above_home_ft > r.ceiling_ft or (airborne and x.airspeed_cal_ftps <= r.stall_ftps):
            return t
    return None


def fault_verdict(rec, progress):
    """The Simplex property for this flight, from the simulator's truth: what the servos were
    driven with (S_u), where the aircraft was while the HA flew (S_x), and when the HA took the
    servos against when it had to (the fault class's own deadline, or the truth leaving S_x,
    passing the ceiling or falling to the stall while the HP flew)."""
    r = rec.regions
    recs = [x for x in rec.periods if x.t_s > rec.ground_s]
    period = r.period_s
    f = rec.fault
    at = f.at_s if f is not None else None
    unsafe_n = sum(1 for x in rec.periods if unsafe(r, x.reply.applied))
    outside_ha, inherited, outside_any, max_row, worst = outside_s_x(r, recs, at)
    due = f.takeover_due_s() if f is not None else None
    truth_due = truth_takeover_due_s(r, recs, at)
    dues = [d for d in (due, truth_due) if d is not None]
    due_s = min(dues) if dues else None
    took = lat = None
    if due_s is not None:
        took = first_takeover_s(rec.ha_periods, due_s)
        lat = None if took is None else round(took - due_s, 4) + 0.0
    off = back = None
    if at is not None:
        off = next((x.t_s for x in recs if x.t_s >= at - 1e-9 and x.reply.controller != HP), None)
        if off is not None:
            back = next((x.t_s for x in recs if x.t_s > off and x.reply.controller == HP), None)
    airborne = [x for x in recs if not x.truth.on_ground]
    crashed = any("aircraft crashed" in e["event"] for e in rec.events)
    env_s = round(outside_ha * period, 4)
    takeover_ok = due_s is None or (lat is not None and lat <= period + 1e-9)
    # The stall judged on the truth: the wing past its stall angle of attack while the HA's side
    # flies is the HA's own failure (it flies to keep the aircraft flying), whoever stalled it.
    alphas = rec.stall_alphas_deg
    launch = launch_stall_periods(recs, alphas)
    flown = recs[launch:]
    stalled_ha = sum(1 for x in flown if x.reply.controller in HA_SIDE and stalled(x.truth, alphas))
    stalled_any = sum(1 for x in recs if (at is None or x.t_s >= at - 1e-9) and stalled(x.truth, alphas))
    losses = recovery_height_losses(recs, at if at is not None else rec.ground_s)
    return {
        "ok": unsafe_n == 0 and outside_ha == 0 and takeover_ok and not crashed and stalled_ha == 0,
        "stall_alpha_deg": round(alphas[0], 3),
        "stalled_under_ha_s": round(stalled_ha * period, 4),
        "longest_stall_under_ha_s": round(longest_stall_s(flown, alphas, period), 4),
        "stalled_at_launch_s": round(launch * period, 4),
        "stalled_from_fault_s": round(stalled_any * period, 4),
        "recovery_height_loss_ft": round(max(v for _, v, _ in losses), 2) if losses else None,
        "recoveries": [{"takeover_s": round(t, 3), "height_lost_ft": round(v, 2), "recovered": ok}
                       for t, v, ok in losses],
        "unsafe_commands": unsafe_n,
        "envelope_violations_under_ha_s": env_s,
        "envelope_under_ha": {"outside_S_x_s": env_s, "inherited_from_hp_s": round(inherited * period, 4),
                              "left_under_ha_s": round((outside_ha - inherited) * period, 4),
                              "max_S_x_row": None if max_row is None else round(max_row, 4),
                              "worst": None if max_row is None else worst_state(worst)},
        # Whoever flew, from the fault on: the HA switches on an inset of S_x so that this can
        # be 0 too, not only the time under the HA.
        "outside_S_x_from_fault_s": round(outside_any * period, 4),
        "takeover_due_s": None if due_s is None else round(due_s, 4),
        "takeover_due_by": None if due_s is None else ("fault" if due is not None and due_s == due else "truth"),
        "takeover_s": None if took is None else round(took, 4),
        "takeover_latency_s": lat,
        "takeover_within_one_period": takeover_ok,
        "hp_lost_control_s": None if off is None else round(off, 4),
        "recovery_s": None if back is None else round(back - at, 4),
        "latched": any(x.reply.controller == HA_LATCHED for x in recs),
        "aircraft_crashed": crashed,
        "min_height_agl_ft": round(min(x.truth.height_above_home_ft for x in airborne), 2) if airborne else None,
        "min_airspeed_margin_ftps": round(min(x.airspeed_cal_ftps for x in airborne) - r.stall_ftps, 2) if airborne else None,
        "mission_progress": round(sum(1 for p in progress if p["first_reached_s"] is not None) / float(len(progress)), 4)
        if progress else 0.0,
    }


def worst_state(x):
    """Where the state was at the step of the largest S_x row under the HA."""
    m = x.truth
    return {"t_s": round(x.t_s, 3), "controller": CONTROLLERS.get(x.reply.controller),
            "alpha_deg": round(m.alpha_deg, 2), "beta_deg": round(m.beta_deg, 2), "roll_deg": round(m.roll_deg, 2),
            "pitch_deg": round(m.pitch_deg, 2), "p_deg_s": round(m.p_deg_s, 1), "q_deg_s": round(m.q_deg_s, 1),
            "r_deg_s": round(m.r_deg_s, 1), "height_ft": round(m.height_above_home_ft, 1),
            "calibrated_airspeed_ftps": round(x.airspeed_cal_ftps, 2)}


def world(rec):
    """The air the flight flew in: the field's elevation and temperature, the density at the
    start (and what it makes of the pitot: IAS = TAS sqrt(rho / rho0)), the scenario's wind and,
    when a fault changed it, the wind at the end."""
    air = rec.world
    rho = air.start_density_kg_m3
    w, w_end = air.wind, air.wind_at_end

    def wind(x):
        return {"from_deg": x.mean_from_deg, "mps": x.mean_mps, "ftps": round(x.mean_mps * FT_PER_M, 2),
                "turbulence": x.turbulence}
    return {"field_elevation_ft": round(air.field_elevation_ft, 1), "temperature_c": round(air.temperature_c, 2),
            "air_density_kg_m3": None if rho is None else round(rho, 5),
            "ias_over_tas": None if rho is None else round(math.sqrt(rho / 1.225), 4),
            "wind": wind(w), "wind_at_end": wind(w_end), "beyond_design_wind": beyond_design_wind(rec)}


def beyond_design_wind(rec):
    """Why the flight's air went beyond the aircraft's design wind (hil/design_wind.py): its
    steady wind and turbulence, and a fault's change of the wind ([]: within; the property is
    claimed there, and beyond it the flight is judged on survival)."""
    design = rec.world.design_wind
    if design is None:
        return []
    w = rec.world.wind
    why = design.steady(w.mean_mps, w.turbulence)
    change = getattr(rec.fault, "beyond_design_wind", None)
    return why + [x for x in (change() if callable(change) else []) if x not in why]


def fault_record(rec):
    f = rec.fault
    if f is None:
        return {"class": "none", "at_s": None, "duration_s": None, "params": {}, "took_effect": True,
                "evidence": "no fault injected"}
    took, evidence = f.effect()
    detail = getattr(f, "detail", None)  # a class's own figures for its story test, if it has any
    return {"class": f.name, "at_s": f.at_s, "duration_s": f.duration_s, "params": f.params,
            "took_effect": bool(took), "evidence": evidence, "notes": f.notes,
            "detail": detail() if callable(detail) else None}


def summarize(rec):
    """summary.json of a flight (hil.flight_record.FlightRecord)."""
    r = rec.regions
    recs = rec.periods
    airborne = [x for x in recs if not x.truth.on_ground and x.truth.height_above_home_ft > r.airborne_ft]
    unsafe_servo = [x for x in recs if unsafe(r, x.reply.applied)]
    ha_flying = [x for x in recs if x.reply.controller in HA_SIDE and x.t_s > rec.ground_s]
    sx_ha = max((r.sx_max(x.truth) for x in ha_flying), default=None)
    segs = segments(recs)
    crash = rec.crashed_at
    takeover = None
    if crash is not None:
        takeover = crash_takeover(rec.ha_periods, crash, r)
        t_ha = takeover["takeover_s"]
        t_back = None if t_ha is None else next(
            (x.t_s for x in recs if x.t_s > t_ha and x.reply.controller == HP), None)
        takeover["hand_back_s"] = None if t_back is None else round(t_back, 3)
    handbacks = []
    prev = None
    for p in recs:
        reply = p.reply
        if prev is not None and prev != HP and reply.controller == HP:
            handbacks.append({"t_s": round(p.t_s, 3), "stable_for_s": round(reply.stable_for_s, 3),
                              "after_stable_window": reply.stable_for_s + 1e-6 >= r.stable_window_s,
                              "calibrated_airspeed_ftps": round(p.airspeed_cal_ftps, 2)})
        prev = reply.controller
    heights = [x.truth.height_above_home_ft for x in airborne]
    cal = [x.airspeed_cal_ftps for x in airborne]
    reach_ft = rec.reach_ft  # the controller's own "waypoint reached" distance (dist2b)
    progress = waypoint_progress(rec.plan, rec.home, recs, reach_ft)
    fault = fault_record(rec)
    verdict = fault_verdict(rec, progress)
    flown = len(recs) * rec.period_us * 1e-6
    t = rec.step_totals
    steps = max(len(recs), 1)
    return {
        "aircraft": rec.aircraft,
        "seed": rec.seed,
        "mode": rec.mode,
        "rate_hz": rec.rate_hz,
        "controller_rate_hz": round(1.0 / rec.controller_dt_s, 3),
        "simulated_s": round(flown, 3),
        "wall_s": round(rec.wall_s, 3),
        "x_real_time": round(flown / rec.wall_s, 2) if rec.wall_s > 0 else None,
        # The simulator's own work, which the wall time of a step hides on a loaded machine.
        "sim_cpu_ms_per_step": round(rec.cpu_s * 1000.0 / steps, 4),
        "step_time_ms": {k: round(v * 1000.0 / steps, 4) for k, v in sorted(t.items())
                         if k != "mission_upload_and_trim"},
        "mission_upload_and_trim_s": round(t.get("mission_upload_and_trim", 0.0), 3),
        "sensor_to_servo_latency": rec.latency,
        "takeover": takeover,
        "hand_backs": handbacks,
        "who_flew": segs,
        "margins": {
            "min_height_above_home_ft": round(min(heights), 2) if heights else None,
            "ceiling_ft": r.ceiling_ft,
            "min_ceiling_margin_ft": round(r.ceiling_ft - max(heights), 2) if heights else None,
            "stall_speed_ftps": r.stall_ftps,
            "min_calibrated_airspeed_ftps": round(min(cal), 2) if cal else None,
            "min_stall_margin_ftps": round(min(cal) - r.stall_ftps, 2) if cal else None,
        },
        "unsafe_servo_commands": {"steps": len(recs), "outside_S_u": len(unsafe_servo),
                                  "max_S_u_row": round(max(r.su_max(x.reply.applied) for x in recs), 5) if recs else None},
        "state_while_ha_flies": {"steps": len(ha_flying),
                                 "max_S_x_row": None if sx_ha is None else round(sx_ha, 4),
                                 "inside_S_x": sx_ha is None or sx_ha <= 1.0},
        "mission": {"waypoints": len(rec.plan.items),
                    "reached_within_ft": reach_ft,
                    "reached": sum(1 for p in progress if p["first_reached_s"] is not None),
                    "per_waypoint": progress,
                    "tracking": mission_tracking(rec.plan, rec.home, recs, progress),
                    "guidance_waypoint_index": rec.waypoint_log},
        "ground_station": ground_station_view(rec),
        "world": world(rec),
        "events": rec.events,
        "fault": fault,
        "verdict": verdict,
        "status": "ok" if fault["took_effect"] else "fault_not_effective",
    }
