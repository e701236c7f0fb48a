"""Render a scene exported by `interiornet layout export` with Blender Cycles (CPU).

    blender -b --factory-startup -P bench/cycles_gltf.py -- \\
        --gltf apt.gltf [--camera camera.json] --spp 64 --out out/cycles \\
        [--threads 2] [--max-bounces 8] [--seed 0] [--formats exr,png] [--materials ours|gltf]
    blender -b --factory-startup -P bench/cycles_gltf.py -- --gltf apt.glb --summary out.json

The file is read with Blender's own glTF importer (io_scene_gltf2). With --materials ours
(default) every material that carries our parameters in its extras ("interiornet_type", see
docs/gltf.md) is rebuilt from Cycles nodes as close to our BSDFs as Cycles allows, reusing the
importer's texture nodes:
  lambertian     Diffuse BSDF (exact)
  plastic        Principled, metallic 0, specular from the IOR ((n-1)/(n+1))^2 / 0.08
  conductor      Principled, metallic 1, base colour = F0 of the metal (Schlick, not complex IOR)
  dielectric     Glass BSDF (GGX), IOR, colour = transmittance
  thin_dielectric  a pane: Transparent (colour = transmittance) mixed with a sharp Glossy by the
                 two-interface reflectance 2R / (1 + R) of the Fresnel node's R
  translucent    Diffuse (albedo) + Translucent (transmittance): exact
  emission       added on the front side only (our emitters are one-sided)
With --materials gltf the importer's Principled materials are rendered as they are.
Lights: the importer's point, spot and sun lights (683 lm/W, as we export): points, or bulbs of
the radius in their extras; spots given the blend that makes Cycles' cone edge our smoothstep
exactly, and the sun given its angular diameter, both from the light's extras. The sky: the
equirectangular EXR the export baked (scene extras "sky_image") as the world.
Camera: --camera (camera.json: width, height, fx, fy, cx, cy, cam_to_world or
position/look_at/up) or else the file's camera. Sampling: fixed spp, no adaptive sampling, no
denoising, no light threshold, no clamping, box filter 1 px, given bounces.

Writes <out>.exr (linear RGB, float) and/or <out>.png (sRGB, 'Standard'), and prints one line
"BENCH_JSON {...}" with import_s, render_s, save_s, script_s. --summary writes what the
importer made (objects, classes, instances, lights, bounds) as JSON and renders nothing.
"""
import argparse
import json
import math
import os
import struct
import sys
import time

import bpy
import numpy
from mathutils import Matrix, Vector

# Debian's Blender 3.4 glTF importer still says np.bool, which Debian 12's NumPy 1.24 removed
# (the importer then fails on every mesh with smooth normals); the alias meant the builtin.
if "bool" not in numpy.__dict__:
    numpy.bool = bool

T0 = time.perf_counter()


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="cycles_gltf.py")
    ap.add_argument("--gltf", required=True, help=".gltf or .glb written by layout export")
    ap.add_argument("--camera", help="camera.json; default: the file's camera")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--out", help="output path without extension")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--max-bounces", type=int, default=8)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--formats", default="exr,png")
    ap.add_argument("--materials", choices=["ours", "gltf"], default="ours")
    ap.add_argument("--summary", help="write an import summary (JSON) here and stop")
    a = ap.parse_args(argv)
    if not a.summary and not a.out:
        ap.error("--out is needed to render")
    return a


