#!/usr/bin/env python3
"""Compares two MCAP logs of the same run byte for byte (Python standard library only).

Usage: scripts/mcap_compare.py A.mcap B.mcap

Prints one line: the bytes compared and the records, chunks and messages per topic the logs hold;
exit code 0 when they are identical. When they differ, one line saying where: the first differing
record (its kind and number; inside a chunk: the chunk's number, the message's topic, its index on
that topic, its sequence number and log time), and the byte offset; exit code 1.

Nothing is masked. What the recorder writes (src/record/) holds no field that may differ between
two runs of the same scenario, on one platform or two: the Header is profile "beam-impact" and
library "mcap-rust/<version>" (the crate's, not the platform's), the Metadata record is the scenario
with the crate version and the log format, the attachments (scenario.toml, modelDescription.xml)
carry log_time = create_time = 0, every message's times are simulated times, the log lines are
made of simulated values; no wall-clock time, path, instance name, host or platform string is
written. (log.path, the instance name and the library's platform are in the FMU's logger messages,
not in the log.) So a log of the win64 DLL under wine must equal the Linux library's byte for byte.

Compressed chunks (zstd by default since issue 41, lz4) are compared as their bytes: the same
compressor (the zstd and lz4 C sources the crate builds, on every platform) at the same level
gives the same bytes for the same records; their messages are counted from the MessageIndex
records after each chunk, and a difference inside one is reported at the chunk (its records are
not decompressed here: the standard library has no zstd).
"""

import struct
import sys

MAGIC = b"\x89MCAP0\r\n"
KINDS = {
    0x01: "Header",
    0x02: "Footer",
    0x03: "Schema",
    0x04: "Channel",
    0x05: "Message",
    0x06: "Chunk",
    0x07: "MessageIndex",
    0x08: "ChunkIndex",
    0x09: "Attachment",
    0x0A: "AttachmentIndex",
    0x0B: "Statistics",
    0x0C: "Metadata",
    0x0D: "MetadataIndex",
    0x0E: "SummaryOffset",
    0x0F: "DataEnd",
}


class Bad(Exception):
    pass


def records(data, start, end):
    """(offset, opcode, body start, body end) of each record in data[start:end]."""
    at = start
    while at < end:
        if at + 9 > end:
            raise Bad(f"a record header cut short at byte {at}")
        op = data[at]
        (length,) = struct.unpack_from("<Q", data, at + 1)
        body = at + 9
        if body + length > end:
            raise Bad(f"record {KINDS.get(op, hex(op))} at byte {at} runs past its end")
        yield at, op, body, body + length
        at = body + length


def string(data, at):
    (n,) = struct.unpack_from("<I", data, at)
    return data[at + 4 : at + 4 + n].decode("utf-8", "replace"), at + 4 + n


def chunk_records(data, body):
    """Where a Chunk's records lie, and its compression."""
    at = body + 8 + 8 + 8 + 4
    compression, at = string(data, at)
    (length,) = struct.unpack_from("<Q", data, at)
    return compression, at + 8, at + 8 + length


class Log:
    """One log: its bytes, the data section's records, channel topics, message counts."""

    def __init__(self, path):
        self.path = path
        with open(path, "rb") as f:
            self.data = f.read()
        d = self.data
        if len(d) < 2 * len(MAGIC) or d[: len(MAGIC)] != MAGIC or d[-len(MAGIC) :] != MAGIC:
            raise Bad(f"{path} is not a complete MCAP file (magic missing at its start or end)")
        self.top = list(records(d, len(MAGIC), len(d) - len(MAGIC)))
        self.topics = {}
        for _, op, body, _ in self.top:
            if op == 0x04:
                (cid,) = struct.unpack_from("<H", d, body)
                self.topics[cid], _ = string(d, body + 4)

    def inner(self, body):
        """A chunk's records; none for a compressed chunk (compared as its bytes)."""
        compression, start, end = chunk_records(self.data, body)
        if compression:
            return iter(())
        return records(self.data, start, end)

    def count(self):
        """Records (a compressed chunk's own not decoded), chunks and messages per topic (from
        the MessageIndex records: channel id, then the byte length of its (time, offset) pairs)."""
        n, chunks, per_topic = 0, 0, {}
        for _, op, body, _ in self.top:
            n += 1
            if op == 0x06:
                chunks += 1
                n += sum(1 for _ in self.inner(body))
            elif op == 0x07:
                cid, length = struct.unpack_from("<HI", self.data, body)
                topic = self.topics.get(cid, f"channel {cid}")
                per_topic[topic] = per_topic.get(topic, 0) + length // 16
        return n, chunks, per_topic


