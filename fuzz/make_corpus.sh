#!/usr/bin/env bash
# Usage: fuzz/make_corpus.sh OUT_DIR [DATA_DIR]
#
# Writes the seed corpus of the fuzz targets (fuzz/*_fuzzer.cc) into
# OUT_DIR/<target>/: the meshes of DATA_DIR/simple and DATA_DIR/plate
# (default: ../shared/data next to the checkout) converted to ASCII PLY,
# binary PLY (little endian, double; big endian, float), OBJ and OFF, plus
# hand-written edge cases of each format and masks: the OFF header variants
# ([ST][C][N][4][n]OFF, binary OFF) and headers declaring huge counts
# (2^31 - 1 vertices, faces, rows of an extra element with and without
# properties, list counts of 2^32 - 1), blank lines. Deterministic: the same
# files every time. Needs python3.
set -euo pipefail
out="${1:?usage: $0 OUT_DIR [DATA_DIR]}"
src="$(cd "$(dirname "$0")/.." && pwd)"
data="${2:-$src/../shared/data}"
mkdir -p "$out"
python3 - "$out" "$data" <<'PY'
import glob, os, struct, sys
out, data = sys.argv[1], sys.argv[2]
targets = ["ply_ascii_fuzzer", "ply_binary_fuzzer", "obj_fuzzer",
           "off_fuzzer", "mask_fuzzer"]
for t in targets:
    os.makedirs(os.path.join(out, t), exist_ok=True)

def put(target, name, content):
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(os.path.join(out, target, name), mode) as f:
        f.write(content)

def read_ascii_ply(path):
    lines = open(path).read().split("\n")
    nv = nf = 0
    i = 0
    while lines[i].strip() != "end_header":
        w = lines[i].split()
        if w[:2] == ["element", "vertex"]: nv = int(w[2])
        if w[:2] == ["element", "face"]: nf = int(w[2])
        i += 1
    body = [l.split() for l in lines[i + 1:] if l.strip()]
    verts = [[float(x) for x in l[:3]] for l in body[:nv]]
    faces = [[int(x) for x in l[1:4]] for l in body[nv:nv + nf]]
    return verts, faces

def ply_header(fmt, nv, nf, coord, index):
    return ("ply\nformat %s 1.0\nelement vertex %d\nproperty %s x\n"
            "property %s y\nproperty %s z\nelement face %d\n"
            "property list uchar %s vertex_indices\nend_header\n"
            % (fmt, nv, coord, coord, coord, nf, index))

def binary_ply(verts, faces, big):
    e = ">" if big else "<"
    coord = "f" if big else "d"
    b = ply_header("binary_big_endian" if big else "binary_little_endian",
                   len(verts), len(faces), "float" if big else "double",
                   "int").encode()
    for v in verts: b += struct.pack(e + 3 * coord, *v)
    for f in faces: b += struct.pack(e + "B3i", 3, *f)
    return b

meshes = sorted(glob.glob(os.path.join(data, "simple", "*.ply")) +
                glob.glob(os.path.join(data, "plate", "plate121*.ply")))
for path in meshes:
    name = os.path.splitext(os.path.basename(path))[0]
    verts, faces = read_ascii_ply(path)
    put("ply_ascii_fuzzer", name + ".ply", open(path).read())
    put("ply_binary_fuzzer", name + "_le.ply", binary_ply(verts, faces, False))
    put("ply_binary_fuzzer", name + "_be.ply", binary_ply(verts, faces, True))
    put("obj_fuzzer", name + ".obj",
        "".join("v %r %r %r\n" % tuple(v) for v in verts) +
        "".join("f %d %d %d\n" % tuple(i + 1 for i in f) for f in faces))
    put("off_fuzzer", name + ".off",
        "OFF\n%d %d 0\n" % (len(verts), len(faces)) +
        "".join("%r %r %r\n" % tuple(v) for v in verts) +
        "".join("3 %d %d %d\n" % tuple(f) for f in faces))

