/* Host benchmark of the generated C: ns per encode+decode of one message and
 * stream-parser MB/s (byte at a time and in place, with each CRC method), next
 * to hand-written C, MAVLink's generated C and memcpy.
 * Built by bench/c_host.py with gcc -O2; prints one "key value" line per
 * figure (medians over interleaved rounds). Usage:
 *   host_bench ROUNDS MTV4_CAPTURE MAVLINK_CAPTURE */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "route.h"
#include "car.h"
#include "mtv4.h"
#include "tr24.h"
#include "tank.h"
#include "common/mavlink.h"
#include "handwritten.h"

#define N_MSGS 64
volatile uint32_t sink;

static route_object_t route_msgs[N_MSGS];
static car_master_control_t car_msgs[N_MSGS];
static mtv4_set_wheels_velocities_with_odometry_t odo_msgs[N_MSGS];
static tr24_command_t tr24_msgs[N_MSGS];
static tank_telemetry_t tank_msgs[N_MSGS];

/* schemas/tank.yaml example "driving forward-left, fractional and negative readings" */
static const char TANK_LINE[] = "$:a,50,s,1.25,-0.5,0.01,-0.02,9.81,0,0,-1.5,23,-7,41.5,55.7558,37.6173,12.6,1,0,1;";

/* CPU time of this process: on a shared machine, waits for a core are not its own */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int fill(void)
{
    for (int i = 0; i < N_MSGS; i++) {
        route_object_t *r = &route_msgs[i];
        r->ns = i & 7; r->nl = (i >> 3) & 7; r->no = (i * 5) & 7; r->na = 10 + (i % 8);
        r->dl = 1 + i % 5; r->rc = i & 3; r->dr = 1 + (i * 3) % 5; r->cm = 1 + i % 15;
        car_master_control_t *c = &car_msgs[i];
        memset(c, 0, sizeof *c);
        c->forward_words = true; c->motor.enable = i & 1; c->motor.direction = i & 3;
        c->motor.speed = (i >> 2) & 3; c->motor.duration = (i >> 4) & 3; c->led.led = i & 3;
        c->ultrasonic.radius = (i >> 1) & 3; c->voice = (i >> 3) & 1;
        mtv4_set_wheels_velocities_with_odometry_t *o = &odo_msgs[i];
        memset(o, 0, sizeof *o);
        o->group = i & 15; o->robots = (uint16_t)(1u << (i & 15)); o->status = i & 7;
        o->vl = (int16_t)(i * 97 - 3000); o->vr = (int16_t)(2000 - i * 31);
        o->x = 1.5f * i; o->y = -0.25f; o->th = 3.140625f;
        tr24_command_t *t = &tr24_msgs[i];
        t->seq = i & 1; t->sender = i; t->receiver = 255 - i;
        for (int k = 0; k < 7; k++) t->data[k] = (uint8_t)(i * 7 + k);
        tank_telemetry_t *k = &tank_msgs[i];
        memset(k, 0, sizeof *k);
        if (tank_telemetry_decode(TANK_LINE, sizeof TANK_LINE - 1, k) != CW_OK) return 0;
        k->move = "fblracde"[i & 7]; k->speed = (uint8_t)(i * 3 % 101);
        k->lcurr = cw_decimal_from_scaled(125 + 7 * i, 2); k->accx = cw_decimal_from_scaled(-13 * i, 3);
        k->gyroz = cw_decimal_from_scaled(15 + i, 6); /* 1.5e-05: the exponent form */
        k->magx = cw_decimal_from_scaled(230 - 11 * i, 1); k->vbat = cw_decimal_from_scaled(126 - i % 20, 1);
        k->systemstatus = (uint8_t)(i % 7); k->extid = (uint8_t)i; k->extstatus = (uint8_t)(i % 6);
    }
    return 1;
}

static int same_decimal(const cw_decimal_t *a, const cw_decimal_t *b)
{
    return a->digits == b->digits && a->exp10 == b->exp10 && a->negative == b->negative;
}

