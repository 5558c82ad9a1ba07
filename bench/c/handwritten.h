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

#endif
