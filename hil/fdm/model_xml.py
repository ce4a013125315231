"""Generates the JSBSim model of an aircraft from its airframe.yaml (through Airframe).

Sign conventions, the one place they are mapped: the model does not use JSBSim's own
fcs/*-pos-rad properties or its trim, whose surface signs differ between aircraft files. The
servo model writes fcs/hil/<surface>-pos-rad in the signs of msg/pwm.msg (elevator trailing edge
down +, aileron + rolls right, rudder trailing edge left + yaws left), which are also the signs
the stability derivatives of airframe.yaml are stated in, so the functions below use them as
they are. Forces and moments are given in JSBSim's body axes X (forward), Y (right), Z (down)
and ROLL, PITCH, YAW about them: the FRD frame of airframe.yaml. JSBSim's structural frame (X
aft, Y right, Z up) is only used for locations, converted in _structural().

Usage: python -m hil.fdm <aircraft_dir> <out_root>  (writes <out_root>/aircraft/<name>/)
"""
import math
import os
import sys
from xml.sax.saxutils import escape

from stack_common.units import FT_PER_M

from .airframe import LBF_PER_N, Airframe

THRUST_PROPERTY = "external_reactions/thrust/magnitude"
SURFACE_PROPERTIES = {
    "elevator": "fcs/hil/elevator-pos-rad",
    "aileron": "fcs/hil/aileron-pos-rad",
    "rudder": "fcs/hil/rudder-pos-rad",
}
THROTTLE_PROPERTY = "fcs/hil/throttle-pos-norm"
# Steerable wheels follow the rudder: full rudder is the wheel's max_steer. JSBSim steers a
# positive angle to the right; rudder + (trailing edge left) yaws left, so the sign flips.
STEER_SIGN = -1.0


def _structural(x_m, y_m, z_m):
    """Body FRD from the CG -> JSBSim structural frame (X aft, Y right, Z up), metres."""
    return -x_m, y_m, -z_m


def _num(v):
    return repr(float(v))


def _table(prop, pts):
    rows = "\n".join(f"          {x:.6f} {y:.9f}" for x, y in pts)
    return (f"<table>\n        <independentVar>{prop}</independentVar>\n"
            f"        <tableData>\n{rows}\n        </tableData>\n      </table>")


def _table2(row_prop, col_prop, grid):
    rows_bp, cols_bp, rows = grid
    head = "          " + " ".join(f"{c:.6f}" for c in cols_bp)
    body = "\n".join(f"          {r:.6f} " + " ".join(f"{v:.9f}" for v in vals) for r, vals in zip(rows_bp, rows))
    return (f'<table>\n        <independentVar lookup="row">{row_prop}</independentVar>\n'
            f'        <independentVar lookup="column">{col_prop}</independentVar>\n'
            f"        <tableData>\n{head}\n{body}\n        </tableData>\n      </table>")


def _products(terms):
    """terms: list of (coefficient, [property, ...]) -> JSBSim <product>s, one per term."""
    parts = []
    for coeff, props in terms:
        inner = "".join(f"<property>{p}</property>" for p in props)
        parts.append(f"<product><value>{_num(coeff)}</value>{inner}</product>")
    return "".join(parts)


def _sum_of_products(terms):
    return "<sum>" + _products(terms) + "</sum>"