def gltf_json(path):
    """The JSON document of a .gltf or .glb."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        length, kind = struct.unpack_from("<II", data, 12)
        if kind != 0x4E4F534A:
            raise SystemExit(f"{path}: the first GLB chunk is not JSON")
        return json.loads(data[20:20 + length])
    return json.loads(data)


def socket_source(node, name):
    """The output socket linked into node.inputs[name], or None."""
    if node is None or name not in node.inputs or not node.inputs[name].is_linked:
        return None
    return node.inputs[name].links[0].from_socket


def rebuild_material(mat):
    kind = mat.get("interiornet_type")
    if kind is None or not mat.use_nodes:
        return False
    nt = mat.node_tree
    principled = next((n for n in nt.nodes if n.type == "BSDF_PRINCIPLED"), None)
    out = next((n for n in nt.nodes if n.type == "OUTPUT_MATERIAL"), None)
    base_src = socket_source(principled, "Base Color")
    rough_src = socket_source(principled, "Roughness")
    normal_src = socket_source(principled, "Normal")
    albedo = list(mat.get("albedo", (0.8, 0.8, 0.8)))
    rough = float(mat.get("roughness", 0.0))
    ior = float(mat.get("ior", 1.5))
    trans = list(mat.get("transmittance", (1.0, 1.0, 1.0)))
    emission = list(mat.get("emission", (0.0, 0.0, 0.0)))

    def new(type_name, **inputs):
        n = nt.nodes.new(type_name)
        for k, v in inputs.items():
            n.inputs[k].default_value = v
        return n

    def link_inputs(n, color=None, roughness=True):
        if color is not None and base_src is not None:
            nt.links.new(base_src, n.inputs[color])
        if roughness and rough_src is not None and "Roughness" in n.inputs:
            nt.links.new(rough_src, n.inputs["Roughness"])
        if normal_src is not None and "Normal" in n.inputs:
            nt.links.new(normal_src, n.inputs["Normal"])

    if kind == "lambertian":
        bsdf = new("ShaderNodeBsdfDiffuse", Color=albedo + [1.0], Roughness=0.0)
        link_inputs(bsdf, "Color", roughness=False)
        shader = bsdf.outputs[0]
    elif kind == "translucent":
        d = new("ShaderNodeBsdfDiffuse", Color=albedo + [1.0], Roughness=0.0)
        link_inputs(d, "Color", roughness=False)
        t = new("ShaderNodeBsdfTranslucent", Color=trans + [1.0])
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(d.outputs[0], add.inputs[0])
        nt.links.new(t.outputs[0], add.inputs[1])
        shader = add.outputs[0]
    elif kind == "dielectric":
        g = new("ShaderNodeBsdfGlass", Color=trans + [1.0], Roughness=rough, IOR=ior)  # Cycles: alpha = r^2, as ours
        g.distribution = "GGX"
        shader = g.outputs[0]
    elif kind == "thin_dielectric":
        fres = new("ShaderNodeFresnel", IOR=ior)
        # a pane's two interfaces reflect 2R / (1 + R) (incoherent sum of the bounces)
        num = nt.nodes.new("ShaderNodeMath")
        num.operation = "MULTIPLY"
        num.inputs[1].default_value = 2.0
        nt.links.new(fres.outputs[0], num.inputs[0])
        den = nt.nodes.new("ShaderNodeMath")
        den.operation = "ADD"
        den.inputs[1].default_value = 1.0
        nt.links.new(fres.outputs[0], den.inputs[0])
        ratio = nt.nodes.new("ShaderNodeMath")
        ratio.operation = "DIVIDE"
        nt.links.new(num.outputs[0], ratio.inputs[0])
        nt.links.new(den.outputs[0], ratio.inputs[1])
        refl = new("ShaderNodeBsdfGlossy", Color=(1, 1, 1, 1), Roughness=0.0)
        through = new("ShaderNodeBsdfTransparent", Color=trans + [1.0])
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(ratio.outputs[0], mix.inputs["Fac"])
        nt.links.new(through.outputs[0], mix.inputs[1])
        nt.links.new(refl.outputs[0], mix.inputs[2])
        shader = mix.outputs[0]
    elif kind in ("plastic", "conductor"):
        if principled is None:
            return False
        principled.inputs["Emission Strength"].default_value = 0.0
        principled.inputs["Specular"].default_value = ((ior - 1) / (ior + 1)) ** 2 / 0.08 \
            if kind == "plastic" else 0.5
        shader = principled.outputs[0]
    else:
        return False
    if max(emission) > 0:  # one-sided, along the geometric normal
        em = new("ShaderNodeEmission", Color=emission + [1.0], Strength=1.0)
        black = new("ShaderNodeEmission", Color=(0, 0, 0, 1), Strength=0.0)
        geo = nt.nodes.new("ShaderNodeNewGeometry")
        side = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(geo.outputs["Backfacing"], side.inputs["Fac"])
        nt.links.new(em.outputs[0], side.inputs[1])
        nt.links.new(black.outputs[0], side.inputs[2])
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(shader, add.inputs[0])
        nt.links.new(side.outputs[0], add.inputs[1])
        shader = add.outputs[0]
        if principled is not None:
            principled.inputs["Emission Strength"].default_value = 0.0
    nt.links.new(shader, out.inputs["Surface"])
    return True


def setup_world(scene, doc, gltf_dir):
    ex = doc.get("scenes", [{}])[doc.get("scene", 0)].get("extras", {}).get("interiornet", {})
    world = bpy.data.worlds.new("interiornet_sky")
    world.use_nodes = True
    bg = world.node_tree.nodes.get("Background")
    bg.inputs["Color"].default_value = (0, 0, 0, 1)
    bg.inputs["Strength"].default_value = 1.0
    image = ex.get("sky_image")
    if image:
        env = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
        env.image = bpy.data.images.load(os.path.join(gltf_dir, image))
        env.image.colorspace_settings.name = "Linear"
        env.interpolation = "Linear"
        world.node_tree.links.new(env.outputs["Color"], bg.inputs["Color"])
    scene.world = world
    return bool(image)


def setup_lights(scene):
    n = 0
    for ob in scene.objects:
        if ob.type != "LIGHT":
            continue
        n += 1
        ld = ob.data
        if ld.type in ("POINT", "SPOT"):
            # a bulb's radius: Cycles draws such a light as a disk of that radius facing the
            # shaded point, I / (d^2 + r^2), as we do (Light::radius); else a point
            ld.shadow_soft_size = float(ld.get("radius", 0.0))
        if ld.type == "SPOT" and "cone_deg" in ld:
            # Cycles: smoothstep over (1 - cos(half angle)) x blend in cosine; ours: smoothstep
            # from cos(cone) to cos(cone - falloff). This blend makes the two the same curve.
            outer = math.radians(float(ld["cone_deg"]))
            inner = math.radians(max(0.0, float(ld["cone_deg"]) - float(ld["falloff_deg"])))
            ld.spot_size = 2 * outer
            ld.spot_blend = (math.cos(inner) - math.cos(outer)) / (1 - math.cos(outer))
        if ld.type == "SUN":
            ld.angle = math.radians(float(ld.get("angular_diameter_deg", 0.53)))
    return n


def setup_camera(scene, path):
    with open(path) as f:
        spec = json.load(f)
    w, h = int(spec["width"]), int(spec["height"])
    fx = float(spec["fx"])
    fy = float(spec.get("fy", fx))
    if abs(fy - fx) > 1e-6 * fx:
        print("warning: fx != fy: Blender has square pixels; fx used", file=sys.stderr)
    cx, cy = float(spec.get("cx", w / 2.0)), float(spec.get("cy", h / 2.0))
    cd = bpy.data.cameras.new("frame_camera")
    cd.sensor_fit = "HORIZONTAL"
    cd.sensor_width = 36.0
    cd.lens = fx * 36.0 / w
    cd.shift_x = (w / 2.0 - cx) / max(w, h)
    cd.shift_y = (cy - h / 2.0) / max(w, h)
    cd.clip_start = 0.01
    cam = bpy.data.objects.new("frame_camera", cd)
    scene.collection.objects.link(cam)
    if "cam_to_world" in spec:
        m = Matrix([list(r) for r in spec["cam_to_world"]])
        rot, pos = m.to_3x3() @ Matrix(((1, 0, 0), (0, -1, 0), (0, 0, -1))), m.translation
    else:
        pos = Vector(spec["position"])
        fwd = (Vector(spec["look_at"]) - pos).normalized()
        right = fwd.cross(Vector(spec.get("up", (0, 0, 1)))).normalized()
        rot = Matrix((right, right.cross(fwd), -fwd)).transposed()
    mw = rot.to_4x4()
    mw.translation = pos
    cam.matrix_world = mw
    scene.camera = cam
    return w, h


def summary(scene, path):
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    classes, instances, objects = {}, set(), 0
    for ob in scene.objects:
        if ob.type != "MESH":
            continue
        objects += 1
        for c in ob.bound_box:
            p = ob.matrix_world @ Vector(c)
            for k in range(3):
                lo[k], hi[k] = min(lo[k], p[k]), max(hi[k], p[k])
        if "instance" in ob:
            instances.add(int(ob["instance"]))
            cls = int(ob.get("nyu40", 0))
            classes[cls] = classes.get(cls, 0) + 1
    out = {"objects": objects, "instances": len(instances),
           "parts_per_class": {str(k): v for k, v in sorted(classes.items())},
           "lights": sum(1 for ob in scene.objects if ob.type == "LIGHT"),
           "cameras": sum(1 for ob in scene.objects if ob.type == "CAMERA"),
           "materials": len(bpy.data.materials), "bounds_min": lo, "bounds_max": hi}
    with open(path, "w") as f:
        json.dump(out, f, indent=1)


def main():
    a = parse_args()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    t0 = time.perf_counter()
    path = os.path.abspath(a.gltf)
    bpy.ops.import_scene.gltf(filepath=path)
    if a.summary:
        summary(scene, a.summary)
        return
    doc = gltf_json(path)
    rebuilt = 0
    if a.materials == "ours":
        rebuilt = sum(1 for m in bpy.data.materials if rebuild_material(m))
    has_sky = setup_world(scene, doc, os.path.dirname(path))
    lights = setup_lights(scene)
    t_import = time.perf_counter() - t0
    if a.camera:
        w, h = setup_camera(scene, a.camera)
    else:
        cams = [ob for ob in scene.objects if ob.type == "CAMERA"]
        if not cams:
            raise SystemExit(f"{a.gltf}: no camera in the file; give --camera")
        scene.camera = cams[0]
        ex = cams[0].data.get("width"), cams[0].data.get("height")
        w, h = (int(ex[0]), int(ex[1])) if ex[0] else (640, 480)

    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = w, h, 100
    r.engine = "CYCLES"
    r.threads_mode = "FIXED"
    r.threads = a.threads
    r.film_transparent = False
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.light_sampling_threshold = 0.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = a.max_bounces
    c.transmission_bounces = c.transparent_max_bounces = a.max_bounces
    c.volume_bounces = 0
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.seed = a.seed
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.display_settings.display_device = "sRGB"

    t1 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    t_render = time.perf_counter() - t1

    t2 = time.perf_counter()
    img = bpy.data.images["Render Result"]
    os.makedirs(os.path.dirname(os.path.abspath(a.out)) or ".", exist_ok=True)
    for fmt in [f.strip() for f in a.formats.split(",") if f.strip()]:
        s = scene.render.image_settings
        if fmt == "exr":
            s.file_format, s.color_depth, s.exr_codec = "OPEN_EXR", "32", "ZIP"
            s.color_mode = "RGB"
        else:
            s.file_format, s.color_depth, s.color_mode = "PNG", "8", "RGB"
        img.save_render(filepath=f"{a.out}.{fmt}", scene=scene)
    t_save = time.perf_counter() - t2
    print("BENCH_JSON " + json.dumps({
        "import_s": t_import, "render_s": t_render, "save_s": t_save,
        "script_s": time.perf_counter() - T0, "spp": a.spp, "max_bounces": a.max_bounces,
        "threads": a.threads, "width": w, "height": h, "materials_rebuilt": rebuilt,
        "lights": lights, "sky": has_sky, "blender": bpy.app.version_string}))


main()
