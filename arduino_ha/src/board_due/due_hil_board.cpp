#include "due_hil_board.h"

#include "due_config.h"
#if HA_DUE_HIL /* the flight build flies due_board.cpp instead */

#include <Arduino.h>

#include "../hil/ha_sil_records.h"
#include "due_common.h"

#if DUE_HP_LINK_PORT != DUE_HP_LINK_PORT_PROGRAMMING
#error "the HIL build takes its records on the native USB port: the HP link must stay on Serial"
#endif

/* Bytes taken from the native port in one pass: two step frames (60 bytes each) and then some;
 * the rest waits in the port's ring, so a flood cannot hold the loop off its period. */
#define DUE_HIL_RX_PER_PASS 256u

namespace {

DueHilBoard *as_hil(void *ctx) { return static_cast<DueHilBoard *>(ctx); }

/* The reset line is the simulator's to act on (the reply's flag): on a bench the pin may well be
 * wired to the computer running it. */
void hil_set_hp_reset(void *ctx, int asserted) { as_hil(ctx)->pins.hp_reset = asserted; }

}  // namespace

void due_hil_board_begin(DueHilBoard *hil) {
  hil->pins.have_in = 0;
  hil->pins.standalone = 0;
  hil->pins.hp_reset = 0;
  hil->records_undecodable = 0u;
  hil->commands = 0u;
  hil->tx_dropped = 0u;
  pil_frame_rx_init(&hil->records);
  hil->board.ctx = hil;
  ha_sil_pins_board(&hil->board);
  due_common_board(&hil->board); /* the clock, ports, LEDs, watchdog and backup registers */
  hil->board.set_hp_reset = hil_set_hp_reset;
  due_common_begin();
  SerialUSB.begin(0u); /* CDC: no rate */
}

const HaBoard *due_hil_board_interface(DueHilBoard *hil) { return &hil->board; }

void due_hil_board_count_command(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us) {
  (void)cmd;
  (void)arrival_us;
  as_hil(ctx)->commands++;
}

DueHilRequest due_hil_board_take_records(DueHilBoard *hil) {
  for (uint32_t n = 0u; n < DUE_HIL_RX_PER_PASS && SerialUSB.available() > 0; ++n) {
    const uint8_t *payload = nullptr;
    const size_t len =
        pil_frame_rx_byte(&hil->records, static_cast<uint8_t>(SerialUSB.read()), &payload);
    if (len == 0u) {
      continue;
    }
    const uint32_t magic = ha_sil_pins_take_record(&hil->pins, payload, len);
    if (magic == 0u) {
      hil->records_undecodable++;
    } else if (magic == HA_SIL_MAGIC_RESET) {
      hil->pins.hp_reset = 0; /* the Due's pins come up low: the HP out of reset */
      return DUE_HIL_RESET;
    }
    /* A poll record: nothing to do in real time, where every period is answered anyway. */
  }
  return DUE_HIL_NOTHING;
}

void due_hil_board_reply(DueHilBoard *hil, const HaFirmware *fw, uint32_t pass_us) {
  uint8_t frame[PIL_REPLY_FRAME_LEN];
  const HaSilReplyBoard rb = {HA_SIL_R_STEPPED,          fw->period_at_us,   hil->commands,
                              fw->ins.counts.bytes_read, hil->pins.hp_reset, 0u};
  /* rx_dropped stays 0: USB's flow control keeps unread bytes at the host (due_hil_board.h). */
  const PilReplyTrailer tr = {
      hil->records.bad_length + hil->records.bad_crc + hil->records_undecodable, pass_us,
      hil->tx_dropped, 0u};
  pil_reply_frame(fw, &rb, &tr, frame);
  const size_t sent = SerialUSB.write(frame, sizeof frame);
  hil->tx_dropped += static_cast<uint32_t>(sizeof frame - sent);
}

#endif /* HA_DUE_HIL */