# Hand-written edge cases: the unit square (4 vertices, 2 faces) with one
# defect each.
sq_v = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
sq_f = [[0, 1, 2], [0, 2, 3]]
V = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
edge_ply = {
    "nan": V.replace("1 0 0", "nan 0 0") + "3 0 1 2\n3 0 2 3\n",
    "range": V + "3 0 1 2\n3 0 2 99\n",
    "float_index": V + "3 0 1 2\n3 0 2.7 3\n",
    "quad": V + "4 0 1 2 3\n3 0 2 3\n",
    "extra_token": V + "3 0 1 2 5\n3 0 2 3\n",
    "extra_line": V + "3 0 1 2\n3 0 2 3\n3 0 1 3\n",
    "duplicate": V + "3 0 1 2\n3 0 2 1\n",
    "short": V + "3 0 1 2\n",
}
for name, body in sorted(edge_ply.items()):
    put("ply_ascii_fuzzer", "edge_" + name + ".ply",
        ply_header("ascii", 4, 2, "double", "int") + body)
# Headers declaring more rows than the file holds.
BIG = 2147483647
def huge_ply(fmt, nv, nf, extra, body):
    return (ply_header(fmt, nv, nf, "double", "int") .replace(
        "end_header\n", extra + "end_header\n")).encode() + body
ascii_body = (V + "3 0 1 2\n3 0 2 3\n").encode()
for name, nv, nf, extra in [
        ("vertices", BIG, 2, ""), ("faces", 4, BIG, ""),
        ("extra_no_properties", 4, 2, "element junk %d\n" % BIG),
        ("extra_uchar", 4, 2, "element junk %d\nproperty uchar a\n" % BIG),
        ("extra_list", 4, 2, "element junk 1\nproperty list uint uchar a\n")]:
    put("ply_ascii_fuzzer", "huge_" + name + ".ply",
        huge_ply("ascii", nv, nf, extra, ascii_body +
                 (b"4294967295\n" if name == "extra_list" else b"")))
    body = binary_ply(sq_v, sq_f, False)
    body = body[body.index(b"end_header\n") + 11:]
    put("ply_binary_fuzzer", "huge_" + name + ".ply",
        huge_ply("binary_little_endian", nv, nf, extra, body +
                 (b"\xff\xff\xff\xff" if name == "extra_list" else b"")))
put("ply_ascii_fuzzer", "blank_lines.ply",
    ply_header("ascii", 4, 2, "double", "int") + "\n" * 4000 + V +
    "\n" * 2000 + "3 0 1 2\n3 0 2 3\n")
put("ply_ascii_fuzzer", "edge_comments.ply",
    "ply\r\nformat ascii 1.0\r\ncomment c\r\nobj_info o\r\nelement vertex 4\r\n"
    "property float x\r\nproperty float y\r\nproperty float z\r\n"
    "property uchar red\r\nelement face 2\r\nproperty list uchar int "
    "vertex_indices\r\nelement edge 1\r\nproperty int a\r\nproperty int b\r\n"
    "end_header\r\n0 0 0 1\r\n1 0 0 2\r\n1 1 0 3\r\n0 1 0 4\r\n3 0 1 2\r\n"
    "3 0 2 3\r\n0 1\r\n")
b = binary_ply(sq_v, sq_f, False)
put("ply_binary_fuzzer", "edge_trailing.ply", b + b"junk")
put("ply_binary_fuzzer", "edge_truncated.ply", b[:-3])
put("ply_binary_fuzzer", "edge_range.ply",
    b[:-4] + struct.pack("<i", 99))
put("ply_binary_fuzzer", "edge_types.ply",
    ply_header("binary_little_endian", 4, 2, "float", "ushort").encode()
    .replace(b"uchar ushort", b"uint8 uint16") +
    b"".join(struct.pack("<3f", *v) for v in sq_v) +
    b"".join(struct.pack("<B3H", 3, *f) for f in sq_f))
put("ply_binary_fuzzer", "body_only.bin",
    b"".join(struct.pack("<3f", *v) for v in sq_v) +
    b"".join(struct.pack("<B3i", 3, *f) for f in sq_f))
