"""`beam_impact.load_log` on hostile files (issue 16, item 3: a Python reader as safe as `report`).

The reader is the Rust one of `beam-impact report` (the native module `beam_impact._native`); these
tests hold the Python package to its bounds. Goal: any file either loads or raises
`beam_impact.LogError` (a ValueError, one line), in time and memory bounded by the file's size: a FIFO, a device, a directory or a text file is refused at once;
a log format other than 1 or 2 is refused as `beam-impact report` refuses it; a zstd bomb (a chunk
declaring or holding far more than the file) is refused within a bounded memory; a log of
rollbacks loads in time linear in its messages (it was quadratic); 200 seeded mutations of real
logs (byte-level, and inside a chunk behind a correct CRC) raise nothing but LogError; and
`python -m beam_impact log` says what is wrong in one line on stderr, exit status 2, no traceback.

Tolerances: the bounds are generous multiples of what is measured on a shared 2-core machine
(time limits 5 s per file where the old reader took 25 s to minutes; memory growth 200 MB where it
took 1-3 GB); the linear-time check compares a rollback-heavy log with a log of as many step
messages without rollbacks, so it does not depend on the machine's speed.
"""

from __future__ import annotations

import math
import os
import random
import signal
import struct
import subprocess
import sys
import time
import zlib
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
import zstandard

from beam_impact import LogError, load_log

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "corpus" / "logs"
REAL = CORPUS / "real-2ms.mcap"  # a real run's log: format 1, zstd chunks
MAGIC = b"\x89MCAP0\r\n"
OP_HEADER, OP_FOOTER, OP_CHANNEL, OP_MESSAGE, OP_CHUNK, OP_METADATA, OP_DATA_END = 1, 2, 4, 5, 6, 0x0C, 0x0F
TOPICS = {"/beam/model": 1, "/beam/step": 2, "/beam/modes": 3, "/beam/contact": 4, "/beam/log": 5}
STEP_NS = 25_000


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


@contextmanager
def deadline(seconds: int):
    """Fails the test (instead of hanging it) if the block takes longer than `seconds`."""

    def expired(signum, frame):
        raise TimeoutError(f"still running after {seconds} s")

    previous = signal.signal(signal.SIGALRM, expired)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def assert_one_line(error: Exception) -> str:
    text = str(error)
    assert "\n" not in text and "\r" not in text and 0 < len(text) < 1000, repr(text)
    return text


# ------------------------------------------------------------------------------------------------
# Protobuf and MCAP written by hand, independently of the reader under test.


def varint(n: int) -> bytes:
    out = bytearray()
    while True:
        byte, n = n & 0x7F, n >> 7
        out.append(byte | (0x80 if n else 0))
        if not n:
            return bytes(out)


def pb_uint(field: int, n: int) -> bytes:
    return varint(field << 3) + varint(n)


def pb_double(field: int, x: float) -> bytes:
    return varint(field << 3 | 1) + struct.pack("<d", x)


def pb_bytes(field: int, data: bytes) -> bytes:
    return varint(field << 3 | 2) + varint(len(data)) + data


def step_message(k: int, coordinates=None) -> bytes:
    """A beam_impact.Step: step k at k * 25 us, a deflection, energies and peaks, and (format 1)
    float32 modal coordinates."""
    body = pb_uint(1, k) + pb_uint(2, k * STEP_NS) + pb_double(4, STEP_NS * 1e-9) + pb_double(6, -math.sin(k * 1e-3))
    body += pb_bytes(14, pb_double(1, float(k)) + pb_double(6, 1e-9 * k)) + pb_bytes(15, pb_double(1, float(k)))
    if coordinates is not None:
        body += pb_bytes(16, struct.pack(f"<{len(coordinates)}f", *coordinates))
    return body


def modes_message(k: int, coordinates) -> bytes:
    return pb_uint(1, k) + pb_uint(2, k * STEP_NS) + pb_bytes(4, struct.pack(f"<{len(coordinates)}d", *coordinates))


def contact_message(k: int, start: bool) -> bytes:
    body = pb_uint(1, int(start)) + pb_uint(2, k * STEP_NS) + pb_uint(3, k)
    return body + pb_double(4, -1.0) + pb_double(5, k * STEP_NS * 1e-9)


