"""The hostile apitrace cases (tests/hostile/cases.json, "generate"), built at run time.

apitrace's binary format (its docs/FORMAT.markdown; trace_io/apitrace_reader.cpp reads it):
"at", then chunks of (uint32 length, snappy data) whose concatenation is the stream of
version, properties and call events. Built here rather than stored because some are large
once written (the decompression bombs) and all are easier to read as code than as bytes.
Snappy itself is Debian's python3-snappy.
"""
import struct

import snappy


class Stream:
    """The decompressed stream, written value by value."""

    def __init__(self, version=6):
        self.raw = bytearray()
        self.next_sig = 0
        self.sigs = {}
        self.calls = 0
        self.uint(version)
        if version >= 6:
            self.uint(version)            # semantic version
            self.string(b"process.name")
            self.string(b"/usr/bin/hostile")
            self.string(b"")              # end of properties

    def byte(self, b):
        self.raw.append(b)

    def uint(self, v):
        while True:
            b = v & 0x7F
            v >>= 7
            self.raw.append(b | (0x80 if v else 0))
            if not v:
                return

    def string(self, s):
        self.uint(len(s))
        self.raw += s

    # Values (tags of FORMAT.markdown "Values").
    def int_value(self, v):
        if v < 0:
            self.byte(0x03)
            self.uint(-v)
        else:
            self.byte(0x04)
            self.uint(v)

    def float_value(self, f):
        self.byte(0x05)
        self.raw += struct.pack("<f", f)

    def blob_value(self, data):
        self.byte(0x08)
        self.string(data)

    def value(self, v):
        if v is None:
            self.byte(0x00)
        elif isinstance(v, bytes):
            self.blob_value(v)
        elif isinstance(v, float):
            self.float_value(v)
        else:
            self.int_value(v)

    def call(self, name, args, leave=True):
        """One call: its enter event with every argument, then (by default) its leave event."""
        self.byte(0)                      # enter
        self.uint(0)                      # thread
        if name in self.sigs:
            self.uint(self.sigs[name])
        else:
            self.sigs[name] = self.next_sig
            self.uint(self.next_sig)
            self.next_sig += 1
            self.string(name.encode())
            self.uint(len(args))
            for k in range(len(args)):
                self.string(b"arg%d" % k)
        for k, v in enumerate(args):
            self.byte(1)                  # argument
            self.uint(k)
            self.value(v)
        self.byte(0)                      # end of details
        number = self.calls
        self.calls += 1
        if leave:
            self.byte(1)                  # leave
            self.uint(number)
            self.byte(0)
        return number

    def viewport(self, w=8, h=8):
        return self.call("glViewport", [0, 0, w, h])

    def file(self, chunk=1 << 20):
        out = bytearray(b"at")
        for at in range(0, len(self.raw), chunk):
            packed = snappy.compress(bytes(self.raw[at:at + chunk]))
            out += struct.pack("<I", len(packed)) + packed
        return bytes(out)


def chunk(payload_compressed):
    return struct.pack("<I", len(payload_compressed)) + payload_compressed


GL_RGBA, GL_UNSIGNED_BYTE, GL_COLOR, GL_TRIANGLES = 0x1908, 0x1401, 0x1800, 0x0004


def truncated_in_chunk():
    s = Stream()
    s.viewport()
    s.call("glClear", [0x4000])
    data = s.file()
    return data[:len(data) - 3]


def truncated_chunk_header():
    s = Stream()
    s.viewport()
    return s.file() + b"\x05\x00"


def truncated_mid_call():
    s = Stream()
    s.viewport()
    s.byte(0)
    s.uint(0)
    s.uint(0)  # glViewport again, its arguments missing
    return s.file()


def corrupt_snappy():
    s = Stream()
    s.viewport()
    return s.file() + chunk(b"\xff\xff\xff\xff\x0f" + b"\xaa" * 40)


def chunk_claims_4gib():
    s = Stream()
    s.viewport()
    return s.file() + b"\xff\xff\xff\xff" + b"\x00" * 16


def chunk_declares_huge_output():
    # A valid varint declaring 2^32 - 1 decompressed bytes, with 3 bytes of data.
    s = Stream()
    s.viewport()
    return s.file() + chunk(b"\xff\xff\xff\xff\x0f\x08abc")


def huge_string_length():
    s = Stream()
    s.viewport()
    s.byte(0); s.uint(0); s.uint(s.next_sig)
    s.string(b"glStringMarkerGREMEDY"); s.uint(2); s.string(b"len"); s.string(b"string")
    s.byte(1); s.uint(1); s.byte(0x07); s.uint(1 << 62)   # a string of 2^62 bytes, 10 given
    s.raw += b"0123456789"
    return s.file()


