#!/usr/bin/env python3
"""Writes the decompression bombs of the recording fuzzers' seed corpora (docs/formats.md,
"Limits of recordings"): a few kB that declare, and would really decompress to, far more than a
chunk may hold. Run once from the repository's root; the files are kept in the corpora:

  python3 formats/fuzz/make_bombs.py

- rosbag_fuzzer/bomb-bz2.bag: python-bz2.bag with its first chunk's data replaced by bzip2 of
  1 GiB of zeros (its `size` says so, and the bag header's index position follows the chunk);
- mcap_fuzzer/bomb-zstd.mcap: one zstd chunk of 1 GiB of zeros (zstd, the command, from Debian).
Before the limits, each cost seconds and gigabytes before it was refused."""
import bz2
import struct
import subprocess

BOMB_BYTES = 1 << 30


def zeros_compressed(compress):
    piece = bytes(1 << 20)
    return compress(piece, BOMB_BYTES // len(piece))


def bzip2_zeros(piece, count):
    c = bz2.BZ2Compressor(9)
    out = b"".join(c.compress(piece) for _ in range(count))
    return out + c.flush()


def zstd_zeros(piece, count):
    run = subprocess.run(["zstd", "-19", "-q", "-c"], input=piece * count, capture_output=True,
                         check=True)
    return run.stdout


def field(name, value):
    f = name + b"=" + value
    return struct.pack("<I", len(f)) + f


def header_fields(data):
    fields, i = [], 0
    while i < len(data):
        n = struct.unpack("<I", data[i:i + 4])[0]
        k, v = data[i + 4:i + 4 + n].split(b"=", 1)
        fields.append((k, v))
        i += 4 + n
    return fields


def rosbag_bomb():
    bag = open("formats/fuzz/corpus/rosbag_fuzzer/python-bz2.bag", "rb").read()
    at = 13
    header_len = struct.unpack("<I", bag[at:at + 4])[0]
    bag_header = header_fields(bag[at + 4:at + 4 + header_len])
    chunk_at = at + 8 + header_len + struct.unpack("<I", bag[at + 4 + header_len:at + 8 +
                                                             header_len])[0]
    chunk_header_len = struct.unpack("<I", bag[chunk_at:chunk_at + 4])[0]
    chunk_fields = header_fields(bag[chunk_at + 4:chunk_at + 4 + chunk_header_len])
    data_len_at = chunk_at + 4 + chunk_header_len
    data_len = struct.unpack("<I", bag[data_len_at:data_len_at + 4])[0]
    data = zeros_compressed(bzip2_zeros)
    chunk_header = b"".join(
        field(k, struct.pack("<I", BOMB_BYTES) if k == b"size" else v) for k, v in chunk_fields)
    chunk = struct.pack("<I", len(chunk_header)) + chunk_header + struct.pack("<I", len(data)) + data
    rest = bag[data_len_at + 4 + data_len:]
    shift = len(chunk) - (data_len_at + 4 + data_len - chunk_at)
    fields = []
    for k, v in bag_header:
        if k == b"index_pos":
            v = struct.pack("<Q", struct.unpack("<Q", v)[0] + shift)
        fields.append(field(k, v))
    new_header = b"".join(fields)
    # The bag header record is padded to 4096 bytes: keep its length.
    padded = bag[at:chunk_at]
    header_record = struct.pack("<I", len(new_header)) + new_header
    header_record += padded[len(header_record):]
    out = bytearray(bag[:at] + header_record + chunk + rest)
    # The chunk infos at the index give each chunk's position: those after the first move too.
    pos = struct.unpack("<Q", dict(bag_header)[b"index_pos"])[0] + shift
    while pos < len(out):
        hl = struct.unpack("<I", out[pos:pos + 4])[0]
        i = pos + 4
        while i < pos + 4 + hl:
            n = struct.unpack("<I", out[i:i + 4])[0]
            if out[i + 4:i + 14] == b"chunk_pos=":
                old = struct.unpack("<Q", out[i + 14:i + 22])[0]
                if old > chunk_at:
                    out[i + 14:i + 22] = struct.pack("<Q", old + shift)
            i += 4 + n
        dl = struct.unpack("<I", out[pos + 4 + hl:pos + 8 + hl])[0]
        pos += 8 + hl + dl
    open("formats/fuzz/corpus/rosbag_fuzzer/bomb-bz2.bag", "wb").write(bytes(out))


def record(opcode, content):
    return bytes([opcode]) + struct.pack("<Q", len(content)) + content


def string(s):
    return struct.pack("<I", len(s)) + s


def mcap_bomb():
    magic = b"\x89MCAP0\r\n"
    data = zeros_compressed(zstd_zeros)
    chunk = (struct.pack("<QQQI", 0, 0, BOMB_BYTES, 0) + string(b"zstd") +
             struct.pack("<Q", len(data)) + data)
    out = (magic + record(0x01, string(b"ros2") + string(b"bomb")) +
           record(0x03, struct.pack("<H", 1) + string(b"std_msgs/msg/String") +
                  string(b"ros2msg") + string(b"string data\n")) +
           record(0x04, struct.pack("<HH", 7, 1) + string(b"/chat") + string(b"cdr") +
                  struct.pack("<I", 0)) +
           record(0x06, chunk) + record(0x0f, struct.pack("<I", 0)) +
           record(0x02, struct.pack("<QQI", 0, 0, 0)) + magic)
    open("formats/fuzz/corpus/mcap_fuzzer/bomb-zstd.mcap", "wb").write(out)


rosbag_bomb()
mcap_bomb()
