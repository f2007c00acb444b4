#!/usr/bin/env python3
"""Writes the malformed-input cases of tests/malformed/ (run by tests/app/test_malformed.cpp).

Each case is an input file NAME.EXT (a lumis JSON scene, a .gltf, a .glb or an image) and NAME.expect:

    stderr: <substring that lumis must print on stderr>
    exit: <expected exit code; default 1>
    args: <extra command-line arguments, optional>

Exit code 0 means the input must load and render (an output image is written); any other code means no output
file may be created. glTF files are small hand-written JSON whose buffers are base64 data: URIs, so every case is
self-contained. Usage: python3 tests/malformed/make_cases.py   (rewrites the cases in place)
"""
import base64
import copy
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
written = []


def case(name, ext, content, stderr, exit_code=1, args=None):
    """Write NAME.EXT (str or bytes) and NAME.expect."""
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(os.path.join(HERE, name + ext), mode) as f:
        f.write(content)
    lines = ["stderr: " + stderr]
    if exit_code != 1:
        lines.append("exit: %d" % exit_code)
    if args:
        lines.append("args: " + args)
    with open(os.path.join(HERE, name + ".expect"), "w") as f:
        f.write("\n".join(lines) + "\n")
    written.append(name)


def aux(name, content):
    """A file that cases refer to (texture, buffer), not a case itself."""
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(os.path.join(HERE, name), mode) as f:
        f.write(content)


# ---------------------------------------------------------------------------------------------------------------
# lumis JSON scenes

