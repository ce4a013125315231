"""The firmware is built for the build's aircraft: the sketch arduino-cli compiles (make sketch-ha,
due-image) and the QEMU image (make pil-image, run_flight.py --ha qemu) carry the limits of
AIRCRAFT=<name>, and without it the checked-in header of the default aircraft."""
import os
import subprocess

from stack_tools.paths import ROOT

HA = os.path.join(ROOT, "arduino_ha")
CHECKED_IN = os.path.join(HA, "src", "generated", "aircraft_config.h")


def assemble(out, aircraft=None):
    env = dict(os.environ)
    env.pop("AIRCRAFT", None)
    if aircraft:
        env["AIRCRAFT"] = aircraft
    done = subprocess.run(["bash", os.path.join(HA, "tools", "assemble_sketch.sh"), str(out)], env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    with open(os.path.join(done.stdout.strip(), "src", "generated", "aircraft_config.h")) as f:
        return f.read()


def test_the_sketch_for_another_aircraft_carries_its_limits(tmp_path):
    config = assemble(tmp_path / "aerosonde", "Aerosonde")
    assert '.aircraft = "Aerosonde"' in config
    with open(CHECKED_IN) as f:
        assert config != f.read()


def test_the_sketch_without_an_aircraft_is_the_checked_in_one_and_the_default_regenerates_it(tmp_path):
    with open(CHECKED_IN) as f:
        checked_in = f.read()
    assert assemble(tmp_path / "plain") == checked_in
    assert assemble(tmp_path / "dg808", "DG808") == checked_in


def test_the_qemu_image_of_another_aircraft_is_compiled_with_its_limits(tmp_path):
    env = dict(os.environ, AIRCRAFT="Aerosonde")
    done = subprocess.run(["bash", os.path.join(HA, "pil", "build_pil_image.sh"), str(tmp_path)], env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    with open(tmp_path / "ha_pil.elf", "rb") as f:
        image = f.read()
    assert b"Aerosonde\0" in image and b"DG808\0" not in image