def model_message(cols: int, rows: int = 2) -> bytes:
    shapes = struct.pack(f"<{rows * cols}d", *range(rows * cols))
    return (
        pb_bytes(1, b"drop_height = 0.8\n")
        + pb_bytes(2, struct.pack("<2d", 0.0, 12.0))
        + pb_bytes(3, struct.pack("<2d", 0.0, 29.0))
        + pb_uint(4, rows)
        + pb_uint(5, cols)
        + pb_bytes(6, shapes)
    )


def record(opcode: int, body: bytes) -> bytes:
    return struct.pack("<BQ", opcode, len(body)) + body


def string(text: str) -> bytes:
    data = text.encode()
    return struct.pack("<I", len(data)) + data


def string_map(pairs: dict) -> bytes:
    data = b"".join(string(k) + string(v) for k, v in pairs.items())
    return struct.pack("<I", len(data)) + data


def message(channel: int, log_time: int, data: bytes) -> bytes:
    return record(OP_MESSAGE, struct.pack("<HIQQ", channel, 0, log_time, log_time) + data)


def chunk(records: bytes, compression: str = "zstd", declared: int | None = None, data: bytes | None = None) -> bytes:
    """A chunk record of `records` (compressed with `compression`, or `data` as given), declaring
    `declared` uncompressed bytes (default: the truth) and the records' CRC."""
    if data is None:
        data = zstandard.ZstdCompressor(level=3).compress(records) if compression == "zstd" else records
    size = len(records) if declared is None else declared
    body = struct.pack("<QQQI", 0, 0, size, zlib.crc32(records)) + string(compression)
    return record(OP_CHUNK, body + struct.pack("<Q", len(data)) + data)


def build_log(messages, metadata: dict | None = None, per_chunk: int = 2000, compression: str = "zstd") -> bytes:
    """A log as the recorder lays it out: header, channels, the `scenario` metadata, the
    messages ((topic, data) in order, log time = their index) in chunks of `per_chunk`, data end,
    footer and closing magic."""
    out = [MAGIC, record(OP_HEADER, string("beam-impact") + string("test"))]
    channels = b"".join(
        record(OP_CHANNEL, struct.pack("<HH", id, 0) + string(topic) + string("protobuf") + string_map({}))
        for topic, id in TOPICS.items()
    )
    out.append(chunk(channels, compression))
    metadata = {"log_format": "2"} if metadata is None else metadata
    out.append(record(OP_METADATA, string("scenario") + string_map(metadata)))
    batch = []
    for t, (topic, data) in enumerate(messages):
        batch.append(message(TOPICS[topic], t, data))
        if len(batch) == per_chunk:
            out.append(chunk(b"".join(batch), compression))
            batch = []
    if batch:
        out.append(chunk(b"".join(batch), compression))
    out += [record(OP_DATA_END, struct.pack("<I", 0)), record(OP_FOOTER, struct.pack("<QQI", 0, 0, 0)), MAGIC]
    return b"".join(out)


def top_records(log: bytes):
    """(opcode, start, end) of each record at the top level of `log`, while the framing holds."""
    pos = len(MAGIC)
    while pos + 9 <= len(log):
        opcode, length = struct.unpack_from("<BQ", log, pos)
        if length > len(log) - pos - 9:
            return
        yield opcode, pos, pos + 9 + length
        pos += 9 + length


def edit_chunks(log: bytes, edit) -> bytes:
    """`log` with the records of each zstd or uncompressed chunk rewritten by edit(index, records)
    and recompressed with a correct size and CRC: mutations that reach the messages."""
    out, last, index = [log[:8]], 8, 0
    for opcode, start, end in top_records(log):
        if opcode != OP_CHUNK:
            continue
        body = log[start + 9 : end]
        (clen,) = struct.unpack_from("<I", body, 28)
        compression = body[32 : 32 + clen].decode()
        (dlen,) = struct.unpack_from("<Q", body, 32 + clen)
        data = body[40 + clen : 40 + clen + dlen]
        if compression == "zstd":
            records = zstandard.ZstdDecompressor().decompress(data, max_output_size=1 << 24)
        elif compression == "":
            records = data
        else:
            continue
        out += [log[last:start], chunk(edit(index, records), compression)]
        last, index = end, index + 1
    out.append(log[last:])
    return b"".join(out)


