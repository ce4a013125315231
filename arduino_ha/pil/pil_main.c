/* The HA firmware as Cortex-M3 machine code on QEMU's mps2-an385: processor in the loop.
 *
 * The same firmware loop the Due runs (src/firmware/ha_firmware.h) over a Board of this machine:
 *   UART0 (serial0)  the rosserial link to the HP, where the `arduino` node opens its pty;
 *   UART1 (serial1)  the VN-200's port 1, the simulator's sensor pty, as the Due's Serial1;
 *   UART2 (serial2)  the simulator's control records (../sil/ha_sil_channel.h) framed with a
 *                    length and a CRC-32 (pil_frame.h): what the Due reads from its pins comes in
 *                    (time, RC incl. the PIC/CIC channel, airspeed, battery), what it drives goes
 *                    back (servos, HP reset line, decision, the safety controller's own command).
 * Lockstep only: the board's micros() is the time of the latest step record, never a free-running
 * clock. CMSDK APB timer 0 runs free only to bound the waits for a period's inputs (wait_ms, as the
 * SIL bounds them in wall time) and to count the period's instructions under -icount shift=0
 * (../bench/insn_timer.h: 40 instructions a tick).
 *
 * The reply frame is the SIL's reply record followed by a PilReplyTrailer (three u32 LE).
 * hil/ha_qemu.py starts QEMU and bridges the simulator's control socket to UART2. */
#include <stdint.h>
#include <string.h>

#include "../bench/insn_timer.h"
#include "../sil/ha_sil_pins.h"
#include "../sil/ha_sil_records.h"
#include "../src/core/ha_aircraft.h"
#include "../src/firmware/ha_firmware.h"
#include "pil_frame.h"

/* ---- CMSDK APB UART (ARM CMSDK technical reference; mps2-an385: UART n at 0x40004000 + n 4 KiB)
 */

#define UART_BASE(n) (0x40004000u + 0x1000u * (uint32_t)(n))
#define UART_DATA(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x00u))
#define UART_STATE(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x04u))
#define UART_CTRL(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x08u))
#define UART_BAUDDIV(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x10u))
#define UART_STATE_TX_FULL 1u
#define UART_STATE_RX_FULL 2u
#define UART_CTRL_TX_RX 3u
#define UART_HP 0
#define UART_INS 1
#define UART_CONTROL 2
#define TIMER_TICKS_PER_MS 25000u
/* A byte the host side does not take within this much timer time is dropped (and counted): a pty
 * nobody reads must not stop the HA (the link is built to lose bytes, as a full USB buffer on the
 * Due loses them). Generous, since QEMU's thread that writes the pty may wait for a loaded CPU. */
#define UART_TX_WAIT_TICKS (50u * TIMER_TICKS_PER_MS)
/* After a period's inputs have come, the ports are read on until they have been quiet this long:
 * QEMU hands a UART one byte at a time, so "what has arrived" is only known by waiting a little,
 * and bytes left unread (the host's time sync, say) would pile up from period to period. */
#define QUIET_TICKS (TIMER_TICKS_PER_MS / 2u)
#ifndef PIL_IDLE_SPINS
#define PIL_IDLE_SPINS 200u
#endif /* the board's 25 MHz APB clock */

static void uart_init(int n) {
  UART_BAUDDIV(n) = 217u; /* 25 MHz / 115200; QEMU moves bytes at the host's pace anyway */
  UART_CTRL(n) = UART_CTRL_TX_RX;
}

/* Polls without touching a device: every register read of a spinning guest takes QEMU's big lock,
 * which the thread bringing the host's bytes to the UARTs needs too. */
static void idle_a_little(void) {
  volatile uint32_t k;
  for (k = 0u; k < PIL_IDLE_SPINS; ++k) {
  }
}

static size_t uart_read(int n, uint8_t *bytes, size_t max_len) {
  size_t got = 0u;
  while (got < max_len && (UART_STATE(n) & UART_STATE_RX_FULL) != 0u) {
    bytes[got++] = (uint8_t)UART_DATA(n);
  }
  return got;
}

static uint32_t g_tx_dropped;

