"""Giving the fragments their materials back.

shatter's fragments carry a `surface` material on the original's faces and an
`interior` one on the cut faces (with issue 13, the original's own materials, by the
names the add-on wrote). Blender's importer makes materials of those names (`.001`
when the name is taken); here each is replaced by the one it stands for:
  - an OBJ name the add-on gave one of the original's slots -> that material itself
    (objfile.NO_MATERIAL -> none);
  - `interior` -> the interior material (chosen, or "Shatter Interior", made once);
  - `surface` -> the original's first material (none if it has none).
The stand-ins the import made, and images only they used, are then deleted.
"""

import re

import bpy

from .objfile import NO_MATERIAL
from .runner import ShatterError

DEFAULT_INTERIOR = "Shatter Interior"
INTERIOR_COLOUR = (0.80, 0.32, 0.12, 1.0)
_SUFFIX = re.compile(r"\.\d{3,}$")


def base_name(name):
    """A datablock's name without Blender's `.001` suffix."""
    return _SUFFIX.sub("", name)


def interior_material(name=""):
    """The named material (ShatterError if there is none), or the default one."""
    if name:
        mat = bpy.data.materials.get(name)
        if mat is None:
            raise ShatterError("There is no material named %r for the interior faces" % name)
        return mat
    mat = bpy.data.materials.get(DEFAULT_INTERIOR)
    if mat is None:
        mat = bpy.data.materials.new(DEFAULT_INTERIOR)
        mat.diffuse_color = INTERIOR_COLOUR  # the viewport's and Workbench's colour
        mat.use_nodes = True
        bsdf = mat.node_tree.nodes.get("Principled BSDF")
        if bsdf is not None:
            bsdf.inputs["Base Color"].default_value = INTERIOR_COLOUR
            bsdf.inputs["Roughness"].default_value = 0.9
    return mat


def reassign(fragments, original_materials, by_name, made, interior):
    """Replaces the imported stand-in materials of every fragment and returns how many
    fragments have interior faces. `by_name`: OBJ name -> the original's material (or
    None for an empty slot); `made`: the materials the import created, deleted (with
    images only they used) once unused."""
    originals = [m for m in original_materials if m is not None]
    surface = originals[0] if originals else None
    by_name = dict(by_name)
    by_name[NO_MATERIAL] = None
    with_interior = 0
    for obj in fragments:
        slots = obj.data.materials
        has_interior = False
        for i, mat in enumerate(slots):
            if mat is None or mat in originals or mat is interior:
                has_interior |= mat is interior
                continue
            name = mat.name if mat.name in by_name else base_name(mat.name)
            if name in by_name:
                new = by_name[name]
            elif name == "interior":
                new = interior
                has_interior = True
            elif name == "surface":
                new = surface
            else:
                continue  # a material shatter carried over under a name we do not know
            slots[i] = new
        with_interior += has_interior
    images = {node.image for mat in made if mat.node_tree
              for node in mat.node_tree.nodes if getattr(node, "image", None)}
    for mat in made:
        if mat.users == 0:
            bpy.data.materials.remove(mat)
    for img in images:
        if img.users == 0:
            bpy.data.images.remove(img)
    return with_interior