def _aero(af):
    a = af.aero
    de, da, dr = (SURFACE_PROPERTIES[k] for k in ("elevator", "aileron", "rudder"))
    qs = ["aero/qbar-psf", "metrics/Sw-sqft"]
    fns = []

    def fn(name, body, desc):
        fns.append(f'  <function name="{name}">\n    <description>{escape(desc)}</description>\n'
                   f'    {body}\n  </function>')

    fn("aero/hil/cl-static", _table("aero/alpha-deg", af.lift_table()),
       "static lift curve with the stall")
    fn("aero/hil/phat", _products([(1.0, ["aero/bi2vel", "velocities/p-aero-rad_sec"])]),
       "roll rate p b/2V")
    fn("aero/hil/roll-damping-phat", _table2("aero/alpha-deg", "aero/hil/phat", af.roll_damping_grid()),
       "the roll rate cl_p acts on, by strip theory over the lift curve: autorotation past the stall, bounded")
    fn("aero/hil/cd-separation", _table("aero/alpha-deg", af.separation_drag_table()),
       "drag of separated flow past the stall")
    fn("aero/hil/cl", "<sum><property>aero/hil/cl-static</property>"
       + _products([(a["cl_q_per_rad"], ["aero/ci2vel", "velocities/q-aero-rad_sec"]),
                    (a["cl_elevator_per_rad"], [de])]) + "</sum>",
       "CL = CL_static(alpha) + cl_q q c/2V + cl_de de")
    fn("aero/hil/cd", f"<sum><value>{_num(a['cd0'])}</value>"
       f"<product><value>{_num(a['cd_k'])}</value><property>aero/hil/cl</property>"
       f"<property>aero/hil/cl</property></product><property>aero/hil/cd-separation</property></sum>",
       "CD = cd0 + k CL^2 + CD_sep(alpha)")
    fn("aero/hil/cy", _sum_of_products([(a["cy_beta_per_rad"], ["aero/beta-rad"]),
                                        (a["cy_rudder_per_rad"], [dr])]), "side force coefficient")
    # Pitching moment: cm_alpha * alpha with alpha clipped to +-90 deg (reversed flow does not
    # keep winding the moment up).
    alpha_clipped = (f'<min><value>{_num(math.pi / 2)}</value><max><value>{_num(-math.pi / 2)}</value>'
                     f'<property>aero/alpha-rad</property></max></min>')
    fn("aero/hil/cm", f'<sum><value>{_num(a["cm0"])}</value>'
       f'<product><value>{_num(a["cm_alpha_per_rad"])}</value>{alpha_clipped}</product>'
       + _products([(a["cm_q_per_rad"], ["aero/ci2vel", "velocities/q-aero-rad_sec"]),
                    (a["cm_elevator_per_rad"], [de])]) + "</sum>",
       "Cm about the CG")
    fn("aero/hil/croll", _sum_of_products([
        (a["cl_beta_per_rad"], ["aero/beta-rad"]),
        (a["cl_p_per_rad"], ["aero/hil/roll-damping-phat"]),
        (a["cl_r_per_rad"], ["aero/bi2vel", "velocities/r-aero-rad_sec"]),
        (a["cl_aileron_per_rad"], [da]), (a["cl_rudder_per_rad"], [dr])]), "rolling moment coefficient")
    fn("aero/hil/cn", _sum_of_products([
        (a["cn_beta_per_rad"], ["aero/beta-rad"]),
        (a["cn_p_per_rad"], ["aero/bi2vel", "velocities/p-aero-rad_sec"]),
        (a["cn_r_per_rad"], ["aero/bi2vel", "velocities/r-aero-rad_sec"]),
        (a["cn_aileron_per_rad"], [da]), (a["cn_rudder_per_rad"], [dr])]), "yawing moment coefficient")

    def prod(*items):
        return "<product>" + "".join(items) + "</product>"

    def p(name):
        return f"<property>{name}</property>"

    def v(x):
        return f"<value>{_num(x)}</value>"

    qsp = p(qs[0]) + p(qs[1])
    # Body forces from lift and drag exactly as the design model resolves them (no beta terms):
    # X = -D cos(alpha) + L sin(alpha), Z = -D sin(alpha) - L cos(alpha).
    cos_a = "<cos>" + p("aero/alpha-rad") + "</cos>"
    sin_a = "<sin>" + p("aero/alpha-rad") + "</sin>"
    fx = "<sum>" + prod(v(-1.0), qsp, p("aero/hil/cd"), cos_a) + prod(qsp, p("aero/hil/cl"), sin_a) + "</sum>"
    fz = ("<sum>" + prod(v(-1.0), qsp, p("aero/hil/cd"), sin_a)
          + prod(v(-1.0), qsp, p("aero/hil/cl"), cos_a) + "</sum>")
    fy = prod(qsp, p("aero/hil/cy"))
    mx = prod(qsp, p("metrics/bw-ft"), p("aero/hil/croll"))
    my = prod(qsp, p("metrics/cbarw-ft"), p("aero/hil/cm"))
    mz = prod(qsp, p("metrics/bw-ft"), p("aero/hil/cn"))

    def axis(name, body, unit):
        return (f'  <axis name="{name}">\n    <function name="aero/hil/{name.lower()}-{unit}">\n'
                f'      {body}\n    </function>\n  </axis>')

    axes = [axis("X", fx, "lbs"), axis("Y", fy, "lbs"), axis("Z", fz, "lbs"),
            axis("ROLL", mx, "lbsft"), axis("PITCH", my, "lbsft"), axis("YAW", mz, "lbsft")]
    return "<aerodynamics>\n" + "\n".join(fns) + "\n" + "\n".join(axes) + "\n</aerodynamics>"


def _gear(af):
    out = ["<ground_reactions>"]
    for c in af.contacts:
        x, y, z = _structural(c.x_m, c.y_m, c.z_m)
        out.append(
            f'  <contact type="{c.kind}" name="{c.name}">\n'
            f'    <location unit="M"><x>{_num(x)}</x><y>{_num(y)}</y><z>{_num(z)}</z></location>\n'
            f'    <static_friction>{_num(af.gear_static_friction)}</static_friction>\n'
            f'    <dynamic_friction>{_num(af.gear_dynamic_friction)}</dynamic_friction>\n'
            f'    <rolling_friction>{_num(af.gear_rolling_friction)}</rolling_friction>\n'
            f'    <spring_coeff unit="N/M">{_num(af.gear_spring_n_per_m)}</spring_coeff>\n'
            f'    <damping_coeff unit="N/M/SEC">{_num(af.gear_damping_n_s_per_m)}</damping_coeff>\n'
            f'    <max_steer unit="DEG">{_num(c.max_steer_deg)}</max_steer>\n'
            f'    <brake_group>NONE</brake_group>\n'
            f'    <retractable>0</retractable>\n'
            f'  </contact>')
    out.append("</ground_reactions>")
    return "\n".join(out)


