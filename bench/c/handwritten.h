/* Hand-written C codecs for the benchmarked messages: the floor the generated
 * C is compared against. Same layouts and checks as the schemas (see
 * ../shared/PROTOCOLS.md); same structs as the generated headers, so both
 * sides do the same work. */
#ifndef BENCH_HANDWRITTEN_H
#define BENCH_HANDWRITTEN_H

#include <math.h>
#include <stdint.h>
#include <string.h>

/* route object: 29 bits MSB first, left-aligned in 4 bytes (ROUTE-D4) */
static inline int hw_route_object_encode(const route_object_t *m, uint8_t *b)
{
    uint32_t na, cs, w;
    if (m->ns > 7 || m->nl > 7 || m->no > 7 || m->na < 10 || m->na > 17 || m->dl < 1 || m->dl > 5
        || m->rc > 3 || m->dr < 1 || m->dr > 5 || m->cm < 1 || m->cm > 15) {
        return -1;
    }
    na = m->na - 10u; /* ROUTE-D6 */
    cs = (1u + m->ns + m->nl + m->no + na + m->dl + m->rc + m->dr + m->cm) & 7u; /* ROUTE-D1 */
    w = (1u << 27 | (uint32_t)m->ns << 24 | (uint32_t)m->nl << 21 | (uint32_t)m->no << 18 | na << 15
         | (uint32_t)m->dl << 12 | (uint32_t)m->rc << 10 | (uint32_t)m->dr << 7 | (uint32_t)m->cm << 3 | cs) << 3;
    b[0] = (uint8_t)(w >> 24); b[1] = (uint8_t)(w >> 16); b[2] = (uint8_t)(w >> 8); b[3] = (uint8_t)w;
    return 4;
}

