/* CAN messages in C on the host: codeword's generated encoders and decoders of
 * examples/can_mixed.yaml against cantools' generated C for examples/can_mixed.dbc
 * (`can_mixed.c`, generated at bench time), on the same values and the same data.
 * codeword's frame holds the identifier and the data length (5 bytes) before the 8
 * bytes of data that cantools packs; each side checks what it checks (codeword every
 * value's range and the frame's constants, cantools nothing).
 *
 * Usage: can_bench ROUNDS. Prints "<message> <side> <op>\t<ns per call>" lines, each the
 * median of ROUNDS timed batches taken in turn, so that the machine's other work falls on
 * both sides alike; and "<message> agree\t1" when both sides wrote the same data. */
#define _POSIX_C_SOURCE 199309L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "can_mixed.h"   /* codeword: generated/examples/c */
#include "cantools_can_mixed.h"

#define CALLS 200000L
#define MAX_ROUNDS 64

static volatile int sink;

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int compare(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef void (*batch_fn)(void);

static uint8_t frame[13];  /* codeword: identifier, length, data */
static uint8_t data[8];    /* cantools: data */
static can_mixed_steering_t cw_steering;
static struct cantools_can_mixed_steering_t ct_steering;
static can_mixed_extended_t cw_extended;
static struct cantools_can_mixed_extended_t ct_extended;

/* codeword's header functions are inline: each is called through a function of its own, as
 * cantools' are compiled apart, so that both sides pay one call and neither is folded into
 * the timing loop (same inputs every time) */
#define CALL_APART __attribute__((noinline, noclone))
static CALL_APART int cw_steering_encode_one(const can_mixed_steering_t *m, uint8_t *b, size_t n) { return can_mixed_steering_encode(m, b, n); }
static CALL_APART int cw_steering_decode_one(const uint8_t *b, size_t n, can_mixed_steering_t *m) { return can_mixed_steering_decode(b, n, m); }
static CALL_APART int cw_extended_encode_one(const can_mixed_extended_t *m, uint8_t *b, size_t n) { return can_mixed_extended_encode(m, b, n); }
static CALL_APART int cw_extended_decode_one(const uint8_t *b, size_t n, can_mixed_extended_t *m) { return can_mixed_extended_decode(b, n, m); }

static void cw_steering_encode(void) { long i; for (i = 0; i < CALLS; i++) sink += cw_steering_encode_one(&cw_steering, frame, sizeof frame); }
static void ct_steering_encode(void) { long i; for (i = 0; i < CALLS; i++) sink += cantools_can_mixed_steering_pack(data, &ct_steering, sizeof data); }
static void cw_steering_decode(void) { long i; can_mixed_steering_t m = {0}; for (i = 0; i < CALLS; i++) { sink += cw_steering_decode_one(frame, sizeof frame, &m); sink += m.rate; } }
static void ct_steering_decode(void) { long i; struct cantools_can_mixed_steering_t m = {0}; for (i = 0; i < CALLS; i++) { sink += cantools_can_mixed_steering_unpack(&m, data, sizeof data); sink += m.rate; } }
static void cw_extended_encode(void) { long i; for (i = 0; i < CALLS; i++) sink += cw_extended_encode_one(&cw_extended, frame, sizeof frame); }
static void ct_extended_encode(void) { long i; for (i = 0; i < CALLS; i++) sink += cantools_can_mixed_extended_pack(data, &ct_extended, sizeof data); }
static void cw_extended_decode(void) { long i; can_mixed_extended_t m = {0}; for (i = 0; i < CALLS; i++) { sink += cw_extended_decode_one(frame, sizeof frame, &m); sink += m.s0; } }
static void ct_extended_decode(void) { long i; struct cantools_can_mixed_extended_t m = {0}; for (i = 0; i < CALLS; i++) { sink += cantools_can_mixed_extended_unpack(&m, data, sizeof data); sink += m.s0; } }

static void timed(const char *names[], batch_fn fns[], int n, int rounds)
{
    double t[8][MAX_ROUNDS];
    int r, k;
    for (r = 0; r < rounds; r++) {
        for (k = 0; k < n; k++) {
            double start = now_ns();
            fns[k]();
            t[k][r] = (now_ns() - start) / (double)CALLS;
        }
    }
    for (k = 0; k < n; k++) {
        qsort(t[k], (size_t)rounds, sizeof(double), compare);
        printf("%s\t%.3f\n", names[k], t[k][rounds / 2]);
    }
}

int main(int argc, char **argv)
{
    int rounds = argc > 1 ? atoi(argv[1]) : 7;
    if (rounds < 1 || rounds > MAX_ROUNDS) {
        return 2;
    }
    /* the same values on both sides: rate 4095, torque -1.5 Nm, angle -0.5 deg, counter 9, valid */
    cw_steering.rate = 4095; cw_steering.torque = -150; cw_steering.angle = -1; cw_steering.counter = 9;
    cw_steering.valid = true;
    ct_steering.rate = 4095; ct_steering.torque = -150; ct_steering.angle = -1; ct_steering.counter = 9;
    ct_steering.valid = 1;
    /* s0 = 0 selects s1; s1 = 0 selects s2 and s3; s6 = 1 selects s7 */
    memset(&cw_extended, 0, sizeof cw_extended);
    cw_extended.s2 = -3; cw_extended.s3 = 1000; cw_extended.s6 = 1; cw_extended.s7 = -100000;
    memset(&ct_extended, 0, sizeof ct_extended);
    ct_extended.s2 = -3; ct_extended.s3 = 1000; ct_extended.s6 = 1; ct_extended.s7 = -100000;

    if (can_mixed_steering_encode(&cw_steering, frame, sizeof frame) != 13 ||
        cantools_can_mixed_steering_pack(data, &ct_steering, sizeof data) != 8) {
        return 1;
    }
    printf("steering agree\t%d\n", memcmp(frame + 5, data, 8) == 0);
    {
        const char *names[] = {"steering codeword encode", "steering cantools encode",
                               "steering codeword decode", "steering cantools decode"};
        batch_fn fns[] = {cw_steering_encode, ct_steering_encode, cw_steering_decode, ct_steering_decode};
        timed(names, fns, 4, rounds);
    }
    if (can_mixed_extended_encode(&cw_extended, frame, sizeof frame) != 13 ||
        cantools_can_mixed_extended_pack(data, &ct_extended, sizeof data) != 8) {
        return 1;
    }
    printf("extended agree\t%d\n", memcmp(frame + 5, data, 8) == 0);
    {
        const char *names[] = {"extended codeword encode", "extended cantools encode",
                               "extended codeword decode", "extended cantools decode"};
        batch_fn fns[] = {cw_extended_encode, ct_extended_encode, cw_extended_decode, ct_extended_decode};
        timed(names, fns, 4, rounds);
    }
    return 0;
}
