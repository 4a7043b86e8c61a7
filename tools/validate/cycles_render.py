# Ground truth from an independent renderer (issue 12): builds a validation scene in Blender 3.4
# and renders it with Cycles — the empty photo, the photo with the objects (the truth), the
# objects' coverage, the truth again with another seed (its noise), and six 90° shots from the
# insertion point — then writes the insitu scene
# that reproduces it (the true camera, the shots as the environment, the floor as local scene).
#
#   blender -b --factory-startup --python tools/validate/cycles_render.py -- SCENE.json OUT_DIR
#   ... -- SCENE.json OUT_DIR --ladder 16,64,256,1024 --reference 4096
#   ... -- SCENE.json OUT_DIR --panorama 2048
# The third form renders only the empty room as an equirectangular panorama from the insertion
# point (OUT_DIR/pano.exr; tools/validate/panorama.sh makes the phone's JPEG of it).
# The second form (bench/cycles/run.sh, issue 16) renders only the truth, at each spp of the ladder
# with the scene's seed and at the reference spp with the next seed, as cycles_SPP.exr and
# cycles_reference.exr, and writes each render's wall-clock seconds (scene sync and BVH included,
# Blender's start-up not) to cycles_times.json.
#
# SCENE.json describes the scene in insitu's world frame (DESIGN.md: right-handed, +Y up, metres):
#   {"hdri": "...exr", "hdri_strength": 1, "ground": {"size": 40, "checker": [[r,g,b], [r,g,b]],
#    "checker_scale": 20}, "objects": [{"mesh": "...obj", "translate": [x,y,z], "rotate": deg,
#    "scale": s}], "camera": {"eye": [...], "look": [...], "hfov_deg": 50, "width": 320,
#    "height": 240}, "insertion": [x,y,z], "samples": {"photo": 1024, "shots": 256},
#    "shot_size": 128, "seed": 1}; "max_depth": n caps every kind of Cycles bounce at n and is the
# insitu scene's render.max_depth (without it, Cycles follows every kind of bounce up to
# FULL_BOUNCES and insitu takes its default 5).
# "handheld": {"hfov_deg": 110, "aspect": 0.75, "aim_sigma_deg": 2, "seed": 3} renders the shots as
# a hand aims them: shot_size wide and aspect × as tall, with hfov_deg across, each turned from its
# nominal direction by a rotation vector of normal components σ = aim_sigma_deg (roll included),
# written to OUT_DIR/aims.json; the insitu scene is told only the nominal directions.
# A closed room adds "room": {"min": [...], "max": [...], "albedo": [...], "window": {...},
# "lamp": {...}, "sun": {...}} (make_room below). "references": [{"sphere": {"center": [x,y,z],
# "radius": r}, "albedo": a, "stand": r_rod}] puts a grey ball of albedo a (on a rod of radius r_rod from the floor,
# if "stand" is given) into the real scene (the photo, the
# truth and the shots; not the objects' coverage), and into the insitu scene as inverse
# lighting's reference (issue 13). Paths in it are relative to the file. Every OBJ material is made a pure Lambertian (Diffuse BSDF,
# roughness 0) of the MTL's Kd or map_Kd, the reflectance model insitu's MTL reading gives a
# material without Ks; a glTF object (one file, data URIs) keeps the materials Blender's importer
# gives it, as insitu's export does (blender_prelude.gltf_object); the pixel filter is a 1-pixel box, insitu's.
import json
import math
import os
import shutil
import sys

import bpy
from mathutils import Matrix, Vector

# The Cycles settings shared with insitu's Blender export (src/interop/blender_prelude.py).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "src", "interop"))
from blender_prelude import cycles_common, gltf_object, set_bounces  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
desc_path, out_dir = os.path.abspath(argv[0]), os.path.abspath(argv[1])
desc = json.load(open(desc_path))
here = os.path.dirname(desc_path)
os.makedirs(os.path.join(out_dir, "shots"), exist_ok=True)


def rel(p):
    return p if os.path.isabs(p) else os.path.normpath(os.path.join(here, p))


def to_blender(v):
    """insitu (Y up) -> Blender (Z up): (x, y, z) -> (x, -z, y), a proper rotation."""
    return Vector((v[0], -v[2], v[1]))