static inline int hw_route_object_decode(const uint8_t *b, size_t len, route_object_t *m)
{
    uint32_t w;
    if (len != 4) {
        return -1;
    }
    w = (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
    if ((w & 7u) != 0 || w >> 30 != 1u) {
        return -1;
    }
    w >>= 3;
    m->ns = (w >> 24) & 7u; m->nl = (w >> 21) & 7u; m->no = (w >> 18) & 7u;
    m->na = (uint8_t)(((w >> 15) & 7u) + 10u);
    m->dl = (w >> 12) & 7u; m->rc = (w >> 10) & 3u; m->dr = (w >> 7) & 7u; m->cm = (w >> 3) & 15u;
    if (m->dl < 1 || m->dl > 5 || m->dr < 1 || m->dr > 5 || m->cm < 1) {
        return -1;
    }
    if ((w & 7u) != ((1u + m->ns + m->nl + m->no + (m->na - 10u) + m->dl + m->rc + m->dr + m->cm) & 7u)) {
        return -1;
    }
    return 0;
}

/* car master control word: 32 bits big-endian, even parity in the last bit (CAR-D2) */
static inline int hw_car_master_encode(const car_master_control_t *m, uint8_t *b)
{
    uint32_t w;
    if (m->accept_ir || !m->forward_words || m->motor.direction > 3 || m->motor.speed > 3
        || m->motor.duration > 3 || m->led.led > 3 || m->led.duration > 3 || m->ultrasonic.radius > 3
        || m->ultrasonic.duration > 3) {
        return -1;
    }
    w = 1u << 30 | (uint32_t)m->motor.enable << 29 | (uint32_t)m->motor.direction << 27
        | (uint32_t)m->motor.speed << 25 | (uint32_t)m->motor.duration << 23 | (uint32_t)m->led.led << 21
        | (uint32_t)m->led.duration << 19 | (uint32_t)m->ultrasonic.enable << 18
        | (uint32_t)m->ultrasonic.radius << 16 | (uint32_t)m->ultrasonic.duration << 14
        | (uint32_t)m->voice << 13 | (uint32_t)m->body_sensor << 12;
    w |= (uint32_t)__builtin_parity(w);
    b[0] = (uint8_t)(w >> 24); b[1] = (uint8_t)(w >> 16); b[2] = (uint8_t)(w >> 8); b[3] = (uint8_t)w;
    return 4;
}

static inline int hw_car_master_decode(const uint8_t *b, size_t len, car_master_control_t *m)
{
    uint32_t w;
    if (len != 4) {
        return -1;
    }
    w = (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
    if (__builtin_parity(w) || (w & 0xffeu) != 0 || w >> 30 != 1u) {
        return -1;
    }
    m->accept_ir = false; m->forward_words = true;
    m->motor.enable = (w >> 29) & 1u; m->motor.direction = (w >> 27) & 3u;
    m->motor.speed = (w >> 25) & 3u; m->motor.duration = (w >> 23) & 3u;
    m->led.led = (w >> 21) & 3u; m->led.duration = (w >> 19) & 3u;
    m->ultrasonic.enable = (w >> 18) & 1u; m->ultrasonic.radius = (w >> 16) & 3u;
    m->ultrasonic.duration = (w >> 14) & 3u;
    m->voice = (w >> 13) & 1u; m->body_sensor = (w >> 12) & 1u;
    return 0;
}

/* mtv4 SetWheelsVelocitiesWithOdometry: 26 bytes little-endian, CRC-16/CMS big-endian (MTV4-D1) */
static uint16_t hw_crc_table[256];

static void hw_crc_init(void)
{
    for (unsigned byte = 0; byte < 256; byte++) {
        uint16_t reg = (uint16_t)(byte << 8);
        for (int k = 0; k < 8; k++) {
            reg = (reg & 0x8000u) ? (uint16_t)((reg << 1) ^ 0x8005u) : (uint16_t)(reg << 1);
        }
        hw_crc_table[byte] = reg;
    }
}

static inline uint16_t hw_crc16(const uint8_t *d, size_t n)
{
    uint16_t reg = 0xffffu;
    while (n--) {
        reg = (uint16_t)(hw_crc_table[(reg >> 8) ^ *d++] ^ (reg << 8));
    }
    return reg;
}

static inline int hw_f32_ok(float v) { return isfinite(v); }

static inline int hw_odometry_encode(const mtv4_set_wheels_velocities_with_odometry_t *m, uint8_t *b)
{
    uint16_t crc;
    if (m->group > 15 || m->radio_crc_flag > 1 || m->robots == 0 || (m->robots & (m->robots - 1u))
        || (m->status & ~7u) || !hw_f32_ok(m->x) || !hw_f32_ok(m->y) || !hw_f32_ok(m->th)) {
        return -1;
    }
    b[0] = 0xAA; b[1] = 22; b[2] = m->group; b[3] = (uint8_t)(m->radio_crc_flag << 7 | 3u);
    memcpy(b + 4, &m->robots, 2); memcpy(b + 6, &m->status, 2); /* little-endian host */
    memcpy(b + 8, &m->vl, 2); memcpy(b + 10, &m->vr, 2);
    memcpy(b + 12, &m->x, 4); memcpy(b + 16, &m->y, 4); memcpy(b + 20, &m->th, 4);
    crc = hw_crc16(b + 1, 23);
    b[24] = (uint8_t)(crc >> 8); b[25] = (uint8_t)crc;
    return 26;
}

static inline int hw_odometry_decode(const uint8_t *b, size_t len, mtv4_set_wheels_velocities_with_odometry_t *m)
{
    if (len != 26 || b[0] != 0xAA || b[1] != 22 || (b[3] & 0x7fu) != 3u || b[2] > 15) {
        return -1;
    }
    if (((uint16_t)b[24] << 8 | b[25]) != hw_crc16(b + 1, 23)) {
        return -1;
    }
    m->group = b[2]; m->radio_crc_flag = b[3] >> 7;
    memcpy(&m->robots, b + 4, 2); memcpy(&m->status, b + 6, 2);
    memcpy(&m->vl, b + 8, 2); memcpy(&m->vr, b + 10, 2);
    memcpy(&m->x, b + 12, 4); memcpy(&m->y, b + 16, 4); memcpy(&m->th, b + 20, 4);
    if (m->robots == 0 || (m->robots & (m->robots - 1u)) || (m->status & ~7u)
        || !hw_f32_ok(m->x) || !hw_f32_ok(m->y) || !hw_f32_ok(m->th)) {
        return -1;
    }
    return 0;
}

/* tr24 command: start 0x02, service byte (reserved 6 bits, type 0, seq), sender, receiver, 7 data, stop 0x03 */
static inline int hw_tr24_command_encode(const tr24_command_t *m, uint8_t *b)
{
    if (m->seq > 1) {
        return -1;
    }
    b[0] = 2; b[1] = m->seq; b[2] = m->sender; b[3] = m->receiver;
    memcpy(b + 4, m->data, 7);
    b[11] = 3;
    return 12;
}

static inline int hw_tr24_command_decode(const uint8_t *b, size_t len, tr24_command_t *m)
{
    if (len != 12 || b[0] != 2 || b[11] != 3 || (b[1] & 0xfeu)) {
        return -1;
    }
    m->seq = b[1]; m->sender = b[2]; m->receiver = b[3];
    memcpy(m->data, b + 4, 7);
    return 0;
}

/* tank telemetry line: "$:" then 20 comma-separated fields and ';' (TANK-D3, TANK-D5).
 * Decimals stay decimal, as the struct holds them (cw_decimal_t: digits and a
 * power of ten): read digit by digit, written back as Python's repr writes
 * the float (positional for exponents -4..15, else d.ddde+XX). */
#define HW_TANK_TEXT_MAX 32

static inline int hw_tank_clean(const char *s, size_t n) /* no ',' or ';', printable ASCII, no edge spaces */
{
    size_t i;
    if (n > HW_TANK_TEXT_MAX || (n && (s[0] == ' ' || s[n - 1] == ' '))) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        if (s[i] == ',' || s[i] == ';' || s[i] < ' ' || s[i] > '~') {
            return 0;
        }
    }
    return 1;
}

static inline int hw_tank_decimal_ok(const cw_decimal_t *d) { return d->digits <= 99999999999999999ULL; }

static inline char *hw_tank_put_uint(char *b, unsigned v)
{
    if (v >= 100u) {
        *b++ = (char)('0' + v / 100u);
    }
    if (v >= 10u) {
        *b++ = (char)('0' + v / 10u % 10u);
    }
    *b++ = (char)('0' + v % 10u);
    return b;
}

static inline char *hw_tank_put_decimal(char *b, const cw_decimal_t *d)
{
    char t[20]; /* digits, least significant first */
    int n = 0, top, i;
    uint64_t v = d->digits;
    do {
        t[n++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v);
    if (d->negative) {
        *b++ = '-';
    }
    if (d->digits == 0) {
        *b++ = '0';
        return b;
    }
    top = d->exp10 + n - 1; /* exponent of the leading digit */
    if (top < -4 || top > 15) {
        int e = top < 0 ? -top : top;
        *b++ = t[n - 1];
        if (n > 1) {
            *b++ = '.';
            for (i = n - 2; i >= 0; i--) {
                *b++ = t[i];
            }
        }
        *b++ = 'e';
        *b++ = top < 0 ? '-' : '+';
        if (e >= 100) {
            *b++ = (char)('0' + e / 100);
        }
        *b++ = (char)('0' + e / 10 % 10);
        *b++ = (char)('0' + e % 10);
    } else if (top < 0) { /* 0.000ddd */
        *b++ = '0';
        *b++ = '.';
        for (i = -1; i > top; i--) {
            *b++ = '0';
        }
        for (i = n - 1; i >= 0; i--) {
            *b++ = t[i];
        }
    } else {
        for (i = n - 1; i >= 0; i--) {
            *b++ = t[i];
            if (i == -d->exp10 && i > 0) {
                *b++ = '.';
            }
        }
        for (i = 0; i < d->exp10; i++) { /* trailing zeros of an integer */
            *b++ = '0';
        }
    }
    return b;
}

/* [+-]digits[.digits][e[+-]digits], at most 17 significant digits, |value| < 1e309 */
static inline int hw_tank_get_decimal(const char *s, const char *e, cw_decimal_t *d)
{
    uint64_t v = 0;
    int exp10 = 0, n = 0, any = 0;
    d->negative = s < e && *s == '-';
    if (s < e && (*s == '-' || *s == '+')) {
        s++;
    }
    for (; s < e && *s >= '0' && *s <= '9'; s++, any = 1) {
        if (v || *s != '0') {
            if (++n > 17) {
                return -1;
            }
            v = v * 10u + (uint64_t)(*s - '0');
        }
    }
    if (s < e && *s == '.') {
        for (s++; s < e && *s >= '0' && *s <= '9'; s++, any = 1) {
            if (v || *s != '0') {
                if (++n > 17) {
                    return -1;
                }
                v = v * 10u + (uint64_t)(*s - '0');
            }
            exp10--;
        }
    }
    if (!any) {
        return -1;
    }
    if (s < e && (*s == 'e' || *s == 'E')) {
        int neg, x = 0;
        s++;
        neg = s < e && *s == '-';
        if (s < e && (*s == '-' || *s == '+')) {
            s++;
        }
        if (s == e) {
            return -1;
        }
        for (; s < e && *s >= '0' && *s <= '9'; s++) {
            if (x < 10000) {
                x = x * 10 + (*s - '0');
            }
        }
        exp10 += neg ? -x : x;
    }
    if (s != e) {
        return -1;
    }
    if (v == 0) {
        exp10 = 0;
    } else if (exp10 + n > 309) { /* 1e309 or more: beyond the largest double */
        return -1;
    }
    while (v && v % 10u == 0) {
        v /= 10u;
        exp10++;
    }
    d->digits = v;
    d->exp10 = (int16_t)exp10;
    return 0;
}

static inline int hw_tank_get_uint(const char *s, const char *e, unsigned max, unsigned *out)
{
    unsigned v = 0;
    if (s == e || e - s > 3) {
        return -1;
    }
    for (; s < e; s++) {
        if (*s < '0' || *s > '9') {
            return -1;
        }
        v = v * 10u + (unsigned)(*s - '0');
    }
    if (v > max) {
        return -1;
    }
    *out = v;
    return 0;
}

static inline int hw_tank_move_ok(char c)
{
    return c == 'f' || c == 'b' || c == 'l' || c == 'r' || c == 'a' || c == 'c' || c == 'd' || c == 'e';
}

/* Writes the line and a NUL into b (TANK_TELEMETRY_MAX_TEXT chars); the length, or -1. */
static inline int hw_tank_telemetry_encode(const tank_telemetry_t *m, char *b)
{
    const cw_decimal_t *f[11] = {&m->lcurr, &m->rcurr, &m->accx, &m->accy, &m->accz, &m->gyrox,
                                 &m->gyroy, &m->gyroz, &m->magx, &m->magy, &m->magz};
    size_t lan = strlen(m->lan), lon = strlen(m->lon);
    char *p = b;
    int i;
    if (!hw_tank_move_ok(m->move) || m->speed > 100 || m->systemstatus > 6 || m->extstatus > 5
        || !hw_tank_clean(&m->value, 1) || !hw_tank_clean(m->lan, lan) || !hw_tank_clean(m->lon, lon)
        || !hw_tank_decimal_ok(&m->vbat)) {
        return -1;
    }
    for (i = 0; i < 11; i++) {
        if (!hw_tank_decimal_ok(f[i])) {
            return -1;
        }
    }
    *p++ = '$';
    *p++ = ':';
    *p++ = m->move;
    *p++ = ',';
    p = hw_tank_put_uint(p, m->speed);
    *p++ = ',';
    *p++ = m->value;
    for (i = 0; i < 11; i++) {
        *p++ = ',';
        p = hw_tank_put_decimal(p, f[i]);
    }
    *p++ = ',';
    memcpy(p, m->lan, lan);
    p += lan;
    *p++ = ',';
    memcpy(p, m->lon, lon);
    p += lon;
    *p++ = ',';
    p = hw_tank_put_decimal(p, &m->vbat);
    *p++ = ',';
    p = hw_tank_put_uint(p, m->systemstatus);
    *p++ = ',';
    p = hw_tank_put_uint(p, m->extid);
    *p++ = ',';
    p = hw_tank_put_uint(p, m->extstatus);
    *p++ = ';';
    *p = '\0';
    return (int)(p - b);
}

static inline int hw_tank_telemetry_decode(const char *line, size_t len, tank_telemetry_t *m)
{
    cw_decimal_t *f[11] = {&m->lcurr, &m->rcurr, &m->accx, &m->accy, &m->accz, &m->gyrox,
                           &m->gyroy, &m->gyroz, &m->magx, &m->magy, &m->magz};
    const char *t[21]; /* field k is [t[k], t[k + 1] - 1) */
    const char *s = line + 2, *end = line + len - 1;
    unsigned v;
    int n = 1, i;
    if (len < 3 || line[0] != '$' || line[1] != ':' || *end != ';') {
        return -1;
    }
    t[0] = s;
    for (; s < end; s++) {
        if (*s == ',') {
            if (n == 20) {
                return -1;
            }
            t[n++] = s + 1;
        }
    }
    if (n != 20) {
        return -1;
    }
    t[20] = end + 1;
    if (t[1] - t[0] != 2 || !hw_tank_move_ok(*t[0]) || t[3] - t[2] != 2 || !hw_tank_clean(t[2], 1)) {
        return -1;
    }
    m->move = *t[0];
    m->value = *t[2];
    if (hw_tank_get_uint(t[1], t[2] - 1, 100, &v)) {
        return -1;
    }
    m->speed = (uint8_t)v;
    for (i = 0; i < 11; i++) {
        if (hw_tank_get_decimal(t[3 + i], t[4 + i] - 1, f[i])) {
            return -1;
        }
    }
    if (!hw_tank_clean(t[14], (size_t)(t[15] - 1 - t[14])) || !hw_tank_clean(t[15], (size_t)(t[16] - 1 - t[15]))) {
        return -1;
    }
    memcpy(m->lan, t[14], (size_t)(t[15] - 1 - t[14]));
    m->lan[t[15] - 1 - t[14]] = '\0';
    memcpy(m->lon, t[15], (size_t)(t[16] - 1 - t[15]));
    m->lon[t[16] - 1 - t[15]] = '\0';
    if (hw_tank_get_decimal(t[16], t[17] - 1, &m->vbat)) {
        return -1;
    }
    if (hw_tank_get_uint(t[17], t[18] - 1, 6, &v)) {
        return -1;
    }
    m->systemstatus = (uint8_t)v;
    if (hw_tank_get_uint(t[18], t[19] - 1, 255, &v)) {
        return -1;
    }
    m->extid = (uint8_t)v;
    if (hw_tank_get_uint(t[19], t[20] - 1, 5, &v)) {
        return -1;
    }
    m->extstatus = (uint8_t)v;
    return 0;
}

#endif
