"""Time Blender's Cell Fracture add-on on a mesh with given seed points (headless).

    blender -b --factory-startup --python cell_fracture.py -- MESH.obj SEEDS.xyz
            [--out OUT.obj] [--solver EXACT|FAST]

Imports MESH.obj without axis conversion (so its coordinates are the seeds'), welds
vertices at equal positions (an exported OBJ repeats vertices along sharp edges; Cell
Fracture's boolean needs a closed manifold), adds a child mesh object whose vertices are
the seeds, and calls bpy.ops.object.add_fracture_cell_objects with source={'VERT_CHILD'}
and every optional extra off (no recursion, noise, margin, sharp-edge split, interior
vertex group, recentering, progress redraw). Only that operator call is timed
(time.perf_counter for wall time, time.process_time for the CPU time of all threads).
Prints one line starting with RESULT.

The add-on leaves the boolean modifier's solver at its default (EXACT in Blender 3.4);
--solver FAST patches the add-on's cell_fracture_boolean (in memory) to use the FAST
(BMesh) solver instead, as an extra data point; without --solver the add-on runs as
shipped.
"""
import random
import sys
import time

import inspect

import addon_utils
import bmesh
import bpy


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    opts = {"--out": None, "--solver": None}
    for name in opts:
        if name in argv:
            i = argv.index(name)
            opts[name] = argv[i + 1]
            del argv[i:i + 2]
    if len(argv) != 2 or opts["--solver"] not in (None, "EXACT", "FAST"):
        sys.exit("usage: blender -b --factory-startup --python cell_fracture.py -- "
                 "MESH.obj SEEDS.xyz [--out OUT.obj] [--solver EXACT|FAST]")
    return argv[0], argv[1], opts["--out"], opts["--solver"]


def patch_solver(solver):
    """Make the add-on's boolean step use SOLVER (rewrites one function in memory)."""
    from object_fracture_cell import fracture_cell_setup as setup
    src = inspect.getsource(setup.cell_fracture_boolean)
    old = "mod.operation = 'INTERSECT'"
    if src.count(old) != 1:
        sys.exit("error: cannot patch the add-on's solver (its source changed)")
    src = src.replace(old, old + "\n        mod.solver = %r" % solver)
    exec(compile(src, setup.__file__, "exec"), setup.__dict__)


def read_points(path):
    points = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                points.append(tuple(float(c) for c in line[:3]))
    return points


def mesh_volume(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bm.transform(obj.matrix_world)
    v = bm.calc_volume(signed=True)
    bm.free()
    return v


def load_mesh(mesh_path):
    """Empties the scene, imports MESH.obj without axis conversion and welds it; returns
    the object and its vertex counts before and after welding."""
    # Empty scene (factory startup has a cube, a camera and a light).
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)

    # Forward Y, up Z is the identity: no axis conversion.
    bpy.ops.import_scene.obj(filepath=mesh_path, axis_forward="Y", axis_up="Z",
                             use_split_objects=False, use_split_groups=False)
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if len(meshes) != 1:
        sys.exit("error: expected one mesh object in %s, got %d" % (mesh_path, len(meshes)))
    target = meshes[0]
    target.matrix_world.identity()

    bm = bmesh.new()
    bm.from_mesh(target.data)
    n_before = len(bm.verts)
    bmesh.ops.remove_doubles(bm, verts=bm.verts, dist=1e-6)  # exact duplicates (float32); the bird's shortest edge is far longer
    n_after = len(bm.verts)
    bm.to_mesh(target.data)
    bm.free()
    target.data.update()
    return target, n_before, n_after


def add_seed_child(target, seeds):
    """A mesh object whose vertices are the seeds, child of the target."""
    seed_mesh = bpy.data.meshes.new("seeds")
    seed_mesh.from_pydata(seeds, [], [])
    seed_obj = bpy.data.objects.new("seeds", seed_mesh)
    bpy.context.collection.objects.link(seed_obj)
    seed_obj.parent = target  # identity parent: the seeds stay where they are
    return seed_obj


def default_solver(obj):
    probe = obj.modifiers.new(name="probe", type="BOOLEAN")
    solver = probe.solver
    obj.modifiers.remove(probe)
    return solver


def cell_fracture(target, seed_obj, remove_original=True):
    """Runs the add-on on the target with the seeds' vertices; returns (wall seconds,
    CPU seconds, the pieces made)."""
    bpy.ops.object.select_all(action="DESELECT")
    target.select_set(True)
    bpy.context.view_layer.objects.active = target
    random.seed(0)  # the add-on jitters cell vertices with random.random()
    c0 = time.process_time()
    t0 = time.perf_counter()
    result = bpy.ops.object.add_fracture_cell_objects(
        source={"VERT_CHILD"},
        source_limit=0,
        source_noise=0.0,
        cell_scale=(1.0, 1.0, 1.0),
        recursion=0,
        use_smooth_faces=False,
        use_sharp_edges=False,
        use_sharp_edges_apply=False,
        use_data_match=False,
        use_island_split=True,  # a cell the mesh cuts in two gives two pieces, as in shatter
        margin=0.0,
        material_index=0,
        use_interior_vgroup=False,
        mass_mode="UNIFORM",
        mass=1.0,
        use_recenter=False,
        use_remove_original=remove_original,
        collection_name="",
        use_debug_points=False,
        use_debug_redraw=False,
        use_debug_bool=False,
    )
    seconds = time.perf_counter() - t0
    cpu_seconds = time.process_time() - c0
    if result != {"FINISHED"}:
        sys.exit("error: operator returned %s" % result)
    pieces = [o for o in bpy.context.selected_objects if o is not target and o is not seed_obj]
    pieces = [o for o in pieces if o.type == "MESH"]
    return seconds, cpu_seconds, pieces


def enable_cell_fracture(solver=None):
    mod = addon_utils.enable("object_fracture_cell", default_set=True)
    if mod is None:
        sys.exit("error: the Cell Fracture add-on (object_fracture_cell) could not be enabled")
    if solver is not None:
        patch_solver(solver)
    return ".".join(map(str, mod.bl_info["version"]))


def main():
    mesh_path, seeds_path, out_path, solver = parse_args()
    version = enable_cell_fracture(solver)
    target, n_before, n_after = load_mesh(mesh_path)
    v0 = mesh_volume(target)
    seeds = read_points(seeds_path)
    seed_obj = add_seed_child(target, seeds)

    print("mesh %s: %d vertices (%d after welding), %d faces, volume %.6f; %d seeds"
          % (mesh_path, n_before, n_after, len(target.data.polygons), v0, len(seeds)))
    used_solver = solver or default_solver(seed_obj)

    n_objects_before = len(bpy.data.objects)
    seconds, cpu_seconds, pieces = cell_fracture(target, seed_obj)
    nonempty = [o for o in pieces if len(o.data.polygons) > 0]
    volume = sum(mesh_volume(o) for o in nonempty)
    created = len(bpy.data.objects) - n_objects_before
    print("RESULT blender_seconds=%.4f cpu_seconds=%.4f objects=%d nonempty=%d created=%d "
          "volume=%.6f mesh_volume=%.6f solver=%s addon=%s blender=%s"
          % (seconds, cpu_seconds, len(pieces), len(nonempty), created, volume, v0,
             used_solver, version, bpy.app.version_string))

    if out_path:
        bpy.ops.object.select_all(action="DESELECT")
        for o in nonempty:
            o.select_set(True)
        bpy.ops.export_scene.obj(filepath=out_path, use_selection=True, axis_forward="Y",
                                 axis_up="Z", use_materials=False)


if __name__ == "__main__":
    main()
