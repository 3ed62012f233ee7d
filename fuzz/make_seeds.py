#!/usr/bin/env python3
# Writes the seed inputs of the fuzz targets (fuzz/*_fuzzer.cpp) into OUT/<target>/: small valid
# files of every variant each reader knows (binary ones built here byte by byte, so the repository
# holds no binary seeds), plus the shipped scenes and meshes of REPO (scenes/, bench/, tests/) and
# SHARED (the bench material), each scene with the files it names appended as "#@file" sections.
# Usage: fuzz/make_seeds.py OUT REPO SHARED   (called by scripts/fuzz.sh)
import glob
import gzip
import os
import re
import struct
import sys
import zlib

out, repo, shared = sys.argv[1], sys.argv[2], sys.argv[3]
MAX_SEED = 64 * 1024  # larger files would only be truncated by -max_len


def put(target, name, data):
    d = os.path.join(out, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


# ---- meshes ----
PLY_HEAD = "ply\nformat {fmt} 1.0\ncomment seed\nelement vertex 4\nproperty float x\nproperty float y\n" \
           "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float u\n" \
           "property float v\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
VERTS = [(0, 0, 0, 0, 0, 1, 0, 0), (1, 0, 0, 0, 0, 1, 1, 0), (1, 1, 0, 0, 0, 1, 1, 1), (0, 1, 0, 0, 0, 1, 0, 1)]
FACES = [(0, 1, 2), (0, 2, 3)]
put("ply", "ascii.ply", PLY_HEAD.format(fmt="ascii") + "".join(" ".join(map(str, v)) + "\n" for v in VERTS) +
    "3 0 1 2\n4 0 1 2 3\n")
for fmt, e in (("binary_little_endian", "<"), ("binary_big_endian", ">")):
    body = b"".join(struct.pack(e + "8f", *v) for v in VERTS)
    body += b"".join(struct.pack(e + "B3i", 3, *f) for f in FACES)
    put("ply", fmt + ".ply", PLY_HEAD.format(fmt=fmt).encode() + body)
put("ply", "other-elements.ply",
    "ply\nformat ascii 1.0\nobj_info x\nelement vertex 3\nproperty double x\nproperty double y\n"
    "property double z\nproperty uchar red\nelement face 1\nproperty list ushort uint vertex_index\n"
    "property list uchar float extra\nelement edge 1\nproperty int vertex1\nproperty int vertex2\n"
    "end_header\n0 0 0 1\n1 0 0 2\n0 1 0 3\n3 0 1 2 2 0.5 0.25\n0 1\n")

put("off", "off.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 1 2 3 0.5 0.5 0.5\n")
put("off", "stcnoff.off",
    "STCNOFF 3 1\n0 0 0 0 0 1 1 0 0 1 0 0\n1 0 0 0 0 1 0 1 0 1 1 0\n0 1 0 0 0 1 0 0 1 1 0 1\n3 0 1 2\n")
put("off", "coff.off", "# comment\nCOFF\n3 1 3\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 2 1 0\n")

put("obj", "quad.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 1\ng quad\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/4/1\no other\nusemtl blue\nf -4 -3 -2\n"
    "#@file m.mtl\nnewmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\nmap_Kd t.png\n")
put("obj", "plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\np 3\ns 1\n")

# ---- images (first byte: extension index, see image_fuzzer.cpp; 0x80 = sRGB) ----
EXT = {"exr": 0, "pfm": 1, "png": 2, "jpg": 3, "tga": 4, "bmp": 5, "hdr": 6, "jpeg": 7}


def image(name, ext, data):
    put("image", name, bytes([EXT[ext] | 0x80]) + data)


def png(width, height, colour, depth, rows, extra=b"", interlace=0):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    ihdr = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, interlace)
    raw = b"".join(b"\0" + r for r in rows)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + extra + chunk(b"IDAT", zlib.compress(raw)) + \
        chunk(b"IEND", b"")


