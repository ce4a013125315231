/* Commands that configure the VN-200, as complete ASCII sentences with checksum and "\r\n".
 * VN-200 User Manual: "Write Register" command ($VNWRG), "Read Register" ($VNRRG); registers
 * 5 (Serial Baud Rate), 6 (Async Data Output Type) and 75-77 (Binary Output 1-3: AsyncMode,
 * RateDivisor, OutputGroup, then one GroupField per selected group, in hex).
 * Builders write into a caller buffer and return the sentence length, or 0 (buffer untouched
 * beyond cap) when an argument is outside what the sensor accepts: a command the sensor would
 * refuse is never put on the wire. */
#ifndef VN_COMMAND_H
#define VN_COMMAND_H

#include <stddef.h>
#include <stdint.h>

#include "vn_binary.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VN_CMD_MAX 96u /* longest sentence these builders produce, with margin */
#define VN_REG_BAUD_RATE 5u
#define VN_REG_ASYNC_TYPE 6u
#define VN_REG_BINARY_OUTPUT_1 75u
#define VN_REG_MODEL 1u
/* The IMU rate the binary output divisor divides (manual, Binary Output register RateDivisor). */
#define VN_BINARY_BASE_RATE_HZ 800u

typedef enum { VN_CK_XOR8 = 0, VN_CK_CRC16 = 1 } VnChecksumMode;

/* AsyncMode of a binary output register: which serial port(s) the packets go to. */
typedef enum {
  VN_ASYNC_NONE = 0,
  VN_ASYNC_PORT1 = 1,
  VN_ASYNC_PORT2 = 2,
  VN_ASYNC_BOTH = 3
} VnAsyncMode;

typedef struct {
  uint8_t output;                     /* 1..3: register 75, 76 or 77 */
  uint8_t async_mode;                 /* VnAsyncMode */
  uint16_t rate_divisor;              /* output rate = 800 Hz / divisor, 1..65535 */
  uint8_t groups;                     /* VN_GROUP_* */
  uint16_t masks[VN_BIN_GROUP_COUNT]; /* by group index; must be 0 for absent groups */
} VnBinaryOutputConfig;

size_t vn_cmd_read_register(char *buf, size_t cap, unsigned reg, VnChecksumMode ck);
/* Register 6 = 0: stop the ASCII async stream so only requested packets share the port. */
size_t vn_cmd_async_off(char *buf, size_t cap, VnChecksumMode ck);
/* Register 5 on the port the command arrives on. Only the manual's baud rates are accepted. */
size_t vn_cmd_set_baud(char *buf, size_t cap, uint32_t baud, VnChecksumMode ck);
int vn_baud_supported(uint32_t baud);
size_t vn_cmd_binary_output(char *buf, size_t cap, const VnBinaryOutputConfig *cfg,
                            VnChecksumMode ck);
/* Payload length in bytes (sync to CRC) of the packets a configuration produces; 0 if invalid. */
size_t vn_binary_output_packet_len(const VnBinaryOutputConfig *cfg);

#ifdef __cplusplus
}
#endif
#endif
