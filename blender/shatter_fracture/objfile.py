"""Writing the mesh shatter fractures: a Wavefront OBJ (and its .mtl) of Blender's own
triangles, exactly.

Why not Blender's exporters: its OBJ exporter rounds coordinates to 6 decimals (a mesh
a few millimetres across would lose its shape), and its glTF exporter splits a
non-planar quad along its own diagonal, not the one Blender draws (1.5e-2 off Suzanne's
surface), and costs about 1.5 s the first time it loads in a session. Here:
  - the triangles are the mesh's loop triangles, the ones the viewport shows, so the
    fragments lie on the surface the user sees;
  - coordinates are written with 9 significant digits, which round-trips Blender's
    float32 exactly;
  - one `vt` and one `vn` per corner (the active UV map and the split normals), one
    `usemtl` group per material slot; the .mtl names each slot's material with its
    viewport colour (`Kd`) and its first image texture file (`map_Kd`), if any;
  - coordinates are the object's local ones, Blender's axes (+Z up), unchanged.
Material names are made OBJ-safe (no spaces); `write` returns the name used per slot.
Faces of an empty slot are grouped under NO_MATERIAL.
"""

import os

import bpy

# The group name of faces whose slot is empty (never a material's OBJ name).
NO_MATERIAL = "shatter_no_material"


def safe_name(name, taken):
    """An OBJ-safe, unique material name for `name` (spaces and '#' replaced)."""
    base = "".join("_" if c.isspace() or c == "#" else c for c in name) or "material"
    out, k = base, 1
    while out in taken:
        k += 1
        out = "%s_%d" % (base, k)
    taken.add(out)
    return out


def _image_file(mat):
    """The file of the first image texture in a material's nodes, or None."""
    if mat is None or not mat.use_nodes or mat.node_tree is None:
        return None
    for node in mat.node_tree.nodes:
        image = getattr(node, "image", None)
        if image is not None and image.source == 'FILE' and image.filepath:
            return bpy.path.abspath(image.filepath, library=image.library)
    return None


def _get(collection, attr, per_item, zero=0):
    values = [zero] * (per_item * len(collection))
    collection.foreach_get(attr, values)
    return values


def write(mesh, materials, path, name="mesh"):
    """Writes `mesh` (its loop triangles) to `path` and `path`'s .mtl; `materials` are
    the slots' materials (None for an empty slot). Returns the OBJ names of the slots
    (None for an empty slot)."""
    mesh.calc_loop_triangles()
    mesh.calc_normals_split()
    tris = mesh.loop_triangles
    co = _get(mesh.vertices, "co", 3, 0.0)
    normals = _get(mesh.loops, "normal", 3, 0.0)
    tri_loops = _get(tris, "loops", 3)
    tri_verts = _get(tris, "vertices", 3)
    tri_poly = _get(tris, "polygon_index", 1)
    poly_mat = _get(mesh.polygons, "material_index", 1)
    uv_layer = mesh.uv_layers.active
    uvs = _get(uv_layer.data, "uv", 2, 0.0) if uv_layer is not None else None

    taken = {NO_MATERIAL}
    names = [safe_name(m.name, taken) if m is not None else None for m in materials]
    mtl_path = os.path.splitext(path)[0] + ".mtl"
    with open(mtl_path, "w") as f:
        f.write("# materials of %s, written by the Blender add-on shatter_fracture\n" % name)
        # Faces of an empty slot: defined, so shatter does not warn about it; it maps
        # back to an empty slot on import.
        f.write("newmtl %s\nKd 0.8 0.8 0.8\n" % NO_MATERIAL)
        for mat, obj_name in zip(materials, names):
            if obj_name is None:
                continue
            r, g, b = mat.diffuse_color[:3]
            f.write("newmtl %s\nKd %.6g %.6g %.6g\n" % (obj_name, r, g, b))
            image = _image_file(mat)
            if image:
                f.write("map_Kd %s\n" % image)

    out = ["# %s, written by the Blender add-on shatter_fracture" % name,
           "mtllib %s" % os.path.basename(mtl_path), "o %s" % name.replace(" ", "_")]
    out += ["v %.9g %.9g %.9g" % tuple(co[i:i + 3]) for i in range(0, len(co), 3)]
    if uvs is not None:
        out += ["vt %.9g %.9g" % tuple(uvs[i:i + 2]) for i in range(0, len(uvs), 2)]
    out += ["vn %.9g %.9g %.9g" % tuple(normals[i:i + 3]) for i in range(0, len(normals), 3)]
    by_slot = {}
    for t, p in enumerate(tri_poly):
        by_slot.setdefault(poly_mat[p], []).append(t)
    for slot in sorted(by_slot):
        obj_name = names[slot] if slot < len(names) else None
        out.append("usemtl %s" % (obj_name or NO_MATERIAL))
        for t in by_slot[slot]:
            corners = []
            for k in range(3):
                v, loop = tri_verts[3 * t + k] + 1, tri_loops[3 * t + k] + 1
                corners.append("%d/%d/%d" % (v, loop, loop) if uvs is not None
                               else "%d//%d" % (v, loop))
            out.append("f " + " ".join(corners))
    with open(path, "w") as f:
        f.write("\n".join(out))
        f.write("\n")
    return names
