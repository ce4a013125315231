"""An HP that flies into a stall with valid commands is taken over by the stall speed.

Known defect (a finding of this test; the assertion stays as the property states it), seed 11:
the HA sees the stall through its own pitot (AMS5812 offset and noise) 0.06 s (6 periods) after
the truth's calibrated airspeed fell to the stall speed; the aircraft falls 2.2 ft/s below it;
the HP, restarted and given control back, pulls up again three times until the HA latches, and
the aircraft is 1.34 s outside S_x while the HA drives, 0.93 s of it in excursions that began
under the HA, the worst latched, at 35.1 s: roll rate -563 deg/s (S_x row 4.7), a snap roll
after the repeated stalls. Whether the HA's safety controller or the flight model's post-stall
roll (hil/fdm: negative roll damping past the stall) is the cause is not settled here: the
replay command in the failure message reproduces the flight bit for bit. strict: this fails the
day the flight keeps the property, and the marker must then go."""
import pytest

from flight import assert_property, fly


@pytest.mark.xfail(strict=True, reason="HA sees the stall 6 periods late through its pitot and the aircraft "
                                       "departs (roll rate -563 deg/s) outside S_x under the HA (finding)")
def test_an_hp_flying_into_a_stall_is_taken_over():
    s = fly("stall", at_s=12.0, duration_s=-1.0, flight_s=40.0)
    assert_property(s, takeover_due=True)