def first_difference(a, b):
    """One line saying where logs a and b first differ (they do)."""
    da, db = a.data, b.data
    seen = {}  # messages per channel so far (identical in both until the difference)
    chunk = 0
    for i, (ra, rb) in enumerate(zip(a.top, b.top)):
        (oa, opa, ba, ea), (ob, opb, bb, eb) = ra, rb
        if da[oa:ea] == db[ob:eb]:
            if opa == 0x06:
                chunk += 1
                for _, iop, ibody, _ in a.inner(ba):
                    if iop == 0x05:
                        (cid,) = struct.unpack_from("<H", da, ibody)
                        seen[cid] = seen.get(cid, 0) + 1
            continue
        where = f"record #{i} ({KINDS.get(opa, hex(opa))} at byte {oa}"
        if opa != opb:
            return f"{where}) is a {KINDS.get(opb, hex(opb))} in {b.path}"
        if opa != 0x06:
            return f"{where}) differs"
        for j, (x, y) in enumerate(zip(a.inner(ba), b.inner(bb))):
            (xo, xop, xb, xe), (yo, yop, yb, ye) = x, y
            if da[xo:xe] == db[yo:ye]:
                if xop == 0x05:
                    (cid,) = struct.unpack_from("<H", da, xb)
                    seen[cid] = seen.get(cid, 0) + 1
                continue
            inside = f"{where}: chunk #{chunk}, its record #{j}, {KINDS.get(xop, hex(xop))} at byte {xo}"
            if xop == 0x05 and yop == 0x05:
                cid, seq, log_time = struct.unpack_from("<HIQ", da, xb)
                topic = a.topics.get(cid, f"channel {cid}")
                k = seen.get(cid, 0)
                same_header = da[xb : xb + 22] == db[yb : yb + 22]
                what = "its data" if same_header else "its header (channel, sequence or times)"
                return f"{inside}) differs: {topic} message #{k} (sequence {seq}, log time {log_time} ns), {what}"
            return f"{inside}) differs"
        compression, _, _ = chunk_records(da, ba)
        if compression:
            return f"{where}) differs: chunk #{chunk}, compressed with {compression} (not decoded here)"
        return f"{where}) differs: chunk #{chunk} holds a different number of records or its header differs"
    if len(a.top) != len(b.top):
        return f"{a.path} has {len(a.top)} records, {b.path} {len(b.top)}"
    return "the bytes differ outside the records (magic)"


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: mcap_compare.py A.mcap B.mcap")
    try:
        a, b = Log(sys.argv[1]), Log(sys.argv[2])
        if a.data != b.data:
            print(f"mcap-compare: {a.path} and {b.path} differ at {first_difference(a, b)}")
            return 1
        n, chunks, per_topic = a.count()
    except (Bad, struct.error) as e:
        print(f"mcap-compare: {e}")
        return 1
    messages = sum(per_topic.values())
    topics = ", ".join(f"{t} {c}" for t, c in sorted(per_topic.items()))
    print(f"{len(a.data)} bytes identical, 0 masked: {n} records, {chunks} chunks, {messages} messages ({topics})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
