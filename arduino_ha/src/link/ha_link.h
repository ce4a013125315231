/* The Due's end of the HA-HP rosserial link: topic negotiation, time sync, logs, parameter
 * requests, publishing the HA's sensors and decisions, and decoding the HP's commands into the
 * core's plain structs. The link judges nothing about an HP command: the HA core checks its CRC,
 * freshness and order; the link only hands it over with its arrival time. An operator request
 * is checked here, before any board sees it: one whose CRC-32 does not match is counted and
 * dropped, never handed over (SET_HOME goes to the INS adapter, not the core).
 * C99, no heap, no recursion, bounded buffers, time passed in (the core's free-running
 * microsecond clock, wrapping). */
#ifndef HA_LINK_H
#define HA_LINK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "ha_link_frame.h"
#include "ha_link_msgs.h"
#include "hp_command.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Topic ids as stock rosserial_arduino assigns them: subscribers from 100, publishers after
 * room for 25 subscribers (ros_lib's MAX_SUBSCRIBERS), so captures read the same. */
#define HA_LINK_TOPIC_SERVO_OP 100u
#define HA_LINK_TOPIC_OPERATOR_COMMAND 101u
#define HA_LINK_TOPIC_PWM 125u
#define HA_LINK_TOPIC_DECISION_STATUS 126u
#define HA_LINK_TOPIC_HOME 127u
#define HA_LINK_TOPIC_COUNT 5u

/* How often the device asks the host for the time, and how long without an answer before it
 * considers the host gone and stops publishing until the host asks for topics again. */
#define HA_LINK_SYNC_PERIOD_US 500000u
/* Home is repeated this often while latched, so a restarted host hears it within a few seconds. */
#define HA_LINK_HOME_REPEAT_US 2000000u
#define HA_LINK_SYNC_LOST_US 1500000u
/* A time sync that sets the clock back by at most this holds the stamps still instead. */
#define HA_LINK_HOLD_STEP_BACK_NS 1000000000u
/* A frame taking longer than this from its sync byte is dropped (at 115200 baud, 256 bytes
 * take 22 ms; the clock is in microseconds like the core's). */
#define HA_LINK_FRAME_TIMEOUT_US 50000u
#define HA_LINK_TX_MAX (HA_LINK_MAX_PAYLOAD + HA_LINK_FRAME_OVERHEAD)

typedef struct {
  uint16_t topic_id;
  bool is_publisher;
  const char *name;
  const char *type;
  const char *md5;
} HaLinkTopic;

typedef struct {
  uint32_t topic_requests;    /* host's topic requests answered */
  uint32_t time_syncs;        /* time replies applied */
  uint32_t commands;          /* ServoCommand payloads decoded and handed to the core */
  uint32_t operator_commands; /* operator requests with a matching CRC, handed over */
  uint32_t operator_bad_crc;  /* operator requests dropped: their CRC-32 does not match */
  uint32_t param_replies;
  uint32_t unknown_topic; /* valid frame on a topic id the device does not know */
  uint32_t bad_payload;   /* valid frame whose payload does not decode as its type */
  uint32_t tx_dropped;    /* a message that could not be sent (too big, or not connected) */
  uint32_t tx_stops;      /* host said it is going away */
  uint32_t sync_losses;   /* the host stopped answering time requests */
} HaLinkCounters;

typedef void (*HaLinkWriteFn)(void *ctx, const uint8_t *bytes, size_t len);
typedef void (*HaLinkCommandFn)(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us);
typedef void (*HaLinkOperatorFn)(void *ctx, const drone_ros_OperatorCommand *cmd,
                                 uint32_t arrival_us);
typedef void (*HaLinkParamFn)(void *ctx, const rosserial_msgs_RequestParamResponse *reply);

typedef struct {
  HaLinkWriteFn write;
  HaLinkCommandFn on_command;
  HaLinkOperatorFn on_operator; /* may be NULL */
  HaLinkParamFn on_param;       /* may be NULL */
  void *ctx;
} HaLinkCallbacks;

typedef struct {
  HaLinkDecoder decoder;
  HaLinkCallbacks cb;
  bool configured; /* the host asked for topics and answers time requests */
  bool time_valid; /* at least one time sync since boot */
  uint32_t last_sync_request_us;
  uint32_t last_sync_reply_us;
  uint32_t sync_request_sent_us;
  HaRosTime ros_at_sync; /* host time at sync_local_us */
  HaRosTime stamp_floor; /* no stamp earlier than this: the clock before a small step back */
  uint32_t sync_local_us;
  HaLinkCounters counters;
  uint32_t home_sent_seq; /* the home last sent (0: none since the last negotiation) */
  uint32_t home_sent_us;
  uint8_t tx[HA_LINK_TX_MAX];
  uint8_t scratch[HA_LINK_MAX_PAYLOAD];
} HaLink;

/* The device's topics, in the order they are announced. */
const HaLinkTopic *ha_link_topics(size_t *count);

void ha_link_init(HaLink *link, const HaLinkCallbacks *cb);

/* Feeds received bytes; completed frames are dispatched before this returns. Across all calls
 * now_us must never run backwards (it may wrap). */
void ha_link_receive(HaLink *link, const uint8_t *bytes, size_t len, uint32_t now_us);

/* Call every loop: drops stale partial frames, keeps time sync going, notices a silent host. */
void ha_link_poll(HaLink *link, uint32_t now_us);

bool ha_link_connected(const HaLink *link);

/* Host (ROS) time now, from the last sync; {0, 0} before the first. It never runs backwards
 * by up to HA_LINK_HOLD_STEP_BACK_NS across a sync. */
HaRosTime ha_link_ros_time(const HaLink *link, uint32_t now_us);

/* Publishing works only while connected (as in ros_lib); false when dropped. */
bool ha_link_publish_pwm(HaLink *link, const drone_ros_pwm *msg);
bool ha_link_publish_decision_status(HaLink *link, const drone_ros_DecisionStatus *msg);
/* Home (topic "home"): sent when it changes and every HA_LINK_HOME_REPEAT_US, never every period
 * (28 bytes a time: the link's budget goes to pwm and decision_status). */
bool ha_link_publish_home(HaLink *link, const drone_ros_HomePosition *msg);
/* Calls ha_link_publish_home when msg->seq (0: no home yet, nothing sent) differs from the home
 * last sent since the host negotiated, or HA_LINK_HOME_REPEAT_US after it. Call every period. */
bool ha_link_offer_home(HaLink *link, const drone_ros_HomePosition *msg, uint32_t now_us);

/* level: ROSSERIAL_MSGS_LOG_* ; the host forwards it to rosout. */
bool ha_link_log(HaLink *link, uint8_t level, const char *text);

/* Asks the host for a parameter; the answer comes through on_param. */
bool ha_link_request_param(HaLink *link, const char *name);

/* The ServoCommand on the wire, as the core's struct (field by field, the CRC untouched). */
void ha_link_command_from_msg(const drone_ros_ServoCommand *msg, HaHpCommand *cmd);

#ifdef __cplusplus
}
#endif

#endif /* HA_LINK_H */
