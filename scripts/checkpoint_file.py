#!/usr/bin/python3
"""Reads and writes exdyn's restart checkpoints (docs/output.md, "Checkpoints";
src/output/checkpoint_file.hpp) in Python: the sections, their hashes and the trailer.
For tests that need a checkpoint the program must refuse (another version, a changed
section) with every checksum right, and for looking inside one:

    /usr/bin/python3 scripts/checkpoint_file.py CHECKPOINT      # lists the sections

A section written in pieces by the ranks of a run on many ranks (NAME#0, NAME#1, ...) is
listed joined, as the program reads it.
"""

import struct
import sys

HEAD = b"EXDYNCKP"
TAIL = b"EXDYNEND"
FORMAT = 1
MASK = (1 << 64) - 1


def _mix(x, w):
    x = ((x ^ w) * 0x9E3779B97F4A7C15) & MASK
    return ((x << 29) | (x >> 35)) & MASK


def hash_bytes(data):
    """The program's hash_bytes: four lanes of 8-byte words, the zero-padded tail, the length."""
    lanes = [0x243F6A8885A308D3, 0x13198A2E03707344, 0xA4093822299F31D0, 0x082EFA98EC4E6C89]
    n = len(data)
    full = n // 32 * 32
    words = struct.unpack_from(f"<{full // 8}Q", data)
    for i in range(0, len(words), 4):
        for k in range(4):
            lanes[k] = _mix(lanes[k], words[i + k])
    tail = bytes(data[full:]) + bytes(32 - (n - full))
    for k, w in enumerate(struct.unpack("<4Q", tail)):
        lanes[k] = _mix(lanes[k], w)
    h = n
    for lane in lanes:
        h = _mix(h, lane)
    return h ^ (h >> 31)


def read(path):
    """The sections of a checkpoint as an ordered dict name -> bytes (checksums checked)."""
    data = open(path, "rb").read()
    if data[:8] != HEAD or data[-32:-24] != TAIL:
        raise ValueError(f"{path} is not a whole exdyn checkpoint")
    count, total, _ = struct.unpack("<3Q", data[-24:])
    at = 12
    sections = {}
    for _ in range(count):
        (length,) = struct.unpack_from("<I", data, at)
        name = data[at + 4:at + 4 + length].decode()
        at += 4 + length
        size, digest = struct.unpack_from("<2Q", data, at)
        at += 16
        body = data[at:at + size]
        if hash_bytes(body) != digest:
            raise ValueError(f"{path}: section {name} does not match its checksum")
        sections[name] = body
        at += size
    return sections


def joined(sections):
    """The sections as the program reads them: those written in pieces (NAME#0, NAME#1, ...:
    a run on many ranks) joined into NAME, with the number of pieces of each."""
    whole, pieces = {}, {}
    for name, body in sections.items():
        base, mark, k = name.rpartition("#")
        if mark and k.isdigit():
            pieces.setdefault(base, {})[int(k)] = body
        else:
            whole[name] = (body, 1)
    for base, parts in pieces.items():
        if sorted(parts) != list(range(len(parts))) or base in whole:
            raise ValueError(f"section {base}: pieces {sorted(parts)[:8]} do not make it whole")
        whole[base] = (b"".join(parts[k] for k in range(len(parts))), len(parts))
    return whole


def write(path, sections):
    """Writes sections (name -> bytes, in order) as a checkpoint with every checksum right."""
    out = bytearray(HEAD + struct.pack("<I", FORMAT))
    headers = bytearray()
    for name, body in sections.items():
        key = name.encode()
        digest = hash_bytes(body)
        out += struct.pack("<I", len(key)) + key + struct.pack("<2Q", len(body), digest) + body
        headers += key + struct.pack("<2Q", len(body), digest)
    total = len(out) + 32
    out += TAIL + struct.pack("<3Q", len(sections), total, hash_bytes(bytes(headers)))
    with open(path, "wb") as f:
        f.write(out)


if __name__ == "__main__":
    for section, (value, count) in joined(read(sys.argv[1])).items():
        shown = value.decode(errors="replace")[:60].replace("\n", " ") if section in ("exdyn_version", "isa") else ""
        written = f" in {count} pieces" if count > 1 else ""
        print(f"{section:45s} {len(value):12d} bytes{written} {shown}")
