"""The E2E Profile 1 CRC in closed form, independent of the C++ codec
(docs/can.md#e2e), shared by the Python peers and log checkers of the CAN and
SIL tests."""


def p01_crc(data_id, payload):
    """Profile 1, DataIDMode BOTH: CRC-8 poly 0x1D, register starting at 0x00,
    no final XOR, over id_lo, id_hi, payload[1:8]."""
    reg = 0
    for b in bytes([data_id & 0xFF, data_id >> 8]) + bytes(payload[1:8]):
        reg ^= b
        for _ in range(8):
            reg = ((reg << 1) ^ 0x1D) & 0xFF if reg & 0x80 else (reg << 1) & 0xFF
    return reg
