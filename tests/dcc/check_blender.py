# A manual check in Blender itself (Blender is not a dependency of skyspec, so this is not part of
# the test command; its result is recorded in docs/other-tools.md#blender):
#
#   skyspec render --camera equirectangular --width 512 --height 256 --panorama-convention blender \
#     --sun-azimuth 123 --sun-elevation 17 --set sun.distance_au=0.2 --exr-space "Linear Rec.709" --out pano
#   blender -b --factory-startup --python tests/dcc/check_blender.py -- pano/sky-linear-rec709.exr 123 17
#
# 1. Blender's own Sun Position add-on (sun_position/hdr.py, "Sync Sun to Texture") turns the
#    texture coordinate of the brightest pixel into an azimuth and elevation: they must be the
#    sun's. 2. Cycles renders the world, with the file as its Environment Texture (default mapping,
#    colour space as Blender assigns it), through a camera turned as docs/other-tools.md says to
#    look at the sun: the sun must be at the centre of the image. Exit status 0 when both hold.
import math
import sys

import bpy

exr, azimuth, elevation = sys.argv[sys.argv.index("--") + 1:][:3]
azimuth, elevation = float(azimuth), float(elevation)

image = bpy.data.images.load(exr)
w, h = image.size
pixels = image.pixels[:]  # RGBA, bottom row first
lum = [0.2126 * pixels[4 * i] + 0.7152 * pixels[4 * i + 1] + 0.0722 * pixels[4 * i + 2] for i in range(w * h)]
best = max(range(w * h), key=lum.__getitem__)
u, v = (best % w + 0.5) / w, (best // w + 0.5) / h
# sun_position/hdr.py, equirectangular: el = v pi - pi/2, az = u 2 pi - pi/2 (+ the texture's z rotation, 0)
hdr_elevation = math.degrees(v * math.pi - math.pi / 2)
hdr_azimuth = math.degrees(u * 2 * math.pi - math.pi / 2) % 360.0
print(f"colour space Blender gave the file: {image.colorspace_settings.name}")
print(f"Sun Position add-on: azimuth {hdr_azimuth:.2f}, elevation {hdr_elevation:.2f} "
      f"(skyspec: {azimuth}, {elevation}; one pixel is {360.0 / w:.2f} deg)")
ok = abs((hdr_azimuth - azimuth + 180.0) % 360.0 - 180.0) <= 360.0 / w and abs(hdr_elevation - elevation) <= 180.0 / h

scene = bpy.context.scene
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
world = bpy.data.worlds.new("skyspec") if scene.world is None else scene.world
scene.world = world
world.use_nodes = True
nodes = world.node_tree.nodes
env = nodes.new("ShaderNodeTexEnvironment")
env.image = image
world.node_tree.links.new(env.outputs["Color"], nodes["Background"].inputs["Color"])
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
scene.collection.objects.link(camera)
scene.camera = camera
camera.data.angle = math.radians(20.0)
# Looking at the sun: the camera's -Z onto (cos el sin az, cos el cos az, sin el).
camera.rotation_euler = (math.radians(90.0 + elevation), 0.0, math.radians(-azimuth))
scene.render.engine = "CYCLES"
scene.cycles.samples = 4
scene.cycles.use_denoising = False
scene.render.resolution_x = scene.render.resolution_y = 33
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.filepath = "/tmp/skyspec-blender-check.exr"
bpy.ops.render.render(write_still=True)
result = bpy.data.images.load(scene.render.filepath)
rw, rh = result.size
rp = result.pixels[:]
rl = [0.2126 * rp[4 * i] + 0.7152 * rp[4 * i + 1] + 0.0722 * rp[4 * i + 2] for i in range(rw * rh)]
rb = max(range(rw * rh), key=rl.__getitem__)
print(f"Cycles, camera turned to the sun: brightest pixel {rb % rw}, {rb // rw} of {rw}x{rh} (centre {rw // 2}, {rh // 2})")
ok = ok and abs(rb % rw - rw // 2) <= 1 and abs(rb // rw - rh // 2) <= 1
print("blender check:", "PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
