"""The bond graph in Blender: custom properties, or rigid bodies held together by
breakable "Fixed" constraints.

A bond is two fragments sharing a cut face (shatter's `--json-bonds`: fragment indices
`a < b`, the face's area, centroid and normal, in the object's local frame).

Properties, on each fragment:
  - `shatter_fragment`: its index in shatter's output;
  - `shatter_bonded`: the indices of the fragments it is bonded to;
  - `shatter_bond_area`: the shared areas in world space, in the same order.
Constraints: every fragment gets an active rigid body (convex hull, mass = density x
volume), and every bond an empty at the face's centroid with a Fixed rigid-body
constraint between the two fragments, breaking above `threshold` (times the area in
world space, when `scale_by_area`).
"""

import bpy
from mathutils import Vector

from .runner import ShatterError


def world_area(bond, linear):
    """A bond's area in world space: `linear` (3x3) maps the mesh's local frame to the
    world, and a planar area A with unit normal n becomes A |det L| |L^-T n|."""
    n = Vector(bond["normal"])
    return float(bond["area"]) * abs(linear.determinant()) * (
        linear.inverted_safe().transposed() @ n).length


def write_properties(fragments, bonds, linear):
    """Custom properties on every fragment of `fragments` ({index: object}); `linear`
    as for `world_area`."""
    neighbours = {i: [] for i in fragments}
    for bond in bonds:
        a, b, area = int(bond["a"]), int(bond["b"]), world_area(bond, linear)
        if a in neighbours and b in neighbours:
            neighbours[a].append((b, area))
            neighbours[b].append((a, area))
    for i, obj in fragments.items():
        obj["shatter_fragment"] = i
        obj["shatter_bonded"] = [j for j, _ in neighbours[i]]
        obj["shatter_bond_area"] = [area for _, area in neighbours[i]]


def _ensure_world(context):
    if context.scene.rigidbody_world is None:
        bpy.ops.rigidbody.world_add()
    if context.scene.rigidbody_world is None:
        raise ShatterError("Cannot add a rigid-body world to the scene")
    return context.scene.rigidbody_world


def _as_active(context, obj, op, **kw):
    """Runs a rigid-body operator on `obj`: they act on the view layer's active object
    (a context override of `object` is ignored), so it is made active for the call."""
    layer = context.view_layer
    previous = layer.objects.active
    layer.objects.active = obj
    try:
        result = op(**kw)
    finally:
        layer.objects.active = previous
    if result != {'FINISHED'}:
        raise ShatterError("Blender's %s failed on %s" % (op.idname_py(), obj.name))


def add_rigid_bodies(context, fragments, volumes, density):
    """Active rigid bodies (convex hull) with mass = density x world volume."""
    _ensure_world(context)
    for i, obj in fragments.items():
        _as_active(context, obj, bpy.ops.rigidbody.object_add, type='ACTIVE')
        rb = obj.rigid_body
        rb.collision_shape = 'CONVEX_HULL'
        rb.mass = max(density * volumes[i], 1e-6)


def add_constraints(context, fragments, bonds, matrix, collection, threshold,
                    scale_by_area=True, size=0.05):
    """One breakable Fixed constraint per bond whose two fragments exist; returns the
    constraint empties. `matrix` takes shatter's frame (Blender-local of the original)
    to world space."""
    empties = []
    for bond in bonds:
        a, b = int(bond["a"]), int(bond["b"])
        if a not in fragments or b not in fragments:
            continue
        empty = bpy.data.objects.new("%s_bond_%d_%d" % (collection.name, a, b), None)
        empty.empty_display_type = 'PLAIN_AXES'
        empty.empty_display_size = size
        empty.location = matrix @ Vector(bond["centroid"])
        collection.objects.link(empty)
        _as_active(context, empty, bpy.ops.rigidbody.constraint_add, type='FIXED')
        c = empty.rigid_body_constraint
        c.object1 = fragments[a]
        c.object2 = fragments[b]
        c.use_breaking = True
        area = world_area(bond, matrix.to_3x3())
        c.breaking_threshold = threshold * area if scale_by_area else threshold
        c.disable_collisions = True
        empty["shatter_bond"] = [a, b]
        empty["shatter_bond_area"] = area
        empties.append(empty)
    return empties
