"""The Due image `make due-image` builds (arduino_ha/tools/build_due_image.sh: the assembled sketch
compiled and linked with the SAM core 1.6.12's platform.txt recipes, the variant's flash.ld and
libsam) read back from its .elf and .bin: it resets into flash, holds the sketch and the core's
step, leaves no symbol undefined and fits the SAM3X8E. The image is built here, into a temporary
folder, from the current sources. Two negative controls relink the same objects wrongly (for the
SRAM layout; without the sketch) and must be caught by the same checks."""
import os
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / "arduino_ha" / "tools" / "build_due_image.sh"
FLASH = (0x00080000, 0x00100000)  # SAM3X8E: 512 KiB of flash
RAM = (0x20070000, 0x20088000)  # 96 KiB of SRAM as one block (flash.ld's `ram`)
FLASH_BYTES = FLASH[1] - FLASH[0]
RAM_BYTES = RAM[1] - RAM[0]
# What the sketch must hold: the Arduino entry points arduino_ha.ino defines and the core's step,
# which the board layer's period calls (through ha_app_period today).
SKETCH_SYMBOLS = ("setup", "loop", "ha_core_step")
# One symbol each from the SAM core, libsam, Wire and Servo: the image is linked with the real
# ones, not the host shim (verify/arduino_shim).
PLATFORM_SYMBOLS = ("main", "Reset_Handler", "pmc_enable_periph_clk", "_ZN7TwoWire5beginEv",
                    "_ZN5Servo6attachEiii", "_ZN9UARTClass5beginEm")


# The HIL build's own (src/board_due/due_hil_board.h): the loop that takes the records, the frame
# decoder and the record decoder the QEMU board uses too (src/hil/), the reply's encoder.
HIL_SYMBOLS = ("_Z26due_hil_board_take_recordsP11DueHilBoard", "pil_frame_rx_byte",
               "ha_sil_decode_step", "pil_reply_frame")


def build(out, extra_flags=None):
    env = dict(os.environ, DUE_EXTRA_FLAGS=extra_flags) if extra_flags else None
    done = subprocess.run(["bash", str(BUILD), str(out)], capture_output=True, text=True, env=env)
    assert done.returncode == 0, "build_due_image.sh failed:\n%s\n%s" % (done.stdout, done.stderr)
    return done


@pytest.fixture(scope="module")
def image(tmp_path_factory):
    out = tmp_path_factory.mktemp("due_image")
    done = build(out)
    metrics = dict(re.findall(r"^metric: (\S+) (\S+)", done.stdout, re.M))
    sam = re.search(r"^sources: SAM core (\S+),", done.stdout, re.M).group(1)
    return {"out": out, "elf": out / "arduino_ha.ino.elf", "bin": out / "arduino_ha.ino.bin",
            "metrics": metrics, "variant": pathlib.Path(sam) / "variants" / "arduino_due_x"}


def symbols(elf):
    """name -> (type letter, address) of every symbol nm lists, undefined ones with address None."""
    table = {}
    lines = subprocess.run(["arm-none-eabi-nm", str(elf)], check=True, capture_output=True,
                           text=True).stdout.splitlines()
    for line in lines:
        parts = line.split()
        if len(parts) == 3:
            table[parts[2]] = (parts[1], int(parts[0], 16))
        elif len(parts) == 2:
            table[parts[1]] = (parts[0], None)
    return table


def undefined(elf):
    return subprocess.run(["arm-none-eabi-nm", "-u", str(elf)], check=True, capture_output=True,
                          text=True).stdout.split()


def sections(elf):
    """name -> (size, address) from size -A."""
    found = {}
    lines = subprocess.run(["arm-none-eabi-size", "-A", str(elf)], check=True, capture_output=True,
                           text=True).stdout.splitlines()
    for line in lines:
        parts = line.split()
        if len(parts) == 3 and parts[1].isdigit():
            found[parts[0]] = (int(parts[1]), int(parts[2]))
    return found


