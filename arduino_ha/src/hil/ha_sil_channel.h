/* The simulator's control channel to the HA in the loop: fixed little-endian binary records on a
 * unix SOCK_SEQPACKET socket (one record per packet), the simulator listening, the SIL connecting
 * (ha_sil --lockstep PATH). hil/ha_channel.py is the simulator's end and states the same layouts
 * as struct formats; test_ha_channel_layout (hil/test) checks the two agree.
 *
 * What crosses it is exactly what the Due's board layer reads from and writes to the hardware
 * (arduino_ha/src/board_due/): the clock (micros), the RC receiver incl. the PIC/CIC channel, the
 * AMS5812 airspeed, the battery ADC; back come the servo outputs, the HP reset line, and the
 * decision the core took. The INS does not cross it: the HA reads its VN-200 on its own serial
 * port (a pty), as the Due reads Serial1. The HP commands do not cross it either: they arrive over
 * the rosserial link from the real `arduino` node.
 *
 * Lockstep: the simulator sends HA_SIL_STEP; the SIL sets its clock to t_us, reads its VN-200
 * port until it has taken vn_bytes bytes in total, reads the link until the HP command with
 * sequence number cmd_seq has arrived (when HA_SIL_WAIT_COMMAND is set), each bounded by
 * wait_ms of wall time, runs one period of the core with the board inputs of the record, services
 * the link (publishes /pwm and /decision_status) and answers HA_SIL_REPLY. HA_SIL_POLL only
 * services the link and the VN-200 port at the current clock (before the first step, while the
 * host negotiates topics) and answers a reply without stepping.
 * Real time (--rate-hz clock, --lockstep PATH --realtime): STEP records only set the board inputs
 * (t_us ignored); the SIL answers a reply after each of its own periods, stamped with its tick
 * (the simulator dates the HA's periods by it). Until the first STEP record the board reads no
 * pitot and no battery.
 * HA_SIL_RESET (same layout, every other field ignored) resets the HA as a watchdog or brown-out
 * reset resets the Due: the core, the INS adapter and the link device start afresh (the link
 * silent until the host asks for topics again), the board's retained words (ha_board.h) are kept,
 * and ha_app_restore takes them back. The pty, the clock and the SIL's own counts (bytes, commands)
 * go on. In lockstep it is answered with a reply without stepping. */
#ifndef HA_SIL_CHANNEL_H
#define HA_SIL_CHANNEL_H

#include <stdint.h>

#define HA_SIL_MAGIC_STEP 0x50545348u  /* "HSTP" */
#define HA_SIL_MAGIC_POLL 0x4C505348u  /* "HSPL" */
#define HA_SIL_MAGIC_REPLY 0x4C505248u /* "HRPL" */
#define HA_SIL_MAGIC_RESET 0x54535248u /* "HRST" */
#define HA_SIL_VERSION 1u

/* HaSilStep.flags */
#define HA_SIL_WAIT_COMMAND 1u /* wait for the HP command cmd_seq before stepping */
#define HA_SIL_AIRSPEED_OK 2u  /* the AMS5812 read succeeded (else the core gets -1) */
#define HA_SIL_BATTERY_OK 4u
#define HA_SIL_RC_VALID 8u /* every RC channel captured recently */
/* With HA_SIL_WAIT_COMMAND: cmd_seq counts the HP commands the link must have delivered since the
 * start, not a sequence number (a fault relay may repeat or replay sequence numbers). */
#define HA_SIL_WAIT_COUNT 16u

/* HaSilReply.flags */
#define HA_SIL_R_LINK_CONNECTED \
  1u /* the host negotiated topics: /pwm and /decision_status go out */
#define HA_SIL_R_COMMAND_TIMEOUT 2u /* the wait for cmd_seq ran out */
#define HA_SIL_R_VN_TIMEOUT 4u      /* the wait for vn_bytes ran out */
#define HA_SIL_R_STATE_VALID 8u     /* the INS state the core used was valid */
#define HA_SIL_R_HP_RESET 16u       /* the HP reset line is asserted */
#define HA_SIL_R_RESTART_REQUESTED 32u
#define HA_SIL_R_STEPPED 64u /* this reply follows a period of the core */
#define HA_SIL_R_HOME 128u   /* the HA's INS adapter has a home (latched, set or kept) */

/* Layout: "<IHHQQIIHHHHHHff" (52 bytes). */
typedef struct {
  uint32_t magic;
  uint16_t version;
  uint16_t flags;
  uint64_t t_us;           /* simulation time of this period */
  uint64_t vn_bytes;       /* VN-200 bytes written to the HA's port since the start */
  uint32_t cmd_seq;        /* with HA_SIL_WAIT_COMMAND: the HP command to wait for */
  uint32_t wait_ms;        /* bound on each wall-clock wait */
  uint16_t rc_pulse_us[5]; /* HA_RC_* order: throttle, elevator, aileron, rudder, PIC */
  uint16_t reserved;
  float airspeed_ftps; /* AMS5812 reading as the board layer converts it */
  float battery_v;
} HaSilStep;

/* Layout: "<IHHQ4f4fBBHIIIIfffIIIII" (100 bytes). */
typedef struct {
  uint32_t magic;
  uint16_t version;
  uint16_t flags;
  uint64_t t_us;       /* the period's clock: the step's (lockstep); the SIL's micros(), i.e.
                          CLOCK_MONOTONIC in us, 32 bits, wrapping (real time) */
  float applied[4];    /* at the servos: elevator, aileron, rudder (deg), throttle */
  float ha_command[4]; /* the safety controller's own, same order */
  uint8_t controller;  /* DecisionStatus.CONTROLLER_* */
  uint8_t leds;
  uint16_t restart_count;
  uint32_t reasons;
  uint32_t reasons_at_switch;
  uint32_t last_seq;
  uint32_t commands_received; /* HP commands the link delivered since start */
  float stable_for_s;
  float state_region_max;
  float actuator_region_max;
  uint32_t vn_bytes_read;
  uint32_t ins_solutions_used;
  uint32_t ins_solutions_rejected;
  uint32_t ins_bad_packets;
  uint32_t wait_us; /* wall time this period waited for its command and VN-200 bytes */
} HaSilReply;

#endif /* HA_SIL_CHANNEL_H */