static int same_tank(const tank_telemetry_t *a, const tank_telemetry_t *b)
{
    const cw_decimal_t *x[12] = {&a->lcurr, &a->rcurr, &a->accx, &a->accy, &a->accz, &a->gyrox, &a->gyroy,
                                 &a->gyroz, &a->magx, &a->magy, &a->magz, &a->vbat};
    const cw_decimal_t *y[12] = {&b->lcurr, &b->rcurr, &b->accx, &b->accy, &b->accz, &b->gyrox, &b->gyroy,
                                 &b->gyroz, &b->magx, &b->magy, &b->magz, &b->vbat};
    for (int k = 0; k < 12; k++) {
        if (!same_decimal(x[k], y[k])) return 0;
    }
    return a->move == b->move && a->speed == b->speed && a->value == b->value && !strcmp(a->lan, b->lan)
           && !strcmp(a->lon, b->lon) && a->systemstatus == b->systemstatus && a->extid == b->extid
           && a->extstatus == b->extstatus;
}

/* Both sides must write the same bytes for every message (equal work); for
 * the tank line also read back the same values. */
static int agree(void)
{
    uint8_t a[64], b[64];
    char ta[TANK_TELEMETRY_MAX_TEXT], tb[TANK_TELEMETRY_MAX_TEXT];
    tank_telemetry_t ka, kb;
    for (int i = 0; i < N_MSGS; i++) {
        if (route_object_encode(&route_msgs[i], a, sizeof a) != hw_route_object_encode(&route_msgs[i], b) || memcmp(a, b, 4)) return 0;
        if (car_master_control_encode(&car_msgs[i], a, sizeof a) != hw_car_master_encode(&car_msgs[i], b) || memcmp(a, b, 4)) return 0;
        if (mtv4_set_wheels_velocities_with_odometry_encode(&odo_msgs[i], a, sizeof a) != hw_odometry_encode(&odo_msgs[i], b) || memcmp(a, b, 26)) return 0;
        if (tr24_command_encode(&tr24_msgs[i], a, sizeof a) != hw_tr24_command_encode(&tr24_msgs[i], b) || memcmp(a, b, 12)) return 0;
        int n = tank_telemetry_encode(&tank_msgs[i], ta, sizeof ta);
        if (n <= 0 || n != hw_tank_telemetry_encode(&tank_msgs[i], tb) || memcmp(ta, tb, (size_t)n + 1)) return 0;
        if (tank_telemetry_decode(ta, (size_t)n, &ka) != CW_OK || hw_tank_telemetry_decode(ta, (size_t)n, &kb) != 0
            || !same_tank(&ka, &kb) || !same_tank(&ka, &tank_msgs[i])) return 0;
    }
    return 1;
}

#define ROUNDTRIP(NAME, MSGS, T, ENC, DEC, FIELD) ROUNDTRIP_IN(NAME, T, uint8_t, 64, ENC, DEC, FIELD)
#define ROUNDTRIP_IN(NAME, T, BUF_T, BUF_N, ENC, DEC, FIELD)                       \
    static __attribute__((noinline)) uint32_t NAME(long n)                        \
    {                                                                              \
        BUF_T buf[BUF_N];                                                          \
        T out;                                                                     \
        uint32_t acc = 0;                                                          \
        for (long i = 0; i < n; i++) {                                             \
            int len = ENC;                                                         \
            int rc = DEC;                                                          \
            acc += (uint32_t)rc + (uint32_t)out.FIELD + (uint32_t)len;            \
        }                                                                          \
        return acc;                                                                \
    }

