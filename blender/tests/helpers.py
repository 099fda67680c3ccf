"""Scene builders and geometric checks for the add-on's headless test (test_addon.py).

Everything is measured in world space with bmesh and BVH trees of the original's
evaluated mesh, independently of the add-on's own code.
"""

import math
import random

import bmesh
import bpy
from mathutils import Euler, Matrix, Vector
from mathutils.bvhtree import BVHTree
from mathutils.geometry import barycentric_transform


class Tally:
    """Counts checks; prints one line per check and a closing 'N passed, N failed'."""

    def __init__(self):
        self.passed = 0
        self.failed = 0
        self.skipped = 0

    def check(self, name, ok, detail=""):
        if ok:
            self.passed += 1
            print("PASS %s" % name)
        else:
            self.failed += 1
            print("FAIL %s%s" % (name, (": " + detail) if detail else ""))
        return ok

    def skip(self, name, why):
        self.skipped += 1
        print("SKIP %s: %s" % (name, why))

    def summary(self, label):
        return "%s: %d passed, %d failed, %d skipped" % (label, self.passed, self.failed,
                                                          self.skipped)


# A transform that is not the identity (translated, rotated, scaled unevenly), so that
# the fragments' world placement is tested, not assumed.
PLACEMENT = (Vector((1.0, -2.0, 0.5)), Euler((0.3, 0.2, 0.9)), Vector((1.2, 0.8, 1.0)))


def clear_scene():
    scene = bpy.context.scene
    if scene.rigidbody_world is not None:
        bpy.ops.rigidbody.world_remove()
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in list(bpy.data.collections):
        bpy.data.collections.remove(coll)
    for data in (bpy.data.meshes, bpy.data.materials, bpy.data.particles):
        for block in list(data):
            data.remove(block)
    for img in list(bpy.data.images):
        if img.type == 'IMAGE':
            bpy.data.images.remove(img)
    scene.cursor.location = (0.0, 0.0, 0.0)
    scene.frame_set(1)


def _place(obj):
    loc, rot, scale = PLACEMENT
    obj.location, obj.rotation_euler, obj.scale = loc, rot, scale
    bpy.context.view_layer.update()
    return obj


def uv_sphere():
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8, radius=1.0)
    obj = bpy.context.active_object
    obj.name = "Sphere"
    return _place(obj)


def _components(bm):
    seen, parts = set(), []
    for v in bm.verts:
        if v in seen:
            continue
        seen.add(v)
        stack, part = [v], []
        while stack:
            x = stack.pop()
            part.append(x)
            for e in x.link_edges:
                y = e.other_vert(x)
                if y not in seen:
                    seen.add(y)
                    stack.append(y)
        parts.append(part)
    return parts


def suzanne(closed=True):
    """Suzanne; closed: without her two open eyeballs and with the head's holes filled
    (as shipped she has 42 boundary edges and no inside)."""
    bpy.ops.mesh.primitive_monkey_add(size=2.0)
    obj = bpy.context.active_object
    obj.name = "Suzanne" if closed else "SuzanneOpen"
    if closed:
        bm = bmesh.new()
        bm.from_mesh(obj.data)
        parts = sorted(_components(bm), key=len)
        bmesh.ops.delete(bm, geom=[v for part in parts[:-1] for v in part], context='VERTS')
        bmesh.ops.holes_fill(bm, edges=bm.edges[:], sides=0)
        bmesh.ops.triangulate(bm, faces=[f for f in bm.faces if len(f.verts) > 4])
        bm.to_mesh(obj.data)
        bm.free()
        obj.data.update()
    return _place(obj)


def plane():
    """A flat square: an open sheet that encloses nothing."""
    bpy.ops.mesh.primitive_plane_add(size=2.0)
    obj = bpy.context.active_object
    obj.name = "Plane"
    return _place(obj)


