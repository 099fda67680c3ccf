"""The Shatter Fracture add-on's operator against Cell Fracture's, in one Blender, on the
same object with the same seeds (the seeds as a child mesh's vertices for both).

    blender -b --factory-startup --python addon_vs_cell_fracture.py -- \
            MESH.obj SEEDS.xyz ADDON.zip SHATTER RUNS

Imports and welds MESH.obj as cell_fracture.py does, then RUNS rounds; each round runs
both operators one after the other (which one goes first alternates), each timed around
the operator call alone (time.perf_counter): Cell Fracture as in cell_fracture.py
(EXACT boolean, island split, no recentering), Shatter Fracture with the child vertices
as seeds, no bond graph and no recentering (Cell Fracture makes neither). Between runs
the fragments are deleted and the original shown again. Prints one RESULT line per run:

    RESULT tool=cell|shatter seconds=... objects=... volume=... [shatter_ms=...]
"""

import json
import os
import sys
import time

import addon_utils
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cell_fracture as cf  # noqa: E402


def remove(objects):
    for o in objects:
        mesh = o.data if o.type == 'MESH' else None
        bpy.data.objects.remove(o, do_unlink=True)
        if mesh is not None and mesh.users == 0:
            bpy.data.meshes.remove(mesh)


def run_cell(target, seeds):
    seconds, _cpu, pieces = cf.cell_fracture(target, seeds, remove_original=False)
    volume = sum(cf.mesh_volume(o) for o in pieces)
    n = len(pieces)
    remove(pieces)
    return "tool=cell seconds=%.4f objects=%d volume=%.6f" % (seconds, n, volume)


def run_shatter(target, seeds):
    bpy.ops.object.select_all(action="DESELECT")
    target.select_set(True)
    bpy.context.view_layer.objects.active = target
    t0 = time.perf_counter()
    result = bpy.ops.object.shatter_fracture(method='VORONOI', source='VERT_CHILD',
                                             bonds='NONE', recenter=False,
                                             collection_name="shatter_fragments")
    seconds = time.perf_counter() - t0
    if result != {'FINISHED'}:
        sys.exit("error: Shatter Fracture returned %s" % result)
    coll = bpy.data.collections["shatter_fragments"]
    pieces = list(coll.objects)
    report = json.loads(coll["shatter_report"])
    volume = sum(cf.mesh_volume(o) for o in pieces)
    remove(pieces)
    bpy.data.collections.remove(coll)
    target.hide_set(False)
    target.hide_render = False
    return "tool=shatter seconds=%.4f objects=%d volume=%.6f shatter_ms=%.2f" % (
        seconds, len(pieces), volume, report["millis"])


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    if len(argv) != 5:
        sys.exit("usage: blender -b --factory-startup --python addon_vs_cell_fracture.py -- "
                 "MESH.obj SEEDS.xyz ADDON.zip SHATTER RUNS")
    mesh_path, seeds_path, zip_path, shatter, runs = argv[0], argv[1], argv[2], argv[3], int(argv[4])
    cf.enable_cell_fracture()
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    if addon_utils.enable("shatter_fracture", default_set=True) is None:
        sys.exit("error: the Shatter Fracture add-on could not be enabled from %s" % zip_path)
    bpy.context.preferences.addons["shatter_fracture"].preferences.shatter_path = shatter
    target, _, _ = cf.load_mesh(mesh_path)
    seeds = cf.add_seed_child(target, cf.read_points(seeds_path))
    print("INFO mesh_volume=%.6f seeds=%d blender=%s"
          % (cf.mesh_volume(target), len(seeds.data.vertices), bpy.app.version_string))
    # One untimed run of each first (the first boolean and the first glTF import load
    # code and caches), then the timed rounds.
    run_cell(target, seeds)
    run_shatter(target, seeds)
    for r in range(runs):
        order = (run_cell, run_shatter) if r % 2 == 0 else (run_shatter, run_cell)
        for tool in order:
            print("RESULT round=%d %s" % (r, tool(target, seeds)))


main()