image("rgb8.png", "png", png(2, 2, 2, 8, [bytes([255, 0, 0, 0, 255, 0]), bytes([0, 0, 255, 255, 255, 255])]))
image("grey16.png", "png", png(2, 1, 0, 16, [struct.pack(">HH", 0, 65535)]))
image("rgba8.png", "png", png(1, 2, 6, 8, [bytes([1, 2, 3, 4]), bytes([5, 6, 7, 8])]))
image("palette.png", "png", png(4, 1, 3, 2, [bytes([0x1B])], extra=b"\0\0\0\x09PLTE" + bytes(range(9)) + b"\0\0\0\0"))
# Adam7: 8x8 at 1 bit is 15 pass rows of one byte each.
image("grey1-interlaced.png", "png", png(8, 8, 0, 1, [bytes([0xA5])] * 15, interlace=1))

bmp_px = bytes([0, 0, 255, 0, 255, 0, 0, 0, 255, 0, 0, 255, 255, 255, 0, 0])
bmp = b"BM" + struct.pack("<IHHI", 54 + len(bmp_px), 0, 0, 54) + \
    struct.pack("<IiiHHIIiiII", 40, 2, 2, 1, 24, 0, len(bmp_px), 2835, 2835, 0, 0) + bmp_px
image("rgb24.bmp", "bmp", bmp)
pal = bytes([0, 0, 0, 0, 255, 255, 255, 0])
bmp8_px = bytes([0, 1, 0, 0, 1, 0, 0, 0])
bmp8 = b"BM" + struct.pack("<IHHI", 54 + 8 + 8, 0, 0, 62) + \
    struct.pack("<IiiHHIIiiII", 40, 2, -2, 1, 8, 0, 8, 0, 0, 2, 0) + pal + bmp8_px
image("pal8-topdown.bmp", "bmp", bmp8)
masks = struct.pack("<III", 0xFF0000, 0xFF00, 0xFF)
bmp32 = b"BM" + struct.pack("<IHHI", 54 + 12 + 4, 0, 0, 66) + \
    struct.pack("<IiiHHIIiiII", 40, 1, 1, 1, 32, 3, 4, 0, 0, 0, 0) + masks + bytes([1, 2, 3, 4])
image("bitfields32.bmp", "bmp", bmp32)

image("rgb24.tga", "tga", struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, 2, 1, 24, 0) + bytes(range(6)))
image("rle.tga", "tga", struct.pack("<BBBHHBHHHHBB", 0, 0, 10, 0, 0, 0, 0, 0, 4, 1, 24, 0x20) +
      bytes([0x83, 10, 20, 30]))

hdr_head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1\n\n-Y 2 +X 2\n"
image("flat.hdr", "hdr", hdr_head + bytes([128, 64, 32, 129] * 4))
# One run-length encoded scanline (stb needs width >= 8 for RLE): per component a run of 8.
rle_line = bytes([2, 2, 0, 8]) + b"".join(bytes([128 + 8, v]) for v in (100, 50, 25, 130))
image("rle.hdr", "hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n" + rle_line)

pfm_rgb = b"PF\n2 2\n-1.0\n" + struct.pack("<12f", *([0.5] * 12))
image("rgb.pfm", "pfm", pfm_rgb)
image("grey-be.pfm", "pfm", b"Pf\n1 2\n1.0\n" + struct.pack(">2f", 0.25, 4.0))

# A minimal baseline JPEG: one 8x8 grey block, one-code Huffman tables (DC 0, then EOB).
jpeg = (b"\xff\xd8" + b"\xff\xdb\x00\x43\x00" + bytes([1] * 64) +
        b"\xff\xc0\x00\x0b\x08\x00\x08\x00\x08\x01\x01\x11\x00" +
        b"\xff\xc4\x00\x14\x00\x01" + bytes(15) + b"\x00" +
        b"\xff\xc4\x00\x14\x10\x01" + bytes(15) + b"\x00" +
        b"\xff\xda\x00\x08\x01\x01\x00\x00\x3f\x00" + b"\x3f" + b"\xff\xd9")
image("grey.jpg", "jpg", jpeg)
image("grey.jpeg", "jpeg", jpeg)


def exr(channels, width, height, pixel_type, compression=0):
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", pixel_type, 0, 1, 1) for c in channels) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", chlist) +
              attr("compression", "compression", bytes([compression])) + attr("dataWindow", "box2i", box) +
              attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    size = 2 if pixel_type == 1 else 4
    lines = []
    for y in range(height):
        data = b"".join((struct.pack("<e", 0.5) if size == 2 else struct.pack("<f", 0.5)) * width
                        for _ in sorted(channels))
        lines.append(struct.pack("<ii", y, len(data)) + data)
    table_end = len(header) + 8 * height
    offsets, pos = [], table_end
    for line in lines:
        offsets.append(pos)
        pos += len(line)
    return header + b"".join(struct.pack("<Q", o) for o in offsets) + b"".join(lines)


