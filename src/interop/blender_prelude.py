# The Python half of `insitu export-blender` (src/interop/blender_export.h): the helper functions
# every exported script starts with, embedded in insitu at build time (cmake/embed_text.cmake).
# tools/validate/cycles_render.py imports it too, for the Cycles settings both renders share
# (cycles_common). Blender 3.4's API (Debian 12).
import array
import os
import sys

import bpy
from mathutils import Matrix

HERE = os.path.dirname(os.path.abspath(__file__)) if "__file__" in globals() else ""


def data_file(name, written):
    """A file written beside the script: found beside it (the pair moved together), else where it was written."""
    p = os.path.join(HERE, name)
    return p if HERE and os.path.exists(p) else written


def new_scene(name):
    scene = bpy.data.scenes.new(name)
    if bpy.context.window is not None:
        bpy.context.window.scene = scene
    return scene


def cycles_common(scene, samples, seed):
    """Cycles as insitu renders, in every render made to compare with insitu (the export's and the
    validation's): the CPU, a fixed number of samples, a 1-pixel box filter, no adaptive sampling,
    no denoising, no clamping, no glossy filter (Cycles roughens glossy lobes after a diffuse
    bounce by default, a bias insitu does not make), and the plain sRGB view."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    scene.cycles.seed = seed
    scene.cycles.sample_clamp_direct = 0.0
    scene.cycles.sample_clamp_indirect = 0.0
    scene.cycles.blur_glossy = 0.0
    scene.view_settings.view_transform = "Standard"


# insitu's cut-outs never end a path: a shadow ray is attenuated by every one it crosses, and a
# traced ray passes through them stochastically without counting a bounce (src/render/cutouts.h).
# Cycles ends a path after transparent_max_bounces of them (default 8); 1024 is its largest.
CUTOUT_CROSSINGS = 1024


def set_bounces(scene, bounces):
    """Every kind of bounce capped at `bounces`, as insitu's max_depth caps a path, and the cut-outs
    as insitu crosses them. Each setting by its own name: Cycles's settings take a name they lack
    as a new Python attribute without a word (a misspelt "transparent_bounces" once left the
    default 8 in place), so a name Cycles lacks fails here."""
    limits = {"max_bounces": bounces, "diffuse_bounces": bounces, "glossy_bounces": bounces,
              "transmission_bounces": bounces, "transparent_max_bounces": CUTOUT_CROSSINGS}
    for name, value in limits.items():
        if name not in scene.cycles.bl_rna.properties:
            raise AttributeError("Cycles has no setting " + name)
        setattr(scene.cycles, name, value)


def render_settings(scene, samples, max_bounces, seed):
    """The export's render: cycles_common, the scene's bounces, caustics, linear output shown through
    the plain sRGB curve, a transparent film for the shadow catchers."""
    cycles_common(scene, samples, seed)
    set_bounces(scene, max_bounces)
    scene.cycles.caustics_reflective = True
    scene.cycles.caustics_refractive = True
    scene.render.film_transparent = True
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0


def load_image(path, linear):
    img = bpy.data.images.load(path, check_existing=True)
    if linear:
        img.colorspace_settings.is_data = False
    return img


def set_world(scene, world_path):
    """The environment, looked up by direction: the layout of insitu's equirect.h is Blender's."""
    world = bpy.data.worlds.new("insitu environment")
    scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    env = nt.nodes.new("ShaderNodeTexEnvironment")
    env.image = load_image(world_path, True)
    bg = nt.nodes["Background"]
    bg.inputs["Strength"].default_value = 1.0
    nt.links.new(env.outputs["Color"], bg.inputs["Color"])


def new_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    return mat, nt, nt.nodes.new("ShaderNodeOutputMaterial")


def rgb_node(nt, blend, a, b):
    """A MixRGB node at factor 1: a (blend) b. a and b are sockets or RGB tuples."""
    n = nt.nodes.new("ShaderNodeMixRGB")
    n.blend_type = blend
    n.inputs["Fac"].default_value = 1.0
    for socket, value in ((n.inputs["Color1"], a), (n.inputs["Color2"], b)):
        if isinstance(value, tuple):
            socket.default_value = (*value, 1.0)
        else:
            nt.links.new(value, socket)
    return n.outputs["Color"]


def surface_material(name, kd, texture="", ks=(0.0, 0.0, 0.0), roughness=1.0, extras=None):
    """insitu's BSDF (src/render/bsdf.h): Lambertian rho_d = Kd x map_Kd; with Ks > 0 a GGX lobe
    of alpha = sqrt(2 / (Ns + 2)) (Blender's roughness is sqrt(alpha)) and Schlick's Fresnel
    F = Ks + (1 - Ks)(1 - cos)^5, the diffuse lobe weighted by 1 - F. Blender's nodes see the
    normal's cosine, not the half-vector's: the glossy weighting is an approximation. extras: the
    MTL's emission and normal map (surface_extras)."""
    mat, nt, out = new_material(name)
    diff = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diff.inputs["Roughness"].default_value = 0.0
    base = tuple(kd)
    if texture:
        base = rgb_node(nt, "MULTIPLY", tuple(kd), image_node(nt, texture, False).outputs["Color"])
    if max(ks) <= 0.0:
        set_input(nt, diff.inputs["Color"], base)
        surface_extras(nt, out, diff.outputs["BSDF"], [diff.inputs["Normal"]], extras)
        return mat
    facing = nt.nodes.new("ShaderNodeLayerWeight")  # Facing = 1 - |n.v| at blend 0.5
    facing.inputs["Blend"].default_value = 0.5
    power = nt.nodes.new("ShaderNodeMath")
    power.operation = "POWER"
    nt.links.new(facing.outputs["Facing"], power.inputs[0])
    power.inputs[1].default_value = 5.0
    fresnel = nt.nodes.new("ShaderNodeMixRGB")  # Ks + (1 - Ks) t
    nt.links.new(power.outputs["Value"], fresnel.inputs["Fac"])
    fresnel.inputs["Color1"].default_value = (*ks, 1.0)
    fresnel.inputs["Color2"].default_value = (1.0, 1.0, 1.0, 1.0)
    left = rgb_node(nt, "SUBTRACT", (1.0, 1.0, 1.0), fresnel.outputs["Color"])
    nt.links.new(rgb_node(nt, "MULTIPLY", base, left), diff.inputs["Color"])
    glossy = nt.nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "GGX"
    glossy.inputs["Roughness"].default_value = roughness
    nt.links.new(fresnel.outputs["Color"], glossy.inputs["Color"])
    add = nt.nodes.new("ShaderNodeAddShader")
    nt.links.new(diff.outputs["BSDF"], add.inputs[0])
    nt.links.new(glossy.outputs["BSDF"], add.inputs[1])
    normals = [diff.inputs["Normal"], glossy.inputs["Normal"], facing.inputs["Normal"]]
    surface_extras(nt, out, add.outputs["Shader"], normals, extras)
    return mat


def principled_material(name, p):
    """An MTL material of the PBR extension as insitu reads it (src/render/obj_materials.h): a
    Principled BSDF (GGX, as insitu's) whose inputs are p's values, each times its map where it
    has one (a grey map through Cycles's colour-to-float conversion, its luminance, as insitu's);
    and the emission and normal map of surface_extras."""
    mat, nt, out = new_material(name)
    bsdf = nt.nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.distribution = "GGX"
    set_input(nt, bsdf.inputs["Base Color"], mapped(nt, tuple(p["base"]), p.get("base_texture", ""), True))
    for key, socket in (("metallic", "Metallic"), ("roughness", "Roughness")):
        set_input(nt, bsdf.inputs[socket], mapped(nt, p[key], p.get(key + "_texture", ""), False))
    bsdf.inputs["Specular"].default_value = p["specular"]
    bsdf.inputs["Clearcoat"].default_value = p["clearcoat"]
    bsdf.inputs["Clearcoat Roughness"].default_value = p["clearcoat_roughness"]
    bsdf.inputs["Transmission"].default_value = p.get("transmission", 0.0)
    bsdf.inputs["IOR"].default_value = p.get("ior", 1.45)
    surface_extras(nt, out, bsdf.outputs["BSDF"], [bsdf.inputs["Normal"]], p)
    return mat


def surface_extras(nt, out, shader, normal_inputs, extras):
    """The shader to the output, with what an MTL adds to either model: a tangent-space normal map
    (extras["normal_texture"], data, of Normal Map strength extras["normal_strength"]) for the
    normal_inputs, an emission of colour extras["emission"] x extras["emission_texture"], and the
    opacity of opaque_by."""
    extras = extras or {}
    if extras.get("normal_texture"):
        nmap = nt.nodes.new("ShaderNodeNormalMap")
        nmap.space = "TANGENT"
        nmap.uv_map = "UVMap"
        nmap.inputs["Strength"].default_value = extras.get("normal_strength", 1.0)
        nt.links.new(data_image(nt, extras["normal_texture"]).outputs["Color"], nmap.inputs["Color"])
        for socket in normal_inputs:
            nt.links.new(nmap.outputs["Normal"], socket)
    emission = tuple(extras.get("emission", (0.0, 0.0, 0.0)))
    if max(emission) > 0.0:
        emit = nt.nodes.new("ShaderNodeEmission")
        emit.inputs["Strength"].default_value = 1.0
        set_input(nt, emit.inputs["Color"], mapped(nt, emission, extras.get("emission_texture", ""), True))
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(shader, add.inputs[0])
        nt.links.new(emit.outputs["Emission"], add.inputs[1])
        shader = add.outputs["Shader"]
    nt.links.new(opaque_by(nt, shader, extras), out.inputs["Surface"])


def opaque_by(nt, shader, extras):
    """The shader where the surface is there, a Transparent BSDF elsewhere, by the opacity
    extras["opacity"] (MTL's d) x the image extras["opacity_texture"] (map_d, data) through its
    extras["opacity_channel"] output: "Alpha", or "Color" (its grey, Cycles's colour-to-float
    conversion). This is how Cycles renders the Principled BSDF's Alpha."""
    opacity, texture = extras.get("opacity", 1.0), extras.get("opacity_texture", "")
    if opacity >= 1.0 and not texture:
        return shader
    mix = nt.nodes.new("ShaderNodeMixShader")
    if texture:
        times = nt.nodes.new("ShaderNodeMath")
        times.operation = "MULTIPLY"
        times.inputs[0].default_value = opacity
        nt.links.new(data_image(nt, texture).outputs[extras.get("opacity_channel", "Color")], times.inputs[1])
        nt.links.new(times.outputs["Value"], mix.inputs["Fac"])
    else:
        mix.inputs["Fac"].default_value = opacity
    nt.links.new(nt.nodes.new("ShaderNodeBsdfTransparent").outputs["BSDF"], mix.inputs[1])
    nt.links.new(shader, mix.inputs[2])
    return mix.outputs["Shader"]


def image_node(nt, texture, data):
    """An image texture node of texture: a path, or {"path", "scale", "offset"} placed by a Mapping
    node of that Scale and Location on the UVs (an MTL's -s and -o, as Blender's importer reads
    them). data: its stored values (roughness, metallic, a normal map), else a colour."""
    placed = isinstance(texture, dict)
    path = texture["path"] if placed else texture
    tex = nt.nodes.new("ShaderNodeTexImage")
    if data:
        tex.image = bpy.data.images.load(path, check_existing=False)
        tex.image.colorspace_settings.name = "Non-Color"
    else:
        tex.image = load_image(path, False)
    if placed:
        uv = nt.nodes.new("ShaderNodeTexCoord")
        mapping = nt.nodes.new("ShaderNodeMapping")
        mapping.vector_type = "POINT"
        mapping.inputs["Location"].default_value = (*texture["offset"], 0.0)
        mapping.inputs["Scale"].default_value = (*texture["scale"], 1.0)
        nt.links.new(uv.outputs["UV"], mapping.inputs["Vector"])
        nt.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    return tex


def data_image(nt, texture):
    """An image texture node of data: image_node's."""
    return image_node(nt, texture, True)


def mapped(nt, value, texture, colour):
    """value, times an image's colour (colour) or its value (a grey map) where texture names one."""
    if not texture:
        return value
    if colour:
        return rgb_node(nt, "MULTIPLY", value, image_node(nt, texture, False).outputs["Color"])
    times = nt.nodes.new("ShaderNodeMath")
    times.operation = "MULTIPLY"
    times.inputs[0].default_value = value
    nt.links.new(data_image(nt, texture).outputs["Color"], times.inputs[1])
    return times.outputs["Value"]


def set_input(nt, socket, value):
    """A node input from a number, an RGB tuple or another node's output."""
    if isinstance(value, tuple):
        socket.default_value = (*value, 1.0)
    elif isinstance(value, (int, float)):
        socket.default_value = value
    else:
        nt.links.new(value, socket)


def box_emission_material(world_path, capture):
    """The room box of insitu's room light (src/light/room_light.h): a point q of a wall emits
    what the capture point c saw in its direction, L(q) = env((q - c) / |q - c|)."""
    mat, nt, out = new_material("insitu room box")
    geometry = nt.nodes.new("ShaderNodeNewGeometry")
    sub = nt.nodes.new("ShaderNodeVectorMath")
    sub.operation = "SUBTRACT"
    nt.links.new(geometry.outputs["Position"], sub.inputs[0])
    sub.inputs[1].default_value = capture
    norm = nt.nodes.new("ShaderNodeVectorMath")
    norm.operation = "NORMALIZE"
    nt.links.new(sub.outputs["Vector"], norm.inputs[0])
    env = nt.nodes.new("ShaderNodeTexEnvironment")
    env.image = load_image(world_path, True)
    nt.links.new(norm.outputs["Vector"], env.inputs["Vector"])
    emit = nt.nodes.new("ShaderNodeEmission")
    emit.inputs["Strength"].default_value = 1.0
    nt.links.new(env.outputs["Color"], emit.inputs["Color"])
    nt.links.new(emit.outputs["Emission"], out.inputs["Surface"])
    return mat


def quads_object(scene, name, quads, mat):
    """Rectangles given by four corners (Blender's frame), one object."""
    verts = [v for q in quads for v in q]
    faces = [tuple(range(4 * i, 4 * i + 4)) for i in range(len(quads))]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.materials.append(mat)
    obj = bpy.data.objects.new(name, mesh)
    scene.collection.objects.link(obj)
    return obj


def room_box(scene, quads, world_path, capture):
    """The walls emit, and the openings are holes through which the world's distant light comes.
    The walls are shadow catchers too, as in insitu (src/integrators/path.cpp): they catch the objects'
    shadows, and Cycles counts their light as the room's, not as an occluder of the world (an
    ordinary object there would darken the whole floor)."""
    return catcher(quads_object(scene, "insitu room box", quads, box_emission_material(world_path, capture)))


def catcher(obj):
    """A local-scene surface: Cycles' shadow catcher (it receives the objects' shadows and light,
    and lights them back with its albedo), as insitu's differential rendering."""
    obj.is_shadow_catcher = True
    return obj


def load_mesh(scene, name, path, offset, nv, nt_, has_normals, has_uvs, materials):
    """A triangle mesh from the binary file: positions (float32 x 3 per vertex, Blender's frame),
    triangles (uint32 x 3), material index (int32 per triangle), then, when present, a normal
    (float32 x 3) and a UV (float32 x 2) per corner; all little-endian."""
    def read(f, code, n):
        a = array.array(code)
        a.frombytes(f.read(a.itemsize * n))
        if sys.byteorder == "big":
            a.byteswap()
        return a

    with open(path, "rb") as f:
        f.seek(offset)
        pos = read(f, "f", 3 * nv)
        tri = read(f, "i", 3 * nt_)  # uint32 in the file, below 2^31 in any mesh Blender holds
        mat = read(f, "i", nt_)
        nor = read(f, "f", 9 * nt_) if has_normals else None
        uv = read(f, "f", 6 * nt_) if has_uvs else None
    me = bpy.data.meshes.new(name)
    me.vertices.add(nv)
    me.vertices.foreach_set("co", pos)
    me.loops.add(3 * nt_)
    me.loops.foreach_set("vertex_index", tri)
    me.polygons.add(nt_)
    me.polygons.foreach_set("loop_start", array.array("i", range(0, 3 * nt_, 3)))
    me.polygons.foreach_set("loop_total", array.array("i", [3]) * nt_)
    me.polygons.foreach_set("material_index", mat)
    me.update(calc_edges=True)
    if uv is not None:
        me.uv_layers.new(name="UVMap").data.foreach_set("uv", uv)
    if nor is not None:
        me.polygons.foreach_set("use_smooth", [True] * nt_)
        me.use_auto_smooth = True
        me.normals_split_custom_set([nor[i:i + 3] for i in range(0, len(nor), 3)])
    for m in materials:
        me.materials.append(m)
    obj = bpy.data.objects.new(name, me)
    scene.collection.objects.link(obj)
    return obj


def gltf_object(scene, name, path, matrix):
    """A glTF asset imported by Blender's own importer (io_scene_gltf2: the materials as Blender
    reads the file), its objects under one empty placed by insitu's transform (matrix, in
    Blender's frame). Its Principled BSDFs scatter once, GGX, as insitu's (src/render/bsdf.h), and
    an alpha MASK cuts as glTF says (the importer sets it for Eevee only: Cycles would blend)."""
    import numpy
    if "bool" not in numpy.__dict__:  # Debian's Blender 3.4 importer still says np.bool, gone in NumPy 1.24
        numpy.bool = bool
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=path)
    imported = [o for o in bpy.data.objects if o not in before]
    root = bpy.data.objects.new(name, None)
    scene.collection.objects.link(root)
    root.matrix_world = Matrix(matrix)
    for o in imported:
        for c in list(o.users_collection):
            c.objects.unlink(o)
        scene.collection.objects.link(o)
        if o.parent is None:
            o.parent = root
    for mat in {s.material for o in imported for s in o.material_slots if s.material}:
        for node in mat.node_tree.nodes:
            if node.type == "BSDF_PRINCIPLED":
                node.distribution = "GGX"
                if mat.blend_method == "CLIP":
                    alpha_mask(mat.node_tree, node.inputs["Alpha"], mat.alpha_threshold)
    return root


