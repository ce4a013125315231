/* VN-200 ASCII protocol: checksums and sentence decoding.
 * VN-200 User Manual, serial "ASCII" chapter: "$" header "," fields "*" checksum "\r\n". The
 * checksum is two hex digits (8-bit XOR of the characters between '$' and '*') or four (CRC-16,
 * see vn_checksum.h); the literal "XX" tells the sensor to skip the check and the sensor never
 * sends it, but we accept it for sentences typed by hand or replayed from a test. Register
 * responses echo the register id then its fields; errors come back as "$VNERR,<hex code>". */
#ifndef VN_ASCII_H
#define VN_ASCII_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VN_ASCII_MAX_FIELDS 32u

/* 1 when the sentence s[0..len) (with or without its trailing "\r\n") starts with '$' and its
 * checksum is valid or the "XX" bypass; else 0. */
int vn_ascii_checksum_ok(const char *s, size_t len);

typedef enum {
  VN_ASCII_UNKNOWN = 0, /* well formed but a header this driver does not decode */
  VN_ASCII_YPR,         /* $VNYPR: yaw, pitch, roll [deg] */
  VN_ASCII_INS_LLA,     /* $VNINS: INS solution, LLA */
  VN_ASCII_READ_REG,    /* $VNRRG response */
  VN_ASCII_WRITE_REG,   /* $VNWRG response (echo of the written values) */
  VN_ASCII_ERROR        /* $VNERR */
} VnAsciiKind;

/* Sensor error codes (manual, "Error Codes"). */
typedef enum {
  VN_ERR_HARD_FAULT = 1,
  VN_ERR_SERIAL_BUFFER_OVERFLOW = 2,
  VN_ERR_INVALID_CHECKSUM = 3,
  VN_ERR_INVALID_COMMAND = 4,
  VN_ERR_NOT_ENOUGH_PARAMETERS = 5,
  VN_ERR_TOO_MANY_PARAMETERS = 6,
  VN_ERR_INVALID_PARAMETER = 7,
  VN_ERR_INVALID_REGISTER = 8,
  VN_ERR_UNAUTHORIZED_ACCESS = 9,
  VN_ERR_WATCHDOG_RESET = 10,
  VN_ERR_OUTPUT_BUFFER_OVERFLOW = 11,
  VN_ERR_INSUFFICIENT_BAUD_RATE = 12,
  VN_ERR_ERROR_BUFFER_OVERFLOW = 255
} VnSensorError;

typedef struct {
  double tow_s;
  uint16_t week;
  uint16_t ins_status;
  float ypr_deg[3];
  double lat_deg, lon_deg, alt_m;
  float vel_ned_mps[3];
  float att_unc_deg;
  float pos_unc_m;
  float vel_unc_mps;
} VnAsciiIns;

typedef struct {
  VnAsciiKind kind;
  char header[8];                          /* e.g. "VNYPR", NUL terminated */
  uint16_t len;                            /* sentence length without CR LF; fields lie below it */
  uint8_t field_count;                     /* fields after the header */
  uint16_t field_off[VN_ASCII_MAX_FIELDS]; /* offsets into the parsed sentence */
  uint8_t field_len[VN_ASCII_MAX_FIELDS];
  uint16_t reg_id;    /* READ_REG / WRITE_REG */
  uint8_t error_code; /* ERROR */
  float ypr_deg[3];   /* YPR */
  VnAsciiIns ins;     /* INS_LLA */
} VnAsciiMsg;

typedef enum {
  VN_ASCII_OK = 0,
  VN_ASCII_ERR_NULL,
  VN_ASCII_ERR_FORMAT, /* no '$', no '*', bad characters, too many fields */
  VN_ASCII_ERR_CHECKSUM,
  VN_ASCII_ERR_FIELDS /* known header, wrong field count or a field that does not parse */
} VnAsciiResult;

/* Parses one sentence s[0..len) (trailing "\r\n" optional). `out` is fully written. */
VnAsciiResult vn_ascii_parse(const char *s, size_t len, VnAsciiMsg *out);

/* Field accessors over a parsed sentence; return 1 on success. */
int vn_ascii_field_u32(const char *s, const VnAsciiMsg *m, unsigned idx, unsigned base,
                       uint32_t *out);
int vn_ascii_field_f64(const char *s, const VnAsciiMsg *m, unsigned idx, double *out);

/* Number parsers over exactly s[0..len): no locale, no NUL needed, every character checked. */
int vn_parse_u32(const char *s, size_t len, unsigned base, uint32_t *out);
int vn_parse_f64(const char *s, size_t len, double *out);

#ifdef __cplusplus
}
#endif
#endif
