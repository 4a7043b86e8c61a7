#!/usr/bin/env python3
"""Writes the bad-input matrix (tests/bad_input/<case>/): each case holds the files that differ from
_base/ and case.json = {"args": [...insitu arguments...], "exit": 2, "message": "<regex for the one
stderr line>", "unchanged": [files that must be byte-identical afterwards]}. The runner
(tests/bad_input_test.cpp) copies _base/, then the case, into a temporary folder and runs insitu
there. Rerun this script after changing it; it rewrites every case folder it knows."""
import base64, json, os, re, shutil, struct, subprocess, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
BASE_SCENE = json.load(open(os.path.join(HERE, "_base", "scene.json")))


def case(name, args, message, unchanged=(), files=None, scene=None, exit_code=2, links=None):
    d = os.path.join(HERE, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    for rel, content in (files or {}).items():
        p = os.path.join(d, rel)
        os.makedirs(os.path.dirname(p), exist_ok=True)
        with open(p, "wb") as f:
            f.write(content if isinstance(content, bytes) else content.encode())
    for rel, target in (links or {}).items():
        os.symlink(target, os.path.join(d, rel))
    if scene is not None:
        with open(os.path.join(d, "scene.json"), "w") as f:
            f.write(scene if isinstance(scene, str) else json.dumps(scene, indent=1))
    with open(os.path.join(d, "case.json"), "w") as f:
        json.dump({"args": args, "exit": exit_code, "message": message, "unchanged": list(unchanged)}, f, indent=1)
        f.write("\n")


def scene_with(**changes):
    s = json.loads(json.dumps(BASE_SCENE))
    for path, value in changes.items():
        keys = path.split("__")
        node = s
        for k in keys[:-1]:
            node = node[int(k)] if isinstance(node, list) else node[k]
        last = keys[-1]
        if isinstance(node, list):
            node[int(last)] = value
        else:
            node[last] = value
    return s


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png_declaring(width, height):
    """A PNG whose header (with a valid CRC) declares width x height, followed by one tiny IDAT."""
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + png_chunk(b"IDAT", zlib.compress(b"\0" * 4)) + png_chunk(b"IEND", b"")


def oiio_image(path_in_case, args):
    """An image made by oiiotool (which install-deps.sh installs)."""
    tmp = os.path.join(HERE, "_tmp" + os.path.splitext(path_in_case)[1])
    subprocess.check_call(["oiiotool"] + args + ["-o", tmp])
    data = open(tmp, "rb").read()
    os.remove(tmp)
    return data


def gpano_attributes(full_w, full_h, crop_w, crop_h, left, top):
    return ('GPano:ProjectionType="equirectangular" GPano:FullPanoWidthPixels="%d" GPano:FullPanoHeightPixels="%d" '
            'GPano:CroppedAreaImageWidthPixels="%d" GPano:CroppedAreaImageHeightPixels="%d" '
            'GPano:CroppedAreaLeftPixels="%d" GPano:CroppedAreaTopPixels="%d"' % (full_w, full_h, crop_w, crop_h, left, top))


def with_xmp(jpeg, gpano):
    """The JPEG with an XMP packet holding `gpano` in an APP1 segment after its SOI marker, as
    phones write a panorama's placement."""
    xmp = ('<?xpacket begin="" id="W5M0MpCehiHzreSzNTczkc9d"?><x:xmpmeta xmlns:x="adobe:ns:meta/">'
           '<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#"><rdf:Description rdf:about="" '
           'xmlns:GPano="http://ns.google.com/photos/1.0/panorama/" ' + gpano +
           '/></rdf:RDF></x:xmpmeta><?xpacket end="w"?>').encode()
    payload = b"http://ns.adobe.com/xap/1.0/\0" + xmp
    return jpeg[:2] + b"\xff\xe1" + struct.pack(">H", len(payload) + 2) + payload + jpeg[2:]


SHOTS = {k: "s%d.png" % i for i, k in enumerate(["+x", "-x", "+z", "-z", "up", "down"])}


def six_shots(size=8, value="0.4,0.4,0.4"):
    img = oiio_image("x.png", ["--pattern", "constant:color=" + value, "%dx%d" % (size, size), "3", "-d", "uint8"])
    return {f: img for f in SHOTS.values()}


def main():
    for d in os.listdir(HERE):
        if os.path.isfile(os.path.join(HERE, d, "case.json")):
            shutil.rmtree(os.path.join(HERE, d))
    # --- Outputs that would destroy an input (issue 10, "fix first") ---
    case("render_o_is_photo", ["render", "scene.json", "-o", "photo.png"], r"-o|is the photo", ["photo.png"])
    case("render_o_is_photo_through_dotdot", ["render", "scene.json", "-o", "sub/../photo.png"], "is the photo",
         ["photo.png"], files={"sub/.keep": ""})
    case("render_o_is_photo_through_symlink", ["render", "scene.json", "-o", "link.png"], "is the photo", ["photo.png"],
         links={"link.png": "photo.png"})
    case("render_output_image_is_photo", ["render", "scene.json"], "is the photo", ["photo.png"],
         scene=scene_with(output={"image": "photo.png"}))
    shots_scene = scene_with(environment={"shots": dict(SHOTS, faced="-z")})
    case("render_o_is_a_shot", ["render", "scene.json", "-o", "s0.png"], r"is shot \+x", ["s0.png"], files=six_shots(),
         scene=shots_scene)
    tex = oiio_image("t.png", ["--pattern", "checker", "8x8", "3", "-d", "uint8"])
    case("render_o_is_a_texture", ["render", "scene.json", "-o", "tex.png"], "read by .*quad.obj", ["tex.png"],
         files={"tex.png": tex, "quad.mtl": "newmtl red\nKd 1 1 1\nmap_Kd tex.png\n"})
    case("render_layers_is_the_image", ["render", "scene.json"], "is also the output image", ["photo.png"],
         scene=scene_with(output={"image": "out/c.exr", "layers": "out/c.exr"}))
    case("render_layers_is_the_environment", ["render", "scene.json", "--layers", "env.exr"], "is the environment", ["env.exr"])
    case("render_o_is_the_scene_file", ["render", "scene.json", "-o", "scene.json"], "unsupported extension", ["scene.json"])
    points = json.dumps([{"uv": [10 + 5 * i, 8 + 3 * i], "xyz": [i, 0, -i]} for i in range(6)])
    case("calibrate_o_is_the_photo", ["calibrate", "--points", "p.json", "--image", "photo.png", "-o", "photo.png"],
         "is the photo", ["photo.png"], files={"p.json": points})
    case("calibrate_vc_is_the_points", ["calibrate", "--points", "p.json", "--size", "48", "32", "--vc", "p.json"],
         "is the control points", ["p.json"], files={"p.json": points})
    case("compare_o_is_image_a", ["compare", "photo.png", "photo.png", "-o", "photo.png"], "is image A", ["photo.png"])
    case("cubemap_writes_over_its_input", ["cubemap", "cube.exr", "-o", "."], "is the environment argument", ["cube.exr"],
         files={"cube.exr": open(os.path.join(HERE, "_base", "env.exr"), "rb").read()})
    # --- Once exit 1 (internal error) on bad input ---
    case("json_number_overflows_a_double", ["render", "scene.json"], "1e400",
         scene='{"photo": "photo.png", "camera": {"eye": [0, 1, 1e400], "look": [0, 0, 0], "hfov_deg": 60}}')
    case("points_number_overflows_a_double", ["calibrate", "--points", "p.json", "--size", "48", "32"], "p.json.*1e400",
         files={"p.json": '[{"uv": [1e400, 2], "xyz": [0, 0, 0]}]'})
    case("png_header_declares_100000_squared", ["render", "scene.json"], "100000x100000.*megapixels", ["photo.png"],
         files={"photo.png": png_declaring(100000, 100000)})
    case("png_header_declares_20000_squared", ["render", "scene.json"], "20000x20000.*megapixels",
         files={"photo.png": png_declaring(20000, 20000)})
    one = oiio_image("o.png", ["--pattern", "constant:color=0.5,0.5,0.5", "1x1", "3", "-d", "uint8"])
    brackets = {"shots": {k: {"files": ["b%d_a.png" % i, "b%d_b.png" % i], "times": [0.01, 0.04]} for i, k in
                          enumerate(["+x", "-x", "+z", "-z", "up", "down"])}}
    brackets["shots"]["faced"] = "-z"
    files = {}
    for i in range(6):
        files["b%d_a.png" % i] = one
        files["b%d_b.png" % i] = one
    case("brackets_of_1x1_pixel", ["render", "scene.json"], "too small to recover the camera response", files=files,
         scene=scene_with(environment=brackets))
    white = oiio_image("w.png", ["--pattern", "constant:color=1,1,1", "16x16", "3", "-d", "uint8"])
    files = {k: white for k in files}
    case("brackets_all_white", ["render", "scene.json"], "unclipped grey level", files=files,
         scene=scene_with(environment=brackets))
    # Checked before rendering: with 2^20 samples per pixel a render would take minutes first.
    case("output_folder_is_a_file", ["render", "scene.json", "-o", "photo.png/x.png"], r"photo.png/x.png: cannot create its folder",
         ["photo.png"], scene=json.dumps(BASE_SCENE).replace('"spp": 1', '"spp": 1048576'))
    case("o_names_a_directory", ["render", "scene.json", "-o", "d.png"], "d.png: is a directory", files={"d.png/.keep": ""})
    # --- Accepted silently, but wrong ---
    # Missing only its last tenth, a JPEG "decodes" (libjpeg fills the rest): once rendered silently.
    jpeg = oiio_image("p.jpg", ["--pattern", "checker", "480x320", "3", "-d", "uint8"])
    case("truncated_jpeg_photo", ["render", "scene.json"], r"photo.jpg: truncated or corrupt image: .*Premature end",
         files={"photo.jpg": jpeg[: len(jpeg) * 9 // 10]}, scene=scene_with(photo="photo.jpg"))
    case("duplicate_json_key", ["render", "scene.json"], r"\$\.render\.spp: duplicate key",
         scene='{"photo": "photo.png", "camera": {"eye": [0.5, 2, 1.5], "look": [0.5, 0, -0.5], "hfov_deg": 60},'
               ' "environment": "env.exr", "render": {"spp": 1, "spp": 2}}')
    case("nul_byte_after_the_json", ["render", "scene.json"], r"scene.json:1:\d+: a NUL byte",
         scene=json.dumps(BASE_SCENE) + "\0garbage")
    case("kd_nan", ["render", "scene.json"], r"quad.mtl:2: Kd", files={"quad.mtl": "newmtl red\nKd nan 0 0\n"})
    case("ks_out_of_range", ["render", "scene.json"], r"quad.mtl:3: Ks -5 is outside \[0, 1\]",
         files={"quad.mtl": "newmtl red\nKd 0.5 0.5 0.5\nKs -5 1e30 -1\n"})
    case("ns_negative", ["render", "scene.json"], r"quad.mtl:2: Ns -2 is negative", files={"quad.mtl": "newmtl red\nNs -2\n"})
    case("scale_1e300", ["render", "scene.json"], r"\$\.objects\[0\].*(beyond|not finite)", scene=scene_with(objects__0__scale=1e300))
    case("scale_1e-300", ["render", "scene.json"], r"\$\.objects\[0\].*not invertible", scene=scene_with(objects__0__scale=1e-300))
    case("translate_1e300", ["render", "scene.json"], r"\$\.objects\[0\].*beyond",
         scene=scene_with(objects__0__translate=[1e300, 0, 0]))
    case("principal_point_1e300", ["render", "scene.json"], r"\$\.camera\.intrinsics\.cx: 1e\+300 is out of range",
         scene=scene_with(camera={"intrinsics": {"fx": 40, "cx": 1e300}, "pose": {"R": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "t": [0, 0, 3]}}))
    far_points = json.dumps([{"uv": [100 + 60 * i, 50 + 40 * i], "xyz": [i, 0, -i], "name": "p%d" % i} for i in range(6)])
    case("points_outside_the_given_size", ["calibrate", "--points", "p.json", "--size", "64", "48"],
         r"6 point\(s\) outside the 64x48 image: p0 \(100.0, 50.0\), p1 \(160.0, 90.0\)", files={"p.json": far_points})
    case("eye_and_look_overflow", ["render", "scene.json"], "overflows a double",
         scene=scene_with(camera={"eye": [1e300, 0, 0], "look": [-1e300, 0, 0], "hfov_deg": 60}))
    case("spp_two_to_the_64_minus_1", ["render", "scene.json"], "18446744073709551615 is out of range",
         scene=json.dumps(BASE_SCENE).replace('"spp": 1', '"spp": 18446744073709551615'))
    case("size_zero", ["calibrate", "--points", "p.json", "--size", "0", "0"], r"--size: Value 0 not in range 1 to 1048576",
         files={"p.json": points})
    case("scene_is_a_directory", ["render", "sub"], "sub: is a directory", files={"sub/.keep": ""})
    # --- Messages that name the real mistake (issue 9) ---
    case("camera_fov_key", ["render", "scene.json"], r"\$\.camera\.fov: unknown key",
         scene=scene_with(camera={"eye": [0.5, 2, 1.5], "look": [0.5, 0, -0.5], "fov": 70}))
    case("rotate_as_an_array", ["render", "scene.json"], r"\$\.objects\[0\]\.rotate: expected degrees about \+Y",
         scene=scene_with(objects__0__rotate=[0, 20, 0]))
    case("scale_as_a_string", ["render", "scene.json"], r"\$\.objects\[0\]\.scale: expected a number",
         scene=scene_with(objects__0__scale="0.3"))
    case("mesh_is_ply", ["render", "scene.json"], r"only OBJ and glTF meshes are supported \('\.ply'\)",
         files={"chair.ply": "ply\nformat ascii 1.0\nend_header\n"}, scene=scene_with(objects__0__mesh="chair.ply"))
    case("rotation_not_orthonormal", ["render", "scene.json"], r"\$\.camera\.pose\.R: not a rotation",
         scene=scene_with(camera={"intrinsics": {"fx": 40}, "pose": {"R": [[1.01, 0, 0], [0, -1, 0], [0, 0, -1]], "t": [0, 0, 3]}}))
    case("layers_not_exr", ["render", "scene.json", "--layers", "l.png"], "use .exr, or none")
    png = oiio_image("t.png", ["--pattern", "checker", "64x64", "3", "-d", "uint8"])
    case("truncated_png_texture", ["render", "scene.json"], r"quad.obj: material 'red': map_Kd: .*tex.png",
         files={"tex.png": png[: len(png) // 2], "quad.mtl": "newmtl red\nKd 1 1 1\nmap_Kd tex.png\n"})
    systematic_cases()
    more_cases()
    gltf_cases()
    message_cases()
    print("wrote", sum(1 for d in os.listdir(HERE) if os.path.isfile(os.path.join(HERE, d, "case.json"))), "cases")


def systematic_cases():
    """Families of cases over the scene file's keys: a missing file for every key that names one, a
    wrong JSON type for every key, a non-finite or out-of-range number, an unknown key in every
    object, and a missing required key."""
    shots = dict(SHOTS, faced="-z")
    full = scene_with(environment={"shots": shots})
    full["local_scene"] = [{"plane": {"point": [0, 0, 0], "normal": [0, 1, 0]}}]
    full["references"] = [{"polygon_px": [[4, 20], [20, 20], [20, 30], [4, 30]], "albedo": 0.8}]
    full["render"] = {"integrator": "path", "spp": 1, "max_depth": 2, "seed": 1}
    full["composite"] = "ratio"
    full["output"] = {"image": "out/c.png", "layers": "out/l.exr", "tonemap": {"op": "adaptive_log", "key": 1, "bias": 0.85}}
    shot_files = six_shots()

    def variant(name, path, value, message, delete=False):
        s = json.loads(json.dumps(full))
        node = s
        for k in path[:-1]:
            node = node[k]
        if delete:
            del node[path[-1]]
        else:
            node[path[-1]] = value
        where = "$" + "".join("[%d]" % k if isinstance(k, int) else "." + k for k in path)
        case(name, ["render", "scene.json"], message.replace("WHERE", re.escape(where)),
             files=shot_files, scene=s)

    # Missing files, one for each key that names a file.
    file_keys = [(("photo",), "photo"), (("environment", "shots", "+x"), "+x"), (("environment", "shots", "up"), "up"),
                 (("objects", 0, "mesh"), "mesh")]
    for path, tag in file_keys:
        variant("missing_file_" + tag.replace("+", "p"), path, "nowhere.png", r"WHERE: file not found")
    variant("missing_file_points", ("camera",), {"points": "nowhere.json"}, r"\$\.camera\.points: file not found")
    variant("missing_file_camera_file", ("camera",), {"file": "nowhere.json"}, r"\$\.camera\.file: file not found")
    variant("missing_file_environment_image", ("environment",), "nowhere.exr", r"\$\.environment: file not found")
    # Wrong JSON types.
    typed = [(("photo",), 3, "string"), (("camera",), "eye", "object"), (("camera", "eye"), "far", "array"),
             (("camera", "hfov_deg"), "60", "number"), (("environment", "shots", "faced"), 5, "string"),
             (("objects",), {"mesh": "quad.obj"}, "array"), (("objects", 0), "quad.obj", "object"),
             (("objects", 0, "translate"), [1, 2], "3"), (("local_scene", 0, "plane", "normal"), "up", "array"),
             (("render",), [], "object"), (("render", "spp"), 1.5, "integer"), (("render", "spp"), "4", "integer"),
             (("render", "integrator"), 1, "string"), (("render", "seed"), -1, "range"),
             (("render", "max_depth"), 0, "range"), (("composite",), "multiply", "ratio"),
             (("output", "image"), "out/c.bmp", "extension"), (("output", "layers"), "out/l.png", "extension"),
             (("output", "tonemap", "op"), "filmic", "photo"), (("output", "tonemap", "bias"), 2, "range"),
             (("output", "tonemap", "key"), 0, "range"), (("local_scene", 0, "mean_albedo"), "half", "number"),
             (("environment", "inverse_lighting"), "yes", "boolean"), (("render", "noise_target"), "1%", "number"),
             (("references",), {"polygon_px": []}, "array"), (("references", 0, "polygon_px"), [[1, 1], [9, 9]], "3"),
             (("references", 0, "polygon_px", 1), "20, 20", "array"), (("references", 0, "albedo"), "white", "number"),
             (("denoise",), "yes", "boolean")]
    for i, (path, value, word) in enumerate(typed):
        variant("wrong_type_%02d_%s" % (i, "_".join(str(k) for k in path).replace("+", "p")), path, value, r"WHERE: .*")
    # Numbers that are not finite or not sensible.
    for i, (path, value) in enumerate([(("camera", "eye"), [0, "NaN", 0]), (("camera", "look"), [0, 1e309, 0]),
                                       (("camera", "hfov_deg"), 0), (("camera", "hfov_deg"), 180),
                                       (("camera", "hfov_deg"), -30), (("objects", 0, "scale"), 0),
                                       (("objects", 0, "scale"), [1, 0, 1]), (("objects", 0, "rotate"), 1e400),
                                       (("local_scene", 0, "plane", "normal"), [0, 0, 0]),
                                       (("render", "spp"), 0), (("render", "spp"), 1 << 40),
                                       (("render", "noise_target"), -0.01), (("render", "noise_target"), 2),
                                       (("references", 0, "albedo"), 0), (("references", 0, "albedo"), 1.5),
                                       (("references", 0, "polygon_px"), [[1, 1], [5, 5], [9, 9]]),
                                       (("references", 0, "polygon_px"), [[4, 20], [60, 20], [20, 30]])]):
        variant("bad_number_%02d_%s" % (i, "_".join(str(k) for k in path)), path, value, r"scene.json.*")
    # Unknown keys, in every object of the file.
    for i, path in enumerate([("typo",), ("camera", "typo"), ("environment", "typo"), ("environment", "shots", "typo"),
                              ("objects", 0, "typo"), ("local_scene", 0, "typo"), ("local_scene", 0, "plane", "typo"),
                              ("render", "typo"), ("output", "typo"), ("output", "tonemap", "typo"),
                              ("references", 0, "typo")]):
        variant("unknown_key_%02d_%s" % (i, "_".join(str(k) for k in path[:-1]) or "root"), path, 1, r"WHERE: unknown key")
    # Missing required keys.
    for path in [("photo",), ("camera",), ("environment",), ("camera", "look"), ("environment", "shots", "faced"),
                 ("environment", "shots", "down"), ("objects", 0, "mesh"), ("local_scene", 0, "plane", "point"),
                 ("references", 0, "albedo")]:
        variant("missing_key_" + "_".join(str(k) for k in path), path, None, r"scene.json.*(missing|required)", delete=True)


def gltf_quad(indices=(0, 1, 2, 0, 2, 3), count=4, required=(), buffer_uri=None, material=None, draco=None,
              meshopt=None):
    """A unit quad as a .gltf, its buffer in a data URI (or at buffer_uri, not written); draco: the
    primitive's KHR_draco_mesh_compression object; meshopt: buffer view 0's EXT_meshopt_compression."""
    pos = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1)
    idx = struct.pack("<%dH" % len(indices), *indices)
    data = pos + idx
    uri = buffer_uri or "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3"},
                       {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
         "bufferViews": [{"buffer": 0, "byteLength": len(pos)}, {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
         "buffers": [{"uri": uri, "byteLength": len(data)}]}
    if required:
        g["extensionsRequired"] = g["extensionsUsed"] = list(required)
    if material is not None:
        g["materials"] = [material]
        g["meshes"][0]["primitives"][0]["material"] = 0
    if draco is not None:
        g["meshes"][0]["primitives"][0]["extensions"] = {"KHR_draco_mesh_compression": draco}
    if meshopt is not None:
        g["bufferViews"][0]["extensions"] = {"EXT_meshopt_compression": meshopt}
    return json.dumps(g)


def gltf_cases():
    """glTF furniture: each refusal names the file and the JSON path or accessor."""
    at = scene_with(objects__0__mesh="chair.gltf")
    for name, text, message in [
            ("required_webp", gltf_quad(required=["EXT_texture_webp"]),
             r"chair.gltf: \$\.extensionsRequired\[0\]: .*EXT_texture_webp"),
            ("draco_not_a_stream",  # the indices' bytes where the Draco stream should be
             gltf_quad(required=["KHR_draco_mesh_compression"],
                       draco={"bufferView": 1, "attributes": {"POSITION": 0}}),
             r"chair.gltf: \$\.meshes\[0\]\.primitives\[0\]\.extensions\.KHR_draco_mesh_compression: "
             r"Draco cannot decode"),
            ("meshopt_bomb",  # 2³⁰ vertices declared from 48 encoded bytes
             gltf_quad(required=["EXT_meshopt_compression"],
                       meshopt={"buffer": 0, "byteLength": 48, "byteStride": 12, "count": 1 << 30, "mode": "ATTRIBUTES"}),
             r"chair.gltf: \$\.bufferViews\[0\]\.extensions\.EXT_meshopt_compression: .*cannot come from 48"),
            ("index_range", gltf_quad(indices=(0, 1, 7)), r"chair.gltf: \$\.accessors\[1\] \(indices\): index 7"),
            ("past_buffer", gltf_quad(count=40), r"chair.gltf: \$\.accessors\[0\] \(POSITION\): .*past the end"),
            ("missing_bin", gltf_quad(buffer_uri="chair.bin"), r"chair.gltf: .*chair.bin"),
            ("not_json", "{\"asset\": ", r"chair.gltf: "),
            ("alpha_mode", gltf_quad(material={"alphaMode": "CUTOUT"}),
             r"chair.gltf: \$\.materials\[0\]\.alphaMode: 'CUTOUT' is not OPAQUE, MASK or BLEND"),
            ("clearcoat_nan", gltf_quad(material={"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": "x"}}}),
             r"chair.gltf: \$\.materials\[0\]\.extensions\.KHR_materials_clearcoat\.clearcoatFactor: must be a finite")]:
        case("gltf_" + name, ["render", "scene.json"], message, files={"chair.gltf": text}, scene=at)
    # A compressed file (so export-blender writes a plain copy) with a view that no accessor reads
    # into a buffer that does not exist: the render never reads it, the copy would.
    g = json.loads(gltf_quad())
    g["extensionsUsed"] = ["EXT_meshopt_compression"]
    g["bufferViews"].append({"buffer": 5, "byteLength": 4})
    case("gltf_copy_view_outside", ["export-blender", "scene.json", "-o", "s.py"],
         r"chair.gltf: \$\.bufferViews\[2\]: lies outside its buffer", files={"chair.gltf": json.dumps(g)},
         scene=scene_with(objects__0__mesh="chair.gltf", render={"spp": 1, "integrator": "path"}))


def more_cases():
    """Meshes, points, images, command lines, environments and camera files."""
    data = os.path.join(HERE, "..", "data")
    for f in sorted(os.listdir(data)):
        if f.startswith("bad_") and f.endswith(".obj"):
            case("obj_" + f[4:-4], ["render", "scene.json"], r"quad.obj:\d+: ",
                 files={"quad.obj": open(os.path.join(data, f), "rb").read()})
    for name, text in [("empty", ""), ("no_faces", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), ("binary", "\x00\xff\x13garbage\n"),
                       ("face_of_text", "v 0 0 0\nf a b c\n"), ("vertex_inf", "v inf 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                       ("huge_index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n"),
                       ("negative_past_start", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n")]:
        case("obj_" + name, ["render", "scene.json"], r"quad.obj", files={"quad.obj": text})
    for name, text in [("kd_text", "newmtl red\nKd red\n"), ("kd_missing", "newmtl red\nKd\n"), ("d_2", "newmtl red\nd 2\n"),
                       ("ka_negative", "newmtl red\nKa -1 0 0\n"), ("ns_inf", "newmtl red\nNs inf\n"),
                       ("kd_above_one", "newmtl red\nKd 1.5 0.5 0.5\n")]:
        case("mtl_" + name, ["render", "scene.json"], r"quad.mtl:2: ", files={"quad.mtl": text})
    good = [{"uv": [10 + 5 * i, 8 + 3 * i], "xyz": [i, 0, -i]} for i in range(6)]
    for name, fname, text in [("empty_json", "p.json", ""), ("object_not_list", "p.json", '{"uv": [1, 2]}'),
                              ("four_points", "p.json", json.dumps(good[:4])), ("uv_of_one", "p.json", json.dumps([{"uv": [1], "xyz": [0, 0, 0]}] * 6)),
                              ("xyz_nan", "p.json", json.dumps(good).replace("[0, 0, 0]", '[0, "NaN", 0]')),
                              ("unknown_key", "p.json", json.dumps([dict(p, color="red") for p in good])),
                              ("csv_text", "p.csv", "a,b,c,d,e\n1,2,x,4,5\n"), ("csv_four_columns", "p.csv", "1,2,3,4\n" * 6),
                              ("vc_truncated", "p.vc", "1 2 3\n0 0 0\n"), ("unknown_extension", "p.xml", "<points/>"),
                              ("all_one_point", "p.json", json.dumps([{"uv": [10, 10], "xyz": [1, 1, 1]}] * 6)),
                              ("collinear", "p.json", json.dumps([{"uv": [10 + i, 10 + i], "xyz": [i, i, i]} for i in range(6)]))]:
        case("points_" + name, ["calibrate", "--points", fname, "--size", "640", "480"], re.escape(fname), files={fname: text})
    for name, content in [("zero_bytes", b""), ("text", b"not an image at all\n"), ("bad_crc", png_declaring(48, 32)[:-4] + b"\0\0\0\0")]:
        case("photo_" + name, ["render", "scene.json"], r"photo.png", files={"photo.png": content})
    case("photo_is_a_directory", ["render", "scene.json"], r"photo", files={"dir.png/.keep": ""}, scene=scene_with(photo="dir.png"))
    case("environment_garbage_exr", ["render", "scene.json"], r"env.exr", files={"env.exr": b"\x76\x2f\x31\x01garbage"})
    wide = oiio_image("e.exr", ["--pattern", "constant:color=1,1,1", "30x7", "3", "-d", "float"])
    case("environment_wrong_aspect", ["render", "scene.json"], r"env.exr", files={"env.exr": wide})
    pano = oiio_image("p.jpg", ["--pattern", "constant:color=0.5,0.5,0.5", "32x16", "3", "-d", "uint8"])
    for name, attributes, message in [
            ("gpano_outside", gpano_attributes(64, 32, 32, 16, 0, 20), r"pano\.jpg: GPano's cropped area lies outside"),
            ("gpano_not_2_to_1", gpano_attributes(64, 40, 32, 16, 0, 0), r"pano\.jpg: .*2:1"),
            ("gpano_not_a_number", gpano_attributes(64, 32, 32, 16, 0, 0).replace('LeftPixels="0"', 'LeftPixels="left"'),
             r"pano\.jpg: GPano:CroppedAreaLeftPixels")]:
        case("environment_" + name, ["render", "scene.json"], message, files={"pano.jpg": with_xmp(pano, attributes)},
             scene=scene_with(environment={"image": "pano.jpg"}))
    for name, args, message in [
            ("render_without_scene", ["render"], "scene"), ("calibrate_without_points", ["calibrate", "--size", "4", "4"], "points"),
            ("compare_one_image", ["compare", "photo.png"], "b"), ("cubemap_without_output", ["cubemap", "env.exr"], "output"),
            ("irradiance_report_missing", ["irradiance-report", "none.exr"], "none.exr"),
            ("tradeoff_ladder_zero", ["tradeoff", "scene.json", "-o", "t", "--ladder", "0"], "ladder"),
            ("spp_negative", ["render", "scene.json", "--spp", "-1"], "spp"), ("seed_negative", ["render", "scene.json", "--seed", "-5"], "seed"),
            ("tonemap_unknown", ["render", "scene.json", "--tonemap", "filmic"], "tonemap"),
            ("noise_target_negative", ["render", "scene.json", "--noise-target", "-0.1"], "noise-target"),
            ("key_negative", ["render", "scene.json", "--key", "-1"], "key"),
            ("irradiance_unknown", ["render", "scene.json", "--irradiance", "sh4"], "irradiance"),
            ("volume_without_room_box", ["render", "scene.json", "--integrator", "irradiance", "--irradiance", "volume"], "room_box"),
            ("integrator_unknown", ["render", "scene.json", "--integrator", "bdpt"], "unknown integrator 'bdpt'"),
            ("model_unknown", ["calibrate", "--points", "p.json", "--size", "4", "4", "--model", "g"], "model"),
            ("at_two_numbers", ["calibrate", "--points", "p.json", "--size", "4", "4", "--at", "1", "2"], "at"),
            ("size_one_number", ["calibrate", "--points", "p.json", "--size", "10"], "size"),
            ("verb_unknown", ["paint", "scene.json"], "unknown verb .paint. \\(one of: render, calibrate"), ("output_extension", ["render", "scene.json", "-o", "x.bmp"], "x.bmp")]:
        case("cli_" + name, args, message, files={"p.json": json.dumps(good)})
    shots = dict(SHOTS, faced="-z")
    for name, env, message in [
            ("faced_up", dict(shots, faced="up"), "faced"), ("front_axis_up", {k: v for k, v in dict(shots, front="s2.png", right="s0.png", back="s3.png", left="s1.png", front_axis="+y").items() if k not in ("+x", "-x", "+z", "-z")}, "front_axis"),
            ("times_count", dict(shots, **{"+x": {"files": ["s0.png"], "times": [0.1, 0.2]}}), "times"),
            ("hfov_zero", dict(shots, hfov_deg=0), "hfov_deg"), ("exposure_word", {"shots": shots, "exposure": "manual"}, "exposure"),
            ("room_box_inverted", {"shots": shots, "room_box": {"min": [1, 1, 1], "max": [0, 0, 0], "capture": [0.5, 0.5, 0.5]}}, "max"),
            ("capture_outside", {"shots": shots, "room_box": {"min": [0, 0, 0], "max": [1, 1, 1], "capture": [2, 0.5, 0.5]}}, "capture"),
            ("opening_off_the_walls", {"shots": shots, "room_box": {"min": [0, 0, 0], "max": [1, 1, 1], "capture": [0.5, 0.5, 0.5],
                                                               "openings": [{"min": [0.5, 0.2, 0.2], "max": [0.5, 0.8, 0.8]}]}}, "lies on a wall"),
            ("opening_beyond_its_wall", {"shots": shots, "room_box": {"min": [0, 0, 0], "max": [1, 1, 1], "capture": [0.5, 0.5, 0.5],
                                                                  "openings": [{"min": [0, 0.2, 0.2], "max": [0, 1.8, 0.8]}]}}, "beyond"),
            ("opening_empty", {"shots": shots, "room_box": {"min": [0, 0, 0], "max": [1, 1, 1], "capture": [0.5, 0.5, 0.5],
                                                        "openings": [{"min": [0, 0.2, 0.2], "max": [0, 0.2, 0.8]}]}}, "along the wall"),
            ("image_and_shots", {"image": "env.exr", "shots": shots}, "not both"), ("exif_for_image", {"image": "env.exr", "exposure": "exif"}, "factor")]:
        e = env if ("shots" in env or "image" in env) else {"shots": env}
        case("environment_" + name, ["render", "scene.json"], message, files=six_shots(), scene=scene_with(environment=e))
    cam_ok = {"width": 48, "height": 32, "intrinsics": {"fx": 40, "fy": 40, "cx": 24, "cy": 16},
              "pose": {"R": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "t": [0, 0, 3]}}
    for name, cam, message in [("other_size", dict(cam_ok, width=640, height=480), "640x480"),
                               ("no_intrinsics", {k: v for k, v in cam_ok.items() if k != "intrinsics"}, "intrinsics"),
                               ("mirrored", dict(cam_ok, pose={"R": [[1, 0, 0], [0, 1, 0], [0, 0, -1]], "t": [0, 0, 3]}), "not a rotation")]:
        case("camera_file_" + name, ["render", "scene.json"], message, files={"cam.json": json.dumps(cam)},
             scene=scene_with(camera={"file": "cam.json"}))
    fspy_ok = {"principalPoint": {"x": 0.0, "y": 0.0}, "horizontalFieldOfView": 1.0, "imageWidth": 48, "imageHeight": 32,
               "cameraTransform": {"rows": [[1, 0, 0, 0.5], [0, 0, -1, -2.5], [0, 1, 0, 1.0], [0, 0, 0, 1]]}}
    for name, export, message in [
            ("other_aspect", dict(fspy_ok, imageWidth=640, imageHeight=640), r"room.json:\$\.imageWidth: .*not the same aspect ratio"),
            ("not_a_rotation", dict(fspy_ok, cameraTransform={"rows": [[2, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]]}),
             r"room.json:\$\.cameraTransform\.rows: not a rotation"),
            ("no_transform", {k: v for k, v in fspy_ok.items() if k != "cameraTransform"}, r"room.json:\$: .*cameraTransform"),
            ("fov_zero", dict(fspy_ok, horizontalFieldOfView=0), r"room.json:\$\.horizontalFieldOfView"),
            ("not_json", "fSpy project", r"room.json")]:
        case("fspy_" + name, ["render", "scene.json"], message, files={"room.json": export if isinstance(export, str) else json.dumps(export)},
             scene=scene_with(camera={"fspy": "room.json"}))
    case("export_blender_not_py", ["export-blender", "scene.json", "-o", "scene.txt"], r"-o scene.txt: .*\.py")
    env = open(os.path.join(HERE, "_base", "env.exr"), "rb").read()
    case("export_blender_world_is_the_environment", ["export-blender", "scene.json", "-o", "s.py"], r"s.world.exr.*is the environment",
         ["s.world.exr"], files={"s.world.exr": env}, scene=scene_with(environment="s.world.exr"))


def message_cases():
    """Issue 46's messages: a place named once, a key's meaning said, a range of plain numbers."""
    shots = {"shots": dict(SHOTS)}
    case("missing_faced_says_what_it_means", ["render", "scene.json"],
         r"scene\.json:\$\.environment\.shots: missing required key 'faced': the wall you faced when you shot the "
         r"ceiling and the floor", files=six_shots(), scene=scene_with(environment=shots))
    bad_shot = six_shots()
    bad_shot["s0.png"] = "not a png"
    case("shot_error_names_its_place_once", ["render", "scene.json"],
         r"^insitu: error: scene\.json:\$\.environment\.shots\.\+x: s0\.png: (?!.*scene\.json)", files=bad_shot,
         scene=scene_with(environment={"shots": dict(SHOTS, faced="-z")}))
    case("unknown_key_lists_each_name_once", ["render", "scene.json"],
         r"\$\.render\.irradiance_mod: unknown key \(expected one of: [^;]*irradiance[^;]*; or an integrator's object"
         r" of parameters: (?!.*irradiance.*irradiance)", scene=scene_with(render={"irradiance_mod": "sh9"}))
    case("batch_index_negative", ["batch", "b.json", "--index", "-1"], r"--index: Value -1 not in range 0 to [0-9]{1,10} ",
         files={"b.json": json.dumps({"scene": "scene.json", "entries": [{"objects": [{"mesh": "quad.obj"}],
                                                                          "output": "o.png"}]})})


if __name__ == "__main__":
    main()
