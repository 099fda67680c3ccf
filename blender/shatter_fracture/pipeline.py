"""Fracturing one Blender object with shatter, start to end, without any UI.

`fracture_object(context, obj, options)` is what the operator runs, and what scripts can
call (the benchmark in `bench/blender/` does):

    from shatter_fracture.pipeline import Options, fracture_object
    from shatter_fracture.runner import Request
    outcome = fracture_object(bpy.context, bpy.context.active_object,
                              Options(request=Request(method="voronoi", pieces=30)))
    print(len(outcome.fragments), outcome.report["bonds"])

Steps: export the evaluated mesh (OBJ, local frame), gather seed points or the impact
point, run `shatter fracture`, import the fragments, give them the original's transform
(and each its own centre as origin), their materials, the bond graph, and hide or remove
the original. Any failure raises `runner.ShatterError` with a message for the user, and
leaves no half-made fragments behind.
"""

import contextlib
import json
import os
import tempfile
import time
from dataclasses import dataclass, field
from typing import Callable, List, Optional

import bpy
import numpy as np
from mathutils import Matrix, Vector

from . import bonds, exchange, materials, runner, seeds
from .runner import ShatterError


@dataclass
class Options:
    """Everything the redo panel sets."""

    request: runner.Request = field(default_factory=runner.Request)
    # Where voronoi seeds come from: 'PATTERN' (shatter), or a seeds.SOURCES name.
    source: str = 'PATTERN'
    source_limit: int = 0
    # voronoi radial: the impact point is the 3D cursor (else shatter picks one).
    impact_from_cursor: bool = True
    # Interior material's name ("": the default one, made when missing).
    interior_material: str = ""
    keep_original: bool = True
    # Target collection's name ("": "<object>_fragments"); made when missing.
    collection: str = ""
    recenter: bool = True
    # 'NONE', 'PROPERTIES' or 'CONSTRAINTS' (properties, rigid bodies and constraints).
    bonds: str = 'NONE'
    break_threshold: float = 500.0
    scale_by_area: bool = True
    density: float = 1000.0
    # The preference: shatter's path ("": PATH).
    binary: str = ""


@dataclass
class Outcome:
    """What a fracture made."""

    fragments: List[bpy.types.Object]
    collection: bpy.types.Collection
    report: dict
    warnings: List[str]
    constraints: List[bpy.types.Object]
    shatter_seconds: float
    seconds: float


