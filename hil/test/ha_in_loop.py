"""What the stories of the HA in the loop share, on either board (the host SIL, ha_sil; the QEMU
board, hil/ha_qemu.py): the parked aircraft its INS sees, and the PIL image built for a run."""
import os
import subprocess

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


class Parked:
    """Truth of an aircraft parked at a field (what the HA's INS sees before take-off)."""
    lat_deg, lon_deg, alt_msl_m = 38.95, -95.26, 260.0
    vn_mps = ve_mps = vd_mps = 0.0
    roll_deg, pitch_deg, heading_deg = 0.0, 2.0, 30.0
    p_rad_s = q_rad_s = r_rad_s = 0.0
    accel_body_mps2 = (0.0, 0.0, -9.81)
    mag_body_gauss = (0.2, 0.0, 0.45)
    temperature_c, pressure_pa = 20.0, 98000.0


def build_pil_image(out_dir):
    """The firmware for QEMU's mps2-an385, built afresh (make pil-image's script, about 10 s)."""
    subprocess.run(["bash", os.path.join(ROOT, "arduino_ha", "pil", "build_pil_image.sh"), out_dir],
                   check=True, stdout=subprocess.DEVNULL)
    return os.path.join(out_dir, "ha_pil.elf")