def reset_faults(elf, vectors):
    """What is wrong with how the chip starts: the first two words of the vector table (initial
    stack pointer, reset vector) as the boot ROM reads them from the start of flash."""
    faults = []
    stack_top = int.from_bytes(vectors[0:4], "little")
    reset = int.from_bytes(vectors[4:8], "little")
    if not reset & 1:
        faults.append("reset vector 0x%x lacks the Thumb bit" % reset)
    if not FLASH[0] <= (reset & ~1) < FLASH[1]:
        faults.append("reset vector 0x%x is not in flash" % reset)
    if not RAM[0] < stack_top <= RAM[1]:
        faults.append("initial stack pointer 0x%x is not in SRAM" % stack_top)
    handler = symbols(elf).get("Reset_Handler")
    if handler is None or handler[1] != reset & ~1:
        faults.append("reset vector 0x%x is not Reset_Handler (%s)" % (reset, handler))
    return faults


def missing_symbols(elf, names):
    table = symbols(elf)
    return [n for n in names if table.get(n, ("U", None))[0] not in ("T", "t", "W")]


def relink(image, tmp_path, ldscript, leave_out=None):
    """The image's own objects linked again as platform.txt links them, with another linker script
    or without one object; unresolved symbols are let through so that the checks see them."""
    build = image["out"] / "build"
    variant = image["variant"]
    objs = sorted(str(p) for d in ("sketch", "libraries", "core/variant")
                  for p in (build / d).rglob("*.o") if p.name != leave_out)
    elf = tmp_path / "relinked.elf"
    subprocess.run(["arm-none-eabi-gcc", "-mcpu=cortex-m3", "-mthumb", "-Os", "-T%s" % (variant / ldscript),
                    "-Wl,--gc-sections", "-Wl,--entry=Reset_Handler", "-Wl,--unresolved-symbols=ignore-all",
                    "-o", str(elf), "-Wl,--start-group", "-u", "_sbrk", *objs,
                    str(variant / "libsam_sam3x8e_gcc_rel.a"), str(build / "core" / "core.a"),
                    "-Wl,--end-group", "-lm", "-lgcc"], check=True, capture_output=True)
    binary = tmp_path / "relinked.bin"
    subprocess.run(["arm-none-eabi-objcopy", "-O", "binary", str(elf), str(binary)], check=True)
    return elf, binary


def test_the_due_image_resets_into_flash_at_reset_handler(image):
    assert reset_faults(image["elf"], image["bin"].read_bytes()[:8]) == []
    assert sections(image["elf"])[".text"][1] == FLASH[0], "the vector table opens the flash"


def test_the_due_image_holds_setup_loop_and_the_core_step(image):
    assert missing_symbols(image["elf"], SKETCH_SYMBOLS) == []


def test_the_due_image_is_linked_with_the_sam_core_libsam_wire_and_servo(image):
    assert missing_symbols(image["elf"], PLATFORM_SYMBOLS) == []


def test_the_due_image_leaves_no_symbol_undefined(image):
    assert undefined(image["elf"]) == []


def test_the_due_image_fits_the_sam3x8e_flash_and_ram(image):
    found = sections(image["elf"])

    def size(name):
        return found.get(name, (0, 0))[0]

    flash = size(".text") + size(".ARM.exidx") + size(".relocate")  # .relocate's initial values
    ram = size(".relocate") + size(".bss")
    assert image["bin"].stat().st_size == flash, "the .bin bossac writes is the image's flash part"
    assert flash <= FLASH_BYTES and ram <= RAM_BYTES, (flash, ram)
    assert image["metrics"]["due_image_flash"] == str(flash)
    assert image["metrics"]["due_image_ram"] == str(ram)


def test_an_image_linked_for_sram_fails_the_reset_check(image, tmp_path):
    """Negative control: the variant's sram.ld in place of flash.ld puts the reset handler in
    SRAM, where nothing survives a power cycle."""
    elf, binary = relink(image, tmp_path, "linker_scripts/gcc/sram.ld")
    faults = reset_faults(elf, binary.read_bytes()[:8])
    assert any("not in flash" in f for f in faults), faults