BASE = {
    "version": 1,
    "camera": {"from": [0, 1, 4], "to": [0, 1, 0], "fov": 40},
    "film": {"width": 8, "height": 8},
    "render": {"integrator": "nee_mis", "spp": 1},
    "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
    "shapes": [{"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "grey"}],
    "lights": [{"type": "sphere", "center": [0, 3, 0], "radius": 0.25, "radiance": [20, 20, 20]}],
}


def scene(**changes):
    s = copy.deepcopy(BASE)
    for k, v in changes.items():
        if v is None:
            s.pop(k, None)
        else:
            s[k] = v
    return s


def dump(s):
    return json.dumps(s, indent=1) + "\n"


def sphere(**changes):
    sh = copy.deepcopy(BASE["shapes"][0])
    sh.update(changes)
    return sh


# Syntax errors: line and column.
case("json_missing_brace", ".json", '{\n  "version": 1,\n  "shapes": [\n', "invalid JSON")
case("json_syntax_line_col", ".json", '{\n  "version": 1,\n  "film": {"width" 8}\n}\n', ":3:20: invalid JSON")
case("json_trailing_comma", ".json", '{"version": 1, "shapes": [],}\n', ":1:29: invalid JSON")
case("json_empty_file", ".json", "", ":1:1: invalid JSON")
case("json_nan_literal", ".json", dump(BASE).replace('"radius": 1,', '"radius": NaN,', 1), "invalid JSON")
case("json_huge_literal", ".json", dump(BASE).replace('"radius": 1,', '"radius": 1e999,', 1), "invalid JSON")
case("json_binary_garbage", ".json", bytes(range(256)) * 4, "invalid JSON")
case("json_bad_utf8", ".json", dump(BASE).encode().replace(b'"grey"', b'"gr\xff\xfey"', 1), "invalid JSON")
case("json_deep_nesting", ".json", "[" * 20000 + "]" * 20000, "expected an object")
case("json_duplicate_key", ".json", dump(BASE).replace('"version": 1,', '"version": 1, "version": 1,', 1),
     "/version: duplicate key")
case("json_not_object", ".json", "[1, 2, 3]\n", "expected an object")

# Wrong types and unknown keys.
case("json_radius_string", ".json", dump(scene(shapes=[sphere(radius="big")])), "/shapes/0/radius")
case("json_center_two_numbers", ".json", dump(scene(shapes=[sphere(center=[1, 2])])), "/shapes/0/center")
case("json_spp_fraction", ".json", dump(scene(render={"spp": 1.5})), "/render/spp")
case("json_shapes_object", ".json", dump(scene(shapes={"type": "sphere"})), "/shapes: expected an array")
case("json_unknown_top_key", ".json", dump(scene(shape=[])), 'unknown key "shape" (did you mean "shapes"?)')
case("json_unknown_shape_key", ".json", dump(scene(shapes=[dict(sphere(), radus=1)])), '/shapes/0/radus: unknown key')
case("json_bad_version", ".json", dump(scene(version=2)), "unsupported scene format version")
# A shape's name is a string (only used in messages), on every kind of shape; a sphere once took any value.
case("json_sphere_name_object", ".json", dump(scene(shapes=[sphere(name={"a": 1})])),
     "/shapes/0/name: expected a string, found an object")
case("json_sphere_name_null", ".json", dump(scene(shapes=[sphere(name=None)])),
     "/shapes/0/name: expected a string, found null")
case("json_sphere_name_number", ".json", dump(scene(shapes=[sphere(name=5)])),
     "/shapes/0/name: expected a string, found the number 5")
case("json_quad_name_number", ".json",
     dump(scene(shapes=[{"type": "quad", "name": 5, "origin": [-1, 0, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2],
                         "material": "grey"}])), "/shapes/0/name: expected a string")

# Unknown names list the valid ones.
case("json_unknown_integrator", ".json", dump(scene(render={"integrator": "path"})),
     "uniform, bsdf, light, mis")
case("json_unknown_sampler", ".json", dump(scene(render={"sampler": "halton"})), "independent, stratified")
case("json_unknown_material_type", ".json", dump(scene(materials={"grey": {"type": "plastic"}})), "diffuse")
case("json_undefined_material", ".json", dump(scene(shapes=[sphere(material="gold")])), "grey")
case("json_unknown_shape_type", ".json", dump(scene(shapes=[sphere(type="cube")])), "sphere")
case("cli_unknown_integrator", ".json", dump(BASE), "valid: uniform, bsdf, light, mis, nee_mis", 2,
     "--integrator path")
case("cli_unknown_sampler", ".json", dump(BASE), "valid: independent, stratified, sobol", 2, "--sampler halton")

# Out-of-range numbers.
case("json_negative_radius", ".json", dump(scene(shapes=[sphere(radius=-1)])), "/shapes/0/radius: expected a positive radius")
case("json_zero_radius", ".json", dump(scene(shapes=[sphere(radius=0)])), "/shapes/0/radius")
case("json_zero_light_radius", ".json",
     dump(scene(lights=[{"type": "sphere", "center": [0, 3, 0], "radius": 0, "radiance": [1, 1, 1]}])),
     "/lights/0/radius")
case("json_zero_spp", ".json", dump(scene(render={"spp": 0})), "/render/spp")
case("json_negative_spp", ".json", dump(scene(render={"spp": -4})), "/render/spp")
case("json_zero_width", ".json", dump(scene(film={"width": 0, "height": 8})), "/film/width")
case("json_absurd_resolution", ".json", dump(scene(film={"width": 1000000, "height": 8})), "absurd resolution")
case("json_float_overflow", ".json", dump(scene(shapes=[sphere(center=[1e39, 0, 0])])), "/shapes/0/center")
case("json_negative_radiance", ".json",
     dump(scene(lights=[{"type": "sphere", "center": [0, 3, 0], "radius": 1, "radiance": [-1, 1, 1]}])),
     "/lights/0/radiance")
case("json_camera_no_direction", ".json", dump(scene(camera={"from": [0, 1, 0], "to": [0, 1, 0]})), "/camera/to")
case("json_zero_fov", ".json", dump(scene(camera={"from": [0, 1, 4], "to": [0, 1, 0], "fov": 0})), "/camera/fov")
case("cli_zero_spp", ".json", dump(BASE), "--spp: expected a whole number in [1, 1073741824], found 0", 2, "--spp 0")
case("cli_absurd_width", ".json", dump(BASE), "--width", 2, "--width 100000")
# CLI11's ranges let NaN through (every comparison with it is false): a finite-number check comes first.
case("cli_nan_light_probability", ".json", dump(BASE), "--mis-light-probability: expected a finite number", 2,
     "--integrator mis --mis-light-probability nan")
case("cli_nan_time", ".json", dump(BASE), "--time: expected a finite number", 2, "--time nan")
case("cli_inf_exposure", ".json", dump(BASE), "--exposure: expected a finite number", 2, "--exposure inf")
# Light sampling alone never draws directions no light covers: probability 1 would lose indirect light.
case("cli_light_probability_one", ".json", dump(BASE), "expected a probability in [0, 1)", 2,
     "--integrator mis --mis-light-probability 1")
case("json_light_probability_one", ".json", dump(scene(render={"mis_light_probability": 1})),
     "/render/mis_light_probability: expected a probability in [0, 1)")
case("json_version_float", ".json", dump(scene(version=1.0)).replace('"version": 1,', '"version": 1.0,', 1), "", 0)
case("json_exposure_absurd", ".json", dump(scene(render={"exposure": 1000})), "/render/exposure")
case("cli_time_zero_is_no_budget", ".json", dump(scene(render={"spp": 1, "time": 5})), "", 0, "--time 0")
# A transform that is finite but sends the mesh to infinity in float.
case("json_mesh_overflow", ".json",
     dump(scene(shapes=[{"type": "mesh", "positions": [[0, 0, 0], [1e30, 0, 0], [0, 1e30, 0]], "indices": [0, 1, 2],
                         "material": "grey", "transform": {"scale": 1e30}}])), "/shapes/0/transform: the transformed positions are not finite")

# Beyond float arithmetic: Embree aborts on rays from beyond ~1.8e18 (a camera at 1e19 crashed lumis).
case("json_camera_far", ".json", dump(scene(camera={"from": [0, 0, 1e19], "to": [0, 0, 0]})),
     "/camera/from: the camera is 1e+19 scene units from the origin")
case("json_sphere_beyond_float", ".json", dump(scene(camera=None, shapes=[sphere(center=[3e38, 0, 0], radius=3e38)])),
     "/shapes/0: the shape reaches 6e+38 scene units from the origin; coordinates must stay within 1e+12")
case("json_quad_far", ".json",
     dump(scene(shapes=[{"type": "quad", "origin": [2e15, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0],
                         "material": "grey"}])), "/shapes/0: the shape reaches 2e+15")
case("json_light_far", ".json",
     dump(scene(lights=[{"type": "sphere", "center": [0, 0, -3e15], "radius": 1, "radiance": [1, 1, 1]}])),
     "/lights/0: the light reaches 3e+15")

# Empty scenes.
case("json_empty_object", ".json", "{}\n", "scene is empty")
case("json_empty_arrays", ".json", dump(scene(shapes=[], lights=[])), "scene is empty")

# Missing, unreadable or unsupported files referred to by a scene.
case("json_missing_texture", ".json",
     dump(scene(materials={"grey": {"type": "diffuse", "texture": "no-such-texture.png"}})), "no-such-texture.png")
case("json_missing_gltf", ".json", dump(scene(shapes=[{"type": "gltf", "file": "no-such-model.glb"}])),
     "no-such-model.glb")
aux("aux_not_an_image.png", "this is text, not a PNG\n")
case("json_texture_not_image", ".json",
     dump(scene(materials={"grey": {"type": "diffuse", "texture": "aux_not_an_image.png"}})), "aux_not_an_image.png")
aux("aux_texture.txt", "plain text\n")
case("json_texture_unsupported_format", ".json",
     dump(scene(materials={"grey": {"type": "diffuse", "texture": "aux_texture.txt"}})), "aux_texture.txt")
case("json_texture_is_directory", ".json",
     dump(scene(materials={"grey": {"type": "diffuse", "texture": "."}})), "/materials/grey/texture")


def png(width, height, rgb):
    """A tiny 8-bit RGB PNG."""
    raw = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


aux("aux_truncated.png", png(4, 4, [200, 100, 50])[:40])
case("json_texture_truncated_png", ".json",
     dump(scene(materials={"grey": {"type": "diffuse", "texture": "aux_truncated.png"}})),
     "aux_truncated.png: truncated PNG: the file ends inside the chunk header at byte 33")
aux("aux_truncated.exr", b"v/1\x01\x02\x00\x00\x00channels\x00chlist\x00")
case("json_environment_truncated_exr", ".json",
     dump(scene(lights=[{"type": "environment", "file": "aux_truncated.exr"}])), "aux_truncated.exr")

# An image or an unknown file given as the scene itself.
case("image_as_scene", ".png", png(2, 2, [10, 20, 30]), "unknown scene file type")
case("text_as_scene", ".txt", "hello\n", "unknown scene file type")

# ---------------------------------------------------------------------------------------------------------------
# glTF: one triangle (or a quad of two) in a data: URI buffer.


def f32(values):
    return struct.pack("<%df" % len(values), *values)


def u16(values):
    data = struct.pack("<%dH" % len(values), *values)
    return data + b"\x00" * (-len(data) % 4)


def gltf_doc(positions, indices, extra_bytes=b""):
    """A glTF dict with POSITION (accessor 0) and indices (accessor 1) in one buffer, and the buffer's bytes."""
    pos = f32([c for p in positions for c in p])
    idx = u16(indices)
    data = pos + idx + extra_bytes
    finite = [p for p in positions if all(math.isfinite(c) for c in p)] or [(0, 0, 0)]
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": 2 * len(indices)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": [min(p[i] for p in finite) for i in range(3)], "max": [max(p[i] for p in finite) for i in range(3)]},
            {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
    }
    return doc, data


def embed(doc, data):
    doc = copy.deepcopy(doc)
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    return json.dumps(doc, indent=1) + "\n"


def glb(doc, data):
    doc = copy.deepcopy(doc)
    doc["buffers"][0].pop("uri", None)
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    data = data + b"\x00" * (-len(data) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(data), b"BIN\x00") + data
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


TRI = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
good_doc, good_data = gltf_doc(TRI, [0, 1, 2])


def glb_chunks(js, bin_fields=None, payload=b""):
    """A .glb from a JSON chunk's bytes as given (no padding) and, when bin_fields = (length, type) is given, a binary
    chunk header with those fields and PAYLOAD after it; the header's total length is the bytes written."""
    body = struct.pack("<I4s", len(js), b"JSON") + js
    if bin_fields is not None:
        body += struct.pack("<I4s", *bin_fields) + payload
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


good_js = json.dumps({k: v for k, v in good_doc.items() if k != "buffers"} |
                     {"buffers": [{"byteLength": len(good_data)}]}).encode()
good_js += b" " * (-len(good_js) % 4)
good_bin = good_data + b"\x00" * (-len(good_data) % 4)


def variant(mutate, positions=TRI, indices=(0, 1, 2)):
    doc, data = gltf_doc(positions, list(indices))
    mutate(doc)
    return doc, data


# JSON that does not parse is placed at line:column in lumis's words, as in a lumis scene (tinygltf's message was
# nlohmann's, with its prefix and, for ill-formed UTF-8, the raw bytes it last read).
case("gltf_invalid_json", ".gltf", '{"asset": {"version": "2.0"}, "meshes": [\n',
     ":2:1: invalid JSON: syntax error while parsing value - unexpected end of input")
case("gltf_invalid_utf8", ".gltf", b'{"asset": {"version": "2.0"}, "x": "R\xff\xfe"}\n',
     ":1:38: invalid JSON: syntax error while parsing value - invalid string: ill-formed UTF-8 byte; last read: "
     "'\"R\\xff'")
# nlohmann throws out_of_range, not parse_error, for a number beyond the double range: once an uncaught exception
# (found by fuzz_gltf).
case("gltf_number_overflow", ".gltf", '{"asset": {"version": "2.0"}, "x": [1e+200, 1e+894]}\n',
     ":1:50: invalid JSON: number overflow parsing '1e+894' (numbers must be finite)")
case("glb_number_overflow", ".glb",
     glb_chunks(good_js.replace(b'"2.0"}', b'"2.0", "x": 1e999}', 1).ljust(len(good_js) + 12, b" "),
                (len(good_bin), b"BIN\0"), good_bin),
     "invalid JSON chunk: number overflow parsing '1e999' (numbers must be finite)")
case("gltf_empty_file", ".gltf", "", ":1:1: invalid JSON: syntax error while parsing value - unexpected end of input")
case("glb_invalid_json_chunk", ".glb", glb(good_doc, good_data).replace(b'"asset":', b'"asset"=', 1),
     ":1:9: invalid JSON chunk: syntax error while parsing object separator - invalid literal")
case("gltf_not_gltf", ".gltf", '{"hello": 1}\n', "invalid glTF")
good_glb = glb(good_doc, good_data)
# A damaged .glb's framing is named (tinygltf says only "Invalid glTF binary.").
case("glb_truncated", ".glb", good_glb[: len(good_glb) // 2],
     "invalid .glb: the header says the file is %d bytes long, but it is %d (is it cut short?)"
     % (len(good_glb), len(good_glb) // 2))
case("glb_header_only", ".glb", good_glb[:12], "invalid .glb: the file is 12 bytes long, too short for the 12-byte header")
case("glb_empty", ".glb", b"", "invalid")
case("glb_length_too_large", ".glb", good_glb[:8] + struct.pack("<I", 1 << 30) + good_glb[12:],
     "invalid .glb: the header says the file is 1073741824 bytes long")
case("glb_chunk_length_too_large", ".glb", good_glb[:12] + struct.pack("<I", 1 << 30) + good_glb[16:],
     "invalid .glb: the JSON chunk's 1073741824 bytes run past the %d bytes the header gives the file" % len(good_glb))
case("glb_version_1", ".glb", good_glb[:4] + struct.pack("<I", 1) + good_glb[8:],
     "invalid .glb: binary glTF version 1, expected 2")
case("glb_first_chunk_not_json", ".glb", good_glb[:16] + b"BIN\0" + good_glb[20:],
     "invalid .glb: the first chunk (at byte 12) is not of type JSON")
case("glb_bad_magic", ".glb", b"gltf" + good_glb[4:], "invalid")


# The chunks' lengths and types (tinygltf said "Invalid glTF binary." or its own words for these).
case("glb_json_chunk_unpadded", ".glb", glb_chunks(good_js + b" "),
     "invalid .glb: the JSON chunk is %d bytes long; it must be padded with spaces to a non-zero multiple of 4"
     % (len(good_js) + 1))
case("glb_json_chunk_empty", ".glb", glb_chunks(b"", (len(good_bin), b"BIN\0"), good_bin),
     "invalid .glb: the JSON chunk is 0 bytes long")
case("glb_bin_chunk_header_only", ".glb", glb_chunks(good_js, (4, b"BIN\0")),
     "invalid .glb: the 8 bytes after the JSON chunk (at byte %d) are too few for a binary chunk" % (20 + len(good_js)))
case("glb_bin_chunk_not_bin", ".glb", glb_chunks(good_js, (len(good_bin), b"DATA"), good_bin),
     "invalid .glb: the second chunk (at byte %d) is not of type BIN" % (20 + len(good_js)))
case("glb_bin_chunk_unpadded", ".glb", glb_chunks(good_js, (len(good_bin) - 2, b"BIN\0"), good_bin),
     "is %d bytes long; it must be padded to a non-zero multiple of 4" % (len(good_bin) - 2))
# A binary chunk whose length counts its own 8-byte header: tinygltf's bound leaves the header out, so it read the
# buffer's last 8 bytes from past the end of the file's bytes in memory (a heap over-read under AddressSanitizer).
case("glb_bin_chunk_past_end", ".glb",
     glb_chunks(good_js.replace(b'"byteLength": %d' % len(good_data), b'"byteLength": %d' % (len(good_bin) + 8))
                .ljust(len(good_js) + 4, b" "), (len(good_bin) + 8, b"BIN\0"), good_bin),
     "invalid .glb: the binary chunk's %d bytes (from byte %d) run past the %d bytes the header gives the file"
     % (len(good_bin) + 8, 20 + len(good_js) + 4 + 8, 12 + 8 + len(good_js) + 4 + 8 + len(good_bin)))


def set_path(path, value):
    def mutate(doc):
        obj = doc
        for k in path[:-1]:
            obj = obj[k]
        obj[path[-1]] = value
    return mutate


case("gltf_indices_accessor_oob", ".gltf", embed(*variant(set_path(["meshes", 0, "primitives", 0, "indices"], 7))),
     "indices accessor out of bounds")  # tinygltf's own check, before lumis's
case("gltf_position_accessor_negative", ".gltf",
     embed(*variant(set_path(["meshes", 0, "primitives", 0, "attributes", "POSITION"], -3))), "POSITION")
case("gltf_accessor_count_oob", ".gltf", embed(*variant(set_path(["accessors", 0, "count"], 1000))), "accessors[0]")
case("gltf_accessor_offset_oob", ".gltf", embed(*variant(set_path(["accessors", 1, "byteOffset"], 4096))),
     "accessors[1]")
case("gltf_accessor_huge_count", ".gltf", embed(*variant(set_path(["accessors", 0, "count"], 2 ** 40))),
     "accessors[0]")
# Found by reading: a count just under the 2^32 guard allocated count x element size (48 GiB here) before the
# bounds check; an accessor without a bufferView has no buffer to bound it at all.
case("gltf_accessor_count_2e32", ".gltf", embed(*variant(set_path(["accessors", 0, "count"], 2 ** 32))),
     "bytes, but bufferViews[0] has 36")


def zero_accessor(doc):
    del doc["accessors"][0]["bufferView"]
    doc["accessors"][0]["count"] = 2 ** 30


case("gltf_zero_accessor_huge", ".gltf", embed(*variant(zero_accessor)),
     "accessors[0]: count 1073741824 without a bufferView")
case("gltf_bufferview_oob", ".gltf", embed(*variant(set_path(["bufferViews", 1, "byteLength"], 1 << 20))),
     "bufferViews[1]")
# Found by a review (stop 41): byte ranges near 2^64 wrapped the bounds checks' sums to small numbers, and the
# copies then read far outside the buffer (a segmentation fault).
case("gltf_bufferview_offset_wraps", ".gltf",
     embed(*variant(lambda d: d["bufferViews"][0].update(byteOffset=2 ** 64 - 2 ** 40, byteLength=2 ** 40 + 36))),
     "bufferViews[0]: byteOffset 18446742974197923840 + byteLength 1099511627812 exceeds buffers[0]")
case("gltf_accessor_offset_wraps", ".gltf",
     embed(*variant(lambda d: d["accessors"][0].update(count=3000000, byteOffset=2 ** 64 - (12 * 3000000 - 36)))),
     "accessors[0]: byteOffset 18446744073673551652 + 3000000 elements (stride 12) need 18446744073709551652 bytes")
case("gltf_accessor_count_zero", ".gltf", embed(*variant(set_path(["accessors", 0, "count"], 0))),
     "accessors[0].count: 0, expected at least 1 element (used by meshes[0].primitives[0].attributes.POSITION)")
def empty_instancing(d):
    d["accessors"].append({"bufferView": 0, "componentType": 5126, "count": 0, "type": "VEC3"})
    d["nodes"][0]["extensions"] = {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": len(d["accessors"]) - 1}}}
    d["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]


case("gltf_instancing_count_zero", ".gltf", embed(*variant(empty_instancing)),
     "expected at least 1 element (used by nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.TRANSLATION)")
def no_instance_attributes(d):
    d["nodes"][0]["extensions"] = {"EXT_mesh_gpu_instancing": {"attributes": {}}}
    d["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]


# An empty object (which tinygltf reads as no value): the message once said "expected an object" of an object.
case("gltf_instancing_no_attributes", ".gltf", embed(*variant(no_instance_attributes)),
     "nodes[0].extensions.EXT_mesh_gpu_instancing.attributes: expected an object with at least one of TRANSLATION, "
     "ROTATION and SCALE")
# A valid rotation whose components' squares overflow double (1e200): normalised, not rejected. Renders (exit 0).
case("gltf_rotation_huge", ".gltf", embed(*variant(set_path(["nodes", 0, "rotation"], [1e200, 0, 0, 1e200]))), "", 0)
# Found by a user's test (2026-12-06): glTF that breaks the spec in ways tinygltf accepts.
case("gltf_matrix_and_trs", ".gltf",
     embed(*variant(lambda d: d["nodes"][0].update(matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1],
                                                   translation=[1, 0, 0]))),
     "nodes[0]: has both \"matrix\" and translation/rotation/scale")
case("gltf_matrix_projective", ".gltf",
     embed(*variant(set_path(["nodes", 0, "matrix"], [1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]))),
     "nodes[0].matrix: not an affine transform: its last row is (1, 0, 0, 1)")
case("gltf_accessor_offset_negative", ".gltf", embed(*variant(set_path(["accessors", 1, "byteOffset"], -12))),
     "accessors[1].byteOffset: expected a whole number >= 0, found the number -12")  # tinygltf read it as 0
case("gltf_bufferview_stride_negative", ".gltf", embed(*variant(set_path(["bufferViews", 0, "byteStride"], -4))),
     "bufferViews[0].byteStride: expected a whole number >= 0, found the number -4")
case("gltf_scene_root_twice", ".gltf", embed(*variant(set_path(["scenes", 0, "nodes"], [0, 0]))),
     "scenes[0].nodes[1]: node 0 is listed twice")
case("gltf_factor_out_of_range", ".gltf",
     embed(*variant(lambda d: d.update(materials=[{"pbrMetallicRoughness": {"roughnessFactor": 5}}]) or
                    d["meshes"][0]["primitives"][0].update(material=0))),
     "materials[0].pbrMetallicRoughness: a factor outside [0, 1] is clamped", 0)
case("gltf_rotation_zero", ".gltf", embed(*variant(set_path(["nodes", 0, "rotation"], [0, 0, 0, 0]))),
     "nodes[0].rotation: expected a unit quaternion (x, y, z, w), found one of length 0")
# Found by a helper (2026-12-07): tinygltf's own messages for these named no place, and called a perspective
# camera's missing yfov an OrthographicCamera's.
case("gltf_base_color_factor_three", ".gltf",
     embed(*variant(lambda d: d.update(materials=[{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1]}}]) or
                    d["meshes"][0]["primitives"][0].update(material=0))),
     "materials[0].pbrMetallicRoughness.baseColorFactor: expected an array of 4 numbers, found 3")
case("gltf_emissive_factor_two", ".gltf",
     embed(*variant(lambda d: d.update(materials=[{"emissiveFactor": [1, 1]}]) or
                    d["meshes"][0]["primitives"][0].update(material=0))),
     "materials[0].emissiveFactor: expected an array of 3 numbers, found 2")
case("gltf_accessor_type_vec5", ".gltf", embed(*variant(set_path(["accessors", 0, "type"], "VEC5"))),
     "accessors[0].type: expected SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4, found the string \"VEC5\"")
case("gltf_perspective_no_yfov", ".gltf",
     embed(*variant(lambda d: d.update(cameras=[{"type": "perspective", "perspective": {"znear": 0.1}}]))),
     "cameras[0].perspective: has no yfov; a perspective camera needs its vertical field of view, in radians")
# Meshes only another scene draws: once "the glTF file has no triangle meshes", which sent the author looking for
# them in the wrong place.
case("gltf_default_scene_without_meshes", ".gltf",
     embed(*variant(lambda d: d["nodes"].append({"name": "empty"}) or
                    d.update(scenes=[{"nodes": [0]}, {"nodes": [1]}], scene=1))),
     "scene is empty: no node of its default scene, scenes[1], has a mesh (the file's 1 mesh is not drawn)")
case("gltf_first_scene_without_meshes", ".gltf",
     embed(*variant(lambda d: d["nodes"].append({"name": "empty"}) or d.pop("scene", None) or
                    d.update(scenes=[{"nodes": [1]}, {"nodes": [0]}]))),
     "scene is empty: no node of scenes[0] (the file names no default scene) has a mesh (the file's 1 mesh is not")
# Valid glTF that tinygltf 2.7 refused: optional fields it requires, in parts lumis does not read. They render.
case("gltf_skin_without_inverse_bind_matrices", ".gltf",
     embed(*variant(lambda d: d.update(skins=[{"joints": [0]}]) or d["nodes"][0].update(skin=0))),
     "skins ignored (skinned meshes are drawn in their bind pose)", 0)
def nodeless_animation(d):
    d["animations"] = [{"samplers": [{"input": 0, "output": 0}], "channels": [
        {"sampler": 0, "target": {"path": "pointer"}}]}]


case("gltf_animation_target_without_node", ".gltf", embed(*variant(nodeless_animation)), "", 0)
case("glb_animation_target_without_node", ".glb", glb(*variant(nodeless_animation)), "", 0)  # a new JSON chunk


def zero_instance_rotation(d):  # the instance's rotation is the first 16 bytes of the positions: (0, 0, 0, 0)
    d["accessors"].append({"bufferView": 0, "componentType": 5126, "count": 1, "type": "VEC4"})
    d["nodes"][0]["extensions"] = {"EXT_mesh_gpu_instancing": {"attributes": {"ROTATION": len(d["accessors"]) - 1}}}
    d["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]


case("gltf_instance_rotation_zero", ".gltf",
     embed(*variant(zero_instance_rotation, positions=[(0, 0, 0), (0, 1, 0), (1, 0, 0)])),
     "nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.ROTATION: element 0 is (0, 0, 0, 0), expected a unit "
     "quaternion")
case("gltf_bufferview_index_oob", ".gltf", embed(*variant(set_path(["accessors", 0, "bufferView"], 9))),
     "bufferView index 9 out of range")
case("gltf_buffer_index_oob", ".gltf", embed(*variant(set_path(["bufferViews", 0, "buffer"], 4))), "bufferViews[0]")
case("gltf_index_value_oob", ".gltf", embed(*variant(lambda d: None, indices=(0, 1, 99))), "index value 99")
case("gltf_stride_too_small", ".gltf", embed(*variant(set_path(["bufferViews", 0, "byteStride"], 4))),
     "byteStride")
case("gltf_bad_component_type", ".gltf", embed(*variant(set_path(["accessors", 0, "componentType"], 5130))),
     "accessors[0]")
case("gltf_position_vec2", ".gltf", embed(*variant(set_path(["accessors", 0, "type"], "VEC2"))), "expected VEC3")
case("gltf_mesh_index_oob", ".gltf", embed(*variant(set_path(["nodes", 0, "mesh"], 5))), "mesh index 5")
case("gltf_material_index_oob", ".gltf", embed(*variant(set_path(["meshes", 0, "primitives", 0, "material"], 3))),
     "material index 3")
case("gltf_bad_mode", ".gltf", embed(*variant(set_path(["meshes", 0, "primitives", 0, "mode"], 9))), "mode 9")
case("gltf_required_extension", ".gltf",
     embed(*variant(set_path(["extensionsRequired"], ["KHR_draco_mesh_compression"]))), "KHR_draco_mesh_compression")
case("gltf_bad_base64", ".gltf",
     embed(*variant(lambda d: None)).replace("base64,", "base64,!!!!", 1),
     "buffers[0].uri: invalid base64 in the data: URI: '!' at character 0 after the comma")
case("gltf_missing_buffer_file", ".gltf",
     json.dumps(dict(good_doc, buffers=[{"byteLength": len(good_data), "uri": "no-such-buffer.bin"}])),
     "no-such-buffer.bin")
case("gltf_nan_position", ".gltf", embed(*variant(lambda d: None, positions=[(0, 0, 0), (math.nan, 0, 0), (0, 1, 0)])),
     "not finite")
case("gltf_inf_position", ".gltf", embed(*variant(lambda d: None, positions=[(0, 0, 0), (1, 0, 0), (0, math.inf, 0)])),
     "not finite")
case("gltf_huge_translation", ".gltf", embed(*variant(set_path(["nodes", 0, "translation"], [1e300, 0, 0]))),
     "not finite")
# Found by fuzz_gltf: one vertex at -7.85e25 (finite) put the framing camera beyond Embree's ray range (|origin| up
# to 1.8e18), an abort in rtcIntersect1 once the BVH holds any valid triangle. Coordinates are limited to 1e12.
case("gltf_huge_vertex", ".gltf",
     embed(*variant(lambda d: None, positions=[(0, 0, 0), (1, 0, 0), (0, 1, 0), (0.5, -7.85376861999771e+25, 6.4e-18)],
                    indices=(0, 1, 2, 0, 1, 3))),
     "coordinates must stay within 1e+12")
# Degenerate triangles (repeated and collinear corners) load and render; only the good one is visible.
case("gltf_degenerate_triangles", ".gltf",
     embed(*variant(lambda d: None, positions=[(0, 0, 0), (1, 0, 0), (0, 1, 0), (2, 0, 0)],
                    indices=(0, 1, 2, 0, 0, 0, 0, 1, 3, 1, 1, 2))), "", 0)
case("json_degenerate_mesh", ".json",
     dump(scene(shapes=[{"type": "mesh", "positions": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]],
                         "indices": [0, 1, 2, 0, 0, 0, 0, 1, 3], "material": "grey"}])),
     "/shapes/0/indices: warning: degenerate triangles dropped (2)", 0)
case("json_gltf_shape_named", ".json",
     dump(scene(shapes=[{"type": "gltf", "name": "model", "file": "gltf_degenerate_triangles.gltf"}])), "", 0)
case("json_all_degenerate_mesh", ".json",
     dump(scene(shapes=[sphere(), {"type": "mesh", "positions": [[0, 0, 0], [1, 0, 0], [2, 0, 0]],
                                   "indices": [0, 1, 2], "material": "grey", "emission": [1, 1, 1]}])),
     "/shapes/1/indices: every triangle is degenerate")


def hierarchy(nodes):
    def mutate(doc):
        doc["nodes"] = nodes
    return mutate


# Every node has one parent, but the parents form a loop 0 -> 1 -> 2 -> 0.
case("gltf_node_cycle", ".gltf", embed(*variant(hierarchy([{"mesh": 0, "children": [1]}, {"children": [2]},
                                                           {"children": [0]}]))), "cycle")
case("gltf_node_self_child", ".gltf", embed(*variant(hierarchy([{"mesh": 0, "children": [0]}]))), "cycle")
case("gltf_node_two_parents", ".gltf",
     embed(*variant(hierarchy([{"children": [2]}, {"children": [2]}, {"mesh": 0}]))), "already has parent")
case("gltf_node_child_oob", ".gltf", embed(*variant(hierarchy([{"mesh": 0, "children": [42]}]))),
     "node index 42 out of range")
case("gltf_scene_node_oob", ".gltf", embed(*variant(set_path(["scenes", 0, "nodes"], [17]))), "17")


def textured(image):
    def mutate(doc):
        doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        doc["meshes"][0]["primitives"][0]["material"] = 0
        doc["textures"] = [{"source": 0}]
        doc["images"] = [image]
    return mutate


case("gltf_missing_texture", ".gltf", embed(*variant(textured({"uri": "no-such-image.png"}))), "no-such-image.png")
case("gltf_texture_not_image", ".gltf", embed(*variant(textured({"uri": "aux_not_an_image.png"}))),
     "aux_not_an_image.png")
case("gltf_texture_unsupported_mime", ".gltf",
     embed(*variant(textured({"uri": "data:image/gif;base64," + base64.b64encode(b"GIF89a....").decode()}))),
     "images[0]")
case("gltf_texture_corrupt_png", ".gltf",
     embed(*variant(textured({"uri": "data:image/png;base64," + base64.b64encode(png(4, 4, [1, 2, 3])[:50]).decode()}))),
     "images[0]")
case("gltf_texture_index_oob", ".gltf",
     embed(*variant(lambda d: (textured({"uri": "data:image/png;base64," + base64.b64encode(png(1, 1, [9, 9, 9])).decode()})(d),
                               d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"].update(index=8)))),
     "texture index 8")

# Emission: glTF's emissiveFactor is >= 0, and numbers must fit a float (1e39 is a finite double).
def emissive(factor, strength=None):
    def mutate(doc):
        m = {"emissiveFactor": factor}
        if strength is not None:
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        doc["materials"] = [m]
        doc["meshes"][0]["primitives"][0]["material"] = 0
    return mutate


case("gltf_emissive_negative", ".gltf", embed(*variant(emissive([-1, -1, -1]))),
     "materials[0].emissiveFactor: expected numbers >= 0")
case("gltf_emissive_beyond_float", ".gltf", embed(*variant(emissive([1e39, 1, 1]))),
     "materials[0].emissiveFactor: expected finite numbers (within float's range)")
case("gltf_emissive_strength_beyond_float", ".gltf", embed(*variant(emissive([1, 1, 1], 1e39))),
     "emissiveStrength: expected a finite number (within float's range)")
case("gltf_emissive_product_overflow", ".gltf", embed(*variant(emissive([1e30, 1, 1], 1e30))),
     "materials[0].emissiveFactor: times emissiveStrength overflows")

# Empty glTF scenes.
case("gltf_no_meshes", ".gltf", json.dumps({"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "scene": 0}),
     "scene is empty")
case("gltf_only_asset", ".gltf", json.dumps({"asset": {"version": "2.0"}}), "scene is empty")

# glTF 2.0 only; component types as core glTF 2.0 allows them; buffer files named by their glTF path.
case("gltf_version_1", ".gltf", embed(*variant(set_path(["asset", "version"], "1.0"))),
     "asset.version: glTF version \"1.0\": lumis reads glTF 2.0")
case("gltf_position_unsigned_byte", ".gltf", embed(*variant(set_path(["accessors", 0, "componentType"], 5121))),
     "accessors[0].componentType: UNSIGNED_BYTE, expected FLOAT")
case("gltf_float_indices", ".gltf", embed(*variant(set_path(["accessors", 1, "componentType"], 5126))),
     "accessors[1].componentType: FLOAT, expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT")
# A buffer's data: URI that tinygltf cannot decode: the error names the buffer and what is wrong with it. tinygltf's
# own message ("Failed to decode 'uri' : data:...") quoted the whole URI, megabytes for a large model, and no path.
def with_buffer(uri=None, extra_length=0):
    def mutate(doc):
        b = doc["buffers"][0]
        if uri is not None:
            b["uri"] = uri(b["uri"]) if callable(uri) else uri
        b["byteLength"] += extra_length
    return mutate


def spoil_base64(uri):
    head, data = uri.split(",", 1)
    return head + "," + data[:10] + "!" + data[11:] + "A" * 2000


def embedded(mutate):
    doc, data = variant(lambda d: None)
    doc = json.loads(embed(doc, data))
    mutate(doc)
    return json.dumps(doc) + "\n"


case("gltf_buffer_base64_invalid", ".gltf", embedded(with_buffer(spoil_base64)),
     "buffers[0].uri: invalid base64 in the data: URI: '!' at character 10 after the comma")
case("gltf_buffer_uri_empty", ".gltf", embedded(with_buffer("")), "buffers[0].uri: is empty")
case("gltf_buffer_data_uri_not_base64", ".gltf", embedded(with_buffer(lambda u: "data:," + u.split(",", 1)[1])),
     "buffers[0].uri: a data: URI that lumis's glTF reader cannot decode, 'data:,'")
case("gltf_buffer_data_uri_short", ".gltf", embedded(with_buffer(extra_length=3)),
     "buffers[0].byteLength: is 47, but the data: URI holds 44 bytes")
case("gltf_buffer_uri_nul", ".gltf", embedded(with_buffer("tri%00.bin")),
     "buffers[0].uri: 'tri%00.bin' names a file with a NUL character (%00) in it")
case("gltf_missing_buffer_uri", ".gltf",
     json.dumps(dict(good_doc, buffers=[{"byteLength": len(good_data), "uri": "no-such-buffer.bin"}])),
     "buffers[0].uri: buffer file 'no-such-buffer.bin' not found (looked for")
# A minVersion that is not a string (tinygltf ignores it) must not turn the explanation into a JSON type error.
case("gltf_min_version_number", ".gltf",
     json.dumps(dict(good_doc, asset={"version": "2.0", "minVersion": 2},
                     buffers=[{"byteLength": len(good_data), "uri": "no-such-buffer.bin"}])),
     "buffers[0].uri: buffer file 'no-such-buffer.bin' not found")
# A glTF shape's file: .gltf or .glb, not a folder; errors inside it name the shape too.
case("json_gltf_wrong_extension", ".json", dump(scene(shapes=[{"type": "gltf", "file": "json_empty_object.json"}])),
     "/shapes/0/file: expected a .gltf or .glb file, found \".json\"")
case("json_gltf_is_folder", ".json", dump(scene(shapes=[{"type": "gltf", "file": ".."}])),
     "/shapes/0/file: is a folder, expected a file")
case("json_gltf_error_inside", ".json", dump(scene(shapes=[sphere(), {"type": "gltf", "file": "gltf_version_1.gltf"}])),
     "/shapes/1/file: in")

# Found by a review (stop 41): cameras that float arithmetic could not hold.
case("json_camera_huge_near", ".json", dump(scene(camera={"from": [0, 1, 4], "to": [0, 1, 0], "near": 1e20})),
     "/camera/near: the camera's near clip distance, 1e+20, starts its rays up to 1e+20 scene units from the origin")
# Found by a helper (2026-12-07): at 1e13 scene units Embree's triangle test overflows float, and triangles cast no
# shadows; this scene (a floor, a triangle and a quad light, 1e13 times their usual size) once rendered so silently.
case("json_triangle_shadows_out_of_range", ".json",
     dump(scene(camera={"from": [0, 1.2e13, 4e13], "to": [0, 0.8e13, 0], "fov": 45},
                shapes=[{"type": "quad", "origin": [-2e13, 0, 2e13], "edge_u": [4e13, 0, 0], "edge_v": [0, 0, -4e13],
                         "material": "grey"},
                        {"type": "mesh", "positions": [[-1e13, 0.5e13, 0], [-0.2e13, 0.5e13, 0], [-0.6e13, 1.5e13, 0]],
                         "indices": [0, 1, 2], "material": "grey"}],
                lights=[{"type": "quad", "origin": [-0.5e13, 2.2e13, 0], "edge_u": [1e13, 0, 0],
                         "edge_v": [0, 0, 1e13], "radiance": [8, 8, 8]}])),
     "/shapes/0: the shape reaches 2e+13 scene units from the origin; coordinates must stay within 1e+12")
# Found by a helper (2026-12-07): a shadow ray toward a sphere light of radius 1e-18 had a direction beyond Embree's
# FLT_LARGE (1.8e18), and Embree's packet query asserted and aborted lumis (exit 134). It renders (exit 0).
case("json_sphere_light_radius_tiny", ".json",
     dump(scene(camera={"from": [0, 3, 3], "to": [0, 0, 0], "fov": 40}, film={"width": 8, "height": 6},
                shapes=[{"type": "quad", "origin": [-2, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 0, -4],
                         "material": "grey"}],
                lights=[{"type": "sphere", "center": [0, 2, -1.5], "radius": 1e-18, "radiance": [1, 1, 1]}])), "", 0)
case("cli_light_probability_rounds_to_one", ".json", dump(BASE), "expected a probability in [0, 1)", 2,
     "--integrator mis --mis-light-probability 0.99999999999")


def camera(perspective, translation=(0, 0.3, 3)):
    """A perspective camera node looking down -z at the triangle."""
    def mutate(doc):
        doc["cameras"] = [{"type": "perspective", "perspective": perspective}]
        doc["nodes"].append({"camera": 0, "translation": list(translation)})
        doc["scenes"][0]["nodes"].append(1)
    return mutate


case("gltf_camera_huge_znear", ".gltf", embed(*variant(camera({"yfov": 0.8, "znear": 1e30}))),
     "nodes[1]: the camera's near clip distance, 1e+30")
case("gltf_camera_znear_beyond_float", ".gltf", embed(*variant(camera({"yfov": 0.8, "znear": 1e39}))),
     "cameras[0].perspective.znear: expected a number >= 0 that stays finite in float")
case("gltf_camera_yfov_underflows", ".gltf", embed(*variant(camera({"yfov": 1e-50, "znear": 0.01}))),
     "cameras[0].perspective.yfov: expected an angle in (0, pi) radians that is not 0 in float")
# 1e9 units out (within the 1e12 limit) the camera's point at z = -1 rounded onto its position: "degenerate".
case("gltf_camera_far_from_origin", ".gltf",
     embed(*variant(camera({"yfov": 0.8, "znear": 0.01}, (0, 300, 1e9)),
                    positions=[(-1000, 0, 1e9 - 3000), (1000, 0, 1e9 - 3000), (0, 1000, 1e9 - 3000)])), "", 0)
# Found by a review (stop 51): tinygltf 2.7 ignores an optional field of the wrong type and keeps its default (a
# material of "0" rendered the default material, "mode": "1" drew lines as triangles), and truncates an index beyond
# int's range. lumis names each field instead.
PRIM = ["meshes", 0, "primitives", 0]
case("gltf_mode_string", ".gltf", embed(*variant(set_path(PRIM + ["mode"], "1"))),
     "meshes[0].primitives[0].mode: expected a whole number, found the string \"1\"")
case("gltf_mode_beyond_int", ".gltf", embed(*variant(set_path(PRIM + ["mode"], 2 ** 32 + 4))),
     "meshes[0].primitives[0].mode: expected a whole number in int's range, found the number 4294967300")
case("gltf_mesh_index_float", ".gltf", embed(*variant(set_path(["nodes", 0, "mesh"], 0.0))),
     "nodes[0].mesh: expected an index (a whole number >= 0) written without a decimal point or exponent, found 0.0")
case("gltf_material_index_beyond_int", ".gltf", embed(*variant(set_path(PRIM + ["material"], 2 ** 32))),
     "meshes[0].primitives[0].material: expected an index (a whole number >= 0) no greater than 2147483647, found "
     "the number 4294967296")
case("gltf_scene_nodes_string", ".gltf", embed(*variant(set_path(["scenes", 0, "nodes"], ["0"]))),
     "scenes[0].nodes[0]: expected an index (a whole number >= 0), found the string \"0\"")
case("gltf_attributes_array", ".gltf", embed(*variant(set_path(PRIM + ["attributes"], [0]))),
     "meshes[0].primitives[0].attributes: expected an object of indices, found an array of 1 element")
case("gltf_nodes_object", ".gltf", embed(*variant(set_path(["nodes"], {"mesh": 0}))),
     "nodes: expected an array of objects, found an object")
case("gltf_metallic_string", ".gltf",
     embed(*variant(lambda d: d.update(materials=[{"pbrMetallicRoughness": {"metallicFactor": "0"}}]))),
     "materials[0].pbrMetallicRoughness.metallicFactor: expected a number, found the string \"0\"")
case("gltf_base_color_factor_string", ".gltf",
     embed(*variant(lambda d: d.update(materials=[{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, "0", 1]}}]))),
     "materials[0].pbrMetallicRoughness.baseColorFactor[2]: expected a number, found the string \"0\"")
case("gltf_double_sided_number", ".gltf", embed(*variant(lambda d: d.update(materials=[{"doubleSided": 1}]))),
     "materials[0].doubleSided: expected true or false, found the number 1")
case("gltf_texcoord_string", ".gltf",
     embed(*variant(lambda d: d.update(materials=[{"emissiveTexture": {"index": 0, "texCoord": "1"}}]))),
     "materials[0].emissiveTexture.texCoord: expected an index (a whole number >= 0), found the string \"1\"")
case("gltf_camera_aspect_zero", ".gltf",
     embed(*variant(camera({"yfov": 0.8, "znear": 0.01, "aspectRatio": 0}))),
     "cameras[0].perspective.aspectRatio: expected a number > 0, found the number 0")
case("gltf_required_extension_number", ".gltf", embed(*variant(set_path(["extensionsRequired"], [7]))),
     "extensionsRequired[0]: expected a string, found the number 7")
# Fields lumis does not read are left to other tools, whatever their type (here extras and zfar).
case("gltf_unread_fields_any_type", ".gltf",
     embed(*variant(lambda d: d["nodes"][0].update(extras={"mesh": "x"}) or
                    camera({"yfov": 0.8, "znear": 0.01, "zfar": "far"})(d))), "", 0)

# Remove stale cases (files this script no longer writes).
keep = set(written)
for f in os.listdir(HERE):
    if f.endswith(".expect") and f[: -len(".expect")] not in keep:
        os.remove(os.path.join(HERE, f))
print("%d cases" % len(written))
