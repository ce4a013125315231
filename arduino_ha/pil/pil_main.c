/* The HA firmware as Cortex-M3 machine code on QEMU's mps2-an385: processor in the loop.
 *
 * The same firmware loop the Due runs (src/firmware/ha_firmware.h) over a Board of this machine:
 *   UART0 (serial0)  the rosserial link to the HP, where the `arduino` node opens its pty;
 *   UART1 (serial1)  the VN-200's port 1, the simulator's sensor pty, as the Due's Serial1;
 *   UART2 (serial2)  the simulator's control records (../src/hil/ha_sil_channel.h) framed with a
 *                    length and a CRC-32 (pil_frame.h): what the Due reads from its pins comes in
 *                    (time, RC incl. the PIC/CIC channel, airspeed, battery), what it drives goes
 *                    back (servos, HP reset line, decision, the safety controller's own command).
 * In lockstep (the default build) the board's micros() is the time of the latest step record, never
 * a free-running clock. CMSDK APB timer 0 runs free only to bound the waits for a period's inputs
 * (wait_ms, as the SIL bounds them in wall time) and to count the period's instructions under
 * -icount shift=0 (../bench/insn_timer.h: 40 instructions a tick); timer 1 wakes a bounded wait.
 * The UARTs' received bytes come by interrupt into rings, and the loop sleeps (WFI) while nothing
 * comes.
 *
 * Built with PIL_REALTIME=1 (hil/ha_qemu.py --realtime) the board keeps its own clock, as the Due's
 * HIL build does (../src/board_due/due_hil_board.h): micros() is timer 0's count of QEMU's virtual
 * time (without -icount it follows the host's clock), the firmware loop runs its own schedule,
 * a step record only brings the board inputs (its time, waits and counts unused), a poll record is
 * not answered, and each period the firmware ran is answered with a reply. Timer 1 wakes the loop
 * every RT_WAKE_TICKS, so a period starts on time while no byte comes.
 *
 * The reply frame is the SIL's reply record followed by a PilReplyTrailer (four u32 LE).
 * hil/ha_qemu.py starts QEMU and bridges the simulator's control socket to UART2. */
#include <stdint.h>
#include <string.h>

#include "../bench/insn_timer.h"
#include "../src/core/ha_aircraft.h"
#include "../src/firmware/ha_firmware.h"
#include "../src/hil/ha_sil_pins.h"
#include "../src/hil/ha_sil_records.h"
#include "../src/hil/pil_frame.h"

/* ---- CMSDK APB UART (ARM CMSDK technical reference; mps2-an385: UART n at 0x40004000 + n 4 KiB)
 */

#define UART_BASE(n) (0x40004000u + 0x1000u * (uint32_t)(n))
#define UART_DATA(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x00u))
#define UART_STATE(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x04u))
#define UART_CTRL(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x08u))
#define UART_INTSTATUS(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x0Cu)) /* write 1 to clear */
#define UART_BAUDDIV(n) (*(volatile uint32_t *)(UART_BASE(n) + 0x10u))
#define UART_STATE_TX_FULL 1u
#define UART_STATE_RX_FULL 2u
#define UART_CTRL_TX_RX_RXINT 0xBu /* TX and RX enabled, the RX interrupt */
#define UART_INT_RX 2u
#define UART_HP 0
#define UART_INS 1
#define UART_CONTROL 2
#define UART_COUNT 3
/* CMSDK APB timer 1: the wake-up of a bounded wait (timer 0 is the free-running insn_timer). */
#define TIMER1_CTRL (*(volatile uint32_t *)0x40001000u)
#define TIMER1_VALUE (*(volatile uint32_t *)0x40001004u)
#define TIMER1_RELOAD (*(volatile uint32_t *)0x40001008u)
#define TIMER1_INTCLEAR (*(volatile uint32_t *)0x4000100Cu)
#define TIMER_CTRL_ENABLE_IRQ 0x9u
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define SCB_VTOR (*(volatile uint32_t *)0xE000ED08u)
/* mps2-an385's interrupts (QEMU hw/arm/mps2.c): UART n's RX and TX at 2n and 2n + 1 (TX is never
 * enabled in the UART), the timers at 8 and 9. They all go to the one handler, which asks each
 * device itself. The UARTs' overrun line (12) stays off: nothing here would clear it. */