static void uart_write(int n, const uint8_t *bytes, size_t len) {
  size_t k;
  for (k = 0u; k < len; ++k) {
    const uint32_t start = ha_insn_timer_read();
    while ((UART_STATE(n) & UART_STATE_TX_FULL) != 0u) {
      if ((uint32_t)(start - ha_insn_timer_read()) >= UART_TX_WAIT_TICKS) {
        g_tx_dropped += (uint32_t)(len - k);
        return;
      }
      idle_a_little();
    }
    UART_DATA(n) = bytes[k];
  }
}

/* ---- the Board ---- */

typedef struct {
  HaSilPins pins; /* first: the pins' Board functions take this board's ctx (ha_sil_pins.h) */
  HaBoard iface;
  HaFirmware fw;
  uint32_t now_us; /* the latest step record's time */
  uint64_t vn_bytes;
  uint32_t commands;
  uint32_t last_cmd_seq;
  PilFrameRx control;
  uint32_t records_undecodable; /* framed and checked, but no record of ha_sil_channel.h */
  uint32_t period_ticks;
} PilBoard;

static PilBoard g_pil;

static PilBoard *as_pil(void *ctx) { return (PilBoard *)ctx; }

static uint32_t board_micros(void *ctx) { return as_pil(ctx)->now_us; }

static size_t hp_read(void *ctx, uint8_t *bytes, size_t max_len) {
  (void)ctx;
  return uart_read(UART_HP, bytes, max_len);
}

static void hp_write(void *ctx, const uint8_t *bytes, size_t len) {
  (void)ctx;
  uart_write(UART_HP, bytes, len);
}

static size_t ins_read(void *ctx, uint8_t *bytes, size_t max_len) {
  const size_t n = uart_read(UART_INS, bytes, max_len);
  as_pil(ctx)->vn_bytes += n;
  return n;
}

static void on_command(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us) {
  PilBoard *b = as_pil(ctx);
  (void)arrival_us;
  b->commands++;
  b->last_cmd_seq = cmd->seq;
}

static const HaFirmwareOptions k_options = {.link_up_text = "HA QEMU link up",
                                            .probe_param = NULL,
                                            .period_us = 0u,
                                            .reads_per_pass = 1u,
                                            .command_tap = on_command,
                                            .tap_ctx = &g_pil};

/* ---- the control records ---- */

/* What a counted drop of the control channel is: a frame out of length, failing its CRC, or
 * checked but holding no step, poll or reset record. */
typedef struct {
  uint32_t records_dropped;
  uint32_t period_insn_ticks; /* timer ticks of the period's ha_firmware_period (40 instr each
                                 under -icount shift=0) */
  uint32_t tx_dropped;        /* bytes a UART's host side did not take in time */
} PilReplyTrailer;
#define PIL_TRAILER_LEN 12u

static void send_reply(PilBoard *b, uint16_t flags, uint64_t t_us, uint32_t wait_us) {
  uint8_t rec[HA_SIL_REPLY_RECORD_LEN + PIL_TRAILER_LEN];
  uint8_t frame[sizeof rec + PIL_FRAME_OVERHEAD];
  size_t at = HA_SIL_REPLY_RECORD_LEN;
  const HaSilReplyBoard rb = {.flags = flags,
                              .t_us = t_us,
                              .commands = b->commands,
                              .vn_bytes = b->vn_bytes,
                              .hp_reset = b->pins.hp_reset,
                              .wait_us = wait_us};
  PilReplyTrailer tr;
  ha_sil_encode_reply(&b->fw, &rb, rec);
  tr.records_dropped = b->control.bad_length + b->control.bad_crc + b->records_undecodable;
  tr.period_insn_ticks = b->period_ticks;
  tr.tx_dropped = g_tx_dropped;
  ha_sil_put_u32(rec, &at, tr.records_dropped);
  ha_sil_put_u32(rec, &at, tr.period_insn_ticks);
  ha_sil_put_u32(rec, &at, tr.tx_dropped);
  uart_write(UART_CONTROL, frame, pil_frame_encode(rec, sizeof rec, frame, sizeof frame));
}

/* Reads the HP link and the VN-200 port until they have delivered what the simulator says it
 * sent for this period, bounded by wait_ms of timer time. Returns the HA_SIL_R_*_TIMEOUT flags. */