# A photo of a real room holds light of every bounce. Blender's defaults stop diffuse light after 4
# bounces, which left a room of white walls (room_small_white) 22 % darker in its photo, and its
# objects 15 % darker in the truth, than 32 bounces do; beyond 32, ρ³² of a room whose surfaces
# reflect 0.8 is 0.08 %. (docs/validation.md, "Every bounce in the truth")
FULL_BOUNCES = 32


def setup_render(scene, samples, width, height, seed):
    cycles_common(scene, samples, seed)  # the settings insitu's Blender export uses too
    set_bounces(scene, desc.get("max_depth", FULL_BOUNCES))  # as insitu's max_depth caps a path
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "16"  # half floats: small files, 3 significant digits
    scene.render.image_settings.exr_codec = "ZIP"
    scene.render.threads_mode = "AUTO"


def make_world(scene):
    world = bpy.data.worlds.new("hdri")
    scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    env = nt.nodes.new("ShaderNodeTexEnvironment")
    env.image = bpy.data.images.load(rel(desc["hdri"]))
    bg = nt.nodes["Background"]
    bg.inputs["Strength"].default_value = desc.get("hdri_strength", 1.0)
    nt.links.new(env.outputs["Color"], bg.inputs["Color"])


def diffuse_material(name, colour_socket_source=None, colour=(0.8, 0.8, 0.8)):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    diff = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diff.inputs["Roughness"].default_value = 0.0
    diff.inputs["Color"].default_value = (*colour, 1.0)
    nt.links.new(diff.outputs["BSDF"], out.inputs["Surface"])
    return mat, nt, diff


def make_ground():
    g = desc["ground"]
    bpy.ops.mesh.primitive_plane_add(size=g.get("size", 40.0), location=(0, 0, 0))
    plane = bpy.context.active_object
    mat, nt, diff = diffuse_material("ground")
    checker = nt.nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = g.get("checker_scale", 20.0)
    a, b = g.get("checker", [[0.2, 0.2, 0.2], [0.6, 0.6, 0.6]])
    checker.inputs["Color1"].default_value = (*a, 1.0)
    checker.inputs["Color2"].default_value = (*b, 1.0)
    nt.links.new(checker.outputs["Color"], diff.inputs["Color"])
    plane.data.materials.append(mat)
    return plane