#define IRQ_COUNT 16u
#define IRQ_ENABLED 0x33Fu
#define TIMER_TICKS_PER_MS 25000u
/* A byte the host side does not take within this much timer time is dropped (and counted): a pty
 * nobody reads must not stop the HA (the link is built to lose bytes, as a full USB buffer on the
 * Due loses them; ha_qemu.py's relay drains the socket and drops at the pty). Generous: QEMU's
 * socket takes a few hundred one-byte writes before the relay must read, and at load 18 on the
 * 2 shared cores 50 ms lost 77 bytes of the topic negotiation's burst. In lockstep a wait costs
 * no simulated time. */
#ifndef PIL_REALTIME
#define PIL_REALTIME 0
#endif
#if PIL_REALTIME
/* In real time a byte waited on is time off the schedule: a 2 ms wait, then it is dropped. */
#define UART_TX_WAIT_TICKS (2u * TIMER_TICKS_PER_MS)
#define RT_WAKE_TICKS (TIMER_TICKS_PER_MS / 4u)
#else
#define UART_TX_WAIT_TICKS (1000u * TIMER_TICKS_PER_MS)
#endif
#ifndef PIL_IDLE_SPINS
#define PIL_IDLE_SPINS 200u
#endif
/* What each UART's receive interrupt keeps until the loop reads it, as the Due's core keeps its
 * Serial bytes in a ring its UART interrupt fills (a power of two). Between two steps the HP link
 * and the VN-200 deliver one period's bytes, a few hundred. */
#define RX_RING_LEN 2048u

static void uart_init(int n) {
  UART_BAUDDIV(n) = 217u; /* 25 MHz / 115200; QEMU moves bytes at the host's pace anyway */
  UART_CTRL(n) = UART_CTRL_TX_RX_RXINT;
}

/* Polls without touching a device: every register read of a spinning guest takes QEMU's big lock,
 * which the thread bringing the host's bytes to the UARTs needs too. Only the rare full TX
 * register is waited on this way. */
static void idle_a_little(void) {
  volatile uint32_t k;
  for (k = 0u; k < PIL_IDLE_SPINS; ++k) {
  }
}

/* The CMSDK UART holds one received byte, and QEMU hands it the next only from its main loop after
 * the guest has read that one. A guest polling the status register spends its time in register
 * exits that take QEMU's big lock from the thread bringing the bytes (0.1-0.2x real time in a
 * flight). So each byte raises the RX interrupt, the handler moves it into a ring, and the loop
 * sleeps (WFI) until a byte or its deadline: the vCPU idles while the main loop delivers. Spinning
 * on the rings a while before sleeping measured 2-4x slower a step on the shared 2 cores: the
 * spinning vCPU takes the core the main loop needs. */
typedef struct {
  uint8_t bytes[RX_RING_LEN];
  volatile uint32_t head; /* written by the handler only */
  volatile uint32_t tail; /* written by the loop only */
  volatile uint32_t dropped;
} RxRing;

static RxRing g_rx[UART_COUNT];

static void take_received(int n) {
  RxRing *r = &g_rx[n];
  /* Cleared before the data register is read: a byte that comes after the read raises it anew. */
  UART_INTSTATUS(n) = UART_INT_RX;
  while ((UART_STATE(n) & UART_STATE_RX_FULL) != 0u) {
    const uint8_t byte = (uint8_t)UART_DATA(n);
    const uint32_t head = r->head;
    if (head - r->tail < RX_RING_LEN) {
      r->bytes[head % RX_RING_LEN] = byte;
      r->head = head + 1u;
    } else {
      r->dropped++; /* as the Due's Serial drops into a full ring */
    }
  }
}

static void pil_irq_handler(void) {
  int n;
  TIMER1_INTCLEAR = 1u;
  for (n = 0; n < UART_COUNT; ++n) {
    take_received(n);
  }
}

void ha_bench_fault_handler(void); /* bench/startup_m3.c: a fault ends the run */
typedef void (*PilVector)(void);
#define VECTOR_NMI 2u
#define VECTOR_USAGE_FAULT 6u
#define VECTOR_IRQ0 16u
/* The start-up's table has only the core's exceptions; this one adds the device interrupts. In
 * RAM, filled at start (VTOR: aligned to a power of two above its size); entries 0 and 1 are read
 * only at reset, the core's others but the faults never taken here. */
static PilVector g_vectors[VECTOR_IRQ0 + IRQ_COUNT] __attribute__((aligned(128)));

