#include "ha_link.h"

#include <string.h>

/* rosserial's reserved topic ids (rosserial_msgs/TopicInfo constants). */
#define TOPIC_ID_PUBLISHER ((uint16_t)ROSSERIAL_MSGS_TOPICINFO_ID_PUBLISHER)
#define TOPIC_ID_SUBSCRIBER ((uint16_t)ROSSERIAL_MSGS_TOPICINFO_ID_SUBSCRIBER)
#define TOPIC_ID_PARAMETER_REQUEST ((uint16_t)ROSSERIAL_MSGS_TOPICINFO_ID_PARAMETER_REQUEST)
#define TOPIC_ID_LOG ((uint16_t)ROSSERIAL_MSGS_TOPICINFO_ID_LOG)
#define TOPIC_ID_TIME ((uint16_t)ROSSERIAL_MSGS_TOPICINFO_ID_TIME)
#define TOPIC_ID_TX_STOP ((uint16_t)ROSSERIAL_MSGS_TOPICINFO_ID_TX_STOP)

static const HaLinkTopic kTopics[HA_LINK_TOPIC_COUNT] = {
    {HA_LINK_TOPIC_PWM, true, "pwm", DRONE_ROS_PWM_TYPE, DRONE_ROS_PWM_MD5},
    {HA_LINK_TOPIC_DECISION_STATUS, true, "decision_status", DRONE_ROS_DECISIONSTATUS_TYPE,
     DRONE_ROS_DECISIONSTATUS_MD5},
    {HA_LINK_TOPIC_HOME, true, "home", DRONE_ROS_HOMEPOSITION_TYPE, DRONE_ROS_HOMEPOSITION_MD5},
    {HA_LINK_TOPIC_SERVO_OP, false, "servo_op", DRONE_ROS_SERVOCOMMAND_TYPE,
     DRONE_ROS_SERVOCOMMAND_MD5},
    {HA_LINK_TOPIC_OPERATOR_COMMAND, false, "operator_command", DRONE_ROS_OPERATORCOMMAND_TYPE,
     DRONE_ROS_OPERATORCOMMAND_MD5},
};

const HaLinkTopic *ha_link_topics(size_t *count) {
  *count = HA_LINK_TOPIC_COUNT;
  return kTopics;
}

void ha_link_init(HaLink *link, const HaLinkCallbacks *cb) {
  memset(link, 0, sizeof *link);
  ha_link_decoder_init(&link->decoder, HA_LINK_FRAME_TIMEOUT_US);
  link->cb = *cb;
}

static bool send_frame(HaLink *link, uint16_t topic_id, const uint8_t *payload, size_t len) {
  const size_t n = ha_link_encode_frame(topic_id, payload, len, link->tx, sizeof link->tx);
  if ((n == 0u) || (link->cb.write == NULL)) {
    link->counters.tx_dropped++;
    return false;
  }
  link->cb.write(link->cb.ctx, link->tx, n);
  return true;
}

static void request_time(HaLink *link, uint32_t now_us) {
  /* The request carries a zero Time, as ros_lib's does; the host only looks at the topic. */
  std_msgs_Time t;
  size_t n = 0u;
  memset(&t, 0, sizeof t);
  if (std_msgs_Time_serialize(&t, link->scratch, sizeof link->scratch, &n)) {
    (void)send_frame(link, TOPIC_ID_TIME, link->scratch, n);
  }
  link->last_sync_request_us = now_us;
  link->sync_request_sent_us = now_us;
}