def volume_centroid(mesh):
    """Signed volume and volume centroid of a closed mesh, in its own coordinates
    (vectorised: a Python loop over the triangles was a sixth of the operator's time)."""
    mesh.calc_loop_triangles()
    co = np.empty(3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", co)
    tris = np.empty(3 * len(mesh.loop_triangles), dtype=np.int64)
    mesh.loop_triangles.foreach_get("vertices", tris)
    p = co.reshape(-1, 3)[tris.reshape(-1, 3)]
    a, b, c = p[:, 0], p[:, 1], p[:, 2]
    v = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    volume = float(v.sum())
    if abs(volume) < 1e-300:
        return volume, Vector((0.0, 0.0, 0.0))
    acc = (v[:, None] * (a + b + c) / 4.0).sum(axis=0)
    return volume, Vector(acc / volume)


def _target_collection(context, name, parent=None):
    """The collection of that name, or a new one linked under `parent` (the scene's)."""
    coll = bpy.data.collections.get(name)
    if coll is None:
        coll = bpy.data.collections.new(name)
        (parent or context.scene.collection).children.link(coll)
    return coll


def _prepare_request(context, obj, options):
    req = options.request
    req.bonds = options.bonds != 'NONE'
    req.seeds = None
    req.impact = None
    if req.method != "voronoi":
        return req
    if options.source != 'PATTERN':
        depsgraph = context.evaluated_depsgraph_get()
        local = seeds.gather(depsgraph, obj, options.source, options.source_limit, req.seed)
        req.seeds = local
    elif req.pattern == "radial" and options.impact_from_cursor:
        req.impact = tuple(obj.matrix_world.inverted_safe() @ context.scene.cursor.location)
    req.check()
    return req


@contextlib.contextmanager
def _work_dir():
    """A temporary folder for shatter's files; $SHATTER_FRACTURE_KEEP names a folder to
    keep them in instead (to look at what shatter was given and wrote)."""
    keep = os.environ.get("SHATTER_FRACTURE_KEEP")
    if keep:
        os.makedirs(keep, exist_ok=True)
        yield keep
    else:
        with tempfile.TemporaryDirectory(prefix="shatter-blender-") as tmp:
            yield tmp


def _select(view_layer, objects):
    """Selects `objects` only (those in the view layer), the first one active."""
    for o in view_layer.objects:
        if o.select_get():
            o.select_set(False)
    visible = [o for o in objects if o.name in view_layer.objects]
    for o in visible:
        o.select_set(True)
    if visible:
        view_layer.objects.active = visible[0]


def _no_progress(fraction, text):
    pass


def fracture_object(context, obj, options, progress: Optional[Callable] = None):
    """Fractures `obj` (a mesh object) as `options` say; see the module's doc."""
    progress = progress or _no_progress
    start = time.perf_counter()
    if obj is None or obj.type != 'MESH':
        raise ShatterError("Select a mesh object to fracture (the active object is %s)"
                           % ("none" if obj is None else "a " + obj.type.lower()))
    binary = runner.find_binary(options.binary)
    interior = materials.interior_material(options.interior_material)
    req = _prepare_request(context, obj, options)

    progress(0.05, "exporting %s" % obj.name)
    mesh = exchange.evaluated_mesh(context, obj)
    try:
        if len(mesh.polygons) == 0:
            raise ShatterError("%s has no faces to fracture" % obj.name)
        # The object's effective materials (a slot may link one to the object).
        original_materials = [slot.material for slot in obj.material_slots]
        with _work_dir() as tmp:
            mesh_path = os.path.join(tmp, "input.obj")
            out_path = os.path.join(tmp, "fragments.obj")
            seeds_path = os.path.join(tmp, "seeds.xyz")
            obj_names = exchange.export_obj(mesh, original_materials, mesh_path, obj.name)
            if req.seeds is not None:
                runner.write_points(seeds_path, req.seeds)
            args = runner.command_line(binary, mesh_path, out_path, req, seeds_path)
            progress(0.15, "running shatter")
            try:
                result = runner.run(args, progress=lambda s: progress(
                    0.15 + 0.35 * min(s / 10.0, 1.0), "running shatter (%.1f s)" % s))
            except ShatterError as e:
                # Name the object, not the temporary file shatter was given.
                raise ShatterError(str(e).replace(
                    mesh_path, "%s (with its modifiers applied)" % obj.name))
            result.warnings = [w.replace(mesh_path, obj.name) for w in result.warnings]
            if not os.path.isfile(out_path):
                raise ShatterError("shatter reported success but wrote no fragments")
            progress(0.5, "importing %d fragments" % result.report["fragments"])
            fragments, internal, made = exchange.import_obj(out_path)
    finally:
        bpy.data.meshes.remove(mesh)
    try:
        result.report["internal_faces_removed"] = internal
        by_name = dict(zip(obj_names, original_materials))
        return _finish(context, obj, options, interior, (original_materials, by_name, made),
                       result, fragments, progress, start)
    except Exception:
        for frag in fragments.values():
            if frag.name in bpy.data.objects:
                bpy.data.objects.remove(frag, do_unlink=True)
        raise


def _finish(context, obj, options, interior, mats, result, fragments, progress, start):
    expected = int(result.report["fragments"])
    if sorted(fragments) != list(range(expected)):
        raise ShatterError("shatter reported %d fragments but the file holds %d"
                           % (expected, len(fragments)))
    coll = _target_collection(context, options.collection or "%s_fragments" % obj.name)
    # The last fracture's figures, for the user (and the tests): counts, volumes, time.
    coll["shatter_report"] = json.dumps(
        {k: v for k, v in result.report.items() if k != "bond_list"})
    # What shatter repaired or dropped (holes filled, sheets dropped...), for the user.
    coll["shatter_warnings"] = json.dumps(result.warnings)
    matrix = obj.matrix_world.copy()
    det = abs(matrix.to_3x3().determinant())
    width = len(str(max(expected - 1, 0)))
    volumes = {}
    progress(0.7, "placing fragments")
    for i, frag in sorted(fragments.items()):
        exchange.move_to_collection(frag, coll)
        frag.name = "%s_fragment_%0*d" % (obj.name, width, i)
        frag.data.name = frag.name
        local = frag.matrix_world.copy()
        volume, centre = volume_centroid(frag.data)
        if options.recenter:
            frag.data.transform(Matrix.Translation(-centre))
            local = local @ Matrix.Translation(centre)
        frag.matrix_world = matrix @ local
        volumes[i] = abs(volume) * det
    ordered = [fragments[i] for i in range(expected)]
    materials.reassign(ordered, *mats, interior)

    constraints = []
    bond_list = result.report.get("bond_list") or []
    if options.bonds != 'NONE':
        progress(0.8, "bonds")
        bonds.write_properties(fragments, bond_list, matrix.to_3x3())
    if options.bonds == 'CONSTRAINTS':
        bonds.add_rigid_bodies(context, fragments, volumes, options.density)
        sub = _target_collection(context, "%s_constraints" % coll.name, parent=coll)
        size = 0.1 * (sum(volumes.values()) / max(expected, 1)) ** (1.0 / 3.0)
        constraints = bonds.add_constraints(
            context, fragments, bond_list, matrix, sub, options.break_threshold,
            options.scale_by_area, size)

    if options.keep_original:
        obj.hide_render = True
        if obj.name in context.view_layer.objects:
            obj.hide_set(True)
    else:
        bpy.data.objects.remove(obj, do_unlink=True)
    _select(context.view_layer, ordered)
    progress(1.0, "done")
    return Outcome(fragments=ordered, collection=coll, report=result.report,
                   warnings=result.warnings, constraints=constraints,
                   shatter_seconds=result.seconds, seconds=time.perf_counter() - start)
