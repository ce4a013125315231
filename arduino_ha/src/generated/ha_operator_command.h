/* Generated from msg/OperatorCommand.msg by tools/gen_decision_status.py: edit the
 * message, then run `make due-sketch-msgs`. */
#ifndef HA_OPERATOR_COMMAND_H
#define HA_OPERATOR_COMMAND_H

/* the operator's request (OperatorCommand.command) */
enum {
  HA_OP_NONE = 0,
  HA_OP_SELECT_HP = 1,
  HA_OP_SELECT_HA = 2,
  HA_OP_RESTART_HP = 3,
  HA_OP_SELF_TEST = 4,
  HA_OP_SET_HOME = 5
};

#endif
