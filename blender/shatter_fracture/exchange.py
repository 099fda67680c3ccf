"""The mesh's way out to shatter and the fragments' way back, through OBJ files.

Out: the object's evaluated mesh (its modifiers applied) with its materials and UVs, in
its own local frame, written by `objfile.write` (exact float32 coordinates, the
triangles Blender draws). Back: shatter's OBJ (full float64 precision, one object
`fragment_<i>` per fragment, shared vertices), read by Blender's OBJ importer without
axis conversion, cleaned by `weld` (so each fragment is one closed 2-manifold), then
moved into the target collection.

Why OBJ back rather than GLB: Blender's glTF importer is Python and took 0.9 s for the
bird's 100 fragments, where the OBJ importer (C++) takes 0.08 s; it also splits every
vertex per normal and UV, to be welded again. The OBJ importer keeps UVs (`vt`),
normals (`vn`) and material names just the same.
"""

import re

import bmesh
import bpy
import numpy as np

from . import objfile
from .runner import ShatterError

FRAGMENT_NAME = re.compile(r"^fragment_(\d+)(?:\.\d+)?$")
_NORMAL = "shatter_normal"


def evaluated_mesh(context, obj):
    """A new mesh datablock: `obj` with its modifiers applied, in its local frame."""
    depsgraph = context.evaluated_depsgraph_get()
    obj_eval = obj.evaluated_get(depsgraph)
    return bpy.data.meshes.new_from_object(obj_eval, preserve_all_data_layers=True,
                                           depsgraph=depsgraph)


def export_obj(mesh, materials, path, name):
    """Writes the mesh for shatter; returns the OBJ material name of each slot."""
    try:
        return objfile.write(mesh, materials, path, name)
    except OSError as e:
        raise ShatterError("Cannot write the mesh for shatter (%s): %s" % (path, e))


def import_obj(path):
    """Imports shatter's fragments; returns ({fragment index: object}, internal faces
    removed by `weld`, the materials the import made). Every other object the file
    brought is removed."""
    objects_before = set(bpy.data.objects)
    materials_before = set(bpy.data.materials)
    try:
        # (One Blender object per `o`: 3.4's importer always splits so, later ones by
        # default.)
        bpy.ops.wm.obj_import(filepath=path, forward_axis='Y', up_axis='Z',
                              import_vertex_groups=False, validate_meshes=False)
    except Exception as e:  # say what failed, whatever the importer raised
        for obj in set(bpy.data.objects) - objects_before:
            bpy.data.objects.remove(obj, do_unlink=True)
        raise ShatterError("Blender's OBJ importer failed on shatter's fragments: %s" % e)
    fragments = {}
    internal = 0
    for obj in set(bpy.data.objects) - objects_before:
        m = FRAGMENT_NAME.match(obj.name)
        if obj.type == 'MESH' and m:
            internal += weld(obj.data)
            fragments[int(m.group(1))] = obj
        else:
            bpy.data.objects.remove(obj, do_unlink=True)
    return fragments, internal, set(bpy.data.materials) - materials_before


def _cycle(face):
    """A face's corner positions, rotated to start at the smallest: equal for the same
    face, reversed (after the first) for the same face wound the other way."""
    pts = [v.co.to_tuple() for v in face.verts]
    k = pts.index(min(pts))
    return tuple(pts[k:] + pts[:k])


