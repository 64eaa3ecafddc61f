"""Images keep their true width (docs/images.md): OpenImageIO's own tool recovers
the 12-bit codes of a 12-bit attenuation image, and the level count from the file equals
passim's. The PNG's sBIT chunk is read here from the file's bytes (PNG specification §11.3.3.4)."""
import json
import re
import shutil
import struct
import subprocess
import zlib

import numpy as np
import pytest

import passim


def png_chunks(data):
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, chunks = 8, {}
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        assert struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])[0] == zlib.crc32(kind + body)
        chunks.setdefault(kind.decode(), []).append(body)
        pos += 12 + length
    return chunks


def read_png_samples(path):
    """The samples of an 8- or 16-bit greyscale PNG, from its IDAT with the PNG filters undone
    (specification §9), independently of any imaging library."""
    chunks = png_chunks(path.read_bytes())
    width, height, depth, colour = struct.unpack(">IIBB", chunks["IHDR"][0][:10])
    assert colour == 0
    step = depth // 8
    raw = zlib.decompress(b"".join(chunks["IDAT"]))
    stride = width * step
    rows, prev, pos = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[pos], bytearray(raw[pos + 1:pos + 1 + stride])
        pos += 1 + stride
        for i in range(stride):
            a = line[i - step] if i >= step else 0
            b, c = prev[i], prev[i - step] if i >= step else 0
            if kind == 1:
                line[i] = (line[i] + a) & 0xFF
            elif kind == 2:
                line[i] = (line[i] + b) & 0xFF
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 0xFF
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 0xFF
        rows.append(bytes(line))
        prev = line
    return np.frombuffer(b"".join(rows), dtype=">u2" if depth == 16 else "u1").reshape(height, width), chunks


@pytest.fixture(scope="module")
def run12(tmp_path_factory, passim_bin):
    out = tmp_path_factory.mktemp("pcf12")
    subprocess.run([passim_bin, "program", "pcf", "--filter", "2x2", "--bits", "12", "--scene", "edges", "--size",
                    "320x240", "--out", str(out), "-q"], check=True)
    subprocess.run([passim_bin, "program", "pcf", "--filter", "2x2", "--bits", "12", "--scene", "edges", "--size",
                    "320x240", "--tiff", "--out", str(out / "tiff"), "-q"], check=True)
    return out, json.load(open(out / "counters.json"))


def test_png_sbit_gives_the_width_and_the_codes(run12):
    out, counters = run12
    samples, chunks = read_png_samples(out / "attenuation.png")
    assert chunks["sBIT"] == [bytes([12])]  # greyscale: one byte, the significant bits
    codes = samples.astype(np.uint32) >> (16 - 12)
    assert passim.count_levels(codes) == counters["program"]["levels"] == 5
    entry = next(i for i in counters["images"] if i["name"] == "attenuation")
    assert entry["bits"] == [12]


def oiiotool_info(path):
    tool = shutil.which("oiiotool")
    if not tool:
        pytest.skip("oiiotool not installed (Debian: openimageio-tools)")
    return subprocess.run([tool, "--info", "-v", str(path)], check=True, capture_output=True, text=True).stdout


def oiiotool_samples(path):
    """The samples as oiiotool prints them (--dumpdata as a C array: the file's integers)."""
    text = subprocess.run(["oiiotool", "--dumpdata:C=pixels", str(path)], check=True, capture_output=True,
                          text=True).stdout
    return np.array([int(v) for v in re.findall(r"\*/ \{ (\d+)", text)], dtype=np.uint32)


def test_oiiotool_recovers_the_12_bit_codes_of_the_png(run12):
    out, counters = run12
    info = oiiotool_info(out / "attenuation.png")
    width = int(re.search(r'passim:bits: "(\d+)"', info).group(1))
    assert width == 12
    file_bits = 16 if "uint16" in info else 8
    codes = oiiotool_samples(out / "attenuation.png") >> (file_bits - width)
    assert len(codes) == 320 * 240 and codes.max() <= 4095
    assert passim.count_levels(codes) == counters["program"]["levels"]


def test_oiiotool_reads_a_12_bit_tiff(run12):
    out, counters = run12
    info = oiiotool_info(out / "tiff" / "attenuation.tif")
    assert re.search(r"oiio:BitsPerSample: 12", info)
    assert 'passim:bits' in info or "12-bit codes" in info
    codes = oiiotool_samples(out / "tiff" / "attenuation.tif") >> 4  # read back as 16 bits, the code in the top 12
    assert len(codes) == 320 * 240
    assert passim.count_levels(codes) == counters["program"]["levels"]


def test_the_docs_numpy_recipe(run12, source_dir):
    # docs/images.md's Python recipe, run as printed on the file made above.
    oiio = pytest.importorskip("OpenImageIO")
    out, counters = run12
    block = re.search(r"```python\n(.*?)```", (source_dir / "docs" / "images.md").read_text(), re.S).group(1)
    scope = {}
    exec(compile(block.replace("out/pcf12", str(out)), "docs/images.md", "exec"), scope)
    assert scope["bits"] == 12
    assert passim.count_levels(scope["codes"]) == counters["program"]["levels"]