image("rgb-half.exr", "exr", exr(["R", "G", "B"], 2, 2, 1))
image("y-float.exr", "exr", exr(["Y"], 3, 1, 2))
image("rgba-half.exr", "exr", exr(["A", "B", "G", "R"], 1, 2, 1))

# ---- checkpoints (render/progressive_checkpoint.cpp, version 4 with the integrator payload) ----


def hash_bytes(data):
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    h ^= h >> 33
    h = (h * 0xff51afd7ed558ccd) & 0xFFFFFFFFFFFFFFFF
    h ^= h >> 33
    return h


def pstr(s):
    return struct.pack("<I", len(s)) + s.encode()


def checkpoint(name, width, height, spp, options, args, tiles, layers, payload=b""):
    b = b"PHOSCKPT" + struct.pack("<I", 4) + pstr(name) + struct.pack("<III", width, height, spp)
    b += struct.pack("<7Q", 1, 2, 3, 4, 5, 6, 7)
    b += struct.pack("<I", len(options)) + b"".join(pstr(f) + pstr(v) for f, v in options)
    b += struct.pack("<I", len(args)) + b"".join(pstr(a) for a in args)
    n = width * height * spp
    b += struct.pack("<Q", n) + struct.pack("<%dd" % (8 * n), *([0.5] * 8 * n))
    b += struct.pack("<I", len(tiles)) + b"".join(struct.pack("<I", t) for t in tiles)
    b += struct.pack("<I", len(layers))
    for layer in layers:
        b += pstr(layer) + struct.pack("<%dd" % (4 * width * height), *([1.0] * 4 * width * height))
    return b + struct.pack("<Q", len(payload)) + payload


for i, c in enumerate([checkpoint("sppm", 2, 1, 1, [("--alpha", "0.7"), ("--max-depth", "16")],
                                  ["phos", "render", "/x.scn"], [], []),
                       checkpoint("path", 2, 2, 0, [("--spp", "4")], [], [4, 4], ["", "albedo"]),
                       checkpoint("photonmap", 1, 1, 0, [], [], [1], [""], struct.pack("<Q", 2) + b"\1\2"),
                       checkpoint("ppm", 1, 1, 2, [], [], [], [""])]):
    put("checkpoint", "ckpt%d-unsummed" % i, c)  # the harness appends the checksum
    put("checkpoint", "ckpt%d" % i, c + struct.pack("<Q", hash_bytes(c)))

# ---- scenes (several files in one input: see fuzz/fuzz_support.h) ----
put("scn", "include-and-meshes.scn",
    "material 0 0 0 0.5 0.5 0.5 0 0 0 0 0 0 0 0 0 10 1 t.pfm\n"
    "material 0 0 0 0.5 0.5 0.5 0.2 0.2 0.2 0.3 0.3 0.3 1 1 1 100 1.5 0\n"
    "include part.scn\nbegin 1  1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1\n"
    "  mesh -1 m.off\n  mesh 0 m.ply\n  mesh 1 m.obj\n  box 0 0 0 0 1 1 1\n  circle 1 0 0 0 0 1 0 1\n"
    "  cylinder 0 0 0 0 1 2\n  cone 1 0 0 0 1 2\n  line 0 0 0 0 1 1 1\nend\n"
    "background 0.1 0.1 0.1\nambient 0.2 0.2 0.2\ndir_light 1 1 1 0 -1 0\n"
    "point_light 1 1 1 0 2 0 0 0 1\nspot_light 1 1 1 0 2 0 0 -1 0 1 0 0 0.5 2\n"
    "area_light 1 1 1 0 2 0 0 -1 0 0.5 0 0 1\n"
    "rect_light 1 1 1 0 2 0 1 0 0 0 0 1 1 1 0 0 1\n"
    "camera 0 0 5 0 0 -1 0 1 0 0.5 0.01 100\n"
    "#@file part.scn\nmaterial 0 0 0 1 1 1 0 0 0 0 0 0 0 0 0 10 1 t.bmp\ntri 0 0 0 0 1 0 0 0 1 0\n"
    "include inc.scn\n")