static void negotiate_topics(HaLink *link, uint32_t now_us) {
  size_t i;
  for (i = 0u; i < HA_LINK_TOPIC_COUNT; ++i) {
    rosserial_msgs_TopicInfo info;
    size_t n = 0u;
    info.topic_id = kTopics[i].topic_id;
    info.topic_name = ha_ros_string(kTopics[i].name);
    info.message_type = ha_ros_string(kTopics[i].type);
    info.md5sum = ha_ros_string(kTopics[i].md5);
    info.buffer_size = (int32_t)HA_LINK_MAX_PAYLOAD;
    if (rosserial_msgs_TopicInfo_serialize(&info, link->scratch, sizeof link->scratch, &n)) {
      (void)send_frame(link, kTopics[i].is_publisher ? TOPIC_ID_PUBLISHER : TOPIC_ID_SUBSCRIBER,
                       link->scratch, n);
    } else {
      link->counters.tx_dropped++;
    }
  }
  link->counters.topic_requests++;
  link->configured = true;
  link->home_sent_seq = 0u;          /* a (re)connected host hears home at once */
  link->last_sync_reply_us = now_us; /* the host just spoke: give it a full sync window */
  request_time(link, now_us);
}

static uint64_t time_ns(HaRosTime t) { return (uint64_t)t.sec * 1000000000u + t.nsec; }

static void apply_time(HaLink *link, const std_msgs_Time *t, uint32_t now_us) {
  const HaRosTime before = ha_link_ros_time(link, now_us);
  /* The reply left the host about half a round trip ago. */
  const uint32_t half_rtt_us = (uint32_t)(now_us - link->sync_request_sent_us) / 2u;
  uint64_t nsec = (uint64_t)t->data.nsec + (uint64_t)half_rtt_us * 1000u;
  link->ros_at_sync.sec = t->data.sec + (uint32_t)(nsec / 1000000000u);
  link->ros_at_sync.nsec = (uint32_t)(nsec % 1000000000u);
  /* A host that answers late (a loaded one) sets the clock back by its lag, and stamps that run
   * backwards reorder every log of them: hold them at the last one until the clock passes it.
   * A bigger step is a new clock (a restarted simulation, a stepped host clock): follow it. */
  link->stamp_floor = (link->time_valid && time_ns(before) > time_ns(link->ros_at_sync) &&
                       time_ns(before) - time_ns(link->ros_at_sync) <= HA_LINK_HOLD_STEP_BACK_NS)
                          ? before
                          : link->ros_at_sync;
  link->sync_local_us = now_us;
  link->last_sync_reply_us = now_us;
  link->time_valid = true;
  link->counters.time_syncs++;
}

void ha_link_command_from_msg(const drone_ros_ServoCommand *msg, HaHpCommand *cmd) {
  cmd->seq = msg->seq;
  cmd->stamp_sec = msg->stamp.sec;
  cmd->stamp_nsec = msg->stamp.nsec;
  cmd->throttle = msg->throttle;
  cmd->elevator_deg = msg->elevator_deg;
  cmd->aileron_deg = msg->aileron_deg;
  cmd->rudder_deg = msg->rudder_deg;
  cmd->alpha_est_deg = msg->alpha_est_deg;
  cmd->beta_est_deg = msg->beta_est_deg;
  cmd->estimator_converged = msg->estimator_converged;
  cmd->sensor_links_healthy = msg->sensor_links_healthy;
  cmd->crc32 = msg->crc32;
}

/* One handler per topic the device takes; each counts what it cannot take as a bad payload. */
static void on_time_frame(HaLink *link, const HaLinkFrame *frame, uint32_t now_us) {
  size_t used = 0u;
  std_msgs_Time t;
  memset(&t, 0, sizeof t); /* every local starts defined: EVA then needs no path reasoning */
  if (std_msgs_Time_deserialize(&t, frame->payload, frame->payload_len, &used) &&
      (used == frame->payload_len) && (t.data.nsec < 1000000000u)) {
    apply_time(link, &t, now_us);
  } else {
    link->counters.bad_payload++;
  }
}

static void on_param_frame(HaLink *link, const HaLinkFrame *frame) {
  size_t used = 0u;
  rosserial_msgs_RequestParamResponse reply;
  memset(&reply, 0, sizeof reply);
  if (rosserial_msgs_RequestParamResponse_deserialize(&reply, frame->payload, frame->payload_len,
                                                      &used) &&
      (used == frame->payload_len)) {
    link->counters.param_replies++;
    if (link->cb.on_param != NULL) {
      link->cb.on_param(link->cb.ctx, &reply);
    }
  } else {
    link->counters.bad_payload++;
  }
}