def textured_cube():
    """A cube with its UV map, an image-textured material, and a bevel modifier (so the
    fractured mesh is the evaluated one, not the 8-vertex cube)."""
    bpy.ops.mesh.primitive_cube_add(size=2.0)
    obj = bpy.context.active_object
    obj.name = "Cube"
    img = bpy.data.images.new("Checker", 64, 64)
    img.generated_type = 'COLOR_GRID'
    mat = bpy.data.materials.new("Checker")
    mat.use_nodes = True
    tree = mat.node_tree
    tex = tree.nodes.new("ShaderNodeTexImage")
    tex.image = img
    tree.links.new(tex.outputs["Color"], tree.nodes["Principled BSDF"].inputs["Base Color"])
    obj.data.materials.append(mat)
    bevel = obj.modifiers.new("Bevel", 'BEVEL')
    bevel.width = 0.3
    bevel.segments = 1
    return _place(obj)


def select_only(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


class Original:
    """The original's evaluated surface in world space: volume, BVH tree, UVs."""

    def __init__(self, obj):
        depsgraph = bpy.context.evaluated_depsgraph_get()
        obj_eval = obj.evaluated_get(depsgraph)
        mesh = obj_eval.to_mesh()
        matrix = obj.matrix_world
        mesh.calc_loop_triangles()
        self.verts = [matrix @ v.co for v in mesh.vertices]
        self.tris = [tuple(t.vertices) for t in mesh.loop_triangles]
        uv = mesh.uv_layers.active
        self.has_uvs = uv is not None
        self.tri_uvs = ([tuple(Vector((uv.data[i].uv[0], uv.data[i].uv[1], 0.0))
                               for i in t.loops) for t in mesh.loop_triangles]
                        if uv is not None else None)
        self.materials = [s.material for s in obj.material_slots]
        self.base_vertices = len(obj.data.vertices)
        self.vertices = len(mesh.vertices)
        obj_eval.to_mesh_clear()
        self.bvh = BVHTree.FromPolygons(self.verts, self.tris)
        self.volume = sum(self.verts[a].dot(self.verts[b].cross(self.verts[c]))
                          for a, b, c in self.tris) / 6.0
        lo = Vector([min(v[i] for v in self.verts) for i in range(3)])
        hi = Vector([max(v[i] for v in self.verts) for i in range(3)])
        self.size = (hi - lo).length
        self.matrix = matrix.copy()

    def uv_at(self, point):
        """The original's UV at a point on its surface, and the distance to it."""
        loc, _normal, index, dist = self.bvh.find_nearest(point)
        a, b, c = (self.verts[i] for i in self.tris[index])
        ua, ub, uc = self.tri_uvs[index]
        uv = barycentric_transform(loc, a, b, c, ua, ub, uc)
        return (uv[0], uv[1]), dist

    def distance(self, point):
        return self.bvh.find_nearest(point)[3]


def world_bmesh(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bm.transform(obj.matrix_world)
    return bm


def local_centroid(obj):
    """Volume centroid of the object's mesh in its own coordinates."""
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    vol, acc = 0.0, Vector()
    for f in bm.faces:
        a, b, c = (v.co for v in f.verts)
        v = a.dot(b.cross(c)) / 6.0
        vol += v
        acc += v * (a + b + c) / 4.0
    bm.free()
    return acc / vol if vol else acc


def inside(obj, world_point):
    """Whether a world point is inside a closed object (closest-point normal test)."""
    local = obj.matrix_world.inverted() @ world_point
    ok, loc, normal, _ = obj.closest_point_on_mesh(local)
    return ok and (local - loc).dot(normal) < 0.0


def random_points_in_ball(n, radius, seed):
    rng = random.Random(seed)
    points = []
    while len(points) < n:
        p = Vector([rng.uniform(-radius, radius) for _ in range(3)])
        if p.length < radius:
            points.append(p)
    return points


def matrices_close(a, b, tol=1e-5):
    return all(math.isclose(a[i][j], b[i][j], abs_tol=tol) for i in range(3) for j in range(3))


def add_ground(z):
    bpy.ops.mesh.primitive_plane_add(size=50.0, location=(0.0, 0.0, z))
    ground = bpy.context.active_object
    ground.name = "Ground"
    bpy.ops.rigidbody.object_add(type='PASSIVE')
    return ground


def spread(fragments):
    """Pairwise distances between fragment origins (world)."""
    pts = [f.matrix_world.translation.copy() for f in fragments]
    return [(pts[i] - pts[j]).length for i in range(len(pts)) for j in range(i + 1, len(pts))]


def identity():
    return Matrix.Identity(4)

