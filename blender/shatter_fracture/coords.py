"""Blender's frame (Z up) and the glTF file's (Y up): plain Python, no Blender.

The add-on hands shatter the mesh as a GLB written by Blender's glTF exporter with
`+Y up`, so shatter works in glTF coordinates; seeds, the impact point and bond centroids
cross between the frames here. Blender's importer applies the inverse on the way back.

>>> to_gltf((1.0, 2.0, 3.0))
(1.0, 3.0, -2.0)
>>> from_gltf(to_gltf((1.0, 2.0, 3.0)))
(1.0, 2.0, 3.0)
"""


def to_gltf(v):
    """Blender (x, y, z) to glTF (x, z, -y)."""
    x, y, z = v
    return (x, z, -y)


def from_gltf(v):
    """glTF (x, y, z) to Blender (x, -z, y)."""
    x, y, z = v
    return (x, -z, y)
