/* The VN-200 model's navigation-filter errors (hil/sensors.py, InsSolutionErrors): nine
 * first-order Gauss-Markov processes stepped on an 800 Hz grid, 72 unit normals per 100 Hz
 * simulator step (0.144 s of CPU a 4,000-step flight in Python, 0.033 s here: a cProfile had put
 * it at a quarter of the simulator's CPU, an artefact of its per-call cost), the same numbers to
 * the bit, so a seed flies the flight it flew before:
 *  - the uniforms are CPython's random.random(): Mersenne Twister MT19937 (Matsumoto and
 *    Nishimura, 1998) from the state random.Random.getstate() hands over, 53 bits from two words;
 *  - the normals are random.gauss()'s Box-Muller pairs, the second of a pair kept for the next
 *    draw, through the C library's cos, sin, log and sqrt (which Python's math module calls);
 *  - x' = a x + k z in doubles, each product rounded (the build keeps the compiler from fusing
 *    them, -ffp-contract=off, and from merging a pair's cos and sin into one sincos call).
 * Host-only simulator code, loaded by ctypes: the caller owns the state's memory. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define MT_N 624
#define MT_M 397
#define INS_CHANNELS 9
#define INS_KEEP 4096 /* grid steps remembered: far more than one step's packets on either port */

typedef struct {
  uint32_t mt[MT_N];
  int32_t mti; /* the next word of mt to hand out; MT_N: regenerate first */
  int32_t has_cached;
  double cached; /* the second normal of the last Box-Muller pair */
  double a[INS_CHANNELS];
  double k[INS_CHANNELS];
  double x[INS_CHANNELS];
  int64_t index; /* grid index of the newest value */
  double ring[INS_KEEP][INS_CHANNELS];
} InsNoise;

size_t ins_noise_size(void) { return sizeof(InsNoise); }
int ins_noise_keep(void) { return INS_KEEP; }

static uint32_t mt_next(InsNoise *s) {
  if (s->mti >= MT_N) {
    /* Each word from the pair at i, i + 1 and the word M ahead; past the end those are the
     * words this pass already renewed, as the generator's definition has it. */
    for (int i = 0; i < MT_N; i++) {
      uint32_t y = (s->mt[i] & 0x80000000u) | (s->mt[(i + 1) % MT_N] & 0x7fffffffu);
      s->mt[i] = s->mt[(i + MT_M) % MT_N] ^ (y >> 1) ^ ((y & 1u) ? 0x9908b0dfu : 0u);
    }
    s->mti = 0;
  }
  uint32_t y = s->mt[s->mti++];
  y ^= y >> 11;
  y ^= (y << 7) & 0x9d2c5680u;
  y ^= (y << 15) & 0xefc60000u;
  y ^= y >> 18;
  return y;
}

static double uniform(InsNoise *s) {
  uint32_t hi = mt_next(s) >> 5;
  uint32_t lo = mt_next(s) >> 6;
  return (hi * 67108864.0 + lo) * (1.0 / 9007199254740992.0);
}

static double unit_normal(InsNoise *s) {
  double z;
  if (s->has_cached) {
    z = s->cached;
    s->has_cached = 0;
  } else {
    double x2pi = uniform(s) * (2.0 * 3.141592653589793);
    double g2rad = sqrt(-2.0 * log(1.0 - uniform(s)));
    z = cos(x2pi) * g2rad;
    s->cached = sin(x2pi) * g2rad;
    s->has_cached = 1;
  }
  return 0.0 + z; /* gauss(0.0, 1.0) is 0.0 + z * 1.0: a -0.0 comes out as 0.0 */
}

static size_t slot(int64_t index) { return (size_t)(((index % INS_KEEP) + INS_KEEP) % INS_KEEP); }

/* 0 when the generator's state is not one getstate() gives (its position past the end). */
int ins_noise_init(InsNoise *s, const uint32_t *mt, int32_t mti, int32_t has_cached, double cached,
                   const double *a, const double *k, const double *x) {
  if (mti < 0 || mti > MT_N) return 0;
  memset(s, 0, sizeof *s);
  memcpy(s->mt, mt, sizeof s->mt);
  s->mti = mti;
  s->has_cached = has_cached != 0;
  s->cached = cached;
  memcpy(s->a, a, sizeof s->a);
  memcpy(s->k, k, sizeof s->k);
  memcpy(s->x, x, sizeof s->x);
  return 1;
}

/* The grid starts at index with the processes' initial values. */
void ins_noise_start(InsNoise *s, int64_t index) {
  s->index = index;
  memcpy(s->ring[slot(index)], s->x, sizeof s->x);
}

void ins_noise_draw_to(InsNoise *s, int64_t index) {
  while (s->index < index) {
    double z[INS_CHANNELS];
    for (int i = 0; i < INS_CHANNELS; i++) z[i] = unit_normal(s);
    for (int i = 0; i < INS_CHANNELS; i++) s->x[i] = s->a[i] * s->x[i] + s->k[i] * z[i];
    s->index++;
    memcpy(s->ring[slot(s->index)], s->x, sizeof s->x);
  }
}

/* The values at a grid index among the last INS_KEEP drawn; 0 (and out untouched) for one not
 * drawn yet or no longer kept. */
int ins_noise_at(const InsNoise *s, int64_t index, double *out) {
  if (index > s->index || index <= s->index - INS_KEEP) return 0;
  memcpy(out, s->ring[slot(index)], sizeof s->x);
  return 1;
}

/* The next n unit normals (for the test that holds them to random.gauss). */
void ins_noise_normals(InsNoise *s, size_t n, double *out) {
  for (size_t i = 0; i < n; i++) out[i] = unit_normal(s);
}

/* The generator's state back (getstate()'s words and position, and the kept normal). */
void ins_noise_state(const InsNoise *s, uint32_t *mt, int32_t *mti, int32_t *has_cached,
                     double *cached) {
  memcpy(mt, s->mt, sizeof s->mt);
  *mti = s->mti;
  *has_cached = s->has_cached;
  *cached = s->cached;
}