#define M(MSGS) (&MSGS[i & (N_MSGS - 1)])
ROUNDTRIP(cw_route, route_msgs, route_object_t, route_object_encode(M(route_msgs), buf, sizeof buf), route_object_decode(buf, (size_t)len, &out), cm)
ROUNDTRIP(hw_route, route_msgs, route_object_t, hw_route_object_encode(M(route_msgs), buf), hw_route_object_decode(buf, (size_t)len, &out), cm)
ROUNDTRIP(cw_car, car_msgs, car_master_control_t, car_master_control_encode(M(car_msgs), buf, sizeof buf), car_master_control_decode(buf, (size_t)len, &out), motor.speed)
ROUNDTRIP(hw_car, car_msgs, car_master_control_t, hw_car_master_encode(M(car_msgs), buf), hw_car_master_decode(buf, (size_t)len, &out), motor.speed)
ROUNDTRIP(cw_odo, odo_msgs, mtv4_set_wheels_velocities_with_odometry_t, mtv4_set_wheels_velocities_with_odometry_encode(M(odo_msgs), buf, sizeof buf), mtv4_set_wheels_velocities_with_odometry_decode(buf, (size_t)len, &out), vl)
ROUNDTRIP(hw_odo, odo_msgs, mtv4_set_wheels_velocities_with_odometry_t, hw_odometry_encode(M(odo_msgs), buf), hw_odometry_decode(buf, (size_t)len, &out), vl)
ROUNDTRIP(cw_tr24, tr24_msgs, tr24_command_t, tr24_command_encode(M(tr24_msgs), buf, sizeof buf), tr24_command_decode(buf, (size_t)len, &out), sender)
ROUNDTRIP(hw_tr24, tr24_msgs, tr24_command_t, hw_tr24_command_encode(M(tr24_msgs), buf), hw_tr24_command_decode(buf, (size_t)len, &out), sender)
ROUNDTRIP_IN(cw_tank, tank_telemetry_t, char, TANK_TELEMETRY_MAX_TEXT, tank_telemetry_encode(M(tank_msgs), buf, sizeof buf), tank_telemetry_decode(buf, (size_t)len, &out), speed)
ROUNDTRIP_IN(hw_tank, tank_telemetry_t, char, TANK_TELEMETRY_MAX_TEXT, hw_tank_telemetry_encode(M(tank_msgs), buf), hw_tank_telemetry_decode(buf, (size_t)len, &out), speed)

/* MAVLink ATTITUDE: pack and serialise, then parse the bytes back and decode. */
static __attribute__((noinline)) uint32_t mav_attitude(long n)
{
    uint8_t buf[MAVLINK_MAX_PACKET_LEN];
    mavlink_message_t msg, rx;
    mavlink_status_t st;
    mavlink_attitude_t att;
    uint32_t acc = 0;
    memset(&st, 0, sizeof st);
    for (long i = 0; i < n; i++) {
        const mtv4_set_wheels_velocities_with_odometry_t *o = M(odo_msgs);
        mavlink_msg_attitude_pack(1, 1, &msg, (uint32_t)i, o->x, o->y, o->th, 0.01f, -0.02f, 0.125f);
        uint16_t len = mavlink_msg_to_send_buffer(buf, &msg);
        for (uint16_t k = 0; k < len; k++) {
            if (mavlink_parse_char(MAVLINK_COMM_0, buf[k], &rx, &st)) {
                mavlink_msg_attitude_decode(&rx, &att);
                acc += att.time_boot_ms;
            }
        }
    }
    return acc;
}

static unsigned char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    unsigned char *data;
    if (!f) { perror(path); exit(2); }
    fseek(f, 0, SEEK_END);
    *len = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    data = malloc(*len);
    if (fread(data, 1, *len, f) != *len) { perror(path); exit(2); }
    fclose(f);
    return data;
}

static unsigned char *mtv4_cap, *mav_cap;
static size_t mtv4_len, mav_len;
static long mav_good;

/* bench/c/mtv4_stream.c, built once for each CRC method: bench/c_host.py defines
 * CRC_METHODS as X(bitwise) X(nibble) ... */
#define X(m) long mtv4_feed_##m(const unsigned char *buf, size_t len); \
    long mtv4_scan_##m(const unsigned char *buf, size_t len);
CRC_METHODS
#undef X

typedef long (*stream_fn)(const unsigned char *, size_t);
static const struct { const char *key; stream_fn fn; } PARSERS[] = {
#define X(m) {"mtv4_parser_feed/next, CRC " #m, mtv4_feed_##m},
    CRC_METHODS
#undef X
#define X(m) {"mtv4_scan, CRC " #m, mtv4_scan_##m},
    CRC_METHODS
#undef X
};
#define N_PARSERS (sizeof PARSERS / sizeof PARSERS[0])
static long parser_good[N_PARSERS];

