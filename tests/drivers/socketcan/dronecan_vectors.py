#!/usr/bin/python3
"""Derives the DroneCAN test vectors of dronecan_codec_test.cpp independently of the C++ codec.

Serialisation is done the way pydronecan does it (bit strings: a scalar's bits are emitted least
significant byte first, each byte most significant bit first; a tail array has no length prefix),
the transfer CRC with Python's binascii.crc_hqx (CRC-16-CCITT, init 0xFFFF = CCITT-FALSE) over the
little-endian signature then the payload, frames split as libcanard's enqueueTxFrames. The data
type signatures are recomputed from the normalised DSDL text with CRC-64-WE.
Run: /usr/bin/python3 tests/drivers/socketcan/dronecan_vectors.py
"""
import binascii
import struct

MASK64 = 0xFFFFFFFFFFFFFFFF


def crc64we(text):
    crc = MASK64
    for b in text.encode():
        crc ^= (b << 56) & MASK64
        for _ in range(8):
            crc = ((crc << 1) & MASK64) ^ 0x42F0E1EBA9EA3693 if crc & (1 << 63) else (crc << 1) & MASK64
    return crc ^ MASK64


assert crc64we("123456789") == 0x62EC59E3F1A4F00A
RAW_SIG = crc64we("uavcan.equipment.esc.RawCommand\nsaturated int14[<=20] cmd")
STATUS_SIG = crc64we("uavcan.equipment.esc.Status\nsaturated uint32 error_count\n"
                     "saturated float16 voltage\nsaturated float16 current\n"
                     "saturated float16 temperature\nsaturated int18 rpm\n"
                     "saturated uint7 power_rating_pct\nsaturated uint5 esc_index")


def le_from_be_bits(bits):  # pydronecan.transport.le_from_be_bits
    return "".join(bits[max(0, i - 8):i] for i in range(len(bits), 0, -8))


def field(value, bitlen):
    return le_from_be_bits(format(value & ((1 << bitlen) - 1), "0%db" % bitlen))


def to_bytes(bits):
    bits += "0" * (-len(bits) % 8)
    return bytes(int(bits[i:i + 8], 2) for i in range(0, len(bits), 8))


def f16(x):
    return struct.unpack("<H", struct.pack("<e", x))[0]


def frames(can_id, signature, payload, tid):
    if len(payload) <= 7:
        return [(can_id, payload + bytes([0xC0 | tid]))]
    crc = binascii.crc_hqx(signature.to_bytes(8, "little") + payload, 0xFFFF)
    data = crc.to_bytes(2, "little") + payload
    out = []
    chunks = [data[i:i + 7] for i in range(0, len(data), 7)]
    for n, chunk in enumerate(chunks):
        tail = (0x80 if n == 0 else 0) | (0x40 if n == len(chunks) - 1 else 0) | \
               (0x20 if n % 2 else 0) | tid
        out.append((can_id, chunk + bytes([tail])))
    return out, crc


def show(name, result):
    fr, crc = result if isinstance(result, tuple) else (result, None)
    print(name, "crc=0x%04X" % crc if crc is not None else "single frame")
    for can_id, data in fr:
        print("  id=0x%08X data=%s" % (can_id, " ".join("%02X" % b for b in data)))


print("RawCommand signature 0x%016X, Status signature 0x%016X" % (RAW_SIG, STATUS_SIG))
print("CRC-16-CCITT-FALSE('123456789') = 0x%04X" % binascii.crc_hqx(b"123456789", 0xFFFF))
raw_id = (8 << 24) | (1030 << 8) | 10
v1 = to_bytes("".join(field(c, 14) for c in [8191, -1, 0, 4096]))
show("V1 RawCommand [8191,-1,0,4096] prio 8 node 10 tid 0", frames(raw_id, RAW_SIG, v1, 0))
v2 = to_bytes("".join(field(c, 14) for c in [0, 1000, -1000, 8191, -8191, 1, -1, 4095]))
show("V2 RawCommand [0,1000,-1000,8191,-8191,1,-1,4095] prio 8 node 10 tid 31",
     frames(raw_id, RAW_SIG, v2, 31))
status_id = (16 << 24) | (1034 << 8) | 20
v3 = to_bytes(field(5, 32) + field(f16(16.0), 16) + field(f16(2.5), 16) + field(f16(300.0), 16)
              + field(-1500, 18) + field(42, 7) + field(3, 5))
show("V3 Status err 5, 16 V, 2.5 A, 300 K, -1500 rpm, 42 %, esc 3; prio 16 node 20 tid 7",
     frames(status_id, STATUS_SIG, v3, 7))
