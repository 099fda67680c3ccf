"""The mesh's way out to shatter and the fragments' way back, through GLB files.

Out: the object's evaluated mesh (its modifiers applied) with its materials and UVs, in
its own local frame (a temporary object with the identity transform), written by
Blender's glTF exporter. Back: shatter's GLB, one node `fragment_<i>` per fragment, read
by Blender's glTF importer, welded (so each fragment is one closed, connected mesh
again), then moved into the target collection.
"""

import re

import bmesh
import bpy

from .runner import ShatterError

FRAGMENT_NAME = re.compile(r"^fragment_(\d+)(?:\.\d+)?$")


def _numpy_for_gltf():
    """Blender 3.4's glTF importer uses `numpy.bool`, which numpy 1.24 (Debian 12's)
    removed; without this alias the import fails inside the importer."""
    try:
        import numpy
    except ImportError:
        raise ShatterError("Blender's glTF importer needs numpy (Debian: apt-get install "
                           "python3-numpy)")
    if "bool" not in numpy.__dict__:
        numpy.bool = bool


def evaluated_mesh(context, obj):
    """A new mesh datablock: `obj` with its modifiers applied, in its local frame."""
    depsgraph = context.evaluated_depsgraph_get()
    obj_eval = obj.evaluated_get(depsgraph)
    return bpy.data.meshes.new_from_object(obj_eval, preserve_all_data_layers=True,
                                           depsgraph=depsgraph)


def export_glb(context, mesh, path):
    """Writes `mesh` (identity transform) to `path` with Blender's glTF exporter."""
    tmp = bpy.data.objects.new("shatter_export", mesh)
    context.scene.collection.objects.link(tmp)
    view_layer = context.view_layer
    selected = [o for o in view_layer.objects if o.select_get()]
    active = view_layer.objects.active
    try:
        for o in selected:
            o.select_set(False)
        tmp.select_set(True)
        view_layer.objects.active = tmp
        bpy.ops.export_scene.gltf(
            filepath=path, export_format='GLB', use_selection=True, export_apply=False,
            export_yup=True, export_texcoords=True, export_normals=True,
            export_materials='EXPORT', export_colors=True, export_cameras=False,
            export_lights=False, export_animations=False, export_skins=False,
            export_morph=False, export_extras=False)
    except RuntimeError as e:
        raise ShatterError("Blender's glTF exporter failed: %s" % e)
    finally:
        bpy.data.objects.remove(tmp, do_unlink=True)
        for o in selected:
            if o.name in view_layer.objects:
                o.select_set(True)
        view_layer.objects.active = active


def import_glb(path):
    """Imports shatter's fragments; returns {fragment index: object}. Every other object
    the file brought is removed."""
    _numpy_for_gltf()
    before = set(bpy.data.objects)
    try:
        bpy.ops.import_scene.gltf(filepath=path, merge_vertices=True)
    except Exception as e:  # the importer is Python: anything it raises, say so plainly
        for obj in set(bpy.data.objects) - before:
            bpy.data.objects.remove(obj, do_unlink=True)
        raise ShatterError("Blender's glTF importer failed on shatter's fragments: %s" % e)
    fragments = {}
    for obj in set(bpy.data.objects) - before:
        m = FRAGMENT_NAME.match(obj.name)
        if obj.type == 'MESH' and m:
            weld(obj.data)
            fragments[int(m.group(1))] = obj
        else:
            bpy.data.objects.remove(obj, do_unlink=True)
    return fragments


def weld(mesh):
    """Merges vertices at exactly equal positions. The importer keeps a vertex per
    distinct normal and UV (even with merge_vertices), so a fragment arrives as patches
    split along its sharp edges and material borders; shatter wrote the same coordinates
    on both sides, and Blender keeps UVs and normals per corner, so nothing is lost."""
    bm = bmesh.new()
    try:
        bm.from_mesh(mesh)
        bmesh.ops.remove_doubles(bm, verts=bm.verts, dist=0.0)
        bm.to_mesh(mesh)
    finally:
        bm.free()
    mesh.update()


def move_to_collection(obj, collection):
    """Links `obj` into `collection` only."""
    for c in list(obj.users_collection):
        c.objects.unlink(obj)
    collection.objects.link(obj)