put("pbrt", "include-and-files.pbrt",
    "LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
    "Film \"rgb\" \"integer xresolution\" 64 \"integer yresolution\" 64\n"
    "Sampler \"halton\" \"integer pixelsamples\" 16\nIntegrator \"volpath\" \"integer maxdepth\" 5\n"
    "Include \"view.pbrt\"\nWorldBegin\n"
    "LightSource \"infinite\" \"string filename\" \"t.pfm\"\n"
    "Texture \"checks\" \"spectrum\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4\n"
    "Texture \"img\" \"spectrum\" \"imagemap\" \"string filename\" \"t.bmp\"\n"
    "MakeNamedMaterial \"m\" \"string type\" \"diffuse\" \"texture reflectance\" \"img\"\n"
    "NamedMaterial \"m\"\nShape \"plymesh\" \"string filename\" \"m.ply\"\n"
    "Import \"world.pbrt\"\n"
    "#@file view.pbrt\nOption \"bool disablepixeljitter\" true\nColorSpace \"srgb\"\n"
    "#@file world.pbrt\nAttributeBegin\nTranslate 0 1 0\n"
    "AreaLightSource \"diffuse\" \"blackbody L\" 5500 \"float power\" 10\n"
    "Shape \"disk\" \"float radius\" 0.5\nAttributeEnd\n"
    "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.1 0.1 0.1]\n"
    "MediumInterface \"fog\" \"\"\n"
    "Material \"conductor\" \"spectrum eta\" \"s.spd\" \"spectrum k\" \"metal-Cu-k\"\n"
    "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n"
    "ObjectBegin \"o\"\nShape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\nObjectEnd\n"
    "ObjectInstance \"o\"\nInclude \"inc.pbrt\"\n")

put("pbrt", "film-camera-shapes.pbrt",
    "Option \"integer seed\" 3\nOption \"float displacementedgescale\" 2\n"
    "PixelFilter \"mitchell\" \"float B\" 0.5 \"float xradius\" 1.5\n"
    "Film \"gbuffer\" \"integer xresolution\" 32 \"integer yresolution\" 16 "
    "\"float cropwindow\" [0.25 0.75 0 1] \"integer pixelbounds\" [2 20 0 16]\n"
    "Camera \"spherical\" \"string mapping\" \"equirectangular\"\nWorldBegin\n"
    "ColorSpace \"aces2065-1\"\nAttributeBegin\nAttribute \"shape\" \"float radius\" 2\n"
    "Attribute \"light\" \"float scale\" 3\nLightSource \"point\" \"rgb I\" [1 0.5 0.2]\n"
    "Shape \"sphere\" \"float zmin\" -0.5 \"float zmax\" 0.8 \"float phimax\" 270\nAttributeEnd\n"
    "Shape \"loopsubdiv\" \"integer levels\" 2 \"integer indices\" [0 1 2 0 2 3 0 3 1 1 3 2] "
    "\"point3 P\" [0 0 0 1 0 0 0 1 0 0 0 1]\n"
    "Shape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [0 0 0 1 1 0 2 1 0 3 0 0] "
    "\"normal N\" [0 0 1 0 1 1] \"float width0\" 0.2 \"float width1\" 0.05\n"
    "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 1]\n"
    "LightSource \"infinite\" \"rgb L\" [1 1 1] \"point3 portal\" [0 0 0 1 0 0 1 1 0 0 1 0]\n")

put("scene_format", "all-files.scene",
    "mesh a.mesh\nmesh b.mesh\nsphere 0.5 0 1 0 g.mat\nsphere 0.5 2 1 0 t.mat\n"
    "camera 0 1 5 0 1 0 0 1 0 2\nlight point 0 3 0 10 10 10\n"
    "light area 0 3 0 0 -1 0 5 5 5 1 1\nresolution 64 48\nsky 0.1 0.1 0.1\nmedium fog.mat\n"
    "#@file b.mesh\nply m.obj\nmaterial e.mat\nscale 1 2 3\n"
    "#@file e.mat\nemission 1 1 1\nspecular 0.2 0.2 0.2\n"
    "#@file fog.mat\nabsorption 0.01 0.01 0.01\nscattering 0.02 0.02 0.02\nphase -0.2\n")

# ---- shipped files ----


