"""Renders a model fractured by the add-on, its fragments pulled apart (Workbench, headless).

    blender -b --factory-startup --python blender/render_exploded.py -- \
            ADDON.zip SHATTER OUT.png [PIECES=60] [SPREAD=0.8]

Installs the zip, imports shatter's bird (`shatter shape bird`), gives it a blue
material, fractures it with Object > Quick Effects > Shatter Fracture (Voronoi, PIECES
seeds, default interior material), moves every fragment away from the bird's centre by
SPREAD times its offset, and renders it with the Workbench engine (material colours,
studio light, cavity and outline) from a camera framing all fragments.
"""

import math
import os
import subprocess
import sys
import tempfile

import addon_utils
import bpy
from mathutils import Vector


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    if len(argv) < 3:
        sys.exit(__doc__)
    zip_path, shatter, out = argv[0], argv[1], os.path.abspath(argv[2])
    pieces = int(argv[3]) if len(argv) > 3 else 60
    spread = float(argv[4]) if len(argv) > 4 else 0.8

    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    addon_utils.enable("shatter_fracture", default_set=True)
    bpy.context.preferences.addons["shatter_fracture"].preferences.shatter_path = shatter
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "bird.obj")
        subprocess.run([shatter, "shape", "bird", "--out", path], check=True,
                       stdout=subprocess.DEVNULL)
        bpy.ops.import_scene.obj(filepath=path)  # OBJ's +Y up becomes Blender's +Z up
    bird = [o for o in bpy.context.scene.objects if o.type == 'MESH'][0]
    bird.data.materials.clear()
    mat = bpy.data.materials.new("Bird")
    mat.diffuse_color = (0.22, 0.42, 0.80, 1.0)
    bird.data.materials.append(mat)
    bpy.context.view_layer.objects.active = bird
    bird.select_set(True)
    result = bpy.ops.object.shatter_fracture(method='VORONOI', pieces=pieces, seed=4)
    if result != {'FINISHED'}:
        sys.exit("error: the operator returned %s" % result)
    frags = list(bpy.data.collections[bird.name + "_fragments"].objects)

    centre = sum((f.matrix_world.translation for f in frags), Vector()) / len(frags)
    for f in frags:
        f.matrix_world.translation += spread * (f.matrix_world.translation - centre)
    bpy.context.view_layer.update()

    corners = [f.matrix_world @ Vector(c) for f in frags for c in f.bound_box]
    lo = Vector([min(c[i] for c in corners) for i in range(3)])
    hi = Vector([max(c[i] for c in corners) for i in range(3)])
    mid, radius = (lo + hi) / 2, (hi - lo).length / 2
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.lens = 50
    cam = bpy.data.objects.new("Camera", cam_data)
    bpy.context.scene.collection.objects.link(cam)
    direction = Vector((0.8, -1.5, 1.2)).normalized()
    fov = 2 * math.atan(cam_data.sensor_width / (2 * cam_data.lens))
    cam.location = mid + direction * (radius / math.sin(fov / 2)) * 0.9
    cam.rotation_euler = (-direction).to_track_quat('-Z', 'Y').to_euler()

    scene = bpy.context.scene
    scene.camera = cam
    scene.render.engine = 'BLENDER_WORKBENCH'
    scene.render.resolution_x, scene.render.resolution_y = 1000, 625
    scene.render.image_settings.color_mode = 'RGB'
    scene.render.image_settings.compression = 100
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    shading = scene.display.shading
    shading.light = 'STUDIO'
    shading.color_type = 'MATERIAL'
    shading.show_cavity = True
    shading.show_object_outline = True
    if scene.world is None:
        scene.world = bpy.data.worlds.new("World")
    scene.world.color = (0.93, 0.93, 0.91)  # Workbench renders the world's colour
    scene.display.render_aa = '8'
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)
    print("wrote %s: %d fragments, spread %.2f" % (out, len(frags), spread))


main()
