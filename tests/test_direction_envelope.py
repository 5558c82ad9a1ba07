"""An envelope byte whose value depends on the direction: MSP v1 writes `$M<` to
the flight controller and `$M>` back, and a request and its answer share the
command number. The byte tells them apart, so a decoder needs no direction.
Frames worked by hand from the MSP v1 layout: $ M <dir> size command payload
checksum, the checksum the XOR of size, command and payload
(status: 02 ^ 65 ^ e8 ^ 03 = 8c)."""
from __future__ import annotations

from pathlib import Path

from schema_in_a_test import load, render, run_c

SCHEMA = (Path(__file__).parent / "data" / "msp_lite.yaml").read_text(encoding="utf-8")
REQUEST = "24 4d 3c 00 65 65"
STATUS = "24 4d 3e 02 65 e8 03 8c"


def test_python_tells_the_directions_apart_by_the_envelope_byte(tmp_path):
    render(tmp_path, "msplite", SCHEMA)
    mod = load(tmp_path / "msplite.py")
    assert isinstance(mod.decode(bytes.fromhex(REQUEST)), mod.StatusRequest)
    assert mod.decode(bytes.fromhex(STATUS)) == mod.Status(cycle_time=1000)
    assert mod.encode(mod.Status(cycle_time=1000)) == bytes.fromhex(STATUS)
    assert mod.encode(mod.StatusRequest()) == bytes.fromhex(REQUEST)
    try:  # the answer's payload under the request's mark: no such message
        mod.decode(bytes.fromhex("24 4d 3c 02 65 e8 03 8c"))
    except mod.DecodeError as err:
        assert err.rule == "dispatch"
    else:
        raise AssertionError("a status frame marked as a request decoded")
    out = mod.StreamDecoder().feed(bytes.fromhex("24 00" + REQUEST + STATUS))
    assert [type(x).__name__ for x in out] == ["StatusRequest", "Status"]


def test_c_tells_the_directions_apart_by_the_envelope_byte(tmp_path):
    render(tmp_path, "msplite", SCHEMA)
    driver = r"""
#include <stdio.h>
#include "msplite.h"
static const uint8_t request[] = {0x24, 0x4d, 0x3c, 0x00, 0x65, 0x65};
static const uint8_t status[] = {0x24, 0x4d, 0x3e, 0x02, 0x65, 0xe8, 0x03, 0x8c};
static const uint8_t wrong[] = {0x24, 0x4d, 0x3c, 0x02, 0x65, 0xe8, 0x03, 0x8c};
int main(void) {
    msplite_message_t m;
    msplite_status_t s;
    uint8_t out[8];
    int i, n;
    int rc = msplite_decode(request, sizeof request, MSPLITE_DIR_ANY, &m);
    printf("%d %d\n", rc, m.kind == MSPLITE_MSG_STATUS_REQUEST);
    rc = msplite_decode(status, sizeof status, MSPLITE_DIR_ANY, &m);
    printf("%d %d %u\n", rc, m.kind == MSPLITE_MSG_STATUS, (unsigned)m.as.status.cycle_time);
    printf("%d\n", msplite_decode(wrong, sizeof wrong, MSPLITE_DIR_ANY, &m) == CW_ERR_DISPATCH);
    s.cycle_time = 1000;
    n = msplite_status_encode(&s, out, sizeof out);
    printf("%d", n);
    for (i = 0; i < n; i++) printf(" %02x", out[i]);
    printf("\n");
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["0 1", "0 1 1000", "1", "8 " + STATUS]