static uint16_t gather_period_inputs(PilBoard *b, const HaSilStep *st, uint32_t *waited_ticks) {
  const uint32_t start = ha_insn_timer_read();
  const uint32_t bound = (st->wait_ms < 100000u ? st->wait_ms : 100000u) * TIMER_TICKS_PER_MS;
  uint32_t last_byte = start;
  for (;;) {
    int want_cmd;
    int want_vn;
    const uint32_t now = ha_insn_timer_read();
    if (ha_firmware_receive(&b->fw, b->now_us, 1u) > 0u) {
      last_byte = now;
    } else {
      idle_a_little();
    }
    if ((st->flags & HA_SIL_WAIT_COUNT) != 0u) {
      want_cmd = (st->flags & HA_SIL_WAIT_COMMAND) != 0u && b->commands < st->cmd_seq;
    } else {
      want_cmd = (st->flags & HA_SIL_WAIT_COMMAND) != 0u &&
                 !(b->commands > 0u && b->last_cmd_seq == st->cmd_seq);
    }
    want_vn = b->vn_bytes < st->vn_bytes;
    *waited_ticks = start - now; /* a down counter */
    if (!want_cmd && !want_vn && (uint32_t)(last_byte - now) >= QUIET_TICKS) {
      return 0u;
    }
    if (*waited_ticks >= bound) {
      return (uint16_t)((want_cmd ? HA_SIL_R_COMMAND_TIMEOUT : 0u) |
                        (want_vn ? HA_SIL_R_VN_TIMEOUT : 0u));
    }
  }
}

static void start_firmware(PilBoard *b) {
  ha_firmware_start(&b->fw, &b->iface, &ha_aircraft_config, &k_options);
  b->pins.hp_reset = 0; /* the Due's pins come up low: the HP out of reset */
}

static void on_record(PilBoard *b, const uint8_t *payload, size_t len) {
  HaSilStep st;
  uint32_t waited_ticks = 0u;
  uint16_t flags;
  uint32_t t0;
  if (!ha_sil_decode_step(payload, len, &st)) {
    b->records_undecodable++;
    return;
  }
  if (st.magic == HA_SIL_MAGIC_RESET) {
    start_firmware(b); /* as a watchdog reset: RAM afresh but the retained words */
    send_reply(b, 0u, b->now_us, 0u);
    return;
  }
  if (st.magic == HA_SIL_MAGIC_POLL) {
    (void)ha_firmware_receive(&b->fw, b->now_us, 1u);
    ha_firmware_service(&b->fw, b->now_us);
    send_reply(b, 0u, b->now_us, 0u);
    return;
  }
  /* The clock never runs backwards (the link requires it): an earlier step keeps the time. */
  if ((int32_t)((uint32_t)st.t_us - b->now_us) > 0) {
    b->now_us = (uint32_t)st.t_us;
  }
  flags = gather_period_inputs(b, &st, &waited_ticks);
  b->pins.in = st;
  b->pins.have_in = 1;
  t0 = ha_insn_timer_read();
  ha_firmware_period(&b->fw, b->now_us);
  b->period_ticks = t0 - ha_insn_timer_read();
  ha_firmware_service(&b->fw, b->now_us);
  send_reply(b, (uint16_t)(flags | HA_SIL_R_STEPPED), st.t_us,
             waited_ticks / (TIMER_TICKS_PER_MS / 1000u));
}

int main(void) {
  PilBoard *b = &g_pil;
  int n;
  for (n = UART_HP; n <= UART_CONTROL; ++n) {
    uart_init(n);
  }
  ha_insn_timer_start();
  pil_frame_rx_init(&b->control);
  ha_sil_pins_board(&b->iface); /* standalone 0: nothing reads good before the first step */
  b->iface.ctx = b;
  b->iface.micros = board_micros;
  b->iface.hp_link = (HaBytePort){.read = hp_read, .write = hp_write};
  b->iface.ins = (HaBytePort){.read = ins_read, .write = NULL}; /* the HA never writes to it */
  start_firmware(b); /* power-up: the retained words hold no record yet */
  for (;;) {
    uint8_t byte;
    const uint8_t *payload = NULL;
    size_t len;
    if (uart_read(UART_CONTROL, &byte, 1u) == 0u) {
      idle_a_little();
      continue;
    }
    len = pil_frame_rx_byte(&b->control, byte, &payload);
    if (len > 0u) {
      on_record(b, payload, len);
    }
  }
}