def _nothing_to_weld(mesh):
    """Whether `mesh` has no two vertices at one position and no two faces on the same
    corners: then `weld` has nothing to do (shatter's own OBJ shares its vertices and,
    since merged slivers are true unions, has no inner walls), and the bmesh round trip,
    half of the operator's time on the bird's 100 fragments, is skipped. Vectorised."""
    n = len(mesh.vertices)
    co = np.empty(3 * n, dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    if len(np.unique(co.reshape(-1, 3), axis=0)) != n:
        return False
    sizes = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_total", sizes)
    if sizes.size == 0 or np.any(sizes != 3):
        return False  # other polygons: let bmesh look (shatter writes triangles only)
    corners = np.empty(3 * len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("vertices", corners)
    faces = np.sort(corners.reshape(-1, 3), axis=1)
    return len(np.unique(faces, axis=0)) == len(faces)


def weld(mesh):
    """Makes an imported fragment one closed 2-manifold again; returns the number of
    internal faces removed.

    1. shatter merges a sliver into a neighbour as a union of closed shells whose shared
       faces are kept back to back (fracture/merge.rs); in Blender that is an inner wall
       whose edges have four faces. Each pair of faces on the same corners wound
       opposite ways is removed: the shells' union is then a single closed surface.
    2. Vertices at exactly equal positions are welded (shatter's OBJ shares them
       already; this keeps a fragment whole if a writer repeats them, as its GLB does
       per normal). bmesh's remove_doubles does not merge equal positions at tiny
       distances, so copies are paired by their exact coordinates. UVs and normals
       live on the corners, so nothing is lost.
    Walls where the two shells' faces differ (one side's cap only part of the other's,
    or split at other points) are not removed: the fragment stays as shatter made it."""
    if _nothing_to_weld(mesh):
        return 0
    # The file's normals, per corner and absolute: Blender stores custom normals relative
    # to each corner's fan of faces, which welding changes, so they ride through the weld
    # as a corner attribute and are set again afterwards.
    custom = mesh.has_custom_normals
    if custom:
        mesh.calc_normals_split()
        normals = [0.0] * (3 * len(mesh.loops))
        mesh.loops.foreach_get("normal", normals)
    bm = bmesh.new()
    try:
        bm.from_mesh(mesh)
        if custom:
            layer = bm.loops.layers.float_vector.new(_NORMAL)
            starts = [p.loop_start for p in mesh.polygons]
            for face, start in zip(bm.faces, starts):
                for j, loop in enumerate(face.loops):
                    k = 3 * (start + j)
                    loop[layer] = normals[k:k + 3]
        by_corners = {}
        for f in bm.faces:
            by_corners.setdefault(tuple(sorted(v.co.to_tuple() for v in f.verts)), []).append(f)
        internal = []
        for faces in by_corners.values():
            if len(faces) < 2:
                continue
            pending = []
            for f in faces:
                c = _cycle(f)
                mirror = (c[0],) + tuple(reversed(c[1:]))
                match = next((g for g in pending if g[1] == mirror), None)
                if match is not None:
                    pending.remove(match)
                    internal += [match[0], f]
                else:
                    pending.append((f, c))
        if internal:
            bmesh.ops.delete(bm, geom=internal, context='FACES_ONLY')
        first = {}
        targets = {}
        for v in bm.verts:
            key = v.co.to_tuple()
            if key in first:
                targets[v] = first[key]
            else:
                first[key] = v
        if targets:
            bmesh.ops.weld_verts(bm, targetmap=targets)
        # Edges and vertices of removed faces that no face uses any more.
        loose = [e for e in bm.edges if not e.link_faces]
        if loose:
            bmesh.ops.delete(bm, geom=loose, context='EDGES')
        loose = [v for v in bm.verts if not v.link_faces]
        if loose:
            bmesh.ops.delete(bm, geom=loose, context='VERTS')
        bm.to_mesh(mesh)
    finally:
        bm.free()
    if custom:
        attr = mesh.attributes[_NORMAL]
        flat = [0.0] * (3 * len(attr.data))
        attr.data.foreach_get("vector", flat)
        mesh.attributes.remove(attr)
        mesh.use_auto_smooth = True
        mesh.normals_split_custom_set([flat[k:k + 3] for k in range(0, len(flat), 3)])
    mesh.update()
    return len(internal)


def move_to_collection(obj, collection):
    """Links `obj` into `collection` only."""
    for c in list(obj.users_collection):
        c.objects.unlink(obj)
    collection.objects.link(obj)