static void on_servo_op_frame(HaLink *link, const HaLinkFrame *frame, uint32_t now_us) {
  size_t used = 0u;
  drone_ros_ServoCommand msg;
  HaHpCommand cmd;
  memset(&msg, 0, sizeof msg);
  memset(&cmd, 0, sizeof cmd);
  if (drone_ros_ServoCommand_deserialize(&msg, frame->payload, frame->payload_len, &used) &&
      (used == frame->payload_len)) {
    ha_link_command_from_msg(&msg, &cmd);
    link->counters.commands++;
    if (link->cb.on_command != NULL) {
      link->cb.on_command(link->cb.ctx, &cmd, now_us);
    }
  } else {
    link->counters.bad_payload++;
  }
}

static void on_operator_frame(HaLink *link, const HaLinkFrame *frame, uint32_t now_us) {
  size_t used = 0u;
  drone_ros_OperatorCommand msg;
  memset(&msg, 0, sizeof msg);
  if (!drone_ros_OperatorCommand_deserialize(&msg, frame->payload, frame->payload_len, &used) ||
      (used != frame->payload_len) || (frame->payload_len != HA_OPERATOR_COMMAND_FIELDS_LEN + 4u)) {
    link->counters.bad_payload++;
  } else if (ha_crc32(frame->payload, HA_OPERATOR_COMMAND_FIELDS_LEN) != msg.crc32) {
    /* rosserial's 8-bit sum misses a +1/-1 byte pair: SELECT_HA read as SELECT_HP, a home
     * moved by hundreds of metres. A request is acted on only whole, as its sender made it. */
    link->counters.operator_bad_crc++;
  } else {
    link->counters.operator_commands++;
    if (link->cb.on_operator != NULL) {
      link->cb.on_operator(link->cb.ctx, &msg, now_us);
    }
  }
}

static void dispatch(HaLink *link, const HaLinkFrame *frame, uint32_t now_us) {
  if (frame->payload_len > HA_LINK_MAX_PAYLOAD) {
    /* The decoder never delivers this; the check makes the bound local, for EVA and readers. */
    link->counters.bad_payload++;
    return;
  }
  switch (frame->topic_id) {
    case TOPIC_ID_PUBLISHER: /* topic request: the host asks for our topics (empty payload) */
      if (frame->payload_len == 0u) {
        negotiate_topics(link, now_us);
      } else {
        link->counters.bad_payload++;
      }
      break;
    case TOPIC_ID_TIME:
      on_time_frame(link, frame, now_us);
      break;
    case TOPIC_ID_TX_STOP:
      link->configured = false;
      link->counters.tx_stops++;
      break;
    case TOPIC_ID_PARAMETER_REQUEST:
      on_param_frame(link, frame);
      break;
    case HA_LINK_TOPIC_SERVO_OP:
      on_servo_op_frame(link, frame, now_us);
      break;
    case HA_LINK_TOPIC_OPERATOR_COMMAND:
      on_operator_frame(link, frame, now_us);
      break;
    default:
      link->counters.unknown_topic++;
      break;
  }
}

void ha_link_receive(HaLink *link, const uint8_t *bytes, size_t len, uint32_t now_us) {
  size_t i;
  for (i = 0u; i < len; ++i) {
    HaLinkFrame frame;
    /* The decoder only ever points into its own buffer; start there rather than at NULL. */
    frame.topic_id = 0u;
    frame.payload = link->decoder.payload;
    frame.payload_len = 0u;
    ha_link_decoder_push(&link->decoder, bytes[i], now_us);
    /* One byte can complete several frames: those a failed frame had taken in. */
    while (ha_link_decoder_next(&link->decoder, &frame)) {
      dispatch(link, &frame, now_us);
    }
  }
}