def quad(name, corners, mat):
    """A one-sided rectangle from four corners in insitu's frame, counter-clockwise seen from the
    side it faces."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([to_blender(c) for c in corners], [], [(0, 1, 2, 3)])
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    obj.data.materials.append(mat)
    return obj


def wall_rects(lo, hi, hole):
    """The rectangle [lo, hi]² minus an optional hole [hole_lo, hole_hi]², as up to four rectangles."""
    if not hole:
        return [(lo, hi)]
    (u0, v0), (u1, v1) = lo, hi
    (a0, b0), (a1, b1) = hole
    return [((u0, v0), (a0, v1)), ((a1, v0), (u1, v1)), ((a0, v0), (a1, b0)), ((a0, b1), (a1, v1))]


# The four walls: (name, axis across which the wall lies, which end of the box, the in-wall axis u).
WALLS = {"-x": (0, 0, 2), "+x": (0, 1, 2), "-z": (2, 0, 0), "+z": (2, 1, 0)}


def window_of(r):
    """The room's window as (wall, (u0, u1), (y0, y1)): "window": {"wall": "-z", "u": [u0, u1],
    "y": [y0, y1]}, u along the wall (z on an x wall, x on a z wall); without "wall", the -x wall
    and "z" for u."""
    win = r.get("window")
    if not win:
        return None
    return win.get("wall", "-x"), tuple(win.get("u", win.get("z"))), tuple(win["y"])


def make_room():
    """A closed box room (walls, ceiling; the ground is the floor), facing inward, with an optional
    window (a hole in one wall: window_of) and ceiling lamp (an emitting square:
    "lamp": {"centre": [x, z], "size": s, "radiance": [r, g, b]}). Returns its walls, ceiling and
    lamp: the real room, which the objects' coverage does not show."""
    r = desc["room"]
    real = []
    lo, hi = r["min"], r["max"]
    y1 = hi[1]
    albedo = r.get("albedo", [0.6, 0.58, 0.55])
    mat, _, _ = diffuse_material("walls", colour=tuple(albedo))
    win = window_of(r)
    for name, (axis, end, u_axis) in WALLS.items():
        plane = (lo, hi)[end][axis]
        hole = ((win[1][0], win[2][0]), (win[1][1], win[2][1])) if win and win[0] == name else None
        for k, ((ua, ya), (ub, yb)) in enumerate(wall_rects((lo[u_axis], lo[1]), (hi[u_axis], hi[1]), hole)):
            def at(u, y):
                p = [0.0, y, 0.0]
                p[axis], p[u_axis] = plane, u
                return tuple(p)
            corners = [at(ua, ya), at(ub, ya), at(ub, yb), at(ua, yb)]
            c0, c1, c3 = (Vector(c) for c in (corners[0], corners[1], corners[3]))
            centre = 0.5 * (Vector(lo) + Vector(hi))
            if (c1 - c0).cross(c3 - c0).dot(centre - c0) < 0:  # face inward
                corners.reverse()
            real.append(quad(f"wall_{name}_{k}", corners, mat))
    (x0, _, z0), (x1, _, z1) = lo, hi
    real.append(quad("ceiling", [(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)], mat))
    lamp = r.get("lamp")
    if lamp:
        emit = bpy.data.materials.new("lamp")
        emit.use_nodes = True
        nt = emit.node_tree
        nt.nodes.remove(nt.nodes["Principled BSDF"])
        e = nt.nodes.new("ShaderNodeEmission")
        e.inputs["Color"].default_value = (*lamp["radiance"], 1.0)
        e.inputs["Strength"].default_value = 1.0
        nt.links.new(e.outputs["Emission"], nt.nodes["Material Output"].inputs["Surface"])
        (cx, cz), h = lamp["centre"], 0.5 * lamp["size"]
        y = y1 - 1e-3  # just below the ceiling, facing down
        real.append(quad("lamp", [(cx - h, y, cz - h), (cx - h, y, cz + h), (cx + h, y, cz + h), (cx + h, y, cz - h)],
                         emit))
    sun = r.get("sun")
    if sun:
        # A distant sun: direction (toward the sun, insitu frame), strength in W/m², angle in degrees.
        data = bpy.data.lights.new("sun", "SUN")
        data.energy = sun["strength"]
        data.angle = math.radians(sun.get("angle_deg", 0.5))
        light = bpy.data.objects.new("sun", data)
        bpy.context.scene.collection.objects.link(light)
        d = to_blender(sun["direction"]).normalized()
        light.rotation_euler = (-d).to_track_quat("-Z", "Y").to_euler()
        real.append(sun_disc(d, sun["strength"], data.angle))
    return real


def sun_disc(d, irradiance, angle_rad):
    """What a camera sees of the sun: a Cycles sun lamp lights the scene but is invisible to camera
    rays, so shots from inside would miss it. A distant emitting disc of the sun's angular diameter,
    visible to camera rays only, of radiance L = E / Ω (Ω = π tan²(angle/2), the disc's solid angle
    seen from the room), puts the sun into the shots with the irradiance E the lamp gives; the
    lamp still does the lighting (the disc is invisible to every other ray)."""
    distance = 1.0e3  # inside the cameras' clip range (make_camera: 10 km)
    radius = distance * math.tan(0.5 * angle_rad)
    bpy.ops.mesh.primitive_circle_add(vertices=32, radius=radius, fill_type="NGON", location=d * distance)
    disc = bpy.context.active_object
    disc.rotation_euler = d.to_track_quat("Z", "Y").to_euler()
    omega = math.pi * math.tan(0.5 * angle_rad) ** 2
    emit = bpy.data.materials.new("sun_disc")
    emit.use_nodes = True
    nt = emit.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    e = nt.nodes.new("ShaderNodeEmission")
    e.inputs["Strength"].default_value = irradiance / omega
    nt.links.new(e.outputs["Emission"], nt.nodes["Material Output"].inputs["Surface"])
    disc.data.materials.append(emit)
    for ray in ("visible_diffuse", "visible_glossy", "visible_transmission", "visible_volume_scatter", "visible_shadow"):
        setattr(disc, ray, False)
    return disc


