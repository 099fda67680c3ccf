"""Seed points from the scene, as Cell Fracture takes them: the object's own vertices,
its children's vertices, its own or its children's particles.

Points are gathered in world space (child objects and particles live there), then
brought into the fractured object's local frame, the frame its mesh is exported in.
"""

import random

SOURCES = (
    ("PATTERN", "Pattern", "shatter places the seeds itself, in the chosen pattern"),
    ("VERT_OWN", "Own Vertices", "One seed per vertex of the object itself"),
    ("VERT_CHILD", "Child Vertices", "One seed per vertex of the object's children"),
    ("PARTICLE_OWN", "Own Particles", "One seed per particle of the object's particle systems"),
    ("PARTICLE_CHILD", "Child Particles", "One seed per particle of the children's particle systems"),
)


def _vertices_world(depsgraph, obj):
    """World positions of an object's evaluated vertices (meshes, curves, text...)."""
    obj_eval = obj.evaluated_get(depsgraph)
    try:
        mesh = obj_eval.to_mesh()
    except RuntimeError:
        return []
    if mesh is None:
        return []
    matrix = obj_eval.matrix_world.copy()
    points = [matrix @ v.co for v in mesh.vertices]
    obj_eval.to_mesh_clear()
    return points


def _particles_world(depsgraph, obj):
    obj_eval = obj.evaluated_get(depsgraph)
    # Every particle, born or not, as Cell Fracture does.
    return [p.location.copy() for psys in obj_eval.particle_systems for p in psys.particles]


def gather(depsgraph, obj, source, limit=0, seed=0):
    """Seed points for `obj` from `source` (one of SOURCES but PATTERN), in the object's
    local frame. With `limit` > 0, at most that many, drawn at random with `seed`."""
    if source == 'VERT_OWN':
        world = _vertices_world(depsgraph, obj)
    elif source == 'VERT_CHILD':
        world = [p for child in obj.children for p in _vertices_world(depsgraph, child)]
    elif source == 'PARTICLE_OWN':
        world = _particles_world(depsgraph, obj)
    elif source == 'PARTICLE_CHILD':
        world = [p for child in obj.children for p in _particles_world(depsgraph, child)]
    else:
        raise ValueError("no points to gather for source %r" % source)
    to_local = obj.matrix_world.inverted_safe()
    points = [tuple(to_local @ p) for p in world]
    if limit > 0 and len(points) > limit:
        points = random.Random(seed).sample(points, limit)
    return points