def with_metadata(log: bytes, **changes: str) -> bytes:
    """`log` with its `scenario` metadata record rewritten with `changes` (added or replaced)."""
    for opcode, start, end in top_records(log):
        if opcode != OP_METADATA:
            continue
        body, pos, pairs = log[start + 9 : end], 0, {}
        (n,) = struct.unpack_from("<I", body, pos)
        name, pos = body[4 : 4 + n].decode(), 4 + n
        (size,) = struct.unpack_from("<I", body, pos)
        pos, stop = pos + 4, pos + 4 + size
        while pos < stop:
            (n,) = struct.unpack_from("<I", body, pos)
            key, pos = body[pos + 4 : pos + 4 + n].decode(), pos + 4 + n
            (n,) = struct.unpack_from("<I", body, pos)
            pairs[key], pos = body[pos + 4 : pos + 4 + n].decode(), pos + 4 + n
        if name == "scenario":
            pairs.update(changes)
            return log[:start] + record(OP_METADATA, string(name) + string_map(pairs)) + log[end:]
    raise AssertionError("no scenario metadata record")


NASTY = [0, 1, 7, 8, 9, 0x7F, 0x80, 0xFF, 0xFFFF, 0x7FFF_FFFF, 0xFFFF_FFFF, 1 << 32, 1 << 40, 1 << 62,
         (1 << 63) - 1, (1 << 64) - 9, (1 << 64) - 1]


