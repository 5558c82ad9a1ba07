/* Edges of the C text codec that the conformance vectors do not reach: the
 * writer's capacity check near the end of a buffer, decimals of more than 32
 * bits of digits, the decimal reader's fast path and its fall-back, and a byte
 * above 0x7F reported before the error it hides. Expected values are worked
 * out by hand from schemas/tank.yaml. Built by tests/test_c_text.py; prints
 * one line per failure and "TEXT EDGES PASS <n>" at the end. */
#include <stdio.h>
#include <string.h>

#include "tank.h"

static unsigned checks;
static unsigned failures;

static void expect(int ok, const char *what)
{
    checks++;
    if (!ok) {
        failures++;
        printf("FAIL %s\n", what);
    }
}

/* The seed's test line "%:f,100,s,10,1,0,0,0,1;" is 23 characters. */
static void capacity(void)
{
    static const char line[] = "%:f,100,s,10,1,0,0,0,1;";
    tank_command_t m;
    char buf[40];
    size_t cap;
    memset(&m, 0, sizeof m);
    m.move = TANK_MOVE_FORWARD;
    m.speed = 100;
    m.value = 's';
    m.azimutloc = 10;
    m.gpio1.digits = 1;
    m.systemstatus = TANK_SYSTEM_STATUS_WORK;
    for (cap = 0; cap <= 23u; cap++) {
        memset(buf, '#', sizeof buf);
        expect(tank_command_encode(&m, buf, cap) == CW_ERR_CAPACITY, "a line and its NUL need 24 chars");
        expect(buf[cap] == '#', "nothing written past the capacity");
    }
    memset(buf, '#', sizeof buf);
    expect(tank_command_encode(&m, buf, 24u) == 23, "the line fits in 24 chars");
    expect(memcmp(buf, line, sizeof line) == 0, "the seed's line, NUL-terminated");
    expect(buf[24] == '#', "nothing written past the NUL");
}

static void written(uint64_t digits, int16_t exp10, bool negative, const char *want)
{
    cw_decimal_t d;
    char text[CW_DECIMAL_ANY_TEXT];
    size_t n;
    d.digits = digits;
    d.exp10 = exp10;
    d.negative = negative;
    n = cw_format_decimal(d, text, sizeof text);
    expect(n == strlen(want) && memcmp(text, want, n) == 0, want);
}

static void writing(void)
{
    written(17976931348623157ULL, 292, false, "1.7976931348623157e+308");  /* the largest double */
    written(99999999999999999ULL, -17, false, "0.99999999999999999");
    written(12345678901234567ULL, -5, true, "-123456789012.34567");
    written(4294967296ULL, 0, false, "4294967296");  /* 2^32: the first value of more than 32 bits */
    written(5, -324, false, "5e-324");
    written(1, 16, false, "1e+16");
    written(123, 13, false, "1230000000000000");  /* 10^15 still positional */
    written(15, -6, false, "1.5e-05");
    written(25, -5, false, "0.00025");
    written(0, 0, true, "-0");
}

static void read_as(const char *text, int rc, uint64_t digits, int16_t exp10, bool negative)
{
    cw_decimal_t d;
    int got = cw_read_decimal(text, text + strlen(text), &d);
    expect(got == rc && (rc != CW_OK || (d.digits == digits && d.exp10 == exp10 && d.negative == negative)), text);
}

static void reading(void)
{
    read_as("1.5e-05", CW_OK, 15, -6, false);
    read_as("-0", CW_OK, 0, 0, true);
    read_as("+.5", CW_OK, 5, -1, false);
    read_as("1.250", CW_OK, 125, -2, false);
    read_as("100", CW_OK, 1, 2, false);
    read_as("0.000012345", CW_OK, 12345, -9, false);  /* 10 digits */
    read_as("123456789012345", CW_OK, 123456789012345ULL, 0, false);  /* 15 significant digits */
    read_as("1234567890123456", CW_ERR_PRECISION, 0, 0, false);  /* 16: a double may not keep them */
    read_as("12345678901234567", CW_ERR_PRECISION, 0, 0, false);
    read_as("1.79769313486231e308", CW_OK, 179769313486231ULL, 294, false);
    read_as("1.79769313486232e308", CW_ERR_FINITE, 0, 0, false);  /* past the largest double */
    read_as("1.7976931348623157e308", CW_ERR_PRECISION, 0, 0, false);  /* digits before range */
    read_as("1e309", CW_ERR_FINITE, 0, 0, false);
    read_as("1e-307", CW_OK, 1, -307, false);
    read_as("9.99999999999999e-308", CW_ERR_PRECISION, 0, 0, false);  /* subnormal or below */
    read_as("1e-400", CW_ERR_PRECISION, 0, 0, false);
    read_as("1e", CW_ERR_SYNTAX, 0, 0, false);
    read_as(".", CW_ERR_SYNTAX, 0, 0, false);
    read_as("1.2.3", CW_ERR_SYNTAX, 0, 0, false);
}

static void ascii_first(void)
{
    tank_message_t out;
    static const char no_terminator[] = "%:f,100,s,10,1,0,0,0,1;\xff";
    static const char in_text[] = "%:f,100,s,10,1,0,0,0,1,caf\xe9;";
    static const char in_prefix[] = "\xe9:1;";
    expect(tank_decode(no_terminator, sizeof no_terminator - 1, TANK_DIR_ANY, &out) == CW_ERR_TEXT,
           "a byte above 0x7F before a missing terminator");
    expect(tank_decode(in_text, sizeof in_text - 1, TANK_DIR_ANY, &out) == CW_ERR_TEXT,
           "a byte above 0x7F in a text value");
    expect(tank_command_decode(in_text, sizeof in_text - 1, &out.as.command) == CW_ERR_TEXT,
           "a byte above 0x7F in a text value, decoded as a command");
    expect(tank_decode(in_prefix, sizeof in_prefix - 1, TANK_DIR_ANY, &out) == CW_ERR_TEXT,
           "a byte above 0x7F before an unknown prefix");
    expect(tank_decode("?:1;", 4u, TANK_DIR_ANY, &out) == CW_ERR_DISPATCH, "an unknown prefix");
    expect(tank_decode("%:f, 100 ,s,10,1,0,0,0,1;", 25u, TANK_DIR_ANY, &out) == CW_OK
           && out.as.command.speed == 100, "spaces around a value (TANK-D4)");
}

int main(void)
{
    capacity();
    writing();
    reading();
    ascii_first();
    printf("TEXT EDGES %s %u checks %u failures\n", failures ? "FAIL" : "PASS", checks, failures);
    return failures ? 1 : 0;
}
