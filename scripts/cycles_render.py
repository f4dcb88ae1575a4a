# Renders a glTF scene with Blender's Cycles as ripple-render would show it, for scripts/equal-time.sh:
#
#   blender -b --factory-startup --python scripts/cycles_render.py -- SCENE.glb OUT.exr|OUT.pfm \
#       --size 256x256 --max-path-length 5 (--spp N | --time S) --seed K
#
# Matched to ripple-render: the glTF's first camera, or one framing the scene's bounds the way ripple-render
# does (40 degrees vertical, from the front and a little above); for a scene without lights or uniformly
# emissive materials, ripple-render's studio light (a sun of irradiance 2 and angular diameter 0.00925 rad
# from (0.4, -1, -0.6) and an ambient fill of radiance 0.4, the background 0.35/0.35/0.38 seen by camera
# rays); path length = surface interactions (Cycles' bounces + 1); a 1-pixel box filter; no denoising, no
# adaptive sampling, no clamping, no glossy filter (all of these trade bias for noise, and Ripple has none
# of them on).
# Writes linear float RGB as OpenEXR (no view transform applies to EXR data), or as PFM when OUT ends in .pfm.
import argparse
import math
import sys

import bpy
import numpy
from mathutils import Vector

# Debian 12's Blender 3.4 meets Debian's NumPy 1.24, which dropped the `numpy.bool` alias that Blender's glTF
# importer still uses; the alias meant the builtin.
if "bool" not in numpy.__dict__:
    numpy.bool = bool


def parse():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_render.py")
    p.add_argument("scene")
    p.add_argument("output")
    p.add_argument("--size", default="256x256")
    p.add_argument("--max-path-length", type=int, default=5)
    p.add_argument("--spp", type=int, default=0)
    p.add_argument("--time", type=float, default=0.0)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--threads", type=int, default=0)
    return p.parse_args(argv)


def gltf_to_blender(v):
    # glTF is +Y up, Blender +Z up: the importer maps (x, y, z) to (x, -z, y).
    return Vector((v[0], -v[2], v[1]))


