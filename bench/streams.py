"""Python stream decoding: MB/s over a capture with garbage and corrupted frames.

The mtv4 capture holds SetWheelsVelocitiesWithOdometry frames (26 bytes) with
1% of its bytes garbage (random bytes between frames) and 1% of its frames
corrupted (one payload byte flipped, so the CRC fails). The MAVLink stream is
built the same way from ATTITUDE frames (40 bytes) and read with pymavlink's
`parse_buffer`. Everything is fed in 4 KiB chunks, as from a serial port.
"""

import random
import struct
import time

from bench import handwritten as hw
from bench import peers
from bench.protocols import mtv4

CHUNK = 4096
GARBAGE = 0.01
CORRUPT = 0.01


def _stream(frames, size, seed):
    """About `size` bytes of frames from `frames`, with garbage and corruption."""
    rng = random.Random(seed)
    frame_len = len(frames[0])
    # garbage is 1% of all bytes: after each frame, a run of garbage with this probability
    run = 4
    p_garbage = GARBAGE * frame_len / (run * (1 - GARBAGE))
    out, good, total = [], 0, 0
    while total < size:
        f = frames[rng.randrange(len(frames))]
        if rng.random() < CORRUPT:
            f = bytearray(f)
            f[rng.randrange(2, frame_len - 2)] ^= 1 << rng.randrange(8)
            f = bytes(f)
        else:
            good += 1
        out.append(f)
        total += frame_len
        if rng.random() < p_garbage:
            g = bytes(rng.randrange(256) for _ in range(run))
            out.append(g)
            total += run
    return b"".join(out), good


def mtv4_capture(size, seed=1):
    rng = random.Random(seed)
    frames = []
    for _ in range(256):
        m = mtv4.SetWheelsVelocitiesWithOdometry(
            group=rng.randrange(16), robots=mtv4.Robots(1 << rng.randrange(16)),
            status=mtv4.Status(rng.randrange(8)), vl=rng.randrange(-32768, 32768) / 8,
            vr=rng.randrange(-32768, 32768) / 8, x=struct.unpack("<f", struct.pack("<f", rng.uniform(-50, 50)))[0],
            y=0.5, th=rng.choice((0.0, 1.5, -3.0)))
        frames.append(mtv4.encode(m))
    return _stream(frames, size, seed)


def mavlink_capture(size, seed=2):
    rng = random.Random(seed)
    mav = peers.mavlink()
    frames = []
    for _ in range(256):
        values = dict(peers.ATTITUDE_VALUES, time_boot_ms=rng.randrange(1 << 31),
                      roll=rng.uniform(-3, 3), pitch=rng.uniform(-1.5, 1.5))
        frames.append(bytes(peers.pymavlink_attitude_encode(mav, values)))
    return _stream(frames, size, seed)


def _chunks(data):
    view = memoryview(data)
    return [bytes(view[i:i + CHUNK]) for i in range(0, len(data), CHUNK)]


def codeword_stream(chunks):
    dec = mtv4.StreamDecoder()
    good = 0
    for chunk in chunks:
        for item in dec.feed(chunk):
            if not isinstance(item, mtv4.DecodeError):
                good += 1
    return good


def handwritten_stream(chunks):
    """A hand-written resynchronising reader for the one frame kind of the capture."""
    buf = bytearray()
    good = 0
    decode = hw.mtv4_odometry_decode
    for chunk in chunks:
        buf += chunk
        pos = 0
        n = len(buf)
        while True:
            pos = buf.find(0xAA, pos)
            if pos < 0:
                pos = n
                break
            if n - pos < 26:
                break
            if buf[pos + 1] != 22:
                pos += 1
                continue
            try:
                decode(bytes(buf[pos:pos + 26]))
            except ValueError:
                pos += 1
                continue
            good += 1
            pos += 26
        del buf[:pos]
    return good


def pymavlink_stream(chunks):
    mav = peers.mavlink()
    mav.robust_parsing = True  # bad frames come back as MAVLink_bad_data instead of raising
    good = 0
    for chunk in chunks:
        for msg in mav.parse_buffer(chunk) or ():
            if msg.get_type() == "ATTITUDE":
                good += 1
    return good


def timed(fn, chunks, expected, found):
    """A job that decodes `chunks` once and returns the seconds it took; the
    good frames it found go to `found` (one count per run)."""
    def job():
        start = time.perf_counter()
        got = fn(chunks)
        elapsed = time.perf_counter() - start
        if got > expected:
            raise AssertionError(f"{fn.__name__}: {got} good frames, only {expected} were sent")
        found.append(got)
        return elapsed
    return job


def contenders(size_mtv4, size_mavlink):
    """{name: (job, bytes, good frames sent, good frames found per run)}."""
    cap, good = mtv4_capture(size_mtv4)
    mcap, mgood = mavlink_capture(size_mavlink)
    chunks, mchunks = _chunks(cap), _chunks(mcap)
    out = {}
    for name, fn, data, parts, sent in (
            ("codeword", codeword_stream, cap, chunks, good),
            ("hand-written", handwritten_stream, cap, chunks, good),
            ("pymavlink parse_buffer", pymavlink_stream, mcap, mchunks, mgood)):
        found = []
        out[name] = (timed(fn, parts, sent, found), len(data), sent, found)
    return out