def huge_array_length():
    s = Stream()
    s.viewport()
    s.byte(0); s.uint(0); s.uint(s.next_sig)
    s.string(b"glLoadMatrixf"); s.uint(1); s.string(b"m")
    s.byte(1); s.uint(0); s.byte(0x0b); s.uint((1 << 63) - 1)   # an array of 2^63 - 1 floats
    for _ in range(16):
        s.float_value(1.0)
    return s.file()


def many_null_arrays():
    # 32 MiB of nulls in one array argument: each costs a decoded value, the reader's limit ends it.
    s = Stream()
    s.viewport()
    s.byte(0); s.uint(0); s.uint(s.next_sig)
    s.string(b"glCallLists"); s.uint(3); s.string(b"n"); s.string(b"type"); s.string(b"lists")
    s.byte(1); s.uint(2); s.byte(0x0b); s.uint(32 << 20)
    s.raw += bytes(32 << 20)
    s.byte(0)
    return s.file(chunk=8 << 20)


def bomb_of_blobs():
    # Twelve calls, each with a 60 MiB blob of zeros in a chunk of its own (3 MB compressed):
    # 720 MiB decoded in all, but never more than one call's worth held. Packed a call at a
    # time, so that this process never holds more than one either.
    s = Stream()
    s.viewport()
    out = bytearray(s.file())
    for _ in range(12):
        s.raw = bytearray()
        s.call("glFrobnicateHOSTILE", [bytes(60 << 20)])
        out += s.file(chunk=61 << 20)[2:]  # without the "at" header
    return bytes(out)


def deep_nesting():
    s = Stream()
    s.viewport()
    s.byte(0); s.uint(0); s.uint(s.next_sig)
    s.string(b"glLoadMatrixf"); s.uint(1); s.string(b"m")
    s.byte(1); s.uint(0)
    for _ in range(100000):
        s.byte(0x0b); s.uint(1)
    s.byte(0)
    return s.file()


def too_many_arguments():
    s = Stream()
    s.viewport()
    s.byte(0); s.uint(0); s.uint(s.next_sig)
    s.string(b"glClear"); s.uint(1 << 40)
    return s.file()


def varint_overflow():
    s = Stream()
    s.viewport()
    s.byte(0); s.uint(0); s.raw += b"\xff" * 20 + b"\x01"
    return s.file()


def unknown_value_tag():
    s = Stream()
    s.viewport()
    s.byte(0); s.uint(0); s.uint(s.next_sig)
    s.string(b"glClear"); s.uint(1); s.string(b"mask")
    s.byte(1); s.uint(0); s.byte(0x7e)
    return s.file()


def leave_not_pending():
    s = Stream()
    s.viewport()
    s.byte(1); s.uint(123456789); s.byte(0)
    return s.file()


def bad_version():
    s = Stream(version=99)
    return s.file()


def gzip_magic():
    return b"\x1f\x8b\x08\x00" + b"\x00" * 16


def not_a_trace():
    return b"passim-trace 1\n@framebuffer 8x8\n"


def empty_file():
    return b""


def draw_pixels_huge_width():
    s = Stream()
    s.viewport()
    s.call("glRasterPos2i", [0, 0])
    s.call("glDrawPixels", [2147483647, 1, GL_RGBA, GL_UNSIGNED_BYTE, b"\x01\x02\x03\x04"])
    return s.file()


def copy_pixels_huge():
    s = Stream()
    s.viewport()
    s.call("glRasterPos2i", [0, 0])
    s.call("glCopyPixels", [0, 0, 2147483647, 1, GL_COLOR])
    s.call("glCopyPixels", [0, 0, 1, 2147483647, GL_COLOR])
    return s.file()


def draw_arrays_huge():
    s = Stream()
    s.viewport()
    s.call("glEnableClientState", [0x8074])
    s.call("glVertexPointer", [2, 0x1406, 0, struct.pack("<6f", 0, 0, 1, 0, 0, 1)])
    s.call("glDrawArrays", [GL_TRIANGLES, 0, 2147483647])
    return s.file()


def nan_everywhere():
    s = Stream()
    s.viewport()
    nan, inf = float("nan"), float("inf")
    s.call("glClearColor", [nan, inf, -inf, nan])
    s.call("glClear", [0x4000])
    s.call("glBegin", [GL_TRIANGLES])
    for v in [(nan, 0.0), (inf, -inf), (0.0, nan)]:
        s.call("glVertex2f", list(v))
    s.call("glEnd", [])
    return s.file()


CASES = {f.__name__: f for f in [
    truncated_in_chunk, truncated_chunk_header, truncated_mid_call, corrupt_snappy, chunk_claims_4gib,
    chunk_declares_huge_output, huge_string_length, huge_array_length, many_null_arrays, bomb_of_blobs,
    deep_nesting, too_many_arguments, varint_overflow, unknown_value_tag, leave_not_pending, bad_version,
    gzip_magic, not_a_trace, empty_file, draw_pixels_huge_width, copy_pixels_huge, draw_arrays_huge,
    nan_everywhere]}
