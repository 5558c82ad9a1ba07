"""`codeword monitor` on a port whose reads cut the stream anywhere: noise that comes in
a read of its own is shown, counted as skipped and not as a frame, exactly as a replay
of the same bytes shows it. The port is a fake that hands out the given chunks; the
frames are mtv4.yaml's examples (hex copied from the schema)."""
from __future__ import annotations

import pytest

from codeword.cli import main
from codeword.frames import monitor

ROBOT5 = bytes.fromhex("aa 08 03 01 20 00 24 03 60 ff 40 00")
ROBOT12 = bytes.fromhex("aa 08 0f 01 00 10 00 80 ff 7f 9c b3")


class FakePort:
    def __init__(self, chunks: list[bytes]):
        self.chunks = list(chunks)

    def read(self, size: int) -> bytes:
        return self.chunks.pop(0) if self.chunks else b""

    def close(self) -> None:
        pass


def summaries(out: str) -> list[str]:
    return [line.split("  ", 1)[1] for line in out.splitlines()]


@pytest.mark.parametrize("chunks", [
    [ROBOT5, b"\x00\x01", ROBOT12],                  # the noise in a read of its own
    [ROBOT5, b"\x00", b"", b"\x01", ROBOT12],         # over two reads, an empty one between
    [ROBOT5 + b"\x00", b"\x01" + ROBOT12[:3], ROBOT12[3:]],
])
def test_noise_in_reads_of_its_own_is_skipped(chunks, monkeypatch, capsys, tmp_path):
    monkeypatch.setattr(monitor, "_open_source", lambda args: FakePort(chunks))
    assert main(["monitor", "mtv4", "--port", "fake", "--count", "3", "--duration", "30"]) == 1
    captured = capsys.readouterr()
    rows = summaries(captured.out)
    assert len(rows) == 3
    assert rows[0].startswith("[1 frames, 0 errors, 0 skipped]  set_wheels_velocities group=3")
    assert rows[1] == "[1 frames, 0 errors, 2 skipped]  error: 2 byte(s) skipped: not a frame"
    assert rows[2].startswith("[2 frames, 0 errors, 2 skipped]  set_wheels_velocities group=15")
    assert "2 frames, 0 errors, 2 bytes skipped, 26 bytes read" in captured.err
    capture = tmp_path / "capture.bin"
    capture.write_bytes(b"".join(chunks))
    monkeypatch.undo()  # the replay reads the file
    assert main(["monitor", "mtv4", "--replay", str(capture)]) == 1
    assert summaries(capsys.readouterr().out) == rows


def test_noise_at_the_end_of_a_replay_is_shown(monkeypatch, capsys, tmp_path):
    capture = tmp_path / "capture.bin"
    capture.write_bytes(ROBOT5 + b"\x00\x01\x02")
    assert main(["monitor", "mtv4", "--replay", str(capture)]) == 1
    rows = summaries(capsys.readouterr().out)
    assert rows[1:] == ["[1 frames, 0 errors, 3 skipped]  error: 3 byte(s) skipped: not a frame"]