void ha_link_poll(HaLink *link, uint32_t now_us) {
  ha_link_decoder_poll(&link->decoder, now_us);
  if (!link->configured) {
    return;
  }
  if ((uint32_t)(now_us - link->last_sync_reply_us) > HA_LINK_SYNC_LOST_US) {
    /* The host stopped answering: stop publishing until it asks for topics again. */
    link->configured = false;
    link->counters.sync_losses++;
    return;
  }
  if ((uint32_t)(now_us - link->last_sync_request_us) >= HA_LINK_SYNC_PERIOD_US) {
    request_time(link, now_us);
  }
}

bool ha_link_connected(const HaLink *link) { return link->configured; }

HaRosTime ha_link_ros_time(const HaLink *link, uint32_t now_us) {
  HaRosTime t = {0u, 0u};
  if (link->time_valid) {
    const uint64_t elapsed_us = (uint32_t)(now_us - link->sync_local_us);
    const uint64_t nsec = (uint64_t)link->ros_at_sync.nsec + elapsed_us * 1000u;
    t.sec = link->ros_at_sync.sec + (uint32_t)(nsec / 1000000000u);
    t.nsec = (uint32_t)(nsec % 1000000000u);
    if (time_ns(link->stamp_floor) > time_ns(t)) t = link->stamp_floor;
  }
  return t;
}

static bool publish_scratch(HaLink *link, uint16_t topic_id, bool ok, size_t n) {
  if (!ok || !link->configured) {
    link->counters.tx_dropped++;
    return false;
  }
  return send_frame(link, topic_id, link->scratch, n);
}

bool ha_link_publish_pwm(HaLink *link, const drone_ros_pwm *msg) {
  size_t n = 0u;
  const bool ok = drone_ros_pwm_serialize(msg, link->scratch, sizeof link->scratch, &n);
  return publish_scratch(link, HA_LINK_TOPIC_PWM, ok, n);
}

bool ha_link_publish_decision_status(HaLink *link, const drone_ros_DecisionStatus *msg) {
  size_t n = 0u;
  const bool ok = drone_ros_DecisionStatus_serialize(msg, link->scratch, sizeof link->scratch, &n);
  return publish_scratch(link, HA_LINK_TOPIC_DECISION_STATUS, ok, n);
}

bool ha_link_publish_home(HaLink *link, const drone_ros_HomePosition *msg) {
  size_t n = 0u;
  const bool ok = drone_ros_HomePosition_serialize(msg, link->scratch, sizeof link->scratch, &n);
  return publish_scratch(link, HA_LINK_TOPIC_HOME, ok, n);
}

bool ha_link_offer_home(HaLink *link, const drone_ros_HomePosition *msg, uint32_t now_us) {
  if (msg->seq == 0u || !link->configured ||
      (msg->seq == link->home_sent_seq && now_us - link->home_sent_us < HA_LINK_HOME_REPEAT_US)) {
    return false;
  }
  if (!ha_link_publish_home(link, msg)) {
    return false;
  }
  link->home_sent_seq = msg->seq;
  link->home_sent_us = now_us;
  return true;
}

bool ha_link_log(HaLink *link, uint8_t level, const char *text) {
  rosserial_msgs_Log log;
  size_t n = 0u;
  bool ok;
  log.level = level;
  log.msg = ha_ros_string(text);
  ok = rosserial_msgs_Log_serialize(&log, link->scratch, sizeof link->scratch, &n);
  return publish_scratch(link, TOPIC_ID_LOG, ok, n);
}

bool ha_link_request_param(HaLink *link, const char *name) {
  rosserial_msgs_RequestParamRequest req;
  size_t n = 0u;
  bool ok;
  req.name = ha_ros_string(name);
  ok = rosserial_msgs_RequestParamRequest_serialize(&req, link->scratch, sizeof link->scratch, &n);
  return publish_scratch(link, TOPIC_ID_PARAMETER_REQUEST, ok, n);
}