static void interrupts_start(void) {
  uint32_t k;
  for (k = VECTOR_NMI; k <= VECTOR_USAGE_FAULT; ++k) {
    g_vectors[k] = ha_bench_fault_handler;
  }
  for (k = VECTOR_IRQ0; k < VECTOR_IRQ0 + IRQ_COUNT; ++k) {
    g_vectors[k] = pil_irq_handler;
  }
  SCB_VTOR = (uint32_t)(uintptr_t)g_vectors;
  NVIC_ISER0 = IRQ_ENABLED;
}

static int ring_empty(int n) { return g_rx[n].head == g_rx[n].tail; }

static int bytes_waiting(unsigned mask) {
  int n;
  int any = 0;
  for (n = 0; n < UART_COUNT; ++n) {
    any |= ((mask >> n) & 1u) != 0u && !ring_empty(n);
  }
  return any;
}

/* Sleeps until a byte has come on one of the UARTs in mask (bit n: UART n) or another interrupt
 * (timer 1's, say). Interrupts are masked from the check to the WFI, so a byte that comes in
 * between wakes it instead of being missed (a pending interrupt ends WFI even while PRIMASK
 * holds it off). */
static void sleep_until_bytes(unsigned mask) {
  __asm volatile("cpsid i" ::: "memory");
  if (!bytes_waiting(mask)) {
    __asm volatile("wfi" ::: "memory");
  }
  __asm volatile("cpsie i" ::: "memory");
}

/* Timer 1 interrupts every ticks from now until stopped: the deadline of a bounded wait. Armed
 * once a wait, not once a sleep: each register write is an exit into QEMU under its big lock. */
static void wake_every(uint32_t ticks) {
  TIMER1_CTRL = 0u;
  TIMER1_RELOAD = ticks;
  TIMER1_VALUE = ticks;
  TIMER1_CTRL = TIMER_CTRL_ENABLE_IRQ;
}