def alpha_mask(tree, alpha, cutoff):
    """alpha <- 1 - (alpha < cutoff): opaque where alpha >= cutoff, absent elsewhere."""
    less = tree.nodes.new("ShaderNodeMath")
    less.operation = "LESS_THAN"
    less.inputs[1].default_value = cutoff
    if alpha.is_linked:
        tree.links.new(alpha.links[0].from_socket, less.inputs[0])
    else:
        less.inputs[0].default_value = alpha.default_value
    keep = tree.nodes.new("ShaderNodeMath")
    keep.operation = "SUBTRACT"
    keep.inputs[0].default_value = 1.0
    tree.links.new(less.outputs[0], keep.inputs[1])
    tree.links.new(keep.outputs[0], alpha)


def composite_over_photo(scene, photo_path, linear):
    """The render over the photo (Alpha Over of the premultiplied render): the objects, and the
    shadow catchers' darkening and light, on the user's photo."""
    scene.use_nodes = True
    nt = scene.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    layers = nt.nodes.new("CompositorNodeRLayers")
    layers.scene = scene
    photo = nt.nodes.new("CompositorNodeImage")
    photo.image = load_image(photo_path, linear)
    over = nt.nodes.new("CompositorNodeAlphaOver")
    nt.links.new(photo.outputs["Image"], over.inputs[1])
    nt.links.new(layers.outputs["Image"], over.inputs[2])
    out = nt.nodes.new("CompositorNodeComposite")
    nt.links.new(over.outputs["Image"], out.inputs["Image"])


def run_from_command_line(scene):
    """blender -b --python scene.py -- --render out.png [--samples N] [--seed S]: renders the composite."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    args = dict(zip(argv[0::2], argv[1::2]))
    if "--samples" in args:
        scene.cycles.samples = int(args["--samples"])
    if "--seed" in args:
        scene.cycles.seed = int(args["--seed"])
    if "--render" not in args:
        return
    path = os.path.abspath(args["--render"])
    ext = os.path.splitext(path)[1].lower()
    fmt = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG", ".exr": "OPEN_EXR", ".tif": "TIFF", ".tiff": "TIFF"}
    if ext not in fmt:
        raise SystemExit("insitu scene: --render needs .png, .jpg, .exr or .tif: " + path)
    scene.render.image_settings.file_format = fmt[ext]
    if ext == ".exr":
        scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True, scene=scene.name)
    print("insitu scene: wrote", path, flush=True)