static unsigned char *copy_dst;

/* The floor: copying the capture once. */
static void copy_mtv4(void)
{
    memcpy(copy_dst, mtv4_cap, mtv4_len);
    sink = copy_dst[mtv4_len / 2];
}

static void parse_mavlink(void)
{
    mavlink_message_t rx;
    mavlink_status_t st;
    long good = 0;
    memset(&st, 0, sizeof st);
    for (size_t i = 0; i < mav_len; i++) {
        if (mavlink_parse_char(MAVLINK_COMM_1, mav_cap[i], &rx, &st) && rx.msgid == MAVLINK_MSG_ID_ATTITUDE) {
            good++;
        }
    }
    mav_good = good;
}

typedef uint32_t (*roundtrip_fn)(long);
static const struct { const char *key; roundtrip_fn fn; } CASES[] = {
    {"route codeword", cw_route}, {"route hand-written", hw_route},
    {"car codeword", cw_car}, {"car hand-written", hw_car},
    {"mtv4 codeword", cw_odo}, {"mtv4 hand-written", hw_odo},
    {"tr24 codeword", cw_tr24}, {"tr24 hand-written", hw_tr24},
    {"tank codeword", cw_tank}, {"tank hand-written", hw_tank},
    {"mavlink ATTITUDE", mav_attitude},
};
#define N_CASES (sizeof CASES / sizeof CASES[0])

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

int main(int argc, char **argv)
{
    int rounds = argc > 1 ? atoi(argv[1]) : 5;
    long iters[N_CASES];
    double samples[N_CASES][64], parse_cw[N_PARSERS][64], parse_mav[64], copy[64];
    if (rounds < 1 || rounds > 64 || argc < 4) {
        fprintf(stderr, "usage: host_bench ROUNDS MTV4_CAPTURE MAVLINK_CAPTURE\n");
        return 2;
    }
    hw_crc_init();
    if (!fill()) {
        fprintf(stderr, "the tank example line does not decode\n");
        return 1;
    }
    if (!agree()) {
        fprintf(stderr, "hand-written and generated encoders disagree\n");
        return 1;
    }
    mtv4_cap = read_file(argv[2], &mtv4_len);
    mav_cap = read_file(argv[3], &mav_len);
    copy_dst = malloc(mtv4_len);
    for (size_t c = 0; c < N_CASES; c++) { /* calibrate: about 20 ms per measurement */
        long n = 1000;
        double t;
        for (;;) {
            t = now();
            sink = CASES[c].fn(n);
            t = now() - t;
            if (t > 0.005) break;
            n *= 4;
        }
        iters[c] = (long)(n * 0.02 / t) + 1;
    }
    for (int r = 0; r < rounds; r++) {
        for (size_t c = 0; c < N_CASES; c++) {
            double t = now();
            sink = CASES[c].fn(iters[c]);
            samples[c][r] = (now() - t) / iters[c] * 1e9;
        }
        for (size_t k = 0; k < N_PARSERS; k++) {
            double t = now();
            parser_good[k] = PARSERS[k].fn(mtv4_cap, mtv4_len);
            parse_cw[k][r] = mtv4_len / (now() - t) / 1e6;
        }
        double t = now();
        parse_mavlink();
        parse_mav[r] = mav_len / (now() - t) / 1e6;
        t = now();
        copy_mtv4();
        copy[r] = mtv4_len / (now() - t) / 1e6;
    }
    for (size_t c = 0; c < N_CASES; c++) {
        printf("%s\t%.2f\n", CASES[c].key, median(samples[c], rounds));
    }
    for (size_t k = 0; k < N_PARSERS; k++) {
        printf("parser %s MB/s\t%.1f\n", PARSERS[k].key, median(parse_cw[k], rounds));
        printf("parser %s frames\t%ld\n", PARSERS[k].key, parser_good[k]);
    }
    printf("memcpy MB/s\t%.1f\n", median(copy, rounds));
    printf("parser mavlink_parse_char MB/s\t%.1f\n", median(parse_mav, rounds));
    printf("parser mavlink_parse_char frames\t%ld\n", mav_good);
    return 0;
}
