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
_NORMAL = "shatter_normal"


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
    """A new mesh datablock: `obj` with its modifiers applied, in its local frame,
    triangulated as Blender displays it (see `triangulated`)."""
    depsgraph = context.evaluated_depsgraph_get()
    obj_eval = obj.evaluated_get(depsgraph)
    mesh = bpy.data.meshes.new_from_object(obj_eval, preserve_all_data_layers=True,
                                           depsgraph=depsgraph)
    try:
        return triangulated(mesh)
    finally:
        bpy.data.meshes.remove(mesh)


def _get(collection, attr, per_item, count):
    values = [0] * (per_item * count)
    collection.foreach_get(attr, values)
    return values


def triangulated(mesh):
    """A copy of `mesh` made of its loop triangles, the triangles Blender draws, with
    each corner's UVs and colours and each face's material. The exporter splits a
    non-planar quad along its own diagonal otherwise (1.5e-2 off Suzanne's surface), and
    the fragments would not lie on the surface the user sees."""
    mesh.calc_loop_triangles()
    tris = mesh.loop_triangles
    n = len(tris)
    tri_verts = _get(tris, "vertices", 3, n)
    tri_loops = _get(tris, "loops", 3, n)
    tri_poly = _get(tris, "polygon_index", 1, n)
    out = bpy.data.meshes.new(mesh.name + "_triangles")
    out.vertices.add(len(mesh.vertices))
    co = [0.0] * (3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", co)
    out.vertices.foreach_set("co", co)
    out.loops.add(3 * n)
    out.loops.foreach_set("vertex_index", tri_verts)
    out.polygons.add(n)
    out.polygons.foreach_set("loop_start", range(0, 3 * n, 3))
    out.polygons.foreach_set("loop_total", [3] * n)
    for attr in ("material_index", "use_smooth"):
        per_poly = _get(mesh.polygons, attr, 1, len(mesh.polygons))
        out.polygons.foreach_set(attr, [per_poly[p] for p in tri_poly])
    for layer in mesh.uv_layers:
        uv = [0.0] * (2 * len(mesh.loops))
        layer.data.foreach_get("uv", uv)
        new = out.uv_layers.new(name=layer.name, do_init=False)
        new.data.foreach_set("uv", [uv[2 * i + k] for i in tri_loops for k in (0, 1)])
    if mesh.uv_layers.active is not None:
        out.uv_layers.active = out.uv_layers[mesh.uv_layers.active.name]
    for attr in getattr(mesh, "color_attributes", ()):
        if attr.domain not in ('POINT', 'CORNER'):
            continue
        size = len(attr.data)
        colour = [0.0] * (4 * size)
        attr.data.foreach_get("color", colour)
        new = out.color_attributes.new(attr.name, attr.data_type, attr.domain)
        if attr.domain == 'CORNER':
            colour = [colour[4 * i + k] for i in tri_loops for k in range(4)]
        new.data.foreach_set("color", colour)
    for mat in mesh.materials:
        out.materials.append(mat)
    out.update(calc_edges=True)
    return out


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
    """Imports shatter's fragments; returns ({fragment index: object}, internal faces
    removed by `weld`). Every other object the file brought is removed."""
    _numpy_for_gltf()
    before = set(bpy.data.objects)
    try:
        bpy.ops.import_scene.gltf(filepath=path, merge_vertices=True)
    except Exception as e:  # the importer is Python: anything it raises, say so plainly
        for obj in set(bpy.data.objects) - before:
            bpy.data.objects.remove(obj, do_unlink=True)
        raise ShatterError("Blender's glTF importer failed on shatter's fragments: %s" % e)
    fragments = {}
    internal = 0
    for obj in set(bpy.data.objects) - before:
        m = FRAGMENT_NAME.match(obj.name)
        if obj.type == 'MESH' and m:
            internal += weld(obj.data)
            fragments[int(m.group(1))] = obj
        else:
            bpy.data.objects.remove(obj, do_unlink=True)
    return fragments, internal


def _cycle(face):
    """A face's corner positions, rotated to start at the smallest: equal for the same
    face, reversed (after the first) for the same face wound the other way."""
    pts = [v.co.to_tuple() for v in face.verts]
    k = pts.index(min(pts))
    return tuple(pts[k:] + pts[:k])


def weld(mesh):
    """Makes an imported fragment one closed 2-manifold again; returns the number of
    internal faces removed.

    1. shatter merges a sliver into a neighbour as a union of closed shells whose shared
       faces are kept back to back (fracture/merge.rs); in Blender that is an inner wall
       whose edges have four faces. Each pair of faces on the same corners wound
       opposite ways is removed: the shells' union is then a single closed surface.
    2. The importer keeps a vertex per distinct normal and UV (even with merge_vertices),
       so the fragment arrives as patches split along sharp edges and material borders;
       shatter wrote equal float32 coordinates on both sides, so the copies are welded
       by exact position (bmesh's remove_doubles does not merge equal positions at tiny
       distances). UVs and normals live on the corners, so nothing is lost."""
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
