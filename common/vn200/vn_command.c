#include "vn_command.h"

#include "vn_checksum.h"

typedef struct {
  char *buf;
  size_t cap;
  size_t len;
  int ok;
} Writer;

static void put_char(Writer *w, char c) {
  if (!w->ok || w->len >= w->cap) {
    w->ok = 0;
    return;
  }
  w->buf[w->len] = c;
  ++w->len;
}

static void put_str(Writer *w, const char *s) {
  size_t i;
  for (i = 0u; s[i] != '\0' && i < VN_CMD_MAX; ++i) {
    put_char(w, s[i]);
  }
}

static void put_dec(Writer *w, uint32_t v, unsigned min_digits) {
  char tmp[10] = {0};
  unsigned n = 0u;
  do {
    tmp[n] = (char)('0' + (v % 10u));
    v /= 10u;
    ++n;
  } while (v != 0u && n < sizeof tmp);
  while (n < min_digits && n < sizeof tmp) {
    tmp[n] = '0';
    ++n;
  }
  while (n > 0u) {
    --n;
    put_char(w, tmp[n]);
  }
}

static void put_hex(Writer *w, uint32_t v, unsigned digits) {
  static const char k_hex[] = "0123456789ABCDEF";
  unsigned i;
  for (i = digits; i > 0u; --i) {
    put_char(w, k_hex[(v >> (4u * (i - 1u))) & 0xFu]);
  }
}

/* Appends "*<checksum>\r\n" over the characters after '$'. */
static size_t finish(Writer *w, VnChecksumMode ck) {
  if (!w->ok || w->len < 2u) {
    return 0u;
  }
  if (ck == VN_CK_CRC16) {
    uint16_t crc = vn_crc16((const uint8_t *)(w->buf + 1), w->len - 1u);
    put_char(w, '*');
    put_hex(w, crc, 4u);
  } else {
    uint8_t x = vn_xor8((const uint8_t *)(w->buf + 1), w->len - 1u);
    put_char(w, '*');
    put_hex(w, x, 2u);
  }
  put_str(w, "\r\n");
  return w->ok ? w->len : 0u;
}

static int start(Writer *w, char *buf, size_t cap, VnChecksumMode ck) {
  w->buf = buf;
  w->cap = cap;
  w->len = 0u;
  w->ok = buf != NULL && (ck == VN_CK_XOR8 || ck == VN_CK_CRC16);
  return w->ok;
}

size_t vn_cmd_read_register(char *buf, size_t cap, unsigned reg, VnChecksumMode ck) {
  Writer w;
  if (!start(&w, buf, cap, ck) || reg > 255u) {
    return 0u;
  }
  put_str(&w, "$VNRRG,");
  put_dec(&w, reg, 2u);
  return finish(&w, ck);
}

size_t vn_cmd_async_off(char *buf, size_t cap, VnChecksumMode ck) {
  Writer w;
  if (!start(&w, buf, cap, ck)) {
    return 0u;
  }
  put_str(&w, "$VNWRG,06,0");
  return finish(&w, ck);
}

int vn_baud_supported(uint32_t baud) {
  static const uint32_t k_bauds[] = {9600u,   19200u,  38400u,  57600u, 115200u,
                                     128000u, 230400u, 460800u, 921600u};
  size_t i;
  for (i = 0u; i < sizeof k_bauds / sizeof k_bauds[0]; ++i) {
    if (k_bauds[i] == baud) {
      return 1;
    }
  }
  return 0;
}

size_t vn_cmd_set_baud(char *buf, size_t cap, uint32_t baud, VnChecksumMode ck) {
  Writer w;
  if (!start(&w, buf, cap, ck) || !vn_baud_supported(baud)) {
    return 0u;
  }
  put_str(&w, "$VNWRG,05,");
  put_dec(&w, baud, 1u);
  return finish(&w, ck);
}

size_t vn_binary_output_packet_len(const VnBinaryOutputConfig *cfg) {
  uint16_t masks[VN_BIN_GROUP_COUNT] = {0u, 0u, 0u, 0u, 0u, 0u};
  size_t n = 0u;
  unsigned g;
  if (cfg == NULL) {
    return 0u;
  }
  for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
    if ((cfg->groups & (1u << g)) != 0u) {
      if (cfg->masks[g] == 0u) {
        return 0u; /* a selected group with no field is a configuration mistake */
      }
      masks[n] = cfg->masks[g];
      ++n;
    } else if (cfg->masks[g] != 0u) {
      return 0u;
    }
  }
  return vn_bin_packet_len(cfg->groups, masks, n);
}

size_t vn_cmd_binary_output(char *buf, size_t cap, const VnBinaryOutputConfig *cfg,
                            VnChecksumMode ck) {
  Writer w;
  unsigned g;
  if (!start(&w, buf, cap, ck) || cfg == NULL || cfg->output < 1u || cfg->output > 3u ||
      cfg->async_mode > (uint8_t)VN_ASYNC_BOTH || cfg->rate_divisor == 0u ||
      vn_binary_output_packet_len(cfg) == 0u) {
    return 0u;
  }
  put_str(&w, "$VNWRG,");
  put_dec(&w, VN_REG_BINARY_OUTPUT_1 - 1u + cfg->output, 2u);
  put_char(&w, ',');
  put_dec(&w, cfg->async_mode, 1u);
  put_char(&w, ',');
  put_dec(&w, cfg->rate_divisor, 1u);
  put_char(&w, ',');
  put_hex(&w, cfg->groups, 2u);
  for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
    if ((cfg->groups & (1u << g)) != 0u) {
      put_char(&w, ',');
      put_hex(&w, cfg->masks[g], 4u);
    }
  }
  return finish(&w, ck);
}