def main():
    args = parse()
    width, height = (int(n) for n in args.size.lower().split("x"))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=args.scene)
    scene = bpy.context.scene

    meshes = [o for o in scene.objects if o.type == "MESH"]
    if not meshes:
        raise SystemExit(f"{args.scene}: no meshes")
    # A glTF primitive without a material has glTF's default one (white, metallic 1, roughness 1), as in
    # ripple-render; Blender would draw it with its own grey diffuse default.
    default_material = None
    for o in meshes:
        if o.data.materials and all(m is not None for m in o.data.materials):
            continue
        if default_material is None:
            default_material = bpy.data.materials.new("gltf_default")
            default_material.use_nodes = True
            bsdf = default_material.node_tree.nodes["Principled BSDF"]
            bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
            bsdf.inputs["Metallic"].default_value = 1.0
            bsdf.inputs["Roughness"].default_value = 1.0
        if not o.data.materials:
            o.data.materials.append(default_material)
        for i, m in enumerate(o.data.materials):
            if m is None:
                o.data.materials[i] = default_material

    # Ripple's GGX lobes are compensated for multiple scattering between microfacets (a white rough metal
    # keeps all the light it receives; the white furnace test checks it at roughness 1), Blender's Principled
    # BSDF by default is not (its "GGX" loses up to about 40% at roughness 1): use its "Multiscatter GGX", so
    # that rough metals are the same image in both.
    for m in bpy.data.materials:
        if m.use_nodes:
            for node in m.node_tree.nodes:
                if node.type == "BSDF_PRINCIPLED":
                    node.distribution = "MULTI_GGX"

    # Camera: the file's first, else ripple-render's framing of the bounds (in glTF coordinates).
    cameras = [o for o in scene.objects if o.type == "CAMERA"]
    if cameras:
        scene.camera = sorted(cameras, key=lambda o: o.name)[0]
        scene.camera.data.sensor_fit = "VERTICAL"
        # ripple-render does not pass the glTF's znear/zfar on: no clipping here either.
        scene.camera.data.clip_start = 1e-4
        scene.camera.data.clip_end = 1e6
    else:
        lo = [math.inf] * 3
        hi = [-math.inf] * 3
        for o in meshes:
            for corner in o.bound_box:
                w = o.matrix_world @ Vector(corner)
                g = (w.x, w.z, -w.y)  # back to glTF axes
                lo = [min(a, b) for a, b in zip(lo, g)]
                hi = [max(a, b) for a, b in zip(hi, g)]
        center = [(a + b) / 2 for a, b in zip(lo, hi)]
        radius = max(0.5 * math.dist(lo, hi), 1e-6)
        fovy = math.radians(40.0)
        half_y = fovy / 2
        half_x = math.atan(math.tan(half_y) * width / height)
        distance = 1.05 * radius / math.sin(min(half_x, half_y))
        n = math.sqrt(0.35 ** 2 + 1.0)
        frm = (0.0, 0.35 / n, 1.0 / n)
        position = [c + distance * f for c, f in zip(center, frm)]
        cam_data = bpy.data.cameras.new("framed")
        cam_data.sensor_fit = "VERTICAL"
        cam_data.angle_y = fovy
        # Blender clips at 0.1 by default, more than the whole of a small model's view (metal-rough-spheres
        # is 7 mm across): clip planes scaled to the framing distance, as ripple-render has none.
        cam_data.clip_start = distance * 1e-4
        cam_data.clip_end = distance * 1e4
        cam = bpy.data.objects.new("framed", cam_data)
        scene.collection.objects.link(cam)
        cam.location = gltf_to_blender(position)
        direction = gltf_to_blender([-f for f in frm])
        cam.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
        scene.camera = cam

    # ripple-render's studio light for scenes with neither lights nor uniformly emissive materials.
    has_lights = any(o.type == "LIGHT" for o in scene.objects)
    emits = False
    for m in bpy.data.materials:
        if not m.use_nodes:
            continue
        for node in m.node_tree.nodes:
            if node.type == "BSDF_PRINCIPLED":
                strength = node.inputs["Emission Strength"].default_value
                color = node.inputs["Emission"]
                if strength > 0 and not color.is_linked and any(c > 0 for c in color.default_value[:3]):
                    emits = True
    world = bpy.data.worlds.new("world")
    scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputWorld")
    if not has_lights and not emits:
        sun_data = bpy.data.lights.new("key", type="SUN")
        sun_data.energy = 2.0  # irradiance, W/m^2, as the ANARI directional light's
        sun_data.angle = 0.00925  # the sun's 0.53 degrees, as ripple-render's (apps/scene/AnariScene.h)
        sun = bpy.data.objects.new("key", sun_data)
        scene.collection.objects.link(sun)
        d = Vector((0.4, -1.0, -0.6)).normalized()
        sun.rotation_euler = gltf_to_blender(d).to_track_quat("-Z", "Y").to_euler()
        fill = nodes.new("ShaderNodeBackground")
        fill.inputs["Color"].default_value = (0.4, 0.4, 0.4, 1.0)
        seen = nodes.new("ShaderNodeBackground")
        seen.inputs["Color"].default_value = (0.35, 0.35, 0.38, 1.0)
        path = nodes.new("ShaderNodeLightPath")
        mix = nodes.new("ShaderNodeMixShader")
        links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
        links.new(fill.outputs["Background"], mix.inputs[1])
        links.new(seen.outputs["Background"], mix.inputs[2])
        links.new(mix.outputs["Shader"], out.inputs["Surface"])
    else:
        black = nodes.new("ShaderNodeBackground")
        black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        links.new(black.outputs["Background"], out.inputs["Surface"])

    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.blur_glossy = 0.0  # "Filter Glossy" (default 1) blurs glossy paths: a bias that hides fireflies
    bounces = max(args.max_path_length - 1, 0)
    cycles.max_bounces = bounces
    cycles.diffuse_bounces = bounces
    cycles.glossy_bounces = bounces
    cycles.transmission_bounces = bounces
    cycles.transparent_max_bounces = 64
    cycles.caustics_reflective = True
    cycles.caustics_refractive = True
    cycles.seed = args.seed
    if args.time > 0:
        cycles.samples = 1 << 20
        cycles.time_limit = args.time
    else:
        cycles.samples = max(args.spp, 1)
    if args.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = args.threads
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.use_persistent_data = False
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.color_mode = "RGB"
    pfm = args.output.lower().endswith(".pfm")
    scene.render.filepath = args.output[:-4] + ".exr" if pfm else args.output
    bpy.ops.render.render(write_still=True)
    if pfm:
        write_pfm(scene.render.filepath, args.output)


def write_pfm(exr_path, pfm_path):
    """Converts the written EXR to PFM (linear float RGB, rows bottom to top, as Blender holds them)."""
    image = bpy.data.images.load(exr_path)
    width, height = image.size
    pixels = numpy.empty(width * height * 4, dtype=numpy.float32)
    image.pixels.foreach_get(pixels)
    rgb = pixels.reshape(height, width, 4)[:, :, :3]
    with open(pfm_path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        f.write(rgb.astype("<f4").tobytes())


main()
