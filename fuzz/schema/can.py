"""Schemas of CAN framing, as a DBC import writes them: messages at standard and extended
identifiers, classic or CAN FD data lengths, signals placed by start bit in both byte
orders (floats among them), multiplexed payloads, senders as roles."""
from __future__ import annotations

import random

CAN_SHARE = 0.08  # of the seeds, drawn from a generator of their own
CLASSIC = list(range(1, 9))
FD = CLASSIC + [12, 16, 20, 24, 32, 48, 64]


def can_schema(g, placed_signals, multiplexed_signals) -> dict:
    """A whole schema document of CAN framing; `g` is the Generator."""
    rng = random.Random(f"can {g.seed}")
    fd = rng.random() < 0.4
    doc: dict = {"codeword": 1, "protocol": f"fz{g.seed}", "title": f"fuzz schema {g.seed}",
                 "source": "fuzz/schema"}
    senders = ["ecu", "gateway"] if rng.random() < 0.5 else []
    if senders:
        doc["roles"] = {name: {"doc": name} for name in senders}
    doc["framing"] = {"kind": "can", "fd": True} if fd else {"kind": "can"}
    messages: dict = {}
    used: set[tuple[int, bool]] = set()
    for _ in range(rng.randint(1, 4)):
        extended = rng.random() < 0.4
        ident = rng.randint(0, 0x1FFFFFFF if extended else 0x7FF)
        if rng.random() < 0.15:  # the ends of the identifier ranges
            ident = rng.choice([0, 0x1FFFFFFF if extended else 0x7FF])
        if (ident, extended) in used:
            continue
        used.add((ident, extended))
        size = rng.choice(FD if fd else CLASSIC)
        body: dict = {"id": ident}
        if extended:
            body["extended"] = True
        if senders and rng.random() < 0.7:
            body["role"] = rng.choice(senders)
        body["payload_bytes"] = size
        if "multiplexed" in g.on and rng.random() < 0.3:
            body["fields"] = multiplexed_signals(rng, min(size, 8))
        else:
            floats = random.Random(f"placed_float {g.seed}") if "placed_float" in g.on else None
            body["fields"] = placed_signals(rng, size, floats)
        messages[g.name()] = body
    doc["messages"] = messages
    return doc