def test_an_image_without_the_sketch_fails_the_symbol_checks(image, tmp_path):
    """Negative control: the same link without arduino_ha.ino's object leaves setup and loop
    undefined (the core's main calls them)."""
    elf, _ = relink(image, tmp_path, "linker_scripts/gcc/flash.ld", leave_out="arduino_ha.ino.cpp.o")
    assert {"setup", "loop"} <= set(missing_symbols(elf, SKETCH_SYMBOLS))
    assert {"setup", "loop"} <= set(undefined(elf))


def test_the_native_usb_link_build_is_a_whole_image_too(tmp_path):
    """The HP link on the native USB port (DUE_HP_LINK_PORT=2, due_config.h), the build README.md
    offers besides the default, links against the real core and starts the same way."""
    build(tmp_path, "-DDUE_HP_LINK_PORT=2")
    elf = tmp_path / "arduino_ha.ino.elf"
    assert reset_faults(elf, (tmp_path / "arduino_ha.ino.bin").read_bytes()[:8]) == []
    assert missing_symbols(elf, SKETCH_SYMBOLS) == []
    assert undefined(elf) == []
    assert "SerialUSB" in undefined(tmp_path / "build" / "sketch" / "src" / "board_due" / "due_common.cpp.o")


def test_the_default_build_links_the_hp_over_the_programming_port(image):
    """Serial, the UART behind the 16U2 that the programming port flashes through (README.md)."""
    link = undefined(image["out"] / "build" / "sketch" / "src" / "board_due" / "due_common.cpp.o")
    assert "Serial" in link and "SerialUSB" not in link


def test_the_flight_image_holds_no_record_decoder(image):
    """Only the HIL build can be driven by the simulator's records: in the flight build nothing
    reads them (the linker's --gc-sections leaves the shared code out)."""
    assert set(missing_symbols(image["elf"], HIL_SYMBOLS)) == set(HIL_SYMBOLS)


@pytest.fixture(scope="module")
def hil_image(tmp_path_factory):
    out = tmp_path_factory.mktemp("due_hil_image")
    done = build(out, "-DHA_DUE_HIL=1")
    return {"out": out, "elf": out / "arduino_ha.ino.elf", "bin": out / "arduino_ha.ino.bin",
            "metrics": dict(re.findall(r"^metric: (\S+) (\S+)", done.stdout, re.M))}


def test_the_hil_image_resets_into_flash_and_holds_the_sketch_and_the_record_decoder(hil_image):
    assert reset_faults(hil_image["elf"], hil_image["bin"].read_bytes()[:8]) == []
    assert missing_symbols(hil_image["elf"], SKETCH_SYMBOLS + HIL_SYMBOLS) == []
    assert missing_symbols(hil_image["elf"], PLATFORM_SYMBOLS[:3]) == []  # the SAM core, libsam
    assert undefined(hil_image["elf"]) == []


def test_the_hil_image_fits_the_sam3x8e_flash_and_ram(hil_image):
    found = sections(hil_image["elf"])
    flash = sum(found.get(n, (0, 0))[0] for n in (".text", ".ARM.exidx", ".relocate"))
    ram = found.get(".relocate", (0, 0))[0] + found.get(".bss", (0, 0))[0]
    assert hil_image["bin"].stat().st_size == flash
    assert flash <= FLASH_BYTES and ram <= RAM_BYTES, (flash, ram)
    assert hil_image["metrics"]["due_image_flash"] == str(flash)
    assert hil_image["metrics"]["due_image_ram"] == str(ram)


def test_the_hil_image_takes_its_records_on_the_native_usb_port_and_drives_no_servo(hil_image):
    """The records on SerialUSB, the HP link still on Serial (the programming port) and the VN-200
    on Serial1 as in flight; the servos are the simulator's to move (due_hil_board.h)."""
    objs = hil_image["out"] / "build" / "sketch" / "src" / "board_due"
    assert "SerialUSB" in undefined(objs / "due_hil_board.cpp.o")
    ports = undefined(objs / "due_common.cpp.o")
    assert "Serial" in ports and "Serial1" in ports and "SerialUSB" not in ports
    assert not [s for s in symbols(hil_image["elf"]) if s.startswith("_ZN5Servo")]