def shipped(patterns):
    for pattern in patterns:
        for root in (repo, shared):
            for path in sorted(glob.glob(os.path.join(root, pattern), recursive=True)):
                if os.path.isfile(path) and os.path.getsize(path) <= MAX_SEED and "/build" not in path:
                    yield path


def seed_name(path):
    return re.sub(r"[^A-Za-z0-9._-]", "_", os.path.relpath(path, os.path.dirname(repo)))


def read(path):
    with open(path, "rb") as f:
        return f.read()


for target, patterns in (("ply", ["scenes/**/*.ply", "bench/**/*.ply", "tests/**/*.ply"]),
                         ("off", ["scenes/**/*.off", "bench/**/*.off", "tests/**/*.off"]),
                         ("obj", ["scenes/**/*.obj", "bench/**/*.obj", "tests/**/*.obj"])):
    for path in shipped(patterns):
        put(target, seed_name(path), read(path))

# gzip: every PLY seed compressed (mtime 0, so the seeds are the same every run), and one as two
# members one after the other (as `cat a.gz b.gz` makes).
ply_dir = os.path.join(out, "ply")
for name in sorted(os.listdir(ply_dir)):
    data = read(os.path.join(ply_dir, name))
    put("gzip", name + ".gz", gzip.compress(data, mtime=0))
    if name == "ascii.ply":
        put("gzip", "two-members.ply.gz", gzip.compress(data[:40], mtime=0) + gzip.compress(data[40:], mtime=0))

# .scn and pbrt scenes: includes are appended as sections named by their base name, the main file's
# references rewritten to match (fuzz inputs are one directory).
SCN_REF = re.compile(r"^(\s*include\s+)(\S+)", re.M)
PBRT_REF = re.compile(r'((?:Include|Import)\s+")([^"]+)(")')


def flatten(path, pattern, group, depth=0):
    """The file's text with references renamed to base names, and the referenced files' sections."""
    text = read(path).decode("utf-8", "replace")
    sections = []

    def rename(m):
        ref = os.path.join(os.path.dirname(path), m.group(group))
        name = os.path.basename(ref)
        if os.path.isfile(ref) and depth < 4:
            sub_text, sub_sections = flatten(ref, pattern, group, depth + 1)
            sections.append((name, sub_text))
            sections.extend(sub_sections)
        return m.group(0).replace(m.group(group), name)

    return pattern.sub(rename, text), sections


def joined(text, sections):
    parts = [text if text.endswith("\n") else text + "\n"]
    for name, body in sections:
        parts.append("#@file %s\n%s" % (name, body if body.endswith("\n") else body + "\n"))
    return "".join(parts)


for path in shipped(["scenes/**/*.scn", "bench/**/*.scn", "tests/**/*.scn", "bench/scn/*.scn"]):
    put("scn", seed_name(path), joined(*flatten(path, SCN_REF, 2)))
for path in shipped(["scenes/**/*.pbrt", "bench/**/*.pbrt", "tests/**/*.pbrt"]):
    put("pbrt", seed_name(path), joined(*flatten(path, PBRT_REF, 2)))

# .scene files name .mesh and .mat files, which name PLY files and textures, in sub-folders: flatten
# them all; large PLY files and every texture become the fixtures m.ply and t.pfm.
SCENE_REF = re.compile(r"^(\s*(?:mesh|medium|sphere(?:\s+\S+){4}|ply|material|texture)\s+)(\S+)", re.M)


def flatten_scene(path):
    sections, seen = [], set()

    def visit(p):
        text = read(p).decode("utf-8", "replace")

        def rename(m):
            ref = os.path.normpath(os.path.join(os.path.dirname(p), m.group(2)))
            name = os.path.basename(ref)
            if m.group(1).strip() == "texture":
                return m.group(1) + "t.pfm"
            if not os.path.isfile(ref) or (name.endswith(".ply") and os.path.getsize(ref) > 8192):
                return m.group(1) + ("m.ply" if name.endswith(".ply") else name)
            if ref not in seen:
                seen.add(ref)
                sub = visit(ref)
                sections.append((name, sub))
            return m.group(1) + name

        return SCENE_REF.sub(rename, text)

    return visit(path), sections


for path in shipped(["scenes/**/*.scene", "bench/**/*.scene", "tests/**/*.scene"]):
    put("scene_format", seed_name(path), joined(*flatten_scene(path)))
