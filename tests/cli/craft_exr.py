#!/usr/bin/env python3
"""Crafts hostile OpenEXR files from a good single-part scan-line one (standard library only).

The attacks of issue 19 on skyspec's EXR readers, reproducible without an EXR library:

  craft_exr.py IN OUT set-string NAME TEXT     replace (or add) string attribute NAME, offsets fixed
  craft_exr.py IN OUT set-double NAME VALUE    replace (or add) double attribute NAME, offsets fixed
  craft_exr.py IN OUT declare-size NAME BYTES  attribute NAME declares BYTES (the data stays short)
  craft_exr.py IN OUT window W H               the dataWindow says W x H pixels (the chunks do not)
  craft_exr.py IN OUT channel-type NAME TYPE   channel NAME relabelled as TYPE (0 UINT, 1 HALF, 2 FLOAT)

The header is parsed as the OpenEXR file layout describes it: magic, version, attributes (name,
type, size, value) up to an empty name, then the offset table (one 64-bit offset per chunk).
"""
import struct
import sys

MAGIC = 20000630
LINES = {0: 1, 1: 1, 2: 1, 3: 16, 4: 32, 5: 16, 6: 32, 7: 32, 8: 32, 9: 256}


def parse(data):
    if struct.unpack_from("<i", data, 0)[0] != MAGIC:
        raise SystemExit("not an OpenEXR file")
    pos, attrs = 8, []
    while data[pos] != 0:
        name_end = data.index(b"\0", pos)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        value_at = type_end + 5
        attrs.append([data[pos:name_end].decode(), data[name_end + 1:type_end].decode(), data[value_at:value_at + size]])
        pos = value_at + size
    return attrs, pos + 1  # after the empty name that ends the header


def chunk_count(attrs):
    a = {n: v for n, _, v in attrs}
    _, y0, _, y1 = struct.unpack("<4i", a["dataWindow"])
    return (y1 - y0 + 1 + LINES[a["compression"][0]] - 1) // LINES[a["compression"][0]]


def header_bytes(attrs, sizes=None):
    out = bytearray(struct.pack("<ii", MAGIC, 2))
    for name, type_, value in attrs:
        size = (sizes or {}).get(name, len(value))
        out += name.encode() + b"\0" + type_.encode() + b"\0" + struct.pack("<i", size) + value
    return out + b"\0"


def relayout(data, attrs, sizes=None):
    """The file with a new header; the offset table shifted by the header's change in size."""
    old_attrs, end = parse(data)
    n = chunk_count(old_attrs)
    table = struct.unpack_from("<%dQ" % n, data, end)
    head = header_bytes(attrs, sizes)
    delta = len(head) - end
    return bytes(head + struct.pack("<%dQ" % n, *[t + delta for t in table]) + data[end + 8 * n:])


def main(argv):
    src, dst, what = argv[1], argv[2], argv[3]
    data = open(src, "rb").read()
    attrs, end = parse(data)
    if what == "set-string":
        name, text = argv[4], argv[5].encode()
        for a in attrs:
            if a[0] == name:
                a[2] = text
                break
        else:
            attrs.append([name, "string", text])
        out = relayout(data, attrs)
    elif what == "set-double":
        name, value = argv[4], struct.pack("<d", float(argv[5]))
        for a in attrs:
            if a[0] == name:
                a[1], a[2] = "double", value
                break
        else:
            attrs.append([name, "double", value])
        out = relayout(data, attrs)
    elif what == "declare-size":
        name, size = argv[4], int(argv[5])
        head = header_bytes(attrs, {name: size})  # same length: only the declared size changes
        out = bytes(head) + data[end:]
    elif what == "window":
        w, h = int(argv[4]), int(argv[5])
        for a in attrs:
            if a[0] in ("dataWindow", "displayWindow"):
                a[2] = struct.pack("<4i", 0, 0, w - 1, h - 1)
        out = bytes(header_bytes(attrs)) + data[end:]
    elif what == "channel-type":
        name, type_ = argv[4].encode() + b"\0", int(argv[5])
        for a in attrs:
            if a[0] == "channels":
                v = bytearray(a[2])
                at = v.index(name) if v.startswith(name) else v.index(b"\0" + name) + 1
                struct.pack_into("<i", v, at + len(name), type_)
                a[2] = bytes(v)
        out = bytes(header_bytes(attrs)) + data[end:]
    else:
        raise SystemExit("unknown operation " + what)
    open(dst, "wb").write(out)


if __name__ == "__main__":
    main(sys.argv)