def lambertian_copy(mat):
    """The imported material as a pure Diffuse BSDF of its base colour (value or texture)."""
    principled = next((n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    base = principled.inputs["Base Color"] if principled else None
    colour = tuple(base.default_value[:3]) if base else (0.8, 0.8, 0.8)
    new, nt, diff = diffuse_material(mat.name + "_lambert", colour=colour)
    if base and base.is_linked:
        src = base.links[0].from_node
        if src.type == "TEX_IMAGE":
            tex = nt.nodes.new("ShaderNodeTexImage")
            tex.image = src.image
            tex.interpolation = "Closest"
            nt.links.new(tex.outputs["Color"], diff.inputs["Color"])
    return new


def placement(o):
    """insitu's translate · rotate about +Y · scale, in Blender's frame (insitu's +Y is its +Z)."""
    s = o.get("scale", 1.0)
    sx, sy, sz = s if isinstance(s, list) else (s, s, s)
    S = Matrix.Diagonal((sx, sz, sy, 1.0))
    R = Matrix.Rotation(math.radians(o.get("rotate", 0.0)), 4, "Z")
    return Matrix.Translation(to_blender(o.get("translate", [0, 0, 0]))) @ R @ S


def make_objects():
    objects = []
    for o in desc["objects"]:
        if o["mesh"].lower().endswith((".gltf", ".glb")):
            # Blender's own importer, its materials kept, as insitu's export does.
            root = gltf_object(bpy.context.scene, o["mesh"], rel(o["mesh"]), placement(o))
            objects += list(root.children_recursive)
            continue
        before = set(bpy.data.objects)
        bpy.ops.wm.obj_import(filepath=rel(o["mesh"]), forward_axis="NEGATIVE_Z", up_axis="Y")
        for obj in set(bpy.data.objects) - before:
            # After the importer's Y-up -> Z-up turn (kept in the object's matrix).
            obj.matrix_world = placement(o) @ obj.matrix_world.copy()
            for slot in obj.material_slots:
                if slot.material:
                    slot.material = lambertian_copy(slot.material)
            objects.append(obj)
    return objects


def make_references():
    """The real grey balls of "references": smooth UV spheres of a grey Lambertian."""
    balls = []
    for i, r in enumerate(desc.get("references", [])):
        sph = r["sphere"]
        bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, radius=sph["radius"],
                                             location=to_blender(sph["center"]))
        ball = bpy.context.active_object
        bpy.ops.object.shade_smooth()
        a = r["albedo"]
        mat, _, _ = diffuse_material("reference%d" % i, colour=(a, a, a))
        ball.data.materials.append(mat)
        balls.append(ball)
        if r.get("stand"):  # a rod of this radius from the floor to the ball, of the ball's grey
            height = sph["center"][1] - sph["radius"]
            foot = [sph["center"][0], height / 2, sph["center"][2]]
            bpy.ops.mesh.primitive_cylinder_add(vertices=32, radius=r["stand"], depth=height,
                                                location=to_blender(foot))  # along Blender Z, up
            bpy.context.active_object.data.materials.append(mat)
            balls.append(bpy.context.active_object)
    return balls


def make_camera(name, eye, forward, up, angle_deg, sensor_fit="HORIZONTAL"):
    data = bpy.data.cameras.new(name)
    data.sensor_fit = sensor_fit
    data.angle = math.radians(angle_deg)
    data.clip_start, data.clip_end = 0.001, 10000.0
    cam = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(cam)
    f, u = to_blender(forward).normalized(), to_blender(up)
    right = f.cross(u).normalized()
    u = right.cross(f).normalized()
    # A Blender camera looks along its local −Z with +Y up and +X right.
    rot = Matrix((right, u, -f)).transposed()
    cam.matrix_world = Matrix.Translation(to_blender(eye)) @ rot.to_4x4()
    return cam


def render_to(path):
    bpy.context.scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    print("validate: wrote", path, flush=True)


# The six shots insitu reads: walls by the world direction they face (image up = +Y), the ceiling
# and the floor with the faced wall −Z (the ceiling shot's bottom edge and the floor shot's top
# edge point toward it).
SHOTS = {
    "+x": ((1, 0, 0), (0, 1, 0)), "-x": ((-1, 0, 0), (0, 1, 0)),
    "+z": ((0, 0, 1), (0, 1, 0)), "-z": ((0, 0, -1), (0, 1, 0)),
    "up": ((0, 1, 0), (0, 0, 1)), "down": ((0, -1, 0), (0, 0, -1)),
}


def build_scene():
    """The scene with its objects and the photo's camera: (scene, camera, real, objects), real the
    ground and the reference balls (the real scene's objects, hidden for the coverage)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_world(scene)
    ground = make_ground() if desc.get("ground") else None
    room = make_room() if desc.get("room") else []
    balls = make_references()
    objects = make_objects()
    c = desc["camera"]
    eye, look = Vector(c["eye"]), Vector(c["look"])
    camera = make_camera("photo", c["eye"], list(look - eye), [0, 1, 0], c["hfov_deg"])
    scene.camera = camera
    return scene, camera, [g for g in [ground] + balls if g] + room, objects


def option(name):
    return argv[argv.index(name) + 1] if name in argv else None


def ladder(spps, reference):
    """The truth at each spp (the scene's seed) and at the reference spp (the next seed), timed."""
    import time
    scene, _, _, _ = build_scene()
    c, seed = desc["camera"], desc.get("seed", 1)
    times = {}
    for name, spp, s in [(str(n), n, seed) for n in spps] + [("reference", reference, seed + 1)]:
        setup_render(scene, spp, c["width"], c["height"], s)
        start = time.perf_counter()
        render_to(os.path.join(out_dir, "cycles_" + name + ".exr"))
        times[name] = {"spp": spp, "seconds": time.perf_counter() - start}
    with open(os.path.join(out_dir, "cycles_times.json"), "w") as f:
        json.dump({"threads": scene.render.threads, "renders": times}, f, indent=2)


def render_coverage(scene, real):
    """The objects' coverage: only they are seen, over a transparent film (the ground, the room's
    walls and ceiling, the reference balls hidden)."""
    c = desc["camera"]
    for obj in real:
        obj.visible_camera = False
    scene.render.film_transparent = True
    setup_render(scene, 16, c["width"], c["height"], desc.get("seed", 1))
    render_to(os.path.join(out_dir, "coverage.exr"))
    for obj in real:
        obj.visible_camera = True
    scene.render.film_transparent = False


def main():
    scene, camera, real, objects = build_scene()
    c = desc["camera"]
    samples, seed = desc.get("samples", {}), desc.get("seed", 1)

    # The truth: the photo with the objects.
    scene.camera = camera
    setup_render(scene, samples.get("photo", 1024), c["width"], c["height"], seed)
    render_to(os.path.join(out_dir, "truth.exr"))
    # The truth again with another seed: its own noise, for the error's tolerance.
    setup_render(scene, samples.get("photo", 1024), c["width"], c["height"], seed + 1)
    render_to(os.path.join(out_dir, "truth2.exr"))
    render_coverage(scene, real)
    # The empty room: the photo, and the six shots from the insertion point.
    for obj in objects:
        obj.hide_render = True
    setup_render(scene, samples.get("photo", 1024), c["width"], c["height"], seed)
    render_to(os.path.join(out_dir, "photo.exr"))
    n = desc.get("shot_size", 128)
    hand = desc.get("handheld")
    setup_render(scene, samples.get("shots", 256), n, round(n * hand["aspect"]) if hand else n, seed)
    shots = {}
    for face, (forward, up) in shot_aims(hand).items():
        scene.camera = make_camera("shot" + face, desc["insertion"], forward, up, hand["hfov_deg"] if hand else 90.0,
                                   "HORIZONTAL" if hand else "AUTO")
        name = "shot_" + face.replace("+", "p").replace("-", "n") + ".exr"
        render_to(os.path.join(out_dir, "shots", name))
        shots[face] = "shots/" + name
    shots["faced"] = "-z"
    if hand:
        shots["hfov_deg"] = hand["hfov_deg"]
    write_insitu_scene(shots)


def shot_aims(hand):
    """Each shot's (forward, up): nominal (SHOTS), or turned as a hand aims it (see "handheld")."""
    if not hand:
        return SHOTS
    import random
    rng = random.Random(hand.get("seed", 1))
    aims, truth = {}, {}
    for face, (forward, up) in SHOTS.items():
        v = Vector([math.radians(rng.gauss(0, hand["aim_sigma_deg"])) for _ in range(3)])
        R = Matrix.Rotation(v.length, 3, v.normalized()) if v.length > 0 else Matrix.Identity(3)
        aims[face] = (list(R @ Vector(forward)), list(R @ Vector(up)))
        truth[face] = [math.degrees(x) for x in v]
    json.dump({"rotation_vector_deg": truth}, open(os.path.join(out_dir, "aims.json"), "w"), indent=1)
    return aims


def copy_mesh(path):
    """The OBJ and the MTL files it names (a glTF: one file, its buffers as data URIs; a .glb: one
    file), copied into OUT_DIR/meshes: the output stands alone."""
    dest = os.path.join(out_dir, "meshes")
    os.makedirs(dest, exist_ok=True)
    shutil.copy(path, dest)
    if path.lower().endswith(".obj"):
        for line in open(path):
            if line.startswith("mtllib "):
                shutil.copy(os.path.join(os.path.dirname(path), line.split(None, 1)[1].strip()), dest)
    return "meshes/" + os.path.basename(path)


def room_box():
    """The room box insitu reads, with the shots' capture point, for a closed room."""
    r = desc.get("room")
    if not r:
        return {}
    box = {"min": r["min"], "max": r["max"], "capture": desc["insertion"]}
    win = window_of(r)
    if win:  # the hole, as an opening (DESIGN.md: one coordinate on the wall's plane)
        axis, end, u_axis = WALLS[win[0]]
        a, b = [0.0] * 3, [0.0] * 3
        a[axis] = b[axis] = (r["min"], r["max"])[end][axis]
        a[u_axis], b[u_axis] = win[1]
        a[1], b[1] = win[2]
        box["openings"] = [{"min": a, "max": b}]
    return {"room_box": box}


def write_insitu_scene(shots):
    c = desc["camera"]
    objects = []
    for o in desc["objects"]:
        item = {"mesh": copy_mesh(rel(o["mesh"])), "translate": o.get("translate", [0, 0, 0]),
                "rotate": o.get("rotate", 0.0)}
        if "scale" in o:
            item["scale"] = o["scale"]
        objects.append(item)
    scene = {
        "photo": "photo.exr",
        "camera": {"eye": c["eye"], "look": c["look"], "hfov_deg": c["hfov_deg"]},
        # The shots are in the photo's unit (one renderer, one exposure): factor 1.
        "environment": dict({"shots": shots, "exposure": 1.0}, **room_box()),
        "local_scene": [{"plane": {"point": [0, 0, 0], "normal": [0, 1, 0]}}] if desc.get("ground") else [],
        "objects": objects,
        "render": dict({"integrator": "path", "spp": 64}, **({"max_depth": desc["max_depth"]} if "max_depth" in desc else {})),
        "output": {"image": "insitu.exr", "layers": "insitu.layers.exr"},
    }
    if desc.get("references"):  # the stand is the real scene's, not insitu's to know
        scene["references"] = [{k: v for k, v in r.items() if k != "stand"} for r in desc["references"]]
    with open(os.path.join(out_dir, "scene.json"), "w") as f:
        json.dump(scene, f, indent=2)
    print("validate: wrote", os.path.join(out_dir, "scene.json"), flush=True)


def panorama(width):
    """The empty room from the insertion point as one equirectangular panorama, width × width/2,
    as a 360° camera takes it: OUT_DIR/pano.exr. Its centre column looks along +X and its top
    row straight up (light/equirect.h's layout: Cycles' panorama camera centres its image on the
    camera's view and keeps its up)."""
    scene, _, _, objects = build_scene()
    for obj in objects:
        obj.hide_render = True
    cam = make_camera("pano", desc["insertion"], [1, 0, 0], [0, 1, 0], 90.0)
    cam.data.type = "PANO"
    if hasattr(cam.data, "panorama_type"):
        cam.data.panorama_type = "EQUIRECTANGULAR"
    else:
        cam.data.cycles.panorama_type = "EQUIRECTANGULAR"
    scene.camera = cam
    setup_render(scene, desc.get("samples", {}).get("shots", 256), width, width // 2, desc.get("seed", 1))
    render_to(os.path.join(out_dir, "pano.exr"))


if option("--panorama"):
    panorama(int(option("--panorama")))
elif "--coverage" in argv:
    scene, camera, real, _ = build_scene()
    scene.camera = camera
    render_coverage(scene, real)
elif option("--ladder"):
    ladder([int(v) for v in option("--ladder").split(",")], int(option("--reference") or 4096))
else:
    main()