def mutate(data: bytes, rng: random.Random) -> bytes:
    """One to four byte-level mutations (those of tests/fuzz_support's `mutate`): bit flips,
    interesting bytes, 8- and 4-byte length fields, truncation, deletion, duplication and
    insertion of ranges, a record length after an opcode."""
    b = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        if not b:
            b.append(rng.randrange(256))
            continue
        at, kind = rng.randrange(len(b)), rng.randrange(9)
        if kind == 0:
            b[at] ^= 1 << rng.randrange(8)
        elif kind == 1:
            b[at] = rng.choice([0, 1, 0x7F, 0x80, 0xFF, 0x05, 0x06])
        elif kind == 2 and at + 8 <= len(b):
            b[at : at + 8] = struct.pack("<Q", rng.choice(NASTY))
        elif kind == 3 and at + 4 <= len(b):
            b[at : at + 4] = struct.pack("<I", rng.choice(NASTY) & 0xFFFF_FFFF)
        elif kind == 4:
            del b[at:]
        elif kind == 5:
            del b[at : at + 1 + rng.randrange(64)]
        elif kind == 6:
            piece = b[at : at + 1 + rng.randrange(256)]
            to = rng.randrange(len(b))
            b[to:to] = piece
        elif kind == 7:
            b[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
        elif kind == 8:
            opcodes = [i for i in range(len(b) - 8) if 1 <= b[i] <= 0x0F]
            if opcodes:
                i = rng.choice(opcodes)
                b[i + 1 : i + 9] = struct.pack("<Q", rng.choice(NASTY))
    return bytes(b)


def mutate_log(log: bytes, rng: random.Random) -> bytes:
    """Half the time byte-level, half inside one chunk's records behind a correct CRC."""
    if rng.randrange(2) == 0:
        return mutate(log, rng)
    target = rng.randrange(max(1, sum(op == OP_CHUNK for op, _, _ in top_records(log))))
    inner = random.Random(rng.getrandbits(64))
    return edit_chunks(log, lambda i, records: mutate(records, inner) if i == target else records)


# ------------------------------------------------------------------------------------------------


def test_files_that_are_not_regular_are_refused_without_waiting(tmp_path):
    fifo = tmp_path / "fifo.mcap"
    os.mkfifo(fifo)
    # Opening a FIFO for reading waits for a writer: it must not be opened for reading.
    for path in [fifo, tmp_path, Path("/dev/null")]:
        with deadline(5), pytest.raises(LogError, match="not a regular file|is a directory") as e:
            load_log(path)
        assert str(path) in assert_one_line(e.value)
    # A missing file is a bad file too: the same exception type.
    with pytest.raises(LogError, match="No such file"):
        load_log(tmp_path / "missing.mcap")
    assert issubclass(LogError, ValueError)


def test_text_files_empty_files_and_files_too_large_are_refused(tmp_path):
    text = tmp_path / "hostname"
    text.write_text("beam-impact-host\n")
    paths = [text, CORPUS / "empty.mcap", CORPUS / "not-mcap.mcap", CORPUS / "magic-only.mcap"]
    if Path("/etc/hostname").is_file():
        paths.append(Path("/etc/hostname"))
    for path in paths:
        with pytest.raises(LogError, match="not a readable MCAP log") as e:
            load_log(str(path))
        assert str(path) in assert_one_line(e.value)


def test_the_committed_hostile_corpus_loads_or_raises_log_error():
    """Every file of tests/corpus/logs (the crafted ones `report` is tested on): a Log or a
    LogError, nothing else."""
    outcomes = {}
    for path in sorted(CORPUS.glob("*.mcap")):
        with deadline(10):
            try:
                log = load_log(path)
                outcomes[path.name] = "complete" if log.complete else "damaged" if log.damaged else "cut short"
            except LogError as e:
                assert_one_line(e)
                outcomes[path.name] = "LogError"
    assert outcomes["real-2ms.mcap"] == "complete"
    assert outcomes["real-bit-flipped.mcap"] == "damaged"
    assert outcomes["real-cut-half.mcap"] == "cut short"
    assert outcomes["chunk-declares-2p40.mcap"] == outcomes["zstd-bomb-8mib.mcap"] == "LogError"


def test_log_formats_other_than_1_and_2_are_refused_as_report_refuses_them(tmp_path):
    real = REAL.read_bytes()
    assert "log_format" not in load_log(REAL).metadata  # format 1: no log_format
    path = tmp_path / "format.mcap"
    # As Rust's u32 parse: an optional "+" and decimal digits.
    for accepted in ["1", "2", "+2", "02"]:
        path.write_bytes(with_metadata(real, log_format=accepted))
        assert load_log(path).metadata["log_format"] == accepted
    for refused in ["3", "xxx", "", "0", "-1", "2.0", " 2", "2\n", "１", str(2**70), "x" * 10_000]:
        path.write_bytes(with_metadata(real, log_format=refused))
        with pytest.raises(LogError, match="log format .* is not one this reader knows") as e:
            load_log(path)
        text = assert_one_line(e.value)
        assert len(text) < len(str(path)) + 400, "a value from the file is quoted short"


def test_zstd_bombs_are_refused_in_bounded_time_and_memory(tmp_path):
    """Chunks that declare, or hold, far more than the file, read in a fresh process whose peak
    resident memory is compared with its resident memory before each reading."""
    zeros = zstandard.ZstdCompressor(level=3).compressobj()
    bomb = b"".join(zeros.compress(bytes(1 << 20)) for _ in range(256)) + zeros.flush()  # 256 MiB, unsized
    sized = zstandard.ZstdCompressor(level=3).compress(bytes(64 << 20))  # its frame says 64 MiB

    def start(width: int = 2) -> bytes:  # a log with a model message, up to its data end
        return build_log([("/beam/model", model_message(width))])[: -(9 + 4 + 9 + 20 + 8)]

    # Chunks of 100 KB of step messages, or 800 KB of coordinates, in ~150 bytes of zstd each.
    steps = chunk(b"".join(message(2, 0, step_message(0)) for _ in range(1000))) * 1000
    rows = chunk(b"".join(message(3, 0, modes_message(0, [0.0] * 1000)) for _ in range(100))) * 3000
    ending = record(OP_DATA_END, struct.pack("<I", 0)) + record(OP_FOOTER, bytes(20)) + MAGIC
    files = {
        "corpus-8mib": (CORPUS / "zstd-bomb-8mib.mcap").read_bytes(),
        # 256 MiB declared: more than 64x the file (or than the 64 MiB a chunk may be), refused
        # before decompressing.
        "declares-256mib": start() + chunk(b"", "zstd", declared=256 << 20, data=bomb) + ending,
        # Declares 64 KiB but holds 256 MiB of zeros: decompression stops one byte past 64 KiB.
        "holds-256mib": start() + chunk(b"", "zstd", declared=64 << 10, data=bomb) + ending,
        # Its frame header claims 64 MiB, the chunk 4 KiB: the frame's own size is not trusted.
        "frame-claims-64mib": start() + chunk(b"", "zstd", declared=4096, data=sized) + ending,
        # Valid chunks of identical step messages (each after the first a rollback): read until
        # the 64x budget, or the bound on what is decoded, stops it.
        "64x-of-steps": start() + steps + ending,
        # Rows of 1000 modal coordinates, kept until the bound on what is kept stops them.
        "64x-of-coordinates": start(1000) + rows + ending,
    }
    paths = []
    for name, data in files.items():
        paths.append(tmp_path / f"{name}.mcap")
        paths[-1].write_bytes(data)
    # Growth = the peak resident size after the reading (a high-water mark: at least the one
    # before it) less the resident size before it. The peak is this process's own VmHWM (of its
    # memory map), not ru_maxrss: Linux carries ru_maxrss across exec, and a child spawned with a
    # shared memory map (posix_spawn/vfork) starts from the parent's peak, pytest's, which the
    # suite's earlier in-process log loads raise past 400 MB.
    script = (
        # numpy and pandas (which the package's Log uses) imported before the first measure: their
        # ~100 MB are no growth from a file.
        "import os, resource, sys, time, zstandard, numpy, pandas, beam_impact, beam_impact._native\n"
        "for path in sys.argv[1:]:\n"
        "    with open('/proc/self/statm') as statm:\n"
        "        base = int(statm.read().split()[1]) * os.sysconf('SC_PAGE_SIZE') / 1024\n"
        "    t = time.process_time()\n"
        "    try:\n"
        "        log = beam_impact.load_log(path)\n"
        "        outcome = f'loaded, complete {log.complete}: {log.problem}'\n"
        "    except beam_impact.LogError as e:\n"
        "        outcome = f'LogError: {e}'\n"
        "    with open('/proc/self/status') as status:\n"
        "        peak = next(int(l.split()[1]) for l in status if l.startswith('VmHWM:'))\n"
        "    grown = (peak - base) / 1024\n"
        "    print(f'{time.process_time() - t:.3f}\\t{grown:.1f}\\t{outcome}')\n"
    )
    run = subprocess.run([sys.executable, "-c", script, *map(str, paths)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert len(lines) == len(paths), run.stdout
    for path, line in zip(paths, lines):
        seconds, grown, outcome = line.split("\t")
        print(f"{path.name} ({path.stat().st_size} bytes): {seconds} s of CPU, peak memory +{grown} MB: {outcome[:160]}")
        # A bound against a reader that decodes the bomb (256 MiB of zstd takes seconds of CPU, and
        # memory): CPU time of this process, not wall time, so a loaded machine does not fail it;
        # measured 0.000-0.082 s per file (2-core machine, 2026-11-26), so 10 s is a hang, not noise.
        assert float(seconds) < 10 and float(grown) < 200, (path.name, line)
        if not path.name.startswith("64x"):
            assert outcome.startswith("LogError") or "complete False" in outcome, (path.name, outcome)
    assert "more than the" in lines[1] and "does not decompress" in lines[2] and "does not decompress" in lines[3]
    assert "decodes to more than" in lines[4] or "64x the file" in lines[4], lines[4]
    assert "decodes to more than" in lines[5], lines[5]


def rollback_log(n: int, width: int = 4) -> bytes:
    """A format 1 log of `n` steps, each recorded, rolled back to the step before and recorded
    again (the recorder's pattern around an FMU state restored at every step), a contact event
    after every 100th: 3n - 2 step messages, n - 1 rollbacks; uncompressed chunks."""

    def q(k):
        return [float(k)] * width

    messages = [("/beam/model", model_message(width)), ("/beam/step", step_message(0, q(0)))]
    for k in range(1, n):
        step = ("/beam/step", step_message(k, q(k)))
        messages += [step, ("/beam/step", step_message(k - 1, q(k - 1))), step]
        if k % 100 == 0:
            messages.append(("/beam/contact", contact_message(k, k % 200 == 100)))
    return build_log(messages, metadata={}, compression="")


def test_rollbacks_load_in_linear_time(tmp_path):
    """20 000 rollbacks in 60 000 step messages (format 1: a row of coordinates in each), and
    20 000 over 40 000 rows of coordinates in decreasing step order, against a log of 60 000 step
    messages without rollbacks."""
    n, width = 20_000, 4
    path = tmp_path / "rollbacks.mcap"
    path.write_bytes(rollback_log(n, width))
    # As many step messages without a rollback, for the time a log of that size takes.
    linear = tmp_path / "linear.mcap"
    messages = [("/beam/model", model_message(width))]
    messages += [("/beam/step", step_message(k, [float(k)] * width)) for k in range(3 * n - 2)]
    linear.write_bytes(build_log(messages, metadata={}, compression=""))
    # Hostile: modal rows in decreasing step order, then steps going back one by one, each a
    # rollback dropping one row (filtering every row at every rollback was quadratic here too).
    backwards = tmp_path / "backwards.mcap"
    messages = [("/beam/model", model_message(width))]
    messages += [("/beam/modes", modes_message(k, [float(k)] * width)) for k in range(2 * n, 0, -1)]
    messages += [("/beam/step", step_message(k)) for k in range(n, 0, -1)]
    backwards.write_bytes(build_log(messages, compression=""))

    def timed(p):
        started = time.perf_counter()
        log = load_log(p)
        return log, time.perf_counter() - started

    with deadline(120):
        reference, t_linear = timed(linear)
        log, t_rollbacks = timed(path)
        back, t_back = timed(backwards)
    print(f"{3 * n - 2} step messages: {t_linear:.2f} s without rollbacks, {t_rollbacks:.2f} s with {n - 1}; "
          f"{n} rollbacks over {2 * n} unordered rows: {t_back:.2f} s")
    assert len(reference.steps["step"]) == 3 * n - 2 and reference.complete
    assert log.complete and log.rollbacks == n - 1
    assert np.array_equal(log.steps["step"], np.arange(n, dtype=np.uint64))
    assert np.array_equal(log.modal_steps, np.arange(n, dtype=np.uint64))
    assert np.array_equal(log.modal_coordinates[:, 0], np.arange(n, dtype=np.float64))
    assert [e["step"] for e in log.events] == list(range(100, n, 100))
    assert back.rollbacks == n - 1 and list(back.steps["step"]) == [1]
    assert back.modal_steps.size == 0, "every row is of a step >= 1: superseded by the last rollback"
    # Linear: the rollbacks cost no more than the messages (the quadratic reader took minutes).
    assert t_rollbacks < 2 * t_linear + 1.0, (t_rollbacks, t_linear)
    assert t_back < 2 * t_linear + 1.0, (t_back, t_linear)


def test_a_rollback_drops_exactly_the_superseded_rows_and_events(tmp_path):
    """Rows of modal coordinates are not in step order (a peak's coordinates follow later steps):
    a rollback to step s drops the rows of steps >= s wherever they are, and the events after s."""
    width = 2
    messages = [("/beam/model", model_message(width))]
    for k in range(0, 41):
        messages.append(("/beam/step", step_message(k)))
        if k in (5, 15, 27):
            messages.append(("/beam/contact", contact_message(k, k != 15)))
        if k in (10, 20, 30, 40):
            messages.append(("/beam/modes", modes_message(k, [k, k])))
        if k == 30:
            messages.append(("/beam/modes", modes_message(25, [25, 25])))  # the peak at step 25
    messages.append(("/beam/step", step_message(26)))  # the rollback
    path = tmp_path / "peak.mcap"
    path.write_bytes(build_log(messages))
    log = load_log(path)
    assert log.rollbacks == 1 and list(log.steps["step"]) == list(range(27))
    assert list(log.modal_steps) == [10, 20, 25]
    assert log.modal_coordinates.tolist() == [[10, 10], [20, 20], [25, 25]]
    assert [e["step"] for e in log.events] == [5, 15]


@pytest.fixture(scope="module")
def format_2_log(tmp_path_factory):
    path = tmp_path_factory.mktemp("hostile") / "run.mcap"
    subprocess.run(
        [binary(), "run", "--set", "duration=0.01", "--log-compression", "zstd", "--mcap", str(path)],
        check=True,
        capture_output=True,
    )
    return path.read_bytes()


def test_mutations_of_real_logs_load_or_raise_log_error(tmp_path, format_2_log):
    """200 seeded mutations, 100 of each real log: nothing but a Log or a LogError, each in
    bounded time, and a Log's arrays fit together."""
    outcomes: dict[str, int] = {}
    failures, slowest = [], (0.0, "")
    path = tmp_path / "mutation.mcap"
    started = time.perf_counter()
    for source, log_bytes in [("real-2ms", REAL.read_bytes()), ("format-2", format_2_log)]:
        for i in range(100):
            rng = random.Random(f"{source}-{i}")
            path.write_bytes(mutate_log(log_bytes, rng))
            t = time.perf_counter()
            try:
                with deadline(30):
                    log = load_log(path)
                outcome = "complete" if log.complete else "damaged" if log.damaged else "cut short"
                n = len(log.steps["step"])
                assert all(len(column) == n for column in log.steps.values())
                assert log.modal_coordinates.shape == (len(log.modal_steps), log.nodal_shapes.shape[1])
                assert log.complete == (log.problem == "") and "\n" not in log.problem
                # The stress envelope (issue 30): stored, rebuilt from the stations or None; the
                # stations' rows fit their layout.
                envelope = log.envelope
                assert "\n" not in log.envelope_note
                if envelope is not None:
                    assert envelope["source"] in ("attachment", "rebuilt")
                if log.station_layout is not None:
                    assert log.station_values.shape == (len(log.station_steps), len(log.stations))
            except LogError as e:
                assert_one_line(e)
                outcome = "LogError"
            except Exception as e:  # anything else is the bug this test is for
                failures.append(f"{source} mutation {i}: {type(e).__name__}: {e}"[:300])
                outcome = "other exception"
            elapsed = time.perf_counter() - t
            slowest = max(slowest, (elapsed, f"{source} mutation {i}"))
            outcomes[outcome] = outcomes.get(outcome, 0) + 1
    total = time.perf_counter() - started
    print(f"200 mutations in {total:.1f} s: {outcomes}; slowest {slowest[0]:.3f} s ({slowest[1]})")
    assert not failures, failures[:5]
    assert slowest[0] < 5 and total < 60
    # Both outcomes occur: the mutations reach the messages, not only the framing.
    assert outcomes.get("LogError", 0) > 0 and outcomes.get("complete", 0) + outcomes.get("damaged", 0) > 0


def test_the_cli_says_what_is_wrong_in_one_line(tmp_path):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    text = tmp_path / "hostname"
    text.write_text("beam-impact-host\n")
    bad_format = tmp_path / "format-3.mcap"
    bad_format.write_bytes(with_metadata(REAL.read_bytes(), log_format="3"))
    cases = [
        (text, "not a readable MCAP log"),
        (fifo, "not a regular file"),
        (tmp_path, "is a directory"),
        (tmp_path / "missing.mcap", "No such file"),
        (bad_format, 'log format "3" is not one this reader knows'),
    ]
    if Path("/etc/hostname").is_file():
        cases.append((Path("/etc/hostname"), "not a readable MCAP log"))
    for path, expected in cases:
        run = subprocess.run(
            [sys.executable, "-m", "beam_impact", "log", str(path)], capture_output=True, text=True, timeout=60
        )
        assert run.returncode == 2, (path, run.stdout, run.stderr)
        assert "Traceback" not in run.stderr and run.stdout == "", (path, run.stderr)
        lines = run.stderr.splitlines()
        assert len(lines) == 1 and lines[0].startswith("beam_impact: ") and expected in lines[0], (path, run.stderr)
    # A readable log still prints its summary.
    run = subprocess.run(
        [sys.executable, "-m", "beam_impact", "log", str(REAL)], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 0 and "90 step messages" in run.stdout, run.stderr