put("ply_ascii_fuzzer", "body_only.txt", V + "3 0 1 2\n3 0 2 3\n")
OV = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
edge_obj = {
    "variants": "# c\nmtllib a.mtl\no sq\n" + OV.replace("v 1 0 0", "v 1 0 0 1") +
                "vt 0 0\nvn 0 0 1\ns 1\ng g\nusemtl m\nf 1/1/1 2/1/1 3/1/1\nf -4//1 -2//1 -1//1\n",
    "range": OV + "f 1 2 3\nf 1 3 99\n",
    "zero": OV + "f 0 1 2\nf 1 3 4\n",
    "nan": OV.replace("v 1 0 0", "v nan 0 0") + "f 1 2 3\nf 1 3 4\n",
    "nonmanifold": OV + "v 0.5 0.5 1\nf 1 2 3\nf 1 3 4\nf 1 3 5\n",
    "isolated": OV + "v 5 5 5\nf 1 2 3\nf 1 3 4\n",
    "quad": OV + "f 1 2 3 4\n",
    "crlf": (OV + "f 1 2 3\nf 1 3 4\n").replace("\n", "\r\n"),
}
edge_obj["blank_lines"] = "\n" * 6000 + OV + "\n\r\n" * 500 + "f 1 2 3\nf 1 3 4\n"
for name, text in sorted(edge_obj.items()):
    put("obj_fuzzer", "edge_" + name + ".obj", text)
edge_off = {
    "colour": "OFF\n# c\n4 2 0\n" + V + "3 0 1 2 255 0 0\n3 0 2 3 0 255 0 1\n",
    "counts_inline": "OFF 4 2 0\n" + V + "3 0 1 2\n3 0 2 3\n",
    "range": "OFF\n4 2 0\n" + V + "3 0 1 2\n3 0 2 99\n",
    "extra": "OFF\n4 1 0\n" + V + "3 0 1 2\n3 0 2 3\n",
    "short": "OFF\n4 3 0\n" + V + "3 0 1 2\n3 0 2 3\n",
    "float_index": "OFF\n4 2 0\n" + V + "3 0 1 2\n3 0 2.7 3\n",
}
F = "3 0 1 2\n3 0 2 3\n"
def off_variant(keyword, vertex_suffix, face_suffix=""):
    return (keyword + "\n4 2 0\n" +
            "".join(v + vertex_suffix + "\n" for v in V.splitlines()) +
            "".join(f + face_suffix + "\n" for f in F.splitlines()))
edge_off.update({
    "coff": off_variant("COFF", " 192 192 192 255"),
    "coff_rgb": off_variant("COFF", " 0.1 0.2 0.3", " 1 0 0"),
    "noff": off_variant("NOFF", " 0 0 1"),
    "cnoff": off_variant("CNOFF", " 0 0 1 1 1 1 1", " 0 0 0 0"),
    "stoff": off_variant("STOFF", " 0.5 0.5"),
    "stcnoff": off_variant("STCNOFF", " 0 0 1 1 1 1 0.5 0.5"),
    "4off": off_variant("4OFF", " 2"),
    "4off_w0": off_variant("4OFF", " 0"),
    "ndim": "nOFF\n3\n4 2 0\n" + V + F,
    "binary": "OFF BINARY\n4 2 0\n",
    "huge_vertices": "OFF\n2147483647 2 0\n" + V + F,
    "huge_faces": "OFF\n4 2147483647 0\n" + V + F,
    "huge_coff": "COFF 2147483647 2147483647 2147483647\n0 0 0 1 1 1 1\n",
    "above_int": "OFF\n4294967296 2 0\n" + V + F,
    "blank_lines": "OFF\n" + "\n" * 4000 + "4 2 0\n" + V + "\n" * 2000 + F,
})
for name, text in sorted(edge_off.items()):
    put("off_fuzzer", "edge_" + name + ".off", text)
for path in sorted(glob.glob(os.path.join(data, "*", "*mask*.txt"))):
    put("mask_fuzzer", os.path.basename(path), open(path).read())
for name, text in [("simple", "0\n5\n99\n"), ("comments", "# c\n1 2 3 # x\r\n\n4\n"),
                   ("range", "100\n"), ("negative", "-1\n"), ("float", "2.5\n"),
                   ("huge", "99999999999999999999999\n"), ("binary", "0\n\x00\x01\n"),
                   ("blank_lines", "\n" * 6000 + "7\n"),
                   ("repeated", "1 " * 3000 + "\n")]:
    put("mask_fuzzer", "edge_" + name + ".txt", text)
PY
for t in "$out"/*/; do
  echo "corpus $(basename "$t"): $(ls "$t" | wc -l) files, $(cat "$t"/* | wc -c) bytes"
done
