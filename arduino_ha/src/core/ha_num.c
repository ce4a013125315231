#include "ha_num.h"

float ha_clampf(float v, float lo, float hi) {
  const int32_t key = ha_order_key(v);
  if (key > HA_KEY_INF || key < -HA_KEY_INF) {
    return lo > 0.0f ? lo : (hi < 0.0f ? hi : 0.0f); /* NaN: rare, so float compares */
  }
  if (key < ha_order_key(lo)) {
    return lo;
  }
  return key > ha_order_key(hi) ? hi : v;
}