def _propulsion(af):
    """T = throttle * max_thrust * (1 - V / zero_thrust_speed), along body X through the CG."""
    vzero_fps = af.zero_thrust_speed_mps * FT_PER_M
    tmax_lbf = af.max_thrust_n * LBF_PER_N
    fcs = (
        '<system name="hil-propulsion">\n  <channel name="thrust">\n'
        '    <fcs_function name="fcs/hil/thrust-lbs">\n      <function>\n'
        f'        <product><value>{_num(tmax_lbf)}</value><property>{THROTTLE_PROPERTY}</property>\n'
        f'          <difference><value>1.0</value><quotient><property>velocities/vtrue-fps</property>'
        f'<value>{_num(vzero_fps)}</value></quotient></difference></product>\n'
        f'      </function>\n      <output>{THRUST_PROPERTY}</output>\n    </fcs_function>\n'
        '  </channel>\n'
        '  <channel name="steering">\n'
        '    <fcs_function name="fcs/hil/steer-norm">\n      <function>\n'
        f'        <product><value>{_num(STEER_SIGN / math.radians(af.servos["rudder"].limit_deg))}</value>'
        f'<property>{SURFACE_PROPERTIES["rudder"]}</property></product>\n'
        '      </function>\n      <output>fcs/steer-cmd-norm</output>\n    </fcs_function>\n'
        '  </channel>\n</system>')
    ext = (
        '<external_reactions>\n  <force name="thrust" frame="BODY">\n'
        '    <location unit="M"><x>0</x><y>0</y><z>0</z></location>\n'
        '    <direction><x>1</x><y>0</y><z>0</z></direction>\n'
        '  </force>\n</external_reactions>')
    return fcs, ext


def generate(af):
    """The model XML text for Airframe af."""
    props = "\n".join(f'  <property value="0">{p}</property>'
                      for p in list(SURFACE_PROPERTIES.values()) + [THROTTLE_PROPERTY])
    fcs, ext = _propulsion(af)
    return f'''<?xml version="1.0"?>
<!-- GENERATED by hil/fdm/model_xml.py from aircraft/{af.name}/airframe.yaml and limits.yaml.
     Do not edit: change the data. -->
<fdm_config name="{af.name}" version="2.0" release="ALPHA">
<fileheader>
  <author>hil/fdm/model_xml.py</author>
  <description>{af.name} for the drone_ros HiL</description>
</fileheader>
<metrics>
  <wingarea unit="M2">{_num(af.wing_area_m2)}</wingarea>
  <wingspan unit="M">{_num(af.span_m)}</wingspan>
  <chord unit="M">{_num(af.chord_m)}</chord>
  <location name="AERORP" unit="M"><x>0</x><y>0</y><z>0</z></location>
  <location name="EYEPOINT" unit="M"><x>0</x><y>0</y><z>0</z></location>
  <location name="VRP" unit="M"><x>0</x><y>0</y><z>0</z></location>
</metrics>
<mass_balance>
  <ixx unit="KG*M2">{_num(af.ixx)}</ixx>
  <iyy unit="KG*M2">{_num(af.iyy)}</iyy>
  <izz unit="KG*M2">{_num(af.izz)}</izz>
  <ixz unit="KG*M2">{_num(af.ixz)}</ixz>
  <emptywt unit="KG">{_num(af.mass_kg)}</emptywt>
  <location name="CG" unit="M"><x>0</x><y>0</y><z>0</z></location>
</mass_balance>
{_gear(af)}
<propulsion/>
<flight_control name="hil-servos">
{props}
</flight_control>
{fcs}
{ext}
{_aero(af)}
</fdm_config>
'''


def write_model(af, out_root):
    """Writes <out_root>/aircraft/<name>/<name>.xml (and the empty engine/systems folders JSBSim
    expects); returns the model file's path."""
    model_dir = os.path.join(out_root, "aircraft", af.name)
    os.makedirs(model_dir, exist_ok=True)
    for sub in ("engine", "systems"):
        os.makedirs(os.path.join(out_root, sub), exist_ok=True)
    path = os.path.join(model_dir, af.name + ".xml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(generate(af))
    return path


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    print(write_model(Airframe(argv[1]), argv[2]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