static size_t uart_read(int n, uint8_t *bytes, size_t max_len) {
  RxRing *r = &g_rx[n];
  const uint32_t head = r->head;
  uint32_t tail = r->tail;
  size_t got = 0u;
  /* The bytes are not volatile: no read of them may be moved above the read of the head that
   * says they are there (the handler, which runs to its end, has stored them by then). */
  __asm volatile("" ::: "memory");
  while (got < max_len && tail != head) {
    bytes[got++] = r->bytes[tail % RX_RING_LEN];
    tail++;
  }
  r->tail = tail;
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

static uint32_t rx_dropped(void) {
  return g_rx[UART_HP].dropped + g_rx[UART_INS].dropped + g_rx[UART_CONTROL].dropped;
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

#if PIL_REALTIME
/* Timer 0's ticks since power-up, in microseconds: the ticks are summed at every read (the loop
 * reads far more often than the 32-bit counter's 171 s wrap), so the microseconds wrap as the
 * Due's micros() does, at 2^32. */
static uint32_t board_micros(void *ctx) {
  static uint32_t last_tick;
  static uint64_t ticks;
  static int started;
  const uint32_t now = ha_insn_timer_read();
  (void)ctx;
  if (started) {
    ticks += (uint32_t)(last_tick - now); /* a down counter */
  }
  started = 1;
  last_tick = now;
  return (uint32_t)(ticks / (TIMER_TICKS_PER_MS / 1000u));
}
#else
static uint32_t board_micros(void *ctx) { return as_pil(ctx)->now_us; }
#endif

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
                                            .tap_ctx = &g_pil,
                                            .pace_by_command = PIL_REALTIME};

/* ---- the control records ---- */

/* The trailer's period_ticks here: timer ticks of the period's ha_firmware_period (40
 * instructions each under -icount shift=0). */
static void send_reply(PilBoard *b, uint16_t flags, uint64_t t_us, uint32_t wait_us) {
  uint8_t frame[PIL_REPLY_FRAME_LEN];
  const HaSilReplyBoard rb = {.flags = flags,
                              .t_us = t_us,
                              .commands = b->commands,
                              .vn_bytes = b->vn_bytes,
                              .hp_reset = b->pins.hp_reset,
                              .wait_us = wait_us};
  const PilReplyTrailer tr = {
      .records_dropped = b->control.bad_length + b->control.bad_crc + b->records_undecodable,
      .period_ticks = b->period_ticks,
      .tx_dropped = g_tx_dropped,
      .rx_dropped = rx_dropped()};
  pil_reply_frame(&b->fw, &rb, &tr, frame);
  uart_write(UART_CONTROL, frame, sizeof frame);
}

/* Reads the HP link and the VN-200 port until they have delivered what the simulator says it
 * sent for this period, bounded by wait_ms of timer time, as the SIL does (ha_sil.c): what has
 * come is in the receive rings, so no wait for the ports to go quiet. Returns the
 * HA_SIL_R_*_TIMEOUT flags. */
static uint16_t gather_period_inputs(PilBoard *b, const HaSilStep *st, uint32_t *waited_ticks) {
  const uint32_t start = ha_insn_timer_read();
  const uint32_t bound = (st->wait_ms < 100000u ? st->wait_ms : 100000u) * TIMER_TICKS_PER_MS;
  uint16_t timeouts = 0u;
  if (bound > 0u) { /* with none, the first pass returns before it would sleep */
    wake_every(bound);
  }
  for (;;) {
    int want_cmd;
    int want_vn;
    (void)ha_firmware_receive(&b->fw, b->now_us, RX_RING_LEN);
    if ((st->flags & HA_SIL_WAIT_COUNT) != 0u) {
      want_cmd = (st->flags & HA_SIL_WAIT_COMMAND) != 0u && b->commands < st->cmd_seq;
    } else {
      want_cmd = (st->flags & HA_SIL_WAIT_COMMAND) != 0u &&
                 !(b->commands > 0u && b->last_cmd_seq == st->cmd_seq);
    }
    want_vn = b->vn_bytes < st->vn_bytes;
    *waited_ticks = start - ha_insn_timer_read(); /* a down counter */
    if (!want_cmd && !want_vn) {
      break;
    }
    if (*waited_ticks >= bound) {
      timeouts = (uint16_t)((want_cmd ? HA_SIL_R_COMMAND_TIMEOUT : 0u) |
                            (want_vn ? HA_SIL_R_VN_TIMEOUT : 0u));
      break;
    }
    sleep_until_bytes((1u << UART_HP) | (1u << UART_INS));
  }
  TIMER1_CTRL = 0u;
  return timeouts;
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
    (void)ha_firmware_receive(&b->fw, b->now_us, RX_RING_LEN);
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

#if PIL_REALTIME
/* The control UART's records, as the Due's HIL board takes them (due_hil_board.cpp): a step
 * record's inputs become the pins', a reset record restarts the firmware, a poll is ignored. */
static void take_records_realtime(PilBoard *b) {
  uint8_t byte;
  while (uart_read(UART_CONTROL, &byte, 1u) == 1u) {
    const uint8_t *payload = NULL;
    const size_t len = pil_frame_rx_byte(&b->control, byte, &payload);
    uint32_t magic;
    if (len == 0u) {
      continue;
    }
    magic = ha_sil_pins_take_record(&b->pins, payload, len);
    if (magic == 0u) {
      b->records_undecodable++;
    } else if (magic == HA_SIL_MAGIC_RESET) {
      start_firmware(b);
    }
  }
}

static void run_realtime(PilBoard *b) {
  wake_every(RT_WAKE_TICKS);
  for (;;) {
    const uint32_t t0 = ha_insn_timer_read();
    take_records_realtime(b);
    if (ha_firmware_loop(&b->fw)) {
      b->period_ticks = t0 - ha_insn_timer_read();
      send_reply(b, HA_SIL_R_STEPPED, b->fw.period_at_us, 0u);
    }
    sleep_until_bytes((1u << UART_HP) | (1u << UART_INS) | (1u << UART_CONTROL));
  }
}
#endif

int main(void) {
  PilBoard *b = &g_pil;
  int n;
  for (n = UART_HP; n <= UART_CONTROL; ++n) {
    uart_init(n);
  }
  ha_insn_timer_start();
  interrupts_start();
  pil_frame_rx_init(&b->control);
  ha_sil_pins_board(&b->iface); /* standalone 0: nothing reads good before the first step */
  b->iface.ctx = b;
  b->iface.micros = board_micros;
  b->iface.hp_link = (HaBytePort){.read = hp_read, .write = hp_write};
  b->iface.ins = (HaBytePort){.read = ins_read, .write = NULL}; /* the HA never writes to it */
  start_firmware(b); /* power-up: the retained words hold no record yet */
#if PIL_REALTIME
  run_realtime(b);
#endif
  for (;;) {
    uint8_t byte;
    const uint8_t *payload = NULL;
    size_t len;
    if (uart_read(UART_CONTROL, &byte, 1u) == 0u) {
      sleep_until_bytes(1u << UART_CONTROL);
      continue;
    }
    len = pil_frame_rx_byte(&b->control, byte, &payload);
    if (len > 0u) {
      on_record(b, payload, len);
    }
  }
}
