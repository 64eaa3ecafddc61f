#!/usr/bin/env python3
"""Shrinks a decompressed apitrace stream (FORMAT.markdown, version 6) for the fuzz corpus.

apitrace writes each enum signature with every name of its type (the GLenum one lists
thousands), which makes a small trace ~100 KB. The replay needs only the values, so this
keeps one name per enum signature and drops backtraces; every call, argument and value is
kept. Usage: shrink_apitrace_stream.py IN.raw OUT.raw  (raw = the stream after snappy)."""
import sys


class Stream:
    def __init__(self, data):
        self.d, self.p, self.out = data, 0, bytearray()

    def byte(self, copy=True):
        b = self.d[self.p]
        self.p += 1
        if copy:
            self.out.append(b)
        return b

    def uint(self, copy=True):
        v, shift = 0, 0
        while True:
            b = self.byte(copy)
            v |= (b & 0x7F) << shift
            shift += 7
            if not b & 0x80:
                return v

    def raw(self, n, copy=True):
        s = self.d[self.p:self.p + n]
        self.p += n
        if copy:
            self.out += s
        return s

    def string(self, copy=True):
        return self.raw(self.uint(copy), copy)


def put_uint(out, v):
    while True:
        b = v & 0x7F
        v >>= 7
        out.append(b | (0x80 if v else 0))
        if not v:
            return


seen_enums, seen_bitmasks, seen_structs, seen_funcs = set(), set(), {}, {}


def value(s):
    t = s.byte()
    if t in (0, 1, 2):
        return
    if t in (3, 4, 0x0D):
        s.uint()
    elif t == 5:
        s.raw(4)
    elif t == 6:
        s.raw(8)
    elif t in (7, 8):
        s.string()
    elif t == 9:
        sig = s.uint()
        if sig not in seen_enums:
            seen_enums.add(sig)
            n = s.uint(copy=False)
            pairs = []
            for _ in range(n):
                name = s.string(copy=False)
                start = len(s.out)
                value(s)
                pairs.append((name, bytes(s.out[start:])))
                del s.out[start:]
            put_uint(s.out, 1)
            put_uint(s.out, len(pairs[0][0]))
            s.out += pairs[0][0]
            s.out += pairs[0][1]
        value(s)
    elif t == 0x0A:
        sig = s.uint()
        if sig not in seen_bitmasks:
            seen_bitmasks.add(sig)
            for _ in range(s.uint()):
                s.string()
                s.uint()
        s.uint()
    elif t == 0x0B:
        for _ in range(s.uint()):
            value(s)
    elif t == 0x0C:
        sig = s.uint()
        if sig not in seen_structs:
            s.string()
            n = s.uint()
            for _ in range(n):
                s.string()
            seen_structs[sig] = n
        for _ in range(seen_structs[sig]):
            value(s)
    elif t == 0x0E:
        value(s)
        value(s)
    elif t == 0x0F:
        for _ in range(s.uint()):
            s.uint()
    else:
        raise ValueError(f"unknown value type {t:#x} at byte {s.p}")


def details(s):
    while True:
        d = s.byte(copy=False)
        if d == 0:
            s.out.append(0)
            return
        if d == 1:
            s.out.append(1)
            s.uint()
            value(s)
        elif d == 2:
            s.out.append(2)
            value(s)
        elif d == 3:
            s.out.append(3)
            s.uint()
        elif d == 4:  # backtrace: dropped
            for _ in range(s.uint(copy=False)):
                frame = s.uint(copy=False)
                while True:
                    k = s.byte(copy=False)
                    if k == 0:
                        break
                    if k in (4, 5):
                        s.uint(copy=False)
                    else:
                        s.string(copy=False)
        elif d == 5:
            s.out.append(5)
            s.uint()
        else:
            raise ValueError(f"unknown call detail {d:#x} at byte {s.p}")


def main():
    s = Stream(open(sys.argv[1], "rb").read())
    version = s.uint()
    if version != 6:
        raise SystemExit("version 6 streams only")
    s.uint()
    while s.string():
        s.string()
    while s.p < len(s.d):
        event = s.byte()
        if event == 0:
            s.uint()
            sig = s.uint()
            if sig not in seen_funcs:
                s.string()
                n = s.uint()
                for _ in range(n):
                    s.string()
                seen_funcs[sig] = n
            details(s)
        elif event == 1:
            s.uint()
            details(s)
        else:
            raise ValueError(f"unknown event {event} at byte {s.p}")
    open(sys.argv[2], "wb").write(s.out)


if __name__ == "__main__":
    main()
